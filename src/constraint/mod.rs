//! Constraints between two bodies (or a body and a fixed world point).
//!
//! The manual's three — [`JointKind::Spring`], [`JointKind::DampedSpring`] and
//! [`JointKind::Rod`] — and the joints games expect from other engines:
//! [`JointKind::Rope`] (maximum distance), [`JointKind::Pivot`] (revolute, with
//! angle limits and a motor) and [`JointKind::Weld`]. Any of them can be breakable
//! ([`JointDef::breakable`]). Games add their own by implementing [`Constraint`].
//!
//! # How they are solved
//! Built-in joints are plain data in the world's storage (so the snapshot can
//! hold them). They are solved in the same sub-steps as the contacts, before them,
//! in joint-slot order, then the game's constraints in registration order:
//! * springs apply their force `F = −k·(ℓ − ℓ₀) − c·ℓ̇` along the line between the
//!   anchors once per sub-step (explicit, symplectic: periods and damping come out
//!   as the closed forms say; a spring too stiff for the step, `k·h²/m > 4`, is
//!   unstable, as in any explicit integrator);
//! * rods, ropes, pivots and welds are velocity constraints with Box2D v3's soft
//!   position correction (a stiff spring-damper of [`JOINT_HERTZ`] Hz, damping
//!   ratio [`JOINT_DAMPING_RATIO`]), warm-started from the impulses they ended the
//!   last sub-step with, and relaxed like contacts.
//!
//! # Breaking
//! A breakable joint whose impulse over a step exceeds its limit is removed after
//! that step and handed, with its handle, to the world's break callback
//! ([`World::set_joint_break_callback`](crate::World::set_joint_break_callback)),
//! in joint-slot order. It breaks once: the handle is stale afterwards.
//!
//! # Removing a body
//! [`World::remove_body`](crate::World::remove_body) removes every built-in joint
//! attached to the body (without calling the break callback: the game removed the
//! body and knows) and every game constraint attached to it.

mod pivot;
mod rod;
mod spring;
mod weld;

use crate::hook::Hook;

use crate::arena::Handle;
use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::limits::MAX_BODY_RADIUS;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Matrix22;
use crate::math::{Rect, Rot, Vector2};
use crate::solver::SolverBody;

/// Stiffness of the soft position correction of rods, ropes, pivots and welds, Hz
/// (Box2D v3's joint default; capped at a quarter of the sub-step rate).
pub const JOINT_HERTZ: Scalar = Scalar::from_int(60);
/// Damping ratio of that correction (Box2D v3's joint default).
pub const JOINT_DAMPING_RATIO: Scalar = Scalar::from_int(2);
/// Game constraints ([`Constraint`] objects) a world can hold.
pub const MAX_USER_CONSTRAINTS: usize = 16;

/// Marker type naming built-in joints in handles.
#[derive(Debug)]
pub enum JointMarker {}
/// Handle of a built-in joint.
pub type JointHandle = Handle<JointMarker>;
/// Marker type naming game constraints in handles.
#[derive(Debug)]
pub enum ConstraintMarker {}
/// Handle of a game constraint.
pub type ConstraintHandle = Handle<ConstraintMarker>;

/// A game's constraint: applies impulses to its two bodies in every solver
/// iteration (the manual's `Constraint::solve`).
pub trait Constraint {
    /// Called once per step before the iterations, with the step length `dt`
    /// (optional: precompute effective masses here).
    fn prepare(&mut self, a: &Body, b: &Body, dt: Scalar) {
        let _ = (a, b, dt);
    }

    /// Applies impulses to the two bodies for one sub-step of `h` seconds, e.g.
    /// with [`Body::apply_impulse_at`]. A constraint to a fixed world point gets a
    /// static body at the origin as `b`; changes to it are ignored.
    fn solve(&mut self, a: &mut Body, b: &mut Body, h: Scalar);
}

/// A motor's torque limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaxTorque {
    /// At most this torque, N·m (≥ 0).
    Limited(Scalar),
    /// As much as it takes to hold the speed (no overflow: the impulse per
    /// sub-step is bounded by the engine's speed and inertia limits).
    Unlimited,
}

