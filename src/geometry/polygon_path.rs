//! `PolygonPath`: the shared, immutable geometry of a convex polygon.
//!
//! LAYOUT CONTRACT (other modules rely on it): vertices are stored counter-clockwise,
//! relative to the polygon's centroid (so the body's position is its centre of mass),
//! `normals[i]` is the outward unit normal of the edge `vertices[i] → vertices[i+1]`
//! (wrapping), and only the first `count` entries of both arrays are meaningful.
//!
//! # How it is computed
//! [`PolygonPath::new`] works on the raw Q32.32 bits of the points as integers, so
//! every geometric decision is exact:
//!
//! 1. The convex hull by gift wrapping (Jarvis march) straight over the input slice:
//!    no allocation, no sorting, O(n·h) for n points and h hull vertices. Orientation
//!    tests are exact `i128` cross products, so duplicates and collinear points are
//!    recognised exactly and dropped; the hull is strictly convex.
//! 2. Area, centroid and polar moment of inertia from exact integer sums over the
//!    hull (the inertia needs 256-bit products), each rounded once to nearest.
//! 3. The vertices shifted by the rounded centroid: an exact subtraction, so the
//!    stored hull is exactly as convex as the computed one.
//!
//! The hull starts at its lowest vertex (the leftmost of the lowest if there are
//! several) and is a function of the *set* of input points: neither their order nor
//! repetitions change a single bit of the result.
//!
//! A rounded polygon ([`PolygonPath::rounded`]) stores its *core*, the hull inset
//! by the rounding radius, under the same layout contract; the shape is every
//! point within [`rounding`](PolygonPath::rounding) of the core, and its mass
//! properties, bounding radius and core extent are the rounded shape's.

use super::circle::PI_Q64;
use super::wide::U256;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::trig::atan2;
use crate::math::Vector2;

/// Most vertices a polygon may have (after the convex hull removed the rest).
pub const MAX_POLYGON_VERTICES: usize = 8;

/// Largest distance from the centroid to a vertex (m): 128 m.
///
/// Why 128: the polar moment of inertia at density 1 grows with the fourth power of
/// size, and a shape within radius `r` of its centroid has at most the inertia of
/// the full disc, `π r⁴ / 2`. At 128 m that is 4.2e8 kg·m², five times below the
/// Q32.32 limit of 2.1e9. (At 256 m it would be 6.7e9 and overflow.) The same
/// limit applies to circles, [`MAX_CIRCLE_RADIUS`](super::MAX_CIRCLE_RADIUS).
pub const MAX_POLYGON_RADIUS: Scalar = Scalar::from_int(128);

/// Smallest area a polygon may have: 2^-20 m² ≈ 9.5e-7 m² (about a 1 mm square).
///
/// Why: below it the area keeps fewer than 4,096 steps of 2^-32 m², so it, and the
/// mass derived from it, would carry a relative rounding error above 1.2e-4.
pub const MIN_POLYGON_AREA: Scalar = Scalar::from_bits(1 << 12);

/// Smallest thickness a polygon may have: 2^-20 m ≈ 0.95 µm.
///
/// A polygon counts as too thin when its area is below this times the longer side
/// of its axis-aligned bounding box (area / length is, within a factor of two, the
/// polygon's minimum width). Why: rotating a vertex 128 m from the centroid
/// rounds it by up to about 2^-31 · 128 m ≈ 6e-8 m; a sliver thinner than a few
/// of those could turn inside out once rotated.
pub const MIN_POLYGON_THICKNESS: Scalar = Scalar::from_bits(1 << 12);

/// Bounding-box side (raw bits: 512 m) above which [`PolygonPath::new`] rejects the
/// input before forming any product. It is twice what [`MAX_POLYGON_RADIUS`] allows,
/// so it never rejects a valid polygon; its purpose is to bound every intermediate:
/// coordinate differences stay below 2^41, cross products below 2^83, the centroid
/// numerator below 2^126, all inside `i128`.
const MAX_BOX_SIDE_BITS: i128 = 1 << 41;

/// The error for a polygon that is too large (or too far spread).
const TOO_LARGE: Error = Error::OutOfRange { what: "polygon size" };

/// The error for a rounding radius below 0 or too large for the polygon.
const BAD_ROUNDING: Error = Error::OutOfRange { what: "rounding radius" };

/// Least `1 + n₁·n₂` (in units of 2^-62) of two adjacent faces' unit normals
/// for which a corner is inset: 2^-38, a turn within 2^-19 rad of a half turn,
/// where the core vertex would move 2^19.5 times the radius.
const MIN_CORNER_DEN: i128 = 1 << 24;

/// A point as the raw bits of its coordinates (units of 2^-32 m).
type Pt = (i64, i64);
/// A difference of two [`Pt`]s, widened so it is exact.
type Diff = (i128, i128);

/// The geometry of a convex polygon, shared by any number of bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PolygonPath {
    pub(crate) vertices: [Vector2; MAX_POLYGON_VERTICES],
    pub(crate) normals: [Vector2; MAX_POLYGON_VERTICES],
    pub(crate) count: usize,
    /// Area in m².
    pub(crate) area: Scalar,
    /// Polar moment of inertia about the centroid for density 1 kg/m², in kg·m².
    pub(crate) unit_inertia: Scalar,
    /// Centroid of the hull in the coordinates the points were given in.
    pub(crate) centroid: Vector2,
    /// Largest distance from the centroid to a vertex (bounding radius), in m.
    pub(crate) radius: Scalar,
    /// Least distance from the centroid to a face's line (core extent), in m.
    pub(crate) core: Scalar,
    /// Rounding radius (m): the shape is every point within this distance of the
    /// stored (core) polygon. 0 for a sharp polygon.
    pub(crate) rounding: Scalar,
}

