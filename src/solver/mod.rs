//! The contact solver and integrator: a soft step with sub-stepping.
//!
//! The design is Box2D v3's "soft step" (Erin Catto, *Solver2D*, 2024), written
//! here for fixed point. Each step is split into `substeps` sub-steps of
//! `h = dt / substeps`; each sub-step
//!
//! 1. adds its share of the force generators' velocity change (generators run once
//!    per step; their effect is spread evenly, as gravity is in Box2D),
//! 2. warm-starts every contact with the impulse it ended the previous sub-step with,
//! 3. solves the contacts as soft constraints (a spring-damper of
//!    `contact_hertz` / `contact_damping_ratio` pushing overlap out at no more than
//!    `contact_push_speed`; speculative points, still apart, only stop the bodies
//!    from closing the gap within the sub-step), in one sweep, with both points
//!    of a two-point manifold solved together as a 2×2 block (an exact linear
//!    complementarity solve, as in Box2D v2.4, of the system whose Gauss-Seidel
//!    step is Box2D v3's per-point soft update: each point its own spring),
//! 4. integrates positions,
//! 5. relaxes: one sweep without the position bias, so the push-out does not
//!    leave energy behind; the last sub-step adds one more forward sweep.
//!
//! Both sweeps of a sub-step run in the same direction, in pair order or in
//! reverse, and the direction changes every two sub-steps: forward, reverse,
//! reverse, forward (then forward, reverse, reverse, forward with 8 sub-steps),
//! so over a step every pair is solved first as often as last, in the biased
//! sweeps as in the relax sweeps.
//!
//! These choices were measured on `tests/quality.rs` and `tests/scale.rs`, not
//! picked for looks: with one-way sweeps a symmetric pyramid creeps sideways
//! (16 mm in 10 s); solving the two points of a manifold one after the other lets
//! a 20-box stack topple (the first point always takes more). Two relax sweeps in
//! every sub-step (12 sweeps a step) were an earlier design; one sweep (8,
//! Box2D's count) is as good everywhere except a 4-box column recovering from
//! 25 % overlap, which ends steps at 3.6 m/s, above the 3 m/s push speed; the
//! extra forward sweep in the last sub-step (9 sweeps) brings that to 2.98 m/s.
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
//! faster than `restitution_threshold` their bounce, e·v.
//!
//! The separation of each contact point is re-evaluated in every sub-step from
//! how far the bodies moved and turned since the step began (linearised in the
//! turn; see [`contact`]), so no collision detection runs inside the loop.
//! Everything iterates in the canonical arbiter order and body-slot order.
//!
//! The loops run over two dense arrays built once per step (see [`contact`]):
//! a [`SolverBody`] per body slot and a [`ContactConstraint`] per solved arbiter.

mod body;
mod contact;
mod softness;
mod sweep;

pub use body::SolverBody;
pub use contact::ContactConstraint;

pub(crate) use body::inverse_mass;
use contact::{Carried, StepParams};
use managed::ManagedSlice;
pub(crate) use softness::{Row, Softness};
pub(crate) use sweep::{Bias, Sweep};

use crate::arbiter::ArbiterStore;
use crate::arena::Arena;
use crate::body::Body;
use crate::constraint::{Joint, JointMarker, UserConstraints};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::step::StepContext;

/// The direction of sub-step `substep`'s warm start: against the pass before it
/// (the previous sub-step's relax sweep, or the forward constraint build), so
/// that it begins with the constraints that pass left in cache. Warm starting
/// only adds each constraint's own fixed impulses to its bodies' velocities,
/// and fixed-point sums are exact, so the order changes no result (short of a
/// velocity saturating).
fn warm_start_direction(substep: u32) -> Sweep {
    match substep.checked_sub(1) {
        None => Sweep::Reverse,
        Some(previous) => sweep_direction(previous).reversed(),
    }
}

/// The direction of sub-step `substep`'s sweeps: forward, reverse, reverse,
/// forward, forward, reverse, … (each direction twice in a row, so that
/// neither end of the constraint list is always solved first).
fn sweep_direction(substep: u32) -> Sweep {
    if (substep.saturating_add(1) / 2) % 2 == 1 {
        Sweep::Reverse
    } else {
        Sweep::Forward
    }
}

