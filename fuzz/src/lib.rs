//! Shared decoding and execution for the arphysics fuzz targets.
//!
//! The fuzzer's bytes decode (with `arbitrary`) into an [`Input`]: a world
//! specification and a list of [`Op`]s, each one public API call with arbitrary
//! arguments (raw `Scalar` bits included). A [`Runner`] applies the ops to one
//! world and returns an [`Outcome`] per op, so that several worlds driven by the
//! same ops can be compared result by result and hash by hash.
//!
//! The harness itself never does raw arithmetic on `Scalar` (which would panic
//! on overflow with debug assertions): it uses the engine's saturating value types
//! and `saturating_*`, so every panic the fuzzer reports comes from the engine.

use arbitrary::Arbitrary;
use arphysics::constraint::Constraint;
use arphysics::force::Targets;
use arphysics::index::SortAndSweepIndex;
use arphysics::query::{QueryFilter, QueryShape, RayHit};
use arphysics::CollisionFilter;
use arphysics::{
    Arbiter, Body, BodyDef, BodyHandle, BodyType, CallbackContext, Capacities, Capsule, ChainPath,
    ConstraintHandle, Error, FnHandler, ForceGenerator, Generator, GeneratorHandle, GeneratorMut,
    GravityForceGenerator, GravityToPointForceGenerator, Handle, Handler, Hook, Index, Joint, JointDef,
    JointHandle, JointKind, LinearForceGenerator, MaxTorque, Motor, PairSink, PathHandle, PolygonPath, Proxy,
    Rect, Rot, Scalar, Segment, Shape, SpatialIndex, Storage, Transform, Vector2, World, WorldDef,
};

/// Most ops a run executes (keeps one input's run short).
pub const MAX_OPS: usize = 160;
/// Most world steps a run takes in total.
pub const MAX_STEPS: u32 = 240;

// ---- values -------------------------------------------------------------------

/// An arbitrary `Scalar`, biased towards values a game would use but able to be
/// any bit pattern.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum S {
    /// n / 16: −2048 … 2048 in steps of 1/16.
    Small(i16),
    /// n / 65536: −32768 … 32768, fine resolution.
    Fine(i32),
    /// Any bit pattern.
    Raw(i64),
    /// Boundary values.
    Special(Special),
    /// (n + 1) / 16: a positive size, mass or coefficient, 1/16 … 16.
    Pos(u8),
}

/// Boundary values of the engine's ranges.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Special {
    Zero,
    Delta,
    NegDelta,
    One,
    NegOne,
    Max,
    Min,
    MaxCoordinate,
    NegMaxCoordinate,
    MaxSpeed,
    MaxRadius,
    Pi,
    NegPi,
    Quarter,
    Huge,
    NegHuge,
}

impl S {
    /// The value.
    #[must_use]
    pub fn get(self) -> Scalar {
        match self {
            Self::Small(n) => Scalar::from_bits(i64::from(n) << 28),
            Self::Fine(n) => Scalar::from_bits(i64::from(n) << 16),
            Self::Raw(bits) => Scalar::from_bits(bits),
            Self::Pos(n) => Scalar::from_bits((i64::from(n) + 1) << 28),
            Self::Special(s) => match s {
                Special::Zero => Scalar::ZERO,
                Special::Delta => Scalar::DELTA,
                Special::NegDelta => Scalar::from_bits(-1),
                Special::One => Scalar::ONE,
                Special::NegOne => Scalar::NEG_ONE,
                Special::Max => Scalar::MAX,
                Special::Min => Scalar::MIN,
                Special::MaxCoordinate => Scalar::from_bits(1 << 52),
                Special::NegMaxCoordinate => Scalar::from_bits(-(1 << 52)),
                Special::MaxSpeed => Scalar::from_bits(2048 << 32),
                Special::MaxRadius => Scalar::from_bits(128 << 32),
                Special::Pi => Scalar::PI,
                Special::NegPi => -Scalar::PI,
                Special::Quarter => Scalar::from_bits(1 << 30),
                Special::Huge => Scalar::from_bits(i64::MAX >> 1),
                Special::NegHuge => Scalar::from_bits(i64::MIN >> 1),
            },
        }
    }
}

/// An arbitrary vector.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct V(pub S, pub S);

impl V {
    /// The value.
    #[must_use]
    pub fn get(self) -> Vector2 {
        Vector2::new(self.0.get(), self.1.get())
    }
}

/// A point: inside the world bounds (as fractions of its size) or anywhere.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Point {
    /// `min + size · (fx, fy) / 65536`: inside the bounds (or on their edge).
    InBounds(u16, u16),
    /// Anywhere.
    Abs(V),
    /// Near a body (or the centre of the bounds): offset by (dx, dy) / 16 m.
    Near(HandleRef, i8, i8),
}

impl Point {
    /// The point in a world with these bounds.
    #[must_use]
    pub fn get(self, bounds: Rect) -> Vector2 {
        self.resolve(bounds, None)
    }

    /// The point, with `Near` resolved against the runner's bodies.
    fn resolve(self, bounds: Rect, near: Option<(&World<'_>, &[BodyHandle])>) -> Vector2 {
        match self {
            Self::Near(h, dx, dy) => {
                let base = near
                    .and_then(|(w, hs)| w.body(h.get(hs)).ok().map(Body::position))
                    .unwrap_or_else(|| bounds.center());
                base + Vector2::new(
                    Scalar::from_bits(i64::from(dx) << 28),
                    Scalar::from_bits(i64::from(dy) << 28),
                )
            }
            Self::InBounds(fx, fy) => Vector2::new(
                lerp_bits(bounds.min.x, bounds.max.x, fx),
                lerp_bits(bounds.min.y, bounds.max.y, fy),
            ),
            Self::Abs(v) => v.get(),
        }
    }
}

/// `lo + (hi − lo) · f / 65536`, exactly, in 128-bit integers (no overflow).
fn lerp_bits(lo: Scalar, hi: Scalar, f: u16) -> Scalar {
    let (lo, hi) = (i128::from(lo.to_bits()), i128::from(hi.to_bits()));
    let v = lo + (hi - lo) * i128::from(f) / 65536;
    Scalar::from_bits(v.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64)
}

/// A time step: mostly the usual ones, sometimes anything.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dt {
    Sixtieth,
    Thirtieth,
    Hundredth,
    Quarter,
    Any(S),
}

impl Dt {
    /// The value.
    #[must_use]
    pub fn get(self) -> Scalar {
        match self {
            Self::Sixtieth => Scalar::ONE / 60,
            Self::Thirtieth => Scalar::ONE / 30,
            Self::Hundredth => Scalar::ONE / 100,
            Self::Quarter => Scalar::from_bits(1 << 30),
            Self::Any(s) => s.get(),
        }
    }
}

// ---- world --------------------------------------------------------------------

/// World bounds.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bounds {
    /// (0, 0) – (100, 100), the tests' world.
    Small,
    /// (−200, −200) – (200, 200).
    Centred,
    /// ±2^20 m, the largest allowed.
    Largest,
    /// (0, 0) – (w, h).
    Size(S, S),
    /// Any corners (possibly inverted or out of range).
    Corners(V, V),
}

impl Bounds {
    /// The rectangle.
    #[must_use]
    pub fn get(self) -> Rect {
        let r = |a: i64, b: i64| Rect {
            min: Vector2::new(Scalar::from_bits(a << 32), Scalar::from_bits(a << 32)),
            max: Vector2::new(Scalar::from_bits(b << 32), Scalar::from_bits(b << 32)),
        };
        match self {
            Self::Small => r(0, 100),
            Self::Centred => r(-200, 200),
            Self::Largest => r(-(1 << 20), 1 << 20),
            Self::Size(w, h) => Rect { min: Vector2::ZERO, max: Vector2::new(w.get(), h.get()) },
            Self::Corners(a, b) => Rect { min: a.get(), max: b.get() },
        }
    }
}

/// A world's definition and capacities.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct WorldSpec {
    pub bounds: Bounds,
    pub max_linear_speed: Option<S>,
    pub max_angular_speed: Option<S>,
    /// Taken modulo 20: 0 … 19 (0 and 17 … 19 are outside the documented 1 … 16;
    /// larger values only make steps slow, see the report on `substeps`).
    pub substeps: Option<u8>,
    pub contact_hertz: Option<S>,
    pub contact_damping_ratio: Option<S>,
    pub contact_push_speed: Option<S>,
    pub restitution_threshold: Option<S>,
    pub arbiter_persistence: Option<u32>,
    /// Capacities: bodies % 33, paths % 17, contacts % 129, joints % 33;
    /// chain vertices 4 × (paths % 17); shapes of compound bodies as bodies.
    pub bodies: u8,
    pub paths: u8,
    pub contacts: u8,
    pub joints: u8,
}

