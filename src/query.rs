//! World queries: ray casts, point, box and shape overlap queries.
//!
//! Every query takes a [`QueryFilter`] (collision groups, Box2D's category and
//! mask, a body to exclude, static bodies, sensors) and
//! writes its results into a caller-owned slice, so none allocates. Results come
//! in body-slot order, except all-hits ray casts, which come nearest first (ties
//! by slot). Each body's bounding box is tested before its shape. Queries see
//! the world as it was after the last step, and frozen (out-of-bounds) bodies too.

use crate::body::{shape_aabb, Body, BodyHandle, CollisionFilter, Shape};
use crate::collide::{time_of_impact, Swept};
use crate::collision::{collide_shapes, ShapeRef};
use crate::compound::{is_compound, shapes_of};
use crate::error::Error;
use crate::geometry::chain::local_rect;
use crate::geometry::ray::{
    capsule_contains, polygon_contains, ray_capsule, ray_circle, ray_polygon, ray_segment,
};
use crate::geometry::{Capsule, PolygonPath, Segment};
use crate::geometry::{ChainHandle, ChainSegment};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rect, Transform, Vector2};
use crate::world::World;

/// Which bodies a query sees.
///
/// A body is seen when it shares no collision-group bit with `groups`, its
/// category is in `mask_bits` (`body.category_bits & mask_bits != 0`), it is
/// not `exclude`, and it is not static when `skip_static` is set nor a sensor
/// when `skip_sensors` is (rapier's `exclude_sensors`: a line-of-sight ray
/// should not stop at a trigger zone). The query's
/// own `category_bits` must be in the body's mask too (Box2D's rule, so a
/// body that masks out a category is invisible to queries of that category).
/// The default sees every body: build it with the methods or
/// `QueryFilter { mask_bits: 0b10, ..QueryFilter::default() }`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueryFilter {
    /// Group bits of the query: bodies sharing any bit are skipped (the same
    /// rule as collisions). 0 sees every body.
    pub groups: u32,
    /// Skip static bodies.
    pub skip_static: bool,
    /// The query's categories, tested against each body's mask (default all).
    pub category_bits: u64,
    /// The body categories the query sees (default all).
    pub mask_bits: u64,
    /// A body the query never reports, e.g. the player casting the ray.
    pub exclude: Option<BodyHandle>,
    /// Skip sensors (default false: queries see them, as every other body).
    pub skip_sensors: bool,
}

impl Default for QueryFilter {
    fn default() -> Self {
        Self {
            groups: 0,
            skip_static: false,
            category_bits: u64::MAX,
            mask_bits: u64::MAX,
            exclude: None,
            skip_sensors: false,
        }
    }
}

impl QueryFilter {
    /// A filter that sees every body.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The same filter seeing only bodies whose category is in `mask`.
    #[must_use]
    pub fn mask(mut self, mask: u64) -> Self {
        self.mask_bits = mask;
        self
    }

    /// The same filter with the query's own categories.
    #[must_use]
    pub fn category(mut self, category: u64) -> Self {
        self.category_bits = category;
        self
    }

    /// The same filter never reporting `body`.
    #[must_use]
    pub fn exclude(mut self, body: BodyHandle) -> Self {
        self.exclude = Some(body);
        self
    }

    /// The same filter skipping bodies that share a collision-group bit with `groups`.
    #[must_use]
    pub fn groups(mut self, groups: u32) -> Self {
        self.groups = groups;
        self
    }

    /// The same filter skipping static bodies, or not.
    #[must_use]
    pub fn skip_static(mut self, on: bool) -> Self {
        self.skip_static = on;
        self
    }

    /// The same filter skipping sensors, or not.
    #[must_use]
    pub fn skip_sensors(mut self, on: bool) -> Self {
        self.skip_sensors = on;
        self
    }

