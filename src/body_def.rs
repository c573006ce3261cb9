//! [`BodyDef`]: everything needed to create a body, with a default for every
//! option, and [`MassSpec`] (mass from a density or given outright). The world
//! validates a definition when it builds the body
//! ([`World::add_body`](crate::World::add_body)).

use crate::body::{BodyType, PathHandle, Shape};
use crate::geometry::{Capsule, Segment};
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rot, Vector2};

/// Box2D's collision filter, carried by every body: which categories the body
/// is in, which it collides with, and a group that overrides both.
///
/// Two bodies `a` and `b` pass this filter when
/// * they share a non-zero `group_index`: always if it is positive, never if it
///   is negative (whatever the bits), or else
/// * `a.mask_bits & b.category_bits != 0` and `b.mask_bits & a.category_bits != 0`.
///
/// It is combined with the manual's rules: a pair collides only when at least
/// one body is dynamic, the bodies share no collision-group bit
/// ([`BodyDef::collision_groups`], a veto even a positive group index does not
/// lift) *and* the pair passes this filter. The default (category 1, mask all,
/// group 0) lets everything collide, so worlds that do not use it behave as
/// before. Queries test a body's category against the query's mask too
/// ([`QueryFilter`](crate::QueryFilter)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CollisionFilter {
    /// The categories this body is in (default `0x1`).
    pub category_bits: u64,
    /// The categories it collides with (default all: `u64::MAX`).
    pub mask_bits: u64,
    /// Bodies sharing a positive group always collide, a negative one never;
    /// 0 (default) is no group.
    pub group_index: i32,
}

impl CollisionFilter {
    /// Category 1, mask all, no group: collides with everything.
    pub const DEFAULT: Self = Self { category_bits: 1, mask_bits: u64::MAX, group_index: 0 };

    /// True when bodies with filters `self` and `other` may collide (Box2D's rule,
    /// see the type's docs).
    #[inline]
    #[must_use]
    pub fn accepts(&self, other: &Self) -> bool {
        if self.group_index == other.group_index && self.group_index != 0 {
            return self.group_index > 0;
        }
        (self.mask_bits & other.category_bits) != 0 && (other.mask_bits & self.category_bits) != 0
    }
}

impl Default for CollisionFilter {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// How the mass of a new body is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MassSpec {
    /// Mass = density (kg/m²) × area.
    Density(Scalar),
    /// This total mass in kg; 0 makes the body static (as in the manual).
    Mass(Scalar),
}

/// Everything needed to create a body; every option has a default.
///
/// ```
/// use arphysics::{BodyDef, Vector2, Scalar};
/// let ball = BodyDef::circle(Scalar::from_num(5))
///     .position(Vector2::from_int(50, 50))
///     .mass(Scalar::from_num(5));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BodyDef {
    /// Shape. Polygon paths must be added to the world first.
    pub shape: Shape,
    /// Static, kinematic or dynamic (default dynamic).
    pub body_type: BodyType,
    /// Position of the centre of mass, m (default origin). For a capsule or a
    /// segment, the point its ends are given from: the body is placed at the
    /// ends' midpoint (see [`BodyDef::capsule`]).
    pub position: Vector2,
    /// Rotation (default none).
    pub rotation: Rot,
    /// Linear velocity, m/s (default 0).
    pub linear_velocity: Vector2,
    /// Angular velocity, rad/s, counter-clockwise positive (default 0).
    pub angular_velocity: Scalar,
    /// Mass or density (default density 1 kg/m²). Ignored for static and
    /// kinematic bodies, whose mass data is all zeros.
    pub mass: MassSpec,
    /// Coulomb friction coefficient, ≥ 0 (default 0.6).
    pub friction: Scalar,
    /// Restitution (bounciness) in [0, 1] (default 0).
    pub restitution: Scalar,
    /// Collision group bits: two bodies sharing any bit never collide (default 0).
    pub collision_groups: u32,
    /// Collision level, selects the collision handler (default 0 = no level).
    pub collision_level: u32,
    /// A word for the game, e.g. its entity id (default 0). Never read by the engine.
    pub user_data: u64,
    /// Swept against dynamic bodies too when fast (default false; see
    /// [`BodyDef::bullet`]).
    pub bullet: bool,
    /// Never rotates (default false; see [`BodyDef::fixed_rotation`]).
    pub fixed_rotation: bool,
    /// Linear damping, 1/s, in [0, [`MAX_BODY_DAMPING`](crate::limits::MAX_BODY_DAMPING)]
    /// (default 0; see [`BodyDef::linear_damping`]).
    pub linear_damping: Scalar,
    /// Angular damping, 1/s, in the same range (default 0).
    pub angular_damping: Scalar,
    /// Factor on the gravity generators' acceleration, in
    /// ±[`MAX_GRAVITY_SCALE`](crate::limits::MAX_GRAVITY_SCALE) (default 1;
    /// see [`BodyDef::gravity_scale`]).
    pub gravity_scale: Scalar,
    /// Box2D's category, mask and group (default: collides with everything).
    pub filter: CollisionFilter,
    /// Detects overlap and never pushes (default false; see [`BodyDef::sensor`]).
    pub sensor: bool,
}

