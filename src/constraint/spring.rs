//! Spring and damped spring: an explicit force along the line between the anchors.
//!
//! A force, not a constraint: it stays in `Scalar`, on the bodies' own
//! velocities (taken from the lanes and written back around it).

use super::maths::{anchors, apply_linear};
use super::Joint;
use crate::math::scalar::{Scalar, ZERO};
use crate::solver::{BodyLanes, SolverBody};

/// Applies F = −k·(ℓ − ℓ₀) − c·ℓ̇ along the anchor line for a sub-step of `h`
/// seconds (once per sub-step, never in the relax sweeps: it is a force, not a
/// constraint). Anchors that coincide have no direction and get no force.
pub(super) fn apply(
    j: &mut Joint,
    (a, la): (&mut SolverBody, &mut BodyLanes),
    (b, lb): (&mut SolverBody, &mut BodyLanes),
    k: Scalar,
    c: Scalar,
    rest: Scalar,
    h: Scalar,
) {
    a.pull(la);
    b.pull(lb);
    let (ra, rb, d) = anchors(j, a, b);
    let (axis, len) = d.normalize_and_length();
    if len == ZERO {
        return;
    }
    let stretch = len - rest;
    let rate = (b.velocity_at_offset(rb) - a.velocity_at_offset(ra)).dot(axis);
    let force = -((k * stretch) + (c * rate));
    let p = axis * (force * h);
    j.step_linear += p;
    apply_linear(j, a, b, ra, rb, p);
    for (body, lane) in [(a, la), (b, lb)] {
        if body.dynamic {
            body.push(lane);
        }
    }
}
