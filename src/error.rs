//! Error type of every fallible public operation.
//!
//! Each variant says what was wrong and, where it helps, which parameter. An
//! operation that returns an error has changed nothing.

use core::fmt;

/// What went wrong in a call into the engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// A float given at the API edge was NaN, infinite, or outside the range a
    /// [`Scalar`](crate::Scalar) can hold. `what` names the parameter.
    NotFinite {
        /// The parameter.
        what: &'static str,
    },
    /// A parameter was outside its documented range (for example a negative
    /// friction, a zero or negative radius, mass or density). `what` names it.
    OutOfRange {
        /// The parameter.
        what: &'static str,
    },
    /// Fewer than three distinct, non-collinear points were given for a polygon.
    DegeneratePolygon,
    /// The convex hull of the points has more vertices than a polygon may have.
    TooManyVertices {
        /// Vertices on the hull.
        count: usize,
        /// The maximum, [`MAX_POLYGON_VERTICES`](crate::geometry::MAX_POLYGON_VERTICES).
        max: usize,
    },
    /// A position (or a body's extent around it) lies outside the world bounds.
    OutsideBounds,
    /// The time step was below [`MIN_TIME_STEP`](crate::MIN_TIME_STEP) (zero and
    /// negative included) or above [`MAX_TIME_STEP`](crate::MAX_TIME_STEP).
    InvalidTimeStep,
    /// The handle refers to an object that was removed (or never existed in this world).
    StaleHandle,
    /// A fixed-capacity store is full. `what` names it.
    CapacityFull {
        /// The store.
        what: &'static str,
    },
    /// A snapshot does not fit the buffer; `needed` bytes are required.
    BufferTooSmall {
        /// Bytes the snapshot needs.
        needed: usize,
    },
    /// Bytes given to `restore` are not a valid snapshot (truncated, corrupted,
    /// or from another format version). `what` says what was wrong.
    InvalidSnapshot {
        /// What failed to decode or validate.
        what: &'static str,
    },
    /// A valid snapshot that does not fit this world: different world settings,
    /// different polygon paths, too many objects for its capacities, or game hooks
    /// (custom generators) in other slots. `what` says which.
    SnapshotMismatch {
        /// What differs.
        what: &'static str,
    },
    /// The heap could not provide the storage asked for (with `alloc`: a
    /// world's buffers are reserved with `try_reserve`, never by aborting).
    /// `what` names the buffer.
    OutOfMemory {
        /// The buffer.
        what: &'static str,
    },
    /// The operation does not apply to this object in its current state
    /// (for example setting the velocity of a static body). `what` says which.
    InvalidOperation {
        /// The operation.
        what: &'static str,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite { what } => {
                write!(f, "`{what}` is NaN, infinite or out of the fixed-point range")
            }
            Self::OutOfRange { what } => write!(f, "`{what}` is outside its allowed range"),
            Self::DegeneratePolygon => {
                f.write_str("a polygon needs at least 3 distinct, non-collinear points")
            }
            Self::TooManyVertices { count, max } => {
                write!(f, "the convex hull has {count} vertices; at most {max} are allowed")
            }
            Self::OutsideBounds => f.write_str("the position lies outside the world bounds"),
            Self::InvalidTimeStep => f.write_str(
                "the time step must be at least MIN_TIME_STEP (2^-16 s) and at most MAX_TIME_STEP (0.25 s)",
            ),
            Self::StaleHandle => f.write_str("the handle refers to an object that no longer exists"),
            Self::CapacityFull { what } => write!(f, "the {what} store is full"),
            Self::InvalidOperation { what } => write!(f, "invalid operation: {what}"),
            Self::OutOfMemory { what } => write!(f, "the heap could not provide the {what} buffer"),
            Self::BufferTooSmall { needed } => {
                write!(f, "the buffer is too small: {needed} bytes are needed")
            }
            Self::InvalidSnapshot { what } => write!(f, "not a valid snapshot: {what}"),
            Self::SnapshotMismatch { what } => write!(f, "the snapshot does not fit this world: {what}"),
        }
    }
}

impl core::error::Error for Error {}
