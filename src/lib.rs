#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]
//! arphysics (crate docs being written).

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod collide;
pub mod error;
pub mod geometry;
pub mod math;

pub use error::Error;
pub use math::{Matrix22, Rect, Rot, Scalar, Transform, Vector2};

/// The largest time step `World::step` accepts, in seconds.
pub const MAX_TIME_STEP: Scalar = Scalar::ONE;
