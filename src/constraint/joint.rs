//! A built-in joint in a world: its definition and the impulses it carries
//! from sub-step to sub-step (part of the snapshot); once per step it builds
//! its row in the solver's dense joint array ([`JointRow`]) and takes the
//! impulses back from it at the end of the step.

use crate::arena::Handle;
use crate::body::Body;
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};
use crate::solver::{
    pivot_impulses, JointLanes, JointMasses, JointStep, LaneSoft, PivotStart, PointRecord, Softness,
    SolverBody,
};

use super::def::validate_motor;
use super::row::{ConstraintKind, ConstraintRow, JointRow, RowSolve, SpringRow};
use super::{JointDef, JointKind, MaxTorque, Motor};

/// Stiffness of the soft position correction of rods, ropes, pivots and welds, Hz
/// (Box2D v3's joint default; capped at a quarter of the sub-step rate).
pub const JOINT_HERTZ: Scalar = Scalar::from_int(60);
/// Damping ratio of that correction (Box2D v3's joint default).
pub const JOINT_DAMPING_RATIO: Scalar = Scalar::from_int(2);

/// Frequency of a target joint's spin damping, Hz (Box2D v3's mouse joint):
/// a soft angular row with no bias, so it only slows the body's spin (a body
/// held off its centre stops swinging about the held point), with no angle
/// to return to.
pub const TARGET_SPIN_HERTZ: Scalar = Scalar::lit("0.5");
/// Damping ratio of that spin damping (Box2D v3's mouse joint).
pub const TARGET_SPIN_DAMPING_RATIO: Scalar = Scalar::lit("0.1");

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

    /// A target joint's world target point (`None` for other kinds); see
    /// [`World::set_joint_target`](crate::World::set_joint_target).
    #[must_use]
    pub fn target(&self) -> Option<Vector2> {
        matches!(self.def.kind, JointKind::Target { .. }).then_some(self.def.anchor_b)
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
        }
    }

    /// Once per step: the joint's row for the sub-steps, in slot `slot`:
    /// masses, the step's joint softness (see `StepContext::joint_softness`),
    /// the impulses in lane formats and the pose of the first sub-step. `sa`,
    /// `sb` are the solver's copies of `a` and `b`; `step` holds the softness
    /// and the sub-step.
    ///
    /// Written into `row` in place (whatever it held): a constraint's lanes
    /// are some 280 bytes, and building the row and returning it cost three
    /// copies of them a joint a step.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn prepare(
        &mut self,
        row: &mut JointRow,
        slot: u32,
        a: &Body,
        b: &Body,
        sa: &SolverBody,
        sb: &SolverBody,
        step: &JointStep,
    ) {
        let h = step.h;
        let (ma, ia) = crate::solver::inverse_mass(a);
        let (mb, ib) = crate::solver::inverse_mass(b);
        self.step_linear = Vector2::ZERO;
        let world_point = self.def.body_b.is_none();
        row.bodies = [self.def.body_a.index(), self.def.body_b.map_or(0, |hb| hb.index())];
        row.slot = slot;
        row.world_point = world_point;
        row.pivot_colour = JointRow::NO_LANES;
        let anchors = [self.def.anchor_a, self.def.anchor_b];
        let spring = |stiffness, damping, rest_length| {
            RowSolve::Spring(SpringRow {
                stiffness,
                damping,
                rest_length,
                anchors,
                inv_mass: [ma, mb],
                inv_inertia: [ia, ib],
                step_linear: Vector2::ZERO,
            })
        };
        let mut soft = step.lane_soft;
        let (mut max_impulse, mut spin_damping) = (None, None);
        let (kind, motor, limits) = match self.def.kind {
            JointKind::Spring { stiffness, rest_length } => {
                row.solve = spring(stiffness, ZERO, rest_length);
                return;
            }
            JointKind::DampedSpring { stiffness, damping, rest_length } => {
                row.solve = spring(stiffness, damping, rest_length);
                return;
            }
            JointKind::Rod { length } => (ConstraintKind::Rod { length }, None, None),
            JointKind::Rope { max_length } => (ConstraintKind::Rope { max_length }, None, None),
            JointKind::Pivot { limits, motor } => {
                (ConstraintKind::Pivot { limits: limits.is_some(), motor: motor.is_some() }, motor, limits)
            }
            JointKind::Weld => (ConstraintKind::Weld, None, None),
            JointKind::Target { hertz, damping_ratio, max_force } => {
                // Its own spring, discretised for the sub-step, in place of the
                // joints' stiff position correction.
                soft = LaneSoft::new(Softness::new(hertz, damping_ratio, h));
                max_impulse = Some(max_force * h);
                spin_damping = Some(Softness::new(TARGET_SPIN_HERTZ, TARGET_SPIN_DAMPING_RATIO, h));
                (ConstraintKind::Target, None, None)
            }
        };
        let motor = motor.map(|m| {
            let max = match m.max_torque {
                MaxTorque::Limited(t) => Some(t * h),
                MaxTorque::Unlimited => None,
            };
            (m.speed, max)
        });
        let masses = JointMasses {
            inv_mass: [ma, mb],
            inv_inertia: [ia, ib],
            anchors,
            world_point,
            point: matches!(
                kind,
                ConstraintKind::Pivot { .. } | ConstraintKind::Weld | ConstraintKind::Target
            ),
            angular: matches!(kind, ConstraintKind::Weld | ConstraintKind::Target)
                || motor.is_some()
                || limits.is_some(),
            motor,
            limits,
            max_impulse,
            spin_damping,
        };
        let angular = [self.angular_impulse, self.motor_impulse, self.limit_impulse];
        if let RowSolve::Spring(_) = row.solve {
            // Every field of the lanes is set below.
            row.solve = RowSolve::Constraint(ConstraintRow {
                kind,
                reference: self.reference,
                lanes: JointLanes::INACTIVE,
            });
        }
        if let RowSolve::Constraint(c) = &mut row.solve {
            c.kind = kind;
            c.reference = self.reference;
            c.lanes.prepare(&masses, sa, sb, soft, step.inv_h, self.impulse, angular);
            c.measure(sa, sb);
        }
    }

    /// Once per step, for a pivot between two bodies with neither limits nor
    /// a motor (a plain pivot): its colour in the pivot lanes from `colour`
    /// (given its bodies' slots and whether the row moves each), recorded in
    /// the header of `row` for slot `slot`, and true; otherwise false with
    /// nothing written, and the caller prepares the joint's row
    /// ([`prepare`](Self::prepare)). `sa`, `sb` are the solver's copies of
    /// its bodies (`sb` none when B is gone: no lanes then); the lanes' fill
    /// builds the rest from them (`pivot_lanes::Colouring::fill`).
    ///
    /// The row moves a body when ρ or κ is not zero, which is when the body's
    /// inverse mass or inertia is: a dynamic body's mass is within
    /// [[`MIN_MASS`](crate::geometry::mass::MIN_MASS),
    /// [`MAX_MASS`](crate::geometry::mass::MAX_MASS)], a ratio below 2²⁷, so
    /// ρ = (1/m)/s is at least 2⁻²⁷ and never rounds to zero, and a body
    /// that is not dynamic has both zero. So the colour is the one a
    /// prepared row's ρ and κ gave, without the division that prepare needs.
    pub(crate) fn take_lanes(
        &mut self,
        row: &mut JointRow,
        slot: u32,
        (sa, sb): (&SolverBody, Option<&SolverBody>),
        colour: impl FnOnce([u32; 2], [bool; 2]) -> Option<u8>,
    ) -> bool {
        let (JointKind::Pivot { limits: None, motor: None }, Some(hb), Some(sb)) =
            (self.def.kind, self.def.body_b, sb)
        else {
            return false;
        };
        // s = 0: neither body dynamic, no row runs (and no lanes).
        if sa.inv_mass + sb.inv_mass <= ZERO {
            return false;
        }
        let moves = [sa, sb].map(|b| b.inv_mass != ZERO || b.inv_inertia != ZERO);
        let bodies = [self.def.body_a.index(), hb.index()];
        let Some(c) = colour(bodies, moves) else { return false };
        self.step_linear = Vector2::ZERO;
        row.bodies = bodies;
        row.slot = slot;
        row.world_point = false;
        row.pivot_colour = c;
        true
    }

    /// A plain pivot's record for the pivot lanes and its 1/s (see
    /// [`take_lanes`](Self::take_lanes)): what [`prepare`](Self::prepare)
    /// would give its row, the same bits. `None` if the joint is not one.
    #[inline(always)]
    pub(crate) fn pivot_record(&self, sa: &SolverBody, sb: &SolverBody) -> Option<(PointRecord, Scalar)> {
        let masses = JointMasses::plain_pivot(
            [sa.inv_mass, sb.inv_mass],
            [sa.inv_inertia, sb.inv_inertia],
            [self.def.anchor_a, self.def.anchor_b],
        );
        let start = PivotStart::new(&masses, sa, sb)?;
        Some((start.record(sa, sb, self.impulse), start.inv_s()))
    }

    /// A joint whose bodies are gone this step: no row, nothing applied,
    /// nothing to store.
    pub(crate) fn deactivate(&mut self) {
        self.step_linear = Vector2::ZERO;
        self.broken = false;
    }

    /// After the sub-steps, from the joint's row: the impulses back in
    /// `Scalar` (N·s, N·m·s), the step's impulse; true when it breaks.
    pub(crate) fn finish_step(&mut self, row: &JointRow) -> bool {
        match &row.solve {
            RowSolve::Spring(s) => self.step_linear += s.step_linear,
            RowSolve::Constraint(c) => {
                let (linear, angular) = c.lanes.active();
                match c.kind {
                    ConstraintKind::Rod { .. } | ConstraintKind::Rope { .. } => {
                        if linear {
                            self.impulse.x = c.lanes.linear_impulse().x;
                        }
                    }
                    ConstraintKind::Pivot { .. } | ConstraintKind::Weld | ConstraintKind::Target => {
                        if linear {
                            self.impulse = c.lanes.linear_impulse();
                        }
                        if angular {
                            [self.angular_impulse, self.motor_impulse, self.limit_impulse] =
                                c.lanes.angular_impulses();
                        }
                    }
                }
                self.step_linear += c.lanes.step_linear();
            }
        }
        self.breaks()
    }

    /// After the sub-steps, for a pivot in lanes: its accumulated λ̂ and the
    /// λ̂ it applied (see [`finish_step`](Self::finish_step)), with its 1/s;
    /// true when it breaks.
    pub(crate) fn finish_pivot(&mut self, lambda: [i32; 2], sum: [i64; 2], inv_s: Scalar) -> bool {
        let (impulse, step) = pivot_impulses(lambda, sum, inv_s);
        self.impulse = impulse;
        self.step_linear += step;
        self.breaks()
    }

    /// Whether the step's linear impulse breaks the joint.
    fn breaks(&self) -> bool {
        // The magnitude costs a square root: only joints that can break need it.
        self.def.break_impulse.is_some_and(|limit| self.step_linear.length() > limit)
    }
}
