//! `Rot`: a rotation stored as a unit complex number (cos θ, sin θ), and
//! `Transform`: a rotation plus a translation.
//!
//! Storing (cos, sin) instead of an angle means the step never evaluates a
//! trigonometric function: rotating a vector is four multiplies, and advancing
//! the rotation by ω·h is the complex product (c − s·ω·h, s + c·ω·h) followed by a
//! renormalisation (one `sqrt`). Angles exist only at the API edge, through the
//! deterministic fixed-point functions in [`crate::math::trig`].

use super::scalar::{below_one, mul_below_one, Scalar, ONE, ZERO};
use super::trig;
use super::vector2::Vector2;

/// A rotation as a unit complex number: `c = cos θ`, `s = sin θ`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rot {
    /// cos θ.
    pub c: Scalar,
    /// sin θ.
    pub s: Scalar,
}

impl Default for Rot {
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// 2^-10 in bits: the largest |m − 1| [`Rot::integrate`] rescales by the series.
const SERIES_LIMIT: u64 = 1 << 22;

impl Rot {
    /// No rotation.
    pub const IDENTITY: Self = Self { c: ONE, s: ZERO };

    /// The rotation by `angle` radians (any magnitude; reduced exactly).
    #[must_use]
    pub fn from_angle(angle: Scalar) -> Self {
        let (s, c) = trig::sin_cos(angle);
        Self { c, s }
    }

    /// The angle in radians, in (−π, π].
    #[must_use]
    pub fn angle(self) -> Scalar {
        trig::atan2(self.s, self.c)
    }

    /// The rotation pointing along `v`, or `None` for the zero vector.
    #[must_use]
    pub fn from_direction(v: Vector2) -> Option<Self> {
        v.try_normalize().map(|n| Self { c: n.x, s: n.y })
    }

    /// `v` rotated by this rotation.
    #[inline(always)]
    #[must_use]
    pub fn rotate(self, v: Vector2) -> Vector2 {
        Vector2::new(self.c * v.x - self.s * v.y, self.s * v.x + self.c * v.y)
    }

    /// `v` rotated by the inverse of this rotation.
    #[inline(always)]
    #[must_use]
    pub fn inv_rotate(self, v: Vector2) -> Vector2 {
        Vector2::new(self.c * v.x + self.s * v.y, self.c * v.y - self.s * v.x)
    }

    /// The composition `self ∘ other` (rotate by `other`, then by `self`).
    #[inline(always)]
    #[must_use]
    pub fn compose(self, o: Self) -> Self {
        Self { c: self.c * o.c - self.s * o.s, s: self.s * o.c + self.c * o.s }
    }

    /// The inverse rotation.
    #[inline(always)]
    #[must_use]
    pub fn inverse(self) -> Self {
        Self { c: self.c, s: -self.s }
    }

    /// The relative rotation `self⁻¹ ∘ other`.
    #[inline(always)]
    #[must_use]
    pub fn inv_mul(self, o: Self) -> Self {
        self.inverse().compose(o)
    }

    /// The rotation advanced by the small angle `delta` radians (ω·h) and
    /// renormalised to unit length. `delta` should be small (the world clamps
    /// angular speed so that |ω·h| stays well below 1); the result is a unit
    /// rotation whatever it is.
    ///
    /// The length after the turn is √(1 + δ²); while |δ| < 0.03 (|ω| < 7 rad/s
    /// at 240 sub-steps a second) it is rescaled by the series
    /// 1/√m ≈ 1 − e/2 + 3e²/8 with e = m − 1 (error under 5e-10, about two
    /// units of the last place), which costs four products instead of a square
    /// root and two divisions; faster turns are normalised exactly.
    ///
    /// Every operation is `Scalar`'s saturating one; when |δ| < 1 and both
    /// parts are below 2 in magnitude (any unit rotation) none of them can
    /// saturate, and the products are plain 128-bit products shifted (the
    /// bits the saturating ones give when they fit), without the tests. That
    /// path is inlined into the solver's loop; the rest is
    /// `integrate_saturating`, out of line.
    /// Mixed scene, 180 steps: 901.2 → 889.6 M instructions; large 20:
    /// 2,400.5 → 2,386.5 M.
    #[inline(always)]
    #[must_use]
    pub fn integrate(self, delta: Scalar) -> Self {
        let (c0, s0, d) = (self.c.to_bits(), self.s.to_bits(), delta.to_bits());
        if d.unsigned_abs() >> 32 != 0 || (c0.unsigned_abs() | s0.unsigned_abs()) >> 33 != 0 {
            return self.integrate_saturating(delta);
        }
        // ⌊a·b⌋ in Q32.32: the saturating product's bits when it fits.
        let mul = crate::math::scalar::product_bits;
        // |δ·s|, |δ·c| < 2, so |c|, |s| < 4 and c² + s² < 32: nothing overflows.
        let c = c0 - mul(d, s0);
        let s = s0 + mul(d, c0);
        let e = mul(c, c) + mul(s, s) - (1 << 32);
        if e.unsigned_abs() > SERIES_LIMIT {
            return Self { c: Scalar::from_bits(c), s: Scalar::from_bits(s) }.normalized();
        }
        // |e| ≤ 2⁻¹⁰: e² fits an `i64` (2⁴⁴ in bits) and 3/8 of it is
        // ⌊3·e²/8⌋, the product by 3/8 (3·2²⁹) shifted; |k| < 2.
        let k = (1 << 32) - (e >> 1) + ((3 * ((e * e) >> 32)) >> 3);
        Self { c: Scalar::from_bits(mul(c, k)), s: Scalar::from_bits(mul(s, k)) }
    }

