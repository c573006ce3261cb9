//! The solver's copy of a body: what the sub-step loop reads and writes of it.
//!
//! The contact sweeps gather and scatter each body a dozen times a step, so a
//! body's lane record ([`BodyLanes`]: velocity, rim speed, and the position
//! and rim-rotation change since the step began, in the formats of
//! [`lanes`]) is 32 bytes in an array of its own. The rest
//! ([`SolverBody`]) is the `Scalar` state that the joints, the integration
//! and the store use, and the per-body constants of the step.

use crate::body::Body;
use crate::math::scalar::{mul_below_one, Scalar, ZERO};
use crate::math::{Rot, Vector2};

use super::lanes::{self, FP, FV};

/// Index of the linear velocity's x component in [`BodyLanes`].
pub(crate) const VX: usize = 0;
/// … its y component.
pub(crate) const VY: usize = 1;
/// The rim speed ŵ = ω·r_b.
pub(crate) const W: usize = 2;
/// The rim rotation δ̂ = dθ·r_b since the step began.
pub(crate) const DR: usize = 3;
/// The position change since the step began, x.
pub(crate) const DPX: usize = 4;
/// … y.
pub(crate) const DPY: usize = 5;
/// Non-zero when a contact's deep push-out moved the body (changed its
/// motion lanes) since the last integration.
pub(crate) const MOVED: usize = 6;
/// The colours this body's pivots in lanes took this step (a bit mask; see
/// `pivot_lanes`): the record's spare field, which the kernels never read.
pub(crate) const PIVOT_COLOURS: usize = 7;

/// The smallest body radius the solver uses for rim speeds (m): keeps
/// 1/r_b within its format for the tiniest shapes.
const MIN_RADIUS: Scalar = Scalar::from_bits(1 << 24);

/// A body's lane state: `[v_x, v_y, ŵ, δ̂, dp_x, dp_y, moved, 0]`, Q16.16
/// velocities and Q12.20 changes since the step began (solver scratch, one
/// per body slot; see [`Storage`](crate::Storage)). Kept in an array of its
/// own, 32 bytes a body, so that the contact kernels' gathers stay in cache.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct BodyLanes(pub(crate) [i32; 8]);

impl BodyLanes {
    /// An unused record.
    pub const EMPTY: Self = Self([0; 8]);
}

impl Default for BodyLanes {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// A body's inverse mass, rim inverse mass, inverse radius and dynamic flag:
/// what [`SolverBody::same_mass`] compares.
pub(crate) type MassKey = (Scalar, Scalar, Scalar, bool);

/// A body's state as the solver sees it during a step (solver scratch, one per
/// body slot; see [`Storage`](crate::Storage)).
///
/// The `Scalar` velocity is the body's own, at full precision: forces,
/// joints, the speed limits and the integration work on it. The lanes are a
/// copy rounded to the lane format, for the contact kernels; what the kernels
/// change is carried back as a difference ([`SolverBody::pull`]), so a body
/// no contact touches moves exactly as it would without the lanes, and a
/// contact's effect is rounded once, to 1.5e-5 m/s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolverBody {
    /// The velocity lanes as last set from the `Scalar` velocity.
    pub(crate) lane_ref: [i32; 3],
    /// Graph colours taken by this body's constraints this step (scratch).
    pub(crate) colours: u32,
    pub(crate) v: Vector2,
    pub(crate) w: Scalar,
    pub(crate) p: Vector2,
    pub(crate) q: Rot,
    /// The rotation at the start of the step.
    pub(crate) q0: Rot,
    /// The angle turned since the start of the step (rad).
    pub(crate) angle: Scalar,
    /// The position at the start of the step.
    pub(crate) p0: Vector2,
    /// The radius rim speeds are measured at, and its inverse.
    pub(crate) radius: Scalar,
    pub(crate) inv_radius: Scalar,
    /// The inverse mass a contact sees ([`inverse_mass`]) and the rim inverse
    /// mass j = (I⁻¹·r_b)·r_b, for the contact prepare: two products and the
    /// body's type tests once a body here, not once a side in every arbiter
    /// (large scene, 20 steps: 2,523.3 → 2,508.4 M instructions).
    pub(crate) inv_mass: Scalar,
    pub(crate) rim_inv_mass: Scalar,
    /// The inverse inertia a contact or a joint sees ([`inverse_mass`]), for
    /// the plain pivots' prepare (`pivot_lanes::Colouring::fill`), which
    /// then reads no `Body`.
    pub(crate) inv_inertia: Scalar,
    /// This sub-step's share of the force generators' velocity change.
    pub(crate) force_dv: Vector2,
    pub(crate) force_dw: Scalar,
    /// The angular speed limit: the step's, and the rim speed's
    /// ([`MAX_LINEAR_SPEED_LIMIT`](crate::limits::MAX_LINEAR_SPEED_LIMIT) at
    /// the body's radius).
    pub(crate) w_max: Scalar,
    /// The damping factors 1 / (1 + h·c) of the linear and angular velocity,
    /// applied each sub-step before the forces (as Box2D does).
    pub(crate) linear_damping: Scalar,
    pub(crate) angular_damping: Scalar,
    /// Damped: a damping factor is not 1 (dynamic bodies only).
    pub(crate) damped: bool,
    /// Receives the generators' velocity change (dynamic, in bounds).
    pub(crate) forced: bool,
    /// Integrates its position (not static, in bounds).
    pub(crate) moves: bool,
    /// Takes impulses (dynamic, in bounds): contacts change its velocity.
    pub(crate) dynamic: bool,
    /// The lanes hold what [`push`](Self::push) last made of the `Scalar`
    /// velocity (no [`pull`](Self::pull) has changed it since).
    pub(crate) pushed: bool,
    /// Its inverse mass, rim inverse mass, radius and dynamic flag are those
    /// of the last step's load of this slot (see `colour::build`, which then
    /// keeps a lane built from them).
    pub(crate) same_mass: bool,
    /// Continuous collision's marks (see [`crate::continuous`]).
    pub(crate) ccd: u8,
    /// Continuous collision's earliest time of impact this step (1: none).
    pub(crate) toi: Scalar,
}