impl BodyDef {
    /// A dynamic circle of `radius` metres.
    #[must_use]
    pub fn circle(radius: Scalar) -> Self {
        Self::with_shape(Shape::Circle { radius })
    }

    /// A dynamic polygon using a path added with
    /// [`World::add_path`](crate::World::add_path).
    #[must_use]
    pub fn polygon(path: PathHandle) -> Self {
        Self::with_shape(Shape::Polygon(path))
    }

    /// A dynamic capsule (made with [`Capsule::new`]), whose centres are given
    /// relative to [`position`](Self::position) in the body's frame.
    ///
    /// A body's position is its centre of mass, so the world places the body
    /// at the midpoint of the two centres and stores them about it, exactly
    /// symmetric (the first centre moves by at most 2^-32 m when the centres'
    /// sum is odd in the last bit): the capsule lands where the definition
    /// puts it, and [`Body::position`](crate::Body::position) reports the
    /// midpoint. A capsule of zero length is a circle.
    ///
    /// ```
    /// use arphysics::{BodyDef, Capsule, Scalar, Vector2};
    /// // A 1.8 m tall character, 0.3 m wide: upright, feet at y = 0.
    /// let (r, foot, head) = (Scalar::lit("0.3"), Scalar::lit("0.3"), Scalar::lit("1.5"));
    /// let body = Capsule::new(Vector2::new(Scalar::ZERO, foot), Vector2::new(Scalar::ZERO, head), r)
    ///     .map(|c| BodyDef::capsule(c).fixed_rotation(true));
    /// assert!(body.is_ok());
    /// ```
    #[must_use]
    pub fn capsule(capsule: Capsule) -> Self {
        Self::with_shape(Shape::Capsule(capsule))
    }

    /// A **static** segment (made with [`Segment::new`]), whose ends are given
    /// relative to [`position`](Self::position): ground, walls, ramps. Placed
    /// as [`capsule`](Self::capsule) places its centres (the body goes to the
    /// midpoint). A segment has no area: made dynamic it needs a mass
    /// ([`MassSpec::Mass`], a thin rod's inertia); a density is an error.
    /// Segments never collide with segments.
    #[must_use]
    pub fn segment(segment: Segment) -> Self {
        let mut def = Self::with_shape(Shape::Segment(segment));
        def.body_type = BodyType::Static;
        def
    }

    /// A **static** chain made by [`World::add_chain`](crate::World::add_chain),
    /// its points relative to [`position`](Self::position): terrain whose
    /// links a body slides across without catching on the joins. A chain has
    /// no mass: a kinematic or dynamic chain body is an error when added.
    #[must_use]
    pub fn chain(chain: crate::geometry::ChainHandle) -> Self {
        let mut def = Self::with_shape(Shape::Chain(chain));
        def.body_type = BodyType::Static;
        def
    }

    fn with_shape(shape: Shape) -> Self {
        Self {
            shape,
            body_type: BodyType::Dynamic,
            position: Vector2::ZERO,
            rotation: Rot::IDENTITY,
            linear_velocity: Vector2::ZERO,
            angular_velocity: ZERO,
            mass: MassSpec::Density(scalar::ONE),
            friction: const { Scalar::lit("0.6") },
            restitution: ZERO,
            collision_groups: 0,
            collision_level: 0,
            user_data: 0,
            bullet: false,
            fixed_rotation: false,
            linear_damping: ZERO,
            angular_damping: ZERO,
            gravity_scale: scalar::ONE,
            filter: CollisionFilter::DEFAULT,
            sensor: false,
        }
    }

    /// Sets the position of the centre of mass (m).
    #[must_use]
    pub fn position(mut self, p: Vector2) -> Self {
        self.position = p;
        self
    }

    /// Sets the rotation from an angle in radians.
    #[must_use]
    pub fn angle(mut self, radians: Scalar) -> Self {
        self.rotation = Rot::from_angle(radians);
        self
    }

    /// Sets the rotation.
    #[must_use]
    pub fn rotation(mut self, q: Rot) -> Self {
        self.rotation = q;
        self
    }

    /// Sets the linear velocity (m/s).
    #[must_use]
    pub fn linear_velocity(mut self, v: Vector2) -> Self {
        self.linear_velocity = v;
        self
    }

    /// Sets the angular velocity (rad/s).
    #[must_use]
    pub fn angular_velocity(mut self, w: Scalar) -> Self {
        self.angular_velocity = w;
        self
    }

    /// Sets the body type.
    #[must_use]
    pub fn body_type(mut self, t: BodyType) -> Self {
        self.body_type = t;
        self
    }

    /// Makes the body static (the manual's `setStatic`).
    #[must_use]
    pub fn static_body(self) -> Self {
        self.body_type(BodyType::Static)
    }

    /// Makes the body kinematic.
    #[must_use]
    pub fn kinematic(self) -> Self {
        self.body_type(BodyType::Kinematic)
    }

