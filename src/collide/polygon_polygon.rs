//! Convex polygon against convex polygon: separating axes, then clipping.
//!
//! 1. **Separating axis test.** For each face of each polygon, the separation is
//!    how far the other polygon's deepest vertex lies outside that face. The
//!    largest of these over one polygon's faces is the best axis that polygon
//!    offers; if either best axis is beyond the margin, there is no contact.
//!    Each polygon's faces are tested in its own local frame against the other's
//!    vertices brought into that frame, so swapping the arguments recomputes
//!    exactly the same numbers.
//! 2. **Reference face.** The face with the larger separation becomes the
//!    reference face, A's unless B's is better by more than
//!    [`REFERENCE_FACE_TOLERANCE`].
//! 3. **Incident edge.** On the other polygon, the edge whose normal is most
//!    anti-parallel to the reference normal: the edge lying against the face.
//! 4. **Clipping.** The incident edge is cut to the strip between the two side
//!    lines through the reference face's end points; each remaining end is a
//!    contact point with separation measured along the reference normal, kept
//!    when at most the margin.
//!
//! When the polygons are apart (positive separation) and their closest features
//! are a vertex of each, a face normal would misjudge both the direction and the
//! gap, so that case gives one point along the vertex-to-vertex line instead.
//!
//! The whole contact is computed in the reference polygon's local frame: the
//! numbers stay of the size of the bodies, whatever their world position.

use super::manifold::{
    below_one, direction_and_length, dot_below_one, half, relative_transform, BelowOne, ByIdentity,
    LocalPoint, Manifold, Product, Saturating, MAX_MANIFOLD_POINTS,
};
use super::{next_index, Direction};
use crate::geometry::{PolygonPath, MAX_POLYGON_VERTICES};
use crate::math::{Rot, Scalar, Transform, Vector2};

/// How much better (m) B's best separating axis must be than A's before B's face
/// is used as the reference face: 0.5 mm.
///
/// Without it, two nearly equal axes (a box resting flat on a box of the same
/// width, a polygon rotating through the symmetric pose) would let rounding pick
/// A's face one step and B's the next, and the normal would flip between two
/// nearly equal directions. (The feature ids do not depend on which face is the
/// reference, so a flip keeps the warm-start impulses; see
/// [`collide_polygons`].) Box2D v2.4
/// uses 0.1 × its linear slop (0.005 m), and this is that value (Box2D v3 keeps
/// only the tie-break towards A). The tolerance is absolute rather than relative
/// because fixed-point rounding is absolute, and because the flip-flop matters
/// most at rest, where the separations are near zero and a relative tolerance
/// would vanish. The cost is bounded: the reported penetration can exceed the
/// least one by at most this amount.
pub const REFERENCE_FACE_TOLERANCE: Scalar = Scalar::lit("0.0005");

/// Feature id flag: a vertex–vertex point (both indices are vertex indices).
const ID_VERTEX_PAIR: u16 = 1 << 14;

// Feature ids pack vertex and edge indices into 4 bits each.
const _: () = assert!(MAX_POLYGON_VERTICES <= 16);

/// The contact between two convex polygons, A placed by `xf_a` and B by `xf_b`.
///
/// Reports up to two points when the polygons are at most `margin` apart (m, the
/// speculative distance, normally ≥ 0), an empty manifold otherwise. The normal
/// points from A to B; it is the reference face's outward normal (negated when
/// the reference face is B's), or the vertex-to-vertex direction for separated
/// corners. Each point lies midway between the incident polygon's surface and the
/// reference face's line.
///
/// Deterministic tie-breaking, all by index order: equally good faces go to the
/// lower edge index, equally anti-parallel incident edges to the lower index,
/// equally good polygons to A (see [`REFERENCE_FACE_TOLERANCE`]). Two clipped
/// points at exactly the same place (corners touching exactly) are merged into
/// one. Points come in a fixed order, end 0 before end 1 (below).
///
/// # Feature ids
/// An id names features of A and of B, never "reference" and "incident", so it
/// does not change when the reference face passes from one polygon to the other
/// (two boxes resting face to face with a slight relative tilt do that: the
/// better axis changes side as the tilt changes sign). For a face contact, bits
/// 8–11 hold A's edge index, bits 4–7 B's, and bit 0 which end of the overlap
/// the point is at: 0 at A's edge start vertex (which, the edges facing each
/// other, is also the end of B's edge end vertex), 1 at the other. An id holds
/// while the same two edges touch, whether or not the end is clipped and
/// whichever face is the reference; warm starting depends on it (a 100-row box
/// pyramid flips hundreds of reference faces a step while it settles). For a
/// vertex–vertex point bit 14 is set, and bits 8–11 and 4–7 hold A's and B's
/// vertex indices. Box2D v3 names its points by an A index and a B index in the
/// same way.
///
/// # Rounded polygons
/// A polygon with a [`rounding`](PolygonPath::rounding) radius is its stored
/// core grown by that radius. Everything above is computed on the cores; each
/// separation is then less both radii (so the margin applies to the rounded
/// surfaces) and each point lies midway between the rounded surfaces, the
/// incident one its radius inside the incident core's point. A face contact of
/// rounded polygons is therefore the sharp contact with the separation
/// reduced by the radii, and two rounded corners meet along the
/// vertex-to-vertex line with the true gap. A two-vertex polygon (a capsule or
/// segment, see [`collide_polygon_capsule`](super::collide_polygon_capsule))
/// goes through the same code. With both radii 0 the results are those of
/// sharp polygons to the bit (adding an exact 0 changes nothing).
///
/// Degenerate polygons (no vertices) give an empty manifold.
#[must_use]
pub fn collide_polygons(
    poly_a: &PolygonPath,
    xf_a: Transform,
    poly_b: &PolygonPath,
    xf_b: Transform,
    margin: Scalar,
) -> Manifold {
    // Rounded polygons: the cores may be up to `radius` farther apart than the
    // margin (the sum is exact, so a sharp pair sees `reach == margin`).
    // (Sharp pairs, the common case, skip the saturating additions.)
    let radius = poly_a.rounding + poly_b.rounding;
    let reach = if radius == Scalar::ZERO { margin } else { margin + radius };
    let b_in_a = relative_transform(xf_a, xf_b);
    let mut buf_b = [Vector2::ZERO; MAX_POLYGON_VERTICES];
    let verts_b_in_a = transform_vertices(poly_b, b_in_a, &mut buf_b);
    let Some((edge_a, sep_a)) = max_separation(poly_a, verts_b_in_a, b_in_a.p) else {
        return Manifold::EMPTY;
    };
    if sep_a > reach {
        return Manifold::EMPTY;
    }
    let a_in_b = relative_transform(xf_b, xf_a);
    let mut buf_a = [Vector2::ZERO; MAX_POLYGON_VERTICES];
    // A box B against a rectangle A needs only the bounds of A's corners (see
    // `rectangle_bounds`); A's vertices in B's frame are then built only if
    // B's face becomes the reference, which on the box pyramid is 0.2 % of
    // the pairs.
    let mut have_verts_a = false;
    let box_b = box_vertices(poly_b);
    let bounds_a = if box_b.is_some() { rectangle_bounds(poly_a, a_in_b) } else { None };
    let (edge_b, sep_b) = match (box_b, bounds_a) {
        (Some(box_b), Some((lo, hi))) => box_separation(box_b, lo, hi),
        _ => {
            have_verts_a = true;
            let verts_a_in_b = transform_vertices(poly_a, a_in_b, &mut buf_a);
            let Some(found) = max_separation(poly_b, verts_a_in_b, a_in_b.p) else {
                return Manifold::EMPTY;
            };
            found
        }
    };
    if sep_b > reach {
        return Manifold::EMPTY;
    }

    let flip = sep_b > sep_a + REFERENCE_FACE_TOLERANCE;
    let reference = if flip {
        let verts_a_in_b = if have_verts_a {
            buf_a.get(..poly_a.vertices().len().min(MAX_POLYGON_VERTICES)).unwrap_or(&[])
        } else {
            transform_vertices(poly_a, a_in_b, &mut buf_a)
        };
        Reference {
            poly: poly_b,
            edge: edge_b,
            separation: sep_b,
            incident: poly_a,
            incident_vertices: verts_a_in_b,
            incident_rotation: a_in_b.q,
            reference_is_b: true,
            radius,
        }
    } else {
        Reference {
            poly: poly_a,
            edge: edge_a,
            separation: sep_a,
            incident: poly_b,
            incident_vertices: verts_b_in_a,
            incident_rotation: b_in_a.q,
            reference_is_b: false,
            radius,
        }
    };
    let mut points = [LocalPoint::default(); MAX_MANIFOLD_POINTS];
    let Some((normal, count)) = reference.contact(margin, reach, &mut points) else {
        return Manifold::EMPTY;
    };
    let local = points.get(..count).unwrap_or(&[]);
    if flip {
        Manifold::from_local(xf_b, xf_a.p, normal, local, true)
    } else {
        Manifold::from_local(xf_a, xf_b.p, normal, local, false)
    }
}