impl PolygonPath {
    /// The convex hull of `points` (m), with its mass properties.
    ///
    /// `points` may be in any order and contain duplicates, interior points and
    /// collinear points; all of these are dropped, so the hull is strictly convex and
    /// counter-clockwise. Any number of points is accepted (the cost is O(n·h) for
    /// n points and h hull vertices), and the coordinates may lie anywhere in the
    /// `Scalar` range: only their extent around the centroid is limited.
    ///
    /// The result depends only on the set of points. The stored vertices are relative
    /// to the centroid, which [`centroid`](Self::centroid) reports in the input
    /// coordinates (rounded to the nearest 2^-32 m; the shift is exact, so
    /// `vertex + centroid` is exactly an input point). Area, centroid, inertia and
    /// normals are each computed exactly and rounded once, to nearest (to within a
    /// tiny fraction of the last bit); [`radius`](Self::radius) is rounded up so it
    /// always bounds the vertices.
    ///
    /// Valid input (checked in this order):
    /// * the points' bounding box is at most 512 m on each side, else
    ///   [`Error::OutOfRange`] `{ what: "polygon size" }`;
    /// * the hull has at least 3 vertices (3 distinct, non-collinear points), else
    ///   [`Error::DegeneratePolygon`];
    /// * the hull has at most [`MAX_POLYGON_VERTICES`] vertices, else
    ///   [`Error::TooManyVertices`] with the hull's vertex count;
    /// * the area is at least [`MIN_POLYGON_AREA`] and the polygon is not thinner
    ///   than [`MIN_POLYGON_THICKNESS`] (its area is "≈ 0"), else
    ///   [`Error::DegeneratePolygon`];
    /// * every vertex is within [`MAX_POLYGON_RADIUS`] of the centroid, else
    ///   [`Error::OutOfRange`] `{ what: "polygon size" }`.
    ///
    /// Shapes below about 5 cm are accepted, but their `unit_inertia` (which scales
    /// with size⁴) keeps few significant bits: a 1 cm square's is 1.7e-9 m⁴, seven
    /// steps of 2^-32. [`MassData`](super::MassData) rejects inertias that small.
    ///
    /// # Errors
    /// As listed above.
    pub fn new(points: &[Vector2]) -> Result<Self, Error> {
        // Bounding box and the starting vertex (lowest, then leftmost).
        let mut iter = points.iter().map(|&p| bits(p));
        let first = iter.next().ok_or(Error::DegeneratePolygon)?;
        let (mut lo, mut hi, mut start) = (first, first, first);
        for p in iter {
            lo = (lo.0.min(p.0), lo.1.min(p.1));
            hi = (hi.0.max(p.0), hi.1.max(p.1));
            if (p.1, p.0) < (start.1, start.0) {
                start = p;
            }
        }
        let (side_x, side_y) = diff(hi, lo);
        let longest_side = side_x.max(side_y);
        if longest_side > MAX_BOX_SIDE_BITS {
            return Err(TOO_LARGE);
        }

        let (hull, count) = gift_wrap(points, start)?;
        if count < 3 {
            return Err(Error::DegeneratePolygon);
        }
        if count > MAX_POLYGON_VERTICES {
            return Err(Error::TooManyVertices { count, max: MAX_POLYGON_VERTICES });
        }
        let hull = hull.get(..count).ok_or(Error::DegeneratePolygon)?;

        // Twice the area and the centroid numerator, as a fan of triangles from the
        // first vertex (units: 2^-64 m² and 2^-96 m³). Every triangle of the fan has
        // positive area because the hull is strictly convex and counter-clockwise.
        let v0 = *hull.first().ok_or(Error::DegeneratePolygon)?;
        let (mut area2, mut cx, mut cy) = (0i128, 0i128, 0i128);
        for pair in hull.get(1..).unwrap_or(&[]).windows(2) {
            if let [p, q] = *pair {
                let (a, b) = (diff(p, v0), diff(q, v0));
                let d = cross(a, b);
                area2 = area2.saturating_add(d);
                cx = cx.saturating_add(d.saturating_mul(a.0.saturating_add(b.0)));
                cy = cy.saturating_add(d.saturating_mul(a.1.saturating_add(b.1)));
            }
        }

        // "Area ≈ 0": too small, or too thin for its length (see the constants).
        let min_area2 = i128::from(MIN_POLYGON_AREA.to_bits()).saturating_mul(1 << 33);
        let min_thin2 =
            i128::from(MIN_POLYGON_THICKNESS.to_bits()).saturating_mul(2).saturating_mul(longest_side);
        if area2 < min_area2 || area2 < min_thin2 {
            return Err(Error::DegeneratePolygon);
        }

        // Centroid = v0 + Σ dᵢ (aᵢ + bᵢ) / (3 Σ dᵢ), rounded once. It lies inside the
        // bounding box of the points, so adding it to v0 cannot overflow.
        let den = area2.saturating_mul(3);
        let offset = (to_i64(div_round(cx, den))?, to_i64(div_round(cy, den))?);
        let centroid =
            (v0.0.checked_add(offset.0).ok_or(TOO_LARGE)?, v0.1.checked_add(offset.1).ok_or(TOO_LARGE)?);

        // Shift to the centroid (exact) and check the size limit.
        let max_r2 = i128::from(MAX_POLYGON_RADIUS.to_bits()).saturating_pow(2);
        let mut local = [(0i64, 0i64); MAX_POLYGON_VERTICES];
        let mut radius2 = 0i128;
        for (slot, &v) in local.iter_mut().zip(hull) {
            let w = diff(v, centroid);
            *slot = (to_i64(w.0)?, to_i64(w.1)?);
            radius2 = radius2.max(dot(w, w));
        }
        if radius2 > max_r2 {
            return Err(TOO_LARGE);
        }
        let local = local.get(..count).ok_or(Error::DegeneratePolygon)?;

        let mut vertices = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        let mut normals = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        // Polar moment about the centroid: Σ dᵢ (aᵢ·aᵢ + aᵢ·bᵢ + bᵢ·bᵢ) / 12 over the
        // edges aᵢ → bᵢ. With |a|, |b| < 2^39 (128 m) each term is below 2^158,
        // so it is summed exactly in 256 bits. The triangles' signs are kept apart in
        // case the rounded centroid sits a hair outside one of them (it cannot for a
        // polygon that passed the thickness test, but the sum stays exact either way).
        let (mut pos, mut neg) = (U256::default(), U256::default());
        for (i, &a) in local.iter().enumerate() {
            // The edge from the last vertex wraps round to the first.
            let next = local.get(i.saturating_add(1)).or(local.first());
            let (a, b) = (widen(a), widen(*next.unwrap_or(&a)));
            let d = cross(a, b);
            let s = dot(a, a).saturating_add(dot(a, b)).saturating_add(dot(b, b));
            let term = U256::mul(d.unsigned_abs(), s.unsigned_abs());
            if d >= 0 {
                pos = pos.add(term);
            } else {
                neg = neg.add(term);
            }
            if let (Some(v), Some(n)) = (vertices.get_mut(i), normals.get_mut(i)) {
                *v = from_bits(a);
                *n = outward_normal((b.0.saturating_sub(a.0), b.1.saturating_sub(a.1)));
            }
        }
        // Units: 2^-128 m⁴; / 12 and to Q32.32 (2^-32 m⁴): / (3 · 2^98).
        let inertia = pos.saturating_sub(neg).div_round(98, 3).ok_or(TOO_LARGE)?;

        let mut path = Self {
            vertices,
            normals,
            count,
            // Twice the area in 2^-64 m² → the area in 2^-32 m².
            area: Scalar::from_bits(to_i64(div_round(area2, 1 << 33))?),
            unit_inertia: Scalar::from_bits(i64::try_from(inertia).map_err(|_| TOO_LARGE)?),
            centroid: from_bits(widen(centroid)),
            radius: Scalar::from_bits(to_i64(ceil_sqrt(radius2))?),
            core: Scalar::ZERO,
            rounding: Scalar::ZERO,
        };
        path.core =
            path.vertices().iter().zip(path.normals()).map(|(v, n)| n.dot(*v)).min().unwrap_or_default();
        path.core = path.core.max(Scalar::ZERO);
        Ok(path)
    }