impl WorldSpec {
    /// The world definition.
    #[must_use]
    pub fn def(&self) -> WorldDef {
        let mut d = WorldDef::with_bounds(self.bounds.get());
        if let Some(s) = self.max_linear_speed {
            d.max_linear_speed = s.get();
        }
        if let Some(s) = self.max_angular_speed {
            d.max_angular_speed = s.get();
        }
        if let Some(n) = self.substeps {
            d.substeps = u32::from(n % 20);
        }
        if let Some(s) = self.contact_hertz {
            d.contact_hertz = s.get();
        }
        if let Some(s) = self.contact_damping_ratio {
            d.contact_damping_ratio = s.get();
        }
        if let Some(s) = self.contact_push_speed {
            d.contact_push_speed = s.get();
        }
        if let Some(s) = self.restitution_threshold {
            d.restitution_threshold = s.get();
        }
        if let Some(n) = self.arbiter_persistence {
            d.arbiter_persistence = n;
        }
        d
    }

    /// The capacities the spec asks for.
    #[must_use]
    pub fn capacities(&self) -> Capacities {
        Capacities {
            bodies: usize::from(self.bodies % 33),
            paths: usize::from(self.paths % 17),
            contacts: usize::from(self.contacts % 129),
            joints: usize::from(self.joints % 33),
            post_step_callbacks: arphysics::handler::DEFAULT_POST_STEP_CALLBACKS,
            events: 16,
            chain_vertices: 4 * usize::from(self.paths % 17),
            shapes: usize::from(self.bodies % 33),
        }
    }
}

// ---- ops ----------------------------------------------------------------------

/// A handle given to an API call.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandleRef {
    /// The n-th handle the run was given (modulo their number), live or stale.
    Issued(u8),
    /// The most recent one.
    Last,
    /// Made up from parts.
    Parts(u32, u32),
    /// `Handle::NULL`.
    Null,
}

impl HandleRef {
    fn get<T>(self, issued: &[Handle<T>]) -> Handle<T> {
        match self {
            Self::Issued(i) if !issued.is_empty() => issued[usize::from(i) % issued.len()],
            Self::Last => issued.last().copied().unwrap_or(Handle::NULL),
            // Made up in the run's own world (the tag of the handles it was
            // given): the same slot and generation in every world of a run.
            Self::Parts(i, g) => {
                let untagged = Handle::<T>::from_parts(i, g);
                match issued.first() {
                    Some(h) => Handle::from_bits(untagged.to_bits() | (u64::from(h.world_tag()) << 32)),
                    None => untagged,
                }
            }
            Self::Issued(_) | Self::Null => Handle::NULL,
        }
    }
}

/// A polygon path.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum PathSpec {
    Rectangle(S, S),
    RectangleAt(S, S, V),
    Points(Vec<V>),
    /// A regular n-gon (n = 3 … 10) of this radius: valid hulls, some too big.
    Regular(u8, S),
    /// A rounded rectangle: width, height, rounding radius.
    RoundedRectangle(S, S, S),
    /// The hull of the points with rounded corners.
    RoundedPoints(Vec<V>, S),
}

impl PathSpec {
    /// The path, or the error `PolygonPath` gives.
    ///
    /// # Errors
    /// What the constructors return.
    pub fn build(&self) -> Result<PolygonPath, Error> {
        match self {
            Self::Rectangle(w, h) => PolygonPath::rectangle(w.get(), h.get()),
            Self::RectangleAt(w, h, c) => PolygonPath::rectangle_at(w.get(), h.get(), c.get()),
            Self::Points(ps) => {
                let pts: Vec<Vector2> = ps.iter().take(24).map(|p| p.get()).collect();
                PolygonPath::new(&pts)
            }
            Self::Regular(n, r) => {
                let n = 3 + i64::from(*n % 8);
                let pts: Vec<Vector2> = (0..n)
                    .map(|i| {
                        let a = Scalar::TAU * Scalar::from_num(i) / Scalar::from_num(n);
                        arphysics::Rot::from_angle(a).rotate(Vector2::new(r.get(), Scalar::ZERO))
                    })
                    .collect();
                PolygonPath::new(&pts)
            }
            Self::RoundedRectangle(w, h, r) => PolygonPath::rounded_rectangle(w.get(), h.get(), r.get()),
            Self::RoundedPoints(ps, r) => {
                let pts: Vec<Vector2> = ps.iter().take(24).map(|p| p.get()).collect();
                PolygonPath::rounded(&pts, r.get())
            }
        }
    }
}

/// A body's shape.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeSpec {
    Circle(S),
    Polygon(HandleRef),
    /// Two centres and a radius (off-centre, zero-length and bad ones too).
    Capsule(V, V, S),
    /// Two ends.
    Segment(V, V),
}

impl ShapeSpec {
    /// The capsule or segment, or the error its constructor gives.
    fn line_shape(&self) -> Option<Result<Shape, Error>> {
        match self {
            Self::Capsule(a, b, r) => Some(Capsule::new(a.get(), b.get(), r.get()).map(Shape::Capsule)),
            Self::Segment(a, b) => Some(Segment::new(a.get(), b.get()).map(Shape::Segment)),
            _ => None,
        }
    }
}

/// A rotation.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RotSpec {
    Angle(S),
    Raw(S, S),
}

impl RotSpec {
    fn get(self) -> Rot {
        match self {
            Self::Angle(a) => Rot::from_angle(a.get()),
            Self::Raw(c, s) => Rot { c: c.get(), s: s.get() },
        }
    }
}

/// Body type.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TypeSpec {
    Static,
    Kinematic,
    Dynamic,
}

/// A body definition; `None` fields keep `BodyDef`'s defaults.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct BodySpec {
    pub shape: ShapeSpec,
    pub body_type: TypeSpec,
    pub position: Point,
    pub rotation: Option<RotSpec>,
    pub linear_velocity: Option<V>,
    pub angular_velocity: Option<S>,
    /// `Some(true, m)` = mass m, `Some(false, d)` = density d.
    pub mass: Option<(bool, S)>,
    pub friction: Option<S>,
    pub restitution: Option<S>,
    /// Bits 0–3: collision groups; bit 7: bullet.
    pub collision_groups: u8,
    /// Levels 0 … 3, so that handlers registered on small levels fire.
    pub collision_level: u8,
    pub user_data: u64,
}

impl BodySpec {
    fn def(&self, bounds: Rect, paths: &[PathHandle], near: (&World<'_>, &[BodyHandle])) -> BodyDef {
        let mut d = match self.shape {
            ShapeSpec::Circle(r) => BodyDef::circle(r.get()),
            ShapeSpec::Polygon(h) => BodyDef::polygon(h.get(paths)),
            // A capsule or segment the constructor refuses: a circle of no
            // radius, which the world refuses in turn.
            ShapeSpec::Capsule(..) | ShapeSpec::Segment(..) => match self.shape.line_shape() {
                Some(Ok(Shape::Capsule(c))) => BodyDef::capsule(c),
                Some(Ok(Shape::Segment(sg))) => BodyDef::segment(sg),
                _ => BodyDef::circle(Scalar::ZERO),
            },
        };
        d = d.body_type(match self.body_type {
            TypeSpec::Static => BodyType::Static,
            TypeSpec::Kinematic => BodyType::Kinematic,
            TypeSpec::Dynamic => BodyType::Dynamic,
        });
        d = d.position(self.position.resolve(bounds, Some(near)));
        if let Some(r) = self.rotation {
            d = d.rotation(r.get());
        }
        if let Some(v) = self.linear_velocity {
            d = d.linear_velocity(v.get());
        }
        if let Some(w) = self.angular_velocity {
            d = d.angular_velocity(w.get());
        }
        match self.mass {
            Some((true, m)) => d = d.mass(m.get()),
            Some((false, rho)) => d = d.density(rho.get()),
            None => {}
        }
        if let Some(f) = self.friction {
            d = d.friction(f.get());
        }
        if let Some(e) = self.restitution {
            d = d.restitution(e.get());
        }
        // Bit 6 of the group byte makes the body a sensor (with bit 7, the
        // bullet, an error the world must refuse cleanly).
        if self.collision_groups & 0x40 != 0 {
            d = d.sensor();
        }
        // Group bits from a small set so that some pairs share bits; the top
        // bit of the same byte makes the body a bullet (continuous collision
        // against dynamic bodies too).
        d.collision_groups(u32::from(self.collision_groups & 0x0f))
            .bullet(self.collision_groups & 0x80 != 0)
            .collision_level(u32::from(self.collision_level % 4))
            .user_data(self.user_data)
            .fixed_rotation(self.user_data >> 63 != 0)
            .linear_damping(quarter(self.user_data >> 56))
            .angular_damping(quarter(self.user_data >> 52))
            .gravity_scale(quarter(self.user_data >> 48) - Scalar::from_num(2))
            .filter(filter_from(self.user_data >> 40))
    }
}

/// The low 4 bits of `bits` in quarters: 0 to 3.75 (the body options'
/// damping and, shifted by −2, gravity scale; taken from the user data word,
/// which the engine never reads, so earlier inputs keep their shape).
fn quarter(bits: u64) -> Scalar {
    Scalar::from_num((bits & 0xf) as i32) / Scalar::from_num(4)
}

/// A collision filter from 6 bits: one of four categories, a mask without
/// one of four, and a group index of −1, 0, 0 or 1, so that some pairs are
/// filtered each way.
fn filter_from(bits: u64) -> CollisionFilter {
    CollisionFilter {
        category_bits: 1 << (bits & 3),
        mask_bits: !(1 << ((bits >> 2) & 3)),
        group_index: [-1, 0, 0, 1][((bits >> 4) & 3) as usize],
    }
}

/// Which bodies a built-in generator acts on.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum TargetsSpec {
    All,
    Level(u8),
    Bodies(Vec<HandleRef>),
}

