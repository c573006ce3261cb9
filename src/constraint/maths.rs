//! The maths the built-in joints share in `Scalar`: where the anchors are in
//! world space and applying an impulse (springs), the point-to-point
//! constraint's mass (prepare),
//! and the static stand-in body of a joint to a world point.

use crate::body::Body;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Matrix22, Vector2};
use crate::solver::SolverBody;

use super::Joint;

/// The world anchors of a joint: offsets from each centre (world orientation) and
/// the vector between the anchor points, B − A.
pub(crate) fn anchors(j: &Joint, a: &SolverBody, b: &SolverBody) -> (Vector2, Vector2, Vector2) {
    let ra = a.q.rotate(j.def.anchor_a);
    let rb = b.q.rotate(j.def.anchor_b);
    let d = (b.p - a.p) + (rb - ra);
    (ra, rb, d)
}

/// The inverse of K = (mA + mB)·I + iA·[rA]ᵀ[rA] + iB·[rB]ᵀ[rB], the mass matrix
/// of a point-to-point constraint with arms `ra`, `rb`, each entry divided
/// exactly (the determinant is tiny for heavy bodies, where 1/det would lose
/// the digits); `None` when singular.
pub(crate) fn point_mass_inverse(
    ma: Scalar,
    ia: Scalar,
    ra: Vector2,
    mb: Scalar,
    ib: Scalar,
    rb: Vector2,
) -> Option<Matrix22> {
    let m = ma + mb;
    let k11 = (m + (ia * (ra.y * ra.y))) + (ib * (rb.y * rb.y));
    let k12 = -((ia * (ra.x * ra.y)) + (ib * (rb.x * rb.y)));
    let k22 = (m + (ia * (ra.x * ra.x))) + (ib * (rb.x * rb.x));
    let det = (k11 * k22) - (k12 * k12);
    if det <= ZERO {
        return None;
    }
    let off = (-k12).div_or_zero(det);
    Some(Matrix22::new(k22.div_or_zero(det), off, off, k11.div_or_zero(det)))
}

/// Applies a linear impulse `p` at offsets `ra` (negated on A) and `rb`.
pub(crate) fn apply_linear(
    j: &Joint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    ra: Vector2,
    rb: Vector2,
    p: Vector2,
) {
    let ([ma, mb], [ia, ib]) = (j.inv_mass, j.inv_inertia);
    a.v -= p * ma;
    a.w -= ia * ra.cross(p);
    b.v += p * mb;
    b.w += ib * rb.cross(p);
}

/// A static body at the origin: the "other body" of a joint to a world point.
pub(crate) fn ground() -> Body {
    Body::ground()
}
