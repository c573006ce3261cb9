//! Weld joint: the pivot's point constraint plus a fixed relative angle.

use super::Joint;
use crate::solver::{Bias, BodyLanes};

/// One iteration: the angle (measured with the pose only when biased), then
/// the point.
pub(super) fn solve(j: &mut Joint, la: &mut BodyLanes, lb: &mut BodyLanes, bias: Bias) {
    j.lanes.solve_weld(la, lb, bias);
    j.lanes.solve_point(la, lb, bias);
}
