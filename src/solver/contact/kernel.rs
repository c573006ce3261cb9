//! The contact kernels: the impacts before the sub-steps, warm start, the
//! biased and relax sweeps (both points of a two-point manifold solved
//! together as a 2×2 block), and the restitution pass, on `W` lanes of a block
//! at a time.
//!
//! Each kernel is written once over [`L`] lane vectors and instantiated for
//! the eight lanes of a block (a colour's constraints share no dynamic body,
//! so eight of them can be solved at once) and for one lane (the overflow,
//! solved in key order). Every operation is lane-wise integer arithmetic with
//! the rounding of [`lanes::mul`], so every width and every instruction set
//! computes the same bits; the only reductions over lanes ([`M::any`]) decide
//! whether to run work whose results all lanes would discard.
//!
//! The algorithm is the soft step's: per point, the separation is re-evaluated
//! from how far the bodies moved and turned since the step began, linearised
//! in the turn (s = s₀ + n·Δ(dp) + δ̂_B·r̂_B − δ̂_A·r̂_A; the neglected term only
//! makes s smaller, so the estimate errs towards contact); a point still apart
//! is speculative (it may close its gap within the sub-step, no more), one in
//! contact is a soft spring-damper pushing out at no more than the push speed
//! (one deeper than [`DEEP_OVERLAP`] keeps the spring without its bias and is
//! pushed out by moving the bodies, [`push_apart`]), and every row is rigid
//! and unbiased in the relax sweeps.

use core::cell::Cell;

use crate::math::scalar::Scalar;
use crate::solver::body::{DPX, DPY, DR, MOVED, VX, VY, W as WR};
use crate::solver::colour::Kernel;
use crate::solver::lanes::{self, FPHI, FQ, FR, FS, FU, L, L64, LAMBDA_MAX, LANES, M, SPEC_BIAS_MAX, V_WALL};
use crate::solver::{Bias, BodyLanes, Softness};
use crate::step::StepContext;

use super::{f, field, field_mut, Block, A_DYNAMIC, B_DYNAMIC, HAS_BLOCK, STATIC_PAIR, TWO_POINTS};

/// One in Q2.30.
const ONE: i32 = 1 << FU;

/// A softness in lanes.
#[derive(Clone, Copy, Debug)]
struct LaneSoft {
    /// Bias rate (Q22.10), mass scale and impulse scale (Q2.30).
    beta: i32,
    sm: i32,
    si: i32,
    /// The deepest separation whose bias is not already the push speed
    /// (Q13.19): clamping s there keeps s·β in range and changes nothing.
    floor: i32,
}

/// The step's constants in lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneParams {
    /// 1/h (Q22.10).
    inv_h: i32,
    /// [`SPEC_BIAS_MAX`]·h (Q13.19): the largest gap whose bias is below the cap.
    spec_cap: i32,
    /// The push speed (Q16.16).
    push: i32,
    /// The restitution threshold (Q16.16).
    threshold: i32,
    /// Contact and static softness.
    soft: [LaneSoft; 2],
    /// [`DEEP_OVERLAP`] (Q13.19): a point deeper than this is pushed out by
    /// moving its bodies, not by a velocity (see [`sweep`]).
    deep: i32,
    /// The push speed times h (Q13.19): the most a point is pushed out by
    /// moving its bodies in one sub-step.
    shift: i32,
    /// [`DEEP_STATIC_SHIFT`] (Q13.19).
    shift_static: i32,
    /// [`DEEP_TARGET`] (Q13.19).
    target: i32,
}

/// The overlap beyond which a point is pushed out by moving its bodies (m).
///
/// The soft contact pushes overlap out by a velocity, at no more than the
/// push speed per pair, and the relax sweep takes that velocity back out only
/// as far as one Gauss-Seidel sweep converges. Where many bodies overlap
/// deeply at once (bodies created on top of each other, a heap crushed
/// together) every pair asks for the push speed relative to every other and
/// the bodies fly apart many times faster (issue 16's 100 circles created at
/// one point, without gravity: 60.6 m/s with a 3 m/s push speed). So in the
/// biased sweeps a point deeper than this keeps its soft velocity row without
/// the bias (it still stops the bodies closing), and the sweep then moves the
/// bodies apart instead (non-linear Gauss-Seidel on the separation, as Box2D
/// v2.4's position solver does for every contact) out to [`DEEP_TARGET`], by
/// at most the push speed times the sub-step, or [`DEEP_STATIC_SHIFT`]
/// against a static body. A move leaves no velocity behind: the same heap
/// now peaks at 5.5 m/s. The spring keeps the overlaps up to 10 cm, where
/// its bias stays below β·10 cm (0.9 m/s at the default 30 Hz and damping
/// ratio 10), so resting stacks and ordinary impacts are solved as before:
/// at 5 cm, fast impacts (a ball landing on a ball at 12 m/s) went deep,
/// and the moves out of them differed enough from the spring to bounce a
/// resting ball off the ground (`tests/post_step_queue.rs`) and to slow a
/// 25 %-overlapped column's recovery past 1 s (`tests/quality.rs`).
pub(crate) const DEEP_OVERLAP: Scalar = Scalar::lit("0.1");

/// The overlap a deep point is pushed out to by motion (m), Box2D's linear
/// slop: from there the spring takes it over. (Moved out only to
/// [`DEEP_OVERLAP`], a body resting on a deep point would stay there, its
/// weight pushing it back each sub-step and the bias off.)
pub(crate) const DEEP_TARGET: Scalar = Scalar::lit("0.005");

/// The most a deep point against a static body is moved out in one sub-step
/// (m), Box2D v2.4's largest position correction. A body squeezed between a
/// static body and dynamic ones is pushed into the static one by every
/// dynamic pair; moved out at the push speed like them, a circle at the
/// bottom of the 100-circle heap went through the floor.
pub(crate) const DEEP_STATIC_SHIFT: Scalar = Scalar::lit("0.2");

impl LaneParams {
    /// The lanes' form of the step's solver settings.
    pub(crate) fn new(ctx: &StepContext) -> Self {
        let push = ctx.push_speed;
        let soft = |s: &Softness| {
            let floor = if s.bias_rate > Scalar::ZERO {
                push.div_or_zero(s.bias_rate).min(Scalar::from_int(4095))
            } else {
                Scalar::from_int(4095)
            };
            LaneSoft {
                beta: lanes::from_scalar(s.bias_rate, FQ, 1 << 21),
                sm: lanes::from_scalar(s.mass_scale, FU, 1),
                si: lanes::from_scalar(s.impulse_scale, FU, 1),
                floor: lanes::from_scalar(floor, FS, 4095),
            }
        };
        Self {
            inv_h: lanes::from_scalar(ctx.inv_h, FQ, 1 << 21),
            spec_cap: lanes::from_scalar(ctx.h * Scalar::from_int(SPEC_BIAS_MAX as i32), FS, 4095),
            push: lanes::velocity(push),
            threshold: lanes::velocity(ctx.restitution_threshold),
            soft: [soft(&ctx.contact_softness), soft(&ctx.static_softness)],
            deep: lanes::from_scalar(DEEP_OVERLAP, FS, 4095),
            target: lanes::from_scalar(DEEP_TARGET, FS, 4095),
            shift: lanes::from_scalar(ctx.h * push, FS, 4095),
            shift_static: lanes::from_scalar(DEEP_STATIC_SHIFT, FS, 4095),
        }
    }
}