/// A pivot's motor: drives the relative angular speed ωB − ωA towards `speed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Motor {
    /// Target relative angular speed, rad/s.
    pub speed: Scalar,
    /// Torque limit.
    pub max_torque: MaxTorque,
}

/// What kind of joint, with its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A spring of `stiffness` N/m and rest length `rest_length` m.
    Spring {
        /// N/m, ≥ 0.
        stiffness: Scalar,
        /// m, ≥ 0.
        rest_length: Scalar,
    },
    /// A spring with a damper of `damping` N·s/m.
    DampedSpring {
        /// N/m, ≥ 0.
        stiffness: Scalar,
        /// N·s/m, ≥ 0.
        damping: Scalar,
        /// m, ≥ 0.
        rest_length: Scalar,
    },
    /// Keeps the anchors exactly `length` m apart (the manual's Rod).
    Rod {
        /// m, > 0.
        length: Scalar,
    },
    /// Keeps the anchors at most `max_length` m apart; slack below.
    Rope {
        /// m, > 0.
        max_length: Scalar,
    },
    /// Pins the anchors together; the bodies turn freely, within optional limits
    /// on the relative angle θB − θA (rad, measured from the angle at creation),
    /// with an optional motor driving ωB − ωA. For a pivot to a fixed world point
    /// the limits and motor act on the body's own angle and spin.
    Pivot {
        /// Lower and upper relative angle, rad (lower ≤ 0 ≤ upper is typical).
        limits: Option<(Scalar, Scalar)>,
        /// Optional motor.
        motor: Option<Motor>,
    },
    /// Glues the bodies: anchors together, relative angle fixed at its value at
    /// creation.
    Weld,
}

/// Everything needed to create a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointDef {
    /// First body.
    pub body_a: BodyHandle,
    /// Anchor in A's frame, relative to its centre of mass (m).
    pub anchor_a: Vector2,
    /// Second body, or `None` to attach A to a fixed world point.
    pub body_b: Option<BodyHandle>,
    /// Anchor in B's frame (m), or the world point when `body_b` is `None`.
    pub anchor_b: Vector2,
    /// Kind and parameters.
    pub kind: JointKind,
    /// Break when the impulse over one step exceeds this (N·s); `None` never breaks.
    pub break_impulse: Option<Scalar>,
    /// Whether the two bodies still collide with each other (default false, as in
    /// Box2D: a chain's links or a ragdoll's limbs pass through their neighbours).
    pub collide_connected: bool,
}

impl JointDef {
    /// A joint of `kind` between anchors on two bodies (local coordinates).
    #[must_use]
    pub fn new(
        body_a: BodyHandle,
        anchor_a: Vector2,
        body_b: BodyHandle,
        anchor_b: Vector2,
        kind: JointKind,
    ) -> Self {
        Self {
            body_a,
            anchor_a,
            body_b: Some(body_b),
            anchor_b,
            kind,
            break_impulse: None,
            collide_connected: false,
        }
    }

    /// A joint of `kind` between an anchor on a body and a fixed world point.
    #[must_use]
    pub fn to_world(body_a: BodyHandle, anchor_a: Vector2, world_point: Vector2, kind: JointKind) -> Self {
        Self {
            body_a,
            anchor_a,
            body_b: None,
            anchor_b: world_point,
            kind,
            break_impulse: None,
            collide_connected: false,
        }
    }

    /// Lets the two bodies collide with each other.
    #[must_use]
    pub fn collide_connected(mut self, collide: bool) -> Self {
        self.collide_connected = collide;
        self
    }

    /// Makes the joint breakable above `impulse` N·s per step.
    #[must_use]
    pub fn breakable(mut self, impulse: Scalar) -> Self {
        self.break_impulse = Some(impulse);
        self
    }
}

