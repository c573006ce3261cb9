//! The contact solver's per-step working set: constraints built from the
//! arbiters once per step, in blocks of eight lanes, solved in the sub-step
//! loop, and written back.
//!
//! Box2D v3 keeps its solver data apart from its persistent contacts, and so do
//! we: an [`Arbiter`](crate::Arbiter) holds what outlives the step (the
//! manifold, the accumulated impulses, the state), while the sub-step loop
//! reads the constraints about twelve times a step. They are stored as
//! structure-of-arrays blocks: eight consecutive [`ContactConstraint`] records
//! of the world's storage form one block of [`FIELDS`] fields of eight lanes,
//! each lane one contact, so that a kernel works on eight contacts with each
//! field one 32-byte load. Constraints are placed in the blocks in graph-colour
//! order (see [`colour`](super::colour)).
//!
//! The stages, one file each: [`mod@prepare`] builds a lane from an arbiter (in
//! `Scalar`, where the masses are), [`kernel`] warm-starts, sweeps and bounces
//! the lanes in the formats of [`lanes`](super::lanes), and [`mod@store`] writes the
//! impulses back in N·s.

mod kernel;
mod prepare;
mod store;

#[cfg(all(feature = "std", target_arch = "x86_64"))]
pub(crate) use kernel::push_apart;
pub(crate) use kernel::{gather, scatter, Impacts, LaneParams, Restitute, SweepPass, WarmStart};
pub(crate) use prepare::prepare;
pub(crate) use store::store;

use crate::math::scalar::{Scalar, ZERO};

/// What the step keeps per arbiter beside its lane (solver scratch, one per
/// arbiter; see [`Storage`](crate::Storage)): its colour, its lane and the
/// effective masses that turn its impulses back into N·s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContactScratch {
    pub(crate) colour: u8,
    /// Set by the lifecycle: the arbiter's manifold was recycled, its
    /// friction is unchanged and it is at the position of the arbiter it
    /// continues, so this record still holds its last build (see
    /// `colour::build`; in what was padding).
    pub(crate) reuse: bool,
    /// The lane, or [`NO_LANE`] when the arbiter got none.
    pub(crate) lane: u32,
    /// Normal and tangent effective mass of each point (kg).
    pub(crate) mass: [[Scalar; 2]; 2],
}

impl ContactScratch {
    /// An unused record.
    pub const EMPTY: Self = Self { colour: 0, reuse: false, lane: NO_LANE, mass: [[ZERO; 2]; 2] };
}

/// [`ContactScratch::lane`] of an arbiter without a lane.
pub(crate) const NO_LANE: u32 = u32::MAX;

impl Default for ContactScratch {
    fn default() -> Self {
        Self::EMPTY
    }
}

use super::lanes::LANES;

/// Rows of eight lanes per storage record (a power of two, so that a field's
/// place is a shift and a mask).
const ROWS: usize = 8;
/// Fields per block of eight lanes.
pub(crate) const FIELDS: usize = ROWS * LANES;

/// One storage record of the contact solver (solver scratch; see
/// [`Storage`](crate::Storage)). Eight consecutive records form one block of
/// eight contact lanes; the record itself is ten of the block's fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct ContactConstraint {
    rows: [[i32; LANES]; ROWS],
}

impl ContactConstraint {
    /// An unused record.
    pub const EMPTY: Self = Self { rows: [[0; LANES]; ROWS] };
}

