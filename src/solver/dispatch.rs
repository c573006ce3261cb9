//! Which instruction set the contact kernels run on, chosen once per pass.
//!
//! The kernels are written once over lane vectors ([`lanes::L`](super::lanes))
//! of exact integer operations, so every instruction set computes the same
//! bits: the choice changes only the speed. The portable build solves a
//! colour's constraints one lane at a time (on the default x86-64 target,
//! SSE2 has no signed 32×32→64 multiply, and eight lanes spill). On x86-64
//! with `std`, when the processor has AVX2 (detected once at run time), the
//! passes (the contact kernels' and the pivot lanes') are compiled a second
//! time with AVX2 enabled and solve eight lanes at once.
//!
//! This module is the crate's only `unsafe` code: calling a function compiled
//! for AVX2 is unsafe because running it on a processor without AVX2 is
//! undefined behaviour, and so are the few AVX2 intrinsics of `avx2` (the
//! eight-lane gather, scatter and products, which plain lane code compiles badly,
//! reached only from those functions). The two call sites ([`run`] and
//! [`run_pivots`]) go there only when [`simd_level`] says AVX2, which it says
//! only after `is_x86_feature_detected!("avx2")` did (cached), and
//! [`limit_simd_level`] can only lower the level, never raise it past what
//! was detected.
//!
//! Measured gain: `cargo bench --bench scenes -- --levels` steps each scene
//! twice side by side, one world at `SimdLevel::Portable` and one at
//! `SimdLevel::Avx2`, and checks that the two end with equal state hashes. Two
//! runs on 2026-12-05 (AMD EPYC, load 0.7–0.9) gave these ratios of a step's
//! thread CPU time, Portable over AVX2, each the median of a run's samples:
//!
//! | scene | first run | second run |
//! |---|---|---|
//! | pyramid_20 | 2.44 | 2.56 |
//! | large_pyramid | 2.34 | 2.50 |
//! | many_pyramids | 2.26 | 2.40 |
//! | rain | 1.81 | 1.81 |
//! | joint_grid | 1.46 | 1.42 |
#![allow(unsafe_code)]

use core::sync::atomic::{AtomicU8, Ordering};

use super::colour::Kernel;
use super::pivot_lanes::Pass;
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

/// Runs pass `pass` over the pivots in lanes ([`pivot_lanes`](super::pivot_lanes))
/// at the current [`simd_level`].
pub(crate) fn run_pivots(solver: &mut Solver<'_>, pass: Pass) {
    if solver.pivot_runs.count == 0 {
        return;
    }
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        if simd_level() == SimdLevel::Avx2 {
            // SAFETY: as in `run`.
            unsafe { pivots_avx2(solver, pass) };
            return;
        }
    }
    solver.pivot_runs::<false>(pass);
}

/// [`run_pivots`] compiled with AVX2: the pivot kernel inlined here, eight
/// lanes wide.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
fn pivots_avx2(solver: &mut Solver<'_>, pass: Pass) {
    solver.pivot_runs::<true>(pass);
}

/// [`run`] compiled with AVX2: the kernels are inlined here, eight lanes wide.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
fn run_avx2<K: Kernel>(solver: &mut Solver<'_>, sweep: Sweep, k: &K) {
    solver.runs::<K, true>(sweep, k);
}

