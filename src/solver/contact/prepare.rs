//! Building a contact's lane once per step: the arms in body radii, the mass
//! ratios that replace every effective mass in the sweeps, the friction factor
//! and, for a two-point manifold computed in this step, the normalised inverse
//! of its 2×2 mass matrix.
//!
//! **The block only for a computed manifold.** A manifold recycled from an
//! earlier step ([`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance))
//! has its points solved one at a time, in the sweep's direction, as Box2D
//! v3 solves them: a settled pair keeps its anchors, and the 20-box stack
//! then stands without the block (top drift 0.00014 m in 10 s, limit 0.01),
//! where anchors recomputed every step buckle it (0.316 m); without the block
//! the 20-row pyramid runs 8 % fewer instructions a step. A manifold computed
//! this step, a new pair's or one that moved, keeps the block: in a flat
//! impact both points are approaching at once, and one at a time the first
//! point's impulse turns the body and the second's throws the first off the
//! face (a 4 m box striking a wall at 2,048 m/s left it 0.32 m before its
//! impact step ended; `tests/recycle.rs`). A world that turns recycling off
//! computes every manifold, so every two-point manifold takes the block.
//!
//! **A kept lane.** Everything above but the warm-start impulses, the
//! separations and the approach speeds is a function of the manifold's
//! normal and anchors, the pair's friction and the two bodies' inverse
//! masses, rim inverse masses and radii. A recycled manifold keeps its normal
//! and anchors, so when the friction and the masses are also unchanged and
//! the arbiter gets the lane it had in the last build (nothing was added or
//! removed before it, so the layout is the same), the lane still holds those
//! fields and [`prepare`] writes only the others (`again`), reading the arms
//! back for k̂; the bits are those of a full build. A settled scene keeps
//! every lane: the 20-row pyramid runs 8 % fewer instructions a step, and
//! its two divisions a point are gone (see `colour::build` for the checks).
//!
//! For a row along direction d with arms r_A, r_B, k = 1/m_A + 1/m_B +
//! (r_A×d)²/I_A + (r_B×d)²/I_B is the inverse of the mass the pair presents.
//! The lanes carry the impulse as λ̂ = λ·k (m/s) and apply it with ρ = (1/m)/k
//! (≤ 1) and γ̂ = (r×d)·r_b/(I·k), so no mass, and none of the mass range's 27
//! bits, ever enters a lane.
//!
//! **Integer formats.** Written with the arm in body radii, â = (r×d)/r_b,
//! and each body's rim inverse mass j = r_b²/I, the row is
//! k = m_A + m_B + j_A·â_A² + j_B·â_B² (m the inverse masses), and every
//! quantity a lane needs is a ratio of such terms: ρ_A = m_A/k,
//! γ̂_A = j_A·â_A/k. Ratios do not change when all four inverse masses are
//! scaled alike, so prepare scales them once per pair by a power of two that
//! puts m_A + m_B + j_A + j_B in [2³⁰, 2³¹) and works in `i64` from there:
//!
//! | quantity | format | bound |
//! |---|---|---|
//! | m̂, ĵ (the pair's scaled inverse masses) | integer mantissas | < 2³¹ together |
//! | anchor components and arms in body radii | Q3.29 | ±[`ARM_MAX`] (clamped) |
//! | unit vectors, ratios, scales | Q2.30 | ±1 |
//! | k̂ = m̂_A + m̂_B + ĵ_A·â_A² + ĵ_B·â_B² | mantissa | < 2³⁴ (â² ≤ 4) |
//! | r̂ = 2⁶⁰/k̂ | Q.60 of 1/k̂ | ≤ 2⁶⁰ (k̂ ≥ 1) |
//!
//! Every product of two of these fits `i64` except the few with r̂ or an
//! impulse, which take an `i128`; one division per row (r̂) and one per
//! block replace the `Scalar` reciprocals, and nothing here saturates
//! silently: each lane value is clamped to its format's bound. A body whose
//! rim inverse mass dwarfs its inverse mass (an inertia far below m·r_b², which
//! no convex shape has: r_b ≤ 2√2 times the radius of gyration, so j ≤ 8·m)
//! keeps fewer bits of m̂: its ratios lose precision, never range.

use crate::arbiter::{Arbiter, ContactPoint};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::solver::lanes::{self, sym, ARM_MAX, BLOCK_MAX, FM, FR, FS, FU, GAMMA_MAX, PHI_MAX};
use crate::solver::SolverBody;

use super::f;
use super::{Block, A_DYNAMIC, B_DYNAMIC, HAS_BLOCK, LANES, ROWS, STATIC_PAIR, TWO_POINTS};

/// One in Q2.30.
const ONE30: i64 = 1 << FU;
/// The arm bound in Q3.29.
const ARM: i64 = ARM_MAX << FR;

/// One body of a pair as prepare sees it: its inverse mass, its rim inverse
/// mass j = r_b²/I and the inverse of the radius its rim speed is measured at.
#[derive(Clone, Copy)]
struct Side {
    m: Scalar,
    j: Scalar,
    inv_radius: Scalar,
}

impl Side {
    #[inline(always)]
    fn new(sb: &SolverBody) -> Self {
        Self { m: sb.inv_mass, j: sb.rim_inv_mass, inv_radius: sb.inv_radius }
    }

    /// An anchor in body radii (Q3.29), each component clamped to ±[`ARM_MAX`].
    #[inline(always)]
    fn anchor(&self, r: Vector2) -> [i64; 2] {
        [arm_lane(r.x, self.inv_radius), arm_lane(r.y, self.inv_radius)]
    }
}

