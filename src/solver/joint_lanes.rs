//! The built-in joints inside the sub-steps, in 32-bit integer formats.
//!
//! The joints' warm start and their biased and relax iterations work, as the
//! contact kernels do, directly on each body's lane record ([`BodyLanes`]:
//! Q16.16 velocity and rim speed ŵ = ω·r_b), with products as a 32×32→64
//! multiply and a shift ([`lanes::mul`] and its widening form below). What a
//! joint changes in the lanes is carried into the body's `Scalar` velocity by
//! the next [`SolverBody::pull`], exactly as a contact's change is; so the
//! joints need no pull or push of their own and the `Scalar` velocity stays
//! the truth.
//!
//! **Lanes never see a mass.** Once per step (`Joint::prepare`, in `Scalar`)
//! each joint turns its masses into ratios and its accumulated impulses into
//! velocity units:
//!
//! * a linear impulse λ (N·s; the point constraint of pivots and welds, the
//!   axial impulse of rods and ropes) is carried as λ̂ = λ·s, s = 1/m_A + 1/m_B,
//!   the velocity change it makes to the two centres together. It moves a
//!   centre by ρ = (1/m)/s ≤ 1 times λ̂, and a rim speed by κ·(r̂ × λ̂), with
//!   r̂ = r/r_b the anchor's arm in body radii and κ = r_b²/(I·s) ≤ r_b²/ρ_g² ≤ 8
//!   (ρ_g the radius of gyration; r_b ≤ √8·ρ_g for every convex shape, so the
//!   bound comes by construction, and prepare clamps to it).
//! * the point constraint's 2×2 mass becomes M̂ = s·K⁻¹: K ≥ s·I (the arms only
//!   add), so its eigenvalues, and hence its entries, lie in [0, 1].
//! * a rod's effective mass along its current axis becomes μ̂ = s/k ≤ 1,
//!   refreshed each sub-step (the axis turns).
//! * an angular impulse L (N·m·s; motor, limits, the weld's angle) is carried as
//!   L̂ = L·(1/I_A + 1/I_B), the change of relative spin it makes (rad/s). It
//!   moves a rim speed by α·L̂, α = r_b·(1/I)/(1/I_A + 1/I_B) ≤ r_b ≤ 128 m.
//! * a target joint's force limit becomes the largest |λ̂| of its point
//!   constraint, `max_force`·h·s (Q16.16, like λ̂); after every iteration the
//!   accumulated λ̂ is scaled back to it by length, the length being the
//!   integer square root (rounded up) of the exact 64-bit sum of squares, so
//!   the clamp is the same on every target and never overshoots the limit.
//!   Its softness is its own spring's, not the joints' position correction.
//!   Its spin damping (Box2D v3's: a soft angular row with no bias, 0.5 Hz,
//!   damping ratio 0.1) keeps its scales in the pivot's `limits` field.
//!
//! The anchors' arms follow the bodies' rotation: once per sub-step, after the
//! positions are integrated (and at prepare for the first sub-step), each
//! joint rotates its local anchors by the body's rotation (Q2.30) and measures
//! its position error from the `Scalar` positions; the warm start and biased
//! iteration of the next sub-step and the relax iteration of this one use that
//! pose, which is the pose each of them sees. Only pivots with limits and welds
//! also measure their relative angle (a `Scalar` atan2, once per sub-step).
//!
//! | quantity | format | resolution | bound | why |
//! |---|---|---|---|---|
//! | v, ŵ (the body lanes) | Q16.16 | 1.5e-5 m/s | ±[`V_WALL`] | clamped after every joint update, as after every contact update |
//! | λ̂, L̂ (accumulated, velocity units) | Q16.16 | 1.5e-5 m/s, rad/s | ±[`LAMBDA_MAX`] | clamped at every update (the contacts' crush limit) |
//! | anchor rates, relative spin ω_B − ω_A, rate + bias | Q16.16 (64-bit sums) | 1.5e-5 | saturated to ±32,768 before they scale a row | \|v\| ≤ 2,048 m/s; \|ω\| ≤ the step's angular limit after each integration |
//! | ρ, μ̂, soft scales s_m, s_i; M̂ entries; unit axis, rotation (c, s) | Q2.30 | 9.3e-10 | [0, 1]; ±1; ±1 | mass ratios (above), M̂ symmetric with eigenvalues in [0, 1], unit vectors |
//! | κ | Q5.27 | 7.5e-9 | [0, 8] | r_b ≤ √8·ρ_g; clamped |
//! | α | Q9.23 | 1.2e-7 m | [0, 128] | α ≤ r_b ≤ `MAX_BODY_RADIUS` |
//! | local anchor, world arm r (m), 1/r_b | Q10.22 | 2.4e-7 | ±363 m, ≤ 256 1/m | anchors ≤ 256 m a component (`max_anchor`), \|q\| = 1; r_b ≥ 2⁻⁸ m in the solver |
//! | arm in body radii r̂, ĝ = κ·r̂, γ = κ·(r̂ × axis) | Q12.20 | 9.5e-7 | ±1,024 (r̂), ±2,047 | saturated: only an anchor over 1,024 body radii from a tiny body's centre reaches them, and then it loses turning response, never wraps |
//! | position error d, rod length and its error | Q13.19 | 1.9e-6 m | ±2,047 m a component | saturated (the bias it makes is clamped anyway) |
//! | relative angle, limits, their gaps | Q4.28 | 3.7e-9 rad | ±2π | angles in (−π, π], limits in [−π, π] |
//! | bias rate, 1/h | Q22.10 | 9.8e-4 1/s | ≤ 2²⁰ | dt ≥ 2⁻¹⁶ s, ≤ 16 sub-steps |
//! | bias velocity | Q16.16 | 1.5e-5 m/s | ±4,096 | clamped |
//!
//! Every narrowing from a 64-bit sum saturates (`narrow`), so no value wraps,
//! whatever the input. Values enter from `Scalar` rounded half up and
//! saturated to their bound ([`lanes::from_scalar`]); the impulses leave at
//! the end of the step as λ = λ̂/s and L = L̂/(1/I_A + 1/I_B) (`Scalar`), which
//! is what the snapshot holds, so restoring a snapshot and stepping on gives
//! the same bits as stepping on.
//!
//! Springs are forces, not constraints: they stay in `Scalar` (pull, apply,
//! push), once per sub-step.

use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};

use super::body::{BodyLanes, SolverBody, VX, VY, W};
use super::lanes::{self, from_scalar, mul, sym, to_scalar, FQ, FU, FV, LAMBDA_MAX, V_WALL};
use super::{Bias, Softness};

