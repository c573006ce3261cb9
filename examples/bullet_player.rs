//! The manual's "Safely removing Bodies from the World": when a bullet hits a
//! player, `bullet_hit` marks the player dead, schedules a post-step callback
//! keyed by the player, and returns false so the collision is not resolved. After
//! the step, `remove_dead_player` removes both bodies. A body can never be
//! removed during a step: callbacks only get read access and the post-step queue.
//!
//! The bullet is hit-tested as Box2D's bullets are: at any speed the world
//! allows (here up to 2,048 m/s, 34 m a step) it cannot pass through the player
//! between two steps, and `begin` fires only when it touches.
//!
//! Run: `cargo run --example bullet_player`

use arphysics::{
    Arbiter, BodyDef, BodyHandle, CallbackContext, FnHandler, Rect, Scalar, Vector2, World, WorldBuffers,
    WorldDef,
};

const PLAYER_LEVEL: u32 = 1;
const BULLET_LEVEL: u32 = 2;

fn bullet_hit(arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    // Which body is the player and which the bullet, from their levels.
    let Some((player, bullet)) = arbiter.bodies_by_level(PLAYER_LEVEL) else { return true };
    println!("player {player:?} hit by bullet {bullet:?}");
    // Remove them after the step; the key is the player's handle as bits.
    if let Err(e) = ctx.add_post_step_callback(remove_dead_player, player.to_bits()) {
        eprintln!("could not schedule the removal: {e}");
    }
    // No point resolving a collision whose bodies are about to go.
    false
}

/// The game's side: which bullet hit which player. A real game keeps this in its
/// own entity store and puts an entity id in each body's user data; here a player's
/// user data holds the bullet that hit it (slot index and generation: user data is
/// in the state hash, so it holds no world tag), so the key is all the callback
/// needs. A key whose player has gone since decodes to a stale handle: the world
/// answers `StaleHandle` and nothing is removed.
fn remove_dead_player(world: &mut World<'_>, key: u64) {
    let player = BodyHandle::from_bits(key);
    let bullet = world
        .body(player)
        .map(|b| b.user_data())
        .map(|d| world.handle_from_parts((d >> 32) as u32, d as u32));
    let removed_player = world.remove_body(player).is_ok();
    let removed_bullet = bullet.map(|b| world.remove_body(b).is_ok()).unwrap_or(false);
    println!("post-step: removed player {removed_player}, bullet {removed_bullet}");
}

/// Fires a bullet from a shooter at a player 10 m away at `speed` m/s and
/// steps until both are gone; checks that the bullet never began with its
/// shooter (it spawns 0.15 m from the shooter's surface, moving away).
fn duel(speed: f64) -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<8, 32>::new();
    let bounds = Rect::from_corners(Vector2::from_int(-400, -50), Vector2::from_int(400, 50));
    // The fastest the engine allows, so that every speed below is legal.
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    let mut world = World::new(def, buffers.storage())?;
    world.add_collision_handler(
        PLAYER_LEVEL,
        BULLET_LEVEL,
        FnHandler { begin: Some(bullet_hit), ..FnHandler::default() },
    )?;

    let shooter = world.add_body(BodyDef::circle(s(0.5)).position(Vector2::from_int(-5, 0)))?;
    let player = world
        .add_body(BodyDef::circle(s(0.5)).position(Vector2::from_int(5, 0)).collision_level(PLAYER_LEVEL))?;
    // A bullet (continuous collision against dynamic bodies too), so that no
    // speed carries it through the player between two steps.
    let bullet = world.add_body(
        BodyDef::circle(s(0.05))
            .position(Vector2::new(s(-4.35), s(0.0)))
            .linear_velocity(Vector2::new(s(speed), s(0.0)))
            .mass(s(0.01))
            .bullet(true)
            .collision_level(BULLET_LEVEL),
    )?;
    // The game remembers which bullet is flying at the player.
    world.body_mut(player)?.set_user_data((u64::from(bullet.index()) << 32) | u64::from(bullet.generation()));

    println!("bullet at {speed} m/s:");
    for step in 1..=60 {
        let report = world.step(s(1.0 / 60.0))?;
        // `begin` means touching: the bullet never begins with its shooter.
        let with_shooter = world.arbiters().any(|a| {
            let pair = [a.body_a(), a.body_b()];
            pair.contains(&shooter) && pair.contains(&bullet)
        });
        assert!(!with_shooter, "the bullet touched its shooter");
        if report.post_step_callbacks > 0 {
            println!("  step {step}: {} post-step callback(s) ran", report.post_step_callbacks);
        }
    }
    println!("  bodies left in the world: {}", world.body_count());
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
