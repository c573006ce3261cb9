//! [`World`]: the space in which the simulation happens.
//!
//! A world owns every body, polygon path, joint and hook in fixed-capacity
//! storage chosen when it is created ([`Storage`]): borrowed buffers
//! ([`WorldBuffers`], no allocator needed, can live in a `static`), or with the
//! `alloc` feature heap buffers sized at run time ([`Capacities`]). The engine is
//! the same code on both. Nothing ever grows: a full store is an
//! [`Error::CapacityFull`], and a call that returns an error has changed nothing.
//!
//! The world owns the state and runs the step (`step.rs`), whose stages
//! each get the parts they work on, never the world; only the hooks that are
//! given `&mut World` by design (post-step callbacks, the joint-break callback)
//! run with it, after the stages.
//!
//! Files: [`def`] (configuration and its validation), [`storage`] (buffers and
//! capacities), `bodies.rs` (the body API), `joints.rs` (joints and game
//! constraints); this file holds the world itself, the step's entry point, force
//! generators and collision hooks.

mod bodies;
pub mod def;
mod joints;
#[cfg(feature = "std")]
mod panic_guard;
mod shapes;
mod stats;
pub mod storage;

pub use def::WorldDef;
pub use stats::WorldStats;
pub use storage::{Capacities, Storage, WorldBuffers};

pub use crate::force::{GeneratorHandle, GeneratorMarker, MAX_FORCE_GENERATORS};
pub use crate::limits::{
    MAX_ANGULAR_SPEED_LIMIT, MAX_BODY_RADIUS, MAX_COORDINATE, MAX_FRICTION, MAX_LINEAR_SPEED_LIMIT,
    MAX_SUBSTEPS, SPECULATIVE_DISTANCE,
};

use crate::arbiter::{Arbiter, ArbiterStore};
use crate::arena::Arena;
use crate::body::{Body, BodyHandle, ShapeStore};
use crate::collision::{BroadPhase, Index};
use crate::constraint::{Joint, JointHandle, JointMarker, UserConstraints};
use crate::error::Error;
use crate::events::{
    ContactBeginEvent, ContactEndEvent, ContactHitEvent, Events, JointBrokeEvent, SensorEvent,
};
use crate::force::{Generator, GeneratorMut, Generators};
use crate::geometry::chain::ChainSlab;
use crate::geometry::{ChainHandle, ChainPath};
use crate::handler::{Handler, HandlerTable, PostStepQueue, MAX_POST_STEP_ROUNDS};
use crate::index::SortAndSweepIndex;
use crate::math::{Rect, Scalar};
use crate::solver::Solver;
pub use crate::step::StepReport;

use crate::step::{self, StepContext, StepParts};

/// Called after a step for each joint that broke, with its former handle and the
/// joint as it was.
///
/// # If it panics
/// With `std` and the panic guard on (the default), a panic restores the world
/// to its state before the step and then unwinds out of
/// [`World::step`](crate::World::step). Without the guard (`no_std`, or
/// [`World::set_panic_guard`](crate::World::set_panic_guard)`(false)`) it unwinds
/// with the world half-stepped: the step is complete, the joints before this one are removed, this
/// joint is already removed, the later broken joints stay in the world marked broken, and the
/// post-step callbacks have not run. The world stays memory-safe and usable, but its state
/// is not one any uninterrupted run reaches. The way back is the snapshot taken
/// before the step: [`World::restore`](crate::World::restore) it (a game that
/// catches panics with `std::panic::catch_unwind` should restore before it
/// steps again).
pub type JointBreakFn = for<'w> fn(&mut World<'w>, JointHandle, Joint);

/// Every handle packs into 64 bits (see [`crate::arena`]): a store of more than
/// [`MAX_SLOTS`](crate::arena::MAX_SLOTS) slots is an error.
fn check_slot_capacities(bodies: usize, paths: usize, joints: usize) -> Result<(), Error> {
    if bodies.max(paths).max(joints) > crate::arena::MAX_SLOTS {
        return Err(Error::OutOfRange { what: "capacity (at most 1,048,575 slots a store)" });
    }
    Ok(())
}

