//! `Vector2`: a 2D vector of [`Scalar`]s.
//!
//! Every operator saturates instead of overflowing, so an out-of-range
//! intermediate clamps rather than panicking or wrapping, identically in debug and
//! release builds. Inside the engine the ranges are kept far from saturation by
//! design (world bounds, speed limits, validated sizes); saturation is the
//! backstop, not the mechanism.

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use super::scalar::{self, Scalar, ZERO};

/// A 2D vector (metres, metres per second or newtons, depending on use).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vector2 {
    /// The x component.
    pub x: Scalar,
    /// The y component.
    pub y: Scalar,
}

impl Vector2 {
    /// The zero vector.
    pub const ZERO: Self = Self { x: ZERO, y: ZERO };
    /// The unit x axis.
    pub const X: Self = Self { x: scalar::ONE, y: ZERO };
    /// The unit y axis.
    pub const Y: Self = Self { x: ZERO, y: scalar::ONE };

    /// A vector from its components.
    #[inline]
    #[must_use]
    pub const fn new(x: Scalar, y: Scalar) -> Self {
        Self { x, y }
    }

    /// A vector from whole-number components, usable in `const` items.
    #[inline]
    #[must_use]
    pub const fn from_int(x: i32, y: i32) -> Self {
        Self { x: scalar::from_int(x), y: scalar::from_int(y) }
    }

    /// Conversion from floats at the API edge: `None` when a component is NaN,
    /// infinite or outside the `Scalar` range.
    #[must_use]
    pub fn checked_from_f64(x: f64, y: f64) -> Option<Self> {
        Some(Self { x: scalar::checked_from_f64(x)?, y: scalar::checked_from_f64(y)? })
    }

    /// Conversion from `f32` floats at the API edge; see [`Self::checked_from_f64`].
    #[must_use]
    pub fn checked_from_f32(x: f32, y: f32) -> Option<Self> {
        Some(Self { x: scalar::checked_from_f32(x)?, y: scalar::checked_from_f32(y)? })
    }

    /// Conversion from floats at the API edge with an error naming the parameter.
    ///
    /// # Errors
    /// [`Error::NotFinite`](crate::Error::NotFinite) when a component is NaN,
    /// infinite or outside the `Scalar` range.
    pub fn try_from_f64(x: f64, y: f64, what: &'static str) -> Result<Self, crate::Error> {
        Ok(Self { x: scalar::try_from_f64(x, what)?, y: scalar::try_from_f64(y, what)? })
    }

    /// Conversion from `f32` floats at the API edge; see [`Self::try_from_f64`].
    ///
    /// # Errors
    /// [`Error::NotFinite`](crate::Error::NotFinite).
    pub fn try_from_f32(x: f32, y: f32, what: &'static str) -> Result<Self, crate::Error> {
        Ok(Self { x: scalar::try_from_f32(x, what)?, y: scalar::try_from_f32(y, what)? })
    }

    /// Conversion to floats for output (rendering, logging).
    #[must_use]
    pub fn to_f64(self) -> (f64, f64) {
        (self.x.to_f64(), self.y.to_f64())
    }

    /// Conversion to `f32` floats for output (rendering, logging).
    #[must_use]
    pub fn to_f32(self) -> (f32, f32) {
        (self.x.to_f32(), self.y.to_f32())
    }

    /// Dot product `a · b`.
    #[inline]
    #[must_use]
    pub fn dot(self, o: Self) -> Scalar {
        self.x * o.x + self.y * o.y
    }

    /// 2D cross product of two vectors, `a × b = a.x·b.y − a.y·b.x` (a scalar: the z
    /// component of the 3D cross product).
    #[inline]
    #[must_use]
    pub fn cross(self, o: Self) -> Scalar {
        self.x * o.y - self.y * o.x
    }

    /// Cross product of a vector and a scalar (z-axis), `v × s = (s·v.y, −s·v.x)`.
    #[inline]
    #[must_use]
    pub fn cross_vs(self, s: Scalar) -> Self {
        Self { x: s * self.y, y: -(s * self.x) }
    }