    /// The body-level tests: groups, static, the excluded body; and for a
    /// one-shape body its shape's.
    fn accepts(&self, h: BodyHandle, b: &Body) -> bool {
        (self.groups & b.collision_groups) == 0
            && !(self.skip_static && b.is_static())
            && self.exclude != Some(h)
            && (is_compound(b) || self.accepts_shape(b.sensor, &b.filter))
    }

    /// The shape-level tests: sensors, category and mask.
    fn accepts_shape(&self, sensor: bool, filter: &CollisionFilter) -> bool {
        !(self.skip_sensors && sensor)
            && (self.mask_bits & filter.category_bits) != 0
            && (self.category_bits & filter.mask_bits) != 0
    }
}

/// Where a ray, or a shape cast with [`World::shape_cast`], first meets a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayHit {
    /// The body hit.
    pub body: BodyHandle,
    /// Where the ray enters the body (m).
    pub point: Vector2,
    /// Unit outward surface normal there.
    pub normal: Vector2,
    /// Fraction of the ray's length at the hit, in [0, 1].
    pub fraction: Scalar,
}

/// A shape to test for overlap, placed by a transform.
#[derive(Clone, Copy, Debug)]
pub enum QueryShape<'p> {
    /// A circle of this radius (m).
    Circle(Scalar),
    /// A convex (possibly rounded) polygon.
    Polygon(&'p PolygonPath),
    /// A capsule (its centres relative to the transform's origin).
    Capsule(Capsule),
    /// A segment (its ends relative to the transform's origin).
    Segment(Segment),
}

impl QueryShape<'_> {
    /// The shape as the pair functions take it.
    fn as_ref(&self) -> ShapeRef<'_> {
        match self {
            Self::Circle(r) => ShapeRef::Circle(*r),
            Self::Polygon(p) => ShapeRef::Polygon(p),
            Self::Capsule(c) => ShapeRef::Capsule(c),
            Self::Segment(s) => ShapeRef::Segment(s),
        }
    }

    /// Distance from the transform's origin that bounds the shape (m).
    fn reach(&self) -> Scalar {
        match self {
            Self::Circle(r) => *r,
            Self::Polygon(p) => p.radius(),
            Self::Capsule(c) => c.bounding_radius(),
            Self::Segment(s) => s.bounding_radius(),
        }
    }
}

impl<'a> World<'a> {
    /// The direction and length of a ray, or an error for a zero-length one.
    fn ray(from: Vector2, to: Vector2) -> Result<(Vector2, Scalar), Error> {
        let (dir, length) = (to - from).normalize_and_length();
        if length == ZERO {
            return Err(Error::OutOfRange { what: "ray length" });
        }
        Ok((dir, length))
    }

