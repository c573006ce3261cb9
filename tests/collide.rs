//! Narrow-phase properties over random rectangles and circles: the manifold
//! agrees with an independent floating-point computation of the geometry.
//!
//! Floats appear here only as the test's reference geometry (conversions of the
//! engine's fixed-point inputs and outputs), never as engine input.

use arphysics::collide::{
    collide_circles, collide_polygon_circle, collide_polygons, Manifold, REFERENCE_FACE_TOLERANCE,
};
use arphysics::geometry::PolygonPath;
use arphysics::math::scalar::checked_from_f64;
use arphysics::{Rot, Scalar, Transform, Vector2};
use proptest::prelude::*;

/// Slack for rounding in the fixed-point computation (m). Q32.32 rounds at
/// 2.3e-10; a few dozen operations on metre-sized numbers stay far below this.
const EPS: f64 = 1e-6;

type P = (f64, f64);

fn s(v: f64) -> Scalar {
    checked_from_f64(v).unwrap_or(Scalar::ZERO)
}

fn f(v: Vector2) -> P {
    (v.x.to_f64(), v.y.to_f64())
}

fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}

fn dot(a: P, b: P) -> f64 {
    a.0 * b.0 + a.1 * b.1
}

fn len(a: P) -> f64 {
    dot(a, a).sqrt()
}

/// A body placement: position within a few metres, any angle.
#[derive(Clone, Copy, Debug)]
struct Place {
    xf: Transform,
}

impl Place {
    /// World position of a local point, in floats.
    fn apply(self, p: P) -> P {
        let (c, s_) = (self.xf.q.c.to_f64(), self.xf.q.s.to_f64());
        let o = f(self.xf.p);
        (o.0 + c * p.0 - s_ * p.1, o.1 + s_ * p.0 + c * p.1)
    }
    /// Local coordinates of a world point, in floats.
    fn apply_inv(self, p: P) -> P {
        let (c, s_) = (self.xf.q.c.to_f64(), self.xf.q.s.to_f64());
        let d = sub(p, f(self.xf.p));
        (c * d.0 + s_ * d.1, -s_ * d.0 + c * d.1)
    }
}

fn place(x: f64, y: f64, angle: f64) -> Place {
    let q = Rot::from_direction(Vector2::new(s(angle.cos()), s(angle.sin()))).unwrap_or_default();
    Place { xf: Transform::new(Vector2::new(s(x), s(y)), q) }
}

fn arb_place() -> impl Strategy<Value = Place> {
    (-3.0..3.0f64, -3.0..3.0f64, 0.0..std::f64::consts::TAU).prop_map(|(x, y, a)| place(x, y, a))
}

/// A rectangle with sides 0.1–4 m, and its half extents in floats.
fn arb_rect() -> impl Strategy<Value = (PolygonPath, P)> {
    (0.1..4.0f64, 0.1..4.0f64).prop_map(|(w, h)| {
        let (w, h) = (s(w), s(h));
        let poly = PolygonPath::rectangle(w, h).unwrap_or_else(|e| panic!("{e}"));
        (poly, (w.to_f64() / 2.0, h.to_f64() / 2.0))
    })
}

fn arb_radius() -> impl Strategy<Value = Scalar> {
    (0.05..2.0f64).prop_map(s)
}

fn arb_margin() -> impl Strategy<Value = Scalar> {
    prop_oneof![Just(Scalar::ZERO), (0.0..0.5f64).prop_map(s)]
}

/// Signed distance from a world point to a placed rectangle (negative inside).
fn rect_distance(p: P, place: Place, half: P) -> f64 {
    let l = place.apply_inv(p);
    let d = (l.0.abs() - half.0, l.1.abs() - half.1);
    let outside = len((d.0.max(0.0), d.1.max(0.0)));
    outside + d.0.max(d.1).min(0.0)
}

/// World vertices of a placed rectangle, counter-clockwise.
fn rect_vertices(place: Place, half: P) -> [P; 4] {
    let (hx, hy) = half;
    [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)].map(|v| place.apply(v))
}

