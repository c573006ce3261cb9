//! Joint definitions: what a game writes to create a joint (the kinds, their
//! parameters, motors and limits) and the checks a definition must pass, on
//! creation and again when a snapshot is restored.

use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::limits::{
    check_range, MAX_BODY_RADIUS, MAX_DAMPING, MAX_DAMPING_RATIO, MAX_FORCE, MAX_JOINT_LENGTH,
    MAX_MOTOR_SPEED, MAX_STIFFNESS, MAX_TARGET_HERTZ,
};
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rect, Vector2};

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
    /// Target relative angular speed, rad/s, within
    /// ±[`MAX_MOTOR_SPEED`] (512).
    pub speed: Scalar,
    /// Torque limit.
    pub max_torque: MaxTorque,
}

/// What kind of joint, with its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A spring of `stiffness` N/m and rest length `rest_length` m.
    Spring {
        /// N/m, in [0, [`MAX_STIFFNESS`]] (1e6).
        stiffness: Scalar,
        /// m, in [0, [`MAX_JOINT_LENGTH`]] (1,024).
        rest_length: Scalar,
    },
    /// A spring with a damper of `damping` N·s/m.
    DampedSpring {
        /// N/m, in [0, [`MAX_STIFFNESS`]] (1e6).
        stiffness: Scalar,
        /// N·s/m, in [0, [`MAX_DAMPING`]] (1e5).
        damping: Scalar,
        /// m, in [0, [`MAX_JOINT_LENGTH`]] (1,024).
        rest_length: Scalar,
    },
    /// Keeps the anchors exactly `length` m apart (the manual's Rod).
    Rod {
        /// m, in (0, [`MAX_JOINT_LENGTH`]] (1,024).
        length: Scalar,
    },
    /// Keeps the anchors at most `max_length` m apart; slack below.
    Rope {
        /// m, in (0, [`MAX_JOINT_LENGTH`]] (1,024).
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
    /// Pulls body A's anchor towards a world target point (Box2D's mouse joint):
    /// a soft point constraint, a spring–damper given as a frequency and a
    /// damping ratio (so it behaves the same whatever the body's mass: stiffness
    /// m·ω², ω = 2π·`hertz`), whose force never exceeds `max_force`. Only with
    /// [`JointDef::to_world`]: the target is the definition's world point, moved
    /// by [`World::set_joint_target`](crate::World::set_joint_target). What a
    /// game drags a body with (the testbed's mouse). The body turns about the
    /// anchor, its spin softly damped as by Box2D v3's mouse joint
    /// ([`TARGET_SPIN_HERTZ`](crate::constraint::TARGET_SPIN_HERTZ)); removing
    /// the joint lets it fly on with its speed (a throw).
    Target {
        /// Frequency of the spring, Hz, in (0, [`MAX_TARGET_HERTZ`]] (1,000).
        hertz: Scalar,
        /// Damping ratio (1: critically damped), in [0,
        /// [`MAX_DAMPING_RATIO`]] (100).
        damping_ratio: Scalar,
        /// Largest force, N, in [0, [`MAX_FORCE`]]: the
        /// accumulated impulse of each sub-step is clamped to `max_force`·h by
        /// length.
        max_force: Scalar,
    },
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
/// parameters, break impulse. Used by [`World::add_joint`](crate::World::add_joint)
/// and by `restore`; the setters call the same per-value checks.
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
    match def.kind {
        JointKind::Spring { stiffness, rest_length } => {
            check_range(stiffness, ZERO, MAX_STIFFNESS, "stiffness")?;
            check_range(rest_length, ZERO, MAX_JOINT_LENGTH, "rest length")?;
        }
        JointKind::DampedSpring { stiffness, damping, rest_length } => {
            check_range(stiffness, ZERO, MAX_STIFFNESS, "stiffness")?;
            check_range(damping, ZERO, MAX_DAMPING, "damping")?;
            check_range(rest_length, ZERO, MAX_JOINT_LENGTH, "rest length")?;
        }
        JointKind::Rod { length } | JointKind::Rope { max_length: length } => {
            if length <= ZERO || length > MAX_JOINT_LENGTH {
                return Err(Error::OutOfRange { what: "length" });
            }
        }
        JointKind::Pivot { limits, motor } => {
            if let Some((lo, hi)) = limits {
                if lo > hi || lo < -scalar::PI || hi > scalar::PI {
                    return Err(Error::OutOfRange { what: "angle limits" });
                }
            }
            validate_motor(motor)?;
        }
        JointKind::Weld => {}
        JointKind::Target { hertz, damping_ratio, max_force } => {
            if def.body_b.is_some() {
                return Err(Error::InvalidOperation { what: "a target joint with a second body" });
            }
            if hertz <= ZERO || hertz > MAX_TARGET_HERTZ {
                return Err(Error::OutOfRange { what: "hertz" });
            }
            check_range(damping_ratio, ZERO, MAX_DAMPING_RATIO, "damping ratio")?;
            check_range(max_force, ZERO, MAX_FORCE, "max force")?;
        }
    }
    if let Some(limit) = def.break_impulse {
        if limit <= ZERO {
            return Err(Error::OutOfRange { what: "break impulse" });
        }
    }
    Ok(())
}

/// A pivot's motor: speed within ±[`MAX_MOTOR_SPEED`], a torque limit ≥ 0. The
/// one check of a motor, used by `add_joint`, [`Joint::set_motor`](super::Joint::set_motor)
/// and `restore`.
pub(crate) fn validate_motor(motor: Option<Motor>) -> Result<(), Error> {
    let Some(Motor { speed, max_torque }) = motor else { return Ok(()) };
    check_range(speed, -MAX_MOTOR_SPEED, MAX_MOTOR_SPEED, "motor speed")?;
    if let MaxTorque::Limited(t) = max_torque {
        check_range(t, ZERO, Scalar::MAX, "max torque")?;
    }
    Ok(())
}