    /// The shapes of body `b` the filter accepts, each in its world frame.
    fn shapes_in_world<'s>(
        &'s self,
        b: &'s Body,
        filter: &'s QueryFilter,
    ) -> impl Iterator<Item = (Shape, Transform)> + 's {
        let (xf, compound) = (b.transform(), is_compound(b));
        shapes_of(b, &self.paths)
            .filter(move |(_, s)| !compound || filter.accepts_shape(s.sensor, &s.filter))
            .map(move |(_, s)| (s.shape, s.world(xf, compound)))
    }

    /// The nearest entry of the ray into one of body `b`'s shapes the filter
    /// accepts: distance and normal.
    fn ray_body(
        &self,
        b: &Body,
        filter: &QueryFilter,
        from: Vector2,
        dir: Vector2,
        length: Scalar,
    ) -> Option<(Scalar, Vector2)> {
        self.shapes_in_world(b, filter)
            .filter_map(|(shape, xf)| self.ray_shape(b, shape, xf, from, dir, length))
            .reduce(|best, hit| if hit.0 < best.0 { hit } else { best })
    }

    fn ray_shape(
        &self,
        b: &Body,
        shape: Shape,
        xf: Transform,
        from: Vector2,
        dir: Vector2,
        length: Scalar,
    ) -> Option<(Scalar, Vector2)> {
        let hit = match shape {
            Shape::Circle { radius } => ray_circle(from, dir, length, xf.p, radius),
            Shape::Polygon(h) => ray_polygon(from, dir, length, self.paths.get(h)?, xf),
            Shape::Capsule(c) => ray_capsule(from, dir, length, &c, xf),
            Shape::Segment(sg) => ray_segment(from, dir, length, &sg, xf),
            Shape::Chain(h) => {
                // The nearest link the ray enters from its front side.
                let span = Rect::from_corners(from, from + dir * length);
                let mut best: Option<(Scalar, Vector2)> = None;
                self.each_link(b, h, span, |l| {
                    let sg = l.segment();
                    let front = b.rotation.rotate((sg.point2() - sg.point1()).right_perp());
                    if front.dot(dir) >= ZERO {
                        return false;
                    }
                    if let Some(hit) = ray_segment(from, dir, length, &sg, b.transform()) {
                        if best.is_none_or(|(t, _)| hit.distance < t) {
                            best = Some((hit.distance, hit.normal));
                        }
                    }
                    false
                });
                return best;
            }
        }?;
        Some((hit.distance, hit.normal))
    }

    /// Calls `f` with each link of chain `h` (the shape of body `b`) whose
    /// box meets the world box `area`, in link order, until `f` returns true.
    /// Returns whether it did.
    fn each_link(
        &self,
        b: &Body,
        h: ChainHandle,
        area: Rect,
        mut f: impl FnMut(ChainSegment) -> bool,
    ) -> bool {
        let query = local_rect(area, b.transform());
        let mut from = 0u32;
        while let Some(k) = self.paths.chains.next_link(h, from, query) {
            if self.paths.chains.link(h, k).is_some_and(&mut f) {
                return true;
            }
            let Some(next) = k.checked_add(1) else { break };
            from = next;
        }
        false
    }

    fn hits<'s>(
        &'s self,
        from: Vector2,
        to: Vector2,
        filter: QueryFilter,
    ) -> Result<impl Iterator<Item = RayHit> + use<'s, 'a>, Error> {
        let (dir, length) = Self::ray(from, to)?;
        let span = Rect::from_corners(from, to);
        Ok(self.bodies.iter().filter_map(move |(h, b)| {
            if !filter.accepts(h, b) || !b.aabb.overlaps(span) {
                return None;
            }
            let (t, normal) = self.ray_body(b, &filter, from, dir, length)?;
            Some(RayHit { body: h, point: from + dir * t, normal, fraction: t.div_or_zero(length) })
        }))
    }

    /// The closest body the ray from `from` to `to` enters, if any.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] `{ what: "ray length" }` for a zero-length ray.
    pub fn ray_cast(&self, from: Vector2, to: Vector2, filter: QueryFilter) -> Result<Option<RayHit>, Error> {
        // Nearest first; equal fractions go to the lower slot (iteration order).
        Ok(self.hits(from, to, filter)?.fold(None, |best: Option<RayHit>, hit| match best {
            Some(b) if b.fraction <= hit.fraction => Some(b),
            _ => Some(hit),
        }))
    }

    /// Every body the ray enters, nearest first (ties in slot order), into `out`.
    /// Returns how many bodies it hits; when that is more than `out.len()`, `out`
    /// holds the nearest ones.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a zero-length ray.
    pub fn ray_cast_all(
        &self,
        from: Vector2,
        to: Vector2,
        filter: QueryFilter,
        out: &mut [RayHit],
    ) -> Result<usize, Error> {
        let mut count = 0usize;
        for hit in self.hits(from, to, filter)? {
            // Insertion into the sorted prefix; a hit beyond a full buffer drops off.
            let kept = count.min(out.len());
            let mut at = kept;
            while at > 0 && out.get(at - 1).is_some_and(|o| o.fraction > hit.fraction) {
                at -= 1;
            }
            if at < out.len() {
                let end = if kept < out.len() { kept + 1 } else { kept };
                if let Some(tail) = out.get_mut(at..end) {
                    tail.rotate_right(1);
                    if let Some(first) = tail.first_mut() {
                        *first = hit;
                    }
                }
            }
            count = count.saturating_add(1);
        }
        Ok(count)
    }

    /// Bodies containing `point`, in slot order, into `out`; returns how many
    /// there are (possibly more than `out` holds).
    pub fn query_point(&self, point: Vector2, filter: QueryFilter, out: &mut [BodyHandle]) -> usize {
        let found = self.bodies.iter().filter(|(h, b)| {
            filter.accepts(*h, b)
                && b.aabb.contains(point)
                && self.shapes_in_world(b, &filter).any(|(shape, xf)| match shape {
                    Shape::Circle { radius } => {
                        let d = point - xf.p;
                        d.length_squared() <= radius * radius
                    }
                    Shape::Polygon(h) => self.paths.get(h).is_some_and(|p| polygon_contains(p, xf, point)),
                    Shape::Capsule(c) => capsule_contains(&c, xf, point),
                    // No area: a segment or a chain contains no point.
                    Shape::Segment(_) | Shape::Chain(_) => false,
                })
        });
        collect(found.map(|(h, _)| h), out)
    }

    /// Bodies whose bounding boxes overlap `area`, in slot order, into `out`;
    /// returns how many there are. A box with `min == max` is a point.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] `{ what: "query box" }` when `min > max` on an axis.
    pub fn query_aabb(
        &self,
        area: Rect,
        filter: QueryFilter,
        out: &mut [BodyHandle],
    ) -> Result<usize, Error> {
        if area.min.x > area.max.x || area.min.y > area.max.y {
            return Err(Error::OutOfRange { what: "query box" });
        }
        let found = self.bodies.iter().filter(|(h, b)| {
            filter.accepts(*h, b)
                && b.aabb.overlaps(area)
                && (!is_compound(b)
                    || self
                        .shapes_in_world(b, &filter)
                        .any(|(shape, xf)| shape_aabb(shape, xf, ZERO, &self.paths).overlaps(area)))
        });
        Ok(collect(found.map(|(h, _)| h), out))
    }

    /// Bodies overlapping `shape` placed at `xf` (touching counts), in slot
    /// order, into `out`; returns how many there are.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a circle radius ≤ 0.
    pub fn query_shape(
        &self,
        shape: QueryShape<'_>,
        xf: Transform,
        filter: QueryFilter,
        out: &mut [BodyHandle],
    ) -> Result<usize, Error> {
        if let QueryShape::Circle(r) = shape {
            if r <= ZERO {
                return Err(Error::OutOfRange { what: "radius" });
            }
        }
        let reach = shape.reach();
        let area = Rect::from_center(xf.p, Vector2::new(reach, reach));
        let found = self.bodies.iter().filter(|(h, b)| {
            if !filter.accepts(*h, b) || !b.aabb.overlaps(area) {
                return false;
            }
            self.shapes_in_world(b, &filter).any(|(body_shape, bx)| {
                let touches = |body_shape: ShapeRef<'_>| {
                    let m = collide_shapes(shape.as_ref(), xf, body_shape, bx, ZERO);
                    m.points().iter().any(|p| p.separation <= ZERO)
                };
                if let Shape::Chain(ch) = body_shape {
                    return self.each_link(b, ch, area, |l| touches(ShapeRef::ChainLink(l)));
                }
                ShapeRef::of(&body_shape, &self.paths, 0).is_some_and(touches)
            })
        });
        Ok(collect(found.map(|(h, _)| h), out))
    }
}

