//! Which instruction set the contact kernels run on, chosen once per pass.
//!
//! The kernels are written once over lane vectors ([`lanes::L`](super::lanes))
//! of exact integer operations, so every instruction set computes the same
//! bits: the choice changes only the speed. The portable build solves a
//! colour's constraints one lane at a time (on the default x86-64 target,
//! SSE2 has no signed 32×32→64 multiply, and eight lanes spill). On x86-64
//! with `std`, when the processor has AVX2 (detected once at run time), the
//! passes are compiled a second time with AVX2 enabled and solve eight lanes
//! at once.
//!
//! This module is the crate's only `unsafe` code: calling a function compiled
//! for AVX2 is unsafe because running it on a processor without AVX2 is
//! undefined behaviour. The one call site checks
//! `is_x86_feature_detected!("avx2")` first (cached), and
//! [`limit_simd_level`] can only lower the level, never raise it past what
//! was detected. Measured gain: see the README's performance section (the
//! scenes at `SimdLevel::Portable` and `SimdLevel::Avx2`, one run).
#![allow(unsafe_code)]

use core::sync::atomic::{AtomicU8, Ordering};

use super::colour::Kernel;
use super::{Solver, Sweep};

/// The instruction sets the contact kernels can run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// Any processor: one lane at a time.
    Portable,
    /// x86-64 with AVX2 (runtime detection, `std` builds): eight lanes at once.
    Avx2,
}

/// The highest level allowed ([`limit_simd_level`]); `u8::MAX` = no limit.
static LIMIT: AtomicU8 = AtomicU8::new(u8::MAX);
/// The detected level + 1; 0 = not yet detected.
static DETECTED: AtomicU8 = AtomicU8::new(0);

fn detect() -> SimdLevel {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            return SimdLevel::Avx2;
        }
    }
    SimdLevel::Portable
}

fn from_u8(x: u8) -> SimdLevel {
    if x == SimdLevel::Avx2 as u8 {
        SimdLevel::Avx2
    } else {
        SimdLevel::Portable
    }
}

/// The level the contact kernels run at: the best this processor and build
/// offer, lowered by [`limit_simd_level`]. Results are the same at every
/// level.
pub fn simd_level() -> SimdLevel {
    let detected = match DETECTED.load(Ordering::Relaxed) {
        0 => {
            let d = detect();
            DETECTED.store(d as u8 + 1, Ordering::Relaxed);
            d
        }
        x => from_u8(x - 1),
    };
    let limit = LIMIT.load(Ordering::Relaxed);
    if limit < detected as u8 {
        from_u8(limit)
    } else {
        detected
    }
}

/// Caps the level for this process (tests and benchmarks compare the levels
/// with it; results never depend on it). It cannot raise the level above
/// what the processor offers.
#[doc(hidden)]
pub fn limit_simd_level(level: SimdLevel) {
    LIMIT.store(level as u8, Ordering::Relaxed);
}

/// Runs kernel `k` over every constraint in `sweep`'s order at the current
/// [`simd_level`].
pub(crate) fn run<K: Kernel>(solver: &mut Solver<'_>, sweep: Sweep, k: &K) {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        if simd_level() == SimdLevel::Avx2 {
            // SAFETY: `simd_level` returns `Avx2` only when
            // `is_x86_feature_detected!("avx2")` said this processor has it.
            unsafe { run_avx2(solver, sweep, k) };
            return;
        }
    }
    solver.runs::<K, false>(sweep, k);
}

/// [`run`] compiled with AVX2: the kernels are inlined here, eight lanes wide.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
fn run_avx2<K: Kernel>(solver: &mut Solver<'_>, sweep: Sweep, k: &K) {
    solver.runs::<K, true>(sweep, k);
}