/// `lane(x * y, FR, ARM_MAX)` from the exact product, without the saturating
/// product's middle word: the same value.
///
/// The product saturates when its high word is outside [−2³¹, 2³¹); then
/// `lane` clamps the saturated value to ∓ or ±[`ARM`] by the sign, as here.
/// Otherwise s = ⌊x·y/2³²⌋ fits `i64`, and `lane` takes ⌊s/8⌋ plus bit 2 of
/// s, which is (⌊s/4⌋ + 1) >> 1 = ((⌊x·y/2³⁴⌋ + 1) >> 1): one shift of the
/// product instead of the middle word and a bit test (about 4 instructions an
/// anchor, eight anchors an arbiter).
#[inline(always)]
fn arm_lane(x: Scalar, y: Scalar) -> i64 {
    let full = i128::from(x.to_bits()).wrapping_mul(i128::from(y.to_bits()));
    let hi = (full >> 64) as i64;
    // A high word in [−2, 2) is |x·y| < 2⁶⁵: no saturation, ⌊x·y/2³⁴⌋ within
    // [−2³¹, 2³¹) and the rounded value within ±2³⁰ = ±[`ARM`], so neither
    // test below can act; one test instead of two (the anchors are within
    // two body radii all but always: 3 instructions an anchor).
    if (hi as u64).wrapping_add(2) < 4 {
        return (((full >> (32 + (32 - FR) - 1)) as i64) + 1) >> 1;
    }
    arm_lane_wide(full, hi)
}

/// [`arm_lane`] beyond two body radii.
#[cold]
#[inline(never)]
fn arm_lane_wide(full: i128, hi: i64) -> i64 {
    if (hi as u64).wrapping_add(1 << 31) >> 32 == 0 {
        sym((((full >> (32 + (32 - FR) - 1)) as i64) + 1) >> 1, ARM)
    } else {
        arm_saturated(hi)
    }
}

#[cold]
#[inline(never)]
fn arm_saturated(hi: i64) -> i64 {
    if hi < 0 {
        -ARM
    } else {
        ARM
    }
}

/// `x` of a wide value clamped to ±`bound` (`bound ≥ 0`), as [`sym`]: below
/// 2⁶², in range exactly when x + bound, as a `u128`, is at most 2·bound.
#[inline(always)]
fn sym_wide(x: i128, bound: i64) -> i64 {
    if bound >= 1 << 62 {
        return x.clamp(-i128::from(bound), i128::from(bound)) as i64;
    }
    let shifted = x.wrapping_add(i128::from(bound)).cast_unsigned();
    if shifted <= u128::from(bound.cast_unsigned() << 1) {
        x as i64
    } else {
        clamp_wide_cold(x, bound)
    }
}

#[cold]
#[inline(never)]
fn clamp_wide_cold(x: i128, bound: i64) -> i64 {
    x.clamp(-i128::from(bound), i128::from(bound)) as i64
}

/// [`lanes::from_scalar`] with the clamp of [`sym`]: the same value.
#[inline(always)]
fn lane(x: Scalar, f: u32, bound: i64) -> i64 {
    let shift = 32 - f;
    let bits = x.to_bits();
    let rounded = (bits >> shift) + ((bits >> (shift - 1)) & 1);
    sym(rounded, (bound << f).min(i64::from(i32::MAX)))
}

/// `x / 2^k`, rounded half up.
#[inline(always)]
fn rnd(x: i64, k: u32) -> i64 {
    (x + (1 << (k - 1))) >> k
}

/// `x / 2^k` of a wide product, rounded half up and clamped to ±`bound`.
#[inline(always)]
fn rnd_wide(x: i128, k: u32, bound: i64) -> i64 {
    sym_wide((x + (1i128 << (k - 1))) >> k, bound)
}

/// `x / 2^k` of a wide product whose caller proves the quotient fits `i64`,
/// rounded half up and clamped to ±`bound`: the same value as [`rnd_wide`],
/// with the clamp on one word instead of two.
#[inline(always)]
fn rnd_fit(x: i128, k: u32, bound: i64) -> i64 {
    sym(((x + (1i128 << (k - 1))) >> k) as i64, bound)
}

/// `x / 2^k` of a non-negative wide product, rounded half up and capped at
/// `bound`: [`rnd_wide`]'s value (its lower clamp never acts), with one
/// unsigned comparison instead of two signed ones.
#[inline(always)]
fn rnd_unsigned(x: u128, k: u32, bound: u64) -> i64 {
    ((x + (1u128 << (k - 1))) >> k).min(u128::from(bound)) as i64
}

/// The arm â×d (Q3.29) of an anchor `a` (Q3.29) along unit `d` (Q2.30).
#[inline(always)]
fn arm(a: [i64; 2], d: [i64; 2]) -> i64 {
    sym(rnd(a[0] * d[1] - a[1] * d[0], FU), ARM)
}

/// The pair's four inverse masses on one scale (see the module docs).
#[derive(Clone, Copy)]
struct Pair {
    m: [i64; 2],
    j: [i64; 2],
    /// Mantissa = value·2^(32 − shift).
    shift: i32,
    /// The impulse conversion's right shift 48 − shift (within 1..=126) and
    /// its rounding half, once per pair.
    down: u32,
    half: i128,
    /// `down` below 64: `half` fits an `i64` and one word can be shifted by it.
    narrow: bool,
}

impl Pair {
    #[inline(always)]
    fn new(a: &Side, b: &Side) -> Self {
        let bits = |x: Scalar| x.to_bits().max(0).unsigned_abs();
        let (ma, mb, ja, jb) = (bits(a.m), bits(b.m), bits(a.j), bits(b.j));
        let sum = ma.saturating_add(mb).saturating_add(ja).saturating_add(jb);
        // The sum's top bit lands on bit 30 (one guard bit below 2³¹). Each
        // term is at most the (saturating) sum, which is below 2^(31 + shift),
        // so every scaled term is below 2³¹ without a clamp (0 if the sum is).
        let shift = 33 - sum.leading_zeros() as i32;
        let scale = |x: u64| -> i64 {
            (if shift >= 0 { x >> shift.unsigned_abs() } else { x << shift.unsigned_abs() }) as i64
        };
        let down = (48 - shift).clamp(1, 126).unsigned_abs();
        Self {
            m: [scale(ma), scale(mb)],
            j: [scale(ja), scale(jb)],
            shift,
            down,
            half: 1 << (down - 1),
            narrow: down < 64,
        }
    }

