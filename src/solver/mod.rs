//! The contact solver and integrator: a soft step with sub-stepping.
//!
//! The design is Box2D v3's "soft step" (Erin Catto, *Solver2D*, 2024), written
//! here for fixed point. Before the sub-steps, an impact pass resolves every
//! elastic contact point in contact and approaching faster than
//! `restitution_threshold` as a collision of its own, −e·vn, in sweeps until
//! none is left (at most eight), so that a blow travels along a chain of
//! touching bodies one collision at a time, as in Newton's cradle (the soft
//! contacts below solve a chain as one body and share the blow; Guendelman,
//! Bridson and Fedkiw's collision pass, *Nonconvex rigid bodies with
//! stacking*, 2003, is the same idea). Each step is then split into
//! `substeps` sub-steps of `h = dt / substeps`; each sub-step
//!
//! 1. adds its share of the force generators' velocity change (generators run once
//!    per step; their effect is spread evenly, as gravity is in Box2D),
//! 2. warm-starts every contact with the impulse it ended the previous sub-step with,
//! 3. solves the contacts as soft constraints (a spring-damper of
//!    `contact_hertz` / `contact_damping_ratio` pushing overlap out at no more than
//!    `contact_push_speed`; speculative points, still apart, only stop the bodies
//!    from closing the gap within the sub-step), in one sweep. Both points of
//!    a two-point manifold computed this step are solved together as a 2×2
//!    block (an exact linear complementarity solve, as in Box2D v2.4, of the
//!    system whose Gauss-Seidel step is Box2D v3's per-point soft update: each
//!    point its own spring); those of a manifold recycled from an earlier step
//!    one at a time in the sweep's direction, as Box2D v3 solves every
//!    manifold (a settled pair: its kept anchors hold a stack still, and an
//!    impact, whose manifold is new, still gets the exact solve; see
//!    `contact::prepare`);
//!    a point overlapping deeper than 10 cm is not pushed out by the spring's
//!    velocity but by moving its bodies apart in the same sweep (Box2D v2.4's
//!    position solver for those points only), so that bodies created or
//!    crushed deep inside each other separate without flying apart (see
//!    `contact::kernel`'s `DEEP_OVERLAP`),
//! 4. integrates positions,
//! 5. relaxes: one sweep without the position bias, so the push-out does not
//!    leave energy behind (Box2D's one relax iteration).
//!
//! Both sweeps of a sub-step run in the same direction, in colour order or in
//! reverse (see **Order** below), and the direction changes every two
//! sub-steps: forward, reverse, reverse, forward (then forward, reverse,
//! reverse, forward with 8 sub-steps), so over a step every contact is solved
//! first as often as last, in the biased sweeps as in the relax sweeps.
//!
//! These choices were measured on `tests/quality.rs` and `tests/scale.rs`, not
//! picked for looks (the figures below are from the `Scalar` solver in pair-key
//! order that preceded the lanes and colours; `colour` has the measurements
//! that chose the colour order, with which the column ends steps at 2.97 m/s): with one-way sweeps a symmetric pyramid creeps sideways
//! (16 mm in 10 s); solving the two points of a manifold one after the other lets
//! a 20-box stack topple (the first point always takes more). Two relax sweeps in
//! every sub-step (12 sweeps a step) were an earlier design; one sweep (8,
//! Box2D's count) is as good everywhere except a 4-box column recovering from
//! 25 % overlap, which ends steps at 3.6 m/s, above the 3 m/s push speed; an
//! extra forward sweep in the last sub-step (9 sweeps) brought that to 2.98
//! m/s. Once overlaps deeper than 10 cm were pushed out by motion, that column
//! stayed under 1.6 m/s with Box2D's one relax sweep a sub-step and every
//! other threshold held, so the extra sweep went (a step's 15 passes over the
//! contacts became 14, −3 % of the instructions of the contact scenes).
//! The biased sweeps used to run forward in every sub-step (only the relax
//! alternated): 7 forward sweeps a step against 2 in reverse, and Box2D v3's
//! 100-row large_pyramid ended 88 mm off centre at the top (80 rows 53 mm, 90
//! rows 69 mm); in this order it ends 37 mm off (22 mm, 29 mm). Alternating
//! every sub-step (forward, reverse, forward, reverse) centres it as well
//! (38 mm) but ends the overlapped column's steps at 3.03 m/s; a relax sweep
//! against its sub-step's biased sweep undoes the push-out (the overlapped
//! column never separates).
//!
//! After the last sub-step a restitution pass gives contacts that approached
//! faster than `restitution_threshold` during the sub-steps (not in the impact
//! pass, which already bounced them) their bounce, e·v.
//!
//! The impact pass was measured on `tests/quality_issue16.rs`: a row of five
//! touching equal balls (e = 1, no friction) struck at 4 m/s by a sixth. With
//! restitution only after the sub-steps the far ball left at 0.74 of the
//! striker's speed and the striker recoiled at −0.36; with the impact pass the
//! far ball leaves at 1.00 and every other ball keeps under 0.02. The 10 m
//! drop's rebound ratios (`tests/quality.rs`, e² ± 0.03) moved from 0.246 to
//! 0.243 (e = 0.5) and from 1.002 to 0.994 (e = 1; Box2D v3: 0.244 and
//! 0.996). Only points already in contact take part: a speculative point
//! (still apart) is left to the sub-steps and the restitution pass, so that
//! the pair touches and reports its hit before it bounces.
//!
//! The separation of each contact point is re-evaluated in every sub-step from
//! how far the bodies moved and turned since the step began (linearised in the
//! turn; see [`contact`]), so no collision detection runs inside the loop.
//!
//! **Numbers.** The contact kernels and the joints' iterations compute in
//! their own 32-bit integer formats ([`lanes`], [`joint_lanes`]: velocities
//! Q16.16, impulses in velocity units, mass ratios instead of masses), whose
//! products are a 32×32→64 multiply and a shift; everything persistent, the
//! springs and the once-per-step prepare and store stay in `Scalar`. Each body's `Scalar` velocity stays its own: the
//! kernels' changes are carried back as differences ([`body`]), so a body no
//! contact touches moves exactly as before.
//!
//! **Order.** Each step the solved arbiters are coloured ([`colour`]) so that
//! no two contacts of a colour share a dynamic body; a sweep runs the overflow
//! (contacts that found no colour) one at a time in key order, then the colours
//! (the reverse sweep the exact reverse). Within a colour the order changes no
//! bit, so a colour's contacts are solved eight at a time where the processor
//! has AVX2 ([`dispatch`]) and one at a time elsewhere, with identical results.
//! Joints run in joint-slot order, bodies in slot order: every order is a
//! function of the simulation state alone. Prepare writes one row per joint
//! into a dense scratch array (`Solver::joints`, in joint-slot order, each row
//! with its two body slots), the joint passes run over that array and never
//! read the joints themselves, and the end of the step writes the rows'
//! impulses back into the joints, as the contacts' are written back into the
//! arbiters.