/// Runs `$body` for each point of a manifold with `$k` a constant (0, then 1),
/// so that every field number in it is known at compile time.
macro_rules! each_point {
    ($k:ident => $body:block) => {{
        {
            const $k: usize = 0;
            $body
        }
        {
            const $k: usize = 1;
            $body
        }
    }};
}

/// Lanes `base..base + W` of a block.
struct View<'b, const W: usize> {
    blk: &'b mut Block,
    base: usize,
}

impl<const W: usize> View<'_, W> {
    #[inline(always)]
    fn ld(&self, fi: usize) -> L<W> {
        let row = field(self.blk, fi);
        let mut r = [0; W];
        for (i, x) in r.iter_mut().enumerate() {
            *x = super::lane(row, self.base + i);
        }
        L(r)
    }

    /// Stores the lanes of `x` that `m` selects.
    ///
    /// A whole block (every lane active: all but a colour's first and last
    /// block) stores `x` as it is. Written only as the blend of the old and
    /// new lanes, the compiler turns the load, blend and store into one
    /// `vpmaskmovd`, which AMD processors run far slower than a plain
    /// store: on this Zen 4, the same bits in 3–5 % less time (probe,
    /// fastest of 15 alternating runs: the 20-row pyramid 0.296 → 0.282 ms
    /// a step, the rollback scene 0.409 → 0.399, rain 0.333 → 0.321, the
    /// 100-row pyramid 7.71 → 7.35).
    #[inline(always)]
    fn st(&mut self, fi: usize, x: L<W>, m: M<W>) {
        let x = if m.every() { x } else { self.ld(fi).select(m, x) };
        let row = field_mut(self.blk, fi);
        for (i, &x) in x.0.iter().enumerate() {
            row[(self.base + i) % LANES] = x;
        }
    }

    /// Point `p`'s field `x`.
    #[inline(always)]
    fn pt(&self, p: usize, x: usize) -> L<W> {
        self.ld(f::P[p % 2] + x)
    }
}

/// A body's velocity lanes: v_x, v_y, ŵ.
pub(crate) type Vel<const W: usize> = [L<W>; 3];
/// A body's motion since the step began: dp_x, dp_y, δ̂.
pub(crate) type Pose<const W: usize> = [L<W>; 3];

/// Reads the velocity and motion of the bodies in `idx`'s lanes.
#[inline(always)]
pub(crate) fn gather<const W: usize>(bodies: &[BodyLanes], idx: L<W>) -> (Vel<W>, Pose<W>) {
    // Eight lanes (the AVX2 kernels only, see `L`): whole records and a
    // transpose, where the loop below loads field by field into vector
    // inserts (measured with the products: large 20 2,400.5 M → 2,325.6 M
    // instructions, mixed 901.2 M → 865.3 M).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if W == LANES {
        const { assert!(VX == 0 && VY == 1 && WR == 2 && DR == 3 && DPX == 4 && DPY == 5) };
        let [vx, vy, w, dr, dpx, dpy] = crate::solver::dispatch::avx2::gather(bodies, idx.to8());
        let l = L::from8;
        return ([l(vx), l(vy), l(w)], [l(dpx), l(dpy), l(dr)]);
    }
    // Each lane's record in place (no copy), or an empty one out of range.
    let mut rows = [&BodyLanes::EMPTY.0; W];
    for (r, &b) in rows.iter_mut().zip(idx.0.iter()) {
        if let Some(b) = bodies.get(b as u32 as usize) {
            *r = &b.0;
        }
    }
    let mut v = [[0; W]; 6];
    for (k, f) in [VX, VY, WR, DPX, DPY, DR].into_iter().enumerate() {
        for (i, r) in rows.iter().enumerate() {
            v[k][i] = r[f];
        }
    }
    let [vx, vy, w, dpx, dpy, dr] = v;
    ([L(vx), L(vy), L(w)], [L(dpx), L(dpy), L(dr)])
}

/// Writes back the velocity of the bodies in `idx`'s lanes that `m` selects.
#[inline(always)]
pub(crate) fn scatter<const W: usize>(bodies: &mut [BodyLanes], idx: L<W>, v: &Vel<W>, m: M<W>) {
    // Without this barrier LLVM sinks the last velocity updates into the
    // per-lane stores below and computes them lane by lane in general-purpose
    // registers (measured: a third of the AVX2 sweep's multiplies). Only the
    // code changes, never a value.
    let v = core::hint::black_box(*v);
    // Eight lanes (the AVX2 kernels only, see `L`): x and y interleaved
    // into pairs and the mask folded into the indices, where the loop below
    // extracts each value and tests two masks a lane (large 20 2,203.6 M →
    // 2,149.9 M instructions, mixed 828.7 M → 811.1 M; the 20-row pyramid's
    // fastest of 12 alternating runs 0.333 → 0.324 ms a step).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if W == LANES {
        const { assert!(VX == 0 && VY == 1 && WR == 2) };
        let m8 = L(m.0).to8();
        crate::solver::dispatch::avx2::scatter(bodies, idx.to8(), m8, [v[0].to8(), v[1].to8(), v[2].to8()]);
        return;
    }
    for i in 0..W {
        if m.is(i) {
            if let Some(b) = bodies.get_mut(idx.0[i] as u32 as usize) {
                b.0[VX] = v[0].0[i];
                b.0[VY] = v[1].0[i];
                b.0[WR] = v[2].0[i];
            }
        }
    }
}

/// One row's factors: ρ_A·d, γ̂_A, ρ_B·d, γ̂_B.
#[derive(Clone, Copy)]
struct Ratios<const W: usize> {
    ax: L<W>,
    ay: L<W>,
    ga: L<W>,
    bx: L<W>,
    by: L<W>,
    gb: L<W>,
}

impl<const W: usize> Ratios<W> {
    /// Point `p`'s normal row.
    #[inline(always)]
    fn normal(v: &View<'_, W>, p: usize) -> Self {
        Self {
            ax: v.pt(p, f::ANX),
            ay: v.pt(p, f::ANY),
            ga: v.pt(p, f::GAN),
            bx: v.pt(p, f::BNX),
            by: v.pt(p, f::BNY),
            gb: v.pt(p, f::GBN),
        }
    }

    /// Point `p`'s tangent row.
    #[inline(always)]
    fn tangent(v: &View<'_, W>, p: usize) -> Self {
        Self {
            ax: v.pt(p, f::ATX),
            ay: v.pt(p, f::ATY),
            ga: v.pt(p, f::GAT),
            bx: v.pt(p, f::BTX),
            by: v.pt(p, f::BTY),
            gb: v.pt(p, f::GBT),
        }
    }

    /// Applies a change `d` of the row's impulse (velocity units), walled.
    #[inline(always)]
    fn apply(&self, a: &mut Vel<W>, b: &mut Vel<W>, d: L<W>) {
        a[0] = a[0].sub(self.ax.mul::<FU>(d)).clamp_abs(V_WALL);
        a[1] = a[1].sub(self.ay.mul::<FU>(d)).clamp_abs(V_WALL);
        a[2] = a[2].sub(self.ga.mul::<FU>(d)).clamp_abs(V_WALL);
        b[0] = b[0].add(self.bx.mul::<FU>(d)).clamp_abs(V_WALL);
        b[1] = b[1].add(self.by.mul::<FU>(d)).clamp_abs(V_WALL);
        b[2] = b[2].add(self.gb.mul::<FU>(d)).clamp_abs(V_WALL);
    }
}

