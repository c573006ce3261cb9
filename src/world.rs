//! [`World`]: the space in which the simulation happens.
//!
//! A world owns every body, polygon path and force generator in fixed-capacity
//! storage chosen when it is created ([`Storage`]): borrowed buffers
//! ([`WorldBuffers`], no allocator needed, can live in a `static`), or with the
//! `alloc` feature heap buffers sized at run time ([`Capacities`]). The engine is
//! the same code on both. Nothing ever grows: a full store is an
//! [`Error::CapacityFull`], and a call that returns an error has changed nothing.

use managed::ManagedSlice;

use crate::solver::{ContactConstraint, Solver, SolverBody};

use crate::arbiter::Arbiter;
use crate::arena::{Arena, Handle, Slot};
use crate::body::{Body, BodyDef, BodyHandle, BodyType, MassSpec, PathHandle, Shape};
use crate::collision::{Contacts, Index};
use crate::constraint::{
    self, Constraint, ConstraintHandle, ConstraintMarker, Joint, JointDef, JointHandle, JointMarker,
    UserConstraint, MAX_USER_CONSTRAINTS,
};
use crate::error::Error;
use crate::force::Generator;
use crate::geometry::circle::{circle_area, circle_unit_inertia};
use crate::geometry::{MassData, PolygonPath};
use crate::handler::{Handler, HandlerTable, PostStepQueue};
use crate::index::Proxy;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rect, Rot, Vector2};

/// Largest |coordinate| of the world bounds, in metres (2^20 ≈ 1,048 km).
///
/// Keeping positions within ±2^20 leaves 2^11 of headroom in Q32.32 for a body to
/// move past the bounds in one step before it is frozen, so positions never overflow.
pub const MAX_COORDINATE: Scalar = Scalar::from_int(1 << 20);

/// Largest bounding radius of a body about its centre of mass, in metres: the
/// geometry limits ([`MAX_CIRCLE_RADIUS`](crate::geometry::circle::MAX_CIRCLE_RADIUS),
/// [`MAX_POLYGON_RADIUS`](crate::geometry::polygon_path::MAX_POLYGON_RADIUS)), set so
/// that the unit moment of inertia (∝ r⁴) stays 5× inside Q32.32's range.
pub const MAX_BODY_RADIUS: Scalar = crate::geometry::circle::MAX_CIRCLE_RADIUS;

/// Highest speed limit a world may be configured with, in m/s.
///
/// With the longest time step ([`MAX_TIME_STEP`](crate::MAX_TIME_STEP)) a body
/// moves at most 512 m per step, and squared speeds (≤ 8.4e6) stay exact.
pub const MAX_LINEAR_SPEED_LIMIT: Scalar = Scalar::from_int(2048);

/// Highest angular speed limit a world may be configured with, in rad/s. With
/// inertia ≤ [`MAX_INERTIA`](crate::geometry::mass::MAX_INERTIA) (1e6 kg·m²) the
/// angular momentum stays ≤ 2.6e8, 8× inside Q32.32's range.
pub const MAX_ANGULAR_SPEED_LIMIT: Scalar = Scalar::from_int(256);

/// Largest friction coefficient accepted.
pub const MAX_FRICTION: Scalar = Scalar::from_int(100);

/// Speculative contact distance, in metres (Box2D v3's 4 × linear slop): shapes
/// closer than this get contact points before they touch, so the solver can stop
/// them meeting without overshoot, and "touching" for the callbacks means "within
/// this distance".
pub const SPECULATIVE_DISTANCE: Scalar = Scalar::lit("0.02");

/// Most solver sub-steps per step.
pub const MAX_SUBSTEPS: u32 = 16;

/// World configuration; every option has a default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WorldDef {
    /// The region bodies live in. A body whose centre leaves it is frozen and
    /// reported (see [`Body::is_out_of_bounds`]).
    pub bounds: Rect,
    /// Speed limit for every body, m/s (default 400, at most
    /// [`MAX_LINEAR_SPEED_LIMIT`]). Applied after forces and after the solver.
    pub max_linear_speed: Scalar,
    /// Angular speed limit, rad/s (default 200, at most
    /// [`MAX_ANGULAR_SPEED_LIMIT`]). The step also limits rotation to π/4 per step.
    pub max_angular_speed: Scalar,
    /// Solver sub-steps per step, 1 to [`MAX_SUBSTEPS`] (default 4). More
    /// sub-steps stack better and cost proportionally more.
    pub substeps: u32,
    /// Contact stiffness, Hz (default 30; capped at a quarter of the sub-step rate).
    pub contact_hertz: Scalar,
    /// Contact damping ratio (default 10: heavily damped, no bounce from push-out).
    pub contact_damping_ratio: Scalar,
    /// Fastest speed at which overlap is pushed out, m/s (default 3).
    pub contact_push_speed: Scalar,
    /// Contacts approaching slower than this (m/s) do not bounce (default 1), so
    /// resting bodies settle instead of jittering.
    pub restitution_threshold: Scalar,
    /// Steps an arbiter is kept after its bodies stop touching, counting the step
    /// they separate (default 3; the manual's persistence).
    pub arbiter_persistence: u32,
}

