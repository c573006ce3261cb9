//! Bodies: [`Body`], its [`BodyType`] and [`Shape`]; the builder [`BodyDef`] is
//! in `body_def.rs`.
//!
//! A body's position is its centre of mass in world space (metres), its rotation a
//! unit complex number ([`Rot`]). A circle body is centred on its position; a
//! polygon body refers to a shared [`PolygonPath`] whose vertices are stored about
//! their centroid, so sharing one path between many bodies costs one handle per
//! body and no copy of the vertices (the manual's memory-footprint advice).
//!
//! [`PolygonPath`]: crate::geometry::PolygonPath

use crate::arena::{Arena, Handle};
use crate::compound::{is_compound, shapes_of, ShapeSlot, NO_SHAPE};
use crate::geometry::chain::ChainSlab;
use crate::geometry::{Capsule, ChainHandle, MassData, PolygonPath, Segment};
use crate::math::scalar::{below_one, mul_below_one, Scalar, ZERO};
use crate::math::{Rect, Rot, Transform, Vector2};

pub use crate::body_def::{BodyDef, CollisionFilter, MassSpec};

/// Handle of a body in a [`World`](crate::World).
pub type BodyHandle = Handle<Body>;
/// Handle of a shared polygon path in a [`World`](crate::World).
pub type PathHandle = Handle<PolygonPath>;

/// How a body moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u8)]
pub enum BodyType {
    /// Never moves; infinite mass. Floors, walls, terrain. (The manual: mass 0 or
    /// `set_static`.)
    Static = 0,
    /// Moves with its velocity, which only the game sets: pushes dynamic bodies,
    /// is pushed by nothing, ignores force generators. Moving platforms.
    Kinematic = 1,
    /// Moved by forces, contacts and constraints.
    #[default]
    Dynamic = 2,
}

/// The shape of a body.
///
/// Every shape is placed about the body's position, its centre of mass: a
/// circle is centred on it, a polygon path's vertices are stored about their
/// centroid, and a capsule's or segment's two ends are symmetric about it
/// (`center1 == −center2`, `point1 == −point2`; the world re-centres the
/// ends a [`BodyDef`] gives and moves the body by the same offset, see
/// [`BodyDef::capsule`] and [`BodyDef::segment`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// A circle of this radius (m) centred on the body's position.
    Circle {
        /// Radius in metres.
        radius: Scalar,
    },
    /// A convex polygon: a shared path, its vertices about the body's position.
    /// A path made with [`PolygonPath::rounded`] has rounded corners.
    Polygon(PathHandle),
    /// A capsule: the points within its radius of the segment between its two
    /// centres (a character, a limb, a pill).
    Capsule(Capsule),
    /// A line segment: no area, no thickness (ground, walls, terrain). Segments
    /// do not collide with segments.
    Segment(Segment),
    /// A chain: a static polyline or loop of one-sided links with ghost
    /// vertices (terrain), its points in the world's chain slab (see
    /// [`World::add_chain`](crate::World::add_chain)). Chains collide with
    /// neither chains nor segments.
    Chain(ChainHandle),
}

impl Shape {
    /// The order used to canonicalise pairs (shape A is the lower rank):
    /// circles, then capsules, then polygons, then segments, then chains. The manual's
    /// circle-before-polygon order is kept.
    #[inline]
    #[must_use]
    pub fn kind_rank(&self) -> u8 {
        match self {
            Self::Circle { .. } => 0,
            Self::Capsule(_) => 1,
            Self::Polygon(_) => 2,
            Self::Segment(_) => 3,
            Self::Chain(_) => 4,
        }
    }
}

/// The world's shape data that bodies refer to: the polygon paths (what
/// this dereferences to) and the chain slab.
pub(crate) struct ShapeStore<'a> {
    pub(crate) paths: Arena<'a, PolygonPath>,
    pub(crate) chains: ChainSlab<'a>,
    /// The shapes of compound bodies (see [`crate::compound`]).
    pub(crate) slots: Arena<'a, ShapeSlot>,
}

impl<'a> core::ops::Deref for ShapeStore<'a> {
    type Target = Arena<'a, PolygonPath>;
    fn deref(&self) -> &Self::Target {
        &self.paths
    }
}

impl core::ops::DerefMut for ShapeStore<'_> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.paths
    }
}