    /// An axis-aligned rectangle `width` × `height` metres centred on the origin.
    ///
    /// Built by [`new`](Self::new) from its four corners, so it is bit-identical to
    /// `PolygonPath::new` on the same corners. Each half-side is rounded down to a
    /// multiple of 2^-32 m (a side given with an odd last bit loses that bit), so the
    /// rectangle is exactly centred.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] `{ what: "rectangle side" }` when a side is not
    /// positive; otherwise those of [`new`](Self::new) (too large a rectangle:
    /// `"polygon size"`; a sliver: [`Error::DegeneratePolygon`]).
    pub fn rectangle(width: Scalar, height: Scalar) -> Result<Self, Error> {
        Self::rectangle_at(width, height, Vector2::ZERO)
    }

    /// An axis-aligned rectangle `width` × `height` metres centred on `center` (m).
    ///
    /// The vertices are stored relative to the centroid as always, so they equal
    /// those of [`rectangle`](Self::rectangle); [`centroid`](Self::centroid) is
    /// `center` exactly.
    ///
    /// # Errors
    /// Those of [`rectangle`](Self::rectangle), and [`Error::OutOfRange`]
    /// `{ what: "rectangle center" }` when a corner would leave the `Scalar` range.
    pub fn rectangle_at(width: Scalar, height: Scalar, center: Vector2) -> Result<Self, Error> {
        if width <= ZERO || height <= ZERO {
            return Err(Error::OutOfRange { what: "rectangle side" });
        }
        // Halving the raw bits (rounding down) keeps the corners symmetric and exact.
        let (hx, hy) = (width.to_bits() >> 1, height.to_bits() >> 1);
        let c = bits(center);
        let corner = |sx: i64, sy: i64| -> Result<Vector2, Error> {
            let off = Error::OutOfRange { what: "rectangle center" };
            let x = c.0.checked_add(sx.saturating_mul(hx)).ok_or(off)?;
            let y = c.1.checked_add(sy.saturating_mul(hy)).ok_or(off)?;
            Ok(Vector2::new(Scalar::from_bits(x), Scalar::from_bits(y)))
        };
        Self::new(&[corner(-1, -1)?, corner(1, -1)?, corner(1, 1)?, corner(-1, 1)?])
    }

