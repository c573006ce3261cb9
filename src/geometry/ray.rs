//! Ray casts against single shapes.
//!
//! A ray is an origin and a unit direction with a length (m). Nothing here
//! squares a distance between the origin and the shape, so rays from anywhere in
//! the world are safe: circles use the perpendicular offset (bounded by the
//! circle when there is a hit), polygons are clipped face by face (Box2D's
//! method). A ray that starts inside a shape does not hit it.

use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Transform, Vector2};

use super::PolygonPath;

/// Where a ray first enters a shape: distance along the ray (m) and the outward
/// surface normal there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShapeHit {
    /// Distance from the origin, 0 ≤ distance ≤ the ray's length (m).
    pub distance: Scalar,
    /// Unit outward normal of the surface at the hit point.
    pub normal: Vector2,
}

/// The first entry of the ray `origin + t·dir`, 0 ≤ t ≤ `length`, into the circle
/// of `radius` at `center`.
#[must_use]
pub fn ray_circle(
    origin: Vector2,
    dir: Vector2,
    length: Scalar,
    center: Vector2,
    radius: Scalar,
) -> Option<ShapeHit> {
    let m = center - origin;
    // Distance along the ray to the point of closest approach, and the offset.
    let s = m.dot(dir);
    let offset = m - dir * s;
    // |offset| > r: misses; checked by component first so the square is safe.
    if offset.x.abs() > radius || offset.y.abs() > radius {
        return None;
    }
    let h2 = (radius * radius) - offset.length_squared();
    if h2 < ZERO {
        return None;
    }
    let t = s - h2.sqrt();
    if t < ZERO || t > length {
        // Behind the origin (or the origin is inside), or beyond the end.
        return None;
    }
    let p = origin + dir * t;
    let normal = (p - center).try_normalize().unwrap_or(-dir);
    Some(ShapeHit { distance: t, normal })
}

/// The first entry of the ray into `poly` placed at `xf`.
#[must_use]
pub fn ray_polygon(
    origin: Vector2,
    dir: Vector2,
    length: Scalar,
    poly: &PolygonPath,
    xf: Transform,
) -> Option<ShapeHit> {
    let p = xf.apply_inv(origin);
    let d = xf.q.inv_rotate(dir);
    let (mut lower, mut upper) = (ZERO, length);
    let mut entered: Option<usize> = None;
    for (i, (v, n)) in poly.vertices().iter().zip(poly.normals()).enumerate() {
        // Inside the face's half-plane is n·(x − v) ≤ 0; along the ray x = p + t·d:
        // n·(v − p) ≥ t·(n·d).
        let numerator = n.dot(*v - p);
        let denominator = n.dot(d);
        if denominator == ZERO {
            if numerator < ZERO {
                return None;
            }
        } else if denominator < ZERO && numerator < lower * denominator {
            lower = numerator.div_or_zero(denominator);
            entered = Some(i);
        } else if denominator > ZERO && numerator < upper * denominator {
            upper = numerator.div_or_zero(denominator);
        }
        if upper < lower {
            return None;
        }
    }
    let i = entered?;
    let normal = xf.q.rotate(*poly.normals().get(i)?);
    Some(ShapeHit { distance: lower, normal })
}

/// True when `point` lies inside or on `poly` placed at `xf`.
#[must_use]
pub fn polygon_contains(poly: &PolygonPath, xf: Transform, point: Vector2) -> bool {
    let p = xf.apply_inv(point);
    poly.vertices().iter().zip(poly.normals()).all(|(v, n)| n.dot(p - *v) <= ZERO)
}
