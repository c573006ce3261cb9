//! Issue 17: contacts that are real. Contact points only within the constant
//! speculative distance (no ghost hits from fast bodies passing beside
//! others), `begin` only for pairs that touch, and continuous collision so
//! that nothing tunnels at the speeds the world allows.

use arphysics::limits::SPECULATIVE_DISTANCE;
use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;

/// A world without gravity whose speed limit is the engine's largest (2,048
/// m/s), on a 1,200 m square.
fn world(bodies: usize) -> World<'static> {
    let bounds = Rect::from_corners(v(-600.0, -600.0), v(600.0, 600.0));
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    World::with_capacities(def, Capacities::for_bodies(bodies)).expect("world")
}

/// True when the pair has begun: an arbiter past `begin` (resolved or ignored).
fn begun(w: &World<'_>, a: BodyHandle, b: BodyHandle) -> bool {
    w.arbiters().any(|arb| {
        let pair = (arb.body_a() == a && arb.body_b() == b) || (arb.body_a() == b && arb.body_b() == a);
        pair && matches!(arb.state(), ArbiterState::Contact | ArbiterState::Ignoring)
    })
}

/// A 0.05 m circle flying along +x at `speed` past a resting 0.5 m circle at
/// the origin, its path `gap` from the target's surface, starting `phase` of a
/// step's travel further back. Returns (heading change in degrees, whether the
/// pair ever began, the smallest surface distance seen at a step's end).
fn fly_past(speed: f64, gap: f64, phase: f64, target: BodyType) -> (f64, bool, f64) {
    let mut w = world(4);
    let t = w.add_body(BodyDef::circle(s(0.5)).body_type(target).friction(s(0.6))).expect("target");
    let y = 0.5 + 0.05 + gap;
    // Start 40 m back, or two steps' travel back at high speed, plus the phase.
    let back = 40.0_f64.max(2.0 * speed * DT) + phase * speed * DT;
    // A bullet, so that it is swept against the dynamic target too.
    let def = BodyDef::circle(s(0.05)).position(v(-back, y)).linear_velocity(v(speed, 0.0)).bullet(true);
    let bullet = w.add_body(def).expect("bullet");
    let mut ever = false;
    let mut closest = f64::INFINITY;
    let steps = ((2.0 * back) / (speed * DT)).ceil() as usize + 2;
    for _ in 0..steps {
        w.step(s(DT)).expect("step");
        ever |= begun(&w, t, bullet);
        let (bx, by) = w.body(bullet).expect("bullet").position().to_f64();
        let (tx, ty) = w.body(t).expect("target").position().to_f64();
        closest = closest.min((bx - tx).hypot(by - ty) - 0.55);
    }
    let (vx, vy) = w.body(bullet).expect("bullet").linear_velocity().to_f64();
    (vy.atan2(vx).to_degrees().abs(), ever, closest)
}

#[test]
fn a_fast_body_passing_beside_another_is_not_deflected_and_never_begins() {
    let mut worst: f64 = 0.0;
    for target in [BodyType::Static, BodyType::Dynamic] {
        for speed in [30.0, 60.0, 100.0, 150.0, 200.0, 300.0, 400.0] {
            for gap in [0.05, 0.25, 0.95, 2.45, 5.0] {
                for phase in [0.0, 0.25, 0.5, 0.75] {
                    let (turn, ever, closest) = fly_past(speed, gap, phase, target);
                    assert!(closest > SPECULATIVE_DISTANCE.to_num::<f64>(), "the pair came within reach");
                    assert!(
                        turn <= 1.0,
                        "{target:?} target, {speed} m/s, gap {gap} m, phase {phase}: turned {turn:.2}°"
                    );
                    assert!(!ever, "{target:?} target, {speed} m/s, gap {gap} m, phase {phase}: begin fired");
                    worst = worst.max(turn);
                }
            }
        }
    }
    println!("largest heading change of a pair that never touched: {worst:.3e}°");
}

