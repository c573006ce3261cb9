//! Capsule against capsule (and segment against capsule): the closest points of
//! the two core segments, with a two-point contact when one capsule lies along
//! the other.
//!
//! 1. **Closest points** of the core segments, in closed form (no iteration):
//!    the unconstrained minimum of the distance, clamped to one segment, the
//!    other's parameter recomputed and clamped, then the first's again. Nothing
//!    is divided by a length, so a segment of no length (a capsule that is a
//!    circle) needs no special case, and parallel segments (a zero
//!    determinant) take the first segment's start.
//! 2. **Face or vertex.** When the closest point on A's core lies strictly
//!    inside it, or the closest-point direction is A's side normal (to within
//!    [`FACE_COSINE`]), A's side is a flat face there: B's core is clipped to the
//!    strip beside A's core and each end of the clipped part is a point, its
//!    separation measured along A's normal (exact: every point of that strip is
//!    that far from A's core). Otherwise the same with B's side, and otherwise
//!    the two closest points (an end of each) give one point along the line
//!    between them.
//!
//! Segments never collide with segments (as in Box2D), so a segment is only
//! ever the first shape here, as a capsule of radius 0.

use super::capsule_circle::segment_circle;
use super::manifold::{direction_and_length, half, LocalPoint, Manifold, MAX_MANIFOLD_POINTS};
use super::polygon_capsule::{flip, rebase_b};
use super::polygon_polygon::clip_end;
use crate::geometry::{Capsule, Segment};
use crate::math::{Scalar, Transform, Vector2};

/// Largest |cosine| (2^-16 ≈ 1.5e-5) between a core's direction and the line of
/// closest points for which that core's side still counts as the contact face,
/// although the closest point is one of its ends: two capsules stacked exactly
/// end over end have their closest points at the ends, and this keeps them a
/// two-point face contact. The value is a few hundred times the rounding of a
/// unit direction, and a far smaller angle than any a resting stack sees.
pub const FACE_COSINE: Scalar = Scalar::from_bits(1 << 16);

/// The contact between two capsules, A placed by `xf_a` and B by `xf_b`.
///
/// Reports up to two points when the capsules are at most `margin` apart (m, the
/// speculative distance, normally ≥ 0), an empty manifold otherwise. The normal
/// points from A to B: a side normal of A's core (the side B is on), the
/// negated side normal of B's, or for two ends the direction between them.
/// Points lie midway between the two surfaces.
///
/// # Feature ids
/// A face contact's two points are the ends of the overlap of the two cores,
/// named along A's core: id 0 at the end towards A's `center1`, id 1 towards
/// `center2`, whichever side is the face (so a capsule rocking on another keeps
/// its ids while the face passes from one to the other). An end-to-end point
/// has id 0 when A's closest point is its `center1`, 1 otherwise.
///
/// Degenerate input never divides by zero: a capsule of zero length is a
/// circle (the contact of [`collide_capsule_circle`](super::collide_capsule_circle)),
/// parallel cores take the first end of A's as their closest point's start,
/// and cores that cross (zero distance) take A's side normal towards B's
/// midpoint (the right-hand normal on a tie).
#[must_use]
pub fn collide_capsules(
    a: &Capsule,
    xf_a: Transform,
    b: &Capsule,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let core_a = Core { p: a.center1, q: a.center2, radius: a.radius };
    capsules(core_a, xf_a, b, xf_b, margin)
}

/// The contact between a segment (shape A, placed by `xf_a`) and a capsule
/// (shape B, placed by `xf_b`): the capsule contact of [`collide_capsules`] with
/// the segment as a capsule of radius 0 (two-sided; the same ids).
#[must_use]
pub fn collide_segment_capsule(
    segment: &Segment,
    xf_a: Transform,
    capsule: &Capsule,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let core_a = Core { p: segment.point1, q: segment.point2, radius: Scalar::ZERO };
    capsules(core_a, xf_a, capsule, xf_b, margin)
}

/// A core segment and its radius.
#[derive(Clone, Copy)]
struct Core {
    p: Vector2,
    q: Vector2,
    radius: Scalar,
}

