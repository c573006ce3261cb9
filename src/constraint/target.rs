//! Target (mouse) joint: body A's anchor pulled towards a world point by a
//! soft point constraint with a force limit.
//!
//! The point constraint of pivots and welds, in the solver's 32-bit formats
//! ([`JointLanes`]), with two differences: its
//! softness is the joint's own spring (frequency and damping ratio, set at
//! prepare) instead of the joints' stiff position correction, and it stays
//! soft and biased in the relax sweep too (a spring, not an error to remove:
//! Box2D's mouse joint does the same); and its accumulated impulse is clamped
//! by length to `max_force`·h after every iteration, so the force it applies
//! over a sub-step never exceeds `max_force`. Like Box2D v3's mouse joint it
//! also damps the body's spin softly ([`TARGET_SPIN_HERTZ`](super::TARGET_SPIN_HERTZ),
//! no bias: no angle to return to), so a body held off its centre stops
//! swinging about the point held.

use crate::solver::{BodyLanes, JointLanes};

/// One iteration, in the biased and in the relax sweep alike: the spin
/// damping, then the point.
#[inline(always)]
pub(super) fn solve(j: &mut JointLanes, la: &mut BodyLanes, lb: &mut BodyLanes) {
    j.solve_spin_damping(la, lb);
    j.solve_target(la, lb);
}
