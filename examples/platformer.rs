//! A small platformer, played by a scripted controller: a player box with
//! fixed rotation runs, jumps through a one-way platform from below and lands
//! on it, rides a moving (kinematic) platform and collects three coins
//! (sensors). Everything the game learns from the world it reads after each
//! step from the event lists: the ground check from contact begin and end
//! events, the coins from sensor begin events. The only callback is the
//! one-way platform's `begin`, which must decide inside the step.
//!
//! The run checks itself: every coin collected once, the player's angle
//! exactly 0 throughout, carried by the moving platform, never jumping in the
//! air, and done within 30 s of game time.
//!
//! Run: `cargo run --example platformer`

use arphysics::{
    Arbiter, BodyDef, BodyHandle, CallbackContext, Capacities, FnHandler, GravityForceGenerator, PolygonPath,
    QueryFilter, Rect, Rot, Scalar, Vector2, World, WorldDef,
};

/// Collision levels: the player, and the one-way platform.
const PLAYER: u32 = 1;
const ONE_WAY: u32 = 2;
/// The player's half extents (m).
const HALF_W: f64 = 0.4;
const HALF_H: f64 = 0.8;
/// The one-way platform's centre height and half thickness (m).
const ONE_WAY_Y: f64 = 2.5;
const ONE_WAY_HALF_H: f64 = 0.2;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// The one-way platform's `begin`: the pair is solved only when the player
/// arrives from above (its feet above the platform's top, less a little
/// tolerance); otherwise it is ignored until the two separate, so the player
/// passes through from below or from the side.
fn one_way_begin(arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    let (Some(a), Some(b)) = (ctx.body(arbiter.body_a()), ctx.body(arbiter.body_b())) else {
        return true;
    };
    let (player, platform) = if a.collision_level() == PLAYER { (a, b) } else { (b, a) };
    let feet = player.position().y - s(HALF_H);
    let top = platform.position().y + s(ONE_WAY_HALF_H);
    feet >= top - s(0.05) && player.linear_velocity().y <= s(0.0)
}

/// The moving platform's centre x after `step` steps at 60 Hz: a triangle
/// wave between 5 m and 11 m at 3 m/s (a period of 240 steps), from 11 m.
fn mover_x(step: u32) -> Scalar {
    let phase = step % 240;
    let along = if phase < 120 { phase } else { 240 - phase };
    s(11.0) - Scalar::from_int(along as i32) / 20
}

/// What the controller is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Plan {
    /// Walk under the one-way platform and jump up through it.
    ToOneWay,
    /// On the one-way platform: wait at its right edge for the moving one.
    WaitForMover,
    /// In the air towards the moving platform.
    JumpToMover,
    /// Standing still on the moving platform, carried by it.
    Ride,
    /// Off the right end of the moving platform, then along the ground.
    ToLastCoin,
    Done,
}

