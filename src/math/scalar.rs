//! The one number type of the engine and the few helpers every stage uses.
//!
//! `Scalar` is Q32.32 fixed point (`fixed::types::I32F32`): 32 integer bits, 32
//! fraction bits. Resolution is 2^-32 ≈ 2.3e-10 and range ±2^31 ≈ ±2.1e9. The
//! range of *squared* quantities is therefore only |x| < 46,340, which is why the
//! engine squares relative, local quantities and never absolute world positions.
//!
//! # Overflow policy
//! Plain `*`/`+` on a fixed-point number panic on overflow in debug builds and wrap
//! in release builds, which would break the contract that both builds behave the
//! same. Engine code therefore never applies a raw operator to a `Scalar`: it spells
//! out a policy at every operation (`saturating_*` almost everywhere), and the helpers
//! here cover the two operations that can fail outright: division by zero and the
//! square root of a negative number.

/// The fixed-point number type used for every physical quantity (Q32.32).
pub type Scalar = fixed::types::I32F32;

/// 0.
pub const ZERO: Scalar = Scalar::ZERO;
/// 1.
pub const ONE: Scalar = Scalar::ONE;
/// 0.5.
pub const HALF: Scalar = Scalar::lit("0.5");
/// 2.
pub const TWO: Scalar = Scalar::const_from_int(2);
/// π, rounded toward zero to Q32.32 (0.52 ulp below π; the `fixed` crate's
/// constant). `atan2` never returns more than this.
pub const PI: Scalar = Scalar::PI;
/// 2π, as the nearest Q32.32 value.
pub const TAU: Scalar = Scalar::TAU;
/// π/2, as the nearest Q32.32 value.
pub const FRAC_PI_2: Scalar = Scalar::FRAC_PI_2;
/// The smallest positive value, 2^-32.
pub const EPSILON: Scalar = Scalar::DELTA;

/// A `Scalar` from a whole number, usable in `const` items.
#[inline]
#[must_use]
pub const fn from_int(v: i32) -> Scalar {
    Scalar::const_from_int(v as i64)
}

/// Fast saturating arithmetic on [`Scalar`], used on the step's hot paths.
///
/// `fixed`'s `saturating_mul` is correct but generic and about twice as slow as
/// needed here; [`ScalarExt::sat_mul`] computes the same bits (the full 128-bit
/// product, shifted right by 32 with floor rounding, clamped to the range), which
/// a test checks against `fixed` over random and extreme inputs.
pub trait ScalarExt: Sized {
    /// `self · rhs`, saturating, bit-identical to `Scalar::saturating_mul`.
    #[must_use]
    fn sat_mul(self, rhs: Self) -> Self;
    /// `self + rhs`, saturating, bit-identical to `Scalar::saturating_add`.
    #[must_use]
    fn sat_add(self, rhs: Self) -> Self;
    /// `self − rhs`, saturating, bit-identical to `Scalar::saturating_sub`.
    #[must_use]
    fn sat_sub(self, rhs: Self) -> Self;
}

impl ScalarExt for Scalar {
    #[inline(always)]
    fn sat_mul(self, rhs: Self) -> Self {
        // |a·b| < 2^126: the i128 product cannot overflow. The result is bits
        // 32..96 of the product (the shift floors, as `fixed` does); it fits when
        // bits 95..128 are all equal, i.e. the high word lies in [−2³¹, 2³¹),
        // tested as one add and one shift. That test is off the result's
        // dependency chain and almost always true, so the clamp is a cold branch,
        // not a `cmov` chain (about 40 % less latency per product in the solver).
        let full = i128::from(self.to_bits()).wrapping_mul(i128::from(rhs.to_bits()));
        let hi = (full >> 64) as i64;
        if (hi as u64).wrapping_add(1 << 31) >> 32 == 0 {
            Scalar::from_bits(middle_word(full as u64, hi))
        } else {
            saturated(hi)
        }
    }

    #[inline(always)]
    fn sat_add(self, rhs: Self) -> Self {
        // On overflow both operands have the sign of the exact sum.
        match self.to_bits().overflowing_add(rhs.to_bits()) {
            (r, false) => Scalar::from_bits(r),
            (_, true) => saturated(self.to_bits()),
        }
    }

    #[inline(always)]
    fn sat_sub(self, rhs: Self) -> Self {
        // On overflow the exact difference has the sign of `self`.
        match self.to_bits().overflowing_sub(rhs.to_bits()) {
            (r, false) => Scalar::from_bits(r),
            (_, true) => saturated(self.to_bits()),
        }
    }
}

