//! Plain pivots in lanes: the point rows of pivot joints without limits or a
//! motor, coloured and solved eight at a time.
//!
//! A pivot between two bodies whose only row is its point constraint (Box2D's
//! revolute joint with neither limit nor motor: chains, ragdoll-free grids,
//! bridges) is the commonest joint, and its row is a 2×2 block like a
//! two-point contact's. Each step, as the joints are prepared, these pivots
//! are coloured in joint-slot order as the contacts are (each takes the
//! lowest of 32 colours that neither of its dynamic bodies has taken; a
//! static, kinematic or frozen body takes no colour, since the row never
//! changes its velocity); the fill then builds each one's record straight
//! into its lane (its row keeps only a header: see
//! `Joint::take_lanes`), and a colour's pivots are solved in lanes: eight at
//! once where the processor has AVX2 ([`dispatch`](super::dispatch)), one at
//! a time elsewhere, with the same bits, because no two lanes of a colour
//! share a body the row can move. A pivot that finds no colour, or no room in
//! the lane store, stays with the other joints, solved one at a time in slot
//! order.
//!
//! **Order.** Every joint pass (the warm start, the biased iteration and the
//! relax iteration) runs the joints one at a time in slot order and then the
//! colours 0 to 31, as Box2D v3 runs its colours in every stage. The order
//! is a function of the joints, their bodies and the bodies' types, all in
//! the snapshot.
//!
//! The relax colours once ran from 31 down to 0, the exact reverse of the
//! biased iteration, as the rows one at a time then did. On Box2D's joint grid
//! (10,000 circles, 19,800 pivots, 4 colours a body) that order fed energy
//! into the net: after 150 steps 8,500 bodies moved faster than 20 m/s, the
//! fastest at 250 m/s, more than five times what a fall from the net's
//! height gives, and the net kept vibrating. In the forward order no body
//! passes 10 m/s and the tracked body ends where Box2D's does (y = −101.67 m
//! against −101.74 m); see `docs/design/solver-lanes.md` §21.
//!
//! **Numbers.** Each lane computes exactly what
//! [`JointLanes`](super::joint_lanes::JointLanes)'s point row computes for
//! one joint (the same formats, products, roundings and clamps,
//! written as lane operations, its 64-bit sums in 64-bit lanes), so a pivot
//! gives the same bits in a lane as one at a time in the same order; the
//! kernels' unit test holds them to it. What changes with the lanes is only
//! the order in which the pivots meet.
//!
//! **Layout.** Each block holds eight pivots field-major: field `f` of lane
//! `l` at `[f][l]`, 32 fields of eight `i32` (1 KiB). The store has one
//! [`PivotLanes`] record (a quarter of a block) per joint slot, so that eight
//! consecutive records are one block and the store needs no capacity of its
//! own. Blocks are filled in colour order without padding: a block may hold
//! the end of one colour and the start of the next, and is then solved in
//! each with the other's lanes masked, as the contacts' are. The pose pass
//! (before the first sub-step, and once a sub-step after the positions are
//! integrated) turns each local anchor by its body's rotation and measures
//! the position error, as
//! [`JointLanes::pose`](super::joint_lanes::JointLanes::pose) does, one lane
//! at a time.

use crate::arena::Arena;
use crate::constraint::{Joint, JointMarker, JointRow};
use crate::math::scalar::Scalar;

use super::body::{BodyLanes, SolverBody, PIVOT_COLOURS};
use super::joint_lanes::{
    LaneSoft, PointRecord, ARM_HAT_MAX, BIAS_MAX, D_MAX, FA, FD, FH, FK, G_MAX, RATE_MAX,
};
use super::lanes::{FQ, FU, FV, L, L64, LAMBDA_MAX, LANES, M, V_WALL};
use super::Softness;

/// A quarter of a block: the pivot lanes' store holds one per joint slot
/// (solver scratch; see [`Storage`](crate::Storage)).
pub type PivotLanes = [[i32; LANES]; 4];

/// Fields of a block.
const FIELDS: usize = 32;
/// A block: field-major, eight lanes a field.
type Block = [[i32; LANES]; FIELDS];