/// Applies two normal changes at once (the block): one wall clamp after the
/// sum, which is bounded by V_WALL + 2·γ̂·Λ, inside the format.
#[inline(always)]
fn apply_both<const W: usize>(r: &[Ratios<W>; 2], a: &mut Vel<W>, b: &mut Vel<W>, d: [L<W>; 2]) {
    let [r0, r1] = r;
    let [d0, d1] = d;
    a[0] = a[0].sub(r0.ax.mul::<FU>(d0)).sub(r1.ax.mul::<FU>(d1)).clamp_abs(V_WALL);
    a[1] = a[1].sub(r0.ay.mul::<FU>(d0)).sub(r1.ay.mul::<FU>(d1)).clamp_abs(V_WALL);
    a[2] = a[2].sub(r0.ga.mul::<FU>(d0)).sub(r1.ga.mul::<FU>(d1)).clamp_abs(V_WALL);
    b[0] = b[0].add(r0.bx.mul::<FU>(d0)).add(r1.bx.mul::<FU>(d1)).clamp_abs(V_WALL);
    b[1] = b[1].add(r0.by.mul::<FU>(d0)).add(r1.by.mul::<FU>(d1)).clamp_abs(V_WALL);
    b[2] = b[2].add(r0.gb.mul::<FU>(d0)).add(r1.gb.mul::<FU>(d1)).clamp_abs(V_WALL);
}

/// Relative speed of a point along (dx, dy) with arms `ra`, `rb` in body
/// radii: d·(v_B − v_A) + ŵ_B·r̂_B − ŵ_A·r̂_A.
#[inline(always)]
fn speed<const W: usize>(a: &Vel<W>, b: &Vel<W>, d: (L<W>, L<W>), ra: L<W>, rb: L<W>) -> L<W> {
    d.0.mul::<FU>(b[0].sub(a[0]))
        .add(d.1.mul::<FU>(b[1].sub(a[1])))
        .add(b[2].mul::<FR>(rb))
        .sub(a[2].mul::<FR>(ra))
}

/// Applies every point's accumulated impulses again (the warm start). With
/// `count_totals` (every sub-step after the first) it also adds the normal
/// impulses to the step's totals: they are what the sub-step before ended with.
#[inline(always)]
pub(crate) fn warm_start<const W: usize, const TWO: bool>(
    blk: &mut Block,
    base: usize,
    active: M<W>,
    bodies: &mut [BodyLanes],
    count_totals: bool,
) {
    let mut v = View::<W> { blk, base };
    let (ia, ib, flags) = (v.ld(f::IA), v.ld(f::IB), v.ld(f::FLAGS));
    let (mut a, _) = gather(bodies, ia);
    let (mut b, _) = gather(bodies, ib);
    each_point!(P => {
        if P == 0 || TWO {
            let (ln, lt) = (v.pt(P, f::LN), v.pt(P, f::LT));
            Ratios::normal(&v, P).apply(&mut a, &mut b, ln);
            Ratios::tangent(&v, P).apply(&mut a, &mut b, lt);
            if count_totals {
                // Q16.16 → Q18.14, rounded half up.
                let carried = ln.add(L::splat(2)).shr2();
                let tot = v.pt(P, f::TOT).add(carried);
                v.st(f::P[P] + f::TOT, tot, active);
            }
        }
    });
    scatter(bodies, ia, &a, flags.has(A_DYNAMIC).and(active));
    scatter(bodies, ib, &b, flags.has(B_DYNAMIC).and(active));
}

/// The per-point state a sweep updates.
#[derive(Clone, Copy)]
struct State<const W: usize> {
    a: Vel<W>,
    b: Vel<W>,
    ln: [L<W>; 2],
    vrel: [L<W>; 2],
    maxd: [L<W>; 2],
}

impl<const W: usize> State<W> {
    /// The lanes of `o` where `m`, else of `self`.
    #[inline(always)]
    fn select(mut self, m: M<W>, o: &Self) -> Self {
        for k in 0..3 {
            self.a[k] = self.a[k].select(m, o.a[k]);
            self.b[k] = self.b[k].select(m, o.b[k]);
        }
        for k in 0..2 {
            self.ln[k] = self.ln[k].select(m, o.ln[k]);
            self.vrel[k] = self.vrel[k].select(m, o.vrel[k]);
            self.maxd[k] = self.maxd[k].select(m, o.maxd[k]);
        }
        self
    }

    /// Sets point `p`'s normal impulse to `new` (for the approach speed `vn`)
    /// and returns the change: notes the fastest approach of a pushing point
    /// as its restitution reference, and the largest change of the step.
    #[inline(always)]
    fn set_normal(&mut self, p: usize, new: L<W>, vn: L<W>) -> L<W> {
        let p = p % 2;
        let d = new.sub(self.ln[p]);
        let pushing = new.gt(L::splat(0));
        self.vrel[p] = self.vrel[p].select(pushing, self.vrel[p].min(vn));
        self.maxd[p] = self.maxd[p].max(d);
        self.ln[p] = new;
        d
    }
}

/// One row's bias and scales for this sweep.
#[derive(Clone, Copy)]
struct Row<const W: usize> {
    bias: L<W>,
    sm: L<W>,
    si: L<W>,
    speculative: M<W>,
    /// Deeper than [`DEEP_OVERLAP`] (biased sweeps only): pushed out by
    /// moving the bodies beyond what the spring's bias does.
    deep: M<W>,
}

/// Point `p`'s separation (Q13.19) linearised in the bodies' motion since the
/// step began; `dpn` is n·Δ(dp), shared by both points.
#[inline(always)]
fn separation<const W: usize>(v: &View<'_, W>, p: usize, dpn: L<W>, pa: &Pose<W>, pb: &Pose<W>) -> L<W> {
    v.pt(p, f::BASE).add(dpn).add(pb[2].mul::<30>(v.pt(p, f::RBN))).sub(pa[2].mul::<30>(v.pt(p, f::RAN)))
}

/// n·Δ(dp) (Q13.19): Q2.30 × Q12.20 → Q13.19.
#[inline(always)]
fn normal_shift<const W: usize>(n: (L<W>, L<W>), pa: &Pose<W>, pb: &Pose<W>) -> L<W> {
    n.0.mul::<31>(pb[0].sub(pa[0])).add(n.1.mul::<31>(pb[1].sub(pa[1])))
}

/// The softness of each lane's pair, for a biased sweep.
#[derive(Clone, Copy)]
struct Soft<const W: usize> {
    beta: L<W>,
    sm: L<W>,
    si: L<W>,
    floor: L<W>,
}

/// Point `p`'s row: speculative while apart, else soft (biased sweep) or
/// rigid (relax), from the separation linearised in the motion since the
/// step began.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn row<const W: usize>(
    v: &View<'_, W>,
    p: usize,
    dpn: L<W>,
    pa: &Pose<W>,
    pb: &Pose<W>,
    soft: &Soft<W>,
    params: &LaneParams,
    bias: Bias,
) -> Row<W> {
    let zero = L::splat(0);
    let s = separation(v, p, dpn, pa, pb);
    let speculative = s.gt(zero);
    // Q13.19 × Q22.10 → Q16.16.
    let spec_bias = s.min(L::splat(params.spec_cap)).mul::<13>(L::splat(params.inv_h));
    let (soft_bias, sm, si, deep) = match bias {
        Bias::On => {
            // Beyond `DEEP_OVERLAP` the push-out is by motion (`push_apart`).
            let deep = s.lt(L::splat(params.deep).neg());
            let b = s.max(soft.floor.neg()).mul::<13>(soft.beta).max(L::splat(-params.push));
            (zero.select(deep.not(), b), soft.sm, soft.si, deep)
        }
        Bias::Off => (zero, L::splat(ONE), zero, M::none()),
    };
    Row {
        bias: soft_bias.select(speculative, spec_bias),
        sm: sm.select(speculative, L::splat(ONE)),
        si: si.select(speculative, zero),
        speculative,
        deep,
    }
}