/// A rigid body in a [`World`](crate::World).
///
/// Read it with [`World::body`](crate::World::body); change it through the world
/// (which validates positions against the bounds) or through the velocity and
/// impulse methods here, which force generators and games use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Body {
    pub(crate) position: Vector2,
    pub(crate) rotation: Rot,
    pub(crate) linear_velocity: Vector2,
    pub(crate) angular_velocity: Scalar,
    pub(crate) shape: Shape,
    pub(crate) body_type: BodyType,
    pub(crate) mass: MassData,
    pub(crate) friction: Scalar,
    pub(crate) restitution: Scalar,
    pub(crate) collision_groups: u32,
    pub(crate) collision_level: u32,
    pub(crate) user_data: u64,
    /// Left the world bounds: frozen in place until the game moves it back.
    pub(crate) out_of_bounds: bool,
    /// Swept against dynamic bodies too when fast (see [`BodyDef::bullet`]).
    pub(crate) bullet: bool,
    /// Never rotates (see [`BodyDef::fixed_rotation`]).
    pub(crate) fixed_rotation: bool,
    /// Linear damping, 1/s (see [`BodyDef::linear_damping`]).
    pub(crate) linear_damping: Scalar,
    /// Angular damping, 1/s.
    pub(crate) angular_damping: Scalar,
    /// Factor on the gravity generators (see [`BodyDef::gravity_scale`]).
    pub(crate) gravity_scale: Scalar,
    /// Box2D's category, mask and group.
    pub(crate) filter: CollisionFilter,
    /// Detects overlap and never pushes (see [`BodyDef::sensor`]).
    pub(crate) sensor: bool,
    /// Bounding radius about the centre of mass (m), cached from the shape.
    pub(crate) radius: Scalar,
    /// The first of its shapes in the world's shape store, or
    /// [`NO_SHAPE`] for a body whose one shape is `shape`.
    pub(crate) shapes: u32,
    /// How many shapes it has (1 to [`MAX_SHAPES_PER_BODY`](crate::compound::MAX_SHAPES_PER_BODY)).
    pub(crate) shape_count: u8,
    /// World bounding box, refreshed whenever the body moves (derived state).
    pub(crate) aabb: Rect,
    /// Velocity change from the force generators, spread over the sub-steps
    /// (transient: zero outside `step`).
    pub(crate) force_dv: Vector2,
    /// Angular velocity change from the force generators (transient).
    pub(crate) force_dw: Scalar,
}

impl Body {
    /// A static body at the origin that is not in any world: the other side of a
    /// constraint to a fixed world point.
    pub(crate) fn ground() -> Self {
        Self {
            position: Vector2::ZERO,
            rotation: Rot::IDENTITY,
            linear_velocity: Vector2::ZERO,
            angular_velocity: ZERO,
            shape: Shape::Circle { radius: ZERO },
            body_type: BodyType::Static,
            mass: MassData::STATIC,
            friction: ZERO,
            restitution: ZERO,
            collision_groups: 0,
            collision_level: 0,
            user_data: 0,
            out_of_bounds: false,
            bullet: false,
            fixed_rotation: false,
            linear_damping: ZERO,
            angular_damping: ZERO,
            gravity_scale: crate::math::scalar::ONE,
            filter: CollisionFilter::DEFAULT,
            sensor: false,
            radius: ZERO,
            shapes: NO_SHAPE,
            shape_count: 1,
            aabb: Rect { min: Vector2::ZERO, max: Vector2::ZERO },
            force_dv: Vector2::ZERO,
            force_dw: ZERO,
        }
    }

    /// Position of the centre of mass (m).
    #[inline]
    #[must_use]
    pub fn position(&self) -> Vector2 {
        self.position
    }

    /// Rotation.
    #[inline]
    #[must_use]
    pub fn rotation(&self) -> Rot {
        self.rotation
    }

    /// Rotation angle in radians, in (−π, π].
    #[must_use]
    pub fn angle(&self) -> Scalar {
        self.rotation.angle()
    }

    /// The body's transform (local → world).
    #[inline]
    #[must_use]
    pub fn transform(&self) -> Transform {
        Transform::new(self.position, self.rotation)
    }

    /// Linear velocity of the centre of mass (m/s).
    #[inline]
    #[must_use]
    pub fn linear_velocity(&self) -> Vector2 {
        self.linear_velocity
    }

    /// Angular velocity (rad/s, counter-clockwise positive).
    #[inline]
    #[must_use]
    pub fn angular_velocity(&self) -> Scalar {
        self.angular_velocity
    }

    /// Velocity of the world point `p` attached to the body (m/s).
    #[must_use]
    pub fn velocity_at(&self, p: Vector2) -> Vector2 {
        self.velocity_at_offset(p - self.position)
    }

