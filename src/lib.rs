#![cfg_attr(not(feature = "std"), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]
//! # arphysics
//!
//! A deterministic, fixed-point, `no_std`, allocation-optional 2D rigid-body physics
//! engine implementing the ARPhysics design: worlds, pluggable spatial indexing,
//! circle and convex polygon bodies sharing polygon paths, arbiters with the five
//! states of the manual, force generators, collision handlers keyed by collision
//! levels, collision groups and post-step callbacks; sensors and event lists
//! (contact begin, end and hit, sensor begin and end, joint broke) read after
//! each step.
//!
//! Built for lockstep and rollback multiplayer games (every peer computes the
//! bit-identical world from the same inputs), embedded and console targets (no
//! allocator, no FPU needed) and for fuzzing a game for desyncs.
//!
//! ```
//! use arphysics::{BodyDef, GravityForceGenerator, Scalar, Vector2, World, WorldBuffers, WorldDef};
//!
//! // The manual's setup: a 320 × 240 world, a 5 kg ball, gravity.
//! let mut buffers = WorldBuffers::<16, 64>::new(); // static storage: no allocator
//! let mut world = World::new(WorldDef::new(Scalar::from_num(320), Scalar::from_num(240)), buffers.storage())?;
//! let ball = world.add_body(
//!     BodyDef::circle(Scalar::from_num(5)).position(Vector2::from_int(50, 50)).mass(Scalar::from_num(5)),
//! )?;
//! world.add_force_generator(GravityForceGenerator::new(Vector2::new(Scalar::ZERO, Scalar::lit("-9.81"))))?;
//! let dt = Scalar::ONE / 60;
//! for _ in 0..60 {
//!     world.step(dt)?;
//! }
//! let y = world.body(ball)?.position().y;
//! assert!(y < Scalar::from_num(46) && y > Scalar::from_num(44)); // fell ≈ g/2 in 1 s
//! println!("state hash {:#x}", world.state_hash()); // equal on every target
//! # Ok::<(), arphysics::Error>(())
//! ```
//!
//! # Layers
//! * [`math`]: [`Scalar`] (Q32.32 fixed point whose operators saturate) and the
//!   small `Copy` value types [`Vector2`], [`Rot`], [`Transform`], [`Matrix22`],
//!   [`Rect`]; deterministic [`math::trig`] for angles at the API edge.
//! * [`geometry`]: [`PolygonPath`] (exact convex hull, area, centroid, inertia),
//!   circles and [`MassData`].
//! * [`arena`]: fixed-capacity slots with generational [`Handle`]s tagged with
//!   their world: a removed object's handle, or another world's, is an error,
//!   never another object.
//! * [`body`], [`force`], [`hook`]: bodies and their [`BodyDef`], force
//!   generators, and [`Hook`], how a world holds a game's objects.
//! * [`index`], [`collide`], [`arbiter`], [`handler`], [`collision`]: the broad
//!   phase (a trait you can implement), the narrow phase (one file per shape pair),
//!   the arbiter lifecycle and the callbacks.
//! * [`events`]: the event lists a step leaves (contacts, sensors, broken
//!   joints), in fixed-capacity buffers, in pair-key order.
//! * [`continuous`]: continuous collision, which sweeps fast bodies (and
//!   bullets) to their first impact after the solve.
//! * [`constraint`]: the manual's spring, damped spring and rod, plus rope,
//!   pivot (limits, motor) and weld joints, breakable; your own via [`Constraint`].
//! * the solver: a sub-stepped soft contact and joint solver (Box2D v3's design).
//! * [`limits`]: the ranges that stay exact, and the stage that keeps bodies in them.
//! * [`world`]: [`World`], which owns everything and runs [`World::step`].
//! * [`snapshot`]: the canonical encoding with its checksum trailer, restore
//!   (verify, validate, then apply), the state hashes (whole and per part) and
//!   `diff`.
//!
//! # Architecture: one concept per file
//! ```text
//! src/
//!   lib.rs              this page
//!   error.rs limits.rs  errors; the world's limits and the limits stage
//!   hook.rs             Hook: a game's object, borrowed or boxed
//!   math/               scalar/ (the number type; arith.rs: its operators) trig
//!                       vector2 matrix22 rot rect
//!   geometry/           polygon_path (hull, area, centroid, inertia) circle mass ray
//!   arena/              fixed-capacity slots; handle.rs: generational handles tagged with their world
//!   body.rs body_def.rs bodies; their definition
//!   world/              mod (World, step entry, hooks) def (WorldDef, validation)
//!                       storage (Storage, WorldBuffers, Capacities) bodies joints
//!   step.rs             StepContext and the pipeline, in order: broad phase →
//!                       forces → narrow phase and arbiter lifecycle → solve →
//!                       continuous collision → limits → events → post_solve; then (in
//!                       the world) broken joints and post-step callbacks
//!   index/              SpatialIndex, brute_force, sort_and_sweep
//!   collision.rs        the broad- and narrow-phase stages, the arbiter lifecycle
//!   collide/            one file per shape pair, manifold, toi (time of impact)
//!   continuous.rs       the continuous collision stage
//!   arbiter.rs          the manual's five states, ArbiterStore
//!   events.rs           the event lists (contact, sensor, joint broke)
//!   force/              ForceGenerator, the built-ins, the forces stage
//!   solver/             mod (the solve stage) body softness sweep
//!                       contact/ (prepare, solve, restitution)
//!   constraint/         def joint row (the solver's joint rows) maths user, one file
//!                       per joint kind
//!   handler.rs query.rs collision handlers and post-step callbacks; world queries
//!   snapshot/           write hash cursor layout validate apply diff
//! ```
//! Every stage is a function of the step's `StepContext` (`step.rs`) and the
//! parts of the world it touches; nothing below `world/` uses [`World`] except
//! the callbacks that get `&mut World` by design (post-step, joint break) and the
//! `impl World` blocks that add API (queries, snapshots).

