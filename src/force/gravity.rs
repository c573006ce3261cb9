//! `GravityForceGenerator`: uniform gravity.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::limits::{check_components, MAX_ACCELERATION};
use crate::math::{Scalar, Vector2};

/// Uniform gravity: the force is scaled by each body's mass, so every body gets
/// the same acceleration `g` (m/s²): Δv = g · dt, times the body's
/// [gravity scale](crate::BodyDef::gravity_scale) (the scaled acceleration
/// clamped to ±[`MAX_ACCELERATION`] per component).
///
/// Each component of `g` is within ±[`MAX_ACCELERATION`] (16,384 m/s²), checked
/// by [`World::add_force_generator`](crate::World::add_force_generator), by
/// [`set_gravity`](Self::set_gravity) and by `restore`, so a step cannot leave
/// Q32.32's range (see [`MAX_ACCELERATION`] for why).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GravityForceGenerator {
    pub(crate) gravity: Vector2,
    pub(crate) targets: Targets,
}

impl GravityForceGenerator {
    /// Gravity on every dynamic body.
    #[must_use]
    pub fn new(gravity: Vector2) -> Self {
        Self { gravity, targets: Targets::All }
    }

    /// The same generator acting only on `targets`.
    #[must_use]
    pub fn with_targets(mut self, targets: Targets) -> Self {
        self.targets = targets;
        self
    }

    /// The acceleration in m/s², e.g. (0, −9.81).
    #[must_use]
    pub fn gravity(&self) -> Vector2 {
        self.gravity
    }

    /// The bodies it acts on.
    #[must_use]
    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// Changes the acceleration (m/s²).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"gravity"` for a component beyond
    /// ±[`MAX_ACCELERATION`]; the generator is unchanged.
    pub fn set_gravity(&mut self, gravity: Vector2) -> Result<(), Error> {
        check_gravity(gravity)?;
        self.gravity = gravity;
        Ok(())
    }

    /// Changes the bodies it acts on (any list is valid).
    pub fn set_targets(&mut self, targets: Targets) {
        self.targets = targets;
    }

    /// The checks of `add_force_generator` and `restore`.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_gravity(self.gravity)
    }
}

fn check_gravity(g: Vector2) -> Result<(), Error> {
    check_components(g, MAX_ACCELERATION, "gravity")
}

impl ForceGenerator for GravityForceGenerator {
    #[inline]
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    #[inline]
    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        let g = super::scaled_acceleration(self.gravity, body.gravity_scale());
        body.add_linear_velocity(g * dt);
    }
}