mod body;
mod colour;
mod contact;
mod dispatch;
mod joint_lanes;
mod lanes;
mod pivot_lanes;
mod softness;
mod sweep;

pub use body::{BodyLanes, SolverBody};
pub use contact::{ContactConstraint, ContactScratch};
pub use dispatch::{limit_simd_level, simd_level, SimdLevel};
use pivot_lanes::Pass;
pub use pivot_lanes::PivotLanes;
pub(crate) use pivot_lanes::PivotRuns;

pub(crate) use body::{angular_speed_limit, inverse_mass};
use contact::LaneParams;
pub(crate) use joint_lanes::{
    pivot_impulses, JointLanes, JointMasses, JointStep, LaneSoft, PivotStart, PointRecord,
};
use managed::ManagedSlice;
pub(crate) use softness::Softness;
pub(crate) use sweep::{Bias, Sweep};

use crate::arbiter::ArbiterStore;
use crate::arena::Arena;
use crate::body::Body;
use crate::constraint::{Joint, JointMarker, JointRow, UserConstraints};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::step::StepContext;

pub(crate) use colour::RUNS;

/// xorshift64, the solver's unit tests' pseudo-random numbers: no
/// allocation, the same sequence on every target.
#[cfg(test)]
pub(crate) fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// The direction of sub-step `substep`'s warm start: against the pass before it
/// (the previous sub-step's relax sweep, or the forward constraint build), so
/// that it begins with the constraints that pass left in cache. Warm starting
/// only adds each constraint's own fixed impulses to its bodies' velocities,
/// so the order changes no result (short of a velocity reaching the wall).
fn warm_start_direction(substep: u32) -> Sweep {
    match substep.checked_sub(1) {
        None => Sweep::Reverse,
        Some(previous) => sweep_direction(previous).reversed(),
    }
}

