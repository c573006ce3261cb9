//! The contact solver's per-step working set: compact records built from the
//! arbiters once per step, solved in the sub-step loop, and written back.
//!
//! Box2D v3 keeps its solver data apart from its persistent contacts for speed,
//! and so do we: an [`Arbiter`] holds what outlives the step (the manifold, the
//! accumulated impulses, the state) and is double-buffered for the merge with the
//! new pairs, while the sub-step loop reads the same constraint and body data
//! about twelve times a step. Those loops run over two dense arrays:
//!
//! * [`SolverBody`]: one per body slot, the body's velocity and pose and nothing
//!   else (88 bytes, against 216 for a [`Body`] slot);
//! * [`ContactConstraint`]: one per solved arbiter, in arbiter (pair-key) order,
//!   with the anchors, arms, effective masses and impulses precomputed.
//!
//! Both live in the world's [`Storage`](crate::Storage), so the step allocates
//! nothing; their contents are derived each step and are not part of a snapshot.

use crate::arbiter::Arbiter;
use crate::body::Body;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rot, Vector2};

use super::Softness;

/// A body's state as the solver sees it during a step (solver scratch, one per
/// body slot; see [`Storage`](crate::Storage)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolverBody {
    pub(crate) v: Vector2,
    pub(crate) w: Scalar,
    pub(crate) p: Vector2,
    pub(crate) q: Rot,
    /// The angle turned since the start of the step (rad).
    pub(crate) angle: Scalar,
    /// This sub-step's share of the force generators' velocity change.
    pub(crate) pending_v: Vector2,
    pub(crate) pending_w: Scalar,
    /// Receives the generators' velocity change (dynamic, in bounds).
    pub(crate) forced: bool,
    /// Integrates its position (not static, in bounds).
    pub(crate) moves: bool,
    /// Takes impulses (dynamic): contacts change its velocity.
    pub(crate) dynamic: bool,
}

impl SolverBody {
    /// An unused record.
    pub const EMPTY: Self = Self {
        v: Vector2::ZERO,
        w: ZERO,
        p: Vector2::ZERO,
        q: Rot::IDENTITY,
        angle: ZERO,
        pending_v: Vector2::ZERO,
        pending_w: ZERO,
        forced: false,
        moves: false,
        dynamic: false,
    };

    /// Loads a body's state; `inv_n` is 1 / sub-steps.
    #[inline]
    pub(crate) fn load(b: &Body, inv_n: Scalar) -> Self {
        Self {
            v: b.linear_velocity,
            w: b.angular_velocity,
            p: b.position,
            q: b.rotation,
            angle: ZERO,
            pending_v: b.force_dv * inv_n,
            pending_w: b.force_dw * inv_n,
            forced: b.is_dynamic() && !b.out_of_bounds,
            moves: b.moved_by_step(),
            dynamic: b.is_dynamic(),
        }
    }

    /// Writes the velocity and pose back to the body.
    #[inline]
    pub(crate) fn store(&self, b: &mut Body) {
        b.linear_velocity = self.v;
        b.angular_velocity = self.w;
        b.position = self.p;
        b.rotation = self.q;
    }

    /// Velocity of the point at offset `r` from the centre of mass.
    #[inline]
    pub(crate) fn velocity_at_offset(&self, r: Vector2) -> Vector2 {
        self.v + Vector2::cross_sv(self.w, r)
    }

    /// Takes the velocity and pose from the body (after joints moved it).
    #[inline]
    pub(crate) fn reload(&mut self, b: &Body) {
        self.v = b.linear_velocity;
        self.w = b.angular_velocity;
        self.p = b.position;
        self.q = b.rotation;
    }
}

impl Default for SolverBody {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// What warm starting needs of one contact point: its inertia-scaled arms and
/// accumulated impulses. Kept apart from the rest of the point (see
/// [`ContactConstraint`]'s layout).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PointImpulse {
    /// iA·(rA × n), iB·(rB × n) and iA·(rA × t), iB·(rB × t): the angular
    /// velocity change per unit impulse.
    irn: [Scalar; 2],
    irt: [Scalar; 2],
    normal_impulse: Scalar,
    tangent_impulse: Scalar,
    /// The step's sum of the impulses the point ended its sub-steps with, which
    /// equals the sum of every change applied (warm start plus each sweep's
    /// increment), added once per sub-step instead of once per change.
    total_normal_impulse: Scalar,
}

