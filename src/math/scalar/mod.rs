//! The engine's number type: [`Scalar`], Q32.32 fixed point.
//!
//! `Scalar` wraps `fixed::types::I32F32`: 32 integer bits, 32 fraction bits.
//! Resolution is 2^-32 ≈ 2.3e-10 and range ±2^31 ≈ ±2.1e9. The range of
//! *squared* quantities is therefore only |x| < 46,340, which is why the engine
//! squares relative, local quantities and never absolute world positions.
//!
//! # Overflow policy: every operator saturates
//! `fixed`'s own operators panic on overflow in debug builds and wrap in release
//! builds (`I32F32::from_num(50_000)²` panics in one and gives −1.79e9 in the
//! other), which would break the promise that both builds behave the same. The
//! newtype's `+ − * /`, unary `−` and their `*=` forms therefore saturate: a
//! result beyond the range is [`Scalar::MAX`] or [`Scalar::MIN`], by the sign of
//! the exact result, in every build. Engine code and game code write plain
//! arithmetic (`a * b + c`) and get the same bits everywhere.
//!
//! * `a / 0` is [`Scalar::MAX`] for `a > 0`, [`Scalar::MIN`] for `a < 0` and 0
//!   for `a = 0` (the saturated limit). Where a zero divisor means "no effect",
//!   as for inverse masses, [`Scalar::recip`] and [`Scalar::div_or_zero`] give 0.
//! * `-Scalar::MIN` is [`Scalar::MAX`]; `Scalar::MIN.abs()` likewise.
//! * [`Scalar::sqrt`] of a negative number is 0.
//! * `checked_*` methods return `None` instead of saturating, for callers that
//!   must tell.
//!
//! Floats appear only at the API edge: `TryFrom<f32>`/`TryFrom<f64>` (NaN,
//! infinity and out-of-range values are errors), [`Scalar::to_f32`] and
//! [`Scalar::to_f64`]. The step never calls them.

use core::fmt;
use fixed::traits::{FromFixed, ToFixed};
use fixed::types::I32F32;

mod arith;

pub(crate) use arith::{below_one, mul_below_one, product_bits};
use arith::{div_nonzero, saturated_by_sign};

/// The fixed-point number of every physical quantity (Q32.32), with saturating
/// operators (see the [module docs](self)).
///
/// The bits are those of `fixed::types::I32F32`: [`Scalar::to_bits`] and
/// [`Scalar::from_bits`] convert exactly, and snapshots store them.
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Scalar(I32F32);

/// 0.
pub const ZERO: Scalar = Scalar::ZERO;
/// 1.
pub const ONE: Scalar = Scalar::ONE;
/// 0.5.
pub const HALF: Scalar = Scalar::lit("0.5");
/// 2.
pub const TWO: Scalar = Scalar::from_int(2);
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
    Scalar::from_int(v)
}

impl Scalar {
    /// 0.
    pub const ZERO: Self = Self(I32F32::ZERO);
    /// 1.
    pub const ONE: Self = Self(I32F32::ONE);
    /// −1.
    pub const NEG_ONE: Self = Self(I32F32::NEG_ONE);
    /// 0.5.
    pub const HALF: Self = Self::lit("0.5");
    /// The largest value, 2^31 − 2^-32.
    pub const MAX: Self = Self(I32F32::MAX);
    /// The smallest (most negative) value, −2^31.
    pub const MIN: Self = Self(I32F32::MIN);
    /// The smallest positive value, 2^-32 (one unit in the last place).
    pub const DELTA: Self = Self(I32F32::DELTA);
    /// π (rounded toward zero, as `fixed` rounds its constants).
    pub const PI: Self = Self(I32F32::PI);
    /// 2π.
    pub const TAU: Self = Self(I32F32::TAU);
    /// π/2.
    pub const FRAC_PI_2: Self = Self(I32F32::FRAC_PI_2);
    /// π/3.
    pub const FRAC_PI_3: Self = Self(I32F32::FRAC_PI_3);
    /// π/4.
    pub const FRAC_PI_4: Self = Self(I32F32::FRAC_PI_4);
    /// π/6.
    pub const FRAC_PI_6: Self = Self(I32F32::FRAC_PI_6);
    /// √2.
    pub const SQRT_2: Self = Self(I32F32::SQRT_2);
    /// 1/√2.
    pub const FRAC_1_SQRT_2: Self = Self(I32F32::FRAC_1_SQRT_2);

    /// The value whose Q32.32 bits are `bits` (exact).
    #[inline(always)]
    #[must_use]
    pub const fn from_bits(bits: i64) -> Self {
        Self(I32F32::from_bits(bits))
    }

