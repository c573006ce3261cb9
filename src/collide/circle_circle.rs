//! Circle against circle: at most one point, on the line between the centres.

use super::manifold::{direction_and_length, half, LocalPoint, Manifold};
use crate::math::{Scalar, Transform, Vector2};

/// The contact between a circle of radius `radius_a` (m) centred on `xf_a.p` and
/// one of radius `radius_b` centred on `xf_b.p`.
///
/// Reports one point when the gap between the circles is at most `margin` (m, the
/// speculative distance, normally ≥ 0), an empty manifold otherwise. The normal
/// points from A's centre to B's; the point lies midway between the two surfaces
/// on that line; its `id` is always 0 (a circle has a single feature).
///
/// When the centres coincide exactly the direction is undefined: the normal is
/// then the x axis of A's rotation (`xf_a.q.x_axis()`), so the answer depends
/// only on the inputs. The centres are compared in A's local frame, so only the
/// distance between the bodies matters, never their absolute position.
#[must_use]
pub fn collide_circles(
    radius_a: Scalar,
    xf_a: Transform,
    radius_b: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let centre_b = xf_a.apply_inv(xf_b.p);
    let (normal, distance) = direction_and_length(centre_b).unwrap_or((Vector2::X, Scalar::ZERO));
    let separation = (distance - radius_a) - radius_b;
    if separation > margin {
        return Manifold::EMPTY;
    }
    // A's surface is at radius_a along the normal; B's is `separation` further.
    let point = normal * (radius_a + half(separation));
    let local = LocalPoint { point, separation, id: 0 };
    Manifold::from_local(xf_a, xf_b.p, normal, &[local], false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::test_support::{close, TOL};
    use crate::math::scalar::{from_int, ONE, ZERO};
    use crate::math::Rot;

    fn at(x: Scalar, y: Scalar) -> Transform {
        Transform::new(Vector2::new(x, y), Rot::IDENTITY)
    }

    #[test]
    fn unit_circles_one_and_a_half_apart_overlap_by_half() {
        let m = collide_circles(ONE, at(ZERO, ZERO), ONE, at(Scalar::lit("1.5"), ZERO), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::X);
        let p = m.points[0];
        assert_eq!(p.separation, Scalar::lit("-0.5"));
        assert_eq!(p.point, Vector2::new(Scalar::lit("0.75"), ZERO));
        assert_eq!(p.anchor_a, Vector2::new(Scalar::lit("0.75"), ZERO));
        assert_eq!(p.anchor_b, Vector2::new(Scalar::lit("-0.75"), ZERO));
        assert_eq!(p.id, 0);
    }

    #[test]
    fn far_from_the_origin_gives_the_same_relative_answer() {
        let far = from_int(1_000_000);
        let m = collide_circles(ONE, at(far, far), ONE, at(far, far + Scalar::lit("1.5")), ZERO);
        assert_eq!(m.normal, Vector2::Y);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.5"));
        assert_eq!(m.points[0].point, Vector2::new(far, far + Scalar::lit("0.75")));
    }

    #[test]
    fn the_margin_decides_speculative_contacts() {
        let gap = at(Scalar::lit("2.25"), ZERO);
        assert_eq!(collide_circles(ONE, at(ZERO, ZERO), ONE, gap, ZERO).count, 0);
        let m = collide_circles(ONE, at(ZERO, ZERO), ONE, gap, Scalar::lit("0.25"));
        assert_eq!(m.count, 1);
        assert_eq!(m.points[0].separation, Scalar::lit("0.25"));
        assert_eq!(m.points[0].point, Vector2::new(Scalar::lit("1.125"), ZERO));
        // Exactly touching with a zero margin is a contact (separation 0 ≤ margin).
        let touching = collide_circles(ONE, at(ZERO, ZERO), ONE, at(from_int(2), ZERO), ZERO);
        assert_eq!(touching.count, 1);
        assert_eq!(touching.points[0].separation, ZERO);
    }

    #[test]
    fn coincident_centres_use_the_x_axis_of_a() {
        let q = Rot::from_direction(Vector2::from_int(3, 4)).unwrap_or_default();
        let xf = Transform::new(Vector2::from_int(5, -7), q);
        let m = collide_circles(ONE, xf, from_int(2), xf, ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, q.x_axis()), "{:?}", m.normal);
        assert_eq!(m.points[0].separation, from_int(-3));
        // Midway between A's surface (+1 along the normal) and B's (−2).
        assert!(close(m.points[0].anchor_a, q.x_axis() * Scalar::lit("-0.5")));
    }

    #[test]
    fn nearly_coincident_centres_still_give_a_unit_normal() {
        let b = at(Scalar::from_bits(3), Scalar::from_bits(-4));
        let m = collide_circles(ONE, at(ZERO, ZERO), ONE, b, ZERO);
        let expected = Vector2::new(Scalar::lit("0.6"), Scalar::lit("-0.8"));
        assert!(close(m.normal, expected), "{:?}", m.normal);
    }

    #[test]
    fn swapping_the_circles_flips_the_normal_and_keeps_the_point() {
        let a = Transform::new(
            Vector2::from_int(1, 2),
            Rot::from_direction(Vector2::from_int(1, 1)).unwrap_or_default(),
        );
        let b = at(Scalar::lit("1.8"), Scalar::lit("2.9"));
        let ab = collide_circles(ONE, a, Scalar::lit("0.5"), b, ZERO);
        let ba = collide_circles(Scalar::lit("0.5"), b, ONE, a, ZERO);
        assert_eq!((ab.count, ba.count), (1, 1));
        assert!(close(ab.normal, -ba.normal));
        assert!(close(ab.points[0].point, ba.points[0].point));
        assert!((ab.points[0].separation - ba.points[0].separation).abs() < TOL);
        assert!(close(ab.points[0].anchor_a, ba.points[0].anchor_b));
    }
}