    /// The convex hull of `points` (m) with its corners rounded by `radius` (m).
    ///
    /// The outline keeps the hull's flat faces where they are and replaces each
    /// corner by a circular arc of `radius`: the shape is every point within
    /// `radius` of the *core*, the hull inset by `radius` (each face moved inward
    /// by `radius`). The stored [`vertices`](Self::vertices) are the core's and
    /// [`rounding`](Self::rounding) is `radius`. `radius = 0` gives exactly
    /// [`new`](Self::new)`(points)`.
    ///
    /// A core vertex is the hull vertex moved inward along the corner's
    /// bisector by `radius / cos(θ/2)` (θ the turn between the faces' normals),
    /// computed from 62-fraction-bit unit normals and rounded once to 2^-32 m,
    /// so the faces stay within about 2^-32 m of the hull's.
    ///
    /// Mass properties are those of the rounded shape (core polygon, one
    /// `length × radius` rectangle on each core edge, one circular sector at each
    /// core vertex): the area is `A_core + P_core · radius + π radius²`;
    /// centroid and polar inertia sum the pieces' first and second moments
    /// (parallel-axis theorem) in 64-fraction-bit integers and are rounded once.
    /// The core's own terms, the rectangles and `π r²`, `π r⁴ / 2` are exact but
    /// for 2^-64 roundings of each product; the sectors' angles come from the
    /// crate's [`atan2`] (within 1.2e-10 rad, then shifted equally so they sum to
    /// 2π), so a large shape's centroid and inertia can be a few steps of 2^-32
    /// from the exact values (a 4 m triangle rounded by 0.3 m: both within one
    /// step of its outline's; symmetric shapes such as
    /// [`rounded_rectangle`](Self::rounded_rectangle)
    /// keep their centroid exactly at their centre). The stored vertices are
    /// relative to the rounded shape's centroid, which
    /// [`centroid`](Self::centroid) reports in the input coordinates;
    /// [`radius`](Self::radius) and [`core_extent`](Self::core_extent) include
    /// the rounding.
    ///
    /// # Errors
    /// Those of [`new`](Self::new) for the hull, and [`Error::OutOfRange`]
    /// `{ what: "rounding radius" }` when `radius < 0`, or when the inset would
    /// collapse or reverse an edge, or leave a core below [`MIN_POLYGON_AREA`] or
    /// thinner than [`MIN_POLYGON_THICKNESS`] (the radius is too large for the
    /// polygon's inradius: use a capsule or a circle for such shapes).
    pub fn rounded(points: &[Vector2], radius: Scalar) -> Result<Self, Error> {
        if radius < ZERO {
            return Err(BAD_ROUNDING);
        }
        let hull = Self::new(points)?;
        if radius == ZERO {
            return Ok(hull);
        }
        let count = hull.count;
        let r = i128::from(radius.to_bits());
        let mut hv = [(0i128, 0i128); MAX_POLYGON_VERTICES];
        for (slot, v) in hv.iter_mut().zip(hull.vertices()) {
            *slot = widen(bits(*v));
        }
        let hv = hv.get(..count).ok_or(Error::DegeneratePolygon)?;
        let core_pts = inset(hv, r)?;
        let core_pts = core_pts.get(..count).ok_or(Error::DegeneratePolygon)?;
        check_core(hv, core_pts)?;

        // Moments about the hull's centroid (the core's coordinates' origin).
        let m = rounded_moments(core_pts, r)?;
        // The rounded shape's centroid, rounded to 2^-32 m: round(S · 2^32 / A).
        let g = (
            div_round(m.sx.saturating_mul(1 << 32), m.area),
            div_round(m.sy.saturating_mul(1 << 32), m.area),
        );
        // Second moment about g (exactly the point the vertices are shifted by):
        // I_g = I_O − 2 g·S + A |g|².
        let gq = (g.0.saturating_mul(1 << 32), g.1.saturating_mul(1 << 32));
        let gs = mulq(gq.0, m.sx)?.saturating_add(mulq(gq.1, m.sy)?);
        let gg = mulq(gq.0, gq.0)?.saturating_add(mulq(gq.1, gq.1)?);
        let inertia = m.inertia.saturating_sub(gs.saturating_mul(2)).saturating_add(mulq(m.area, gg)?);

        let mut vertices = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        let mut normals = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        let mut radius2 = 0i128;
        for (i, &p) in core_pts.iter().enumerate() {
            let next = *core_pts.get(i.saturating_add(1)).or(core_pts.first()).unwrap_or(&p);
            let a = (p.0.saturating_sub(g.0), p.1.saturating_sub(g.1));
            radius2 = radius2.max(dot(a, a));
            if let (Some(v), Some(n)) = (vertices.get_mut(i), normals.get_mut(i)) {
                *v = from_bits(a);
                *n = outward_normal((next.0.saturating_sub(p.0), next.1.saturating_sub(p.1)));
            }
        }
        let bound = Scalar::from_bits(to_i64(ceil_sqrt(radius2))?) + radius;
        if bound > MAX_POLYGON_RADIUS {
            return Err(TOO_LARGE);
        }
        let centroid = hull.centroid + from_bits(g);
        let mut path = Self {
            vertices,
            normals,
            count,
            area: Scalar::from_bits(to_i64(div_round(m.area, 1 << 32))?),
            unit_inertia: Scalar::from_bits(to_i64(div_round(inertia, 1 << 32))?),
            centroid,
            radius: bound,
            core: ZERO,
            rounding: radius,
        };
        let core =
            path.vertices().iter().zip(path.normals()).map(|(v, n)| n.dot(*v)).min().unwrap_or_default();
        path.core = core.max(ZERO) + radius;
        Ok(path)
    }

