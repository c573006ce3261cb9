//! Capsules and segments: the shapes built on a line segment.
//!
//! A [`Capsule`] is every point within `radius` of the segment between its two
//! centres; a [`Segment`] is the bare segment (no area: on a dynamic body it
//! needs an explicit mass). Both are stored in the body's local frame, relative
//! to its position (the centre of mass), so a capsule of a dynamic body is
//! symmetric about the origin.

use super::circle::{MAX_CIRCLE_RADIUS, PI_Q64};
use super::wide::{sqrt_q62, U256};
use crate::error::Error;
use crate::math::scalar::ZERO;
use crate::math::{Rect, Scalar, Transform, Vector2};

/// Shortest segment: 2^-20 m ≈ 0.95 µm.
///
/// Why: a segment's normal is its direction turned by 90°, and below this length
/// the direction keeps fewer than 12 significant bits in Q32.32 (and at 0 it has
/// none), so contacts against it would point anywhere.
pub const MIN_SEGMENT_LENGTH: Scalar = Scalar::from_bits(1 << 12);

/// The error for a capsule reaching past [`MAX_CIRCLE_RADIUS`] from the origin.
const CAPSULE_TOO_LARGE: Error = Error::OutOfRange { what: "capsule size" };

/// A capsule: the points within `radius` of the segment `center1`–`center2`
/// (body-local, m).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Capsule {
    /// One end of the core segment (body-local, m).
    pub(crate) center1: Vector2,
    /// The other end of the core segment (body-local, m).
    pub(crate) center2: Vector2,
    /// Radius (m), > 0.
    pub(crate) radius: Scalar,
}

/// A line segment `point1`–`point2` (body-local, m): terrain, walls, one link of
/// a chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Segment {
    /// One end (body-local, m).
    pub(crate) point1: Vector2,
    /// The other end (body-local, m).
    pub(crate) point2: Vector2,
}

impl Capsule {
    /// One end of the core segment (body-local, m).
    #[inline]
    #[must_use]
    pub fn center1(&self) -> Vector2 {
        self.center1
    }

    /// The other end of the core segment (body-local, m).
    #[inline]
    #[must_use]
    pub fn center2(&self) -> Vector2 {
        self.center2
    }

    /// Radius (m).
    #[inline]
    #[must_use]
    pub fn radius(&self) -> Scalar {
        self.radius
    }
}

impl Segment {
    /// One end (body-local, m).
    #[inline]
    #[must_use]
    pub fn point1(&self) -> Vector2 {
        self.point1
    }

    /// The other end (body-local, m).
    #[inline]
    #[must_use]
    pub fn point2(&self) -> Vector2 {
        self.point2
    }
}

/// Raw bits of a point, widened.
fn bits(v: Vector2) -> (i128, i128) {
    (i128::from(v.x.to_bits()), i128::from(v.y.to_bits()))
}

/// Exact squared length of `a − b` in units of 2^-64 m² (points within 128 m of
/// the origin: below 2^82).
fn dist2(a: Vector2, b: Vector2) -> u128 {
    let (a, b) = (bits(a), bits(b));
    let (dx, dy) = (a.0.saturating_sub(b.0).unsigned_abs(), a.1.saturating_sub(b.1).unsigned_abs());
    dx.saturating_mul(dx).saturating_add(dy.saturating_mul(dy))
}

/// `√x` rounded to nearest, as a `Scalar` of raw bits (saturating).
fn round_sqrt(x: u128) -> Scalar {
    let r = x.isqrt();
    // (r + ½)² = r² + r + ¼: x lies above it exactly when x − r² > r.
    let r = if x.saturating_sub(r.saturating_mul(r)) > r { r.saturating_add(1) } else { r };
    Scalar::from_bits(i64::try_from(r).unwrap_or(i64::MAX))
}

/// `⌈√x⌉` as a `Scalar` of raw bits (saturating).
fn ceil_sqrt(x: u128) -> Scalar {
    let r = x.isqrt();
    let r = if r.saturating_mul(r) < x { r.saturating_add(1) } else { r };
    Scalar::from_bits(i64::try_from(r).unwrap_or(i64::MAX))
}

/// The midpoint of two points, each coordinate rounded to nearest (ties away
/// from zero, so mirrored inputs give mirrored midpoints).
fn midpoint(a: Vector2, b: Vector2) -> Vector2 {
    let half = |p: i128, q: i128| {
        let s = p.saturating_add(q);
        let h = s.unsigned_abs().saturating_add(1) >> 1;
        let h = i64::try_from(h).unwrap_or(i64::MAX);
        Scalar::from_bits(if s < 0 { h.saturating_neg() } else { h })
    };
    let (a, b) = (bits(a), bits(b));
    Vector2::new(half(a.0, b.0), half(a.1, b.1))
}

/// True when `|a − b| ≤ 2·half` (`half` ≥ 0), exactly.
fn within_length(a: Vector2, b: Vector2, half: Scalar) -> bool {
    let l = u128::from(half.to_bits().unsigned_abs()).saturating_mul(2);
    dist2(a, b) <= l.saturating_mul(l)
}

