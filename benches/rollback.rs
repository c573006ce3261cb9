//! Benchmark of a rollback tick: restore a snapshot taken 8 frames back and
//! re-simulate the 8 frames (ggrs's default prediction window), the cost a
//! rollback game pays on top of its normal step when a late input arrives.
//! Issue 16's target: under 2 ms on the project's build machine.
//!
//! The scene: 500 dynamic bodies (circles r 0.4 m, 0.8 m boxes, triangles and
//! hexagons of radius 0.45 m, in turn) dropped from a 25 × 20 grid, 1.25 m apart,
//! into a static U container (floor 40 m wide inside, walls 20 m tall), gravity
//! (0, −10), 1/60 s steps, the world's default 4 sub-steps. After 120 warm-up
//! steps (2 s: most bodies have landed, the pile is still settling), each sample:
//!
//! 1. takes a snapshot (timed);
//! 2. steps 8 frames, each timed (the single-step figure) and records the state
//!    hash;
//! 3. restores the snapshot and steps the same 8 frames again (timed together:
//!    the rollback figure), then checks the state hash equals the first run's
//!    (a cheap determinism check: a mismatch stops the bench).
//!
//! The scene goes on from there, so the samples cover 8 × `SAMPLES` steps of the
//! settling pile. Figures are medians over the samples (on a shared machine the
//! median is the figure to quote), each beside the fastest sample (the least
//! disturbed when the machine is loaded), with the load average.
//!
//! Run: `cargo bench --bench rollback`.

use std::hint::black_box;
use std::time::Instant;

use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World, WorldDef,
};

/// Frames re-simulated per rollback (ggrs's default prediction window).
const ROLLBACK_FRAMES: usize = 8;
/// Steps before the first sample.
const WARMUP_STEPS: usize = 120;
/// Samples (rollbacks) timed.
const SAMPLES: usize = 101;
/// Dynamic bodies in the scene.
const BODIES: usize = 500;
/// Issue 16's target for restore + 8 steps, ms.
const TARGET_MS: f64 = 2.0;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// The regular polygon of `n` vertices and circumradius `r`, centred on the origin.
fn regular(n: u32, r: f64) -> Result<PolygonPath, arphysics::Error> {
    let points: Vec<Vector2> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * f64::from(k) / f64::from(n) + std::f64::consts::FRAC_PI_2;
            v(r * t.cos(), r * t.sin())
        })
        .collect();
    PolygonPath::new(&points)
}

/// The mixed scene, built and not yet stepped.
fn scene() -> Result<World<'static>, arphysics::Error> {
    let bounds = Rect::from_corners(v(-100.0, -50.0), v(100.0, 150.0));
    let n = BODIES + 3;
    // Falling grids overlap more neighbours' swept boxes than a resting pile: 6
    // candidate pairs per body, as the peers' rain scene.
    let caps = Capacities { bodies: n, paths: 8, contacts: n * 6, joints: 0, ..Capacities::for_bodies(n) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps)?;
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)))?;
    let floor = w.add_path(PolygonPath::rectangle(s(42.0), s(1.0))?)?;
    let wall = w.add_path(PolygonPath::rectangle(s(1.0), s(20.0))?)?;
    w.add_body(BodyDef::polygon(floor).position(v(0.0, -0.5)).static_body())?;
    w.add_body(BodyDef::polygon(wall).position(v(-20.5, 10.0)).static_body())?;
    w.add_body(BodyDef::polygon(wall).position(v(20.5, 10.0)).static_body())?;
    let square = w.add_path(PolygonPath::rectangle(s(0.8), s(0.8))?)?;
    let triangle = w.add_path(regular(3, 0.45)?)?;
    let hexagon = w.add_path(regular(6, 0.45)?)?;
    for k in 0..BODIES {
        let (row, col) = (k / 25, k % 25);
        let x = -15.0 + 1.25 * col as f64 + if row % 2 == 0 { 0.0 } else { 0.3 };
        let y = 2.0 + 1.25 * row as f64;
        let def = match k % 4 {
            0 => BodyDef::circle(s(0.4)),
            1 => BodyDef::polygon(square),
            2 => BodyDef::polygon(triangle),
            _ => BodyDef::polygon(hexagon),
        };
        w.add_body(def.position(v(x, y)))?;
    }
    Ok(w)
}