/// The direction of sub-step `substep`'s sweeps: forward, reverse, reverse,
/// forward, forward, reverse, … (each direction twice in a row, so that
/// neither end of the constraint order is always solved first).
fn sweep_direction(substep: u32) -> Sweep {
    if (substep.saturating_add(1) / 2) % 2 == 1 {
        Sweep::Reverse
    } else {
        Sweep::Forward
    }
}

/// The solve stage: the impacts, then the contacts and joints, sub-stepped,
/// and the positions advanced; then restitution, and the impulses stored back
/// into the arbiters.
pub(crate) fn solve(
    ctx: &StepContext,
    bodies: &mut Arena<'_, Body>,
    arbiters: &mut ArbiterStore<'_>,
    joints: &mut Arena<'_, Joint, JointMarker>,
    constraints: &mut UserConstraints<'_>,
    solver: &mut Solver<'_>,
) {
    let n = ctx.substeps;
    let h = ctx.h;
    let params = LaneParams::new(ctx);
    load(ctx, bodies, arbiters, solver);
    prepare_joints(ctx, bodies, joints, constraints, solver);
    // The built-in joints work on the solver's bodies; the game's constraints
    // see `Body`, so when there are any the solver's copy is written to the
    // bodies around their pass.
    let user = !constraints.is_empty();
    let vmax = ctx.max_linear_speed;
    // The pivots in lanes' arms and position error at the start of the step
    // (their prepare leaves them to this pass).
    dispatch::run_pivots(solver, Pass::Pose);
    impacts(solver, &params);
    for substep in 0..n {
        let sweep = sweep_direction(substep);
        for (sb, lane) in solver.bodies.iter_mut().zip(solver.lanes.iter_mut()).filter(|(sb, _)| sb.forced) {
            sb.add_force(lane);
        }
        for_each_joint(solver, |j, (_, la), (_, lb)| j.warm_start(la, lb));
        dispatch::run_pivots(solver, Pass::Warm);
        let count_totals = substep > 0;
        dispatch::run(solver, warm_start_direction(substep), &contact::WarmStart { count_totals });
        for_each_joint(solver, |j, a, b| j.solve(a, b, h, Bias::On));
        dispatch::run_pivots(solver, Pass::Biased);
        if user {
            store_bodies::<false>(solver, bodies);
            solve_user_constraints(bodies, constraints, h);
            reload_bodies(solver, bodies);
        }
        contact_sweep(solver, &params, Bias::On, sweep);
        for (sb, lane) in solver.bodies.iter_mut().zip(solver.lanes.iter_mut()).filter(|(sb, _)| sb.moves) {
            sb.integrate(h, vmax, lane);
        }
        // Relax: one sweep in the sub-step's direction, as Box2D's one relax
        // iteration. The last sub-step had a second, forward, sweep: it kept
        // a column pushed out of 25 % overlap under the push speed (3.60 m/s
        // without it) before deep overlaps were pushed out by motion. Since
        // then every quality threshold holds without it (that column's
        // fastest 1.58 m/s) and a step makes 14 passes over the contacts
        // instead of 15: −3 % of the instructions of the contact scenes
        // (`docs/design/solver-lanes.md` §23).
        // The joints' relax pass runs in the order of their biased pass:
        // the joints one at a time in slot order, then the pivot lanes'
        // colours. Run in the reverse order, it fed some nets energy: a
        // 24 × 24 net of pivots hung by its corners, its horizontal or its
        // vertical joints made first, gained 116 to 161 × its weight × 1 m
        // in 300 steps, its fastest body at up to 172 m/s (see
        // `docs/design/solver-lanes.md` §21 and `tests/constraints.rs`).
        if solver.pivot_runs.count > 0 {
            dispatch::run_pivots(solver, Pass::Pose);
        }
        for_each_joint(solver, |j, a, b| j.solve(a, b, h, Bias::Off));
        dispatch::run_pivots(solver, Pass::Relax);
        contact_sweep(solver, &params, Bias::Off, sweep);
    }
    dispatch::run(solver, Sweep::Forward, &contact::Restitute { params: &params });
    solver.store_contacts(arbiters.live_mut());
    store_bodies::<true>(solver, bodies);
    store_joints(solver, joints);
}

