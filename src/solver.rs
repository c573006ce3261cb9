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
//!    from closing the gap within the sub-step),
//! 4. integrates positions,
//! 5. relaxes: solves again without the position bias, so the push-out does not
//!    leave energy behind.
//!
//! After the last sub-step a restitution pass gives contacts that approached
//! faster than `restitution_threshold` their bounce, e·v.
//!
//! The contact separation is re-evaluated in every sub-step from the bodies' current
//! positions and rotations (anchors are kept in each body's local frame), so no
//! collision detection runs inside the loop. Everything iterates in the canonical
//! arbiter order and body-slot order.

use crate::arbiter::Arbiter;
use crate::body::{Body, BodyType};
use crate::math::scalar::ScalarExt as _;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;
use crate::world::World;

/// Soft-constraint coefficients for one sub-step length (Box2D's `b2Softness`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Softness {
    bias_rate: Scalar,
    mass_scale: Scalar,
    impulse_scale: Scalar,
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
fn inverse_mass(b: &Body) -> (Scalar, Scalar) {
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
        // Each sub-step gets 1/n of the generators' velocity change.
        for (_, b) in self.bodies.iter_mut() {
            b.pending_v = b.pending_v * inv_n;
            b.pending_w = b.pending_w.sat_mul(inv_n);
        }
        let (vmax, wmax) = (self.def.max_linear_speed, self.angular_limit(dt));
        for _ in 0..n {
            for (_, b) in self.bodies.iter_mut() {
                if b.is_dynamic() && !b.out_of_bounds {
                    b.linear_velocity += b.pending_v;
                    b.angular_velocity = b.angular_velocity.saturating_add(b.pending_w);
                }
            }
            self.warm_start();
            self.solve_contacts(&params, true);
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
            self.solve_contacts(&params, false);
        }
        self.apply_restitution();
        for (_, b) in self.bodies.iter_mut() {
            b.pending_v = Vector2::ZERO;
            b.pending_w = ZERO;
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

    /// One pass over every solved contact. The biased pass runs in pair order and
    /// the relax pass in reverse (symmetric Gauss-Seidel): a one-way sweep favours
    /// the bodies it visits first, which makes a symmetric pyramid creep sideways.
    fn solve_contacts(&mut self, params: &StepParams, use_bias: bool) {
        let World { bodies, contacts, .. } = self;
        let live = contacts.live_mut();
        let mut visit = |arb: &mut Arbiter| {
            if arb.solve {
                if let Some((a, b)) = bodies.get2_at_mut(arb.body_a.index(), arb.body_b.index()) {
                    solve_one(arb, a, b, params, use_bias);
                }
            }
        };
        if use_bias {
            live.iter_mut().for_each(&mut visit);
        } else {
            live.iter_mut().rev().for_each(&mut visit);
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
                    if cp.relative_velocity > -threshold || cp.max_normal_impulse == ZERO {
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
fn solve_one(arb: &mut Arbiter, a: &mut Body, b: &mut Body, params: &StepParams, use_bias: bool) {
    let n = arb.normal;
    let soft = if arb.static_pair { params.static_soft } else { params.soft };
    let count = usize::from(arb.count);
    let dp = b.position - a.position;
    for cp in arb.points.iter_mut().take(count) {
        // Current separation from the bodies' current poses.
        let d = dp + (b.rotation.rotate(cp.local_b) - a.rotation.rotate(cp.local_a));
        let s = d.dot(n).saturating_add(cp.separation);
        let (bias, mass_scale, impulse_scale) = if s > ZERO {
            // Speculative: allow closing the gap within this sub-step, no more.
            (s.sat_mul(params.inv_h), scalar::ONE, ZERO)
        } else if use_bias {
            let push = s.sat_mul(soft.bias_rate).max(params.push_speed.saturating_neg());
            (push, soft.mass_scale, soft.impulse_scale)
        } else {
            (ZERO, scalar::ONE, ZERO)
        };
        let vn = relative_speed(a, b, n, cp.rn);
        let impulse = cp
            .normal_mass
            .sat_mul(mass_scale)
            .sat_mul(vn.saturating_add(bias))
            .saturating_neg()
            .saturating_sub(impulse_scale.sat_mul(cp.normal_impulse));
        let new = cp.normal_impulse.saturating_add(impulse).max(ZERO);
        let applied = new.saturating_sub(cp.normal_impulse);
        cp.normal_impulse = new;
        cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
        cp.total_normal_impulse = cp.total_normal_impulse.saturating_add(applied);
        apply_along(a, b, arb.n_m, cp.irn, applied);
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
