//! `GravityForceGenerator`: uniform gravity.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::math::{Scalar, Vector2};

/// Uniform gravity: the force is scaled by each body's mass, so every body gets
/// the same acceleration `g` (m/s²): Δv = g · dt.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GravityForceGenerator {
    /// The acceleration in m/s², e.g. (0, −9.81).
    pub gravity: Vector2,
    /// The bodies it acts on.
    pub targets: Targets,
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
}

impl ForceGenerator for GravityForceGenerator {
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        body.add_linear_velocity(self.gravity * dt);
    }
}
