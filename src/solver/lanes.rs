//! The solver's own number formats: 32-bit integer lanes.
//!
//! [`Scalar`] (Q32.32) is the API's and the persistent state's number, but its
//! product is a 64×64→128-bit multiply that no SIMD level has. Inside the step
//! the contact sweeps work on `i32` values whose product is a 32×32→64 widening
//! multiply and a shift: one instruction on every target, eight per AVX2
//! instruction. Each quantity has its own format, chosen from the world's
//! documented limits so that no lane can wrap (the design note
//! `docs/design/solver-lanes.md` has the derivation):
//!
//! | quantity | format | resolution | bound in the solver | why |
//! |---|---|---|---|---|
//! | linear velocity v, rim speed ŵ = ω·r_b | Q16.16 | 1.5e-5 m/s | ±[`V_WALL`] | clamped after every update |
//! | position and rim-rotation change over the step (dp, δ̂ = dθ·r_b) | Q12.20 | 9.5e-7 m | ±512 m, ±101 m | \|v\| ≤ 2,048 m/s, dt ≤ 0.25 s; \|dθ\| ≤ π/4 |
//! | unit normal, ρ·d, γ̂, soft scales, restitution | Q2.30 | 9.3e-10 | ±1, ±1, ±[`GAMMA_MAX`], [0, 1], [0, 1] | unit vectors and mass ratios (below) |
//! | contact arm in body radii r̂ = (r×d)/r_b | Q3.29 | 1.9e-9 | ±[`ARM_MAX`] | \|r\| ≤ r_b on the body; deep overlaps clamped |
//! | separation | Q13.19 | 1.9e-6 m | ±2,362 m | shapes ≤ 128 m, the step's motion |
//! | 1/h, bias rate | Q22.10 | 9.8e-4 1/s | ≤ 2²⁰ | dt ≥ 2⁻¹⁶ s ([`MIN_TIME_STEP`](crate::limits::MIN_TIME_STEP)), ≤ 16 sub-steps |
//! | friction factor φ = μ·k_t/k_n | Q9.23 | 1.2e-7 | [0, [`PHI_MAX`]) | μ ≤ 100, clamped |
//! | accumulated impulse in velocity units λ̂ = λ·k | Q16.16 | 1.5e-5 m/s | [0, [`LAMBDA_MAX`]] | clamped at every update |
//! | block inverse M̂, coupling c_ij | Q5.27, Q3.29 | | < [`BLOCK_MAX`], ≤ 2 | the block is used only inside these |
//!
//! **Lanes never see a mass.** Every row keeps its impulse in velocity units,
//! λ̂ = λ·k with k = 1/m_eff of the row, and turns it into velocity changes by
//! ratios: ρ = m_eff/m ≤ 1 for the linear part and γ̂ = m_eff·(r×d)·r_b/I for
//! the rim speed, ≤ r_b/(2ρ_g) ≤ √2 for every convex shape (ρ_g the radius of
//! gyration). The 27-bit mass range (0.001–100,000 kg) never reaches a lane:
//! the once-per-step prepare works on each pair's inverse masses scaled by one
//! power of two (see `contact::prepare`), and store in `Scalar`. A velocity change below one ulp is lost: a
//! 1 g body striking a 100 t one moves it by less than 1.5e-5 m/s, which rounds
//! to nothing (f32 engines absorb it the same way).
//!
//! **Products** are `(a·b + 2^(k−1)) >> k` on the exact 64-bit product, rounding
//! half up, the same on every target; adds and subtracts are plain `i32`, which
//! the bounds above keep from wrapping (the smallest margin, the rim speed after
//! a friction update, is 1.2×). Values enter from `Scalar` rounded the same way
//! and saturated to their bound, and leave exactly (a shift).

use crate::math::scalar::Scalar;

/// Lanes per block: the constraint layout is the same for every instruction
/// set (AVX2 takes a block at once, the portable path goes lane by lane).
pub(crate) const LANES: usize = 8;

