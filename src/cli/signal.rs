//! Ctrl-C and SIGTERM. [`install`] runs first thing in `main`, so a signal at any time is
//! handled: while a run polls the stop flag (it asked for it with [`stop_flag`]) the signal
//! only sets the flag and the run stops after finalising its recording (exit 130); before
//! that, and in the other verbs, the process exits at once with 130. A second signal during a
//! run exits at once too (a computation that does not poll the flag would otherwise never
//! end); the recording's temporary file is then left for `contrail recover`.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

static STOP: OnceLock<Arc<AtomicBool>> = OnceLock::new();
static POLLED: AtomicBool = AtomicBool::new(false);
static SIGNALS: AtomicUsize = AtomicUsize::new(0);

fn flag() -> &'static Arc<AtomicBool> {
    STOP.get_or_init(|| Arc::new(AtomicBool::new(false)))
}

/// Install the handler (once; later calls do nothing).
pub fn install() {
    let stop = flag().clone();
    let _ = ctrlc::set_handler(move || {
        stop.store(true, Ordering::SeqCst);
        let n = SIGNALS.fetch_add(1, Ordering::SeqCst);
        if !POLLED.load(Ordering::SeqCst) {
            std::process::exit(130);
        }
        if n >= 1 {
            eprintln!("interrupted again: stopping without finalising the recording");
            std::process::exit(130);
        }
    });
}

/// The stop flag, for a computation that polls it and ends cleanly when it is set (a signal
/// from now on no longer exits the process). It may already be set.
pub fn stop_flag() -> Arc<AtomicBool> {
    POLLED.store(true, Ordering::SeqCst);
    flag().clone()
}
