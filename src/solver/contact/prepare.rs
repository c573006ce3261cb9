//! Building a contact's lane once per step, in `Scalar`: the arms in body
//! radii, the mass ratios that replace every effective mass in the sweeps, the
//! friction factor and, for a two-point manifold, the normalised inverse of its
//! 2×2 mass matrix.
//!
//! For a row along direction d with arms r_A, r_B, k = 1/m_A + 1/m_B +
//! (r_A×d)²/I_A + (r_B×d)²/I_B is the inverse of the mass the pair presents.
//! The lanes carry the impulse as λ̂ = λ·k (m/s) and apply it with ρ = (1/m)/k
//! (≤ 1) and γ̂ = (r×d)·r_b/(I·k), so no mass, and none of the mass range's 27
//! bits, ever enters a lane.

use crate::arbiter::Arbiter;
use crate::body::Body;
use crate::math::scalar::{Scalar, ONE, ZERO};
use crate::math::Vector2;
use crate::solver::body::inverse_mass;
use crate::solver::lanes::{self, ARM_MAX, BLOCK_MAX, FM, FR, FS, FU, FV, GAMMA_MAX, PHI_MAX};
use crate::solver::SolverBody;

use super::{f, field_mut, Block, A_DYNAMIC, B_DYNAMIC, HAS_BLOCK, STATIC_PAIR, TWO_POINTS};

/// One body of a pair as prepare sees it: its inverse mass and inertia, and
/// the radius its rim speed is measured at.
#[derive(Clone, Copy)]
struct Side {
    m: Scalar,
    i: Scalar,
    radius: Scalar,
    inv_radius: Scalar,
}

impl Side {
    #[inline(always)]
    fn new(b: &Body, sb: &SolverBody) -> Self {
        let (m, i) = inverse_mass(b);
        Self { m, i, radius: sb.radius, inv_radius: sb.inv_radius }
    }

    /// The arm (r×d) in body radii, clamped to ±[`ARM_MAX`].
    #[inline(always)]
    fn arm(&self, rd: Scalar) -> i32 {
        lanes::from_scalar(rd * self.inv_radius, FR, ARM_MAX)
    }

    /// The rim ratio γ̂ = (r×d)·r_b·(1/I)·m_eff, clamped to ±[`GAMMA_MAX`].
    #[inline(always)]
    fn gamma(&self, rd: Scalar, m_eff: Scalar) -> i32 {
        let g = (self.i * rd * m_eff * self.radius).clamp(-GAMMA_MAX, GAMMA_MAX);
        lanes::from_scalar(g, FU, 2)
    }
}

/// Writes `x` into lane `l` of field `fi`.
#[inline(always)]
fn put(blk: &mut Block, fi: usize, l: usize, x: i32) {
    if let Some(dst) = field_mut(blk, fi).get_mut(l) {
        *dst = x;
    }
}

/// 1/(1/m_A + 1/m_B + (r_A×d)²/I_A + (r_B×d)²/I_B) for arms (r×d) `ra`, `rb`.
#[inline(always)]
fn k(a: &Side, b: &Side, ra: Scalar, rb: Scalar) -> Scalar {
    a.m + b.m + a.i * (ra * ra) + b.i * (rb * rb)
}

