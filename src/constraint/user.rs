//! Game constraints: the [`Constraint`] trait a game implements, solved beside
//! the built-in joints, and how a world stores one. They are trait objects, so
//! they are not part of a snapshot; they name their bodies by handle.

use crate::hook::Hook;

use crate::arena::Handle;
use crate::body::{Body, BodyHandle};
use crate::math::scalar::Scalar;

/// Game constraints ([`Constraint`] objects) a world can hold.
pub const MAX_USER_CONSTRAINTS: usize = 16;
/// Marker type naming game constraints in handles.
#[derive(Debug)]
pub enum ConstraintMarker {}
/// Handle of a game constraint.
pub type ConstraintHandle = Handle<ConstraintMarker>;

/// A game's constraint: applies impulses to its two bodies in every solver
/// iteration (the manual's `Constraint::solve`).
///
/// # If it panics
/// With `std` and the panic guard on (the default), a panic restores the world
/// to its state before the step and then unwinds out of
/// [`World::step`](crate::World::step). Without the guard (`no_std`, or
/// [`World::set_panic_guard`](crate::World::set_panic_guard)`(false)`) it unwinds
/// with the world half-stepped: the solver's copy of the bodies is partly written back, some
/// sub-steps are done and positions partly integrated. The world stays memory-safe and usable, but
/// its state
/// is not one any uninterrupted run reaches. The way back is the snapshot taken
/// before the step: [`World::restore`](crate::World::restore) it (a game that
/// catches panics with `std::panic::catch_unwind` should restore before it
/// steps again).
pub trait Constraint {
    /// Called once per step before the iterations, with the step length `dt`
    /// (optional: precompute effective masses here).
    fn prepare(&mut self, a: &Body, b: &Body, dt: Scalar) {
        let _ = (a, b, dt);
    }

    /// Applies impulses to the two bodies for one sub-step of `h` seconds, e.g.
    /// with [`Body::apply_impulse_at`]. A constraint to a fixed world point gets a
    /// static body at the origin as `b`; changes to it are ignored.
    fn solve(&mut self, a: &mut Body, b: &mut Body, h: Scalar);
}

/// A game's constraint stored in a world.
pub(crate) struct UserConstraint<'a> {
    pub(crate) body_a: BodyHandle,
    pub(crate) body_b: Option<BodyHandle>,
    pub(crate) constraint: Hook<'a, dyn Constraint + Send + 'a>,
}

/// A world's game constraints, in registration order (slot order).
pub(crate) type UserConstraints<'a> = crate::arena::Arena<
    'a,
    UserConstraint<'a>,
    ConstraintMarker,
    [crate::arena::Slot<UserConstraint<'a>>; MAX_USER_CONSTRAINTS],
>;