/// The 2×2 block on lanes `want`: the exact solution of the two points'
/// complementarity problem in normalised impulses (both push, only the
/// first, only the second, neither), with the right-hand side in Q17.15 and
/// the products in 64-bit lanes. Returns the new impulses (clamped to
/// [0, Λ]) and the lanes where one of the cases fits.
#[inline(always)]
fn block<const W: usize>(
    v: &View<'_, W>,
    want: M<W>,
    soft_block: M<W>,
    vn: [L<W>; 2],
    rows: &[Row<W>; 2],
    ln: [L<W>; 2],
) -> ([L<W>; 2], M<W>) {
    let (c12, c21) = (v.ld(f::C12), v.ld(f::C21));
    let m = [
        v.ld(f::MR).select(soft_block, v.ld(f::MS)),
        v.ld(f::MR + 1).select(soft_block, v.ld(f::MS + 1)),
        v.ld(f::MR + 2).select(soft_block, v.ld(f::MS + 2)),
        v.ld(f::MR + 3).select(soft_block, v.ld(f::MS + 3)),
    ];
    // q_i = vn_i + bias_i − λ̂_i − c_ij·λ̂_j, up to 42,657 m/s: Q16.16 in 64
    // bits, and Q17.15 for the products.
    let q1 = L64::from(vn[0])
        .add(L64::from(rows[0].bias))
        .sub(L64::from(ln[0]))
        .sub(L64::from(c12.mul::<FR>(ln[1])));
    let q2 = L64::from(vn[1])
        .add(L64::from(rows[1].bias))
        .sub(L64::from(ln[1]))
        .sub(L64::from(c21.mul::<FR>(ln[0])));
    let (h1, h2) = (q1.narrow_shr1(), q2.narrow_shr1());
    // Q5.27 × Q17.15 → Q16.16: shift 26.
    let x1 = L64::mul_shift::<26>(m[0], h1).add(L64::mul_shift::<26>(m[1], h2)).neg();
    let x2 = L64::mul_shift::<26>(m[2], h1).add(L64::mul_shift::<26>(m[3], h2)).neg();
    // Q2.30 × Q17.15 → Q16.16: shift 29.
    let y1 = L64::mul_shift::<29>(rows[0].sm, h1).neg();
    let y2 = L64::mul_shift::<29>(rows[1].sm, h2).neg();
    let (y1c, y2c) = (y1.clamp_narrow(LAMBDA_MAX), y2.clamp_narrow(LAMBDA_MAX));
    let both = x1.nonneg().and(x2.nonneg());
    let first = both.not().and(y1.nonneg()).and(q2.add(L64::mul_shift::<FR>(c21, y1c)).nonneg());
    let second = both.or(first).not().and(y2.nonneg()).and(q1.add(L64::mul_shift::<FR>(c12, y2c)).nonneg());
    let neither = both.or(first).or(second).not().and(q1.nonneg()).and(q2.nonneg());
    let zero = L::splat(0);
    let r1 = zero.select(first, y1c).select(both, x1.clamp_narrow(LAMBDA_MAX));
    let r2 = zero.select(second, y2c).select(both, x2.clamp_narrow(LAMBDA_MAX));
    let ok = both.or(first).or(second).or(neither).and(want);
    ([r1, r2], ok)
}

/// One sweep over lanes `base..base + W` of a block (`active` ones only):
/// normal points (as a block where the pair allows, else one at a time in the
/// sweep's direction), then friction. Returns the lanes with a point deeper
/// than [`DEEP_OVERLAP`] (biased sweeps; none in the relax sweeps), for
/// [`push_apart`].
#[inline(always)]
pub(crate) fn sweep<const W: usize, const TWO: bool>(
    blk: &mut Block,
    base: usize,
    active: M<W>,
    bodies: &mut [BodyLanes],
    params: &LaneParams,
    bias: Bias,
    reverse: bool,
) -> M<W> {
    let mut v = View::<W> { blk, base };
    let (ia, ib, flags) = (v.ld(f::IA), v.ld(f::IB), v.ld(f::FLAGS));
    let (a, pa) = gather(bodies, ia);
    let (b, pb) = gather(bodies, ib);
    // A barrier on the gathered velocities, as in `scatter`: without it
    // LLVM merges the per-lane body reads into the sign extensions of the
    // products that use them and keeps scalar copies of every lane,
    // rebuilding the vectors from the stack later (measured: 2.7 % of the
    // 100-row pyramid's instructions, 1.7 % of the mixed scene's). Only the
    // code changes, never a value. One lane has nothing to rebuild; the
    // same barrier on the motion lanes too, or in the warm start, measured
    // slower.
    let (a, b) = if W > 1 { core::hint::black_box((a, b)) } else { (a, b) };
    let n = (v.ld(f::NX), v.ld(f::NY));
    let t = (n.1, n.0.neg());
    let two = flags.has(TWO_POINTS);
    let static_pair = flags.has(STATIC_PAIR);
    let [c, st] = params.soft;
    let soft = Soft {
        beta: L::splat(c.beta).select(static_pair, L::splat(st.beta)),
        sm: L::splat(c.sm).select(static_pair, L::splat(st.sm)),
        si: L::splat(c.si).select(static_pair, L::splat(st.si)),
        floor: L::splat(c.floor).select(static_pair, L::splat(st.floor)),
    };
    let dpn = normal_shift(n, &pa, &pb);
    let zero = L::splat(0);
    let row1 = if TWO {
        row(&v, 1, dpn, &pa, &pb, &soft, params, bias)
    } else {
        Row { bias: zero, sm: zero, si: zero, speculative: M::none(), deep: M::none() }
    };
    let mut rows = [row(&v, 0, dpn, &pa, &pb, &soft, params, bias), row1];
    // A one-point manifold's second point (all zero) is never deep.
    rows[1].deep = rows[1].deep.and(two);
    let deep = rows[0].deep.or(rows[1].deep).and(active);
    let arms = [(v.pt(0, f::RAN), v.pt(0, f::RBN)), (v.pt(1, f::RAN), v.pt(1, f::RBN))];
    let normal = [Ratios::normal(&v, 0), Ratios::normal(&v, 1)];
    let pre = State {
        a,
        b,
        ln: [v.pt(0, f::LN), v.pt(1, f::LN)],
        vrel: [v.pt(0, f::VREL), v.pt(1, f::VREL)],
        maxd: [v.pt(0, f::MAXD), v.pt(1, f::MAXD)],
    };
    // The block: both points rigid or both soft (a soft point beside a
    // speculative one has no precomputed inverse and goes one at a time).
    let both_spec = rows[0].speculative.and(rows[1].speculative);
    let neither_spec = rows[0].speculative.or(rows[1].speculative).not();
    let (soft_block, mut want) = match bias {
        Bias::On => (neither_spec, flags.has(HAS_BLOCK).and(both_spec.or(neither_spec))),
        Bias::Off => (M::none(), flags.has(HAS_BLOCK)),
    };
    want = want.and(active);
    let mut st = pre;
    let mut solved = M::none();
    if TWO && want.any() {
        let vn =
            [speed(&pre.a, &pre.b, n, arms[0].0, arms[0].1), speed(&pre.a, &pre.b, n, arms[1].0, arms[1].1)];
        let (x, ok) = block(&v, want, soft_block, vn, &rows, pre.ln);
        solved = ok;
        let new = [pre.ln[0].select(ok, x[0]), pre.ln[1].select(ok, x[1])];
        let d = [st.set_normal(0, new[0], vn[0]), st.set_normal(1, new[1], vn[1])];
        apply_both(&normal, &mut st.a, &mut st.b, d);
        st = pre.select(solved, &st);
    }
    let rest = solved.not().and(active);
    if rest.any() {
        // One point at a time, in the sweep's direction, so that neither point
        // is always first.
        let mut sq = pre;
        macro_rules! point {
            ($k:expr) => {{
                const K: usize = $k;
                let live = if K == 1 { two } else { M::all() };
                let vn = speed(&sq.a, &sq.b, n, arms[K].0, arms[K].1);
                let r = &rows[K];
                let raw = r.sm.mul::<FU>(vn.add(r.bias)).add(r.si.mul::<FU>(sq.ln[K])).neg();
                let new = sq.ln[K].add(raw.clamp_abs(LAMBDA_MAX)).clamp(zero, L::splat(LAMBDA_MAX));
                let new = sq.ln[K].select(live, new);
                let d = sq.set_normal(K, new, vn);
                normal[K].apply(&mut sq.a, &mut sq.b, d);
            }};
        }
        if reverse {
            if TWO {
                point!(1);
            }
            point!(0);
        } else {
            point!(0);
            if TWO {
                point!(1);
            }
        }
        st = st.select(rest, &sq);
    }
    // Friction, point by point, bounded by φ·λ̂_n.
    let mut lt = [v.pt(0, f::LT), v.pt(1, f::LT)];
    each_point!(K => {
        if K == 0 || TWO {
            let vt = speed(&st.a, &st.b, t, v.pt(K, f::RAT), v.pt(K, f::RBT));
            let cap = v.pt(K, f::PHI).mul::<FPHI>(st.ln[K].min(v.pt(K, f::CPHI)));
            let new = lt[K].sub(vt).clamp(cap.neg(), cap);
            let d = new.sub(lt[K]);
            lt[K] = new;
            Ratios::tangent(&v, K).apply(&mut st.a, &mut st.b, d);
        }
    });
    each_point!(K => {
        if K == 0 || TWO {
            let p = f::P[K];
            v.st(p + f::LN, st.ln[K], active);
            v.st(p + f::LT, lt[K], active);
            v.st(p + f::VREL, st.vrel[K], active);
            v.st(p + f::MAXD, st.maxd[K], active);
        }
    });
    scatter(bodies, ia, &st.a, flags.has(A_DYNAMIC).and(active));
    scatter(bodies, ib, &st.b, flags.has(B_DYNAMIC).and(active));
    deep
}