impl PointImpulse {
    const EMPTY: Self = Self {
        irn: [ZERO; 2],
        irt: [ZERO; 2],
        normal_impulse: ZERO,
        tangent_impulse: ZERO,
        total_normal_impulse: ZERO,
    };
}

/// The rest of one contact point of a [`ContactConstraint`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PointConstraint {
    /// Separation at the start of the step less n·(pB − pA) then, so that
    /// adding n·(pB − pA) now gives the separation after the bodies moved.
    base_separation: Scalar,
    normal_mass: Scalar,
    /// 1 / normal_mass: the diagonal entry of the block's mass matrix.
    normal_k: Scalar,
    tangent_mass: Scalar,
    /// The fastest approach seen this step (restitution reference).
    relative_velocity: Scalar,
    /// rA × n, rB × n and rA × t, rB × t.
    rn: [Scalar; 2],
    rt: [Scalar; 2],
    max_normal_impulse: Scalar,
}

impl PointConstraint {
    const EMPTY: Self = Self {
        base_separation: ZERO,
        normal_mass: ZERO,
        normal_k: ZERO,
        tangent_mass: ZERO,
        relative_velocity: ZERO,
        rn: [ZERO; 2],
        rt: [ZERO; 2],
        max_normal_impulse: ZERO,
    };
}

/// A solved arbiter's data for one step (solver scratch, one per arbiter; see
/// [`Storage`](crate::Storage)).
///
/// Laid out for the memory traffic of large scenes, where the constraints do not
/// fit in cache (Box2D v3's 100-row pyramid has 15,000 of them) and every pass
/// streams them from memory: seven cache lines, aligned, and what warm starting
/// reads (the bodies, the linear velocity change per impulse, each point's
/// impulses and inertia-scaled arms) in the first three.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct ContactConstraint {
    /// Body slots.
    a: u32,
    b: u32,
    /// Index of the arbiter this came from (the write-back target).
    arbiter: u32,
    count: u8,
    /// One body has infinite mass: the stiffer static softness applies.
    static_pair: bool,
    /// `block` and `soft_block` hold the two-point block solve's matrices; false
    /// for one point or an ill-conditioned pair.
    has_block: bool,
    /// n·mA, n·mB, t·mA, t·mB: the linear velocity change per unit impulse.
    n_m: [Vector2; 2],
    t_m: [Vector2; 2],
    impulses: [PointImpulse; 2],
    normal: Vector2,
    friction: Scalar,
    /// Off-diagonal entry of the normal mass matrix K.
    k12: Scalar,
    /// The symmetric inverse of K, `[a, b, d]` for `[[a, b], [b, d]]`.
    block: [Scalar; 3],
    /// The same for the soft system's matrix (the diagonal divided by the
    /// pair's mass scale; see [`solve_block`]) when both points are soft.
    soft_block: [Scalar; 3],
    points: [PointConstraint; 2],
}

// The layout the comment above describes: warm starting's data in the first
// three cache lines, the whole in seven.
const _: () = {
    assert!(core::mem::offset_of!(ContactConstraint, normal) <= 192);
    assert!(core::mem::size_of::<ContactConstraint>() == 448);
};

impl ContactConstraint {
    /// An unused record.
    pub const EMPTY: Self = Self {
        a: 0,
        b: 0,
        arbiter: 0,
        count: 0,
        static_pair: false,
        has_block: false,
        n_m: [Vector2::ZERO; 2],
        t_m: [Vector2::ZERO; 2],
        impulses: [PointImpulse::EMPTY; 2],
        normal: Vector2::ZERO,
        friction: ZERO,
        k12: ZERO,
        block: [ZERO; 3],
        soft_block: [ZERO; 3],
        points: [PointConstraint::EMPTY; 2],
    };

    /// The used points and their impulses.
    fn points(&self) -> impl Iterator<Item = (&PointConstraint, &PointImpulse)> {
        self.points.iter().zip(self.impulses.iter()).take(usize::from(self.count))
    }

