//! The contact solver's per-step working set: compact records built from the
//! arbiters once per step, solved in the sub-step loop, and written back.
//!
//! Box2D v3 keeps its solver data apart from its persistent contacts for speed,
//! and so do we: an [`Arbiter`](crate::Arbiter) holds what outlives the step
//! (the manifold, the accumulated impulses, the state) and is double-buffered
//! for the merge with the new pairs, while the sub-step loop reads the same
//! constraint and body data about twelve times a step. Those loops run over two
//! dense arrays:
//!
//! * [`SolverBody`](crate::solver::SolverBody): one per body slot, the body's
//!   velocity and pose and nothing else (88 bytes, against 216 for a
//!   [`Body`](crate::Body) slot);
//! * [`ContactConstraint`]: one per solved arbiter, in arbiter (pair-key) order,
//!   with the anchors, arms, effective masses and impulses precomputed.
//!
//! Both live in the world's [`Storage`](crate::Storage), so the step allocates
//! nothing; their contents are derived each step and are not part of a snapshot.
//!
//! The stages, in the order a step runs them, one file each: [`prepare`] builds
//! the constraints, [`solve`] warm-starts and sweeps them in every sub-step, and
//! [`restitution`] adds the bounce and stores the impulses back.

mod prepare;
mod restitution;
mod solve;

pub use prepare::ContactConstraint;
pub(crate) use prepare::{prepare, StepParams};
pub(crate) use restitution::restitute_and_store;
pub(crate) use solve::{solve, warm_start, Carried};