    /// Cross product of a scalar (z-axis) and a vector, `s × v = (−s·v.y, s·v.x)`:
    /// the velocity of point `v` on a body spinning at `s` rad/s.
    #[inline]
    #[must_use]
    pub fn cross_sv(s: Scalar, v: Self) -> Self {
        Self { x: -(s * v.y), y: s * v.x }
    }

    /// The vector rotated by +90°: `(−y, x)`.
    #[inline]
    #[must_use]
    pub fn perp(self) -> Self {
        Self { x: -self.y, y: self.x }
    }

    /// The vector rotated by −90°: `(y, −x)`.
    #[inline]
    #[must_use]
    pub fn right_perp(self) -> Self {
        Self { x: self.y, y: -self.x }
    }

    /// Squared length. Exact only while both components are below about 32,767;
    /// saturates beyond, so use it on relative, local vectors.
    #[inline]
    #[must_use]
    pub fn length_squared(self) -> Scalar {
        self.dot(self)
    }

    /// The vector scaled by a power of two so its larger component is in
    /// [2^13, 2^14), and the exponent: `(scaled, shift)` with
    /// `self = scaled · 2^shift`. Squares of the scaled components are exact to
    /// 2^-32 relative to the length, whatever the original magnitude.
    fn rescaled(self) -> Option<(Self, i32)> {
        /// Raw-bit position of 2^13 in Q32.32.
        const TARGET_BIT: u32 = 45;
        let (xb, yb) = (self.x.to_bits(), self.y.to_bits());
        let top = xb.unsigned_abs().max(yb.unsigned_abs()).checked_ilog2()?;
        // |bits| < 2^(top+1): shifting left by 45 − top keeps |bits| < 2^46 (no
        // overflow); shifting right drops at most 18 low bits (2^-45 relative).
        Some(if top < TARGET_BIT {
            let k = TARGET_BIT - top;
            (Self::new(Scalar::from_bits(xb << k), Scalar::from_bits(yb << k)), -(k as i32))
        } else {
            let k = top - TARGET_BIT;
            (Self::new(Scalar::from_bits(xb >> k), Scalar::from_bits(yb >> k)), k as i32)
        })
    }

    /// `x · 2^shift` for the shifts `rescaled` produces, saturating.
    fn unscale(x: Scalar, shift: i32) -> Scalar {
        let b = x.to_bits();
        Scalar::from_bits(if shift < 0 {
            b >> shift.unsigned_abs().min(63)
        } else {
            b.saturating_mul(1_i64 << shift.unsigned_abs().min(62))
        })
    }

    /// Length, accurate to rounding at every magnitude: the vector is scaled by a
    /// power of two before squaring, so nothing saturates or underflows.
    #[must_use]
    pub fn length(self) -> Scalar {
        match self.rescaled() {
            Some((v, shift)) => Self::unscale(v.length_squared().sqrt(), shift),
            None => ZERO,
        }
    }

    /// The unit vector in the same direction and the original length, accurate
    /// at every magnitude (unit to about 1e-9). The zero vector gives
    /// `(Vector2::ZERO, 0)`: no division by zero is possible.
    #[must_use]
    pub fn normalize_and_length(self) -> (Self, Scalar) {
        let Some((v, shift)) = self.rescaled() else {
            return (Self::ZERO, ZERO);
        };
        let len = v.length_squared().sqrt();
        let n = Self::new(v.x.div_or_zero(len), v.y.div_or_zero(len));
        (n, Self::unscale(len, shift))
    }

    /// The unit vector in the same direction, or `Vector2::ZERO` for the zero vector.
    #[inline]
    #[must_use]
    pub fn normalize(self) -> Self {
        self.normalize_and_length().0
    }

