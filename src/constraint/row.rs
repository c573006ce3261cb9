//! A joint's row in the solver's dense joint array: what the sub-steps of one
//! step need of a built-in joint, and the dispatch of each solver stage to its
//! kind's file ([`rod`], [`pivot`], …).
//!
//! The rows are scratch, as the contacts' constraints are: prepare builds one
//! per joint whose bodies are there, in joint-slot order
//! ([`Joint::prepare`](super::Joint)), the joint passes run over them densely,
//! in slot order, and the end of the step writes their impulses back
//! into the joints ([`Joint::finish_step`](super::Joint)). A row carries the
//! slots of its two bodies, so the passes never read a joint's slot. Nothing
//! in a row outlives the step, so none of it is in the snapshot.

use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};
use crate::solver::{Bias, BodyLanes, JointLanes, SolverBody};

use super::rod::Distance;
use super::{pivot, rod, spring, target, weld};

/// A built-in joint's row for one step.
///
/// A plain pivot the pivot lanes take uses only the header (the fields before
/// [`solve`](Self::solve), the row's first 32 bytes): its bodies,
/// slot, colour, lane and 1/s; the lanes hold the rest, and `solve` keeps
/// whatever it held. Joint grid (19,800 pivots): writing and reading back the
/// whole 320-byte row for each pivot cost some 6 MB of memory traffic a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct JointRow {
    /// Body slots of A and B (B's is unused for a joint to a world point).
    pub(crate) bodies: [u32; 2],
    /// The joint's slot: where the end of the step writes the impulses back.
    pub(crate) slot: u32,
    /// A pivot in lanes: its lane this step.
    pub(crate) lane: u32,
    /// A pivot in lanes: 1/s (1/(1/m_A + 1/m_B)), which turns its λ̂ back
    /// into N·s at the end of the step.
    pub(crate) inv_s: Scalar,
    /// B is a fixed world point: the passes give the joint a static stand-in.
    pub(crate) world_point: bool,
    /// The colour it takes in the pivot lanes this step, or
    /// [`NO_LANES`](Self::NO_LANES) when it is solved one at a time.
    pub(crate) pivot_colour: u8,
    /// The row solved one at a time (unused for a pivot in lanes).
    pub(crate) solve: RowSolve,
}

impl JointRow {
    /// [`pivot_colour`](Self::pivot_colour) of a row solved one at a time.
    pub(crate) const NO_LANES: u8 = u8::MAX;

    /// An unused row.
    pub const EMPTY: Self = Self {
        bodies: [0; 2],
        slot: 0,
        lane: 0,
        inv_s: ZERO,
        world_point: false,
        pivot_colour: Self::NO_LANES,
        solve: RowSolve::Spring(SpringRow::EMPTY),
    };
}

/// What a row solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RowSolve {
    /// A spring or damped spring: a force, in `Scalar`.
    Spring(SpringRow),
    /// A rod, rope, pivot, weld or target joint: a constraint in the solver's
    /// lane formats.
    Constraint(ConstraintRow),
}

/// A spring's data for the step (`Scalar`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SpringRow {
    /// N/m.
    pub(crate) stiffness: Scalar,
    /// N·s/m (zero for an undamped spring).
    pub(crate) damping: Scalar,
    /// m.
    pub(crate) rest_length: Scalar,
    /// Local anchors on A and B (m).
    pub(crate) anchors: [Vector2; 2],
    /// Inverse masses and inertias of A and B.
    pub(crate) inv_mass: [Scalar; 2],
    pub(crate) inv_inertia: [Scalar; 2],
    /// Linear impulse applied over the step so far (N·s).
    pub(crate) step_linear: Vector2,
}

impl SpringRow {
    pub(crate) const EMPTY: Self = Self {
        stiffness: ZERO,
        damping: ZERO,
        rest_length: ZERO,
        anchors: [Vector2::ZERO; 2],
        inv_mass: [ZERO; 2],
        inv_inertia: [ZERO; 2],
        step_linear: Vector2::ZERO,
    };
}

/// Which constraint a [`ConstraintRow`] is, with what its stages need of the
/// definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ConstraintKind {
    Rod { length: Scalar },
    Rope { max_length: Scalar },
    Pivot { limits: bool, motor: bool },
    Weld,
    Target,
}

/// A rod's, rope's, pivot's, weld's or target joint's data for the step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ConstraintRow {
    pub(crate) kind: ConstraintKind,
    /// Relative angle θB − θA at creation, as a rotation (limits and weld).
    pub(crate) reference: Rot,
    /// Everything the iterations use, in the solver's 32-bit formats.
    pub(crate) lanes: JointLanes,
}

impl ConstraintRow {
    /// What the arms and position error imply (after the pose): a rod's axis,
    /// a limited pivot's or a weld's relative angle.
    pub(crate) fn measure(&mut self, a: &SolverBody, b: &SolverBody) {
        match self.kind {
            ConstraintKind::Rod { length } | ConstraintKind::Rope { max_length: length } => {
                self.lanes.axis(length);
            }
            ConstraintKind::Pivot { limits, .. } => {
                if limits {
                    self.lanes.set_angle(pivot::relative_angle(self.reference, a, b));
                }
            }
            ConstraintKind::Weld => self.lanes.set_angle(pivot::relative_angle(self.reference, a, b)),
            ConstraintKind::Target => {}
        }
    }

    /// Applies the impulses it ended the last sub-step with.
    fn warm_start(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, world_point: bool) {
        let l = &mut self.lanes;
        match self.kind {
            ConstraintKind::Rod { .. } | ConstraintKind::Rope { .. } => l.warm_axial(la, lb),
            ConstraintKind::Pivot { .. } => {
                l.warm_point(la, lb);
                l.warm_angular(la, lb, world_point);
            }
            ConstraintKind::Weld => {
                l.warm_point(la, lb);
                l.warm_weld(la, lb);
            }
            ConstraintKind::Target => {
                l.warm_point(la, lb);
                l.warm_weld(la, lb);
            }
        }
    }

    #[inline(always)]
    fn solve(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, world_point: bool, bias: Bias) {
        let l = &mut self.lanes;
        match self.kind {
            ConstraintKind::Rod { .. } => rod::solve(l, la, lb, Distance::Exact, bias),
            ConstraintKind::Rope { .. } => rod::solve(l, la, lb, Distance::AtMost, bias),
            ConstraintKind::Pivot { limits, motor } => {
                pivot::solve(l, la, lb, limits, motor, world_point, bias)
            }
            ConstraintKind::Weld => weld::solve(l, la, lb, bias),
            ConstraintKind::Target => target::solve(l, la, lb),
        }
    }
}

impl JointRow {
    /// Applies the impulses it ended the last sub-step with (springs have
    /// none).
    pub(crate) fn warm_start(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        if let RowSolve::Constraint(c) = &mut self.solve {
            c.warm_start(la, lb, self.world_point);
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
        match &mut self.solve {
            RowSolve::Spring(s) => {
                if bias == Bias::On {
                    spring::apply(s, (a, la), (b, lb), h);
                }
            }
            // Each sweep with its `bias` a constant, so the inlined rows
            // drop what the other sweep needs.
            RowSolve::Constraint(c) => match bias {
                Bias::On => c.solve(la, lb, self.world_point, Bias::On),
                Bias::Off => {
                    c.lanes.pose(a, b);
                    c.measure(a, b);
                    c.solve(la, lb, self.world_point, Bias::Off);
                }
            },
        }
    }
}
