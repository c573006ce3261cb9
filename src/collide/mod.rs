//! Narrow phase: the contact [`Manifold`] between two shapes that the broad phase
//! says may touch.
//!
//! One function per pair of shapes, named `collide_<shape a>_<shape b>`:
//! [`collide_circles`], [`collide_polygon_circle`], [`collide_polygons`],
//! [`collide_capsule_circle`], [`collide_segment_circle`], [`collide_capsules`],
//! [`collide_segment_capsule`], [`collide_polygon_capsule`] and
//! [`collide_segment_polygon`] (segments never collide with segments). Each
//! takes the two shapes with their body transforms and a `margin` (m): points are
//! reported while the shapes are at most `margin` apart (separation ≤ margin), so
//! the solver sees contacts a little before they happen (speculative contacts,
//! which prevent tunnelling and the jitter of contacts that come and go). Farther
//! apart gives [`Manifold::EMPTY`].
//!
//! The normal always points from the first shape to the second. Every function
//! works in the local frame of one body, so only relative positions are ever
//! squared: moving both bodies by the same offset (tested up to ±1e6 m) shifts
//! the contact points by exactly that offset and changes nothing else, bit for
//! bit. Nothing divides by zero, nothing panics, and the
//! result is a function of the inputs' bits alone (all ties are broken by index
//! order, as each function documents).
//!
//! Rounded shapes (capsules, segments as capsules of radius 0, polygons with a
//! [`rounding`](crate::geometry::PolygonPath::rounding) radius) are a convex core
//! grown by a radius: the contact is the cores' with the separation less both
//! radii and each point midway between the rounded surfaces.
//!
//! The approach follows the narrow phase of Box2D v3 (separating axes, reference
//! face, clipping, feature ids for warm starting; a capsule against a polygon as
//! a two-vertex polygon with a radius), written for fixed point.

mod capsule_capsule;
mod capsule_circle;
mod chain_segment;
mod circle_circle;
mod manifold;
mod polygon_capsule;
mod polygon_circle;
mod polygon_polygon;
#[cfg(all(test, feature = "std"))]
mod random_poses;
mod toi;

pub use capsule_capsule::{collide_capsules, collide_segment_capsule, FACE_COSINE};
pub use capsule_circle::{collide_capsule_circle, collide_segment_circle};
pub use chain_segment::{
    collide_chain_segment_capsule, collide_chain_segment_circle, collide_chain_segment_polygon,
    CHAIN_FACE_SINE,
};
pub use circle_circle::collide_circles;
pub(crate) use manifold::{compose_fast, dot_below_one, half, rotate_fast};
pub use manifold::{Manifold, ManifoldPoint, MAX_MANIFOLD_POINTS};
pub use polygon_capsule::{collide_polygon_capsule, collide_segment_polygon};
pub use polygon_circle::collide_polygon_circle;
pub use polygon_polygon::{collide_polygons, REFERENCE_FACE_TOLERANCE};
pub(crate) use toi::{time_of_impact, Swept};

use crate::math::{Rot, Scalar, Vector2};

pub use crate::geometry::ChainSegment;

/// The index after `i` around a polygon of `count` vertices (edge `i` runs from
/// vertex `i` to vertex `next_index(i, count)`).
/// A direction (a face normal, in its polygon's frame) classified once, so
/// that products with it are skipped when it is a coordinate axis, as every
/// normal of an axis-aligned box is.
///
/// Same bits as the `Vector2` operations it stands for: those compute each
/// product with the saturating `Scalar` product, which by an exact 0 gives 0
/// and by an exact ±1 gives ±x (for `x = MIN`, `−1 · x` saturates to `MAX`, as
/// the saturating negation does), and keep their additions, which the forms
/// below write out unchanged (a `+ 0` is folded by the compiler, not by
/// changing the result). A test compares every method with the plain
/// operation over random and extreme inputs.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Direction {
    /// (1, 0)
    PosX,
    /// (−1, 0)
    NegX,
    /// (0, 1)
    PosY,
    /// (0, −1)
    NegY,
    /// Any other vector.
    Any(Vector2),
}

impl Direction {
    /// Classifies `n` (exact comparisons: a normal off an axis by one ulp is
    /// `Any`).
    #[inline]
    pub(crate) fn of(n: Vector2) -> Self {
        let (one, zero) = (Scalar::ONE, Scalar::ZERO);
        match (n.x, n.y) {
            (x, y) if y == zero && x == one => Self::PosX,
            (x, y) if y == zero && x == -one => Self::NegX,
            (x, y) if x == zero && y == one => Self::PosY,
            (x, y) if x == zero && y == -one => Self::NegY,
            _ => Self::Any(n),
        }
    }

    /// `n · d`, as [`Vector2::dot`] computes it.
    #[inline(always)]
    pub(crate) fn dot(self, d: Vector2) -> Scalar {
        let zero = Scalar::ZERO;
        match self {
            Self::PosX => d.x + zero,
            Self::NegX => -d.x + zero,
            Self::PosY => zero + d.y,
            Self::NegY => zero + -d.y,
            Self::Any(n) => n.dot(d),
        }
    }