impl WorldDef {
    /// The manual's world: bounds from (0, 0) to (`width`, `height`) metres.
    #[must_use]
    pub fn new(width: Scalar, height: Scalar) -> Self {
        Self::with_bounds(Rect { min: Vector2::ZERO, max: Vector2::new(width, height) })
    }

    /// A world with arbitrary bounds (e.g. centred on the origin).
    #[must_use]
    pub fn with_bounds(bounds: Rect) -> Self {
        Self {
            bounds,
            max_linear_speed: Scalar::from_int(400),
            max_angular_speed: Scalar::from_int(200),
            substeps: 4,
            contact_hertz: Scalar::from_int(30),
            contact_damping_ratio: Scalar::from_int(10),
            contact_push_speed: Scalar::from_int(3),
            restitution_threshold: Scalar::from_int(1),
            arbiter_persistence: 3,
        }
    }

    fn validate(&self) -> Result<(), Error> {
        let b = self.bounds;
        let inside = |v: Scalar| v.abs() <= MAX_COORDINATE;
        if !(inside(b.min.x) && inside(b.min.y) && inside(b.max.x) && inside(b.max.y)) {
            return Err(Error::OutOfRange { what: "world bounds" });
        }
        if b.min.x >= b.max.x || b.min.y >= b.max.y {
            return Err(Error::OutOfRange { what: "world size" });
        }
        if self.max_linear_speed <= ZERO || self.max_linear_speed > MAX_LINEAR_SPEED_LIMIT {
            return Err(Error::OutOfRange { what: "max_linear_speed" });
        }
        if self.max_angular_speed <= ZERO || self.max_angular_speed > MAX_ANGULAR_SPEED_LIMIT {
            return Err(Error::OutOfRange { what: "max_angular_speed" });
        }
        if self.substeps == 0 || self.substeps > MAX_SUBSTEPS {
            return Err(Error::OutOfRange { what: "substeps" });
        }
        let hundred = Scalar::from_int(100);
        if self.contact_hertz < ZERO || self.contact_hertz > Scalar::from_int(1000) {
            return Err(Error::OutOfRange { what: "contact_hertz" });
        }
        if self.contact_damping_ratio < ZERO || self.contact_damping_ratio > hundred {
            return Err(Error::OutOfRange { what: "contact_damping_ratio" });
        }
        if self.contact_push_speed < ZERO || self.contact_push_speed > hundred {
            return Err(Error::OutOfRange { what: "contact_push_speed" });
        }
        if self.restitution_threshold < ZERO || self.restitution_threshold > hundred {
            return Err(Error::OutOfRange { what: "restitution_threshold" });
        }
        Ok(())
    }
}

/// Marker type naming force generators in handles.
#[derive(Debug)]
pub enum GeneratorMarker {}

/// Handle of a force generator in a [`World`].
pub type GeneratorHandle = Handle<GeneratorMarker>;

/// Force generators a world can hold. Hooks (generators, handlers, callbacks) are
/// few and may borrow the game's objects, so they live inline in the [`World`]
/// with fixed capacities; the bulk data (bodies, paths, arbiters) is in
/// [`Storage`] sized by the caller.
pub const MAX_FORCE_GENERATORS: usize = 16;

/// How many objects of each kind a world can hold (with the `alloc` feature).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacities {
    /// Bodies.
    pub bodies: usize,
    /// Shared polygon paths.
    pub paths: usize,
    /// Candidate pairs per step and arbiters (pairs of bodies in contact, or kept
    /// for persistence). A stack needs about 2 per body, a dense pile about 4.
    pub contacts: usize,
    /// Built-in joints.
    pub joints: usize,
}

impl Default for Capacities {
    fn default() -> Self {
        Self::for_bodies(1024)
    }
}

