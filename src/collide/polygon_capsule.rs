//! Convex polygon against capsule, and segment against polygon: the capsule or
//! segment seen as a two-vertex polygon with a rounding radius, and the
//! polygon–polygon contact ([`collide_polygons`]) generalised to rounded shapes.
//!
//! A segment `p → q` is a degenerate polygon whose two edges are the segment
//! itself, once each way: edge 0 `p → q` with outward normal the direction
//! turned −90°, edge 1 `q → p` with the opposite normal. The separating-axis
//! test over the polygon's faces and these two is complete (two convex shapes,
//! one of them with area, are apart exactly when one of those axes separates
//! them), and the polygon contact's vertex–vertex case gives the true gap
//! between a rounded end and a corner. Box2D v3 does the same (`b2MakeCapsule`
//! fed to its polygon contact).

use super::manifold::{direction_and_length, Manifold};
use super::{collide_polygon_circle, collide_polygons};
use crate::geometry::{Capsule, PolygonPath, Segment};
use crate::math::{Scalar, Transform, Vector2};

/// The contact between a convex polygon (shape A, placed by `xf_a`, rounded or
/// not) and a capsule (shape B, placed by `xf_b`).
///
/// The contract of [`collide_polygons`]: up to two points (a capsule lying on a
/// face gets one at each end of the overlap), normal from the polygon to the
/// capsule, each point midway between the two rounded surfaces, reported while
/// the gap is at most `margin` (m). Feature ids are those of
/// [`collide_polygons`] with the capsule's edge 0 running `center1 → center2`
/// (its right-hand side) and edge 1 back (its left-hand side), vertex 0 at
/// `center1`, vertex 1 at `center2`: they hold while the same face of the
/// polygon touches the same side of the capsule.
///
/// A capsule of zero length is a circle: the contact is that of
/// [`collide_polygon_circle`] with a circle at the capsule's centre (the anchors
/// still relative to B's body position).
#[must_use]
pub fn collide_polygon_capsule(
    poly: &PolygonPath,
    xf_a: Transform,
    capsule: &Capsule,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    match two_gon(capsule.center1, capsule.center2, capsule.radius, poly) {
        Some(view) => collide_polygons(poly, xf_a, &view, xf_b, margin),
        None => {
            let centre = Transform::new(xf_b.apply(capsule.center1), xf_b.q);
            rebase_b(collide_polygon_circle(poly, xf_a, capsule.radius, centre, margin), xf_b.p)
        }
    }
}

/// The contact between a segment (shape A, placed by `xf_a`) and a convex
/// polygon (shape B, placed by `xf_b`, rounded or not).
///
/// The contract of [`collide_polygons`], the segment being a two-vertex polygon
/// (edge 0 `point1 → point2`, its right-hand side, and edge 1 back; vertex 0 at
/// `point1`): a box resting on a segment gets two points whose ids hold while
/// it rests on the same face. The segment is two-sided.
///
/// A segment of zero length (which a valid world never holds) is treated as a
/// point: the contact of [`collide_polygon_circle`] with a circle of radius 0,
/// seen from the point.
#[must_use]
pub fn collide_segment_polygon(
    segment: &Segment,
    xf_a: Transform,
    poly: &PolygonPath,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    match two_gon(segment.point1, segment.point2, Scalar::ZERO, poly) {
        Some(view) => collide_polygons(&view, xf_a, poly, xf_b, margin),
        None => {
            let point = Transform::new(xf_a.apply(segment.point1), xf_a.q);
            let m = collide_polygon_circle(poly, xf_b, Scalar::ZERO, point, margin);
            flip(rebase_b(m, xf_a.p))
        }
    }
}

/// The segment `p → q` (body-local) as a two-vertex polygon with rounding
/// `radius`, or `None` when it has no length (its normal is undefined).
///
/// Only the fields the contact reads are set (vertices, normals, count,
/// rounding); the rest are copied from `like`, which is never a problem since
/// the contact code does not look at them. No allocation: the view lives on the
/// stack for one call.
pub(crate) fn two_gon(p: Vector2, q: Vector2, radius: Scalar, like: &PolygonPath) -> Option<PolygonPath> {
    let (u, _) = direction_and_length(q - p)?;
    let n = u.right_perp();
    let mut view = PolygonPath { count: 2, rounding: radius, ..*like };
    view.vertices[0] = p;
    view.vertices[1] = q;
    view.normals[0] = n;
    view.normals[1] = -n;
    Some(view)
}

