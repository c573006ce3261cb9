//! Compound bodies: several shapes on one body ([`World::add_shape`]).
//!
//! A body made with a [`BodyDef`](crate::BodyDef) has one shape, kept on the
//! body itself (the fast path: most bodies of a game). When a second shape is
//! added, every shape of the body, the first included, moves into the world's
//! shape store: a slot per shape holding the shape, its place on the body (a
//! local [`Transform`] about the body's centre of mass), its own mass, friction,
//! restitution, collision filter and sensor flag, linked in shape order. The
//! body keeps a copy of its first shape's data (what [`Body::shape`],
//! [`Body::friction`] and the other single-shape readers return).
//!
//! The body's mass data is [`compound_mass`] of its shapes' parts (the
//! parallel-axis theorem about their common centre), and its position stays
//! its centre of mass: adding or removing a shape moves the body to the new
//! centre and every shape's offset by the opposite amount, so the shapes stay
//! where they are in the world (exactly for a body at rotation zero; otherwise
//! within the rounding of one rotation, 2^-32 m).
//!
//! Arbiters are per shape pair (see [`Arbiter::shape_a`]); contact events name
//! the shapes; queries, ray and shape casts and continuous collision look at
//! every shape.
//!
//! [`World::add_shape`]: crate::World::add_shape
//! [`Body::shape`]: crate::Body::shape
//! [`Body::friction`]: crate::Body::friction
//! [`Arbiter::shape_a`]: crate::Arbiter::shape_a
//! [`compound_mass`]: crate::geometry::compound_mass

use crate::body::{Body, CollisionFilter, Shape, ShapeStore};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Transform, Vector2};

/// The most shapes one body can carry (the arbiter holds a shape index in
/// three bits, see [`MAX_SHAPE_INDEX`](crate::arbiter::MAX_SHAPE_INDEX)).
pub const MAX_SHAPES_PER_BODY: usize = 8;

/// No slot: the end of a body's shape list, or a body whose one shape is on
/// the body itself.
pub(crate) const NO_SHAPE: u32 = u32::MAX;

/// A shape to add to a body ([`World::add_shape`](crate::World::add_shape)).
///
/// ```
/// use arphysics::{Scalar, ShapeDef, Vector2};
/// // A 0.5 m wheel 1 m to the right of the body's centre of mass.
/// let wheel = ShapeDef::circle(Scalar::lit("0.5"))
///     .offset(Vector2::from_int(1, 0))
///     .friction(Scalar::lit("0.9"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShapeDef {
    /// The shape (not a chain: a chain is a body of its own). A capsule's
    /// centres and a segment's ends are given in the shape's own frame, which
    /// `offset` and `rotation` place on the body.
    pub shape: Shape,
    /// Where the shape's frame sits in the body's frame (m), relative to the
    /// body's position (its centre of mass) when the shape is added.
    pub offset: Vector2,
    /// The shape frame's rotation on the body (default none).
    pub rotation: Rot,
    /// Density, kg/m² (default 1). Ignored for static and kinematic bodies;
    /// a segment has no area and adds no mass.
    pub density: Scalar,
    /// Coulomb friction coefficient, ≥ 0 (default 0.6).
    pub friction: Scalar,
    /// Restitution in [0, 1] (default 0).
    pub restitution: Scalar,
    /// Box2D's category, mask and group, for this shape (default: collides
    /// with everything).
    pub filter: CollisionFilter,
    /// Detects overlap and never pushes (default false): a sensor shape on a
    /// solid body (a character's ground probe).
    pub sensor: bool,
}

impl ShapeDef {
    /// A shape with the defaults: at the body's centre, density 1, friction
    /// 0.6, no restitution, the default filter, not a sensor.
    #[must_use]
    pub fn new(shape: Shape) -> Self {
        Self {
            shape,
            offset: Vector2::ZERO,
            rotation: Rot::IDENTITY,
            density: Scalar::ONE,
            friction: Scalar::lit("0.6"),
            restitution: ZERO,
            filter: CollisionFilter::DEFAULT,
            sensor: false,
        }
    }

    /// A circle of `radius` metres.
    #[must_use]
    pub fn circle(radius: Scalar) -> Self {
        Self::new(Shape::Circle { radius })
    }

    /// A polygon using a path added with [`World::add_path`](crate::World::add_path).
    #[must_use]
    pub fn polygon(path: crate::body::PathHandle) -> Self {
        Self::new(Shape::Polygon(path))
    }

    /// A capsule, its centres in the shape's frame.
    #[must_use]
    pub fn capsule(capsule: crate::geometry::Capsule) -> Self {
        Self::new(Shape::Capsule(capsule))
    }

    /// A segment, its ends in the shape's frame.
    #[must_use]
    pub fn segment(segment: crate::geometry::Segment) -> Self {
        Self::new(Shape::Segment(segment))
    }

    /// Places the shape's frame at `offset` from the body's centre of mass
    /// (body frame, m).
    #[must_use]
    pub fn offset(mut self, offset: Vector2) -> Self {
        self.offset = offset;
        self
    }

    /// Turns the shape's frame by `radians` on the body.
    #[must_use]
    pub fn angle(mut self, radians: Scalar) -> Self {
        self.rotation = Rot::from_angle(radians);
        self
    }

    /// Density, kg/m².
    #[must_use]
    pub fn density(mut self, kg_per_m2: Scalar) -> Self {
        self.density = kg_per_m2;
        self
    }