    /// Velocity of the point at offset `r` from the centre of mass (m/s).
    #[inline]
    #[must_use]
    pub fn velocity_at_offset(&self, r: Vector2) -> Vector2 {
        self.linear_velocity + Vector2::cross_sv(self.angular_velocity, r)
    }

    /// The shape: for a compound body, its first shape in that shape's own
    /// frame (see [`World::shape`](crate::World::shape) for every shape and
    /// its place on the body).
    #[inline]
    #[must_use]
    pub fn shape(&self) -> Shape {
        self.shape
    }

    /// How many shapes the body has (1 unless shapes were added with
    /// [`World::add_shape`](crate::World::add_shape)).
    #[inline]
    #[must_use]
    pub fn shape_count(&self) -> usize {
        usize::from(self.shape_count)
    }

    /// Static, kinematic or dynamic.
    #[inline]
    #[must_use]
    pub fn body_type(&self) -> BodyType {
        self.body_type
    }

    /// True for static bodies.
    #[inline]
    #[must_use]
    pub fn is_static(&self) -> bool {
        self.body_type == BodyType::Static
    }

    /// True for dynamic bodies.
    #[inline]
    #[must_use]
    pub fn is_dynamic(&self) -> bool {
        self.body_type == BodyType::Dynamic
    }

    /// Mass in kg (0 for static and kinematic bodies).
    #[inline]
    #[must_use]
    pub fn mass(&self) -> Scalar {
        self.mass.mass
    }

    /// 1 / mass (0 for static and kinematic bodies).
    #[inline]
    #[must_use]
    pub fn inv_mass(&self) -> Scalar {
        self.mass.inv_mass
    }

    /// Moment of inertia about the centre of mass (kg·m²).
    #[inline]
    #[must_use]
    pub fn inertia(&self) -> Scalar {
        self.mass.inertia
    }

    /// 1 / inertia (0 for static and kinematic bodies).
    #[inline]
    #[must_use]
    pub fn inv_inertia(&self) -> Scalar {
        self.mass.inv_inertia
    }

    /// All mass properties.
    #[inline]
    #[must_use]
    pub fn mass_data(&self) -> MassData {
        self.mass
    }

    /// Friction coefficient.
    #[inline]
    #[must_use]
    pub fn friction(&self) -> Scalar {
        self.friction
    }

    /// Restitution.
    #[inline]
    #[must_use]
    pub fn restitution(&self) -> Scalar {
        self.restitution
    }

    /// Collision group bits.
    #[inline]
    #[must_use]
    pub fn collision_groups(&self) -> u32 {
        self.collision_groups
    }

    /// Collision level.
    #[inline]
    #[must_use]
    pub fn collision_level(&self) -> u32 {
        self.collision_level
    }

    /// The game's user data word.
    #[inline]
    #[must_use]
    pub fn user_data(&self) -> u64 {
        self.user_data
    }

    /// Sets the game's user data word.
    #[inline]
    pub fn set_user_data(&mut self, data: u64) {
        self.user_data = data;
    }

    /// True when the body is a bullet (see [`BodyDef::bullet`]).
    #[inline]
    #[must_use]
    pub fn is_bullet(&self) -> bool {
        self.bullet
    }

    /// Marks the body a bullet or not (see [`BodyDef::bullet`]); takes effect
    /// from the next step. Part of the snapshot and the state hash. A sensor
    /// is never a bullet: on a sensor the call changes nothing.
    #[inline]
    pub fn set_bullet(&mut self, on: bool) {
        self.bullet = on && !self.sensor;
    }

    /// True when the body is a sensor (see [`BodyDef::sensor`]): it reports
    /// overlaps as sensor events and never pushes anything.
    #[inline]
    #[must_use]
    pub fn is_sensor(&self) -> bool {
        self.sensor
    }

    /// True when the body never rotates (see [`BodyDef::fixed_rotation`]).
    #[inline]
    #[must_use]
    pub fn is_fixed_rotation(&self) -> bool {
        self.fixed_rotation
    }

    /// Linear damping, 1/s (see [`BodyDef::linear_damping`]).
    #[inline]
    #[must_use]
    pub fn linear_damping(&self) -> Scalar {
        self.linear_damping
    }

    /// Angular damping, 1/s (see [`BodyDef::angular_damping`]).
    #[inline]
    #[must_use]
    pub fn angular_damping(&self) -> Scalar {
        self.angular_damping
    }