impl SolverBody {
    /// An unused record (also the stand-in ground of a joint to a world point).
    pub const EMPTY: Self = Self {
        lane_ref: [0; 3],
        colours: 0,
        v: Vector2::ZERO,
        w: ZERO,
        p: Vector2::ZERO,
        q: Rot::IDENTITY,
        q0: Rot::IDENTITY,
        angle: ZERO,
        p0: Vector2::ZERO,
        radius: Scalar::ONE,
        inv_radius: Scalar::ONE,
        inv_mass: ZERO,
        rim_inv_mass: ZERO,
        inv_inertia: ZERO,
        force_dv: Vector2::ZERO,
        force_dw: ZERO,
        w_max: ZERO,
        linear_damping: Scalar::ONE,
        angular_damping: Scalar::ONE,
        damped: false,
        forced: false,
        moves: false,
        dynamic: false,
        pushed: false,
        same_mass: false,
        ccd: 0,
        toi: Scalar::ONE,
    };

    /// What a contact's lane is built from of this body (see
    /// [`SolverBody::same_mass`]).
    #[inline]
    pub(crate) fn mass_key(&self) -> MassKey {
        (self.inv_mass, self.rim_inv_mass, self.inv_radius, self.dynamic)
    }

    /// Loads a body's state; `inv_n` is 1 / sub-steps, `h` the sub-step (s),
    /// `wmax` the step's angular speed limit. A frozen (out of bounds) body is
    /// loaded as a static one: no forces, no impulses, not integrated. A
    /// fixed-rotation body is loaded with no spin and an angular limit of 0,
    /// which the integration's clamp holds it to. `prev` is the slot's last
    /// load, for [`SolverBody::same_mass`].
    #[inline]
    pub(crate) fn load(
        b: &Body,
        inv_n: Scalar,
        h: Scalar,
        wmax: Scalar,
        lane: &mut BodyLanes,
        prev: &MassKey,
    ) -> Self {
        let radius = b.radius.max(MIN_RADIUS);
        let inv_radius = radius.recip();
        let dynamic = b.is_dynamic() && !b.out_of_bounds;
        let (inv_mass, inv_inertia) = inverse_mass(b);
        let mut sb = Self {
            lane_ref: [0; 3],
            colours: 0,
            v: b.linear_velocity,
            w: b.angular_velocity,
            p: b.position,
            q: b.rotation,
            q0: b.rotation,
            angle: ZERO,
            p0: b.position,
            radius,
            inv_radius,
            inv_mass,
            // (I⁻¹·r_b)·r_b: r_b² of a small body would keep few bits.
            rim_inv_mass: inv_inertia * radius * radius,
            inv_inertia,
            force_dv: Vector2::ZERO,
            force_dw: ZERO,
            // `angular_speed_limit`, reusing the reciprocal of the radius.
            w_max: if b.fixed_rotation { ZERO } else { wmax.min(rim_limit(inv_radius)) },
            linear_damping: Scalar::ONE,
            angular_damping: Scalar::ONE,
            damped: false,
            forced: dynamic,
            moves: b.moved_by_step(),
            dynamic,
            pushed: false,
            same_mass: false,
            ccd: 0,
            toi: Scalar::ONE,
        };
        sb.same_mass = sb.mass_key() == *prev;
        if dynamic {
            (sb.force_dv, sb.force_dw) = (b.force_dv * inv_n, b.force_dw * inv_n);
            if b.linear_damping != ZERO || b.angular_damping != ZERO {
                // Validated: c ≤ 1,024 /s and h ≤ 0.25 s, so 1 + h·c ≤ 257.
                sb.linear_damping = (Scalar::ONE + h * b.linear_damping).recip();
                sb.angular_damping = (Scalar::ONE + h * b.angular_damping).recip();
                sb.damped = true;
            }
        }
        if b.fixed_rotation {
            (sb.w, sb.force_dw) = (ZERO, ZERO);
        }
        *lane = BodyLanes::EMPTY;
        sb.push(lane);
        sb
    }