/// How near (m) the cast shape must come to count as touching: the contact
/// at the time of impact is computed with this margin, so its normal is the
/// surface's even when the sweep stops a hair early.
const CAST_MARGIN: Scalar = Scalar::lit("0.01");

impl World<'_> {
    /// The first body that `shape`, placed at `xf` and moved along
    /// `translation` (m, without turning), touches: the body, the fraction of
    /// the motion at which they touch, the contact point and the body's
    /// surface normal there (pointing towards the shape). A character
    /// controller casts its capsule along its intended motion and stops at
    /// the fraction.
    ///
    /// A body the shape already overlaps at `xf` is a hit at fraction 0, its
    /// normal the direction that separates them. Equal fractions go to the
    /// lower body slot. The fraction is never late (the shape moved by it does
    /// not overlap the body) and early by at most a fraction of a millimetre
    /// for polygon corners (see the time-of-impact notes in `collide`).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a circle radius ≤ 0.
    pub fn shape_cast(
        &self,
        shape: QueryShape<'_>,
        xf: Transform,
        translation: Vector2,
        filter: QueryFilter,
    ) -> Result<Option<RayHit>, Error> {
        if let QueryShape::Circle(r) = shape {
            if r <= ZERO {
                return Err(Error::OutOfRange { what: "radius" });
            }
        }
        let (cast, reach) = (shape.as_ref(), shape.reach());
        let start = Rect::from_center(xf.p, Vector2::new(reach, reach));
        let end = Rect::from_center(xf.p + translation, Vector2::new(reach, reach));
        let swept_box = Rect { min: start.min.min(end.min), max: start.max.max(end.max) };
        let Some(moving) = swept_of(&cast) else { return Ok(None) };
        let mut best: Option<RayHit> = None;
        for (h, b) in self.bodies.iter() {
            if !filter.accepts(h, b) || !b.aabb.overlaps(swept_box) {
                continue;
            }
            for (body_shape, bx) in self.shapes_in_world(b, &filter) {
                let try_shape = |body_shape: ShapeRef<'_>, best: &mut Option<RayHit>| {
                    let Some(still) = swept_of(&body_shape) else { return };
                    let Some(t) = time_of_impact(still, bx, moving, xf, translation, ZERO) else { return };
                    if best.is_some_and(|hit| hit.fraction <= t) {
                        return;
                    }
                    let at = Transform::new(xf.p + translation * t, xf.q);
                    let m = collide_shapes(body_shape, bx, cast, at, CAST_MARGIN);
                    let (normal, point) = match m.points().first() {
                        Some(p) => (m.normal, p.point),
                        None => (-translation.try_normalize().unwrap_or(Vector2::ZERO), at.p),
                    };
                    *best = Some(RayHit { body: h, point, normal, fraction: t });
                };
                if let Shape::Chain(ch) = body_shape {
                    // Links the shape starts in front of (they are one-sided).
                    let start = bx.apply_inv(xf.p);
                    self.each_link(b, ch, swept_box, |l| {
                        let sg = l.segment();
                        if (sg.point2() - sg.point1()).cross(start - sg.point1()) <= ZERO {
                            try_shape(ShapeRef::ChainLink(l), &mut best);
                        }
                        false
                    });
                    continue;
                }
                let Some(body_shape) = ShapeRef::of(&body_shape, &self.paths, 0) else { continue };
                try_shape(body_shape, &mut best);
            }
        }
        Ok(best)
    }
}

/// The sweep form of a shape.
fn swept_of<'s>(shape: &'s ShapeRef<'_>) -> Option<Swept<'s>> {
    match shape {
        ShapeRef::Circle(r) => Some(Swept::Circle(*r)),
        ShapeRef::Polygon(p) => Some(Swept::Polygon(p)),
        ShapeRef::Capsule(c) => Some(Swept::Capsule(c)),
        ShapeRef::Segment(sg) => Some(Swept::Segment(sg)),
        ShapeRef::ChainLink(l) => Some(Swept::Segment(&l.segment)),
    }
}

/// Writes as many items as fit; returns how many there were.
fn collect<T>(items: impl Iterator<Item = T>, out: &mut [T]) -> usize {
    let mut n = 0usize;
    for item in items {
        if let Some(slot) = out.get_mut(n) {
            *slot = item;
        }
        n = n.saturating_add(1);
    }
    n
}
