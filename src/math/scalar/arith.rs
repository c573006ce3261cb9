//! The arithmetic of [`Scalar`]: saturating operators, and the fast product and
//! quotient behind them, each tested bit for bit against `fixed`'s own
//! saturating operations.

use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use super::{Scalar, ZERO};

#[inline(always)]
fn sat_mul(a: Scalar, b: Scalar) -> Scalar {
    // |a·b| < 2^126: the i128 product cannot overflow. The result is bits
    // 32..96 of the product (the shift floors, as `fixed` does); it fits when
    // bits 95..128 are all equal, i.e. the high word lies in [−2³¹, 2³¹),
    // tested as one add and one shift. That test is off the result's
    // dependency chain and almost always true, so the clamp is a cold branch,
    // not a `cmov` chain (about 40 % less latency per product in the solver).
    let full = i128::from(a.to_bits()).wrapping_mul(i128::from(b.to_bits()));
    let hi = (full >> 64) as i64;
    if (hi as u64).wrapping_add(1 << 31) >> 32 == 0 {
        Scalar::from_bits(middle_word(full as u64, hi))
    } else {
        saturated(hi)
    }
}

#[inline(always)]
fn sat_add(a: Scalar, b: Scalar) -> Scalar {
    // On overflow both operands have the sign of the exact sum.
    match a.to_bits().overflowing_add(b.to_bits()) {
        (r, false) => Scalar::from_bits(r),
        (_, true) => saturated(a.to_bits()),
    }
}

#[inline(always)]
fn sat_sub(a: Scalar, b: Scalar) -> Scalar {
    // On overflow the exact difference has the sign of `a`.
    match a.to_bits().overflowing_sub(b.to_bits()) {
        (r, false) => Scalar::from_bits(r),
        (_, true) => saturated(a.to_bits()),
    }
}

/// Whether `|a| < 1`: then [`mul_below_one`] by `a` is the saturating
/// product's value, whatever the other factor.
#[inline(always)]
pub(crate) fn below_one(a: Scalar) -> bool {
    a.to_bits().unsigned_abs() < 1 << 32
}

/// `a * b` for `|a| < 1` (see [`below_one`]): the same bits as the
/// saturating product, without its test for saturation.
///
/// That product is bits 32..96 of the exact 128-bit product, saturated when
/// they do not fit an `i64`. With `|a| < 2³²` and `|b| ≤ 2⁶³` in bits,
/// `|a·b| < 2⁹⁵`, so `⌊a·b / 2³²⌋` lies in `[−2⁶³, 2⁶³)`: it always fits, and
/// the shift alone gives it. Face normals off the axes and the rotations of
/// turned bodies have both components below 1; their products are most of
/// those in the polygon narrow phase, the polygons' boxes and the
/// integration of rotations.
#[inline(always)]
pub(crate) fn mul_below_one(a: Scalar, b: Scalar) -> Scalar {
    Scalar::from_bits(product_bits(a.to_bits(), b.to_bits()))
}

/// `⌊a·b / 2³²⌋` of two `Scalar` bit patterns, for a caller that knows it
/// fits an `i64`: the saturating product's bits without its test. Taken as
/// [`middle_word`] of the 128-bit product, not a shift of it, which on
/// x86-64 is the funnel shift `SHLD` (see there). On this project's Zen 4
/// (AMD EPYC, family 25 model 17) that cost 1.7 % more instructions and was
/// faster: the fastest of 10–15 alternating runs went 0.319 → 0.310 ms a step
/// (20-row pyramid), 0.355 → 0.348 ms (the rollback scene) and 13.09 →
/// 12.80 ms (100-row pyramid), with this function in `mul_below_one`,
/// `Rot::integrate` and the contact prepare.
#[inline(always)]
pub(crate) fn product_bits(a: i64, b: i64) -> i64 {
    let full = i128::from(a).wrapping_mul(i128::from(b));
    middle_word(full as u64, (full >> 64) as i64)
}

impl Add for Scalar {
    type Output = Self;
    /// Saturating addition.
    #[inline(always)]
    fn add(self, rhs: Self) -> Self {
        sat_add(self, rhs)
    }
}

impl Sub for Scalar {
    type Output = Self;
    /// Saturating subtraction.
    #[inline(always)]
    fn sub(self, rhs: Self) -> Self {
        sat_sub(self, rhs)
    }
}

impl Mul for Scalar {
    type Output = Self;
    /// Saturating multiplication, rounded toward −∞ (as `fixed` rounds).
    #[inline(always)]
    fn mul(self, rhs: Self) -> Self {
        sat_mul(self, rhs)
    }
}

impl Div for Scalar {
    type Output = Self;
    /// Saturating division, truncated toward zero; `a / 0` saturates by the sign
    /// of `a` (0 for `0 / 0`).
    #[inline]
    fn div(self, rhs: Self) -> Self {
        if rhs == ZERO {
            saturated_by_sign(self.to_bits())
        } else {
            div_nonzero(self, rhs)
        }
    }
}