/// One biased or relax sweep over lanes `base..base + W` of a block
/// ([`sweep`]), then the deep points' push-out ([`push_apart`]) where a lane
/// has one. The push-out is called here, after the sweep has returned, not
/// from inside it: a call inside kept the sweep's values alive across it
/// (large scene, no deep point: 2,467.9 M instructions with the call inside
/// the sweep, 2,418.1 M here; 2,431.5 M before the push-out existed).
#[inline(always)]
pub(crate) fn sweep_and_push<const W: usize, const TWO: bool>(
    blk: &mut Block,
    base: usize,
    active: M<W>,
    bodies: &mut [BodyLanes],
    params: &LaneParams,
    bias: Bias,
    reverse: bool,
) {
    let deep = sweep::<W, TWO>(blk, base, active, bodies, params, bias, reverse);
    if deep.any() {
        push_apart_out_of_line::<W, TWO>(blk, base, bodies, deep, params, reverse);
    }
}

/// [`push_apart`] out of line (see [`sweep_and_push`]). Eight lanes (the
/// AVX2 kernels only, see `L`) go to an instance compiled with AVX2: out of
/// line with the caller's features, the eight-lane instance was built for
/// SSE2 and called each lane product's AVX2 intrinsic as a function (rain,
/// 200 steps, where bodies land deep in each other: 974.8 → 923.1 M
/// instructions, the same bits; the scenes without deep points within
/// ±0.2 %).
#[inline(never)]
fn push_apart_out_of_line<const W: usize, const TWO: bool>(
    blk: &mut Block,
    base: usize,
    bodies: &mut [BodyLanes],
    deep: M<W>,
    params: &LaneParams,
    reverse: bool,
) {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    if W == LANES {
        let deep = M(L(deep.0).to8());
        crate::solver::dispatch::avx2::push_apart::<TWO>(blk, base, bodies, deep, params, reverse);
        return;
    }
    push_apart::<W, TWO>(blk, base, bodies, deep, params, reverse);
}

/// The deep points' push-out by motion (biased sweeps, lanes `deep` only):
/// each point in the sweep's direction, its separation re-evaluated from the
/// motion so far, is moved out to [`DEEP_TARGET`] by at most the push speed
/// times h ([`DEEP_STATIC_SHIFT`] against a static body), the bodies sharing
/// the move by the row's mass ratios (a move x of
/// the normalised row changes the separation by x). The motion lanes are
/// marked so that the integration carries the move into the pose
/// ([`SolverBody::integrate`](crate::solver::SolverBody)); velocities are
/// untouched.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn push_apart<const W: usize, const TWO: bool>(
    blk: &mut Block,
    base: usize,
    bodies: &mut [BodyLanes],
    deep: M<W>,
    params: &LaneParams,
    reverse: bool,
) {
    let v = &View::<W> { blk, base };
    let (ia, ib, flags) = (v.ld(f::IA), v.ld(f::IB), v.ld(f::FLAGS));
    let n = (v.ld(f::NX), v.ld(f::NY));
    // The motion as gathered at the sweep's start (the sweep changed only
    // velocities).
    let (_, mut pa) = gather(bodies, ia);
    let (_, mut pb) = gather(bodies, ib);
    let cap = L::splat(params.shift).select(flags.has(STATIC_PAIR), L::splat(params.shift_static));
    let two = if TWO { flags.has(TWO_POINTS) } else { M::none() };
    let order = if reverse { [(1, two), (0, M::all())] } else { [(0, M::all()), (1, two)] };
    for (k, live) in order {
        push_point(v, k, live.and(deep), n, (&mut pa, &mut pb), cap, params);
    }
    scatter_pose(bodies, ia, &pa, flags.has(A_DYNAMIC).and(deep));
    scatter_pose(bodies, ib, &pb, flags.has(B_DYNAMIC).and(deep));
}