/// The simulation: bodies, shared polygon paths, force generators, joints,
/// collision hooks, and `step`.
pub struct World<'a> {
    pub(crate) def: WorldDef,
    pub(crate) bodies: Arena<'a, Body>,
    /// Polygon paths (what this dereferences to) and the chain slab.
    pub(crate) paths: ShapeStore<'a>,
    pub(crate) generators: Generators<'a>,
    pub(crate) broad_phase: BroadPhase<'a>,
    pub(crate) arbiters: ArbiterStore<'a>,
    pub(crate) handlers: HandlerTable<'a>,
    pub(crate) post_step: PostStepQueue<'a>,
    /// True while the step runs its hooks (joint breaks, post-step callbacks):
    /// a `remove_body` then leaves what its `end` handlers queue to the step's
    /// drain instead of draining itself.
    pub(crate) in_step_hooks: bool,
    /// Diagnostics (not state).
    pub(crate) stats: WorldStats,
    pub(crate) joints: Arena<'a, Joint, JointMarker>,
    pub(crate) solver: Solver<'a>,
    pub(crate) constraints: UserConstraints<'a>,
    pub(crate) break_callback: Option<JointBreakFn>,
    /// The last step's event lists (see [`crate::events`]).
    pub(crate) events: Events<'a>,
    pub(crate) step_count: u64,
    /// With `std`: the snapshot a step with hooks is rolled back to if a hook
    /// panics (see `world/panic_guard.rs`).
    #[cfg(feature = "std")]
    pub(crate) panic_guard: panic_guard::PanicGuard,
}

/// Without `std` there is no guard to arm (see `world/panic_guard.rs`).
#[cfg(not(feature = "std"))]
impl World<'_> {
    #[inline]
    pub(crate) fn arm_panic_guard(&mut self) {}
}

impl<'a> World<'a> {
    /// A world on the given storage. The world takes a new tag (see
    /// [`arena`](crate::arena)), which every handle it gives out carries, so
    /// handles of another world are [`Error::StaleHandle`] here.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for bounds that are empty or exceed
    /// ±[`MAX_COORDINATE`], settings outside their ranges, or more than
    /// [`MAX_SLOTS`](crate::arena::MAX_SLOTS) body, path or joint slots.
    pub fn new(def: WorldDef, storage: Storage<'a>) -> Result<Self, Error> {
        def.validate()?;
        let s = storage;
        check_slot_capacities(s.bodies.len(), s.paths.len(), s.joints.len())?;
        let tag = crate::arena::next_world_tag();
        let capacities = Capacities {
            bodies: s.bodies.len(),
            paths: s.paths.len(),
            contacts: s.arbiters.len().min(s.arbiters_next.len()).min(s.pairs.len()),
            joints: s.joints.len(),
            post_step_callbacks: s.post_step.len(),
            events: 0,
            chain_vertices: s.chain_nodes.len(),
            shapes: s.shape_slots.len(),
        };
        let events = Events::new(
            s.contact_begin,
            s.contact_end,
            s.contact_hit,
            s.sensor_begin,
            s.sensor_end,
            s.joint_broke,
        );
        let capacities = Capacities { events: events.capacity(), ..capacities };
        Ok(Self {
            def,
            bodies: Arena::new(s.bodies).with_tag(tag),
            paths: ShapeStore {
                paths: Arena::new(s.paths).with_tag(tag),
                chains: ChainSlab::new(s.chain_nodes),
                slots: Arena::new(s.shape_slots).with_tag(tag),
            },
            generators: Arena::inline().with_tag(tag),
            broad_phase: BroadPhase {
                index: Index::default(),
                auto_sweep: SortAndSweepIndex::new(s.sweep_order),
                proxies: s.proxies,
                proxy_bodies: s.proxy_bodies,
                pairs: s.pairs,
                joint_pairs: s.joint_pairs,
                live: 0,
                held: 0,
            },
            arbiters: ArbiterStore::new(s.arbiters, s.arbiters_next),
            handlers: HandlerTable::new(),
            post_step: PostStepQueue::new(s.post_step),
            in_step_hooks: false,
            stats: WorldStats { capacities, ..WorldStats::default() },
            joints: Arena::new(s.joints).with_tag(tag),
            solver: Solver {
                bodies: s.solver_bodies,
                lanes: s.solver_lanes,
                constraints: s.contact_constraints,
                scratch: s.contact_scratch,
                joints: s.joint_rows,
                joint_count: 0,
                pivots: s.pivot_lanes,
                pivot_runs: crate::solver::PivotRuns::EMPTY,
                ranges: [(0, 0); crate::solver::RUNS],
                count: 0,
                overflow: 0,
            },
            constraints: Arena::inline().with_tag(tag),
            break_callback: None,
            events,
            step_count: 0,
            #[cfg(feature = "std")]
            panic_guard: panic_guard::PanicGuard::default(),
        })
    }