/// A force generator.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum GenSpec {
    Linear(V, TargetsSpec),
    Gravity(V, TargetsSpec),
    GravityToPoint(Point, S, TargetsSpec),
    /// A game's own generator (boxed).
    Custom {
        force: V,
        torque: S,
        level: Option<u8>,
        set_velocity: bool,
    },
}

/// A pivot motor.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct MotorSpec {
    pub speed: S,
    pub max_torque: Option<S>,
}

impl MotorSpec {
    fn get(self) -> Motor {
        Motor {
            speed: self.speed.get(),
            max_torque: self.max_torque.map_or(MaxTorque::Unlimited, |t| MaxTorque::Limited(t.get())),
        }
    }
}

/// A joint kind.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum KindSpec {
    Spring(S, S),
    DampedSpring(S, S, S),
    Rod(S),
    Rope(S),
    Pivot(Option<(S, S)>, Option<MotorSpec>),
    Weld,
    /// hertz, damping ratio, force limit (only valid to a world point).
    Target(S, S, S),
}

impl KindSpec {
    fn get(self) -> JointKind {
        match self {
            Self::Spring(k, l) => JointKind::Spring { stiffness: k.get(), rest_length: l.get() },
            Self::DampedSpring(k, c, l) => {
                JointKind::DampedSpring { stiffness: k.get(), damping: c.get(), rest_length: l.get() }
            }
            Self::Rod(l) => JointKind::Rod { length: l.get() },
            Self::Rope(l) => JointKind::Rope { max_length: l.get() },
            Self::Pivot(limits, motor) => JointKind::Pivot {
                limits: limits.map(|(a, b)| (a.get(), b.get())),
                motor: motor.map(MotorSpec::get),
            },
            Self::Weld => JointKind::Weld,
            Self::Target(f, z, m) => {
                JointKind::Target { hertz: f.get(), damping_ratio: z.get(), max_force: m.get() }
            }
        }
    }
}

/// A joint.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointSpec {
    pub body_a: HandleRef,
    pub anchor_a: V,
    /// `None`: to the world point `anchor_b`.
    pub body_b: Option<HandleRef>,
    pub anchor_b: Point,
    pub kind: KindSpec,
    pub break_impulse: Option<S>,
    pub collide_connected: bool,
}

/// A game constraint (boxed trait object).
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConstraintSpec {
    pub body_a: HandleRef,
    pub body_b: Option<HandleRef>,
    pub impulse: V,
    pub offset: V,
    pub angular: S,
    pub mode: u8,
}

/// A collision handler made of plain functions, chosen from fixed menus.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct HandlerSpec {
    pub begin: Option<u8>,
    pub pre_solve: Option<u8>,
    pub post_solve: Option<u8>,
    pub end: Option<u8>,
}

/// A broad phase.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum IndexSpec {
    /// The default (brute force up to 64 proxies, sort-and-sweep above).
    Auto,
    BruteForce,
    /// Sort-and-sweep with scratch for this many proxies (fewer than the bodies
    /// makes it fall back to brute force).
    SortAndSweep(u8),
    /// A custom index: all pairs (or only overlapping ones), in either order, plus
    /// junk pairs (self, duplicates, out of range), minus every n-th pair.
    Custom {
        all_pairs: bool,
        reverse: bool,
        junk: Vec<(u32, u32)>,
        skip_every: u8,
    },
}

/// What the joint break callback does.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BreakSpec {
    Nothing,
    RemoveBodyA,
    ReAdd,
    MakeBStatic,
}

/// A change to a force generator through `force_generator_mut`.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct GenEdit {
    pub value: V,
    pub scalar: S,
    pub targets: Option<TargetsSpec>,
}

/// One API call.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum Op {
    AddPath(PathSpec),
    RemovePath(HandleRef),
    AddBody(BodySpec),
    RemoveBody(HandleRef),
    SetPosition(HandleRef, Point),
    SetRotation(HandleRef, RotSpec),
    SetAngle(HandleRef, S),
    SetStatic(HandleRef),
    SetLinearVelocity(HandleRef, V),
    SetAngularVelocity(HandleRef, S),
    ApplyLinearImpulse(HandleRef, V),
    ApplyAngularImpulse(HandleRef, S),
    ApplyImpulseAt(HandleRef, V, Point),
    ApplyForce(HandleRef, V, S),
    AddLinearVelocity(HandleRef, V),
    SetUserData(HandleRef, u64),
    AddGenerator(GenSpec),
    EditGenerator(HandleRef, GenEdit),
    RemoveGenerator(HandleRef),
    AddJoint(JointSpec),
    RemoveJoint(HandleRef),
    SetMotor(HandleRef, Option<MotorSpec>),
    /// `set_joint_target` (any joint kind: the others refuse it).
    SetJointTarget(HandleRef, Point),
    /// `set_substeps` with n % 20 (0 and 17 … 19 are out of range).
    SetSubsteps(u8),
    /// `set_contact_recycle_distance` to (n % 32) cm (0 turns recycling off;
    /// 26 … 31 cm are out of range).
    SetContactRecycleDistance(u8),
    /// `add_chain` from the first 2 + n % 5 of the points (a loop if `closed`),
    /// then a static chain body on it (`BodyDef::chain`); the outcome is
    /// `add_chain`'s.
    AddChain([Point; 6], u8, bool),
    AddConstraint(ConstraintSpec),
    RemoveConstraint(HandleRef),
    AddHandler(u8, u8, HandlerSpec),
    RemoveHandler(u8, u8),
    SetDefaultHandler(Option<HandlerSpec>),
    SetIndex(IndexSpec),
    SetBreakCallback(Option<BreakSpec>),
    Step(Dt),
    /// Steps 1 … 16 times.
    StepMany(u8, Dt),
    /// Reads a body through every getter.
    QueryBody(HandleRef, Point),
    /// Reads the arbiter of two bodies, and all arbiters.
    QueryArbiters(HandleRef, HandleRef),
    /// Reads joints, paths and frozen bodies.
    QueryRest(HandleRef),
    /// A ready-made scene: a static floor and a column of bodies on it, so that
    /// inputs reach dense contacts quickly.
    Pile(PileSpec),
    /// `ray_cast` and `ray_cast_all` (into a buffer of n % 6 hits).
    RayCast(Point, Point, Filter, u8),
    /// `query_point` into a buffer of n % 6 handles.
    QueryPoint(Point, Filter, u8),
    /// `query_aabb`.
    QueryAabb(Point, Point, Filter, u8),
    /// `query_shape` with a circle or a path of the world.
    QueryShape(ShapeSpec, Point, RotSpec, Filter, u8),
    /// `snapshot` into a buffer of the right size, or too short by n, or longer.
    Snapshot(SnapBuf),
    /// `restore` a snapshot this run took (the n-th, modulo their number),
    /// possibly corrupted first.
    Restore(u8, Option<Corruption>),
    /// `add_shape` of the shape given, or else of a circle of radius
    /// (1 + n % 32) / 32 m, at the offset (x / 16, y / 16) m on the body,
    /// turned by n / 32 radians, density 1 (mostly valid, so that bodies get
    /// several shapes); the outcome is the shape's index.
    AddShape(HandleRef, u8, i8, i8, Option<ShapeSpec>),
    /// `remove_shape` of shape n % 9 (8 is past every body's last).
    RemoveShape(HandleRef, u8),
}

/// A query filter.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct Filter {
    pub groups: u8,
    pub skip_static: bool,
    pub skip_sensors: bool,
}

impl Filter {
    fn get(self) -> QueryFilter {
        QueryFilter {
            groups: u32::from(self.groups & 0x0f),
            skip_static: self.skip_static,
            skip_sensors: self.skip_sensors,
            ..QueryFilter::default()
        }
    }
}

/// The buffer given to `snapshot`.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SnapBuf {
    Exact,
    /// `snapshot_len() − (n + 1)` bytes (saturating at 0).
    Short(u8),
    /// `snapshot_len() + n` bytes.
    Long(u8),
}

