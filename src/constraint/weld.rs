//! Weld joint: the pivot's point constraint plus a fixed relative angle.

use super::pivot::{relative_angle, solve_point};
use super::{anchors, apply_angular, apply_linear, Joint};
use crate::math::scalar::{self, ScalarExt as _, ZERO};
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
    let rate = b.w.saturating_sub(a.w);
    let (bias, mass_scale, impulse_scale) = if use_bias {
        (relative_angle(j, a, b).sat_mul(j.soft.bias_rate), j.soft.mass_scale, j.soft.impulse_scale)
    } else {
        (ZERO, scalar::ONE, ZERO)
    };
    let impulse = axial
        .sat_mul(mass_scale)
        .sat_mul(rate.saturating_add(bias))
        .saturating_neg()
        .saturating_sub(impulse_scale.sat_mul(j.angular_impulse));
    j.angular_impulse = j.angular_impulse.saturating_add(impulse);
    apply_angular(j, a, b, impulse);
    solve_point(j, a, b, use_bias);
}
