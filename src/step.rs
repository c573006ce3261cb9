//! The step pipeline.
//!
//! [`World::step`](crate::World::step) checks `dt`, builds one [`StepContext`]
//! (every value derived from the configuration and `dt`, computed once) and runs
//! [`run`], which calls the stages below in this order. Each stage is a function
//! over the context and exactly the parts of the world it touches; none sees the
//! world itself.
//!
//! 1. **broad phase** ([`collision::broad_phase`]): proxies and candidate pairs.
//!    A full pair buffer keeps the lowest pair keys and counts the rest as
//!    dropped; with [`WorldDef::strict_capacity`] every capacity the step needs
//!    is checked here instead, before anything changes, so a strict step either
//!    fails with an error and leaves the world as it was, or completes.
//! 2. **forces** ([`force::apply`]): each force generator, in the order added, over
//!    the dynamic bodies it accepts (slot order). The velocity change is spread
//!    over the sub-steps by the solver.
//! 3. **narrow phase and arbiter lifecycle** ([`collision::update_arbiters`]):
//!    manifolds, states, and the `begin`, `pre_solve` and `end` callbacks in
//!    canonical pair order. A full arbiter store keeps the lowest keys and
//!    skips (and counts) the rest.
//! 4. **solve and integrate** ([`solver::solve`]): the sub-stepped soft contact
//!    and joint solver, which also advances positions, then the restitution pass.
//! 5. **continuous collision** ([`continuous::run`]): fast bodies swept from
//!    their pose at the start of the step to their new one, and put back to
//!    the first impact on the way.
//! 6. **limits** ([`limits::enforce`]): speeds clamped to the world's maxima;
//!    bodies whose centre left the bounds are frozen and reported; bounding boxes
//!    refreshed.
//! 7. **events** ([`collision::touch_events`]): on the final poses, which
//!    contact pairs touch and which sensor pairs overlap, with the begin, end
//!    and hit events (see [`crate::events`]), each list sorted by pair key.
//! 8. **`post_solve` callbacks** ([`collision::post_solve`]), in canonical pair
//!    order.
//!
//! The event lists are cleared once the broad phase has succeeded (a step
//! that fails leaves them as they were).
//!
//! After [`run`], the world (which owns the hooks that need it) removes the
//! joints that broke, in joint-slot order, recording a joint-broke event and
//! handing each to the break callback,
//! then runs the post-step callbacks, once per key, in registration order, with
//! `&mut World`: the safe place to remove bodies. Callbacks registered while
//! these run run in the same step, round after round until the queue is empty
//! (at most [`MAX_POST_STEP_ROUNDS`](crate::handler::MAX_POST_STEP_ROUNDS)
//! rounds), so the queue is empty whenever `step` returns.
//!
//! Every loop runs in body-slot or pair-key order, functions of the simulation
//! history alone.

use crate::arbiter::ArbiterStore;
use crate::arena::Arena;
use crate::body::Body;
use crate::body::ShapeStore;
use crate::collision::{self, BroadPhase};
use crate::constraint::{Joint, JointMarker, UserConstraints, JOINT_DAMPING_RATIO, JOINT_HERTZ};
use crate::continuous;
use crate::error::Error;
use crate::events::Events;
use crate::force::{self, Generators};
use crate::handler::{HandlerTable, PostStepQueue};
use crate::limits::{self, MAX_TIME_STEP, MIN_TIME_STEP};
use crate::math::scalar::{self, Scalar};
use crate::math::Rect;
use crate::solver::{self, Softness, Solver};
use crate::world::def::WorldDef;