/// Bits 32..96 of the 128-bit product whose low and high words are `lo` and
/// `hi`: `(lo >> 32) | (hi << 32)`.
///
/// Written that way (or as the `i128` shift) the compiler recognises a funnel
/// shift and, on x86-64 with the default tuning, emits `SHLD`: one micro-op on
/// Intel but six on AMD's Zen 1 (this project's benchmark machine), where it
/// made up half the micro-ops of a product. Putting the low half of `hi` in place
/// of that of `lo` (two XORs, no mask constant to keep in a register) and swapping
/// the halves with a rotate is not matched, and costs three one-cycle operations
/// everywhere: pyramid_20 1.47 → 1.32 ms/step, large_pyramid 42.1 → 38.9 ms/step
/// on this machine (medians of alternating runs). Other targets keep the plain
/// shift, which AArch64 does in one `EXTR`.
/// The same bits either way (see `both_middle_word_forms_take_bits_32_to_96`).
#[inline(always)]
fn middle_word(lo: u64, hi: i64) -> i64 {
    if cfg!(target_arch = "x86_64") {
        middle_word_by_rotate(lo, hi)
    } else {
        middle_word_by_shifts(lo, hi)
    }
}

#[inline(always)]
fn middle_word_by_rotate(lo: u64, hi: i64) -> i64 {
    // The low half of `lo` becomes that of `hi` (x ^ x ^ h), then the halves swap.
    (lo ^ u64::from(lo as u32 ^ hi as u32)).rotate_right(32) as i64
}

#[inline(always)]
fn middle_word_by_shifts(lo: u64, hi: i64) -> i64 {
    ((lo >> 32) | ((hi as u64) << 32)) as i64
}

/// The bound a product or sum clamps to, by the sign of the exact result.
#[cold]
#[inline(never)]
fn saturated(sign: i64) -> Scalar {
    if sign < 0 {
        Scalar::MIN
    } else {
        Scalar::MAX
    }
}

/// `a / b`, saturating on overflow and returning 0 when `b` is 0.
///
/// Callers that need to tell a zero divisor apart check it themselves; inside the
/// step a zero divisor means a degenerate configuration whose correct response is
/// "no impulse", which 0 gives.
///
/// Bit-identical to `fixed`'s `saturating_div` (the quotient of the 96-bit
/// `a · 2³²` by `b`, truncated toward zero), which divides 128-bit integers in
/// software. When |a| ≤ 1, as for every reciprocal (the solver's effective
/// masses) and most of the solver's divisions, the dividend's magnitude fits
/// in 64 bits (or is exactly 2⁶⁴) and one 64-bit division gives the same
/// quotient at about half the cost; a test compares the two over random and
/// extreme inputs.
#[inline]
#[must_use]
pub fn div(a: Scalar, b: Scalar) -> Scalar {
    if b == ZERO {
        return ZERO;
    }
    let (ua, ub) = (a.to_bits().unsigned_abs(), b.to_bits().unsigned_abs());
    let magnitude = if ua < 1 << 32 {
        (ua << 32) / ub
    } else if ua == 1 << 32 {
        // ⌊2⁶⁴ / ub⌋ from ⌊(2⁶⁴ − 1) / ub⌋: one more exactly when ub divides 2⁶⁴.
        // (ub = 1 overflows either way: u64::MAX, which saturates below.)
        let (q, r) = (u64::MAX / ub, u64::MAX % ub);
        q.saturating_add(u64::from(r == ub - 1))
    } else {
        return a.saturating_div(b);
    };
    let negative = (a < ZERO) != (b < ZERO);
    if negative {
        // −2⁶³ is representable; anything larger in magnitude saturates.
        match 0i64.checked_sub_unsigned(magnitude) {
            Some(v) => Scalar::from_bits(v),
            None => Scalar::MIN,
        }
    } else {
        i64::try_from(magnitude).map_or(Scalar::MAX, Scalar::from_bits)
    }
}

/// Square root, with 0 for zero or negative input. Deterministic: the `fixed`
/// crate computes it with integer operations only.
#[inline]
#[must_use]
pub fn sqrt(x: Scalar) -> Scalar {
    if x <= ZERO {
        ZERO
    } else {
        x.sqrt()
    }
}

/// `1 / x`, saturating, with 0 for `x == 0` (the convention for inverse masses).
#[inline]
#[must_use]
pub fn recip(x: Scalar) -> Scalar {
    div(ONE, x)
}

/// `x` clamped to `[lo, hi]` (expects `lo <= hi`; returns `lo` otherwise).
#[inline]
#[must_use]
pub fn clamp(x: Scalar, lo: Scalar, hi: Scalar) -> Scalar {
    if x > hi {
        hi
    } else if x < lo {
        lo
    } else {
        x
    }
}

/// Conversion from `f64` at the API edge: `None` for NaN, infinity or a value
/// outside the `Scalar` range. Rounds to the nearest representable value, which
/// IEEE-754 makes identical on every target.
#[inline]
#[must_use]
pub fn checked_from_f64(v: f64) -> Option<Scalar> {
    Scalar::checked_from_num(v)
}

/// Conversion from `f32` at the API edge; see [`checked_from_f64`].
#[inline]
#[must_use]
pub fn checked_from_f32(v: f32) -> Option<Scalar> {
    Scalar::checked_from_num(v)
}

