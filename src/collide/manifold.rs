//! `Manifold`: what the narrow phase hands to the contact solver, and the small
//! helpers every shape pair uses to produce one.
//!
//! Each pair function computes its contacts in the local frame of one body (so the
//! numbers stay small whatever the world position) and then calls
//! [`Manifold::from_local`] once to express them in world orientation.

use super::Direction;
pub(crate) use crate::math::scalar::{below_one, mul_below_one};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Transform, Vector2};

/// Most contact points a manifold holds: two points are enough to hold a convex
/// shape flat against a face in 2D.
pub const MAX_MANIFOLD_POINTS: usize = 2;

/// One contact point between two shapes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ManifoldPoint {
    /// World position of the contact (m), midway between the two surfaces along
    /// the manifold normal.
    pub point: Vector2,
    /// `point` relative to body A's centre (m), in world orientation.
    pub anchor_a: Vector2,
    /// `point` relative to body B's centre (m), in world orientation.
    pub anchor_b: Vector2,
    /// Distance between the surfaces along the normal (m): negative when the
    /// shapes overlap (penetration depth), positive for a speculative point.
    pub separation: Scalar,
    /// Feature id: the same value while the same pair of features (edges,
    /// vertices) produces this point, so a solver can carry its impulse over from
    /// the previous step (warm starting). Only meaningful between manifolds of the
    /// same shape pair computed with the arguments in the same order.
    pub id: u16,
}

impl ManifoldPoint {
    /// A point with every field zero (the filler of unused slots).
    pub const ZERO: Self = Self {
        point: Vector2::ZERO,
        anchor_a: Vector2::ZERO,
        anchor_b: Vector2::ZERO,
        separation: ZERO,
        id: 0,
    };
}

/// The contact between two shapes: a shared normal and up to two points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Manifold {
    /// Unit normal in world space, pointing from shape A towards shape B: moving B
    /// along it separates the shapes. Zero in an empty manifold.
    pub normal: Vector2,
    /// The contact points; only the first `count` are meaningful (see
    /// [`Manifold::points`]).
    pub points: [ManifoldPoint; MAX_MANIFOLD_POINTS],
    /// Number of valid entries in `points` (0, 1 or 2).
    pub count: usize,
}

impl Manifold {
    /// No contact: the shapes are farther apart than the margin.
    pub const EMPTY: Self =
        Self { normal: Vector2::ZERO, points: [ManifoldPoint::ZERO; MAX_MANIFOLD_POINTS], count: 0 };

    /// The valid contact points (`count` of them).
    #[inline]
    #[must_use]
    pub fn points(&self) -> &[ManifoldPoint] {
        self.points.get(..self.count).unwrap_or(&[])
    }

    /// Builds the world manifold from contacts computed in the local frame of one
    /// body (`frame`, that body's transform), whose centre is the local origin.
    ///
    /// `normal` and each local point are in that frame; `normal` points from the
    /// frame's body towards the other one, whose centre is `other_position` in world
    /// space. `frame_is_b` says the frame belongs to body B (the polygon–polygon test
    /// may use B's face as reference): the normal is then negated so it still points
    /// from A to B, and the anchors are swapped.
    ///
    /// The point is formed as `frame.p + q·local` and the other anchor as
    /// `point − other_position`: fixed-point addition is exact (short of
    /// saturation), so both anchors name exactly the same world point.
    ///
    /// Always inlined: built in the caller's place, the manifold is not copied
    /// out of a call (a `memcpy` of its 152 bytes per pair otherwise).
    #[inline(always)]
    pub(crate) fn from_local(
        frame: Transform,
        other_position: Vector2,
        normal: Vector2,
        local: &[LocalPoint],
        frame_is_b: bool,
    ) -> Self {
        // A turned body's rotation has both components below 1: its products
        // skip the saturation test (`mul_below_one`), the same bits.
        if below_one(frame.q.c) && below_one(frame.q.s) {
            Self::from_local_by(frame, other_position, normal, local, frame_is_b, BelowOne)
        } else if frame.q == Rot::IDENTITY {
            let frame = Transform { p: frame.p, q: Rot::IDENTITY };
            Self::from_local_by(frame, other_position, normal, local, frame_is_b, ByIdentity)
        } else {
            Self::from_local_by(frame, other_position, normal, local, frame_is_b, Saturating)
        }
    }

