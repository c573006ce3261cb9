//! Constraints between two bodies (or a body and a fixed world point).
//!
//! The manual's three — [`JointKind::Spring`], [`JointKind::DampedSpring`] and
//! [`JointKind::Rod`] — and the joints games expect from other engines:
//! [`JointKind::Rope`] (maximum distance), [`JointKind::Pivot`] (revolute, with
//! angle limits and a motor), [`JointKind::Weld`] and [`JointKind::Target`] (Box2D's
//! mouse joint: a body pulled towards a world point the game moves, softly and
//! with a force limit). Any of them can be breakable
//! ([`JointDef::breakable`]). Games add their own by implementing [`Constraint`].
//!
//! # How they are solved
//! Built-in joints are plain data in the world's storage (so the snapshot can
//! hold them). They are solved in the same sub-steps as the contacts, before them,
//! in joint-slot order, then the game's constraints in registration order:
//! * springs apply their force `F = −k·(ℓ − ℓ₀) − c·ℓ̇` along the line between the
//!   anchors once per sub-step (explicit, symplectic: periods and damping come out
//!   as the closed forms say; a spring too stiff for the step, `k·h²/m > 4`, is
//!   unstable, as in any explicit integrator);
//! * rods, ropes, pivots and welds are velocity constraints with Box2D v3's soft
//!   position correction (a stiff spring-damper of [`JOINT_HERTZ`] Hz, damping
//!   ratio [`JOINT_DAMPING_RATIO`]), warm-started from the impulses they ended the
//!   last sub-step with, and relaxed like contacts. Their iterations run in the
//!   solver's 32-bit formats on the bodies' lane velocities, as the contacts
//!   do: impulses in velocity units, masses as ratios (the format table is in
//!   `src/solver/joint_lanes.rs`). Prepare turns the persistent impulses (N·s,
//!   N·m·s, what the snapshot holds) into those units once per step, and the
//!   end of the step turns them back;
//! * a target joint is the pivot's point constraint to a world point with its
//!   own spring (`hertz`, `damping_ratio`) in place of that correction, soft in
//!   the relax sweep too, its accumulated impulse clamped by length so its
//!   force stays within `max_force`, and a soft spin damping (Box2D v3's).
//!
//! The sub-steps work on a row per joint in a dense scratch array of the
//! solver (`row.rs`), built at prepare in joint-slot order: the joints
//! themselves are read once at prepare and written once at the end of the
//! step, which keeps the twelve joint passes of a step off the larger joint
//! slots.
//!
//! # Breaking
//! A breakable joint whose impulse over a step exceeds its limit is removed after
//! that step and handed, with its handle, to the world's break callback
//! ([`World::set_joint_break_callback`](crate::World::set_joint_break_callback)),
//! in joint-slot order. It breaks once: the handle is stale afterwards.
//!
//! # Removing a body
//! [`World::remove_body`](crate::World::remove_body) removes every built-in joint
//! attached to the body (without calling the break callback: the game removed the
//! body and knows) and every game constraint attached to it.

//!
//! # Files
//! [`JointDef`] and its kinds are in `def.rs`, the runtime [`Joint`] in
//! `joint.rs`, its row in the solver's dense joint array and the dispatch of
//! each solver stage in `row.rs`, the maths the joints share in `maths.rs`, one file
//! per kind (`spring.rs`, `rod.rs`, `pivot.rs`, `weld.rs`, `target.rs`), and the game's
//! [`Constraint`] in `user.rs`.

mod def;
mod joint;
mod maths;
mod pivot;
mod rod;
mod row;
mod spring;
mod target;
mod user;
mod weld;

pub(crate) use def::{validate, validate_params};
pub use def::{JointDef, JointKind, MaxTorque, Motor};
pub use joint::{
    Joint, JointHandle, JointMarker, JOINT_DAMPING_RATIO, JOINT_HERTZ, TARGET_SPIN_DAMPING_RATIO,
    TARGET_SPIN_HERTZ,
};
pub(crate) use maths::ground;
pub(crate) use row::JointRow;
pub use user::{Constraint, ConstraintHandle, ConstraintMarker, MAX_USER_CONSTRAINTS};
pub(crate) use user::{UserConstraint, UserConstraints};