/// A change to a snapshot's bytes before `restore`.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub enum Corruption {
    /// Flips bit `bit % 8` of byte `pos % len`.
    FlipBit(u16, u8),
    /// Sets byte `pos % len`.
    SetByte(u16, u8),
    /// Writes 8 bytes (a raw `Scalar`, a count…) at `pos % len`.
    SetWord(u16, u64),
    /// Keeps the first `n % len` bytes.
    Truncate(u16),
    /// Appends bytes.
    Extend(Vec<u8>),
    /// Several of the above.
    Many(Vec<Corruption>),
}

impl Corruption {
    /// Applies the change.
    pub fn apply(&self, buf: &mut Vec<u8>) {
        let at = |pos: u16, len: usize| usize::from(pos) % len.max(1);
        match self {
            Self::FlipBit(pos, bit) => {
                let i = at(*pos, buf.len());
                if let Some(b) = buf.get_mut(i) {
                    *b ^= 1 << (bit % 8);
                }
            }
            Self::SetByte(pos, v) => {
                let i = at(*pos, buf.len());
                if let Some(b) = buf.get_mut(i) {
                    *b = *v;
                }
            }
            Self::SetWord(pos, v) => {
                let i = at(*pos, buf.len());
                for (k, byte) in v.to_le_bytes().iter().enumerate() {
                    if let Some(b) = buf.get_mut(i + k) {
                        *b = *byte;
                    }
                }
            }
            Self::Truncate(n) => {
                let n = at(*n, buf.len());
                buf.truncate(n);
            }
            Self::Extend(bytes) => buf.extend(bytes.iter().take(256)),
            Self::Many(cs) => {
                for c in cs.iter().take(8) {
                    c.apply(buf);
                }
            }
        }
    }
}

/// Recomputes the checksum trailer of the snapshot at the start of `buf` (the
/// XXH64, seed 0, of the bytes before it; see `arphysics::snapshot`), so that a
/// corrupted snapshot passes the checksum and reaches the field validation. Does
/// nothing when the length in the header does not fit the buffer.
pub fn reseal(buf: &mut [u8]) {
    use arphysics::snapshot::{HEADER, TRAILER};
    let Some(len) = buf.get(8..16).map(|b| u64::from_le_bytes(b.try_into().unwrap_or([0; 8]))) else {
        return;
    };
    let Ok(len) = usize::try_from(len) else { return };
    if len < HEADER + TRAILER || len > buf.len() {
        return;
    }
    let sum = twox_hash::XxHash64::oneshot(0, &buf[..len - TRAILER]);
    buf[len - TRAILER..len].copy_from_slice(&sum.to_le_bytes());
}

impl Op {
    /// True for ops whose effect a snapshot captures (body, generator and joint
    /// state, the sub-step count, steps): replayed after a `restore` they must
    /// give the same bits. Paths and chains (the shapes a snapshot only checks
    /// by checksum), hooks (handlers, game constraints, custom generators and
    /// indexes, callbacks) and snapshots themselves are not state.
    #[must_use]
    pub fn is_state_op(&self) -> bool {
        match self {
            Self::AddPath(_)
            | Self::RemovePath(_)
            | Self::AddChain(..)
            | Self::AddConstraint(_)
            | Self::RemoveConstraint(_)
            | Self::AddHandler(..)
            | Self::RemoveHandler(..)
            | Self::SetDefaultHandler(_)
            | Self::SetIndex(_)
            | Self::SetBreakCallback(_)
            | Self::Snapshot(_)
            | Self::Restore(..)
            // Adds paths.
            | Self::Pile(_) => false,
            Self::AddGenerator(g) => !matches!(g, GenSpec::Custom { .. }),
            _ => true,
        }
    }
}

/// A floor and a column of up to 16 bodies above it, touching or overlapping.
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
pub struct PileSpec {
    /// 1 + count % 16 bodies.
    pub count: u8,
    /// Bit 0: boxes (else circles); bit 1: alternate; bit 2: kinematic floor; bit
    /// 3: add gravity; bit 4: joint each body to the one below (a rod); bit 5:
    /// heavy top body.
    pub flags: u8,
    /// Horizontal shift per body, 1/64 m.
    pub shift: i8,
    /// Vertical gap between bodies, 1/64 m (negative: overlapping).
    pub gap: i8,
    /// Restitution of the bodies, n / 255.
    pub restitution: u8,
    pub level: u8,
}

/// The snapshot target's input: a scene, where to take the snapshot, and ways to
/// corrupt it.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct SnapshotInput {
    pub scene: Input,
    /// The snapshot is taken after `split % (ops + 1)` ops; the state ops after it
    /// are run, rewound and run again.
    pub split: u8,
    /// Steps a second, larger world takes before the snapshot is restored into it.
    pub detour: u8,
    pub corruptions: Vec<Corruption>,
}

/// A fuzz input: a world and what to do with it.
#[derive(Arbitrary, Clone, Debug, PartialEq, Eq)]
pub struct Input {
    pub world: WorldSpec,
    pub ops: Vec<Op>,
}

// ---- the game's hooks -----------------------------------------------------------

thread_local! {
    /// Set when a call the harness makes inside the engine's hooks (or inside a
    /// `Pile`) finds a store full: worlds of different capacities then differ
    /// legitimately.
    static CAPACITY_HIT: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Notes a full store in a result the harness otherwise ignores.
fn note<T>(r: Result<T, Error>) -> Result<T, Error> {
    if let Err(Error::CapacityFull { .. }) = r {
        CAPACITY_HIT.with(|c| c.set(true));
    }
    r
}

fn post_remove(w: &mut World<'_>, key: u64) {
    let _ = w.remove_body(BodyHandle::from_bits(key));
}

fn post_make_static(w: &mut World<'_>, key: u64) {
    let _ = w.set_static(BodyHandle::from_bits(key));
}

fn post_teleport_to_centre(w: &mut World<'_>, key: u64) {
    let c = w.bounds().center();
    let _ = w.set_position(BodyHandle::from_bits(key), c);
}

fn post_add_circle(w: &mut World<'_>, key: u64) {
    let c = w.bounds().center();
    // User data is hashed: keep the world tag (which differs between the
    // worlds a target compares) out of it.
    let h = BodyHandle::from_bits(key);
    let data = (u64::from(h.index()) << 32) | u64::from(h.generation());
    let _ = note(w.add_body(BodyDef::circle(Scalar::ONE).position(c).user_data(data)));
}

fn post_spin(w: &mut World<'_>, key: u64) {
    if let Ok(b) = w.body_mut(BodyHandle::from_bits(key)) {
        b.set_angular_velocity(Scalar::MAX);
        b.set_linear_velocity(Vector2::new(Scalar::MIN, Scalar::MAX));
    }
}

fn parity(a: &Arbiter) -> bool {
    (a.body_a().index() ^ a.body_b().generation()) & 1 == 0
}

fn begin_fn(i: u8) -> fn(&mut Arbiter, &mut CallbackContext<'_>) -> bool {
    match i % 5 {
        0 => |_, _| true,
        1 => |_, _| false,
        2 => |a, _| parity(a),
        3 => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_remove, a.body_a().to_bits());
            true
        },
        _ => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_add_circle, a.body_b().to_bits());
            !parity(a)
        },
    }
}

fn pre_solve_fn(i: u8) -> fn(&mut Arbiter, &mut CallbackContext<'_>) -> bool {
    match i % 8 {
        0 => |_, _| true,
        1 => |_, _| false,
        // Out-of-range values are an error that changes nothing; the range's
        // ends are accepted.
        2 => |a, _| {
            let _ = a.set_friction(Scalar::MAX);
            let _ = a.set_friction(arphysics::limits::MAX_FRICTION);
            true
        },
        3 => |a, _| {
            let _ = a.set_restitution(Scalar::MAX);
            let _ = a.set_restitution(Scalar::ONE);
            let _ = a.set_friction(Scalar::ZERO);
            true
        },
        4 => |a, _| {
            let _ = a.set_friction(Scalar::MIN);
            let _ = a.set_restitution(Scalar::MIN);
            a.increase_step_count();
            parity(a)
        },
        5 => |a, ctx| {
            // Read everything the callback can see.
            let mut h = 0u64;
            if let Some(b) = ctx.body(a.body_a()) {
                h ^= b.angle().to_bits() as u64;
                h ^= b.velocity_at(a.normal()).x.to_bits() as u64;
            }
            for p in a.contact_points() {
                h ^= p.total_normal_impulse.to_bits() as u64;
            }
            h ^= a.total_normal_impulse().to_bits() as u64;
            let _ = a.bodies_by_level(1);
            h & 1 == 0
        },
        6 => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_teleport_to_centre, a.body_b().to_bits());
            true
        },
        _ => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_spin, a.body_a().to_bits());
            let _ = ctx.add_post_step_callback(post_make_static, a.body_b().to_bits());
            true
        },
    }
}