/// A built-in joint in a world.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Joint {
    pub(crate) def: JointDef,
    /// Relative angle θB − θA at creation (pivot limits and weld), as a rotation.
    pub(crate) reference: Rot,
    /// Accumulated impulses of the last sub-step: linear (x, y or axial in x) and
    /// angular; warm-start the next one. Part of the snapshot.
    pub(crate) impulse: Vector2,
    pub(crate) angular_impulse: Scalar,
    pub(crate) motor_impulse: Scalar,
    pub(crate) limit_impulse: Scalar,
    /// Linear impulse applied over this step, summed over the sub-steps (N·s);
    /// its magnitude is what breaking compares.
    pub(crate) step_linear: Vector2,
    /// Broke this step; removed after it.
    pub(crate) broken: bool,
    // Per-step solver data (derived).
    pub(crate) soft: crate::solver::Softness,
    pub(crate) inv_mass: [Scalar; 2],
    pub(crate) inv_inertia: [Scalar; 2],
    /// 1 / (iA + iB): the mass against relative rotation (pivot, weld).
    pub(crate) axial_mass: Scalar,
    /// The inverse of the point constraint's 2×2 mass matrix at the start of the
    /// step (pivot, weld); `None` when singular.
    pub(crate) point_mass: Option<Matrix22>,
}

impl Joint {
    /// The definition it was created from.
    #[must_use]
    pub fn def(&self) -> &JointDef {
        &self.def
    }

    /// Magnitude of the linear impulse the joint applied over the last step (N·s),
    /// summed over its sub-steps: what breaking compares. For a body hanging at
    /// rest it is m·g·dt.
    #[must_use]
    pub fn step_impulse(&self) -> Scalar {
        self.step_linear.length()
    }

    /// Changes the motor of a pivot (no effect on other kinds).
    pub fn set_motor(&mut self, motor: Option<Motor>) {
        if let JointKind::Pivot { motor: m, .. } = &mut self.def.kind {
            *m = motor;
        }
    }
}

/// Largest anchor offset from a body's centre of mass: twice the largest body.
fn max_anchor() -> Scalar {
    MAX_BODY_RADIUS * scalar::TWO
}

/// Checks a definition against the bodies it names (looked up by the caller).
pub(crate) fn validate(def: &JointDef, a: &Body, b: Option<&Body>, bounds: Rect) -> Result<(), Error> {
    if Some(def.body_a) == def.body_b {
        return Err(Error::InvalidOperation { what: "a joint between a body and itself" });
    }
    let sane = |v: Vector2| v.x.abs() <= max_anchor() && v.y.abs() <= max_anchor();
    if !sane(def.anchor_a) {
        return Err(Error::OutOfRange { what: "anchor" });
    }
    match b {
        Some(b) => {
            if !sane(def.anchor_b) {
                return Err(Error::OutOfRange { what: "anchor" });
            }
            if !a.is_dynamic() && !b.is_dynamic() {
                return Err(Error::InvalidOperation { what: "a joint between two bodies that cannot move" });
            }
        }
        None => {
            if !bounds.contains(def.anchor_b) {
                return Err(Error::OutsideBounds);
            }
            if !a.is_dynamic() {
                return Err(Error::InvalidOperation { what: "a joint between two bodies that cannot move" });
            }
        }
    }
    validate_params(def)
}