//! # Features
//! * `std` (default): implies `alloc`.
//! * `alloc`: heap storage sized at run time ([`World::with_capacities`]), boxed
//!   user hooks. Without it the whole engine runs on [`WorldBuffers`] (a local or a
//!   `static`) and borrowed hooks; `cargo build --no-default-features --target
//!   thumbv7em-none-eabihf` builds it for a Cortex-M4.
//!
//! # The determinism contract
//! 1. **Bit-identical stepping.** No `f32`/`f64` arithmetic on the path of a step;
//!    floats appear only in the documented conversion helpers
//!    ([`math::scalar::try_from_f64`], [`Vector2::try_from_f64`], `to_f64`…). Equal
//!    inputs give equal bytes of state on every target, in debug and release, at any
//!    capacity; [`World::state_hash`] proves it (a golden hash is tested).
//! 2. **No panic on any input.** Every fallible operation returns [`Error`]; a call
//!    that returns an error has changed nothing. [`Scalar`]'s operators saturate
//!    (`a * b + c` is the same in debug and release, for the engine and for game
//!    code alike; division by zero saturates too), and ranges are kept far from
//!    saturation by validated inputs (see the limits below). A game's hook that
//!    panics is the game's panic; with `std` the world is first put back exactly
//!    as it was before the step ([`World::set_panic_guard`]).
//! 3. **No allocation in a step** (a test counts), and none required at all.
//! 4. **Iteration order comes from simulation state alone**: bodies in slot order,
//!    pairs in (lower slot, higher slot) order, hooks in registration order.
//! 5. **Everything that shapes future steps is hashed**: bodies, the body allocator,
//!    arbiters with their accumulated impulses and persistence counters. The
//!    post-step queue is drained before `step` and `remove_body` return, so nothing
//!    is queued between steps.
//! 6. **A full store never stops the game.** Candidate pairs and arbiters beyond
//!    the contact capacity are skipped in key order (lowest keys kept) and counted
//!    in the [`StepReport`]; [`WorldDef::strict_capacity`] makes it an error
//!    instead. [`World::stats`] reports the high-water marks to size capacities by.
//!
//! # Limits (ranges that stay exact)
//! | quantity | range | why |
//! |---|---|---|
//! | world bounds | within ±2^20 m ([`world::MAX_COORDINATE`]) | positions never overflow |
//! | body radius | ≤ 128 m ([`world::MAX_BODY_RADIUS`]); circles ≥ 1 cm keep their inertia to 1 % (below ≈ 3.5 mm it rounds to 0: `inertia` error) | inertia ∝ r⁴ stays in range |
//! | mass | 0.001 – 100,000 kg ([`geometry::mass`]); ignored (all zeros) for static and kinematic bodies | momentum ≤ 2e8 |
//! | moment of inertia | 1e-6 – 1e6 kg·m² ([`geometry::mass::MAX_INERTIA`]): a circle's is m·r²/2, a w × h box's m·(w² + h²)/12, so a 128 m circle weighs ≤ 122 kg, a 1 cm circle ≥ 20 g | angular momentum ≤ 2.6e8 at 256 rad/s; 1/inertia ≤ 1e6 |
//! | friction, restitution | 0 – 100 ([`limits::MAX_FRICTION`]), 0 – 1; bodies and arbiters alike | friction bound μ·λn |
//! | body damping, gravity scale | 0 – 1,024 /s ([`limits::MAX_BODY_DAMPING`]); ±16 ([`limits::MAX_GRAVITY_SCALE`]), the scaled acceleration clamped to ±16,384 m/s² | damping factor exact; forces in range |
//! | joints | lengths ≤ 1,024 m, stiffness ≤ 1e6 N/m, damping ≤ 1e5 N·s/m, motor speed ≤ ±512 rad/s; a target joint's frequency in (0, 1,000] Hz, damping ratio ≤ 100, force ≤ 1.6e9 N ([`limits`]) | spring forces exact; explicit springs stable |
//! | force generators | ±16,384 m/s² per component ([`limits::MAX_ACCELERATION`]), ±1.6e9 N ([`limits::MAX_FORCE`]), points within ±2^20 m | momentum after forces in range |
//! | arbiter persistence | 0 – 256 steps ([`limits::MAX_ARBITER_PERSISTENCE`]) | separated arbiters expire |
//! | contact recycle distance | 0 – 0.25 m, default 0.05 ([`limits::MAX_CONTACT_RECYCLE_DISTANCE`]) | kept manifolds stay close to computed ones |
//! | speed | ≤ 2,048 m/s configurable, default 400 ([`WorldDef::max_linear_speed`]) | squared speeds exact |
//! | spin | ≤ 256 rad/s, default 200, and ≤ π/4 per step | angular momentum in range |
//! | time step | [2^-16, 0.25] s ([`MIN_TIME_STEP`], [`MAX_TIME_STEP`]) | bounded motion per step; 1/sub-step ≤ 2^20 per second |
//! | polygon | ≤ 8 vertices ([`geometry::MAX_POLYGON_VERTICES`]); a rounding radius the core keeps a positive area with | fixed-size, no allocation |
//! | capsule, segment | half the length plus the radius ≤ 128 m (a segment ≤ 256 m long, ≥ 2^-20 m) | re-centred on the body, within the body radius |
//! | chain | ≥ 2 points (a loop ≥ 3), each link a valid segment (≥ 2^-20 m, ≤ 256 m, points within ±2^20 m); static only | the points of all chains fit [`Capacities::chain_vertices`] |
//!
//! # Coming from Box2D or Chipmunk
//! | Box2D v3 | Chipmunk | arphysics |
//! |---|---|---|
//! | `b2WorldDef`, `b2CreateWorld` | `cpSpaceNew` | [`WorldDef`], [`World::new`] / [`World::with_capacities`] (capacities fixed up front) |
//! | `b2BodyDef` + `b2ShapeDef` + `b2CreatePolygonShape` / `Capsule` / `Segment` | `cpBodyNew` + `cpPolyShapeNew` / `cpSegmentShapeNew` | [`BodyDef::circle`] / [`BodyDef::polygon`] / [`BodyDef::capsule`] / [`BodyDef::segment`]: one shape per body; polygons share a [`PolygonPath`] ([`PolygonPath::rounded`] for `b2MakeRoundedBox`) |
//! | `b2ChainDef`, `b2CreateChain` | — | [`ChainPath`], [`World::add_chain`], [`BodyDef::chain`]: one static body per chain, one arbiter per touching link |
//! | `b2BodyId` (world + index + generation) | `cpBody*` | [`BodyHandle`] (index + generation + world tag; stale or foreign ⇒ [`Error::StaleHandle`]) |
//! | `b2_staticBody` / `b2_kinematicBody` / `b2_dynamicBody` | `cpBodyNewStatic` / kinematic / dynamic | [`BodyType`] |
//! | `b2BodyDef::isBullet`, continuous collision | — | [`BodyDef::bullet`]; fast bodies are always swept against static and kinematic bodies ([`continuous`]) |
//! | gravity in the world def | `cpSpaceSetGravity` | a [`GravityForceGenerator`] (the manual's force generators) |
//! | `b2Filter` categories / masks / group index | `cpShapeFilter` groups | [`CollisionFilter`] on every body ([`BodyDef::filter`], Box2D's rule), vetoed by the manual's collision groups (shared bit ⇒ no collision); collision levels select handlers; [`QueryFilter`] with category, mask and an excluded body |
//! | `b2BodyDef::fixedRotation`, `linearDamping`, `angularDamping`, `gravityScale` | `cpBodySetMoment(INFINITY)`, `cpSpaceSetDamping` | [`BodyDef::fixed_rotation`], [`BodyDef::linear_damping`], [`BodyDef::angular_damping`], [`BodyDef::gravity_scale`] (read by the gravity generators); `World::set_*` to change them |
//! | `b2Body_SetType`, `b2Body_SetMassData`, `b2Body_SetTargetTransform` | `cpBodySetType`, `cpBodySetMass` | [`World::set_static`] / [`World::set_kinematic`] / [`World::set_dynamic`], [`World::set_mass`], [`World::set_target_transform`] |
//! | `b2PreSolveFcn`, begin/end touch callbacks | `cpCollisionHandler` begin / preSolve / postSolve / separate | [`CollisionHandler`] per level pair, [`FnHandler`] (function pointers), [`ClosureHandler`] (closures) |
//! | `b2World_GetContactEvents` (begin / end touch, hit), `b2ContactData` | — | [`World::contact_begin_events`], [`World::contact_end_events`], [`World::contact_hit_events`] ([`events`]); [`Arbiter::is_touching`] |
//! | `b2ShapeDef::isSensor`, `b2World_GetSensorEvents` | `cpShapeSetSensor` | [`BodyDef::sensor`], [`World::sensor_begin_events`], [`World::sensor_end_events`] |
//! | joint break (`b2Joint_GetConstraintForce` + destroy) | — | [`JointDef::breakable`], [`World::joint_broke_events`] |
//! | `cpSpaceAddPostStepCallback` | same | [`CallbackContext::add_post_step_callback`] |
//! | `b2RevoluteJoint`, `b2WeldJoint`, `b2DistanceJoint`, motor, limits, springs | `cpPivotJoint`, `cpDampedSpring`, `cpSlideJoint`… | [`JointKind`]: `Pivot` (limits, motor), `Weld`, `Rod`, `Rope`, `Spring`, `DampedSpring`; breakable |
//! | `b2MouseJoint`, `b2MouseJoint_SetTarget` | (a pivot to a moving static body) | [`JointKind::Target`] (frequency, damping ratio, force limit), [`World::set_joint_target`] |
//! | `b2World_CastRay`, `b2World_CastShape`, `b2World_OverlapAABB` | `cpSpaceSegmentQuery`, `cpSpaceBBQuery` | [`World::ray_cast`], [`World::ray_cast_all`], [`World::shape_cast`], [`World::query_aabb`], [`World::query_point`], [`World::query_shape`] |
//! | `b2World_Step(world, dt, subSteps)` | `cpSpaceStep` | [`World::step`]; sub-steps in [`WorldDef::substeps`], changed with [`World::set_substeps`] |
//! | floats, SIMD, threads | floats | Q32.32 fixed point, one thread, the same bits everywhere; [`World::snapshot`] / [`World::restore`] / [`World::state_hash`] |
//!
//! Units are SI throughout (metres, kilograms, seconds, radians); keep bodies between a
//! few centimetres and 256 m across, as you would in Box2D.
//!
//! # From the manual to Rust
//! * Reference counting (`retain`/`release`/`new`) → ownership: the world owns its
//!   bodies, paths and built-in generators; you hold typed, generational handles.
//! * `new BruteForceIndexing()` → the default [`Index`]; a custom indexing system
//!   implements [`SpatialIndex`] and only finds pairs: the arbiter lifecycle the
//!   manual asks every index to re-implement lives once in the engine.
//! * `Array` → fixed-capacity stores; adding to a full one returns
//!   [`Error::CapacityFull`]. A full contact store inside a step completes the step
//!   (the lowest pair keys kept, the drops counted in the [`StepReport`]; see
//!   [`World::step`] and [`World::stats`]).
//! * `addCollisionHandler(a, b, begin, preSolve, postSolve, end)` →
//!   [`World::add_collision_handler`] with a [`FnHandler`] or any
//!   [`CollisionHandler`]; `addPostStepCallback(func, key)` →
//!   [`CallbackContext::add_post_step_callback`].

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod arbiter;
pub mod arena;
pub mod body;
mod body_def;
pub mod collide;
pub mod collision;
pub mod compound;
pub mod constraint;
pub mod continuous;
pub mod error;
pub mod events;
pub mod force;
pub mod geometry;
pub mod handler;
pub mod hook;
pub mod index;
pub mod limits;
pub mod math;
pub mod query;
pub mod snapshot;
mod solver;
pub(crate) mod step;
pub mod world;

