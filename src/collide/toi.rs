//! Time of impact: when a shape translated along a straight line first comes
//! within a distance of another, for continuous collision
//! ([`crate::continuous`]).
//!
//! Every function here is closed-form: no iteration, no root finder, so there
//! is no iteration count to cap and nothing that could loop. B moves by
//! `t·d` for `t` in [0, 1] while A stays put (a moving A is handled by the
//! caller as a relative motion; rotation during the step by widening `gap`).
//! Each answer is the first `t` at which B is within `gap` of A, or `None`
//! when it never is during the motion.
//!
//! * **A circle against a circle or a polygon** is exact: a ray from B's
//!   centre against A grown by B's radius plus `gap` (a circle, or a polygon
//!   with rounded corners: its faces pushed out, its vertices circles).
//! * **A polygon against a polygon** clips the motion against every face
//!   axis of both (Cyrus–Beck): along a face normal the separation changes
//!   linearly with `t`, so the times at which every axis is within `gap` form
//!   one interval, found with one division per axis. Two convex polygons are
//!   disjoint exactly when some face axis separates them, and no axis ever
//!   reads more than the true distance, so the interval starts no later than
//!   the true time: the answer is never late, and is early by at most the
//!   difference between the polygons' distance and their best axis
//!   separation near a corner (a fraction of `gap`).
//!
//! Work is done in A's frame, so the numbers are of the size of the bodies
//! and the motion, whatever the world position.

use crate::geometry::{PolygonPath, MAX_POLYGON_VERTICES};
use crate::math::scalar::{ONE, ZERO};
use crate::math::{Scalar, Transform, Vector2};

/// The shape a sweep sees.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Swept<'a> {
    /// A circle of this radius about the body's position.
    Circle(Scalar),
    /// A convex polygon about the body's position.
    Polygon(&'a PolygonPath),
}

/// The first `t` in [0, 1] at which `b` (placed by `xf_b`, moved by `t·d`,
/// `d` in world coordinates) is within `gap` of `a` (placed by `xf_a`); 0 when
/// it already is, `None` when it never is.
pub(crate) fn time_of_impact(
    a: Swept<'_>,
    xf_a: Transform,
    b: Swept<'_>,
    xf_b: Transform,
    d: Vector2,
    gap: Scalar,
) -> Option<Scalar> {
    match (a, b) {
        (Swept::Circle(ra), Swept::Circle(rb)) => {
            let c0 = xf_b.p - xf_a.p;
            ray_circle(c0, d, Vector2::ZERO, ra + rb + gap)
        }
        (Swept::Polygon(pa), Swept::Circle(rb)) => {
            let c0 = xf_a.apply_inv(xf_b.p);
            ray_rounded_polygon(pa, c0, xf_a.q.inv_rotate(d), rb + gap)
        }
        (Swept::Circle(ra), Swept::Polygon(pb)) => {
            // A moving by −d against B standing still is the same motion.
            let c0 = xf_b.apply_inv(xf_a.p);
            ray_rounded_polygon(pb, c0, xf_b.q.inv_rotate(-d), ra + gap)
        }
        (Swept::Polygon(pa), Swept::Polygon(pb)) => polygons(pa, xf_a, pb, xf_b, d, gap),
    }
}

/// Where a motion `d` leaves the straight line: its direction and length, or
/// `None` for no motion.
fn direction(d: Vector2) -> Option<(Vector2, Scalar)> {
    let (u, len) = d.normalize_and_length();
    (len > ZERO).then_some((u, len))
}

/// The first `t` in [0, 1] at which the point `c0 + t·d` is within `radius` of
/// `centre`.
fn ray_circle(c0: Vector2, d: Vector2, centre: Vector2, radius: Scalar) -> Option<Scalar> {
    let m = c0 - centre;
    if within(m, radius) {
        return Some(ZERO);
    }
    let (u, len) = direction(d)?;
    fraction(circle_entry(m, u, radius)?, len)
}

/// True when the offset `m` from a circle's centre is within its `radius`.
fn within(m: Vector2, radius: Scalar) -> bool {
    // Squares cannot saturate here: the motion and the gap are bounded by
    // the world (2,048 m/s for at most 0.25 s), so |m| < 2^15, |m|² < 2^30.
    m.length_squared() <= radius * radius
}

