//! Pivot (revolute) joint: a point constraint, optional angle limits, optional motor.

use super::maths::{anchors, apply_angular, apply_linear};
use super::{Joint, MaxTorque, Motor};
use crate::math::scalar::{self, Scalar, ZERO};
use crate::solver::{Bias, Row, SolverBody};

pub(super) fn warm_start(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody) {
    let (ra, rb, _) = anchors(j, a, b);
    j.step_linear += j.impulse;
    apply_linear(j, a, b, ra, rb, j.impulse);
    let angular = (j.motor_impulse + j.limit_impulse) - j.angular_impulse;
    apply_angular(j, a, b, angular * orientation(j));
}

/// The relative angle θB − θA measured from the angle at creation, in (−π, π].
pub(super) fn relative_angle(j: &Joint, a: &SolverBody, b: &SolverBody) -> Scalar {
    j.reference.inv_mul(a.q.inv_mul(b.q)).angle()
}

/// +1, or −1 for a joint to a fixed world point: there the limits and the motor
/// act on the body's own angle and spin (θA, ωA), which is what a game means by
/// "the wheel turns at 5 rad/s", rather than on θB − θA with the world as B.
fn orientation(j: &Joint) -> Scalar {
    if j.def.body_b.is_none() {
        -scalar::ONE
    } else {
        scalar::ONE
    }
}

pub(super) fn solve(
    j: &mut Joint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    limits: Option<(Scalar, Scalar)>,
    motor: Option<Motor>,
    h: Scalar,
    bias: Bias,
) {
    let axial = j.axial_mass;
    let sign = orientation(j);
    let relative_rate = |a: &SolverBody, b: &SolverBody| (b.w - a.w) * sign;
    if let Some(m) = motor {
        // Drive the relative spin towards the target; no position error, no bias.
        let rate = relative_rate(a, b) - m.speed;
        let impulse = -(axial * rate);
        let new = match m.max_torque {
            MaxTorque::Limited(t) => {
                let max = t * h;
                (j.motor_impulse + impulse).clamp(-max, max)
            }
            MaxTorque::Unlimited => j.motor_impulse + impulse,
        };
        let applied = new - j.motor_impulse;
        j.motor_impulse = new;
        apply_angular(j, a, b, applied * sign);
    }
    if let Some((lower, upper)) = limits {
        let angle = relative_angle(j, a, b) * sign;
        // Lower limit: θ − lower ≥ 0, pushes θ up (impulse ≥ 0).
        let c = angle - lower;
        let applied = limit_step(j, c, relative_rate(a, b), axial, h, bias, j.limit_impulse);
        j.limit_impulse += applied;
        apply_angular(j, a, b, applied * sign);
        // Upper limit: upper − θ ≥ 0, pushes θ down (stored as a positive impulse).
        let c = upper - angle;
        let rate = -relative_rate(a, b);
        let applied = limit_step(j, c, rate, axial, h, bias, j.angular_impulse);
        j.angular_impulse += applied;
        apply_angular(j, a, b, -(applied * sign));
    }
    solve_point(j, a, b, bias);
}

/// The change of a one-sided angular limit impulse (accumulated stays ≥ 0):
/// speculative while inside the limit, soft when past it.
fn limit_step(
    j: &Joint,
    c: Scalar,
    rate: Scalar,
    axial: Scalar,
    h: Scalar,
    bias: Bias,
    old: Scalar,
) -> Scalar {
    let row = if c > ZERO { Row::speculative(c, h.recip()) } else { j.soft.row(c, bias) };
    let impulse = row.impulse(axial, rate, old);
    let new = (old + impulse).max(ZERO);
    new - old
}

/// The point constraint shared with the weld joint: the anchors coincide.
pub(super) fn solve_point(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody, bias: Bias) {
    let (ra, rb, d) = anchors(j, a, b);
    let Some(mass) = j.point_mass else { return };
    let rate = b.velocity_at_offset(rb) - a.velocity_at_offset(ra);
    let impulse = j.soft.row(d, bias).impulse(mass, rate, j.impulse);
    j.impulse += impulse;
    j.step_linear += impulse;
    apply_linear(j, a, b, ra, rb, impulse);
}
