//! Capsule or segment against circle: at most one point, on the line from the
//! closest point of the core segment to the circle's centre.

use super::manifold::{direction_and_length, half, LocalPoint, Manifold};
use crate::geometry::{Capsule, Segment};
use crate::math::{Scalar, Transform, Vector2};

/// The contact between a capsule (shape A, placed by `xf_a`) and a circle of
/// radius `radius` (m) centred on `xf_b.p` (shape B).
///
/// Reports one point when the gap is at most `margin` (m, the speculative
/// distance, normally ≥ 0), an empty manifold otherwise. The normal points from
/// the closest point of the capsule's core segment to the circle's centre; the
/// point lies midway between the two surfaces on that line; its `id` is always 0
/// (one point whose impulse varies continuously as the circle rolls from the
/// side round an end).
///
/// Degenerate cases: a capsule of zero length is a circle (the same contact as
/// [`collide_circles`](super::collide_circles) for a capsule centred on its body);
/// a circle centre exactly on the core segment takes the segment's right-hand
/// normal (that of `center1 → center2` turned −90°), or A's x axis when the
/// segment has no length either, so the answer depends only on the inputs.
#[must_use]
pub fn collide_capsule_circle(
    capsule: &Capsule,
    xf_a: Transform,
    radius: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    segment_circle(capsule.center1, capsule.center2, capsule.radius, xf_a, radius, xf_b, margin)
}

/// The contact between a segment (shape A, placed by `xf_a`) and a circle of
/// radius `radius` (m) centred on `xf_b.p` (shape B): a capsule of radius 0, see
/// [`collide_capsule_circle`].
///
/// The segment is two-sided: a circle on either side is pushed away from it.
#[must_use]
pub fn collide_segment_circle(
    segment: &Segment,
    xf_a: Transform,
    radius: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    segment_circle(segment.point1, segment.point2, Scalar::ZERO, xf_a, radius, xf_b, margin)
}

/// The closest point to `c` on the segment `p → q` (all in one frame), and the
/// segment's unit direction (zero for a segment of no length).
///
/// The parameter along the segment is clamped to its length, never divided by
/// it, so a zero-length segment gives `p`.
pub(crate) fn closest_on_segment(p: Vector2, q: Vector2, c: Vector2) -> (Vector2, Vector2) {
    let (u, length) = direction_and_length(q - p).unwrap_or((Vector2::ZERO, Scalar::ZERO));
    let along = u.dot(c - p).clamp(Scalar::ZERO, length);
    (p + u * along, u)
}