/// Fractional bits of velocities, rim speeds and impulses (Q16.16).
pub(crate) const FV: u32 = 16;
/// Fractional bits of position and rim-rotation changes (Q12.20).
pub(crate) const FP: u32 = 20;
/// Fractional bits of unit vectors, ratios and scales (Q2.30).
pub(crate) const FU: u32 = 30;
/// Fractional bits of arms in body radii and block couplings (Q3.29).
pub(crate) const FR: u32 = 29;
/// Fractional bits of separations (Q13.19).
pub(crate) const FS: u32 = 19;
/// Fractional bits of rates, 1/s (Q22.10).
pub(crate) const FQ: u32 = 10;
/// Fractional bits of the friction factor (Q9.23).
pub(crate) const FPHI: u32 = 23;
/// Fractional bits of the block inverse's entries (Q5.27).
pub(crate) const FM: u32 = 27;

/// The velocity wall, m/s: every linear velocity component and rim speed in the
/// solver is clamped to ±`V_WALL` after each update
/// ([`MAX_LINEAR_SPEED_LIMIT`](crate::limits::MAX_LINEAR_SPEED_LIMIT)). The
/// format holds 16 times more; the bounds of every sum spend that room.
pub(crate) const V_WALL: i32 = 2048 << FV;
/// The largest accumulated impulse of a row, in velocity units (m/s): Λ, the
/// "crush limit". One contact transmits at most Λ·m_eff N·s per sub-step; a
/// body resting on the ground at 240 Hz sub-steps could carry 800,000 times its
/// weight, far outside what a stack holds anyway.
pub(crate) const LAMBDA_MAX: i32 = 8192 << FV;
/// The largest bias a speculative (still apart) point gets, m/s: a gap that
/// could not close at 4,096 m/s stops an approach faster than that.
pub(crate) const SPEC_BIAS_MAX: i64 = 4096;
/// Contact arms in body radii are clamped to ±2 (a deep overlap puts the
/// midway anchor outside the body).
pub(crate) const ARM_MAX: i64 = 2;
/// The angular ratio γ̂ is clamped to ±1.5 (≤ √2 for every convex shape).
pub(crate) const GAMMA_MAX: Scalar = Scalar::lit("1.5");
/// The friction factor φ = μ·k_t/k_n is clamped below 256.
pub(crate) const PHI_MAX: i64 = 256;
/// A two-point block is solved together only when every entry of its
/// normalised inverse is below 16 (a well-conditioned pair).
pub(crate) const BLOCK_MAX: Scalar = Scalar::from_int(16);

/// `(a·b + 2^(K−1)) >> K` on the exact 64-bit product, narrowed to `i32`.
/// The callers' bounds make the narrowing lossless.
#[inline(always)]
pub(crate) fn mul<const K: u32>(a: i32, b: i32) -> i32 {
    ((i64::from(a) * i64::from(b) + (1i64 << (K - 1))) >> K) as i32
}

/// A `Scalar` in a lane of `f` fractional bits, rounded half up and saturated
/// to ±`bound` (in the lane's units, whole numbers; at most the format's edge).
#[inline]
pub(crate) fn from_scalar(x: Scalar, f: u32, bound: i64) -> i32 {
    let shift = 32 - f;
    let bits = x.to_bits();
    let rounded = (bits >> shift) + ((bits >> (shift - 1)) & 1);
    let hi = (bound << f).min(i64::from(i32::MAX));
    sym(rounded, hi) as i32
}

/// A lane of `f` fractional bits as a `Scalar` (exact).
#[inline]
pub(crate) fn to_scalar(x: i32, f: u32) -> Scalar {
    Scalar::from_bits(i64::from(x) << (32 - f))
}

/// A 64-bit sum of a Q16.16 value as a `Scalar` (saturating).
#[inline]
pub(crate) fn wide_to_scalar(x: i64) -> Scalar {
    Scalar::from_bits(x.saturating_mul(1 << (32 - FV)))
}

