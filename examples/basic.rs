//! The manual's "Setting up a new physics simulation": a 320 × 240 world, a 5 kg
//! ball of radius 5 at (50, 50), gravity (0, −9.81). Steps it for 2 s at 60 Hz and
//! prints the trajectory beside the closed form of semi-implicit Euler with the
//! world's 4 sub-steps of h = dt/4 (M = 4n sub-steps after n steps),
//! y = y0 + g·h²·M(M+1)/2, and beside the exact parabola y0 + g·t²/2.
//!
//! Run: `cargo run --example basic`

use arphysics::{BodyDef, GravityForceGenerator, Scalar, Vector2, World, WorldBuffers, WorldDef};

fn main() -> Result<(), arphysics::Error> {
    // The manual creates a brute-force index and hands it to the world; here the
    // world owns its storage (static buffers: no allocator needed).
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world =
        World::new(WorldDef::new(Scalar::from_num(320), Scalar::from_num(240)), buffers.storage())?;

    let ball = world.add_body(
        BodyDef::circle(Scalar::from_num(5)).position(Vector2::from_int(50, 50)).mass(Scalar::from_num(5)),
    )?;
    world.add_force_generator(GravityForceGenerator::new(Vector2::try_from_f64(0.0, -9.81, "gravity")?))?;

    let dt = Scalar::from_num(1) / Scalar::from_num(60);
    let substeps = world.def().substeps;
    let (g, step) = (-9.81_f64, 1.0_f64 / 60.0);
    let h = step / f64::from(substeps);
    println!(
        "{:>5} {:>7} {:>14} {:>16} {:>10} {:>14}",
        "step", "t (s)", "y arphysics", "y closed form", "|error|", "y parabola"
    );
    let mut worst = 0.0_f64;
    for n in 1..=120u32 {
        world.step(dt)?;
        let t = f64::from(n) * step;
        let m = f64::from(n * substeps);
        let closed_form = 50.0 + g * h * h * m * (m + 1.0) / 2.0;
        let parabola = 50.0 + g * t * t / 2.0;
        let (_, y) = world.body(ball)?.position().to_f64();
        worst = worst.max((y - closed_form).abs());
        if n % 10 == 0 {
            println!(
                "{n:>5} {t:>7.3} {y:>14.9} {closed_form:>16.9} {:>10.2e} {parabola:>14.9}",
                (y - closed_form).abs()
            );
        }
    }
    println!(
        "largest error against the closed form over 2 s: {worst:.2e} m (semi-implicit Euler runs {:.4} m \
         below the exact parabola after 2 s); state hash {:#018x}",
        (50.0 + g * 2.0 * 2.0 / 2.0) - world.body(ball)?.position().to_f64().1,
        world.state_hash()
    );
    Ok(())
}
