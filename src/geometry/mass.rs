//! Mass properties (TEMPORARY stand-in; replaced by the geometry branch).
use crate::error::Error;
use crate::math::scalar::{self, Scalar, ZERO};

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

impl MassData {
    /// Infinite mass.
    pub const STATIC: Self = Self {
        mass: ZERO,
        inv_mass: ZERO,
        inertia: ZERO,
        inv_inertia: ZERO,
    };
    /// From density.
    pub fn from_density(
        density: Scalar,
        area: Scalar,
        unit_inertia: Scalar,
    ) -> Result<Self, Error> {
        if density <= ZERO {
            return Err(Error::OutOfRange { what: "density" });
        }
        let mass = density.saturating_mul(area);
        let inertia = density.saturating_mul(unit_inertia);
        Ok(Self {
            mass,
            inv_mass: scalar::recip(mass),
            inertia,
            inv_inertia: scalar::recip(inertia),
        })
    }
    /// From mass.
    pub fn from_mass(mass: Scalar, area: Scalar, unit_inertia: Scalar) -> Result<Self, Error> {
        if mass <= ZERO {
            return Err(Error::OutOfRange { what: "mass" });
        }
        Self::from_density(scalar::div(mass, area), area, unit_inertia)
    }
}