#[test]
fn a_fast_body_aimed_at_another_hits_it() {
    // The same flight with the path through the target: it must be stopped or
    // turned (the test above could fail), at every speed.
    for target in [BodyType::Static, BodyType::Dynamic] {
        for speed in [30.0, 400.0] {
            let (turn, ever, _) = fly_past(speed, -0.3, 0.5, target);
            assert!(ever, "{target:?}, {speed} m/s: the hit did not begin");
            assert!(turn > 1.0, "{target:?}, {speed} m/s: not deflected ({turn:.2}°)");
        }
    }
}

#[test]
fn a_bullet_leaving_its_shooter_never_begins_with_it() {
    // The manual's bullet pattern: spawned 0.15 m from the shooter's surface,
    // moving away at 20 m/s (and at 400 m/s).
    for speed in [20.0, 400.0] {
        let mut w = world(4);
        let shooter = w.add_body(BodyDef::circle(s(0.5))).expect("shooter");
        let bullet = w
            .add_body(
                BodyDef::circle(s(0.05)).position(v(0.7, 0.0)).linear_velocity(v(speed, 0.0)).bullet(true),
            )
            .expect("bullet");
        for _ in 0..30 {
            w.step(s(DT)).expect("step");
            assert!(!begun(&w, shooter, bullet), "{speed} m/s: the bullet began with its shooter");
        }
        let (vx, vy) = w.body(bullet).expect("bullet").linear_velocity().to_f64();
        assert_eq!((vx, vy), (speed, 0.0), "the bullet flew on untouched");
    }
}

#[test]
fn begin_fires_only_within_the_speculative_distance() {
    // A box walking at 1.5–12 m/s towards a coin (a circle the game ignores in
    // `begin`): the pair begins on the first step that starts with the shapes
    // within the speculative distance, never earlier.
    fn ignore(_: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
        false
    }
    for speed in [1.5, 5.0, 12.0] {
        let mut w = world(4);
        w.add_collision_handler(1, 2, FnHandler { begin: Some(ignore), ..FnHandler::default() })
            .expect("handler");
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
        let coin = w
            .add_body(BodyDef::circle(s(0.25)).position(v(3.0, 0.0)).static_body().collision_level(2))
            .expect("coin");
        let walker = w
            .add_body(
                BodyDef::polygon(unit)
                    .position(v(0.0, 0.0))
                    .linear_velocity(v(speed, 0.0))
                    .collision_level(1),
            )
            .expect("walker");
        let mut began_at = None;
        for step in 0..120 {
            let before = w.body(walker).expect("walker").position().x.to_num::<f64>();
            w.step(s(DT)).expect("step");
            if begun(&w, walker, coin) {
                // Surface gap at the start of the step: coin's left edge 2.75.
                began_at = Some((step, 2.75 - (before + 0.5)));
                break;
            }
        }
        let (step, gap) = began_at.expect("the walker reached the coin");
        assert!(
            gap <= SPECULATIVE_DISTANCE.to_num::<f64>() + 1e-9,
            "{speed} m/s: began at step {step} with the coin {gap:.4} m away"
        );
    }
}