fn post_solve_fn(i: u8) -> fn(&Arbiter, &mut CallbackContext<'_>) {
    match i % 3 {
        0 => |_, _| {},
        1 => |a, ctx| {
            if a.total_normal_impulse() > Scalar::ONE {
                let _ = ctx.add_post_step_callback(post_remove, a.body_b().to_bits());
            }
        },
        _ => |a, ctx| {
            // Many keys: fills the post-step queue.
            for k in 0..80u64 {
                let _ = ctx.add_post_step_callback(post_spin, a.body_a().to_bits().wrapping_add(k << 44));
            }
        },
    }
}

fn end_fn(i: u8) -> fn(&Arbiter, &mut CallbackContext<'_>) {
    match i % 3 {
        0 => |_, _| {},
        1 => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_remove, a.body_b().to_bits());
        },
        _ => |a, ctx| {
            let _ = ctx.add_post_step_callback(post_add_circle, a.body_a().to_bits());
        },
    }
}

impl HandlerSpec {
    fn handler(self) -> FnHandler {
        FnHandler {
            begin: self.begin.map(begin_fn),
            pre_solve: self.pre_solve.map(pre_solve_fn),
            post_solve: self.post_solve.map(post_solve_fn),
            end: self.end.map(end_fn),
        }
    }
}

fn break_fn(b: BreakSpec) -> Option<arphysics::JointBreakFn> {
    match b {
        BreakSpec::Nothing => Some(|_, _, _| {}),
        BreakSpec::RemoveBodyA => Some(|w, _, j: Joint| {
            let _ = w.remove_body(j.def().body_a);
        }),
        BreakSpec::ReAdd => Some(|w, _, j: Joint| {
            let _ = note(w.add_joint(*j.def()));
        }),
        BreakSpec::MakeBStatic => Some(|w, _, j: Joint| {
            if let Some(b) = j.def().body_b {
                let _ = w.set_static(b);
            }
        }),
    }
}

/// A game's force generator.
struct FuzzGenerator {
    force: Vector2,
    torque: Scalar,
    level: Option<u32>,
    set_velocity: bool,
}

impl ForceGenerator for FuzzGenerator {
    fn applies_to(&self, _: BodyHandle, body: &Body) -> bool {
        self.level.is_none_or(|l| body.collision_level() == l)
    }
    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        body.apply_force(self.force, dt);
        body.apply_angular_impulse(self.torque * dt);
        if self.set_velocity {
            body.set_linear_velocity(self.force);
            body.set_angular_velocity(self.torque);
        }
        let p = body.position();
        body.apply_impulse_at(self.force, p + self.force);
        body.add_linear_velocity(self.force);
    }
}

/// A game's constraint. What `prepare` computes depends on the bodies alone (not
/// on earlier steps), so replaying after a `restore` gives the same bits.
struct FuzzConstraint {
    impulse: Vector2,
    offset: Vector2,
    angular: Scalar,
    mode: u8,
    prepared: Vector2,
}

impl Constraint for FuzzConstraint {
    fn prepare(&mut self, a: &Body, b: &Body, dt: Scalar) {
        self.prepared = (b.position() - a.position()).normalize() * dt;
        if self.mode & 8 != 0 {
            self.offset = self.prepared;
        }
    }
    fn solve(&mut self, a: &mut Body, b: &mut Body, h: Scalar) {
        match self.mode % 5 {
            0 => {
                let p = a.position() + self.offset;
                a.apply_impulse_at(self.impulse, p);
                b.apply_impulse_at(-self.impulse, p);
            }
            1 => {
                a.apply_linear_impulse(self.impulse);
                b.apply_angular_impulse(self.angular);
            }
            2 => {
                a.set_linear_velocity(self.impulse);
                a.set_angular_velocity(self.angular);
                b.set_linear_velocity(-self.impulse);
            }
            3 => {
                a.apply_force(self.impulse, h);
                let w = a.angular_velocity();
                b.apply_angular_impulse(w);
            }
            _ => {
                // A soft distance constraint, written as a game would.
                let d = b.position() - a.position();
                let (n, len) = d.normalize_and_length();
                let err = len - self.offset.length();
                let j = n * (err * self.angular);
                a.apply_linear_impulse(j + self.prepared);
                b.apply_linear_impulse(-j);
            }
        }
    }
}

/// A game's broad phase that reports junk besides the pairs.
struct FuzzIndex {
    all_pairs: bool,
    reverse: bool,
    junk: Vec<(u32, u32)>,
    skip_every: u8,
}

impl SpatialIndex for FuzzIndex {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        let n = u32::try_from(proxies.len()).unwrap_or(u32::MAX);
        let mut count = 0u32;
        for i in 0..n {
            for j in i.saturating_add(1)..n {
                let (pa, pb) = (&proxies[i as usize], &proxies[j as usize]);
                if !self.all_pairs && !arphysics::index::proxies_may_touch(pa, pb) {
                    continue;
                }
                count = count.wrapping_add(1);
                if self.skip_every > 1 && count.is_multiple_of(u32::from(self.skip_every)) {
                    continue;
                }
                let ok = if self.reverse { out.push(j, i) } else { out.push(i, j) };
                if !ok {
                    return;
                }
            }
        }
        for &(a, b) in self.junk.iter().take(64) {
            if !out.push(a, b) {
                return;
            }
        }
    }
}

fn targets(t: &TargetsSpec, bodies: &[BodyHandle]) -> Result<Targets, Error> {
    Ok(match t {
        TargetsSpec::All => Targets::All,
        TargetsSpec::Level(l) => Targets::Level(u32::from(*l % 4)),
        TargetsSpec::Bodies(hs) => {
            let v: Vec<BodyHandle> = hs.iter().take(40).map(|h| h.get(bodies)).collect();
            Targets::bodies(&v)?
        }
    })
}

// ---- running ------------------------------------------------------------------

/// What an op returned, comparable across worlds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    Done,
    Handle(u32, u32),
    Step(arphysics::StepReport),
    /// `StepMany`: how many steps succeeded, and the error that stopped it.
    Steps(u32, Option<Error>),
    Value(u64),
    Err(Error),
}

impl Outcome {
    /// True for an error saying a store was full.
    #[must_use]
    pub fn is_capacity_full(&self) -> bool {
        matches!(
            self,
            Self::Err(Error::CapacityFull { .. }) | Self::Steps(_, Some(Error::CapacityFull { .. }))
        )
    }

    /// The outcome with a step report's count of dropped events zeroed. The
    /// event lists are the step's output, never state: worlds whose event
    /// capacities differ drop different numbers of events and must agree on
    /// everything else, the state hash included.
    #[must_use]
    pub fn without_dropped_events(self) -> Self {
        match self {
            Self::Step(mut r) => {
                r.events_dropped = 0;
                Self::Step(r)
            }
            other => other,
        }
    }
}

fn handle_outcome<T>(r: Result<Handle<T>, Error>) -> Outcome {
    match r {
        Ok(h) => Outcome::Handle(h.index(), h.generation()),
        Err(e) => Outcome::Err(e),
    }
}

fn unit_outcome<T>(r: Result<T, Error>) -> Outcome {
    match r {
        Ok(_) => Outcome::Done,
        Err(e) => Outcome::Err(e),
    }
}

/// FNV-1a over words, to summarise what queries read.
#[derive(Default)]
struct Summary(u64);

impl Summary {
    fn add(&mut self, v: u64) {
        if self.0 == 0 {
            self.0 = 0xcbf2_9ce4_8422_2325;
        }
        for b in v.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn s(&mut self, v: Scalar) {
        self.add(v.to_bits() as u64);
    }
    fn v(&mut self, v: Vector2) {
        self.s(v.x);
        self.s(v.y);
    }
}

fn summarise_handles(count: usize, out: &[BodyHandle]) -> u64 {
    let mut s = Summary::default();
    s.add(count as u64);
    for h in out.iter().take(count) {
        // Index and generation: the world tag differs between compared worlds.
        s.add((u64::from(h.index()) << 32) | u64::from(h.generation()));
    }
    s.0
}

/// Lengths of a runner's handle lists and its step count.
#[derive(Clone, Copy, Debug)]
pub struct Marks([usize; 5], u32);

/// One world and the handles it gave out (live or since removed).
pub struct Runner<'w> {
    pub world: World<'w>,
    pub bodies: Vec<BodyHandle>,
    pub paths: Vec<PathHandle>,
    pub generators: Vec<GeneratorHandle>,
    pub joints: Vec<JointHandle>,
    pub constraints: Vec<ConstraintHandle>,
    /// Steps taken so far (successful or not), to bound a run.
    pub steps: u32,
    /// Snapshots taken by `Op::Snapshot`, with the state hash when taken.
    pub snapshots: Vec<(Vec<u8>, u64)>,
    /// The last op found a store full somewhere its outcome does not show (in a
    /// hook or a `Pile`).
    pub capacity_hit: bool,
    /// Queries summarise only what a snapshot holds, not the last step's outputs
    /// (impulses, contact geometry), which `restore` does not bring back.
    pub state_only_queries: bool,
}