    /// k̂ for arms `ra`, `rb` (Q3.29): at most 2³¹·(1 + 4) < 2³⁴.
    #[inline(always)]
    fn k(&self, ra: i64, rb: i64) -> i64 {
        self.m[0]
            + self.m[1]
            + ((self.j[0] * rnd(ra * ra, FR)) >> FR)
            + ((self.j[1] * rnd(rb * rb, FR)) >> FR)
    }

    /// The off-diagonal k̂12 of two normal rows with arms (`a1`, `b1`), (`a2`, `b2`).
    #[inline(always)]
    fn k12(&self, (a1, b1): (i64, i64), (a2, b2): (i64, i64)) -> i64 {
        self.m[0]
            + self.m[1]
            + ((self.j[0] * rnd(a1 * a2, FR)) >> FR)
            + ((self.j[1] * rnd(b1 * b2, FR)) >> FR)
    }

    /// 1/k as a `Scalar` (kg) from r̂ = 2⁶⁰/k̂: its bits are r̂·2^(4 − shift).
    /// In one word: r̂ ≥ 0, so a left shift saturates exactly when r̂ exceeds
    /// `i64::MAX >> e`, and a right shift of 63 or more leaves 0 (r̂ ≤ 2⁶⁰).
    #[inline(always)]
    fn mass(&self, r: i64) -> Scalar {
        let e = 4 - self.shift;
        let by = e.unsigned_abs().min(63);
        let bits = if e < 0 {
            r >> by
        } else if r > i64::MAX >> by {
            i64::MAX
        } else {
            r << by
        };
        Scalar::from_bits(bits)
    }

    /// λ·k in Q16.16 for an impulse λ (N·s), clamped to ±`bound` (Q16.16):
    /// λ_bits·k̂·2^(shift − 48).
    #[inline(always)]
    fn impulse(&self, lambda: Scalar, k: i64, bound: i64) -> i64 {
        // Mostly λ_bits·k̂ and the rounding half both fit one word (the half
        // does when the shift does, `narrow`): the same sum and shift in
        // `i64`, two overflow tests instead of the `i128` product, sum and
        // variable shift (about 13 instructions an impulse, four a pair).
        if self.narrow {
            if let Some(x) = lambda.to_bits().checked_mul(k).and_then(|x| x.checked_add(self.half as i64)) {
                return sym(x >> self.down, bound);
            }
        }
        let x = i128::from(lambda.to_bits()) * i128::from(k);
        sym_wide((x + self.half) >> self.down, bound)
    }
}

/// 2⁶⁰/k̂, or 0 for a row nothing can move.
#[inline(always)]
fn recip60(k: i64) -> i64 {
    if k > 0 {
        ((1u64 << 60) / k.unsigned_abs()) as i64
    } else {
        0
    }
}

/// One row's lane values: ρ_A·d, ρ_B·d (Q2.30) and γ̂_A, γ̂_B (Q2.30).
#[inline(always)]
fn row(pair: &Pair, r: i64, d: [i64; 2], (ra, rb): (i64, i64)) -> [i64; 6] {
    // ρ = m̂/k̂ ≤ 1: 0 ≤ m̂ ≤ k̂ (k̂'s other terms are ≥ 0) and r̂ = ⌊2⁶⁰/k̂⌋,
    // so m̂·r̂ ≤ k̂·r̂ ≤ 2⁶⁰ and the ratio is at most 2³⁰ without a clamp.
    let ratio = |m: i64| (m * r) >> FU;
    let (pa, pb) = (ratio(pair.m[0]), ratio(pair.m[1]));
    // γ̂ = ĵ·â/k̂: |ĵ·â| ≤ 2³¹·2³⁰, times r̂ ≤ 2⁶⁰ in i128, then 2⁻⁵⁹: ≤ 2⁶² + 1.
    let g_max = lanes::from_scalar(GAMMA_MAX, FU, 2).into();
    let gamma = |j: i64, a: i64| rnd_fit(i128::from(j * a) * i128::from(r), 60 + FR - FU, g_max);
    [
        rnd(pa * d[0], FU),
        rnd(pa * d[1], FU),
        rnd(pb * d[0], FU),
        rnd(pb * d[1], FU),
        gamma(pair.j[0], ra),
        gamma(pair.j[1], rb),
    ]
}

/// Writes `x` into lane `l` of field `fi` (both taken modulo their ranges).
#[inline(always)]
fn put(blk: &mut Block, fi: usize, l: usize, x: i64) {
    blk[(fi / ROWS) % LANES].rows[fi % ROWS][l % LANES] = x as i32;
}

/// What both points of a pair share: the bodies as prepare sees them, the
/// pair's scale, the normal and tangent (Q2.30) and the friction coefficient.
struct Shared {
    /// Each body's velocity and angular velocity at the start of the step,
    /// from the solver's copy, which the step has just loaded from the
    /// bodies (a fixed-rotation body's spin is 0 in both: the world stops it
    /// when it locks the body and `restore` refuses a snapshot that spins
    /// one), so prepare reads no `Body`: colouring no longer looks the
    /// bodies up a second time (large scene, 20 steps: 2,139.1 → 2,129.9 M
    /// instructions and 36.74 → 36.38 M first-level data-cache misses in
    /// cachegrind; the same bits).
    vel: [(Vector2, Scalar); 2],
    side_a: Side,
    side_b: Side,
    pair: Pair,
    normal: Vector2,
    n: [i64; 2],
    t: [i64; 2],
    friction: u128,
    /// Both bodies' velocities within 2¹³ and the normal's components
    /// within 2: see [`approach`].
    small: bool,
}

/// What the pair keeps of a point once its fields are written: k̂ and r̂ of the
/// normal row, the normal arms (for the block) and the effective masses.
struct PointOut {
    k_n: i64,
    r_n: i64,
    arms_n: (i64, i64),
    masses: [Scalar; 2],
}

