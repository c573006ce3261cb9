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
pub mod storage;

pub use def::WorldDef;
pub use storage::{Capacities, Storage, WorldBuffers};

pub use crate::force::{GeneratorHandle, GeneratorMarker, MAX_FORCE_GENERATORS};
pub use crate::limits::{
    MAX_ANGULAR_SPEED_LIMIT, MAX_BODY_RADIUS, MAX_COORDINATE, MAX_FRICTION, MAX_LINEAR_SPEED_LIMIT,
    MAX_SUBSTEPS, SPECULATIVE_DISTANCE,
};

use crate::arbiter::{Arbiter, ArbiterStore};
use crate::arena::Arena;
use crate::body::{Body, BodyHandle};
use crate::collision::{BroadPhase, Index};
use crate::constraint::{Joint, JointHandle, JointMarker, UserConstraints};
use crate::error::Error;
use crate::force::{Generator, Generators};
use crate::geometry::PolygonPath;
use crate::handler::{Handler, HandlerTable, PostStepQueue};
use crate::index::SortAndSweepIndex;
use crate::math::{Rect, Scalar};
use crate::solver::Solver;
pub use crate::step::StepReport;

use crate::step::{self, StepContext, StepParts};

/// Called after a step for each joint that broke, with its former handle and the
/// joint as it was.
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
    pub(crate) paths: Arena<'a, PolygonPath>,
    pub(crate) generators: Generators<'a>,
    pub(crate) broad_phase: BroadPhase<'a>,
    pub(crate) arbiters: ArbiterStore<'a>,
    pub(crate) handlers: HandlerTable<'a>,
    pub(crate) post_step: PostStepQueue,
    pub(crate) joints: Arena<'a, Joint, JointMarker>,
    pub(crate) solver: Solver<'a>,
    pub(crate) constraints: UserConstraints<'a>,
    pub(crate) break_callback: Option<JointBreakFn>,
    pub(crate) step_count: u64,
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
        Ok(Self {
            def,
            bodies: Arena::new(s.bodies).with_tag(tag),
            paths: Arena::new(s.paths).with_tag(tag),
            generators: Arena::inline().with_tag(tag),
            broad_phase: BroadPhase {
                index: Index::default(),
                auto_sweep: SortAndSweepIndex::new(s.sweep_order),
                proxies: s.proxies,
                proxy_bodies: s.proxy_bodies,
                pairs: s.pairs,
                joint_pairs: s.joint_pairs,
            },
            arbiters: ArbiterStore::new(s.arbiters, s.arbiters_next),
            handlers: HandlerTable::new(),
            post_step: PostStepQueue::new(),
            joints: Arena::new(s.joints).with_tag(tag),
            solver: Solver { bodies: s.solver_bodies, constraints: s.contact_constraints, count: 0 },
            constraints: Arena::inline().with_tag(tag),
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
        // Checked before allocating, as `new` checks it after.
        check_slot_capacities(capacities.bodies, capacities.paths, capacities.joints)?;
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

    // ---- the step -------------------------------------------------------------

    /// Advances the simulation by `dt` seconds: the stages of the step pipeline (`step.rs`),
    /// then the broken joints' callback and the post-step callbacks.
    ///
    /// # Errors
    /// [`Error::InvalidTimeStep`] when `dt ≤ 0` or `dt > MAX_TIME_STEP`;
    /// [`Error::CapacityFull`] when the candidate pairs or arbiters do not fit the
    /// contact buffers. On error the world is unchanged.
    pub fn step(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        let ctx = StepContext::new(&self.def, dt)?;
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
        };
        let mut report = step::run(&ctx, parts)?;
        self.step_count = self.step_count.wrapping_add(1);
        report.joints_broken = self.remove_broken_joints();
        report.post_step_callbacks = self.run_post_step_callbacks();
        Ok(report)
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
                if let Some(f) = self.break_callback {
                    f(self, h, joint);
                }
            }
        }
        broken
    }

    /// Runs the queued post-step callbacks, in registration order. Returns how
    /// many ran.
    fn run_post_step_callbacks(&mut self) -> u32 {
        let queue = core::mem::take(&mut self.post_step);
        let mut ran = 0u32;
        for (f, key) in queue {
            f(self, key);
            ran = ran.saturating_add(1);
        }
        ran
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

    // ---- collisions ----------------------------------------------------------

    /// Replaces the spatial index (the manual's custom indexing system).
    pub fn set_spatial_index(&mut self, index: Index<'a>) {
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
        self.arbiters.live().iter()
    }

    /// The arbiter of two bodies, if they touch or recently touched.
    #[must_use]
    pub fn arbiter(&self, a: BodyHandle, b: BodyHandle) -> Option<&Arbiter> {
        let key = if a.index() <= b.index() { (a.index(), b.index()) } else { (b.index(), a.index()) };
        let live = self.arbiters.live();
        let i = live.binary_search_by(|arb| arb.key().cmp(&key)).ok()?;
        live.get(i).filter(|arb| (arb.body_a == a && arb.body_b == b) || (arb.body_a == b && arb.body_b == a))
    }
}
