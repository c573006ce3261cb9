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
//!    from closing the gap within the sub-step), in pair order, with both points
//!    of a two-point manifold solved together as a 2×2 block (an exact linear
//!    complementarity solve, as in Box2D v2.4),
//! 4. integrates positions,
//! 5. relaxes: two sweeps without the position bias, forward then in reverse pair
//!    order (symmetric Gauss-Seidel), so the push-out does not leave energy behind.
//!
//! These choices were measured on `tests/quality.rs`, not picked for looks: with
//! one-way sweeps a symmetric pyramid creeps sideways (16 mm in 10 s); solving the
//! two points of a manifold one after the other lets a 20-box stack topple (the
//! first point always takes more); a single relax sweep leaves a 4-box column
//! recovering from overlap at 3.4 m/s and a pyramid jittering at 2 cm/s after 10 s.
//! The second relax sweep costs about 13 % of the step.
//!
//! After the last sub-step a restitution pass gives contacts that approached
//! faster than `restitution_threshold` their bounce, e·v.
//!
//! The contact separation is re-evaluated in every sub-step from the bodies' current
//! positions and rotations (anchors are kept in each body's local frame), so no
//! collision detection runs inside the loop. Everything iterates in the canonical
//! arbiter order and body-slot order.

use crate::arbiter::{Arbiter, ContactPoint};
use crate::body::{Body, BodyType};
use crate::math::scalar::ScalarExt as _;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;
use crate::world::World;

/// Soft-constraint coefficients for one sub-step length (Box2D's `b2Softness`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Softness {
    pub(crate) bias_rate: Scalar,
    pub(crate) mass_scale: Scalar,
    pub(crate) impulse_scale: Scalar,
}

impl Softness {
    /// A spring of `hertz` and damping ratio `zeta`, discretised for sub-step `h`.
    pub(crate) fn new(hertz: Scalar, zeta: Scalar, h: Scalar) -> Self {
        if hertz == ZERO {
            return Self { bias_rate: ZERO, mass_scale: scalar::ONE, impulse_scale: ZERO };
        }
        let omega = scalar::TAU.sat_mul(hertz);
        let a1 = zeta.sat_mul(scalar::TWO).saturating_add(h.sat_mul(omega));
        let a2 = h.sat_mul(omega).sat_mul(a1);
        let a3 = scalar::recip(scalar::ONE.saturating_add(a2));
        Self { bias_rate: scalar::div(omega, a1), mass_scale: a2.sat_mul(a3), impulse_scale: a3 }
    }
}

/// Per-step solver settings.
#[derive(Clone, Copy, Debug)]
struct StepParams {
    inv_h: Scalar,
    soft: Softness,
    static_soft: Softness,
    push_speed: Scalar,
}

/// Inverse mass and inertia a body contributes to a contact (0 unless dynamic).
pub(crate) fn inverse_mass(b: &Body) -> (Scalar, Scalar) {
    if b.body_type == BodyType::Dynamic {
        (b.mass.inv_mass, b.mass.inv_inertia)
    } else {
        (ZERO, ZERO)
    }
}

