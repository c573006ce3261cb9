//! Building a contact's constraint once per step: the arms, the effective
//! masses and, for a two-point manifold, the inverse of its 2×2 mass matrix.
//!
//! Everything here is derived from the arbiter and the bodies at the start of
//! the step, so that the sweeps ([`super::solve`]) divide only in the rare
//! block of one soft and one speculative point.

use crate::arbiter::Arbiter;
use crate::body::Body;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;
use crate::solver::body::inverse_mass;
use crate::solver::Softness;

/// What warm starting needs of one contact point: its inertia-scaled arms and
/// accumulated impulses. Kept apart from the rest of the point (see
/// [`ContactConstraint`]'s layout).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PointImpulse {
    /// iA·(rA × n), iB·(rB × n) and iA·(rA × t), iB·(rB × t): the angular
    /// velocity change per unit impulse.
    pub(super) irn: [Scalar; 2],
    pub(super) irt: [Scalar; 2],
    pub(super) normal_impulse: Scalar,
    pub(super) tangent_impulse: Scalar,
    /// The step's sum of the impulses the point ended its sub-steps with, which
    /// equals the sum of every change applied (warm start plus each sweep's
    /// increment), added once per sub-step instead of once per change.
    pub(super) total_normal_impulse: Scalar,
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
pub(super) struct PointConstraint {
    /// Separation at the start of the step less n·(pB − pA) then, so that
    /// adding n·(pB − pA) now gives the separation after the bodies moved.
    pub(super) base_separation: Scalar,
    pub(super) normal_mass: Scalar,
    /// 1 / normal_mass: the diagonal entry of the block's mass matrix.
    pub(super) normal_k: Scalar,
    pub(super) tangent_mass: Scalar,
    /// The fastest approach seen this step (restitution reference).
    pub(super) relative_velocity: Scalar,
    /// rA × n, rB × n and rA × t, rB × t.
    pub(super) rn: [Scalar; 2],
    pub(super) rt: [Scalar; 2],
    pub(super) max_normal_impulse: Scalar,
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
    pub(super) a: u32,
    pub(super) b: u32,
    /// Index of the arbiter this came from (the write-back target).
    pub(super) arbiter: u32,
    pub(super) count: u8,
    /// One body has infinite mass: the stiffer static softness applies.
    pub(super) static_pair: bool,
    /// `block` and `soft_block` hold the two-point block solve's matrices; false
    /// for one point or an ill-conditioned pair.
    pub(super) has_block: bool,
    /// n·mA, n·mB, t·mA, t·mB: the linear velocity change per unit impulse.
    pub(super) n_m: [Vector2; 2],
    pub(super) t_m: [Vector2; 2],
    pub(super) impulses: [PointImpulse; 2],
    pub(super) normal: Vector2,
    pub(super) friction: Scalar,
    /// Off-diagonal entry of the normal mass matrix K.
    pub(super) k12: Scalar,
    /// The symmetric inverse of K, `[a, b, d]` for `[[a, b], [b, d]]`.
    pub(super) block: [Scalar; 3],
    /// The same for the soft system's matrix (the diagonal divided by the
    /// pair's mass scale; see [`solve_block`](super::solve::solve_block)) when both points are soft.
    pub(super) soft_block: [Scalar; 3],
    pub(super) points: [PointConstraint; 2],
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
    pub(super) fn points(&self) -> impl Iterator<Item = (&PointConstraint, &PointImpulse)> {
        self.points.iter().zip(self.impulses.iter()).take(usize::from(self.count))
    }

    /// The used points and their impulses, mutably.
    pub(super) fn points_mut(&mut self) -> impl Iterator<Item = (&mut PointConstraint, &mut PointImpulse)> {
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
pub(super) fn inverse_from_diagonal_inverses(u1: Scalar, u2: Scalar, k12: Scalar) -> Option<[Scalar; 3]> {
    let (a, b) = (k12 * u1, k12 * u2);
    let rest = scalar::ONE - a * b;
    if rest <= ZERO {
        return None;
    }
    let m = rest.recip();
    let off = -(a * u2 * m);
    Some([u1 * m, off, u2 * m])
}