/// `poly`'s vertices mapped by `xf` (into the other body's frame), written to
/// the start of `out` and returned as that slice (as many as `poly` has).
///
/// Computes `xf.apply(v)` for each vertex, `(c·x − s·y + px, s·x + c·y + py)`,
/// but reuses the two products of a coordinate equal to the previous vertex's
/// (the same inputs give the same bits): a polygon's consecutive corners often
/// share x or y. An axis-aligned rectangle (four vertices whose consecutive
/// corners share y, x, y and x in turn, as `PolygonPath::rectangle` makes
/// them) has each coordinate's products taken once, 8 in all instead of the
/// loop's 10: its last corner shares x with the first, which the loop does
/// not look back to (looking back in the loop cost more than it saved).
///
/// Inlined into its caller and writing into the caller's buffer, so the
/// vertices are not copied out as a whole array.
#[inline(always)]
fn transform_vertices<'o>(
    poly: &PolygonPath,
    xf: Transform,
    out: &'o mut [Vector2; MAX_POLYGON_VERTICES],
) -> &'o [Vector2] {
    // A turned body's rotation has both components below 1: its products
    // skip the saturation test (`mul_below_one`), the same bits. The test is
    // made once, outside the products (as a test inside each product it
    // saved nothing on the box pyramid); on the rollback scene this took
    // `collide_polygons` from 87.2 to 78.8 M instructions in 180 steps.
    if below_one(xf.q.c) && below_one(xf.q.s) {
        transform_vertices_by(poly, xf, out, BelowOne)
    } else if xf.q == Rot::IDENTITY {
        // Unrotated relative to each other (an unturned box on the ground):
        // `v + p`, the same bits (see `ByIdentity`).
        transform_vertices_by(poly, Transform { p: xf.p, q: Rot::IDENTITY }, out, ByIdentity)
    } else {
        transform_vertices_by(poly, xf, out, Saturating)
    }
}

/// [`transform_vertices`] with the product `mul`.
#[inline(always)]
fn transform_vertices_by<'o>(
    poly: &PolygonPath,
    xf: Transform,
    out: &'o mut [Vector2; MAX_POLYGON_VERTICES],
    mul: impl Product,
) -> &'o [Vector2] {
    let count = poly.vertices().len().min(MAX_POLYGON_VERTICES);
    let (c, s, p) = (xf.q.c, xf.q.s, xf.p);
    if let (Some(([x0, x1], [y0, y1])), [o0, o1, o2, o3, ..]) = (axis_rectangle(poly), out.as_mut_slice()) {
        // An axis-aligned rectangle: two x and two y coordinates, each
        // product taken once (8 instead of the loop's 10).
        let ([cx0, sx0], [cx1, sx1]) = ([mul.mul(c, x0), mul.mul(s, x0)], [mul.mul(c, x1), mul.mul(s, x1)]);
        let ([sy0, cy0], [sy1, cy1]) = ([mul.mul(s, y0), mul.mul(c, y0)], [mul.mul(s, y1), mul.mul(c, y1)]);
        // `Vector2 + p` written out by component (the same additions):
        // as four more `Vector2::add` calls here, the compiler stopped
        // inlining that function (13 instructions a call).
        *o0 = Vector2::new((cx0 - sy0) + p.x, (sx0 + cy0) + p.y);
        *o1 = Vector2::new((cx1 - sy0) + p.x, (sx1 + cy0) + p.y);
        *o2 = Vector2::new((cx1 - sy1) + p.x, (sx1 + cy1) + p.y);
        *o3 = Vector2::new((cx0 - sy1) + p.x, (sx0 + cy1) + p.y);
        return out.get(..4).unwrap_or(&[]);
    }
    let mut prev: Option<(Vector2, [Scalar; 4])> = None;
    for (slot, v) in out.iter_mut().zip(poly.vertices()) {
        // [c·x, s·x, s·y, c·y]
        let [cx, sx] = match prev {
            Some((u, k)) if u.x == v.x => [k[0], k[1]],
            _ => [mul.mul(c, v.x), mul.mul(s, v.x)],
        };
        let [sy, cy] = match prev {
            Some((u, k)) if u.y == v.y => [k[2], k[3]],
            _ => [mul.mul(s, v.y), mul.mul(c, v.y)],
        };
        *slot = Vector2::new(cx - sy, sx + cy) + p;
        prev = Some((*v, [cx, sx, sy, cy]));
    }
    out.get(..count).unwrap_or(&[])
}

