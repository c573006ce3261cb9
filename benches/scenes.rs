//! Benchmarks: Box2D v3's benchmark scenes, same definitions, stepped at 1/60 s
//! with gravity (0, −10) and the world's default 4 sub-steps. Each reports
//! milliseconds per step as the median over samples after a warm-up (on a shared
//! machine the median is the figure to quote), plus memory.
//!
//! Run all: `cargo bench --bench scenes`; one: `cargo bench --bench scenes -- pyramid_20`.
//! `-- --narrow` adds the narrow phase timed alone; `-- --quick` takes one
//! sample per scene (for `valgrind --tool=callgrind`, whose instruction counts
//! per stage do not depend on the load of a shared machine). `-- --levels`
//! measures what the run-time SIMD dispatch gains instead: each scene built
//! twice, one world stepped at `SimdLevel::Portable` and one at the best level
//! this processor offers, sample by sample in turn (see [`levels`]).

use std::time::Instant;

use arphysics::{
    limit_simd_level, simd_level, Arbiter, Body, Capacities, PolygonPath, Scalar, SimdLevel, Slot, Storage,
    World,
};

#[path = "scenes/defs.rs"]
mod defs;

use defs::{joint_grid, large_pyramid, many_pyramids, plain_world, pyramid_20, rain, s};

type Build = fn() -> Result<World<'static>, arphysics::Error>;

/// This thread's CPU time so far (ns), from Linux's `/proc/thread-self/schedstat`
/// (`None` elsewhere). On a shared machine it leaves out the time other
/// processes held the core, so it is steadier than the wall clock.
fn thread_cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// The narrow phase alone: every touching pair of `w` (its arbiters, bodies in
/// arbiter order) collided `rounds` times per sample with the public collide
/// functions, the speculative distance as margin. Prints ns per pair (thread
/// CPU time, median and min of the samples). A steadier figure for the
/// narrow phase than its share of a step on a shared machine.
fn narrow_phase(name: &str, w: &World<'_>) -> Result<(), arphysics::Error> {
    use arphysics::collide::{collide_circles, collide_polygon_circle, collide_polygons, Manifold};
    use arphysics::math::Transform;
    enum Part<'p> {
        Circle(Scalar),
        Polygon(&'p PolygonPath),
        /// A shape the scenes here do not use (timed as no contact).
        Other,
    }
    let part = |b: &Body| -> Result<Part<'_>, arphysics::Error> {
        Ok(match b.shape() {
            arphysics::Shape::Circle { radius } => Part::Circle(radius),
            arphysics::Shape::Polygon(p) => Part::Polygon(w.path(p)?),
            _ => Part::Other,
        })
    };
    let mut pairs: Vec<(Part<'_>, Transform, Part<'_>, Transform)> = Vec::new();
    for arb in w.arbiters() {
        let (a, b) = (w.body(arb.body_a())?, w.body(arb.body_b())?);
        pairs.push((part(a)?, a.transform(), part(b)?, b.transform()));
    }
    let margin = arphysics::limits::SPECULATIVE_DISTANCE;
    let collide = |(a, xa, b, xb): &(Part<'_>, Transform, Part<'_>, Transform)| -> Manifold {
        match (a, b) {
            (Part::Circle(ra), Part::Circle(rb)) => collide_circles(*ra, *xa, *rb, *xb, margin),
            (Part::Polygon(pa), Part::Polygon(pb)) => collide_polygons(pa, *xa, pb, *xb, margin),
            (Part::Polygon(pa), Part::Circle(rb)) => collide_polygon_circle(pa, *xa, *rb, *xb, margin),
            (Part::Circle(ra), Part::Polygon(pb)) => collide_polygon_circle(pb, *xb, *ra, *xa, margin),
            _ => Manifold::EMPTY,
        }
    };
    // About a million collisions per sample, so that the CPU clock's tick
    // granularity (schedstat is updated at ticks and switches) is negligible.
    let (rounds, samples) = ((1_000_000 / pairs.len().max(1)).max(1), 9);
    let mut cpu = Vec::new();
    let mut points = 0usize;
    for _ in 0..samples {
        let Some(c0) = thread_cpu_ns() else { return Ok(()) };
        for _ in 0..rounds {
            for pair in &pairs {
                points += std::hint::black_box(collide(std::hint::black_box(pair))).count;
            }
        }
        let c1 = thread_cpu_ns().unwrap_or(c0);
        cpu.push(c1.saturating_sub(c0) as f64 / (rounds * pairs.len().max(1)) as f64);
    }
    cpu.sort_by(f64::total_cmp);
    println!(
        "{name:>14}: narrow phase alone, {} pairs: median {:.1} ns/pair (min {:.1}), {} points",
        pairs.len(),
        cpu[cpu.len() / 2],
        cpu[0],
        points / (rounds * samples)
    );
    Ok(())
}

/// A scene built and stepped 30 times (the warm-up before any sample).
fn warmed(build: Build, dt: Scalar) -> Result<World<'static>, arphysics::Error> {
    let mut w = build()?;
    for _ in 0..30 {
        w.step(dt)?;
    }
    Ok(w)
}