/// Fractional bits of anchors, world arms and 1/r_b (Q10.22).
pub(super) const FA: u32 = 22;
/// Fractional bits of arms in body radii and their κ multiples (Q12.20).
pub(super) const FH: u32 = 20;
/// Fractional bits of κ (Q5.27).
pub(super) const FK: u32 = 27;
/// Fractional bits of α (Q9.23).
const FAL: u32 = 23;
/// Fractional bits of position errors and lengths (Q13.19).
pub(super) const FD: u32 = 19;
/// Fractional bits of angles (Q4.28).
const FT: u32 = 28;
/// One in Q2.30.
const ONE_U: i32 = 1 << FU;
/// Bound of arms in body radii (whole radii).
pub(super) const ARM_HAT_MAX: i64 = 1024;
/// Bound of ĝ and γ.
pub(super) const G_MAX: i64 = 2047;
/// Bound of position errors and lengths, m.
pub(super) const D_MAX: i64 = 2047;
/// Bound of a bias velocity, Q16.16.
pub(super) const BIAS_MAX: i64 = 4096 << FV;
/// Bound of a rate or rate + bias before it scales a row, Q16.16.
pub(super) const RATE_MAX: i64 = (1 << 31) - 1;

/// `(a·b + 2^(K−1)) >> K` on the exact 64-bit product, kept in 64 bits.
#[inline(always)]
fn wide<const K: u32>(a: i32, b: i32) -> i64 {
    (i64::from(a) * i64::from(b) + (1i64 << (K - 1))) >> K
}

/// A 64-bit value (|x| ≤ 2³²) scaled by a Q2.30 factor, rounded as [`mul`].
#[inline(always)]
fn scale(x: i64, s: i32) -> i64 {
    (sym(x, RATE_MAX) * i64::from(s) + (1i64 << (FU - 1))) >> FU
}

/// Saturated to ±`bound` (< 2³¹) and narrowed.
#[inline(always)]
fn narrow(x: i64, bound: i64) -> i32 {
    sym(x, bound) as i32
}

/// Adds `dv` to lane `k` of a body, at the velocity wall.
#[inline(always)]
fn add(lane: &mut BodyLanes, k: usize, dv: i64) {
    if let Some(x) = lane.0.get_mut(k) {
        *x = narrow(i64::from(*x) + dv, i64::from(V_WALL));
    }
}

/// log₂ of 2·`V_WALL`, a power of two: (x + `V_WALL`) >> `WALL_BITS` is
/// zero exactly when −`V_WALL` ≤ x < `V_WALL` (x = `V_WALL` is within the
/// wall too, but fails this test).
const WALL_BITS: u32 = V_WALL.trailing_zeros() + 1;
const _: () = assert!(V_WALL.count_ones() == 1);

/// Lanes v_x, v_y and ŵ set to `v`, each clamped at the velocity wall.
#[cold]
#[inline(never)]
fn wall_cold(l: &mut [i32; 8], v: [i64; 3]) {
    let wall = i64::from(V_WALL);
    [l[VX], l[VY], l[W]] = v.map(|x| x.clamp(-wall, wall) as i32);
}

#[inline(always)]
fn get(lane: &BodyLanes, k: usize) -> i32 {
    lane.0.get(k).copied().unwrap_or(0)
}

/// A soft row in lane formats: bias rate (Q22.10), mass and impulse scales
/// (Q2.30).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct LaneSoft {
    pub(super) rate: i32,
    pub(super) mass_scale: i32,
    pub(super) impulse_scale: i32,
}

impl LaneSoft {
    pub(crate) fn new(s: Softness) -> Self {
        Self {
            rate: from_scalar(s.bias_rate, FQ, 1 << 21),
            mass_scale: from_scalar(s.mass_scale, FU, 1),
            impulse_scale: from_scalar(s.impulse_scale, FU, 1),
        }
    }

    /// (bias velocity Q16.16, s_m, s_i) for a position error `c` of `f`
    /// fractional bits: soft and biased with `Bias::On`, rigid without.
    #[inline(always)]
    fn row<const SHIFT: u32>(&self, c: i32, bias: Bias) -> (i64, i32, i32) {
        match bias {
            Bias::On => {
                let b = sym(wide::<SHIFT>(c, self.rate), BIAS_MAX);
                (b, self.mass_scale, self.impulse_scale)
            }
            Bias::Off => (0, ONE_U, 0),
        }
    }
}

/// What every joint's prepare shares in a step: the joints' softness and the
/// sub-step, in `Scalar` and in lane formats, converted once a step rather
/// than once a joint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointStep {
    /// The joints' soft position correction, in lane formats.
    pub(crate) lane_soft: LaneSoft,
    /// The sub-step (s).
    pub(crate) h: Scalar,
    /// 1/h (Q22.10).
    pub(crate) inv_h: i32,
}

impl JointStep {
    pub(crate) fn new(soft: Softness, h: Scalar, inv_h: Scalar) -> Self {
        Self { lane_soft: LaneSoft::new(soft), h, inv_h: from_scalar(inv_h, FQ, 1 << 21) }
    }
}

/// M̂ = (K/s)⁻¹ as (m11, m12, m22), from the normalised masses (`ma` = ρ_A,
/// `ia` = (1/I_A)/s, …) and the arms. K/s is (ρ_A + ρ_B)·I plus the arms'
/// terms (1/I)/s·\[r\]ᵀ\[r\], so its eigenvalues are ≥ ρ_A + ρ_B = 1, its
/// determinant is ≥ 1 and one reciprocal serves the three entries. `None`
/// when singular (only when the entries saturate).
fn point_mass(
    ma: Scalar,
    ia: Scalar,
    ra: Vector2,
    mb: Scalar,
    ib: Scalar,
    rb: Vector2,
) -> Option<[Scalar; 3]> {
    let m = ma + mb;
    let k11 = (m + (ia * (ra.y * ra.y))) + (ib * (rb.y * rb.y));
    let k12 = -((ia * (ra.x * ra.y)) + (ib * (rb.x * rb.y)));
    let k22 = (m + (ia * (ra.x * ra.x))) + (ib * (rb.x * rb.x));
    let det = (k11 * k22) - (k12 * k12);
    if det <= ZERO {
        return None;
    }
    let inv = det.recip();
    Some([k22 * inv, -(k12 * inv), k11 * inv])
}

/// The two sides of a joint's rows for the step (ratios, inverse radius,
/// local anchor; no pose yet) and the normalised masses ((1/m)/s, (1/I)/s)
/// of A and B: [`JointLanes::prepare`]'s and [`PivotStart`]'s.
#[inline(always)]
fn sides(
    m: &JointMasses,
    inv_s: Scalar,
    inv_k: Scalar,
    anchors: [Vector2; 2],
    a: &SolverBody,
    b: &SolverBody,
) -> ((Scalar, Scalar), (Scalar, Scalar), [Side; 2]) {
    let ([ma, mb], [ia, ib]) = (m.inv_mass, m.inv_inertia);
    // The normalised masses, once for the sides and the point mass.
    let (na, nb) = ((ma * inv_s, ia * inv_s), (mb * inv_s, ib * inv_s));
    (na, nb, [Side::new(anchors[0], na, ia, a, inv_k), Side::new(anchors[1], nb, ib, b, inv_k)])
}

/// M̂ = (K/s)⁻¹ in Q2.30 from the arms at the start of the step (all zero
/// when singular): the normalised K has eigenvalues ≥ 1, so M̂'s entries
/// are in [−1, 1].
#[inline(always)]
fn point_lanes(na: (Scalar, Scalar), nb: (Scalar, Scalar), side: &[Side; 2]) -> [i32; 3] {
    let (ra, rb) = (side[0].arm(), side[1].arm());
    point_mass(na.0, na.1, ra, nb.0, nb.1, rb).map_or([0; 3], |mm| mm.map(|x| from_scalar(x, FU, 1)))
}