/// How far along the unit direction `u` a point starting at offset `m` from a
/// circle's centre (outside it) enters the circle of `radius`, if it does.
fn circle_entry(m: Vector2, u: Vector2, radius: Scalar) -> Option<Scalar> {
    // s² + 2·b·s + c = 0 with b = m·u, c = |m|² − radius².
    let b = m.dot(u);
    if b >= ZERO {
        return None;
    }
    let disc = b * b - (m.length_squared() - radius * radius);
    if disc < ZERO {
        return None;
    }
    Some((-b - disc.sqrt()).max(ZERO))
}

/// `s / len` when `s ≤ len` (a point on the motion), else `None`.
fn fraction(s: Scalar, len: Scalar) -> Option<Scalar> {
    if s > len {
        return None;
    }
    Some(s.div_or_zero(len).clamp(ZERO, ONE))
}

/// The first `t` in [0, 1] at which the point `c0 + t·d` (polygon frame) is
/// within `radius` of the polygon: the ray against the polygon with each face
/// pushed out by `radius` and a circle of `radius` on each vertex.
fn ray_rounded_polygon(poly: &PolygonPath, c0: Vector2, d: Vector2, radius: Scalar) -> Option<Scalar> {
    let (vertices, normals) = (poly.vertices(), poly.normals());
    let count = vertices.len().min(normals.len());
    if count == 0 {
        return None;
    }
    if point_within(vertices, normals, c0, radius) {
        return Some(ZERO);
    }
    let (u, len) = direction(d)?;
    let mut best: Option<Scalar> = None;
    let mut keep = |s: Scalar| {
        if s >= ZERO && s <= len && best.is_none_or(|b| s < b) {
            best = Some(s);
        }
    };
    for i in 0..count {
        let (Some(&v), Some(&n), Some(&w)) =
            (vertices.get(i), normals.get(i), vertices.get(super::next_index(i, count)))
        else {
            continue;
        };
        // The face pushed out by `radius`: entered where n·(c − v) falls to
        // `radius`, from outside, within the face's length.
        let (s0, rate) = (n.dot(c0 - v), n.dot(u));
        if s0 > radius && rate < ZERO {
            let s = (s0 - radius).div_or_zero(-rate);
            let q = c0 + u * s;
            let e = w - v;
            let along = (q - v).dot(e);
            if along >= ZERO && along <= e.length_squared() {
                keep(s);
            }
        }
        // The vertex's circle (the start is outside it: checked above).
        if let Some(s) = circle_entry(c0 - v, u, radius) {
            keep(s);
        }
    }
    best.and_then(|s| fraction(s, len))
}

/// True when `p` is within `radius` of the convex polygon (inside it, or
/// closer than `radius` to one of its edges).
fn point_within(vertices: &[Vector2], normals: &[Vector2], p: Vector2, radius: Scalar) -> bool {
    let count = vertices.len().min(normals.len());
    let mut inside = true;
    for i in 0..count {
        let (Some(&v), Some(&n), Some(&w)) =
            (vertices.get(i), normals.get(i), vertices.get(super::next_index(i, count)))
        else {
            continue;
        };
        let s = n.dot(p - v);
        if s > radius {
            return false;
        }
        if s > ZERO {
            inside = false;
            // Outside this face: within `radius` of its segment?
            let e = w - v;
            let along = (p - v).dot(e);
            let len2 = e.length_squared();
            let near = if along <= ZERO {
                (p - v).length_squared()
            } else if along >= len2 {
                (p - w).length_squared()
            } else {
                s * s
            };
            if near <= radius * radius {
                return true;
            }
        }
    }
    inside
}