/// A velocity (m/s) as a lane, saturated at the wall.
#[inline]
pub(crate) fn velocity(x: Scalar) -> i32 {
    from_scalar(x, FV, 2048)
}

/// `x` clamped to ±`bound` (`bound ≥ 0`): `x.clamp(-bound, bound)`.
///
/// The contact prepare clamps some fifty values an arbiter, and a joint's
/// iterations a dozen a sub-step, and almost none of them is ever out of
/// range, so the test is one add and one unsigned comparison
/// (x + bound ∈ [0, 2·bound] exactly when x is in range; any other x, wrapped
/// or not, lands at or above 2⁶³ or above 2·bound) and the clamp a cold call,
/// not a two-`cmov` chain (with prepare's `inverse` inlined by hand, the large
/// scene's 20 steps: 2,577.2 → 2,542.5 M instructions; the joints' clamps,
/// the joint grid's 10 steps: 1,435.1 → 1,419.7 M).
#[inline(always)]
pub(crate) fn sym(x: i64, bound: i64) -> i64 {
    // From 2⁶² on, x + bound of an x below −bound can wrap to at most 2·bound
    // and pass the test: such bounds take the plain clamp. Every caller's
    // bound is a constant, so the branch folds away.
    if bound >= 1 << 62 {
        return x.clamp(-bound, bound);
    }
    if within(x, bound) {
        x
    } else {
        clamp_cold(x, bound)
    }
}

/// `-bound ≤ x ≤ bound`, for `0 ≤ bound < 2⁶²`, as [`sym`] tests it: one add
/// and one unsigned comparison.
#[inline(always)]
pub(crate) fn within(x: i64, bound: i64) -> bool {
    x.wrapping_add(bound).cast_unsigned() <= bound.cast_unsigned() << 1
}

#[cold]
#[inline(never)]
fn clamp_cold(x: i64, bound: i64) -> i64 {
    x.clamp(-bound, bound)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_round_half_up_and_reach_the_format_edges() {
        assert_eq!(mul::<16>(3 << 16, 5 << 16), 15 << 16);
        // ½ ulp rounds up, −½ ulp rounds up (toward +∞).
        assert_eq!(mul::<1>(1, 1), 1);
        assert_eq!(mul::<1>(-1, 1), 0);
        // The largest bounded product: a wall speed times a unit normal.
        assert_eq!(mul::<FU>(V_WALL, 1 << FU), V_WALL);
        assert_eq!(mul::<FU>(-V_WALL, 1 << FU), -V_WALL);
        // Λ by the largest γ̂ fits the rim-speed format with room.
        let g = from_scalar(GAMMA_MAX, FU, 2);
        let x = i64::from(V_WALL) + 2 * i64::from(mul::<FU>(g, LAMBDA_MAX));
        assert!(x < i64::from(i32::MAX));
    }

    #[test]
    fn conversions_saturate_at_the_bound_and_return_exactly() {
        assert_eq!(velocity(Scalar::from_int(5000)), V_WALL);
        assert_eq!(velocity(Scalar::from_int(-5000)), -V_WALL);
        assert_eq!(velocity(Scalar::MAX), V_WALL);
        assert_eq!(velocity(Scalar::MIN), -V_WALL);
        let v = Scalar::lit("-3.25");
        assert_eq!(to_scalar(velocity(v), FV), v);
        // Rounding half up of a value between two lane steps.
        let half = Scalar::from_bits(1 << 15);
        assert_eq!(velocity(half), 1);
        assert_eq!(velocity(-half), 0);
        assert_eq!(from_scalar(Scalar::ONE, FU, 1), 1 << FU);
        assert_eq!(from_scalar(-Scalar::ONE, FU, 1), -(1 << FU));
    }

    /// The pivot kernels' biased product shift gives `mul_shift`'s bits (and
    /// the exact rounded quotient) at the ends of the `i32` range, at ±½ ulp
    /// and on random lanes, for every shift the pivot kernels use and the
    /// extremes.
    /// (Its eight-lane form is plain code, safe on any processor.)
    #[test]
    fn biased_product_shift_equals_the_arithmetic_one() {
        use crate::solver::joint_lanes::{FA, FD, FH, FK};
        fn check<const K: u32>(a: [i32; LANES], b: [i32; LANES]) {
            let (a, b) = (L(a), L(b));
            let got = L64::<LANES>::mul_shift_biased::<K>(a, b);
            assert_eq!(got, L64::<LANES>::mul_shift::<K>(a, b), "K = {K}");
            for ((&g, &x), &y) in got.0.iter().zip(&a.0).zip(&b.0) {
                let exact = (i128::from(x) * i128::from(y) + (1i128 << (K - 1))).div_euclid(1i128 << K);
                assert_eq!(i128::from(g), exact, "{x} * {y} >> {K}");
            }
        }
        let edges = [i32::MIN, i32::MIN + 1, -(1 << 16), -1, 0, 1, 1 << 16, i32::MAX - 1, i32::MAX];
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 16) as u32 as i32
        };
        for round in 0..200 {
            let mut a = [0; LANES];
            let mut b = [0; LANES];
            for (k, (p, q)) in a.iter_mut().zip(b.iter_mut()).enumerate() {
                // Every pair of edge values over the rounds, then random lanes.
                let i = round * LANES + k;
                (*p, *q) = if i < edges.len() * edges.len() {
                    (edges[i % edges.len()], edges[i / edges.len()])
                } else {
                    (next(), next())
                };
            }
            check::<1>(a, b);
            check::<FH>(a, b);
            check::<FU>(a, b);
            check::<{ FD + FQ - FV }>(a, b);
            check::<{ 2 * FA - FH }>(a, b);
            check::<FK>(a, b);
            check::<31>(a, b);
            check::<32>(a, b);
            check::<62>(a, b);
        }
    }
}

