//! The manual's "Setting up a new physics simulation": a 320 × 240 world, a 5 kg
//! ball of radius 5 at (50, 50), gravity (0, −9.81). Steps it for 2 s at 60 Hz and
//! prints the trajectory beside the closed form of semi-implicit Euler,
//! y_n = y0 + g·dt²·n(n+1)/2.
//!
//! Run: `cargo run --example basic`

use arphysics::{BodyDef, GravityForceGenerator, Scalar, Vector2, World, WorldBuffers, WorldDef};

fn main() -> Result<(), arphysics::Error> {
    // The manual creates a brute-force index and hands it to the world; here the
    // world owns its storage (static buffers: no allocator needed).
    let mut buffers = WorldBuffers::<16>::new();
    let mut world = World::new(
        WorldDef::new(Scalar::from_num(320), Scalar::from_num(240)),
        buffers.storage(),
    )?;

    let ball = world.add_body(
        BodyDef::circle(Scalar::from_num(5))
            .position(Vector2::from_int(50, 50))
            .mass(Scalar::from_num(5)),
    )?;
    world.add_force_generator(GravityForceGenerator::new(Vector2::try_from_f64(
        0.0, -9.81, "gravity",
    )?))?;

    let dt = Scalar::from_num(1) / Scalar::from_num(60);
    let (g, h) = (-9.81_f64, 1.0_f64 / 60.0);
    println!(
        "{:>5} {:>8} {:>14} {:>14} {:>10}",
        "step", "t (s)", "y arphysics", "y analytic", "|error|"
    );
    let mut worst = 0.0_f64;
    for n in 1..=120u32 {
        world.step(dt)?;
        let nf = f64::from(n);
        let analytic = 50.0 + g * h * h * nf * (nf + 1.0) / 2.0;
        let (_, y) = world.body(ball)?.position().to_f64();
        worst = worst.max((y - analytic).abs());
        if n % 10 == 0 {
            println!(
                "{n:>5} {:>8.3} {y:>14.9} {analytic:>14.9} {:>10.2e}",
                nf * h,
                (y - analytic).abs()
            );
        }
    }
    println!(
        "largest error over 2 s: {worst:.2e} m; state hash {:#018x}",
        world.state_hash()
    );
    Ok(())
}