    /// A `width` × `height` rectangle centred on the origin with its corners
    /// rounded by `radius` (m): [`rounded`](Self::rounded) on the corners
    /// [`rectangle`](Self::rectangle) uses. Its area is
    /// `width · height − (4 − π) radius²`.
    ///
    /// # Errors
    /// Those of [`rectangle`](Self::rectangle) and [`rounded`](Self::rounded)
    /// (`"rounding radius"` when `2 · radius` reaches the shorter side, or leaves
    /// a core thinner than the minima).
    pub fn rounded_rectangle(width: Scalar, height: Scalar, radius: Scalar) -> Result<Self, Error> {
        if width <= ZERO || height <= ZERO {
            return Err(Error::OutOfRange { what: "rectangle side" });
        }
        let (hx, hy) = (width.to_bits() >> 1, height.to_bits() >> 1);
        let corner = |sx: i64, sy: i64| {
            Vector2::new(Scalar::from_bits(sx.saturating_mul(hx)), Scalar::from_bits(sy.saturating_mul(hy)))
        };
        Self::rounded(&[corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)], radius)
    }

    /// The hull's vertices, counter-clockwise, relative to the centroid (m).
    #[inline]
    #[must_use]
    pub fn vertices(&self) -> &[Vector2] {
        self.vertices.get(..self.count).unwrap_or(&[])
    }

    /// Outward unit normal of each edge `vertices[i] → vertices[i + 1]`.
    #[inline]
    #[must_use]
    pub fn normals(&self) -> &[Vector2] {
        self.normals.get(..self.count).unwrap_or(&[])
    }

    /// Area in m².
    #[inline]
    #[must_use]
    pub fn area(&self) -> Scalar {
        self.area
    }

    /// Moment of inertia about the centroid at density 1 kg/m² (kg·m²).
    #[inline]
    #[must_use]
    pub fn unit_inertia(&self) -> Scalar {
        self.unit_inertia
    }

    /// Centroid of the hull in the coordinates the points were given in (m). The
    /// stored vertices are shifted by it, so a body's position is its centroid.
    #[inline]
    #[must_use]
    pub fn centroid(&self) -> Vector2 {
        self.centroid
    }

    /// Bounding radius: the largest distance from the centroid to a vertex, plus
    /// the [`rounding`](Self::rounding) radius (m), rounded up.
    #[inline]
    #[must_use]
    pub fn radius(&self) -> Scalar {
        self.radius
    }

    /// Core extent: the least distance from the centroid to a face's line, plus
    /// the [`rounding`](Self::rounding) radius (m): the radius of the largest
    /// circle about the centroid inside the shape.
    /// Continuous collision measures what counts as fast against it.
    #[inline]
    #[must_use]
    pub fn core_extent(&self) -> Scalar {
        self.core
    }

    /// Rounding radius (m): the shape is every point within this distance of
    /// the stored vertices' polygon (0 for a sharp polygon).
    #[inline]
    #[must_use]
    pub fn rounding(&self) -> Scalar {
        self.rounding
    }
}

/// The convex hull of `points` by gift wrapping from `start` (a hull vertex: the
/// lowest point, leftmost among the lowest). Returns the first
/// [`MAX_POLYGON_VERTICES`] hull vertices, counter-clockwise, and the full count
/// (the wrap goes on counting past the array so the error can say how many).
///
/// Each step picks, among the points other than the current vertex `p`, the one
/// every other point lies left of (or on) as seen along `p → q`, and among points
/// on that line the farthest, which skips collinear points. Because `p` is always a
/// strict hull vertex, all points lie within an angle below 180° as seen from `p`,
/// so the cross-product comparison is a consistent order and the choice is unique:
/// it depends on the point values, never on their order in the slice.
fn gift_wrap(points: &[Vector2], start: Pt) -> Result<([Pt; MAX_POLYGON_VERTICES], usize), Error> {
    let mut hull = [(0i64, 0i64); MAX_POLYGON_VERTICES];
    let mut count = 0usize;
    let mut p = start;
    loop {
        if let Some(slot) = hull.get_mut(count) {
            *slot = p;
        }
        count = count.saturating_add(1);

        let mut next: Option<Pt> = None;
        for r in points.iter().map(|&v| bits(v)) {
            if r == p {
                continue;
            }
            next = Some(match next {
                None => r,
                Some(q) => {
                    let (pq, pr) = (diff(q, p), diff(r, p));
                    let turn = cross(pq, pr);
                    // r right of p → q, or on it and farther: r wraps tighter.
                    if turn < 0 || (turn == 0 && dot(pr, pr) > dot(pq, pq)) {
                        r
                    } else {
                        q
                    }
                }
            });
        }
        // No other point at all (every point equal): a single vertex.
        let Some(q) = next else { break };
        if q == start {
            break;
        }
        // A hull never has more vertices than there are points; this guard only
        // makes termination evident.
        if count >= points.len() {
            return Err(Error::DegeneratePolygon);
        }
        p = q;
    }
    Ok((hull, count))
}

/// The raw bits of a vector's coordinates.
fn bits(v: Vector2) -> Pt {
    (v.x.to_bits(), v.y.to_bits())
}

/// A vector from widened raw bits (callers pass values that fit an `i64`; larger
/// ones saturate).
fn from_bits(p: Diff) -> Vector2 {
    let clamp = |v: i128| i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX });
    Vector2::new(Scalar::from_bits(clamp(p.0)), Scalar::from_bits(clamp(p.1)))
}

/// A point widened to `i128`.
fn widen(p: Pt) -> Diff {
    (i128::from(p.0), i128::from(p.1))
}

/// `a − b`, exact (two `i64` differ by less than 2^64).
fn diff(a: Pt, b: Pt) -> Diff {
    (i128::from(a.0).saturating_sub(i128::from(b.0)), i128::from(a.1).saturating_sub(i128::from(b.1)))
}

/// `a × b`, exact for components below 2^62 (callers keep them below 2^42).
fn cross(a: Diff, b: Diff) -> i128 {
    a.0.saturating_mul(b.1).saturating_sub(a.1.saturating_mul(b.0))
}