/// Eight lanes as `W` (`W` = 8; other widths are padded with zeros or cut):
/// the AVX2 helpers' eight-lane results as the kernels' lane types.
#[cfg(all(feature = "std", target_arch = "x86_64"))]
#[inline(always)]
fn resized<T: Copy + Default, const W: usize>(x: [T; LANES]) -> [T; W] {
    let mut r = [T::default(); W];
    for (r, x) in r.iter_mut().zip(x) {
        *r = x;
    }
    r
}

/// `W` lanes of `i32`: the kernels are written once over these and compiled
/// for each width and instruction set. Every operation is lane-wise and
/// exact, so no width or instruction set can change a result.
///
/// On x86-64 with `std`, eight lanes are the AVX2 kernels' alone: some of
/// their operations run AVX2 instructions ([`dispatch::avx2`](super::dispatch)),
/// so `L<8>` must be used only in code reached from `dispatch::run_avx2` (the
/// contact kernels' `WIDE` instantiation; the portable path solves one lane
/// at a time).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct L<const W: usize>(pub(crate) [i32; W]);

/// A lane mask: −1 (all bits set) where true, 0 where false, so that every
/// mask operation is a vector bit operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct M<const W: usize>(pub(crate) [i32; W]);

/// A lane-wise binary operation, written as a plain loop (no closure), so
/// that it inlines and vectorises wherever the kernel is compiled.
macro_rules! lanewise {
    ($(#[$m:meta])* $name:ident, |$a:ident, $b:ident| $e:expr) => {
        $(#[$m])*
        #[inline(always)]
        pub(crate) fn $name(self, o: Self) -> Self {
            let mut r = self.0;
            for (r, &$b) in r.iter_mut().zip(&o.0) {
                let $a = *r;
                *r = $e;
            }
            Self(r)
        }
    };
}

impl<const W: usize> L<W> {
    /// The lanes as eight (`W` = 8; other widths are padded or cut).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[inline(always)]
    pub(crate) fn to8(self) -> [i32; LANES] {
        let mut r = [0; LANES];
        for (r, &x) in r.iter_mut().zip(&self.0) {
            *r = x;
        }
        r
    }
    /// Eight lanes as `W` (`W` = 8; other widths are padded or cut).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[inline(always)]
    pub(crate) fn from8(x: [i32; LANES]) -> Self {
        Self(resized(x))
    }
    #[inline(always)]
    pub(crate) fn splat(x: i32) -> Self {
        Self([x; W])
    }
    lanewise!(add, |a, b| a.wrapping_add(b));
    lanewise!(sub, |a, b| a.wrapping_sub(b));
    lanewise!(min, |a, b| if a < b { a } else { b });
    lanewise!(max, |a, b| if a > b { a } else { b });
    #[inline(always)]
    pub(crate) fn neg(self) -> Self {
        let mut r = self.0;
        for x in r.iter_mut() {
            *x = x.wrapping_neg();
        }
        Self(r)
    }
    /// Clamped to ±`b` (b ≥ 0).
    #[inline(always)]
    pub(crate) fn clamp_abs(self, b: i32) -> Self {
        self.max(Self::splat(-b)).min(Self::splat(b))
    }
    #[inline(always)]
    pub(crate) fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }
    /// The lane-wise product with shift `K` ([`mul`]). Eight lanes on
    /// x86-64 are the AVX2 kernels' (see [`L`]): their products are
    /// `dispatch::avx2::mul`, the same bits in nine instructions where the
    /// loop below compiles to twelve (measured with the gather: large 20
    /// 2,400.5 M → 2,325.6 M instructions, mixed 901.2 M → 865.3 M).
    #[inline(always)]
    pub(crate) fn mul<const K: u32>(self, o: Self) -> Self {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        if W == LANES {
            return Self::from8(super::dispatch::avx2::mul::<K>(self.to8(), o.to8()));
        }
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            *r = mul::<K>(*r, b);
        }
        Self(r)
    }
    #[inline(always)]
    pub(crate) fn gt(self, o: Self) -> M<W> {
        let mut r = [0; W];
        for ((r, &a), &b) in r.iter_mut().zip(&self.0).zip(&o.0) {
            *r = -i32::from(a > b);
        }
        M(r)
    }
    #[inline(always)]
    pub(crate) fn lt(self, o: Self) -> M<W> {
        o.gt(self)
    }
    /// Lanes of `a` where `m`, else of `self`.
    #[inline(always)]
    pub(crate) fn select(self, m: M<W>, a: Self) -> Self {
        let mut r = self.0;
        for ((r, &a), &m) in r.iter_mut().zip(&a.0).zip(&m.0) {
            *r = (a & m) | (*r & !m);
        }
        Self(r)
    }
    /// The lanes whose bits `bit` are set.
    #[inline(always)]
    pub(crate) fn has(self, bit: i32) -> M<W> {
        let mut r = [0; W];
        for (r, &a) in r.iter_mut().zip(&self.0) {
            *r = -i32::from(a & bit != 0);
        }
        M(r)
    }
    /// Arithmetic shift right by two (Q16.16 → Q18.14 after the rounding add).
    #[inline(always)]
    pub(crate) fn shr2(self) -> Self {
        let mut r = self.0;
        for x in r.iter_mut() {
            *x >>= 2;
        }
        Self(r)
    }
    /// Lanes not equal to zero.
    #[inline(always)]
    pub(crate) fn nonzero(self) -> M<W> {
        self.has(-1)
    }
}