pub use arbiter::{Arbiter, ArbiterState, ContactPoint};
pub use arena::{Handle, Slot};
pub use body::{Body, BodyDef, BodyHandle, BodyType, CollisionFilter, MassSpec, PathHandle, Shape};
pub use collision::Index;
pub use compound::{BodyShape, ShapeDef, MAX_SHAPES_PER_BODY};
pub use constraint::{
    Constraint, ConstraintHandle, Joint, JointDef, JointHandle, JointKind, MaxTorque, Motor,
};
pub use error::Error;
pub use events::{
    ContactBeginEvent, ContactEndEvent, ContactHitEvent, JointBrokeEvent, SensorEvent, TOUCH_DISTANCE,
};
pub use force::{
    ForceGenerator, Generator, GeneratorMut, GravityForceGenerator, GravityToPointForceGenerator,
    LinearForceGenerator, Targets,
};
pub use geometry::{Capsule, ChainHandle, ChainPath, MassData, PolygonPath, Segment};
pub use handler::{CallbackContext, ClosureHandler, CollisionHandler, FnHandler, Handler, PostStepFn};
pub use hook::Hook;
pub use index::{BruteForceIndex, PairSink, Proxy, SpatialIndex};
pub use limits::{MAX_TIME_STEP, MIN_TIME_STEP};
pub use managed::ManagedSlice;
pub use math::{Matrix22, Rect, Rot, Scalar, Transform, Vector2};
pub use query::{QueryFilter, QueryShape, RayHit};
pub use solver::{limit_simd_level, simd_level, SimdLevel};
pub use world::{
    Capacities, GeneratorHandle, JointBreakFn, StepReport, Storage, World, WorldBuffers, WorldDef, WorldStats,
};

/// The README's examples, compiled and run as doctests so they cannot rot.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
