//! A chain's link (a one-sided segment with ghost vertices) against a circle,
//! a capsule or a polygon.
//!
//! Each function first takes the two-sided segment contact, then applies the
//! link's two rules:
//! 1. **One side.** A shape whose centre is behind the link (on its solid,
//!    left side) gets no contact: it is inside the chain's solid or beyond
//!    its edge, and the neighbouring links answer for it.
//! 2. **Admissible normals.** The normal (in the link's frame) must be the
//!    link's own outward normal (to within [`CHAIN_FACE_SINE`]) or lie in the
//!    link's half of the vertex cone of a convex join (between its normal and
//!    the bisector with the neighbour's; the shared bisector goes to the link
//!    after the join, so exactly one link owns every direction). At a flat or
//!    concave join there is no vertex cone: any other normal is a ghost, the
//!    internal edge seen from the wrong side (a box sliding over a seam whose
//!    side face the next link's end pokes into). A ghost normal is replaced by
//!    the link's face: the shape's edge facing the link, clipped to the strip
//!    beside it, with separations along the link's normal (nothing when that
//!    edge lies beside the strip: the neighbour has it). A circle has no edge
//!    to clip: its ghost contact is dropped (its centre is then beside the
//!    strip, where the neighbour's face contact holds it). A ghost equal to
//!    its end (an open chain's first or last point) is a free end: every
//!    normal on the link's front side is admitted there.
//!
//! Box2D v3 has the same rules (`b2CollideChainSegmentAndPolygon`, its smooth
//! segment cases); this is our own formulation of them.

use super::manifold::{direction_and_length, half, LocalPoint, Manifold, MAX_MANIFOLD_POINTS};
use super::polygon_polygon::clip_end;
use super::ChainSegment;
use super::{collide_segment_capsule, collide_segment_circle, collide_segment_polygon, next_index};
use crate::geometry::{Capsule, PolygonPath, MAX_POLYGON_VERTICES};
use crate::math::{Scalar, Transform, Vector2};

/// Largest |sine| (2^-16 ≈ 1.5e-5) between a contact normal and the link's own
/// normal for which it still counts as the face normal: a few hundred times
/// the rounding of a rotated unit vector, far below any real corner.
pub const CHAIN_FACE_SINE: Scalar = Scalar::from_bits(1 << 16);

/// The contact between a chain link (shape A, placed by `xf_a`) and a circle of
/// radius `radius` (m) centred on `xf_b.p` (shape B): that of
/// [`collide_segment_circle`] when the centre is in front of the link and the
/// normal is admissible (see the module docs), else none.
#[must_use]
pub fn collide_chain_segment_circle(
    chain: &ChainSegment,
    xf_a: Transform,
    radius: Scalar,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let Some(link) = Link::of(chain) else { return Manifold::EMPTY };
    if link.behind(xf_a.apply_inv(xf_b.p)) {
        return Manifold::EMPTY;
    }
    let m = collide_segment_circle(&chain.segment, xf_a, radius, xf_b, margin);
    if m.count == 0 || link.admits(xf_a.q.inv_rotate(m.normal)) {
        m
    } else {
        Manifold::EMPTY
    }
}

/// The contact between a chain link (shape A, placed by `xf_a`) and a capsule
/// (shape B, placed by `xf_b`): that of [`collide_segment_capsule`] (its ids
/// too) when the capsule's centre is in front of the link and the normal is
/// admissible; a ghost normal gives the face contact against the link instead
/// (see the module docs), with ids 0 and 1 along the link as
/// [`collide_capsules`](super::collide_capsules) names them.
#[must_use]
pub fn collide_chain_segment_capsule(
    chain: &ChainSegment,
    xf_a: Transform,
    capsule: &Capsule,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let Some(link) = Link::of(chain) else { return Manifold::EMPTY };
    let b_in_a = xf_a.inv_mul(xf_b);
    let (c1, c2) = (b_in_a.apply(capsule.center1), b_in_a.apply(capsule.center2));
    if link.behind(c1 + (c2 - c1) * Scalar::HALF) {
        return Manifold::EMPTY;
    }
    let m = collide_segment_capsule(&chain.segment, xf_a, capsule, xf_b, margin);
    if m.count == 0 || link.admits(xf_a.q.inv_rotate(m.normal)) {
        return m;
    }
    let Some((u, _)) = direction_and_length(c2 - c1) else { return Manifold::EMPTY };
    let side = u.right_perp();
    let core = Incident { vertices: [c1, c2], normals: [side, -side], count: 2, radius: capsule.radius };
    link.face_contact(&core, xf_a, xf_b.p, margin, Ids::AlongLink)
}

