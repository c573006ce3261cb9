//! [`WorldDef`]: a world's configuration, with a sane default for every option,
//! and its validation (one function, used by [`World::new`](crate::World::new)
//! and by `restore`).

use crate::error::Error;
use crate::limits::{
    DEFAULT_CONTACT_RECYCLE_DISTANCE, MAX_ANGULAR_SPEED_LIMIT, MAX_ARBITER_PERSISTENCE,
    MAX_CONTACT_RECYCLE_DISTANCE, MAX_COORDINATE, MAX_LINEAR_SPEED_LIMIT, MAX_SUBSTEPS,
};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rect, Vector2};

/// World configuration; every option has a default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WorldDef {
    /// The region bodies live in. A body whose centre leaves it is frozen and
    /// reported (see [`Body::is_out_of_bounds`](crate::Body::is_out_of_bounds)).
    pub bounds: Rect,
    /// Speed limit for every body, m/s (default 400, at most
    /// [`MAX_LINEAR_SPEED_LIMIT`]). Applied after forces and after the solver.
    pub max_linear_speed: Scalar,
    /// Angular speed limit, rad/s (default 200, at most
    /// [`MAX_ANGULAR_SPEED_LIMIT`]). The step also limits rotation to π/4 per step.
    pub max_angular_speed: Scalar,
    /// Solver sub-steps per step, 1 to [`MAX_SUBSTEPS`] (default 4). More
    /// sub-steps stack better and cost proportionally more.
    pub substeps: u32,
    /// Contact stiffness, Hz (default 30; capped at a quarter of the sub-step rate).
    pub contact_hertz: Scalar,
    /// Contact damping ratio (default 10: heavily damped, no bounce from push-out).
    pub contact_damping_ratio: Scalar,
    /// Fastest speed at which overlap is pushed out, m/s (default 3).
    pub contact_push_speed: Scalar,
    /// Contacts approaching slower than this (m/s) do not bounce (default 1), so
    /// resting bodies settle instead of jittering.
    pub restitution_threshold: Scalar,
    /// Steps an arbiter is kept after its bodies stop touching, counting the step
    /// they separate (default 3; the manual's persistence), 0 to
    /// [`MAX_ARBITER_PERSISTENCE`] (256): a separated arbiter holds a slot of the
    /// arbiter store meanwhile, and at `u32::MAX` none would ever expire.
    pub arbiter_persistence: u32,
    /// How far (m) two touching bodies may move relative to each other
    /// before their contact manifold is computed again (default 0.05, 0 to
    /// [`MAX_CONTACT_RECYCLE_DISTANCE`]; 0 computes every manifold every
    /// step). Meanwhile the manifold's normal, points and feature ids carry
    /// on, each point's separation following the bodies: Box2D v3's contact
    /// recycling, the same default. The relative motion counts the turn at
    /// the bodies' radius, and either body turning more than about 11.5°
    /// also ends it. Settled piles then skip most of the narrow phase (the
    /// 20-row pyramid about 11 % of a step's instructions). Part of the
    /// snapshot and the state hash, and restored with them, like
    /// [`substeps`](WorldDef::substeps).
    pub contact_recycle_distance: Scalar,
    /// What a step does when the candidate pairs or the arbiters do not fit the
    /// contact buffers ([`Capacities::contacts`](crate::Capacities::contacts)).
    /// `false` (the default): it completes, keeping the lowest pair keys, and
    /// counts what it left out in the
    /// [`StepReport`](crate::StepReport) (`pairs_dropped`, `arbiters_dropped`).
    /// `true`: it fails with [`Error::CapacityFull`] and changes nothing. Like the
    /// capacities, this belongs to the world, not to its state: snapshots do not
    /// record it and a restore keeps the restoring world's setting.
    pub strict_capacity: bool,
}

impl WorldDef {
    /// The manual's world: bounds from (0, 0) to (`width`, `height`) metres.
    #[must_use]
    pub fn new(width: Scalar, height: Scalar) -> Self {
        Self::with_bounds(Rect { min: Vector2::ZERO, max: Vector2::new(width, height) })
    }