    /// [`integrate`](Self::integrate) with every operation saturating, for a
    /// turn of 1 rad or more or a rotation far from unit length.
    #[cold]
    #[inline(never)]
    fn integrate_saturating(self, delta: Scalar) -> Self {
        const THREE_EIGHTHS: Scalar = Scalar::lit("0.375");
        // A factor below 1 in magnitude (the turn, a turned rotation's parts,
        // `e` in the series' range, 3/8) skips the saturation test of its
        // products ([`mul_below_one`], the same bits; a product's factors
        // commute).
        let mul = |a: Scalar, b: Scalar| if below_one(a) { mul_below_one(a, b) } else { a * b };
        let c = self.c - mul(delta, self.s);
        let s = self.s + mul(delta, self.c);
        let turned = below_one(c) && below_one(s);
        let (cc, ss) = if turned { (mul_below_one(c, c), mul_below_one(s, s)) } else { (c * c, s * s) };
        let e = cc + ss - Scalar::ONE;
        if e.to_bits().unsigned_abs() <= SERIES_LIMIT {
            let half_e = Scalar::from_bits(e.to_bits() >> 1);
            let k = Scalar::ONE - half_e + mul_below_one(THREE_EIGHTHS, mul_below_one(e, e));
            if turned {
                Self { c: mul_below_one(c, k), s: mul_below_one(s, k) }
            } else {
                Self { c: c * k, s: s * k }
            }
        } else {
            Self { c, s }.normalized()
        }
    }

    /// The same rotation rescaled to unit length; the identity if both parts are 0.
    #[must_use]
    pub fn normalized(self) -> Self {
        match Vector2::new(self.c, self.s).try_normalize() {
            Some(n) => Self { c: n.x, s: n.y },
            None => Self::IDENTITY,
        }
    }

    /// The rotated x axis (the body's local x direction in world space).
    #[inline]
    #[must_use]
    pub fn x_axis(self) -> Vector2 {
        Vector2::new(self.c, self.s)
    }
}

/// A rigid transform: rotate by `q`, then translate by `p`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Transform {
    /// Translation (metres).
    pub p: Vector2,
    /// Rotation.
    pub q: Rot,
}

impl Transform {
    /// The identity transform.
    pub const IDENTITY: Self = Self { p: Vector2::ZERO, q: Rot::IDENTITY };

    /// A transform from a translation and a rotation.
    #[inline]
    #[must_use]
    pub const fn new(p: Vector2, q: Rot) -> Self {
        Self { p, q }
    }

    /// A local point mapped to world space: `q·v + p`.
    #[inline(always)]
    #[must_use]
    pub fn apply(self, v: Vector2) -> Vector2 {
        self.q.rotate(v) + self.p
    }

    /// A world point mapped to local space: `q⁻¹·(v − p)`.
    #[inline(always)]
    #[must_use]
    pub fn apply_inv(self, v: Vector2) -> Vector2 {
        self.q.inv_rotate(v - self.p)
    }