impl World<'_> {
    /// Solves the contacts and advances positions for a step of `dt`.
    pub(crate) fn solve_and_integrate(&mut self, dt: Scalar) {
        let n = self.def.substeps.max(1);
        let inv_n = scalar::recip(Scalar::from_num(n));
        let h = dt.sat_mul(inv_n);
        let inv_h = scalar::recip(h);
        // Box2D caps the contact stiffness at a quarter of the sub-step rate.
        let hertz = self.def.contact_hertz.min(inv_h.sat_mul(Scalar::lit("0.25")));
        let zeta = self.def.contact_damping_ratio;
        let params = StepParams {
            inv_h,
            soft: Softness::new(hertz, zeta, h),
            static_soft: Softness::new(hertz.sat_mul(scalar::TWO), zeta, h),
            push_speed: self.def.contact_push_speed,
        };
        self.prepare_contacts();
        self.prepare_constraints(dt, h);
        // Each sub-step gets 1/n of the generators' velocity change.
        for (_, b) in self.bodies.iter_mut() {
            b.pending_v = b.pending_v * inv_n;
            b.pending_w = b.pending_w.sat_mul(inv_n);
        }
        let (vmax, wmax) = (self.def.max_linear_speed, self.angular_limit(dt));
        for substep in 0..n {
            for (_, b) in self.bodies.iter_mut() {
                if b.is_dynamic() && !b.out_of_bounds {
                    b.linear_velocity += b.pending_v;
                    b.angular_velocity = b.angular_velocity.saturating_add(b.pending_w);
                }
            }
            self.for_each_joint(|j, a, b| j.warm_start(a, b));
            self.warm_start();
            self.for_each_joint(|j, a, b| j.solve(a, b, h, true));
            self.solve_user_constraints(h);
            self.solve_contacts(&params, true, false, false);
            for (_, b) in self.bodies.iter_mut() {
                if b.is_awake_mover() {
                    // Component clamps are cheap and bound the displacement; the
                    // exact speed limit is applied once at the end of the step.
                    let v = b.linear_velocity;
                    b.linear_velocity =
                        Vector2::new(scalar::clamp(v.x, -vmax, vmax), scalar::clamp(v.y, -vmax, vmax));
                    b.angular_velocity = scalar::clamp(b.angular_velocity, -wmax, wmax);
                    b.position += b.linear_velocity * h;
                    b.rotation = b.rotation.integrate(b.angular_velocity.sat_mul(h));
                }
            }
            // Relax: a symmetric Gauss-Seidel pair of sweeps, forward then back.
            self.for_each_joint_in(true, |j, a, b| j.solve(a, b, h, false));
            self.solve_contacts(&params, false, substep % 2 == 1, false);
            self.solve_contacts(&params, false, substep % 2 == 0, true);
        }
        self.apply_restitution();
        for (_, j) in self.joints.iter_mut() {
            j.broken = j.finish_step();
        }
        for (_, b) in self.bodies.iter_mut() {
            b.pending_v = Vector2::ZERO;
            b.pending_w = ZERO;
        }
    }

    /// Runs `f` on every joint with its two bodies, in joint-slot order. A joint
    /// to a world point gets a static stand-in body for B.
    fn for_each_joint(&mut self, f: impl FnMut(&mut crate::constraint::Joint, &mut Body, &mut Body)) {
        self.for_each_joint_in(false, f);
    }

    /// [`World::for_each_joint`] in slot order or in `reverse`.
    fn for_each_joint_in(
        &mut self,
        reverse: bool,
        mut f: impl FnMut(&mut crate::constraint::Joint, &mut Body, &mut Body),
    ) {
        let World { bodies, joints, .. } = self;
        let used = joints.slots_used();
        for k in 0..used {
            let i = if reverse { used.saturating_sub(1).saturating_sub(k) } else { k };
            let Some(j) = joints.get_at_mut(i) else { continue };
            let ia = j.def.body_a.index();
            match j.def.body_b {
                Some(hb) => {
                    if let Some((a, b)) = bodies.get2_at_mut(ia, hb.index()) {
                        f(j, a, b);
                    }
                }
                None => {
                    let mut ground = crate::constraint::ground();
                    ground.position = Vector2::ZERO;
                    if let Some(a) = bodies.get_at_mut(ia) {
                        f(j, a, &mut ground);
                    }
                }
            }
        }
    }

    /// Once per step: joint masses and softness; the game's `prepare`.
    fn prepare_constraints(&mut self, dt: Scalar, h: Scalar) {
        let World { bodies, joints, constraints, .. } = self;
        let ground = crate::constraint::ground();
        for (_, j) in joints.iter_mut() {
            let b = j.def.body_b.and_then(|hb| bodies.get(hb)).unwrap_or(&ground);
            if let Some(a) = bodies.get(j.def.body_a) {
                j.prepare(a, b, h);
            }
        }
        for (_, c) in constraints.iter_mut() {
            let b = c.body_b.and_then(|hb| bodies.get(hb)).unwrap_or(&ground);
            if let Some(a) = bodies.get(c.body_a) {
                c.constraint.prepare(a, b, dt);
            }
        }
    }

    /// The game's constraints, once per sub-step, in registration order.
    fn solve_user_constraints(&mut self, h: Scalar) {
        let World { bodies, constraints, .. } = self;
        for (_, c) in constraints.iter_mut() {
            let ia = c.body_a.index();
            match c.body_b {
                Some(hb) => {
                    if let Some((a, b)) = bodies.get2_at_mut(ia, hb.index()) {
                        c.constraint.solve(a, b, h);
                    }
                }
                None => {
                    let mut ground = crate::constraint::ground();
                    if let Some(a) = bodies.get_at_mut(ia) {
                        c.constraint.solve(a, &mut ground, h);
                    }
                }
            }
        }
    }

    /// Anchors in each body's frame, effective masses, approach speeds.
    fn prepare_contacts(&mut self) {
        let World { bodies, contacts, .. } = self;
        for arb in contacts.live_mut() {
            if !arb.solve {
                continue;
            }
            let (Some(a), Some(b)) = (bodies.get(arb.body_a), bodies.get(arb.body_b)) else {
                arb.solve = false;
                continue;
            };
            let ((ma, ia), (mb, ib)) = (inverse_mass(a), inverse_mass(b));
            let n = arb.normal;
            let t = n.right_perp();
            let count = usize::from(arb.count);
            for cp in arb.points.iter_mut().take(count) {
                let (ra, rb) = (cp.anchor_a, cp.anchor_b);
                cp.local_a = a.rotation.inv_rotate(ra);
                cp.local_b = b.rotation.inv_rotate(rb);
                cp.normal_mass = effective_mass(ma, mb, ia, ib, ra, rb, n);
                cp.tangent_mass = effective_mass(ma, mb, ia, ib, ra, rb, t);
                let dv = b.velocity_at_offset(rb) - a.velocity_at_offset(ra);
                cp.relative_velocity = dv.dot(n);
                cp.rn = [ra.cross(n), rb.cross(n)];
                cp.rt = [ra.cross(t), rb.cross(t)];
                cp.irn = [ia.sat_mul(cp.rn[0]), ib.sat_mul(cp.rn[1])];
                cp.irt = [ia.sat_mul(cp.rt[0]), ib.sat_mul(cp.rt[1])];
                cp.total_normal_impulse = ZERO;
                cp.max_normal_impulse = ZERO;
            }
            arb.k12 = ma.saturating_add(mb);
            let [p1, p2] = &arb.points;
            arb.k12 = arb
                .k12
                .saturating_add(p1.irn[0].sat_mul(p2.rn[0]))
                .saturating_add(p1.irn[1].sat_mul(p2.rn[1]));
            arb.block = block_inverse(arb);
            arb.n_m = [n * ma, n * mb];
            arb.t_m = [t * ma, t * mb];
            arb.inv_mass = [ma, mb];
            arb.inv_inertia = [ia, ib];
            arb.static_pair = ma == ZERO || mb == ZERO;
        }
    }

    fn warm_start(&mut self) {
        let World { bodies, contacts, .. } = self;
        for arb in contacts.live_mut() {
            if !arb.solve {
                continue;
            }
            let Some((a, b)) = bodies.get2_at_mut(arb.body_a.index(), arb.body_b.index()) else { continue };
            let ([ma, mb], [ia, ib]) = (arb.inv_mass, arb.inv_inertia);
            let (n, t) = (arb.normal, arb.normal.right_perp());
            let count = usize::from(arb.count);
            for cp in arb.points.iter_mut().take(count) {
                let p = n * cp.normal_impulse + t * cp.tangent_impulse;
                cp.total_normal_impulse = cp.total_normal_impulse.saturating_add(cp.normal_impulse);
                apply(a, b, ma, ia, mb, ib, cp.anchor_a, cp.anchor_b, p);
            }
        }
    }

    /// One sweep over every solved contact, in pair order or in `reverse`.
    fn solve_contacts(&mut self, params: &StepParams, use_bias: bool, reverse_points: bool, reverse: bool) {
        let World { bodies, contacts, .. } = self;
        let live = contacts.live_mut();
        let mut visit = |arb: &mut Arbiter| {
            if arb.solve {
                if let Some((a, b)) = bodies.get2_at_mut(arb.body_a.index(), arb.body_b.index()) {
                    solve_one(arb, a, b, params, use_bias, reverse_points);
                }
            }
        };
        if reverse {
            live.iter_mut().rev().for_each(&mut visit);
        } else {
            live.iter_mut().for_each(&mut visit);
        }
    }

    /// The restitution pass, iterated: one Gauss-Seidel pass over a two-point
    /// manifold leaves the first point bouncing faster than the second (the second
    /// point's impulse feeds back through the rotation), which spins a box that hit
    /// a wall square-on. Each further pass shrinks that error by the coupling ratio
    /// squared (≈ 0.2 for a box), so `RESTITUTION_ITERATIONS` passes make the bounce
    /// symmetric to a fraction of a percent.
    fn apply_restitution(&mut self) {
        const RESTITUTION_ITERATIONS: u32 = 4;
        let threshold = self.def.restitution_threshold;
        let World { bodies, contacts, .. } = self;
        for arb in contacts.live_mut() {
            if !arb.solve || arb.restitution == ZERO {
                continue;
            }
            let Some((a, b)) = bodies.get2_at_mut(arb.body_a.index(), arb.body_b.index()) else { continue };
            let ([ma, mb], [ia, ib]) = (arb.inv_mass, arb.inv_inertia);
            let (n, e) = (arb.normal, arb.restitution);
            let count = usize::from(arb.count);
            for _ in 0..RESTITUTION_ITERATIONS {
                for cp in arb.points.iter_mut().take(count) {
                    if cp.relative_velocity > threshold.saturating_neg() || cp.max_normal_impulse == ZERO {
                        continue;
                    }
                    let vn = (b.velocity_at_offset(cp.anchor_b) - a.velocity_at_offset(cp.anchor_a)).dot(n);
                    let target = vn.saturating_add(e.sat_mul(cp.relative_velocity));
                    let impulse = cp.normal_mass.sat_mul(target).saturating_neg();
                    let new = cp.normal_impulse.saturating_add(impulse).max(ZERO);
                    let applied = new.saturating_sub(cp.normal_impulse);
                    cp.normal_impulse = new;
                    cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
                    cp.total_normal_impulse = cp.total_normal_impulse.saturating_add(applied);
                    apply(a, b, ma, ia, mb, ib, cp.anchor_a, cp.anchor_b, n * applied);
                }
            }
        }
    }

    /// The angular speed limit for a step: the configured one, and at most a
    /// quarter turn per step.
    pub(crate) fn angular_limit(&self, dt: Scalar) -> Scalar {
        let quarter_turn = scalar::div(scalar::FRAC_PI_2.sat_mul(scalar::HALF), dt);
        self.def.max_angular_speed.min(quarter_turn)
    }
}