/// An accumulated impulse (N·s, N·m·s) in velocity units (Q16.16), `x`
/// being it times s or 1/I_A + 1/I_B, rounded and held to the crush limit.
#[inline(always)]
fn impulse_lane(x: Scalar) -> i32 {
    from_scalar(x, FV, i64::from(LAMBDA_MAX >> FV))
}

/// The persistent linear impulse as λ̂ = λ·s (Q16.16).
#[inline(always)]
fn linear_lanes(impulse: Vector2, s: Scalar) -> [i32; 2] {
    [impulse_lane(impulse.x * s), impulse_lane(impulse.y * s)]
}

/// A plain pivot's masses and sides for the step, from which the pivot
/// lanes' fill builds its [`PointRecord`] ([`PivotStart::record`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PivotStart {
    s: Scalar,
    inv_s: Scalar,
    /// (1/m)/s and (1/I)/s of A and B.
    n: [(Scalar, Scalar); 2],
    side: [Side; 2],
}

impl PivotStart {
    /// A pivot between two bodies with neither limits nor motor, `m` its
    /// masses and anchors (B's on body B); `None` when s = 0 (neither body
    /// dynamic: the row would not run, and the lanes take no such pivot).
    #[inline(always)]
    pub(crate) fn new(m: &JointMasses, a: &SolverBody, b: &SolverBody) -> Option<Self> {
        let s = m.inv_mass[0] + m.inv_mass[1];
        if s <= ZERO {
            return None;
        }
        let inv_s = s.recip();
        let (na, nb, side) = sides(m, inv_s, ZERO, m.anchors, a, b);
        Some(Self { s, inv_s, n: [na, nb], side })
    }

    /// What [`JointLanes::prepare`] gives the point row of this pivot, in
    /// the lanes' record: the same products and roundings, so the same bits.
    /// `a`, `b` are the bodies as the step loaded them (their rotations turn
    /// the anchors for M̂) and `impulse` the persistent λ (N·s).
    #[inline(always)]
    pub(crate) fn record(&self, a: &SolverBody, b: &SolverBody, impulse: Vector2) -> PointRecord {
        let mut side = self.side;
        let [sa, sb] = &mut side;
        sa.r = world_arm(sa.anchor, a.q);
        sb.r = world_arm(sb.anchor, b.q);
        PointRecord {
            rho: [sa.rho, sb.rho],
            kappa: [sa.kappa, sb.kappa],
            iota: [sa.iota, sb.iota],
            anchor: [sa.anchor, sb.anchor],
            m: point_lanes(self.n[0], self.n[1], &side),
            lambda: linear_lanes(impulse, self.s),
        }
    }

    /// 1/s: what turns λ̂ back into N·s at the end of the step
    /// ([`linear_impulse`]).
    pub(crate) fn inv_s(&self) -> Scalar {
        self.inv_s
    }
}

/// An accumulated λ̂ (Q16.16) in N·s, from 1/s.
#[inline]
fn linear_impulse(lambda: [i32; 2], inv_s: Scalar) -> Vector2 {
    Vector2::new(to_scalar(lambda[0], FV) * inv_s, to_scalar(lambda[1], FV) * inv_s)
}

/// The λ̂ applied over a step (a 64-bit sum of Q16.16) in N·s, from 1/s.
#[inline]
fn step_linear(sum: [i64; 2], inv_s: Scalar) -> Vector2 {
    Vector2::new(lanes::wide_to_scalar(sum[0]) * inv_s, lanes::wide_to_scalar(sum[1]) * inv_s)
}

/// A pivot in lanes' accumulated λ̂ and the λ̂ it applied over the step
/// (see `pivot_lanes::point_state`) in N·s, from its 1/s: what
/// [`JointLanes::linear_impulse`] and [`JointLanes::step_linear`] give a row.
pub(crate) fn pivot_impulses(lambda: [i32; 2], sum: [i64; 2], inv_s: Scalar) -> (Vector2, Vector2) {
    (linear_impulse(lambda, inv_s), step_linear(sum, inv_s))
}

/// `v` scaled down to length `max` (≥ 0) when longer, in integers: the
/// length is the integer square root, rounded up, of the exact 64-bit sum of
/// squares (|v| components ≤ 2³⁰ after `narrow`, so the sum fits), and each
/// component is scaled by max/len rounding towards zero, so the result is
/// never longer than `max` and the same on every target.
///
/// A vector within `max` is returned before the square root: with `max` a
/// whole number, ⌈√sq⌉ ≤ max exactly when sq ≤ max² (at most 2⁶², exact).
fn clamp_length(v: [i32; 2], max: i32) -> [i32; 2] {
    let [x, y] = v.map(i64::from);
    let sq = (x * x + y * y).unsigned_abs();
    let max = i64::from(max.max(0));
    if sq <= (max * max).unsigned_abs() {
        return v;
    }
    let floor = sq.isqrt();
    let len = (if floor * floor < sq { floor + 1 } else { floor }) as i64;
    // len > max ≥ 0, and |x|·max ≤ 2³⁰·2³⁰.
    [(x * max / len) as i32, (y * max / len) as i32]
}

/// A local anchor (Q10.22) turned by `q`: the world arm r (Q10.22), the arm
/// in body radii r̂ = r/r_b (Q12.20, from `iota` = 1/r_b) and ĝ = κ·r̂
/// (Q12.20), for the point rows of the joints one at a time and of the
/// pivots in lanes ([`pivot_lanes`](super::pivot_lanes)) alike.
#[inline(always)]
pub(super) fn arm_at(anchor: [i32; 2], iota: i32, kappa: i32, q: Rot) -> [[i32; 2]; 3] {
    let r = world_arm(anchor, q);
    let rh = r.map(|r| narrow(wide::<{ 2 * FA - FH }>(r, iota), ARM_HAT_MAX << FH));
    let g = rh.map(|rh| narrow(wide::<FK>(kappa, rh), G_MAX << FH));
    [r, rh, g]
}

/// A local anchor (Q10.22) turned by `q`: the world arm r (Q10.22) of
/// [`arm_at`].
#[inline(always)]
fn world_arm(anchor: [i32; 2], q: Rot) -> [i32; 2] {
    // `from_scalar(x, FU, 1)` with the clamp a cold call (`narrow`).
    let unit = |x: Scalar| {
        let bits = x.to_bits();
        narrow((bits >> (32 - FU)) + ((bits >> (31 - FU)) & 1), 1 << FU)
    };
    let (c, s) = (unit(q.c), unit(q.s));
    let [x, y] = anchor;
    // |anchor| ≤ 256 m a component, so each component stays ≤ 363 m.
    [mul::<FU>(c, x).wrapping_sub(mul::<FU>(s, y)), mul::<FU>(s, x).wrapping_add(mul::<FU>(c, y))]
}