impl<'w> Runner<'w> {
    /// A runner on a world made from `spec` on `storage`.
    ///
    /// # Errors
    /// What `World::new` returns.
    pub fn new(spec: &WorldSpec, storage: Storage<'w>) -> Result<Self, Error> {
        Ok(Self::with_world(World::new(spec.def(), storage)?))
    }

    /// A runner on an existing world.
    #[must_use]
    pub fn with_world(world: World<'w>) -> Self {
        Self {
            world,
            bodies: Vec::new(),
            paths: Vec::new(),
            generators: Vec::new(),
            joints: Vec::new(),
            constraints: Vec::new(),
            steps: 0,
            snapshots: Vec::new(),
            capacity_hit: false,
            state_only_queries: false,
        }
    }

    fn step(&mut self, dt: Dt) -> Outcome {
        self.steps = self.steps.saturating_add(1);
        match self.world.step(dt.get()) {
            Ok(r) => {
                // A full store completes the step by dropping what does not fit
                // (lowest keys kept): a world with larger stores differs from here.
                if r.pairs_dropped > 0
                    || r.arbiters_dropped > 0
                    || r.post_step_refused > 0
                    || r.post_step_dropped > 0
                {
                    CAPACITY_HIT.with(|c| c.set(true));
                }
                Outcome::Step(r)
            }
            Err(e) => Outcome::Err(e),
        }
    }

    /// Where the handle lists and the step budget stand (to rewind them with the
    /// world in [`Runner::rewind`]).
    #[must_use]
    pub fn marks(&self) -> Marks {
        Marks(
            [
                self.bodies.len(),
                self.paths.len(),
                self.generators.len(),
                self.joints.len(),
                self.constraints.len(),
            ],
            self.steps,
        )
    }

    /// Forgets the handles given out since `m` (after restoring the world to a
    /// snapshot taken then, the same calls give out the same handles again).
    pub fn rewind(&mut self, m: Marks) {
        let [b, p, g, j, c] = m.0;
        self.bodies.truncate(b);
        self.paths.truncate(p);
        self.generators.truncate(g);
        self.joints.truncate(j);
        self.constraints.truncate(c);
        self.steps = m.1;
    }

    /// The world's snapshot, checked against `snapshot_len`.
    #[must_use]
    pub fn take_snapshot(&self) -> Vec<u8> {
        let mut buf = vec![0u8; self.world.snapshot_len()];
        let n = self.world.snapshot(&mut buf).expect("a buffer of snapshot_len() bytes is enough");
        assert_eq!(n, buf.len(), "snapshot wrote other than snapshot_len() bytes");
        buf
    }

    /// True when the run has stepped as much as one input may.
    #[must_use]
    pub fn exhausted(&self) -> bool {
        self.steps >= MAX_STEPS
    }

    /// Applies one op.
    pub fn apply(&mut self, op: &Op) -> Outcome {
        CAPACITY_HIT.with(|c| c.set(false));
        let out = self.apply_inner(op);
        self.capacity_hit = CAPACITY_HIT.with(std::cell::Cell::get);
        out
    }

    /// True when the last op's outcome, or something it did that its outcome does
    /// not show, found a store full: a world with larger stores may differ from
    /// then on.
    #[must_use]
    pub fn hit_capacity(&self, out: &Outcome) -> bool {
        self.capacity_hit || out.is_capacity_full()
    }

