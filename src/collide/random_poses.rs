//! Random poses of every pair with a rounded shape: the contract checked
//! against a brute-force distance.
//!
//! Each shape is a convex core (point, segment or polygon) grown by a radius.
//! The reference gap is computed in `f64` from the cores' vertices and edges
//! (apart, two convex cores are closest at a vertex of one and an edge of the
//! other, so the minimum over all such pairs is the distance), less both
//! radii. Checked for every pose: no panic, at most two points, a unit normal
//! (to 1e-6), and when the cores are apart by more than 1 cm:
//! * a gap more than the tolerance below the margin gives a contact whose
//!   least separation is the gap to within the tolerance;
//! * a gap more than the tolerance above the margin gives none.
//!
//! The tolerance is [`TOL`] for the closest-point pairs, and that plus
//! [`REFERENCE_FACE_TOLERANCE`] when the contact has a reference face
//! (polygon–polygon, and a capsule or segment against a polygon): A's face is
//! kept while B's is better by less than that, and the reported separation can
//! then exceed the least by that much (documented at the constant).
//!
//! Overlapping cores must give a contact with a negative separation.

use super::toi::{time_of_impact, Swept};
use super::*;
use crate::geometry::{Capsule, PolygonPath, Segment};
use crate::math::{Rot, Scalar, Transform, Vector2};

/// Agreement with the brute-force gap (m): fixed-point rounding of rotations
/// and square roots is a few units of 2^-32 m per operation; 1e-6 m leaves a
/// wide margin for shapes of a few metres.
const TOL: f64 = 1e-6;

#[derive(Clone, Copy)]
enum Shape<'a> {
    Circle(Scalar),
    Capsule(&'a Capsule),
    Segment(&'a Segment),
    Polygon(&'a PolygonPath),
}

/// The core's world vertices (f64) and its radius.
fn core(shape: Shape<'_>, xf: Transform) -> (Vec<(f64, f64)>, f64) {
    let place = |v: Vector2| {
        let w = xf.apply(v);
        (w.x.to_f64(), w.y.to_f64())
    };
    match shape {
        Shape::Circle(r) => (vec![place(Vector2::ZERO)], r.to_f64()),
        Shape::Capsule(c) => (vec![place(c.center1), place(c.center2)], c.radius.to_f64()),
        Shape::Segment(s) => (vec![place(s.point1), place(s.point2)], 0.0),
        Shape::Polygon(p) => (p.vertices().iter().map(|v| place(*v)).collect(), p.rounding.to_f64()),
    }
}

fn edges(vs: &[(f64, f64)]) -> Vec<((f64, f64), (f64, f64))> {
    match vs.len() {
        1 => vec![(vs[0], vs[0])],
        2 => vec![(vs[0], vs[1])],
        n => (0..n).map(|i| (vs[i], vs[(i + 1) % n])).collect(),
    }
}

fn point_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (ex, ey) = (b.0 - a.0, b.1 - a.1);
    let len2 = ex * ex + ey * ey;
    let t = if len2 > 0.0 { (((p.0 - a.0) * ex + (p.1 - a.1) * ey) / len2).clamp(0.0, 1.0) } else { 0.0 };
    ((p.0 - a.0 - t * ex).powi(2) + (p.1 - a.1 - t * ey).powi(2)).sqrt()
}

/// True when the cores overlap (separating axes over both's edge normals,
/// or for two segments a strict crossing).
fn overlap(a: &[(f64, f64)], b: &[(f64, f64)]) -> bool {
    let cross =
        |o: (f64, f64), p: (f64, f64), q: (f64, f64)| (p.0 - o.0) * (q.1 - o.1) - (p.1 - o.1) * (q.0 - o.0);
    if a.len() < 3 && b.len() < 3 {
        if a.len() < 2 || b.len() < 2 {
            return false;
        }
        let s = |p: (f64, f64), q: (f64, f64), r: (f64, f64), t: (f64, f64)| {
            cross(p, q, r) * cross(p, q, t) < 0.0
        };
        return s(a[0], a[1], b[0], b[1]) && s(b[0], b[1], a[0], a[1]);
    }
    let mut axes = Vec::new();
    for vs in [a, b] {
        for (p, q) in edges(vs) {
            axes.push((q.1 - p.1, p.0 - q.0));
        }
    }
    axes.iter().all(|&(nx, ny)| {
        let range = |vs: &[(f64, f64)]| {
            vs.iter()
                .map(|v| v.0 * nx + v.1 * ny)
                .fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
        };
        let ((alo, ahi), (blo, bhi)) = (range(a), range(b));
        ahi >= blo && bhi >= alo
    })
}

/// The cores' distance (0 when overlapping) and the sum of the radii.
fn brute_force(a: Shape<'_>, xa: Transform, b: Shape<'_>, xb: Transform) -> (f64, f64) {
    let ((va, ra), (vb, rb)) = (core(a, xa), core(b, xb));
    if overlap(&va, &vb) {
        return (0.0, ra + rb);
    }
    let mut d = f64::MAX;
    for (x, y) in [(&va, &vb), (&vb, &va)] {
        for p in x.iter() {
            for (s, t) in edges(y) {
                d = d.min(point_segment(*p, s, t));
            }
        }
    }
    (d, ra + rb)
}

fn collide(a: Shape<'_>, xa: Transform, b: Shape<'_>, xb: Transform, margin: Scalar) -> Option<Manifold> {
    Some(match (a, b) {
        (Shape::Capsule(c), Shape::Circle(r)) => collide_capsule_circle(c, xa, r, xb, margin),
        (Shape::Segment(s), Shape::Circle(r)) => collide_segment_circle(s, xa, r, xb, margin),
        (Shape::Capsule(c), Shape::Capsule(d)) => collide_capsules(c, xa, d, xb, margin),
        (Shape::Segment(s), Shape::Capsule(d)) => collide_segment_capsule(s, xa, d, xb, margin),
        (Shape::Polygon(p), Shape::Capsule(d)) => collide_polygon_capsule(p, xa, d, xb, margin),
        (Shape::Segment(s), Shape::Polygon(p)) => collide_segment_polygon(s, xa, p, xb, margin),
        (Shape::Polygon(p), Shape::Polygon(q)) => collide_polygons(p, xa, q, xb, margin),
        (Shape::Polygon(p), Shape::Circle(r)) => collide_polygon_circle(p, xa, r, xb, margin),
        _ => return None,
    })
}

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [lo, hi) to 2^-20.
    fn range(&mut self, lo: f64, hi: f64) -> Scalar {
        let u = (self.next() >> 44) as f64 / (1u64 << 20) as f64;
        Scalar::from_num(lo + (hi - lo) * u)
    }

    fn pose(&mut self, spread: f64) -> Transform {
        let q = Rot::from_angle(self.range(-4.0, 4.0));
        // Every eighth pose unturned, so axis-aligned ties come up.
        let q = if self.next().is_multiple_of(8) { Rot::IDENTITY } else { q };
        Transform::new(Vector2::new(self.range(-spread, spread), self.range(-spread, spread)), q)
    }
}