/// The face of `poly` with the greatest separation from the convex polygon with
/// vertices `other` (in `poly`'s frame), and that separation (m): the signed
/// distance of `other`'s deepest vertex beyond the face. The first face (lowest
/// index) wins ties. `None` when either polygon has no vertices.
///
/// A box in its own frame (normals −y, +x, +y, −x, as
/// [`PolygonPath::rectangle`] makes them) takes a straight-line scan for the
/// bounds of `other`, then one subtraction a face; without early exits there is
/// nothing to mispredict. Any other polygon is scanned face by face from the face looking
/// towards `towards` (the other polygon's origin in `poly`'s frame, judged by
/// a coarse integer dot product), which is usually the answer: a face replaces the best only when its deepest vertex is
/// shallower (or as shallow with a lower index), so each later face's scan
/// stops at its first vertex at or below the best. The result is the same for
/// every start and on both paths (a test holds both to the definition).
///
/// The box path is inlined into [`collide_polygons`]: the call's register
/// saves and its result through memory were 7.5 M of the 80.7 M instructions
/// `max_separation` took in 20 steps of the 100-row pyramid. Any other
/// polygon goes to [`max_separation_scan`].
#[inline(always)]
fn max_separation(poly: &PolygonPath, other: &[Vector2], towards: Vector2) -> Option<(usize, Scalar)> {
    let &first = other.first()?;
    if let Some(box_vertices) = box_vertices(poly) {
        // The bounds of `other`, then one subtraction a face (see
        // `box_separation`).
        let (mut lo, mut hi) = (first, first);
        for w in other {
            (lo.x, lo.y) = (lo.x.min(w.x), lo.y.min(w.y));
            (hi.x, hi.y) = (hi.x.max(w.x), hi.y.max(w.y));
        }
        return Some(box_separation(box_vertices, lo, hi));
    }
    max_separation_scan(poly, other, towards)
}

/// `poly`'s four vertices when it is a box in its own frame (normals −y, +x,
/// +y, −x, as [`PolygonPath::rectangle`] makes them).
#[inline(always)]
fn box_vertices(poly: &PolygonPath) -> Option<[Vector2; 4]> {
    match poly.vertices() {
        &[v0, v1, v2, v3] if is_box_in_own_frame(poly.normals()) => Some([v0, v1, v2, v3]),
        _ => None,
    }
}

/// [`max_separation`] of a box in its own frame (its vertices `box_vertices`)
/// from a polygon whose vertices have the least coordinates `lo` and the
/// greatest `hi`.
///
/// Each face's distance is a subtraction (the dot product by an axis, its
/// `+ 0` changing nothing). The saturating `w.y − v.y` never decreases as
/// `w.y` grows and the saturating negation never increases, so the least
/// distance over the other polygon is the distance of its least or greatest
/// coordinate, to the bit: one subtraction a face. Straight-line, without
/// early exits or a start face; the first of equal faces wins, as in the
/// definition.
#[inline(always)]
fn box_separation(box_vertices: [Vector2; 4], lo: Vector2, hi: Vector2) -> (usize, Scalar) {
    let [v0, v1, v2, v3] = box_vertices;
    let z = Scalar::ZERO;
    let d0 = z + -(hi.y - v0.y);
    let d1 = (lo.x - v1.x) + z;
    let d2 = z + (lo.y - v2.y);
    let d3 = -(hi.x - v3.x) + z;
    let mut best = (0, d0);
    for (i, d) in [(1, d1), (2, d2), (3, d3)] {
        if d > best.1 {
            best = (i, d);
        }
    }
    best
}

/// The two x and the two y coordinates of `poly` when it is an axis-aligned
/// rectangle (four vertices, each edge along an axis, in the order
/// [`PolygonPath::rectangle`] makes them: the first edge horizontal), in the
/// order of its first two vertices and of its first and third.
#[inline(always)]
fn axis_rectangle(poly: &PolygonPath) -> Option<([Scalar; 2], [Scalar; 2])> {
    match *poly.vertices() {
        [v0, v1, v2, v3] if v1.y == v0.y && v2.x == v1.x && v3.y == v2.y && v3.x == v0.x => {
            Some(([v0.x, v1.x], [v0.y, v2.y]))
        }
        _ => None,
    }
}

/// The least and the greatest coordinates of `poly`'s vertices mapped by
/// `xf`, the bounds of [`transform_vertices`]' output to the bit, when `poly`
/// is an axis-aligned rectangle (as that function recognises it); `None`
/// otherwise.
///
/// The corners are `(c·xᵢ − s·yⱼ + px, s·xᵢ + c·yⱼ + py)` for all four pairs
/// of the rectangle's two x and two y coordinates. The saturating
/// subtraction never decreases as its first input grows nor as its second
/// shrinks, and the saturating addition never decreases as either grows, so
/// the least x is `(min c·xᵢ − max s·yⱼ) + px` and so on: the same bits as
/// the bounds of the four corners, from the same eight products, without
/// building the corners (a test compares both, extreme values included).
#[inline(always)]
fn rectangle_bounds(poly: &PolygonPath, xf: Transform) -> Option<(Vector2, Vector2)> {
    let (xs, ys) = axis_rectangle(poly)?;
    Some(if below_one(xf.q.c) && below_one(xf.q.s) {
        rectangle_bounds_by(xs, ys, xf, BelowOne)
    } else if xf.q == Rot::IDENTITY {
        rectangle_bounds_by(xs, ys, Transform { p: xf.p, q: Rot::IDENTITY }, ByIdentity)
    } else {
        rectangle_bounds_by(xs, ys, xf, Saturating)
    })
}

/// [`rectangle_bounds`] of the rectangle with the x coordinates `xs` and the
/// y coordinates `ys`, with the product `mul`.
#[inline(always)]
fn rectangle_bounds_by(
    xs: [Scalar; 2],
    ys: [Scalar; 2],
    xf: Transform,
    mul: impl Product,
) -> (Vector2, Vector2) {
    let (c, s, p) = (xf.q.c, xf.q.s, xf.p);
    let (cx0, sx0, cx1, sx1) = (mul.mul(c, xs[0]), mul.mul(s, xs[0]), mul.mul(c, xs[1]), mul.mul(s, xs[1]));
    let (sy0, cy0, sy1, cy1) = (mul.mul(s, ys[0]), mul.mul(c, ys[0]), mul.mul(s, ys[1]), mul.mul(c, ys[1]));
    let lo = Vector2::new((cx0.min(cx1) - sy0.max(sy1)) + p.x, (sx0.min(sx1) + cy0.min(cy1)) + p.y);
    let hi = Vector2::new((cx0.max(cx1) - sy0.min(sy1)) + p.x, (sx0.max(sx1) + cy0.max(cy1)) + p.y);
    (lo, hi)
}