impl Default for ContactConstraint {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// Eight records: one block of eight lanes.
pub(crate) type Block = [ContactConstraint; LANES];

/// Field `f` of a block (all eight lanes).
#[inline(always)]
pub(crate) fn field(b: &Block, f: usize) -> &[i32; LANES] {
    &b[(f / ROWS) % LANES].rows[f % ROWS]
}

/// Lane `l` of a row (the lane number is taken modulo eight).
#[inline(always)]
pub(crate) fn lane(row: &[i32; LANES], l: usize) -> i32 {
    row[l % LANES]
}

/// Field `f` of a block, mutably.
#[inline(always)]
pub(crate) fn field_mut(b: &mut Block, f: usize) -> &mut [i32; LANES] {
    &mut b[(f / ROWS) % LANES].rows[f % ROWS]
}

/// The field numbers. Per-point fields are `P[p] + X`.
pub(crate) mod f {
    /// Body slots of A and B.
    pub(crate) const IA: usize = 0;
    pub(crate) const IB: usize = 1;
    /// [`super::A_DYNAMIC`] | [`super::B_DYNAMIC`] | [`super::TWO_POINTS`] | …
    pub(crate) const FLAGS: usize = 2;
    /// The normal (Q2.30), from A to B.
    pub(crate) const NX: usize = 3;
    pub(crate) const NY: usize = 4;
    /// Restitution (Q2.30).
    pub(crate) const E: usize = 5;
    /// Block couplings k12/k22 and k12/k11 (Q3.29).
    pub(crate) const C12: usize = 6;
    pub(crate) const C21: usize = 7;
    /// The normalised block inverse M̂ (Q5.27), rigid and soft: 11, 12, 21, 22.
    pub(crate) const MR: usize = 8;
    pub(crate) const MS: usize = 12;
    /// First field of each point.
    pub(crate) const P: [usize; 2] = [16, 16 + POINT];
    /// Fields per point.
    pub(crate) const POINT: usize = 24;
    /// Arms in body radii (Q3.29): (r×n)/r_b for A and B, (r×t)/r_b.
    pub(crate) const RAN: usize = 0;
    pub(crate) const RBN: usize = 1;
    pub(crate) const RAT: usize = 2;
    pub(crate) const RBT: usize = 3;
    /// ρ_A·n, ρ_B·n (Q2.30) and the rim ratios γ̂_A, γ̂_B of the normal row.
    pub(crate) const ANX: usize = 4;
    pub(crate) const ANY: usize = 5;
    pub(crate) const BNX: usize = 6;
    pub(crate) const BNY: usize = 7;
    pub(crate) const GAN: usize = 8;
    pub(crate) const GBN: usize = 9;
    /// The same for the tangent row.
    pub(crate) const ATX: usize = 10;
    pub(crate) const ATY: usize = 11;
    pub(crate) const BTX: usize = 12;
    pub(crate) const BTY: usize = 13;
    pub(crate) const GAT: usize = 14;
    pub(crate) const GBT: usize = 15;
    /// Accumulated impulses in velocity units (Q16.16).
    pub(crate) const LN: usize = 16;
    pub(crate) const LT: usize = 17;
    /// Separation at the start of the step (Q13.19).
    pub(crate) const BASE: usize = 18;
    /// Friction factor φ (Q9.23) and the normal impulse cap c_φ (Q16.16).
    pub(crate) const PHI: usize = 19;
    pub(crate) const CPHI: usize = 20;
    /// The fastest approach seen (restitution reference, Q16.16).
    pub(crate) const VREL: usize = 21;
    /// The largest normal impulse change of the step (Q16.16).
    pub(crate) const MAXD: usize = 22;
    /// The step's sum of the impulses carried from one sub-step to the next
    /// (Q18.14: at most 15 × Λ).
    pub(crate) const TOT: usize = 23;
}

const _: () = assert!(f::P[1] + f::POINT == FIELDS);

/// Flag: body A takes impulses.
pub(crate) const A_DYNAMIC: i32 = 1;
/// Flag: body B takes impulses.
pub(crate) const B_DYNAMIC: i32 = 2;
/// Flag: the manifold has two points.
pub(crate) const TWO_POINTS: i32 = 4;
/// Flag: one body has infinite mass (the static softness applies).
pub(crate) const STATIC_PAIR: i32 = 8;
/// Flag: the two points may be solved as a block (set only with [`TWO_POINTS`]).
pub(crate) const HAS_BLOCK: i32 = 16;