    /// Carries what the contact kernels did to the lanes since the last
    /// [`push`](Self::push) into the `Scalar` velocity (before a joint, the
    /// game's constraints, the integration or the store reads it).
    #[inline]
    pub(crate) fn pull(&mut self, lane: &BodyLanes) {
        let lane = &lane.0;
        let d = |k: usize| lane[k].wrapping_sub(self.lane_ref[k]);
        let (dx, dy, dw) = (d(VX), d(VY), d(W));
        if dx | dy | dw != 0 {
            self.v += Vector2::new(lanes::to_scalar(dx, FV), lanes::to_scalar(dy, FV));
            self.w += lanes::to_scalar(dw, FV) * self.inv_radius;
            self.lane_ref = [lane[VX], lane[VY], lane[W]];
            self.pushed = false;
        }
    }

    /// Sets the lanes from the `Scalar` velocity (after it changed), rounded
    /// and walled.
    #[inline]
    pub(crate) fn push(&mut self, lane: &mut BodyLanes) {
        let lane = &mut lane.0;
        lane[VX] = lanes::velocity(self.v.x);
        lane[VY] = lanes::velocity(self.v.y);
        lane[W] = lanes::velocity(self.w * self.radius);
        self.lane_ref = [lane[VX], lane[VY], lane[W]];
        self.pushed = true;
    }

    /// Damps the velocity and adds this sub-step's share of the forces:
    /// v ← v / (1 + h·c) + Δv (Box2D's order).
    #[inline]
    pub(crate) fn add_force(&mut self, lane: &mut BodyLanes) {
        self.pull(lane);
        if self.damped {
            self.v = self.v * self.linear_damping;
            self.w *= self.angular_damping;
        }
        self.v += self.force_dv;
        self.w += self.force_dw;
        self.push(lane);
    }

    /// Clamps the velocity to the step's limits (`vmax` per component, the
    /// body's angular limit) and advances the pose by `h`: the `Scalar`
    /// position and rotation (what joints and the store read) and the lanes'
    /// change since the step began (what the contacts read).
    #[inline]
    pub(crate) fn integrate(&mut self, h: Scalar, vmax: Scalar, lane: &mut BodyLanes) {
        self.pull(lane);
        if lane.0[MOVED] != 0 {
            self.pull_pose(lane);
        }
        // Within the limits is one add and one unsigned comparison a
        // component ([`lanes::within`]: `vmax` ≤ 2,048 m/s and `w_max` ≤
        // 2¹⁹ rad/s by validation, far inside its range); the clamps are a
        // cold call. With the products below: mixed scene 818.7 → 808.1 M
        // instructions, large 20 2,153.4 → 2,139.1 M, joint 10 944.6 →
        // 935.5 M, the same bits.
        let (vb, wb) = (vmax.to_bits(), self.w_max.to_bits());
        let (vx, vy, w) = (self.v.x.to_bits(), self.v.y.to_bits(), self.w.to_bits());
        if !(lanes::within(vx, vb) & lanes::within(vy, vb) & lanes::within(w, wb)) {
            self.clamp_velocity(vmax);
            self.push(lane);
        } else if !self.pushed {
            // A body nothing moved since its last push, within its limits,
            // has those lanes already (the only other writer of the `Scalar`
            // velocity, a joint's `apply_linear`, pushes every body it can
            // move). Mixed scene: 955.2 → 948.2 M instructions; large 20:
            // 2,503.3 → 2,497.3 M.
            self.push(lane);
        }
        // h ≤ [`MAX_TIME_STEP`](crate::limits::MAX_TIME_STEP) < 1: the
        // products need no saturation test (the same bits).
        self.p += Vector2::new(mul_below_one(h, self.v.x), mul_below_one(h, self.v.y));
        let turn = mul_below_one(h, self.w);
        self.angle += turn;
        self.q = self.q.integrate(turn);
        [lane.0[DPX], lane.0[DPY], lane.0[DR]] = self.motion_lanes();
    }

