//! `Matrix22`: a 2×2 matrix, used for point constraints (pivots, welds) and block
//! solvers.

use core::ops::{Add, Mul};

use super::scalar::{Scalar, ZERO};
use super::vector2::Vector2;

/// A 2×2 matrix stored by columns: `[col1 col2]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Matrix22 {
    /// First column.
    pub col1: Vector2,
    /// Second column.
    pub col2: Vector2,
}

impl Matrix22 {
    /// The zero matrix.
    pub const ZERO: Self = Self { col1: Vector2::ZERO, col2: Vector2::ZERO };
    /// The identity matrix.
    pub const IDENTITY: Self = Self { col1: Vector2::X, col2: Vector2::Y };

    /// A matrix from its two columns.
    #[inline]
    #[must_use]
    pub const fn from_cols(col1: Vector2, col2: Vector2) -> Self {
        Self { col1, col2 }
    }

    /// A matrix from its entries in reading order: `[[a, b], [c, d]]`.
    #[inline]
    #[must_use]
    pub const fn new(a: Scalar, b: Scalar, c: Scalar, d: Scalar) -> Self {
        Self { col1: Vector2::new(a, c), col2: Vector2::new(b, d) }
    }

    /// The transpose.
    #[inline]
    #[must_use]
    pub fn transpose(self) -> Self {
        Self::new(self.col1.x, self.col1.y, self.col2.x, self.col2.y)
    }

    /// The determinant.
    #[inline]
    #[must_use]
    pub fn determinant(self) -> Scalar {
        self.col1.cross(self.col2)
    }

    /// The inverse, or `None` when the matrix is singular (determinant 0).
    #[must_use]
    pub fn inverse(self) -> Option<Self> {
        let det = self.determinant();
        if det == ZERO {
            return None;
        }
        let inv = det.recip();
        let (a, b, c, d) = (self.col1.x, self.col2.x, self.col1.y, self.col2.y);
        Some(Self::new(d * inv, -b * inv, -c * inv, a * inv))
    }

    /// Solves `self · x = b` for `x`, or `None` when the matrix is singular.
    #[must_use]
    pub fn solve(self, b: Vector2) -> Option<Vector2> {
        let det = self.determinant();
        if det == ZERO {
            return None;
        }
        let (a11, a12, a21, a22) = (self.col1.x, self.col2.x, self.col1.y, self.col2.y);
        let x = (a22 * b.x) - (a12 * b.y);
        let y = (a11 * b.y) - (a21 * b.x);
        Some(Vector2::new(x.div_or_zero(det), y.div_or_zero(det)))
    }
}

impl Mul<Vector2> for Matrix22 {
    type Output = Vector2;
    #[inline]
    fn mul(self, v: Vector2) -> Vector2 {
        self.col1 * v.x + self.col2 * v.y
    }
}

impl Mul for Matrix22 {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self::from_cols(self * o.col1, self * o.col2)
    }
}

impl Add for Matrix22 {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::from_cols(self.col1 + o.col1, self.col2 + o.col2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::scalar::from_int;

    #[test]
    fn inverse_times_matrix_is_identity() {
        let m = Matrix22::new(from_int(4), from_int(7), from_int(2), from_int(6));
        let inv = m.inverse().expect("non-singular");
        let p = m * inv;
        let err = (p.col1 - Vector2::X).length() + (p.col2 - Vector2::Y).length();
        assert!(err < Scalar::lit("0.00000001"), "{err}");
        assert_eq!(m.solve(Vector2::from_int(18, 14)), Some(Vector2::from_int(1, 2)));
    }

    #[test]
    fn singular_matrix_is_reported() {
        let m = Matrix22::new(from_int(1), from_int(2), from_int(2), from_int(4));
        assert!(m.inverse().is_none());
        assert!(m.solve(Vector2::X).is_none());
        assert_eq!(m.transpose(), Matrix22::new(from_int(1), from_int(2), from_int(2), from_int(4)));
    }
}
