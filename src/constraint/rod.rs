//! Rod (fixed distance) and rope (maximum distance) between the anchors.
//!
//! The axis follows the current anchors: it is measured once per sub-step
//! with the pose ([`JointLanes::axis`](crate::solver::JointLanes)), with the
//! effective mass along it; the iterations run in the solver's 32-bit formats.

use crate::solver::{Bias, BodyLanes, JointLanes};

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
/// this sub-step).
#[inline(always)]
pub(super) fn solve(
    j: &mut JointLanes,
    la: &mut BodyLanes,
    lb: &mut BodyLanes,
    distance: Distance,
    bias: Bias,
) {
    j.solve_axial(la, lb, distance == Distance::AtMost, bias);
}