    /// Factor on the gravity generators' acceleration (see
    /// [`BodyDef::gravity_scale`]).
    #[inline]
    #[must_use]
    pub fn gravity_scale(&self) -> Scalar {
        self.gravity_scale
    }

    /// Box2D's collision filter: category, mask and group (see
    /// [`CollisionFilter`]).
    #[inline]
    #[must_use]
    pub fn filter(&self) -> CollisionFilter {
        self.filter
    }

    /// True once the body left the world bounds: it is frozen until
    /// [`World::set_position`](crate::World::set_position) brings it back or the
    /// game removes it. A frozen body keeps zero velocity and is moved by
    /// nothing: not integrated, not collided, not pushed by force generators,
    /// joints or game constraints (impulses and velocity changes on it are
    /// ignored). The solver treats it as a static body, so a body jointed to it
    /// is held as if anchored to a fixed point.
    #[inline]
    #[must_use]
    pub fn is_out_of_bounds(&self) -> bool {
        self.out_of_bounds
    }

    /// World-space bounding box (m).
    #[inline]
    #[must_use]
    pub fn aabb(&self) -> Rect {
        self.aabb
    }

    /// Bounding radius about the centre of mass (m).
    #[inline]
    #[must_use]
    pub fn bounding_radius(&self) -> Scalar {
        self.radius
    }

    /// True when the step moves this body (dynamic or kinematic, inside the bounds).
    #[inline]
    pub(crate) fn moved_by_step(&self) -> bool {
        self.body_type != BodyType::Static && !self.out_of_bounds
    }

    /// Sets the linear velocity (m/s). Ignored for static and frozen bodies; the
    /// step clamps it to the world's speed limit.
    #[inline]
    pub fn set_linear_velocity(&mut self, v: Vector2) {
        if self.moved_by_step() {
            self.linear_velocity = v;
        }
    }

    /// Sets the angular velocity (rad/s). Ignored for static, frozen and
    /// fixed-rotation bodies.
    #[inline]
    pub fn set_angular_velocity(&mut self, w: Scalar) {
        if self.moved_by_step() && !self.fixed_rotation {
            self.angular_velocity = w;
        }
    }

    /// Applies an impulse (N·s) at the centre of mass: Δv = J / m. Dynamic bodies only.
    #[inline]
    pub fn apply_linear_impulse(&mut self, impulse: Vector2) {
        if self.is_dynamic() && !self.out_of_bounds {
            self.linear_velocity += impulse * self.mass.inv_mass;
        }
    }

    /// Applies an angular impulse (N·m·s): Δω = L / I. Dynamic bodies only;
    /// none on a fixed-rotation body (its inertia counts as infinite).
    #[inline]
    pub fn apply_angular_impulse(&mut self, impulse: Scalar) {
        if self.is_dynamic() && !self.out_of_bounds && !self.fixed_rotation {
            self.angular_velocity += impulse * self.mass.inv_inertia;
        }
    }

    /// Applies an impulse (N·s) at the world point `p`, changing both velocities.
    #[inline]
    pub fn apply_impulse_at(&mut self, impulse: Vector2, p: Vector2) {
        self.apply_linear_impulse(impulse);
        self.apply_angular_impulse((p - self.position).cross(impulse));
    }

    /// Applies a force (N) at the centre of mass for `dt` seconds: an impulse F·dt.
    #[inline]
    pub fn apply_force(&mut self, force: Vector2, dt: Scalar) {
        self.apply_linear_impulse(force * dt);
    }

    /// Changes the linear velocity by `dv` (m/s) whatever the mass: how gravity
    /// acts. Dynamic bodies only.
    #[inline]
    pub fn add_linear_velocity(&mut self, dv: Vector2) {
        if self.is_dynamic() && !self.out_of_bounds {
            self.linear_velocity += dv;
        }
    }
}

/// The bounding radius of `shape` about the origin of its frame (m): 0 for
/// a polygon whose path is gone.
pub(crate) fn shape_radius(shape: Shape, paths: &ShapeStore<'_>) -> Scalar {
    match shape {
        Shape::Circle { radius } => radius,
        Shape::Polygon(h) => paths.get(h).map_or(ZERO, PolygonPath::radius),
        Shape::Capsule(c) => c.bounding_radius(),
        Shape::Segment(s) => s.bounding_radius(),
        Shape::Chain(h) => paths.chains.radius(h),
    }
}