/// The position error B − A of two anchors (m, Q13.19) from the bodies'
/// centres `pa`, `pb` (`pb` plus `base`, a joint to a world point's fixed
/// point) and the world arms `ra`, `rb` (Q10.22).
#[inline(always)]
pub(super) fn position_error(
    pa: Vector2,
    pb: Vector2,
    base: Vector2,
    ra: [i32; 2],
    rb: [i32; 2],
) -> [i32; 2] {
    // B − A in 64 bits: positions (Q32.32, |x| < 2³¹ each) differ by
    // less than 2⁶³, and the arms (Q10.22) are exact in Q32.32.
    let c = (pb + base) - pa;
    let arm = |r: i32| i64::from(r) << (32 - FA);
    let dx = c.x.to_bits().saturating_add(arm(rb[0]) - arm(ra[0]));
    let dy = c.y.to_bits().saturating_add(arm(rb[1]) - arm(ra[1]));
    let round = |x: i64| narrow((x >> (32 - FD)) + ((x >> (31 - FD)) & 1), D_MAX << FD);
    [round(dx), round(dy)]
}

/// One body's side of a joint: its ratios for the step and its arm at the
/// current pose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Side {
    /// Local anchor (m, Q10.22).
    anchor: [i32; 2],
    /// ρ = (1/m)/s (Q2.30).
    rho: i32,
    /// κ = r_b²·(1/I)/s (Q5.27).
    kappa: i32,
    /// α = r_b·(1/I)/(1/I_A + 1/I_B) (m, Q9.23).
    alpha: i32,
    /// 1/r_b (Q10.22).
    iota: i32,
    /// Arm in world orientation (m, Q10.22).
    r: [i32; 2],
    /// Arm in body radii (Q12.20).
    rh: [i32; 2],
    /// κ·r̂ (Q12.20).
    g: [i32; 2],
}

impl Side {
    /// `mass_s`, `inertia_s` are (1/m)/s and (1/I)/s, which the point
    /// constraint's mass needs too. Inlined into the joint prepare, which
    /// builds the two sides straight into its row (joint 10: 935.5 →
    /// 926.8 M instructions, the same bits).
    #[inline(always)]
    fn new(
        anchor: Vector2,
        (mass_s, inertia_s): (Scalar, Scalar),
        inv_inertia: Scalar,
        body: &SolverBody,
        inv_k: Scalar,
    ) -> Self {
        let r = body.radius;
        Self {
            anchor: [from_scalar(anchor.x, FA, 511), from_scalar(anchor.y, FA, 511)],
            rho: from_scalar(mass_s, FU, 1),
            // Each factor saturates in Scalar only beyond the bound of 8.
            kappa: from_scalar((inertia_s * r) * r, FK, 8).max(0),
            // 0 without angular rows (`inv_k` = 0), which every plain pivot is.
            alpha: if inv_k == ZERO { 0 } else { from_scalar((inv_inertia * inv_k) * r, FAL, 255).max(0) },
            iota: from_scalar(body.inv_radius, FA, 511),
            r: [0; 2],
            rh: [0; 2],
            g: [0; 2],
        }
    }

    /// The arm at rotation `q`.
    #[inline(always)]
    fn pose(&mut self, q: Rot) {
        [self.r, self.rh, self.g] = arm_at(self.anchor, self.iota, self.kappa, q);
    }

    /// The arm in world orientation as a `Scalar` (exact).
    fn arm(&self) -> Vector2 {
        Vector2::new(to_scalar(self.r[0], FA), to_scalar(self.r[1], FA))
    }

    /// Velocity of the anchor point (Q16.16, 64-bit): v + ŵ·perp(r̂).
    #[inline(always)]
    fn anchor_velocity(&self, l: &BodyLanes) -> [i64; 2] {
        let w = get(l, W);
        [i64::from(get(l, VX)) - wide::<FH>(w, self.rh[1]), i64::from(get(l, VY)) + wide::<FH>(w, self.rh[0])]
    }

    /// Spin ω = ŵ/r_b (rad/s, Q16.16, 64-bit).
    #[inline(always)]
    fn spin(&self, l: &BodyLanes) -> i64 {
        wide::<FA>(get(l, W), self.iota)
    }

    /// Applies p (a linear impulse in velocity units) at the anchor, or −p
    /// when `NEG` (body A).
    #[inline(always)]
    fn apply_point<const NEG: bool>(&self, l: &mut BodyLanes, p: [i32; 2]) {
        // |ρ·p| ≤ 2Λ = 2³⁰ and |v| ≤ the wall (2²⁷): the sums cannot wrap.
        let dx = mul::<FU>(self.rho, p[0]);
        let dy = mul::<FU>(self.rho, p[1]);
        let dw = wide::<FH>(self.g[0], p[1]) - wide::<FH>(self.g[1], p[0]);
        let (dx, dy, dw) = if NEG { (dx.wrapping_neg(), dy.wrapping_neg(), -dw) } else { (dx, dy, dw) };
        let l = &mut l.0;
        let x = i64::from(l[VX].wrapping_add(dx));
        let y = i64::from(l[VY].wrapping_add(dy));
        let w = i64::from(l[W]) + dw;
        // One test for the three lanes: each is within the wall when x +
        // V_WALL ∈ [0, 2·V_WALL]; all three are below 2·V_WALL (a power of
        // two) exactly when their bitwise or is, and a negative one sets the
        // top bits. What fails (only a lane past or at the wall) takes the
        // exact clamps, so the bits are the clamps' either way.
        let wall = i64::from(V_WALL);
        if ((x + wall) | (y + wall) | (w + wall)) >> WALL_BITS == 0 {
            [l[VX], l[VY], l[W]] = [x as i32, y as i32, w as i32];
        } else {
            wall_cold(l, [x, y, w]);
        }
    }

    /// Applies `sign`·l (an angular impulse in relative-spin units).
    #[inline(always)]
    fn apply_angular(&self, lane: &mut BodyLanes, l: i32, negate: bool) {
        let dw = wide::<FAL>(self.alpha, l);
        add(lane, W, if negate { -dw } else { dw });
    }
}

/// The axis of a rod or rope at the current pose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Axis {
    /// Unit axis from A's anchor to B's (Q2.30); zero when the anchors meet.
    n: [i32; 2],
    /// Length error ℓ − length (m, Q13.19).
    c: i32,
    /// μ̂ = s/k along the axis (Q2.30).
    mu: i32,
    /// ρ·n for each body (Q2.30).
    pn: [[i32; 2]; 2],
    /// r̂ × n for each body (Q12.20).
    x: [i32; 2],
    /// κ·(r̂ × n) for each body (Q12.20).
    gamma: [i32; 2],
}

