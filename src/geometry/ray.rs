//! Ray casts against single shapes.
//!
//! A ray is an origin and a unit direction with a length (m). Nothing here
//! squares a distance between the origin and the shape, so rays from anywhere in
//! the world are safe: circles use the perpendicular offset (bounded by the
//! circle when there is a hit), polygons are clipped face by face (Box2D's
//! method). A ray that starts inside a shape does not hit it.
//!
//! Rounded shapes (capsules, polygons with a rounding radius) are the union of
//! their core, one slab beside each core edge and one disc at each core vertex:
//! a ray from outside enters first through a slab's outer face or a disc, so the
//! hit is the nearest of the faces' hits (within the edge's extent) and the
//! discs' hits ([`ray_circle`]). A segment is hit from either side, never along
//! its own line (it has no thickness).

use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Transform, Vector2};

use super::{Capsule, PolygonPath, Segment};

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
    if poly.rounding() > ZERO {
        return ray_rounded_polygon(p, d, length, poly).map(|h| rotated(h, xf));
    }
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
    if poly.rounding() > ZERO {
        return rounded_polygon_contains(poly, p);
    }
    poly.vertices().iter().zip(poly.normals()).all(|(v, n)| n.dot(p - *v) <= ZERO)
}

/// The first entry of the ray into `capsule` placed at `xf`: through one of the
/// two flat sides or one of the two end circles (a zero-length capsule is a
/// circle). A ray starting inside does not hit.
#[must_use]
pub fn ray_capsule(
    origin: Vector2,
    dir: Vector2,
    length: Scalar,
    capsule: &Capsule,
    xf: Transform,
) -> Option<ShapeHit> {
    let p = xf.apply_inv(origin);
    let d = xf.q.inv_rotate(dir);
    let (a, b, r) = (capsule.center1, capsule.center2, capsule.radius);
    if within_of_segment(p, a, b, r) {
        return None;
    }
    let mut best = nearer(ray_circle(p, d, length, a, r), ray_circle(p, d, length, b, r));
    let (u, len) = (b - a).normalize_and_length();
    if len > ZERO {
        let n = u.right_perp();
        for side in [n, -n] {
            best = nearer(best, ray_flat_face(p, d, length, a, side, u, len, r));
        }
    }
    best.map(|h| rotated(h, xf))
}

/// The ray crossing `segment` placed at `xf`, from either side; the normal faces
/// the ray (points back towards its origin's side). A ray along the segment's
/// line, or starting on it, does not hit (a segment has no thickness); a ray
/// through an end point does.
#[must_use]
pub fn ray_segment(
    origin: Vector2,
    dir: Vector2,
    length: Scalar,
    segment: &Segment,
    xf: Transform,
) -> Option<ShapeHit> {
    let p = xf.apply_inv(origin);
    let d = xf.q.inv_rotate(dir);
    let a = segment.point1;
    let (u, len) = (segment.point2 - a).normalize_and_length();
    let n = u.right_perp();
    // Height of the origin above the line, and the ray's rate towards it.
    let h = n.dot(p - a);
    let dn = n.dot(d);
    if h == ZERO || dn == ZERO || (h > ZERO) == (dn > ZERO) {
        return None;
    }
    let t = h.abs().div_or_zero(dn.abs());
    if t > length {
        return None;
    }
    let s = u.dot(p + d * t - a);
    if s < ZERO || s > len {
        return None;
    }
    let normal = if h > ZERO { n } else { -n };
    Some(ShapeHit { distance: t, normal: xf.q.rotate(normal) })
}

/// True when `point` lies inside or on `capsule` placed at `xf` (within its
/// radius of the core segment).
#[must_use]
pub fn capsule_contains(capsule: &Capsule, xf: Transform, point: Vector2) -> bool {
    within_of_segment(xf.apply_inv(point), capsule.center1, capsule.center2, capsule.radius)
}

/// The hit with the smaller distance (the first on a tie).
fn nearer(a: Option<ShapeHit>, b: Option<ShapeHit>) -> Option<ShapeHit> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.distance < x.distance { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

/// A local hit with its normal turned into world space.
fn rotated(h: ShapeHit, xf: Transform) -> ShapeHit {
    ShapeHit { distance: h.distance, normal: xf.q.rotate(h.normal) }
}

/// The entry of the local ray `p + t·d` through the flat face at distance `r`
/// beyond the edge from `a` along the unit direction `u` (of length `len`) on
/// the side of the outward unit normal `n`: the face's line crossed inwards, at
/// a point whose projection onto the edge lies within it.
#[allow(clippy::too_many_arguments)]
fn ray_flat_face(
    p: Vector2,
    d: Vector2,
    length: Scalar,
    a: Vector2,
    n: Vector2,
    u: Vector2,
    len: Scalar,
    r: Scalar,
) -> Option<ShapeHit> {
    let dn = n.dot(d);
    // Height of the origin above the face's line (≥ 0: outside or on it).
    let h = n.dot(p - a) - r;
    if dn >= ZERO || h < ZERO {
        return None;
    }
    let t = h.div_or_zero(-dn);
    if t > length {
        return None;
    }
    let s = u.dot(p + d * t - a);
    if s < ZERO || s > len {
        return None;
    }
    Some(ShapeHit { distance: t, normal: n })
}

/// True when `p` is within `r` of the segment `a`–`b` (local coordinates).
fn within_of_segment(p: Vector2, a: Vector2, b: Vector2, r: Scalar) -> bool {
    let e = b - a;
    let ee = e.length_squared();
    let t = if ee > ZERO { (p - a).dot(e).div_or_zero(ee).clamp(ZERO, Scalar::ONE) } else { ZERO };
    let q = p - (a + e * t);
    // Components first, so the square below cannot saturate.
    if q.x.abs() > r || q.y.abs() > r {
        return false;
    }
    q.length_squared() <= r * r
}

/// True when the local point `p` is within the rounding radius of `poly`'s core.
fn rounded_polygon_contains(poly: &PolygonPath, p: Vector2) -> bool {
    let r = poly.rounding();
    let mut inside_core = true;
    for (v, n) in poly.vertices().iter().zip(poly.normals()) {
        let sep = n.dot(p - *v);
        if sep > r {
            return false;
        }
        inside_core &= sep <= ZERO;
    }
    if inside_core {
        return true;
    }
    let vs = poly.vertices();
    vs.iter().zip(vs.iter().cycle().skip(1)).any(|(a, b)| within_of_segment(p, *a, *b, r))
}

/// [`ray_polygon`] for a rounded polygon, in its local frame.
fn ray_rounded_polygon(p: Vector2, d: Vector2, length: Scalar, poly: &PolygonPath) -> Option<ShapeHit> {
    if rounded_polygon_contains(poly, p) {
        return None;
    }
    let r = poly.rounding();
    let vs = poly.vertices();
    let mut best = None;
    for ((a, b), n) in vs.iter().zip(vs.iter().cycle().skip(1)).zip(poly.normals()) {
        let (u, len) = (*b - *a).normalize_and_length();
        best = nearer(best, ray_flat_face(p, d, length, *a, *n, u, len, r));
        best = nearer(best, ray_circle(p, d, length, *a, r));
    }
    best
}