/// Builds lane `l` of `blk` from an arbiter between bodies `a` and `b` (slots
/// `ia`, `ib`; at least one dynamic); the scales are the mass scales of the
/// contact and static softness. Returns each point's normal and tangent
/// effective mass, for the store.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prepare(
    arb: &Arbiter,
    (ia, ib): (u32, u32),
    (a, b): (&Body, &Body),
    (sa, sb): (&SolverBody, &SolverBody),
    (contact_scale, static_scale): (Scalar, Scalar),
    blk: &mut Block,
    l: usize,
) -> [[Scalar; 2]; 2] {
    let mut masses = [[ZERO; 2]; 2];
    let (side_a, side_b) = (Side::new(a, sa), Side::new(b, sb));
    let n = arb.normal;
    let t = n.right_perp();
    let count = usize::from(arb.count.min(2));
    let static_pair = side_a.m == ZERO || side_b.m == ZERO;
    let mut flags = 0;
    if sa.dynamic {
        flags |= A_DYNAMIC;
    }
    if sb.dynamic {
        flags |= B_DYNAMIC;
    }
    if static_pair {
        flags |= STATIC_PAIR;
    }
    put(blk, f::IA, l, ia as i32);
    put(blk, f::IB, l, ib as i32);
    put(blk, f::NX, l, lanes::from_scalar(n.x, FU, 1));
    put(blk, f::NY, l, lanes::from_scalar(n.y, FU, 1));
    put(blk, f::E, l, lanes::from_scalar(arb.restitution, FU, 1));
    let mut kn = [ONE; 2];
    let mut rn = [(ZERO, ZERO); 2];
    for (p, src) in arb.points.iter().enumerate() {
        let base = f::P[p % 2];
        if p >= count {
            // An unused point: nothing pushes, nothing is applied.
            for x in 0..f::POINT {
                put(blk, base + x, l, 0);
            }
            continue;
        }
        let (ra, rb) = (src.anchor_a, src.anchor_b);
        let (rna, rnb, rta, rtb) = (ra.cross(n), rb.cross(n), ra.cross(t), rb.cross(t));
        let k_n = k(&side_a, &side_b, rna, rnb);
        let k_t = k(&side_a, &side_b, rta, rtb);
        let (m_n, m_t) = (k_n.recip(), k_t.recip());
        kn[p % 2] = k_n;
        rn[p % 2] = (rna, rnb);
        put(blk, base + f::RAN, l, side_a.arm(rna));
        put(blk, base + f::RBN, l, side_b.arm(rnb));
        put(blk, base + f::RAT, l, side_a.arm(rta));
        put(blk, base + f::RBT, l, side_b.arm(rtb));
        let ratio = |m: Scalar, me: Scalar, d: Vector2| {
            let r = (m * me).min(ONE);
            (lanes::from_scalar(d.x * r, FU, 1), lanes::from_scalar(d.y * r, FU, 1))
        };
        let (anx, any) = ratio(side_a.m, m_n, n);
        let (bnx, bny) = ratio(side_b.m, m_n, n);
        let (atx, aty) = ratio(side_a.m, m_t, t);
        let (btx, bty) = ratio(side_b.m, m_t, t);
        for (fi, x) in [
            (f::ANX, anx),
            (f::ANY, any),
            (f::BNX, bnx),
            (f::BNY, bny),
            (f::GAN, side_a.gamma(rna, m_n)),
            (f::GBN, side_b.gamma(rnb, m_n)),
            (f::ATX, atx),
            (f::ATY, aty),
            (f::BTX, btx),
            (f::BTY, bty),
            (f::GAT, side_a.gamma(rta, m_t)),
            (f::GBT, side_b.gamma(rtb, m_t)),
        ] {
            put(blk, base + fi, l, x);
        }
        let lambda_max = lanes::to_scalar(lanes::LAMBDA_MAX, FV);
        let ln = (src.normal_impulse * k_n).clamp(ZERO, lambda_max);
        let lt = (src.tangent_impulse * k_t).clamp(-lambda_max, lambda_max);
        put(blk, base + f::LN, l, lanes::from_scalar(ln, FV, 8192));
        put(blk, base + f::LT, l, lanes::from_scalar(lt, FV, 8192));
        put(blk, base + f::BASE, l, lanes::from_scalar(src.separation, FS, 4095));
        // |λ_t| ≤ μ·λ_n ⇔ |λ̂_t| ≤ μ·(k_t/k_n)·λ̂_n; φ·min(λ̂_n, c_φ) ≤ Λ.
        let phi = (arb.friction * k_t * m_n).min(Scalar::from_int(PHI_MAX as i32 - 1));
        let c_phi = if phi > ONE { lambda_max.div_or_zero(phi) } else { lambda_max };
        put(blk, base + f::PHI, l, lanes::from_scalar(phi, lanes::FPHI, PHI_MAX));
        put(blk, base + f::CPHI, l, lanes::from_scalar(c_phi, FV, 8192));
        let dv = b.velocity_at_offset(rb) - a.velocity_at_offset(ra);
        put(blk, base + f::VREL, l, lanes::velocity(dv.dot(n)));
        put(blk, base + f::MAXD, l, 0);
        put(blk, base + f::TOT, l, 0);
        if let Some(m) = masses.get_mut(p) {
            *m = [m_n, m_t];
        }
    }
    if count == 2 {
        flags |= TWO_POINTS;
        let k12 = side_a.m + side_b.m + side_a.i * (rn[0].0 * rn[1].0) + side_b.i * (rn[0].1 * rn[1].1);
        let scale = if static_pair { static_scale } else { contact_scale };
        if let Some(block) = block_inverse(kn, [masses[0][0], masses[1][0]], k12, scale) {
            flags |= HAS_BLOCK;
            let [c12, c21, r11, r12, r21, r22, s11, s12, s21, s22] = block;
            put(blk, f::C12, l, c12);
            put(blk, f::C21, l, c21);
            for (j, x) in [r11, r12, r21, r22].into_iter().enumerate() {
                put(blk, f::MR + j, l, x);
            }
            for (j, x) in [s11, s12, s21, s22].into_iter().enumerate() {
                put(blk, f::MS + j, l, x);
            }
        }
    }
    put(blk, f::FLAGS, l, flags);
    masses
}

