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
//! * **Anything against a capsule or a segment** is exact too: each shape is
//!   a convex core (a point, a segment or a polygon) grown by a radius, and
//!   two cores first come within the sum of the radii and `gap` when a vertex
//!   of one reaches the other's boundary grown by that distance (a capsule
//!   round each edge), so the answer is the earliest of the rays from every
//!   vertex of each core against every grown edge of the other (the other
//!   moving the opposite way), after a test that the cores are not already
//!   that close (a vertex–edge distance) or overlapping (separating axes, or
//!   for two segments, a crossing test).
//!
//! A rounded polygon is its core grown by its rounding radius: the radius is
//! added to `gap` for its core (for the Cyrus–Beck case that makes the
//! answer early by up to about 0.4 times the radius near a corner, never late).
//!
//! Work is done in A's frame, so the numbers are of the size of the bodies
//! and the motion, whatever the world position.

use super::capsule_circle::closest_on_segment;
use super::manifold::direction_and_length;
use crate::geometry::{Capsule, PolygonPath, Segment, MAX_POLYGON_VERTICES};
use crate::math::scalar::{ONE, ZERO};
use crate::math::{Scalar, Transform, Vector2};

/// The shape a sweep sees.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Swept<'a> {
    /// A circle of this radius about the body's position.
    Circle(Scalar),
    /// A convex polygon about the body's position (rounded or not).
    Polygon(&'a PolygonPath),
    /// A capsule (body-local centres).
    Capsule(&'a Capsule),
    /// A segment (body-local ends).
    Segment(&'a Segment),
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
            ray_rounded_polygon(pa, c0, xf_a.q.inv_rotate(d), rb + pa.rounding + gap)
        }
        (Swept::Circle(ra), Swept::Polygon(pb)) => {
            // A moving by −d against B standing still is the same motion.
            let c0 = xf_b.apply_inv(xf_a.p);
            ray_rounded_polygon(pb, c0, xf_b.q.inv_rotate(-d), ra + pb.rounding + gap)
        }
        (Swept::Polygon(pa), Swept::Polygon(pb)) => {
            polygons(pa, xf_a, pb, xf_b, d, gap + pa.rounding + pb.rounding)
        }
        _ => {
            let b_in_a = xf_a.inv_mul(xf_b);
            let core_a = Core::of(a, Transform::IDENTITY);
            let core_b = Core::of(b, b_in_a);
            cores(&core_a, &core_b, xf_a.q.inv_rotate(d), gap)
        }
    }
}

/// A shape's convex core in A's frame: its vertices (one for a circle, two for
/// a capsule or segment of some length), their edges' outward normals (a
/// polygon's; a segment's two side normals) and the radius it is grown by.
struct Core {
    vertices: [Vector2; MAX_POLYGON_VERTICES],
    normals: [Vector2; MAX_POLYGON_VERTICES],
    count: usize,
    radius: Scalar,
}

impl Core {
    /// The core of `shape` placed by `xf` (relative to A).
    fn of(shape: Swept<'_>, xf: Transform) -> Self {
        let mut core = Self {
            vertices: [Vector2::ZERO; MAX_POLYGON_VERTICES],
            normals: [Vector2::ZERO; MAX_POLYGON_VERTICES],
            count: 1,
            radius: ZERO,
        };
        let segment = |core: &mut Self, p: Vector2, q: Vector2| {
            let (p, q) = (xf.apply(p), xf.apply(q));
            core.vertices[0] = p;
            if let Some((u, _)) = direction_and_length(q - p) {
                core.vertices[1] = q;
                core.normals[0] = u.right_perp();
                core.normals[1] = -u.right_perp();
                core.count = 2;
            }
        };
        match shape {
            Swept::Circle(r) => {
                core.vertices[0] = xf.p;
                core.radius = r;
            }
            Swept::Polygon(poly) => {
                let (vs, ns) = (poly.vertices(), poly.normals());
                core.count = vs.len().min(ns.len());
                for (k, (v, n)) in vs.iter().zip(ns).enumerate() {
                    if let (Some(sv), Some(sn)) = (core.vertices.get_mut(k), core.normals.get_mut(k)) {
                        *sv = xf.apply(*v);
                        *sn = xf.q.rotate(*n);
                    }
                }
                core.radius = poly.rounding;
            }
            Swept::Capsule(c) => {
                segment(&mut core, c.center1, c.center2);
                core.radius = c.radius;
            }
            Swept::Segment(sg) => segment(&mut core, sg.point1, sg.point2),
        }
        core
    }