impl Capacities {
    /// Room for `bodies` bodies, each with its own polygon path, 4 contacts and
    /// 2 joints per body.
    #[must_use]
    pub fn for_bodies(bodies: usize) -> Self {
        Self { bodies, paths: bodies, contacts: bodies.saturating_mul(4), joints: bodies.saturating_mul(2) }
    }
}

/// The storage a world runs on: one slice per store, each borrowed or owned.
pub struct Storage<'a> {
    /// Body slots.
    pub bodies: ManagedSlice<'a, Slot<Body>>,
    /// Polygon path slots.
    pub paths: ManagedSlice<'a, Slot<PolygonPath>>,
    /// Broad-phase proxies, one per body (scratch).
    pub proxies: ManagedSlice<'a, Proxy>,
    /// Body slot of each proxy, one per body (scratch).
    pub proxy_bodies: ManagedSlice<'a, u32>,
    /// Candidate pairs (scratch); its length is the pair capacity.
    pub pairs: ManagedSlice<'a, (u32, u32)>,
    /// Arbiters; its length is the arbiter capacity.
    pub arbiters: ManagedSlice<'a, Arbiter>,
    /// The arbiter buffer the next step writes into; same length as `arbiters`.
    pub arbiters_next: ManagedSlice<'a, Arbiter>,
    /// Built-in joint slots.
    pub joints: ManagedSlice<'a, Slot<Joint>>,
    /// Body pairs held by joints that do not collide (scratch); as long as `joints`.
    pub joint_pairs: ManagedSlice<'a, (u32, u32)>,
    /// The automatic index's sort order (scratch), one entry per body.
    pub sweep_order: ManagedSlice<'a, u32>,
    /// The solver's copy of each body during a step (scratch), one per body.
    pub solver_bodies: ManagedSlice<'a, SolverBody>,
    /// The solver's contact constraints (scratch); as long as `arbiters`.
    pub contact_constraints: ManagedSlice<'a, ContactConstraint>,
}

impl Storage<'_> {
    /// Heap storage with the given capacities.
    #[cfg(feature = "alloc")]
    #[must_use]
    pub fn with_capacities(c: Capacities) -> Self {
        fn buf<T>(n: usize) -> alloc::vec::Vec<Slot<T>> {
            let mut v = alloc::vec::Vec::with_capacity(n);
            v.resize_with(n, || Slot::EMPTY);
            v
        }
        fn plain<T: Clone>(n: usize, v: T) -> alloc::vec::Vec<T> {
            alloc::vec![v; n]
        }
        let empty_proxy = Proxy { aabb: Rect::default(), is_static: false };
        Self {
            bodies: ManagedSlice::Owned(buf(c.bodies)),
            paths: ManagedSlice::Owned(buf(c.paths)),
            proxies: ManagedSlice::Owned(plain(c.bodies, empty_proxy)),
            proxy_bodies: ManagedSlice::Owned(plain(c.bodies, 0)),
            pairs: ManagedSlice::Owned(plain(c.contacts, (0, 0))),
            arbiters: ManagedSlice::Owned(plain(c.contacts, Arbiter::EMPTY)),
            arbiters_next: ManagedSlice::Owned(plain(c.contacts, Arbiter::EMPTY)),
            joints: ManagedSlice::Owned(buf(c.joints)),
            joint_pairs: ManagedSlice::Owned(plain(c.joints, (0, 0))),
            sweep_order: ManagedSlice::Owned(plain(c.bodies, 0)),
            solver_bodies: ManagedSlice::Owned(plain(c.bodies, SolverBody::EMPTY)),
            contact_constraints: ManagedSlice::Owned(plain(c.contacts, ContactConstraint::EMPTY)),
        }
    }
}

/// Statically sized buffers for a world that needs no allocator: `BODIES` bodies
/// and as many polygon paths, `CONTACTS` candidate pairs and arbiters, `JOINTS`
/// built-in joints (default 16). `new` is `const`, so the buffers can be a
/// `static` (e.g. in a `static_cell::StaticCell`) or a local.
pub struct WorldBuffers<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize = 16> {
    bodies: [Slot<Body>; BODIES],
    paths: [Slot<PolygonPath>; BODIES],
    proxies: [Proxy; BODIES],
    proxy_bodies: [u32; BODIES],
    pairs: [(u32, u32); CONTACTS],
    arbiters: [Arbiter; CONTACTS],
    arbiters_next: [Arbiter; CONTACTS],
    joints: [Slot<Joint>; JOINTS],
    joint_pairs: [(u32, u32); JOINTS],
    sweep_order: [u32; BODIES],
    solver_bodies: [SolverBody; BODIES],
    contact_constraints: [ContactConstraint; CONTACTS],
}