/// A joint's state in lane formats for one step, held in its row of the
/// solver's dense joint array (scratch, not part of the snapshot: prepare
/// rebuilds it from the joint's persistent impulses every step).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct JointLanes {
    /// The linear rows run (s > 0).
    linear: bool,
    /// The angular rows run (1/I_A + 1/I_B > 0).
    angular: bool,
    side: [Side; 2],
    /// M̂ = s·K⁻¹ (Q2.30): m11, m12, m22; all zero when K is singular.
    m: [i32; 3],
    soft: LaneSoft,
    /// 1/h (Q22.10).
    inv_h: i32,
    /// A fixed world point B's anchor is measured from (a joint to a world
    /// point), else zero.
    base: Vector2,
    /// Position error B − A of the anchors (m, Q13.19).
    d: [i32; 2],
    axis: Axis,
    /// Relative angle (rad, Q4.28), when measured.
    angle: i32,
    /// A pivot's limits (rad, Q4.28): lower, upper; for a target joint the
    /// mass and impulse scales of its spin damping (Q2.30).
    limits: [i32; 2],
    /// A pivot motor's target speed (rad/s, Q16.16) and largest accumulated
    /// impulse (Q16.16); for a target joint (no motor), [0, its largest |λ̂|
    /// (Q16.16): `max_force`·h·s], so the row stays the size it was.
    motor: [i32; 2],
    /// Accumulated linear impulse λ̂ (Q16.16): point (x, y) or axial (x).
    lambda: [i32; 2],
    /// Accumulated angular impulses L̂ (Q16.16): [angular, motor, limit].
    pub(crate) ang: [i32; 3],
    /// Linear impulse applied this step, λ̂ summed (Q16.16, 64-bit).
    sum: [i64; 2],
    inv_s: Scalar,
    inv_k: Scalar,
}

/// A point row's per-step values that the pivot lanes take from its row, in
/// the formats of [`JointLanes`]: per side ρ, κ, 1/r_b and the local anchor;
/// M̂ (m11, m12, m22); λ̂. (The pose, the arms r̂ and ĝ = κ·r̂ and the
/// position error d, the lanes measure themselves.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PointRecord {
    pub(super) rho: [i32; 2],
    pub(super) kappa: [i32; 2],
    pub(super) iota: [i32; 2],
    pub(super) anchor: [[i32; 2]; 2],
    pub(super) m: [i32; 3],
    pub(super) lambda: [i32; 2],
}

impl PointRecord {
    /// A pivot that moves nothing (no mass ratios, M̂ = 0, no impulse).
    pub(crate) const INERT: Self =
        Self { rho: [0; 2], kappa: [0; 2], iota: [0; 2], anchor: [[0; 2]; 2], m: [0; 3], lambda: [0; 2] };
}

/// A point row's pose: per side the arm r̂ and ĝ = κ·r̂, and the position
/// error d (the pivot lanes' unit test sets them directly).
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PointPose {
    pub(super) rh: [[i32; 2]; 2],
    pub(super) g: [[i32; 2]; 2],
    pub(super) d: [i32; 2],
}

/// Which accumulated angular impulse a row uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Angular {
    /// The weld's angle, or a pivot's upper limit.
    Main = 0,
    /// A pivot's motor.
    Motor = 1,
    /// A pivot's lower limit.
    Limit = 2,
}

/// Per-step inputs of [`JointLanes::prepare`] (all `Scalar`).
pub(crate) struct JointMasses {
    pub(crate) inv_mass: [Scalar; 2],
    pub(crate) inv_inertia: [Scalar; 2],
    pub(crate) anchors: [Vector2; 2],
    /// Whether B is a fixed world point (its anchor is then that point).
    pub(crate) world_point: bool,
    /// Whether the point constraint's 2×2 mass is needed (pivot, weld).
    pub(crate) point: bool,
    /// Whether there are angular rows (a weld, a pivot with a motor or
    /// limits); without, the angular impulses are neither used nor stored.
    pub(crate) angular: bool,
    /// A pivot motor's target speed (rad/s) and largest impulse per sub-step
    /// (N·m·s; `None` unlimited).
    pub(crate) motor: Option<(Scalar, Option<Scalar>)>,
    /// A pivot's limits (rad).
    pub(crate) limits: Option<(Scalar, Scalar)>,
    /// A target joint's largest linear impulse per sub-step (N·s): its
    /// accumulated point impulse is clamped to it by length.
    pub(crate) max_impulse: Option<Scalar>,
    /// A target joint's spin damping (a soft row with no bias).
    pub(crate) spin_damping: Option<Softness>,
}

impl JointMasses {
    /// A plain pivot's (between two bodies, neither limits nor a motor):
    /// the bodies' inverse masses and inertias, the local anchors.
    pub(crate) fn plain_pivot(
        inv_mass: [Scalar; 2],
        inv_inertia: [Scalar; 2],
        anchors: [Vector2; 2],
    ) -> Self {
        Self {
            inv_mass,
            inv_inertia,
            anchors,
            world_point: false,
            point: true,
            angular: false,
            motor: None,
            limits: None,
            max_impulse: None,
            spin_damping: None,
        }
    }
}

