//! Benchmarks of rollback's costs: `state_hash`, `state_hashes`, `snapshot` and
//! `restore` on a settled mixed scene (pyramids of boxes with circles resting on
//! them, so there are contacts) of about 500 and 5,000 bodies. Each figure is the
//! median over samples after a warm-up, in microseconds per call (on a shared
//! machine the median is the figure to quote). For comparison it also times
//! FNV-1a byte by byte over the same bytes, the state hash before format 2
//! (kept here only).
//!
//! Run: `cargo bench --bench snapshot`.

use std::hint::black_box;
use std::time::Instant;

use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// `pyramids` pyramids of 10 rows (55 boxes) side by side, each with 8 circles
/// dropped on it, stepped until settled.
fn settled_scene(pyramids: u32) -> Result<World<'static>, arphysics::Error> {
    let bodies = pyramids as usize * 64 + 16;
    let half = f64::from(pyramids) * 7.0 + 20.0;
    let bounds = Rect::from_corners(v(-half - 50.0, -100.0), v(half + 50.0, 400.0));
    let caps =
        Capacities { bodies, paths: 8, contacts: bodies * 4, joints: 0, ..Capacities::for_bodies(bodies) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps)?;
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)))?;
    let piece = w.add_path(PolygonPath::rectangle(s(100.0), s(2.0))?)?;
    let mut x = -half + 50.0;
    while x < half + 50.0 {
        w.add_body(BodyDef::polygon(piece).position(v(x, -1.0)).static_body())?;
        x += 100.0;
    }
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    for p in 0..pyramids {
        let x0 = -half + 20.0 + f64::from(p) * 14.0;
        for row in 0..10u32 {
            let count = 10 - row;
            for j in 0..count {
                let x = x0 + f64::from(j) - f64::from(count) * 0.5 + 0.5;
                w.add_body(BodyDef::polygon(unit).position(v(x, 0.5 + f64::from(row))))?;
            }
        }
        for k in 0..8u32 {
            let r = 0.2 + 0.05 * f64::from(k % 4);
            w.add_body(BodyDef::circle(s(r)).position(v(x0 - 3.5 + f64::from(k), 12.0 + f64::from(k % 2))))?;
        }
    }
    for _ in 0..240 {
        w.step(Scalar::ONE / 60)?;
    }
    Ok(w)
}

/// Median microseconds per call of each of `ops`, over `samples` samples of
/// `reps` calls. The ops take turns within each sample, so a change of load on a
/// shared machine touches them alike.
fn medians_us<const N: usize>(samples: usize, reps: usize, ops: &mut [&mut dyn FnMut(); N]) -> [f64; N] {
    let mut t = vec![[0.0f64; N]; samples + 1];
    for sample in &mut t {
        for (k, op) in ops.iter_mut().enumerate() {
            let start = Instant::now();
            for _ in 0..reps {
                op();
            }
            sample[k] = start.elapsed().as_secs_f64() * 1e6 / reps as f64;
        }
    }
    t.remove(0); // warm-up
    core::array::from_fn(|k| {
        let mut col: Vec<f64> = t.iter().map(|s| s[k]).collect();
        col.sort_by(f64::total_cmp);
        col[col.len() / 2]
    })
}

fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn main() -> Result<(), arphysics::Error> {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    println!(
        "{:>7} {:>7} {:>9} | {:>10} {:>12} {:>9} {:>9} | {:>12}  (µs, median)",
        "bodies", "arbiters", "bytes", "state_hash", "state_hashes", "snapshot", "restore", "old FNV-1a"
    );
    for pyramids in [8u32, 80] {
        let name = format!("{}", pyramids * 63);
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let w = settled_scene(pyramids)?;
        let mut buf = vec![0u8; w.max_snapshot_len()];
        let n = w.snapshot(&mut buf)?;
        let (samples, reps) = if pyramids < 20 { (41, 40) } else { (21, 4) };
        let saved = buf[..n].to_vec();
        let mut restored = settled_scene(pyramids)?;
        let [hash, hashes, snap, restore, fnv] = medians_us(
            samples,
            reps,
            &mut [
                &mut || {
                    black_box(w.state_hash());
                },
                &mut || {
                    black_box(w.state_hashes());
                },
                &mut || {
                    black_box(w.snapshot(black_box(&mut buf)).ok());
                },
                &mut || {
                    black_box(restored.restore(black_box(&saved)).ok());
                },
                &mut || {
                    black_box(fnv1a(black_box(&saved[..n - 8])));
                },
            ],
        );
        println!(
            "{:>7} {:>7} {:>9} | {:>10.1} {:>12.1} {:>9.1} {:>9.1} | {:>12.1}",
            w.body_count(),
            w.arbiters().count(),
            n,
            hash,
            hashes,
            snap,
            restore,
            fnv
        );
    }
    Ok(())
}