/// One scene at two SIMD levels: two worlds built alike, one stepped with the
/// contact and pivot kernels at `SimdLevel::Portable` (one lane at a time) and
/// one at the best level this processor offers, `steps` steps a sample, the
/// two in turn (each first in every other sample) so that both see the same
/// load. The worlds stay bit-identical (the levels compute the same bits),
/// which the state hashes at the end check. Prints each level's median thread
/// CPU ms/step and the median of the per-sample ratios.
fn levels(name: &str, build: Build, steps: usize, samples: usize) -> Result<(), arphysics::Error> {
    limit_simd_level(SimdLevel::Avx2);
    let best = simd_level();
    let dt = s(1.0 / 60.0);
    let (mut portable, mut fast) = (warmed(build, dt)?, warmed(build, dt)?);
    let run = |w: &mut World<'_>, level: SimdLevel| -> Result<Option<f64>, arphysics::Error> {
        limit_simd_level(level);
        let c0 = thread_cpu_ns();
        for _ in 0..steps {
            w.step(dt)?;
        }
        Ok(c0.zip(thread_cpu_ns()).map(|(c0, c1)| c1.saturating_sub(c0) as f64 / 1e6 / steps as f64))
    };
    let (mut p, mut f, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..samples {
        // Each level goes first in every other sample.
        let (tp, tf) = if k % 2 == 0 {
            let tp = run(&mut portable, SimdLevel::Portable)?;
            (tp, run(&mut fast, best)?)
        } else {
            let tf = run(&mut fast, best)?;
            (run(&mut portable, SimdLevel::Portable)?, tf)
        };
        let (Some(tp), Some(tf)) = (tp, tf) else {
            println!("{name:>14}: no thread CPU clock on this system");
            return Ok(());
        };
        p.push(tp);
        f.push(tf);
        ratio.push(tp / tf);
    }
    limit_simd_level(SimdLevel::Avx2);
    for v in [&mut p, &mut f, &mut ratio] {
        v.sort_by(f64::total_cmp);
    }
    let median = |v: &[f64]| v[v.len() / 2];
    let same = portable.state_hash() == fast.state_hash();
    println!(
        "{name:>14}: Portable {:.3} ms/step, {best:?} {:.3} ms/step (thread CPU, medians of {samples}); \
         Portable / {best:?} {:.2} (median of the samples' ratios, {:.2}–{:.2}); state hashes {}",
        median(&p),
        median(&f),
        median(&ratio),
        ratio[0],
        ratio[ratio.len() - 1],
        if same { "equal" } else { "DIFFER" },
    );
    assert!(same, "{name}: the SIMD levels stepped to different states");
    Ok(())
}

fn main() -> Result<(), arphysics::Error> {
    let filter: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    // `--narrow`: also time the narrow phase alone (large_pyramid and rain).
    // `--quick`: one sample per scene (for instruction counts under valgrind).
    let narrow = std::env::args().any(|a| a == "--narrow");
    let quick = std::env::args().any(|a| a == "--quick");
    // `--levels`: the SIMD dispatch's gain (see `levels`).
    let by_level = std::env::args().any(|a| a == "--levels");
    let scenes: [(&str, Build, usize, usize); 5] = [
        ("pyramid_20", || pyramid_20(plain_world), 60, 15),
        ("rain", || rain(plain_world), 30, 7),
        ("large_pyramid", || large_pyramid(plain_world), 10, 5),
        ("many_pyramids", || many_pyramids(plain_world), 5, 5),
        ("joint_grid", || joint_grid(plain_world), 10, 5),
    ];
    let dt = s(1.0 / 60.0);
    for (name, build, steps, samples) in scenes {
        if !filter.is_empty() && !filter.iter().any(|f| name.contains(f.as_str())) {
            continue;
        }
        if by_level {
            // Five times the steps a sample: the thread CPU clock advances at
            // the scheduler's ticks, a few ms, too coarse for 12 ms samples.
            levels(name, build, steps * 5, if quick { 1 } else { samples })?;
            continue;
        }
        let mut w = warmed(build, dt)?;
        let samples = if quick { 1 } else { samples };
        let mut times = Vec::new();
        let mut cpu = Vec::new();
        for _ in 0..samples {
            let (t, c) = (Instant::now(), thread_cpu_ns());
            for _ in 0..steps {
                w.step(dt)?;
            }
            times.push(t.elapsed().as_secs_f64() * 1000.0 / steps as f64);
            if let (Some(c0), Some(c1)) = (c, thread_cpu_ns()) {
                cpu.push(c1.saturating_sub(c0) as f64 / 1e6 / steps as f64);
            }
        }
        times.sort_by(f64::total_cmp);
        cpu.sort_by(f64::total_cmp);
        let cpu_median = cpu.get(cpu.len() / 2).map_or(String::new(), |c| format!(", thread CPU {c:.3}"));
        println!(
            "{name:>14}: {:>5} bodies, {:>6} contact pairs, {:>5} joints: median {:.3} ms/step (min {:.3}, max {:.3}){cpu_median}, state hash {:016x}",
            w.body_count(),
            w.arbiters().count(),
            w.joints().count(),
            times[times.len() / 2],
            times[0],
            times[times.len() - 1],
            w.state_hash(),
        );
        if narrow && (name == "large_pyramid" || name == "rain") {
            narrow_phase(name, &w)?;
        }
    }
    // Storage per body slot (the body, its broad-phase entries and the solver's
    // copy) and per contact slot (two arbiter buffers, the candidate pair and
    // the solver's constraint), as the world reports it.
    let (per_body, per_contact) = (Storage::BYTES_PER_BODY, Storage::BYTES_PER_CONTACT);
    let large = Capacities {
        bodies: 5100,
        paths: 0,
        contacts: 20400,
        joints: 0,
        post_step_callbacks: 64,
        events: 64,
        chain_vertices: 0,
        shapes: 0,
    };
    println!(
        "memory: {per_body} bytes per body slot (body {}), {per_contact} per contact slot \
         (arbiter {} twice); large_pyramid's capacities (5,100 bodies, 20,400 contacts): {:.1} MiB",
        std::mem::size_of::<Slot<Body>>(),
        std::mem::size_of::<Arbiter>(),
        large.storage_bytes() as f64 / (1024.0 * 1024.0)
    );
    Ok(())
}