impl<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize> WorldBuffers<BODIES, CONTACTS, JOINTS> {
    /// Empty buffers.
    #[must_use]
    pub const fn new() -> Self {
        let empty_proxy = Proxy { aabb: Rect { min: Vector2::ZERO, max: Vector2::ZERO }, is_static: false };
        Self {
            bodies: [Slot::EMPTY; BODIES],
            paths: [Slot::EMPTY; BODIES],
            proxies: [empty_proxy; BODIES],
            proxy_bodies: [0; BODIES],
            pairs: [(0, 0); CONTACTS],
            arbiters: [Arbiter::EMPTY; CONTACTS],
            arbiters_next: [Arbiter::EMPTY; CONTACTS],
            joints: [Slot::EMPTY; JOINTS],
            joint_pairs: [(0, 0); JOINTS],
            sweep_order: [0; BODIES],
            solver_bodies: [SolverBody::EMPTY; BODIES],
            contact_constraints: [ContactConstraint::EMPTY; CONTACTS],
        }
    }

    /// The buffers as a world's storage.
    pub fn storage(&mut self) -> Storage<'_> {
        Storage {
            bodies: ManagedSlice::Borrowed(&mut self.bodies[..]),
            paths: ManagedSlice::Borrowed(&mut self.paths[..]),
            proxies: ManagedSlice::Borrowed(&mut self.proxies[..]),
            proxy_bodies: ManagedSlice::Borrowed(&mut self.proxy_bodies[..]),
            pairs: ManagedSlice::Borrowed(&mut self.pairs[..]),
            arbiters: ManagedSlice::Borrowed(&mut self.arbiters[..]),
            arbiters_next: ManagedSlice::Borrowed(&mut self.arbiters_next[..]),
            joints: ManagedSlice::Borrowed(&mut self.joints[..]),
            joint_pairs: ManagedSlice::Borrowed(&mut self.joint_pairs[..]),
            sweep_order: ManagedSlice::Borrowed(&mut self.sweep_order[..]),
            solver_bodies: ManagedSlice::Borrowed(&mut self.solver_bodies[..]),
            contact_constraints: ManagedSlice::Borrowed(&mut self.contact_constraints[..]),
        }
    }
}

impl<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize> Default
    for WorldBuffers<BODIES, CONTACTS, JOINTS>
{
    fn default() -> Self {
        Self::new()
    }
}

/// What happened during a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Bodies that left the bounds this step (now frozen; see
    /// [`World::out_of_bounds_bodies`]).
    pub left_bounds: u32,
    /// Arbiters alive after the step (touching pairs and persisted ones).
    pub arbiters: u32,
    /// Post-step callbacks that ran after the step.
    pub post_step_callbacks: u32,
    /// Breakable joints that broke this step (and were removed).
    pub joints_broken: u32,
}

/// Called after a step for each joint that broke, with its former handle and the
/// joint as it was.
pub type JointBreakFn = for<'w> fn(&mut World<'w>, JointHandle, Joint);