/// The checks on a definition's own values (no bodies needed): anchors, kind
/// parameters, break impulse. Also used to validate snapshots.
pub(crate) fn validate_params(def: &JointDef) -> Result<(), Error> {
    let sane = |v: Vector2| v.x.abs() <= max_anchor() && v.y.abs() <= max_anchor();
    if !sane(def.anchor_a) || (def.body_b.is_some() && !sane(def.anchor_b)) {
        return Err(Error::OutOfRange { what: "anchor" });
    }
    if def.body_b.is_none()
        && (def.anchor_b.x.abs() > crate::limits::MAX_COORDINATE
            || def.anchor_b.y.abs() > crate::limits::MAX_COORDINATE)
    {
        return Err(Error::OutOfRange { what: "anchor" });
    }
    let non_negative = |v: Scalar, what| if v < ZERO { Err(Error::OutOfRange { what }) } else { Ok(()) };
    let limit = MAX_BODY_RADIUS * Scalar::from_int(8);
    match def.kind {
        JointKind::Spring { stiffness, rest_length } => {
            non_negative(stiffness, "stiffness")?;
            non_negative(rest_length, "rest length")?;
        }
        JointKind::DampedSpring { stiffness, damping, rest_length } => {
            non_negative(stiffness, "stiffness")?;
            non_negative(damping, "damping")?;
            non_negative(rest_length, "rest length")?;
        }
        JointKind::Rod { length } | JointKind::Rope { max_length: length } => {
            if length <= ZERO || length > limit {
                return Err(Error::OutOfRange { what: "length" });
            }
        }
        JointKind::Pivot { limits, motor } => {
            if let Some((lo, hi)) = limits {
                if lo > hi || lo < -scalar::PI || hi > scalar::PI {
                    return Err(Error::OutOfRange { what: "angle limits" });
                }
            }
            if let Some(Motor { max_torque: MaxTorque::Limited(t), .. }) = motor {
                non_negative(t, "max torque")?;
            }
        }
        JointKind::Weld => {}
    }
    if let Some(limit) = def.break_impulse {
        if limit <= ZERO {
            return Err(Error::OutOfRange { what: "break impulse" });
        }
    }
    Ok(())
}

impl Joint {
    pub(crate) fn new(def: JointDef, a: &Body, b: &Body) -> Self {
        Self::restored(def, a.rotation.inv_mul(b.rotation))
    }

    /// A joint with no accumulated impulses (creation, or a snapshot that sets them).
    pub(crate) fn restored(def: JointDef, reference: Rot) -> Self {
        Self {
            def,
            reference,
            impulse: Vector2::ZERO,
            angular_impulse: ZERO,
            motor_impulse: ZERO,
            limit_impulse: ZERO,
            step_linear: Vector2::ZERO,
            broken: false,
            soft: crate::solver::Softness::new(ZERO, ZERO, ZERO),
            inv_mass: [ZERO; 2],
            inv_inertia: [ZERO; 2],
            axial_mass: ZERO,
            point_mass: None,
        }
    }

    /// Once per step: masses and softness.
    pub(crate) fn prepare(&mut self, a: &Body, b: &Body, h: Scalar) {
        let (ma, ia) = crate::solver::inverse_mass(a);
        let (mb, ib) = crate::solver::inverse_mass(b);
        self.inv_mass = [ma, mb];
        self.inv_inertia = [ia, ib];
        // Divisions are slow in fixed point: the masses are inverted once per
        // step, at the step's anchors, as Box2D v2 does (v3 re-solves the 2×2
        // system every iteration, which here would cost two divisions a time).
        self.axial_mass = (ia + ib).recip();
        self.point_mass = if matches!(self.def.kind, JointKind::Pivot { .. } | JointKind::Weld) {
            let ra = a.rotation.rotate(self.def.anchor_a);
            let rb = b.rotation.rotate(self.def.anchor_b);
            point_mass_inverse(ma, ia, ra, mb, ib, rb)
        } else {
            None
        };
        const QUARTER: Scalar = Scalar::lit("0.25");
        let hertz = JOINT_HERTZ.min(h.recip() * QUARTER);
        self.soft = crate::solver::Softness::new(hertz, JOINT_DAMPING_RATIO, h);
        self.step_linear = Vector2::ZERO;
    }

    /// After the sub-steps: the step's impulse magnitude; true when it breaks.
    pub(crate) fn finish_step(&mut self) -> bool {
        // The magnitude costs a square root: only joints that can break need it.
        self.def.break_impulse.is_some_and(|limit| self.step_linear.length() > limit)
    }

    /// Applies the impulses it ended the last sub-step with.
    pub(crate) fn warm_start(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        match self.def.kind {
            JointKind::Spring { .. } | JointKind::DampedSpring { .. } => {}
            JointKind::Rod { .. } | JointKind::Rope { .. } => rod::warm_start(self, a, b),
            JointKind::Pivot { .. } => pivot::warm_start(self, a, b),
            JointKind::Weld => weld::warm_start(self, a, b),
        }
    }