/// The closest points of the segments `p1 + s·u1` (`0 ≤ s ≤ l1`) and
/// `p2 + t·u2` (`0 ≤ t ≤ l2`), `u1`, `u2` unit or zero: `(s, t)`.
///
/// Setting both partial derivatives of the squared distance to zero gives
/// `s − b·t = −c` and `t − b·s = f` (`b = u1·u2`, `c = u1·w`, `f = u2·w`,
/// `w = p1 − p2`), so `s = (b·f − c) / (1 − b²)`. That `s` is clamped, `t`
/// follows and is clamped, and if it was, `s` is recomputed from it (Ericson,
/// *Real-Time Collision Detection*, §5.1.9, in unit directions so no product
/// of two squared lengths can saturate).
pub(crate) fn closest_parameters(
    p1: Vector2,
    u1: Vector2,
    l1: Scalar,
    p2: Vector2,
    u2: Vector2,
    l2: Scalar,
) -> (Scalar, Scalar) {
    let zero = Scalar::ZERO;
    let w = p1 - p2;
    let (b, c, f) = (u1.dot(u2), u1.dot(w), u2.dot(w));
    let det = Scalar::ONE - b * b;
    // Parallel (or a zero direction with b = 0 giving det = 1): s from 0.
    let s = if det > zero { (b * f - c).div_or_zero(det).clamp(zero, l1) } else { zero };
    let t = b * s + f;
    if t < zero {
        ((-c).clamp(zero, l1), zero)
    } else if t > l2 {
        ((b * l2 - c).clamp(zero, l1), l2)
    } else {
        (s, t)
    }
}

/// The capsule contact with A's core `a` (body-local).
fn capsules(a: Core, xf_a: Transform, b: &Capsule, xf_b: Transform, margin: Scalar) -> Manifold {
    let zero = Scalar::ZERO;
    // A capsule of no length is a circle: the circle contact, to the bit.
    if b.center1 == b.center2 {
        let centre = Transform::new(xf_b.apply(b.center1), xf_b.q);
        let m = segment_circle(a.p, a.q, a.radius, xf_a, b.radius, centre, margin);
        return rebase_b(m, xf_b.p);
    }
    if a.p == a.q {
        let centre = Transform::new(xf_a.apply(a.p), xf_a.q);
        let m = segment_circle(b.center1, b.center2, b.radius, xf_b, a.radius, centre, margin);
        return flip(rebase_b(m, xf_a.p));
    }
    let b_in_a = xf_a.inv_mul(xf_b);
    let (p1, q1) = (a.p, a.q);
    let (p2, q2) = (b_in_a.apply(b.center1), b_in_a.apply(b.center2));
    let (u1, l1) = direction_and_length(q1 - p1).unwrap_or((Vector2::ZERO, zero));
    let (u2, l2) = direction_and_length(q2 - p2).unwrap_or((Vector2::ZERO, zero));
    let (s, t) = closest_parameters(p1, u1, l1, p2, u2, l2);
    let (c1, c2) = (p1 + u1 * s, p2 + u2 * t);
    let radius = a.radius + b.radius;
    let w = c2 - c1;
    let line = direction_and_length(w);
    let distance = line.map_or(zero, |(_, d)| d);
    if distance - radius > margin {
        return Manifold::EMPTY;
    }
    let along = |u: Vector2| line.is_some_and(|(n, _)| u.dot(n).abs() <= FACE_COSINE);
    let face_a = l1 > zero && ((s > zero && s < l1) || along(u1));
    let face_b = l2 > zero && ((t > zero && t < l2) || along(u2));

    let mut out = [LocalPoint::default(); MAX_MANIFOLD_POINTS];
    let (normal, count) = if face_a {
        // A's side facing B: B's core clipped to the strip beside A's.
        let n = side_normal(u1, w, (p2 - p1) + (q2 - p1));
        let ends = [(p2, q2), (q2, p2)].map(|(x, y)| (x, y, u1.dot(x - p1), u1.dot(y - p1)));
        let clipped = ends.map(|(x, y, tx, ty)| (clip_end(x, y, tx, ty, l1), tx));
        let point = |x: Vector2| {
            let separation = n.dot(x - p1) - radius;
            (x - n * (b.radius + half(separation)), separation)
        };
        (n, face_points(clipped, point, margin, &mut out))
    } else if face_b {
        // B's side facing A: A's core clipped to the strip beside B's.
        let n = side_normal(u2, -w, (p1 - p2) + (q1 - p2));
        let ends = [(p1, q1), (q1, p1)].map(|(x, y)| (x, y, u2.dot(x - p2), u2.dot(y - p2)));
        // A's own order: p1's end first (the lower along A's core).
        let clipped = ends.map(|(x, y, tx, ty)| (clip_end(x, y, tx, ty, l2), u1.dot(x - p1)));
        let point = |x: Vector2| {
            let separation = n.dot(x - p2) - radius;
            (x - n * (a.radius + half(separation)), separation)
        };
        (-n, face_points(clipped, point, margin, &mut out))
    } else {
        // An end of each (or a circle): along the line between the closest points.
        let fallback = if l1 > zero { u1.right_perp() } else { Vector2::X };
        let (n, _) = line.unwrap_or((fallback, zero));
        let separation = distance - radius;
        let point = c1 + n * (a.radius + half(separation));
        out[0] = LocalPoint { point, separation, id: u16::from(s > zero) };
        (n, 1)
    };
    let local = out.get(..count).unwrap_or(&[]);
    if local.is_empty() {
        return Manifold::EMPTY;
    }
    Manifold::from_local(xf_a, xf_b.p, normal, local, false)
}

