//! Soft constraints: Box2D v3's `b2Softness`, one spring-damper discretised for
//! the sub-step, shared by the contacts and every joint.
//!
//! A soft constraint of position error C is solved as a velocity constraint
//! with a bias: the impulse is −m·s_m·(v + ω_b·C) − s_i·λ, with bias rate ω_b,
//! mass scale s_m and impulse scale s_i from the spring's frequency and damping
//! ratio (Erin Catto, *Solver2D*, 2024). Keeping the coefficients in one place
//! keeps contacts and joints on the same discretisation.

use core::ops::Mul;

use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Matrix22, Vector2};

use super::sweep::Bias;

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
        inv_h * Scalar::lit("0.25")
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

    /// How a constraint of position error `c` (m, rad, or a vector of them)
    /// is solved in a sweep: soft, biased by `c` at the bias rate, when `bias`
    /// is on; rigid and unbiased in the relax sweeps.
    #[inline(always)]
    pub(crate) fn row<T>(&self, c: T, bias: Bias) -> Row<T>
    where
        T: Mul<Scalar, Output = T> + Default,
    {
        match bias {
            Bias::On => Row {
                bias: c * self.bias_rate,
                mass_scale: self.mass_scale,
                impulse_scale: self.impulse_scale,
            },
            Bias::Off => Row { bias: T::default(), mass_scale: scalar::ONE, impulse_scale: ZERO },
        }
    }
}

/// One constraint row in one sweep: the bias velocity added to the velocity
/// error and the soft constraint's mass and impulse scales (a rigid row has
/// 1 and 0). Contacts and every joint form their impulse from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Row<T = Scalar> {
    /// Velocity bias (m/s or rad/s).
    pub(crate) bias: T,
    pub(crate) mass_scale: Scalar,
    pub(crate) impulse_scale: Scalar,
}

impl Row {
    /// A rigid row without bias.
    pub(crate) const RIGID: Self = Self { bias: ZERO, mass_scale: scalar::ONE, impulse_scale: ZERO };

    /// A one-sided constraint not yet active: the `gap` (m or rad) may close
    /// within the sub-step of 1/`inv_h` seconds, no more (rigid, no softness).
    #[inline(always)]
    pub(crate) fn speculative(gap: Scalar, inv_h: Scalar) -> Self {
        Self { bias: gap * inv_h, mass_scale: scalar::ONE, impulse_scale: ZERO }
    }

    /// The change of the accumulated impulse `accumulated` for effective mass
    /// `mass` and velocity error `rate`: −m·s_m·(rate + bias) − s_i·λ.
    #[inline(always)]
    pub(crate) fn impulse(&self, mass: Scalar, rate: Scalar, accumulated: Scalar) -> Scalar {
        -(mass * self.mass_scale * (rate + self.bias)) - self.impulse_scale * accumulated
    }
}

impl Row<Vector2> {
    /// [`Row::impulse`] for a 2-D point constraint whose mass is the inverse
    /// matrix `mass`: −(M·(rate + bias))·s_m − s_i·λ (the matrix product first).
    #[inline(always)]
    pub(crate) fn impulse(&self, mass: Matrix22, rate: Vector2, accumulated: Vector2) -> Vector2 {
        let solved = mass * (rate + self.bias);
        -(solved * self.mass_scale) - accumulated * self.impulse_scale
    }
}