    /// The velocity clamped to ±`vmax` a component and the angular speed to
    /// the body's limit.
    #[cold]
    #[inline(never)]
    fn clamp_velocity(&mut self, vmax: Scalar) {
        self.v = Vector2::new(self.v.x.clamp(-vmax, vmax), self.v.y.clamp(-vmax, vmax));
        self.w = self.w.clamp(-self.w_max, self.w_max);
    }

    /// The motion since the step began as the lanes hold it: dp_x, dp_y and
    /// δ̂ = dθ·r_b, rounded and saturated.
    #[inline]
    fn motion_lanes(&self) -> [i32; 3] {
        let dp = self.p - self.p0;
        [
            lanes::from_scalar(dp.x, FP, 2047),
            lanes::from_scalar(dp.y, FP, 2047),
            lanes::from_scalar(self.angle * self.radius, FP, 2047),
        ]
    }

    /// Carries a deep push-out's move of the motion lanes (see
    /// `contact::kernel`'s `push_apart`) into the `Scalar` pose: the
    /// difference between the lanes and what the pose would load them with.
    #[inline(never)]
    fn pull_pose(&mut self, lane: &mut BodyLanes) {
        let [x, y, r] = self.motion_lanes();
        let lane = &mut lane.0;
        lane[MOVED] = 0;
        let (dx, dy, dr) = (lane[DPX].wrapping_sub(x), lane[DPY].wrapping_sub(y), lane[DR].wrapping_sub(r));
        self.p += Vector2::new(lanes::to_scalar(dx, FP), lanes::to_scalar(dy, FP));
        if dr != 0 {
            let turn = lanes::to_scalar(dr, FP) * self.inv_radius;
            self.angle += turn;
            self.q = self.q.integrate(turn);
        }
    }

    /// Velocity of the point at offset `r` from the centre of mass (from the
    /// `Scalar` view).
    #[inline]
    pub(crate) fn velocity_at_offset(&self, r: Vector2) -> Vector2 {
        self.v + Vector2::cross_sv(self.w, r)
    }

    /// Writes the velocity and pose back to the body.
    #[inline]
    pub(crate) fn store(&mut self, b: &mut Body, lane: &BodyLanes) {
        self.pull(lane);
        b.linear_velocity = self.v;
        b.angular_velocity = self.w;
        b.position = self.p;
        b.rotation = self.q;
    }

    /// Takes the velocity and pose from the body (after the game's constraints
    /// moved it).
    #[inline]
    pub(crate) fn reload(&mut self, b: &Body, lane: &mut BodyLanes) {
        self.v = b.linear_velocity;
        self.w = b.angular_velocity;
        self.p = b.position;
        self.q = b.rotation;
        self.push(lane);
    }
}

impl Default for SolverBody {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Inverse mass and inertia a body contributes to a contact or a joint (0
/// unless dynamic and in bounds: a frozen body is as immovable as a static one,
/// see [`Body::is_out_of_bounds`]). A fixed-rotation body's inverse inertia is
/// 0: nothing can turn it.
pub(crate) fn inverse_mass(b: &Body) -> (Scalar, Scalar) {
    if b.is_dynamic() && !b.out_of_bounds {
        (b.mass.inv_mass, if b.fixed_rotation { ZERO } else { b.mass.inv_inertia })
    } else {
        (ZERO, ZERO)
    }
}

/// The angular speed the solver lets body `b` reach in a step whose limit is
/// `wmax` (rad/s): `wmax`, and at most the rim speed
/// [`MAX_LINEAR_SPEED_LIMIT`](crate::limits::MAX_LINEAR_SPEED_LIMIT) at the
/// body's radius; 0 for a fixed-rotation body.
pub(crate) fn angular_speed_limit(b: &Body, wmax: Scalar) -> Scalar {
    if b.fixed_rotation {
        return ZERO;
    }
    wmax.min(rim_limit(b.radius.max(MIN_RADIUS).recip()))
}

/// The angular speed at which a body's rim, at 1 / `inv_radius` m from its
/// centre, reaches the lanes' velocity wall (rad/s).
#[inline]
fn rim_limit(inv_radius: Scalar) -> Scalar {
    lanes::to_scalar(lanes::V_WALL, FV) * inv_radius
}

/// Bodies `i` and `j`, mutably; `None` if they are the same or out of range.
#[inline(always)]
pub(crate) fn pair_at<T>(bodies: &mut [T], i: u32, j: u32) -> Option<(&mut T, &mut T)> {
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