/// What happened during a step.
///
/// The `*_dropped` and `*_refused` counts are how a game learns that a store
/// was full: the step completed without what they count (see
/// [`World::step`](crate::World::step) for the policy, and
/// [`World::stats`](crate::World::stats) for the high-water marks to size the
/// capacities by). They are zero whenever every store was large enough.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Bodies that left the bounds this step (now frozen; see
    /// [`World::out_of_bounds_bodies`](crate::World::out_of_bounds_bodies)).
    pub left_bounds: u32,
    /// Candidate pairs the broad phase kept this step.
    pub candidate_pairs: u32,
    /// Arbiters alive after the step (touching pairs and persisted ones).
    pub arbiters: u32,
    /// Post-step callbacks that ran after the step (all rounds).
    pub post_step_callbacks: u32,
    /// Breakable joints that broke this step (and were removed).
    pub joints_broken: u32,
    /// Candidate pairs left out because the pair buffer
    /// ([`Capacities::contacts`](crate::Capacities::contacts)) was full: the
    /// pairs with the highest keys (lower body slot, then higher).
    pub pairs_dropped: u32,
    /// Pairs skipped because the arbiter store was full: candidate pairs not
    /// collided and arbiters dropped (ended, with `end` if they had begun), the
    /// highest keys first.
    pub arbiters_dropped: u32,
    /// Post-step callbacks refused during this step because the queue was full
    /// (each was also an `Err` to the callback that asked).
    pub post_step_refused: u32,
    /// Post-step callbacks still queued after
    /// [`MAX_POST_STEP_ROUNDS`](crate::handler::MAX_POST_STEP_ROUNDS) rounds,
    /// dropped without running.
    pub post_step_dropped: u32,
    /// Pair sweeps continuous collision computed (each closed-form: there is
    /// no iteration to cap; see [`crate::continuous`]).
    pub continuous_sweeps: u32,
    /// Fast bodies continuous collision put back to their time of impact.
    pub continuous_hits: u32,
    /// Touching pairs whose manifold carried on from the previous step
    /// instead of being computed (see
    /// [`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance);
    /// Box2D's `recycledContactCount`).
    pub manifolds_recycled: u32,
    /// Events left out because their list was full
    /// ([`Capacities::events`](crate::Capacities::events); see
    /// [`crate::events`]), all lists together.
    pub events_dropped: u32,
}

/// Everything a step derives from the world's configuration and `dt`, computed
/// once per step and read by every stage.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepContext {
    /// The step, s.
    pub(crate) dt: Scalar,
    /// Solver sub-steps.
    pub(crate) substeps: u32,
    /// 1 / `substeps`: the share of the generators' velocity change per sub-step.
    pub(crate) inv_substeps: Scalar,
    /// The sub-step `h = dt / substeps`, s.
    pub(crate) h: Scalar,
    /// 1 / `h`, 1/s.
    pub(crate) inv_h: Scalar,
    /// The speed limit, m/s.
    pub(crate) max_linear_speed: Scalar,
    /// The spin limit for this step, rad/s: the configured one, and at most π/4
    /// (an eighth of a turn) per step, so the linearised rotation of the solver
    /// and the contact margins stay accurate.
    pub(crate) max_angular_speed: Scalar,
    /// The world bounds.
    pub(crate) bounds: Rect,
    /// Contact softness between two moving bodies.
    pub(crate) contact_softness: Softness,
    /// Contact softness against a static or kinematic body (twice as stiff).
    pub(crate) static_softness: Softness,
    /// The soft position correction of rods, ropes, pivots and welds.
    pub(crate) joint_softness: Softness,
    /// Fastest speed at which overlap is pushed out, m/s.
    pub(crate) push_speed: Scalar,
    /// Approach speed below which contacts do not bounce, m/s.
    pub(crate) restitution_threshold: Scalar,
    /// Steps an arbiter outlives the contact.
    pub(crate) arbiter_persistence: u32,
    /// [`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance), m.
    pub(crate) recycle_distance: Scalar,
    /// A full pair or arbiter store fails the step instead of dropping pairs.
    pub(crate) strict_capacity: bool,
}