    /// The Q32.32 bits (exact): the value times 2^32.
    #[inline(always)]
    #[must_use]
    pub const fn to_bits(self) -> i64 {
        self.0.to_bits()
    }

    /// A whole number; exact, since every `i32` is in range. Usable in `const`.
    #[inline]
    #[must_use]
    pub const fn from_int(v: i32) -> Self {
        Self::from_bits((v as i64) << 32)
    }

    /// A decimal literal, rounded to the nearest Q32.32 value, usable in `const`
    /// (`Scalar::lit("0.01")`). A malformed or out-of-range literal fails to
    /// compile in a `const` and panics otherwise: it is for constants written in
    /// the source, not for input.
    #[inline]
    #[must_use]
    pub const fn lit(src: &str) -> Self {
        Self(I32F32::lit(src))
    }

    /// Any number `fixed` can convert (integers, floats, other fixed-point
    /// types), rounded to the nearest value and **saturated** to the range; NaN
    /// gives 0. A convenience for literals in examples and tests; input from
    /// outside should go through `Scalar::try_from` (an error for NaN, infinity
    /// or out-of-range values).
    #[inline]
    #[must_use]
    pub fn from_num<T: ToFixed + PartialOrd + Default + Copy>(v: T) -> Self {
        match I32F32::checked_from_num(v) {
            Some(x) => Self(x),
            None if v > T::default() => Self::MAX,
            None if v < T::default() => Self::MIN,
            None => Self::ZERO,
        }
    }

    /// Like [`Scalar::from_num`], but `None` when the value is NaN, infinite or
    /// out of range.
    #[inline]
    #[must_use]
    pub fn checked_from_num<T: ToFixed>(v: T) -> Option<Self> {
        I32F32::checked_from_num(v).map(Self)
    }

    /// This value as any number type `fixed` converts to, saturating for integer
    /// types too narrow for it. For output, never used by the step.
    #[inline]
    #[must_use]
    pub fn to_num<T: FromFixed>(self) -> T {
        self.0.saturating_to_num()
    }

    /// Conversion to `f64` for output (rendering, logging): exact. Never used by
    /// the step.
    #[inline]
    #[must_use]
    pub fn to_f64(self) -> f64 {
        self.0.to_num::<f64>()
    }

    /// Conversion to `f32` for output, rounded to nearest. Never used by the step.
    #[inline]
    #[must_use]
    pub fn to_f32(self) -> f32 {
        self.0.to_num::<f32>()
    }

    /// |self|, saturating (`|MIN|` is `MAX`).
    #[inline]
    #[must_use]
    pub const fn abs(self) -> Self {
        Self(self.0.saturating_abs())
    }

    /// −1, 0 or 1 by the sign.
    #[inline]
    #[must_use]
    pub const fn signum(self) -> Self {
        Self(self.0.signum())
    }

    /// `true` when below zero.
    #[inline]
    #[must_use]
    pub const fn is_negative(self) -> bool {
        self.0.is_negative()
    }

    /// `true` when above zero.
    #[inline]
    #[must_use]
    pub const fn is_positive(self) -> bool {
        self.0.is_positive()
    }

    /// The square root, rounded down, with 0 for zero or negative input. Integer
    /// operations only, so the same bits everywhere: the bits of √x in Q32.32
    /// are ⌊√(bits·2³²)⌋, core's exact integer square root of a 96-bit value
    /// (the same result as `fixed`'s bit-by-bit root, tested bit for bit below,
    /// at about a fifth of its cost: 580 instructions a call, the root of
    /// contact normals and mixed friction, 1.4 % of a step's count).
    #[inline]
    #[must_use]
    pub fn sqrt(self) -> Self {
        let bits = self.0.to_bits();
        if bits <= 0 {
            Self::ZERO
        } else {
            // bits < 2⁶³, so the root of bits·2³² is below 2^47.5: it fits.
            Self::from_bits(((bits.unsigned_abs() as u128) << 32).isqrt() as i64)
        }
    }

    /// `1 / self`, saturating, with 0 for 0 (the convention for inverse masses
    /// and inertias: an infinite mass has inverse 0).
    #[inline]
    #[must_use]
    pub fn recip(self) -> Self {
        Self::ONE.div_or_zero(self)
    }

    /// `self / rhs`, saturating, with 0 when `rhs` is 0: inside the step a zero
    /// divisor means a degenerate configuration whose correct response is "no
    /// impulse". The `/` operator saturates instead.
    #[inline]
    #[must_use]
    pub fn div_or_zero(self, rhs: Self) -> Self {
        if rhs.0 == I32F32::ZERO {
            Self::ZERO
        } else {
            div_nonzero(self, rhs)
        }
    }