    fn vertices(&self) -> &[Vector2] {
        self.vertices.get(..self.count).unwrap_or(&[])
    }

    /// The edge normals that are separating axes: a polygon's, a segment's
    /// side (one suffices: the other is its negation), a point's none.
    fn axes(&self) -> &[Vector2] {
        let n = if self.count >= 3 { self.count } else { self.count.saturating_sub(1) };
        self.normals.get(..n).unwrap_or(&[])
    }

    /// Edge `i` (for `i < edges()`): the polygon's edges, a segment's one
    /// edge, a point as an edge of no length.
    fn edge(&self, i: usize) -> (Vector2, Vector2) {
        let v = self.vertices.get(i).copied().unwrap_or_default();
        let w = if self.count >= 3 {
            self.vertices.get(super::next_index(i, self.count)).copied().unwrap_or_default()
        } else {
            self.vertices.get(self.count.saturating_sub(1)).copied().unwrap_or_default()
        };
        (v, w)
    }

    fn edges(&self) -> usize {
        if self.count >= 3 {
            self.count
        } else {
            1
        }
    }
}

/// Sweeps core `b` by `d` (A's frame) against core `a` (see the module docs):
/// the first `t` at which they are within both radii and `gap`.
fn cores(a: &Core, b: &Core, d: Vector2, gap: Scalar) -> Option<Scalar> {
    if a.count == 0 || b.count == 0 {
        return None;
    }
    let reach = a.radius + b.radius + gap;
    if cores_within(a, b, reach) {
        return Some(ZERO);
    }
    let (u, len) = direction(d)?;
    let mut best: Option<Scalar> = None;
    // B's vertices moving by +u against A's grown edges, and A's vertices
    // moving by −u against B's (the same relative motion).
    for (moving, fixed, dir) in [(b, a, u), (a, b, -u)] {
        for &w in moving.vertices() {
            for k in 0..fixed.edges() {
                let (p, q) = fixed.edge(k);
                if let Some(s) = ray_capsule(w, dir, p, q, reach) {
                    if s <= len && best.is_none_or(|x| s < x) {
                        best = Some(s);
                    }
                }
            }
        }
    }
    best.and_then(|s| fraction(s, len))
}