/// Conversion from `f64` at the API edge with an error naming the parameter:
/// [`Error::NotFinite`](crate::Error::NotFinite) for NaN, infinity or a value
/// outside the `Scalar` range.
///
/// # Errors
/// As described.
pub fn try_from_f64(v: f64, what: &'static str) -> Result<Scalar, crate::Error> {
    checked_from_f64(v).ok_or(crate::Error::NotFinite { what })
}

/// Conversion from `f32` at the API edge; see [`try_from_f64`].
///
/// # Errors
/// [`Error::NotFinite`](crate::Error::NotFinite).
pub fn try_from_f32(v: f32, what: &'static str) -> Result<Scalar, crate::Error> {
    checked_from_f32(v).ok_or(crate::Error::NotFinite { what })
}

/// Conversion to `f64` for output (rendering, logging). Never used by the step.
#[inline]
#[must_use]
pub fn to_f64(v: Scalar) -> f64 {
    v.to_num::<f64>()
}

/// Conversion to `f32` for output (rendering, logging). Never used by the step.
#[inline]
#[must_use]
pub fn to_f32(v: Scalar) -> f32 {
    v.to_num::<f32>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn div_by_zero_is_zero_and_overflow_saturates() {
        assert_eq!(div(ONE, ZERO), ZERO);
        assert_eq!(div(Scalar::MAX, EPSILON), Scalar::MAX);
        assert_eq!(div(from_int(3), from_int(2)), Scalar::lit("1.5"));
    }

    #[test]
    fn sat_mul_matches_fixed_bit_for_bit() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            // xorshift64*: a deterministic spread over all bit patterns.
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            x.wrapping_mul(0x2545_f491_4f6c_dd1d) as i64
        };
        let edges = [0, 1, -1, i64::MAX, i64::MIN, 1 << 32, -(1 << 32), 46_341 << 32, -(46_341 << 32)];
        for &a in &edges {
            for &b in &edges {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!(a.sat_mul(b), a.saturating_mul(b), "{a} {b}");
            }
        }
        for _ in 0..200_000 {
            let (a, b) = (next(), next());
            // Also small magnitudes, where real values live.
            for (a, b) in [(a, b), (a >> 24, b >> 24), (a >> 40, b >> 16)] {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!(a.sat_mul(b), a.saturating_mul(b), "{a} {b}");
            }
        }
    }

    #[test]
    fn both_middle_word_forms_take_bits_32_to_96() {
        let mut x: u64 = 0x94d0_49bb_1331_11eb;
        for _ in 0..100_000 {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            let lo = x.wrapping_mul(0x2545_f491_4f6c_dd1d);
            let hi = (x.rotate_left(17) as i64) >> (x % 40);
            let full = (i128::from(hi) << 64) | i128::from(lo);
            let expected = (full >> 32) as i64;
            assert_eq!(middle_word_by_rotate(lo, hi), expected, "{lo:x} {hi:x}");
            assert_eq!(middle_word_by_shifts(lo, hi), expected, "{lo:x} {hi:x}");
        }
    }

    #[test]
    fn sat_add_and_sub_match_fixed_bit_for_bit() {
        let edges = [0, 1, -1, 2, -2, i64::MAX, i64::MIN, i64::MAX - 1, i64::MIN + 1, 1 << 62, -(1 << 62)];
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        // Fixed arrays, so the test runs in the no-allocator build too.
        let mut random = [0i64; 2_000];
        for v in &mut random {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            *v = x.wrapping_mul(0x9e37_79b9_7f4a_7c15) as i64;
        }
        let vals = || edges.iter().chain(&random);
        for &a in vals() {
            for &b in vals().take(200) {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!(a.sat_add(b), a.saturating_add(b), "{a} + {b}");
                assert_eq!(a.sat_sub(b), a.saturating_sub(b), "{a} - {b}");
            }
        }
    }

    #[test]
    fn div_matches_fixed_bit_for_bit() {
        let edges = [
            1,
            -1,
            2,
            -2,
            3,
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            (1 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
            -(1 << 32),
            1 << 31,
            1 << 33,
            3 << 30,
        ];
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        // Fixed arrays, so the test runs in the no-allocator build too.
        let mut random = [0i64; 3_000];
        for (k, v) in random.iter_mut().enumerate() {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            let r = x.wrapping_mul(0x2545_f491_4f6c_dd1d) as i64;
            // All bit patterns, and magnitudes around 1 where real values live.
            *v = r >> (k % 48);
        }
        let vals = || edges.iter().chain(&random).filter(|&&v| v != 0);
        for &a in vals().chain(&[0]) {
            for &b in vals() {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!(div(a, b), a.saturating_div(b), "{a} / {b}");
            }
        }
    }

    #[test]
    fn sqrt_of_negative_is_zero() {
        assert_eq!(sqrt(from_int(-4)), ZERO);
        assert_eq!(sqrt(from_int(9)), from_int(3));
    }

    #[test]
    fn float_conversion_rejects_non_finite() {
        assert!(checked_from_f64(f64::NAN).is_none());
        assert!(checked_from_f64(f64::INFINITY).is_none());
        assert!(checked_from_f64(1e12).is_none());
        assert_eq!(checked_from_f64(0.5), Some(HALF));
    }
}