impl JointLanes {
    /// Once per step: ratios, softness and the accumulated impulses in lane
    /// formats, and the arms and position error of the first sub-step. `impulse` (N·s) and
    /// `angular` (N·m·s: angular, motor, limit) are the persistent impulses.
    ///
    /// Written in place, field by field, over whatever the row held: every
    /// field is set, those a kind leaves unused to [`INACTIVE`](Self::INACTIVE)'s
    /// value, so the record is what building it afresh gave, without
    /// building the ~280 bytes on the stack and copying them into the row
    /// (joint 10: three copies a joint a step through `Joint::prepare`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn prepare(
        &mut self,
        m: &JointMasses,
        a: &SolverBody,
        b: &SolverBody,
        soft: LaneSoft,
        inv_h: i32,
        impulse: Vector2,
        angular: [Scalar; 3],
    ) {
        let [ma, mb] = m.inv_mass;
        let [ia, ib] = m.inv_inertia;
        let s = ma + mb;
        let k = ia + ib;
        let rows = m.angular && k > ZERO;
        let inv_s = s.recip();
        let inv_k = if rows { k.recip() } else { ZERO };
        let (anchor_b, base) =
            if m.world_point { (Vector2::ZERO, m.anchors[1]) } else { (m.anchors[1], Vector2::ZERO) };
        let j = self;
        j.linear = s > ZERO;
        j.angular = rows;
        let (na, nb, side) = sides(m, inv_s, inv_k, [m.anchors[0], anchor_b], a, b);
        j.side = side;
        j.m = [0; 3];
        j.soft = soft;
        j.inv_h = inv_h;
        j.base = base;
        // `d` is set by the pose below, `lambda` after it; the rest as INACTIVE.
        j.axis = Self::INACTIVE.axis;
        j.angle = 0;
        j.limits = [0; 2];
        j.motor = [0; 2];
        j.ang = [0; 3];
        j.sum = [0; 2];
        j.inv_s = inv_s;
        j.inv_k = inv_k;
        if let Some((lower, upper)) = m.limits {
            j.limits = [from_scalar(lower, FT, 7), from_scalar(upper, FT, 7)];
        }
        if let Some((speed, max)) = m.motor {
            let lim = i64::from(LAMBDA_MAX >> FV);
            j.motor = [
                from_scalar(speed, FV, 1024),
                max.map_or(LAMBDA_MAX, |t| from_scalar(t * k, FV, lim).max(0)),
            ];
        }
        j.pose(a, b);
        if m.point && j.linear {
            j.m = point_lanes(na, nb, &j.side);
        }
        j.lambda = linear_lanes(impulse, s);
        let v = impulse_lane;
        if let Some(d) = m.spin_damping {
            // A target joint has no limits: the field holds the damping's
            // scales (Q2.30) instead, so the row stays the size it was.
            let d = LaneSoft::new(d);
            j.limits = [d.mass_scale, d.impulse_scale];
        }
        if let Some(max) = m.max_impulse {
            // Rounded half up like every value entering the lanes; the clamp
            // by length below keeps |λ̂| within it.
            j.motor = [0, v(max * s).max(0)];
        }
        if rows {
            j.ang = [v(angular[0] * k), v(angular[1] * k), v(angular[2] * k)];
        }
    }

    /// A record with no rows to run: what prepare's fields start from.
    pub(crate) const INACTIVE: Self = Self {
        linear: false,
        angular: false,
        side: [Side { anchor: [0; 2], rho: 0, kappa: 0, alpha: 0, iota: 0, r: [0; 2], rh: [0; 2], g: [0; 2] };
            2],
        m: [0; 3],
        soft: LaneSoft { rate: 0, mass_scale: 0, impulse_scale: 0 },
        inv_h: 0,
        base: Vector2::ZERO,
        d: [0; 2],
        axis: Axis { n: [0; 2], c: 0, mu: 0, pn: [[0; 2]; 2], x: [0; 2], gamma: [0; 2] },
        angle: 0,
        limits: [0; 2],
        motor: [0; 2],
        lambda: [0; 2],
        ang: [0; 3],
        sum: [0; 2],
        inv_s: ZERO,
        inv_k: ZERO,
    };

    /// The anchors' arms and position error at the bodies' current pose.
    pub(crate) fn pose(&mut self, a: &SolverBody, b: &SolverBody) {
        let [sa, sb] = &mut self.side;
        sa.pose(a.q);
        sb.pose(b.q);
        self.d = position_error(a.p, b.p, self.base, sa.r, sb.r);
    }

    /// The rod's axis, length error and effective mass at the current pose
    /// (after [`pose`](Self::pose)); `length` in m.
    pub(crate) fn axis(&mut self, length: Scalar) {
        let [dx, dy] = self.d;
        // |d| ≤ 2,047 m a component: the square fits 61 bits.
        let sq = i64::from(dx) * i64::from(dx) + i64::from(dy) * i64::from(dy);
        let len = sq.unsigned_abs().isqrt() as i64;
        if len == 0 {
            self.axis = Axis::default();
            return;
        }
        let n = [((i64::from(dx) << FU) / len) as i32, ((i64::from(dy) << FU) / len) as i32];
        let c = narrow(len - i64::from(from_scalar(length, FD, D_MAX)), D_MAX << FD);
        let mut k = 1i64 << FU;
        let mut ax = Axis { n, c, ..Axis::default() };
        for (i, s) in self.side.iter().enumerate() {
            let x = narrow(wide::<FU>(s.rh[0], n[1]) - wide::<FU>(s.rh[1], n[0]), G_MAX << FH);
            // κ·x² in Q2.30: x² (Q.20, ≤ 2⁴²) times κ at 17 fractional bits.
            k += (wide::<FH>(x, x) * i64::from(s.kappa >> 10) + (1 << 6)) >> 7;
            if let (Some(xi), Some(gi), Some(pi)) = (ax.x.get_mut(i), ax.gamma.get_mut(i), ax.pn.get_mut(i)) {
                *xi = x;
                *gi = narrow(wide::<FK>(s.kappa, x), G_MAX << FH);
                *pi = [mul::<FU>(s.rho, n[0]), mul::<FU>(s.rho, n[1])];
            }
        }
        // k ≥ 1, so μ̂ = 1/k ≤ 1.
        ax.mu = ((1i64 << (2 * FU)) / k) as i32;
        self.axis = ax;
    }

    /// Sets the relative angle (rad, in (−π, π]).
    pub(crate) fn set_angle(&mut self, angle: Scalar) {
        self.angle = from_scalar(angle, FT, 7);
    }

    /// The point constraint's warm start: the accumulated λ̂ again.
    // Inlined into the warm start's dispatch (joint 10: 1,303.0 → 1,294.3 M
    // instructions; a call a joint a sub-step).
    #[inline(always)]
    pub(crate) fn warm_point(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        if !self.linear {
            return;
        }
        self.apply_point(la, lb, self.lambda);
    }

    // Inlined into its three callers: the call's register saves were some
    // 15 of its 80 instructions.
    #[inline(always)]
    fn apply_point(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, p: [i32; 2]) {
        self.sum[0] += i64::from(p[0]);
        self.sum[1] += i64::from(p[1]);
        let [sa, sb] = &self.side;
        sa.apply_point::<true>(la, p);
        sb.apply_point::<false>(lb, p);
    }

    /// One iteration of the point constraint (pivot, weld): the anchors
    /// coincide.
    #[inline]
    pub(crate) fn solve_point(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, bias: Bias) {
        self.point_row(la, lb, bias, false);
    }

    /// One iteration of a target joint: the point constraint, always soft and
    /// biased (its own spring), the accumulated λ̂ clamped by length to the
    /// force limit.
    #[inline]
    pub(crate) fn solve_target(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        self.point_row(la, lb, Bias::On, true);
    }

    /// The point row; with `clamp`, |λ̂| ≤ a target joint's largest (`motor[1]`).
    #[inline(always)]
    fn point_row(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, bias: Bias, clamp: bool) {
        if !self.linear {
            return;
        }
        let [sa, sb] = &self.side;
        let (va, vb) = (sa.anchor_velocity(la), sb.anchor_velocity(lb));
        let (bx, sm, si) = self.soft.row::<{ FD + FQ - FV }>(self.d[0], bias);
        let (by, _, _) = self.soft.row::<{ FD + FQ - FV }>(self.d[1], bias);
        let u = [narrow(vb[0] - va[0] + bx, RATE_MAX), narrow(vb[1] - va[1] + by, RATE_MAX)];
        let [m11, m12, m22] = self.m;
        let mu =
            [wide::<FU>(m11, u[0]) + wide::<FU>(m12, u[1]), wide::<FU>(m12, u[0]) + wide::<FU>(m22, u[1])];
        let old = self.lambda;
        for k in 0..2 {
            let delta = match bias {
                Bias::On => -scale(mu[k], sm) - wide::<FU>(si, old[k]),
                // Rigid (s_m = 1, s_i = 0): scale(x, 1) = (x·2³⁰ + 2²⁹) >> 30
                // is x (clamped) exactly, and s_i·λ̂ is zero; written out so
                // that the relax sweep, its `bias` a constant where this is
                // inlined, skips the two products.
                Bias::Off => -sym(mu[k], RATE_MAX),
            };
            self.lambda[k] = narrow(i64::from(old[k]) + delta, i64::from(LAMBDA_MAX));
        }
        if clamp {
            self.lambda = clamp_length(self.lambda, self.motor[1]);
        }
        let applied = [self.lambda[0].wrapping_sub(old[0]), self.lambda[1].wrapping_sub(old[1])];
        self.apply_point(la, lb, applied);
    }

    /// Applies an axial impulse `l` (velocity units) along the axis.
    fn apply_axial(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, l: i32) {
        let ax = &self.axis;
        self.sum[0] += wide::<FU>(ax.n[0], l);
        self.sum[1] += wide::<FU>(ax.n[1], l);
        for (i, (lane, sign)) in [(la, -1i64), (lb, 1i64)].into_iter().enumerate() {
            let (Some(pn), Some(&g)) = (ax.pn.get(i), ax.gamma.get(i)) else { continue };
            add(lane, VX, sign * i64::from(mul::<FU>(pn[0], l)));
            add(lane, VY, sign * i64::from(mul::<FU>(pn[1], l)));
            add(lane, W, sign * wide::<FH>(g, l));
        }
    }

    /// The rod's warm start.
    #[inline]
    pub(crate) fn warm_axial(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        if !self.linear {
            return;
        }
        self.apply_axial(la, lb, self.lambda[0]);
    }

    /// One iteration of a rod (`rope` false: `|d| = length`) or a rope
    /// (`|d| ≤ length`: pulls only, and only when taut or about to be within
    /// the sub-step).
    #[inline]
    pub(crate) fn solve_axial(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, rope: bool, bias: Bias) {
        let ax = self.axis;
        if !self.linear || ax.mu == 0 {
            return;
        }
        let dvx = i64::from(get(lb, VX)) - i64::from(get(la, VX));
        let dvy = i64::from(get(lb, VY)) - i64::from(get(la, VY));
        let rate = ((dvx * i64::from(ax.n[0]) + dvy * i64::from(ax.n[1]) + (1 << (FU - 1))) >> FU)
            + wide::<FH>(get(lb, W), ax.x[1])
            - wide::<FH>(get(la, W), ax.x[0]);
        let (b, sm, si) = if rope && ax.c < 0 {
            // Slack: let it lengthen up to the slack within this sub-step, no more.
            (wide::<{ FD + FQ - FV }>(ax.c, self.inv_h).clamp(-BIAS_MAX, BIAS_MAX), ONE_U, 0)
        } else {
            self.soft.row::<{ FD + FQ - FV }>(ax.c, bias)
        };
        let t = scale(rate + b, sm);
        let old = self.lambda[0];
        let delta = -scale(t, ax.mu) - wide::<FU>(si, old);
        let mut new = narrow(i64::from(old) + delta, i64::from(LAMBDA_MAX));
        if rope {
            // A rope only pulls: the impulse on B along A→B is never positive.
            new = new.min(0);
        }
        self.lambda[0] = new;
        self.apply_axial(la, lb, new.wrapping_sub(old));
    }

    /// Relative spin ω_B − ω_A (rad/s, Q16.16, 64-bit).
    #[inline(always)]
    fn relative_spin(&self, la: &BodyLanes, lb: &BodyLanes) -> i64 {
        let [sa, sb] = &self.side;
        sb.spin(lb) - sa.spin(la)
    }

    /// Applies an angular impulse `l` (relative-spin units; negated on A).
    #[inline(always)]
    fn apply_angular(&self, la: &mut BodyLanes, lb: &mut BodyLanes, l: i32) {
        let [sa, sb] = &self.side;
        sa.apply_angular(la, l, true);
        sb.apply_angular(lb, l, false);
    }

    /// Warm start of the angular rows: `sign`·(motor + limit − main).
    #[inline]
    pub(crate) fn warm_angular(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, negate: bool) {
        if !self.angular {
            return;
        }
        let [main, motor, limit] = self.ang.map(i64::from);
        let l = narrow(motor + limit - main, RATE_MAX);
        if l == 0 {
            return;
        }
        self.apply_angular(la, lb, if negate { l.wrapping_neg() } else { l });
    }

    /// The weld's angular warm start.
    #[inline]
    pub(crate) fn warm_weld(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        if self.angular {
            self.apply_angular(la, lb, self.ang[0]);
        }
    }

    /// The weld's angular row: the relative angle held at zero.
    #[inline]
    pub(crate) fn solve_weld(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, bias: Bias) {
        if !self.angular {
            return;
        }
        let (b, sm, si) = self.soft.row::<{ FT + FQ - FV }>(self.angle, bias);
        self.angular_row(la, lb, b, sm, si);
    }

    /// A target joint's spin damping: a soft row with no bias driving the
    /// relative spin to zero, with the scales prepare put in `limits` (a
    /// target joint has no limits).
    #[inline]
    pub(crate) fn solve_spin_damping(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes) {
        if !self.angular {
            return;
        }
        let [sm, si] = self.limits;
        self.angular_row(la, lb, 0, sm, si);
    }

    /// The main angular row: λ̂ += −s_m·(ω_B − ω_A + b) − s_i·λ̂.
    #[inline(always)]
    fn angular_row(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, b: i64, sm: i32, si: i32) {
        let rate = self.relative_spin(la, lb);
        let old = self.ang[0];
        let delta = -scale(rate + b, sm) - wide::<FU>(si, old);
        let new = narrow(i64::from(old) + delta, i64::from(LAMBDA_MAX));
        self.ang[0] = new;
        self.apply_angular(la, lb, new.wrapping_sub(old));
    }

    /// A pivot's motor: drives `sign`·(ω_B − ω_A) towards its target speed,
    /// within its torque limit.
    #[inline]
    pub(crate) fn solve_motor(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, negate: bool) {
        if !self.angular {
            return;
        }
        let [speed, max] = self.motor.map(i64::from);
        let spin = self.relative_spin(la, lb);
        let spin = if negate { -spin } else { spin };
        let rate = (spin - speed).clamp(-RATE_MAX, RATE_MAX);
        let old = self.ang[Angular::Motor as usize];
        let new = narrow((i64::from(old) - rate).clamp(-max, max), i64::from(LAMBDA_MAX));
        self.ang[Angular::Motor as usize] = new;
        let applied = new.wrapping_sub(old);
        self.apply_angular(la, lb, if negate { applied.wrapping_neg() } else { applied });
    }

    /// A pivot's limits, `lower` ≤ `sign`·θ ≤ `upper` (rad): each one-sided,
    /// speculative while inside the limit, soft when past it.
    #[inline]
    pub(crate) fn solve_limits(&mut self, la: &mut BodyLanes, lb: &mut BodyLanes, negate: bool, bias: Bias) {
        if !self.angular {
            return;
        }
        let angle = if negate { self.angle.wrapping_neg() } else { self.angle };
        let [lower, upper] = self.limits;
        let sign = |x: i32| if negate { x.wrapping_neg() } else { x };
        // Lower limit: θ − lower ≥ 0, pushes θ up (impulse ≥ 0).
        let spin = self.relative_spin(la, lb);
        let spin = if negate { -spin } else { spin };
        let applied = self.limit_step(angle.wrapping_sub(lower), spin, bias, Angular::Limit);
        self.apply_angular(la, lb, sign(applied));
        // Upper limit: upper − θ ≥ 0, pushes θ down (stored as a positive impulse).
        let spin = self.relative_spin(la, lb);
        let spin = if negate { -spin } else { spin };
        let applied = self.limit_step(upper.wrapping_sub(angle), -spin, bias, Angular::Main);
        self.apply_angular(la, lb, sign(applied).wrapping_neg());
    }

    fn limit_step(&mut self, c: i32, rate: i64, bias: Bias, which: Angular) -> i32 {
        let (b, sm, si) = if c > 0 {
            (wide::<{ FT + FQ - FV }>(c, self.inv_h).clamp(-BIAS_MAX, BIAS_MAX), ONE_U, 0)
        } else {
            self.soft.row::<{ FT + FQ - FV }>(c, bias)
        };
        let i = which as usize;
        let Some(&old) = self.ang.get(i) else { return 0 };
        let delta = -scale(rate + b, sm) - wide::<FU>(si, old);
        let new = narrow((i64::from(old) + delta).max(0), i64::from(LAMBDA_MAX));
        if let Some(x) = self.ang.get_mut(i) {
            *x = new;
        }
        new.wrapping_sub(old)
    }

    /// A point row built from a record and a softness (the pivot lanes'
    /// unit test's reference).
    #[cfg(test)]
    pub(super) fn from_point_record(r: &PointRecord, p: &PointPose, soft: LaneSoft) -> Self {
        let mut j = Self::INACTIVE;
        j.linear = true;
        j.side = [0, 1].map(|s| Side {
            anchor: r.anchor[s],
            rho: r.rho[s],
            kappa: r.kappa[s],
            alpha: 0,
            iota: r.iota[s],
            r: [0; 2],
            rh: p.rh[s],
            g: p.g[s],
        });
        (j.m, j.d, j.lambda, j.soft) = (r.m, p.d, r.lambda, soft);
        j
    }

    /// The arms in body radii, ĝ and the position error (tests).
    #[cfg(test)]
    pub(super) fn pose_state(&self) -> ([[i32; 2]; 2], [[i32; 2]; 2], [i32; 2]) {
        let [a, b] = &self.side;
        ([a.rh, b.rh], [a.g, b.g], self.d)
    }

    /// The accumulated λ̂ and the λ̂ applied this step, summed (tests).
    #[cfg(test)]
    pub(super) fn point_state(&self) -> ([i32; 2], [i64; 2]) {
        (self.lambda, self.sum)
    }

    /// Whether the linear rows ran this step (the persistent impulses are
    /// then replaced by [`linear_impulse`](Self::linear_impulse)).
    pub(crate) fn active(&self) -> (bool, bool) {
        (self.linear, self.angular)
    }

    /// The accumulated linear impulse in N·s.
    pub(crate) fn linear_impulse(&self) -> Vector2 {
        linear_impulse(self.lambda, self.inv_s)
    }

    /// The accumulated angular impulses in N·m·s: [angular, motor, limit].
    pub(crate) fn angular_impulses(&self) -> [Scalar; 3] {
        self.ang.map(|l| to_scalar(l, FV) * self.inv_k)
    }

    /// The linear impulse applied over the step (N·s).
    pub(crate) fn step_linear(&self) -> Vector2 {
        step_linear(self.sum, self.inv_s)
    }
}