#[test]
fn random_poses_keep_the_contract_against_the_brute_force_gap() {
    let capsule = Capsule {
        center1: Vector2::from_int(-1, 0),
        center2: Vector2::from_int(1, 0),
        radius: Scalar::lit("0.4"),
    };
    let short = Capsule {
        center1: Vector2::new(Scalar::lit("-0.2"), Scalar::lit("0.1")),
        center2: Vector2::new(Scalar::lit("0.3"), Scalar::lit("-0.1")),
        radius: Scalar::lit("0.25"),
    };
    let segment = Segment {
        point1: Vector2::from_int(-2, 0),
        point2: Vector2::new(Scalar::lit("1.5"), Scalar::lit("0.5")),
    };
    let boxy = PolygonPath::rectangle(Scalar::lit("1.5"), Scalar::ONE).unwrap_or_else(|_| unreachable!());
    let rounded = PolygonPath { rounding: Scalar::lit("0.15"), ..boxy };
    let tri = PolygonPath::new(&[
        Vector2::from_int(0, 0),
        Vector2::from_int(2, 0),
        Vector2::new(Scalar::lit("0.5"), Scalar::lit("1.2")),
    ])
    .unwrap_or_else(|_| unreachable!());
    let rounded_tri = PolygonPath { rounding: Scalar::lit("0.05"), ..tri };
    let circle = Shape::Circle(Scalar::lit("0.3"));
    let polys = [Shape::Polygon(&boxy), Shape::Polygon(&rounded), Shape::Polygon(&rounded_tri)];
    let caps = [Shape::Capsule(&capsule), Shape::Capsule(&short)];
    let mut pairs: Vec<(Shape<'_>, Shape<'_>)> = Vec::new();
    for c in caps {
        pairs.push((c, circle));
        pairs.push((Shape::Segment(&segment), c));
        for d in caps {
            pairs.push((c, d));
        }
        for p in polys {
            pairs.push((p, c));
        }
    }
    pairs.push((Shape::Segment(&segment), circle));
    for p in polys {
        pairs.push((Shape::Segment(&segment), p));
        pairs.push((p, circle));
        for q in polys {
            pairs.push((p, q));
        }
    }
    let margin = Scalar::lit("0.5");
    let mut rng = Rng(0x5EED_CAB5_0123_4567);
    let (mut apart, mut overlapping) = (0, 0);
    for k in 0..40_000usize {
        let (a, b) = pairs[k % pairs.len()];
        let (xa, xb) = (rng.pose(0.5), rng.pose(2.5));
        let Some(m) = collide(a, xa, b, xb, margin) else { continue };
        assert!(m.count <= 2, "case {k}");
        if m.count > 0 {
            let n = m.normal.to_f64();
            assert!((n.0 * n.0 + n.1 * n.1 - 1.0).abs() < 1e-6, "case {k}: {n:?}");
        }
        let (distance, radii) = brute_force(a, xa, b, xb);
        let faces = matches!(
            (a, b),
            (Shape::Polygon(_) | Shape::Segment(_), Shape::Polygon(_))
                | (Shape::Polygon(_), Shape::Capsule(_))
        );
        let tol = if faces { TOL + REFERENCE_FACE_TOLERANCE.to_f64() } else { TOL };
        let gap = distance - radii;
        let least = m.points().iter().map(|p| p.separation.to_f64()).fold(f64::MAX, f64::min);
        if distance == 0.0 {
            overlapping += 1;
            assert!(m.count > 0 && least < 0.0, "case {k}: overlapping cores, {m:?}");
        } else if distance > 0.01 {
            apart += 1;
            if gap < margin.to_f64() - tol {
                assert!(m.count > 0, "case {k}: gap {gap}, no contact");
                assert!((least - gap).abs() < tol, "case {k}: least separation {least}, gap {gap}, {m:?}");
            } else if gap > margin.to_f64() + tol {
                assert_eq!(m.count, 0, "case {k}: gap {gap}, {m:?}");
            }
        }
        // Moving both shapes far away moves the points by exactly that much.
        if k.is_multiple_of(16) {
            let far = Vector2::from_int(1_000_000, -1_000_000);
            let shift = |x: Transform| Transform::new(x.p + far, x.q);
            let Some(f) = collide(a, shift(xa), b, shift(xb), margin) else { continue };
            assert_eq!((f.count, f.normal), (m.count, m.normal), "case {k}");
            for (p, q) in f.points().iter().zip(m.points()) {
                assert_eq!(p.point, q.point + far, "case {k}");
                assert_eq!(
                    (p.anchor_a, p.anchor_b, p.separation, p.id),
                    (q.anchor_a, q.anchor_b, q.separation, q.id)
                );
            }
        }
    }
    // The poses cover both regimes.
    assert!(apart > 10_000 && overlapping > 5_000, "{apart} apart, {overlapping} overlapping");
}

