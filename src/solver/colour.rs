//! Deterministic graph colouring (Box2D v3's constraint graph, recomputed
//! every step): the contacts are grouped into colours so that no two in a
//! colour share a dynamic body, which lets a kernel solve eight of one colour
//! at once with the same result as one at a time.
//!
//! Each step, in pair-key order, every solved arbiter takes the first colour
//! free for both its dynamic bodies: the lowest of colours 0–19 for a pair of
//! dynamic bodies, the highest of 1–22 for a dynamic body against a static,
//! kinematic or frozen one (those take no colour bit: the contacts never write
//! them, so any number of a colour may read the same ground). One that finds
//! none goes to the overflow, solved one at a time in key order before the
//! colours (after them in a reverse sweep). The colours are a function of the
//! live arbiters, their `solve` flags and the bodies' types and frozen flags:
//! all restored by a snapshot or derived from it, so nothing is added to it.
//!
//! An arbiter whose manifold was recycled, whose friction and bodies' masses
//! are unchanged and that gets the lane it had in the last build keeps what
//! that build wrote there (see `contact::prepare`): the lifecycle marks the
//! arbiters whose scratch record is still their own
//! ([`ContactScratch::reuse`](super::ContactScratch): the arbiter list has
//! not moved since the build, [`ArbiterStore::built`](crate::arbiter::ArbiterStore::built),
//! and the arbiter is at the position of the one it continues), the load
//! marks the bodies whose masses are unchanged ([`SolverBody::same_mass`]),
//! and an arbiter left without a lane has its record's lane cleared. A
//! restore, a removal or any other change of the arbiter list rebuilds every
//! lane.
//!
//! The lanes are laid out in run order, the overflow first and then colours
//! 0 to 22, the overflow's constraints in key order and each colour's
//! two-point manifolds before its one-point ones, each in key order (a
//! colour's lanes are independent, so this order changes no result; it keeps
//! most blocks all of one kind, and a block of one-point manifolds skips the
//! kernels' second-point work); colours are not padded, so
//! a block may hold the end of one colour and the start of the next, and is
//! then solved in each with the other's lanes masked.

use crate::arbiter::Arbiter;
use crate::math::scalar::{Scalar, ZERO};

use super::contact::{self, Block, NO_LANE};
use super::lanes::{LANES, M};
use super::{BodyLanes, Solver, SolverBody, Sweep};

/// Runs: the overflow, then the 23 colours.
pub(crate) const RUNS: usize = 24;
/// The overflow's colour number.
const OVERFLOW: u8 = 23;
/// Not solved this step.
const NONE: u8 = u8::MAX;
/// Colours a pair of dynamic bodies may take (0–19).
const DYNAMIC_COLOURS: u32 = (1 << 20) - 1;
/// Colours a pair with one dynamic body may take (1–22).
const STATIC_COLOURS: u32 = ((1 << 23) - 1) & !1;

/// A kernel the runs are handed to: eight lanes of a block with a mask (a
/// colour's), or one lane (the overflow's). `WIDE` kernels solve the eight
/// lanes at once; the others one at a time (identical results: no two lanes
/// of a colour share a dynamic body).
pub(crate) trait Kernel {
    /// Lanes `active` of `blk`.
    fn eight<const WIDE: bool>(&self, blk: &mut Block, active: M<LANES>, bodies: &mut [BodyLanes]);
    /// Lane `lane` (modulo 8) of `blk`.
    fn one(&self, blk: &mut Block, lane: usize, bodies: &mut [BodyLanes]);
}

/// The block holding lane `lane`.
fn block_of(constraints: &mut [contact::ContactConstraint], lane: usize) -> Option<&mut Block> {
    let first = lane - lane % LANES;
    constraints.get_mut(first..first.checked_add(LANES)?)?.try_into().ok()
}

/// The runs of a forward sweep after the overflow: the colours only pairs
/// with a static body take (22, 21, 20), then 0 to 19, so that in a stack a
/// forward sweep meets the ground first and then goes up (lowest colours
/// first), as the key order of a stack built bottom-up did. Measured on
/// `tests/quality.rs`: with the static colours last, a 4-box column pushed out
/// of 25 % overlap ends a step at 3.29 m/s (push speed 3) and the bottom ball
/// of a 3-ball column struck from above lifts 4.7 cm off the ground; with all
/// colours in plain order, 3.006 m/s; in this order, 2.97 m/s and no lift.
const FORWARD_ORDER: [usize; RUNS - 1] =
    [23, 22, 21, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20];

