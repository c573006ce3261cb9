//! `Rect`: an axis-aligned rectangle (the world bounds and every bounding box).

use super::scalar::{Scalar, HALF};
use super::vector2::Vector2;

/// An axis-aligned rectangle from `min` (lower-left) to `max` (upper-right), in metres.
/// A rectangle with `min == max` is a point; both edges are inclusive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rect {
    /// Lower-left corner.
    pub min: Vector2,
    /// Upper-right corner.
    pub max: Vector2,
}

impl Rect {
    /// The rectangle spanning two corners given in any order.
    #[inline]
    #[must_use]
    pub fn from_corners(a: Vector2, b: Vector2) -> Self {
        Self { min: a.min(b), max: a.max(b) }
    }

    /// The rectangle with lower-left corner `origin`, `width` and `height`.
    #[inline]
    #[must_use]
    pub fn from_origin_size(origin: Vector2, width: Scalar, height: Scalar) -> Self {
        Self::from_corners(origin, origin + Vector2::new(width, height))
    }

    /// The rectangle centred on `center` reaching `half_extents` each way.
    #[inline]
    #[must_use]
    pub fn from_center(center: Vector2, half_extents: Vector2) -> Self {
        let h = half_extents.abs();
        Self { min: center - h, max: center + h }
    }

    /// Width (`max.x − min.x`).
    #[inline]
    #[must_use]
    pub fn width(self) -> Scalar {
        self.max.x - self.min.x
    }

    /// Height (`max.y − min.y`).
    #[inline]
    #[must_use]
    pub fn height(self) -> Scalar {
        self.max.y - self.min.y
    }

    /// The centre point.
    #[inline]
    #[must_use]
    pub fn center(self) -> Vector2 {
        (self.min + self.max) * HALF
    }

    /// The smallest rectangle containing both.
    #[inline]
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    /// True when the rectangles share at least one point (touching edges count).
    #[inline]
    #[must_use]
    pub fn overlaps(self, o: Self) -> bool {
        self.min.x <= o.max.x && o.min.x <= self.max.x && self.min.y <= o.max.y && o.min.y <= self.max.y
    }

    /// True when `p` lies inside or on the edge.
    #[inline]
    #[must_use]
    pub fn contains(self, p: Vector2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// True when `o` lies entirely inside (or on the edge of) this rectangle.
    #[inline]
    #[must_use]
    pub fn contains_rect(self, o: Self) -> bool {
        self.contains(o.min) && self.contains(o.max)
    }

    /// The rectangle grown by `margin` on every side (shrunk for a negative margin,
    /// never past its centre).
    #[must_use]
    pub fn expand(self, margin: Scalar) -> Self {
        let m = Vector2::new(margin, margin);
        let r = Self { min: self.min - m, max: self.max + m };
        if r.min.x > r.max.x || r.min.y > r.max.y {
            let c = self.center();
            Self { min: c, max: c }
        } else {
            r
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::scalar::from_int;

    #[test]
    fn overlap_union_contains_expand() {
        let a = Rect::from_corners(Vector2::from_int(0, 0), Vector2::from_int(2, 2));
        let b = Rect::from_corners(Vector2::from_int(2, 1), Vector2::from_int(5, 3));
        let c = Rect::from_corners(Vector2::from_int(3, 3), Vector2::from_int(4, 4));
        assert!(a.overlaps(b) && b.overlaps(a), "touching edges overlap");
        assert!(!a.overlaps(c));
        assert_eq!(a.union(c), Rect::from_corners(Vector2::ZERO, Vector2::from_int(4, 4)));
        assert!(a.contains(Vector2::from_int(1, 2)) && !a.contains(Vector2::from_int(3, 1)));
        assert_eq!(a.expand(from_int(1)).min, Vector2::from_int(-1, -1));
        assert_eq!(
            a.expand(from_int(-5)),
            Rect::from_corners(Vector2::from_int(1, 1), Vector2::from_int(1, 1))
        );
        assert!(a.expand(from_int(1)).contains_rect(a));
        assert_eq!(a.width(), from_int(2));
    }
}