/// Point `k`'s push-out in [`push_apart`] on lanes `m`, moving the motion
/// lanes `pa`, `pb`. A function, not a closure: a closure is compiled apart
/// from the AVX2 function the kernels are inlined into, without AVX2, and
/// called there (with its lane products as calls of their own).
#[inline(always)]
fn push_point<const W: usize>(
    v: &View<'_, W>,
    k: usize,
    m: M<W>,
    n: (L<W>, L<W>),
    (pa, pb): (&mut Pose<W>, &mut Pose<W>),
    cap: L<W>,
    params: &LaneParams,
) {
    let zero = L::splat(0);
    let edge = L::splat(POSE_EDGE);
    let s = separation(v, k, normal_shift(n, pa, pb), pa, pb);
    // −(s + T), clamped to [0, cap]: out to T, from where the spring takes
    // the point over (moved out only to D, a resting body would sit at D,
    // its weight pushing it back each sub-step).
    let x = s.add(L::splat(params.target)).neg().clamp(zero, cap);
    let x = zero.select(m, x);
    let r = Ratios::normal(v, k);
    // Q2.30 × Q13.19 → Q12.20.
    pa[0] = pa[0].sub(r.ax.mul::<29>(x)).clamp(edge.neg(), edge);
    pa[1] = pa[1].sub(r.ay.mul::<29>(x)).clamp(edge.neg(), edge);
    pa[2] = pa[2].sub(r.ga.mul::<29>(x)).clamp(edge.neg(), edge);
    pb[0] = pb[0].add(r.bx.mul::<29>(x)).clamp(edge.neg(), edge);
    pb[1] = pb[1].add(r.by.mul::<29>(x)).clamp(edge.neg(), edge);
    pb[2] = pb[2].add(r.gb.mul::<29>(x)).clamp(edge.neg(), edge);
}

/// The bound of the motion lanes (Q12.20): 2,047 m, as they are loaded.
const POSE_EDGE: i32 = 2047 << 20;

/// Writes back the motion of the bodies in `idx`'s lanes that `m` selects and
/// marks it moved.
#[inline(always)]
fn scatter_pose<const W: usize>(bodies: &mut [BodyLanes], idx: L<W>, p: &Pose<W>, m: M<W>) {
    for i in 0..W {
        if m.is(i) {
            if let Some(b) = bodies.get_mut(idx.0[i] as u32 as usize) {
                b.0[DPX] = p[0].0[i];
                b.0[DPY] = p[1].0[i];
                b.0[DR] = p[2].0[i];
                b.0[MOVED] = 1;
            }
        }
    }
}

/// The bounce: passes of the rigid normal rows towards vn = −e·v_rel for the
/// points that approached faster than the threshold and pushed. Iterated
/// because one Gauss-Seidel pass over a two-point manifold leaves the first
/// point bouncing faster than the second (which spins a box that hit a wall
/// square-on); each further pass shrinks that error by the coupling squared.
#[inline(always)]
pub(crate) fn restitute<const W: usize>(
    blk: &mut Block,
    base: usize,
    active: M<W>,
    bodies: &mut [BodyLanes],
    params: &LaneParams,
) {
    const RESTITUTION_ITERATIONS: u32 = 4;
    let mut v = View::<W> { blk, base };
    let flags = v.ld(f::FLAGS);
    let e = v.ld(f::E);
    let zero = L::splat(0);
    let live = [M::all(), flags.has(TWO_POINTS)];
    let mut bounce = [M::none(); 2];
    each_point!(K => {
        let fast = v.pt(K, f::VREL).lt(L::splat(-params.threshold).add(L::splat(1)));
        let pushed = v.pt(K, f::MAXD).nonzero();
        bounce[K] = fast.and(pushed).and(e.gt(zero)).and(live[K]).and(active);
    });
    if !bounce[0].or(bounce[1]).any() {
        return;
    }
    let (ia, ib) = (v.ld(f::IA), v.ld(f::IB));
    let (mut a, _) = gather(bodies, ia);
    let (mut b, _) = gather(bodies, ib);
    let n = (v.ld(f::NX), v.ld(f::NY));
    let mut ln = [v.pt(0, f::LN), v.pt(1, f::LN)];
    let mut maxd = [v.pt(0, f::MAXD), v.pt(1, f::MAXD)];
    for _ in 0..RESTITUTION_ITERATIONS {
        each_point!(K => {
            let vn = speed(&a, &b, n, v.pt(K, f::RAN), v.pt(K, f::RBN));
            let target = vn.add(e.mul::<FU>(v.pt(K, f::VREL)));
            let new = ln[K].add(target.neg().clamp_abs(LAMBDA_MAX)).clamp(zero, L::splat(LAMBDA_MAX));
            let new = ln[K].select(bounce[K], new);
            let d = new.sub(ln[K]);
            ln[K] = new;
            maxd[K] = maxd[K].select(bounce[K], maxd[K].max(d));
            Ratios::normal(&v, K).apply(&mut a, &mut b, d);
        });
    }
    each_point!(K => {
        v.st(f::P[K] + f::LN, ln[K], active);
        v.st(f::P[K] + f::MAXD, maxd[K], active);
    });
    scatter(bodies, ia, &a, flags.has(A_DYNAMIC).and(active));
    scatter(bodies, ib, &b, flags.has(B_DYNAMIC).and(active));
}

/// The impacts of a step, before its sub-steps: every elastic point (e > 0)
/// in contact (s ≤ 0) approaching faster than the restitution threshold is
/// resolved as a collision of its own, its normal speed turned
/// from vn into −e·vn by an impulse on its two bodies alone. Returns whether
/// any lane had one.
///
/// Run in sweeps until one finds no impact, this propagates a blow along a
/// chain of touching bodies as a sequence of collisions: a ball striking a
/// resting row stops, the next takes its speed and strikes the one after,
/// and the far end leaves with it (a Newton's cradle). The sub-steps' soft
/// contacts solve all the points of a chain at once, as one body, and share
/// the blow among them; the restitution pass after them cannot undo that,
/// since a velocity target per point cannot tell the row's first contact
/// (which should end at rest) from its last (which should separate at the
/// striker's speed).
///
/// A point resolved here ends the pass separating, so the sub-steps do not
/// push it; its restitution reference is cleared so that the restitution
/// pass does not bounce it twice, unless the sub-steps push it again. Its
/// impulse is not carried into the warm start (the collision is over); it
/// counts in the step's total and largest impulse. Two points are iterated
/// as in [`restitute`], each towards its own −e·vn.
#[inline(always)]
pub(crate) fn impact<const W: usize>(
    blk: &mut Block,
    base: usize,
    active: M<W>,
    bodies: &mut [BodyLanes],
    params: &LaneParams,
) -> bool {
    const IMPACT_ITERATIONS: u32 = 4;
    let mut v = View::<W> { blk, base };
    let e = v.ld(f::E);
    let zero = L::splat(0);
    let elastic = e.gt(zero).and(active);
    if !elastic.any() {
        return false;
    }
    let (ia, ib, flags) = (v.ld(f::IA), v.ld(f::IB), v.ld(f::FLAGS));
    let (mut a, _) = gather(bodies, ia);
    let (mut b, _) = gather(bodies, ib);
    let n = (v.ld(f::NX), v.ld(f::NY));
    let live = [M::all(), flags.has(TWO_POINTS)];
    let mut hit = [M::none(); 2];
    let mut target = [zero; 2];
    each_point!(K => {
        let vn = speed(&a, &b, n, v.pt(K, f::RAN), v.pt(K, f::RBN));
        // Only points already in contact: a speculative one (s > 0) is
        // left to the sub-steps and the restitution pass, so that its bodies
        // touch and the contact begins (and reports its hit) before it
        // bounces; bounced from its gap it would never touch (measured:
        // `examples/car_wall.rs` at 60 m/s bounced without a hit event).
        let fast = vn.lt(L::splat(-params.threshold).add(L::splat(1)));
        let touching = v.pt(K, f::BASE).gt(zero).not();
        hit[K] = fast.and(touching).and(live[K]).and(elastic);
        target[K] = e.mul::<FU>(vn).neg();
    });
    let any = hit[0].or(hit[1]);
    if !any.any() {
        return false;
    }
    let mut ln = [zero; 2];
    for _ in 0..IMPACT_ITERATIONS {
        each_point!(K => {
            let vn = speed(&a, &b, n, v.pt(K, f::RAN), v.pt(K, f::RBN));
            let new = ln[K].add(target[K].sub(vn).clamp_abs(LAMBDA_MAX)).clamp(zero, L::splat(LAMBDA_MAX));
            let new = ln[K].select(hit[K], new);
            let d = new.sub(ln[K]);
            ln[K] = new;
            Ratios::normal(&v, K).apply(&mut a, &mut b, d);
        });
    }
    each_point!(K => {
        let p = f::P[K];
        v.st(p + f::VREL, zero, hit[K]);
        v.st(p + f::MAXD, v.pt(K, f::MAXD).max(ln[K]), hit[K]);
        // Q16.16 → Q18.14, one below 2²⁷ at most: with the 15 impulses the
        // warm starts carry (each ≤ Λ/4 = 2²⁷) the total stays below 2³¹.
        let carried = ln[K].add(L::splat(2)).shr2().min(L::splat((LAMBDA_MAX >> 2) - 1));
        v.st(p + f::TOT, v.pt(K, f::TOT).add(carried), hit[K]);
    });
    scatter(bodies, ia, &a, flags.has(A_DYNAMIC).and(any));
    scatter(bodies, ib, &b, flags.has(B_DYNAMIC).and(any));
    true
}