/// Most sweeps of the impact pass a step: a blow crosses at least one contact
/// of a chain per sweep (more when the chain runs in the sweep's direction),
/// so a struck row of nine touching bodies passes it on to the last.
const IMPACT_SWEEPS: u32 = 8;

/// The impacts before the sub-steps (see `contact::Impacts`): sweeps in
/// alternating directions, forward first, until one finds none or
/// [`IMPACT_SWEEPS`] have run. A step without an elastic contact closing
/// faster than the threshold pays one sweep that reads each block's
/// restitution and nothing else.
fn impacts(solver: &mut Solver<'_>, params: &LaneParams) {
    let pass = contact::Impacts { params, hit: core::cell::Cell::new(false) };
    for k in 0..IMPACT_SWEEPS {
        pass.hit.set(false);
        let sweep = if k % 2 == 0 { Sweep::Forward } else { Sweep::Reverse };
        dispatch::run(solver, sweep, &pass);
        if !pass.hit.get() {
            break;
        }
    }
}

/// One sweep over every contact, in colour order (`sweep`'s direction).
fn contact_sweep(solver: &mut Solver<'_>, params: &LaneParams, bias: Bias, sweep: Sweep) {
    let reverse = sweep == Sweep::Reverse;
    dispatch::run(solver, sweep, &contact::SweepPass { params, bias, reverse });
}

/// Copies the bodies into the solver's array, colours the arbiters solved this
/// step and builds their constraints in colour order.
fn load(
    ctx: &StepContext,
    bodies: &Arena<'_, Body>,
    arbiters: &mut ArbiterStore<'_>,
    solver: &mut Solver<'_>,
) {
    let sbodies: &mut [SolverBody] = &mut solver.bodies;
    let lanes: &mut [BodyLanes] = &mut solver.lanes;
    for (i, b) in bodies.iter() {
        let k = i.index() as usize;
        if let (Some(sb), Some(lane)) = (sbodies.get_mut(k), lanes.get_mut(k)) {
            let prev = sb.mass_key();
            *sb = SolverBody::load(b, ctx.inv_substeps, ctx.h, ctx.max_angular_speed, lane, &prev);
        }
    }
    let scales = (ctx.contact_softness.mass_scale, ctx.static_softness.mass_scale);
    colour::build(arbiters.live_mut(), solver, scales);
    arbiters.mark_built();
}

/// Writes the solver's copy of every body the step moves back to the bodies
/// (static and frozen bodies keep their state untouched); at the `END` of
/// the step also clears every body's share of the forces, in the same pass
/// over the bodies (a second pass cost the joint grid's 10,000 bodies about
/// 1 % of its step in cache misses). Never inlined, like `colour::build`:
/// `solve`'s inlining otherwise moves with unrelated changes (inlined, the
/// 20-row pyramid took 0.3 % more instructions).
#[inline(never)]
fn store_bodies<const END: bool>(solver: &mut Solver<'_>, bodies: &mut Arena<'_, Body>) {
    let sbodies: &mut [SolverBody] = &mut solver.bodies;
    let lanes: &[BodyLanes] = &solver.lanes;
    for (i, b) in bodies.iter_mut() {
        let k = i.index() as usize;
        if let (Some(sb), Some(lane)) = (sbodies.get_mut(k).filter(|sb| sb.moves), lanes.get(k)) {
            sb.store(b, lane);
        }
        if END {
            b.force_dv = Vector2::ZERO;
            b.force_dw = ZERO;
        }
    }
}