/// Writes point `src`'s fields, from field `BASE` on, into lane `l`. Inlined
/// once per point with the field numbers constant, each field is one store
/// straight into the block: returning the 24 values and copying them cost
/// about 120 instructions a point (large scene, 20 steps: 2,648.6 → 2,577.2 M).
#[inline(always)]
fn point<const BASE: usize>(c: &Shared, src: &ContactPoint, blk: &mut Block, l: usize) -> PointOut {
    let (pair, n, t) = (&c.pair, c.n, c.t);
    let phi_max = ((PHI_MAX - 1) << lanes::FPHI).unsigned_abs();
    let (aa, ab) = (c.side_a.anchor(src.anchor_a), c.side_b.anchor(src.anchor_b));
    // Each field is stored as soon as it is known: fewer values live at once,
    // fewer spills (about 40 instructions an arbiter: large scene, 20 steps,
    // 2,542.5 → 2,529.6 M).
    let mut put_at = |x: usize, v: i64| put(blk, BASE + x, l, v);
    let (ran, rbn, rat, rbt) = (arm(aa, n), arm(ab, n), arm(aa, t), arm(ab, t));
    put_at(f::RAN, ran);
    put_at(f::RBN, rbn);
    put_at(f::RAT, rat);
    put_at(f::RBT, rbt);
    let (k_n, k_t) = (pair.k(ran, rbn), pair.k(rat, rbt));
    let (r_n, r_t) = (recip60(k_n), recip60(k_t));
    for (x, v) in
        [f::ANX, f::ANY, f::BNX, f::BNY, f::GAN, f::GBN].into_iter().zip(row(pair, r_n, n, (ran, rbn)))
    {
        put_at(x, v);
    }
    for (x, v) in
        [f::ATX, f::ATY, f::BTX, f::BTY, f::GAT, f::GBT].into_iter().zip(row(pair, r_t, t, (rat, rbt)))
    {
        put_at(x, v);
    }
    // |λ_t| ≤ μ·λ_n ⇔ |λ̂_t| ≤ μ·(k_t/k_n)·λ̂_n; φ·min(λ̂_n, c_φ) ≤ Λ.
    // k_t/k_n in Q2.30 (clamped at 2¹⁰), then μ (Q32.32) times it.
    // Both products are of non-negative factors (k̂, r̂, μ ≥ 0).
    let ratio =
        rnd_unsigned(u128::from(k_t.unsigned_abs()) * u128::from(r_n.unsigned_abs()), 60 - FU, 1 << 40);
    let phi = rnd_unsigned(c.friction * u128::from(ratio.unsigned_abs()), 32 + FU - lanes::FPHI, phi_max);
    put_at(f::PHI, phi);
    let lambda_max = i64::from(lanes::LAMBDA_MAX);
    put_at(f::CPHI, if phi > 1 << lanes::FPHI { (lambda_max << lanes::FPHI) / phi } else { lambda_max });
    per_step::<BASE>(c, src, blk, l, (k_n, k_t));
    PointOut { k_n, r_n, arms_n: (ran, rbn), masses: [pair.mass(r_n), pair.mass(r_t)] }
}

/// Writes the fields of point `src` that change from step to step, from
/// field `BASE` on, into lane `l`: the warm-start impulses (with the rows'
/// k̂ `k`), the separation, the approach speed, and the step's largest and
/// total impulse (0).
#[inline(always)]
fn per_step<const BASE: usize>(
    c: &Shared,
    src: &ContactPoint,
    blk: &mut Block,
    l: usize,
    (k_n, k_t): (i64, i64),
) {
    let lambda_max = i64::from(lanes::LAMBDA_MAX);
    let mut put_at = |x: usize, v: i64| put(blk, BASE + x, l, v);
    put_at(f::LN, c.pair.impulse(src.normal_impulse, k_n, lambda_max).max(0));
    put_at(f::LT, c.pair.impulse(src.tangent_impulse, k_t, lambda_max));
    put_at(f::BASE, lane(src.separation, FS, 4095));
    // [`lanes::velocity`]: saturated at the wall.
    put_at(f::VREL, lane(approach(c, src), lanes::FV, 2048));
    put_at(f::MAXD, 0);
    put_at(f::TOT, 0);
}

/// [`point`] for a lane that holds what it wrote in the last build, from the
/// same manifold, friction and masses (see `colour::build`): the arms are
/// read back for the rows' k̂ and only [`per_step`]'s fields are written.
/// The bits are those [`point`] writes.
#[inline(always)]
fn point_again<const BASE: usize>(c: &Shared, src: &ContactPoint, blk: &mut Block, l: usize) {
    let arm = |x: usize| i64::from(super::lane(super::field(blk, BASE + x), l));
    let k = (c.pair.k(arm(f::RAN), arm(f::RBN)), c.pair.k(arm(f::RAT), arm(f::RBT)));
    per_step::<BASE>(c, src, blk, l, k);
}

/// Whether every value lies in [−2^`k`, 2^`k`): then x + 2^`k` is below
/// 2^(`k` + 1) as a `u64` (any other x lands at or above it, wrapped or
/// not), and so is the `or` of them all exactly when each is.
#[inline(always)]
fn within<const N: usize>(xs: [i64; N], k: u32) -> bool {
    xs.iter().fold(0u64, |acc, &x| acc | x.wrapping_add(1 << k).cast_unsigned()) < 1 << (k + 1)
}

/// `⌊a·b/2³²⌋` of two `Scalar` bit patterns whose product fits: the
/// saturating product's value when it does not saturate.
#[inline(always)]
fn mul_bits(a: i64, b: i64) -> i64 {
    crate::math::scalar::product_bits(a, b)
}

