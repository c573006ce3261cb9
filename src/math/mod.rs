//! Fixed-point math: the [`Scalar`] number type and the small `Copy` value types
//! built on it. Every operator on these types saturates rather than overflows.

pub mod matrix22;
pub mod rect;
pub mod rot;
pub mod scalar;
pub mod trig;
pub mod vector2;

pub use matrix22::Matrix22;
pub use rect::Rect;
pub use rot::{Rot, Transform};
pub use scalar::Scalar;
pub use vector2::Vector2;