/// The field numbers of a block.
mod f {
    /// Body slots of A and B.
    pub(super) const IA: usize = 0;
    pub(super) const IB: usize = 1;
    // Field 2 is spare (it held the row's index; the end of the step now
    // goes from each row to its lane: see the solver's `store_joints`).
    /// ρ of A and B (Q2.30).
    pub(super) const RHO: [usize; 2] = [3, 4];
    /// κ of A and B (Q5.27).
    pub(super) const KAPPA: [usize; 2] = [5, 6];
    /// 1/r_b of A and B (Q10.22).
    pub(super) const IOTA: [usize; 2] = [7, 8];
    /// Local anchors of A (x, y) and B (Q10.22).
    pub(super) const ANCHOR: [[usize; 2]; 2] = [[9, 10], [11, 12]];
    /// Arms in body radii of A and B (Q12.20).
    pub(super) const RH: [[usize; 2]; 2] = [[13, 14], [15, 16]];
    /// ĝ = κ·r̂ of A and B (Q12.20).
    pub(super) const G: [[usize; 2]; 2] = [[17, 18], [19, 20]];
    /// M̂: m11, m12, m22 (Q2.30).
    pub(super) const M11: usize = 21;
    pub(super) const M12: usize = 22;
    pub(super) const M22: usize = 23;
    /// Position error (Q13.19).
    pub(super) const D: [usize; 2] = [24, 25];
    /// Accumulated λ̂ (Q16.16).
    pub(super) const LAMBDA: [usize; 2] = [26, 27];
    /// λ̂ applied over the step, x and y, each as (low, high) words of an `i64`.
    pub(super) const SUM: [[usize; 2]; 2] = [[28, 29], [30, 31]];
}

/// Colours the pivots may take.
pub(crate) const COLOURS: usize = 32;

/// The pivots in lanes this step: where each colour's lanes are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PivotRuns {
    /// Lanes `ranges[c].0..ranges[c].1` hold colour `c`.
    pub(crate) ranges: [(u32, u32); COLOURS],
    /// Lanes in use.
    pub(crate) count: usize,
    /// Rows solved one at a time (none: the joint passes skip the rows).
    pub(crate) one_at_a_time: usize,
    /// The rows' softness in lane formats (every joint's is the world's).
    pub(crate) soft: LaneSoft,
}

impl PivotRuns {
    pub(crate) const EMPTY: Self = Self {
        ranges: [(0, 0); COLOURS],
        count: 0,
        one_at_a_time: 0,
        soft: LaneSoft { rate: 0, mass_scale: 0, impulse_scale: 0 },
    };
}

/// Block `b` of the store, if the store holds all of it.
fn block_mut(store: &mut [PivotLanes], b: usize) -> Option<&mut Block> {
    let first = b.checked_mul(LANES)?;
    let records = store.get_mut(first..first.checked_add(LANES)?)?;
    records.as_flattened_mut().try_into().ok()
}

/// Block `b` of the store, read only ([`block_mut`]).
fn block(store: &[PivotLanes], b: usize) -> Option<&Block> {
    let first = b.checked_mul(LANES)?;
    let records = store.get(first..first.checked_add(LANES)?)?;
    records.as_flattened().try_into().ok()
}

/// Lanes the store can hold: whole blocks only.
pub(crate) fn capacity(store: &[PivotLanes]) -> usize {
    store.len() / LANES * LANES
}

/// The colouring's running state over a step's rows.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Colouring {
    counts: [u32; COLOURS],
    total: usize,
    capacity: usize,
}

impl Colouring {
    /// Colouring into a store of `store`'s size.
    pub(crate) fn new(store: &[PivotLanes]) -> Self {
        Self { counts: [0; COLOURS], total: 0, capacity: capacity(store) }
    }

    /// The colour of the next plain pivot in joint-slot order, between the
    /// bodies in slots `ia`, `ib`: the lowest that neither body has taken (a
    /// body's colours are its lane record's field [`PIVOT_COLOURS`], cleared
    /// each step when the body is loaded), which the body then takes; or
    /// `None` (no lanes: the row runs one at a time) when the store is full
    /// or no colour is free. A body the row cannot move (`moves`: ρ = κ = 0,
    /// not dynamic) takes no colour: its lanes are written back unchanged.
    #[inline]
    pub(crate) fn take(
        &mut self,
        [ia, ib]: [u32; 2],
        moves: [bool; 2],
        bodies: &mut [BodyLanes],
    ) -> Option<u8> {
        if self.total == self.capacity {
            return None;
        }
        let (a, b) = super::body::pair_at(bodies, ia, ib)?;
        let (a, b) = (&mut a.0[PIVOT_COLOURS], &mut b.0[PIVOT_COLOURS]);
        let taken = |x: i32, moves: bool| if moves { x.cast_unsigned() } else { 0 };
        let free = !(taken(*a, moves[0]) | taken(*b, moves[1]));
        let c = free.trailing_zeros();
        let n = self.counts.get_mut(c as usize)?;
        for (x, moves) in [(a, moves[0]), (b, moves[1])] {
            if moves {
                *x |= 1 << c;
            }
        }
        *n += 1;
        self.total += 1;
        Some(c as u8)
    }