impl<const W: usize> M<W> {
    /// Every lane.
    #[inline(always)]
    pub(crate) fn all() -> Self {
        Self([-1; W])
    }
    /// No lane.
    #[inline(always)]
    pub(crate) fn none() -> Self {
        Self([0; W])
    }
    /// Whether lane `i` is set.
    #[inline(always)]
    pub(crate) fn is(&self, i: usize) -> bool {
        self.0.get(i).is_some_and(|&m| m != 0)
    }
    #[inline(always)]
    pub(crate) fn and(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            *r &= b;
        }
        Self(r)
    }
    #[inline(always)]
    pub(crate) fn or(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            *r |= b;
        }
        Self(r)
    }
    #[inline(always)]
    pub(crate) fn not(self) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r = !*r;
        }
        Self(r)
    }
    /// True if every lane is set: used only to choose how to store a result
    /// (the same values either way), never to choose the result.
    #[inline(always)]
    pub(crate) fn every(self) -> bool {
        self.0.iter().fold(-1, |a, &m| a & m) == -1
    }
    /// True if any lane is set: used only to skip work whose results every
    /// lane would discard, never to choose a result.
    #[inline(always)]
    pub(crate) fn any(self) -> bool {
        self.0.iter().fold(0, |a, &m| a | m) != 0
    }
}

