//! `LinearForceGenerator`: a constant force.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::limits::{check_components, MAX_FORCE};
use crate::math::{Scalar, Vector2};

/// Applies a constant force (N) to its targets: Δv = F/m · dt, so heavy bodies
/// accelerate less (wind, thrust). Compare [`GravityForceGenerator`](super::GravityForceGenerator).
///
/// Each component of the force is within ±[`MAX_FORCE`] (about 1.6e9 N), checked
/// by [`World::add_force_generator`](crate::World::add_force_generator), by
/// [`set_force`](Self::set_force) and by `restore` (see [`MAX_FORCE`] for why).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LinearForceGenerator {
    pub(crate) force: Vector2,
    pub(crate) targets: Targets,
}

impl LinearForceGenerator {
    /// A force on every dynamic body.
    #[must_use]
    pub fn new(force: Vector2) -> Self {
        Self { force, targets: Targets::All }
    }

    /// The same generator acting only on `targets`.
    #[must_use]
    pub fn with_targets(mut self, targets: Targets) -> Self {
        self.targets = targets;
        self
    }

    /// The force in newtons.
    #[must_use]
    pub fn force(&self) -> Vector2 {
        self.force
    }

    /// The bodies it acts on.
    #[must_use]
    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// Changes the force (N).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"force"` for a component beyond ±[`MAX_FORCE`];
    /// the generator is unchanged.
    pub fn set_force(&mut self, force: Vector2) -> Result<(), Error> {
        check_force(force)?;
        self.force = force;
        Ok(())
    }

    /// Changes the bodies it acts on (any list is valid).
    pub fn set_targets(&mut self, targets: Targets) {
        self.targets = targets;
    }

    /// The checks of `add_force_generator` and `restore`.
    pub(crate) fn validate(&self) -> Result<(), Error> {
        check_force(self.force)
    }
}

fn check_force(f: Vector2) -> Result<(), Error> {
    check_components(f, MAX_FORCE, "force")
}

impl ForceGenerator for LinearForceGenerator {
    #[inline]
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    #[inline]
    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        body.apply_force(self.force, dt);
    }
}