/// [`max_separation`] for any polygon that is not a box in its own frame: the
/// face-by-face scan from the face looking towards `towards`.
#[inline(never)]
fn max_separation_scan(poly: &PolygonPath, other: &[Vector2], towards: Vector2) -> Option<(usize, Scalar)> {
    let (vertices, normals) = (poly.vertices(), poly.normals());
    let count = vertices.len().min(normals.len());
    // The start changes only how soon the scans stop, never the result, so
    // it is picked by a coarse dot product in plain integer arithmetic: the
    // normal's components (|n| ≤ 1, at most 2^32 in bits) to 16 fractional
    // bits, `towards` to 12 (at most 2^43 in bits): each product is below
    // 2^59, the sum below 2^60, so nothing wraps.
    let coarse = |n: &Vector2| {
        let (nx, ny) = (n.x.to_bits() >> 16, n.y.to_bits() >> 16);
        let (tx, ty) = (towards.x.to_bits() >> 20, towards.y.to_bits() >> 20);
        nx.wrapping_mul(tx).wrapping_add(ny.wrapping_mul(ty))
    };
    let mut start: Option<(usize, i64)> = None;
    for (i, n) in normals.iter().take(count).enumerate() {
        let along = coarse(n);
        if start.is_none_or(|(_, a)| along > a) {
            start = Some((i, along));
        }
    }
    let start = start.map_or(0, |(i, _)| i);
    let mut best: Option<(usize, Scalar)> = None;
    for k in 0..count {
        let i = if start + k < count { start + k } else { start + k - count };
        // Each face classified where it is used: an array of the classes
        // cost its stores and loads (rollback scene: 46.5 -> 40.7 M).
        let (Some(v), Some(n)) = (vertices.get(i), normals.get(i)) else { continue };
        let deepest = match Direction::of(*n) {
            Direction::PosX => deepest_vertex(other, best, i, |w| (w.x - v.x) + Scalar::ZERO),
            Direction::NegX => deepest_vertex(other, best, i, |w| -(w.x - v.x) + Scalar::ZERO),
            Direction::PosY => deepest_vertex(other, best, i, |w| Scalar::ZERO + (w.y - v.y)),
            Direction::NegY => deepest_vertex(other, best, i, |w| Scalar::ZERO + -(w.y - v.y)),
            // A face off the axes has both components below 1: its products
            // skip the saturation test (rollback scene: 47.6 -> 45.8 M).
            Direction::Any(n) if below_one(n.x) && below_one(n.y) => {
                deepest_vertex(other, best, i, |w| dot_below_one(n, w - *v))
            }
            Direction::Any(n) => deepest_vertex(other, best, i, |w| n.dot(w - *v)),
        };
        let replaces = match best {
            None => true,
            Some((bi, b)) => deepest > b || (deepest == b && i < bi),
        };
        if replaces {
            best = Some((i, deepest));
        }
    }
    best
}

/// Whether `normals` are exactly −y, +x, +y, −x, in that order (a box in its
/// own frame, as [`PolygonPath::rectangle`] makes it): the same test as
/// classifying each with [`Direction::of`], by comparing bits directly.
#[inline(always)]
fn is_box_in_own_frame(normals: &[Vector2]) -> bool {
    let (one, zero) = (Scalar::ONE, Scalar::ZERO);
    matches!(normals, [n0, n1, n2, n3]
        if n0.x == zero && n0.y == -one
            && n1.x == one && n1.y == zero
            && n2.x == zero && n2.y == one
            && n3.x == -one && n3.y == zero)
}

/// The least of `distance(w)` over `other`, face `face`'s deepest vertex, or
/// any value that does not replace `best` once the scan shows it cannot (see
/// [`max_separation`]).
#[inline(always)]
fn deepest_vertex(
    other: &[Vector2],
    best: Option<(usize, Scalar)>,
    face: usize,
    distance: impl Fn(Vector2) -> Scalar,
) -> Scalar {
    let mut deepest = Scalar::MAX;
    for w in other {
        deepest = deepest.min(distance(*w));
        if let Some((bi, b)) = best {
            if deepest < b || (deepest == b && face > bi) {
                break;
            }
        }
    }
    deepest
}

/// The chosen reference face and the other polygon, in the reference polygon's
/// local frame.
struct Reference<'a> {
    /// The polygon owning the reference face.
    poly: &'a PolygonPath,
    /// Index of the reference edge.
    edge: usize,
    /// Its separation from the incident polygon (m).
    separation: Scalar,
    /// The other polygon.
    incident: &'a PolygonPath,
    /// Its vertices in the reference polygon's frame.
    incident_vertices: &'a [Vector2],
    /// Its rotation relative to the reference polygon.
    incident_rotation: Rot,
    /// The reference face is polygon B's.
    reference_is_b: bool,
    /// The sum of both polygons' rounding radii (m): 0 for sharp polygons.
    radius: Scalar,
}

