//! Circle geometry: area and moment of inertia at density 1.
//!
//! Both are computed from the radius's raw bits with exact integer products and a
//! 64-fraction-bit π, then rounded once to nearest, so they are correctly rounded
//! (the Q32.32 [`PI`](crate::math::scalar::PI) alone would already cost 1e-10
//! relative error, and squaring in Q32.32 would add more).

use super::wide::U256;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};

/// Largest circle radius (m): 128 m.
///
/// Why 128 and not more: the moment of inertia at density 1, `π r⁴ / 2`, grows
/// with the fourth power of the radius. At 128 m it is 4.2e8 kg·m², five times
/// below the Q32.32 limit of 2.1e9; at 181 m it would reach the limit and at 512 m
/// it would be 1.1e11. Polygons share the same limit,
/// [`MAX_POLYGON_RADIUS`](super::MAX_POLYGON_RADIUS).
pub const MAX_CIRCLE_RADIUS: Scalar = Scalar::from_int(128);

/// π · 2^64, rounded to nearest (π = 3.243F6A8885A308D3|13… in hexadecimal).
pub(super) const PI_Q64: u128 = 0x3_243F_6A88_85A3_08D3;

/// The radius as raw bits (units of 2^-32 m), once checked.
fn radius_bits(radius: Scalar) -> Result<u128, Error> {
    if radius <= ZERO || radius > MAX_CIRCLE_RADIUS {
        return Err(Error::OutOfRange { what: "circle radius" });
    }
    Ok(radius.to_bits().unsigned_abs().into())
}

/// Area of a circle, `π r²`, in m², for a radius in m.
///
/// Correctly rounded to the nearest 2^-32 m². Very small radii give few
/// significant bits (below about 1e-5 m the area rounds to 0).
///
/// # Errors
/// [`Error::OutOfRange`] `{ what: "circle radius" }` unless
/// `0 < radius ≤` [`MAX_CIRCLE_RADIUS`].
pub fn circle_area(radius: Scalar) -> Result<Scalar, Error> {
    let r = radius_bits(radius)?;
    // r² < 2^78 (units 2^-64 m²); × π·2^64 → units 2^-128 m²; to 2^-32 m²: / 2^96.
    let r2 = r.saturating_mul(r);
    to_scalar(U256::mul(r2, PI_Q64).div_round(96, 1))
}

/// Polar moment of inertia of a disc about its centre at density 1 kg/m²,
/// `π r⁴ / 2`, in kg·m² (per kg/m² of density), for a radius in m. Per unit mass
/// it is `r² / 2`.
///
/// Rounded to the nearest 2^-32 kg·m² (to within 2^-31 of a step: the r⁴ term
/// drops bits worth 2^-64 before the multiplication by π). It scales with r⁴, so
/// small circles keep few significant bits: at r = 1 cm it is 1.6e-8, only 67
/// steps of 2^-32; at r = 1 mm it rounds to 0.
///
/// # Errors
/// [`Error::OutOfRange`] `{ what: "circle radius" }` unless
/// `0 < radius ≤` [`MAX_CIRCLE_RADIUS`].
pub fn circle_unit_inertia(radius: Scalar) -> Result<Scalar, Error> {
    let r = radius_bits(radius)?;
    // r⁴ < 2^156 (units 2^-128 m⁴): keep its top part in units of 2^-64 m⁴ (< 2^92),
    // × π·2^64 → units 2^-128 m⁴; halve and convert to 2^-32 m⁴: / 2^97.
    let r2 = r.saturating_mul(r);
    let r4 = U256::mul(r2, r2).div_round(64, 1).ok_or(TOO_LARGE)?;
    to_scalar(U256::mul(r4, PI_Q64).div_round(97, 1))
}

/// The error for a result outside the `Scalar` range (unreachable within
/// [`MAX_CIRCLE_RADIUS`]).
const TOO_LARGE: Error = Error::OutOfRange { what: "circle radius" };

/// A rounded quotient in units of 2^-32 as a `Scalar`.
fn to_scalar(bits: Option<u128>) -> Result<Scalar, Error> {
    let bits = bits.ok_or(TOO_LARGE)?;
    i64::try_from(bits).map(Scalar::from_bits).map_err(|_| TOO_LARGE)
}
