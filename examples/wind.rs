//! The manual's custom force generator: wind that blows only inside an area.
//!
//! `AreaWind` implements [`ForceGenerator`]: `applies_to` (the manual's
//! `shouldApplyToBody`) picks the bodies whose centre is inside the area, and
//! `apply` (`applyToBody`) pushes them. Six crates float in zero gravity, one per
//! lane so they never touch; the wind blows to the right in the band
//! −10 m ≤ x ≤ 10 m. The crates that start in the band accelerate until they leave
//! it and then coast; a crate that drifts into the band from the left is caught by
//! it; the crates to the right of the band never move at all.
//!
//! Run: `cargo run --example wind`

use arphysics::{
    Body, BodyDef, BodyHandle, ForceGenerator, Generator, PolygonPath, Rect, Scalar, Vector2, World,
    WorldBuffers, WorldDef,
};

/// Wind inside `area`: a constant `force` (N) on every dynamic body whose centre
/// is in the area. `pushes` counts the (body, step) pairs it pushed.
struct AreaWind {
    area: Rect,
    force: Vector2,
    pushes: u32,
}

impl ForceGenerator for AreaWind {
    fn applies_to(&self, _: BodyHandle, body: &Body) -> bool {
        self.area.contains(body.position())
    }

    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        self.pushes += 1;
        body.apply_force(self.force, dt);
    }
}

fn main() -> Result<(), arphysics::Error> {
    let band = Rect::from_corners(Vector2::from_int(-10, -50), Vector2::from_int(10, 50));
    let mut wind = AreaWind {
        area: band,
        force: Vector2::from_int(4, 0), // 4 N to the right: 4 m/s² on a 1 kg crate
        pushes: 0,
    };
    let dt = Scalar::ONE / 60;
    let mut buffers = WorldBuffers::<8, 32>::new();
    {
        let bounds = Rect::from_corners(Vector2::from_int(-100, -50), Vector2::from_int(100, 50));
        let mut world = World::new(WorldDef::with_bounds(bounds), buffers.storage())?;
        // No gravity: only the wind moves anything.
        world.add_force_generator(Generator::borrowed(&mut wind))?;
        let crate_path = world.add_path(PolygonPath::rectangle(Scalar::ONE, Scalar::ONE)?)?;
        // (start x, initial velocity x): one crate drifts slowly towards the band.
        let starts = [(-30, 3), (-5, 0), (0, 0), (8, 0), (20, 0), (35, 0)];
        let mut crates = Vec::new();
        for (lane, &(x, vx)) in starts.iter().enumerate() {
            let y = 3 * lane as i32 - 8;
            let def = BodyDef::polygon(crate_path)
                .position(Vector2::from_int(x, y))
                .linear_velocity(Vector2::from_int(vx, 0));
            crates.push(world.add_body(def)?);
        }
        let start: Vec<Vector2> =
            crates.iter().map(|&c| world.body(c).map(Body::position)).collect::<Result<_, _>>()?;

        let show = |world: &World<'_>, t: u32| -> Result<(), arphysics::Error> {
            let mut line = format!("{t:>3} s ");
            for &c in &crates {
                let b = world.body(c)?;
                let inside = band.contains(b.position());
                line.push_str(&format!(
                    " {:>7.2}{} {:>5.2}",
                    b.position().x.to_num::<f64>(),
                    if inside { '*' } else { ' ' },
                    b.linear_velocity().x.to_num::<f64>()
                ));
            }
            println!("{line}");
            Ok(())
        };
        println!("each crate's x (m) and speed (m/s); * = in the wind, −10 m ≤ x ≤ 10 m");
        println!(
            "      {}",
            (0..crates.len()).map(|i| format!("{:>14}", format!("crate {i}"))).collect::<String>()
        );
        show(&world, 0)?;
        for second in 1..=8 {
            for _ in 0..60 {
                world.step(dt)?;
            }
            show(&world, second)?;
        }
        for (i, (&c, &p0)) in crates.iter().zip(&start).enumerate() {
            let b = world.body(c)?;
            let moved = (b.position() - p0).x.to_num::<f64>();
            let verdict = if b.position() == p0 {
                "never moved: the wind never touched it (bit-identical position)".to_string()
            } else {
                format!("moved {moved:+.2} m")
            };
            println!("crate {i} (start x = {:>3} m): {verdict}", starts[i].0);
        }
    }
    // The world is gone; the game's generator is still here, with its count.
    println!(
        "the wind pushed {} times in 480 steps (a push = one crate in the band for one step)",
        wind.pushes
    );
    Ok(())
}