/// The contact between a chain link (shape A, placed by `xf_a`) and a convex
/// polygon (shape B, placed by `xf_b`, rounded or not): that of
/// [`collide_segment_polygon`] (its ids too: the link's front is edge 0) when the
/// polygon's centre is in front of the link and the normal is admissible; a
/// ghost normal gives the face contact against the link instead (see the
/// module docs), with the ids [`collide_polygons`](super::collide_polygons)
/// gives a face contact on the link's edge 0.
///
/// A box sliding across the join of two collinear links gets only the links'
/// normal from either.
#[must_use]
pub fn collide_chain_segment_polygon(
    chain: &ChainSegment,
    xf_a: Transform,
    poly: &PolygonPath,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    let Some(link) = Link::of(chain) else { return Manifold::EMPTY };
    let b_in_a = xf_a.inv_mul(xf_b);
    if link.behind(b_in_a.p) {
        return Manifold::EMPTY;
    }
    let m = collide_segment_polygon(&chain.segment, xf_a, poly, xf_b, margin);
    if m.count == 0 || link.admits(xf_a.q.inv_rotate(m.normal)) {
        return m;
    }
    let mut core = Incident {
        vertices: [Vector2::ZERO; MAX_POLYGON_VERTICES],
        normals: [Vector2::ZERO; MAX_POLYGON_VERTICES],
        count: poly.vertices().len().min(poly.normals().len()),
        radius: poly.rounding,
    };
    for ((v, n), (sv, sn)) in
        poly.vertices().iter().zip(poly.normals()).zip(core.vertices.iter_mut().zip(core.normals.iter_mut()))
    {
        *sv = b_in_a.apply(*v);
        *sn = b_in_a.q.rotate(*n);
    }
    link.face_contact(&core, xf_a, xf_b.p, margin, Ids::Polygon)
}

/// How a face contact against the link names its points.
#[derive(Clone, Copy)]
enum Ids {
    /// As [`collide_polygons`](super::collide_polygons) names a face contact
    /// with A's edge 0 as reference: B's edge in bits 4–7, bit 0 clear at the
    /// incident edge's end vertex (the end towards the link's `point1`), set at
    /// its start vertex; that end first.
    Polygon,
    /// As [`collide_capsules`](super::collide_capsules) does: 0 at the end
    /// towards the link's `point1`, 1 at the other; in that order.
    AlongLink,
}

/// The other shape's core in the link's frame: vertices, edge normals, the
/// number in use, and its radius.
struct Incident<const N: usize> {
    vertices: [Vector2; N],
    normals: [Vector2; N],
    count: usize,
    radius: Scalar,
}

/// A link of non-zero length in its own body's frame.
struct Link {
    p1: Vector2,
    p2: Vector2,
    ghost1: Vector2,
    ghost2: Vector2,
    /// Unit direction `p1 → p2`.
    u: Vector2,
    /// Outward normal (`u` turned −90°).
    n: Vector2,
    length: Scalar,
}

impl Link {
    fn of(chain: &ChainSegment) -> Option<Self> {
        let (p1, p2) = (chain.segment.point1, chain.segment.point2);
        let (u, length) = direction_and_length(p2 - p1)?;
        Some(Self { p1, p2, ghost1: chain.ghost1, ghost2: chain.ghost2, u, n: u.right_perp(), length })
    }