    /// Writes the coloured pivots' lanes in colour order (all but the fields
    /// of the pose, which the pose pass then measures), each built from its
    /// joint and the solver's copies of its bodies
    /// ([`Joint::pivot_record`]), and records each one's lane and 1/s in its
    /// row's header; returns where each colour is.
    pub(crate) fn fill(
        &self,
        rows: &mut [JointRow],
        joints: &Arena<'_, Joint, JointMarker>,
        bodies: &[SolverBody],
        store: &mut [PivotLanes],
        softness: Softness,
    ) -> PivotRuns {
        let mut runs = PivotRuns { count: self.total, soft: LaneSoft::new(softness), ..PivotRuns::EMPTY };
        let mut next = [0u32; COLOURS];
        let mut start = 0;
        for ((range, next), &n) in runs.ranges.iter_mut().zip(next.iter_mut()).zip(&self.counts) {
            *range = (start, start + n);
            *next = start;
            start += n;
        }
        for row in rows.iter_mut() {
            let Some(next) = next.get_mut(usize::from(row.pivot_colour)) else {
                runs.one_at_a_time += 1;
                continue;
            };
            let [ia, ib] = row.bodies;
            let side = |k: u32| bodies.get(k as usize).unwrap_or(&SolverBody::EMPTY);
            let built = joints.get_at(row.slot).and_then(|j| j.pivot_record(side(ia), side(ib)));
            // Every coloured row is a live plain pivot with s > 0 (see
            // `Joint::take_lanes`), so `built` is there; were it not, the
            // lane would hold a pivot that moves nothing.
            let (rec, inv_s) = built.unwrap_or((PointRecord::INERT, Scalar::ZERO));
            put(store, *next as usize, (ia, ib), &rec);
            row.lane = *next;
            row.inv_s = inv_s;
            *next += 1;
        }
        runs
    }
}

/// Writes a pivot's record into lane `lane`, all but its pose (the arms in
/// body radii, ĝ and the position error: the pose pass measures them before
/// the first sub-step); `ia`, `ib` are its bodies' slots.
pub(crate) fn put(store: &mut [PivotLanes], lane: usize, (ia, ib): (u32, u32), r: &PointRecord) {
    let Some(blk) = block_mut(store, lane / LANES) else { return };
    let l = lane % LANES;
    let mut set = |fi: usize, x: i32| {
        if let Some(field) = blk.get_mut(fi) {
            field[l] = x;
        }
    };
    set(f::IA, ia as i32);
    set(f::IB, ib as i32);
    for s in 0..2 {
        set(f::RHO[s], r.rho[s]);
        set(f::KAPPA[s], r.kappa[s]);
        set(f::IOTA[s], r.iota[s]);
        for k in 0..2 {
            set(f::ANCHOR[s][k], r.anchor[s][k]);
            set(f::SUM[s][k], 0);
        }
        set(f::LAMBDA[s], r.lambda[s]);
    }
    set(f::M11, r.m[0]);
    set(f::M12, r.m[1]);
    set(f::M22, r.m[2]);
}

/// Field `fi` of lane `l` (0 out of range).
#[inline(always)]
fn get(blk: &Block, fi: usize, l: usize) -> i32 {
    blk.get(fi).and_then(|x| x.get(l)).copied().unwrap_or(0)
}

/// At the end of the step: the accumulated λ̂ of the pivot in lane `lane`
/// and the λ̂ it applied over the step, summed (zeros outside the store).
pub(crate) fn point_state(store: &[PivotLanes], lane: usize) -> ([i32; 2], [i64; 2]) {
    let Some(blk) = block(store, lane / LANES) else { return ([0; 2], [0; 2]) };
    let l = lane % LANES;
    let sum = |s: usize| join(get(blk, f::SUM[s][0], l), get(blk, f::SUM[s][1], l));
    ([get(blk, f::LAMBDA[0], l), get(blk, f::LAMBDA[1], l)], [sum(0), sum(1)])
}

/// An `i64` from its low and high words.
#[inline(always)]
fn join(lo: i32, hi: i32) -> i64 {
    (i64::from(hi) << 32) | i64::from(lo as u32)
}

/// Which pass a kernel runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pass {
    /// The arms and position error at the bodies' current pose (once a
    /// sub-step, after the positions are integrated).
    Pose,
    /// The accumulated λ̂ applied again.
    Warm,
    /// One iteration, soft and biased.
    Biased,
    /// One iteration, rigid and unbiased (the relax sweep); also sums the
    /// λ̂ each pivot ends the sub-step with.
    Relax,
}

/// Lanes `base..base + W` of a block.
struct View<'b, const W: usize> {
    blk: &'b mut Block,
    base: usize,
    /// The kernel's mask selects every lane: its stores write whole rows.
    full: bool,
}

impl<'b, const W: usize> View<'b, W> {
    /// Lanes `base..base + W` of `blk`, for a kernel run on lanes `m`.
    #[inline(always)]
    fn new(blk: &'b mut Block, base: usize, m: M<W>) -> Self {
        // Tested once here rather than at each of a pass's stores.
        Self { blk, base, full: m.every() }
    }

    #[inline(always)]
    fn ld(&self, fi: usize) -> L<W> {
        let mut r = [0; W];
        for (i, x) in r.iter_mut().enumerate() {
            *x = get(self.blk, fi, self.base + i);
        }
        L(r)
    }