fn swept(shape: Shape<'_>) -> Swept<'_> {
    match shape {
        Shape::Circle(r) => Swept::Circle(r),
        Shape::Capsule(c) => Swept::Capsule(c),
        Shape::Segment(s) => Swept::Segment(s),
        Shape::Polygon(p) => Swept::Polygon(p),
    }
}

#[test]
fn random_sweeps_are_never_late_and_exact_ones_never_early() {
    let capsule = Capsule {
        center1: Vector2::from_int(-1, 0),
        center2: Vector2::from_int(1, 0),
        radius: Scalar::lit("0.3"),
    };
    let segment = Segment { point1: Vector2::from_int(-2, 0), point2: Vector2::from_int(1, 1) };
    let boxy = PolygonPath::rectangle(Scalar::lit("1.5"), Scalar::ONE).unwrap_or_else(|_| unreachable!());
    let rounded = PolygonPath { rounding: Scalar::lit("0.1"), ..boxy };
    let shapes = [
        Shape::Circle(Scalar::lit("0.25")),
        Shape::Capsule(&capsule),
        Shape::Segment(&segment),
        Shape::Polygon(&boxy),
        Shape::Polygon(&rounded),
    ];
    let gap = Scalar::lit("0.05");
    let mut rng = Rng(0x70E5_1A7E_0000_0001);
    let (mut hits, mut misses) = (0, 0);
    for k in 0..6_000usize {
        let (a, b) = (shapes[k % 5], shapes[(k / 5) % 5]);
        if matches!((a, b), (Shape::Segment(_), Shape::Segment(_))) {
            continue;
        }
        let (xa, xb) = (rng.pose(0.5), rng.pose(4.0));
        let d = Vector2::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0));
        let t = time_of_impact(swept(a), xa, swept(b), xb, d, gap);
        let moved = |s: f64| Transform::new(xb.p + d * Scalar::from_num(s), xb.q);
        let gap_at = |s: f64| {
            let (distance, radii) = brute_force(a, xa, b, moved(s));
            distance - radii
        };
        let target = gap.to_f64();
        // Never late: no earlier time is already within the gap.
        let (end, last) = t.map_or((1.0, 48), |t| (t.to_f64(), 47));
        for i in 0..=last {
            let s = end * f64::from(i) / 48.0;
            if t.is_some() && s >= end {
                continue;
            }
            assert!(gap_at(s) > target - TOL, "case {k}: within the gap at {s}, answer {t:?}");
        }
        match t {
            None => misses += 1,
            Some(t) => {
                hits += 1;
                // Exact unless both are polygons (Cyrus–Beck, early near corners).
                let exact = !matches!((a, b), (Shape::Polygon(_), Shape::Polygon(_)));
                if exact {
                    assert!(
                        gap_at(t.to_f64()) < target + TOL,
                        "case {k}: early, {} at {t:?}",
                        gap_at(t.to_f64())
                    );
                }
            }
        }
    }
    assert!(hits > 500 && misses > 500, "{hits} hits, {misses} misses");
}

