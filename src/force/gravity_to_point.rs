//! `GravityToPointForceGenerator`: attraction towards a point.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::limits::{check_components, check_range, MAX_ACCELERATION, MAX_COORDINATE};
use crate::math::{Scalar, Vector2};

/// Accelerates bodies towards `point` at `acceleration` m/s², whatever their
/// mass or distance (a planet in a small game, a vortex, a tractor beam), times
/// the body's [gravity scale](crate::BodyDef::gravity_scale) (the scaled
/// acceleration clamped to ±[`MAX_ACCELERATION`]). A body exactly at the point
/// has no direction and is left alone.
///
/// The point's coordinates are within ±[`MAX_COORDINATE`] (2^20 m, so its
/// distance to any body stays exact) and the acceleration within
/// ±[`MAX_ACCELERATION`] (16,384 m/s²), checked by
/// [`World::add_force_generator`](crate::World::add_force_generator), by the
/// setters and by `restore`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GravityToPointForceGenerator {
    pub(crate) point: Vector2,
    pub(crate) acceleration: Scalar,
    pub(crate) targets: Targets,
}

impl GravityToPointForceGenerator {
    /// Attraction of every dynamic body towards `point`.
    #[must_use]
    pub fn new(point: Vector2, acceleration: Scalar) -> Self {
        Self { point, acceleration, targets: Targets::All }
    }

    /// The same generator acting only on `targets`.
    #[must_use]
    pub fn with_targets(mut self, targets: Targets) -> Self {
        self.targets = targets;
        self
    }

    /// The attracting point (m).
    #[must_use]
    pub fn point(&self) -> Vector2 {
        self.point
    }

    /// The acceleration towards it (m/s²; negative repels).
    #[must_use]
    pub fn acceleration(&self) -> Scalar {
        self.acceleration
    }

    /// The bodies it acts on.
    #[must_use]
    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// Moves the attracting point (m).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"point"` for a coordinate beyond
    /// ±[`MAX_COORDINATE`]; the generator is unchanged.
    pub fn set_point(&mut self, point: Vector2) -> Result<(), Error> {
        check_point(point)?;
        self.point = point;
        Ok(())
    }

    /// Changes the acceleration (m/s²; negative repels).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"acceleration"` beyond ±[`MAX_ACCELERATION`];
    /// the generator is unchanged.
    pub fn set_acceleration(&mut self, acceleration: Scalar) -> Result<(), Error> {
        check_acceleration(acceleration)?;
        self.acceleration = acceleration;
        Ok(())
    }

    /// Changes the bodies it acts on (any list is valid).
    pub fn set_targets(&mut self, targets: Targets) {
        self.targets = targets;
    }

    /// The checks of `add_force_generator` and `restore`.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_point(self.point)?;
        check_acceleration(self.acceleration)
    }
}

fn check_point(p: Vector2) -> Result<(), Error> {
    check_components(p, MAX_COORDINATE, "point")
}

fn check_acceleration(a: Scalar) -> Result<(), Error> {
    check_range(a, -MAX_ACCELERATION, MAX_ACCELERATION, "acceleration")
}

impl ForceGenerator for GravityToPointForceGenerator {
    #[inline]
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    #[inline]
    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        // `normalize` scales before squaring, so any distance within the world is safe.
        let dir = (self.point - body.position()).normalize();
        let a = if body.gravity_scale() == Scalar::ONE {
            self.acceleration
        } else {
            (self.acceleration * body.gravity_scale()).clamp(-MAX_ACCELERATION, MAX_ACCELERATION)
        };
        body.add_linear_velocity(dir * (a * dt));
    }
}