/// `W` lanes of `i64`: the 2×2 block's right-hand side and products.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct L64<const W: usize>(pub(crate) [i64; W]);

impl<const W: usize> L64<W> {
    /// Eight lanes as `W` (`W` = 8; other widths are padded or cut).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[inline(always)]
    pub(crate) fn from8(x: [i64; LANES]) -> Self {
        Self(resized(x))
    }
    /// Sign-extended from `i32` lanes.
    #[inline(always)]
    pub(crate) fn from(x: L<W>) -> Self {
        let mut r = [0i64; W];
        for (r, &x) in r.iter_mut().zip(&x.0) {
            *r = i64::from(x);
        }
        Self(r)
    }
    /// `(a·b + 2^(K−1)) >> K` on the exact 64-bit products of `i32` lanes.
    #[inline(always)]
    pub(crate) fn mul_shift<const K: u32>(a: L<W>, b: L<W>) -> Self {
        let mut r = [0i64; W];
        for ((r, &a), &b) in r.iter_mut().zip(&a.0).zip(&b.0) {
            *r = (i64::from(a) * i64::from(b) + (1i64 << (K - 1))) >> K;
        }
        Self(r)
    }
    /// [`mul_shift`](Self::mul_shift), the same bits, for the pivot kernels.
    ///
    /// Eight lanes on x86-64 are the AVX2 kernels' (see [`L`]), and AVX2 has
    /// no 64-bit arithmetic shift: LLVM builds one from a 32-bit arithmetic
    /// shift, a logical one and a blend. Here the product is shifted
    /// logically instead, 2⁶² above itself: a·b lies in [−2⁶² + 2³¹, 2⁶²], so
    /// a·b + 2^(K−1) + 2⁶² is in [0, 2⁶⁴) as a `u64`, and since 2⁶² is a
    /// multiple of 2^K its logical shift is the arithmetic shift's value plus
    /// 2^(62−K), which is subtracted. Joint grid, 10 steps: 849.1 → 834.3 M
    /// instructions. In the contact kernels' 2×2 block, whose products are
    /// summed in pairs, it measured 0.1 % more (large pyramid and
    /// pyramid_20), so they keep [`mul_shift`](Self::mul_shift).
    #[inline(always)]
    pub(crate) fn mul_shift_biased<const K: u32>(a: L<W>, b: L<W>) -> Self {
        const { assert!(K >= 1 && K <= 62) };
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        if W == LANES {
            let bias = (1u64 << 62) + (1u64 << (K - 1));
            let mut r = [0i64; W];
            for ((r, &a), &b) in r.iter_mut().zip(&a.0).zip(&b.0) {
                let p = (i64::from(a) * i64::from(b)).cast_unsigned();
                *r = (p.wrapping_add(bias) >> K).cast_signed() - (1i64 << (62 - K));
            }
            return Self(r);
        }
        Self::mul_shift::<K>(a, b)
    }
    #[inline(always)]
    pub(crate) fn add(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            *r = r.wrapping_add(b);
        }
        Self(r)
    }
    #[inline(always)]
    pub(crate) fn sub(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            *r = r.wrapping_sub(b);
        }
        Self(r)
    }
    #[inline(always)]
    pub(crate) fn neg(self) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r = r.wrapping_neg();
        }
        Self(r)
    }
    /// Lanes ≥ 0.
    #[inline(always)]
    pub(crate) fn nonneg(self) -> M<W> {
        let mut r = [0; W];
        for (r, &a) in r.iter_mut().zip(&self.0) {
            *r = -i32::from(a >= 0);
        }
        M(r)
    }
    /// Halved, rounded half up, as `i32` (a Q16.16 value as Q17.15; the
    /// callers' bounds keep it within 2³¹).
    #[inline(always)]
    pub(crate) fn narrow_shr1(self) -> L<W> {
        let mut r = [0i32; W];
        for (r, &a) in r.iter_mut().zip(&self.0) {
            *r = ((a + 1) >> 1) as i32;
        }
        L(r)
    }
    /// Clamped to ±`b` (b ≥ 0).
    #[inline(always)]
    pub(crate) fn clamp_abs(self, b: i64) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r = (*r).clamp(-b, b);
        }
        Self(r)
    }
    /// The low 32 bits of each lane (the callers' bounds make it lossless).
    #[inline(always)]
    pub(crate) fn narrow(self) -> L<W> {
        let mut r = [0i32; W];
        for (r, &a) in r.iter_mut().zip(&self.0) {
            *r = a as i32;
        }
        L(r)
    }
    /// `x >> k` (arithmetic; `k` < 64, a constant where inlined).
    #[inline(always)]
    pub(crate) fn shr(self, k: u32) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r >>= k % 64;
        }
        Self(r)
    }
    /// `x << k` (bits shifted out are lost; `k` < 64).
    #[inline(always)]
    pub(crate) fn shl(self, k: u32) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r <<= k % 64;
        }
        Self(r)
    }
    /// Bitwise and with `b`.
    #[inline(always)]
    pub(crate) fn and(self, b: i64) -> Self {
        let mut r = self.0;
        for r in r.iter_mut() {
            *r &= b;
        }
        Self(r)
    }
    /// The saturating sum (`i64::saturating_add`), without a branch.
    #[inline(always)]
    pub(crate) fn saturating_add(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            let a = *r;
            let s = a.wrapping_add(b);
            // Overflow: both operands of one sign and the sum of the other;
            // then the bound of a's sign.
            let over = ((a ^ s) & (b ^ s)) < 0;
            *r = if over { (a >> 63) ^ i64::MAX } else { s };
        }
        Self(r)
    }
    /// The saturating difference (`i64::saturating_sub`), without a branch.
    #[inline(always)]
    pub(crate) fn saturating_sub(self, o: Self) -> Self {
        let mut r = self.0;
        for (r, &b) in r.iter_mut().zip(&o.0) {
            let a = *r;
            let s = a.wrapping_sub(b);
            let over = ((a ^ b) & (a ^ s)) < 0;
            *r = if over { (a >> 63) ^ i64::MAX } else { s };
        }
        Self(r)
    }
    /// Lanes made of low and high words.
    #[inline(always)]
    pub(crate) fn join(lo: L<W>, hi: L<W>) -> Self {
        let mut r = [0i64; W];
        for ((r, &lo), &hi) in r.iter_mut().zip(&lo.0).zip(&hi.0) {
            *r = (i64::from(hi) << 32) | i64::from(lo.cast_unsigned());
        }
        Self(r)
    }
    /// The low and high words of each lane.
    #[inline(always)]
    pub(crate) fn split(self) -> (L<W>, L<W>) {
        let (mut lo, mut hi) = ([0i32; W], [0i32; W]);
        for ((lo, hi), &a) in lo.iter_mut().zip(hi.iter_mut()).zip(&self.0) {
            (*lo, *hi) = (a as i32, (a >> 32) as i32);
        }
        (L(lo), L(hi))
    }
    /// Clamped to [0, `hi`] and narrowed.
    #[inline(always)]
    pub(crate) fn clamp_narrow(self, hi: i32) -> L<W> {
        let mut r = [0i32; W];
        for (r, &a) in r.iter_mut().zip(&self.0) {
            *r = a.clamp(0, i64::from(hi)) as i32;
        }
        L(r)
    }
}