/// (median, fastest) of the samples: on a loaded machine the fastest sample is
/// the one least disturbed by the other processes.
fn median_min(mut xs: Vec<f64>) -> (f64, f64) {
    xs.sort_by(f64::total_cmp);
    (xs.get(xs.len() / 2).copied().unwrap_or(f64::NAN), xs.first().copied().unwrap_or(f64::NAN))
}

/// The 1, 5 and 15 minute load averages (the machine is shared; a busy one
/// stretches every figure).
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".to_owned())
}

fn main() -> Result<(), arphysics::Error> {
    let load_start = load_average();
    let dt = Scalar::ONE / 60;
    let mut w = scene()?;
    for _ in 0..WARMUP_STEPS {
        w.step(dt)?;
    }
    let mut buf = vec![0u8; w.max_snapshot_len()];
    let (mut snapshot_us, mut restore_us, mut rollback_ms, mut step_ms) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (mut first_after_restore_ms, mut later_after_restore_ms) = (Vec::new(), Vec::new());
    let mut bytes = 0;
    for sample in 0..SAMPLES {
        let t = Instant::now();
        bytes = w.snapshot(black_box(&mut buf))?;
        snapshot_us.push(t.elapsed().as_secs_f64() * 1e6);

        for _ in 0..ROLLBACK_FRAMES {
            let t = Instant::now();
            black_box(w.step(dt)?);
            step_ms.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let first = w.state_hash();

        let t = Instant::now();
        w.restore(black_box(&buf[..bytes]))?;
        let restored = t.elapsed();
        for k in 0..ROLLBACK_FRAMES {
            let s = Instant::now();
            black_box(w.step(dt)?);
            if k == 0 {
                first_after_restore_ms.push(s.elapsed().as_secs_f64() * 1e3);
            } else {
                later_after_restore_ms.push(s.elapsed().as_secs_f64() * 1e3);
            }
        }
        let total = t.elapsed();
        restore_us.push(restored.as_secs_f64() * 1e6);
        rollback_ms.push(total.as_secs_f64() * 1e3);

        let again = w.state_hash();
        assert_eq!(
            first, again,
            "sample {sample}: re-simulating {ROLLBACK_FRAMES} frames after a restore gave another state \
             (hash {first:#018x} first, {again:#018x} again)"
        );
    }
    let arbiters = w.arbiters().count();
    let (rollback, rollback_min) = median_min(rollback_ms);
    let (single, single_min) = median_min(step_ms);
    let (restore, restore_min) = median_min(restore_us);
    let (snapshot, snapshot_min) = median_min(snapshot_us);
    println!(
        "rollback: {} bodies ({BODIES} dynamic), {arbiters} arbiters at the end, snapshot {bytes} bytes; \
         {WARMUP_STEPS} warm-up steps, {SAMPLES} samples (median, fastest)",
        w.body_count()
    );
    println!(
        "  restore + {ROLLBACK_FRAMES} steps: {rollback:.3} ms, {rollback_min:.3} ms (target < {TARGET_MS} ms{})",
        if rollback < TARGET_MS { ", met" } else { ", not met" }
    );
    println!("  single step:       {single:.3} ms, {single_min:.3} ms");
    let (first, first_min) = median_min(first_after_restore_ms);
    let (later, later_min) = median_min(later_after_restore_ms);
    println!("    after a restore: {first:.3} ms, {first_min:.3} ms the first, {later:.3} ms, {later_min:.3} ms the others");
    println!("  restore:           {restore:.1} µs, {restore_min:.1} µs");
    println!("  snapshot:          {snapshot:.1} µs, {snapshot_min:.1} µs");
    println!("  re-simulated state hash equal to the first run's in all {SAMPLES} samples");
    println!("  load average at start / end: {load_start} / {}", load_average());
    Ok(())
}