/// A projectile (`shape`: 0.05 m circle or 0.05 m box) fired at 2,048 m/s at
/// `angle` degrees into a thin wall (0.1 m × 4 m) 30 m ahead, its normal
/// `tilt` degrees off the path; the wall static, or dynamic and the projectile a bullet. Returns the
/// projectile's largest signed depth past the wall's near face, along the
/// path, measured in the wall's frame while beside the wall's face, over 40
/// steps (more than 0.1 m means its centre went past the far face).
fn fire_at_wall(angle: f64, tilt: f64, polygon: bool, dynamic_wall: bool) -> f64 {
    let mut w = world(4);
    let (c, sn) = (angle.to_radians().cos(), angle.to_radians().sin());
    let wall_path = w.add_path(PolygonPath::rectangle(s(0.1), s(4.0)).expect("wall")).expect("path");
    // The wall centred 30 m ahead, its normal (its local x) `tilt` off the path.
    let turn = (angle + tilt).to_radians();
    let mut def = BodyDef::polygon(wall_path).position(v(30.0 * c, 30.0 * sn)).angle(s(turn));
    def = if dynamic_wall { def.mass(s(20.0)) } else { def.static_body() };
    let wall = w.add_body(def).expect("wall");
    let shape = if polygon {
        let p = w.add_path(PolygonPath::rectangle(s(0.05), s(0.05)).expect("bullet")).expect("path");
        BodyDef::polygon(p)
    } else {
        BodyDef::circle(s(0.025))
    };
    // 0.2 kg: a 20 kg wall takes about 20 m/s from it.
    let bullet = w
        .add_body(shape.linear_velocity(v(2048.0 * c, 2048.0 * sn)).bullet(dynamic_wall).mass(s(0.2)))
        .expect("bullet");
    let mut deepest = f64::NEG_INFINITY;
    for _ in 0..40 {
        w.step(s(DT)).expect("step");
        let b = w.body(bullet).expect("bullet").position();
        let wb = w.body(wall).expect("wall");
        let local = wb.transform().apply_inv(b);
        // Near face at local x = −0.05; depth past it along the wall normal,
        // counted while the projectile is beside the wall's face (one that
        // glances off and slides past its end goes round it, not through).
        if local.y.abs() <= s(2.05) {
            deepest = deepest.max(local.x.to_num::<f64>() + 0.05);
        }
    }
    deepest
}

/// Fires at the wall from `angles` directions (degrees, `step` apart from
/// `first`) at each tilt, circle and box projectiles; asserts none went
/// through and returns the deepest any got past the near face.
fn fire_all(count: u32, step: f64, first: f64, tilts: &[f64], dynamic_wall: bool) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for k in 0..count {
        let angle = step * f64::from(k) + first;
        for &tilt in tilts {
            for polygon in [false, true] {
                let depth = fire_at_wall(angle, tilt, polygon, dynamic_wall);
                let what = format!("angle {angle}°, tilt {tilt}°, polygon {polygon}");
                assert!(depth < 0.1, "{what}: {depth:.3} m past the near face");
                worst = worst.max(depth);
            }
        }
    }
    worst
}

#[test]
fn nothing_tunnels_through_a_thin_static_wall_at_any_angle() {
    let worst = fire_all(48, 7.5, 1.3, &[0.0, 35.0, 70.0, -80.0], false);
    println!("deepest a projectile got past a static wall's near face: {worst:.4} m");
}

#[test]
fn a_bullet_does_not_tunnel_through_a_thin_dynamic_box() {
    let worst = fire_all(24, 15.0, 4.1, &[0.0, 50.0, -75.0], true);
    println!("deepest a bullet got past a dynamic box's near face: {worst:.4} m");
}

#[test]
fn continuous_collision_is_reported_and_bit_identical_after_a_restore() {
    let mut w = world(8);
    let wall = w.add_path(PolygonPath::rectangle(s(0.1), s(100.0)).expect("wall")).expect("path");
    w.add_body(BodyDef::polygon(wall).position(v(20.0, 0.0)).static_body()).expect("wall");
    w.add_body(BodyDef::polygon(wall).position(v(-20.0, 0.0)).static_body()).expect("wall");
    w.add_body(BodyDef::circle(s(0.05)).linear_velocity(v(1500.0, 10.0)).restitution(s(1.0))).expect("ball");
    let mut snap = vec![0u8; w.max_snapshot_len()];
    let len = w.snapshot(&mut snap).expect("snapshot");
    let mut hits = 0;
    let mut hashes = Vec::new();
    for _ in 0..30 {
        let r = w.step(s(DT)).expect("step");
        hits += r.continuous_hits;
        assert!(r.continuous_sweeps >= r.continuous_hits);
        hashes.push(w.state_hash());
    }
    // 25 m a step between walls 40 m apart; each impact costs the rest of its
    // step and the next step's bounce: about one every three steps.
    assert!(hits >= 8, "the ball bounced between the walls: {hits} impacts swept");
    w.restore(&snap[..len]).expect("restore");
    for h in hashes {
        w.step(s(DT)).expect("step");
        assert_eq!(w.state_hash(), h);
    }
}