impl Reference<'_> {
    /// The feature id bits naming index `reference` of the reference polygon and
    /// index `incident` of the incident one: A's in bits 8–11, B's in bits 4–7,
    /// whichever polygon owns the reference face.
    fn pair_id(&self, reference: usize, incident: usize) -> u16 {
        let (a, b) = if self.reference_is_b { (incident, reference) } else { (reference, incident) };
        ((a as u16 & 0xF) << 8) | ((b as u16 & 0xF) << 4)
    }

    /// Fills `out` with the contact points (local to the reference polygon) and
    /// returns the local normal and the number of points, or `None` for no contact.
    /// `reach` is `margin` plus both rounding radii: the greatest separation of
    /// the cores that is a contact.
    fn contact(
        &self,
        margin: Scalar,
        reach: Scalar,
        out: &mut [LocalPoint; MAX_MANIFOLD_POINTS],
    ) -> Option<(Vector2, usize)> {
        let ref_vertices = self.poly.vertices();
        let edge_end = next_index(self.edge, ref_vertices.len());
        let n = *self.poly.normals().get(self.edge)?;
        let n_dir = Direction::of(n);
        let v1 = *ref_vertices.get(self.edge)?;
        let v2 = *ref_vertices.get(edge_end)?;

        // Incident edge: smallest normal · reference normal, first index on ties.
        // Comparing in the incident polygon's own frame avoids rotating its normals.
        let n_incident = n_dir.inv_rotated(self.incident_rotation);
        let incident_normals = self.incident.normals();
        let k1 = if is_box_in_own_frame(incident_normals) {
            // A box in its own frame (the normals −y, +x, +y, −x): the same
            // products and comparisons as the loop below, without classifying
            // each normal again.
            let mut best = (0, Direction::NegY.dot(n_incident));
            for (k, m) in [(1, Direction::PosX), (2, Direction::PosY), (3, Direction::NegX)] {
                let d = m.dot(n_incident);
                if d < best.1 {
                    best = (k, d);
                }
            }
            best.0
        } else {
            let mut incident: Option<(usize, Scalar)> = None;
            for (k, m) in incident_normals.iter().enumerate() {
                let d = Direction::of(*m).dot(n_incident);
                if incident.is_none_or(|(_, b)| d < b) {
                    incident = Some((k, d));
                }
            }
            incident?.0
        };
        let k2 = next_index(k1, self.incident_vertices.len());
        let i1 = *self.incident_vertices.get(k1)?;
        let i2 = *self.incident_vertices.get(k2)?;

        if self.separation > Scalar::ZERO {
            let reference_ends = [(v1, v2, self.edge), (v2, v1, edge_end)];
            let incident_ends = [(i2, i1, k2), (i1, i2, k1)];
            if let Some((direction, point)) = self.vertex_pair(reference_ends, incident_ends) {
                return single(direction, point, margin, out);
            }
        }

        // Clip the incident edge to the strip of the reference face. `t` runs
        // along the face from v1 to v2 (the outward normal turned +90°, for a
        // counter-clockwise polygon); `tau` is the coordinate along it.
        let t = Direction::of(n.perp());
        let length = t.dot(v2 - v1);
        let (tau1, tau2) = (t.dot(i1 - v1), t.dot(i2 - v1));
        let outside_low = tau1 < Scalar::ZERO && tau2 < Scalar::ZERO;
        let outside_high = tau1 > length && tau2 > length;
        // The overlap's two ends are named from A's and B's edges, not from the
        // reference face: end 0 is the end of A's edge start vertex (and of B's
        // edge end vertex, the edges being anti-parallel), end 1 the other. With
        // A's face as reference that is the incident edge's second vertex (`i2`),
        // with B's its first (`i1`).
        let base_id = self.pair_id(self.edge, k1);
        let (id2, id1) = if self.reference_is_b { (base_id | 1, base_id) } else { (base_id, base_id | 1) };
        // The cores' separation and the point midway between them; rounded
        // polygons are adjusted once the points are chosen (`round_face`).
        let face_point = |p: Vector2, id: u16| {
            let separation = n_dir.dot(p - v1);
            LocalPoint { point: p - n_dir.scale(half(separation)), separation, id }
        };
        if outside_low || outside_high {
            // The incident edge lies wholly beside the strip: not proven
            // impossible, never observed (millions of random boxes and
            // triangles, overlapping or not). Apart, the face axis says
            // nothing true about the gap there: no contact. Overlapping, keep the
            // deeper end so an overlap is never silently dropped.
            if self.separation > Scalar::ZERO {
                return None;
            }
            let (end2, end1) = (face_point(i2, id2), face_point(i1, id1));
            let deeper = if end2.separation <= end1.separation { end2 } else { end1 };
            let found = single(n, deeper, reach, out);
            if let Some((_, count)) = found {
                self.round_face(n_dir, count, out);
            }
            return found;
        }
        let p1 = clip_end(i1, i2, tau1, tau2, length);
        let p2 = clip_end(i2, i1, tau2, tau1, length);

        let ends = if self.reference_is_b { [(p1, id1), (p2, id2)] } else { [(p2, id2), (p1, id1)] };
        let mut count = 0;
        for (k, (p, id)) in ends.into_iter().enumerate() {
            let point = face_point(p, id);
            // `p1 == p2` only when the strip and the edge meet at a single point
            // (corners touching exactly): one point, not two identical ones.
            let duplicate = k == 1 && count == 1 && p1 == p2;
            if point.separation <= reach && !duplicate {
                if let Some(slot) = out.get_mut(count) {
                    *slot = point;
                    count += 1;
                }
            }
        }
        if count == 0 {
            None
        } else {
            self.round_face(n_dir, count, out);
            Some((n, count))
        }
    }

    /// Rounded polygons: turns the first `count` face points of the cores
    /// (separation along the reference normal, point midway between the
    /// cores) into those of the rounded surfaces: the separation less both
    /// radii, the point midway between the reference surface and the incident
    /// one (its radius inside the incident core's point). Sharp polygons are
    /// left alone, so their contact keeps its bits and its cost. Inlined, so
    /// that for them it is one comparison, not a call.
    #[inline(always)]
    fn round_face(&self, n_dir: Direction, count: usize, out: &mut [LocalPoint; MAX_MANIFOLD_POINTS]) {
        if self.radius == Scalar::ZERO {
            return;
        }
        for lp in out.iter_mut().take(count) {
            // Back to the core point (an exact addition), then out again.
            let core_point = lp.point + n_dir.scale(half(lp.separation));
            let separation = lp.separation - self.radius;
            lp.point = core_point - n_dir.scale(self.incident.rounding + half(separation));
            lp.separation = separation;
        }
    }

    /// The separated vertex–vertex case: some end `a` of the reference edge and
    /// some end `b` of the incident edge that are each other's closest points on
    /// the two edges. Returns the direction from `a` to `b` and the point midway,
    /// with the distance as separation; `None` when no pair qualifies (the face
    /// normal is right).
    ///
    /// `b` is closest to `a` on the reference edge when `(b − a)·(a' − a) < 0`
    /// (`a'` the edge's other end), and `a` to `b` when `(b − a)·(b' − b) > 0`.
    /// Strict inequalities leave the boundary case, where the vertex direction
    /// equals the face normal, to the face contact. The pairs are tried in a
    /// fixed order and the first that qualifies is used.
    fn vertex_pair(
        &self,
        reference_ends: [(Vector2, Vector2, usize); 2],
        incident_ends: [(Vector2, Vector2, usize); 2],
    ) -> Option<(Vector2, LocalPoint)> {
        for (a, a_other, ia) in reference_ends {
            for (b, b_other, ib) in incident_ends {
                let d = b - a;
                if d.dot(a_other - a) >= Scalar::ZERO || d.dot(b_other - b) <= Scalar::ZERO {
                    continue;
                }
                let (direction, distance) = direction_and_length(d)?;
                let id = ID_VERTEX_PAIR | self.pair_id(ia, ib);
                // Rounded corners: the gap is the distance less both radii, and
                // the reference surface lies its radius out from the vertex.
                let separation = distance - self.radius;
                let point = a + direction * (self.poly.rounding + half(separation));
                let point = LocalPoint { point, separation, id };
                return Some((direction, point));
            }
        }
        None
    }
}

/// A one-point contact with `normal`, or none when the point is beyond the margin.
fn single(
    normal: Vector2,
    point: LocalPoint,
    margin: Scalar,
    out: &mut [LocalPoint; MAX_MANIFOLD_POINTS],
) -> Option<(Vector2, usize)> {
    if point.separation > margin {
        return None;
    }
    let slot = out.first_mut()?;
    *slot = point;
    Some((normal, 1))
}

/// End `p` of the segment `p → q` moved along it into the strip
/// `0 ≤ tau ≤ length`, where `tau_p` and `tau_q` are the ends' coordinates
/// across the strip. The caller guarantees the segment meets the strip, so a
/// moved end's divisor (`tau_q − tau_p`) is never zero.
///
/// The common case, an end already inside the strip, is inlined into the
/// caller; moving an end (a division) is not.
#[inline(always)]
pub(super) fn clip_end(p: Vector2, q: Vector2, tau_p: Scalar, tau_q: Scalar, length: Scalar) -> Vector2 {
    if tau_p >= Scalar::ZERO && tau_p <= length {
        p
    } else {
        clip_end_moved(p, q, tau_p, tau_q, length)
    }
}

