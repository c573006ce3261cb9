//! After the last sub-step: the bounce of contacts that approached fast
//! enough, and the write-back of every constraint's impulses to its arbiter.

use crate::arbiter::Arbiter;
use crate::math::scalar::{Scalar, ZERO};
use crate::solver::{SolverBody, Sweep};

use super::prepare::ContactConstraint;
use super::solve::{apply_along, relative_speed, set_normal, visit_all, with_pair, Prefetch};

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
    visit_all(constraints, Sweep::Forward, Prefetch::Whole, |c| {
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

/// Copies what outlives the step back into the arbiter: the impulses that warm-start
/// the next step and the totals a game reads. The total gets the impulse the
/// last sub-step (and the restitution pass) ended with here; see
/// [`PointImpulse::total_normal_impulse`](super::prepare::PointImpulse::total_normal_impulse).
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