/// `a · b`, exact for components below 2^62 (callers keep them below 2^42).
fn dot(a: Diff, b: Diff) -> i128 {
    a.0.saturating_mul(b.0).saturating_add(a.1.saturating_mul(b.1))
}

/// `num / den` rounded to nearest, ties away from zero, so mirrored shapes get
/// exactly mirrored results. `den` must be positive (0 for anything else).
fn div_round(num: i128, den: i128) -> i128 {
    if den <= 0 {
        return 0;
    }
    let twice = num.unsigned_abs().saturating_mul(2);
    let den = den.unsigned_abs();
    let q = twice.saturating_add(den).checked_div(den.saturating_mul(2)).unwrap_or(0);
    let q = i128::try_from(q).unwrap_or(i128::MAX);
    if num < 0 {
        q.saturating_neg()
    } else {
        q
    }
}

/// `⌈√x⌉` (0 for `x ≤ 0`): rounding up keeps the bounding radius conservative.
fn ceil_sqrt(x: i128) -> i128 {
    let Ok(x) = u128::try_from(x) else { return 0 };
    let r = x.isqrt();
    let r = if r.saturating_mul(r) < x { r.saturating_add(1) } else { r };
    i128::try_from(r).unwrap_or(i128::MAX)
}

/// An `i128` that must fit an `i64` (it does by the size checks; an error, not a
/// panic, if it somehow did not).
fn to_i64(v: i128) -> Result<i64, Error> {
    i64::try_from(v).map_err(|_| TOO_LARGE)
}

/// The outward unit normal of a counter-clockwise edge `d`: `d` turned by −90° and
/// normalised in integers. The edge is first scaled by a power of two (which does
/// not change its direction) to about 2^60, so the integer square root carries 60
/// significant bits and each component is correctly rounded; axis-aligned edges
/// give exactly ±1 and 0.
fn outward_normal(d: Diff) -> Vector2 {
    let (nx, ny) = (d.1, d.0.saturating_neg());
    let m = nx.unsigned_abs().max(ny.unsigned_abs());
    if m == 0 {
        return Vector2::ZERO;
    }
    let bit_len = 128u32.saturating_sub(m.leading_zeros());
    let shift = 61u32.saturating_sub(bit_len);
    let (sx, sy) = (nx.checked_shl(shift).unwrap_or(nx), ny.checked_shl(shift).unwrap_or(ny));
    let len2 = sx.unsigned_abs().saturating_pow(2).saturating_add(sy.unsigned_abs().saturating_pow(2));
    let len = i128::try_from(len2.isqrt()).unwrap_or(i128::MAX);
    let one = 1i128 << 32;
    from_bits((div_round(sx.saturating_mul(one), len), div_round(sy.saturating_mul(one), len)))
}

/// The hull `hv` (raw bits, counter-clockwise) with every face moved inward by
/// `r` (raw bits, > 0): each vertex moves by `r · (n₁ + n₂) / (1 + n₁·n₂)`
/// against the outward unit normals `n₁`, `n₂` of its two faces (the point at
/// distance `r` inside both face lines), rounded once to 2^-32 m.
fn inset(hv: &[Diff], r: i128) -> Result<[Diff; MAX_POLYGON_VERTICES], Error> {
    let count = hv.len();
    let edge = |i: usize| -> Diff {
        let a = hv.get(i % count.max(1)).copied().unwrap_or_default();
        let b = hv.get(i.saturating_add(1) % count.max(1)).copied().unwrap_or_default();
        (b.0.saturating_sub(a.0), b.1.saturating_sub(a.1))
    };
    let mut core = [(0i128, 0i128); MAX_POLYGON_VERTICES];
    for (i, (slot, v)) in core.iter_mut().zip(hv).enumerate() {
        let n1 = unit_normal_q62(edge(i.saturating_add(count).saturating_sub(1)));
        let n2 = unit_normal_q62(edge(i));
        // 1 + n₁·n₂ in units of 2^-124, then 2^-62 (|nᵢ| ≤ 2^62 + 2).
        let den = (1i128 << 124).saturating_add(dot(n1, n2)) >> 62;
        if den < MIN_CORNER_DEN {
            return Err(BAD_ROUNDING);
        }
        // q = (n₁ + n₂) / (1 + n₁·n₂) in units of 2^-62 (|q| < 2^82 by the guard).
        let q = (
            div_round(n1.0.saturating_add(n2.0).saturating_mul(1 << 62), den),
            div_round(n1.1.saturating_add(n2.1).saturating_mul(1 << 62), den),
        );
        let off = (div_round(r.saturating_mul(q.0), 1 << 62), div_round(r.saturating_mul(q.1), 1 << 62));
        *slot = (v.0.saturating_sub(off.0), v.1.saturating_sub(off.1));
    }
    Ok(core)
}