/// The eight-lane operations that plain lane code does not compile to well,
/// written with AVX2 intrinsics for the kernels' eight-lane instantiation.
///
/// Only the contact kernels' `W = 8` instantiation calls these (the lane
/// types [`L`](super::lanes::L) and the kernels' `gather` choose them by the
/// width), and that instantiation is reached only from [`run_avx2`], which
/// runs only on a processor with AVX2 (and, in the kernels' unit test, only
/// after `is_x86_feature_detected!("avx2")`). Each is exact integer
/// arithmetic computing the same bits as the portable code it replaces.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub(crate) mod avx2 {
    use core::arch::x86_64::{
        __m256i, _mm256_add_epi64, _mm256_blend_epi32, _mm256_blendv_epi8, _mm256_loadu_si256,
        _mm256_mul_epi32, _mm256_permute2x128_si256, _mm256_set1_epi32, _mm256_set1_epi64x,
        _mm256_shuffle_epi32, _mm256_sll_epi64, _mm256_srl_epi64, _mm256_unpackhi_epi32,
        _mm256_unpackhi_epi64, _mm256_unpacklo_epi32, _mm256_unpacklo_epi64, _mm_cvtsi32_si128,
    };
    use core::mem::transmute;

    use crate::math::{Rot, Vector2};
    use crate::solver::{BodyLanes, SolverBody};

    /// `(a·b + 2^(K−1)) >> K` on the exact 64-bit products, narrowed to
    /// `i32` ([`lanes::mul`](crate::solver::lanes::mul)), eight lanes: the
    /// even lanes' products from `vpmuldq` in place, the odd lanes' from the
    /// lanes shifted down, each rounded and shifted into its own half of the
    /// 64-bit lane (down by K, up by 32 − K: the low 32 bits of the shift are
    /// the narrowing), then blended. Nine instructions; the lane loop
    /// compiled to twelve (sign extensions, two products, and the shuffles
    /// that pack the halves). The odd lanes are brought down by a dword
    /// shuffle (each odd dword copied into the even place below it), not a
    /// 64-bit shift: from two shifts by 32 LLVM rebuilt the signed product
    /// as a full 64-bit one (three unsigned products, a sign extraction and
    /// the shifts to join them, about ten instructions instead of three) in
    /// 51 places of the sweep kernel (pyramid_20, 100 steps: 312.6 →
    /// 305.7 M instructions; large pyramid, 10 steps: 800.3 → 784.4 M).
    #[inline(always)]
    pub(crate) fn mul<const K: u32>(a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        const { assert!(K >= 1 && K <= 32) };
        // SAFETY: the transmutes are between plain integer types of 32
        // bytes, valid for every bit pattern. The intrinsics need AVX2:
        // only the kernels' eight-lane instantiation calls this, reached
        // only from `run_avx2`, which runs only when AVX2 was detected (see
        // the module's note).
        unsafe {
            let (a, b) = (transmute::<[i32; 8], __m256i>(a), transmute::<[i32; 8], __m256i>(b));
            let round = _mm256_set1_epi64x(1i64 << (K - 1));
            let even = _mm256_add_epi64(_mm256_mul_epi32(a, b), round);
            let odd = _mm256_mul_epi32(_mm256_shuffle_epi32::<0xF5>(a), _mm256_shuffle_epi32::<0xF5>(b));
            let odd = _mm256_add_epi64(odd, round);
            let even = _mm256_srl_epi64(even, _mm_cvtsi32_si128(K as i32));
            let odd = _mm256_sll_epi64(odd, _mm_cvtsi32_si128(32 - K as i32));
            transmute::<__m256i, [i32; 8]>(_mm256_blend_epi32::<0b1010_1010>(even, odd))
        }
    }

    /// The deep points' push-out ([`push_apart`](crate::solver::contact::push_apart))
    /// on eight lanes, compiled with AVX2 in a function of its own: the
    /// sweeps stay as lean as without it (it runs only for a block with a
    /// point deeper than 10 cm), and its lane products are AVX2
    /// instructions, not calls (rain, 200 steps, where bodies land deep in
    /// each other: 974.8 → 923.1 M instructions; compiled with the crate's
    /// SSE2, this instance called each intrinsic as a function).
    #[inline(always)]
    pub(crate) fn push_apart<const TWO: bool>(
        blk: &mut crate::solver::contact::Block,
        base: usize,
        bodies: &mut [BodyLanes],
        deep: crate::solver::lanes::M<8>,
        params: &crate::solver::contact::LaneParams,
        reverse: bool,
    ) {
        // SAFETY: only the kernels' eight-lane instantiation calls this,
        // reached only from `run_avx2`, which runs only on a processor with
        // AVX2 (see the module's note).
        unsafe { push_apart_avx2::<TWO>(blk, base, bodies, deep, params, reverse) }
    }

    #[target_feature(enable = "avx2")]
    #[inline(never)]
    fn push_apart_avx2<const TWO: bool>(
        blk: &mut crate::solver::contact::Block,
        base: usize,
        bodies: &mut [BodyLanes],
        deep: crate::solver::lanes::M<8>,
        params: &crate::solver::contact::LaneParams,
        reverse: bool,
    ) {
        crate::solver::contact::push_apart::<8, TWO>(blk, base, bodies, deep, params, reverse);
    }

    /// The rotation and position of the bodies `idx` selects, as the pivot
    /// lanes' pose pass reads them: the bits of cos, sin, x and y, one array
    /// of eight lanes each (an index out of range reads
    /// [`SolverBody::EMPTY`]). Each body's position and rotation are one
    /// 32-byte load (they lie side by side in the record), then two 4×4
    /// transposes by 64-bit interleaves and 128-bit permutes. A lane at a
    /// time (and from four loads a body, which the compiler turns the same
    /// transposes back into) the gather took four loads and four stores to
    /// the stack a lane, each side of each block, five passes a step.
    #[inline(always)]
    pub(crate) fn gather_pose(bodies: &[SolverBody], idx: [i32; 8]) -> [[i64; 8]; 4] {
        // The position's two words, then the rotation's.
        const AT: usize = core::mem::offset_of!(SolverBody, p);
        const ADJACENT: bool = core::mem::offset_of!(SolverBody, q) == AT + 16
            && core::mem::offset_of!(Vector2, x) == 0
            && core::mem::offset_of!(Vector2, y) == 8
            && core::mem::offset_of!(Rot, c) == 0
            && core::mem::offset_of!(Rot, s) == 8
            && size_of::<Vector2>() == 16
            && size_of::<Rot>() == 16
            && size_of::<crate::math::scalar::Scalar>() == 8;
        let row = |i: i32| {
            let sb = bodies.get(i as u32 as usize).unwrap_or(&SolverBody::EMPTY);
            if ADJACENT {
                // SAFETY: the 32 bytes from offset `AT` are `p` and `q` of
                // `*sb` (checked above), plain integers inside one live
                // record read through a pointer derived from a reference
                // to the whole record; an unaligned load needs no
                // alignment; AVX2 as in `mul`.
                unsafe {
                    _mm256_loadu_si256((sb as *const SolverBody).cast::<u8>().add(AT).cast::<__m256i>())
                }
            } else {
                let words = [sb.p.x.to_bits(), sb.p.y.to_bits(), sb.q.c.to_bits(), sb.q.s.to_bits()];
                // SAFETY: a plain integer transmute.
                unsafe { transmute::<[i64; 4], __m256i>(words) }
            }
        };
        let [i0, i1, i2, i3, i4, i5, i6, i7] = idx;
        // SAFETY: as in `mul`: plain integer transmutes, and AVX2 intrinsics
        // reached only under `pivots_avx2`, which runs only when AVX2 was
        // detected.
        unsafe {
            // Four rows [x, y, c, s] to four columns of four lanes.
            let columns = |r0: __m256i, r1: __m256i, r2: __m256i, r3: __m256i| {
                // x0 x1 | c0 c1, y0 y1 | s0 s1, and the same for rows 2, 3.
                let (a, b) = (_mm256_unpacklo_epi64(r0, r1), _mm256_unpackhi_epi64(r0, r1));
                let (c, d) = (_mm256_unpacklo_epi64(r2, r3), _mm256_unpackhi_epi64(r2, r3));
                [
                    _mm256_permute2x128_si256::<0x20>(a, c),
                    _mm256_permute2x128_si256::<0x20>(b, d),
                    _mm256_permute2x128_si256::<0x31>(a, c),
                    _mm256_permute2x128_si256::<0x31>(b, d),
                ]
            };
            let lo = columns(row(i0), row(i1), row(i2), row(i3));
            let hi = columns(row(i4), row(i5), row(i6), row(i7));
            let join = |k: usize| {
                let (a, b) = (transmute::<__m256i, [i64; 4]>(lo[k]), transmute::<__m256i, [i64; 4]>(hi[k]));
                [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
            };
            [join(2), join(3), join(0), join(1)]
        }
    }

    /// Fields 0–5 of the records `idx` selects (an index out of range reads
    /// [`BodyLanes::EMPTY`]), one array of eight lanes per field: each lane's
    /// whole 32-byte record in one load, then an 8×8 transpose by 32-bit and
    /// 64-bit interleaves and 128-bit permutes (the two fields not needed
    /// left out).
    #[inline(always)]
    pub(crate) fn gather(bodies: &[BodyLanes], idx: [i32; 8]) -> [[i32; 8]; 6] {
        let row = |i: i32| bodies.get(i as u32 as usize).unwrap_or(&BodyLanes::EMPTY).0;
        let [i0, i1, i2, i3, i4, i5, i6, i7] = idx;
        // SAFETY: as in `mul`: plain integer transmutes, and AVX2 intrinsics
        // reached only under `run_avx2`.
        unsafe {
            let r = |i: i32| transmute::<[i32; 8], __m256i>(row(i));
            let (r0, r1, r2, r3) = (r(i0), r(i1), r(i2), r(i3));
            let (r4, r5, r6, r7) = (r(i4), r(i5), r(i6), r(i7));
            // Lanes 0/1, 2/3, …, interleaved: t0 = r0[0] r1[0] r0[1] r1[1] | r0[4] r1[4] r0[5] r1[5].
            let (t0, t1) = (_mm256_unpacklo_epi32(r0, r1), _mm256_unpackhi_epi32(r0, r1));
            let (t2, t3) = (_mm256_unpacklo_epi32(r2, r3), _mm256_unpackhi_epi32(r2, r3));
            let (t4, t5) = (_mm256_unpacklo_epi32(r4, r5), _mm256_unpackhi_epi32(r4, r5));
            let (t6, t7) = (_mm256_unpacklo_epi32(r6, r7), _mm256_unpackhi_epi32(r6, r7));
            // u0 = field 0 of lanes 0–3 | field 4 of lanes 0–3; u1: 1 | 5; u2: 2 | 6; u3: 3 | 7.
            let (u0, u1) = (_mm256_unpacklo_epi64(t0, t2), _mm256_unpackhi_epi64(t0, t2));
            let (u2, u3) = (_mm256_unpacklo_epi64(t1, t3), _mm256_unpackhi_epi64(t1, t3));
            let (u4, u5) = (_mm256_unpacklo_epi64(t4, t6), _mm256_unpackhi_epi64(t4, t6));
            let (u6, u7) = (_mm256_unpacklo_epi64(t5, t7), _mm256_unpackhi_epi64(t5, t7));
            let lo = |x, y| transmute::<__m256i, [i32; 8]>(_mm256_permute2x128_si256::<0x20>(x, y));
            let hi = |x, y| transmute::<__m256i, [i32; 8]>(_mm256_permute2x128_si256::<0x31>(x, y));
            [lo(u0, u4), lo(u1, u5), lo(u2, u6), lo(u3, u7), hi(u0, u4), hi(u1, u5)]
        }
    }

    /// Writes fields 0–2 of the records `idx` selects from `v` (one array of
    /// eight lanes per field), in the lanes `m` sets (−1; 0 leaves the lane
    /// out); an index out of range is skipped. The lanes left out get index
    /// −1, past every record, so the bounds test each store makes anyway is
    /// the only test a lane; fields 0 and 1 come interleaved as one 64-bit
    /// pair a lane (which the compiler stores as one), not extracted one by
    /// one. Written as the gather's reverse (whole records) it cost more:
    /// fields 3–7 would need loading first.
    #[inline(always)]
    pub(crate) fn scatter(bodies: &mut [BodyLanes], idx: [i32; 8], m: [i32; 8], v: [[i32; 8]; 3]) {
        // SAFETY: as in `mul`.
        let (pairs, idx) = unsafe {
            let x = transmute::<[i32; 8], __m256i>(v[0]);
            let y = transmute::<[i32; 8], __m256i>(v[1]);
            // Lanes 0, 1, 4, 5 and 2, 3, 6, 7 as (x, y) pairs.
            let lo = transmute::<__m256i, [u64; 4]>(_mm256_unpacklo_epi32(x, y));
            let hi = transmute::<__m256i, [u64; 4]>(_mm256_unpackhi_epi32(x, y));
            let idx = _mm256_blendv_epi8(
                _mm256_set1_epi32(-1),
                transmute::<[i32; 8], __m256i>(idx),
                transmute::<[i32; 8], __m256i>(m),
            );
            ([lo[0], lo[1], hi[0], hi[1], lo[2], lo[3], hi[2], hi[3]], transmute::<__m256i, [i32; 8]>(idx))
        };
        for ((&i, &p), &w) in idx.iter().zip(&pairs).zip(&v[2]) {
            if let Some(b) = bodies.get_mut(i as u32 as usize) {
                b.0[0] = p as u32 as i32;
                b.0[1] = (p >> 32) as u32 as i32;
                b.0[2] = w;
            }
        }
    }
}