    /// Friction coefficient.
    #[must_use]
    pub fn friction(mut self, mu: Scalar) -> Self {
        self.friction = mu;
        self
    }

    /// Restitution.
    #[must_use]
    pub fn restitution(mut self, e: Scalar) -> Self {
        self.restitution = e;
        self
    }

    /// Collision filter.
    #[must_use]
    pub fn filter(mut self, filter: CollisionFilter) -> Self {
        self.filter = filter;
        self
    }

    /// Makes the shape a sensor.
    #[must_use]
    pub fn sensor(mut self) -> Self {
        self.sensor = true;
        self
    }
}

/// One shape of a body as the world holds it ([`World::shape`](crate::World::shape)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BodyShape {
    /// The shape, in its own frame.
    pub shape: Shape,
    /// The shape's frame in the body's frame (about the centre of mass).
    pub local: Transform,
    /// The shape's own mass (kg; 0 on a static or kinematic body and for a
    /// segment).
    pub mass: Scalar,
    /// The shape's moment of inertia about its own centre (kg·m²).
    pub inertia: Scalar,
    /// Friction coefficient.
    pub friction: Scalar,
    /// Restitution.
    pub restitution: Scalar,
    /// Collision filter.
    pub filter: CollisionFilter,
    /// Sensor flag.
    pub sensor: bool,
}

impl BodyShape {
    /// The first shape of a one-shape body: its data is the body's.
    #[inline]
    pub(crate) fn of_body(b: &Body) -> Self {
        Self {
            shape: b.shape,
            local: Transform::IDENTITY,
            mass: b.mass.mass,
            inertia: b.mass.inertia,
            friction: b.friction,
            restitution: b.restitution,
            filter: b.filter,
            sensor: b.sensor,
        }
    }

    /// The shape's frame in the world, for its body at `body` (a one-shape
    /// body's shape is at the body's own frame).
    #[inline]
    pub(crate) fn world(&self, body: Transform, compound: bool) -> Transform {
        if compound {
            body.compose(self.local)
        } else {
            body
        }
    }
}

/// A slot of the world's shape store: one shape of a compound body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ShapeSlot {
    /// The body slot that owns it.
    pub(crate) owner: u32,
    /// The next shape of the body ([`NO_SHAPE`] after the last).
    pub(crate) next: u32,
    /// The shape and its data.
    pub(crate) data: BodyShape,
}

/// True when `b` keeps its shapes in the shape store.
#[inline]
pub(crate) fn is_compound(b: &Body) -> bool {
    b.shapes != NO_SHAPE
}

/// Every shape of body `b` in order, with its index.
pub(crate) fn shapes_of<'s>(
    b: &Body,
    store: &'s ShapeStore<'_>,
) -> impl Iterator<Item = (u32, BodyShape)> + 's {
    let single = (!is_compound(b)).then(|| BodyShape::of_body(b));
    let mut at = b.shapes;
    let mut index = 0u32;
    let mut first = single;
    core::iter::from_fn(move || {
        if let Some(s) = first.take() {
            index = 1;
            return Some((0, s));
        }
        if single.is_some() || index as usize >= MAX_SHAPES_PER_BODY {
            return None;
        }
        let slot = store.slots.get_at(at)?;
        at = slot.next;
        let i = index;
        index = index.saturating_add(1);
        Some((i, slot.data))
    })
}

/// One shape's data as the step reads it: implemented by a one-shape
/// [`Body`] (its own fields: the common case, nothing copied) and by a
/// compound body's [`BodyShape`], so the pair code is compiled once for each.
pub(crate) trait ShapeData {
    /// True when the shape has a frame of its own on the body.
    const PLACED: bool;
    /// The shape.
    fn geometry(&self) -> &Shape;
    /// The collision filter.
    fn filters(&self) -> &CollisionFilter;
    /// The sensor flag.
    fn senses(&self) -> bool;
    /// Friction and restitution.
    fn material(&self) -> (Scalar, Scalar);
    /// The shape's frame in the world for its body at `body`.
    fn place(&self, body: Transform) -> Transform;
}

/// The accessors of [`ShapeData`] for a type whose fields carry the same
/// names (`shape`, `filter`, `sensor`, `friction`, `restitution`).
macro_rules! shape_fields {
    () => {
        #[inline(always)]
        fn geometry(&self) -> &Shape {
            &self.shape
        }
        #[inline(always)]
        fn filters(&self) -> &CollisionFilter {
            &self.filter
        }
        #[inline(always)]
        fn senses(&self) -> bool {
            self.sensor
        }
        #[inline(always)]
        fn material(&self) -> (Scalar, Scalar) {
            (self.friction, self.restitution)
        }
    };
}

impl ShapeData for Body {
    const PLACED: bool = false;
    shape_fields!();
    #[inline(always)]
    fn place(&self, body: Transform) -> Transform {
        body
    }
}

impl ShapeData for BodyShape {
    const PLACED: bool = true;
    shape_fields!();
    #[inline(always)]
    fn place(&self, body: Transform) -> Transform {
        body.compose(self.local)
    }
}

/// Shape `index` of body `b` (0 is the first), copied; `None` past its last.
#[inline]
pub(crate) fn shape_of(b: &Body, index: u32, store: &ShapeStore<'_>) -> Option<BodyShape> {
    if !is_compound(b) {
        return (index == 0).then(|| BodyShape::of_body(b));
    }
    let mut at = b.shapes;
    for _ in 0..index {
        at = store.slots.get_at(at)?.next;
    }
    store.slots.get_at(at).map(|s| s.data)
}