/// Runs `f(lane)` for each active lane.
#[inline(always)]
fn each(active: M<LANES>, mut f: impl FnMut(usize)) {
    for l in 0..LANES {
        if active.is(l) {
            f(l);
        }
    }
}

/// The warm-start pass as a [`Kernel`].
pub(crate) struct WarmStart {
    /// Add the carried impulses to the step's totals (every sub-step after the first).
    pub(crate) count_totals: bool,
}

impl Kernel for WarmStart {
    #[inline(always)]
    fn eight<const WIDE: bool>(&self, blk: &mut Block, active: M<LANES>, bodies: &mut [BodyLanes]) {
        let c = self.count_totals;
        if !WIDE {
            each(active, |l| self.one(blk, l, bodies));
        } else if any_two(blk, active) {
            warm_start::<LANES, true>(blk, 0, active, bodies, c);
        } else {
            warm_start::<LANES, false>(blk, 0, active, bodies, c);
        }
    }
    #[inline(always)]
    fn one(&self, blk: &mut Block, lane: usize, bodies: &mut [BodyLanes]) {
        if lane_two(blk, lane) {
            warm_start::<1, true>(blk, lane, M::all(), bodies, self.count_totals);
        } else {
            warm_start::<1, false>(blk, lane, M::all(), bodies, self.count_totals);
        }
    }
}

/// Whether an active lane of `blk` holds a two-point manifold. When none
/// does, the kernels run without the second point: its fields are all zero
/// (see `prepare`), so its rows would change nothing, and the results are
/// the same bits either way.
#[inline(always)]
fn any_two(blk: &Block, active: M<LANES>) -> bool {
    let flags = field(blk, f::FLAGS);
    flags.iter().zip(active.0.iter()).fold(0, |acc, (&x, &m)| acc | (x & m)) & TWO_POINTS != 0
}

/// Whether lane `l` of `blk` holds a two-point manifold.
#[inline(always)]
fn lane_two(blk: &Block, l: usize) -> bool {
    super::lane(field(blk, f::FLAGS), l) & TWO_POINTS != 0
}

/// A sweep as a [`Kernel`].
pub(crate) struct SweepPass<'p> {
    pub(crate) params: &'p LaneParams,
    pub(crate) bias: Bias,
    /// The sweep runs in reverse (two points solved one at a time go last first).
    pub(crate) reverse: bool,
}

impl Kernel for SweepPass<'_> {
    #[inline(always)]
    fn eight<const WIDE: bool>(&self, blk: &mut Block, active: M<LANES>, bodies: &mut [BodyLanes]) {
        let (p, b, r) = (self.params, self.bias, self.reverse);
        if !WIDE {
            each(active, |l| self.one(blk, l, bodies));
        } else if any_two(blk, active) {
            sweep_and_push::<LANES, true>(blk, 0, active, bodies, p, b, r);
        } else {
            sweep_and_push::<LANES, false>(blk, 0, active, bodies, p, b, r);
        }
    }
    #[inline(always)]
    fn one(&self, blk: &mut Block, lane: usize, bodies: &mut [BodyLanes]) {
        let (p, b, r) = (self.params, self.bias, self.reverse);
        if lane_two(blk, lane) {
            sweep_and_push::<1, true>(blk, lane, M::all(), bodies, p, b, r);
        } else {
            sweep_and_push::<1, false>(blk, lane, M::all(), bodies, p, b, r);
        }
    }
}

/// The impact pass as a [`Kernel`]: notes whether any lane had an impact.
pub(crate) struct Impacts<'p> {
    pub(crate) params: &'p LaneParams,
    /// Whether a lane had an impact since the flag was last cleared.
    pub(crate) hit: Cell<bool>,
}

impl Kernel for Impacts<'_> {
    #[inline(always)]
    fn eight<const WIDE: bool>(&self, blk: &mut Block, active: M<LANES>, bodies: &mut [BodyLanes]) {
        if WIDE {
            if impact::<LANES>(blk, 0, active, bodies, self.params) {
                self.hit.set(true);
            }
        } else {
            each(active, |l| self.one(blk, l, bodies));
        }
    }
    #[inline(always)]
    fn one(&self, blk: &mut Block, lane: usize, bodies: &mut [BodyLanes]) {
        if impact::<1>(blk, lane, M::all(), bodies, self.params) {
            self.hit.set(true);
        }
    }
}

/// The restitution pass as a [`Kernel`].
pub(crate) struct Restitute<'p> {
    pub(crate) params: &'p LaneParams,
}