/// The colour of an arbiter between bodies with colour masks `ma`, `mb`, of
/// which `da`, `db` are dynamic.
fn pick(ma: u32, mb: u32, da: bool, db: bool) -> u8 {
    let free = match (da, db) {
        (true, true) => !(ma | mb) & DYNAMIC_COLOURS,
        (true, false) => !ma & STATIC_COLOURS,
        (false, true) => !mb & STATIC_COLOURS,
        (false, false) => return NONE,
    };
    if free == 0 {
        OVERFLOW
    } else if da && db {
        free.trailing_zeros() as u8
    } else {
        (31 - free.leading_zeros()) as u8
    }
}

/// The run of a colour: the overflow is run 0.
fn run_of(colour: u8) -> usize {
    if colour == OVERFLOW {
        0
    } else {
        usize::from(colour) + 1
    }
}

/// Colours the solved arbiters and prepares their lanes in run order.
/// `scales` are the contact and static softness mass scales. An arbiter with
/// no dynamic body (a frozen body on the ground) gets no lanes and stores no
/// impulse. Never inlined: once a step, it gains nothing in the caller,
/// and the caller's own inlining then moves with every change elsewhere
/// (inlined into `solve` it cost the 20-row pyramid 0.7 % more
/// instructions).
#[inline(never)]
pub(crate) fn build(arbiters: &mut [Arbiter], solver: &mut Solver<'_>, scales: (Scalar, Scalar)) {
    let mut counts = [0u32; RUNS];
    // Two-point manifolds per run: each run lays them out first, so that the
    // kernels' second-point work (skipped for blocks of one-point manifolds)
    // and their 2×2 blocks meet few mixed blocks. The lanes of a colour are
    // independent, so their order within it changes no result.
    let mut twos = [0u32; RUNS];
    // An arbiter beyond the scratch is not solved.
    for arb in arbiters.iter_mut().skip(solver.scratch.len()) {
        arb.solve = false;
    }
    for (arb, scratch) in arbiters.iter_mut().zip(solver.scratch.iter_mut()) {
        scratch.colour = NONE;
        let slot = &mut scratch.colour;
        if !arb.solve {
            continue;
        }
        // By slot, without looking the handles up: the lifecycle has just
        // written every live arbiter with the handles it found live, and
        // nothing between it and the solve can remove a body (its callbacks
        // see the bodies shared).
        let (ia, ib) = (arb.body_a.index() as usize, arb.body_b.index() as usize);
        let sbodies: &mut [SolverBody] = &mut solver.bodies;
        let (Some(ma), Some(mb)) = (sbodies.get(ia), sbodies.get(ib)) else {
            arb.solve = false;
            continue;
        };
        let (da, db) = (ma.dynamic, mb.dynamic);
        let c = pick(ma.colours, mb.colours, da, db);
        if c == NONE {
            for p in arb.points.iter_mut() {
                p.normal_impulse = ZERO;
                p.tangent_impulse = ZERO;
                p.total_normal_impulse = ZERO;
                p.max_normal_impulse = ZERO;
            }
            continue;
        }
        if c != OVERFLOW {
            for (i, d) in [(ia, da), (ib, db)] {
                if let (Some(sb), true) = (sbodies.get_mut(i), d) {
                    sb.colours |= 1 << c;
                }
            }
        }
        *slot = c;
        if let Some(n) = counts.get_mut(run_of(c)) {
            *n += 1;
        }
        if let (Some(n), true) = (twos.get_mut(run_of(c)), arb.count >= 2) {
            *n += 1;
        }
    }
    let capacity = (solver.constraints.len() / LANES * LANES) as u32;
    // Laid out in the order a forward sweep visits the runs.
    let mut start = 0u32;
    for r in core::iter::once(0).chain(FORWARD_ORDER) {
        let (Some(range), Some(&n)) = (solver.ranges.get_mut(r), counts.get(r)) else { continue };
        let end = start.saturating_add(n).min(capacity);
        *range = (start, end);
        start = end;
    }
    solver.count = start as usize;
    solver.overflow = counts[0];
    // Each run's two-point manifolds from its start, the others after them,
    // each in key order.
    let mut cursor = [solver.ranges.map(|r| r.0), solver.ranges.map(|r| r.0)];
    for (one, (&n, &(s, e))) in cursor[1].iter_mut().zip(twos.iter().zip(solver.ranges.iter())) {
        *one = s.saturating_add(n).min(e);
    }
    let ends = [solver.ranges.map(|r| r.1), solver.ranges.map(|r| r.1)];
    for (arb, scratch) in arbiters.iter().zip(solver.scratch.iter_mut()) {
        if scratch.colour == NONE {
            scratch.lane = NO_LANE;
            continue;
        }
        let run = run_of(scratch.colour);
        // The overflow is solved one at a time: it keeps key order.
        let kind = usize::from(arb.count < 2 && run != 0);
        let (Some(at), Some(&end)) = (cursor[kind].get_mut(run), ends[kind].get(run)) else { continue };
        if *at >= end {
            scratch.colour = NONE;
            scratch.lane = NO_LANE;
            continue;
        }
        // The lane it had in the last build, holding what that build wrote
        // from the same manifold, friction and masses (see `ContactScratch::reuse`):
        // only what changes from step to step is written again.
        let same_lane = scratch.reuse && scratch.lane == *at;
        let lane = *at as usize;
        *at += 1;
        // (A lane left unbuilt is recorded as none, so that no later build
        // keeps what it holds.)
        scratch.lane = NO_LANE;
        // The first pass checked both handles (a coloured arbiter's bodies
        // are live): by slot, without the tag and generation tests again.
        let (ia, ib) = (arb.body_a.index(), arb.body_b.index());
        let sbodies: &[SolverBody] = &solver.bodies;
        let (Some(sa), Some(sb)) = (sbodies.get(ia as usize), sbodies.get(ib as usize)) else { continue };
        let Some(blk) = block_of(&mut solver.constraints, lane) else { continue };
        scratch.lane = lane as u32;
        let keep = same_lane && sa.same_mass && sb.same_mass;
        if let Some(mass) = contact::prepare(arb, (ia, ib), (sa, sb), scales, keep, blk, lane % LANES) {
            scratch.mass = mass;
        }
    }
}

