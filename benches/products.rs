//! The cost of one Q32.32 product on this machine: the unit the engine's speed is
//! made of (a pyramid_20 step takes about 478,000 of them; see the README's
//! "Performance"). Each product here is `sat_mul` followed by `sat_add` over
//! arrays of independent values, so the processor overlaps as many as it can:
//! a throughput, the best case for the engine's code. A vectorised f32
//! multiply-add over the same arrays is measured beside it for scale.
//!
//! Run: `cargo bench --bench products`.

use std::hint::black_box;
use std::time::Instant;

use arphysics::math::scalar::ScalarExt as _;
use arphysics::Scalar;

const N: usize = 1024;
const REPS: usize = 100_000;
const SAMPLES: usize = 7;

fn q32(a: &[Scalar; N], b: &[Scalar; N], out: &mut [Scalar; N]) {
    for _ in 0..REPS {
        for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
            *o = o.sat_add(x.sat_mul(*y));
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
    let q = median_ns(|| q32(&a, &b, &mut [Scalar::ZERO; N]));
    let f = median_ns(|| f32s(&af, &bf, &mut [0.0; N]));
    println!("Q32.32 sat_mul + sat_add: {q:.3} ns per product (median of {SAMPLES})");
    println!("f32 multiply-add (vectorised): {f:.3} ns per product; ratio {:.1}", q / f);
}
