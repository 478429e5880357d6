//! A second thread for the element kernels of mid-size models (a few hundred to a few
//! thousand elements), where one assembly takes a fraction of a millisecond.
//!
//! rayon's workers fall asleep about 30 µs after their last job, and between two
//! assemblies the caller factorises the tangent (≈ 0.15 ms on the 120×4 strip): every
//! assembly then waits for a wake-up, and the measured gain of rayon on the 480 elements
//! of that strip was nil. This helper instead spins for [`SPIN`] after each job before it
//! parks, as OpenMP runtimes do between parallel regions (GNU's `GOMP_SPINCOUNT`, Intel's
//! `KMP_BLOCKTIME`), so it is awake when the next assembly comes. The price is CPU time:
//! during a run it keeps a second core busy. Sweeps that run several solves side by side
//! switch it off ([`set_allowed`]), and so does `RAYON_NUM_THREADS=1`.
//!
//! One job at a time: [`Helper::join`] hands a closure to the helper, runs another on the
//! calling thread and returns when both are done, so the closures may borrow the caller's
//! data (as `std::thread::scope` or `rayon::join` allow, without a spawn per call).

use std::cell::UnsafeCell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long the helper spins for the next job before it parks. (Yielding the core while
/// waiting, after a few µs of spinning or every 256 spins, was measured on the 120×4
/// strip-channel: no consistent gain over one thread, 1.5–2.0 s against 1.3–1.4 s spinning.)
pub const SPIN: Duration = Duration::from_millis(2);

static ALLOWED: AtomicBool = AtomicBool::new(true);

/// Allow or forbid helper threads for assemblers created from now on (a process-wide
/// policy: a sweep running one solve per core forbids them).
pub fn set_allowed(allowed: bool) {
    ALLOWED.store(allowed, Ordering::Relaxed);
}

/// Whether new assemblers may start a helper thread: allowed, and more than one thread in
/// rayon's pool (so `RAYON_NUM_THREADS=1` makes every run single-threaded).
pub fn allowed() -> bool {
    ALLOWED.load(Ordering::Relaxed) && rayon::current_num_threads() > 1
}

/// A type-erased pointer to the caller's closure (valid until [`Helper::join`] returns).
type Job = *const (dyn Fn() + Sync);

struct Shared {
    /// Number of jobs posted.
    posted: AtomicU64,
    /// Number of jobs finished.
    finished: AtomicU64,
    /// The current job; written by the caller before `posted` is raised, read by the helper
    /// after it sees the raise, untouched by either until `finished` catches up.
    job: UnsafeCell<Option<Job>>,
    /// The current job panicked.
    panicked: AtomicBool,
    quit: AtomicBool,
}

// SAFETY: `job` is only accessed under the posted/finished hand-over protocol described on
// the field (release/acquire on the counters orders the accesses); the closure behind it is
// `Sync`.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

/// One spinning worker thread (see the module docs).
pub struct Helper {
    shared: Arc<Shared>,
    handle: Option<JoinHandle<()>>,
}

impl Helper {
    /// Start the thread; `None` if it cannot be spawned.
    pub fn start() -> Option<Self> {
        let shared = Arc::new(Shared {
            posted: AtomicU64::new(0),
            finished: AtomicU64::new(0),
            job: UnsafeCell::new(None),
            panicked: AtomicBool::new(false),
            quit: AtomicBool::new(false),
        });
        let s = Arc::clone(&shared);
        let handle = std::thread::Builder::new()
            .name("contrail-assembly".into())
            .spawn(move || work(&s))
            .ok()?;
        Some(Helper {
            shared,
            handle: Some(handle),
        })
    }

    /// Run `on_helper` on the helper thread and `here` on the calling thread; return when
    /// both have finished. A panic in either is resumed on the calling thread.
    pub fn join<A, B>(&self, on_helper: &A, here: B)
    where
        A: Fn() + Sync,
        B: FnOnce(),
    {
        let job: &(dyn Fn() + Sync) = on_helper;
        // SAFETY: the lifetime is erased for the hand-over only: this function does not
        // return (nor unwind) before the helper has finished with `job` (the wait below
        // runs even when `here` panics).
        let job: Job = unsafe { std::mem::transmute::<&(dyn Fn() + Sync), Job>(job) };
        let n = self.shared.posted.load(Ordering::Relaxed) + 1;
        // SAFETY: the helper has finished every earlier job (`finished == posted`), so it
        // does not read `job` until the raise of `posted` below.
        unsafe { *self.shared.job.get() = Some(job) };
        self.shared.posted.store(n, Ordering::Release);
        if let Some(h) = &self.handle {
            h.thread().unpark();
        }
        let mine = catch_unwind(AssertUnwindSafe(here));
        let mut spins = 0u32;
        while self.shared.finished.load(Ordering::Acquire) < n {
            spins += 1;
            if spins < 1 << 16 {
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
        if let Err(p) = mine {
            std::panic::resume_unwind(p);
        }
        if self.shared.panicked.swap(false, Ordering::Relaxed) {
            panic!("the assembly helper thread panicked");
        }
    }
}

impl Drop for Helper {
    fn drop(&mut self) {
        self.shared.quit.store(true, Ordering::Release);
        if let Some(h) = self.handle.take() {
            h.thread().unpark();
            let _ = h.join();
        }
    }
}

/// The helper's loop: spin (then park) until a job is posted, run it, report it finished.
fn work(s: &Shared) {
    let mut done = 0u64;
    loop {
        let idle = Instant::now();
        let mut spins = 0u32;
        loop {
            if s.posted.load(Ordering::Acquire) > done {
                break;
            }
            if s.quit.load(Ordering::Acquire) {
                return;
            }
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(64) && idle.elapsed() > SPIN {
                // parked until `join` or `drop` unparks (or spuriously): check again
                std::thread::park_timeout(Duration::from_millis(100));
            } else {
                std::hint::spin_loop();
            }
        }
        done += 1;
        // SAFETY: posted > finished: the caller wrote `job` before raising `posted` and
        // waits for `finished` before touching it again or returning.
        let job = unsafe { (*s.job.get()).expect("a posted job") };
        // SAFETY: the closure outlives the job (see `Helper::join`).
        let f = unsafe { &*job };
        if catch_unwind(AssertUnwindSafe(f)).is_err() {
            s.panicked.store(true, Ordering::Relaxed);
        }
        s.finished.store(done, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn both_halves_run_and_see_borrowed_data() {
        let h = Helper::start().expect("a thread");
        let data: Vec<usize> = (0..1000).collect();
        for round in 0..200 {
            let left = AtomicUsize::new(0);
            let mut right = 0;
            h.join(
                &|| left.store(data[..500].iter().sum::<usize>() + round, Ordering::Relaxed),
                || {
                    right = data[500..].iter().sum::<usize>();
                },
            );
            assert_eq!(left.load(Ordering::Relaxed) + right, 499_500 + round);
            if round % 50 == 0 {
                // long enough for the helper to park: it must wake for the next job
                std::thread::sleep(SPIN + Duration::from_millis(3));
            }
        }
    }

    #[test]
    fn a_panic_on_the_helper_reaches_the_caller_and_the_helper_goes_on() {
        let h = Helper::start().expect("a thread");
        let r = catch_unwind(AssertUnwindSafe(|| h.join(&|| panic!("boom"), || {})));
        assert!(r.is_err());
        let ran = AtomicBool::new(false);
        h.join(&|| ran.store(true, Ordering::Relaxed), || {});
        assert!(ran.load(Ordering::Relaxed));
    }
}