    /// Frame `local` (given in frame `self`) in the frame `self` is given in:
    /// `self ∘ local`. The identity on either side gives the other exactly.
    #[inline]
    #[must_use]
    pub fn compose(self, local: Self) -> Self {
        Self { p: self.apply(local.p), q: self.q.compose(local.q) }
    }

    /// The transform of frame `b` expressed in frame `self`: `self⁻¹ ∘ b`.
    #[inline(always)]
    #[must_use]
    pub fn inv_mul(self, b: Self) -> Self {
        Self { p: self.q.inv_rotate(b.p - self.p), q: self.q.inv_mul(b.q) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrating_keeps_unit_length() {
        let mut q = Rot::IDENTITY;
        let step = Scalar::lit("0.05");
        for _ in 0..10_000 {
            q = q.integrate(step);
            let len2 = q.c * q.c + q.s * q.s;
            assert!((len2 - ONE).abs() < Scalar::lit("0.000000005"));
        }
    }

    #[test]
    fn series_rescaling_is_as_accurate_as_exact_normalisation() {
        // Small turns take the series path. N turns of δ rotate by N·atan(δ);
        // the series path must track that as well as exact normalisation does
        // (both round every step) and stay unit length.
        for step in [0.03, 0.01, -0.004, 0.0001, -0.0000001] {
            let d = Scalar::from_num(step);
            let (mut q, mut exact) = (Rot::IDENTITY, Rot::IDENTITY);
            let n = 20_000;
            for _ in 0..n {
                q = q.integrate(d);
                let c = exact.c - exact.s * d;
                let s = exact.s + exact.c * d;
                exact = Rot { c, s }.normalized();
                let len2 = q.c * q.c + q.s * q.s;
                assert!((len2 - ONE).abs() < Scalar::lit("0.000000005"), "{step}: {len2}");
            }
            let angle = f64::from(n) * d.to_num::<f64>().atan();
            let err = |r: Rot| {
                (r.c.to_num::<f64>() - angle.cos()).abs().max((r.s.to_num::<f64>() - angle.sin()).abs())
            };
            let (e_series, e_exact) = (err(q), err(exact));
            assert!(e_series <= e_exact.max(1e-7) * 2.0, "{step}: series {e_series:e}, exact {e_exact:e}");
        }
    }

    #[test]
    fn integrate_gives_the_saturating_operations_bits() {
        // Random parts below 2 and turns below 1 (the unchecked path), and
        // some at and past those edges, against the all-saturating path.
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as i64
        };
        let edges =
            [0, 1, -1, 1 << 32, -(1 << 32), (1 << 33) - 1, -(1 << 33) + 1, 1 << 33, i64::MAX, i64::MIN];
        for k in 0..200_000 {
            let (c, s, d) = match k % 4 {
                0 => (next() >> 30, next() >> 30, next() >> 31),
                1 => (next() >> 31, next() >> 31, next() >> 40),
                2 => (edges[(k / 4) % edges.len()], next() >> 31, next() >> 31),
                _ => {
                    let q = Rot::from_angle(Scalar::from_bits(next() >> 29));
                    (q.c.to_bits(), q.s.to_bits(), next() >> (32 + (k / 4) % 28))
                }
            };
            let q = Rot { c: Scalar::from_bits(c), s: Scalar::from_bits(s) };
            let d = Scalar::from_bits(d);
            assert_eq!(q.integrate(d), q.integrate_saturating(d), "{q:?} {d:?}");
        }
    }

    #[test]
    fn rotate_then_inverse_rotate_is_identity_within_rounding() {
        let q = Rot::from_direction(Vector2::from_int(3, 4)).unwrap_or_default();
        let v = Vector2::from_int(7, -2);
        let back = q.inv_rotate(q.rotate(v));
        assert!((back - v).length() < Scalar::lit("0.0000001"));
        let x = q.rotate(Vector2::X) - Vector2::new(Scalar::lit("0.6"), Scalar::lit("0.8"));
        assert!(x.length() < Scalar::lit("0.000000001"), "{x:?}");
    }

    #[test]
    fn transform_round_trip() {
        let t = Transform::new(Vector2::from_int(10, 5), Rot { c: ZERO, s: ONE });
        assert_eq!(t.apply(Vector2::X), Vector2::from_int(10, 6));
        assert_eq!(t.apply_inv(Vector2::from_int(10, 6)), Vector2::X);
    }
}