/// The solve stage: the contacts and joints, sub-stepped, and the positions
/// advanced; then restitution, and the impulses stored back into the arbiters.
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
    let params = StepParams {
        inv_h: ctx.inv_h,
        soft: ctx.contact_softness,
        static_soft: ctx.static_softness,
        push_speed: ctx.push_speed,
    };
    load(bodies, arbiters, solver, ctx.inv_substeps, &params);
    prepare_joints(ctx, bodies, joints, constraints);
    // The built-in joints work on the solver's bodies; the game's constraints
    // see `Body`, so when there are any the solver's copy is written to the
    // bodies around their pass.
    let user = !constraints.is_empty();
    let (vmax, wmax) = (ctx.max_linear_speed, ctx.max_angular_speed);
    for substep in 0..n {
        let sweep = sweep_direction(substep);
        let (sbodies, _) = solver.split();
        for sb in sbodies.iter_mut().filter(|sb| sb.forced) {
            sb.v += sb.force_dv;
            sb.w += sb.force_dw;
        }
        for_each_joint(joints, solver, Sweep::Forward, |j, a, b| j.warm_start(a, b));
        let (sbodies, cs) = solver.split();
        contact::warm_start(sbodies, cs, warm_start_direction(substep), Carried::for_substep(substep));
        for_each_joint(joints, solver, Sweep::Forward, |j, a, b| j.solve(a, b, h, Bias::On));
        if user {
            store_bodies(solver, bodies);
            solve_user_constraints(bodies, constraints, h);
            reload_bodies(solver, bodies);
        }
        let (sbodies, cs) = solver.split();
        contact::solve(sbodies, cs, &params, Bias::On, sweep);
        for sb in sbodies.iter_mut().filter(|sb| sb.moves) {
            // Component clamps are cheap and bound the displacement; the
            // exact speed limit is applied once at the end of the step.
            let v = sb.v;
            sb.v = Vector2::new(v.x.clamp(-vmax, vmax), v.y.clamp(-vmax, vmax));
            sb.w = sb.w.clamp(-wmax, wmax);
            sb.p += sb.v * h;
            let turn = sb.w * h;
            sb.angle += turn;
            sb.q = sb.q.integrate(turn);
        }
        // Relax: one sweep in the sub-step's direction; the last sub-step
        // adds a forward sweep, which drains what the push-out left in the
        // velocities the step ends with.
        // The joints' relax pass runs in reverse slot order in every sub-step.
        for_each_joint(joints, solver, Sweep::Reverse, |j, a, b| j.solve(a, b, h, Bias::Off));
        let (sbodies, cs) = solver.split();
        contact::solve(sbodies, cs, &params, Bias::Off, sweep);
        if substep + 1 == n {
            contact::solve(sbodies, cs, &params, Bias::Off, Sweep::Forward);
        }
    }
    let (sbodies, cs) = solver.split();
    contact::restitute_and_store(sbodies, cs, arbiters.live_mut(), ctx.restitution_threshold);
    store_bodies(solver, bodies);
    for (_, j) in joints.iter_mut() {
        j.broken = j.finish_step();
    }
    for (_, b) in bodies.iter_mut() {
        b.force_dv = Vector2::ZERO;
        b.force_dw = ZERO;
    }
}