/// [`clip_end`] for an end outside the strip (`tau_p < 0` or `tau_p > length`).
#[inline(never)]
fn clip_end_moved(p: Vector2, q: Vector2, tau_p: Scalar, tau_q: Scalar, length: Scalar) -> Vector2 {
    let (over, span) = if tau_p < Scalar::ZERO {
        (-tau_p, tau_q - tau_p)
    } else if tau_p > length {
        (tau_p - length, tau_p - tau_q)
    } else {
        return p;
    };
    let ratio = over.div_or_zero(span).clamp(Scalar::ZERO, Scalar::ONE);
    p + (q - p) * ratio
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::test_support::{at, close, near, v};
    use crate::math::scalar::{from_int, ONE, ZERO};

    fn rect(w: i32, h: i32) -> PolygonPath {
        PolygonPath::rectangle(from_int(w), from_int(h)).unwrap_or_else(|_| unreachable!())
    }

    /// A convex polygon straight from counter-clockwise `points` (the hull code
    /// lives elsewhere; collision needs only the vertices and edge normals).
    fn polygon(points: &[Vector2]) -> PolygonPath {
        let mut p = rect(1, 1);
        p.count = points.len();
        for (i, a) in points.iter().enumerate() {
            let b = points[next_index(i, points.len())];
            p.vertices[i] = *a;
            p.normals[i] = (b - *a).normalize().right_perp();
        }
        p
    }

    /// The definition `max_separation` must match: every face scanned in full,
    /// in index order, the first of equal faces kept.
    fn max_separation_by_definition(poly: &PolygonPath, other: &[Vector2]) -> Option<(usize, Scalar)> {
        if other.is_empty() {
            return None;
        }
        let mut best: Option<(usize, Scalar)> = None;
        for (i, (v, n)) in poly.vertices().iter().zip(poly.normals()).enumerate() {
            let deepest = other.iter().map(|w| n.dot(*w - *v)).min().unwrap_or(Scalar::MAX);
            if best.is_none_or(|(_, b)| deepest > b) {
                best = Some((i, deepest));
            }
        }
        best
    }

    #[test]
    fn rectangle_bounds_are_those_of_the_transformed_vertices_even_where_they_saturate() {
        // Turned, unrotated, nearly unrotated (c exactly 1, s not 0) and
        // quarter-turned rotations; offsets anywhere up to the ends of the
        // range, where the corners saturate.
        let shapes = [rect(1, 1), rect(4, 2), polygon(&[v("0", "0"), v("3", "0"), v("3", "1"), v("0", "1")])];
        let extremes =
            [Scalar::MIN, Scalar::MIN + Scalar::ONE, -Scalar::ONE, Scalar::ZERO, Scalar::ONE, Scalar::MAX];
        let mut x = 0xB0B5_1DE5_F05E_ED01u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for k in 0..20_000usize {
            let r = next();
            let q = match k % 5 {
                0 => Rot::IDENTITY,
                1 => Rot { c: ONE, s: Scalar::from_bits((r as i64) >> 50) },
                2 => Rot { c: ZERO, s: -ONE },
                _ => Rot::from_angle(Scalar::from_bits((r as i64) >> 29)),
            };
            let mut coordinate = || {
                let bits = next();
                if bits.is_multiple_of(3) {
                    extremes[(bits >> 8) as usize % extremes.len()]
                } else {
                    Scalar::from_bits((bits as i64) >> (bits % 40))
                }
            };
            let xf = Transform::new(Vector2::new(coordinate(), coordinate()), q);
            let shape = &shapes[k % shapes.len()];
            let mut buf = [Vector2::ZERO; MAX_POLYGON_VERTICES];
            let corners = transform_vertices(shape, xf, &mut buf);
            let (mut lo, mut hi) = (corners[0], corners[0]);
            for w in corners {
                (lo.x, lo.y) = (lo.x.min(w.x), lo.y.min(w.y));
                (hi.x, hi.y) = (hi.x.max(w.x), hi.y.max(w.y));
            }
            assert_eq!(rectangle_bounds(shape, xf), Some((lo, hi)), "{xf:?}");
        }
        let tri = polygon(&[v("0", "-0.2"), v("1", "1"), v("-1", "1")]);
        assert_eq!(rectangle_bounds(&tri, at("0", "0")), None);
    }

    #[test]
    fn max_separation_of_a_box_is_the_definition_even_where_distances_saturate() {
        // The box path takes the least and greatest coordinates first; with
        // coordinates at the ends of the range every distance saturates one
        // way or the other, and the result must still be the definition's.
        let boxes = [rect(1, 1), rect(4, 2)];
        let extremes =
            [Scalar::MIN, Scalar::MIN + Scalar::ONE, -Scalar::ONE, Scalar::ZERO, Scalar::ONE, Scalar::MAX];
        let mut x = 0x5A7E_D157_A9CE_0001u64;
        for k in 0..4_000 {
            let mut pick = || {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                if x.is_multiple_of(3) {
                    Scalar::from_bits((x as i64) >> 28)
                } else {
                    extremes[(x >> 8) as usize % extremes.len()]
                }
            };
            let n = 1 + k % 5;
            let mut points = [Vector2::ZERO; 5];
            for p in &mut points {
                *p = Vector2::new(pick(), pick());
            }
            let other = &points[..n];
            let b = &boxes[k % boxes.len()];
            assert_eq!(
                max_separation(b, other, Vector2::ZERO),
                max_separation_by_definition(b, other),
                "{other:?}"
            );
        }
    }

    #[test]
    fn max_separation_is_the_first_best_face_from_any_start() {
        // The rectangles take the box path, the triangle the general one.
        let unit = rect(1, 1);
        assert_eq!(unit.normals().len(), 4);
        let dirs: [Direction; 4] = core::array::from_fn(|i| Direction::of(unit.normals()[i]));
        assert!(matches!(dirs, [Direction::NegY, Direction::PosX, Direction::PosY, Direction::NegX]));
        let tri = polygon(&[v("0", "-0.2"), v("1", "1"), v("-1", "1")]);
        let shapes = [rect(1, 1), rect(4, 2), tri, rect(2, 2)];
        let mut x = 0x0DDB_1A5E_5BAD_5EEDu64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for k in 0..20_000usize {
            let (a, b) = (&shapes[k % 4], &shapes[(k / 4) % 4]);
            let r = next();
            // Every fourth case unrotated and on a quarter-metre grid: exact ties.
            let q =
                if k % 4 == 0 { Rot::IDENTITY } else { Rot::from_angle(Scalar::from_bits((r as i64) >> 29)) };
            let grid = |bits: u64| Scalar::from_bits(((bits % 17) as i64 - 8) << 30);
            let p = if k % 4 == 0 {
                Vector2::new(grid(r >> 8), grid(r >> 20))
            } else {
                Vector2::new(
                    Scalar::from_bits((next() as i64) >> 30),
                    Scalar::from_bits((next() as i64) >> 30),
                )
            };
            let mut buf = [Vector2::ZERO; MAX_POLYGON_VERTICES];
            let other = transform_vertices(b, Transform::new(p, q), &mut buf);
            let towards = Vector2::new(
                Scalar::from_bits((next() as i64) >> 28),
                Scalar::from_bits((next() as i64) >> 28),
            );
            for t in [p, towards, Vector2::ZERO] {
                assert_eq!(max_separation(a, other, t), max_separation_by_definition(a, other), "case {k}");
            }
        }
    }

    #[test]
    fn transformed_vertices_are_those_of_transform_apply() {
        let tri = polygon(&[v("0", "-0.2"), v("1", "1"), v("-1", "1")]);
        let shapes =
            [rect(1, 1), rect(4, 2), tri, polygon(&[v("0", "0"), v("1", "0"), v("1", "1"), v("0", "1")])];
        let mut x = 0x1234_5678_9ABC_DEF1u64;
        for k in 0..2_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let angle = Scalar::from_bits((x as i64) >> 28);
            let p = Vector2::new(
                Scalar::from_bits((x as i64) >> 20),
                Scalar::from_bits((x.rotate_left(17) as i64) >> 20),
            );
            let xf = Transform::new(p, Rot::from_angle(angle));
            let shape = &shapes[k % shapes.len()];
            let mut buf = [Vector2::ZERO; MAX_POLYGON_VERTICES];
            let got = transform_vertices(shape, xf, &mut buf);
            assert_eq!(got.len(), shape.vertices().len());
            for (g, w) in got.iter().zip(shape.vertices()) {
                assert_eq!(*g, xf.apply(*w));
            }
        }
    }

    #[test]
    fn box_resting_on_a_box_gives_two_points_with_the_overlap() {
        // 4×2 ground, top face at y = 1; a 2×2 box whose bottom is at y = 0.9.
        let m = collide_polygons(&rect(4, 2), at("0", "0"), &rect(2, 2), at("0.5", "1.9"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::Y);
        let [p, q] = m.points;
        assert_eq!((p.separation, q.separation), (Scalar::lit("-0.1"), Scalar::lit("-0.1")));
        // A's edge 2 (top) is the reference, B's edge 0 (bottom) the incident edge.
        assert_eq!((p.id, q.id), (0x200, 0x201));
        assert_eq!(p.point, v("1.5", "0.95"));
        assert_eq!(q.point, v("-0.5", "0.95"));
        assert_eq!(p.anchor_b, v("1", "-0.95"));
    }

    #[test]
    fn overhanging_box_is_clipped_to_the_reference_face_and_keeps_its_ids() {
        let m = collide_polygons(&rect(4, 2), at("0", "0"), &rect(2, 2), at("2.5", "1.9"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::Y);
        assert_eq!(m.points[0].point, v("2", "0.95"));
        assert_eq!(m.points[1].point, v("1.5", "0.95"));
        assert_eq!((m.points[0].id, m.points[1].id), (0x200, 0x201));
    }

    #[test]
    fn speculative_points_respect_the_margin() {
        // Gap 0.1 between the faces.
        let (a, b) = (at("0", "0"), at("0.5", "2.1"));
        assert_eq!(collide_polygons(&rect(4, 2), a, &rect(2, 2), b, Scalar::lit("0.05")).count, 0);
        let m = collide_polygons(&rect(4, 2), a, &rect(2, 2), b, Scalar::lit("0.1"));
        assert_eq!(m.count, 2);
        assert_eq!(m.points[0].separation, Scalar::lit("0.1"));
        assert_eq!(m.points[0].point, v("1.5", "1.05"));
    }

    /// The box turned so that (cos, sin) = (0.8, 0.6): its corner (−1, −1) sits
    /// at (−0.2, −1.4) from its centre.
    fn tilted() -> Rot {
        Rot::from_direction(Vector2::from_int(4, 3)).unwrap_or_default()
    }

    #[test]
    fn rotated_box_corner_into_a_face_gives_one_point() {
        let xf_b = Transform::new(v("0", "2.3"), tilted());
        let m = collide_polygons(&rect(4, 2), at("0", "0"), &rect(2, 2), xf_b, ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        let p = m.points[0];
        assert!(near(p.separation, Scalar::lit("-0.1")), "{:?}", p.separation);
        assert!(close(p.point, v("-0.2", "0.95")), "{:?}", p.point);
        // The corner is the first vertex of B's edge 0: end 1.
        assert_eq!(p.id, 0x201);
    }

    #[test]
    fn swapped_arguments_flip_the_normal_and_keep_the_points() {
        let (xf_a, xf_b) = (at("0", "0"), Transform::new(v("0", "2.3"), tilted()));
        let ab = collide_polygons(&rect(4, 2), xf_a, &rect(2, 2), xf_b, ZERO);
        let ba = collide_polygons(&rect(2, 2), xf_b, &rect(4, 2), xf_a, ZERO);
        assert_eq!(ba.count, 1);
        assert_eq!(ba.normal, -ab.normal);
        let (p, q) = (ab.points[0], ba.points[0]);
        // Same reference face, same frame: the same numbers to the last bit.
        assert_eq!((q.point, q.separation), (p.point, p.separation));
        assert_eq!((q.anchor_a, q.anchor_b), (p.anchor_b, p.anchor_a));
        // The id names A's and B's features, so it follows the arguments: the
        // ground's edge 2 and the box's edge 0 trade places, and the corner (the
        // end of the ground edge's end vertex, 1) is at the box edge's start
        // vertex (0).
        assert_eq!((p.id, q.id), (0x201, 0x020));
    }

    #[test]
    fn b_face_is_the_reference_only_when_clearly_better() {
        // A small box poking down into a wide box B from above, rotated: B's top
        // face is clearly the best axis, and it is B's.
        let xf_a = Transform::new(v("0", "2.3"), tilted());
        // (A's faces are tilted: only B's top face gives exactly −y.)
        let m = collide_polygons(&rect(2, 2), xf_a, &rect(4, 2), at("0", "0"), ZERO);
        assert_eq!(m.normal, -Vector2::Y);
        // A slight tilt of the upper box: A's face is the reference while it
        // is not clearly worse.
        let xf_b = Transform::new(v("1", "1.95"), small_tilt("0.0004"));
        let m = collide_polygons(&rect(2, 2), at("0", "0"), &rect(2, 2), xf_b, ZERO);
        assert_eq!(m.normal, Vector2::Y);
    }

    /// A rotation by about `tan` radians.
    fn small_tilt(tan: &str) -> Rot {
        Rot::from_direction(v("1", tan)).unwrap_or_default()
    }

    #[test]
    fn ids_do_not_depend_on_which_face_is_the_reference() {
        // Box B rests half over box A, as in a brick pyramid, 5 cm deep. Tilted
        // one way, A's top face is the better axis; tilted the other way, by
        // more than the tolerance, B's bottom face is. The same two edges
        // touch, so the points keep their ids and their order.
        let a = at("0", "0");
        let pos = collide_polygons(
            &rect(2, 2),
            a,
            &rect(2, 2),
            Transform::new(v("1", "1.95"), small_tilt("0.002")),
            ZERO,
        );
        let neg = collide_polygons(
            &rect(2, 2),
            a,
            &rect(2, 2),
            Transform::new(v("1", "1.95"), small_tilt("-0.002")),
            ZERO,
        );
        let within = |p: Vector2, q: Vector2| (p - q).length() < Scalar::lit("0.01");
        // B's bottom normal, negated, is tilted: the reference face changed.
        assert_eq!(pos.normal, Vector2::Y);
        assert!(neg.normal != Vector2::Y && within(neg.normal, Vector2::Y), "{:?}", neg.normal);
        assert_eq!((pos.count, neg.count), (2, 2));
        // A's top edge is edge 2, B's bottom edge is edge 0.
        assert_eq!((pos.points[0].id, pos.points[1].id), (0x200, 0x201));
        assert_eq!((neg.points[0].id, neg.points[1].id), (0x200, 0x201));
        for (p, q) in pos.points().iter().zip(neg.points()) {
            assert!(within(p.point, q.point), "{:?} {:?}", p.point, q.point);
        }
        // End 0 is at A's edge start vertex, the top-right corner (1, 1); end 1
        // at B's bottom-left corner, over A's centre.
        assert!(within(pos.points[0].point, v("1", "0.975")), "{:?}", pos.points[0].point);
        assert!(within(pos.points[1].point, v("0", "0.975")), "{:?}", pos.points[1].point);
    }

    #[test]
    fn identical_overlapping_polygons() {
        let xf = Transform::new(v("3", "-4"), tilted());
        let m = collide_polygons(&rect(2, 2), xf, &rect(2, 2), xf, ZERO);
        assert_eq!(m.count, 2);
        // All faces tie at −2: A's edge 0 (normal −y in A's frame) wins.
        assert!(close(m.normal, tilted().rotate(-Vector2::Y)));
        for p in m.points() {
            assert!(near(p.separation, from_int(-2)));
        }
    }

    #[test]
    fn polygon_inside_another_leaves_through_the_nearest_face() {
        let m = collide_polygons(&rect(4, 2), at("0", "0"), &rect(1, 1), at("1.2", "0"), ZERO);
        assert_eq!(m.count, 2);
        assert_eq!(m.normal, Vector2::X);
        for p in m.points() {
            assert_eq!(p.separation, Scalar::lit("-1.3"));
            assert_eq!(p.point.x, Scalar::lit("1.35"));
        }
    }

    #[test]
    fn corners_touching_exactly_give_one_point() {
        let m = collide_polygons(&rect(2, 2), at("0", "0"), &rect(2, 2), at("2", "2"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::X);
        assert_eq!(m.points[0].point, Vector2::from_int(1, 1));
        assert_eq!(m.points[0].separation, ZERO);
    }

    #[test]
    fn separated_corners_use_the_vertex_to_vertex_distance() {
        // Corners (1, 1) and (1.1, 1.1): both face axes say 0.1, the true gap is 0.1·√2.
        let (a, b) = (at("0", "0"), at("2.1", "2.1"));
        assert_eq!(collide_polygons(&rect(2, 2), a, &rect(2, 2), b, Scalar::lit("0.1")).count, 0);
        let m = collide_polygons(&rect(2, 2), a, &rect(2, 2), b, Scalar::lit("0.2"));
        assert_eq!(m.count, 1);
        let diagonal = Vector2::new(Scalar::SQRT_2, Scalar::SQRT_2) * Scalar::lit("0.5");
        assert!(close(m.normal, diagonal), "{:?}", m.normal);
        let p = m.points[0];
        assert!(near(p.separation, Scalar::lit("0.141421356237")), "{:?}", p.separation);
        assert!(close(p.point, v("1.05", "1.05")));
        // A's vertex 2 and B's vertex 0.
        assert_eq!(p.id, ID_VERTEX_PAIR | 0x200);
    }

    #[test]
    fn triangle_tip_into_a_box() {
        // Tip down at (0, −0.2) relative to the triangle's frame origin.
        let tri = polygon(&[v("0", "-0.2"), v("1", "1"), v("-1", "1")]);
        let m = collide_polygons(&rect(4, 2), at("0", "0"), &tri, at("0.5", "1.1"), ZERO);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vector2::Y);
        assert!(near(m.points[0].separation, Scalar::lit("-0.1")));
        assert!(close(m.points[0].point, v("0.5", "0.95")));
    }

    #[test]
    fn triangle_face_on_a_triangle_face() {
        // Two right triangles whose hypotenuses overlap by 0.1 along the diagonal.
        let lower = polygon(&[v("0", "0"), v("1", "0"), v("0", "1")]);
        let upper = polygon(&[v("1", "1"), v("0", "1"), v("1", "0")]);
        let shift = Scalar::lit("0.1") * Scalar::FRAC_1_SQRT_2;
        let xf_b = Transform::new(Vector2::new(-shift, -shift), Rot::IDENTITY);
        let m = collide_polygons(&lower, at("0", "0"), &upper, xf_b, ZERO);
        assert_eq!(m.count, 2);
        let diagonal = Vector2::new(Scalar::FRAC_1_SQRT_2, Scalar::FRAC_1_SQRT_2);
        assert!(close(m.normal, diagonal), "{:?}", m.normal);
        for p in m.points() {
            assert!(near(p.separation, Scalar::lit("-0.1")), "{:?}", p.separation);
        }
    }

    #[test]
    fn far_from_the_origin_gives_the_same_relative_answer() {
        let far = Vector2::from_int(1_000_000, -1_000_000);
        let near_origin = collide_polygons(&rect(4, 2), at("0", "0"), &rect(2, 2), at("0.5", "1.9"), ZERO);
        let xf_a = Transform::new(far, Rot::IDENTITY);
        let xf_b = Transform::new(far + v("0.5", "1.9"), Rot::IDENTITY);
        let far_away = collide_polygons(&rect(4, 2), xf_a, &rect(2, 2), xf_b, ZERO);
        assert_eq!(far_away.normal, near_origin.normal);
        for (p, q) in far_away.points().iter().zip(near_origin.points()) {
            assert_eq!(p.point, q.point + far);
            assert_eq!((p.anchor_a, p.anchor_b, p.separation), (q.anchor_a, q.anchor_b, q.separation));
        }
    }

    #[test]
    fn incident_edge_beside_the_strip_keeps_the_deeper_end_only_when_overlapping() {
        // Not reachable from consistent geometry in millions of random trials; this
        // drives the defensive branch directly: the incident box lies wholly to
        // the right of the reference face's strip.
        let (ground, small) = (rect(4, 2), rect(2, 2));
        let mut buf = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        let verts = transform_vertices(&small, at("5", "1.5"), &mut buf);
        let mut reference = Reference {
            poly: &ground,
            edge: 2,
            separation: Scalar::lit("-0.5"),
            incident: &small,
            incident_vertices: verts,
            incident_rotation: Rot::IDENTITY,
            reference_is_b: false,
            radius: ZERO,
        };
        let mut out = [LocalPoint::default(); MAX_MANIFOLD_POINTS];
        assert_eq!(reference.contact(ZERO, ZERO, &mut out), Some((Vector2::Y, 1)));
        // Both ends are 0.5 deep: the tie goes to the end listed first (end 0).
        assert_eq!(out[0].point, v("6", "0.75"));
        assert_eq!(out[0].separation, Scalar::lit("-0.5"));
        assert_eq!(out[0].id, 0x200);
        reference.separation = Scalar::lit("0.1");
        assert_eq!(reference.contact(ONE, ONE, &mut out), None);
    }

    #[test]
    fn empty_polygons_give_no_contact() {
        let mut empty = rect(1, 1);
        empty.count = 0;
        assert_eq!(collide_polygons(&empty, at("0", "0"), &rect(1, 1), at("0", "0"), ONE), Manifold::EMPTY);
        assert_eq!(collide_polygons(&rect(1, 1), at("0", "0"), &empty, at("0", "0"), ONE), Manifold::EMPTY);
    }
}
