//! Circle geometry (TEMPORARY stand-in; replaced by the geometry branch).
use crate::error::Error;
use crate::math::scalar::{Scalar, PI, ZERO};

/// Area of a circle.
pub fn circle_area(radius: Scalar) -> Result<Scalar, Error> {
    if radius <= ZERO {
        return Err(Error::OutOfRange { what: "radius" });
    }
    Ok(PI.saturating_mul(radius.saturating_mul(radius)))
}
/// Unit inertia of a circle.
pub fn circle_unit_inertia(radius: Scalar) -> Result<Scalar, Error> {
    let a = circle_area(radius)?;
    Ok(a.saturating_mul(radius.saturating_mul(radius))
        .saturating_mul(crate::math::scalar::HALF))
}