    /// A world with arbitrary bounds (e.g. centred on the origin).
    #[must_use]
    pub fn with_bounds(bounds: Rect) -> Self {
        Self {
            bounds,
            max_linear_speed: Scalar::from_int(400),
            max_angular_speed: Scalar::from_int(200),
            substeps: 4,
            contact_hertz: Scalar::from_int(30),
            contact_damping_ratio: Scalar::from_int(10),
            contact_push_speed: Scalar::from_int(3),
            restitution_threshold: Scalar::from_int(1),
            arbiter_persistence: 3,
            contact_recycle_distance: DEFAULT_CONTACT_RECYCLE_DISTANCE,
            strict_capacity: false,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        let b = self.bounds;
        let inside = |v: Scalar| v.abs() <= MAX_COORDINATE;
        if !(inside(b.min.x) && inside(b.min.y) && inside(b.max.x) && inside(b.max.y)) {
            return Err(Error::OutOfRange { what: "world bounds" });
        }
        if b.min.x >= b.max.x || b.min.y >= b.max.y {
            return Err(Error::OutOfRange { what: "world size" });
        }
        if self.max_linear_speed <= ZERO || self.max_linear_speed > MAX_LINEAR_SPEED_LIMIT {
            return Err(Error::OutOfRange { what: "max_linear_speed" });
        }
        if self.max_angular_speed <= ZERO || self.max_angular_speed > MAX_ANGULAR_SPEED_LIMIT {
            return Err(Error::OutOfRange { what: "max_angular_speed" });
        }
        if self.substeps == 0 || self.substeps > MAX_SUBSTEPS {
            return Err(Error::OutOfRange { what: "substeps" });
        }
        let hundred = Scalar::from_int(100);
        if self.contact_hertz < ZERO || self.contact_hertz > Scalar::from_int(1000) {
            return Err(Error::OutOfRange { what: "contact_hertz" });
        }
        if self.contact_damping_ratio < ZERO || self.contact_damping_ratio > hundred {
            return Err(Error::OutOfRange { what: "contact_damping_ratio" });
        }
        if self.contact_push_speed < ZERO || self.contact_push_speed > hundred {
            return Err(Error::OutOfRange { what: "contact_push_speed" });
        }
        if self.restitution_threshold < ZERO || self.restitution_threshold > hundred {
            return Err(Error::OutOfRange { what: "restitution_threshold" });
        }
        if self.arbiter_persistence > MAX_ARBITER_PERSISTENCE {
            return Err(Error::OutOfRange { what: "arbiter_persistence" });
        }
        if self.contact_recycle_distance < ZERO
            || self.contact_recycle_distance > MAX_CONTACT_RECYCLE_DISTANCE
        {
            return Err(Error::OutOfRange { what: "contact_recycle_distance" });
        }
        Ok(())
    }
}

impl crate::World<'_> {
    /// Changes the solver's sub-steps per step, 1 to [`MAX_SUBSTEPS`], from the
    /// next step on (what [`WorldDef::substeps`] set at creation). The count is
    /// part of the snapshot and the state hash, and
    /// [`restore`](crate::World::restore) brings back the count the snapshot
    /// was taken with, so rolling back across a change replays bit for bit.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"substeps"` for 0 or more than
    /// [`MAX_SUBSTEPS`]; the world is unchanged.
    pub fn set_substeps(&mut self, n: u32) -> Result<(), Error> {
        let def = WorldDef { substeps: n, ..self.def };
        def.validate()?;
        self.def = def;
        Ok(())
    }

    /// Changes how far touching bodies may move before their manifold is
    /// computed again ([`WorldDef::contact_recycle_distance`]), from the next
    /// step on; 0 turns recycling off. Like the sub-steps, the setting is part
    /// of the snapshot and the state hash, and a restore brings back the one
    /// the snapshot was taken with. Manifolds kept before a change carry on
    /// only while they meet the new distance.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"contact_recycle_distance"` below 0 or
    /// above [`MAX_CONTACT_RECYCLE_DISTANCE`]; the world is unchanged.
    pub fn set_contact_recycle_distance(&mut self, distance: Scalar) -> Result<(), Error> {
        let def = WorldDef { contact_recycle_distance: distance, ..self.def };
        def.validate()?;
        self.def = def;
        Ok(())
    }
}