impl Kernel for Restitute<'_> {
    #[inline(always)]
    fn eight<const WIDE: bool>(&self, blk: &mut Block, active: M<LANES>, bodies: &mut [BodyLanes]) {
        if WIDE {
            restitute::<LANES>(blk, 0, active, bodies, self.params);
        } else {
            each(active, |l| restitute::<1>(blk, l, M::all(), bodies, self.params));
        }
    }
    #[inline(always)]
    fn one(&self, blk: &mut Block, lane: usize, bodies: &mut [BodyLanes]) {
        restitute::<1>(blk, lane, M::all(), bodies, self.params);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::contact::{field_mut, ContactConstraint};

    /// xorshift64: fixed arrays, no allocation, the same on every target.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            crate::solver::xorshift(&mut self.0)
        }
        /// Uniform in [lo, hi], or one of the edges and zero a quarter of the time.
        fn range(&mut self, lo: i32, hi: i32) -> i32 {
            let r = self.next();
            match r % 16 {
                0 => lo,
                1 => hi,
                2 => 0.clamp(lo, hi),
                _ => (i64::from(lo) + ((r >> 8) % (i64::from(hi) - i64::from(lo) + 1) as u64) as i64) as i32,
            }
        }
    }

    const ONE30: i32 = 1 << 30;

    /// A block of eight random lanes within the documented bounds, on bodies
    /// 1–16 (each lane its own two, so no two lanes share a dynamic body) or
    /// the static body 0.
    fn random_block(rng: &mut Rng) -> (Block, [BodyLanes; 17]) {
        let mut blk = [ContactConstraint::EMPTY; LANES];
        // One block in four holds one-point manifolds only.
        let one_point_only = rng.next().is_multiple_of(4);
        for l in 0..LANES {
            let mut put = |fi: usize, x: i32| field_mut(&mut blk, fi)[l] = x;
            let a_static = rng.next().is_multiple_of(4);
            put(f::IA, if a_static { 0 } else { 1 + 2 * l as i32 });
            put(f::IB, 2 + 2 * l as i32);
            let kinds = if one_point_only { STATIC_PAIR } else { TWO_POINTS | STATIC_PAIR | HAS_BLOCK };
            let mut flags = (rng.next() as i32 & kinds) | B_DYNAMIC | if a_static { 0 } else { A_DYNAMIC };
            if flags & TWO_POINTS == 0 {
                // `prepare` gives only two-point manifolds a block.
                flags &= !HAS_BLOCK;
            }
            put(f::FLAGS, flags);
            // A unit normal from the engine's own trig (no float in src/).
            let n = crate::math::Rot::from_angle(Scalar::from_bits((rng.next() % (27 << 30)) as i64));
            put(f::NX, lanes::from_scalar(n.c, FU, 1));
            put(f::NY, lanes::from_scalar(n.s, FU, 1));
            put(f::E, rng.range(0, ONE30));
            put(f::C12, rng.range(-(1 << 30), 1 << 30));
            put(f::C21, rng.range(-(1 << 30), 1 << 30));
            for k in 0..8 {
                put(f::MR + k, rng.range(-(15 << 27), 15 << 27));
            }
            for &p in &f::P {
                for x in [f::RAN, f::RBN, f::RAT, f::RBT] {
                    put(p + x, rng.range(-(2 << 29), 2 << 29));
                }
                for x in [f::ANX, f::ANY, f::BNX, f::BNY, f::ATX, f::ATY, f::BTX, f::BTY] {
                    put(p + x, rng.range(-ONE30, ONE30));
                }
                for x in [f::GAN, f::GBN, f::GAT, f::GBT] {
                    put(p + x, rng.range(-(3 << 29), 3 << 29));
                }
                put(p + f::LN, rng.range(0, LAMBDA_MAX));
                put(p + f::LT, rng.range(-LAMBDA_MAX, LAMBDA_MAX));
                put(p + f::BASE, rng.range(-(512 << 19), 512 << 19));
                put(p + f::PHI, rng.range(0, (255 << 23) - 1));
                put(p + f::CPHI, rng.range(0, LAMBDA_MAX));
                put(p + f::VREL, rng.range(-V_WALL, V_WALL));
                put(p + f::MAXD, rng.range(-LAMBDA_MAX, LAMBDA_MAX));
                put(p + f::TOT, rng.range(0, 15 * (LAMBDA_MAX >> 2)));
            }
            if flags & TWO_POINTS == 0 {
                // As `prepare` leaves a one-point manifold's second point.
                for x in 0..f::POINT {
                    put(f::P[1] + x, 0);
                }
            }
        }
        let mut bodies = [BodyLanes::EMPTY; 17];
        for b in bodies.iter_mut().skip(1) {
            for k in 0..3 {
                b.0[k] = rng.range(-V_WALL, V_WALL);
            }
            for k in 3..6 {
                b.0[k] = rng.range(-(100 << 20), 100 << 20);
            }
        }
        bodies[0].0[3..6].copy_from_slice(&[0, 0, 0]);
        (blk, bodies)
    }

    fn params(rng: &mut Rng) -> LaneParams {
        let soft = |rng: &mut Rng| LaneSoft {
            beta: rng.range(0, 1 << 20),
            sm: rng.range(0, ONE30),
            si: 0,
            floor: rng.range(0, 4095 << 19),
        };
        let mut p = LaneParams {
            inv_h: rng.range(1 << 10, 1 << 30),
            spec_cap: rng.range(0, 4095 << 19),
            push: rng.range(0, 100 << 16),
            threshold: rng.range(0, 10 << 16),
            soft: [soft(rng), soft(rng)],
            deep: rng.range(0, 1 << 19),
            target: rng.range(0, 1 << 17),
            shift: rng.range(0, 64 << 19),
            shift_static: rng.range(0, 4095 << 19),
        };
        for s in p.soft.iter_mut() {
            s.si = ONE30 - s.sm;
        }
        p
    }

    /// Every kernel gives the same bytes on eight lanes at once (any mask,
    /// through the dispatch that skips the second point of blocks without
    /// two-point manifolds) as on each active lane alone with both points,
    /// on random and extreme inputs.
    #[test]
    fn eight_lanes_at_once_equal_one_at_a_time() {
        // Eight lanes run AVX2 instructions on x86-64 (see `L`).
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut impacts, mut pushed) = (0, 0);
        for round in 0..12_000 {
            let (mut blk, bodies) = random_block(&mut rng);
            if round % 7 == 3 {
                // A lane whose body B is past the end of the records: read as
                // empty and never written, on eight lanes as on one.
                field_mut(&mut blk, f::IB)[round % LANES] = 17 + (round % 5) as i32;
            }
            let p = params(&mut rng);
            let mut active = M::<LANES>::none();
            for (j, a) in active.0.iter_mut().enumerate() {
                *a = -i32::from(round % 3 == 0 || (rng.next() >> j) & 1 == 1);
            }
            let kernel = round % 6;
            let (bias, reverse) = (if round % 2 == 0 { Bias::On } else { Bias::Off }, round % 4 < 2);
            let (mut b8, mut bodies8) = (blk, bodies);
            let (mut b1, mut bodies1) = (blk, bodies);
            match kernel {
                0 => {
                    let k = WarmStart { count_totals: round % 3 == 1 };
                    k.eight::<true>(&mut b8, active, &mut bodies8);
                    each(active, |l| {
                        warm_start::<1, true>(&mut b1, l, M::all(), &mut bodies1, k.count_totals)
                    });
                }
                1 => {
                    restitute::<LANES>(&mut b8, 0, active, &mut bodies8, &p);
                    each(active, |l| restitute::<1>(&mut b1, l, M::all(), &mut bodies1, &p));
                }
                5 => {
                    let k = Impacts { params: &p, hit: Cell::new(false) };
                    k.eight::<true>(&mut b8, active, &mut bodies8);
                    let mut hit = false;
                    each(active, |l| hit |= impact::<1>(&mut b1, l, M::all(), &mut bodies1, &p));
                    assert_eq!(k.hit.get(), hit, "round {round}: whether any lane had an impact");
                    impacts += usize::from(hit);
                }
                _ => {
                    SweepPass { params: &p, bias, reverse }.eight::<true>(&mut b8, active, &mut bodies8);
                    each(active, |l| {
                        sweep_and_push::<1, true>(&mut b1, l, M::all(), &mut bodies1, &p, bias, reverse)
                    });
                    pushed += usize::from(bodies8.iter().any(|b| b.0[MOVED] != 0));
                }
            }
            assert_eq!(b8, b1, "round {round}: kernel {kernel} constraint lanes");
            assert_eq!(bodies8, bodies1, "round {round}: kernel {kernel} bodies");
        }
        // The impact kernel's rounds mostly have impacts (random approach
        // speeds, half the points in contact; 1,423 measured): the comparison
        // is not of no-ops.
        assert!(impacts > 1_200, "{impacts} of 2,000 impact rounds had an impact");
        // Likewise the deep push-out in the biased sweeps' rounds (random
        // separations down to −512 m, depths from 0 to 1 m; 3,729 measured).
        assert!(pushed > 1_000, "{pushed} of 4,000 sweep rounds pushed a body apart");
    }
}