/// True when both coordinates are within the world's coordinate range.
fn in_world(p: Vector2) -> bool {
    let max = crate::limits::MAX_COORDINATE;
    p.x.abs() <= max && p.y.abs() <= max
}

/// The bounding box of the segment `a`–`b` placed at `xf`, grown by `margin`.
fn placed_box(a: Vector2, b: Vector2, margin: Scalar, xf: Transform) -> Rect {
    let (a, b) = (xf.apply(a), xf.apply(b));
    let m = Vector2::new(margin, margin);
    Rect { min: a.min(b) - m, max: a.max(b) + m }
}

impl Capsule {
    /// The capsule of `radius` (m) around the segment `center1`–`center2`
    /// (body-local, m).
    ///
    /// A zero-length core (`center1 == center2`) is allowed: the capsule is then
    /// a circle, and its area and inertia equal [`circle_area`] and
    /// [`circle_unit_inertia`] bit for bit.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `what`:
    /// * `"capsule radius"` unless `0 < radius ≤` [`MAX_CIRCLE_RADIUS`];
    /// * `"capsule size"` when the capsule is longer than a body may be (half
    ///   its core length plus the radius above [`MAX_CIRCLE_RADIUS`], 128 m:
    ///   a body re-centres it, and then it lies within 128 m of its centre),
    ///   or a centre is outside the world's coordinate range
    ///   (±[`MAX_COORDINATE`](crate::limits::MAX_COORDINATE)); checked exactly.
    ///
    /// [`circle_area`]: super::circle_area
    /// [`circle_unit_inertia`]: super::circle_unit_inertia
    pub fn new(center1: Vector2, center2: Vector2, radius: Scalar) -> Result<Self, Error> {
        if radius <= ZERO || radius > MAX_CIRCLE_RADIUS {
            return Err(Error::OutOfRange { what: "capsule radius" });
        }
        let reach = MAX_CIRCLE_RADIUS - radius;
        if !in_world(center1) || !in_world(center2) || !within_length(center1, center2, reach) {
            return Err(CAPSULE_TOO_LARGE);
        }
        Ok(Self { center1, center2, radius })
    }

    /// Length of the core segment, `|center2 − center1|` (m), correctly rounded.
    #[must_use]
    pub fn length(&self) -> Scalar {
        round_sqrt(dist2(self.center2, self.center1))
    }

    /// Centroid: the midpoint of the centres (m, body-local), each coordinate
    /// rounded to nearest.
    #[must_use]
    pub fn centroid(&self) -> Vector2 {
        midpoint(self.center1, self.center2)
    }

    /// Area, `π r² + 2 r L` (m²), for radius `r` and core length `L`.
    ///
    /// Formed in integers from the raw bits (π with 64 fraction bits, `L` with 62
    /// more fraction bits than Q32.32) and rounded once to the nearest 2^-32 m²:
    /// correctly rounded unless the exact value lies within 2^-60 m² of a tie.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] `{ what: "capsule size" }` for a capsule outside the
    /// limits of [`new`](Self::new) (only possible for one built otherwise).
    pub fn area(&self) -> Result<Scalar, Error> {
        let r: u128 = self.radius.to_bits().unsigned_abs().into();
        let l = sqrt_q62(dist2(self.center2, self.center1)).ok_or(CAPSULE_TOO_LARGE)?;
        // π r²: units 2^-128 m². 2 r L: r (2^-32 m) × L (2^-94 m) = 2^-126 m²,
        // so 8 r L is 2 r L in units of 2^-128 m² (8r < 2^42, L < 2^103).
        let circle = U256::mul(r.saturating_mul(r), PI_Q64);
        let band = U256::mul(r.saturating_mul(8), l);
        to_scalar(circle.add(band).div_round(96, 1))
    }

    /// Polar moment of inertia about the centroid at density 1 kg/m² (kg·m²):
    ///
    /// `π r² (r²/2 + L²/4) + r L (2 r² + L²/6)`
    ///
    /// (the two half discs with the parallel-axis theorem, and the `L × 2r`
    /// rectangle between them). `L²` is exact in integers and `L` carries 62 more
    /// fraction bits than Q32.32; the sum is rounded once to the nearest
    /// 2^-32 kg·m² (within 2^-31 of a step, as
    /// [`circle_unit_inertia`](super::circle_unit_inertia), whose value it equals
    /// bit for bit when `L = 0`).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] `{ what: "capsule size" }` for a capsule outside the
    /// limits of [`new`](Self::new) (only possible for one built otherwise).
    pub fn unit_inertia(&self) -> Result<Scalar, Error> {
        let r: u128 = self.radius.to_bits().unsigned_abs().into();
        let d = dist2(self.center2, self.center1);
        let l = sqrt_q62(d).ok_or(CAPSULE_TOO_LARGE)?;
        let r2 = r.saturating_mul(r); // < 2^79 (units 2^-64 m²)
                                      // Y = 2 r⁴ + r² L² in units of 2^-64 m⁴ (each part rounded as the circle
                                      // rounds its r⁴, so Y = 2·r4 exactly when L = 0); π r² (r²/2 + L²/4) is
                                      // π Y / 4.
        let r4 = U256::mul(r2, r2).div_round(64, 1).ok_or(CAPSULE_TOO_LARGE)?;
        let r2l2 = U256::mul(r2, d).div_round(64, 1).ok_or(CAPSULE_TOO_LARGE)?;
        let y = r4.saturating_mul(2).saturating_add(r2l2); // < 2^98
        let pi_y = U256::mul(y, PI_Q64); // units 2^-128 m⁴, < 2^164
                                         // Z = r L (12 r² + L²) in units of 2^-190 m⁴ (r·(12 r² + L²) < 2^124,
                                         // L < 2^103); r L (2 r² + L²/6) is Z / 6.
        let z = U256::mul(r.saturating_mul(r2.saturating_mul(12).saturating_add(d)), l);
        // In units of 2^-32 kg·m²: π Y / 2^98 + Z / (6 · 2^158)
        //   = (3 · 2^22 · π Y + Z / 2^39) / (3 · 2^120).
        let lhs = pi_y.shl(22).add(pi_y.shl(23));
        to_scalar(lhs.add(z.shr(39)).div_round(120, 3))
    }