/// The core of a rounded polygon must keep every edge (same direction as the
/// hull's), stay strictly convex, and pass the area and thickness minima.
fn check_core(hv: &[Diff], core: &[Diff]) -> Result<(), Error> {
    let count = core.len();
    let at = |s: &[Diff], i: usize| s.get(i % count.max(1)).copied().unwrap_or_default();
    let sub = |a: Diff, b: Diff| (a.0.saturating_sub(b.0), a.1.saturating_sub(b.1));
    let (mut lo, mut hi) = (at(core, 0), at(core, 0));
    let mut area2 = 0i128;
    for i in 0..count {
        let e = sub(at(hv, i.saturating_add(1)), at(hv, i));
        let c = sub(at(core, i.saturating_add(1)), at(core, i));
        let c_next = sub(at(core, i.saturating_add(2)), at(core, i.saturating_add(1)));
        if dot(e, c) <= 0 || cross(c, c_next) <= 0 {
            return Err(BAD_ROUNDING);
        }
        let p = at(core, i);
        lo = (lo.0.min(p.0), lo.1.min(p.1));
        hi = (hi.0.max(p.0), hi.1.max(p.1));
        area2 = area2.saturating_add(cross(p, at(core, i.saturating_add(1))));
    }
    let longest_side = (hi.0.saturating_sub(lo.0)).max(hi.1.saturating_sub(lo.1));
    let min_area2 = i128::from(MIN_POLYGON_AREA.to_bits()).saturating_mul(1 << 33);
    let min_thin2 =
        i128::from(MIN_POLYGON_THICKNESS.to_bits()).saturating_mul(2).saturating_mul(longest_side);
    if area2 < min_area2 || area2 < min_thin2 {
        return Err(BAD_ROUNDING);
    }
    Ok(())
}

/// Area, first moment and polar second moment of a rounded polygon about the
/// origin of its core's coordinates, in units of 2^-64 (m², m³, m⁴).
struct Moments {
    area: i128,
    sx: i128,
    sy: i128,
    inertia: i128,
}

/// The moments of the points within `r` (raw bits) of the convex polygon `core`
/// (raw bits, counter-clockwise, within 128 m of the origin): the core, a
/// rectangle `ℓ × r` outside each edge and a sector of angle φ at each vertex.
///
/// Per edge `a → b` (ℓ its length, `m` its midpoint, `N = ℓ n` its outward
/// normal scaled by its length, exact): area `r ℓ`, first moment
/// `r ℓ m + r² N / 2`, second moment `r ℓ (ℓ²/12 + |m|² + r²/3) + r² m·N`.
/// Per vertex `p` between the normals `n₀` and `n₁`: area `φ r² / 2`, first
/// moment `φ r² p / 2 + r³ (n₁ − n₀)⊥ / 3` (the sector's own first moment about
/// its apex, with `(x, y)⊥ = (y, −x)`), second moment
/// `φ r⁴ / 4 + 2 r³ p·(n₁ − n₀)⊥ / 3 + φ r² |p|² / 2`. The sectors' angles sum
/// to 2π, so their areas are summed as `π r²` and their `φ r⁴ / 4` as `π r⁴ / 2`
/// exactly; `φ` itself (from `atan2`, within 1.2e-10 rad, then corrected to sum
/// to 2π) only weighs the vertex positions.
fn rounded_moments(core: &[Diff], r: i128) -> Result<Moments, Error> {
    let count = core.len();
    let at = |i: usize| core.get(i % count.max(1)).copied().unwrap_or_default();
    let edge = |i: usize| {
        let (a, b) = (at(i), at(i.saturating_add(1)));
        (b.0.saturating_sub(a.0), b.1.saturating_sub(a.1))
    };
    let q64 = |v: i128| v.saturating_mul(1 << 32);
    let rq = q64(r);
    let r2 = mulq(rq, rq)?;
    let r3 = mulq(r2, rq)?;
    let ru: u128 = r.unsigned_abs();

    // π r² and π r⁴ / 2 (units 2^-64), as circle_area and circle_unit_inertia form them.
    let r2_raw = ru.saturating_mul(ru);
    let pi_r2 = U256::mul(r2_raw, PI_Q64).div_round(64, 1).ok_or(TOO_LARGE)?;
    let r4 = U256::mul(r2_raw, r2_raw).div_round(64, 1).ok_or(TOO_LARGE)?;
    let pi_r4_2 = U256::mul(r4, PI_Q64).div_round(65, 1).ok_or(TOO_LARGE)?;
    let to_i = |v: u128| i128::try_from(v).map_err(|_| TOO_LARGE);

    // The sectors' angles (units 2^-64 rad), corrected so they sum to 2π: each
    // gets an equal share of what the rounded atan2 values miss (so equal
    // corners, as a rectangle's, get exactly equal angles).
    let mut phis = [0i128; MAX_POLYGON_VERTICES];
    let mut sum = 0i128;
    for (i, slot) in phis.iter_mut().enumerate().take(count) {
        let prev = edge(i.saturating_add(count).saturating_sub(1));
        *slot = q64(i128::from(turn_angle(prev, edge(i)).to_bits()));
        sum = sum.saturating_add(*slot);
    }
    let two_pi = to_i(PI_Q64)?.saturating_mul(2);
    let share = div_round(two_pi.saturating_sub(sum), i128::try_from(count).unwrap_or(1));
    for slot in phis.iter_mut().take(count) {
        *slot = slot.saturating_add(share);
    }

    let mut area2_core = 0i128;
    let (mut sx, mut sy) = (0i128, 0i128);
    let (mut ipos, mut ineg) = (U256::default(), U256::default());
    let mut area = to_i(pi_r2)?;
    let mut inertia = to_i(pi_r4_2)?;
    for i in 0..count {
        let (a, b) = (at(i), at(i.saturating_add(1)));
        // Core: the triangle (origin, a, b), signed.
        let d = cross(a, b);
        area2_core = area2_core.saturating_add(d);
        let den = 6i128 << 32;
        sx = sx.saturating_add(div_round(d.saturating_mul(a.0.saturating_add(b.0)), den));
        sy = sy.saturating_add(div_round(d.saturating_mul(a.1.saturating_add(b.1)), den));
        let s2 = dot(a, a).saturating_add(dot(a, b)).saturating_add(dot(b, b));
        let term = U256::mul(d.unsigned_abs(), s2.unsigned_abs());
        if d >= 0 {
            ipos = ipos.add(term);
        } else {
            ineg = ineg.add(term);
        }

        // Edge rectangle.
        let c = edge(i);
        let len2 = dot(c, c);
        let ell = super::wide::sqrt_q62(len2.unsigned_abs()).ok_or(TOO_LARGE)?;
        let ell = to_i(ell.saturating_add(1 << 29) >> 30)?; // units 2^-64 m
        let ae = mulq(rq, ell)?;
        area = area.saturating_add(ae);
        let mid = (
            a.0.saturating_add(b.0).saturating_mul(1 << 31),
            a.1.saturating_add(b.1).saturating_mul(1 << 31),
        );
        let nn = (q64(c.1), q64(c.0.saturating_neg()));
        sx = sx.saturating_add(mulq(ae, mid.0)?).saturating_add(mulq(r2, nn.0)? / 2);
        sy = sy.saturating_add(mulq(ae, mid.1)?).saturating_add(mulq(r2, nn.1)? / 2);
        let mm = mulq(mid.0, mid.0)?.saturating_add(mulq(mid.1, mid.1)?);
        let bracket = div_round(len2, 12).saturating_add(mm).saturating_add(r2 / 3);
        let mn = mulq(mid.0, nn.0)?.saturating_add(mulq(mid.1, nn.1)?);
        inertia = inertia.saturating_add(mulq(ae, bracket)?).saturating_add(mulq(r2, mn)?);

        // Corner sector at a, between the normals of the edges before and after it.
        let prev = edge(i.saturating_add(count).saturating_sub(1));
        let phi = phis.get(i).copied().unwrap_or_default();
        let (n0, n1) = (unit_normal_q62(prev), unit_normal_q62(c));
        let dn = (n1.0.saturating_sub(n0.0).saturating_mul(4), n1.1.saturating_sub(n0.1).saturating_mul(4));
        let rp = (dn.1, dn.0.saturating_neg());
        let p = (q64(a.0), q64(a.1));
        let sa = mulq(phi, r2)? / 2;
        sx = sx.saturating_add(mulq(sa, p.0)?).saturating_add(mulq(r3, rp.0)? / 3);
        sy = sy.saturating_add(mulq(sa, p.1)?).saturating_add(mulq(r3, rp.1)? / 3);
        let prp = mulq(p.0, rp.0)?.saturating_add(mulq(p.1, rp.1)?);
        let pp = mulq(p.0, p.0)?.saturating_add(mulq(p.1, p.1)?);
        inertia = inertia.saturating_add(mulq(r3, prp)?.saturating_mul(2) / 3).saturating_add(mulq(sa, pp)?);
    }
    // Core: area2 in 2^-64 m² is twice the area; Σ d (a·a + a·b + b·b) / 12 in
    // 2^-128 m⁴ → 2^-64: / (3 · 2^66).
    area = area.saturating_add(div_round(area2_core, 2));
    // The core's second moment about the origin is positive (a polygon's polar
    // moment about any point is), so the signed triangles sum to at least 0.
    let core_i = to_i(ipos.saturating_sub(ineg).div_round(66, 3).ok_or(TOO_LARGE)?)?;
    inertia = inertia.saturating_add(core_i);
    if area <= 0 {
        return Err(BAD_ROUNDING);
    }
    Ok(Moments { area, sx, sy, inertia })
}

