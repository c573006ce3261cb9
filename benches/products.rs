//! The cost of one Q32.32 product on this machine: the unit of the stages that
//! work in `Scalar` (the per-body sub-step, the arbiter lifecycle, the narrow
//! phase; about half of a contact step, see `docs/design/solver-lanes.md` §31),
//! while the solver's kernels use the 32-bit lanes measured beside it (issue 16
//! chose them from these figures). Each product here is a saturating `*`
//! followed by a saturating `+` over arrays of independent values, so the
//! processor overlaps as many as it can: a throughput, the best case for the
//! engine's code. Beside it, for scale: the same in Q16.16 `i32` lanes, with and
//! without range checks, and a vectorised f32 multiply-add.
//!
//! Run: `cargo bench --bench products`.

use std::hint::black_box;
use std::time::Instant;

use arphysics::Scalar;

const N: usize = 1024;
const REPS: usize = 100_000;
const SAMPLES: usize = 7;

fn q32(a: &[Scalar; N], b: &[Scalar; N], out: &mut [Scalar; N]) {
    for _ in 0..REPS {
        for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
            *o += *x * *y;
        }
        black_box(&mut *out);
    }
}

/// A 32-bit-lane product, the kind a narrower solver format would use: Q16.16
/// values in `i32`, the exact product in `i64`, shifted back and added with
/// saturation (the same overflow policy as `Scalar`). Integer, so as
/// deterministic as the Q32.32 one, and the compiler vectorises it.
fn q16(a: &[i32; N], b: &[i32; N], out: &mut [i32; N]) {
    for _ in 0..REPS {
        for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
            let p = (i64::from(*x) * i64::from(*y)) >> 16;
            let p = p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
            *o = o.saturating_add(p);
        }
        black_box(&mut *out);
    }
}

/// The same without the range checks, as a solver could do where its ranges
/// are bounded by construction (the product is exact; only the add wraps).
fn q16_unchecked(a: &[i32; N], b: &[i32; N], out: &mut [i32; N]) {
    for _ in 0..REPS {
        for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
            let p = (i64::from(*x) * i64::from(*y)) >> 16;
            *o = o.wrapping_add(p as i32);
        }
        black_box(&mut *out);
    }
}

fn f32s(a: &[f32; N], b: &[f32; N], out: &mut [f32; N]) {
    for _ in 0..REPS {
        for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
            *o += x * y;
        }
        black_box(&mut *out);
    }
}

/// Median ns per product over the samples.
fn median_ns(mut run: impl FnMut()) -> f64 {
    let mut ns: Vec<f64> = (0..SAMPLES)
        .map(|_| {
            let t = Instant::now();
            run();
            t.elapsed().as_secs_f64() * 1e9 / (REPS * N) as f64
        })
        .collect();
    ns.sort_by(f64::total_cmp);
    ns[SAMPLES / 2]
}

fn main() {
    let values = |i: usize| ((i % 17) as f64 * 0.01 - 0.08, (i % 13) as f64 * 0.003 + 0.5);
    let a: [Scalar; N] = black_box(core::array::from_fn(|i| Scalar::from_num(values(i).0)));
    let b: [Scalar; N] = black_box(core::array::from_fn(|i| Scalar::from_num(values(i).1)));
    let af: [f32; N] = black_box(core::array::from_fn(|i| values(i).0 as f32));
    let bf: [f32; N] = black_box(core::array::from_fn(|i| values(i).1 as f32));
    let a16: [i32; N] = black_box(core::array::from_fn(|i| (values(i).0 * 65536.0) as i32));
    let b16: [i32; N] = black_box(core::array::from_fn(|i| (values(i).1 * 65536.0) as i32));
    let q = median_ns(|| q32(&a, &b, &mut [Scalar::ZERO; N]));
    let n = median_ns(|| q16(&a16, &b16, &mut [0; N]));
    let u = median_ns(|| q16_unchecked(&a16, &b16, &mut [0; N]));
    let f = median_ns(|| f32s(&af, &bf, &mut [0.0; N]));
    println!("Q32.32 product + sum: {q:.3} ns per product (median of {SAMPLES})");
    println!("Q16.16 in i32 lanes, saturating: {n:.3} ns per product; Q32.32 takes {:.1}x", q / n);
    println!("Q16.16 in i32 lanes, unchecked: {u:.3} ns per product; Q32.32 takes {:.1}x", q / u);
    println!("f32 multiply-add (vectorised): {f:.3} ns per product; Q32.32 takes {:.1}x", q / f);
}
