//! Wider vector instructions for the hot kernels where the processor has them.
//!
//! The release build targets the baseline x86-64 instruction set (SSE2: two `f64` per
//! vector), so one binary runs on every machine. The few kernels that dominate a run (the
//! quadrilateral element, the banded LU) are compiled a second time with AVX2 (four `f64`
//! per vector) and chosen at run time by [`wide_vectors`]. Both copies perform the same
//! floating-point operations in the same order — the compiler does not fuse or reassociate
//! without being told to, and no kernel uses `mul_add` — so a run's figures are the same to
//! the last bit on either path (asserted by the kernels' tests).

/// Whether the processor has AVX2 (detected once; `false` off x86-64, or with
/// `CONTRAIL_NO_AVX2` set, which forces the baseline path for comparisons).
pub fn wide_vectors() -> bool {
    use std::sync::OnceLock;
    static WIDE: OnceLock<bool> = OnceLock::new();
    *WIDE.get_or_init(|| std::env::var_os("CONTRAIL_NO_AVX2").is_none() && detected())
}

#[cfg(target_arch = "x86_64")]
fn detected() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

#[cfg(not(target_arch = "x86_64"))]
fn detected() -> bool {
    false
}