/// `m` with every `anchor_b` measured from `position` (B's body position)
/// instead of from where the contact was computed: the same world point, so
/// `point − position` is the exact anchor.
pub(crate) fn rebase_b(mut m: Manifold, position: Vector2) -> Manifold {
    let count = m.count;
    for p in m.points.iter_mut().take(count) {
        p.anchor_b = p.point - position;
    }
    m
}

/// `m` with the shapes' roles swapped: the normal negated, the anchors traded.
pub(crate) fn flip(mut m: Manifold) -> Manifold {
    m.normal = -m.normal;
    let count = m.count;
    for p in m.points.iter_mut().take(count) {
        core::mem::swap(&mut p.anchor_a, &mut p.anchor_b);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::test_support::{at, close, near, v};
    use crate::math::scalar::{from_int, ONE, ZERO};
    use crate::math::Rot;

    fn rect(w: i32, h: i32) -> PolygonPath {
        PolygonPath::rectangle(from_int(w), from_int(h)).unwrap_or_else(|_| unreachable!())
    }

    /// A horizontal capsule 2 m long between centres, radius 0.5.
    fn capsule() -> Capsule {
        Capsule { center1: v("-1", "0"), center2: v("1", "0"), radius: Scalar::lit("0.5") }
    }

    #[test]
    fn capsule_lying_on_a_box_gets_two_points_at_its_centres() {
        // Box 4×2, top at y = 1; capsule core at y = 1.45: 0.05 deep.
        let m = collide_polygon_capsule(&rect(4, 2), at("0", "0"), &capsule(), at("0.5", "1.45"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::Y);
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-0.05"));
            assert_eq!(p.point.y, Scalar::lit("0.975"));
        }
        let xs = [m.points[0].point.x, m.points[1].point.x];
        assert_eq!(xs, [Scalar::lit("1.5"), Scalar::lit("-0.5")]);
        // The box's top (edge 2) against the capsule's edge 0 (centre1 →
        // centre2, its right-hand side, facing down): the ids of two boxes
        // resting face to face.
        assert_eq!((m.points[0].id, m.points[1].id), (0x200, 0x201));
    }

    #[test]
    fn ids_hold_while_the_capsule_rocks_and_slides_on_the_face() {
        let ids = |xf: Transform| {
            let m = collide_polygon_capsule(&rect(4, 2), at("0", "0"), &capsule(), xf, ZERO);
            (m.count, m.normal, m.points.map(|p| p.id))
        };
        let flat = ids(at("0.5", "1.45"));
        let tilt = |t: &str| Rot::from_direction(v("1", t)).unwrap_or_default();
        for (x, t) in [("0.3", "0.001"), ("0.7", "-0.001"), ("1.2", "0.0005")] {
            let m = ids(Transform::new(v(x, "1.45"), tilt(t)));
            assert_eq!((m.0, m.2), (flat.0, flat.2), "{x} {t}");
            assert!(close(m.1, Vector2::Y) || (m.1 - Vector2::Y).length() < Scalar::lit("0.002"));
        }
    }

    #[test]
    fn capsule_end_against_a_box_corner_uses_the_rounded_end() {
        // End centre (2.3, 1.4) from the corner (2, 1): 0.5 away, radius 0.5:
        // touching; moved 0.1 closer along the diagonal: 0.1 deep.
        let xf_b = at("3.24", "1.32");
        let m = collide_polygon_capsule(&rect(4, 2), at("0", "0"), &capsule(), xf_b, ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, v("0.6", "0.8")), "{:?}", m.normal);
        assert!(near(m.points[0].separation, Scalar::lit("-0.1")), "{:?}", m.points[0].separation);
        // Corner + normal · (−0.05).
        assert!(close(m.points[0].point, v("1.97", "0.96")), "{:?}", m.points[0].point);
    }

    #[test]
    fn capsule_end_on_to_a_face() {
        // A vertical capsule standing on the box: lower end centre 0.45 above the top.
        let upright = Transform::new(v("0.5", "2.45"), Rot { c: ZERO, s: ONE });
        let m = collide_polygon_capsule(&rect(4, 2), at("0", "0"), &capsule(), upright, ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        assert!(near(m.points[0].separation, Scalar::lit("-0.05")));
        assert!(close(m.points[0].point, v("0.5", "0.975")), "{:?}", m.points[0].point);
    }

    #[test]
    fn zero_length_capsule_is_the_circle_at_its_centre() {
        let point = Capsule { center1: v("0.2", "0"), center2: v("0.2", "0"), radius: Scalar::lit("0.5") };
        let m = collide_polygon_capsule(&rect(4, 2), at("0", "0"), &point, at("0.8", "1.25"), ZERO);
        let c = collide_polygon_circle(&rect(4, 2), at("0", "0"), Scalar::lit("0.5"), at("1", "1.25"), ZERO);
        assert_eq!((m.normal, m.count), (c.normal, c.count));
        assert_eq!(m.points[0].point, c.points[0].point);
        assert_eq!(m.points[0].separation, c.points[0].separation);
        assert_eq!(m.points[0].anchor_b, c.points[0].anchor_b + v("0.2", "0"));
    }

    #[test]
    fn box_resting_on_a_segment_gets_two_points_with_stable_ids() {
        let ground = Segment { point1: v("-5", "0"), point2: v("5", "0") };
        let m = collide_segment_polygon(&ground, at("0", "0"), &rect(2, 2), at("0.5", "0.95"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::Y);
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-0.05"));
            assert_eq!(p.point.y, Scalar::lit("-0.025"));
        }
        // The segment's edge 1 (upward normal) and the box's bottom, edge 0.
        let ids = (m.points[0].id, m.points[1].id);
        assert_eq!(ids, (0x100, 0x101));
        // Sliding along and tilting a little keeps them.
        for (x, t) in [("2", "0.001"), ("-3", "-0.001")] {
            let q = Rot::from_direction(v("1", t)).unwrap_or_default();
            let m = collide_segment_polygon(
                &ground,
                at("0", "0"),
                &rect(2, 2),
                Transform::new(v(x, "0.95"), q),
                ZERO,
            );
            assert_eq!((m.count, m.points[0].id, m.points[1].id), (2, ids.0, ids.1), "{x} {t}");
        }
        // Below the segment the box is pushed down: two-sided.
        let under = collide_segment_polygon(&ground, at("0", "0"), &rect(2, 2), at("0.5", "-0.95"), ZERO);
        assert_eq!(under.normal, -Vector2::Y);
        assert_eq!(under.count, 2);
    }

    #[test]
    fn box_corner_beyond_a_segment_end_uses_the_vertex_gap() {
        // Segment end (1, 0); box corner (1.3, 0.4) at distance 0.5.
        let seg = Segment { point1: v("-1", "0"), point2: v("1", "0") };
        let m = collide_segment_polygon(&seg, at("0", "0"), &rect(2, 2), at("2.3", "1.4"), ONE);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, v("0.6", "0.8")), "{:?}", m.normal);
        assert!(near(m.points[0].separation, Scalar::lit("0.5")));
        assert!(close(m.points[0].point, v("1.15", "0.2")));
    }

    #[test]
    fn zero_length_segment_is_a_point() {
        let dot = Segment { point1: v("0", "1.9"), point2: v("0", "1.9") };
        let m = collide_segment_polygon(&dot, at("0", "0"), &rect(4, 2), at("0", "1"), ZERO);
        // The point is 0.1 inside the box's top face: pushed down out of B.
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, -Vector2::Y);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.1"));
        assert_eq!(m.points[0].anchor_a, m.points[0].point);
        assert_eq!(m.points[0].anchor_b, m.points[0].point - v("0", "1"));
    }

    #[test]
    fn rounded_polygon_face_contact_is_the_sharp_one_less_the_radius() {
        let sharp = rect(4, 2);
        let r = Scalar::lit("0.1");
        let round = PolygonPath { rounding: r, ..sharp };
        // The box face up, a capsule on it; then a rounded box on a rounded box.
        let xf = at("0.5", "1.45");
        let (s, t) = (
            collide_polygon_capsule(&sharp, at("0", "0"), &capsule(), xf, ONE),
            collide_polygon_capsule(&round, at("0", "0"), &capsule(), xf, ONE),
        );
        assert_eq!((s.count, t.count, s.normal, t.normal), (2, 2, Vector2::Y, Vector2::Y));
        for (p, q) in s.points().iter().zip(t.points()) {
            assert_eq!(q.separation, p.separation - r);
            assert_eq!(q.id, p.id);
            // Midway between the surfaces: the rounded face is 0.1 higher.
            assert_eq!(q.point, p.point + v("0", "0.05"));
        }
        let small = rect(2, 2);
        let small_round = PolygonPath { rounding: r, ..small };
        let xf = at("0.5", "1.9");
        let s = collide_polygons(&sharp, at("0", "0"), &small, xf, ONE);
        let t = collide_polygons(&round, at("0", "0"), &small_round, xf, ONE);
        assert_eq!((t.count, t.normal), (s.count, s.normal));
        for (p, q) in s.points().iter().zip(t.points()) {
            assert_eq!(q.separation, p.separation - r - r);
            assert_eq!((q.point, q.id), (p.point, p.id));
        }
        // And the circle against a rounded box.
        let s = collide_polygon_circle(&sharp, at("0", "0"), Scalar::lit("0.5"), at("1", "1.25"), ONE);
        let t = collide_polygon_circle(&round, at("0", "0"), Scalar::lit("0.5"), at("1", "1.25"), ONE);
        assert_eq!(t.points[0].separation, s.points[0].separation - r);
        assert_eq!(t.points[0].point, s.points[0].point + v("0", "0.05"));
    }

    #[test]
    fn rounded_corners_meet_along_the_vertex_line() {
        // Two unit boxes rounded by 0.1, corners (0.5, 0.5) and (0.8, 0.9): 0.5
        // apart, the surfaces 0.3.
        let round = PolygonPath { rounding: Scalar::lit("0.1"), ..rect(1, 1) };
        let m = collide_polygons(&round, at("0", "0"), &round, at("1.3", "1.4"), ONE);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, v("0.6", "0.8")), "{:?}", m.normal);
        assert!(near(m.points[0].separation, Scalar::lit("0.3")), "{:?}", m.points[0].separation);
        // A's corner + normal · (0.1 + 0.15).
        assert!(close(m.points[0].point, v("0.65", "0.7")), "{:?}", m.points[0].point);
    }

    #[test]
    fn polygon_capsule_symmetry_under_a_large_offset() {
        let tilt = Rot::from_direction(v("4", "3")).unwrap_or_default();
        let (xa, xb) = (Transform::new(v("0.2", "-0.1"), tilt), at("0.7", "1.6"));
        let base = collide_polygon_capsule(&rect(2, 2), xa, &capsule(), xb, Scalar::lit("0.1"));
        assert!(base.count > 0);
        for far in [Vector2::from_int(1_000_000, 1_000_000), Vector2::from_int(-1_000_000, -1_000_000)] {
            let m = collide_polygon_capsule(
                &rect(2, 2),
                Transform::new(xa.p + far, tilt),
                &capsule(),
                Transform::new(xb.p + far, xb.q),
                Scalar::lit("0.1"),
            );
            assert_eq!((m.count, m.normal), (base.count, base.normal));
            for (p, q) in m.points().iter().zip(base.points()) {
                assert_eq!(p.point, q.point + far);
                assert_eq!(
                    (p.anchor_a, p.anchor_b, p.separation, p.id),
                    (q.anchor_a, q.anchor_b, q.separation, q.id)
                );
            }
        }
    }
}