/// The simulation: bodies, shared polygon paths, force generators, and `step`.
pub struct World<'a> {
    pub(crate) def: WorldDef,
    pub(crate) bodies: Arena<'a, Body>,
    pub(crate) paths: Arena<'a, PolygonPath>,
    pub(crate) generators:
        Arena<'a, Generator<'a>, GeneratorMarker, [Slot<Generator<'a>>; MAX_FORCE_GENERATORS]>,
    pub(crate) index: Index<'a>,
    pub(crate) sweep: crate::index::SortAndSweepIndex<'a>,
    pub(crate) handlers: HandlerTable<'a>,
    pub(crate) post_step: PostStepQueue,
    pub(crate) contacts: Contacts<'a>,
    pub(crate) joints: Arena<'a, Joint, JointMarker>,
    pub(crate) solver: Solver<'a>,
    pub(crate) constraints:
        Arena<'a, UserConstraint<'a>, ConstraintMarker, [Slot<UserConstraint<'a>>; MAX_USER_CONSTRAINTS]>,
    pub(crate) break_callback: Option<JointBreakFn>,
    pub(crate) step_count: u64,
}

impl<'a> World<'a> {
    /// A world on the given storage.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for bounds that are empty or exceed
    /// ±[`MAX_COORDINATE`], or settings outside their ranges;
    /// [`Error::InvalidOperation`] when the proxy buffers are shorter than the
    /// body buffer or the two arbiter buffers differ in length.
    pub fn new(def: WorldDef, storage: Storage<'a>) -> Result<Self, Error> {
        def.validate()?;
        let nb = storage.bodies.len();
        if storage.proxies.len() < nb || storage.proxy_bodies.len() < nb {
            return Err(Error::InvalidOperation { what: "proxy buffers must hold one entry per body" });
        }
        if storage.solver_bodies.len() < nb {
            return Err(Error::InvalidOperation {
                what: "the solver body buffer must hold one entry per body",
            });
        }
        if storage.contact_constraints.len() < storage.arbiters.len() {
            return Err(Error::InvalidOperation {
                what: "the contact constraint buffer must be as long as the arbiter buffer",
            });
        }
        if storage.joint_pairs.len() < storage.joints.len() {
            return Err(Error::InvalidOperation { what: "joint pair buffer must hold one entry per joint" });
        }
        if storage.arbiters.len() != storage.arbiters_next.len() {
            return Err(Error::InvalidOperation {
                what: "the two arbiter buffers must have the same length",
            });
        }
        Ok(Self {
            def,
            bodies: Arena::new(storage.bodies),
            paths: Arena::new(storage.paths),
            generators: Arena::inline(),
            index: Index::default(),
            sweep: crate::index::SortAndSweepIndex::new(storage.sweep_order),
            handlers: HandlerTable::new(),
            post_step: PostStepQueue::new(),
            contacts: Contacts {
                proxies: storage.proxies,
                proxy_bodies: storage.proxy_bodies,
                pairs: storage.pairs,
                arbiters: storage.arbiters,
                next: storage.arbiters_next,
                arbiter_count: 0,
                joint_pairs: storage.joint_pairs,
            },
            joints: Arena::new(storage.joints),
            solver: Solver {
                bodies: storage.solver_bodies,
                constraints: storage.contact_constraints,
                count: 0,
            },
            constraints: Arena::inline(),
            break_callback: None,
            step_count: 0,
        })
    }

    /// A world on heap storage with the given capacities.
    ///
    /// # Errors
    /// As [`World::new`].
    #[cfg(feature = "alloc")]
    pub fn with_capacities(def: WorldDef, capacities: Capacities) -> Result<Self, Error> {
        Self::new(def, Storage::with_capacities(capacities))
    }

    /// The configuration.
    #[must_use]
    pub fn def(&self) -> &WorldDef {
        &self.def
    }

    /// The world bounds.
    #[must_use]
    pub fn bounds(&self) -> Rect {
        self.def.bounds
    }

    /// Steps taken so far.
    #[must_use]
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    // ---- polygon paths -------------------------------------------------------

    /// Stores a polygon path for bodies to share.
    ///
    /// # Errors
    /// [`Error::CapacityFull`] when the path store is full.
    pub fn add_path(&mut self, path: PolygonPath) -> Result<PathHandle, Error> {
        self.paths.insert(path).map_err(|_| Error::CapacityFull { what: "path" })
    }

    /// The path behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn path(&self, h: PathHandle) -> Result<&PolygonPath, Error> {
        self.paths.get(h).ok_or(Error::StaleHandle)
    }

    /// Removes a path no body uses any more.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::InvalidOperation`] while a body uses it.
    pub fn remove_path(&mut self, h: PathHandle) -> Result<PolygonPath, Error> {
        if !self.paths.contains(h) {
            return Err(Error::StaleHandle);
        }
        if self.bodies.iter().any(|(_, b)| b.shape == Shape::Polygon(h)) {
            return Err(Error::InvalidOperation { what: "remove a path that bodies use" });
        }
        self.paths.remove(h).ok_or(Error::StaleHandle)
    }

    // ---- bodies --------------------------------------------------------------

    /// Creates a body.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a radius, mass, density, friction, restitution,
    /// speed or rotation outside its range; [`Error::StaleHandle`] for an unknown
    /// polygon path; [`Error::OutsideBounds`] when the position is outside the
    /// world; [`Error::CapacityFull`] when the body store is full.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyHandle, Error> {
        let body = self.build_body(&def)?;
        self.bodies.insert(body).map_err(|_| Error::CapacityFull { what: "body" })
    }

    fn build_body(&self, def: &BodyDef) -> Result<Body, Error> {
        let (area, unit_inertia, radius) = match def.shape {
            Shape::Circle { radius } => {
                if radius <= ZERO || radius > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "radius" });
                }
                (circle_area(radius)?, circle_unit_inertia(radius)?, radius)
            }
            Shape::Polygon(h) => {
                let p = self.paths.get(h).ok_or(Error::StaleHandle)?;
                if p.radius() > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "polygon size" });
                }
                (p.area(), p.unit_inertia(), p.radius())
            }
        };
        let mut body_type = def.body_type;
        let mass = match (body_type, def.mass) {
            (BodyType::Dynamic, MassSpec::Mass(m)) if m == ZERO => {
                body_type = BodyType::Static;
                MassData::STATIC
            }
            (BodyType::Dynamic, MassSpec::Mass(m)) => MassData::from_mass(m, area, unit_inertia)?,
            (BodyType::Dynamic, MassSpec::Density(d)) => MassData::from_density(d, area, unit_inertia)?,
            _ => MassData::STATIC,
        };
        if def.friction < ZERO || def.friction > MAX_FRICTION {
            return Err(Error::OutOfRange { what: "friction" });
        }
        if def.restitution < ZERO || def.restitution > scalar::ONE {
            return Err(Error::OutOfRange { what: "restitution" });
        }
        let rotation = normalized_rotation(def.rotation)?;
        if !self.def.bounds.contains(def.position) {
            return Err(Error::OutsideBounds);
        }
        let moving = body_type != BodyType::Static;
        let v = if moving { def.linear_velocity } else { Vector2::ZERO };
        let w = if moving { def.angular_velocity } else { ZERO };
        if v.x.abs() > self.def.max_linear_speed
            || v.y.abs() > self.def.max_linear_speed
            || v.length() > self.def.max_linear_speed
        {
            return Err(Error::OutOfRange { what: "linear velocity" });
        }
        if w.abs() > self.def.max_angular_speed {
            return Err(Error::OutOfRange { what: "angular velocity" });
        }
        let mut body = Body {
            position: def.position,
            rotation,
            linear_velocity: v,
            angular_velocity: w,
            shape: def.shape,
            body_type,
            mass,
            friction: def.friction,
            restitution: def.restitution,
            collision_groups: def.collision_groups,
            collision_level: def.collision_level,
            user_data: def.user_data,
            out_of_bounds: false,
            radius,
            aabb: Rect::default(),
            pending_v: Vector2::ZERO,
            pending_w: ZERO,
        };
        body.aabb = compute_aabb(&body, &self.paths);
        Ok(body)
    }

    /// Removes a body and returns it. Its arbiters end at once: `end` is called
    /// for each pair that had begun (the body is still readable then), in pair
    /// order, and the arbiters are dropped. Safe to call from a post-step callback.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_body(&mut self, h: BodyHandle) -> Result<Body, Error> {
        if !self.bodies.contains(h) {
            return Err(Error::StaleHandle);
        }
        self.end_arbiters_of(h.index());
        self.remove_constraints_of(h);
        self.bodies.remove(h).ok_or(Error::StaleHandle)
    }

    /// Removes every joint and game constraint attached to `h`.
    fn remove_constraints_of(&mut self, h: BodyHandle) {
        for i in 0..self.joints.slots_used() {
            let attached =
                self.joints.get_at(i).is_some_and(|j| j.def.body_a == h || j.def.body_b == Some(h));
            if let (true, Some(jh)) = (attached, self.joints.handle_at(i)) {
                self.joints.remove(jh);
            }
        }
        for i in 0..self.constraints.slots_used() {
            let attached = self.constraints.get_at(i).is_some_and(|c| c.body_a == h || c.body_b == Some(h));
            if let (true, Some(ch)) = (attached, self.constraints.handle_at(i)) {
                self.constraints.remove(ch);
            }
        }
    }

    /// The body behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] (a removed body's handle never names another body).
    pub fn body(&self, h: BodyHandle) -> Result<&Body, Error> {
        self.bodies.get(h).ok_or(Error::StaleHandle)
    }

    /// The body behind `h`, to change its velocity or apply impulses.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn body_mut(&mut self, h: BodyHandle) -> Result<&mut Body, Error> {
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)
    }

    /// Every body with its handle, in slot order (the engine's canonical order).
    pub fn bodies(&self) -> impl Iterator<Item = (BodyHandle, &Body)> + '_ {
        self.bodies.iter()
    }

    /// Number of bodies.
    #[must_use]
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Bodies frozen after leaving the bounds.
    pub fn out_of_bounds_bodies(&self) -> impl Iterator<Item = BodyHandle> + '_ {
        self.bodies.iter().filter(|(_, b)| b.out_of_bounds).map(|(h, _)| h)
    }

    /// Moves a body (teleport). Brings a frozen body back into play.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::OutsideBounds`] for a point outside the world.
    pub fn set_position(&mut self, h: BodyHandle, p: Vector2) -> Result<(), Error> {
        if !self.def.bounds.contains(p) {
            return Err(Error::OutsideBounds);
        }
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.position = p;
        b.out_of_bounds = false;
        b.aabb = compute_aabb(b, &self.paths);
        Ok(())
    }

    /// Sets a body's rotation.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::OutOfRange`] for a zero rotation.
    pub fn set_rotation(&mut self, h: BodyHandle, q: Rot) -> Result<(), Error> {
        let q = normalized_rotation(q)?;
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.rotation = q;
        b.aabb = compute_aabb(b, &self.paths);
        Ok(())
    }

    /// Sets a body's rotation from an angle in radians.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_angle(&mut self, h: BodyHandle, radians: Scalar) -> Result<(), Error> {
        self.set_rotation(h, Rot::from_angle(radians))
    }

    /// Makes a body static (the manual's `setStatic`): it stops and never moves again.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_static(&mut self, h: BodyHandle) -> Result<(), Error> {
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.body_type = BodyType::Static;
        b.mass = MassData::STATIC;
        b.linear_velocity = Vector2::ZERO;
        b.angular_velocity = ZERO;
        Ok(())
    }

    // ---- force generators ----------------------------------------------------

    /// Adds a force generator; generators run in the order they were added.
    ///
    /// # Errors
    /// [`Error::CapacityFull`] when the generator store is full.
    pub fn add_force_generator(&mut self, g: impl Into<Generator<'a>>) -> Result<GeneratorHandle, Error> {
        self.generators.insert(g.into()).map_err(|_| Error::CapacityFull { what: "force generator" })
    }

    /// Removes a force generator and returns it.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_force_generator(&mut self, h: GeneratorHandle) -> Result<Generator<'a>, Error> {
        self.generators.remove(h).ok_or(Error::StaleHandle)
    }

    /// The force generator behind `h`, to change its parameters.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn force_generator_mut(&mut self, h: GeneratorHandle) -> Result<&mut Generator<'a>, Error> {
        self.generators.get_mut(h).ok_or(Error::StaleHandle)
    }

    // ---- constraints ---------------------------------------------------------

    /// Adds a built-in joint (spring, damped spring, rod, rope, pivot, weld).
    ///
    /// # Errors
    /// [`Error::StaleHandle`] for an unknown body; [`Error::InvalidOperation`] for a
    /// joint between a body and itself or between two bodies that cannot move;
    /// [`Error::OutOfRange`] for a negative stiffness or damping, a zero or huge
    /// length, inverted angle limits, a negative torque limit or break impulse, or
    /// an anchor more than 256 m from its body's centre; [`Error::OutsideBounds`]
    /// for a world anchor outside the world; [`Error::CapacityFull`].
    pub fn add_joint(&mut self, def: JointDef) -> Result<JointHandle, Error> {
        let a = self.bodies.get(def.body_a).ok_or(Error::StaleHandle)?;
        let b = match def.body_b {
            Some(hb) => Some(self.bodies.get(hb).ok_or(Error::StaleHandle)?),
            None => None,
        };
        constraint::validate(&def, a, b, self.def.bounds)?;
        let ground = constraint::ground();
        let joint = Joint::new(def, a, b.unwrap_or(&ground));
        self.joints.insert(joint).map_err(|_| Error::CapacityFull { what: "joint" })
    }

    /// Removes a joint and returns it.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_joint(&mut self, h: JointHandle) -> Result<Joint, Error> {
        self.joints.remove(h).ok_or(Error::StaleHandle)
    }

    /// The joint behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] (also once a breakable joint broke).
    pub fn joint(&self, h: JointHandle) -> Result<&Joint, Error> {
        self.joints.get(h).ok_or(Error::StaleHandle)
    }

    /// The joint behind `h`, e.g. to change a pivot's motor.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn joint_mut(&mut self, h: JointHandle) -> Result<&mut Joint, Error> {
        self.joints.get_mut(h).ok_or(Error::StaleHandle)
    }

    /// Every joint with its handle, in slot order (the order they are solved in).
    pub fn joints(&self) -> impl Iterator<Item = (JointHandle, &Joint)> + '_ {
        self.joints.iter()
    }

    /// Sets the function called after a step for each joint that broke.
    pub fn set_joint_break_callback(&mut self, f: Option<JointBreakFn>) {
        self.break_callback = f;
    }

    /// Adds a game constraint between `a` and `b` (or a fixed point when `b` is
    /// `None`), borrowed or boxed: `Managed::Borrowed(&mut c)` /
    /// `Managed::Owned(Box::new(c))`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::InvalidOperation`] for a body with itself;
    /// [`Error::CapacityFull`] when
    /// [`MAX_USER_CONSTRAINTS`] are in use.
    pub fn add_constraint(
        &mut self,
        a: BodyHandle,
        b: Option<BodyHandle>,
        c: managed::Managed<'a, dyn Constraint + Send + 'a>,
    ) -> Result<ConstraintHandle, Error> {
        if !self.bodies.contains(a) || b.is_some_and(|b| !self.bodies.contains(b)) {
            return Err(Error::StaleHandle);
        }
        if Some(a) == b {
            return Err(Error::InvalidOperation { what: "a constraint between a body and itself" });
        }
        self.constraints
            .insert(UserConstraint { body_a: a, body_b: b, constraint: c })
            .map_err(|_| Error::CapacityFull { what: "constraint" })
    }

    /// Removes a game constraint.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_constraint(&mut self, h: ConstraintHandle) -> Result<(), Error> {
        self.constraints.remove(h).map(drop).ok_or(Error::StaleHandle)
    }

    // ---- collisions ----------------------------------------------------------

    /// Replaces the spatial index (the manual's custom indexing system).
    pub fn set_spatial_index(&mut self, index: Index<'a>) {
        self.index = index;
    }

    /// Registers a handler for collisions between bodies of levels `a` and `b`
    /// (either order; `a == b` allowed). The manual's `addCollisionHandler`,
    /// which reported failure by returning false.
    ///
    /// # Errors
    /// [`Error::InvalidOperation`] when a handler for these levels exists;
    /// [`Error::CapacityFull`] when
    /// [`MAX_COLLISION_HANDLERS`](crate::handler::MAX_COLLISION_HANDLERS) are registered.
    pub fn add_collision_handler(
        &mut self,
        a: u32,
        b: u32,
        handler: impl Into<Handler<'a>>,
    ) -> Result<(), Error> {
        self.handlers.add(a, b, handler.into())
    }

    /// Removes and returns the handler for levels `a` and `b`, if any.
    pub fn remove_collision_handler(&mut self, a: u32, b: u32) -> Option<Handler<'a>> {
        self.handlers.remove(a, b)
    }

    /// Replaces the default handler (used for level pairs without their own);
    /// `None` restores "resolve everything". Returns the previous one.
    pub fn set_default_collision_handler(&mut self, handler: Option<Handler<'a>>) -> Option<Handler<'a>> {
        self.handlers.set_default(handler)
    }

    /// The arbiters (touching or persisting pairs), in canonical pair order.
    pub fn arbiters(&self) -> impl Iterator<Item = &Arbiter> + '_ {
        self.contacts.live().iter()
    }

    /// The arbiter of two bodies, if they touch or recently touched.
    #[must_use]
    pub fn arbiter(&self, a: BodyHandle, b: BodyHandle) -> Option<&Arbiter> {
        let key = if a.index() <= b.index() { (a.index(), b.index()) } else { (b.index(), a.index()) };
        let live = self.contacts.live();
        let i = live.binary_search_by(|arb| arb.key().cmp(&key)).ok()?;
        live.get(i).filter(|arb| (arb.body_a == a && arb.body_b == b) || (arb.body_a == b && arb.body_b == a))
    }

    // ---- state ---------------------------------------------------------------
}

/// The unit rotation in the direction of `q`, or an error for (0, 0).
fn normalized_rotation(q: Rot) -> Result<Rot, Error> {
    Rot::from_direction(Vector2::new(q.c, q.s)).ok_or(Error::OutOfRange { what: "rotation" })
}

/// The world bounding box of a body at its current transform.
pub(crate) fn compute_aabb(b: &Body, paths: &Arena<'_, PolygonPath>) -> Rect {
    match b.shape {
        Shape::Circle { radius } => Rect::from_center(b.position, Vector2::new(radius, radius)),
        Shape::Polygon(h) => match paths.get(h) {
            Some(p) => {
                let xf = b.transform();
                let mut it = p.vertices().iter().map(|v| xf.apply(*v));
                let first = it.next().unwrap_or(b.position);
                it.fold(Rect { min: first, max: first }, |r, v| Rect { min: r.min.min(v), max: r.max.max(v) })
            }
            None => Rect::from_center(b.position, Vector2::new(b.radius, b.radius)),
        },
    }
}