/// The couplings c12 = k12/k22, c21 = k12/k11 (`m` holds 1/k11, 1/k22) and the
/// normalised inverses
/// M̂ = D·K⁻¹ (D = diag(k11, k22)) of the rigid system and of the soft one
/// (diagonal k_ii/s), when the pair is well conditioned: the diagonal
/// entries within a factor 4 of each other and every entry of M̂ below
/// [`BLOCK_MAX`]; otherwise `None` and the points are solved one at a time.
///
/// With ρ² = c12·c21 = k12²/(k11·k22) ≤ 1 and a mass scale s,
/// M̂ = 1/(1 − s²ρ²)·[[s, −s²·c12], [−s²·c21, s]].
fn block_inverse(k: [Scalar; 2], m: [Scalar; 2], k12: Scalar, s: Scalar) -> Option<[i32; 10]> {
    let [k11, k22] = k;
    let four = Scalar::from_int(4);
    if k11 <= ZERO || k22 <= ZERO || k11 > k22 * four || k22 > k11 * four {
        return None;
    }
    // k12/k22 and k12/k11, by the effective masses already computed.
    let (c12, c21) = (k12 * m[1], k12 * m[0]);
    let rho2 = c12 * c21;
    let inverse = |s: Scalar| -> Option<[Scalar; 4]> {
        let ss = s * s;
        let det = ONE - ss * rho2;
        if det <= ZERO {
            return None;
        }
        let m = det.recip();
        let e = [s * m, -(ss * c12 * m), -(ss * c21 * m), s * m];
        e.iter().all(|x| x.abs() < BLOCK_MAX).then_some(e)
    };
    let rigid = inverse(ONE)?;
    let soft = inverse(s)?;
    let q = |x: Scalar| lanes::from_scalar(x, FM, 16);
    Some([
        lanes::from_scalar(c12, FR, 2),
        lanes::from_scalar(c21, FR, 2),
        q(rigid[0]),
        q(rigid[1]),
        q(rigid[2]),
        q(rigid[3]),
        q(soft[0]),
        q(soft[1]),
        q(soft[2]),
        q(soft[3]),
    ])
}