/// Copies the bodies into the solver's array and builds the contact
/// constraints of the arbiters solved this step, in arbiter order.
fn load(
    bodies: &Arena<'_, Body>,
    arbiters: &mut ArbiterStore<'_>,
    solver: &mut Solver<'_>,
    inv_n: Scalar,
    params: &StepParams,
) {
    let sbodies: &mut [SolverBody] = &mut solver.bodies;
    for (i, b) in bodies.iter() {
        if let Some(sb) = sbodies.get_mut(i.index() as usize) {
            *sb = SolverBody::load(b, inv_n);
        }
    }
    let mut count = 0usize;
    for (k, arb) in arbiters.live_mut().iter_mut().enumerate() {
        if !arb.solve {
            continue;
        }
        let (Some(a), Some(b)) = (bodies.get(arb.body_a), bodies.get(arb.body_b)) else {
            arb.solve = false;
            continue;
        };
        // The constraint buffer is as long as the arbiter buffer.
        let Some(slot) = solver.constraints.get_mut(count) else { break };
        contact::prepare(k as u32, arb, (arb.body_a.index(), arb.body_b.index()), (a, b), params, slot);
        count = count.saturating_add(1);
    }
    solver.count = count;
}

/// Writes the solver's copy of every body the step moves back to the bodies
/// (static and frozen bodies keep their state untouched).
fn store_bodies(solver: &Solver<'_>, bodies: &mut Arena<'_, Body>) {
    let sbodies: &[SolverBody] = &solver.bodies;
    for (i, b) in bodies.iter_mut() {
        if let Some(sb) = sbodies.get(i.index() as usize).filter(|sb| sb.moves) {
            sb.store(b);
        }
    }
}

/// Reads back into the solver's copy what a pass on the bodies changed.
fn reload_bodies(solver: &mut Solver<'_>, bodies: &Arena<'_, Body>) {
    let sbodies: &mut [SolverBody] = &mut solver.bodies;
    for (i, b) in bodies.iter() {
        if let Some(sb) = sbodies.get_mut(i.index() as usize) {
            sb.reload(b);
        }
    }
}

/// Runs `f` on every joint with its two solver bodies, in joint-slot order
/// (`Sweep::Forward`) or the reverse. A joint to a world point gets a static
/// stand-in body for B.
fn for_each_joint(
    joints: &mut Arena<'_, Joint, JointMarker>,
    solver: &mut Solver<'_>,
    order: Sweep,
    mut f: impl FnMut(&mut Joint, &mut SolverBody, &mut SolverBody),
) {
    let bodies: &mut [SolverBody] = &mut solver.bodies;
    let used = joints.slots_used();
    for k in 0..used {
        let i = match order {
            Sweep::Forward => k,
            Sweep::Reverse => used.saturating_sub(1).saturating_sub(k),
        };
        let Some(j) = joints.get_at_mut(i) else { continue };
        let ia = j.def.body_a.index();
        match j.def.body_b {
            Some(hb) => {
                if let Some((a, b)) = body::pair_at(bodies, ia, hb.index()) {
                    f(j, a, b);
                }
            }
            None => {
                let mut ground = SolverBody::EMPTY;
                if let Some(a) = bodies.get_mut(ia as usize) {
                    f(j, a, &mut ground);
                }
            }
        }
    }
}

/// Once per step: joint masses and softness; the game's `prepare`.
fn prepare_joints(
    ctx: &StepContext,
    bodies: &Arena<'_, Body>,
    joints: &mut Arena<'_, Joint, JointMarker>,
    constraints: &mut UserConstraints<'_>,
) {
    let ground = crate::constraint::ground();
    for (_, j) in joints.iter_mut() {
        let b = j.def.body_b.and_then(|hb| bodies.get(hb)).unwrap_or(&ground);
        if let Some(a) = bodies.get(j.def.body_a) {
            j.prepare(a, b, ctx.joint_softness);
        }
    }
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

/// The solver's per-step arrays (see [`contact`]).
pub(crate) struct Solver<'a> {
    /// One per body slot.
    pub(crate) bodies: ManagedSlice<'a, SolverBody>,
    /// One per arbiter; the first `count` are this step's.
    pub(crate) constraints: ManagedSlice<'a, ContactConstraint>,
    pub(crate) count: usize,
}

impl Solver<'_> {
    /// The body array and this step's constraints.
    fn split(&mut self) -> (&mut [SolverBody], &mut [ContactConstraint]) {
        let n = self.count;
        let constraints: &mut [ContactConstraint] = &mut self.constraints;
        (&mut self.bodies, constraints.get_mut(..n).unwrap_or(&mut []))
    }
}