    /// `n · s`, as `Vector2 * Scalar` computes it.
    #[inline(always)]
    pub(crate) fn scale(self, s: Scalar) -> Vector2 {
        let zero = Scalar::ZERO;
        match self {
            Self::PosX => Vector2::new(s, zero),
            Self::NegX => Vector2::new(-s, zero),
            Self::PosY => Vector2::new(zero, s),
            Self::NegY => Vector2::new(zero, -s),
            Self::Any(n) => n * s,
        }
    }

    /// `q.rotate(n)`, as [`Rot::rotate`] computes it:
    /// `(c·x − s·y, s·x + c·y)`.
    #[inline(always)]
    pub(crate) fn rotated(self, q: Rot) -> Vector2 {
        let zero = Scalar::ZERO;
        match self {
            Self::PosX => Vector2::new(q.c - zero, q.s + zero),
            Self::NegX => Vector2::new(-q.c - zero, -q.s + zero),
            Self::PosY => Vector2::new(zero - q.s, zero + q.c),
            Self::NegY => Vector2::new(zero - -q.s, zero + -q.c),
            Self::Any(n) => q.rotate(n),
        }
    }

    /// `q.inv_rotate(n)`, as [`Rot::inv_rotate`] computes it:
    /// `(c·x + s·y, c·y − s·x)`.
    #[inline(always)]
    pub(crate) fn inv_rotated(self, q: Rot) -> Vector2 {
        let zero = Scalar::ZERO;
        match self {
            Self::PosX => Vector2::new(q.c + zero, zero - q.s),
            Self::NegX => Vector2::new(-q.c + zero, zero - -q.s),
            Self::PosY => Vector2::new(zero + q.s, q.c - zero),
            Self::NegY => Vector2::new(zero + -q.s, -q.c - zero),
            Self::Any(n) => q.inv_rotate(n),
        }
    }
}

#[inline]
fn next_index(i: usize, count: usize) -> usize {
    if i + 1 < count {
        i + 1
    } else {
        0
    }
}

/// Helpers shared by the unit tests of the pair functions.
#[cfg(test)]
mod direction_tests {
    use super::Direction;
    use crate::math::{Rot, Scalar, Vector2};

    #[test]
    fn axis_forms_give_the_bits_of_the_plain_operations() {
        let extremes = [
            Scalar::MIN,
            Scalar::MAX,
            Scalar::ZERO,
            Scalar::ONE,
            -Scalar::ONE,
            Scalar::from_bits(1),
            Scalar::from_bits(-1),
            Scalar::from_bits(i64::MIN + 1),
        ];
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let r = x as i64;
            // Mostly small, sometimes anything.
            Scalar::from_bits(if r & 3 == 0 { r } else { r >> 28 })
        };
        let axes = [Vector2::X, -Vector2::X, Vector2::Y, -Vector2::Y];
        for k in 0..20_000usize {
            let pick = |v: Scalar, i: usize| extremes.get(i % 11).copied().unwrap_or(v);
            let (a, b, c) = (pick(next(), k), pick(next(), k / 11), pick(next(), k / 121));
            let d = Vector2::new(a, b);
            let q = Rot { c: b, s: c };
            let any = Vector2::new(c, a);
            for n in axes.into_iter().chain([any]) {
                let dir = Direction::of(n);
                assert_eq!(dir.dot(d), n.dot(d), "{n:?} . {d:?}");
                assert_eq!(dir.scale(a), n * a, "{n:?} * {a:?}");
                assert_eq!(dir.rotated(q), q.rotate(n), "{q:?} {n:?}");
                assert_eq!(dir.inv_rotated(q), q.inv_rotate(n), "{q:?} {n:?}");
            }
            assert!(matches!(
                Direction::of(axes[k % 4]),
                Direction::PosX | Direction::NegX | Direction::PosY | Direction::NegY
            ));
        }
    }
}

#[cfg(test)]
mod test_support {
    use crate::math::{Rot, Scalar, Transform, Vector2};

    /// Tolerance for results that go through a rotation or a square root (m):
    /// about 40 units of 2^-32.
    pub const TOL: Scalar = Scalar::lit("1e-8");

    /// `a` and `b` within [`TOL`].
    pub fn close(a: Vector2, b: Vector2) -> bool {
        (a - b).length() < TOL
    }

    /// `a` and `b` within [`TOL`].
    pub fn near(a: Scalar, b: Scalar) -> bool {
        (a - b).abs() < TOL
    }

    /// The vector `(x, y)` from decimal literals.
    pub fn v(x: &str, y: &str) -> Vector2 {
        Vector2::new(Scalar::lit(x), Scalar::lit(y))
    }

    /// An unrotated transform at `(x, y)` from decimal literals.
    pub fn at(x: &str, y: &str) -> Transform {
        Transform::new(v(x, y), Rot::IDENTITY)
    }
}