#[test]
fn random_poses_against_chain_links_give_unit_normals_from_the_front() {
    // A link at a convex corner, one at a concave one, one between collinear
    // links, and one whose ghosts coincide with its ends (no neighbours).
    let link = |g1: (i32, i32), p1: (i32, i32), p2: (i32, i32), g2: (i32, i32)| ChainSegment {
        ghost1: Vector2::from_int(g1.0, g1.1),
        segment: Segment { point1: Vector2::from_int(p1.0, p1.1), point2: Vector2::from_int(p2.0, p2.1) },
        ghost2: Vector2::from_int(g2.0, g2.1),
    };
    let links = [
        link((2, 0), (1, 0), (0, 0), (0, -1)),
        link((2, 0), (1, 0), (0, 0), (-1, 1)),
        link((3, 0), (1, 0), (-1, 0), (-3, 0)),
        link((1, 1), (1, 1), (-1, 0), (-1, 0)),
    ];
    let capsule = Capsule {
        center1: Vector2::from_int(-1, 0),
        center2: Vector2::from_int(1, 0),
        radius: Scalar::lit("0.3"),
    };
    let rounded = PolygonPath {
        rounding: Scalar::lit("0.1"),
        ..PolygonPath::rectangle(Scalar::lit("1.5"), Scalar::ONE).unwrap_or_else(|_| unreachable!())
    };
    let mut rng = Rng(0xC4A1_0000_5EED_0002);
    let mut contacts = 0;
    for k in 0..20_000usize {
        let chain = &links[k % links.len()];
        let (xa, xb) = (rng.pose(0.5), rng.pose(2.0));
        let margin = Scalar::lit("0.2");
        let m = match (k / links.len()) % 3 {
            0 => collide_chain_segment_circle(chain, xa, Scalar::lit("0.4"), xb, margin),
            1 => collide_chain_segment_capsule(chain, xa, &capsule, xb, margin),
            _ => collide_chain_segment_polygon(chain, xa, &rounded, xb, margin),
        };
        assert!(m.count <= 2);
        if m.count > 0 {
            contacts += 1;
            let n = m.normal.to_f64();
            assert!((n.0 * n.0 + n.1 * n.1 - 1.0).abs() < 1e-6, "case {k}: {n:?}");
            // The normal leaves the link's front: never against its outward side.
            let seg = chain.segment;
            let d = xa.q.rotate(seg.point2 - seg.point1);
            let outward = d.right_perp();
            assert!(m.normal.dot(outward) > Scalar::ZERO, "case {k}: {:?}", m.normal);
        }
    }
    assert!(contacts > 2_000, "{contacts}");
}