    /// One iteration. `use_bias` is false in the relax sweep.
    pub(crate) fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, h: Scalar, use_bias: bool) {
        match self.def.kind {
            JointKind::Spring { stiffness, rest_length } => {
                if use_bias {
                    spring::apply(self, a, b, stiffness, ZERO, rest_length, h);
                }
            }
            JointKind::DampedSpring { stiffness, damping, rest_length } => {
                if use_bias {
                    spring::apply(self, a, b, stiffness, damping, rest_length, h);
                }
            }
            JointKind::Rod { length } => rod::solve(self, a, b, length, false, h, use_bias),
            JointKind::Rope { max_length } => rod::solve(self, a, b, max_length, true, h, use_bias),
            JointKind::Pivot { limits, motor } => pivot::solve(self, a, b, limits, motor, h, use_bias),
            JointKind::Weld => weld::solve(self, a, b, h, use_bias),
        }
    }
}

/// The world anchors of a joint: offsets from each centre (world orientation) and
/// the vector between the anchor points, B − A.
pub(crate) fn anchors(j: &Joint, a: &SolverBody, b: &SolverBody) -> (Vector2, Vector2, Vector2) {
    let ra = a.q.rotate(j.def.anchor_a);
    let rb = b.q.rotate(j.def.anchor_b);
    let d = (b.p - a.p) + (rb - ra);
    (ra, rb, d)
}

/// The inverse of K = (mA + mB)·I + iA·[rA]ᵀ[rA] + iB·[rB]ᵀ[rB], the mass matrix
/// of a point-to-point constraint with arms `ra`, `rb`, each entry divided
/// exactly (the determinant is tiny for heavy bodies, where 1/det would lose
/// the digits); `None` when singular.
fn point_mass_inverse(
    ma: Scalar,
    ia: Scalar,
    ra: Vector2,
    mb: Scalar,
    ib: Scalar,
    rb: Vector2,
) -> Option<Matrix22> {
    let m = ma + mb;
    let k11 = (m + (ia * (ra.y * ra.y))) + (ib * (rb.y * rb.y));
    let k12 = -((ia * (ra.x * ra.y)) + (ib * (rb.x * rb.y)));
    let k22 = (m + (ia * (ra.x * ra.x))) + (ib * (rb.x * rb.x));
    let det = (k11 * k22) - (k12 * k12);
    if det <= ZERO {
        return None;
    }
    let off = (-k12).div_or_zero(det);
    Some(Matrix22::new(k22.div_or_zero(det), off, off, k11.div_or_zero(det)))
}

/// Applies a linear impulse `p` at offsets `ra` (negated on A) and `rb`.
pub(crate) fn apply_linear(
    j: &Joint,
    a: &mut SolverBody,
    b: &mut SolverBody,
    ra: Vector2,
    rb: Vector2,
    p: Vector2,
) {
    let ([ma, mb], [ia, ib]) = (j.inv_mass, j.inv_inertia);
    a.v -= p * ma;
    a.w -= ia * ra.cross(p);
    b.v += p * mb;
    b.w += ib * rb.cross(p);
}

/// Applies an angular impulse `l` (negated on A).
pub(crate) fn apply_angular(j: &Joint, a: &mut SolverBody, b: &mut SolverBody, l: Scalar) {
    let [ia, ib] = j.inv_inertia;
    a.w -= ia * l;
    b.w += ib * l;
}

/// A game's constraint stored in a world.
pub(crate) struct UserConstraint<'a> {
    pub(crate) body_a: BodyHandle,
    pub(crate) body_b: Option<BodyHandle>,
    pub(crate) constraint: Hook<'a, dyn Constraint + Send + 'a>,
}

/// A world's game constraints, in registration order (slot order).
pub(crate) type UserConstraints<'a> = crate::arena::Arena<
    'a,
    UserConstraint<'a>,
    ConstraintMarker,
    [crate::arena::Slot<UserConstraint<'a>>; MAX_USER_CONSTRAINTS],
>;

/// A static body at the origin: the "other body" of a joint to a world point.
pub(crate) fn ground() -> Body {
    Body::ground()
}
