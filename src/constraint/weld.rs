//! Weld joint: the pivot's point constraint plus a fixed relative angle.

use super::maths::{anchors, apply_angular, apply_linear};
use super::pivot::{relative_angle, solve_point};
use super::Joint;
use crate::solver::{Bias, Row, SolverBody};

pub(super) fn warm_start(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody) {
    let (ra, rb, _) = anchors(j, a, b);
    j.step_linear += j.impulse;
    apply_linear(j, a, b, ra, rb, j.impulse);
    apply_angular(j, a, b, j.angular_impulse);
}

pub(super) fn solve(j: &mut Joint, a: &mut SolverBody, b: &mut SolverBody, _h: crate::Scalar, bias: Bias) {
    let axial = j.axial_mass;
    let rate = b.w - a.w;
    // The angle costs a trigonometric call: measured only when it is used.
    let row = match bias {
        Bias::On => j.soft.row(relative_angle(j, a, b), bias),
        Bias::Off => Row::RIGID,
    };
    let impulse = row.impulse(axial, rate, j.angular_impulse);
    j.angular_impulse += impulse;
    apply_angular(j, a, b, impulse);
    solve_point(j, a, b, bias);
}