/// The bounding radius of a body's shapes about its centre of mass (m): for
/// a compound body the largest of each shape's offset length plus its own
/// radius (rounded up by one unit of 2^-32 m, so it bounds the exact value).
pub(crate) fn body_radius(b: &Body, paths: &ShapeStore<'_>) -> Scalar {
    if !is_compound(b) {
        return shape_radius(b.shape, paths);
    }
    shapes_of(b, paths)
        .map(|(_, s)| s.local.p.length() + shape_radius(s.shape, paths) + Scalar::DELTA)
        .fold(ZERO, Scalar::max)
}

/// The world bounding box of a body at its current transform (for a
/// compound body, the union of its shapes' boxes).
pub(crate) fn compute_aabb(b: &Body, paths: &ShapeStore<'_>) -> Rect {
    if !is_compound(b) {
        return shape_aabb(b.shape, b.transform(), b.radius, paths);
    }
    let xf = b.transform();
    let mut boxes = shapes_of(b, paths).map(|(_, s)| shape_aabb(s.shape, xf.compose(s.local), ZERO, paths));
    let first = boxes.next().unwrap_or(Rect { min: b.position, max: b.position });
    boxes.fold(first, Rect::union)
}

/// The world bounding box of `shape` in frame `xf` (a polygon whose path is
/// gone: the box of `fallback_radius` about the frame's origin).
pub(crate) fn shape_aabb(
    shape: Shape,
    xf: Transform,
    fallback_radius: Scalar,
    paths: &ShapeStore<'_>,
) -> Rect {
    match shape {
        Shape::Circle { radius } => Rect::from_center(xf.p, Vector2::new(radius, radius)),
        Shape::Polygon(h) => match paths.get(h) {
            Some(p) => {
                // A sharp polygon's box is already in order, so growing it by
                // 0 would change nothing: the out-of-line `expand` is skipped
                // (with the products below, the boxes' functions on mixed
                // 180 steps 26.6 -> 22.6 M instructions).
                let r = p.rounding();
                let aabb = polygon_aabb(p.vertices(), xf);
                if r == ZERO {
                    aabb
                } else {
                    aabb.expand(r)
                }
            }
            None => Rect::from_center(xf.p, Vector2::new(fallback_radius, fallback_radius)),
        },
        Shape::Capsule(c) => c.aabb(xf),
        Shape::Segment(s) => s.aabb(xf),
        Shape::Chain(h) => paths.chains.aabb(h, xf).unwrap_or(Rect { min: xf.p, max: xf.p }),
    }
}

/// The bounding box of `vertices` mapped by `xf`: the least and greatest of
/// `xf.apply(v)` over the vertices, per coordinate (the point `xf.p` for no
/// vertices).
///
/// Computed with fewer operations but to the same bits. The translation is
/// added once to the extremes of the rotated vertices instead of to every
/// vertex: a saturating sum is non-decreasing in each operand, so adding `p`
/// commutes with taking the least or greatest. A rectangle laid out as
/// [`PolygonPath::rectangle`] makes it (the four corners of {x0, x1} × {y0, y1}
/// in turn, see [`is_grid_rectangle`])
/// takes eight products instead of sixteen: a rotated x is `c·x − s·y`,
/// non-decreasing in `c·x` and non-increasing in `s·y`, so over the four
/// corners it is least at the least `c·x` and the greatest `s·y` (and the
/// other way round for the greatest); a rotated y, `s·x + c·y`, is
/// non-decreasing in both. Any other polygon reuses the products of a
/// coordinate equal to the previous vertex's (a regular hexagon's sides share
/// x, a triangle's base y).
///
/// A turned body's rotation has both parts below 1 in magnitude: its products
/// skip the saturation test ([`mul_below_one`], the same bits).
pub(crate) fn polygon_aabb(vertices: &[Vector2], xf: Transform) -> Rect {
    if below_one(xf.q.c) && below_one(xf.q.s) {
        polygon_aabb_by(vertices, xf, mul_below_one)
    } else {
        polygon_aabb_by(vertices, xf, |k, x| k * x)
    }
}

