//! The thread budget of a run: how many threads it may use, and how a machine is divided
//! among runs that share it (a sweep's jobs, the service's workers, a Slurm allocation).

/// The cores this process may use: `std::thread::available_parallelism` (which honours the
/// affinity mask and a cgroup CPU quota), and no more than `SLURM_CPUS_PER_TASK` inside a
/// Slurm job that sets it.
pub fn available_cores() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let slurm = std::env::var("SLURM_CPUS_PER_TASK")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok());
    match slurm {
        Some(n) if n > 0 => cores.min(n),
        _ => cores,
    }
}

/// The threads of a run whose setting is `threads` (0: [`available_cores`]).
pub fn resolve(threads: usize) -> usize {
    if threads == 0 {
        available_cores()
    } else {
        threads
    }
}

/// Threads for each of `runs` runs sharing `cores` cores side by side (at least one).
pub fn share(cores: usize, runs: usize) -> usize {
    (cores / runs.max(1)).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_machine_is_divided_among_its_runs() {
        assert_eq!(share(16, 4), 4);
        assert_eq!(share(2, 2), 1);
        assert_eq!(share(2, 3), 1);
        assert_eq!(share(3, 2), 1);
        assert_eq!(share(8, 0), 8);
        assert_eq!(resolve(3), 3);
        assert!(resolve(0) >= 1);
    }
}