    /// A world on heap storage with the given capacities.
    ///
    /// # Errors
    /// As [`World::new`], and as [`Storage::with_capacities`] for capacities the
    /// heap cannot hold ([`Error::OutOfRange`], [`Error::OutOfMemory`]).
    #[cfg(feature = "alloc")]
    pub fn with_capacities(def: WorldDef, capacities: Capacities) -> Result<Self, Error> {
        // Checked before allocating, as `new` checks it after.
        check_slot_capacities(capacities.bodies, capacities.paths, capacities.joints)?;
        Self::new(def, Storage::with_capacities(capacities)?)
    }

    /// The world's capacities, high-water marks and drop counts since it was
    /// created: what a game needs to size its stores. Diagnostics, not state:
    /// in neither the snapshot nor the hash, and unchanged by `restore`.
    #[must_use]
    pub fn stats(&self) -> WorldStats {
        let mut s = self.stats;
        s.peak_bodies = s.peak_bodies.max(self.bodies.slots_used() as usize);
        s.peak_joints = s.peak_joints.max(self.joints.slots_used() as usize);
        s.peak_post_step_callbacks = s.peak_post_step_callbacks.max(self.post_step.state.peak);
        s
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

    // ---- the step -------------------------------------------------------------

    /// Advances the simulation by `dt` seconds: the stages of the step pipeline (`step.rs`),
    /// then the broken joints' callback and the post-step callbacks.
    ///
    /// # A full store never stops the game
    /// When the candidate pairs or the arbiters do not fit the contact buffers,
    /// the step completes: the lowest pair keys (lower body slot, then higher)
    /// are kept, the rest skipped and counted in the report (`pairs_dropped`,
    /// `arbiters_dropped`), and a skipped arbiter that had begun gets its `end`.
    /// With [`WorldDef::strict_capacity`] it is an error instead. The
    /// post-step queue is run to exhaustion (see
    /// [`CallbackContext::add_post_step_callback`](crate::CallbackContext::add_post_step_callback)),
    /// so it is empty when `step` returns. [`World::stats`] has the
    /// high-water marks to size the capacities by.
    ///
    /// # Errors
    /// [`Error::InvalidTimeStep`] when `dt < MIN_TIME_STEP` (2^-16 s; zero and
    /// negative included) or `dt > MAX_TIME_STEP`; with
    /// [`WorldDef::strict_capacity`], [`Error::CapacityFull`] when the candidate
    /// pairs or arbiters do not fit the contact buffers. On error the world is
    /// unchanged.
    ///
    /// # Panics
    /// The engine itself does not panic. A game's hook that panics (a
    /// [`ForceGenerator`](crate::ForceGenerator), a
    /// [`CollisionHandler`](crate::CollisionHandler) method, a
    /// [`Constraint`](crate::constraint::Constraint), a post-step callback or the
    /// joint-break callback) unwinds out of `step`. With `std` and the panic
    /// guard on (the default; see [`World::set_panic_guard`]) the world is first
    /// restored to exactly its state before the step (a snapshot taken before
    /// every step of a world with hooks; the hooks' own objects keep what they
    /// changed). Without it the world is left half-stepped: the stages before the
    /// hook have run, those after it have not (each hook's docs say what exactly).
    /// It is still memory-safe, but its state is one no uninterrupted run
    /// reaches, so its future differs from every peer's: [`restore`](World::restore)
    /// the snapshot taken before the step.
    pub fn step(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        #[cfg(feature = "std")]
        return self.step_guarded(dt);
        #[cfg(not(feature = "std"))]
        return self.step_stages_and_hooks(dt);
    }

    /// The step itself: the stages, then the broken joints and the post-step
    /// callbacks.
    fn step_stages_and_hooks(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        let ctx = StepContext::new(&self.def, dt)?;
        self.post_step.state.refused = 0;
        let parts = StepParts {
            bodies: &mut self.bodies,
            paths: &self.paths,
            generators: &mut self.generators,
            broad_phase: &mut self.broad_phase,
            arbiters: &mut self.arbiters,
            handlers: &mut self.handlers,
            post_step: &mut self.post_step,
            joints: &mut self.joints,
            constraints: &mut self.constraints,
            solver: &mut self.solver,
            events: &mut self.events,
        };
        let mut report = step::run(&ctx, parts)?;
        self.step_count = self.step_count.wrapping_add(1);
        let outer = core::mem::replace(&mut self.in_step_hooks, true);
        report.joints_broken = self.remove_broken_joints();
        report.events_dropped = self.events.dropped;
        let (ran, dropped) = self.drain_post_step();
        self.in_step_hooks = outer;
        report.post_step_callbacks = ran;
        report.post_step_dropped = dropped;
        report.post_step_refused = core::mem::take(&mut self.post_step.state.refused);
        self.record(&report);
        Ok(report)
    }

    /// Adds a step's report to the stats.
    fn record(&mut self, r: &StepReport) {
        let s = &mut self.stats;
        let wanted = u64::from(r.candidate_pairs).saturating_add(u64::from(r.pairs_dropped));
        s.peak_pairs = s.peak_pairs.max(usize::try_from(wanted).unwrap_or(usize::MAX));
        s.peak_arbiters = s.peak_arbiters.max(self.arbiters.len());
        s.peak_contact_constraints = s.peak_contact_constraints.max(self.solver.count);
        s.peak_overflow_constraints = s.peak_overflow_constraints.max(self.solver.overflow as usize);
        s.pairs_dropped = s.pairs_dropped.saturating_add(u64::from(r.pairs_dropped));
        s.arbiters_dropped = s.arbiters_dropped.saturating_add(u64::from(r.arbiters_dropped));
        s.post_step_refused = s.post_step_refused.saturating_add(u64::from(r.post_step_refused));
        s.post_step_dropped = s.post_step_dropped.saturating_add(u64::from(r.post_step_dropped));
        s.events_dropped = s.events_dropped.saturating_add(u64::from(r.events_dropped));
    }

    /// Removes the joints that broke this step, in slot order, handing each to
    /// the break callback. Returns how many broke.
    fn remove_broken_joints(&mut self) -> u32 {
        let mut broken = 0u32;
        for i in 0..self.joints.slots_used() {
            if !self.joints.get_at(i).is_some_and(|j| j.broken) {
                continue;
            }
            let Some(h) = self.joints.handle_at(i) else { continue };
            if let Some(joint) = self.joints.remove(h) {
                broken = broken.saturating_add(1);
                self.events.joint_broke(JointBrokeEvent {
                    joint: h,
                    body_a: joint.def.body_a,
                    body_b: joint.def.body_b,
                });
                if let Some(f) = self.break_callback {
                    f(self, h, joint);
                }
            }
        }
        broken
    }

    /// Runs the queued post-step callbacks to exhaustion: those queued when it
    /// starts, in registration order, then those they queued, round after round,
    /// for at most [`MAX_POST_STEP_ROUNDS`] rounds. Returns how many ran and how
    /// many were still queued after the last round (dropped).
    fn drain_post_step(&mut self) -> (u32, u32) {
        let mut ran = 0u32;
        let mut rounds = 0u32;
        while self.post_step.pending() > 0 && rounds < MAX_POST_STEP_ROUNDS {
            rounds = rounds.saturating_add(1);
            for _ in 0..self.post_step.pending() {
                let Some((f, key)) = self.post_step.pop() else { break };
                f(self, key);
                ran = ran.saturating_add(1);
            }
        }
        let dropped = u32::try_from(self.post_step.clear()).unwrap_or(u32::MAX);
        (ran, dropped)
    }

    /// After a call outside a step that may have queued post-step callbacks
    /// (a game's `remove_body`): runs them now, so the queue is empty when the
    /// call returns. Inside the step's hooks, leaves them to the step's drain.
    pub(crate) fn drain_post_step_outside_step(&mut self) {
        if self.in_step_hooks || self.post_step.pending() == 0 {
            return;
        }
        self.in_step_hooks = true;
        let (_, dropped) = self.drain_post_step();
        self.in_step_hooks = false;
        let s = &mut self.stats;
        s.post_step_dropped = s.post_step_dropped.saturating_add(u64::from(dropped));
        let refused = core::mem::take(&mut self.post_step.state.refused);
        s.post_step_refused = s.post_step_refused.saturating_add(u64::from(refused));
    }

    // ---- force generators ----------------------------------------------------

    /// Adds a force generator; generators run in the order they were added.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a built-in's parameter outside its range
    /// (`"force"`, `"gravity"`, `"point"`, `"acceleration"`: see
    /// [`MAX_FORCE`](crate::limits::MAX_FORCE) and
    /// [`MAX_ACCELERATION`](crate::limits::MAX_ACCELERATION));
    /// [`Error::CapacityFull`] when the generator store is full.
    pub fn add_force_generator(&mut self, g: impl Into<Generator<'a>>) -> Result<GeneratorHandle, Error> {
        let g = g.into();
        g.validate()?;
        let custom = matches!(g, Generator::Custom(_));
        let h = self.generators.insert(g).map_err(|_| Error::CapacityFull { what: "force generator" })?;
        if custom {
            self.arm_panic_guard();
        }
        Ok(h)
    }

    /// Removes a force generator and returns it.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_force_generator(&mut self, h: GeneratorHandle) -> Result<Generator<'a>, Error> {
        self.generators.remove(h).ok_or(Error::StaleHandle)
    }