/// Reads back into the solver's copy what a pass on the bodies changed.
fn reload_bodies(solver: &mut Solver<'_>, bodies: &Arena<'_, Body>) {
    let sbodies: &mut [SolverBody] = &mut solver.bodies;
    let lanes: &mut [BodyLanes] = &mut solver.lanes;
    for (i, b) in bodies.iter() {
        let k = i.index() as usize;
        if let (Some(sb), Some(lane)) = (sbodies.get_mut(k), lanes.get_mut(k)) {
            sb.reload(b, lane);
        }
    }
}

/// A solver body with its lanes.
type BodyPair<'b> = (&'b mut SolverBody, &'b mut BodyLanes);

/// Runs `f` on every joint row solved one at a time (not in the pivot lanes)
/// with its two solver bodies and their lanes, in joint-slot order (every
/// joint pass: see the relax pass in [`solve`]). A joint to a world
/// point gets a static stand-in body for B. The joints write the lanes as the
/// contact kernels do; the next [`SolverBody::pull`] carries what they did
/// into the `Scalar` velocity.
fn for_each_joint(solver: &mut Solver<'_>, mut f: impl FnMut(&mut JointRow, BodyPair<'_>, BodyPair<'_>)) {
    let bodies: &mut [SolverBody] = &mut solver.bodies;
    let lanes: &mut [BodyLanes] = &mut solver.lanes;
    let rows: &mut [JointRow] = &mut solver.joints;
    let rows = rows.get_mut(..solver.joint_count).unwrap_or_default();
    if solver.pivot_runs.one_at_a_time == 0 {
        return;
    }
    let mut visit = |row: &mut JointRow| {
        if row.pivot_colour != JointRow::NO_LANES {
            return;
        }
        let [ia, ib] = row.bodies;
        if row.world_point {
            let (mut ground, mut ground_lanes) = (SolverBody::EMPTY, BodyLanes::EMPTY);
            if let (Some(a), Some(la)) = (bodies.get_mut(ia as usize), lanes.get_mut(ia as usize)) {
                f(row, (a, la), (&mut ground, &mut ground_lanes));
            }
        } else if let (Some((a, b)), Some((la, lb))) =
            (body::pair_at(bodies, ia, ib), body::pair_at(lanes, ia, ib))
        {
            f(row, (a, la), (b, lb));
        }
    };
    rows.iter_mut().for_each(&mut visit);
}

/// Once per step: each joint's row (masses, softness, lane formats), in
/// joint-slot order; the game's `prepare`. The solver's copies of the bodies
/// are already loaded.
fn prepare_joints(
    ctx: &StepContext,
    bodies: &Arena<'_, Body>,
    joints: &mut Arena<'_, Joint, JointMarker>,
    constraints: &mut UserConstraints<'_>,
    solver: &mut Solver<'_>,
) {
    let ground = crate::constraint::ground();
    let sground = SolverBody::EMPTY;
    let sbodies: &[SolverBody] = &solver.bodies;
    let lanes: &mut [BodyLanes] = &mut solver.lanes;
    let rows: &mut [JointRow] = &mut solver.joints;
    let mut colouring = pivot_lanes::Colouring::new(&solver.pivots);
    let step = JointStep::new(ctx.joint_softness, ctx.h, ctx.inv_h);
    let mut count = 0;
    for (i, j) in joints.iter_mut() {
        // B, if the joint has one and it is there (else a static stand-in).
        let live_b = j.def.body_b.and_then(|hb| Some((bodies.get(hb)?, sbodies.get(hb.index() as usize)?)));
        let (b, sb) = live_b.unwrap_or((&ground, &sground));
        let a = bodies.get(j.def.body_a);
        let sa = sbodies.get(j.def.body_a.index() as usize);
        // The rows are as many as the joint slots, so one is always free.
        match (a, sa, rows.get_mut(count)) {
            (Some(a), Some(sa), Some(row)) => {
                // A plain pivot the lanes take is coloured here and built
                // straight into its lane by the fill below; every other
                // joint's row runs one at a time.
                let take = |ids, moves| colouring.take(ids, moves, lanes);
                if !j.take_lanes(row, i.index(), (sa, live_b.map(|(_, sb)| sb)), take) {
                    j.prepare(row, i.index(), a, b, sa, sb, &step);
                }
                count += 1;
            }
            _ => j.deactivate(),
        }
    }
    solver.joint_count = count;
    let rows: &mut [JointRow] = &mut solver.joints;
    let rows = rows.get_mut(..count).unwrap_or_default();
    solver.pivot_runs = colouring.fill(rows, joints, &solver.bodies, &mut solver.pivots, ctx.joint_softness);
    // A dormant game constraint (a body of it removed) is skipped.
    for (_, c) in constraints.iter_mut() {
        let b = match c.body_b {
            Some(hb) => bodies.get(hb),
            None => Some(&ground),
        };
        if let (Some(a), Some(b)) = (bodies.get(c.body_a), b) {
            c.constraint.prepare(a, b, ctx.dt);
        }
    }
}

