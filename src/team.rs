//! A team of worker threads for the element kernels and the iterative solver's products and
//! smoothing, sized by the run's thread budget, whose idle workers *sleep* (a condition
//! variable: no busy-waiting, no CPU taken from other processes between jobs).
//!
//! One job at a time: [`Team::run`] posts `chunks` pieces of work, wakes the workers, and
//! the calling thread claims pieces itself from the same atomic counter. Whoever is awake
//! does the work: a worker that the operating system does not schedule in time (another
//! process holds the core) claims nothing, and the caller does its share instead, so an
//! assembly costs at most one piece more than on the calling thread alone. The caller
//! returns once every worker that joined the job has left it, so the job may borrow the
//! caller's data (as `std::thread::scope` allows, without a spawn per call).
//!
//! Whether the team pays at all is measured while the run goes (see
//! [`super::pacing::Pacing`]): the team is a means, never a requirement.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

/// A type-erased pointer to the caller's job (valid while [`Team::run`] has not returned).
type Job = *const (dyn Fn(usize) + Sync);

/// What the caller and the workers share under the lock.
struct Control {
    /// Raised for every job posted.
    generation: u64,
    /// The current job and its number of pieces; `None` once the caller has stopped
    /// accepting new workers into it.
    job: Option<(Job, usize)>,
    /// Workers inside the current job.
    active: usize,
    quit: bool,
}

struct Shared {
    control: Mutex<Control>,
    /// Workers wait here for a job.
    work: Condvar,
    /// The caller waits here for the last active worker to leave.
    left: Condvar,
    /// The next piece to claim.
    next: AtomicUsize,
    /// A piece panicked.
    panicked: AtomicBool,
}

// SAFETY: the raw job pointer is only dereferenced by a worker registered in `active`
// under the lock while the job is posted; the caller does not return before `active` is
// back to zero, so the closure (which is `Sync`) outlives every use.
unsafe impl Send for Shared {}
unsafe impl Sync for Shared {}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Control> {
        self.control.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Claim and run pieces of `job` until none is left.
    fn claim(&self, job: &(dyn Fn(usize) + Sync), pieces: usize) {
        loop {
            let k = self.next.fetch_add(1, Ordering::Relaxed);
            if k >= pieces {
                return;
            }
            if catch_unwind(AssertUnwindSafe(|| job(k))).is_err() {
                self.panicked.store(true, Ordering::Relaxed);
            }
        }
    }
}

/// The calling thread and `threads − 1` sleeping workers.
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

impl std::fmt::Debug for Team {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Team").field("threads", &self.threads()).finish()
    }
}

impl Team {
    /// A team of `threads` (the caller included): `threads − 1` workers are started; fewer
    /// if the system refuses a thread (the team then has fewer hands, nothing else changes).
    pub fn new(threads: usize) -> Self {
        let shared = Arc::new(Shared {
            control: Mutex::new(Control {
                generation: 0,
                job: None,
                active: 0,
                quit: false,
            }),
            work: Condvar::new(),
            left: Condvar::new(),
            next: AtomicUsize::new(0),
            panicked: AtomicBool::new(false),
        });
        let workers = (1..threads.max(1))
            .map_while(|i| {
                let s = Arc::clone(&shared);
                std::thread::Builder::new()
                    .name(format!("contrail-elements-{i}"))
                    .spawn(move || work(&s))
                    .ok()
            })
            .collect();
        Team { shared, workers }
    }

    /// Threads of the team, the caller included.
    pub fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    /// Run `job(k)` for every piece `k < pieces`, on the calling thread and on whichever
    /// workers wake in time; return when all pieces are done. A panic in any piece is
    /// resumed here.
    pub fn run(&self, pieces: usize, job: &(dyn Fn(usize) + Sync)) {
        if self.workers.is_empty() || pieces < 2 {
            (0..pieces).for_each(job);
            return;
        }
        // SAFETY: the lifetime is erased for the hand-over only; this function does not
        // return (nor unwind: pieces are run under `catch_unwind`) before every worker that
        // took the pointer has left the job (`active == 0` below).
        let erased: Job = unsafe { std::mem::transmute::<&(dyn Fn(usize) + Sync), Job>(job) };
        {
            let mut c = self.shared.lock();
            self.shared.next.store(0, Ordering::Relaxed);
            c.generation += 1;
            c.job = Some((erased, pieces));
        }
        self.shared.work.notify_all();
        self.shared.claim(job, pieces);
        let mut c = self.shared.lock();
        // no worker joins from now on; wait for those inside to leave
        c.job = None;
        while c.active > 0 {
            c = self.shared.left.wait(c).unwrap_or_else(|e| e.into_inner());
        }
        drop(c);
        if self.shared.panicked.swap(false, Ordering::Relaxed) {
            panic!("an element kernel panicked on a worker thread");
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.lock().quit = true;
        self.shared.work.notify_all();
        for w in self.workers.drain(..) {
            let _ = w.join();
        }
    }
}

/// A worker: sleep until a job is posted that it has not seen, join it, claim pieces until
/// none is left, leave it.
fn work(s: &Shared) {
    let mut seen = 0u64;
    loop {
        let (job, pieces) = {
            let mut c = s.lock();
            loop {
                if c.quit {
                    return;
                }
                match c.job {
                    Some(_) if c.generation != seen => break,
                    _ => c = s.work.wait(c).unwrap_or_else(|e| e.into_inner()),
                }
            }
            seen = c.generation;
            c.active += 1;
            c.job.expect("a posted job")
        };
        // SAFETY: registered in `active` while the job was posted: the caller waits for this
        // worker to leave before the closure goes out of scope.
        s.claim(unsafe { &*job }, pieces);
        let mut c = s.lock();
        c.active -= 1;
        if c.active == 0 {
            s.left.notify_one();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_piece_runs_once_and_sees_borrowed_data() {
        for threads in [1, 2, 4] {
            let team = Team::new(threads);
            let data: Vec<usize> = (0..1000).collect();
            for round in 0..300 {
                let hits: Vec<AtomicUsize> = (0..10).map(|_| AtomicUsize::new(0)).collect();
                team.run(10, &|k| {
                    let s: usize = data[100 * k..100 * (k + 1)].iter().sum();
                    hits[k].fetch_add(s + round, Ordering::Relaxed);
                });
                let total: usize = hits.iter().map(|h| h.load(Ordering::Relaxed)).sum();
                assert_eq!(total, 499_500 + 10 * round, "{threads} threads, round {round}");
                if round % 100 == 0 {
                    // the workers fall asleep: they must wake for the next job
                    std::thread::sleep(std::time::Duration::from_millis(5));
                }
            }
        }
    }

    #[test]
    fn a_panic_in_a_piece_reaches_the_caller_and_the_team_goes_on() {
        let team = Team::new(2);
        let r = catch_unwind(AssertUnwindSafe(|| {
            team.run(8, &|k| {
                if k == 5 {
                    panic!("boom")
                }
            })
        }));
        assert!(r.is_err());
        let ran = AtomicUsize::new(0);
        team.run(8, &|_| {
            ran.fetch_add(1, Ordering::Relaxed);
        });
        assert_eq!(ran.load(Ordering::Relaxed), 8);
    }
}