/// Segment `p → q` grown by `radius_a` (A, body-local) against a circle.
pub(crate) fn segment_circle(
    p: Vector2,
    q: Vector2,
    radius_a: Scalar,
    xf_a: Transform,
    radius_b: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let centre = xf_a.apply_inv(xf_b.p);
    let (closest, u) = closest_on_segment(p, q, centre);
    // On the core itself: the right-hand normal, or the x axis for a point.
    let fallback = if u.is_zero() { Vector2::X } else { u.right_perp() };
    let (normal, distance) = direction_and_length(centre - closest).unwrap_or((fallback, Scalar::ZERO));
    let separation = distance - (radius_a + radius_b);
    if separation > margin {
        return Manifold::EMPTY;
    }
    let point = closest + normal * (radius_a + half(separation));
    let local = LocalPoint { point, separation, id: 0 };
    Manifold::from_local(xf_a, xf_b.p, normal, &[local], false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::collide_circles;
    use crate::collide::test_support::{at, close, near, v};
    use crate::math::scalar::{from_int, ONE, ZERO};
    use crate::math::Rot;

    /// A horizontal capsule from (−1, 0) to (1, 0), radius 0.5.
    fn capsule() -> Capsule {
        Capsule { center1: v("-1", "0"), center2: v("1", "0"), radius: Scalar::lit("0.5") }
    }

    #[test]
    fn circle_resting_on_the_side_of_a_capsule() {
        // Circle radius 0.25 at (0.5, 0.7): the capsule's top is at y = 0.5,
        // the circle's bottom at 0.45: 0.05 deep, midway at y = 0.475.
        let m = collide_capsule_circle(&capsule(), at("0", "0"), Scalar::lit("0.25"), at("0.5", "0.7"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        let p = m.points[0];
        assert!(near(p.separation, Scalar::lit("-0.05")));
        assert!(close(p.point, v("0.5", "0.475")));
        assert!(close(p.anchor_b, v("0", "-0.225")));
        assert_eq!(p.id, 0);
    }

    #[test]
    fn circle_beyond_an_end_sees_the_end_cap() {
        // Centre (1.3, 0.4) from the end (1, 0): distance 0.5, radius sum 0.6.
        let m = collide_capsule_circle(&capsule(), at("0", "0"), Scalar::lit("0.1"), at("1.3", "0.4"), ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, v("0.6", "0.8")), "{:?}", m.normal);
        assert!(near(m.points[0].separation, Scalar::lit("-0.1")));
        // End + normal · (0.5 − 0.05).
        assert!(close(m.points[0].point, v("1.27", "0.36")), "{:?}", m.points[0].point);
    }

    #[test]
    fn the_margin_decides_speculative_contacts() {
        let (a, b) = (at("0", "0"), at("0", "1"));
        let r = Scalar::lit("0.25");
        // Gap 0.25.
        assert_eq!(collide_capsule_circle(&capsule(), a, r, b, Scalar::lit("0.2")).count, 0);
        let m = collide_capsule_circle(&capsule(), a, r, b, Scalar::lit("0.25"));
        assert_eq!(m.count, 1);
        assert_eq!(m.points[0].separation, Scalar::lit("0.25"));
        assert_eq!(m.points[0].point, v("0", "0.625"));
    }

    #[test]
    fn centre_on_the_core_takes_the_right_hand_normal() {
        let m = collide_capsule_circle(&capsule(), at("0", "0"), Scalar::lit("0.25"), at("0.3", "0"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, -Vector2::Y);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.75"));
        // A's surface 0.5 below, the circle's 0.25 above: midway −0.125.
        assert_eq!(m.points[0].point, v("0.3", "-0.125"));
    }

    #[test]
    fn zero_length_capsule_is_the_circle() {
        let q = Rot::from_direction(Vector2::from_int(3, 4)).unwrap_or_default();
        let xf_a = Transform::new(v("5", "-7"), q);
        let point = Capsule { center1: Vector2::ZERO, center2: Vector2::ZERO, radius: ONE };
        for b in [v("5.5", "-6.2"), v("5", "-7"), v("7", "-7"), v("5", "-9.1")] {
            let xf_b = Transform::new(b, Rot::IDENTITY);
            let m = collide_capsule_circle(&point, xf_a, Scalar::lit("0.5"), xf_b, Scalar::lit("0.6"));
            let c = collide_circles(ONE, xf_a, Scalar::lit("0.5"), xf_b, Scalar::lit("0.6"));
            assert_eq!(m, c, "{b:?}");
        }
    }

    #[test]
    fn segment_is_a_capsule_of_radius_zero_on_both_sides() {
        let seg = Segment { point1: v("-2", "0"), point2: v("2", "0") };
        let r = Scalar::lit("0.5");
        let up = collide_segment_circle(&seg, at("0", "0"), r, at("1", "0.4"), ZERO);
        assert_eq!(up.normal, Vector2::Y);
        assert_eq!(up.points[0].separation, Scalar::lit("-0.1"));
        assert_eq!(up.points[0].point, v("1", "-0.05"));
        let down = collide_segment_circle(&seg, at("0", "0"), r, at("1", "-0.4"), ZERO);
        assert_eq!(down.normal, -Vector2::Y);
        assert_eq!(down.points[0].separation, Scalar::lit("-0.1"));
        // A circle centre exactly on the segment: the right-hand normal (−y).
        let on = collide_segment_circle(&seg, at("0", "0"), r, at("1", "0"), ZERO);
        assert_eq!(on.normal, -Vector2::Y);
        assert_eq!(on.points[0].separation, -r);
        // A zero-length segment and a coincident centre: A's x axis.
        let dot = Segment { point1: v("1", "1"), point2: v("1", "1") };
        let m = collide_segment_circle(&dot, at("0", "0"), r, at("1", "1"), ZERO);
        assert_eq!((m.normal, m.points[0].separation), (Vector2::X, -r));
    }

    #[test]
    fn rotated_and_far_capsules_give_the_same_relative_answer() {
        // The capsule turned 90° (vertical) at (10, 20); circle to its right.
        let quarter = Rot { c: ZERO, s: ONE };
        let xf_a = Transform::new(Vector2::from_int(10, 20), quarter);
        let m = collide_capsule_circle(&capsule(), xf_a, Scalar::lit("0.25"), at("10.7", "20.5"), ZERO);
        assert!(close(m.normal, Vector2::X), "{:?}", m.normal);
        assert!(near(m.points[0].separation, Scalar::lit("-0.05")));
        assert!(close(m.points[0].point, v("10.475", "20.5")));
        let base =
            collide_capsule_circle(&capsule(), at("0", "0"), Scalar::lit("0.25"), at("0.8", "0.6"), ZERO);
        for far in [Vector2::from_int(1_000_000, -1_000_000), Vector2::from_int(-1_000_000, 1_000_000)] {
            let xa = Transform::new(far, Rot::IDENTITY);
            let xb = Transform::new(far + v("0.8", "0.6"), Rot::IDENTITY);
            let m = collide_capsule_circle(&capsule(), xa, Scalar::lit("0.25"), xb, ZERO);
            assert_eq!(m.normal, base.normal);
            assert_eq!(m.points[0].point, base.points[0].point + far);
            assert_eq!(m.points[0].separation, base.points[0].separation);
            assert_eq!(
                (m.points[0].anchor_a, m.points[0].anchor_b),
                (base.points[0].anchor_a, base.points[0].anchor_b)
            );
        }
        let _ = from_int(0);
    }
}
