//! Rod (fixed distance) and rope (maximum distance) between the anchors.

use super::maths::{anchors, apply_linear};
use super::Joint;
use crate::math::scalar::{Scalar, ZERO};
use crate::solver::{Bias, Row, SolverBody};

pub(super) fn warm_start(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody) {
    let (ra, rb, d) = anchors(j, a, b);
    let p = d.normalize() * j.impulse.x;
    j.step_linear += p;
    apply_linear(j, a, b, ra, rb, p);
}

/// Which distance a [`solve`] keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Distance {
    /// Exactly the length: a rod.
    Exact,
    /// At most the length: a rope, slack below.
    AtMost,
}

/// One iteration of the distance constraint `|d| = length` (rod) or
/// `|d| ≤ length` (rope: pulls only, and only when taut or about to be within
/// this sub-step). The axis follows the current anchors.
pub(super) fn solve(
    j: &mut Joint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    length: Scalar,
    distance: Distance,
    h: Scalar,
    bias: Bias,
) {
    let rope = distance == Distance::AtMost;
    let (ra, rb, d) = anchors(j, a, b);
    let (axis, len) = d.normalize_and_length();
    if len == ZERO {
        return;
    }
    let ([ma, mb], [ia, ib]) = (j.inv_mass, j.inv_inertia);
    let (rna, rnb) = (ra.cross(axis), rb.cross(axis));
    let k = ((ma + mb) + (ia * (rna * rna))) + (ib * (rnb * rnb));
    let mass = k.recip();
    let c = len - length;
    let rate = (b.velocity_at_offset(rb) - a.velocity_at_offset(ra)).dot(axis);
    let row = if rope && c < ZERO {
        // Slack: let it lengthen up to the slack within this sub-step, no more.
        Row::speculative(c, h.recip())
    } else {
        j.soft.row(c, bias)
    };
    let impulse = row.impulse(mass, rate, j.impulse.x);
    let mut new = j.impulse.x + impulse;
    if rope {
        // A rope only pulls: the impulse on B along A→B is never positive.
        new = new.min(ZERO);
    }
    let applied = new - j.impulse.x;
    j.impulse.x = new;
    let p = axis * applied;
    j.step_linear += p;
    apply_linear(j, a, b, ra, rb, p);
}
