//! Benchmarks: Box2D v3's benchmark scenes, same definitions, stepped at 1/60 s
//! with gravity (0, −10) and the world's default 4 sub-steps. Each reports
//! milliseconds per step as the median over samples after a warm-up (on a shared
//! machine the median is the figure to quote), plus memory.
//!
//! Run all: `cargo bench --bench scenes`; one: `cargo bench --bench scenes -- pyramid_20`.
//! `-- --narrow` adds the narrow phase timed alone; `-- --quick` takes one
//! sample per scene (for `valgrind --tool=callgrind`, whose instruction counts
//! per stage do not depend on the load of a shared machine).

use std::time::Instant;

use arphysics::{
    Arbiter, Body, BodyDef, Capacities, GravityForceGenerator, JointDef, JointKind, PathHandle, PolygonPath,
    Rect, Scalar, Slot, Storage, Vector2, World, WorldDef,
};

type Build = fn() -> Result<World<'static>, arphysics::Error>;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

fn world(bodies: usize, joints: usize) -> Result<World<'static>, arphysics::Error> {
    let bounds = Rect::from_corners(v(-1000.0, -100.0), v(1000.0, 1000.0));
    let caps =
        Capacities { bodies, paths: 16, contacts: bodies * 4, joints, post_step_callbacks: 64, events: 64 };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps)?;
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)))?;
    Ok(w)
}

/// A pyramid of `rows` rows of 1 m boxes with its base centred on `x0`; all
/// boxes share one polygon path.
fn pyramid_at(
    w: &mut World<'_>,
    unit: PathHandle,
    rows: u32,
    x0: f64,
    y0: f64,
) -> Result<(), arphysics::Error> {
    for row in 0..rows {
        let count = rows - row;
        for j in 0..count {
            let x = x0 + f64::from(j) - f64::from(count) * 0.5 + 0.5;
            w.add_body(BodyDef::polygon(unit).position(v(x, y0 + 0.5 + f64::from(row))))?;
        }
    }
    Ok(())
}

/// Static ground boxes covering [−half, half] at y ∈ [−2, 0] (a body is at most
/// 256 m across, so a wide ground is several boxes).
fn ground(w: &mut World<'_>, half: f64) -> Result<(), arphysics::Error> {
    let piece = w.add_path(PolygonPath::rectangle(s(100.0), s(2.0))?)?;
    let mut x = -half + 50.0;
    while x < half {
        w.add_body(BodyDef::polygon(piece).position(v(x, -1.0)).static_body())?;
        x += 100.0;
    }
    Ok(())
}

fn large_pyramid() -> Result<World<'static>, arphysics::Error> {
    let mut w = world(5100, 0)?;
    ground(&mut w, 100.0)?;
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    pyramid_at(&mut w, unit, 100, 0.0, 0.0)?;
    Ok(w)
}

fn many_pyramids() -> Result<World<'static>, arphysics::Error> {
    let mut w = world(20 * 20 * 55 + 128, 0)?;
    ground(&mut w, 250.0)?;
    // 20 × 20 pyramids of 10 rows: 20 side by side on each of 20 shelves,
    // the shelves segments as in Box2D (two 250 m ones each: a body is at most
    // 256 m across).
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    for k in 0..20 {
        let y0 = f64::from(k) * 14.0;
        if k > 0 {
            for x in [-125.0, 125.0] {
                let shelf = arphysics::Segment::new(v(-125.0, 0.0), v(125.0, 0.0))?;
                w.add_body(BodyDef::segment(shelf).position(v(x, y0)))?;
            }
        }
        for i in 0..20 {
            pyramid_at(&mut w, unit, 10, -228.0 + f64::from(i) * 24.0, y0)?;
        }
    }
    Ok(w)
}

fn pyramid_20() -> Result<World<'static>, arphysics::Error> {
    let mut w = world(260, 0)?;
    ground(&mut w, 100.0)?;
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    pyramid_at(&mut w, unit, 20, 0.0, 0.0)?;
    Ok(w)
}

fn rain() -> Result<World<'static>, arphysics::Error> {
    let mut w = world(1100, 0)?;
    ground(&mut w, 50.0)?;
    let wall = w.add_path(PolygonPath::rectangle(s(2.0), s(60.0))?)?;
    for x in [-41.0, 41.0] {
        w.add_body(BodyDef::polygon(wall).position(v(x, 30.0)).static_body())?;
    }
    let unit = w.add_path(PolygonPath::rectangle(s(0.8), s(0.8))?)?;
    let tri = w.add_path(PolygonPath::new(&[v(-0.5, -0.4), v(0.5, -0.4), v(0.0, 0.5)])?)?;
    for i in 0..1000 {
        let (x, y) = (f64::from(i % 50) * 1.5 - 37.0, 10.0 + f64::from(i / 50) * 1.5);
        let def = match i % 3 {
            0 => BodyDef::circle(s(0.4)),
            1 => BodyDef::polygon(unit),
            _ => BodyDef::polygon(tri),
        };
        w.add_body(def.position(v(x, y)))?;
    }
    Ok(w)
}

fn joint_grid() -> Result<World<'static>, arphysics::Error> {
    let n = 100usize;
    let mut w = world(n * n + 8, 2 * n * n)?;
    let mut ids = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let mut def =
                BodyDef::circle(s(0.4)).position(v(j as f64 - 50.0, 150.0 - i as f64)).collision_groups(1);
            if i == 0 && (j == 0 || j == n - 1) {
                def = def.static_body();
            }
            ids.push(w.add_body(def)?);
        }
    }
    let pivot = JointKind::Pivot { limits: None, motor: None };
    for i in 0..n {
        for j in 0..n {
            let a = ids[i * n + j];
            if j + 1 < n {
                w.add_joint(JointDef::new(a, v(0.5, 0.0), ids[i * n + j + 1], v(-0.5, 0.0), pivot))?;
            }
            if i + 1 < n {
                w.add_joint(JointDef::new(a, v(0.0, -0.5), ids[(i + 1) * n + j], v(0.0, 0.5), pivot))?;
            }
        }
    }
    Ok(w)
}

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

fn main() -> Result<(), arphysics::Error> {
    let filter: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    // `--narrow`: also time the narrow phase alone (large_pyramid and rain).
    // `--quick`: one sample per scene (for instruction counts under valgrind).
    let narrow = std::env::args().any(|a| a == "--narrow");
    let quick = std::env::args().any(|a| a == "--quick");
    let scenes: [(&str, Build, usize, usize); 5] = [
        ("pyramid_20", pyramid_20, 60, 15),
        ("rain", rain, 30, 7),
        ("large_pyramid", large_pyramid, 10, 5),
        ("many_pyramids", many_pyramids, 5, 5),
        ("joint_grid", joint_grid, 10, 5),
    ];
    let dt = s(1.0 / 60.0);
    for (name, build, steps, samples) in scenes {
        if !filter.is_empty() && !filter.iter().any(|f| name.contains(f.as_str())) {
            continue;
        }
        let mut w = build()?;
        for _ in 0..30 {
            w.step(dt)?;
        }
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