fn main() -> Result<(), arphysics::Error> {
    let dt = s(1.0 / 60.0);
    let bounds = Rect::from_corners(v(-40.0, -20.0), v(40.0, 40.0));
    let mut world = World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(16))?;
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -20.0)))?;

    let ground_path = world.add_path(PolygonPath::rectangle(s(60.0), s(1.0))?)?;
    let ground = world
        .add_body(BodyDef::polygon(ground_path).position(v(0.0, -0.5)).static_body().friction(s(0.8)))?;
    let one_way_path = world.add_path(PolygonPath::rectangle(s(4.0), s(2.0 * ONE_WAY_HALF_H))?)?;
    let one_way = world.add_body(
        BodyDef::polygon(one_way_path)
            .position(v(0.0, ONE_WAY_Y))
            .static_body()
            .friction(s(0.8))
            .collision_level(ONE_WAY),
    )?;
    let mover_path = world.add_path(PolygonPath::rectangle(s(3.0), s(0.4))?)?;
    let mover =
        world.add_body(BodyDef::polygon(mover_path).position(v(11.0, 4.5)).kinematic().friction(s(0.8)))?;
    let player_path = world.add_path(PolygonPath::rectangle(s(2.0 * HALF_W), s(2.0 * HALF_H))?)?;
    let player = world.add_body(
        BodyDef::polygon(player_path)
            .position(v(-8.0, HALF_H))
            .density(s(1.0))
            .friction(s(0.8))
            .fixed_rotation(true)
            .collision_level(PLAYER),
    )?;
    world.add_collision_handler(
        PLAYER,
        ONE_WAY,
        FnHandler { begin: Some(one_way_begin), ..FnHandler::default() },
    )?;
    // Coins: static sensors, on the one-way platform, in the moving
    // platform's path and on the ground beyond.
    let coin_at = [v(0.0, 3.5), v(8.0, 5.6), v(16.0, 0.6)];
    let mut coins = [BodyHandle::default(); 3];
    for (c, &p) in coins.iter_mut().zip(&coin_at) {
        *c = world.add_body(BodyDef::circle(s(0.3)).position(p).static_body().sensor())?;
    }

    let mut collected = [0u32; 3];
    // The bodies the player stands on: contacts whose normal points up into it.
    let mut supports: Vec<BodyHandle> = Vec::new();
    let mut plan = Plan::ToOneWay;
    let mut jumps = 0;
    let (mut ride_from, mut ride_distance) = (None, s(0.0));
    let mut was_below_one_way = false;
    let mut passed_one_way_from_below = false;
    let mut step = 0u32;
    while plan != Plan::Done {
        step += 1;
        if step > 1800 {
            panic!("the controller did not finish in 30 s: stuck in {plan:?}");
        }
        // The moving platform reaches its next pose at the end of this step.
        world.set_target_transform(mover, Vector2::new(mover_x(step), s(4.5)), Rot::IDENTITY, dt)?;

        let p = *world.body(player)?;
        let (pos, vel) = (p.position(), p.linear_velocity());
        let grounded = !supports.is_empty();
        let on = |h: BodyHandle| supports.contains(&h);
        let mover_pos = world.body(mover)?.position();
        let mover_vx = world.body(mover)?.linear_velocity().x;
        // The controller: a horizontal speed (None: no input, friction rules)
        // and whether to jump, with the speed a jump of `h` metres needs.
        let jump_speed = |h: f64| s((2.0 * 20.0 * h).sqrt());
        let (mut run, mut jump) = (None, None);
        match plan {
            Plan::ToOneWay => {
                if grounded && on(ground) && pos.x > s(-0.3) {
                    jump = Some(jump_speed(3.4));
                    run = Some(s(0.0));
                } else if on(one_way) {
                    plan = Plan::WaitForMover;
                } else if grounded {
                    run = Some(s(4.0));
                }
            }
            Plan::WaitForMover => {
                let goal = s(1.5);
                run = Some(((goal - pos.x) * 4).clamp(s(-3.0), s(3.0)));
                // Jump when the moving platform heads left and will be near.
                if grounded && pos.x > s(1.3) && mover_vx < s(0.0) && mover_pos.x < s(8.5) {
                    jump = Some(jump_speed(3.0));
                    plan = Plan::JumpToMover;
                }
            }
            Plan::JumpToMover => {
                // Air control: steer over the moving platform's centre.
                run = Some(((mover_pos.x - pos.x) * 3 + mover_vx).clamp(s(-6.0), s(6.0)));
                if on(mover) {
                    plan = Plan::Ride;
                    ride_from = Some(pos.x);
                }
            }
            Plan::Ride => {
                if let Some(x0) = ride_from {
                    ride_distance = ride_distance.max((pos.x - x0).abs());
                }
                if collected[1] > 0 && mover_vx > s(0.0) && mover_pos.x > s(10.0) && grounded {
                    jump = Some(jump_speed(1.0));
                    run = Some(s(5.0));
                    plan = Plan::ToLastCoin;
                }
            }
            Plan::ToLastCoin => {
                run = Some(s(5.0));
                if collected[2] > 0 {
                    plan = Plan::Done;
                }
            }
            Plan::Done => {}
        }
        if jump.is_some() {
            // The event-based ground check against the geometry: a ray down
            // from either bottom corner (skipping the player and the coins)
            // meets a surface within 5 cm of its feet.
            let filter = QueryFilter::default().exclude(player).skip_sensors(true);
            let mut below = false;
            for dx in [-(HALF_W - 0.05), HALF_W - 0.05] {
                let from = pos + v(dx, 0.0);
                below |= world.ray_cast(from, from - v(0.0, HALF_H + 0.05), filter)?.is_some();
            }
            assert!(grounded && below, "the controller jumped in the air at step {step}");
            jumps += 1;
        }
        if run.is_some() || jump.is_some() {
            let body = world.body_mut(player)?;
            let vx = run.unwrap_or(vel.x);
            let vy = jump.unwrap_or(vel.y);
            body.set_linear_velocity(Vector2::new(vx, vy));
        }
        let feet = pos.y - s(HALF_H);
        if feet < s(ONE_WAY_Y - ONE_WAY_HALF_H) && pos.x.abs() < s(2.0) {
            was_below_one_way = true;
        }

        world.step(dt)?;

        for e in world.contact_begin_events() {
            // The normal points from body A to body B: up into the player
            // when the player is B, down out of it when the player is A.
            let up =
                (e.body_b == player && e.normal.y > s(0.7)) || (e.body_a == player && e.normal.y < s(-0.7));
            let other = if e.body_a == player { e.body_b } else { e.body_a };
            if up && (e.body_a == player || e.body_b == player) && !supports.contains(&other) {
                supports.push(other);
                if other == one_way && was_below_one_way {
                    passed_one_way_from_below = true;
                }
            }
        }
        for e in world.contact_end_events() {
            supports.retain(|&h| {
                !((e.body_a == player && e.body_b == h) || (e.body_b == player && e.body_a == h))
            });
        }
        for e in world.sensor_begin_events() {
            if e.visitor == player {
                if let Some(k) = coins.iter().position(|&c| c == e.sensor) {
                    collected[k] += 1;
                    let x = world.body(player)?.position().x.to_num::<f64>();
                    println!("step {step:4}: coin {k} collected at x = {x:.2}");
                }
            }
        }
        assert_eq!(world.body(player)?.angle(), s(0.0), "fixed rotation keeps the player upright");
    }
    let end = world.body(player)?.position();
    println!(
        "done in {step} steps ({:.1} s): {jumps} jumps, ridden {:.2} m on the moving platform, player at ({:.2}, {:.2})",
        f64::from(step) / 60.0,
        ride_distance.to_num::<f64>(),
        end.x.to_num::<f64>(),
        end.y.to_num::<f64>()
    );
    assert_eq!(collected, [1, 1, 1], "every coin collected exactly once");
    assert!(passed_one_way_from_below, "the player jumped up through the one-way platform");
    assert!(ride_distance > s(2.0), "the moving platform carried the player");
    Ok(())
}