    /// The smaller of the two.
    #[inline]
    #[must_use]
    pub fn min(self, other: Self) -> Self {
        if other < self {
            other
        } else {
            self
        }
    }

    /// The larger of the two.
    #[inline]
    #[must_use]
    pub fn max(self, other: Self) -> Self {
        if other > self {
            other
        } else {
            self
        }
    }

    /// `self` clamped to `[lo, hi]`. Never panics: when `lo > hi` it returns
    /// `hi` for values above `hi` and `lo` otherwise below `lo`, as the
    /// comparisons fall.
    #[inline]
    #[must_use]
    pub fn clamp(self, lo: Self, hi: Self) -> Self {
        if self > hi {
            hi
        } else if self < lo {
            lo
        } else {
            self
        }
    }

    /// The largest whole number ≤ `self`.
    #[inline]
    #[must_use]
    pub const fn floor(self) -> Self {
        Self(self.0.floor())
    }

    /// The smallest whole number ≥ `self`, saturating.
    #[inline]
    #[must_use]
    pub const fn ceil(self) -> Self {
        Self(self.0.saturating_ceil())
    }

    /// The nearest whole number (ties away from zero), saturating.
    #[inline]
    #[must_use]
    pub const fn round(self) -> Self {
        Self(self.0.saturating_round())
    }

    /// The integer part, rounded toward zero.
    #[inline]
    #[must_use]
    pub const fn int(self) -> Self {
        Self(self.0.int())
    }

    /// The fractional part (`self − floor(self)`, in [0, 1)).
    #[inline]
    #[must_use]
    pub const fn frac(self) -> Self {
        Self(self.0.frac())
    }

    /// `self + rhs`, or `None` on overflow.
    #[inline]
    #[must_use]
    pub const fn checked_add(self, rhs: Self) -> Option<Self> {
        match self.0.checked_add(rhs.0) {
            Some(v) => Some(Self(v)),
            None => None,
        }
    }

    /// `self − rhs`, or `None` on overflow.
    #[inline]
    #[must_use]
    pub const fn checked_sub(self, rhs: Self) -> Option<Self> {
        match self.0.checked_sub(rhs.0) {
            Some(v) => Some(Self(v)),
            None => None,
        }
    }

    /// `self · rhs`, or `None` on overflow.
    #[inline]
    #[must_use]
    pub fn checked_mul(self, rhs: Self) -> Option<Self> {
        self.0.checked_mul(rhs.0).map(Self)
    }

    /// `self / rhs`, or `None` on overflow or division by zero.
    #[inline]
    #[must_use]
    pub fn checked_div(self, rhs: Self) -> Option<Self> {
        self.0.checked_div(rhs.0).map(Self)
    }

    /// `self · rhs` for an integer `rhs`, saturating.
    #[inline]
    #[must_use]
    pub fn mul_int(self, rhs: i32) -> Self {
        Self(self.0.saturating_mul_int(i64::from(rhs)))
    }

    /// `self / rhs` for an integer `rhs`, rounded toward zero; division by zero
    /// saturates as the `/` operator does.
    #[inline]
    #[must_use]
    pub fn div_int(self, rhs: i32) -> Self {
        if rhs == 0 {
            return saturated_by_sign(self.to_bits());
        }
        Self(self.0.saturating_div_int(i64::from(rhs)))
    }
}

macro_rules! from_int_exact {
    ($($t:ty),*) => {$(
        impl From<$t> for Scalar {
            /// Exact: every value of this integer type is in range.
            #[inline]
            fn from(v: $t) -> Self {
                Self::from_int(i32::from(v))
            }
        }
    )*};
}

from_int_exact!(i8, u8, i16, u16, i32);

impl TryFrom<f64> for Scalar {
    type Error = crate::Error;
    /// Rounds to the nearest value; NaN, infinity or a value outside the range is
    /// [`Error::NotFinite`](crate::Error::NotFinite).
    fn try_from(v: f64) -> Result<Self, crate::Error> {
        try_from_f64(v, "scalar")
    }
}

impl TryFrom<f32> for Scalar {
    type Error = crate::Error;
    /// Rounds to the nearest value; NaN, infinity or a value outside the range is
    /// [`Error::NotFinite`](crate::Error::NotFinite).
    fn try_from(v: f32) -> Result<Self, crate::Error> {
        try_from_f32(v, "scalar")
    }
}