/// True when cores `a` and `b` overlap or are within `reach` of each other.
fn cores_within(a: &Core, b: &Core, reach: Scalar) -> bool {
    // Apart, the distance of two convex cores is that of a vertex of one to an
    // edge of the other.
    for (x, y) in [(a, b), (b, a)] {
        for &w in x.vertices() {
            for k in 0..y.edges() {
                let (p, q) = y.edge(k);
                let (c, _) = closest_on_segment(p, q, w);
                if within(w - c, reach) {
                    return true;
                }
            }
        }
    }
    if a.count < 3 && b.count < 3 {
        // Two segments (or a point, which the distances above settled): they
        // overlap only by crossing, each one's ends strictly either side of the
        // other's line.
        let straddles = |(p, q): (Vector2, Vector2), (r, s): (Vector2, Vector2)| {
            let e = q - p;
            let (x, y) = (e.cross(r - p), e.cross(s - p));
            (x > ZERO && y < ZERO) || (x < ZERO && y > ZERO)
        };
        return straddles(a.edge(0), b.edge(0)) && straddles(b.edge(0), a.edge(0));
    }
    // One has area: they overlap when no edge normal of either separates them.
    let (va, vb) = (a.vertices(), b.vertices());
    let apart = |n: &Vector2| {
        let range = |vs: &[Vector2]| {
            vs.iter()
                .map(|v| n.dot(*v))
                .fold((Scalar::MAX, Scalar::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
        };
        let ((a_lo, a_hi), (b_lo, b_hi)) = (range(va), range(vb));
        a_hi < b_lo || b_hi < a_lo
    };
    !a.axes().iter().chain(b.axes()).any(apart)
}

/// How far along the unit direction `u` the point `c0` first comes within
/// `radius` of the segment `p → q` (a capsule; a circle when `p == q`), if it
/// does at some distance ≥ 0. `c0` starts farther than `radius` from it.
fn ray_capsule(c0: Vector2, u: Vector2, p: Vector2, q: Vector2, radius: Scalar) -> Option<Scalar> {
    let mut best = circle_entry(c0 - p, u, radius);
    let mut keep = |s: Scalar| {
        if best.is_none_or(|b| s < b) {
            best = Some(s);
        }
    };
    if let Some((e, _)) = direction_and_length(q - p) {
        if let Some(s) = circle_entry(c0 - q, u, radius) {
            keep(s);
        }
        // The side facing c0, pushed out by `radius`.
        let n = e.right_perp();
        let (s0, rate) = (n.dot(c0 - p), n.dot(u));
        let (s0, rate) = if s0 < ZERO { (-s0, -rate) } else { (s0, rate) };
        if s0 > radius && rate < ZERO {
            let s = (s0 - radius).div_or_zero(-rate);
            let along = (c0 + u * s - p).dot(q - p);
            if along >= ZERO && along <= (q - p).length_squared() {
                keep(s);
            }
        }
    }
    best
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
    use crate::geometry::{Capsule, Segment};
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

    fn capsule() -> Capsule {
        // Horizontal, centres (±1, 0), radius 0.5.
        Capsule { center1: v(-1.0, 0.0), center2: v(1.0, 0.0), radius: s(0.5) }
    }

    #[test]
    fn a_circle_falls_on_a_capsule_side_and_end() {
        let cap = capsule();
        let (a, c) = (Swept::Capsule(&cap), Swept::Circle(s(0.25)));
        // From y = 10 down 20 m: touching at y = 0.75, t = 9.25 / 20.
        close(toi(a, c, (0.3, 10.0, 0.0), (0.0, -20.0), 0.0), 0.4625, 1e-6);
        // Over the end cap at x = 1.5: (0.5)² + y² = 0.75² → y = √0.3125.
        let y = 0.3125f64.sqrt();
        close(toi(a, c, (1.5, 10.0, 0.0), (0.0, -20.0), 0.0), (10.0 - y) / 20.0, 1e-6);
        // Beside the end (x = 2.3 > 1.75): a miss; and the circle as A.
        assert_eq!(toi(a, c, (2.3, 10.0, 0.0), (0.0, -20.0), 0.0), None);
        let swapped = time_of_impact(c, at(0.3, 10.0, 0.0), a, at(0.0, 0.0, 0.0), v(0.0, 20.0), ZERO);
        close(swapped.map(|t| t.to_num::<f64>()), 0.4625, 1e-6);
    }

    #[test]
    fn capsules_end_to_end_meet_at_their_caps_not_at_the_start() {
        // Collinear: B's near centre at x = 9, A's at 1, radii 0.5 each: the
        // caps touch once B has moved 7 of its 20 m. (Face axes alone would read
        // a zero gap on both side normals and answer 0.)
        let cap = capsule();
        let a = Swept::Capsule(&cap);
        close(toi(a, a, (10.0, 0.0, 0.0), (-20.0, 0.0), 0.0), 0.35, 1e-6);
        // With a gap of 0.1 m: 0.1 m sooner.
        close(toi(a, a, (10.0, 0.0, 0.0), (-20.0, 0.0), 0.1), 0.345, 1e-6);
        // Flat on it: cores 1 m apart, radii 1 m: touching now; from 3 m above,
        // touching after 2 of the 4 m.
        assert_eq!(toi(a, a, (0.5, 1.0, 0.0), (0.0, -4.0), 0.0), Some(0.0));
        close(toi(a, a, (0.5, 3.0, 0.0), (0.0, -4.0), 0.0), 0.5, 1e-6);
        // Crossing at the start (B upright through A): 0.
        assert_eq!(toi(a, a, (0.0, 0.0, core::f64::consts::FRAC_PI_2), (0.0, -4.0), 0.0), Some(0.0));
        // A segment under a capsule: the capsule's side 0.5 from the core.
        let seg = Segment { point1: v(-5.0, 0.0), point2: v(5.0, 0.0) };
        close(toi(Swept::Segment(&seg), a, (0.0, 3.0, 0.0), (0.0, -5.0), 0.0), 0.5, 1e-6);
    }

    #[test]
    fn capsules_and_segments_against_polygons() {
        let unit = PolygonPath::rectangle(s(2.0), s(2.0)).unwrap();
        let cap = capsule();
        let (p, c) = (Swept::Polygon(&unit), Swept::Capsule(&cap));
        // An upright capsule 5 m above the box's centre falling 10 m: its lower
        // cap reaches the top face (y = 1) when its lower centre is at 1.5.
        let upright = core::f64::consts::FRAC_PI_2;
        close(toi(p, c, (0.0, 5.0, upright), (0.0, -10.0), 0.0), 0.25, 1e-6);
        // Flat, beside the box's corner: the cap meets the corner (1, 1) when
        // the end centre (x = 1.3 at height y) is 0.5 away: y = 1.4.
        close(toi(p, c, (2.3, 5.0, 0.0), (0.0, -10.0), 0.0), 0.36, 1e-6);
        // And the polygon as the moving shape.
        let swapped = time_of_impact(c, at(2.3, 5.0, 0.0), p, at(0.0, 0.0, 0.0), v(0.0, 10.0), ZERO);
        close(swapped.map(|t| t.to_num::<f64>()), 0.36, 1e-6);
        // A box falling on a segment, and a segment through a box at the start.
        let seg = Segment { point1: v(-5.0, 0.0), point2: v(5.0, 0.0) };
        let g = Swept::Segment(&seg);
        close(toi(g, p, (0.3, 3.0, 0.0), (0.0, -6.0), 0.0), 2.0 / 6.0, 1e-6);
        // Turned 45°, corner first: the corner is √2 below the centre.
        let corner = (3.0 - core::f64::consts::SQRT_2) / 6.0;
        close(toi(g, p, (0.3, 3.0, core::f64::consts::FRAC_PI_4), (0.0, -6.0), 0.0), corner, 1e-6);
        assert_eq!(toi(g, p, (0.3, 0.2, 0.0), (0.0, -6.0), 0.0), Some(0.0));
        // A long segment across a small box: no vertex is near an edge, but
        // they overlap.
        let long = Segment { point1: v(-50.0, 0.0), point2: v(50.0, 0.0) };
        let big = PolygonPath::rectangle(s(20.0), s(20.0)).unwrap();
        assert_eq!(
            toi(Swept::Polygon(&big), Swept::Segment(&long), (0.0, 0.0, 0.0), (0.0, 1.0), 0.0),
            Some(0.0)
        );
        // A circle on a segment.
        close(toi(g, Swept::Circle(s(0.5)), (1.0, 3.0, 0.0), (0.0, -5.0), 0.0), 0.5, 1e-6);
        // Moving along the segment, beside it: no hit.
        assert_eq!(toi(g, Swept::Circle(s(0.5)), (-8.0, 0.6, 0.0), (16.0, 0.0), 0.0), None);
    }

    #[test]
    fn rounded_polygons_are_never_late() {
        let sharp = PolygonPath::rectangle(ONE, ONE).unwrap();
        let round = PolygonPath { rounding: s(0.1), ..sharp };
        let (r, q) = (Swept::Polygon(&round), Swept::Polygon(&sharp));
        // Face on: the rounded face 0.1 m sooner (exact on a face axis).
        close(toi(r, q, (-5.0, 0.0, 0.0), (10.0, 0.0), 0.0), 0.39, 1e-6);
        // Against a circle: exact, corner included.
        close(toi(r, Swept::Circle(s(0.5)), (-5.0, 0.0, 0.0), (10.0, 0.0), 0.0), 0.39, 1e-6);
        // Corner to corner along the diagonal: the true time has the rounded
        // corners 0.1 + 0 apart; the answer may be early, never late.
        // The corners (−1.5, −1.5) and (−0.5, −0.5) are √2 apart; B moves 4√2.
        let sqrt2 = core::f64::consts::SQRT_2;
        let truth = (sqrt2 - 0.1) / (4.0 * sqrt2);
        let t = toi(r, q, (-2.0, -2.0, 0.0), (4.0, 4.0), 0.0);
        // The face axes read 1 − 0.1 = 0.9 m to go, at 4 m per unit t: 0.225.
        close(t, 0.225, 1e-6);
        assert!(t.is_some_and(|t| t <= truth && t >= truth - 0.01), "{t:?} {truth}");
        // A rounded polygon against a capsule: the exact core method.
        let cap = capsule();
        close(toi(r, Swept::Capsule(&cap), (0.0, 5.0, 0.0), (0.0, -10.0), 0.0), (5.0 - 1.1) / 10.0, 1e-6);
    }

    #[test]
    fn swapping_the_shapes_and_reversing_the_motion_gives_the_same_time() {
        let cap = capsule();
        let seg = Segment { point1: v(-1.5, -0.5), point2: v(1.0, 0.5) };
        let boxy = PolygonPath::rectangle(s(1.5), s(1.0)).unwrap();
        let round = PolygonPath { rounding: s(0.1), ..boxy };
        let shapes = [
            Swept::Circle(s(0.3)),
            Swept::Capsule(&cap),
            Swept::Segment(&seg),
            Swept::Polygon(&boxy),
            Swept::Polygon(&round),
        ];
        let mut hits = 0;
        for (i, &a) in shapes.iter().enumerate() {
            for (j, &b) in shapes.iter().enumerate() {
                // Polygon against polygon is Cyrus–Beck (not symmetric near a
                // corner); segment against segment never collides.
                if (i >= 3 && j >= 3) || (i == 2 && j == 2) {
                    continue;
                }
                for (xb, d) in [
                    ((4.0, 0.7, 0.3), (-8.0, -1.0)),
                    ((0.5, 5.0, -1.2), (0.3, -9.0)),
                    ((-3.0, -3.0, 2.0), (6.0, 5.5)),
                ] {
                    let (xa, xb) = (at(0.1, -0.2, 0.4), at(xb.0, xb.1, xb.2));
                    let t = time_of_impact(a, xa, b, xb, v(d.0, d.1), s(0.02));
                    let back = time_of_impact(b, xb, a, xa, v(-d.0, -d.1), s(0.02));
                    match (t, back) {
                        (Some(t), Some(u)) => {
                            hits += 1;
                            assert!((t - u).abs() < s(1e-6), "{i} {j}: {t:?} {u:?}");
                        }
                        (None, None) => {}
                        other => panic!("{i} {j}: {other:?}"),
                    }
                }
            }
        }
        assert!(hits >= 30, "{hits}");
    }
}
