//! A built-in joint in a world: its definition, the impulses it carries from
//! sub-step to sub-step (part of the snapshot), the masses and softness it
//! derives once per step, and the dispatch of each solver stage to its kind's
//! file ([`rod`](super::rod), [`pivot`](super::pivot), …).

use crate::arena::Handle;
use crate::body::Body;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};
use crate::solver::{Bias, BodyLanes, JointLanes, JointMasses, Softness, SolverBody};

use super::def::validate_motor;
use super::rod::Distance;
use super::{pivot, rod, spring, weld, JointDef, JointKind, MaxTorque, Motor};

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
    /// Inverse masses and inertias (springs, which stay in `Scalar`).
    pub(crate) inv_mass: [Scalar; 2],
    pub(crate) inv_inertia: [Scalar; 2],
    /// Everything else the sub-steps use, in the solver's 32-bit formats
    /// (rebuilt from the impulses above at every prepare).
    pub(crate) lanes: JointLanes,
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
            inv_mass: [ZERO; 2],
            inv_inertia: [ZERO; 2],
            lanes: JointLanes::INACTIVE,
        }
    }

    /// Once per step: masses, the step's joint softness (see
    /// `StepContext::joint_softness`), the impulses in lane formats and the
    /// pose of the first sub-step. `sa`, `sb` are the solver's copies of `a`
    /// and `b`; `h` is the sub-step.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn prepare(
        &mut self,
        a: &Body,
        b: &Body,
        sa: &SolverBody,
        sb: &SolverBody,
        soft: Softness,
        h: Scalar,
        inv_h: Scalar,
    ) {
        let (ma, ia) = crate::solver::inverse_mass(a);
        let (mb, ib) = crate::solver::inverse_mass(b);
        self.inv_mass = [ma, mb];
        self.inv_inertia = [ia, ib];
        self.step_linear = Vector2::ZERO;
        let (point, motor, limits) = match self.def.kind {
            JointKind::Spring { .. } | JointKind::DampedSpring { .. } => {
                self.lanes = JointLanes::INACTIVE;
                return;
            }
            JointKind::Rod { .. } | JointKind::Rope { .. } => (false, None, None),
            JointKind::Pivot { limits, motor } => (true, motor, limits),
            JointKind::Weld => (true, None, None),
        };
        let motor = motor.map(|m| {
            let max = match m.max_torque {
                MaxTorque::Limited(t) => Some(t * h),
                MaxTorque::Unlimited => None,
            };
            (m.speed, max)
        });
        let masses = JointMasses {
            inv_mass: self.inv_mass,
            inv_inertia: self.inv_inertia,
            anchors: [self.def.anchor_a, self.def.anchor_b],
            world_point: self.def.body_b.is_none(),
            point,
            angular: matches!(self.def.kind, JointKind::Weld) || motor.is_some() || limits.is_some(),
            motor,
            limits,
        };
        let angular = [self.angular_impulse, self.motor_impulse, self.limit_impulse];
        self.lanes = JointLanes::prepare(&masses, sa, sb, soft, inv_h, self.impulse, angular);
        self.measure(sa, sb);
    }

    /// A joint whose bodies are gone this step: nothing to solve, nothing to
    /// store.
    pub(crate) fn deactivate(&mut self) {
        self.lanes = JointLanes::INACTIVE;
        self.step_linear = Vector2::ZERO;
    }

    /// The pose-dependent part at the bodies' current pose: arms, position
    /// error, then [`measure`](Self::measure).
    fn refresh(&mut self, a: &SolverBody, b: &SolverBody) {
        if !matches!(self.def.kind, JointKind::Spring { .. } | JointKind::DampedSpring { .. }) {
            self.lanes.pose(a, b);
            self.measure(a, b);
        }
    }

    /// What the arms and position error imply (after `pose`): a rod's axis, a
    /// limited pivot's or a weld's relative angle.
    fn measure(&mut self, a: &SolverBody, b: &SolverBody) {
        match self.def.kind {
            JointKind::Spring { .. } | JointKind::DampedSpring { .. } => {}
            JointKind::Rod { length } | JointKind::Rope { max_length: length } => self.lanes.axis(length),
            JointKind::Pivot { limits, .. } => {
                if limits.is_some() {
                    self.lanes.set_angle(pivot::relative_angle(self, a, b));
                }
            }
            JointKind::Weld => self.lanes.set_angle(pivot::relative_angle(self, a, b)),
        }
    }

    /// After the sub-steps: the impulses back in `Scalar` (N·s, N·m·s), the
    /// step's impulse; true when it breaks.
    pub(crate) fn finish_step(&mut self) -> bool {
        let (linear, angular) = self.lanes.active();
        match self.def.kind {
            JointKind::Spring { .. } | JointKind::DampedSpring { .. } => {}
            JointKind::Rod { .. } | JointKind::Rope { .. } => {
                if linear {
                    self.impulse.x = self.lanes.linear_impulse().x;
                }
            }
            JointKind::Pivot { .. } | JointKind::Weld => {
                if linear {
                    self.impulse = self.lanes.linear_impulse();
                }
                if angular {
                    [self.angular_impulse, self.motor_impulse, self.limit_impulse] =
                        self.lanes.angular_impulses();
                }
            }
        }
        self.step_linear += self.lanes.step_linear();
        // The magnitude costs a square root: only joints that can break need it.
        self.def.break_impulse.is_some_and(|limit| self.step_linear.length() > limit)
    }

    /// Applies the impulses it ended the last sub-step with.
    pub(crate) fn warm_start(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        let world_point = self.def.body_b.is_none();
        let l = &mut self.lanes;
        match self.def.kind {
            JointKind::Spring { .. } | JointKind::DampedSpring { .. } => {}
            JointKind::Rod { .. } | JointKind::Rope { .. } => l.warm_axial(la, lb),
            JointKind::Pivot { .. } => {
                l.warm_point(la, lb);
                l.warm_angular(la, lb, world_point);
            }
            JointKind::Weld => {
                l.warm_point(la, lb);
                l.warm_weld(la, lb);
            }
        }
    }

    /// One iteration: with `Bias::On` in the biased sweep of each sub-step
    /// (springs apply their force only then), `Bias::Off` in the relax sweep,
    /// which follows the integration and so first measures the new pose.
    pub(crate) fn solve(
        &mut self,
        (a, la): (&mut SolverBody, &mut BodyLanes),
        (b, lb): (&mut SolverBody, &mut BodyLanes),
        h: Scalar,
        bias: Bias,
    ) {
        if bias == Bias::Off {
            self.refresh(a, b);
        }
        match self.def.kind {
            JointKind::Spring { stiffness, rest_length } => {
                if bias == Bias::On {
                    spring::apply(self, (a, la), (b, lb), stiffness, ZERO, rest_length, h);
                }
            }
            JointKind::DampedSpring { stiffness, damping, rest_length } => {
                if bias == Bias::On {
                    spring::apply(self, (a, la), (b, lb), stiffness, damping, rest_length, h);
                }
            }
            JointKind::Rod { .. } => rod::solve(self, la, lb, Distance::Exact, bias),
            JointKind::Rope { .. } => rod::solve(self, la, lb, Distance::AtMost, bias),
            JointKind::Pivot { limits, motor } => {
                pivot::solve(self, la, lb, limits.is_some(), motor.is_some(), bias)
            }
            JointKind::Weld => weld::solve(self, la, lb, bias),
        }
    }
}
