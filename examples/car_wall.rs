//! The manual's car/wall collision handler: `crash` runs when a car first hits a
//! wall, `end` when it bounces off. Handlers are registered for a pair of collision
//! levels, here with plain functions and the other two callbacks left out, exactly
//! like `addCollisionHandler(CAR_LEVEL, WALL_LEVEL, crash, NULL, NULL, end)`.
//!
//! `crash` means touching: at any speed the world allows, the car is stopped at
//! the wall (continuous collision) and `crash` fires once, on contact.
//!
//! Run: `cargo run --example car_wall`

use std::sync::atomic::{AtomicU32, Ordering};

use arphysics::{
    Arbiter, BodyDef, CallbackContext, FnHandler, PolygonPath, Rect, Scalar, Vector2, World, WorldBuffers,
    WorldDef,
};

const CAR_LEVEL: u32 = 1;
const WALL_LEVEL: u32 = 2;

/// Called when a car first hits a wall: play a sound, mark it damaged… and
/// return true so the collision is resolved.
fn crash(arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    CRASHES.fetch_add(1, Ordering::Relaxed);
    if let Some((car, _wall)) = arbiter.bodies_by_level(CAR_LEVEL) {
        let speed = ctx.body(car).map(|b| b.linear_velocity().length()).unwrap_or_default();
        println!("crash! car {car:?} hit the wall at {:.2} m/s", speed.to_num::<f64>());
    }
    true
}

/// Called when the car bounces off the wall.
fn end(arbiter: &Arbiter, ctx: &mut CallbackContext<'_>) {
    if let Some((car, _)) = arbiter.bodies_by_level(CAR_LEVEL) {
        let v = ctx.body(car).map(|b| b.linear_velocity()).unwrap_or_default();
        println!(
            "car {car:?} bounced off, now moving at ({:.2}, {:.2}) m/s",
            v.x.to_num::<f64>(),
            v.y.to_num::<f64>()
        );
    }
}

/// `crash` calls so far (the handler is a plain function: it counts here).
static CRASHES: AtomicU32 = AtomicU32::new(0);

/// Drives the car into the wall at `speed` m/s for 2 s.
fn drive(speed: i32) -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<8, 32>::new();
    let bounds = Rect::from_corners(Vector2::from_int(-3000, -50), Vector2::from_int(50, 50));
    // The fastest the engine allows, so that every speed below is legal.
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    let mut world = World::new(def, buffers.storage())?;
    let added = world.add_collision_handler(
        CAR_LEVEL,
        WALL_LEVEL,
        FnHandler { begin: Some(crash), end: Some(end), ..FnHandler::default() },
    );
    if let Err(e) = added {
        // The manual's "handle not adding collision handler".
        eprintln!("could not add the handler: {e}");
        return Err(e);
    }
    let wall = world.add_path(PolygonPath::rectangle(s(1.0), s(10.0))?)?;
    world.add_body(
        BodyDef::polygon(wall).position(Vector2::from_int(10, 0)).static_body().collision_level(WALL_LEVEL),
    )?;
    let car_shape = world.add_path(PolygonPath::rectangle(s(4.0), s(1.5))?)?;
    let car = world.add_body(
        BodyDef::polygon(car_shape)
            .position(Vector2::from_int(0, 0))
            .linear_velocity(Vector2::from_int(speed, 0))
            .restitution(s(0.5))
            .collision_level(CAR_LEVEL),
    )?;
    CRASHES.store(0, Ordering::Relaxed);
    println!("car at {speed} m/s:");
    for _ in 0..120 {
        world.step(s(1.0 / 60.0))?;
        // The car's front is 2 m ahead of its centre, the wall's face at
        // x = 9.5. A car moving less than half its core extent (0.75 m) a step
        // may end a step that far into the wall, and the contact pushes it
        // out (Box2D's rule); a faster one is swept and stopped at the face.
        assert!(world.body(car)?.position().x < s(7.5 + 0.375), "the car went into the wall");
    }
    let v = world.body(car)?.linear_velocity();
    println!("  after 2 s the car moves at {:.2} m/s (it bounced back)", v.x.to_num::<f64>());
    assert_eq!(CRASHES.load(Ordering::Relaxed), 1, "one crash");
    assert!(v.x < Scalar::ZERO);
    Ok(())
}

fn main() -> Result<(), arphysics::Error> {
    // From a walk to the engine's speed limit (34 m a step at 2,048 m/s).
    for speed in [8, 60, 400, 2048] {
        drive(speed)?;
    }
    Ok(())
}
