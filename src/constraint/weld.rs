//! Weld joint: the pivot's point constraint plus a fixed relative angle.

use crate::solver::{Bias, BodyLanes, JointLanes};

/// One iteration: the angle (measured with the pose only when biased), then
/// the point.
#[inline(always)]
pub(super) fn solve(j: &mut JointLanes, la: &mut BodyLanes, lb: &mut BodyLanes, bias: Bias) {
    j.solve_weld(la, lb, bias);
    j.solve_point(la, lb, bias);
}