/// The side normal of a core with direction `u` facing along `w` (the line from
/// this core's closest point to the other's); when that is zero (the cores
/// cross), facing along `towards` (twice the other core's midpoint), and the
/// right-hand normal on a tie.
fn side_normal(u: Vector2, w: Vector2, towards: Vector2) -> Vector2 {
    let n = u.right_perp();
    let side = n.dot(w);
    let side = if side == Scalar::ZERO { n.dot(towards) } else { side };
    if side < Scalar::ZERO {
        -n
    } else {
        n
    }
}

/// Writes the clipped ends (`(point on the clipped core, its coordinate along
/// A's core)`) as contact points, in A's core order with ids 0 and 1, keeping
/// those within `margin`; two ends at the same place are one point.
fn face_points(
    clipped: [(Vector2, Scalar); 2],
    point: impl Fn(Vector2) -> (Vector2, Scalar),
    margin: Scalar,
    out: &mut [LocalPoint; MAX_MANIFOLD_POINTS],
) -> usize {
    let [(x0, k0), (x1, k1)] = clipped;
    let ordered = if k1 < k0 { [x1, x0] } else { [x0, x1] };
    let mut count = 0;
    for (id, x) in (0u16..).zip(ordered) {
        if id == 1 && ordered[0] == ordered[1] {
            // The clipped core is a single point: one contact, not two.
            break;
        }
        let (p, separation) = point(x);
        if separation <= margin {
            if let Some(slot) = out.get_mut(count) {
                *slot = LocalPoint { point: p, separation, id };
                count += 1;
            }
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::collide_capsule_circle;
    use crate::collide::test_support::{at, close, near, v};
    use crate::math::scalar::{ONE, ZERO};
    use crate::math::Rot;

    /// A horizontal capsule from (−1, 0) to (1, 0), radius 0.5.
    fn capsule() -> Capsule {
        Capsule { center1: v("-1", "0"), center2: v("1", "0"), radius: Scalar::lit("0.5") }
    }

    fn tilt(t: &str) -> Rot {
        Rot::from_direction(v("1", t)).unwrap_or_default()
    }

    #[test]
    fn closest_parameters_of_crossing_parallel_and_skew_segments() {
        let (x, y) = (Vector2::X, Vector2::Y);
        let two = Scalar::from_int(2);
        // Crossing at (1, 0): s = 1 along A from the origin, t = 1 along B from (1, −1).
        assert_eq!(closest_parameters(Vector2::ZERO, x, two, v("1", "-1"), y, two), (ONE, ONE));
        // Parallel, B above and shifted right by 0.5: A's start is not on B's
        // span, so B's start (0.5 along A) is the closest point.
        let (s, t) = closest_parameters(Vector2::ZERO, x, two, v("0.5", "1"), x, two);
        assert_eq!((s, t), (Scalar::lit("0.5"), ZERO));
        // Beyond each other's ends: end to end.
        assert_eq!(closest_parameters(Vector2::ZERO, x, two, v("3", "1"), y, two), (two, ZERO));
        // A point (zero direction) against a segment.
        assert_eq!(closest_parameters(v("1", "1"), Vector2::ZERO, ZERO, Vector2::ZERO, x, two), (ZERO, ONE));
    }

    #[test]
    fn capsule_lying_on_a_capsule_gets_two_points() {
        // B 0.95 above A, shifted 0.5 right: 0.05 deep over x ∈ [−0.5, 1].
        let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), at("0.5", "0.95"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::Y);
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-0.05"));
            assert_eq!(p.point.y, Scalar::lit("0.475"));
        }
        assert_eq!((m.points[0].point.x, m.points[1].point.x), (Scalar::lit("-0.5"), ONE));
        assert_eq!((m.points[0].id, m.points[1].id), (0, 1));
        // Exactly end over end, and overhanging to the left (B's side is the
        // face then): the same two ids in the same order.
        for x in ["0", "-0.5", "0.25"] {
            let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), at(x, "0.95"), ZERO);
            assert_eq!((m.count, m.normal), (2, Vector2::Y), "{x}");
            assert_eq!((m.points[0].id, m.points[1].id), (0, 1), "{x}");
            assert_eq!(m.points[0].separation, Scalar::lit("-0.05"), "{x}");
        }
    }

    #[test]
    fn ids_hold_while_a_capsule_rocks_on_a_capsule() {
        for (x, t) in [("0.5", "0.002"), ("0.5", "-0.002"), ("-0.6", "0.001"), ("-0.6", "-0.001")] {
            let m = collide_capsules(
                &capsule(),
                at("0", "0"),
                &capsule(),
                Transform::new(v(x, "0.95"), tilt(t)),
                ZERO,
            );
            assert_eq!(m.count, 2, "{x} {t}");
            assert_eq!((m.points[0].id, m.points[1].id), (0, 1), "{x} {t}");
            assert!((m.normal - Vector2::Y).length() < Scalar::lit("0.003"), "{:?}", m.normal);
            assert!(m.points[0].point.x < m.points[1].point.x);
        }
    }

    #[test]
    fn capsule_standing_on_a_capsule_gets_one_point() {
        // B upright, its lower end centre 0.95 above A's core.
        let upright = Transform::new(v("0.3", "1.95"), Rot { c: ZERO, s: ONE });
        let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), upright, Scalar::lit("0.1"));
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        assert_eq!(m.points[0].separation, Scalar::lit("-0.05"));
        assert!(close(m.points[0].point, v("0.3", "0.475")), "{:?}", m.points[0].point);
    }

    #[test]
    fn end_to_end_capsules_meet_along_the_line_of_their_ends() {
        // Collinear, A's end (1, 0), B's start (2.2, 0): gap 0.2.
        let b = at("3.2", "0");
        assert_eq!(collide_capsules(&capsule(), at("0", "0"), &capsule(), b, Scalar::lit("0.1")).count, 0);
        let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), b, Scalar::lit("0.25"));
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::X);
        assert!(near(m.points[0].separation, Scalar::lit("0.2")));
        assert!(close(m.points[0].point, v("1.6", "0")));
        assert_eq!(m.points[0].id, 1);
        // Diagonal ends: (1, 0) and (1.3, 0.4), 0.5 apart, 0.5 deep.
        let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), at("2.3", "0.4"), ZERO);
        assert_eq!(m.count, 1);
        assert!(close(m.normal, v("0.6", "0.8")));
        assert!(near(m.points[0].separation, Scalar::lit("-0.5")));
    }

    #[test]
    fn crossing_capsules_push_apart_along_a_side() {
        // B upright through A's middle, its centre 0.1 above A's core.
        let upright = Transform::new(v("0", "0.1"), Rot { c: ZERO, s: ONE });
        let m = collide_capsules(&capsule(), at("0", "0"), &capsule(), upright, ZERO);
        assert!(m.count >= 1);
        assert_eq!(m.normal, Vector2::Y);
        // The deepest point is B's lower end, 0.9 below A's core: 1.9 deep.
        let deepest = m.points().iter().map(|p| p.separation).min().unwrap_or(ZERO);
        assert_eq!(deepest, Scalar::lit("-1.9"));
    }

    #[test]
    fn zero_length_capsules_are_circles() {
        let dot = Capsule { center1: Vector2::ZERO, center2: Vector2::ZERO, radius: Scalar::lit("0.3") };
        let xb = at("0.5", "0.6");
        // Against a capsule: the capsule–circle contact, seen from either side.
        let m = collide_capsules(&capsule(), at("0", "0"), &dot, xb, ZERO);
        let c = collide_capsule_circle(&capsule(), at("0", "0"), Scalar::lit("0.3"), xb, ZERO);
        assert_eq!(m, c);
        let m = collide_capsules(&dot, xb, &capsule(), at("0", "0"), ZERO);
        assert_eq!(m.normal, -c.normal);
        assert_eq!(m.points[0].separation, c.points[0].separation);
        assert_eq!(m.points[0].point, c.points[0].point);
        assert_eq!(
            (m.points[0].anchor_a, m.points[0].anchor_b),
            (c.points[0].anchor_b, c.points[0].anchor_a)
        );
        // Two coincident points: A's x axis.
        let m = collide_capsules(&dot, at("1", "1"), &dot, at("1", "1"), ZERO);
        assert_eq!((m.normal, m.points[0].separation), (Vector2::X, Scalar::lit("-0.6")));
    }

    #[test]
    fn segment_under_a_capsule() {
        let ground = Segment { point1: v("-5", "0"), point2: v("5", "0") };
        let m = collide_segment_capsule(&ground, at("0", "0"), &capsule(), at("1", "0.45"), ZERO);
        assert_eq!((m.count, m.normal), (2, Vector2::Y));
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-0.05"));
            assert_eq!(p.point.y, Scalar::lit("-0.025"));
        }
        assert_eq!((m.points[0].point.x, m.points[1].point.x), (ZERO, Scalar::from_int(2)));
        let under = collide_segment_capsule(&ground, at("0", "0"), &capsule(), at("1", "-0.45"), ZERO);
        assert_eq!((under.count, under.normal), (2, -Vector2::Y));
    }

    #[test]
    fn rotated_and_far_capsules_give_the_same_relative_answer() {
        let (xa, xb) =
            (Transform::new(v("0.1", "0.2"), tilt("0.3")), Transform::new(v("0.6", "1.1"), tilt("-0.2")));
        let base = collide_capsules(&capsule(), xa, &capsule(), xb, Scalar::lit("0.1"));
        assert!(base.count > 0);
        // The whole scene turned a quarter turn: the normal turns with it.
        let quarter = Rot { c: ZERO, s: ONE };
        let turn = |x: Transform| Transform::new(quarter.rotate(x.p), quarter.compose(x.q));
        let turned = collide_capsules(&capsule(), turn(xa), &capsule(), turn(xb), Scalar::lit("0.1"));
        assert_eq!(turned.count, base.count);
        assert!(close(turned.normal, quarter.rotate(base.normal)));
        for (p, q) in turned.points().iter().zip(base.points()) {
            assert!(close(p.point, quarter.rotate(q.point)));
            assert!(near(p.separation, q.separation));
            assert_eq!(p.id, q.id);
        }
        for far in [Vector2::from_int(1_000_000, -1_000_000), Vector2::from_int(-1_000_000, 1_000_000)] {
            let m = collide_capsules(
                &capsule(),
                Transform::new(xa.p + far, xa.q),
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