#[test]
fn the_bullet_flag_is_state_and_harmless_where_it_does_nothing() {
    let mut w = world(4);
    let st = w.add_body(BodyDef::circle(s(1.0)).static_body().bullet(true)).expect("static bullet");
    let kin = w
        .add_body(BodyDef::circle(s(1.0)).position(v(5.0, 0.0)).kinematic().bullet(true))
        .expect("kinematic");
    let dy = w.add_body(BodyDef::circle(s(0.1)).position(v(-5.0, 0.0))).expect("dynamic");
    assert!(w.body(st).expect("body").is_bullet() && w.body(kin).expect("body").is_bullet());
    assert!(!w.body(dy).expect("body").is_bullet());
    let before = w.state_hash();
    w.body_mut(dy).expect("body").set_bullet(true);
    assert_ne!(w.state_hash(), before, "the flag is in the state hash");
    let mut snap = vec![0u8; w.max_snapshot_len()];
    let len = w.snapshot(&mut snap).expect("snapshot");
    w.body_mut(dy).expect("body").set_bullet(false);
    w.restore(&snap[..len]).expect("restore");
    assert!(w.body(dy).expect("body").is_bullet(), "the flag is in the snapshot");
    for _ in 0..10 {
        w.step(s(DT)).expect("a static or kinematic bullet steps like any other body");
    }
}

