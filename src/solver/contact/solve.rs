//! The contact stages of each sub-step: the warm start and the sweeps, with
//! both points of a two-point manifold solved together as a 2×2 block.

use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::solver::{Bias, Row, SolverBody, Sweep};

use super::prepare::{
    inverse_from_diagonal_inverses, ContactConstraint, PointConstraint, PointImpulse, StepParams,
};

/// Runs `f` on a constraint and copies of its two bodies, then writes back the
/// velocity of each dynamic one (the only state a contact changes). A static or
/// kinematic body takes no impulse (its inverse mass is 0, so the solver would
/// store back the same bits), and not storing it keeps constraints that share
/// only such a body independent: the processor overlaps them instead of
/// waiting on a store that changes nothing. Skips (cannot happen for
/// constraints built this step, but must not panic) a body out of range or a
/// constraint of a body with itself.
#[inline(always)]
pub(super) fn with_pair(
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

/// Where the impulses a warm start applies again come from, which decides
/// whether they count towards the step's totals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Carried {
    /// The impulses the previous step ended with (the first sub-step): already
    /// in that step's totals.
    FromPreviousStep,
    /// The impulses the previous sub-step of this step ended with: added to
    /// the step's totals now.
    FromPreviousSubstep,
}

impl Carried {
    /// What sub-step `substep` (from 0) warm-starts from.
    pub(crate) fn for_substep(substep: u32) -> Self {
        if substep == 0 {
            Carried::FromPreviousStep
        } else {
            Carried::FromPreviousSubstep
        }
    }
}

/// Applies the previous sub-step's impulses again: all points' impulses summed
/// into one linear and one angular change per body. After the first sub-step
/// ([`Carried::FromPreviousSubstep`]) it also adds them to the step's totals:
/// they are what the sub-step before ended with.
pub(crate) fn warm_start(
    bodies: &mut [SolverBody],
    constraints: &mut [ContactConstraint],
    sweep: Sweep,
    carried: Carried,
) {
    visit_all(constraints, sweep, Prefetch::WarmStart, |c| {
        with_pair(bodies, c, |c, a, b| warm_start_one(c, a, b, carried))
    });
}

/// How many constraints ahead of the one being solved [`visit_all`] touches:
/// on Box2D v3's 100-row pyramid 2 gains 12 %, 8 gains 14 %, 16 and (for
/// warm starting alone) 32 no more.
const AHEAD: usize = 8;

/// Which cache lines of a constraint ahead [`visit_all`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Prefetch {
    /// Only the lines warm starting reads (the first three).
    WarmStart,
    /// Every line: the sweeps and the restitution pass read the whole record.
    Whole,
}

