//! `GravityToPointForceGenerator`: attraction towards a point.

use super::{ForceGenerator, Targets};
use crate::body::{Body, BodyHandle};
use crate::math::{Scalar, Vector2};

/// Accelerates bodies towards `point` at `acceleration` m/s², whatever their
/// mass or distance (a planet in a small game, a vortex, a tractor beam). A body
/// exactly at the point has no direction and is left alone.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GravityToPointForceGenerator {
    /// The attracting point (m).
    pub point: Vector2,
    /// The acceleration towards it (m/s²; negative repels).
    pub acceleration: Scalar,
    /// The bodies it acts on.
    pub targets: Targets,
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
}

impl ForceGenerator for GravityToPointForceGenerator {
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        self.targets.contains(handle, body)
    }

    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        // `normalize` scales before squaring, so any distance within the world is safe.
        let dir = (self.point - body.position()).normalize();
        body.add_linear_velocity(dir * (self.acceleration * dt));
    }
}
