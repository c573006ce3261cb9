//! A bullet hits a player: the game learns it from the world's contact begin
//! events after the step and removes both bodies then (outside the step, where
//! `&mut World` is safe), with no callbacks, shared state or handles in user
//! data. The manual's way (a `begin` handler that schedules a post-step
//! callback, "Safely removing Bodies from the World") still works and is
//! what to use when the removal must happen before the next step's hooks see
//! the bodies; `tests/post_step_queue.rs` covers it.
//!
//! The bullet is hit-tested as Box2D's bullets are: at any speed the world
//! allows (here up to 2,048 m/s, 34 m a step) it cannot pass through the
//! player between two steps, and the contact begins only when it touches.
//!
//! Run: `cargo run --example bullet_player`

use arphysics::{BodyDef, Rect, Scalar, Vector2, World, WorldBuffers, WorldDef};

/// Fires a bullet from a shooter at a player 10 m away at `speed` m/s and
/// steps until both are gone; checks that the bullet never touched its
/// shooter (it spawns 0.15 m from the shooter's surface, moving away).
fn duel(speed: f64) -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<8, 32>::new();
    let bounds = Rect::from_corners(Vector2::from_int(-400, -50), Vector2::from_int(400, 50));
    // The fastest the engine allows, so that every speed below is legal.
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    let mut world = World::new(def, buffers.storage())?;

    let shooter = world.add_body(BodyDef::circle(s(0.5)).position(Vector2::from_int(-5, 0)))?;
    let player = world.add_body(BodyDef::circle(s(0.5)).position(Vector2::from_int(5, 0)))?;
    // A bullet (continuous collision against dynamic bodies too), so that no
    // speed carries it through the player between two steps.
    let bullet = world.add_body(
        BodyDef::circle(s(0.05))
            .position(Vector2::new(s(-4.35), s(0.0)))
            .linear_velocity(Vector2::new(s(speed), s(0.0)))
            .mass(s(0.01))
            .bullet(true),
    )?;

    println!("bullet at {speed} m/s:");
    let mut hits = 0;
    for step in 1..=60 {
        world.step(s(1.0 / 60.0))?;
        // The events of this step, in pair order; copied out (a small fixed
        // array would do as well) because removing bodies needs `&mut world`.
        let begun: Vec<_> = world.contact_begin_events().iter().map(|e| (e.body_a, e.body_b)).collect();
        for (a, b) in begun {
            let pair = [a, b];
            assert!(!(pair.contains(&shooter) && pair.contains(&bullet)), "the bullet touched its shooter");
            if pair.contains(&player) && pair.contains(&bullet) {
                hits += 1;
                println!("  step {step}: player {player:?} hit by bullet {bullet:?}");
                world.remove_body(player)?;
                world.remove_body(bullet)?;
            }
        }
    }
    println!("  bodies left in the world: {}", world.body_count());
    assert_eq!(hits, 1);
    assert!(world.body(player).is_err() && world.body(bullet).is_err());
    assert!(world.body(shooter).is_ok(), "the shooter is still there");
    Ok(())
}

fn main() -> Result<(), arphysics::Error> {
    for speed in [20.0, 100.0, 400.0, 2048.0] {
        duel(speed)?;
    }
    Ok(())
}