/// The angle (rad, in (0, π) for a convex corner) turning the direction `a` into
/// `b`, from the crate's `atan2` on the exact cross and dot products scaled down
/// to fit a `Scalar` (a shift of both, which keeps the direction to 2^-61).
fn turn_angle(a: Diff, b: Diff) -> Scalar {
    let (y, x) = (cross(a, b), dot(a, b));
    let m = y.unsigned_abs().max(x.unsigned_abs());
    let shift = (128u32.saturating_sub(m.leading_zeros())).saturating_sub(62);
    let fit = |v: i128| Scalar::from_bits(i64::try_from(v >> shift).unwrap_or(0));
    atan2(fit(y), fit(x))
}

/// The outward unit normal of the counter-clockwise edge `d` in units of 2^-62
/// (as [`outward_normal`], with 30 more bits: within a few units of 2^-62).
fn unit_normal_q62(d: Diff) -> Diff {
    let (nx, ny) = (d.1, d.0.saturating_neg());
    let m = nx.unsigned_abs().max(ny.unsigned_abs());
    if m == 0 {
        return (0, 0);
    }
    let bit_len = 128u32.saturating_sub(m.leading_zeros());
    let shift = 61u32.saturating_sub(bit_len);
    let (sx, sy) = (nx.checked_shl(shift).unwrap_or(nx), ny.checked_shl(shift).unwrap_or(ny));
    let len2 = sx.unsigned_abs().saturating_pow(2).saturating_add(sy.unsigned_abs().saturating_pow(2));
    let len = i128::try_from(len2.isqrt()).unwrap_or(i128::MAX);
    (div_round(sx.saturating_mul(1 << 62), len), div_round(sy.saturating_mul(1 << 62), len))
}

/// `a · b / 2^64` rounded to nearest (ties away from zero), exact in 256 bits;
/// [`TOO_LARGE`] when it does not fit an `i128`.
fn mulq(a: i128, b: i128) -> Result<i128, Error> {
    let p = U256::mul(a.unsigned_abs(), b.unsigned_abs()).div_round(64, 1).ok_or(TOO_LARGE)?;
    let p = i128::try_from(p).map_err(|_| TOO_LARGE)?;
    Ok(if (a < 0) != (b < 0) { p.saturating_neg() } else { p })
}