/// 1 / (mA + mB + iA·(rA × d)² + iB·(rB × d)²): the inverse of the mass the
/// pair presents to an impulse along `d` at anchors `ra`, `rb` (0 if infinite).
#[allow(clippy::too_many_arguments)]
fn effective_mass(
    ma: Scalar,
    mb: Scalar,
    ia: Scalar,
    ib: Scalar,
    ra: Vector2,
    rb: Vector2,
    d: Vector2,
) -> Scalar {
    let (rda, rdb) = (ra.cross(d), rb.cross(d));
    let k = ma
        .saturating_add(mb)
        .saturating_add(ia.sat_mul(rda.sat_mul(rda)))
        .saturating_add(ib.sat_mul(rdb.sat_mul(rdb)));
    scalar::recip(k)
}

/// Applies impulse `p` at anchors `ra` (to A, negated) and `rb` (to B).
#[allow(clippy::too_many_arguments)]
#[inline]
fn apply(
    a: &mut Body,
    b: &mut Body,
    ma: Scalar,
    ia: Scalar,
    mb: Scalar,
    ib: Scalar,
    ra: Vector2,
    rb: Vector2,
    p: Vector2,
) {
    a.linear_velocity -= p * ma;
    a.angular_velocity = a.angular_velocity.saturating_sub(ia.sat_mul(ra.cross(p)));
    b.linear_velocity += p * mb;
    b.angular_velocity = b.angular_velocity.saturating_add(ib.sat_mul(rb.cross(p)));
}