/// After the sub-steps: each row's impulses (a pivot in lanes: its lane's)
/// back into its joint, and whether the joint broke.
fn store_joints(solver: &Solver<'_>, joints: &mut Arena<'_, Joint, JointMarker>) {
    let rows: &[JointRow] = &solver.joints;
    let store: &[PivotLanes] = &solver.pivots;
    for row in rows.get(..solver.joint_count).unwrap_or_default() {
        if let Some(j) = joints.get_at_mut(row.slot) {
            j.broken = if row.pivot_colour == JointRow::NO_LANES {
                j.finish_step(row)
            } else {
                let (lambda, sum) = pivot_lanes::point_state(store, row.lane as usize);
                j.finish_pivot(lambda, sum, row.inv_s)
            };
        }
    }
}

/// The game's constraints, once per sub-step, in registration order. Bodies
/// are looked up by handle (slot, generation and world), so a constraint never
/// acts on another body that took the slot of its own; a dormant one (a body
/// of it removed) is skipped.
fn solve_user_constraints(bodies: &mut Arena<'_, Body>, constraints: &mut UserConstraints<'_>, h: Scalar) {
    for (_, c) in constraints.iter_mut() {
        match c.body_b {
            Some(hb) => {
                if let Some((a, b)) = bodies.get2_mut(c.body_a, hb) {
                    c.constraint.solve(a, b, h);
                }
            }
            None => {
                let mut ground = crate::constraint::ground();
                if let Some(a) = bodies.get_mut(c.body_a) {
                    c.constraint.solve(a, &mut ground, h);
                }
            }
        }
    }
}

/// The solver's per-step arrays (see [`contact`] and [`colour`]).
pub(crate) struct Solver<'a> {
    /// One per body slot.
    pub(crate) bodies: ManagedSlice<'a, SolverBody>,
    /// One per body slot: what the contact kernels read and write.
    pub(crate) lanes: ManagedSlice<'a, BodyLanes>,
    /// The contact lanes, eight records a block; as long as the arbiter buffer
    /// rounded up to a whole block.
    pub(crate) constraints: ManagedSlice<'a, ContactConstraint>,
    /// Each live arbiter's colour, lane and effective masses this step
    /// (scratch); as long as the arbiters.
    pub(crate) scratch: ManagedSlice<'a, ContactScratch>,
    /// One row per live joint this step, in joint-slot order (scratch); as
    /// long as the joint slots.
    pub(crate) joints: ManagedSlice<'a, JointRow>,
    /// Joint rows in use this step.
    pub(crate) joint_count: usize,
    /// The plain pivots' lanes ([`pivot_lanes`]): one record per joint slot.
    pub(crate) pivots: ManagedSlice<'a, PivotLanes>,
    /// Where each colour of them is this step.
    pub(crate) pivot_runs: PivotRuns,
    /// Where each colour's lanes are: the overflow, then colours 0..23.
    pub(crate) ranges: [(u32, u32); colour::RUNS],
    /// Lanes in use this step.
    pub(crate) count: usize,
    /// This step's overflow constraints.
    pub(crate) overflow: u32,
}
