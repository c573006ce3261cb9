//! The maths the built-in joints share in `Scalar`: where the anchors are in
//! world space and applying an impulse (springs), and the static stand-in body
//! of a joint to a world point.

use crate::body::Body;
use crate::math::Vector2;
use crate::solver::SolverBody;

use super::row::SpringRow;

/// The world anchors of a joint with local anchors `[anchor_a, anchor_b]`:
/// offsets from each centre (world orientation) and the vector between the
/// anchor points, B − A.
pub(crate) fn anchors(
    [anchor_a, anchor_b]: [Vector2; 2],
    a: &SolverBody,
    b: &SolverBody,
) -> (Vector2, Vector2, Vector2) {
    let ra = a.q.rotate(anchor_a);
    let rb = b.q.rotate(anchor_b);
    let d = (b.p - a.p) + (rb - ra);
    (ra, rb, d)
}

/// Applies a linear impulse `p` at offsets `ra` (negated on A) and `rb`.
pub(crate) fn apply_linear(
    s: &SpringRow,
    a: &mut SolverBody,
    b: &mut SolverBody,
    ra: Vector2,
    rb: Vector2,
    p: Vector2,
) {
    let ([ma, mb], [ia, ib]) = (s.inv_mass, s.inv_inertia);
    a.v -= p * ma;
    a.w -= ia * ra.cross(p);
    b.v += p * mb;
    b.w += ib * rb.cross(p);
}

/// A static body at the origin: the "other body" of a joint to a world point.
pub(crate) fn ground() -> Body {
    Body::ground()
}