    fn apply_inner(&mut self, op: &Op) -> Outcome {
        let bounds = self.world.bounds();
        let body = |h: &HandleRef, s: &Self| h.get(&s.bodies);
        match op {
            Op::AddPath(p) => {
                let r = p.build().and_then(|p| self.world.add_path(p));
                if let Ok(h) = r {
                    self.paths.push(h);
                }
                handle_outcome(r)
            }
            Op::RemovePath(h) => unit_outcome(self.world.remove_path(h.get(&self.paths))),
            Op::AddBody(spec) => {
                let def = spec.def(bounds, &self.paths, (&self.world, &self.bodies));
                let r = self.world.add_body(def);
                if let Ok(h) = r {
                    self.bodies.push(h);
                }
                handle_outcome(r)
            }
            Op::RemoveBody(h) => unit_outcome(self.world.remove_body(body(h, self))),
            Op::SetPosition(h, p) => {
                let p = self.point(*p);
                unit_outcome(self.world.set_position(body(h, self), p))
            }
            Op::SetRotation(h, q) => unit_outcome(self.world.set_rotation(body(h, self), q.get())),
            Op::SetAngle(h, a) => unit_outcome(self.world.set_angle(body(h, self), a.get())),
            Op::SetStatic(h) => unit_outcome(self.world.set_static(body(h, self))),
            Op::SetLinearVelocity(h, v) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.set_linear_velocity(v.get())))
            }
            Op::SetAngularVelocity(h, w) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.set_angular_velocity(w.get())))
            }
            Op::ApplyLinearImpulse(h, j) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.apply_linear_impulse(j.get())))
            }
            Op::ApplyAngularImpulse(h, j) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.apply_angular_impulse(j.get())))
            }
            Op::ApplyImpulseAt(h, j, p) => {
                let p = self.point(*p);
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.apply_impulse_at(j.get(), p)))
            }
            Op::ApplyForce(h, f, dt) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.apply_force(f.get(), dt.get())))
            }
            Op::AddLinearVelocity(h, v) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.add_linear_velocity(v.get())))
            }
            Op::SetUserData(h, d) => {
                unit_outcome(self.world.body_mut(body(h, self)).map(|b| b.set_user_data(*d)))
            }
            Op::AddGenerator(g) => {
                let r = self.generator(g).and_then(|g| self.world.add_force_generator(g));
                if let Ok(h) = r {
                    self.generators.push(h);
                }
                handle_outcome(r)
            }
            Op::EditGenerator(h, e) => {
                let t = match &e.targets {
                    Some(t) => match targets(t, &self.bodies) {
                        Ok(t) => Some(t),
                        Err(e) => return Outcome::Err(e),
                    },
                    None => None,
                };
                // One op, one outcome: the fallible setters run first and the
                // targets change only if they all succeeded, so an `Err` leaves the
                // generator as it was (the property `scene_ops` checks).
                let r = self.world.force_generator_mut(h.get(&self.generators)).and_then(|g| match g {
                    GeneratorMut::Linear(g) => {
                        g.set_force(e.value.get())?;
                        if let Some(t) = t {
                            g.set_targets(t);
                        }
                        Ok(())
                    }
                    GeneratorMut::Gravity(g) => {
                        g.set_gravity(e.value.get())?;
                        if let Some(t) = t {
                            g.set_targets(t);
                        }
                        Ok(())
                    }
                    GeneratorMut::GravityToPoint(g) => {
                        let old_point = g.point();
                        g.set_point(e.value.get())?;
                        if let Err(err) = g.set_acceleration(e.scalar.get()) {
                            g.set_point(old_point)?;
                            return Err(err);
                        }
                        if let Some(t) = t {
                            g.set_targets(t);
                        }
                        Ok(())
                    }
                    GeneratorMut::Custom(_) => Ok(()),
                });
                unit_outcome(r)
            }
            Op::RemoveGenerator(h) => {
                unit_outcome(self.world.remove_force_generator(h.get(&self.generators)))
            }
            Op::AddJoint(j) => {
                let def = JointDef {
                    body_a: body(&j.body_a, self),
                    anchor_a: j.anchor_a.get(),
                    body_b: j.body_b.map(|b| body(&b, self)),
                    anchor_b: match j.body_b {
                        Some(_) => match j.anchor_b {
                            Point::Abs(v) => v.get(),
                            // A local anchor: the fractions as a small offset.
                            Point::InBounds(x, y) => Vector2::new(
                                Scalar::from_bits(i64::from(x as i16) << 24),
                                Scalar::from_bits(i64::from(y as i16) << 24),
                            ),
                            Point::Near(_, dx, dy) => Vector2::new(
                                Scalar::from_bits(i64::from(dx) << 28),
                                Scalar::from_bits(i64::from(dy) << 28),
                            ),
                        },
                        None => self.point(j.anchor_b),
                    },
                    kind: j.kind.get(),
                    break_impulse: j.break_impulse.map(S::get),
                    collide_connected: j.collide_connected,
                };
                let r = self.world.add_joint(def);
                if let Ok(h) = r {
                    self.joints.push(h);
                }
                handle_outcome(r)
            }
            Op::RemoveJoint(h) => unit_outcome(self.world.remove_joint(h.get(&self.joints))),
            Op::SetJointTarget(h, p) => {
                let p = self.point(*p);
                unit_outcome(self.world.set_joint_target(h.get(&self.joints), p))
            }
            Op::SetSubsteps(n) => unit_outcome(self.world.set_substeps(u32::from(n % 20))),
            Op::SetContactRecycleDistance(n) => {
                unit_outcome(self.world.set_contact_recycle_distance(
                    Scalar::from_int(i32::from(n % 32)) / Scalar::from_int(100),
                ))
            }
            Op::AddChain(points, n, closed) => {
                let mut pts = [Vector2::ZERO; 6];
                for (dst, &p) in pts.iter_mut().zip(points.iter()) {
                    *dst = self.point(p);
                }
                let pts = pts.get(..2 + usize::from(n % 5)).unwrap_or(&[]);
                let path = if *closed { ChainPath::closed(pts) } else { ChainPath::open(pts) };
                // Two calls: the outcome is the chain's (its slab keeps the
                // chain whatever the body does); a full body store for the
                // chain's body is a capacity hit the outcome does not show.
                let chain = path.and_then(|path| self.world.add_chain(path));
                if let Ok(c) = chain {
                    match self.world.add_body(BodyDef::chain(c)) {
                        Ok(h) => self.bodies.push(h),
                        Err(Error::CapacityFull { .. }) => CAPACITY_HIT.with(|c| c.set(true)),
                        Err(_) => {}
                    }
                }
                unit_outcome(chain)
            }
            Op::SetMotor(h, m) => unit_outcome(
                self.world.joint_mut(h.get(&self.joints)).and_then(|j| j.set_motor(m.map(MotorSpec::get))),
            ),
            Op::AddConstraint(c) => {
                let user = FuzzConstraint {
                    impulse: c.impulse.get(),
                    offset: c.offset.get(),
                    angular: c.angular.get(),
                    mode: c.mode,
                    prepared: Vector2::ZERO,
                };
                let r = self.world.add_constraint(
                    body(&c.body_a, self),
                    c.body_b.map(|b| body(&b, self)),
                    Hook::Boxed(Box::new(user)),
                );
                if let Ok(h) = r {
                    self.constraints.push(h);
                }
                handle_outcome(r)
            }
            Op::RemoveConstraint(h) => unit_outcome(self.world.remove_constraint(h.get(&self.constraints))),
            Op::AddHandler(a, b, h) => unit_outcome(self.world.add_collision_handler(
                u32::from(*a % 4),
                u32::from(*b % 4),
                h.handler(),
            )),
            Op::RemoveHandler(a, b) => {
                let had = self.world.remove_collision_handler(u32::from(*a % 4), u32::from(*b % 4));
                Outcome::Value(u64::from(had.is_some()))
            }
            Op::SetDefaultHandler(h) => {
                let old = self.world.set_default_collision_handler(h.map(|h| Handler::from(h.handler())));
                Outcome::Value(u64::from(old.is_some()))
            }
            Op::SetIndex(i) => {
                self.world.set_spatial_index(match i {
                    IndexSpec::Auto => Index::default(),
                    IndexSpec::BruteForce => Index::BruteForce(arphysics::BruteForceIndex),
                    IndexSpec::SortAndSweep(n) => {
                        // At most 47 entries: the allocator never refuses them.
                        match SortAndSweepIndex::with_capacity(usize::from(*n % 48)) {
                            Ok(i) => Index::SortAndSweep(i),
                            Err(e) => return Outcome::Err(e),
                        }
                    }
                    IndexSpec::Custom { all_pairs, reverse, junk, skip_every } => {
                        Index::boxed(Box::new(FuzzIndex {
                            all_pairs: *all_pairs,
                            reverse: *reverse,
                            junk: junk.clone(),
                            skip_every: *skip_every,
                        }))
                    }
                });
                Outcome::Done
            }
            Op::SetBreakCallback(b) => {
                self.world.set_joint_break_callback(b.and_then(break_fn));
                Outcome::Done
            }
            Op::Step(dt) => self.step(*dt),
            Op::StepMany(n, dt) => {
                let mut ok = 0u32;
                for _ in 0..=(n % 16) {
                    match self.step(*dt) {
                        Outcome::Err(e) if ok == 0 => return Outcome::Err(e),
                        Outcome::Err(e) => return Outcome::Steps(ok, Some(e)),
                        _ => ok += 1,
                    }
                    if self.exhausted() {
                        break;
                    }
                }
                Outcome::Steps(ok, None)
            }
            Op::QueryBody(h, p) => match self.world.body(body(h, self)) {
                Ok(b) => {
                    let mut s = Summary::default();
                    let p = p.resolve(bounds, Some((&self.world, &self.bodies)));
                    s.v(b.position());
                    s.s(b.angle());
                    s.v(b.velocity_at(p));
                    s.v(b.transform().apply(p));
                    s.v(b.transform().apply_inv(p));
                    s.v(b.rotation().rotate(p));
                    s.s(b.mass());
                    s.s(b.inv_mass());
                    s.s(b.inertia());
                    s.s(b.inv_inertia());
                    s.v(b.aabb().min);
                    s.v(b.aabb().max);
                    s.s(b.bounding_radius());
                    s.add(u64::from(b.is_out_of_bounds()));
                    s.add(b.user_data());
                    Outcome::Value(s.0)
                }
                Err(e) => Outcome::Err(e),
            },
            Op::QueryArbiters(a, b) => {
                // Per-step outputs (manifold geometry, the impulses of the last
                // step) are not in a snapshot: summarised only when asked.
                let outputs = !self.state_only_queries;
                let mut s = Summary::default();
                if let Some(arb) = self.world.arbiter(body(a, self), body(b, self)) {
                    s.add(u64::from(arb.body_a().index()));
                    if outputs {
                        s.v(arb.normal());
                        s.s(arb.friction());
                        s.s(arb.restitution());
                    }
                }
                for arb in self.world.arbiters() {
                    s.add(u64::from(arb.body_a().index()));
                    s.add(u64::from(arb.body_b().index()));
                    s.add(arb.state() as u64);
                    s.add(u64::from(arb.steps_separated()));
                    if outputs {
                        s.s(arb.total_normal_impulse());
                        for p in arb.contact_points() {
                            s.v(p.point);
                            s.s(p.separation);
                        }
                    }
                }
                Outcome::Value(s.0)
            }
            Op::Pile(p) => Outcome::Value(self.pile(p)),
            Op::RayCast(from, to, f, n) => {
                let (from, to) = (self.point(*from), self.point(*to));
                let mut s = Summary::default();
                let hit = |s: &mut Summary, h: &RayHit| {
                    s.add(u64::from(h.body.index()));
                    s.v(h.point);
                    s.v(h.normal);
                    s.s(h.fraction);
                };
                match self.world.ray_cast(from, to, f.get()) {
                    Ok(Some(h)) => {
                        assert!(h.fraction >= Scalar::ZERO && h.fraction <= Scalar::ONE, "{h:?}");
                        hit(&mut s, &h);
                    }
                    Ok(None) => s.add(1),
                    Err(e) => return Outcome::Err(e),
                }
                let none = RayHit {
                    body: Handle::NULL,
                    point: Vector2::ZERO,
                    normal: Vector2::ZERO,
                    fraction: Scalar::ZERO,
                };
                let mut out = [none; 5];
                let len = usize::from(*n) % 6;
                match self.world.ray_cast_all(from, to, f.get(), &mut out[..len]) {
                    Ok(count) => {
                        s.add(count as u64);
                        for h in out.iter().take(count.min(len)) {
                            hit(&mut s, h);
                        }
                    }
                    Err(e) => return Outcome::Err(e),
                }
                Outcome::Value(s.0)
            }
            Op::QueryPoint(p, f, n) => {
                let p = self.point(*p);
                let mut out = [BodyHandle::NULL; 5];
                let len = usize::from(*n) % 6;
                let count = self.world.query_point(p, f.get(), &mut out[..len]);
                Outcome::Value(summarise_handles(count, &out[..len]))
            }
            Op::QueryAabb(a, b, f, n) => {
                let area = Rect { min: self.point(*a), max: self.point(*b) };
                let mut out = [BodyHandle::NULL; 5];
                let len = usize::from(*n) % 6;
                match self.world.query_aabb(area, f.get(), &mut out[..len]) {
                    Ok(count) => Outcome::Value(summarise_handles(count, &out[..len])),
                    Err(e) => Outcome::Err(e),
                }
            }
            Op::QueryShape(shape, p, q, f, n) => {
                let xf = Transform::new(self.point(*p), q.get());
                let mut out = [BodyHandle::NULL; 5];
                let len = usize::from(*n) % 6;
                let path;
                let shape = match shape {
                    ShapeSpec::Circle(r) => QueryShape::Circle(r.get()),
                    ShapeSpec::Polygon(h) => match self.world.path(h.get(&self.paths)) {
                        Ok(p) => {
                            path = *p;
                            QueryShape::Polygon(&path)
                        }
                        Err(e) => return Outcome::Err(e),
                    },
                    ShapeSpec::Capsule(..) | ShapeSpec::Segment(..) => match shape.line_shape() {
                        Some(Ok(Shape::Capsule(c))) => QueryShape::Capsule(c),
                        Some(Ok(Shape::Segment(sg))) => QueryShape::Segment(sg),
                        Some(Err(e)) => return Outcome::Err(e),
                        _ => return Outcome::Err(Error::OutOfRange { what: "query shape" }),
                    },
                };
                match self.world.query_shape(shape, xf, f.get(), &mut out[..len]) {
                    Ok(count) => Outcome::Value(summarise_handles(count, &out[..len])),
                    Err(e) => Outcome::Err(e),
                }
            }
            Op::Snapshot(b) => {
                let needed = self.world.snapshot_len();
                let len = match b {
                    SnapBuf::Exact => needed,
                    SnapBuf::Short(n) => needed.saturating_sub(usize::from(*n) + 1),
                    SnapBuf::Long(n) => needed + usize::from(*n),
                };
                let mut buf = vec![0xa5u8; len];
                match self.world.snapshot(&mut buf) {
                    Ok(written) => {
                        assert_eq!(written, needed, "snapshot wrote other than snapshot_len() bytes");
                        assert!(buf[written..].iter().all(|&b| b == 0xa5), "snapshot wrote past its length");
                        buf.truncate(written);
                        self.snapshots.push((buf, self.world.state_hash()));
                        Outcome::Value(written as u64)
                    }
                    Err(e) => {
                        assert_eq!(e, Error::BufferTooSmall { needed }, "snapshot into {len} bytes");
                        assert!(buf.iter().all(|&b| b == 0xa5), "a failed snapshot wrote into the buffer");
                        Outcome::Err(e)
                    }
                }
            }
            Op::AddShape(h, n, x, y, shape) => {
                let shape = match shape {
                    None => Shape::Circle { radius: Scalar::from_bits((1 + i64::from(n % 32)) << 27) },
                    Some(ShapeSpec::Circle(r)) => Shape::Circle { radius: r.get() },
                    Some(ShapeSpec::Polygon(p)) => Shape::Polygon(p.get(&self.paths)),
                    Some(line) => match line.line_shape() {
                        Some(Ok(s)) => s,
                        Some(Err(e)) => return Outcome::Err(e),
                        None => return Outcome::Err(Error::OutOfRange { what: "shape" }),
                    },
                };
                let offset = Vector2::new(
                    Scalar::from_bits(i64::from(*x) << 28),
                    Scalar::from_bits(i64::from(*y) << 28),
                );
                let def = arphysics::ShapeDef::new(shape)
                    .offset(offset)
                    .angle(Scalar::from_bits(i64::from(*n) << 27));
                match self.world.add_shape(body(h, self), def) {
                    Ok(i) => Outcome::Value(u64::from(i)),
                    Err(e) => Outcome::Err(e),
                }
            }
            Op::RemoveShape(h, i) => unit_outcome(self.world.remove_shape(body(h, self), u32::from(i % 9))),
            Op::Restore(i, corruption) => {
                if self.snapshots.is_empty() {
                    return Outcome::Value(0);
                }
                let (mut buf, hash) = self.snapshots[usize::from(*i) % self.snapshots.len()].clone();
                if let Some(c) = corruption {
                    c.apply(&mut buf);
                }
                match self.world.restore(&buf) {
                    Ok(()) => {
                        if corruption.is_none() {
                            assert_eq!(self.world.state_hash(), hash, "restore did not bring back the state");
                        }
                        Outcome::Done
                    }
                    Err(e) => Outcome::Err(e),
                }
            }
            Op::QueryRest(h) => {
                let mut s = Summary::default();
                for (jh, j) in self.world.joints() {
                    s.add(u64::from(jh.index()));
                    if !self.state_only_queries {
                        s.s(j.step_impulse());
                    }
                }
                if let Ok(p) = self.world.path(h.get(&self.paths)) {
                    s.s(p.area());
                    s.s(p.unit_inertia());
                    s.s(p.radius());
                    s.v(p.centroid());
                    for (v, n) in p.vertices().iter().zip(p.normals()) {
                        s.v(*v);
                        s.v(*n);
                    }
                }
                for b in self.world.out_of_bounds_bodies() {
                    s.add(u64::from(b.index()));
                }
                s.add(self.world.body_count() as u64);
                s.add(self.world.step_count());
                Outcome::Value(s.0)
            }
        }
    }

    /// Builds a pile; returns how many calls succeeded.
    fn pile(&mut self, p: &PileSpec) -> u64 {
        let mut ok = 0u64;
        let bounds = self.world.bounds();
        let c = bounds.center();
        let one = Scalar::ONE;
        let half = Scalar::from_bits(1 << 31);
        let sixty_fourth = |n: i8| Scalar::from_bits(i64::from(n) << 26);
        // Floor: 30 m × 1 m, its top 1 m above the bottom of the bounds (or at the
        // centre for very large worlds).
        let floor_y = if bounds.height() > Scalar::from_num(200) { c.y } else { bounds.min.y + one };
        if let Ok(fp) = PolygonPath::rectangle(Scalar::from_num(30), one) {
            if let Ok(path) = note(self.world.add_path(fp)) {
                self.paths.push(path);
                ok += 1;
                let mut def = BodyDef::polygon(path).position(Vector2::new(c.x, floor_y - half));
                def = if p.flags & 4 != 0 { def.kinematic() } else { def.static_body() };
                if let Ok(h) = note(self.world.add_body(def.collision_level(u32::from(p.level % 4)))) {
                    self.bodies.push(h);
                    ok += 1;
                }
            }
        }
        let box_path = if p.flags & 1 != 0 {
            PolygonPath::rectangle(one, one).ok().and_then(|b| note(self.world.add_path(b)).ok())
        } else {
            None
        };
        if let Some(b) = box_path {
            self.paths.push(b);
        }
        if p.flags & 8 != 0 {
            let g = GravityForceGenerator::new(Vector2::new(Scalar::ZERO, Scalar::from_num(-10)));
            if let Ok(h) = note(self.world.add_force_generator(g)) {
                self.generators.push(h);
                ok += 1;
            }
        }
        let n = 1 + i64::from(p.count % 16);
        let mut below: Option<BodyHandle> = None;
        for i in 0..n {
            let x = c.x + sixty_fourth(p.shift) * Scalar::from_num(i);
            let y = floor_y + half + (one + sixty_fourth(p.gap)) * Scalar::from_num(i);
            let use_box = box_path.is_some() && (p.flags & 2 == 0 || i % 2 == 0);
            let mut def = match box_path {
                Some(b) if use_box => BodyDef::polygon(b),
                _ => BodyDef::circle(half),
            };
            def = def
                .position(Vector2::new(x, y))
                .restitution(Scalar::from_num(p.restitution) / 255)
                .collision_level(u32::from((p.level >> 2) % 4));
            if p.flags & 32 != 0 && i == n - 1 {
                def = def.mass(Scalar::from_num(1000));
            }
            let Ok(h) = note(self.world.add_body(def)) else { continue };
            self.bodies.push(h);
            ok += 1;
            if let (true, Some(b)) = (p.flags & 16 != 0, below) {
                let rod = JointDef::new(b, Vector2::ZERO, h, Vector2::ZERO, JointKind::Rod { length: one });
                if let Ok(j) = note(self.world.add_joint(rod)) {
                    self.joints.push(j);
                    ok += 1;
                }
            }
            below = Some(h);
        }
        ok
    }

    fn point(&self, p: Point) -> Vector2 {
        p.resolve(self.world.bounds(), Some((&self.world, &self.bodies)))
    }

    fn generator(&self, g: &GenSpec) -> Result<Generator<'w>, Error> {
        Ok(match g {
            GenSpec::Linear(f, t) => {
                LinearForceGenerator::new(f.get()).with_targets(targets(t, &self.bodies)?).into()
            }
            GenSpec::Gravity(f, t) => {
                GravityForceGenerator::new(f.get()).with_targets(targets(t, &self.bodies)?).into()
            }
            GenSpec::GravityToPoint(p, a, t) => GravityToPointForceGenerator::new(self.point(*p), a.get())
                .with_targets(targets(t, &self.bodies)?)
                .into(),
            GenSpec::Custom { force, torque, level, set_velocity } => {
                Generator::boxed(Box::new(FuzzGenerator {
                    force: force.get(),
                    torque: torque.get(),
                    level: level.map(|l| u32::from(l % 4)),
                    set_velocity: *set_velocity,
                }))
            }
        })
    }
}