/// The approach speed (v_B(r_B) − v_A(r_A))·n at a point, as the saturating
/// `Scalar` operations give it.
///
/// When the bodies' velocities, the arms and the normal are small (checked
/// per pair in [`Shared::small`], and here for the arms) none of those
/// operations can saturate, and the plain integer operations give the same
/// bits without a test on each (the saturating form took about 100
/// instructions a point, this one about 55 with its checks; net, large
/// scene, 20 steps: 2,384.0 → 2,374.2 M). With |v|, |ω|, |r| < 2¹³ and
/// |n| < 2: |ω·r| < 2²⁶, each velocity < 2²⁷, their difference < 2²⁸ and
/// each term of the dot product < 2²⁹, all far inside the ±2³¹ of a `Scalar`
/// (and every product's ⌊·/2³²⌋ fits an `i64`).
#[inline(always)]
fn approach(c: &Shared, src: &ContactPoint) -> Scalar {
    let [(va, wa), (vb, wb)] = c.vel;
    approach_of([(va, wa, src.anchor_a), (vb, wb, src.anchor_b)], c.normal, c.small)
}

/// [`approach`] from each body's velocity, angular velocity and arm, the
/// normal and the pair's [`Shared::small`].
#[inline(always)]
fn approach_of(
    [(va, wa, ra), (vb, wb, rb)]: [(Vector2, Scalar, Vector2); 2],
    n: Vector2,
    small: bool,
) -> Scalar {
    let arms = [ra.x.to_bits(), ra.y.to_bits(), rb.x.to_bits(), rb.y.to_bits()];
    if small && within(arms, SMALL) {
        let at = |v: Vector2, w: Scalar, r: Vector2| {
            let w = w.to_bits();
            [v.x.to_bits() - mul_bits(w, r.y.to_bits()), v.y.to_bits() + mul_bits(w, r.x.to_bits())]
        };
        let (a, b) = (at(va, wa, ra), at(vb, wb, rb));
        Scalar::from_bits(mul_bits(b[0] - a[0], n.x.to_bits()) + mul_bits(b[1] - a[1], n.y.to_bits()))
    } else {
        // [`Body::velocity_at_offset`] of each.
        let dv = (vb + Vector2::cross_sv(wb, rb)) - (va + Vector2::cross_sv(wa, ra));
        dv.dot(n)
    }
}

/// Whether both bodies' velocities lie within [`approach`]'s bound and the
/// normal's components within 2: [`Shared::small`].
#[inline(always)]
fn small_pair([(va, wa), (vb, wb)]: [(Vector2, Scalar); 2], n: Vector2) -> bool {
    within([va.x, va.y, wa, vb.x, vb.y, wb].map(Scalar::to_bits), SMALL)
        && within([n.x.to_bits(), n.y.to_bits()], SMALL_NORMAL)
}

/// The bound of [`approach`]'s plain path on velocities, angular velocities
/// and arms: 2¹³ (m/s, rad/s, m) in `Scalar` bits.
const SMALL: u32 = 32 + 13;
/// Its bound on the normal's components: 2.
const SMALL_NORMAL: u32 = 32 + 1;

/// Zeroes an unused point's fields, from field `BASE` on, in lane `l`:
/// nothing pushes, nothing is applied.
#[inline(always)]
fn no_point<const BASE: usize>(blk: &mut Block, l: usize) {
    for x in 0..f::POINT {
        put(blk, BASE + x, l, 0);
    }
}

/// Builds lane `l` of `blk` from an arbiter between bodies `a` and `b` (slots
/// `ia`, `ib`; at least one dynamic); the scales are the mass scales of the
/// contact and static softness. Returns each point's normal and tangent
/// effective mass, for the store.
///
/// With `again`, the lane holds what the last build wrote for this arbiter
/// from the same manifold, friction and masses (`colour::build` checks it):
/// only the fields that change from step to step are written, and `None`
/// is returned (the masses of the last build stand). The bits are those of
/// a full build.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prepare(
    arb: &Arbiter,
    (ia, ib): (u32, u32),
    (sa, sb): (&SolverBody, &SolverBody),
    (contact_scale, static_scale): (Scalar, Scalar),
    again: bool,
    blk: &mut Block,
    l: usize,
) -> Option<[[Scalar; 2]; 2]> {
    let (side_a, side_b) = (Side::new(sa), Side::new(sb));
    let pair = Pair::new(&side_a, &side_b);
    // A kept lane holds the bodies' slots and the normal already (the same
    // arbiter's, its manifold recycled): written only in a full build.
    let unit = |x: Scalar| lane(x, FU, 1);
    let n = if again { [0; 2] } else { [unit(arb.normal.x), unit(arb.normal.y)] };
    let t = [n[1], -n[0]];
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
    if !again {
        put(blk, f::IA, l, i64::from(ia));
        put(blk, f::IB, l, i64::from(ib));
        put(blk, f::NX, l, n[0]);
        put(blk, f::NY, l, n[1]);
    }
    put(blk, f::E, l, lane(arb.restitution, FU, 1));
    let vel = [(sa.v, sa.w), (sb.v, sb.w)];
    let shared = Shared {
        vel,
        side_a,
        side_b,
        pair,
        normal: arb.normal,
        n,
        t,
        friction: u128::from(arb.friction.max(ZERO).to_bits().unsigned_abs()),
        small: small_pair(vel, arb.normal),
    };
    let [first, second] = &arb.points;
    if again {
        point_again::<{ f::P[0] }>(&shared, first, blk, l);
        if arb.count < 2 {
            if arb.count == 0 {
                no_point::<{ f::P[0] }>(blk, l);
            }
            no_point::<{ f::P[1] }>(blk, l);
        } else {
            point_again::<{ f::P[1] }>(&shared, second, blk, l);
            flags |= TWO_POINTS;
        }
        put(blk, f::FLAGS, l, i64::from(flags));
        return None;
    }
    let one = point::<{ f::P[0] }>(&shared, first, blk, l);
    let mut masses = [one.masses, [ZERO; 2]];
    if arb.count < 2 {
        if arb.count == 0 {
            // An unused point: nothing pushes, nothing is applied (what
            // `point` wrote is overwritten; no branch on the common path).
            no_point::<{ f::P[0] }>(blk, l);
            masses[0] = [ZERO; 2];
        }
        no_point::<{ f::P[1] }>(blk, l);
    } else {
        let two = point::<{ f::P[1] }>(&shared, second, blk, l);
        masses[1] = two.masses;
        flags |= TWO_POINTS;
        let scale = if static_pair { static_scale } else { contact_scale };
        let inverse =
            || block_inverse([one.k_n, two.k_n], [one.r_n, two.r_n], pair.k12(one.arms_n, two.arms_n), scale);
        // The block for a manifold computed this step only (see the module
        // docs); both points of a manifold are kept or computed together.
        if let Some(block) = if first.recycled { None } else { inverse() } {
            flags |= HAS_BLOCK;
            for (fi, x) in [
                f::C12,
                f::C21,
                f::MR,
                f::MR + 1,
                f::MR + 2,
                f::MR + 3,
                f::MS,
                f::MS + 1,
                f::MS + 2,
                f::MS + 3,
            ]
            .into_iter()
            .zip(block)
            {
                put(blk, fi, l, x);
            }
        }
    }
    put(blk, f::FLAGS, l, i64::from(flags));
    Some(masses)
}

