//! After the last sub-step: every lane's impulses back to its arbiter, in N·s
//! (λ = λ̂·m_eff), with the step's totals a game reads.

use crate::arbiter::Arbiter;
use crate::math::scalar::Scalar;
use crate::solver::lanes::{self, FV};

use super::{f, field, Block, TWO_POINTS};

/// Writes lane `l` of `blk` back to its arbiter; `mass` are the points'
/// normal and tangent effective masses.
pub(crate) fn store(blk: &Block, l: usize, arb: &mut Arbiter, mass: &[[Scalar; 2]; 2]) {
    let get = |fi: usize| super::lane(field(blk, fi), l);
    let count = if get(f::FLAGS) & TWO_POINTS != 0 { 2 } else { 1 };
    for ((dst, &p), &[m_n, m_t]) in arb.points.iter_mut().zip(f::P.iter()).zip(mass).take(count) {
        let ln = get(p + f::LN);
        dst.normal_impulse = lanes::to_scalar(ln, FV) * m_n;
        dst.tangent_impulse = lanes::to_scalar(get(p + f::LT), FV) * m_t;
        let total = i64::from(get(p + f::TOT)) * 4 + i64::from(ln);
        dst.total_normal_impulse = lanes::wide_to_scalar(total) * m_n;
        dst.max_normal_impulse = lanes::to_scalar(get(p + f::MAXD), FV) * m_n;
    }
}
