//! Weld joint: the pivot's point constraint plus a fixed relative angle.

use super::maths::{anchors, apply_angular, apply_linear};
use super::pivot::{relative_angle, solve_point};
use super::Joint;
use crate::math::scalar::{self, ZERO};
use crate::solver::SolverBody;

pub(super) fn warm_start(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody) {
    let (ra, rb, _) = anchors(j, a, b);
    j.step_linear += j.impulse;
    apply_linear(j, a, b, ra, rb, j.impulse);
    apply_angular(j, a, b, j.angular_impulse);
}

pub(super) fn solve(
    j: &mut Joint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    _h: crate::Scalar,
    use_bias: bool,
) {
    let axial = j.axial_mass;
    let rate = b.w - a.w;
    let (bias, mass_scale, impulse_scale) = if use_bias {
        (relative_angle(j, a, b) * j.soft.bias_rate, j.soft.mass_scale, j.soft.impulse_scale)
    } else {
        (ZERO, scalar::ONE, ZERO)
    };
    let impulse = (-(axial * mass_scale * (rate + bias))) - (impulse_scale * j.angular_impulse);
    j.angular_impulse += impulse;
    apply_angular(j, a, b, impulse);
    solve_point(j, a, b, use_bias);
}
