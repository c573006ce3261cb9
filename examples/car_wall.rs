//! A car driven into a wall: the crash and the bounce read from the world's
//! event lists after each step (no callbacks, no shared counters). The crash
//! is a contact hit event (Box2D's: the pair began touching faster than the
//! world's hit threshold, with the approach speed, point and normal); the
//! bounce is a contact end event.
//!
//! The manual's collision handler (`addCollisionHandler(CAR_LEVEL, WALL_LEVEL,
//! crash, NULL, NULL, end)`, here an `FnHandler`) still works and is the tool
//! for what must happen inside the step, e.g. `pre_solve` deciding whether a
//! pair is solved; events are for what the game does after it.
//!
//! At any speed the world allows the car is stopped at the wall (continuous
//! collision) and the crash is reported once, at the speed it hit.
//!
//! Run: `cargo run --example car_wall`

use arphysics::{BodyDef, PolygonPath, Rect, Scalar, Vector2, World, WorldBuffers, WorldDef};

/// Drives the car into the wall at `speed` m/s for 2 s.
fn drive(speed: i32) -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<8, 32>::new();
    let bounds = Rect::from_corners(Vector2::from_int(-3000, -50), Vector2::from_int(50, 50));
    // The fastest the engine allows, so that every speed below is legal.
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    let mut world = World::new(def, buffers.storage())?;
    let wall = world.add_path(PolygonPath::rectangle(s(1.0), s(10.0))?)?;
    let wall = world.add_body(BodyDef::polygon(wall).position(Vector2::from_int(10, 0)).static_body())?;
    let car_shape = world.add_path(PolygonPath::rectangle(s(4.0), s(1.5))?)?;
    let car = world.add_body(
        BodyDef::polygon(car_shape)
            .position(Vector2::from_int(0, 0))
            .linear_velocity(Vector2::from_int(speed, 0))
            .restitution(s(0.5)),
    )?;
    let is_car_and_wall = |a, b| (a, b) == (car, wall) || (a, b) == (wall, car);
    let (mut crashes, mut bounces) = (0, 0);
    println!("car at {speed} m/s:");
    for _ in 0..120 {
        world.step(s(1.0 / 60.0))?;
        for hit in world.contact_hit_events() {
            if is_car_and_wall(hit.body_a, hit.body_b) {
                crashes += 1;
                println!(
                    "  crash! the car hit the wall at {:.2} m/s, at ({:.2}, {:.2})",
                    hit.speed.to_num::<f64>(),
                    hit.point.x.to_num::<f64>(),
                    hit.point.y.to_num::<f64>()
                );
                // The approach speed is the speed the car was driven at.
                assert!((hit.speed - Scalar::from_num(speed)).abs() < s(0.01 * f64::from(speed)));
            }
        }
        for end in world.contact_end_events() {
            if is_car_and_wall(end.body_a, end.body_b) {
                bounces += 1;
                let v = world.body(car)?.linear_velocity();
                println!("  the car bounced off, now moving at {:.2} m/s", v.x.to_num::<f64>());
            }
        }
        // The car's front is 2 m ahead of its centre, the wall's face at
        // x = 9.5. A car moving less than half its core extent (0.75 m) a step
        // may end a step that far into the wall, and the contact pushes it
        // out (Box2D's rule); a faster one is swept and stopped at the face.
        assert!(world.body(car)?.position().x < s(7.5 + 0.375), "the car went into the wall");
    }
    let v = world.body(car)?.linear_velocity();
    println!("  after 2 s the car moves at {:.2} m/s (it bounced back)", v.x.to_num::<f64>());
    assert_eq!((crashes, bounces), (1, 1), "one crash, one bounce");
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