    /// [`Manifold::from_local`] with the product `mul` (by a component of
    /// `frame.q` first).
    #[inline(always)]
    fn from_local_by(
        frame: Transform,
        other_position: Vector2,
        normal: Vector2,
        local: &[LocalPoint],
        frame_is_b: bool,
        mul: impl Product,
    ) -> Self {
        let q = frame.q;
        let n = match Direction::of(normal) {
            Direction::Any(n) => rotate_by(q, n, mul),
            d => d.rotated(q),
        };
        let world = |lp: &LocalPoint| world_point(frame, other_position, lp, frame_is_b, mul);
        // One struct expression, each slot a value (a point, or zero past
        // the count, as in `EMPTY`): the compiler stores it straight into
        // the caller's manifold. Written as `EMPTY` with its slots filled
        // in a loop, it was built on the stack and copied out of
        // `collide_polygons` with a `memcpy` call (large 20: that function
        // with its `memcpy` 346.1 -> 339.4 M instructions).
        let (p0, p1) = match local {
            [] => (ManifoldPoint::ZERO, ManifoldPoint::ZERO),
            [a] => (world(a), ManifoldPoint::ZERO),
            [a, b, ..] => (world(a), world(b)),
        };
        Self {
            normal: if frame_is_b { -n } else { n },
            points: [p0, p1],
            count: local.len().min(MAX_MANIFOLD_POINTS),
        }
    }
}

/// The world point of `lp` (see [`Manifold::from_local`]). A function always
/// inlined, not a closure: as a closure called for both points the compiler
/// left it out of line (45.7 M instructions in 20 steps of the box pyramid).
#[inline(always)]
fn world_point(
    frame: Transform,
    other_position: Vector2,
    lp: &LocalPoint,
    frame_is_b: bool,
    mul: impl Product,
) -> ManifoldPoint {
    let anchor_frame = rotate_by(frame.q, lp.point, mul);
    // `Vector2` additions written out by component (the same operations):
    // as `+` and `−` the compiler left `Vector2::add` out of line here.
    let point = Vector2::new(frame.p.x + anchor_frame.x, frame.p.y + anchor_frame.y);
    let anchor_other = Vector2::new(point.x - other_position.x, point.y - other_position.y);
    let (anchor_a, anchor_b) =
        if frame_is_b { (anchor_other, anchor_frame) } else { (anchor_frame, anchor_other) };
    ManifoldPoint { point, anchor_a, anchor_b, separation: lp.separation, id: lp.id }
}

/// `q.rotate(v)`, `(c·x − s·y, s·x + c·y)`, with the product `mul` (the
/// saturating one, or [`mul_below_one`] when both of `q`'s components are
/// below 1): the same bits.
#[inline(always)]
pub(crate) fn rotate_by(q: Rot, v: Vector2, mul: impl Product) -> Vector2 {
    Vector2::new(mul.mul(q.c, v.x) - mul.mul(q.s, v.y), mul.mul(q.s, v.x) + mul.mul(q.c, v.y))
}

/// `q.rotate(v)` with the cheapest product `q`'s components allow
/// ([`mul_below_one`] when both are below 1, none for the identity): the
/// same bits.
#[inline(always)]
pub(crate) fn rotate_fast(q: Rot, v: Vector2) -> Vector2 {
    if below_one(q.c) && below_one(q.s) {
        rotate_by(q, v, BelowOne)
    } else if q == Rot::IDENTITY {
        v
    } else {
        q.rotate(v)
    }
}