/// Cyrus–Beck over the face axes of both polygons (see the module docs).
fn polygons(
    pa: &PolygonPath,
    xf_a: Transform,
    pb: &PolygonPath,
    xf_b: Transform,
    d: Vector2,
    gap: Scalar,
) -> Option<Scalar> {
    let b_in_a = xf_a.inv_mul(xf_b);
    let d = xf_a.q.inv_rotate(d);
    let (va, na) = (pa.vertices(), pa.normals());
    let (ca, cb) = (va.len().min(na.len()), pb.vertices().len().min(pb.normals().len()));
    if ca == 0 || cb == 0 {
        return None;
    }
    let mut vb = [Vector2::ZERO; MAX_POLYGON_VERTICES];
    for (slot, v) in vb.iter_mut().zip(pb.vertices()) {
        *slot = b_in_a.apply(*v);
    }
    let vb = vb.get(..cb).unwrap_or(&[]);
    let (mut lo, mut hi) = (ZERO, ONE);
    // One axis: separation `s0` at t = 0, changing by `rate` per unit t.
    let mut clip = |s0: Scalar, rate: Scalar| -> bool {
        if s0 > gap {
            // Must fall to `gap`: from t = (s0 − gap)/(−rate) on.
            if rate >= ZERO || s0 - gap > -rate {
                return false;
            }
            lo = lo.max((s0 - gap).div_or_zero(-rate));
        } else if rate > ZERO && gap - s0 < rate {
            // Within `gap` now, leaving it at t = (gap − s0)/rate.
            hi = hi.min((gap - s0).div_or_zero(rate));
        }
        lo <= hi
    };
    for (v, n) in va.iter().zip(na).take(ca) {
        let s0 = vb.iter().map(|w| n.dot(*w - *v)).min().unwrap_or(Scalar::MAX);
        if !clip(s0, n.dot(d)) {
            return None;
        }
    }
    for (k, n) in pb.normals().iter().take(cb).enumerate() {
        let (Some(&w), n) = (vb.get(k), b_in_a.q.rotate(*n)) else { continue };
        let s0 = va.iter().take(ca).map(|v| n.dot(*v - w)).min().unwrap_or(Scalar::MAX);
        if !clip(s0, -n.dot(d)) {
            return None;
        }
    }
    Some(lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rot;

    fn s(x: f64) -> Scalar {
        Scalar::from_num(x)
    }

    fn v(x: f64, y: f64) -> Vector2 {
        Vector2::new(s(x), s(y))
    }

    fn at(x: f64, y: f64, angle: f64) -> Transform {
        Transform::new(v(x, y), Rot::from_angle(s(angle)))
    }

    /// A at the origin unturned; B at `b` (turned by `b.2`), moved by `d`.
    fn toi(a: Swept<'_>, b: Swept<'_>, at_b: (f64, f64, f64), d: (f64, f64), gap: f64) -> Option<f64> {
        let xb = at(at_b.0, at_b.1, at_b.2);
        time_of_impact(a, at(0.0, 0.0, 0.0), b, xb, v(d.0, d.1), s(gap)).map(|t| t.to_num::<f64>())
    }

    fn close(t: Option<f64>, want: f64, tol: f64) {
        assert!(t.is_some_and(|t| (t - want).abs() <= tol), "{t:?}, want {want}");
    }

    #[test]
    fn circles_meet_where_their_rims_touch() {
        let (a, b) = (Swept::Circle(s(0.5)), Swept::Circle(s(0.25)));
        // Centres 10 m apart, B moving 20 m towards A: touching after
        // 10 − 0.75 = 9.25 m, t = 0.4625; with a 0.05 m gap, 0.05 m sooner.
        close(toi(a, b, (10.0, 0.0, 0.0), (-20.0, 0.0), 0.0), 0.4625, 1e-6);
        close(toi(a, b, (10.0, 0.0, 0.0), (-20.0, 0.0), 0.05), 0.46, 1e-6);
        // Passing 0.76 m beside, moving away, stopping short: no impact.
        assert_eq!(toi(a, b, (10.0, 0.76, 0.0), (-20.0, 0.0), 0.0), None);
        assert_eq!(toi(a, b, (10.0, 0.0, 0.0), (20.0, 0.0), 0.0), None);
        assert_eq!(toi(a, b, (10.0, 0.0, 0.0), (-9.0, 0.0), 0.0), None);
        // Already overlapping.
        assert_eq!(toi(a, b, (0.5, 0.0, 0.0), (5.0, 0.0), 0.0), Some(0.0));
    }

    #[test]
    fn a_circle_hits_a_thin_wall_face_on_and_rounds_its_corner() {
        // A wall 0.1 m thick, 4 m tall, at the origin; a 0.05 m circle from
        // x = −30 moving 60 m to the right: touches at x = −0.1, t = 29.9/60,
        // whichever side of the call the circle is on.
        let wall = PolygonPath::rectangle(s(0.1), s(4.0)).unwrap();
        let (w, c) = (Swept::Polygon(&wall), Swept::Circle(s(0.05)));
        close(toi(w, c, (-30.0, 1.0, 0.0), (60.0, 0.0), 0.0), 29.9 / 60.0, 1e-6);
        let swapped = time_of_impact(c, at(-30.0, 1.0, 0.0), w, at(0.0, 0.0, 0.0), v(-60.0, 0.0), ZERO);
        close(swapped.map(|t| t.to_num::<f64>()), 29.9 / 60.0, 1e-6);
        // Past the top corner (2, 0.05) by 0.03 m: the rounded corner reaches
        // 0.05 m, so it hits, at x where (x + 0.05)² + 0.03² = 0.05².
        let x = -0.05 - (0.05f64 * 0.05 - 0.03 * 0.03).sqrt();
        close(toi(w, c, (-30.0, 2.03, 0.0), (60.0, 0.0), 0.0), (x + 30.0) / 60.0, 1e-6);
        // 0.06 m above it: a miss, although a square corner would catch it.
        assert_eq!(toi(w, c, (-30.0, 2.06, 0.0), (60.0, 0.0), 0.0), None);
    }

    #[test]
    fn polygons_are_clipped_on_every_face_axis() {
        // A unit box moving 10 m right towards a box 5 m away (4 m between
        // faces): t = 0.4, and with a gap of 0.5 m, 0.35.
        let unit = PolygonPath::rectangle(ONE, ONE).unwrap();
        let u = Swept::Polygon(&unit);
        close(toi(u, u, (-5.0, 0.0, 0.0), (10.0, 0.0), 0.0), 0.4, 1e-6);
        close(toi(u, u, (-5.0, 0.0, 0.0), (10.0, 0.0), 0.5), 0.35, 1e-6);
        // B turned 45°, corner first: the corner is √2/2 from its centre.
        let corner = (4.5 - core::f64::consts::FRAC_1_SQRT_2) / 10.0;
        close(toi(u, u, (-5.0, 0.0, core::f64::consts::FRAC_PI_4), (10.0, 0.0), 0.0), corner, 1e-6);
        // Passing 1.01 m beside (faces 0.01 m apart): a miss; overlapping: 0.
        assert_eq!(toi(u, u, (-5.0, 1.01, 0.0), (10.0, 0.0), 0.0), None);
        assert_eq!(toi(u, u, (-0.5, 0.0, 0.0), (10.0, 0.0), 0.0), Some(0.0));
        // Through a 0.1 m wall from 30 m away at 2,048 m/s for 1/60 s.
        let wall = PolygonPath::rectangle(s(0.1), s(4.0)).unwrap();
        let bullet = PolygonPath::rectangle(s(0.05), s(0.05)).unwrap();
        let step = 2048.0 / 60.0;
        let t = toi(Swept::Polygon(&wall), Swept::Polygon(&bullet), (-30.0, 0.3, 0.0), (step, 0.0), 0.0);
        close(t, (30.0 - 0.075) / step, 1e-6);
    }

    #[test]
    fn no_motion_is_a_hit_only_when_already_within_the_gap() {
        let unit = PolygonPath::rectangle(ONE, ONE).unwrap();
        let (u, c) = (Swept::Polygon(&unit), Swept::Circle(s(0.5)));
        for (x, want) in [(1.5, None), (1.0, Some(0.0))] {
            assert_eq!(toi(u, u, (x, 0.0, 0.0), (0.0, 0.0), 0.0), want);
            assert_eq!(toi(u, c, (x, 0.0, 0.0), (0.0, 0.0), 0.0), want);
            assert_eq!(toi(c, c, (x, 0.0, 0.0), (0.0, 0.0), 0.0), want);
        }
    }
}