/// The inverse of the 2×2 normal mass matrix K of a two-point manifold,
/// `[a, c, b, d]` by columns, when K is well conditioned (k11² < 1000·det K, Box2D's
/// test); otherwise `None` and the points are solved one at a time.
fn block_inverse(arb: &Arbiter) -> Option<[Scalar; 4]> {
    if arb.count != 2 {
        return None;
    }
    let [p1, p2] = &arb.points;
    let k11 = scalar::recip(p1.normal_mass);
    let k22 = scalar::recip(p2.normal_mass);
    let k12 = arb.k12;
    let det = k11.sat_mul(k22).saturating_sub(k12.sat_mul(k12));
    if det <= ZERO || k11.sat_mul(k11) >= det.sat_mul(Scalar::const_from_int(1000)) {
        return None;
    }
    let inv = scalar::recip(det);
    Some([
        k22.sat_mul(inv),
        k12.saturating_neg().sat_mul(inv),
        k12.saturating_neg().sat_mul(inv),
        k11.sat_mul(inv),
    ])
}

/// Solves both normal points of a two-point manifold together: the soft update
/// with the full 2×2 mass matrix K instead of its diagonal. A sequential sweep over
/// the two points leaves the first with more impulse than the second, which tilts
/// stacked boxes a little every step; the block solve has no favourite.
///
/// With r = v_n + bias (current velocities), the new accumulated impulses x solve
/// the linear complementarity problem x ≥ 0, g = q + K·x ≥ 0, xᵢ·gᵢ = 0 with
/// q = s_m·r − (1 − s_i)·K·λ; when both points push this is exactly
/// x = (1 − s_i)·λ − s_m·K⁻¹·r, Box2D's soft update. The four cases (both push,
/// only the first, only the second, neither) are tried in turn, as in Box2D v2.4's
/// block solver. Returns false, changing nothing, when no case fits (round-off)
/// so the caller can solve the points one at a time.
fn solve_block(arb: &mut Arbiter, a: &mut Body, b: &mut Body, inv: [Scalar; 4], terms: [Terms; 2]) -> bool {
    let [(bias1, ms1, is1), (bias2, ms2, is2)] = terms;
    let n = arb.normal;
    let [p1, p2] = &arb.points;
    let (l1, l2) = (p1.normal_impulse, p2.normal_impulse);
    let k11 = scalar::recip(p1.normal_mass);
    let k22 = scalar::recip(p2.normal_mass);
    let k12 = arb.k12;
    let (v1, v2) = (relative_speed(a, b, n, p1.rn), relative_speed(a, b, n, p2.rn));
    let (r1, r2) = (v1.saturating_add(bias1), v2.saturating_add(bias2));
    // Each point keeps its own softness (a speculative point is rigid).
    let (keep1, keep2) = (scalar::ONE.saturating_sub(is1), scalar::ONE.saturating_sub(is2));
    let q1 = ms1.sat_mul(r1).saturating_sub(keep1.sat_mul(k11.sat_mul(l1).saturating_add(k12.sat_mul(l2))));
    let q2 = ms2.sat_mul(r2).saturating_sub(keep2.sat_mul(k12.sat_mul(l1).saturating_add(k22.sat_mul(l2))));
    let [i11, i21, i12, i22] = inv;
    // Case 1: both push.
    let x1 = i11.sat_mul(q1).saturating_add(i12.sat_mul(q2)).saturating_neg();
    let x2 = i21.sat_mul(q1).saturating_add(i22.sat_mul(q2)).saturating_neg();
    let x = if x1 >= ZERO && x2 >= ZERO {
        Some((x1, x2))
    } else {
        // Case 2: only the first pushes; the second must not be approaching.
        let x1 = scalar::div(q1, k11).saturating_neg();
        if x1 >= ZERO && q2.saturating_add(k12.sat_mul(x1)) >= ZERO {
            Some((x1, ZERO))
        } else {
            // Case 3: only the second pushes.
            let x2 = scalar::div(q2, k22).saturating_neg();
            if x2 >= ZERO && q1.saturating_add(k12.sat_mul(x2)) >= ZERO {
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
    for ((cp, new), vn) in arb.points.iter_mut().zip([x1, x2]).zip([v1, v2]) {
        note_approach(cp, vn, new);
        let applied = new.saturating_sub(cp.normal_impulse);
        cp.normal_impulse = new;
        cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
        cp.total_normal_impulse = cp.total_normal_impulse.saturating_add(applied);
        apply_along(a, b, arb.n_m, cp.irn, applied);
    }
    true
}

/// Keeps the fastest approach a pushing point has seen this step as its
/// restitution reference. The speed at the start of the step is not enough: with
/// speculative contacts a falling body meets the ground part-way through the step,
/// after gravity added up to g·dt more, and bouncing off the earlier speed would
/// lose that (a 2 % lower rebound from 10 m).
#[inline(always)]
fn note_approach(cp: &mut ContactPoint, vn: Scalar, new_impulse: Scalar) {
    if new_impulse > ZERO && vn < cp.relative_velocity {
        cp.relative_velocity = vn;
    }
}

/// A contact point's (bias velocity, mass scale, impulse scale) for one pass.
type Terms = (Scalar, Scalar, Scalar);

/// Relative velocity of the contact point along a direction, from the
/// precomputed arms: (vB − vA)·d + ωB·(rB × d) − ωA·(rA × d).
#[inline(always)]
fn relative_speed(a: &Body, b: &Body, d: Vector2, r: [Scalar; 2]) -> Scalar {
    (b.linear_velocity - a.linear_velocity)
        .dot(d)
        .saturating_add(b.angular_velocity.sat_mul(r[1]))
        .saturating_sub(a.angular_velocity.sat_mul(r[0]))
}

/// Applies an impulse of magnitude `lambda` along the direction whose
/// precomputed per-mass vectors are `m` and inertia-scaled arms are `ir`.
#[inline(always)]
fn apply_along(a: &mut Body, b: &mut Body, m: [Vector2; 2], ir: [Scalar; 2], lambda: Scalar) {
    a.linear_velocity -= m[0] * lambda;
    a.angular_velocity = a.angular_velocity.saturating_sub(ir[0].sat_mul(lambda));
    b.linear_velocity += m[1] * lambda;
    b.angular_velocity = b.angular_velocity.saturating_add(ir[1].sat_mul(lambda));
}

/// One pass over one arbiter: normal constraints, then friction.
fn solve_one(
    arb: &mut Arbiter,
    a: &mut Body,
    b: &mut Body,
    params: &StepParams,
    use_bias: bool,
    reverse_points: bool,
) {
    let n = arb.normal;
    let soft = if arb.static_pair { params.static_soft } else { params.soft };
    let count = usize::from(arb.count);
    let dp = b.position - a.position;
    // Bias and softness per point, from the current separation.
    let mut terms: [Terms; 2] = [(ZERO, scalar::ONE, ZERO); 2];
    for (term, cp) in terms.iter_mut().zip(arb.points.iter().take(count)) {
        let d = dp + (b.rotation.rotate(cp.local_b) - a.rotation.rotate(cp.local_a));
        let s = d.dot(n).saturating_add(cp.separation);
        *term = if s > ZERO {
            // Speculative: allow closing the gap within this sub-step, no more.
            (s.sat_mul(params.inv_h), scalar::ONE, ZERO)
        } else if use_bias {
            let push = s.sat_mul(soft.bias_rate).max(params.push_speed.saturating_neg());
            (push, soft.mass_scale, soft.impulse_scale)
        } else {
            (ZERO, scalar::ONE, ZERO)
        };
    }
    // Two-point manifolds are solved as a block; the point-by-point fallback
    // (ill-conditioned or round-off) alternates its order between sweeps so that
    // neither point is always first.
    let solved_together = match arb.block {
        Some(inv) => solve_block(arb, a, b, inv, terms),
        None => false,
    };
    if !solved_together {
        let order: [usize; 2] = if reverse_points && count == 2 { [1, 0] } else { [0, 1] };
        for &i in order.iter().take(count) {
            let (Some(cp), Some(&(bias, mass_scale, impulse_scale))) = (arb.points.get_mut(i), terms.get(i))
            else {
                continue;
            };
            let vn = relative_speed(a, b, n, cp.rn);
            let impulse = cp
                .normal_mass
                .sat_mul(mass_scale)
                .sat_mul(vn.saturating_add(bias))
                .saturating_neg()
                .saturating_sub(impulse_scale.sat_mul(cp.normal_impulse));
            let new = cp.normal_impulse.saturating_add(impulse).max(ZERO);
            note_approach(cp, vn, new);
            let applied = new.saturating_sub(cp.normal_impulse);
            cp.normal_impulse = new;
            cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
            cp.total_normal_impulse = cp.total_normal_impulse.saturating_add(applied);
            apply_along(a, b, arb.n_m, cp.irn, applied);
        }
    }
    let t = n.right_perp();
    let mu = arb.friction;
    for cp in arb.points.iter_mut().take(count) {
        let vt = relative_speed(a, b, t, cp.rt);
        let impulse = cp.tangent_mass.sat_mul(vt).saturating_neg();
        let max_f = mu.sat_mul(cp.normal_impulse);
        let new = scalar::clamp(cp.tangent_impulse.saturating_add(impulse), max_f.saturating_neg(), max_f);
        let applied = new.saturating_sub(cp.tangent_impulse);
        cp.tangent_impulse = new;
        apply_along(a, b, arb.t_m, cp.irt, applied);
    }
}
