//! Capsules and segments: the shapes built on a line segment.
//!
//! A [`Capsule`] is every point within `radius` of the segment between its two
//! centres; a [`Segment`] is the bare segment (no area: on a dynamic body it
//! needs an explicit mass). Both are stored in the body's local frame, relative
//! to its position (the centre of mass), so a capsule of a dynamic body is
//! symmetric about the origin.

use crate::math::{Scalar, Vector2};

/// A capsule: the points within `radius` of the segment `center1`–`center2`
/// (body-local, m).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Capsule {
    /// One end of the core segment (body-local, m).
    pub(crate) center1: Vector2,
    /// The other end of the core segment (body-local, m).
    pub(crate) center2: Vector2,
    /// Radius (m), > 0.
    pub(crate) radius: Scalar,
}

/// A line segment `point1`–`point2` (body-local, m): terrain, walls, one link of
/// a chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Segment {
    /// One end (body-local, m).
    pub(crate) point1: Vector2,
    /// The other end (body-local, m).
    pub(crate) point2: Vector2,
}

impl Capsule {
    /// One end of the core segment (body-local, m).
    #[inline]
    #[must_use]
    pub fn center1(&self) -> Vector2 {
        self.center1
    }

    /// The other end of the core segment (body-local, m).
    #[inline]
    #[must_use]
    pub fn center2(&self) -> Vector2 {
        self.center2
    }

    /// Radius (m).
    #[inline]
    #[must_use]
    pub fn radius(&self) -> Scalar {
        self.radius
    }
}

impl Segment {
    /// One end (body-local, m).
    #[inline]
    #[must_use]
    pub fn point1(&self) -> Vector2 {
        self.point1
    }

    /// The other end (body-local, m).
    #[inline]
    #[must_use]
    pub fn point2(&self) -> Vector2 {
        self.point2
    }
}