/// `q.compose(o)` with [`mul_below_one`] when both of `q`'s components are
/// below 1 (a turned body): the same bits.
#[inline(always)]
pub(crate) fn compose_fast(q: Rot, o: Rot) -> Rot {
    if below_one(q.c) && below_one(q.s) {
        let m = BelowOne;
        Rot { c: m.mul(q.c, o.c) - m.mul(q.s, o.s), s: m.mul(q.s, o.c) + m.mul(q.c, o.s) }
    } else {
        q.compose(o)
    }
}

/// `xf.inv_mul(other)`: `other` in `xf`'s frame, `(q⁻¹·(p' − p), q⁻¹∘q')`, the
/// same bits. Every product has a component of `xf.q` (or its negated sine)
/// as a factor, so when both are below 1 (a turned body) the products skip
/// the saturation test ([`mul_below_one`]).
#[inline(always)]
pub(crate) fn relative_transform(xf: Transform, other: Transform) -> Transform {
    if below_one(xf.q.c) && below_one(xf.q.s) {
        relative_transform_by(xf, other, BelowOne)
    } else if xf.q == Rot::IDENTITY {
        // An unrotated body (the ground, a box that has not turned): the
        // products by 1 and 0 are exact, `other.p − xf.p` and `other.q`
        // come out of the additions of 0 unchanged.
        relative_transform_by(Transform { p: xf.p, q: Rot::IDENTITY }, other, ByIdentity)
    } else {
        xf.inv_mul(other)
    }
}

/// [`relative_transform`] with the product `mul`, written out as
/// [`Transform::inv_mul`] computes it: `inv_rotate` of the offset, then the
/// inverse rotation `(c, −s)` composed with `other.q`.
#[inline(always)]
fn relative_transform_by(xf: Transform, other: Transform, mul: impl Product) -> Transform {
    let (c, s) = (xf.q.c, xf.q.s);
    let d = other.p - xf.p;
    let p = Vector2::new(mul.mul(c, d.x) + mul.mul(s, d.y), mul.mul(c, d.y) - mul.mul(s, d.x));
    let (ns, o) = (-s, other.q);
    let q = Rot { c: mul.mul(c, o.c) - mul.mul(ns, o.s), s: mul.mul(ns, o.c) + mul.mul(c, o.s) };
    Transform { p, q }
}

/// A product `k * x` by a factor `k` of a known kind, with the same bits as
/// the saturating product. A trait of zero-sized types rather than a
/// closure: passed as closures, the products were left out of line, a call
/// each (13 M instructions in 20 steps of the box pyramid).
pub(crate) trait Product: Copy {
    /// `k * x`.
    fn mul(self, k: Scalar, x: Scalar) -> Scalar;
}

/// The saturating product.
#[derive(Clone, Copy)]
pub(crate) struct Saturating;

impl Product for Saturating {
    #[inline(always)]
    fn mul(self, k: Scalar, x: Scalar) -> Scalar {
        k * x
    }
}

/// [`mul_below_one`]: for `|k| < 1` (see [`below_one`]).
#[derive(Clone, Copy)]
pub(crate) struct BelowOne;

impl Product for BelowOne {
    #[inline(always)]
    fn mul(self, k: Scalar, x: Scalar) -> Scalar {
        mul_below_one(k, x)
    }
}

/// For `k` a component of [`Rot::IDENTITY`] (exactly 1 or 0): the saturating
/// product is then exactly `x` or 0 (`x · 2³² / 2³²` always fits). With `k`
/// a constant (a transform built with `Rot::IDENTITY`), the compiler folds
/// the product away, and the additions of 0 after it.
#[derive(Clone, Copy)]
pub(crate) struct ByIdentity;

impl Product for ByIdentity {
    #[inline(always)]
    fn mul(self, k: Scalar, x: Scalar) -> Scalar {
        if k == Scalar::ONE {
            x
        } else {
            ZERO
        }
    }
}