/// [`polygon_aabb`] with `mul(k, x)` for each product `k * x` of a part `k` of
/// the rotation and a coordinate `x`.
#[inline(always)]
fn polygon_aabb_by(vertices: &[Vector2], xf: Transform, mul: impl Fn(Scalar, Scalar) -> Scalar) -> Rect {
    let (c, s) = (xf.q.c, xf.q.s);
    let (lo, hi) = match vertices {
        [v0, v1, v2, v3] if is_grid_rectangle(*v0, *v1, *v2, *v3) => {
            let (cx0, cx1, sx0, sx1) = (mul(c, v0.x), mul(c, v2.x), mul(s, v0.x), mul(s, v2.x));
            let (sy0, sy1, cy0, cy1) = (mul(s, v0.y), mul(s, v2.y), mul(c, v0.y), mul(c, v2.y));
            let lo = Vector2::new(cx0.min(cx1) - sy0.max(sy1), sx0.min(sx1) + cy0.min(cy1));
            let hi = Vector2::new(cx0.max(cx1) - sy0.min(sy1), sx0.max(sx1) + cy0.max(cy1));
            (lo, hi)
        }
        [first, rest @ ..] => {
            // Each vertex rotated as `Rot::rotate` does, `(c·x − s·y, s·x + c·y)`,
            // reusing the products of a coordinate equal to the previous
            // vertex's (the same operands give the same bits).
            let k = [mul(c, first.x), mul(s, first.x), mul(s, first.y), mul(c, first.y)];
            let w = Vector2::new(k[0] - k[2], k[1] + k[3]);
            let (mut lo, mut hi) = (w, w);
            let mut prev = (*first, k);
            for v in rest {
                let (u, k) = prev;
                let [cx, sx] = if u.x == v.x { [k[0], k[1]] } else { [mul(c, v.x), mul(s, v.x)] };
                let [sy, cy] = if u.y == v.y { [k[2], k[3]] } else { [mul(s, v.y), mul(c, v.y)] };
                let w = Vector2::new(cx - sy, sx + cy);
                (lo, hi) = (lo.min(w), hi.max(w));
                prev = (*v, [cx, sx, sy, cy]);
            }
            (lo, hi)
        }
        [] => (Vector2::ZERO, Vector2::ZERO),
    };
    Rect { min: lo + xf.p, max: hi + xf.p }
}

/// True when the four vertices, in turn, are the corners of {v0.x, v2.x} ×
/// {v0.y, v2.y}: consecutive corners share a y, then an x (or an x, then a y).
#[inline]
fn is_grid_rectangle(v0: Vector2, v1: Vector2, v2: Vector2, v3: Vector2) -> bool {
    (v0.y == v1.y && v1.x == v2.x && v2.y == v3.y && v3.x == v0.x)
        || (v0.x == v1.x && v1.y == v2.y && v2.x == v3.x && v3.y == v0.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition: every vertex mapped, then the least and greatest.
    fn aabb_by_definition(vertices: &[Vector2], xf: Transform) -> Rect {
        let mut it = vertices.iter().map(|v| xf.apply(*v));
        let first = it.next().unwrap_or(xf.p);
        it.fold(Rect { min: first, max: first }, |r, v| Rect { min: r.min.min(v), max: r.max.max(v) })
    }

    /// A small deterministic generator (xorshift), for many varied inputs.
    fn next(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn polygon_bounding_box_equals_the_definition_bit_for_bit() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut scalar = |range_bits: u32| {
            let r = next(&mut seed) as i64 >> (64 - range_bits);
            Scalar::from_bits(r)
        };
        for case in 0..20_000 {
            // Rotations near unit length and arbitrary ones; positions small,
            // large and at the edge of the range (where the sums saturate).
            let q = if case % 3 == 0 {
                Rot { c: scalar(34), s: scalar(34) }
            } else {
                Rot::from_angle(scalar(36))
            };
            let p_bits = [40, 52, 64][case % 3];
            let p = Vector2::new(scalar(p_bits), scalar(p_bits));
            let (x0, x1, y0, y1) = (scalar(40), scalar(40), scalar(40), scalar(40));
            let v = |x, y| Vector2::new(x, y);
            let rect_a = [v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)];
            let rect_b = [v(x0, y0), v(x0, y1), v(x1, y1), v(x1, y0)];
            let other = [v(x0, y0), v(x1, y0), v(x1, y1), v(scalar(40), y1)];
            let tri = [v(x0, y0), v(x1, y1), v(scalar(40), scalar(40))];
            let z = Scalar::ZERO;
            let hex = [v(z, y0), v(-x0, y1), v(-x0, -y1), v(z, -y0), v(x0, -y1), v(x0, y1)];
            let xf = Transform::new(p, q);
            for poly in [&rect_a[..], &rect_b[..], &other[..], &tri[..], &hex[..], &rect_a[..1], &[]] {
                assert_eq!(polygon_aabb(poly, xf), aabb_by_definition(poly, xf), "{poly:?} {xf:?}");
            }
        }
    }
}
