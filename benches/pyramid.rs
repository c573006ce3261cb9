//! Benchmark: the 20-row pyramid (210 boxes of 1 m on a static ground), stepped at
//! 1/60 s with gravity (0, −10). Reports milliseconds per step over samples of 60
//! steps each, after a warm-up second, as median, minimum and maximum: on a shared
//! machine the median is the figure to quote.
//!
//! Run: `cargo bench --bench pyramid`

use std::time::Instant;

use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World, WorldDef,
};

fn pyramid(rows: u32) -> Result<World<'static>, arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let bounds = Rect::from_corners(Vector2::from_int(-500, -100), Vector2::from_int(500, 900));
    let n = (rows * (rows + 1) / 2 + 1) as usize;
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(n))?;
    let ground = w.add_path(PolygonPath::rectangle(s(200.0), s(2.0))?)?;
    w.add_body(BodyDef::polygon(ground).position(Vector2::new(s(0.0), s(-1.0))).static_body())?;
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    for row in 0..rows {
        let count = rows - row;
        for j in 0..count {
            let x = f64::from(j) - f64::from(count) * 0.5 + 0.5;
            let y = 0.5 + f64::from(row);
            w.add_body(BodyDef::polygon(unit).position(Vector2::new(s(x), s(y))))?;
        }
    }
    w.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-10.0))))?;
    Ok(w)
}

fn main() -> Result<(), arphysics::Error> {
    let dt = Scalar::from_num(1) / Scalar::from_num(60);
    let mut world = pyramid(20)?;
    for _ in 0..60 {
        world.step(dt)?;
    }
    let mut samples = Vec::new();
    for _ in 0..15 {
        let t = Instant::now();
        for _ in 0..60 {
            world.step(dt)?;
        }
        samples.push(t.elapsed().as_secs_f64() * 1000.0 / 60.0);
    }
    samples.sort_by(f64::total_cmp);
    let median = samples[samples.len() / 2];
    println!(
        "pyramid_20 ({} bodies, {} arbiters): median {median:.3} ms/step, min {:.3}, max {:.3} ({} samples of 60 steps)",
        world.body_count(),
        world.arbiters().count(),
        samples[0],
        samples[samples.len() - 1],
        samples.len()
    );
    Ok(())
}
