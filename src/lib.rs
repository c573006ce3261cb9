#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]
//! arphysics (crate docs being written).

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod arbiter;
pub mod arena;
pub mod body;
pub mod collide;
pub mod collision;
pub mod error;
pub mod force;
pub mod geometry;
pub mod handler;
pub mod index;
pub mod math;
mod snapshot;
mod solver;
mod step;
pub mod world;

pub use arbiter::{Arbiter, ArbiterState, ContactPoint};
pub use arena::{Handle, Slot};
pub use body::{Body, BodyDef, BodyHandle, BodyType, MassSpec, PathHandle, Shape};
pub use collision::Index;
pub use error::Error;
pub use force::{
    ForceGenerator, Generator, GravityForceGenerator, GravityToPointForceGenerator, LinearForceGenerator,
    Targets,
};
pub use geometry::{MassData, PolygonPath};
pub use handler::{CallbackContext, CollisionHandler, FnHandler, Handler, PostStepFn};
pub use index::{BruteForceIndex, PairSink, Proxy, SpatialIndex};
pub use math::{Matrix22, Rect, Rot, Scalar, Transform, Vector2};
pub use world::{Capacities, GeneratorHandle, StepReport, Storage, World, WorldBuffers, WorldDef};

/// The longest time step [`World::step`] accepts: 0.25 s. Longer steps are never
/// physically meaningful and would let fast bodies move too far in one step.
pub const MAX_TIME_STEP: Scalar = Scalar::lit("0.25");
