//! The joint and game-constraint API of [`World`].

use crate::body::BodyHandle;
use crate::constraint::{
    self, Constraint, ConstraintHandle, Joint, JointDef, JointHandle, JointKind, UserConstraint,
};
use crate::error::Error;
use crate::hook::Hook;
use crate::math::Vector2;

use super::{JointBreakFn, World};

impl<'a> World<'a> {
    /// Adds a built-in joint (spring, damped spring, rod, rope, pivot, weld,
    /// target).
    ///
    /// # Errors
    /// [`Error::StaleHandle`] for an unknown body; [`Error::InvalidOperation`] for a
    /// joint between a body and itself or between two bodies that cannot move, or
    /// a target joint with a second body;
    /// [`Error::OutOfRange`] for a negative stiffness or damping, a zero or huge
    /// length, inverted angle limits, a negative torque limit or break impulse, or
    /// an anchor more than 256 m from its body's centre, a target joint's hertz,
    /// damping ratio or force limit out of range; [`Error::OutsideBounds`]
    /// for a world anchor outside the world; [`Error::CapacityFull`].
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointHandle, Error> {
        let a = self.bodies.get(def.body_a).ok_or(Error::StaleHandle)?;
        let b = match def.body_b {
            Some(hb) => Some(self.bodies.get(hb).ok_or(Error::StaleHandle)?),
            None => None,
        };
        constraint::validate(&def, a, b, self.def.bounds)?;
        let ground = constraint::ground();
        let joint = Joint::new(def, a, b.unwrap_or(&ground));
        self.joints.insert(joint).map_err(|_| Error::CapacityFull { what: "joint" })
    }

    /// Removes a joint and returns it.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_joint(&mut self, h: JointHandle) -> Result<Joint, Error> {
        self.joints.remove(h).ok_or(Error::StaleHandle)
    }

    /// The joint behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] (also once a breakable joint broke).
    pub fn joint(&self, h: JointHandle) -> Result<&Joint, Error> {
        self.joints.get(h).ok_or(Error::StaleHandle)
    }

    /// The joint behind `h`, e.g. to change a pivot's motor.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn joint_mut(&mut self, h: JointHandle) -> Result<&mut Joint, Error> {
        self.joints.get_mut(h).ok_or(Error::StaleHandle)
    }

    /// Moves a target joint's world target point ([`JointKind::Target`]): what
    /// a game calls each frame while the player drags. The joint pulls its
    /// body towards the new point from the next step on; the target is part
    /// of the snapshot and the state hash.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] for a removed (or broken) joint;
    /// [`Error::InvalidOperation`] for a joint of another kind;
    /// [`Error::OutsideBounds`] for a point outside the world's bounds. The
    /// world is unchanged on an error.
    pub fn set_joint_target(&mut self, h: JointHandle, point: Vector2) -> Result<(), Error> {
        let bounds = self.def.bounds;
        let j = self.joints.get_mut(h).ok_or(Error::StaleHandle)?;
        if !matches!(j.def.kind, JointKind::Target { .. }) {
            return Err(Error::InvalidOperation { what: "a target on a joint that is not a target joint" });
        }
        if !bounds.contains(point) {
            return Err(Error::OutsideBounds);
        }
        j.def.anchor_b = point;
        Ok(())
    }

    /// A target joint's world target point.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] for a removed joint; [`Error::InvalidOperation`]
    /// for a joint of another kind.
    pub fn joint_target(&self, h: JointHandle) -> Result<Vector2, Error> {
        let j = self.joints.get(h).ok_or(Error::StaleHandle)?;
        j.target().ok_or(Error::InvalidOperation { what: "a target on a joint that is not a target joint" })
    }

    /// Every joint with its handle, in slot order (the order they are solved in).
    pub fn joints(&self) -> impl Iterator<Item = (JointHandle, &Joint)> + '_ {
        self.joints.iter()
    }

    /// Sets the function called after a step for each joint that broke.
    pub fn set_joint_break_callback(&mut self, f: Option<JointBreakFn>) {
        if f.is_some() {
            self.arm_panic_guard();
        }
        self.break_callback = f;
    }

    /// Adds a game constraint between `a` and `b` (or a fixed point when `b` is
    /// `None`), borrowed or boxed: `Hook::Borrowed(&mut c)` /
    /// `Hook::Boxed(Box::new(c))` (see [`Hook`]).
    ///
    /// The constraint names its bodies by handle. It is a game hook, not state:
    /// it is not in a snapshot, and [`restore`](World::restore) leaves it
    /// registered as it is. While one of its bodies is gone (removed, or not in
    /// the state a restore brought back) it is *dormant*: not solved, and never
    /// handed another body that took the slot. It comes back to life when that
    /// very body (same handle) is back, e.g. after a restore to a snapshot taken
    /// before the removal, so rolling back across
    /// [`remove_body`](World::remove_body) replays bit for bit. Only
    /// [`remove_constraint`](World::remove_constraint) removes it (and frees its
    /// place among the
    /// [`MAX_USER_CONSTRAINTS`](crate::constraint::MAX_USER_CONSTRAINTS)); see
    /// [`constraint_is_active`](World::constraint_is_active) and
    /// [`dormant_constraints`](World::dormant_constraints).
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::InvalidOperation`] for a body with itself;
    /// [`Error::CapacityFull`] when
    /// [`MAX_USER_CONSTRAINTS`](crate::constraint::MAX_USER_CONSTRAINTS) are in use.
    pub fn add_constraint(
        &mut self,
        a: BodyHandle,
        b: Option<BodyHandle>,
        c: Hook<'a, dyn Constraint + Send + 'a>,
    ) -> Result<ConstraintHandle, Error> {
        if !self.bodies.contains(a) || b.is_some_and(|b| !self.bodies.contains(b)) {
            return Err(Error::StaleHandle);
        }
        if Some(a) == b {
            return Err(Error::InvalidOperation { what: "a constraint between a body and itself" });
        }
        let h = self
            .constraints
            .insert(UserConstraint { body_a: a, body_b: b, constraint: c })
            .map_err(|_| Error::CapacityFull { what: "constraint" })?;
        self.arm_panic_guard();
        Ok(h)
    }

    /// Removes a game constraint, active or dormant.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_constraint(&mut self, h: ConstraintHandle) -> Result<(), Error> {
        self.constraints.remove(h).map(drop).ok_or(Error::StaleHandle)
    }

    /// True when the game constraint is solved by the next step: its bodies are
    /// all in the world. False when it is dormant (a body of it is gone; see
    /// [`add_constraint`](World::add_constraint)).
    ///
    /// # Errors
    /// [`Error::StaleHandle`] for a constraint that was removed.
    pub fn constraint_is_active(&self, h: ConstraintHandle) -> Result<bool, Error> {
        let c = self.constraints.get(h).ok_or(Error::StaleHandle)?;
        Ok(self.attached(c))
    }

    /// The dormant game constraints (a body of each is gone), in registration
    /// (slot) order: a game that removed them for good calls
    /// [`remove_constraint`](World::remove_constraint) on each.
    pub fn dormant_constraints(&self) -> impl Iterator<Item = ConstraintHandle> + use<'_, 'a> {
        self.constraints.iter().filter(|(_, c)| !self.attached(c)).map(|(h, _)| h)
    }

    /// True when every body of `c` is alive.
    fn attached(&self, c: &UserConstraint<'_>) -> bool {
        self.bodies.contains(c.body_a) && c.body_b.is_none_or(|b| self.bodies.contains(b))
    }
}