#[cfg(test)]
mod tests {
    use super::clamp_length;

    /// `Joint::take_lanes` colours a plain pivot as its prepared row's ρ and
    /// κ would: a body moves exactly when its inverse mass or inertia is not
    /// zero. Within the mass limits even the heaviest body pinned to the
    /// lightest keeps a ρ above zero.
    #[test]
    fn a_dynamic_body_keeps_a_mass_ratio_above_zero_at_the_mass_limits() {
        use super::{JointMasses, PivotStart, SolverBody};
        use crate::geometry::mass::{MAX_MASS, MIN_MASS};
        use crate::math::scalar::{Scalar, ZERO};
        use crate::math::Vector2;
        let (heavy, light) = (MAX_MASS.recip(), MIN_MASS.recip());
        for (inv_mass, moves) in [
            ([heavy, light], [true, true]),
            ([light, heavy], [true, true]),
            ([heavy, ZERO], [true, false]),
            ([ZERO, heavy], [false, true]),
        ] {
            let inv_inertia = inv_mass.map(|m| if m == ZERO { ZERO } else { Scalar::ONE });
            let m = JointMasses::plain_pivot(inv_mass, inv_inertia, [Vector2::ZERO; 2]);
            let b = SolverBody::EMPTY;
            let start = PivotStart::new(&m, &b, &b).expect("s > 0");
            let rho = start.side.map(|s| s.rho);
            assert_eq!(rho.map(|r| r > 0), moves, "{inv_mass:?}: ρ {rho:?}");
            // ρ ≥ 2⁻²⁷ in Q2.30: at least eight units.
            assert!(rho.iter().all(|&r| r == 0 || r >= 8), "{rho:?}");
        }
    }

