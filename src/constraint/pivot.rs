//! Pivot (revolute) joint: a point constraint, optional angle limits, optional motor.
//!
//! The iterations run in the solver's 32-bit formats
//! ([`JointLanes`]); the relative angle the limits
//! need is measured here, once per sub-step, with the pose.

use crate::math::scalar::Scalar;
use crate::math::Rot;
use crate::solver::{Bias, BodyLanes, JointLanes, SolverBody};

/// The relative angle θB − θA measured from `reference` (the relative angle at
/// creation), in (−π, π].
pub(super) fn relative_angle(reference: Rot, a: &SolverBody, b: &SolverBody) -> Scalar {
    reference.inv_mul(a.q.inv_mul(b.q)).angle()
}

/// One iteration: motor, limits, then the point. For a joint to a fixed world
/// point (`world_point`) the limits and the motor act on the body's own angle
/// and spin (θA, ωA), which is what a game means by "the wheel turns at 5
/// rad/s", rather than on θB − θA with the world as B.
#[inline(always)]
pub(super) fn solve(
    j: &mut JointLanes,
    la: &mut BodyLanes,
    lb: &mut BodyLanes,
    limits: bool,
    motor: bool,
    world_point: bool,
    bias: Bias,
) {
    if motor {
        // Drive the relative spin towards the target; no position error, no bias.
        j.solve_motor(la, lb, world_point);
    }
    if limits {
        j.solve_limits(la, lb, world_point, bias);
    }
    j.solve_point(la, lb, bias);
}
