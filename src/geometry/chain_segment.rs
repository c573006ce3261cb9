//! `ChainSegment`: one link of a chain, a one-sided segment that knows its
//! neighbours.
//!
//! A chain (terrain, a level's outline) is a polyline of segments. Each link
//! collides on one side only, to the right of `point1 → point2` (outward normal
//! `(d.y, −d.x)` for `d = point2 − point1`), so a counter-clockwise loop has its
//! solid inside. The ghost vertices are the far ends of the neighbouring links:
//! the narrow phase uses them to tell a join's internal edges from real corners,
//! so a body sliding across collinear links never meets the next link's end
//! (the "ghost collision" that makes a box catch on a seam).

use crate::geometry::Segment;
use crate::math::Vector2;

/// One link of a chain: the segment and the vertices before and after it
/// (body-local, m).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ChainSegment {
    /// The previous link's start (its end is `segment.point1`).
    pub(crate) ghost1: Vector2,
    /// This link, solid on its left, colliding on its right.
    pub(crate) segment: Segment,
    /// The next link's end (its start is `segment.point2`).
    pub(crate) ghost2: Vector2,
}

impl ChainSegment {
    /// The previous link's start (body-local, m).
    #[inline]
    #[must_use]
    pub fn ghost1(&self) -> Vector2 {
        self.ghost1
    }

    /// The link itself (body-local).
    #[inline]
    #[must_use]
    pub fn segment(&self) -> Segment {
        self.segment
    }

    /// The next link's end (body-local, m).
    #[inline]
    #[must_use]
    pub fn ghost2(&self) -> Vector2 {
        self.ghost2
    }
}