    /// Sets the total mass in kg, in [[`MIN_MASS`](crate::geometry::mass::MIN_MASS),
    /// [`MAX_MASS`](crate::geometry::mass::MAX_MASS)] (see the limits table in the
    /// crate docs: the moment of inertia it gives must be in range too). As in the
    /// manual, a mass of 0 makes the body static. A static or kinematic body
    /// ignores its mass or density (whatever the value): its mass data is all
    /// zeros, which is what makes it immovable.
    #[must_use]
    pub fn mass(mut self, kg: Scalar) -> Self {
        self.mass = MassSpec::Mass(kg);
        self
    }

    /// Sets the density in kg/m² (mass = density × area).
    #[must_use]
    pub fn density(mut self, kg_per_m2: Scalar) -> Self {
        self.mass = MassSpec::Density(kg_per_m2);
        self
    }

    /// Sets the friction coefficient (≥ 0).
    #[must_use]
    pub fn friction(mut self, mu: Scalar) -> Self {
        self.friction = mu;
        self
    }

    /// Sets the restitution, 0 (no bounce) to 1 (elastic).
    #[must_use]
    pub fn restitution(mut self, e: Scalar) -> Self {
        self.restitution = e;
        self
    }

    /// Sets the collision group bits.
    #[must_use]
    pub fn collision_groups(mut self, bits: u32) -> Self {
        self.collision_groups = bits;
        self
    }

    /// Sets the collision level.
    #[must_use]
    pub fn collision_level(mut self, level: u32) -> Self {
        self.collision_level = level;
        self
    }

    /// Sets the game's user data word.
    #[must_use]
    pub fn user_data(mut self, data: u64) -> Self {
        self.user_data = data;
        self
    }

    /// Marks the body a bullet (Box2D's term): when it is fast, continuous
    /// collision sweeps it against dynamic bodies as well as static and
    /// kinematic ones, so a small fast projectile cannot pass through a thin
    /// dynamic box (see [`crate::continuous`]). Every fast dynamic body is
    /// already swept against static and kinematic bodies. Costs a sweep per
    /// nearby body each step it is fast. On a static or kinematic body the
    /// flag is kept but does nothing (they are never swept).
    #[must_use]
    pub fn bullet(mut self, on: bool) -> Self {
        self.bullet = on;
        self
    }

    /// Keeps the body from rotating (Box2D's `fixedRotation`, rapier's
    /// `lock_rotations`): contacts, joints and impulses see an infinite moment
    /// of inertia, and its angular velocity stays exactly 0, so its angle never
    /// changes unless the game sets it. For a player character that must stay
    /// upright.
    #[must_use]
    pub fn fixed_rotation(mut self, on: bool) -> Self {
        self.fixed_rotation = on;
        self
    }

    /// Sets the linear damping c (1/s), in [0, [`MAX_BODY_DAMPING`](crate::limits::MAX_BODY_DAMPING)]:
    /// each sub-step of h seconds scales the velocity by 1 / (1 + h·c) (as Box2D
    /// does), so without other forces the speed decays as e^(−c·t). Air drag for a
    /// top-down game. Dynamic bodies only.
    #[must_use]
    pub fn linear_damping(mut self, c: Scalar) -> Self {
        self.linear_damping = c;
        self
    }

    /// Sets the angular damping (1/s), in the same range, acting on the
    /// angular velocity the same way.
    #[must_use]
    pub fn angular_damping(mut self, c: Scalar) -> Self {
        self.angular_damping = c;
        self
    }

    /// Sets the gravity scale, in ±[`MAX_GRAVITY_SCALE`](crate::limits::MAX_GRAVITY_SCALE)
    /// (default 1): the built-in [`GravityForceGenerator`](crate::GravityForceGenerator)
    /// and [`GravityToPointForceGenerator`](crate::GravityToPointForceGenerator)
    /// multiply their acceleration by it (0 floats, −1 falls up). Other
    /// generators ignore it; a game's own can read [`Body::gravity_scale`](crate::Body::gravity_scale).
    #[must_use]
    pub fn gravity_scale(mut self, scale: Scalar) -> Self {
        self.gravity_scale = scale;
        self
    }

    /// Sets Box2D's collision filter (see [`CollisionFilter`]).
    #[must_use]
    pub fn filter(mut self, filter: CollisionFilter) -> Self {
        self.filter = filter;
        self
    }

    /// Makes the body a sensor (Box2D's and rapier's term): it detects the
    /// bodies that overlap it and reports them as sensor events
    /// ([`World::sensor_begin_events`](crate::World::sensor_begin_events)),
    /// but never pushes: no contact is solved with it, no velocity changes,
    /// continuous collision ignores it. Overlap is true overlap (no
    /// speculative margin). Sensors do not detect other sensors; a static
    /// sensor detects dynamic and kinematic bodies (a coin, a trigger zone).
    /// A sensor cannot be a bullet: [`World::add_body`](crate::World::add_body)
    /// refuses the pair.
    #[must_use]
    pub fn sensor(mut self) -> Self {
        self.sensor = true;
        self
    }
}