    /// The used points and their impulses, mutably.
    fn points_mut(&mut self) -> impl Iterator<Item = (&mut PointConstraint, &mut PointImpulse)> {
        let count = usize::from(self.count);
        self.points.iter_mut().zip(self.impulses.iter_mut()).take(count)
    }
}

impl Default for ContactConstraint {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Per-step solver settings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepParams {
    pub(crate) inv_h: Scalar,
    pub(crate) soft: Softness,
    pub(crate) static_soft: Softness,
    pub(crate) push_speed: Scalar,
}

/// Inverse mass and inertia a body contributes to a contact (0 unless dynamic).
pub(crate) fn inverse_mass(b: &Body) -> (Scalar, Scalar) {
    if b.is_dynamic() {
        (b.mass.inv_mass, b.mass.inv_inertia)
    } else {
        (ZERO, ZERO)
    }
}

/// Builds, in `c`, the constraint of arbiter `index` (which is solved this
/// step) between bodies `a` and `b` in slots `ia`, `ib`.
pub(crate) fn prepare(
    index: u32,
    arb: &Arbiter,
    (ia, ib): (u32, u32),
    (a, b): (&Body, &Body),
    params: &StepParams,
    c: &mut ContactConstraint,
) {
    let ((ma, iia), (mb, iib)) = (inverse_mass(a), inverse_mass(b));
    let n = arb.normal;
    let t = n.right_perp();
    *c = ContactConstraint {
        arbiter: index,
        a: ia,
        b: ib,
        normal: n,
        friction: arb.friction,
        count: arb.count.min(2),
        ..ContactConstraint::EMPTY
    };
    let n0 = (b.position - a.position).dot(n);
    for ((cp, ci), src) in c.points_mut().zip(arb.points.iter()) {
        let (ra, rb) = (src.anchor_a, src.anchor_b);
        cp.base_separation = src.separation - n0;
        let k = mass_matrix(ma, mb, iia, iib, ra, rb, n);
        cp.normal_k = k;
        cp.normal_mass = k.recip();
        cp.tangent_mass = mass_matrix(ma, mb, iia, iib, ra, rb, t).recip();
        let dv = b.velocity_at_offset(rb) - a.velocity_at_offset(ra);
        cp.relative_velocity = dv.dot(n);
        cp.rn = [ra.cross(n), rb.cross(n)];
        cp.rt = [ra.cross(t), rb.cross(t)];
        ci.irn = [iia * cp.rn[0], iib * cp.rn[1]];
        ci.irt = [iia * cp.rt[0], iib * cp.rt[1]];
        ci.normal_impulse = src.normal_impulse;
        ci.tangent_impulse = src.tangent_impulse;
    }
    let ([p1, p2], [i1, _]) = (&c.points, &c.impulses);
    c.k12 = ma + mb + i1.irn[0] * p2.rn[0] + i1.irn[1] * p2.rn[1];
    c.static_pair = ma == ZERO || mb == ZERO;
    if let Some(rigid) = block_inverse(c) {
        let ms = if c.static_pair { params.static_soft.mass_scale } else { params.soft.mass_scale };
        let (u1, u2) = (p1.normal_mass * ms, p2.normal_mass * ms);
        if let Some(soft) = inverse_from_diagonal_inverses(u1, u2, c.k12) {
            (c.block, c.soft_block, c.has_block) = (rigid, soft, true);
        }
    }
    c.n_m = [n * ma, n * mb];
    c.t_m = [t * ma, t * mb];
}

/// Copies what outlives the step back into the arbiter: the impulses that warm-start
/// the next step and the totals a game reads. The total gets the impulse the
/// last sub-step (and the restitution pass) ended with here; see
/// [`PointImpulse::total_normal_impulse`].
fn store(c: &ContactConstraint, arb: &mut Arbiter) {
    for (dst, (cp, ci)) in arb.points.iter_mut().zip(c.points()) {
        dst.normal_impulse = ci.normal_impulse;
        dst.tangent_impulse = ci.tangent_impulse;
        dst.total_normal_impulse = ci.total_normal_impulse + ci.normal_impulse;
        dst.max_normal_impulse = cp.max_normal_impulse;
    }
}

/// The arbiter a constraint was built from.
fn arbiter_index(c: &ContactConstraint) -> usize {
    c.arbiter as usize
}

/// Runs `f` on a constraint and copies of its two bodies, then writes back the
/// velocity of each dynamic one (the only state a contact changes). A static or
/// kinematic body takes no impulse (its inverse mass is 0, so the solver would
/// store back the same bits), and not storing it keeps constraints that share
/// only such a body independent: the processor overlaps them instead of
/// waiting on a store that changes nothing. Skips (cannot happen for
/// constraints built this step, but must not panic) a body out of range or a
/// constraint of a body with itself.
#[inline(always)]
fn with_pair(
    bodies: &mut [SolverBody],
    c: &mut ContactConstraint,
    f: impl FnOnce(&mut ContactConstraint, &mut SolverBody, &mut SolverBody),
) {
    let (ia, ib) = (c.a as usize, c.b as usize);
    let (Some(&a), Some(&b)) = (bodies.get(ia), bodies.get(ib)) else { return };
    if ia == ib {
        return;
    }
    let (mut a, mut b) = (a, b);
    f(c, &mut a, &mut b);
    for (i, sb) in [(ia, a), (ib, b)] {
        if sb.dynamic {
            if let Some(dst) = bodies.get_mut(i) {
                dst.v = sb.v;
                dst.w = sb.w;
            }
        }
    }
}

/// Bodies `i` and `j`, mutably; `None` if they are the same or out of range.
#[inline(always)]
pub(crate) fn pair_at(
    bodies: &mut [SolverBody],
    i: u32,
    j: u32,
) -> Option<(&mut SolverBody, &mut SolverBody)> {
    let (i, j) = (i as usize, j as usize);
    if i < j {
        let (lo, hi) = bodies.split_at_mut(j);
        Some((lo.get_mut(i)?, hi.first_mut()?))
    } else if j < i {
        let (lo, hi) = bodies.split_at_mut(i);
        Some((hi.first_mut()?, lo.get_mut(j)?))
    } else {
        None
    }
}

/// Applies the previous sub-step's impulses again: all points' impulses summed
/// into one linear and one angular change per body. After the first sub-step,
/// `total` also adds them to the step's totals: they are what the sub-step
/// before ended with.
pub(crate) fn warm_start(
    bodies: &mut [SolverBody],
    constraints: &mut [ContactConstraint],
    reverse: bool,
    total: bool,
) {
    visit_all(constraints, reverse, false, |c| {
        with_pair(bodies, c, |c, a, b| warm_start_one(c, a, b, total))
    });
}

/// How many constraints ahead of the one being solved [`visit_all`] touches:
/// on Box2D v3's 100-row pyramid 2 gains 12 %, 8 gains 14 %, 16 and (for
/// warm starting alone) 32 no more.
const AHEAD: usize = 8;

/// Runs `f` on every constraint, in order or in `reverse`, first reading one
/// value from each cache line of the constraint [`AHEAD`] places further on
/// (only the lines warm starting reads unless `whole`), so that the memory
/// system is already fetching it: in a scene whose constraints do not fit in
/// cache each pass streams them from memory, and the processor's own prefetch
/// does not look far enough ahead at this stride.
#[inline(always)]
fn visit_all(
    constraints: &mut [ContactConstraint],
    reverse: bool,
    whole: bool,
    mut f: impl FnMut(&mut ContactConstraint),
) {
    let n = constraints.len();
    for k in 0..n {
        let i = if reverse { n.wrapping_sub(1).wrapping_sub(k) } else { k };
        let ahead = if reverse { i.checked_sub(AHEAD) } else { i.checked_add(AHEAD) };
        if let Some(c) = ahead.and_then(|j| constraints.get(j)) {
            let [i0, i1] = &c.impulses;
            core::hint::black_box((c.a, i0.normal_impulse, i1.tangent_impulse));
            if whole {
                let [p0, p1] = &c.points;
                core::hint::black_box((c.normal.x, p0.base_separation, p0.max_normal_impulse, p1.rt[0]));
            }
        }
        if let Some(c) = constraints.get_mut(i) {
            f(c);
        }
    }
}

/// [`warm_start`] on one constraint.
fn warm_start_one(c: &mut ContactConstraint, a: &mut SolverBody, b: &mut SolverBody, total: bool) {
    let (mut sn, mut st, mut wa, mut wb) = (ZERO, ZERO, ZERO, ZERO);
    let count = usize::from(c.count);
    for ci in c.impulses.iter_mut().take(count) {
        let (ln, lt) = (ci.normal_impulse, ci.tangent_impulse);
        if total {
            ci.total_normal_impulse += ln;
        }
        sn += ln;
        st += lt;
        wa = wa + ci.irn[0] * ln + ci.irt[0] * lt;
        wb = wb + ci.irn[1] * ln + ci.irt[1] * lt;
    }
    a.v -= c.n_m[0] * sn + c.t_m[0] * st;
    a.w -= wa;
    b.v += c.n_m[1] * sn + c.t_m[1] * st;
    b.w += wb;
}

/// One sweep over every constraint, in pair order or in `reverse`.
pub(crate) fn solve(
    bodies: &mut [SolverBody],
    constraints: &mut [ContactConstraint],
    params: &StepParams,
    use_bias: bool,
    reverse_points: bool,
    reverse: bool,
) {
    visit_all(constraints, reverse, true, |c| {
        with_pair(bodies, c, |c, a, b| solve_one(c, a, b, params, use_bias, reverse_points));
    });
}

/// The restitution pass, iterated: one Gauss-Seidel pass over a two-point
/// manifold leaves the first point bouncing faster than the second (the second
/// point's impulse feeds back through the rotation), which spins a box that hit
/// a wall square-on. Each further pass shrinks that error by the coupling ratio
/// squared (≈ 0.2 for a box), so `RESTITUTION_ITERATIONS` passes make the bounce
/// symmetric to a fraction of a percent.
///
/// Each constraint then goes back to its arbiter ([`store`]) in the same pass:
/// a constraint's impulses are final once its own restitution is done.
pub(crate) fn restitute_and_store(
    bodies: &mut [SolverBody],
    constraints: &mut [ContactConstraint],
    arbiters: &mut [Arbiter],
    threshold: Scalar,
) {
    visit_all(constraints, false, true, |c| {
        let Some(arb) = arbiters.get_mut(arbiter_index(c)) else { return };
        let e = arb.restitution;
        if e != ZERO {
            with_pair(bodies, c, |c, a, b| restitute(c, a, b, e, threshold));
        }
        store(c, arb);
    });
}

/// [`restitute_and_store`]'s restitution on one constraint.
fn restitute(
    c: &mut ContactConstraint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    e: Scalar,
    threshold: Scalar,
) {
    const RESTITUTION_ITERATIONS: u32 = 4;
    let (n, n_m) = (c.normal, c.n_m);
    for _ in 0..RESTITUTION_ITERATIONS {
        for (cp, ci) in c.points_mut() {
            if cp.relative_velocity > -threshold || cp.max_normal_impulse == ZERO {
                continue;
            }
            let vn = relative_speed(a, b, n, cp.rn);
            let target = vn + e * cp.relative_velocity;
            let impulse = -(cp.normal_mass * target);
            let new = (ci.normal_impulse + impulse).max(ZERO);
            let applied = set_normal(cp, ci, new);
            apply_along(a, b, n_m, ci.irn, applied);
        }
    }
}

/// mA + mB + iA·(rA × d)² + iB·(rB × d)²: the inverse of the mass the pair
/// presents to an impulse along `d` at anchors `ra`, `rb` (0 if infinite).
#[allow(clippy::too_many_arguments)]
fn mass_matrix(
    ma: Scalar,
    mb: Scalar,
    ia: Scalar,
    ib: Scalar,
    ra: Vector2,
    rb: Vector2,
    d: Vector2,
) -> Scalar {
    let (rda, rdb) = (ra.cross(d), rb.cross(d));
    ma + mb + ia * (rda * rda) + ib * (rdb * rdb)
}

/// The inverse of the 2×2 normal mass matrix K of a two-point manifold, `[a, b, d]`
/// for the symmetric `[[a, b], [b, d]]`, when K is well conditioned
/// (k11² < 1000·det K, Box2D's test); otherwise `None` and the points are solved
/// one at a time.
fn block_inverse(c: &ContactConstraint) -> Option<[Scalar; 3]> {
    if c.count != 2 {
        return None;
    }
    let [p1, p2] = &c.points;
    let (k11, k22, k12) = (p1.normal_k, p2.normal_k, c.k12);
    let det = k11 * k22 - k12 * k12;
    if det <= ZERO || k11 * k11 >= det * Scalar::from_int(1000) {
        return None;
    }
    let inv = det.recip();
    Some([k22 * inv, -k12 * inv, k11 * inv])
}

/// The inverse of the symmetric 2×2 matrix with diagonal entries 1/`u1`, 1/`u2`
/// and off-diagonal entry `k12`, `[a, b, d]` as in [`block_inverse`], or `None`
/// when it is singular. Formed from the inverses of the diagonal entries so that no product
/// of two diagonal entries (which can be large for light bodies) is needed:
/// K⁻¹ = 1/(1 − ρ) · [u1, −k12·u1·u2; −k12·u1·u2, u2] with ρ = k12²·u1·u2.
fn inverse_from_diagonal_inverses(u1: Scalar, u2: Scalar, k12: Scalar) -> Option<[Scalar; 3]> {
    let (a, b) = (k12 * u1, k12 * u2);
    let rest = scalar::ONE - a * b;
    if rest <= ZERO {
        return None;
    }
    let m = rest.recip();
    let off = -(a * u2 * m);
    Some([u1 * m, off, u2 * m])
}

/// Solves both normal points of a two-point manifold together. A sequential
/// sweep over the two points leaves the first with more impulse than the second,
/// which tilts stacked boxes a little every step; the block solve has no
/// favourite.
///
/// Box2D's soft update of one point, Δλᵢ = −mᵢ·(s_m·(vᵢ + biasᵢ) + s_i·kᵢᵢ·λᵢ)
/// with mᵢ = 1/kᵢᵢ, is exactly one Gauss-Seidel step (relaxation s_m + s_i = 1)
/// on the soft system (K + Γ)·Δλ = −(v + bias + Γ·λ) with Γ = diag(s_i/s_m·kᵢᵢ):
/// each point is its own spring, and at rest it is compressed by kᵢᵢ·λᵢ/(h·ω²).
/// This solves that same 2×2 system exactly. K + Γ is K with its diagonal
/// divided by s_m (a speculative or unbiased point has s_m = 1, Γᵢ = 0), so
/// the new accumulated impulses x solve the linear complementarity problem
/// x ≥ 0, g = q + (K + Γ)·x ≥ 0, xᵢ·gᵢ = 0 with q = v + bias − K·λ. The four
/// cases (both push, only the first, only the second, neither) are tried in
/// turn, as in Box2D v2.4's block solver. Without bias this is the rigid block
/// solve.
///
/// An earlier form, x = (1 − s_i)·λ − s_m·K⁻¹·(v + bias), is the exact solve
/// of Γ = s_i/s_m·K instead: springs coupled through K. Pressed evenly, such a
/// pair is compressed by (k₁₁ + k₁₂)·λ/(h·ω²) per point instead of k₁₁·λ/(h·ω²):
/// stiffer than Box2D's for a box centred on a box (k₁₁ = 5, k₁₂ = −1 per kg
/// for unit boxes; a 20-box stack sagged 0.108 m, against 0.135 m now), but
/// 1.57× softer for a box resting half over another (brick bond: k₁₁ = 3.5,
/// k₁₂ = +2). Box2D v3's large_pyramid sagged 1.13 m at rest with it (Box2D:
/// 0.73 m) and sags 0.73 m with this.
///
/// Returns false, changing nothing, when no case fits (round-off) or the
/// system is singular, so the caller can solve the points one at a time.
fn solve_block(c: &mut ContactConstraint, a: &mut SolverBody, b: &mut SolverBody, terms: [Terms; 2]) -> bool {
    let [(bias1, ms1, is1), (bias2, ms2, is2)] = terms;
    let n = c.normal;
    let ([p1, p2], [pi1, pi2]) = (&c.points, &c.impulses);
    let inv = match (is1 > ZERO, is2 > ZERO) {
        (false, false) => c.block,
        (true, true) => c.soft_block,
        // One point soft, one speculative: rare, formed here.
        _ => match inverse_from_diagonal_inverses(p1.normal_mass * ms1, p2.normal_mass * ms2, c.k12) {
            Some(inv) => inv,
            None => return false,
        },
    };
    let (l1, l2) = (pi1.normal_impulse, pi2.normal_impulse);
    let (k11, k22, k12) = (p1.normal_k, p2.normal_k, c.k12);
    let dvn = (b.v - a.v).dot(n);
    let v1 = dvn + b.w * p1.rn[1] - a.w * p1.rn[0];
    let v2 = dvn + b.w * p2.rn[1] - a.w * p2.rn[0];
    let q1 = v1 + bias1 - k11 * l1 - k12 * l2;
    let q2 = v2 + bias2 - k12 * l1 - k22 * l2;
    let [i11, i12, i22] = inv;
    // Case 1: both push.
    let x1 = -(i11 * q1 + i12 * q2);
    let x2 = -(i12 * q1 + i22 * q2);
    let x = if x1 >= ZERO && x2 >= ZERO {
        Some((x1, x2))
    } else {
        // Case 2: only the first pushes; the second must not be approaching.
        // The diagonal entry is k₁₁/s_m.
        let x1 = p1.normal_mass_div(q1) * ms1;
        if x1 >= ZERO && q2 + k12 * x1 >= ZERO {
            Some((x1, ZERO))
        } else {
            // Case 3: only the second pushes.
            let x2 = p2.normal_mass_div(q2) * ms2;
            if x2 >= ZERO && q1 + k12 * x2 >= ZERO {
                Some((ZERO, x2))
            } else if q1 >= ZERO && q2 >= ZERO {
                // Case 4: neither pushes.
                Some((ZERO, ZERO))
            } else {
                None
            }
        }
    };
    let Some((x1, x2)) = x else { return false };
    // Both impulses act along n: one linear update per body, two angular terms.
    let ([cp1, cp2], [ci1, ci2]) = (&mut c.points, &mut c.impulses);
    let d1 = accumulate_normal(cp1, ci1, v1, x1);
    let d2 = accumulate_normal(cp2, ci2, v2, x2);
    let d = d1 + d2;
    a.v -= c.n_m[0] * d;
    a.w = a.w - ci1.irn[0] * d1 - ci2.irn[0] * d2;
    b.v += c.n_m[1] * d;
    b.w = b.w + ci1.irn[1] * d1 + ci2.irn[1] * d2;
    true
}

impl PointConstraint {
    /// −q / k for the point's diagonal entry k (0 when k is 0).
    #[inline(always)]
    fn normal_mass_div(&self, q: Scalar) -> Scalar {
        -q.div_or_zero(self.normal_k)
    }
}

/// A sweep's update of a point's normal impulse: notes the approach speed `vn`
/// as the restitution reference ([`note_approach`]), then [`set_normal`].
#[inline(always)]
fn accumulate_normal(cp: &mut PointConstraint, ci: &mut PointImpulse, vn: Scalar, new: Scalar) -> Scalar {
    note_approach(cp, vn, new);
    set_normal(cp, ci, new)
}

/// Sets a point's accumulated normal impulse to `new` and keeps the step's
/// largest change; returns the change, which the caller applies. The one place
/// a sweep or the restitution pass changes a normal impulse.
#[inline(always)]
fn set_normal(cp: &mut PointConstraint, ci: &mut PointImpulse, new: Scalar) -> Scalar {
    let applied = new - ci.normal_impulse;
    ci.normal_impulse = new;
    cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
    applied
}

/// Keeps the fastest approach a pushing point has seen this step as its
/// restitution reference. The speed at the start of the step is not enough: with
/// speculative contacts a falling body meets the ground part-way through the step,
/// after gravity added up to g·dt more, and bouncing off the earlier speed would
/// lose that (a 2 % lower rebound from 10 m).
#[inline(always)]
fn note_approach(cp: &mut PointConstraint, vn: Scalar, new_impulse: Scalar) {
    if new_impulse > ZERO && vn < cp.relative_velocity {
        cp.relative_velocity = vn;
    }
}

/// A contact point's (bias velocity, mass scale, impulse scale) for one pass.
type Terms = (Scalar, Scalar, Scalar);

/// Relative velocity of the contact point along a direction, from the
/// precomputed arms: (vB − vA)·d + ωB·(rB × d) − ωA·(rA × d).
#[inline(always)]
fn relative_speed(a: &SolverBody, b: &SolverBody, d: Vector2, r: [Scalar; 2]) -> Scalar {
    (b.v - a.v).dot(d) + b.w * r[1] - a.w * r[0]
}

/// Applies an impulse of magnitude `lambda` along the direction whose
/// precomputed per-mass vectors are `m` and inertia-scaled arms are `ir`.
#[inline(always)]
fn apply_along(a: &mut SolverBody, b: &mut SolverBody, m: [Vector2; 2], ir: [Scalar; 2], lambda: Scalar) {
    a.v -= m[0] * lambda;
    a.w -= ir[0] * lambda;
    b.v += m[1] * lambda;
    b.w += ir[1] * lambda;
}

/// One pass over one constraint: normal points, then friction.
fn solve_one(
    c: &mut ContactConstraint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    params: &StepParams,
    use_bias: bool,
    reverse_points: bool,
) {
    let n = c.normal;
    let soft = if c.static_pair { params.static_soft } else { params.soft };
    let count = usize::from(c.count);
    // Bias and softness per point, from the current separation, linearised in
    // the rotation (4 products a point instead of 10):
    // s = s₀ + n·Δ(pB − pA) + ΔθB·(rB × n) − ΔθA·(rA × n). The neglected term,
    // (1 − cos Δθ)·|n·r| per body, only ever makes s smaller (a point on a convex
    // surface turning about the centre moves away from the tangent line), so the
    // estimate errs towards contact, never towards tunnelling; it is zero at rest,
    // and for a circle it is the exact answer (rotation does not move its surface).
    // The narrow phase measures the true separation again at the next step.
    let dpn = (b.p - a.p).dot(n);
    let mut terms: [Terms; 2] = [(ZERO, scalar::ONE, ZERO); 2];
    for (term, (cp, _)) in terms.iter_mut().zip(c.points()) {
        let s = cp.base_separation + dpn + b.angle * cp.rn[1] - a.angle * cp.rn[0];
        *term = if s > ZERO {
            // Speculative: allow closing the gap within this sub-step, no more.
            (s * params.inv_h, scalar::ONE, ZERO)
        } else if use_bias {
            let push = (s * soft.bias_rate).max(-params.push_speed);
            (push, soft.mass_scale, soft.impulse_scale)
        } else {
            (ZERO, scalar::ONE, ZERO)
        };
    }
    // Two-point manifolds are solved as a block; the point-by-point fallback
    // (ill-conditioned or round-off) alternates its order between sweeps so that
    // neither point is always first.
    let solved_together = c.has_block && solve_block(c, a, b, terms);
    if !solved_together {
        let order: [usize; 2] = if reverse_points && count == 2 { [1, 0] } else { [0, 1] };
        let n_m = c.n_m;
        for &i in order.iter().take(count) {
            let (Some(cp), Some(ci), Some(&(bias, mass_scale, impulse_scale))) =
                (c.points.get_mut(i), c.impulses.get_mut(i), terms.get(i))
            else {
                continue;
            };
            let vn = relative_speed(a, b, n, cp.rn);
            let impulse = -(cp.normal_mass * mass_scale * (vn + bias)) - impulse_scale * ci.normal_impulse;
            let new = (ci.normal_impulse + impulse).max(ZERO);
            let applied = accumulate_normal(cp, ci, vn, new);
            apply_along(a, b, n_m, ci.irn, applied);
        }
    }
    let t = n.right_perp();
    let (mu, t_m) = (c.friction, c.t_m);
    for (cp, ci) in c.points_mut() {
        let vt = relative_speed(a, b, t, cp.rt);
        let impulse = -(cp.tangent_mass * vt);
        let max_f = mu * ci.normal_impulse;
        let new = (ci.tangent_impulse + impulse).clamp(-max_f, max_f);
        let applied = new - ci.tangent_impulse;
        ci.tangent_impulse = new;
        apply_along(a, b, t_m, ci.irt, applied);
    }
}
