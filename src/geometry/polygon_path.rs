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

use super::wide::U256;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
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

    /// Bounding radius: the largest distance from the centroid to a vertex (m).
    #[inline]
    #[must_use]
    pub fn radius(&self) -> Scalar {
        self.radius
    }

    /// Core extent: the least distance from the centroid to a face's line (m),
    /// the radius of the largest circle about the centroid inside the polygon.
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