/// A ball touching a static chain's wall link `gap` above its floor link
/// steps away from the wall (its arbiter with the chain is kept, without
/// points), then is sent down at `speed`: whether its bottom ends any step
/// more than the speculative distance below the floor.
fn ball_leaving_a_wall_falls_through(speed: f64, gap: f64) -> bool {
    let bounds = Rect::from_corners(v(-600.0, -600.0), v(600.0, 600.0));
    let caps = Capacities { chain_vertices: 4, ..Capacities::for_bodies(2) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    // Clockwise: the links' fronts face in (up from the floor, left from the wall).
    let points = [v(5.0, 10.0), v(5.0, 0.0), v(-5.0, 0.0), v(-5.0, 10.0)];
    let c = w.add_chain(ChainPath::open(&points).expect("path")).expect("chain");
    w.add_body(BodyDef::chain(c)).expect("room");
    let ball = w.add_body(BodyDef::circle(s(0.25)).position(v(4.75, 0.25 + gap))).expect("ball");
    w.step(s(DT)).expect("step");
    w.body_mut(ball).expect("ball").set_linear_velocity(v(-3.0, 0.0));
    w.step(s(DT)).expect("step");
    w.body_mut(ball).expect("ball").set_linear_velocity(v(0.0, -speed));
    (0..30).any(|_| {
        w.step(s(DT)).expect("step");
        let bottom = w.body(ball).expect("ball").position().to_f64().1 - 0.25;
        bottom < -SPECULATIVE_DISTANCE.to_f64()
    })
}

/// A body that just left one link of a chain (its arbiter with the chain kept
/// without points) is still swept against the chain's other links: continuous
/// collision skips a pair only when the game refused to solve it. (It used to
/// skip every pair whose arbiters were all unsolved, which an arbiter without
/// points is: the ball fell through the floor.)
#[test]
fn a_ball_leaving_a_chain_wall_does_not_fall_through_its_floor() {
    for gap in [0.05, 0.1, 0.2] {
        for speed in [20.0, 30.0, 45.0] {
            assert!(!ball_leaving_a_wall_falls_through(speed, gap), "{gap} m above the floor, {speed} m/s");
        }
    }
}

/// A net of 24 × 24 circles (0.4 m, 1 m apart) on plain pivots, hung from
/// its top-left corner, swings down onto a 0.2 m thick static floor 25 m
/// below its top, hundreds of bodies at once: its fast bodies are swept
/// against the floor (160 sweeps measured). Returns the lowest centre seen
/// and the sweeps computed.
fn falling_net() -> (f64, u64) {
    const N: usize = 24;
    let bounds = Rect::from_corners(v(-300.0, -300.0), v(300.0, 300.0));
    let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
    let caps = Capacities { joints: 2 * N * N, ..Capacities::for_bodies(N * N + 1) };
    let mut w = World::with_capacities(def, caps).expect("world");
    let floor = w.add_path(PolygonPath::rectangle(s(200.0), s(0.2)).expect("floor")).expect("path");
    w.add_body(BodyDef::polygon(floor).position(v(0.0, 35.0)).static_body()).expect("floor");
    let mut ids = Vec::new();
    for i in 0..N {
        for j in 0..N {
            let mut def = BodyDef::circle(s(0.4)).position(v(j as f64, 60.0 - i as f64)).collision_groups(1);
            if i == 0 && j == 0 {
                def = def.static_body();
            }
            ids.push(w.add_body(def).expect("body"));
        }
    }
    let pivot = JointKind::Pivot { limits: None, motor: None };
    for k in 0..N * N {
        if k % N + 1 < N {
            w.add_joint(JointDef::new(ids[k], v(0.5, 0.0), ids[k + 1], v(-0.5, 0.0), pivot)).expect("joint");
        }
        if k + N < N * N {
            w.add_joint(JointDef::new(ids[k], v(0.0, -0.5), ids[k + N], v(0.0, 0.5), pivot)).expect("joint");
        }
    }
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let (mut lowest, mut sweeps) = (f64::MAX, 0u64);
    for _ in 0..300 {
        sweeps += u64::from(w.step(s(DT)).expect("step").continuous_sweeps);
        for &b in &ids {
            lowest = lowest.min(w.body(b).expect("body").position().y.to_num::<f64>());
        }
    }
    (lowest, sweeps)
}

/// See [`falling_net`].
#[test]
fn a_falling_net_of_pivots_never_tunnels_through_the_floor() {
    let (lowest, sweeps) = falling_net();
    println!("lowest centre {lowest:.3} m, {sweeps} sweeps");
    assert!(sweeps > 0, "the net's fast bodies were swept");
    // The floor's top is at 35.1 m; a centre stays above it.
    assert!(lowest > 35.1, "lowest centre at {lowest:.3} m");
}

/// A kinematic bar moving at 60 m/s yanks 30 small balls, each pivoted to
/// it, from rest: in the first step each ball's path leaves its broad-phase
/// box (stretched by its velocity when the step began, zero), so each is
/// swept against every body near its path, with the targets outside the
/// loop (the bar and a thin static wall, fewer than the balls). The ball
/// nearest the wall, 0.25 m from it, must stop at it, not pass through.
/// Returns the rightmost ball's x after the first step.
fn yanked_into_a_wall() -> f64 {
    let mut w = world(40);
    let wall = w.add_path(PolygonPath::rectangle(s(0.1), s(0.6)).expect("wall")).expect("path");
    w.add_body(BodyDef::polygon(wall).position(v(4.8, 4.0)).static_body()).expect("wall");
    let bar_path = w.add_path(PolygonPath::rectangle(s(10.0), s(0.2)).expect("bar")).expect("path");
    let bar = w
        .add_body(BodyDef::polygon(bar_path).position(v(0.0, 5.0)).kinematic().linear_velocity(v(60.0, 0.0)))
        .expect("bar");
    let pivot = JointKind::Pivot { limits: None, motor: None };
    let mut last = None;
    for k in 0..30 {
        let x = -4.5 + 9.0 * f64::from(k) / 29.0;
        let ball = w.add_body(BodyDef::circle(s(0.05)).position(v(x, 4.0))).expect("ball");
        w.add_joint(JointDef::new(bar, v(x, -1.0), ball, v(0.0, 0.0), pivot)).expect("pivot");
        last = Some(ball);
    }
    w.step(s(DT)).expect("step");
    w.body(last.expect("ball")).expect("ball").position().x.to_num::<f64>()
}

/// See [`yanked_into_a_wall`].
#[test]
fn balls_yanked_off_their_course_stop_at_a_wall() {
    let x = yanked_into_a_wall();
    // The wall's near face is at 4.75 m: the ball's centre stops short of it.
    assert!(x < 4.75, "the rightmost ball's centre is at {x:.3} m");
}