/// The couplings c12 = k12/k22, c21 = k12/k11 (`r` holds 2⁶⁰/k̂11, 2⁶⁰/k̂22)
/// and the normalised inverses M̂ = D·K⁻¹ (D = diag(k11, k22)) of the rigid
/// system and of the soft one (diagonal k_ii/s), when the pair is well
/// conditioned: the diagonal entries within a factor 4 of each other and every
/// entry of M̂ below [`BLOCK_MAX`]; otherwise `None` and the
/// points are solved one at a time.
///
/// With ρ² = c12·c21 = k12²/(k11·k22) ≤ 1 and a mass scale s,
/// M̂ = 1/(1 − s²ρ²)·[[s, −s²·c12], [−s²·c21, s]].
fn block_inverse(k: [i64; 2], r: [i64; 2], k12: i64, s: Scalar) -> Option<[i64; 10]> {
    let [k11, k22] = k;
    if k11 <= 0 || k22 <= 0 || k11 > k22 * 4 || k22 > k11 * 4 {
        return None;
    }
    // |k12| ≤ √(k11·k22) ≤ 2·min(k11, k22): the couplings are within ±2 (Q3.29).
    let c_max = 2 << FR;
    let c12 = rnd_wide(i128::from(k12) * i128::from(r[1]), 60 - FR, c_max);
    let c21 = rnd_wide(i128::from(k12) * i128::from(r[0]), 60 - FR, c_max);
    let rho2 = rnd(c12 * c21, 2 * FR - FU);
    let rigid = inverse(ONE30, rho2, (c12, c21))?;
    let soft = inverse(lane(s, FU, 1), rho2, (c12, c21))?;
    Some([c12, c21, rigid[0], rigid[1], rigid[2], rigid[3], soft[0], soft[1], soft[2], soft[3]])
}