impl fmt::Display for Scalar {
    /// The exact decimal value, as `fixed` prints it (precision flags honoured).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.0, f)
    }
}

impl fmt::Debug for Scalar {
    /// The same as `Display`: the decimal value.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.0, f)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_by_zero_saturates_by_sign_and_div_or_zero_gives_zero() {
        assert_eq!(ONE / ZERO, Scalar::MAX);
        assert_eq!(-ONE / ZERO, Scalar::MIN);
        assert_eq!(ZERO / ZERO, ZERO);
        assert_eq!(ONE.div_or_zero(ZERO), ZERO);
        assert_eq!(ZERO.recip(), ZERO);
        assert_eq!(Scalar::MAX / EPSILON, Scalar::MAX);
        assert_eq!(from_int(3) / from_int(2), Scalar::lit("1.5"));
        assert_eq!(from_int(3) / 0, Scalar::MAX);
        assert_eq!(from_int(-3) / 2, Scalar::lit("-1.5"));
    }

    #[test]
    fn operators_saturate_in_every_build() {
        // The measurement: 50,000² panics in debug and wraps in release
        // with `fixed`'s operators; here it is MAX in both.
        let big = Scalar::from_num(50_000);
        assert_eq!(big * big, Scalar::MAX);
        assert_eq!(-big * big, Scalar::MIN);
        assert_eq!(Scalar::MAX + ONE, Scalar::MAX);
        assert_eq!(Scalar::MIN - ONE, Scalar::MIN);
        assert_eq!(-Scalar::MIN, Scalar::MAX);
        assert_eq!(Scalar::MIN.abs(), Scalar::MAX);
        assert_eq!(Scalar::MAX * 2, Scalar::MAX);
        assert_eq!(2 * Scalar::MIN, Scalar::MIN);
        let mut x = Scalar::MAX;
        x += ONE;
        x *= TWO;
        assert_eq!(x, Scalar::MAX);
    }

    #[test]
    fn conversions_at_the_edge() {
        assert_eq!(Scalar::from(7i32), from_int(7));
        assert_eq!(Scalar::from(i32::MIN), Scalar::MIN);
        assert_eq!(Scalar::from(-3i16).to_bits(), -3 << 32);
        assert_eq!(Scalar::try_from(0.25f64), Ok(Scalar::lit("0.25")));
        assert_eq!(Scalar::try_from(0.25f32), Ok(Scalar::lit("0.25")));
        assert!(Scalar::try_from(f64::NAN).is_err());
        assert!(Scalar::try_from(f32::INFINITY).is_err());
        assert!(Scalar::try_from(3e9f64).is_err());
        assert_eq!(Scalar::from_num(3e9f64), Scalar::MAX);
        assert_eq!(Scalar::from_num(-3e9f64), Scalar::MIN);
        assert_eq!(Scalar::from_num(f64::NAN), ZERO);
        assert_eq!(Scalar::lit("1.5").to_f64(), 1.5);
        assert_eq!(Scalar::lit("-1.5").to_f32(), -1.5);
        assert_eq!(Scalar::MAX.to_num::<i16>(), i16::MAX);
        assert_eq!(from_int(5).clamp(from_int(7), from_int(6)), from_int(7));
    }

    /// The integer root equals `fixed`'s own `sqrt` bit for bit: every power of
    /// two and its neighbours, and 200,000 pseudo-random values across the range.
    #[test]
    fn sqrt_matches_fixed_bit_for_bit() {
        let check = |bits: i64| {
            let x = I32F32::from_bits(bits);
            let want = if bits <= 0 { I32F32::ZERO } else { x.sqrt() };
            assert_eq!(Scalar(x).sqrt().0, want, "sqrt of bits {bits:#x}");
        };
        for k in 0..63 {
            let p = 1i64 << k;
            for b in [p - 1, p, p + 1] {
                check(b);
            }
        }
        check(i64::MAX);
        check(i64::MIN);
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            // Spread the magnitudes: shift by 0..63.
            check((r >> (r % 64)) as i64);
        }
    }

    #[test]
    fn sqrt_of_negative_is_zero() {
        assert_eq!(from_int(-4).sqrt(), ZERO);
        assert_eq!(from_int(9).sqrt(), from_int(3));
    }

    #[test]
    fn float_conversion_rejects_non_finite() {
        assert!(checked_from_f64(f64::NAN).is_none());
        assert!(checked_from_f64(f64::INFINITY).is_none());
        assert!(checked_from_f64(1e12).is_none());
        assert_eq!(checked_from_f64(0.5), Some(HALF));
    }
}