/// Runs `k` on lane `lane` alone.
#[inline(always)]
fn one<K: Kernel>(
    constraints: &mut [contact::ContactConstraint],
    bodies: &mut [BodyLanes],
    k: &K,
    lane: u32,
) {
    let lane = lane as usize;
    if let Some(blk) = block_of(constraints, lane) {
        k.one(blk, lane, bodies);
    }
}

/// Runs `k` on the blocks of the lanes `s..e` (one colour), each with the
/// colour's lanes active, in order or in reverse.
#[inline(always)]
fn colour<K: Kernel, const WIDE: bool>(
    constraints: &mut [contact::ContactConstraint],
    bodies: &mut [BodyLanes],
    k: &K,
    (s, e): (u32, u32),
    forward: bool,
) {
    let (s, e) = (s as usize, e as usize);
    if s >= e {
        return;
    }
    let (first, last) = (s / LANES, (e - 1) / LANES);
    for i in 0..=(last - first) {
        let b = if forward { first + i } else { last - i };
        let lo = b * LANES;
        let mut active = M::<LANES>::all();
        if lo < s || lo + LANES > e {
            // The colour's first or last block: only its lanes.
            for (j, a) in active.0.iter_mut().enumerate() {
                *a = -i32::from((s..e).contains(&(lo + j)));
            }
        }
        if let Some(blk) = block_of(constraints, lo) {
            k.eight::<WIDE>(blk, active, bodies);
        }
    }
}

impl Solver<'_> {
    /// Runs `k` over every constraint in run order (`Sweep::Forward`: the
    /// overflow one lane at a time in key order, then each colour's blocks) or
    /// the exact reverse.
    #[inline(always)]
    pub(crate) fn runs<K: Kernel, const WIDE: bool>(&mut self, sweep: Sweep, k: &K) {
        let bodies: &mut [BodyLanes] = &mut self.lanes;
        let constraints: &mut [contact::ContactConstraint] = &mut self.constraints;
        let ranges = self.ranges;
        let forward = sweep == Sweep::Forward;
        let (os, oe) = ranges[0];
        if forward {
            for lane in os..oe {
                one(constraints, bodies, k, lane);
            }
        }
        for i in 1..RUNS {
            let j = if forward { i - 1 } else { RUNS - 1 - i };
            let r = FORWARD_ORDER.get(j).copied().unwrap_or(0);
            if let Some(&range) = ranges.get(r) {
                colour::<K, WIDE>(constraints, bodies, k, range, forward);
            }
        }
        if !forward {
            for lane in (os..oe).rev() {
                one(constraints, bodies, k, lane);
            }
        }
    }

    /// Writes every lane's impulses back to its arbiter.
    pub(crate) fn store_contacts(&mut self, arbiters: &mut [Arbiter]) {
        let constraints: &mut [contact::ContactConstraint] = &mut self.constraints;
        for (arb, scratch) in arbiters.iter_mut().zip(self.scratch.iter()) {
            if scratch.colour == NONE {
                continue;
            }
            let lane = scratch.lane as usize;
            if let Some(blk) = block_of(constraints, lane) {
                contact::store(blk, lane, arb, &scratch.mass);
            }
        }
    }
}