    /// `c` lies on the solid side of the link's line.
    fn behind(&self, c: Vector2) -> bool {
        self.n.dot(c - self.p1) < Scalar::ZERO
    }

    /// The link owns contacts with normal `nl` (link frame, unit).
    fn admits(&self, nl: Vector2) -> bool {
        let zero = Scalar::ZERO;
        if self.n.dot(nl) <= zero {
            return false;
        }
        let along = self.u.dot(nl);
        if along.abs() <= CHAIN_FACE_SINE {
            return true;
        }
        if along > zero {
            // Past p2: the join with the next link, convex when it turns left.
            let next = self.ghost2 - self.p2;
            // A free end (an open chain's last point): a corner turned all
            // the way, every front normal is the link's.
            let Some((w, _)) = direction_and_length(next) else { return true };
            self.u.cross(next) > zero && nl.dot(self.n) >= nl.dot(w.right_perp())
        } else {
            let previous = self.p1 - self.ghost1;
            let Some((w, _)) = direction_and_length(previous) else { return true };
            previous.cross(self.u) > zero && nl.dot(self.n) > nl.dot(w.right_perp())
        }
    }

    /// The face contact of `core` against the link: its edge most opposed to
    /// the link's normal (the first on a tie) clipped to the strip beside the
    /// link, the points named by `ids`.
    fn face_contact<const N: usize>(
        &self,
        core: &Incident<N>,
        xf_a: Transform,
        position_b: Vector2,
        margin: Scalar,
        ids: Ids,
    ) -> Manifold {
        let count = core.count.min(N);
        let mut edge: Option<(usize, Scalar)> = None;
        for (k, m) in core.normals.iter().take(count).enumerate() {
            let d = m.dot(self.n);
            if edge.is_none_or(|(_, b)| d < b) {
                edge = Some((k, d));
            }
        }
        let Some((k, _)) = edge else { return Manifold::EMPTY };
        let (Some(&i1), Some(&i2)) = (core.vertices.get(k), core.vertices.get(next_index(k, count))) else {
            return Manifold::EMPTY;
        };
        let (t1, t2) = (self.u.dot(i1 - self.p1), self.u.dot(i2 - self.p1));
        let zero = Scalar::ZERO;
        if (t1 < zero && t2 < zero) || (t1 > self.length && t2 > self.length) {
            return Manifold::EMPTY;
        }
        let x1 = clip_end(i1, i2, t1, t2, self.length);
        let x2 = clip_end(i2, i1, t2, t1, self.length);
        let ends = match ids {
            Ids::Polygon => {
                let base = (k as u16 & 0xF) << 4;
                [(x2, base), (x1, base | 1)]
            }
            Ids::AlongLink if t1 < t2 => [(x1, 0), (x2, 1)],
            Ids::AlongLink => [(x2, 0), (x1, 1)],
        };
        let mut out = [LocalPoint::default(); MAX_MANIFOLD_POINTS];
        let mut n_out = 0;
        for (j, (x, id)) in ends.into_iter().enumerate() {
            if j == 1 && x1 == x2 {
                break;
            }
            let separation = self.n.dot(x - self.p1) - core.radius;
            if separation <= margin {
                if let Some(slot) = out.get_mut(n_out) {
                    let point = x - self.n * (core.radius + half(separation));
                    *slot = LocalPoint { point, separation, id };
                    n_out += 1;
                }
            }
        }
        let local = out.get(..n_out).unwrap_or(&[]);
        if local.is_empty() {
            return Manifold::EMPTY;
        }
        Manifold::from_local(xf_a, position_b, self.n, local, false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::test_support::{at, close, v};
    use crate::geometry::Segment;
    use crate::math::scalar::{from_int, ONE, ZERO};
    use crate::math::Rot;

    /// Link `k` of flat ground at y = 0, running right to left (so its
    /// outward normal is +y) over x ∈ [k, k + 1], its neighbours collinear.
    fn ground_link(k: i32) -> ChainSegment {
        ChainSegment {
            ghost1: Vector2::from_int(k + 2, 0),
            segment: Segment { point1: Vector2::from_int(k + 1, 0), point2: Vector2::from_int(k, 0) },
            ghost2: Vector2::from_int(k - 1, 0),
        }
    }

    fn unit_box() -> PolygonPath {
        PolygonPath::rectangle(ONE, ONE).unwrap_or_else(|_| unreachable!())
    }

    #[test]
    fn a_box_sliding_across_a_flat_join_gets_only_the_up_normal() {
        let (left, right) = (ground_link(0), ground_link(1));
        let bx = unit_box();
        let mut contacts = 0;
        for step in 0..=140 {
            // Centre from x = 0.3 to 1.7 by 1 cm, 5 mm deep, tilted a little
            // either way.
            let x = Scalar::lit("0.3") + Scalar::lit("0.01") * from_int(step);
            for tilt in ["0", "0.002", "-0.002"] {
                let q = Rot::from_direction(v("1", tilt)).unwrap_or_default();
                let xf_b = Transform::new(Vector2::new(x, Scalar::lit("0.495")), q);
                let mut here = 0;
                for link in [&left, &right] {
                    let m = collide_chain_segment_polygon(link, at("0", "0"), &bx, xf_b, Scalar::lit("0.01"));
                    if m.count > 0 {
                        assert_eq!(m.normal, Vector2::Y, "x {x:?} tilt {tilt}");
                        here += m.count;
                    }
                }
                assert!(here >= 1, "x {x:?} tilt {tilt}: no support");
                contacts += here;
            }
        }
        assert!(contacts > 400, "{contacts}");
    }

    #[test]
    fn the_plain_segment_catches_where_the_link_does_not() {
        // The box's right bottom corner 2 mm past the join, 5 mm deep: the
        // right link's end pokes 2 mm into the box's side face, which a
        // two-sided segment takes as the reference (a normal pushing back);
        // the link gives the up normal, its face clipped to the 2 mm strip.
        let right = ground_link(1);
        let xf_b = at("0.502", "0.495");
        let plain = collide_segment_polygon(&right.segment, at("0", "0"), &unit_box(), xf_b, ZERO);
        assert!(plain.count > 0 && plain.normal.x < Scalar::lit("-0.9"), "{:?}", plain.normal);
        let m = collide_chain_segment_polygon(&right, at("0", "0"), &unit_box(), xf_b, ZERO);
        assert_eq!(m.normal, Vector2::Y);
        assert_eq!(m.count, 2);
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-0.005"));
            assert!(p.point.x >= ONE && p.point.x <= Scalar::lit("1.002"), "{:?}", p.point);
        }
        // The ids are those of a face contact on the link's edge 0 with the
        // box's bottom (edge 0).
        assert_eq!((m.points[0].id, m.points[1].id), (0x000, 0x001));
    }

    #[test]
    fn only_the_front_side_collides() {
        let link = ground_link(0);
        let below = at("0.5", "-0.45");
        assert_eq!(collide_chain_segment_polygon(&link, at("0", "0"), &unit_box(), below, ONE).count, 0);
        assert_eq!(
            collide_chain_segment_circle(&link, at("0", "0"), Scalar::lit("0.5"), below, ONE).count,
            0
        );
        let cap = Capsule { center1: v("-0.5", "0"), center2: v("0.5", "0"), radius: Scalar::lit("0.5") };
        assert_eq!(collide_chain_segment_capsule(&link, at("0", "0"), &cap, below, ONE).count, 0);
        // The same shapes above: contacts with the up normal.
        let above = at("0.5", "0.45");
        let m = collide_chain_segment_polygon(&link, at("0", "0"), &unit_box(), above, ZERO);
        assert_eq!((m.count, m.normal), (2, Vector2::Y));
        let m = collide_chain_segment_circle(&link, at("0", "0"), Scalar::lit("0.5"), above, ZERO);
        assert_eq!((m.count, m.normal), (1, Vector2::Y));
        let m = collide_chain_segment_capsule(&link, at("0", "0"), &cap, above, ZERO);
        assert_eq!((m.count, m.normal), (2, Vector2::Y));
    }

    #[test]
    fn a_circle_over_a_convex_corner_is_owned_by_exactly_one_link() {
        // A step down to the left: the top link ends at (0, 0), the wall link
        // runs from (0, 0) down to (0, −1) (outward normal −x).
        let top = ChainSegment {
            ghost1: v("2", "0"),
            segment: Segment { point1: v("1", "0"), point2: v("0", "0") },
            ghost2: v("0", "-1"),
        };
        let wall = ChainSegment {
            ghost1: v("1", "0"),
            segment: Segment { point1: v("0", "0"), point2: v("0", "-1") },
            ghost2: v("-1", "-1"),
        };
        let r = Scalar::lit("0.6");
        for (centre, owner, normal) in
            [(at("-0.3", "0.4"), 0, v("-0.6", "0.8")), (at("-0.4", "0.3"), 1, v("-0.8", "0.6"))]
        {
            let ms = [
                collide_chain_segment_circle(&top, at("0", "0"), r, centre, ZERO),
                collide_chain_segment_circle(&wall, at("0", "0"), r, centre, ZERO),
            ];
            for (k, m) in ms.iter().enumerate() {
                assert_eq!(m.count, usize::from(k == owner), "link {k}");
            }
            assert!(close(ms[owner].normal, normal), "{:?}", ms[owner].normal);
        }
        // Exactly on the bisector: the link after the join (the wall) owns it.
        let diagonal = at("-0.35", "0.35");
        let top_m = collide_chain_segment_circle(&top, at("0", "0"), r, diagonal, ZERO);
        let wall_m = collide_chain_segment_circle(&wall, at("0", "0"), r, diagonal, ZERO);
        assert_eq!(top_m.count + wall_m.count, 1);
    }

    #[test]
    fn a_circle_rolling_over_a_flat_join_never_sees_the_corner() {
        let (left, right) = (ground_link(0), ground_link(1));
        let r = Scalar::lit("0.25");
        for step in 0..=100 {
            let x = Scalar::lit("0.5") + Scalar::lit("0.01") * from_int(step);
            let xf_b = Transform::new(Vector2::new(x, Scalar::lit("0.249")), Rot::IDENTITY);
            let mut support = 0;
            for link in [&left, &right] {
                let m = collide_chain_segment_circle(link, at("0", "0"), r, xf_b, ZERO);
                if m.count > 0 {
                    // (Up to the rounding of a vertex direction a hair past
                    // the join, within the face tolerance.)
                    assert!(close(m.normal, Vector2::Y), "{x:?} {:?}", m.normal);
                    support += 1;
                }
            }
            assert!(support >= 1, "{x:?}");
        }
    }

    #[test]
    fn a_capsule_lying_across_a_flat_join_gets_only_the_up_normal() {
        let (left, right) = (ground_link(0), ground_link(1));
        let cap = Capsule { center1: v("-0.5", "0"), center2: v("0.5", "0"), radius: Scalar::lit("0.25") };
        for step in 0..=100 {
            let x = Scalar::lit("0.5") + Scalar::lit("0.01") * from_int(step);
            for tilt in ["0", "0.003", "-0.003"] {
                let q = Rot::from_direction(v("1", tilt)).unwrap_or_default();
                let xf_b = Transform::new(Vector2::new(x, Scalar::lit("0.248")), q);
                let mut support = 0;
                for link in [&left, &right] {
                    let m =
                        collide_chain_segment_capsule(link, at("0", "0"), &cap, xf_b, Scalar::lit("0.01"));
                    if m.count > 0 {
                        assert!(
                            (m.normal - Vector2::Y).length() < Scalar::lit("0.004"),
                            "{x:?} {tilt} {:?}",
                            m.normal
                        );
                        support += m.count;
                    }
                }
                assert!(support >= 1, "{x:?} {tilt}");
            }
        }
    }
}