    /// Stores the lanes of `x` that `m` selects: a whole block as it is, not
    /// as a masked store (see the contact kernels' `View::st`).
    #[inline(always)]
    fn st(&mut self, fi: usize, x: L<W>, m: M<W>) {
        let x = if self.full { x } else { self.ld(fi).select(m, x) };
        if let Some(row) = self.blk.get_mut(fi) {
            for (i, &x) in x.0.iter().enumerate() {
                row[(self.base + i) % LANES] = x;
            }
        }
    }
}

/// One body side's change from a point impulse `p` (velocity units),
/// negated for A: [`JointLanes`](super::joint_lanes::JointLanes)'s
/// `Side::apply_point`, lane by lane.
#[inline(always)]
fn apply_side<const W: usize, const NEG: bool>(v: &mut [L<W>; 3], rho: L<W>, g: [L<W>; 2], p: [L<W>; 2]) {
    let (mut dx, mut dy) = (rho.mul::<FU>(p[0]), rho.mul::<FU>(p[1]));
    let mut dw = L64::mul_shift_biased::<FH>(g[0], p[1]).sub(L64::mul_shift_biased::<FH>(g[1], p[0]));
    if NEG {
        (dx, dy, dw) = (dx.neg(), dy.neg(), dw.neg());
    }
    // |ρ·p| ≤ 2³⁰ and |v| ≤ the wall (2²⁷): the `i32` sums cannot wrap.
    v[0] = v[0].add(dx).clamp_abs(V_WALL);
    v[1] = v[1].add(dy).clamp_abs(V_WALL);
    v[2] = L64::from(v[2]).add(dw).clamp_abs(i64::from(V_WALL)).narrow();
}

/// The velocity of an anchor at arm `r` (body radii): v + ŵ·perp(r̂), 64-bit.
#[inline(always)]
fn anchor_velocity<const W: usize>(vel: &[L<W>; 3], r: [L<W>; 2]) -> [L64<W>; 2] {
    [
        L64::from(vel[0]).sub(L64::mul_shift_biased::<FH>(vel[2], r[1])),
        L64::from(vel[1]).add(L64::mul_shift_biased::<FH>(vel[2], r[0])),
    ]
}

/// Fields `x`, `y` of a view.
#[inline(always)]
fn pair<const W: usize>(v: &View<'_, W>, [x, y]: [usize; 2]) -> [L<W>; 2] {
    [v.ld(x), v.ld(y)]
}

/// One iteration of the point row (biased or relax) on lanes `m`: the new
/// λ̂ stored, and the impulse to apply (new − old) returned.
#[inline(always)]
fn iterate<const W: usize>(
    v: &mut View<'_, W>,
    m: M<W>,
    relax: bool,
    soft: &LaneSoft,
    (va, vb): (&[L<W>; 3], &[L<W>; 3]),
    old: [L<W>; 2],
) -> [L<W>; 2] {
    let (aa, ab) = (anchor_velocity(va, pair(v, f::RH[0])), anchor_velocity(vb, pair(v, f::RH[1])));
    let mut u = [L::splat(0); 2];
    for k in 0..2 {
        let mut rate = ab[k].sub(aa[k]);
        if !relax {
            let d = v.ld(f::D[k]);
            rate = rate
                .add(L64::mul_shift_biased::<{ FD + FQ - FV }>(d, L::splat(soft.rate)).clamp_abs(BIAS_MAX));
        }
        u[k] = rate.clamp_abs(RATE_MAX).narrow();
    }
    let (m11, m12, m22) = (v.ld(f::M11), v.ld(f::M12), v.ld(f::M22));
    let mu = [
        L64::mul_shift_biased::<FU>(m11, u[0]).add(L64::mul_shift_biased::<FU>(m12, u[1])),
        L64::mul_shift_biased::<FU>(m12, u[0]).add(L64::mul_shift_biased::<FU>(m22, u[1])),
    ];
    let mut applied = [L::splat(0); 2];
    for k in 0..2 {
        let mu = mu[k].clamp_abs(RATE_MAX).narrow();
        let delta = if relax {
            // Rigid: s_m = 1, s_i = 0.
            L64::from(mu).neg()
        } else {
            // −s_m·μ − s_i·λ̂.
            L64::mul_shift_biased::<FU>(mu, L::splat(soft.mass_scale))
                .neg()
                .sub(L64::mul_shift_biased::<FU>(L::splat(soft.impulse_scale), old[k]))
        };
        let new = L64::from(old[k]).add(delta).clamp_abs(i64::from(LAMBDA_MAX)).narrow();
        v.st(f::LAMBDA[k], new, m);
        if relax {
            let [lo, hi] = f::SUM[k];
            let (lo_new, hi_new) = L64::join(v.ld(lo), v.ld(hi)).add(L64::from(new)).split();
            v.st(lo, lo_new, m);
            v.st(hi, hi_new, m);
        }
        applied[k] = new.sub(old[k]);
    }
    applied
}

