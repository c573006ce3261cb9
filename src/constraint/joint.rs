//! A built-in joint in a world: its definition, the impulses it carries from
//! sub-step to sub-step (part of the snapshot), the masses and softness it
//! derives once per step, and the dispatch of each solver stage to its kind's
//! file ([`rod`](super::rod), [`pivot`](super::pivot), …).

use crate::arena::Handle;
use crate::body::Body;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Matrix22;
use crate::math::{Rot, Vector2};
use crate::solver::{Bias, Softness, SolverBody};

use super::def::validate_motor;
use super::maths::point_mass_inverse;
use super::rod::Distance;
use super::{pivot, rod, spring, weld, JointDef, JointKind, Motor};

/// Stiffness of the soft position correction of rods, ropes, pivots and welds, Hz
/// (Box2D v3's joint default; capped at a quarter of the sub-step rate).
pub const JOINT_HERTZ: Scalar = Scalar::from_int(60);
/// Damping ratio of that correction (Box2D v3's joint default).
pub const JOINT_DAMPING_RATIO: Scalar = Scalar::from_int(2);

/// Marker type naming built-in joints in handles.
#[derive(Debug)]
pub enum JointMarker {}
/// Handle of a built-in joint.
pub type JointHandle = Handle<JointMarker>;

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

    /// Changes the motor of a pivot (no effect on other kinds), checked exactly
    /// as [`World::add_joint`](crate::World::add_joint) and
    /// [`World::restore`](crate::World::restore) check it, so the world's
    /// snapshot always restores.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"motor speed"` for a speed beyond
    /// ±[`MAX_MOTOR_SPEED`](crate::limits::MAX_MOTOR_SPEED) or `"max torque"` for
    /// a negative torque limit; the joint is unchanged.
    pub fn set_motor(&mut self, motor: Option<Motor>) -> Result<(), Error> {
        validate_motor(motor)?;
        if let JointKind::Pivot { motor: m, .. } = &mut self.def.kind {
            *m = motor;
        }
        Ok(())
    }
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
            soft: Softness::RIGID,
            inv_mass: [ZERO; 2],
            inv_inertia: [ZERO; 2],
            axial_mass: ZERO,
            point_mass: None,
        }
    }

    /// Once per step: masses, and the step's joint softness (see
    /// `StepContext::joint_softness`).
    pub(crate) fn prepare(&mut self, a: &Body, b: &Body, soft: Softness) {
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
        self.soft = soft;
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

    /// One iteration: with `Bias::On` in the biased sweep of each sub-step
    /// (springs apply their force only then), `Bias::Off` in the relax sweep.
    pub(crate) fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, h: Scalar, bias: Bias) {
        match self.def.kind {
            JointKind::Spring { stiffness, rest_length } => {
                if bias == Bias::On {
                    spring::apply(self, a, b, stiffness, ZERO, rest_length, h);
                }
            }
            JointKind::DampedSpring { stiffness, damping, rest_length } => {
                if bias == Bias::On {
                    spring::apply(self, a, b, stiffness, damping, rest_length, h);
                }
            }
            JointKind::Rod { length } => rod::solve(self, a, b, length, Distance::Exact, h, bias),
            JointKind::Rope { max_length } => rod::solve(self, a, b, max_length, Distance::AtMost, h, bias),
            JointKind::Pivot { limits, motor } => pivot::solve(self, a, b, limits, motor, h, bias),
            JointKind::Weld => weld::solve(self, a, b, h, bias),
        }
    }
}