    /// The definition: scaled by max/⌈|v|⌉ (towards zero) when ⌈|v|⌉ > max.
    fn by_definition(v: [i32; 2], max: i32) -> [i32; 2] {
        let [x, y] = v.map(i64::from);
        let sq = (x * x + y * y).unsigned_abs();
        let floor = sq.isqrt();
        let len = (if floor * floor < sq { floor + 1 } else { floor }) as i64;
        let max = i64::from(max.max(0));
        if len <= max {
            return v;
        }
        [(x * max / len) as i32, (y * max / len) as i32]
    }

    /// The early return below max² gives the same bits as the square root,
    /// on the boundary (3-4-5, lengths one ulp either side of max), at the
    /// format's ends and on a pseudo-random sweep; a clamped vector is never
    /// longer than max.
    #[test]
    fn clamp_length_matches_its_definition() {
        let check = |v: [i32; 2], max: i32| {
            let got = clamp_length(v, max);
            assert_eq!(got, by_definition(v, max), "{v:?} max {max}");
            let sq = i64::from(got[0]).pow(2) + i64::from(got[1]).pow(2);
            assert!(sq <= i64::from(max.max(0)).pow(2), "{got:?} longer than {max}");
        };
        let edge = 1 << 30;
        for (v, max) in [
            ([3, 4], 5),
            ([3, 4], 4),
            ([3, 4], 6),
            ([0, 0], 0),
            ([1, 0], 0),
            ([-5, 12], 13),
            ([-5, 12], 12),
            ([edge, -edge], i32::MAX),
            ([edge, edge], 1_518_500_250),
            ([edge, edge], 1_518_500_249),
            ([-edge, 0], edge),
            ([-edge, 0], edge - 1),
            ([7, 7], -3),
        ] {
            check(v, max);
        }
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..20_000 {
            let r = crate::solver::xorshift(&mut seed);
            let shift = (r % 31) as u32;
            let x = ((r >> 8) as i32) >> (shift + 1);
            let y = ((r >> 40) as i32) << 8 >> (shift + 1);
            let len = (i64::from(x).pow(2) + i64::from(y).pow(2)).unsigned_abs().isqrt() as i32;
            // Lengths within two of max either way.
            check([x, y], len.saturating_add(((r >> 4) % 5) as i32 - 2));
        }
    }
}