/// A `Scalar`'s bits to `F` fractional bits, rounded half up, clamped to
/// ±`bound` ([`lanes::from_scalar`](super::lanes::from_scalar)).
#[inline(always)]
fn round<const W: usize, const F: u32>(x: L64<W>, bound: i64) -> L<W> {
    let down = x.shr(32 - F);
    let half = x.shr(31 - F).and(1);
    down.add(half).clamp_abs(bound).narrow()
}

/// A body's pose as the pose pass reads it: cos, sin of its rotation and
/// its position, each a `Scalar`'s bits.
#[inline(always)]
fn body_pose<const W: usize>(bodies: &[SolverBody], idx: L<W>) -> [L64<W>; 4] {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if W == LANES {
        return super::dispatch::avx2::gather_pose(bodies, idx.to8()).map(L64::from8);
    }
    let mut r = [[0i64; W]; 4];
    for (i, &b) in idx.0.iter().enumerate() {
        let sb = bodies.get(b as u32 as usize).unwrap_or(&SolverBody::EMPTY);
        for (k, x) in [sb.q.c, sb.q.s, sb.p.x, sb.p.y].into_iter().enumerate() {
            if let Some(slot) = r.get_mut(k).and_then(|f| f.get_mut(i)) {
                *slot = x.to_bits();
            }
        }
    }
    r.map(L64)
}

/// The pose pass on lanes `m` of view `v`:
/// [`arm_at`](super::joint_lanes::arm_at) for each side and
/// [`position_error`](super::joint_lanes::position_error), lane by lane (the
/// same bits; the unit test compares them with
/// [`JointLanes::pose`](super::joint_lanes::JointLanes::pose)).
#[inline(always)]
fn pose_kernel<const W: usize>(v: &mut View<'_, W>, m: M<W>, bodies: &[SolverBody]) {
    let mut arms = [[L::splat(0); 2]; 2];
    let mut centres = [[L64([0; W]); 2]; 2];
    for s in 0..2 {
        let [c, sn, px, py] = body_pose(bodies, v.ld(if s == 0 { f::IA } else { f::IB }));
        centres[s] = [px, py];
        let (c, sn) = (round::<W, FU>(c, 1 << FU), round::<W, FU>(sn, 1 << FU));
        let [x, y] = pair(v, f::ANCHOR[s]);
        let r = [c.mul::<FU>(x).sub(sn.mul::<FU>(y)), sn.mul::<FU>(x).add(c.mul::<FU>(y))];
        let (iota, kappa) = (v.ld(f::IOTA[s]), v.ld(f::KAPPA[s]));
        for ((rk, rh_field), g_field) in r.into_iter().zip(f::RH[s]).zip(f::G[s]) {
            let rh = L64::mul_shift_biased::<{ 2 * FA - FH }>(rk, iota).clamp_abs(ARM_HAT_MAX << FH).narrow();
            let g = L64::mul_shift_biased::<FK>(kappa, rh).clamp_abs(G_MAX << FH).narrow();
            v.st(rh_field, rh, m);
            v.st(g_field, g, m);
        }
        arms[s] = r;
    }
    for k in 0..2 {
        // B − A in 64 bits, saturating as the `Scalar` operations do; the
        // arms (Q10.22) exact in Q32.32.
        let arm = L64::from(arms[1][k]).shl(32 - FA).sub(L64::from(arms[0][k]).shl(32 - FA));
        let x = centres[1][k].saturating_sub(centres[0][k]).saturating_add(arm);
        let d = round::<W, FD>(x, D_MAX << FD);
        v.st(f::D[k], d, m);
    }
}

/// The mask of lanes `lo..hi` of a block (`lo ≤ hi ≤ LANES`): the lanes
/// below `hi` and not below `lo`, two rows of a table, where a loop over the
/// lanes tested each in turn.
#[inline(always)]
fn lane_range(lo: usize, hi: usize) -> M<LANES> {
    /// Row `n`: the lanes below `n`.
    const BELOW: [[i32; LANES]; LANES + 1] = {
        let mut t = [[0; LANES]; LANES + 1];
        let mut n = 0;
        while n <= LANES {
            let mut l = 0;
            while l < n {
                t[n][l] = -1;
                l += 1;
            }
            n += 1;
        }
        t
    };
    let row = |n: usize| M(BELOW.get(n).copied().unwrap_or([-1; LANES]));
    row(hi).and(row(lo).not())
}

/// Runs `pass` on lanes `m` of view `v`.
#[inline(always)]
fn kernel<const W: usize>(
    v: &mut View<'_, W>,
    m: M<W>,
    pass: Pass,
    soft: &LaneSoft,
    bodies: &mut [BodyLanes],
) {
    let (ia, ib) = (v.ld(f::IA), v.ld(f::IB));
    let (mut va, _) = super::contact::gather(bodies, ia);
    let (mut vb, _) = super::contact::gather(bodies, ib);
    let old = pair(v, f::LAMBDA);
    let p = match pass {
        Pass::Warm | Pass::Pose => old,
        Pass::Biased => iterate(v, m, false, soft, (&va, &vb), old),
        Pass::Relax => iterate(v, m, true, soft, (&va, &vb), old),
    };
    apply_side::<W, true>(&mut va, v.ld(f::RHO[0]), pair(v, f::G[0]), p);
    apply_side::<W, false>(&mut vb, v.ld(f::RHO[1]), pair(v, f::G[1]), p);
    super::contact::scatter(bodies, ia, &va, m);
    super::contact::scatter(bodies, ib, &vb, m);
}

