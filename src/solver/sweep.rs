//! What a sweep is: one pass over the constraints, in a direction, with or
//! without the position bias. The sub-step loop names both at every call
//! (`contact::solve(.., Bias::Off, Sweep::Reverse)`) instead of passing bare
//! flags.

/// The direction of a sweep over the constraints: in their canonical order
/// (contacts in colour order, joints in slot order) or in reverse. A contact's
/// two points, when solved one at a time, follow the same direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sweep {
    /// First to last.
    Forward,
    /// Last to first.
    Reverse,
}

impl Sweep {
    /// The other direction.
    pub(crate) fn reversed(self) -> Self {
        match self {
            Sweep::Forward => Sweep::Reverse,
            Sweep::Reverse => Sweep::Forward,
        }
    }
}

/// Whether a sweep corrects positions. The biased sweeps of a sub-step push
/// overlap and joint error out through the soft constraints (and springs apply
/// their force); the relax sweeps after the positions are integrated solve the
/// velocity constraints rigidly, so the push-out leaves no energy behind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Bias {
    /// Soft, with the position bias.
    On,
    /// Rigid, without it (relax).
    Off,
}
