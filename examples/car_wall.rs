//! The manual's car/wall collision handler: `crash` runs when a car first hits a
//! wall, `end` when it bounces off. Handlers are registered for a pair of collision
//! levels, here with plain functions and the other two callbacks left out, exactly
//! like `addCollisionHandler(CAR_LEVEL, WALL_LEVEL, crash, NULL, NULL, end)`.
//!
//! Run: `cargo run --example car_wall`

use arphysics::{
    Arbiter, BodyDef, CallbackContext, FnHandler, PolygonPath, Rect, Scalar, Vector2, World, WorldBuffers,
    WorldDef,
};

const CAR_LEVEL: u32 = 1;
const WALL_LEVEL: u32 = 2;

/// Called when a car first hits a wall: play a sound, mark it damaged… and
/// return true so the collision is resolved.
fn crash(arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
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

fn main() -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<8, 32>::new();
    let bounds = Rect::from_corners(Vector2::from_int(-50, -50), Vector2::from_int(50, 50));
    let mut world = World::new(WorldDef::with_bounds(bounds), buffers.storage())?;

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
            .linear_velocity(Vector2::from_int(8, 0))
            .restitution(s(0.5))
            .collision_level(CAR_LEVEL),
    )?;

    for _ in 0..120 {
        world.step(s(1.0 / 60.0))?;
    }
    let v = world.body(car)?.linear_velocity();
    println!("after 2 s the car moves at {:.2} m/s (it bounced back)", v.x.to_num::<f64>());
    Ok(())
}