impl StepContext {
    /// The context of a step of `dt` seconds in a world configured by `def`.
    ///
    /// # Errors
    /// [`Error::InvalidTimeStep`] when `dt < MIN_TIME_STEP` (zero and negative
    /// included) or `dt > MAX_TIME_STEP`.
    pub(crate) fn new(def: &WorldDef, dt: Scalar) -> Result<Self, Error> {
        if dt < MIN_TIME_STEP || dt > MAX_TIME_STEP {
            return Err(Error::InvalidTimeStep);
        }
        let substeps = def.substeps.max(1);
        let inv_substeps = Scalar::from_num(substeps).recip();
        let h = dt * inv_substeps;
        let inv_h = h.recip();
        // Box2D caps every stiffness at a quarter of the sub-step rate.
        let max_hertz = Softness::max_hertz(inv_h);
        let hertz = def.contact_hertz.min(max_hertz);
        let zeta = def.contact_damping_ratio;
        let eighth_turn = (scalar::FRAC_PI_2 * scalar::HALF).div_or_zero(dt);
        Ok(Self {
            dt,
            substeps,
            inv_substeps,
            h,
            inv_h,
            max_linear_speed: def.max_linear_speed,
            max_angular_speed: def.max_angular_speed.min(eighth_turn),
            bounds: def.bounds,
            contact_softness: Softness::new(hertz, zeta, h),
            static_softness: Softness::new(hertz * scalar::TWO, zeta, h),
            joint_softness: Softness::new(JOINT_HERTZ.min(max_hertz), JOINT_DAMPING_RATIO, h),
            push_speed: def.contact_push_speed,
            restitution_threshold: def.restitution_threshold,
            arbiter_persistence: def.arbiter_persistence,
            recycle_distance: def.contact_recycle_distance,
            strict_capacity: def.strict_capacity,
        })
    }
}

/// The parts of a world the step's stages work on, borrowed apart so that each
/// stage gets exactly the ones it touches.
pub(crate) struct StepParts<'w, 'a> {
    pub(crate) bodies: &'w mut Arena<'a, Body>,
    pub(crate) paths: &'w ShapeStore<'a>,
    pub(crate) generators: &'w mut Generators<'a>,
    pub(crate) broad_phase: &'w mut BroadPhase<'a>,
    pub(crate) arbiters: &'w mut ArbiterStore<'a>,
    pub(crate) handlers: &'w mut HandlerTable<'a>,
    pub(crate) post_step: &'w mut PostStepQueue<'a>,
    pub(crate) joints: &'w mut Arena<'a, Joint, JointMarker>,
    pub(crate) constraints: &'w mut UserConstraints<'a>,
    pub(crate) solver: &'w mut Solver<'a>,
    pub(crate) events: &'w mut Events<'a>,
}

/// Runs the stages of one step. On error nothing has changed.
///
/// # Errors
/// With `strict_capacity`, [`Error::CapacityFull`] when the candidate pairs
/// or arbiters do not fit the contact buffers.
pub(crate) fn run(ctx: &StepContext, p: StepParts<'_, '_>) -> Result<StepReport, Error> {
    let found = collision::broad_phase(ctx, p.bodies, p.paths, p.joints, p.broad_phase, p.arbiters)?;
    p.events.clear();
    force::apply(ctx, p.bodies, p.generators);
    let candidates = p.broad_phase.candidates(found.count);
    let updated = collision::update_arbiters(
        ctx,
        candidates,
        p.bodies,
        p.paths,
        p.arbiters,
        p.handlers,
        p.post_step,
        p.events,
        &mut p.solver.scratch,
    );
    solver::solve(ctx, p.bodies, p.arbiters, p.joints, p.constraints, p.solver);
    let ccd =
        continuous::run(p.bodies, p.paths, &mut p.solver.bodies, p.broad_phase, found.count, p.arbiters);
    let left_bounds = limits::enforce(ctx, p.bodies, p.paths);
    collision::touch_events(p.bodies, p.paths, &p.solver.bodies, p.arbiters, p.events);
    collision::post_solve(p.bodies, p.arbiters, p.handlers, p.post_step);
    let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    Ok(StepReport {
        left_bounds,
        candidate_pairs: count(found.count),
        arbiters: count(p.arbiters.len()),
        pairs_dropped: count(found.dropped),
        arbiters_dropped: count(updated.skipped),
        manifolds_recycled: count(updated.recycled),
        continuous_sweeps: ccd.sweeps,
        continuous_hits: ccd.hits,
        events_dropped: p.events.dropped,
        ..StepReport::default()
    })
}
