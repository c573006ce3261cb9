//! Convex polygon against circle: at most one point, against the polygon's
//! closest face or vertex.

use super::manifold::{direction_and_length, half, LocalPoint, Manifold};
use super::{next_index, Direction};
use crate::geometry::PolygonPath;
use crate::math::{Scalar, Transform};

/// The contact between a convex polygon (shape A, placed by `xf_a`) and a circle
/// of radius `radius_b` (m) centred on `xf_b.p` (shape B).
///
/// Reports one point when the gap is at most `margin` (m, the speculative
/// distance, normally ≥ 0), an empty manifold otherwise. The normal points from
/// the polygon towards the circle:
/// - circle centre outside the polygon, nearest a face: that face's normal;
/// - nearest a vertex: the direction from the vertex to the centre, and the
///   separation is measured from the vertex;
/// - centre on or inside the polygon: the normal of the face the centre is
///   closest to (least penetration), so the circle is pushed out the short way.
///
/// A rounded polygon ([`PolygonPath::rounding`] > 0) is its core grown by the
/// rounding radius: the distances above are the core's, less both radii.
///
/// Ties between faces go to the lower edge index. The point lies midway between
/// the polygon's surface and the circle's, and its `id` is always 0: a single
/// point whose impulse varies continuously as the circle rolls from a face
/// around a vertex, so keeping one id keeps warm starting across the change.
#[must_use]
pub fn collide_polygon_circle(
    poly: &PolygonPath,
    xf_a: Transform,
    radius_b: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let centre = xf_a.apply_inv(xf_b.p);
    let vertices = poly.vertices();
    let normals = poly.normals();

    // The face whose outward side the centre is farthest on (strict `>`: the
    // first of equal faces wins).
    let mut best: Option<(usize, Scalar)> = None;
    for (i, (v, n)) in vertices.iter().zip(normals).enumerate() {
        let s = Direction::of(*n).dot(centre - *v);
        if best.is_none_or(|(_, b)| s > b) {
            best = Some((i, s));
        }
    }
    let Some((edge, face_separation)) = best else {
        return Manifold::EMPTY;
    };
    // A rounded polygon's surface lies `rounding` out from its core: the core
    // may be that much farther away (the sum is exact; 0 for a sharp polygon).
    let radius = poly.rounding + radius_b;
    // The distance to the polygon is at least the face separation: far enough ⇒ done.
    if face_separation > radius + margin {
        return Manifold::EMPTY;
    }
    let (Some(&v1), Some(&v2), Some(&face_normal)) =
        (vertices.get(edge), vertices.get(next_index(edge, vertices.len())), normals.get(edge))
    else {
        return Manifold::EMPTY;
    };

    // Outside the face line, the closest feature is this face or one of its two
    // vertices (for a convex polygon the face of greatest separation is always
    // adjacent to the closest vertex). Beyond an end of the edge ⇒ that vertex.
    let corner = if face_separation > Scalar::ZERO {
        if (centre - v1).dot(v2 - v1) < Scalar::ZERO {
            Some(v1)
        } else if (centre - v2).dot(v1 - v2) < Scalar::ZERO {
            Some(v2)
        } else {
            None
        }
    } else {
        None
    };

    let (normal, surface_a, distance) = match corner
        .and_then(|v| direction_and_length(centre - v).map(|(n, d)| (n, v, d)))
    {
        Some(found) => found,
        // Face region, or the centre inside: project the centre onto the face.
        None => (face_normal, centre - Direction::of(face_normal).scale(face_separation), face_separation),
    };
    let separation = distance - radius;
    if separation > margin {
        return Manifold::EMPTY;
    }
    let offset = poly.rounding + half(separation);
    let local = LocalPoint { point: surface_a + Direction::of(normal).scale(offset), separation, id: 0 };
    Manifold::from_local(xf_a, xf_b.p, normal, &[local], false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::test_support::{at, close, near};
    use crate::math::scalar::{from_int, ONE, ZERO};
    use crate::math::{Rot, Vector2};

    /// A 4 m × 2 m box.
    fn box_4x2() -> PolygonPath {
        PolygonPath::rectangle(from_int(4), from_int(2)).unwrap_or_else(|_| unreachable!())
    }

    #[test]
    fn circle_resting_into_the_top_face() {
        let m = collide_polygon_circle(&box_4x2(), at("0", "0"), Scalar::lit("0.5"), at("1", "1.25"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        let p = m.points[0];
        assert_eq!(p.separation, Scalar::lit("-0.25"));
        // Face at y = 1, circle bottom at y = 0.75: midway y = 0.875.
        assert_eq!(p.point, Vector2::new(ONE, Scalar::lit("0.875")));
        assert_eq!(p.anchor_b, Vector2::new(ZERO, Scalar::lit("-0.375")));
    }

    #[test]
    fn circle_against_a_corner_uses_the_vertex_direction() {
        // Corner (2, 1); centre at (2.3, 1.4): distance 0.5, radius 0.6.
        let m = collide_polygon_circle(&box_4x2(), at("0", "0"), Scalar::lit("0.6"), at("2.3", "1.4"), ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, Vector2::new(Scalar::lit("0.6"), Scalar::lit("0.8"))), "{:?}", m.normal);
        let p = m.points[0];
        assert!(near(p.separation, Scalar::lit("-0.1")), "{:?}", p.separation);
        // Corner + normal · (−0.05).
        assert!(close(p.point, Vector2::new(Scalar::lit("1.97"), Scalar::lit("0.96"))), "{:?}", p.point);
    }

    #[test]
    fn corner_gap_counts_the_true_distance_not_the_face_distance() {
        // Both faces are 0.3 away, the corner 0.3·√2 ≈ 0.424.
        let xf_b = at("2.3", "1.3");
        let r = Scalar::lit("0.1");
        assert_eq!(collide_polygon_circle(&box_4x2(), at("0", "0"), r, xf_b, Scalar::lit("0.3")).count, 0);
        let m = collide_polygon_circle(&box_4x2(), at("0", "0"), r, xf_b, Scalar::lit("0.33"));
        assert_eq!(m.count, 1);
        assert!(near(m.points[0].separation, Scalar::lit("0.324264068711928")));
    }

    #[test]
    fn centre_inside_pushes_out_through_the_nearest_face() {
        // Inside, 0.25 from the right face (x = 2) and 0.75 from the top.
        let m =
            collide_polygon_circle(&box_4x2(), at("0", "0"), Scalar::lit("0.5"), at("1.75", "0.25"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::X);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.75"));
        assert_eq!(m.points[0].point, Vector2::new(Scalar::lit("1.625"), Scalar::lit("0.25")));
    }

    #[test]
    fn centre_exactly_at_the_polygon_centre_picks_the_first_least_deep_face() {
        // Square: every face is 1 m away; the tie goes to edge 0 (normal −y).
        let square = PolygonPath::rectangle(from_int(2), from_int(2)).unwrap_or_else(|_| unreachable!());
        let m = collide_polygon_circle(&square, at("3", "3"), Scalar::lit("0.5"), at("3", "3"), ZERO);
        assert_eq!(m.normal, -Vector2::Y);
        assert_eq!(m.points[0].separation, Scalar::lit("-1.5"));
    }

    #[test]
    fn centre_exactly_on_a_corner() {
        let m = collide_polygon_circle(&box_4x2(), at("0", "0"), Scalar::lit("0.5"), at("2", "1"), ZERO);
        assert_eq!(m.count, 1);
        // Separation 0 on two faces: the first (edge 1, normal +x) is chosen.
        assert_eq!(m.normal, Vector2::X);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.5"));
    }

    #[test]
    fn rotated_polygon_results_come_back_in_world_space() {
        // The box turned 90°: its long side is vertical, x half-extent 1.
        let xf_a = Transform::new(Vector2::from_int(10, 20), Rot { c: ZERO, s: ONE });
        let m = collide_polygon_circle(&box_4x2(), xf_a, Scalar::lit("0.5"), at("11.25", "21"), ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, Vector2::X));
        assert_eq!(m.points[0].separation, Scalar::lit("-0.25"));
        assert!(close(m.points[0].point, Vector2::new(Scalar::lit("10.875"), from_int(21))));
        assert!(close(m.points[0].anchor_a, Vector2::new(Scalar::lit("0.875"), ONE)));
    }
}
