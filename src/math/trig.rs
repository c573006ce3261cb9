//! Deterministic fixed-point trigonometry (being written: placeholder values).

use super::scalar::{Scalar, ONE, ZERO};

/// `(sin x, cos x)` for any `x` in radians.
#[must_use]
pub fn sin_cos(_x: Scalar) -> (Scalar, Scalar) {
    (ZERO, ONE)
}

/// `atan2(y, x)` in (−π, π].
#[must_use]
pub fn atan2(_y: Scalar, _x: Scalar) -> Scalar {
    ZERO
}