/// [`block_inverse`]'s M̂ for mass scale `s` (Q2.30), from ρ² (Q2.30) and the
/// couplings (Q3.29), or `None` when an entry reaches [`BLOCK_MAX`]. Inlined
/// by hand: as a closure the compiler called it (about 30 M more
/// instructions in the large scene's 20 steps).
#[inline(always)]
fn inverse(s: i64, rho2: i64, (c12, c21): (i64, i64)) -> Option<[i64; 4]> {
    // BLOCK_MAX in Q5.27: 2³¹, so an entry below it fits an `i32`.
    let e_max = BLOCK_MAX.to_bits() >> (32 - FM);
    let ss = rnd(s * s, FU);
    let det = ONE30 - rnd(ss * rho2, FU);
    if det <= 0 {
        return None;
    }
    // 1/det in Q5.27 (det ≥ 1 ulp: at most 2⁵⁷).
    let inv = (1i64 << (FU + FM)) / det;
    // |s| ≤ 2³⁰ and |ss·c| ≤ 2⁶⁰ (rounded to ≤ 2³¹ + 1) times inv ≤ 2⁵⁷, then
    // 2⁻³⁰: both quotients fit `i64`.
    let diag = rnd_fit(i128::from(s) * i128::from(inv), FU, e_max);
    let off = |c: i64| -rnd_fit(i128::from(rnd(ss * c, FR)) * i128::from(inv), FU, e_max);
    let e = [diag, off(c12), off(c21), diag];
    e.iter().all(|x| x.abs() < e_max).then_some(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn side(mass: f64, radius: f64, inertia: f64) -> Side {
        let inv = |x: f64| if x > 0.0 { Scalar::from_num(1.0 / x) } else { ZERO };
        let r = Scalar::from_num(radius);
        Side { m: inv(mass), j: inv(inertia) * r * r, inv_radius: r.recip() }
    }

    /// The integer ratios against a float reference of the same formulas, at
    /// the ends of the mass range (0.001–100,000 kg), radii 1 cm–100 m,
    /// arms across ±2 radii and one side static.
    #[test]
    fn ratios_match_the_definition_across_the_limits() {
        let masses = [0.001, 0.37, 1.0, 250.0, 100_000.0, 0.0];
        let radii = [0.01, 0.5, 3.0, 100.0];
        let arms = [-2.0, -1.3, -0.01, 0.0, 0.25, 0.999, 2.0];
        let q = |x: i64, f: u32| x as f64 / (1i64 << f) as f64;
        let mut checked = 0;
        for &ma in &masses {
            for &mb in &masses[..5] {
                for &ra in &radii {
                    for &rb in &radii {
                        // A disc and a thin rod: j = 2m and 3m.
                        let (ia, ib) = (ma * ra * ra / 2.0, mb * rb * rb / 3.0);
                        let (a, b) = (side(ma, ra, ia), side(mb, rb, ib));
                        let pair = Pair::new(&a, &b);
                        // The reference takes the same `Scalar` inputs (a heavy
                        // body's 1/m keeps few bits in Q32.32 either way).
                        let g = |x: Scalar| x.to_num::<f64>();
                        let (ma_i, mb_i, ja, jb) = (g(a.m), g(b.m), g(a.j), g(b.j));
                        for &xa in &arms {
                            for &xb in &arms {
                                let (aa, ab) =
                                    ((xa * (1 << FR) as f64) as i64, (xb * (1 << FR) as f64) as i64);
                                let k = pair.k(aa, ab);
                                let r = recip60(k);
                                let [_, _, _, _, ga, gb] = row(&pair, r, [0, ONE30], (aa, ab));
                                let (xa, xb) = (q(aa, FR), q(ab, FR));
                                let k_ref = ma_i + mb_i + ja * xa * xa + jb * xb * xb;
                                let ratio_a = q((pair.m[0] * r) >> FU, FU);
                                assert!(
                                    (ratio_a - ma_i / k_ref).abs() < 2e-7,
                                    "ρ_A {ratio_a} vs {}",
                                    ma_i / k_ref
                                );
                                assert!(
                                    (q(ga, FU) - (ja * xa / k_ref).clamp(-1.5, 1.5)).abs() < 2e-7,
                                    "γ_A {} vs {} (m {ma} {mb} r {ra} {rb} arm {xa} {xb})",
                                    q(ga, FU),
                                    ja * xa / k_ref
                                );
                                assert!((q(gb, FU) - (jb * xb / k_ref).clamp(-1.5, 1.5)).abs() < 2e-7, "γ_B");
                                let m_eff = pair.mass(r).to_num::<f64>();
                                // Relative 1e-6, or the Scalar's own resolution.
                                let tol = 1e-6 / k_ref + 1.0 / (1u64 << 31) as f64;
                                assert!(
                                    (m_eff - 1.0 / k_ref).abs() < tol,
                                    "m_eff {m_eff} vs {}",
                                    1.0 / k_ref
                                );
                                // An impulse of 1 N·s in velocity units: k m/s.
                                let l = q(pair.impulse(Scalar::ONE, k, i64::MAX), FV_BITS);
                                assert!(
                                    (l - k_ref.min(32_768.0)).abs() <= 1e-4 * k_ref.max(1.0),
                                    "λ̂ {l} vs {k_ref}"
                                );
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert_eq!(checked, 6 * 5 * 16 * 49);
    }

    const FV_BITS: u32 = lanes::FV;

    /// The one-word and unsigned roundings give [`rnd_wide`]'s value wherever
    /// their callers use them: quotients that fit `i64`, and non-negative
    /// products below 2¹²⁷ (the friction factor's μ_bits·ratio is below 2¹⁰³).
    #[test]
    fn narrow_roundings_match_rnd_wide() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || crate::solver::xorshift(&mut seed);
        for _ in 0..20_000 {
            let (a, b) = (next(), next());
            let k = 1 + (a % 60) as u32;
            let bound = (b >> (b % 64)) as i64 & i64::MAX;
            // Non-negative, up to 2^127 − 1.
            let x = (u128::from(a) << 64 | u128::from(b)) >> (1 + a % 100);
            assert_eq!(rnd_unsigned(x, k, bound.unsigned_abs()), rnd_wide(x as i128, k, bound));
            // Signed, with the quotient within i64 (|x| < 2^(62 + k)).
            let y = ((u128::from(b) << 64 | u128::from(a)) as i128) >> (65 - k.min(60) + (b % 3) as u32);
            assert_eq!(rnd_fit(y, k, bound), rnd_wide(y, k, bound), "{y} {k} {bound}");
        }
    }

    /// The cold-branch clamps against `clamp`, at and around the edges of
    /// the bounds prepare uses and across the whole range.
    #[test]
    fn cold_branch_clamps_match_clamp() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || crate::solver::xorshift(&mut seed);
        for bound in [0i64, 1, 4095 << FS, ARM, 1 << 31, i64::from(i32::MAX), (1 << 62) - 1] {
            let edges = [0, 1, bound - 1, bound, bound + 1, i64::MAX - bound, i64::MAX, i64::MAX - 1];
            let randoms = (0..2_000).map(|_| next() as i64 >> (next() % 64));
            for x in edges.into_iter().flat_map(|e| [e, e.wrapping_neg(), !e]).chain(randoms) {
                assert_eq!(sym(x, bound), x.clamp(-bound, bound), "{x} {bound}");
                for w in
                    [i128::from(x), i128::from(x) << 64, (i128::from(x) << 64) | 0xffff, i128::from(x) << 20]
                {
                    let want = w.clamp(-i128::from(bound), i128::from(bound)) as i64;
                    assert_eq!(sym_wide(w, bound), want, "{w} {bound}");
                }
            }
        }
        assert_eq!(sym(i64::MIN, 5), -5);
        assert_eq!(sym_wide(i128::MIN, 5), -5);
        assert_eq!(sym_wide(i128::MAX, 5), 5);
    }

    /// `lane` is [`lanes::from_scalar`] with the cold-branch clamp.
    #[test]
    fn lane_matches_from_scalar() {
        let mut seed = 0x1234_5678_9abc_def1u64;
        let mut next = || crate::solver::xorshift(&mut seed);
        for _ in 0..20_000 {
            let x = Scalar::from_bits(next() as i64 >> (next() % 64));
            for (f, bound) in [(FR, ARM_MAX), (FU, 1), (FS, 4095), (lanes::FV, 2048)] {
                assert_eq!(lane(x, f, bound), i64::from(lanes::from_scalar(x, f, bound)));
            }
        }
        assert_eq!(lane(Scalar::from_bits(i64::MIN), FU, 1), -(1 << FU));
        assert_eq!(lane(Scalar::from_bits(i64::MAX), FU, 1), 1 << FU);
    }

    /// The anchor from the exact product against `lane` of the saturating
    /// one, across the range and at the saturation edges.
    #[test]
    fn arm_lane_matches_lane_of_the_product() {
        let mut seed = 0x0bad_5eed_1234_5678u64;
        let mut next = || crate::solver::xorshift(&mut seed);
        let edges = [0i64, 1, 2, 3, 4, 5, 7, 8, 1 << 32, (1 << 32) - 1, i64::MAX, i64::MIN, i64::MIN + 1];
        let randoms: [i64; 4_000] = core::array::from_fn(|_| next() as i64 >> (next() % 64));
        for &x in edges.iter().chain(randoms.iter()) {
            let y = next() as i64 >> (next() % 64);
            for (a, b) in [(x, y), (y, x), (x, x), (x, -y), (x, 1 << 31), (x, 3 << 29)] {
                let (a, b) = (Scalar::from_bits(a), Scalar::from_bits(b));
                assert_eq!(arm_lane(a, b), lane(a * b, FR, ARM_MAX), "{a:?} {b:?}");
            }
        }
    }

    /// The plain path of [`approach_of`] against the saturating one, at
    /// magnitudes across its bounds (where the plain path is taken, the two
    /// agree; beyond them, the saturating path is the one taken).
    #[test]
    fn approach_plain_path_matches_saturating() {
        let mut seed = 0x05ee_d0fa_11c0_ffee_u64;
        let mut next = || crate::solver::xorshift(&mut seed);
        let mut plain = 0;
        for _ in 0..50_000 {
            // Magnitudes from 2³⁹ to 2⁴⁶ in bits, around the bound 2⁴⁵; the
            // normal's from 2³³ to 2³⁵, around its bound 2³³, or a unit one.
            let mut val = |shift: u64| Scalar::from_bits(next() as i64 >> (shift + next() % 8));
            let (va, vb) = (Vector2::new(val(17), val(17)), Vector2::new(val(17), val(17)));
            let (ra, rb) = (Vector2::new(val(17), val(17)), Vector2::new(val(17), val(17)));
            let (wa, wb) = (val(17), val(17));
            let n = Vector2::new(val(28), val(28));
            let small = small_pair([(va, wa), (vb, wb)], n);
            let sides = [(va, wa, ra), (vb, wb, rb)];
            let want = approach_of(sides, n, false);
            assert_eq!(approach_of(sides, n, small), want, "{sides:?} {n:?}");
            plain += usize::from(small);
        }
        assert!(plain > 5_000, "{plain}");
    }

    /// The one-word impulse against its `i128` definition, for every shift a
    /// pair can take, λ across the range (both paths) and k̂ up to 2³⁴.
    #[test]
    fn impulse_in_one_word_matches_the_wide_definition() {
        let mut seed = 0x7a3f_0c11_5eed_b0b0u64;
        let mut next = || crate::solver::xorshift(&mut seed);
        for shift in -80i32..=80 {
            let down = (48 - shift).clamp(1, 126).unsigned_abs();
            let pair = Pair { m: [0; 2], j: [0; 2], shift, down, half: 1 << (down - 1), narrow: down < 64 };
            for _ in 0..400 {
                let lambda = next() as i64 >> (next() % 64);
                let k = (next() >> (30 + next() % 34)) as i64;
                let bound = [i64::from(lanes::LAMBDA_MAX), i64::MAX][(next() % 2) as usize];
                let wide = i128::from(lambda) * i128::from(k);
                let want = sym_wide((wide + pair.half) >> pair.down, bound);
                assert_eq!(pair.impulse(Scalar::from_bits(lambda), k, bound), want, "{lambda} {k} {shift}");
            }
        }
    }

    /// 1/k from r̂ in one word against its definition in i128 (r̂·2^(4 − shift),
    /// saturated at `i64::MAX`), for every shift a pair can take and r̂ from 0
    /// to 2⁶⁰: the bits of 1/k̂ scaled back to kg.
    #[test]
    fn mass_is_the_scaled_reciprocal_in_one_word() {
        let ends = [0i64, 1, 2, 3, (1 << 30) - 1, 1 << 30, (1 << 59) + 12_345, (1 << 60) - 1, 1 << 60];
        for shift in -40..=40 {
            let pair = Pair { m: [0; 2], j: [0; 2], shift, down: 1, half: 1, narrow: true };
            for r in ends.into_iter().chain((1..=60).map(|b| recip60(1 << b) + b)) {
                let e = 4 - shift;
                let wide = if e >= 0 { i128::from(r) << e } else { i128::from(r) >> -e };
                let want = wide.min(i128::from(i64::MAX)) as i64;
                assert_eq!(pair.mass(r).to_bits(), want, "r {r} shift {shift}");
            }
        }
    }

    /// The block inverse against the 2×2 inverse it stands for.
    #[test]
    fn block_inverse_is_the_normalised_inverse() {
        let (k11, k22, k12) = (3.0_f64, 2.0, 1.5);
        let scale = |x: f64| (x * (1u64 << 30) as f64) as i64;
        let k = [scale(k11), scale(k22)];
        let r = [recip60(k[0]), recip60(k[1])];
        let block = block_inverse(k, r, scale(k12), Scalar::from_num(0.8)).expect("well conditioned");
        let q = |x: i64| x as f64 / (1u64 << FM) as f64;
        // M̂ = D·K⁻¹: D = diag(k11, k22), K⁻¹ = 1/det·[[k22, −k12], [−k12, k11]].
        let det = k11 * k22 - k12 * k12;
        let rigid = [k11 * k22 / det, -k11 * k12 / det, -k22 * k12 / det, k22 * k11 / det];
        for (x, want) in block[2..6].iter().zip(rigid) {
            assert!((q(*x) - want).abs() < 1e-7, "{} vs {want}", q(*x));
        }
        assert!((block[0] as f64 / (1u64 << FR) as f64 - k12 / k22).abs() < 1e-8);
        // A pair whose diagonal differs by more than 4 is solved point by point.
        assert!(block_inverse([k[0], k[0] / 5], r, 0, Scalar::ONE).is_none());
        // A singular block (identical rows) is refused.
        assert!(block_inverse([k[0], k[0]], [r[0], r[0]], k[0], Scalar::ONE).is_none());
    }
}
