//! Mass properties (placeholder, being written).
use crate::math::Scalar;

/// Mass properties of a body.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MassData {
    /// Mass in kg (0 for static and kinematic bodies).
    pub mass: Scalar,
    /// 1 / mass, or 0.
    pub inv_mass: Scalar,
    /// Moment of inertia about the centre of mass, kg·m².
    pub inertia: Scalar,
    /// 1 / inertia, or 0.
    pub inv_inertia: Scalar,
}