impl Neg for Scalar {
    type Output = Self;
    /// Saturating negation (`-MIN` is `MAX`).
    #[inline(always)]
    fn neg(self) -> Self {
        Self(self.0.saturating_neg())
    }
}

impl Mul<i32> for Scalar {
    type Output = Self;
    /// Saturating multiplication by a whole number.
    #[inline]
    fn mul(self, rhs: i32) -> Self {
        self.mul_int(rhs)
    }
}

impl Mul<Scalar> for i32 {
    type Output = Scalar;
    /// Saturating multiplication by a whole number.
    #[inline]
    fn mul(self, rhs: Scalar) -> Scalar {
        rhs.mul_int(self)
    }
}

impl Div<i32> for Scalar {
    type Output = Self;
    /// Division by a whole number, truncated toward zero; by zero it saturates.
    #[inline]
    fn div(self, rhs: i32) -> Self {
        self.div_int(rhs)
    }
}

macro_rules! assign_ops {
    ($($tr:ident $method:ident $op:tt $rhs:ty;)*) => {$(
        impl $tr<$rhs> for Scalar {
            #[inline(always)]
            fn $method(&mut self, rhs: $rhs) {
                *self = *self $op rhs;
            }
        }
    )*};
}

assign_ops! {
    AddAssign add_assign + Scalar;
    SubAssign sub_assign - Scalar;
    MulAssign mul_assign * Scalar;
    DivAssign div_assign / Scalar;
    MulAssign mul_assign * i32;
    DivAssign div_assign / i32;
}

impl core::iter::Sum for Scalar {
    /// Saturating sum, in iteration order.
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::ZERO, |a, b| a + b)
    }
}

/// Bits 32..96 of the 128-bit product whose low and high words are `lo` and
/// `hi`: `(lo >> 32) | (hi << 32)`.
///
/// Written that way (or as the `i128` shift) the compiler recognises a funnel
/// shift and, on x86-64 with the default tuning, emits `SHLD`: one micro-op on
/// Intel but six on AMD's Zen 1 (this project's benchmark machine until
/// December 2026), where it made up half the micro-ops of a product. Putting the
/// low half of `hi` in place of that of `lo` (two XORs, no mask constant to keep
/// in a register) and swapping the halves with a rotate is not matched, and costs
/// three one-cycle operations everywhere: pyramid_20 1.47 → 1.32 ms/step,
/// large_pyramid 42.1 → 38.9 ms/step on that machine (medians of alternating
/// runs). On the Zen 4 that replaced it this form is still the faster one (see
/// [`product_bits`], measured there). Other targets keep the plain
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

/// The bound an operation clamps to for a result of the sign of `sign`; 0 for 0
/// (`0 / 0`).
#[cold]
#[inline(never)]
pub(super) fn saturated_by_sign(sign: i64) -> Scalar {
    match sign.signum() {
        -1 => Scalar::MIN,
        0 => Scalar::ZERO,
        _ => Scalar::MAX,
    }
}

/// `a / b` for `b ≠ 0`, saturating on overflow.
///
/// Bit-identical to `fixed`'s `saturating_div` (the quotient of the 96-bit
/// `a · 2³²` by `b`, truncated toward zero), which divides 128-bit integers in
/// software. When |a| ≤ 1, as for every reciprocal (the solver's effective
/// masses) and most of the solver's divisions, the dividend's magnitude fits
/// in 64 bits (or is exactly 2⁶⁴) and one 64-bit division gives the same
/// quotient at about half the cost; a test compares the two over random and
/// extreme inputs.
#[inline]
pub(super) fn div_nonzero(a: Scalar, b: Scalar) -> Scalar {
    let (ua, ub) = (a.to_bits().unsigned_abs(), b.to_bits().unsigned_abs());
    let magnitude = if ua < 1 << 32 {
        (ua << 32) / ub
    } else if ua == 1 << 32 {
        // ⌊2⁶⁴ / ub⌋ from ⌊(2⁶⁴ − 1) / ub⌋: one more exactly when ub divides 2⁶⁴.
        // (ub = 1 overflows either way: u64::MAX, which saturates below.)
        let (q, r) = (u64::MAX / ub, u64::MAX % ub);
        q.saturating_add(u64::from(r == ub - 1))
    } else {
        return Scalar(a.0.saturating_div(b.0));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mul_matches_fixed_bit_for_bit() {
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
                assert_eq!((a * b).0, a.0.saturating_mul(b.0), "{a} {b}");
            }
        }
        for _ in 0..200_000 {
            let (a, b) = (next(), next());
            // Also small magnitudes, where real values live.
            for (a, b) in [(a, b), (a >> 24, b >> 24), (a >> 40, b >> 16)] {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!((a * b).0, a.0.saturating_mul(b.0), "{a} {b}");
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
    fn add_and_sub_match_fixed_bit_for_bit() {
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
                assert_eq!((a + b).0, a.0.saturating_add(b.0), "{a} + {b}");
                assert_eq!((a - b).0, a.0.saturating_sub(b.0), "{a} - {b}");
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
                assert_eq!((a / b).0, a.0.saturating_div(b.0), "{a} / {b}");
            }
        }
    }
}
