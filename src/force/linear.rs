//! `LinearForceGenerator`: a constant force.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::math::{Scalar, Vector2};

/// Applies a constant force (N) to its targets: Δv = F/m · dt, so heavy bodies
/// accelerate less (wind, thrust). Compare [`GravityForceGenerator`](super::GravityForceGenerator).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LinearForceGenerator {
    /// The force in newtons.
    pub force: Vector2,
    /// The bodies it acts on.
    pub targets: Targets,
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
}

impl ForceGenerator for LinearForceGenerator {
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        body.apply_force(self.force, dt);
    }
}