impl super::Solver<'_> {
    /// Runs `pass` over the pivots in lanes, colours 0 to 31. `WIDE` solves eight lanes of a block at once;
    /// otherwise one lane at a time (the same bits). Inlined into
    /// `dispatch`'s AVX2 function, like the contacts' runs.
    #[inline(always)]
    pub(crate) fn pivot_runs<const WIDE: bool>(&mut self, pass: Pass) {
        // Plain loops, no closure: a closure would be compiled apart from
        // the AVX2 function this is inlined into, without AVX2.
        // Each pass its own loop (the pass a constant in it), so that no
        // block pays for the others' branches.
        match pass {
            Pass::Pose => self.pivot_pose::<WIDE>(),
            Pass::Warm => self.pivot_colours::<WIDE>(Pass::Warm),
            Pass::Biased => self.pivot_colours::<WIDE>(Pass::Biased),
            Pass::Relax => self.pivot_colours::<WIDE>(Pass::Relax),
        }
    }

    /// [`pivot_runs`](Self::pivot_runs) of a pass other than the pose.
    #[inline(always)]
    fn pivot_colours<const WIDE: bool>(&mut self, pass: Pass) {
        let ranges = self.pivot_runs.ranges;
        let soft = self.pivot_runs.soft;
        let store: &mut [PivotLanes] = &mut self.pivots;
        let bodies: &mut [BodyLanes] = &mut self.lanes;
        for c in 0..COLOURS {
            let Some(&(start, end)) = ranges.get(c) else { continue };
            let (start, end) = (start as usize, end as usize);
            for b in start / LANES..end.div_ceil(LANES) {
                let Some(blk) = block_mut(store, b) else { break };
                let first = b * LANES;
                let (lo, hi) = (start.max(first) - first, end.min(first + LANES) - first);
                if WIDE {
                    let m = lane_range(lo, hi);
                    kernel::<LANES>(&mut View::new(blk, 0, m), m, pass, &soft, bodies);
                } else {
                    for l in lo..hi {
                        kernel::<1>(&mut View::new(&mut *blk, l, M::all()), M::all(), pass, &soft, bodies);
                    }
                }
            }
        }
    }

    /// The pose pass over every pivot in lanes, eight at a time with `WIDE`.
    #[inline(always)]
    fn pivot_pose<const WIDE: bool>(&mut self) {
        let count = self.pivot_runs.count;
        let store: &mut [PivotLanes] = &mut self.pivots;
        let bodies: &[SolverBody] = &self.bodies;
        for b in 0..count.div_ceil(LANES) {
            let Some(blk) = block_mut(store, b) else { break };
            let n = (count - b * LANES).min(LANES);
            if WIDE {
                let m = lane_range(0, n);
                pose_kernel::<LANES>(&mut View::new(blk, 0, m), m, bodies);
            } else {
                for l in 0..n {
                    pose_kernel::<1>(&mut View::new(&mut *blk, l, M::all()), M::all(), bodies);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::scalar::Scalar;
    use crate::solver::joint_lanes::{JointLanes, PointPose};

    use crate::math::{Rot, Vector2};
    use crate::solver::{xorshift, Bias};

    /// The pose fields [`put`] leaves to the pose pass, from a record (the
    /// kernels' unit test, which runs the passes without it).
    fn put_pose(store: &mut [PivotLanes], lane: usize, r: &PointPose) {
        let Some(blk) = block_mut(store, lane / LANES) else { return };
        let l = lane % LANES;
        for s in 0..2 {
            for k in 0..2 {
                blk[f::RH[s][k]][l] = r.rh[s][k];
                blk[f::G[s][k]][l] = r.g[s][k];
            }
            blk[f::D[s]][l] = r.d[s];
        }
    }

    /// A value in [lo, hi]; one round in eight takes an end.
    fn range(seed: &mut u64, lo: i64, hi: i64) -> i32 {
        let r = xorshift(seed);
        match r % 16 {
            0 => lo as i32,
            1 => hi as i32,
            _ => (lo + ((r >> 8) % (hi - lo + 1).unsigned_abs()) as i64) as i32,
        }
    }

    /// A random pivot: lane `l` joins bodies 2l and 2l + 1, or the static
    /// body 16 (ρ = 0, ĝ = 0 on that side) and 2l + 1.
    fn record(seed: &mut u64, static_a: bool) -> (PointRecord, PointPose) {
        let u = 1i64 << FU;
        let side = |seed: &mut u64, fixed: bool| {
            let arm = ARM_HAT_MAX << FH;
            let g = G_MAX << FH;
            let rho = if fixed { 0 } else { range(seed, 0, u) };
            let rh = [range(seed, -arm, arm), range(seed, -arm, arm)];
            let gg = if fixed { [0; 2] } else { [range(seed, -g, g), range(seed, -g, g)] };
            (rho, rh, gg)
        };
        let (ra, rha, ga) = side(seed, static_a);
        let (rb, rhb, gb) = side(seed, false);
        let d = D_MAX << FD;
        let lam = i64::from(LAMBDA_MAX);
        let rec = PointRecord {
            rho: [ra, rb],
            kappa: [0; 2],
            iota: [0; 2],
            anchor: [[0; 2]; 2],
            m: [range(seed, 0, u), range(seed, -u, u), range(seed, 0, u)],
            lambda: [range(seed, -lam, lam), range(seed, -lam, lam)],
        };
        (rec, PointPose { rh: [rha, rhb], g: [ga, gb], d: [range(seed, -d, d), range(seed, -d, d)] })
    }

    /// Each pass gives the same bits on eight lanes at once (any mask) as on
    /// each active lane alone, and both the same as [`JointLanes`]'s point
    /// row one joint at a time (its warm start, biased and relax
    /// iterations, and the λ̂ it sums), on random and extreme inputs.
    #[test]
    fn lanes_equal_the_point_row_one_at_a_time() {
        let wide = {
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            {
                std::arch::is_x86_feature_detected!("avx2")
            }
            #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
            {
                false
            }
        };
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut moved = 0;
        for round in 0..4_000 {
            let soft = LaneSoft {
                rate: range(&mut seed, 0, 1 << 21),
                mass_scale: range(&mut seed, 0, 1 << FU),
                impulse_scale: range(&mut seed, 0, 1 << FU),
            };
            let mut store = [[[0; LANES]; 4]; LANES];
            let mut recs = [record(&mut seed, false); LANES];
            for (l, (rec, pose)) in recs.iter_mut().enumerate() {
                let fixed = round % 3 == 0 && l % 3 == 0;
                (*rec, *pose) = record(&mut seed, fixed);
                let ia = if fixed { 16 } else { 2 * l as u32 };
                put(&mut store, l, (ia, 2 * l as u32 + 1), rec);
                put_pose(&mut store, l, pose);
            }
            let wall = i64::from(V_WALL);
            let mut bodies = [BodyLanes::EMPTY; 17];
            for b in bodies.iter_mut() {
                for k in 0..3 {
                    b.0[k] = range(&mut seed, -wall, wall);
                }
            }
            let mut active = M::<LANES>::none();
            for (j, a) in active.0.iter_mut().enumerate() {
                *a = -i32::from(round % 4 == 0 || (xorshift(&mut seed) >> j) & 1 == 1);
            }
            let start = bodies;
            let (mut s1, mut b1) = (store, bodies);
            let (mut s8, mut b8) = (store, bodies);
            let mut joints = recs.map(|(r, p)| JointLanes::from_point_record(&r, &p, soft));
            let mut bref = bodies;
            for pass in [Pass::Warm, Pass::Biased, Pass::Relax] {
                if let Some(blk) = block_mut(&mut s1, 0) {
                    for l in (0..LANES).filter(|&l| active.is(l)) {
                        kernel::<1>(&mut View::new(&mut *blk, l, M::all()), M::all(), pass, &soft, &mut b1);
                    }
                }
                if wide {
                    if let Some(blk) = block_mut(&mut s8, 0) {
                        kernel::<LANES>(&mut View::new(blk, 0, active), active, pass, &soft, &mut b8);
                    }
                }
                for (l, j) in joints.iter_mut().enumerate().filter(|&(l, _)| active.is(l)) {
                    let ia = if round % 3 == 0 && l % 3 == 0 { 16 } else { 2 * l as u32 };
                    let Some((la, lb)) = super::super::body::pair_at(&mut bref, ia, 2 * l as u32 + 1) else {
                        continue;
                    };
                    match pass {
                        Pass::Warm | Pass::Pose => j.warm_point(la, lb),
                        Pass::Biased => j.solve_point(la, lb, Bias::On),
                        Pass::Relax => j.solve_point(la, lb, Bias::Off),
                    }
                }
            }
            assert_eq!(b1, bref, "round {round}: one lane at a time against the point row");
            if wide {
                assert_eq!(s8, s1, "round {round}: eight lanes against one");
                assert_eq!(b8, b1, "round {round}: bodies, eight lanes against one");
            }
            let blk = block_mut(&mut s1, 0).map(|b| *b).unwrap_or([[0; LANES]; FIELDS]);
            for (l, j) in joints.iter().enumerate().filter(|&(l, _)| active.is(l)) {
                let (lambda, sum) = j.point_state();
                assert_eq!([blk[f::LAMBDA[0]][l], blk[f::LAMBDA[1]][l]], lambda, "round {round} lane {l}: λ̂");
                let summed = |s: usize| join(blk[f::SUM[s][0]][l], blk[f::SUM[s][1]][l]);
                assert_eq!([summed(0), summed(1)], sum, "round {round} lane {l}: λ̂ summed");
            }
            moved += usize::from(b1 != start);
        }
        // The passes move bodies in nearly every round: the comparison is
        // not of no-ops.
        assert!(moved > 3_900, "{moved} of 4,000 rounds moved a body");
    }

    /// A `Scalar` of random bits within ±2^`bits` (its ends one round in
    /// eight, and now and then the format's own ends).
    fn scalar_bits(seed: &mut u64, bits: u32) -> Scalar {
        let r = xorshift(seed);
        let b = 1i64 << bits;
        Scalar::from_bits(match r % 32 {
            0 => i64::MIN,
            1 => i64::MAX,
            2 | 3 => -b,
            4 | 5 => b,
            _ => ((r >> 1) as i64) >> (63 - bits),
        })
    }

    /// The pose pass gives on eight lanes at once the bits it gives on each
    /// lane alone, and both [`JointLanes::pose`]'s: arms, ĝ and position
    /// error, for random anchors, radii, mass ratios, rotations (unit and
    /// not) and positions (up to the format's ends, where the difference
    /// saturates).
    #[test]
    fn the_pose_pass_equals_the_point_rows_pose() {
        let wide = {
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            {
                std::arch::is_x86_feature_detected!("avx2")
            }
            #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
            {
                false
            }
        };
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut saturated = 0;
        for round in 0..3_000 {
            let mut bodies = [SolverBody::EMPTY; 16];
            for b in bodies.iter_mut() {
                let big = if round % 5 == 0 { 62 } else { 38 };
                b.p = Vector2::new(scalar_bits(&mut seed, big), scalar_bits(&mut seed, big));
                let angle = Scalar::from_bits(((xorshift(&mut seed) >> 1) as i64) >> 29);
                b.q = if round % 7 == 0 {
                    Rot { c: scalar_bits(&mut seed, 33), s: scalar_bits(&mut seed, 33) }
                } else {
                    Rot::from_angle(angle)
                };
            }
            let mut store = [[[0; LANES]; 4]; LANES];
            let mut joints = [JointLanes::INACTIVE; LANES];
            for (l, j) in joints.iter_mut().enumerate() {
                let (mut rec, pose) = record(&mut seed, false);
                let a = (511i64) << FA;
                rec.anchor = [0, 1].map(|_| [range(&mut seed, -a, a), range(&mut seed, -a, a)]);
                rec.iota = [range(&mut seed, 0, 1 << 30), range(&mut seed, 0, 1 << 30)];
                rec.kappa = [range(&mut seed, 0, 1 << 30), range(&mut seed, 0, 1 << 30)];
                put(&mut store, l, (2 * l as u32, 2 * l as u32 + 1), &rec);
                *j =
                    JointLanes::from_point_record(&rec, &pose, LaneSoft::new(crate::solver::Softness::RIGID));
                if let (Some(a), Some(b)) = (bodies.get(2 * l), bodies.get(2 * l + 1)) {
                    j.pose(a, b);
                }
            }
            let mut s1 = store;
            if let Some(blk) = block_mut(&mut s1, 0) {
                for l in 0..LANES {
                    pose_kernel::<1>(&mut View::new(&mut *blk, l, M::all()), M::all(), &bodies);
                }
            }
            if wide {
                let mut s8 = store;
                if let Some(blk) = block_mut(&mut s8, 0) {
                    pose_kernel::<LANES>(&mut View::new(blk, 0, M::all()), M::all(), &bodies);
                }
                assert_eq!(s8, s1, "round {round}: eight lanes against one");
            }
            let blk = block_mut(&mut s1, 0).map(|b| *b).unwrap_or([[0; LANES]; FIELDS]);
            for (l, j) in joints.iter().enumerate() {
                let (rh, g, d) = j.pose_state();
                for s in 0..2 {
                    assert_eq!(
                        [blk[f::RH[s][0]][l], blk[f::RH[s][1]][l]],
                        rh[s],
                        "round {round} lane {l}: r̂"
                    );
                    assert_eq!([blk[f::G[s][0]][l], blk[f::G[s][1]][l]], g[s], "round {round} lane {l}: ĝ");
                }
                assert_eq!([blk[f::D[0]][l], blk[f::D[1]][l]], d, "round {round} lane {l}: d");
                saturated += usize::from(d.iter().any(|&x| x.unsigned_abs() == (D_MAX << FD) as u32));
            }
        }
        // Some errors reach the format's bound (far bodies): the clamps are
        // compared too.
        assert!(saturated > 100, "{saturated} lanes had a saturated error");
    }
}