    /// Bounding radius about the body's origin: the largest distance from the
    /// origin to a centre plus the radius (m), rounded up.
    #[must_use]
    pub fn bounding_radius(&self) -> Scalar {
        let far = dist2(self.center1, Vector2::ZERO).max(dist2(self.center2, Vector2::ZERO));
        ceil_sqrt(far) + self.radius
    }

    /// The bounding box of the capsule placed at `xf`: the box of the two
    /// placed centres grown by the radius, which is exact (a capsule's extreme
    /// points along an axis are on its end circles).
    #[must_use]
    pub fn aabb(&self, xf: Transform) -> Rect {
        placed_box(self.center1, self.center2, self.radius, xf)
    }
}

impl Segment {
    /// The segment `point1`–`point2` (body-local, m).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `what`:
    /// * `"segment length"` when the segment is shorter than
    ///   [`MIN_SEGMENT_LENGTH`] (zero length included: its normal would be
    ///   undefined);
    /// * `"segment size"` when it is longer than a body may be (twice
    ///   [`MAX_CIRCLE_RADIUS`], 256 m: a body re-centres it, and then it lies
    ///   within 128 m of its centre), or an end is outside the world's
    ///   coordinate range (±[`MAX_COORDINATE`](crate::limits::MAX_COORDINATE)).
    ///
    /// Both are checked exactly, in that order.
    pub fn new(point1: Vector2, point2: Vector2) -> Result<Self, Error> {
        let min: u128 = MIN_SEGMENT_LENGTH.to_bits().unsigned_abs().into();
        if dist2(point1, point2) < min.saturating_mul(min) {
            return Err(Error::OutOfRange { what: "segment length" });
        }
        if !in_world(point1) || !in_world(point2) || !within_length(point1, point2, MAX_CIRCLE_RADIUS) {
            return Err(Error::OutOfRange { what: "segment size" });
        }
        Ok(Self { point1, point2 })
    }

    /// Length, `|point2 − point1|` (m), correctly rounded.
    #[must_use]
    pub fn length(&self) -> Scalar {
        round_sqrt(dist2(self.point2, self.point1))
    }

    /// Centroid: the midpoint (m, body-local), each coordinate rounded to nearest.
    #[must_use]
    pub fn centroid(&self) -> Vector2 {
        midpoint(self.point1, self.point2)
    }

    /// Moment of inertia per kg of a thin rod along the segment about its
    /// midpoint, `L² / 12` (m², i.e. kg·m² per kg): a segment has no area, so a
    /// dynamic body made of one takes its mass from the caller. Exact in
    /// integers, rounded once to nearest.
    #[must_use]
    pub fn rod_unit_inertia(&self) -> Scalar {
        // L² in units of 2^-64 m²; / 12 and to 2^-32: / (3 · 2^34), to nearest.
        let d = dist2(self.point2, self.point1);
        let den: u128 = 3 << 34;
        let q = d.saturating_mul(2).saturating_add(den) / den.saturating_mul(2);
        Scalar::from_bits(i64::try_from(q).unwrap_or(i64::MAX))
    }

    /// Bounding radius about the body's origin: the larger distance from the
    /// origin to an end (m), rounded up.
    #[must_use]
    pub fn bounding_radius(&self) -> Scalar {
        ceil_sqrt(dist2(self.point1, Vector2::ZERO).max(dist2(self.point2, Vector2::ZERO)))
    }

    /// The bounding box of the segment placed at `xf` (exact: the box of the two
    /// placed ends).
    #[must_use]
    pub fn aabb(&self, xf: Transform) -> Rect {
        placed_box(self.point1, self.point2, ZERO, xf)
    }
}

/// A rounded quotient in units of 2^-32 as a `Scalar`.
fn to_scalar(bits: Option<u128>) -> Result<Scalar, Error> {
    let bits = bits.ok_or(CAPSULE_TOO_LARGE)?;
    i64::try_from(bits).map(Scalar::from_bits).map_err(|_| CAPSULE_TOO_LARGE)
}