    /// The force generator behind `h`, to change its parameters: a built-in
    /// through its checked setters (e.g.
    /// [`GravityForceGenerator::set_gravity`](crate::GravityForceGenerator::set_gravity)),
    /// so whatever it holds is in range and the world's snapshot restores.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn force_generator_mut(&mut self, h: GeneratorHandle) -> Result<GeneratorMut<'_, 'a>, Error> {
        self.generators.get_mut(h).map(Generator::as_mut).ok_or(Error::StaleHandle)
    }

    // ---- collisions ----------------------------------------------------------

    /// Replaces the spatial index (the manual's custom indexing system).
    pub fn set_spatial_index(&mut self, index: Index<'a>) {
        if matches!(index, Index::Custom(_)) {
            self.arm_panic_guard();
        }
        self.broad_phase.index = index;
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
        self.handlers.add(a, b, handler.into())?;
        self.arm_panic_guard();
        Ok(())
    }

    /// Removes and returns the handler for levels `a` and `b`, if any.
    pub fn remove_collision_handler(&mut self, a: u32, b: u32) -> Option<Handler<'a>> {
        self.handlers.remove(a, b)
    }

    /// Replaces the default handler (used for level pairs without their own);
    /// `None` restores "resolve everything". Returns the previous one.
    pub fn set_default_collision_handler(&mut self, handler: Option<Handler<'a>>) -> Option<Handler<'a>> {
        if handler.is_some() {
            self.arm_panic_guard();
        }
        self.handlers.set_default(handler)
    }

    /// Copies a chain into the world's chain slab (see
    /// [`crate::geometry::chain`]) for [`BodyDef::chain`](crate::BodyDef::chain)
    /// bodies to use; several bodies may share it. The slab is filled in
    /// order and never freed: chains are level geometry.
    ///
    /// # Errors
    /// [`Error::CapacityFull`] `{ what: "chain vertex" }` when the slab
    /// ([`Capacities::chain_vertices`]) has fewer free entries than the chain
    /// has points; the world is unchanged.
    pub fn add_chain(&mut self, path: ChainPath<'_>) -> Result<ChainHandle, Error> {
        self.paths.chains.add(&path)
    }

    /// The points of chain `h` (body-local, m), in order; none for a handle
    /// this world's slab does not hold.
    pub fn chain_points(&self, h: ChainHandle) -> impl Iterator<Item = crate::math::Vector2> + '_ {
        let n = if self.paths.chains.valid(h) { h.points() } else { 0 };
        self.paths.chains.points().skip(h.start as usize).take(n)
    }

    /// Link `i` of chain `h` with its ghost vertices (body-local), if the
    /// chain has it: link `i` runs from point `i` to point `i + 1` (a loop's
    /// last link back to point 0).
    #[must_use]
    pub fn chain_link(&self, h: ChainHandle, i: u32) -> Option<crate::geometry::ChainSegment> {
        self.paths.chains.link(h, i)
    }

    /// Chain points in use and the slab's size.
    #[must_use]
    pub fn chain_vertices(&self) -> (usize, usize) {
        (self.paths.chains.used() as usize, self.paths.chains.capacity())
    }

    /// The arbiters (touching or persisting pairs), in canonical pair order.
    pub fn arbiters(&self) -> impl Iterator<Item = &Arbiter> + '_ {
        self.arbiters.live().iter()
    }

    /// The arbiter of two bodies, if they touch or recently touched (for a
    /// body against a chain, the one of the lowest link: see
    /// [`World::arbiters`] for all of them).
    #[must_use]
    pub fn arbiter(&self, a: BodyHandle, b: BodyHandle) -> Option<&Arbiter> {
        let key = if a.index() <= b.index() { (a.index(), b.index()) } else { (b.index(), a.index()) };
        let live = self.arbiters.live();
        let i = live.partition_point(|arb| arb.pair() < key);
        live.get(i)
            .filter(|arb| arb.pair() == key)
            .filter(|arb| (arb.body_a == a && arb.body_b == b) || (arb.body_a == b && arb.body_b == a))
    }

    // ---- events --------------------------------------------------------------

    /// Pairs that started touching during the last step, in pair-key order
    /// (see [`crate::events`]).
    #[must_use]
    pub fn contact_begin_events(&self) -> &[ContactBeginEvent] {
        self.events.contact_begin.as_slice()
    }

    /// Pairs that stopped touching during the last step, in pair-key order.
    #[must_use]
    pub fn contact_end_events(&self) -> &[ContactEndEvent] {
        self.events.contact_end.as_slice()
    }

    /// Pairs that started touching during the last step faster than the hit
    /// threshold ([`World::set_hit_event_threshold`]), in pair-key order.
    #[must_use]
    pub fn contact_hit_events(&self) -> &[ContactHitEvent] {
        self.events.contact_hit.as_slice()
    }

    /// Bodies that started overlapping a sensor during the last step, in
    /// pair-key order.
    #[must_use]
    pub fn sensor_begin_events(&self) -> &[SensorEvent] {
        self.events.sensor_begin.as_slice()
    }

    /// Bodies that stopped overlapping a sensor during the last step, in
    /// pair-key order.
    #[must_use]
    pub fn sensor_end_events(&self) -> &[SensorEvent] {
        self.events.sensor_end.as_slice()
    }

    /// Joints that broke during the last step (and were removed), in joint-slot
    /// order.
    #[must_use]
    pub fn joint_broke_events(&self) -> &[JointBrokeEvent] {
        self.events.joint_broke.as_slice()
    }

    /// The approach speed (m/s) above which a pair that begins touching is
    /// also a hit event.
    #[must_use]
    pub fn hit_event_threshold(&self) -> Scalar {
        self.events.hit_threshold
    }

    /// Sets the hit-event threshold (m/s; default
    /// [`DEFAULT_HIT_EVENT_THRESHOLD`](crate::events::DEFAULT_HIT_EVENT_THRESHOLD),
    /// 1 m/s). A setting of the world, like its handlers: it shapes no future
    /// step and is not in the snapshot.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"hit event threshold"` when negative; the
    /// threshold is unchanged.
    pub fn set_hit_event_threshold(&mut self, speed: Scalar) -> Result<(), Error> {
        if speed < Scalar::ZERO {
            return Err(Error::OutOfRange { what: "hit event threshold" });
        }
        self.events.hit_threshold = speed;
        Ok(())
    }
}
