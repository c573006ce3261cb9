//! Narrow phase: the contact [`Manifold`] between two shapes that the broad phase
//! says may touch.
//!
//! One function per pair of shapes, named `collide_<shape a>_<shape b>`:
//! [`collide_circles`], [`collide_polygon_circle`] and [`collide_polygons`]. Each
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
//! The approach follows the narrow phase of Box2D v3 (separating axes, reference
//! face, clipping, feature ids for warm starting), written for fixed point.

mod circle_circle;
mod manifold;
mod polygon_circle;
mod polygon_polygon;

pub use circle_circle::collide_circles;
pub use manifold::{Manifold, ManifoldPoint, MAX_MANIFOLD_POINTS};
pub use polygon_circle::collide_polygon_circle;
pub use polygon_polygon::{collide_polygons, REFERENCE_FACE_TOLERANCE};

/// The index after `i` around a polygon of `count` vertices (edge `i` runs from
/// vertex `i` to vertex `next_index(i, count)`).
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