    /// The unit vector in the same direction, or `None` for the zero vector.
    #[must_use]
    pub fn try_normalize(self) -> Option<Self> {
        let (n, len) = self.normalize_and_length();
        if len == ZERO {
            None
        } else {
            Some(n)
        }
    }

    /// Component-wise minimum.
    #[inline]
    #[must_use]
    pub fn min(self, o: Self) -> Self {
        Self::new(self.x.min(o.x), self.y.min(o.y))
    }

    /// Component-wise maximum.
    #[inline]
    #[must_use]
    pub fn max(self, o: Self) -> Self {
        Self::new(self.x.max(o.x), self.y.max(o.y))
    }

    /// Component-wise absolute value.
    #[inline]
    #[must_use]
    pub fn abs(self) -> Self {
        Self::new(self.x.abs(), self.y.abs())
    }

    /// Linear interpolation `a + (b − a)·t`.
    #[inline]
    #[must_use]
    pub fn lerp(self, b: Self, t: Scalar) -> Self {
        self + (b - self) * t
    }

    /// True when both components are zero.
    #[inline]
    #[must_use]
    pub fn is_zero(self) -> bool {
        self.x == ZERO && self.y == ZERO
    }
}

impl Add for Vector2 {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Vector2 {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y)
    }
}

impl Neg for Vector2 {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y)
    }
}

impl Mul<Scalar> for Vector2 {
    type Output = Self;
    #[inline]
    fn mul(self, s: Scalar) -> Self {
        Self::new(self.x * s, self.y * s)
    }
}

impl Mul<Vector2> for Scalar {
    type Output = Vector2;
    #[inline]
    fn mul(self, v: Vector2) -> Vector2 {
        v * self
    }
}

impl AddAssign for Vector2 {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl SubAssign for Vector2 {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::scalar::{from_int, EPSILON as EPS, ONE};

    #[test]
    fn crosses_follow_the_right_hand_rule() {
        assert_eq!(Vector2::X.cross(Vector2::Y), from_int(1));
        assert_eq!(Vector2::X.cross_vs(from_int(1)), -Vector2::Y);
        assert_eq!(Vector2::cross_sv(from_int(1), Vector2::X), Vector2::Y);
        assert_eq!(Vector2::X.perp(), Vector2::Y);
    }

    #[test]
    fn length_is_exact_for_pythagorean_triples_at_any_scale() {
        assert_eq!(Vector2::from_int(3, 4).length(), from_int(5));
        assert_eq!(Vector2::from_int(300_000, 400_000).length(), from_int(500_000));
        let big = Vector2::from_int(1_000_000_000, 0).length();
        assert_eq!(big, from_int(1_000_000_000));
    }

    #[test]
    fn normalizing_zero_gives_zero_not_a_division() {
        assert_eq!(Vector2::ZERO.normalize(), Vector2::ZERO);
        assert!(Vector2::ZERO.try_normalize().is_none());
        // A vector one ulp long still has a direction.
        assert_eq!(Vector2::new(ZERO, EPS).normalize(), Vector2::Y);
        // Millimetre vectors normalise to unit length within 1e-9.
        let (n, l) = Vector2::new(Scalar::lit("0.0003"), Scalar::lit("0.0004")).normalize_and_length();
        assert!((n.length() - ONE).abs() < Scalar::lit("0.000000001"), "{n:?}");
        // The inputs themselves are rounded to 2^-32 ≈ 2.3e-10.
        assert!((l - Scalar::lit("0.0005")).abs() < Scalar::lit("0.000000001"), "{l}");
        let (n, l) = Vector2::from_int(0, -7).normalize_and_length();
        assert_eq!((n, l), (Vector2::from_int(0, -1), from_int(7)));
    }

    #[test]
    fn operators_saturate_instead_of_panicking() {
        let big = Vector2::new(Scalar::MAX, Scalar::MIN);
        assert_eq!(big + big, big);
        assert_eq!((big * from_int(4)).x, Scalar::MAX);
        assert_eq!(big.length_squared(), Scalar::MAX);
    }
}
