//! Spring and damped spring: an explicit force along the line between the anchors.
//!
//! A force, not a constraint: it stays in `Scalar`, on the bodies' own
//! velocities (taken from the lanes and written back around it).

use super::maths::{anchors, apply_linear};
use super::row::SpringRow;
use crate::math::scalar::{Scalar, ZERO};
use crate::solver::{BodyLanes, SolverBody};

/// Applies F = −k·(ℓ − ℓ₀) − c·ℓ̇ along the anchor line for a sub-step of `h`
/// seconds (once per sub-step, never in the relax sweeps: it is a force, not a
/// constraint). Anchors that coincide have no direction and get no force.
pub(super) fn apply(
    s: &mut SpringRow,
    (a, la): (&mut SolverBody, &mut BodyLanes),
    (b, lb): (&mut SolverBody, &mut BodyLanes),
    h: Scalar,
) {
    a.pull(la);
    b.pull(lb);
    let (ra, rb, d) = anchors(s.anchors, a, b);
    let (axis, len) = d.normalize_and_length();
    if len == ZERO {
        return;
    }
    let stretch = len - s.rest_length;
    let rate = (b.velocity_at_offset(rb) - a.velocity_at_offset(ra)).dot(axis);
    let force = -((s.stiffness * stretch) + (s.damping * rate));
    let p = axis * (force * h);
    s.step_linear += p;
    apply_linear(s, a, b, ra, rb, p);
    for (body, lane) in [(a, la), (b, lb)] {
        if body.dynamic {
            body.push(lane);
        }
    }
}
