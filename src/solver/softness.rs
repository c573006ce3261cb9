//! Soft constraints: Box2D v3's `b2Softness`, one spring-damper discretised for
//! the sub-step, shared by the contacts and every joint.
//!
//! A soft constraint of position error C is solved as a velocity constraint
//! with a bias: the impulse is −m·s_m·(v + ω_b·C) − s_i·λ, with bias rate ω_b,
//! mass scale s_m and impulse scale s_i from the spring's frequency and damping
//! ratio (Erin Catto, *Solver2D*, 2024). Keeping the coefficients in one place
//! keeps contacts and joints on the same discretisation.

use crate::math::scalar::{self, Scalar, ZERO};

/// Soft-constraint coefficients for one sub-step length (Box2D's `b2Softness`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Softness {
    pub(crate) bias_rate: Scalar,
    pub(crate) mass_scale: Scalar,
    pub(crate) impulse_scale: Scalar,
}

impl Softness {
    /// No spring: what [`Softness::new`] gives for 0 Hz, a rigid constraint
    /// with no position correction.
    pub(crate) const RIGID: Self = Self { bias_rate: ZERO, mass_scale: scalar::ONE, impulse_scale: ZERO };

    /// The stiffest spring a sub-step of 1/`inv_h` seconds resolves, Hz: Box2D
    /// caps contacts and joints at a quarter of the sub-step rate.
    pub(crate) fn max_hertz(inv_h: Scalar) -> Scalar {
        // In a const block: `lit` parses its text, which at run time would link
        // the parser into every build (8 KB of wasm).
        inv_h * const { Scalar::lit("0.25") }
    }

    /// A spring of `hertz` and damping ratio `zeta`, discretised for sub-step `h`.
    pub(crate) fn new(hertz: Scalar, zeta: Scalar, h: Scalar) -> Self {
        if hertz == ZERO {
            return Self::RIGID;
        }
        let omega = scalar::TAU * hertz;
        let a1 = (zeta * scalar::TWO) + (h * omega);
        let a2 = h * omega * a1;
        let a3 = (scalar::ONE + a2).recip();
        Self { bias_rate: omega.div_or_zero(a1), mass_scale: a2 * a3, impulse_scale: a3 }
    }
}