/// The best separating-axis value among `a`'s faces against `b` (m).
fn best_face_separation(a: &[P; 4], b: &[P; 4]) -> f64 {
    (0..4)
        .map(|i| {
            let (p, q) = (a[i], a[(i + 1) % 4]);
            let e = sub(q, p);
            let n = (e.1 / len(e), -e.0 / len(e));
            b.iter().map(|w| dot(n, sub(*w, p))).fold(f64::INFINITY, f64::min)
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

fn segment_distance(p: P, a: P, b: P) -> f64 {
    let e = sub(b, a);
    let t = (dot(sub(p, a), e) / dot(e, e)).clamp(0.0, 1.0);
    len(sub(p, (a.0 + e.0 * t, a.1 + e.1 * t)))
}

/// Distance between two convex quadrilaterals: 0 when they overlap.
fn polygon_distance(a: &[P; 4], b: &[P; 4]) -> f64 {
    if best_face_separation(a, b) <= 0.0 && best_face_separation(b, a) <= 0.0 {
        return 0.0;
    }
    let one_way = |x: &[P; 4], y: &[P; 4]| {
        x.iter()
            .flat_map(|p| (0..4).map(move |i| segment_distance(*p, y[i], y[(i + 1) % 4])))
            .fold(f64::INFINITY, f64::min)
    };
    one_way(a, b).min(one_way(b, a))
}

/// The checks every manifold must pass, whatever the shapes.
fn check_common(m: &Manifold, margin: Scalar) -> Result<(), TestCaseError> {
    prop_assert!(m.count <= 2);
    prop_assert_eq!(m.points().len(), m.count);
    if m.count > 0 {
        prop_assert!((len(f(m.normal)) - 1.0).abs() < EPS, "normal {:?}", m.normal);
    }
    for p in m.points() {
        prop_assert!(p.separation <= margin, "{:?} > margin {:?}", p.separation, margin);
    }
    Ok(())
}

/// Each point is on or inside a shape, within its own |separation| (it lies
/// midway between the two surfaces) plus rounding.
fn check_inside(m: &Manifold, distance_to_shape: impl Fn(P) -> f64) -> Result<(), TestCaseError> {
    for p in m.points() {
        let d = distance_to_shape(f(p.point));
        let allowed = p.separation.to_f64().abs() + 1e-4;
        prop_assert!(d <= allowed, "point {:?} is {} from the shape (allowed {})", p.point, d, allowed);
    }
    Ok(())
}

/// Anchors name the same world point as `point`, from each body's centre.
fn check_anchors(m: &Manifold, a: Place, b: Place) -> Result<(), TestCaseError> {
    for p in m.points() {
        prop_assert_eq!(p.point, a.xf.p + p.anchor_a);
        prop_assert_eq!(p.point, b.xf.p + p.anchor_b);
    }
    Ok(())
}

fn min_separation(m: &Manifold) -> f64 {
    m.points().iter().map(|p| p.separation.to_f64()).fold(f64::INFINITY, f64::min)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn circles(ra in arb_radius(), rb in arb_radius(), a in arb_place(), b in arb_place(), margin in arb_margin()) {
        let m = collide_circles(ra, a.xf, rb, b.xf, margin);
        check_common(&m, margin)?;
        check_anchors(&m, a, b)?;
        let (ca, cb) = (f(a.xf.p), f(b.xf.p));
        let gap = len(sub(cb, ca)) - ra.to_f64() - rb.to_f64();
        if gap > margin.to_f64() + EPS {
            prop_assert_eq!(m.count, 0);
        }
        if gap < margin.to_f64() - EPS {
            prop_assert_eq!(m.count, 1);
            prop_assert!((m.points[0].separation.to_f64() - gap).abs() < EPS);
            let n = f(m.normal);
            if len(sub(cb, ca)) > 1e-3 {
                // Along the line of centres, from A to B.
                prop_assert!(dot(n, sub(cb, ca)) > 0.0);
            }
        }
        check_inside(&m, |p| len(sub(p, ca)) - ra.to_f64())?;
        check_inside(&m, |p| len(sub(p, cb)) - rb.to_f64())?;

        let swapped = collide_circles(rb, b.xf, ra, a.xf, margin);
        prop_assert_eq!(swapped.count, m.count);
        if m.count == 1 && len(sub(cb, ca)) > 1e-6 {
            prop_assert!(len(sub(f(m.normal), (-swapped.normal.x.to_f64(), -swapped.normal.y.to_f64()))) < EPS);
            prop_assert!((m.points[0].separation.to_f64() - swapped.points[0].separation.to_f64()).abs() < EPS);
            prop_assert!(len(sub(f(m.points[0].point), f(swapped.points[0].point))) < EPS);
        }
    }

    #[test]
    fn polygon_and_circle((poly, half) in arb_rect(), a in arb_place(), r in arb_radius(), b in arb_place(), margin in arb_margin()) {
        let m = collide_polygon_circle(&poly, a.xf, r, b.xf, margin);
        check_common(&m, margin)?;
        check_anchors(&m, a, b)?;
        let centre = f(b.xf.p);
        // Signed distance from the circle's surface to the rectangle: exactly what
        // the separation must be.
        let gap = rect_distance(centre, a, half) - r.to_f64();
        if gap > margin.to_f64() + EPS {
            prop_assert_eq!(m.count, 0);
        }
        if gap < margin.to_f64() - EPS {
            prop_assert_eq!(m.count, 1);
            prop_assert!((m.points[0].separation.to_f64() - gap).abs() < EPS,
                "separation {:?}, expected {}", m.points[0].separation, gap);
        }
        check_inside(&m, |p| rect_distance(p, a, half))?;
        check_inside(&m, |p| len(sub(p, centre)) - r.to_f64())?;
    }

    #[test]
    fn polygons((pa, ha) in arb_rect(), a in arb_place(), (pb, hb) in arb_rect(), b in arb_place(), margin in arb_margin()) {
        let m = collide_polygons(&pa, a.xf, &pb, b.xf, margin);
        check_common(&m, margin)?;
        check_anchors(&m, a, b)?;
        let (va, vb) = (rect_vertices(a, ha), rect_vertices(b, hb));
        let (sep_a, sep_b) = (best_face_separation(&va, &vb), best_face_separation(&vb, &va));
        let distance = polygon_distance(&va, &vb);
        if distance > margin.to_f64() + EPS {
            prop_assert_eq!(m.count, 0);
        }
        // Overlapping shapes always produce a contact, no deeper than the least
        // penetration allows (the reference face may be up to the tolerance worse).
        if sep_a.max(sep_b) < -EPS {
            prop_assert!(m.count >= 1, "overlap by {} missed", sep_a.max(sep_b));
        }
        if m.count > 0 {
            let floor = sep_a.max(sep_b) - REFERENCE_FACE_TOLERANCE.to_f64() - EPS;
            prop_assert!(min_separation(&m) >= floor, "{} < {}", min_separation(&m), floor);
            if distance > EPS {
                // Apart: a speculative point never claims less than the true gap.
                prop_assert!(min_separation(&m) >= distance - EPS);
            }
        }
        check_inside(&m, |p| rect_distance(p, a, ha))?;
        check_inside(&m, |p| rect_distance(p, b, hb))?;

        let swapped = collide_polygons(&pb, b.xf, &pa, a.xf, margin);
        prop_assert_eq!(swapped.count > 0, m.count > 0);
        if m.count > 0 && (sep_a - sep_b).abs() > REFERENCE_FACE_TOLERANCE.to_f64() + EPS {
            // Unambiguous: the same polygon's face is the reference either way,
            // so the same numbers are computed in the same frame: exactly
            // mirrored. The ends are named from each call's A and B, so two
            // points come in the other order.
            prop_assert_eq!(swapped.normal, -m.normal);
            prop_assert_eq!(swapped.count, m.count);
            for (p, q) in m.points().iter().zip(swapped.points().iter().rev()) {
                prop_assert_eq!((p.point, p.separation), (q.point, q.separation));
                prop_assert_eq!((p.anchor_a, p.anchor_b), (q.anchor_b, q.anchor_a));
            }
        }
    }

    #[test]
    fn far_from_the_origin_only_the_position_shifts(
        (pa, _ha) in arb_rect(), a in arb_place(), (pb, _hb) in arb_rect(), b in arb_place(),
        r in arb_radius(), margin in arb_margin(),
        offset in (-1.0e6..1.0e6f64, -1.0e6..1.0e6f64),
    ) {
        let shift = Vector2::new(s(offset.0), s(offset.1));
        let moved = |x: Transform| Transform::new(x.p + shift, x.q);
        let pairs = [
            (collide_polygons(&pa, a.xf, &pb, b.xf, margin), collide_polygons(&pa, moved(a.xf), &pb, moved(b.xf), margin)),
            (collide_polygon_circle(&pa, a.xf, r, b.xf, margin), collide_polygon_circle(&pa, moved(a.xf), r, moved(b.xf), margin)),
            (collide_circles(r, a.xf, r, b.xf, margin), collide_circles(r, moved(a.xf), r, moved(b.xf), margin)),
        ];
        for (near, far) in pairs {
            prop_assert_eq!(far.count, near.count);
            prop_assert_eq!(far.normal, near.normal);
            for (p, q) in near.points().iter().zip(far.points()) {
                prop_assert_eq!(q.point, p.point + shift);
                prop_assert_eq!((q.anchor_a, q.anchor_b, q.separation, q.id), (p.anchor_a, p.anchor_b, p.separation, p.id));
            }
        }
    }
}

/// The same inputs give the same bits, call after call (no hidden state).
#[test]
fn repeated_calls_are_bit_identical() {
    let box_a = PolygonPath::rectangle(s(3.0), s(1.0)).unwrap_or_else(|e| panic!("{e}"));
    let box_b = PolygonPath::rectangle(s(1.0), s(2.0)).unwrap_or_else(|e| panic!("{e}"));
    let (a, b) = (place(0.1, 0.2, 0.3), place(0.9, 1.1, 2.0));
    let first = collide_polygons(&box_a, a.xf, &box_b, b.xf, s(0.1));
    assert!(first.count > 0);
    for _ in 0..10 {
        assert_eq!(collide_polygons(&box_a, a.xf, &box_b, b.xf, s(0.1)), first);
    }
}