/// Runs `f` on every constraint in the `sweep`'s direction, first reading one
/// value from each cache line of the constraint [`AHEAD`] places further on
/// that `prefetch` names, so that the memory system is already fetching it: in
/// a scene whose constraints do not fit in cache each pass streams them from
/// memory, and the processor's own prefetch does not look far enough ahead at
/// this stride.
#[inline(always)]
pub(super) fn visit_all(
    constraints: &mut [ContactConstraint],
    sweep: Sweep,
    prefetch: Prefetch,
    mut f: impl FnMut(&mut ContactConstraint),
) {
    let n = constraints.len();
    let reverse = sweep == Sweep::Reverse;
    for k in 0..n {
        let i = if reverse { n.wrapping_sub(1).wrapping_sub(k) } else { k };
        let ahead = if reverse { i.checked_sub(AHEAD) } else { i.checked_add(AHEAD) };
        if let Some(c) = ahead.and_then(|j| constraints.get(j)) {
            let [i0, i1] = &c.impulses;
            core::hint::black_box((c.a, i0.normal_impulse, i1.tangent_impulse));
            if prefetch == Prefetch::Whole {
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
fn warm_start_one(c: &mut ContactConstraint, a: &mut SolverBody, b: &mut SolverBody, carried: Carried) {
    let (mut sn, mut st, mut wa, mut wb) = (ZERO, ZERO, ZERO, ZERO);
    let count = usize::from(c.count);
    for ci in c.impulses.iter_mut().take(count) {
        let (ln, lt) = (ci.normal_impulse, ci.tangent_impulse);
        if carried == Carried::FromPreviousSubstep {
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

/// One sweep over every constraint, in pair order or in reverse, with the
/// position bias or without (relax).
pub(crate) fn solve(
    bodies: &mut [SolverBody],
    constraints: &mut [ContactConstraint],
    params: &StepParams,
    bias: Bias,
    sweep: Sweep,
) {
    visit_all(constraints, sweep, Prefetch::Whole, |c| {
        with_pair(bodies, c, |c, a, b| solve_one(c, a, b, params, bias, sweep));
    });
}

/// Solves both normal points of a two-point manifold together. Solving the two
/// points one after the other leaves the first with more impulse than the
/// second, which tilts stacked boxes a little every step; the block solve has
/// no favourite.
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
fn solve_block(c: &mut ContactConstraint, a: &mut SolverBody, b: &mut SolverBody, rows: [Row; 2]) -> bool {
    let [r1, r2] = rows;
    let n = c.normal;
    let ([p1, p2], [pi1, pi2]) = (&c.points, &c.impulses);
    let inv = match (r1.impulse_scale > ZERO, r2.impulse_scale > ZERO) {
        (false, false) => c.block,
        (true, true) => c.soft_block,
        // One point soft, one speculative: rare, formed here.
        _ => match inverse_from_diagonal_inverses(
            p1.normal_mass * r1.mass_scale,
            p2.normal_mass * r2.mass_scale,
            c.k12,
        ) {
            Some(inv) => inv,
            None => return false,
        },
    };
    let (l1, l2) = (pi1.normal_impulse, pi2.normal_impulse);
    let (k11, k22, k12) = (p1.normal_k, p2.normal_k, c.k12);
    let dvn = (b.v - a.v).dot(n);
    let v1 = dvn + b.w * p1.rn[1] - a.w * p1.rn[0];
    let v2 = dvn + b.w * p2.rn[1] - a.w * p2.rn[0];
    let q1 = v1 + r1.bias - k11 * l1 - k12 * l2;
    let q2 = v2 + r2.bias - k12 * l1 - k22 * l2;
    let [i11, i12, i22] = inv;
    // Case 1: both push.
    let x1 = -(i11 * q1 + i12 * q2);
    let x2 = -(i12 * q1 + i22 * q2);
    let x = if x1 >= ZERO && x2 >= ZERO {
        Some((x1, x2))
    } else {
        // Case 2: only the first pushes; the second must not be approaching.
        // The diagonal entry is k₁₁/s_m.
        let x1 = p1.normal_mass_div(q1) * r1.mass_scale;
        if x1 >= ZERO && q2 + k12 * x1 >= ZERO {
            Some((x1, ZERO))
        } else {
            // Case 3: only the second pushes.
            let x2 = p2.normal_mass_div(q2) * r2.mass_scale;
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
pub(super) fn set_normal(cp: &mut PointConstraint, ci: &mut PointImpulse, new: Scalar) -> Scalar {
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

/// Relative velocity of the contact point along a direction, from the
/// precomputed arms: (vB − vA)·d + ωB·(rB × d) − ωA·(rA × d).
#[inline(always)]
pub(super) fn relative_speed(a: &SolverBody, b: &SolverBody, d: Vector2, r: [Scalar; 2]) -> Scalar {
    (b.v - a.v).dot(d) + b.w * r[1] - a.w * r[0]
}

/// Applies an impulse of magnitude `lambda` along the direction whose
/// precomputed per-mass vectors are `m` and inertia-scaled arms are `ir`.
#[inline(always)]
pub(super) fn apply_along(
    a: &mut SolverBody,
    b: &mut SolverBody,
    m: [Vector2; 2],
    ir: [Scalar; 2],
    lambda: Scalar,
) {
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
    bias: Bias,
    sweep: Sweep,
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
    let mut rows = [Row::RIGID; 2];
    for (row, (cp, _)) in rows.iter_mut().zip(c.points()) {
        let s = cp.base_separation + dpn + b.angle * cp.rn[1] - a.angle * cp.rn[0];
        *row = if s > ZERO {
            // Speculative: allow closing the gap within this sub-step, no more.
            Row::speculative(s, params.inv_h)
        } else {
            soft.row(s, bias).pushing_at_most(params.push_speed)
        };
    }
    // Two-point manifolds are solved as a block; the point-by-point fallback
    // (ill-conditioned or round-off) takes the points in the sweep's direction,
    // which alternates, so that neither point is always first.
    let solved_together = c.has_block && solve_block(c, a, b, rows);
    if !solved_together {
        let order: [usize; 2] = if sweep == Sweep::Reverse && count == 2 { [1, 0] } else { [0, 1] };
        let n_m = c.n_m;
        for &i in order.iter().take(count) {
            let (Some(cp), Some(ci), Some(row)) = (c.points.get_mut(i), c.impulses.get_mut(i), rows.get(i))
            else {
                continue;
            };
            let vn = relative_speed(a, b, n, cp.rn);
            let impulse = row.impulse(cp.normal_mass, vn, ci.normal_impulse);
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