/// A contact point in the local frame of the body a pair function works in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct LocalPoint {
    /// Midway between the surfaces (m, local frame).
    pub point: Vector2,
    /// Separation along the normal (m).
    pub separation: Scalar,
    /// Feature id.
    pub id: u16,
}

/// `x / 2` (its lowest bit rounded as the `fixed` crate rounds products).
///
/// The same bits as `x * HALF`: that product is `⌊x · 2³¹ / 2³²⌋ = ⌊x / 2⌋`,
/// which always fits, i.e. an arithmetic shift by one, without the 128-bit
/// product.
#[inline]
pub(crate) fn half(x: Scalar) -> Scalar {
    Scalar::from_bits(x.to_bits() >> 1)
}

/// `n · d` for `n` with both components below 1 (see [`below_one`]): the same
/// bits as [`Vector2::dot`], the two products without their saturation test.
#[inline(always)]
pub(crate) fn dot_below_one(n: Vector2, d: Vector2) -> Scalar {
    mul_below_one(n.x, d.x) + mul_below_one(n.y, d.y)
}

/// The unit vector along `v` and the length of `v` (m), or `None` for the zero
/// vector. Contact normals often come from very short vectors (nearly coincident
/// circle centres, a circle centre just outside a corner); `Vector2` rescales by an
/// exact power of two before squaring, so the normal is unit to about 1e-9 for
/// every non-zero input.
pub(crate) fn direction_and_length(v: Vector2) -> Option<(Vector2, Scalar)> {
    // `Vector2` rescales by a power of two before squaring, so this is accurate
    // for any non-zero vector.
    let (n, len) = v.normalize_and_length();
    if n.is_zero() {
        None
    } else {
        Some((n, len))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::scalar::HALF;
    use crate::math::scalar::{self, from_int, ONE};

    fn unit_error(n: Vector2) -> Scalar {
        (n.length_squared() - ONE).abs()
    }

    #[test]
    fn products_below_one_are_the_saturating_products() {
        let edges =
            [Scalar::MIN, Scalar::MAX, Scalar::ZERO, ONE, -ONE, Scalar::from_bits(1), Scalar::from_bits(-1)];
        let below =
            [Scalar::from_bits((1 << 32) - 1), Scalar::from_bits(1 - (1 << 32)), Scalar::ZERO, HALF, -HALF];
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as i64
        };
        for k in 0..100_000usize {
            let a = match below.get(k) {
                Some(&a) => a,
                None => Scalar::from_bits(next() % (1 << 32)),
            };
            let b = match edges.get(k % 16) {
                Some(&b) => b,
                None => Scalar::from_bits(next() >> (k % 40)),
            };
            assert!(below_one(a));
            assert_eq!(mul_below_one(a, b), a * b, "{a:?} {b:?}");
            let (n, d) = (Vector2::new(a, Scalar::from_bits(next() % (1 << 32))), Vector2::new(b, b));
            assert_eq!(dot_below_one(n, d), n.dot(d));
        }
        assert!(!below_one(ONE) && !below_one(-ONE) && !below_one(Scalar::MIN));
    }

    #[test]
    fn relative_transform_and_rotate_by_are_the_plain_operations() {
        let mut x = 0x51F1_5EED_0DDB_A11Eu64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as i64
        };
        for k in 0..20_000 {
            // Turned rotations, the identity and quarter turns (components ±1).
            let mut rot = |k: usize| match k % 5 {
                0 => Rot::IDENTITY,
                1 => Rot { c: ZERO, s: -ONE },
                _ => Rot::from_angle(Scalar::from_bits(next() >> 29)),
            };
            let (qa, qb) = (rot(k), rot(k / 5));
            let shift = 20 + (k % 40) as u32;
            let mut point =
                || Vector2::new(Scalar::from_bits(next() >> shift), Scalar::from_bits(next() >> shift));
            let (xa, xb) = (Transform::new(point(), qa), Transform::new(point(), qb));
            assert_eq!(relative_transform(xa, xb), xa.inv_mul(xb), "{xa:?} {xb:?}");
            let v = point();
            assert_eq!(rotate_by(qa, v, Saturating), qa.rotate(v));
            if below_one(qa.c) && below_one(qa.s) {
                assert_eq!(rotate_by(qa, v, BelowOne), qa.rotate(v), "{qa:?} {v:?}");
            }
            if qa == Rot::IDENTITY {
                assert_eq!(rotate_by(Rot::IDENTITY, v, ByIdentity), qa.rotate(v), "{v:?}");
            }
        }
    }

    #[test]
    fn half_is_the_product_by_one_half() {
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        for k in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = match k {
                0 => Scalar::MIN,
                1 => Scalar::MAX,
                2 => Scalar::from_bits(-1),
                3 => Scalar::from_bits(1),
                _ => Scalar::from_bits(x as i64 >> (k % 40)),
            };
            assert_eq!(half(v), v * HALF, "{v:?}");
        }
    }

    #[test]
    fn direction_of_a_tiny_vector_is_unit_and_exact() {
        let tiny = Vector2::new(scalar::EPSILON, scalar::EPSILON * from_int(2));
        let (n, len) = direction_and_length(tiny).unwrap_or_default();
        assert!(unit_error(n) < Scalar::lit("1e-9"), "{n:?}");
        // |(1, 2)| · 2^-32 = 2.236 · 2^-32: 2 ulps after rounding.
        assert!(len >= scalar::EPSILON && len <= Scalar::from_bits(3), "{len:?}");
        let (n, len) = direction_and_length(Vector2::new(ZERO, -scalar::EPSILON)).unwrap_or_default();
        assert_eq!((n, len), (-Vector2::Y, scalar::EPSILON));
    }

    #[test]
    fn direction_of_large_and_ordinary_vectors() {
        let (n, len) = direction_and_length(Vector2::from_int(3, 4)).unwrap_or_default();
        assert!((n - Vector2::new(Scalar::lit("0.6"), Scalar::lit("0.8"))).length() < Scalar::lit("1e-9"));
        assert_eq!(len, from_int(5));
        let (n, len) = direction_and_length(Vector2::from_int(-2_000_000_000, 0)).unwrap_or_default();
        assert_eq!(n, -Vector2::X);
        assert_eq!(len, from_int(2_000_000_000));
        let extreme = Vector2::new(Scalar::MIN, Scalar::MIN);
        let (n, _) = direction_and_length(extreme).unwrap_or_default();
        // |n|² − 1 ≈ 2(|n| − 1): a few units of 2^-32 from rounding n's components.
        assert!(unit_error(n) < Scalar::lit("4e-9"), "{n:?}");
        assert!(direction_and_length(Vector2::ZERO).is_none());
    }

    #[test]
    fn from_local_swaps_anchors_and_flips_the_normal_for_frame_b() {
        let frame = Transform::new(Vector2::from_int(10, 0), Rot { c: ZERO, s: ONE });
        let other = Vector2::from_int(10, 3);
        let lp = LocalPoint { point: Vector2::from_int(1, 0), separation: from_int(-1), id: 7 };
        let a = Manifold::from_local(frame, other, Vector2::X, &[lp], false);
        assert_eq!(a.normal, Vector2::Y);
        assert_eq!(a.points().len(), 1);
        let p = a.points[0];
        assert_eq!(p.point, Vector2::from_int(10, 1));
        assert_eq!(p.anchor_a, Vector2::from_int(0, 1));
        assert_eq!(p.anchor_b, Vector2::from_int(0, -2));
        let b = Manifold::from_local(frame, other, Vector2::X, &[lp], true);
        assert_eq!(b.normal, -Vector2::Y);
        assert_eq!((b.points[0].anchor_a, b.points[0].anchor_b), (p.anchor_b, p.anchor_a));
        assert_eq!(Manifold::EMPTY.points().len(), 0);
    }
}
