//! Issue 18: sensors. A sensor body reports the bodies that overlap it (true
//! overlap, no speculative margin) on exactly the steps they start and stop
//! overlapping, and never pushes: a body falling through one moves bit for bit
//! as it would without it.

use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;
const SUBSTEPS: f64 = 4.0;
const G: f64 = 10.0;

fn world() -> World<'static> {
    let def = WorldDef::with_bounds(Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0)));
    assert_eq!(def.substeps, SUBSTEPS as u32);
    let mut w = World::with_capacities(def, Capacities::for_bodies(16)).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -G))).expect("gravity");
    w
}

/// How far a body released at rest has fallen after `n` steps: the solver
/// adds g·h to the velocity, then moves by v·h, every sub-step h = dt/S, so
/// after N = n·S sub-steps the fall is g·h²·N(N+1)/2.
fn fallen(n: u32) -> f64 {
    let h = DT / SUBSTEPS;
    let big_n = f64::from(n) * SUBSTEPS;
    G * h * h * big_n * (big_n + 1.0) / 2.0
}

/// The first step after which the fall exceeds `d` (strictly when `strict`),
/// checking that the crossing is not within 1e-4 m of a step's end (so fixed
/// point rounding cannot move it).
fn first_step_past(d: f64, strict: bool) -> u32 {
    let n = (1..10_000).find(|&n| if strict { fallen(n) > d } else { fallen(n) >= d }).expect("crosses");
    assert!((fallen(n) - d).abs() > 1e-4 && (fallen(n - 1) - d).abs() > 1e-4, "step {n} is borderline");
    n
}

/// A 0.25 m ball released at rest at y = 10 falls through a static 2 m square
/// sensor centred at y = 5 (top 6, bottom 4). It overlaps once its bottom is
/// below 6 (a fall of more than 3.75 m) and stops once its top is at or below
/// 4 (a fall of at least 6.25 m).
#[test]
fn a_falling_ball_begins_and_ends_on_the_analytic_steps_and_falls_as_if_the_sensor_were_not_there() {
    let begin_at = first_step_past(10.0 - 0.25 - 6.0, true);
    let end_at = first_step_past(10.0 + 0.25 - 4.0, false);
    assert!(begin_at < end_at);

    let mut with = world();
    let square = with.add_path(PolygonPath::rectangle(s(2.0), s(2.0)).expect("square")).expect("path");
    let sensor =
        with.add_body(BodyDef::polygon(square).position(v(0.0, 5.0)).static_body().sensor()).expect("sensor");
    assert!(with.body(sensor).expect("sensor").is_sensor());
    let ball_def = BodyDef::circle(s(0.25)).position(v(0.0, 10.0));
    let ball = with.add_body(ball_def).expect("ball");
    // The same ball alone.
    let mut without = world();
    let alone = without.add_body(ball_def).expect("ball");

    let (mut begins, mut ends) = (Vec::new(), Vec::new());
    for n in 1..=end_at + 10 {
        with.step(s(DT)).expect("step");
        without.step(s(DT)).expect("step");
        let (b, a) = (with.body(ball).expect("ball"), without.body(alone).expect("ball"));
        assert_eq!(b.position(), a.position(), "step {n}: the sensor moved the ball");
        assert_eq!(b.linear_velocity(), a.linear_velocity(), "step {n}: the sensor changed a velocity");
        assert_eq!(b.angular_velocity(), a.angular_velocity());
        // The integration is the analytic one (to the fixed point's rounding).
        assert!((10.0 - b.position().y.to_f64() - fallen(n)).abs() < 1e-6, "step {n}");
        for e in with.sensor_begin_events() {
            assert_eq!((e.sensor, e.visitor), (sensor, ball));
            begins.push(n);
        }
        for e in with.sensor_end_events() {
            assert_eq!((e.sensor, e.visitor), (sensor, ball));
            ends.push(n);
        }
        assert!(with.contact_begin_events().is_empty() && with.contact_hit_events().is_empty());
    }
    assert_eq!(begins, vec![begin_at], "sensor begin (expected after step {begin_at})");
    assert_eq!(ends, vec![end_at], "sensor end (expected after step {end_at})");
    // A sensor pair never touches and is gone once it stops overlapping.
    assert!(with.arbiters().all(|a| !a.is_touching()));
    assert!(with.arbiter(sensor, ball).is_none());
}

/// A kinematic body moving at a constant 3 m/s through a static sensor
/// (a coin picked up by a moving platform) is detected; so is a dynamic body
/// resting in it. Sensors do not detect sensors.
#[test]
fn a_static_sensor_detects_kinematic_bodies_and_not_other_sensors() {
    let def = WorldDef::with_bounds(Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0)));
    let mut w = World::with_capacities(def, Capacities::for_bodies(16)).expect("world");
    let coin = w.add_body(BodyDef::circle(s(0.5)).static_body().sensor()).expect("coin");
    let other = w.add_body(BodyDef::circle(s(0.5)).position(v(0.3, 0.0)).sensor()).expect("dynamic sensor");
    // Centre at x = -2.125 moving +x at 3 m/s: touches the coin once x > -1
    // (the radii sum is 1), leaves once x >= 1.
    let platform = w
        .add_body(BodyDef::circle(s(0.5)).position(v(-2.125, 0.0)).kinematic().linear_velocity(v(3.0, 0.0)))
        .expect("platform");
    let (mut begin, mut end) = (None, None);
    for n in 1..=80u32 {
        w.step(s(DT)).expect("step");
        for e in w.sensor_begin_events() {
            assert_ne!(e.visitor, other, "a sensor detected a sensor");
            if e.sensor == coin && e.visitor == platform {
                assert!(begin.replace(n).is_none());
            }
        }
        for e in w.sensor_end_events() {
            assert_ne!(e.visitor, other, "a sensor detected a sensor");
            if e.sensor == coin && e.visitor == platform {
                assert!(end.replace(n).is_none());
            }
        }
        // The dynamic sensor, without gravity, is never pushed by anything.
        assert_eq!(w.body(other).expect("sensor").linear_velocity(), Vector2::ZERO);
        assert_eq!(w.body(platform).expect("platform").linear_velocity(), v(3.0, 0.0));
    }
    // x(n) = -2.125 + 3·n/60 = -2.125 + n/20: above -1 from n = 23 (22.5),
    // at or above 1 from n = 63 (62.5).
    assert_eq!(begin, Some(23));
    assert_eq!(end, Some(63));
}

#[test]
fn a_sensor_marked_bullet_is_an_error_and_the_world_is_unchanged() {
    let mut w = world();
    let before = w.state_hash();
    let r = w.add_body(BodyDef::circle(s(0.5)).sensor().bullet(true));
    assert!(matches!(r, Err(Error::InvalidOperation { .. })), "{r:?}");
    assert_eq!(w.state_hash(), before);
    assert_eq!(w.body_count(), 0);
    // A sensor ignores being made a bullet later.
    let h = w.add_body(BodyDef::circle(s(0.5)).sensor()).expect("sensor");
    w.body_mut(h).expect("sensor").set_bullet(true);
    assert!(!w.body(h).expect("sensor").is_bullet());
}

/// The sensor flag and a sensor's overlaps are state: a restore brings them
/// back: no second begin after the restore.
#[test]
fn the_sensor_flag_and_its_overlaps_survive_a_snapshot() {
    let mut w = world();
    let zone = w.add_body(BodyDef::circle(s(2.0)).static_body().sensor()).expect("zone");
    let ball = w.add_body(BodyDef::circle(s(0.25)).position(v(0.0, 1.0))).expect("ball");
    w.step(s(DT)).expect("step");
    assert_eq!(
        w.sensor_begin_events(),
        &[SensorEvent { sensor: zone, visitor: ball, sensor_shape: 0, visitor_shape: 0 }]
    );
    let mut buf = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut buf).expect("snapshot");
    let hash = w.state_hash();
    // Move the ball out (an end), then go back.
    w.set_position(ball, v(10.0, 10.0)).expect("move");
    w.step(s(DT)).expect("step");
    assert_eq!(
        w.sensor_end_events(),
        &[SensorEvent { sensor: zone, visitor: ball, sensor_shape: 0, visitor_shape: 0 }]
    );
    w.restore(&buf).expect("restore");
    assert!(w.body(zone).expect("zone").is_sensor());
    assert_eq!(w.state_hash(), hash);
    // Still overlapping: no second begin after the restore.
    w.step(s(DT)).expect("step");
    assert!(w.sensor_begin_events().is_empty() && w.sensor_end_events().is_empty());
    // Another world restores it too, the flag with it.
    let mut fresh = world();
    fresh.restore(&buf).expect("restore");
    assert_eq!(fresh.state_hash(), hash);
    assert_eq!(fresh.bodies().filter(|(_, b)| b.is_sensor()).count(), 1);
}

/// A snapshot whose body-type byte says "sensor and bullet" (edited and
/// resealed, so the checksum passes) is refused, and the world is unchanged.
#[test]
fn a_snapshot_with_a_sensor_marked_bullet_is_refused() {
    use arphysics::snapshot::TRAILER;
    use twox_hash::XxHash64;
    let take = |sensor: bool| {
        let mut w = world();
        let def = BodyDef::circle(s(0.5)).position(v(1.0, 2.0));
        w.add_body(if sensor { def.sensor() } else { def }).expect("body");
        let mut buf = vec![0u8; w.snapshot_len()];
        w.snapshot(&mut buf).expect("snapshot");
        buf
    };
    let (plain, sensor) = (take(false), take(true));
    let n = plain.len();
    assert_eq!(n, sensor.len());
    // The only byte that differs before the trailer is the body-type byte:
    // dynamic (2) with bit 5 (0x20) for the sensor.
    let at: Vec<usize> = (0..n - TRAILER).filter(|&i| plain[i] != sensor[i]).collect();
    assert_eq!(at.len(), 1, "{at:?}");
    let i = at[0];
    assert_eq!((plain[i], sensor[i]), (0x02, 0x22));
    let mut bad = sensor.clone();
    bad[i] = 0x32; // sensor | bullet | dynamic
    let sum = XxHash64::oneshot(0, &bad[..n - TRAILER]);
    bad[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
    let mut w = world();
    w.add_body(BodyDef::circle(s(0.25))).expect("body");
    let before = w.state_hash();
    let r = w.restore(&bad);
    assert!(matches!(r, Err(Error::InvalidSnapshot { .. })), "{r:?}");
    assert_eq!(w.state_hash(), before);
    // The sensor snapshot itself restores, the flag with it.
    w.restore(&sensor).expect("restore");
    assert!(w.bodies().all(|(_, b)| b.is_sensor()));
}

/// Box2D's filter applies to sensors as to contacts: a coin sensor whose mask
/// leaves out the enemies' category never reports an enemy, while the player
/// passing the same way is reported; the collision groups veto the same way.
/// Queries see sensors unless told to skip them.
#[test]
fn sensors_obey_the_collision_filter_and_queries_can_skip_them() {
    const PLAYER: u64 = 0b01;
    const ENEMY: u64 = 0b10;
    let def = WorldDef::with_bounds(Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0)));
    let mut w = World::with_capacities(def, Capacities::for_bodies(16)).expect("world");
    let coin_filter = CollisionFilter { mask_bits: PLAYER, ..CollisionFilter::DEFAULT };
    let coin = w.add_body(BodyDef::circle(s(0.5)).static_body().sensor().filter(coin_filter)).expect("coin");
    let walker = |y: f64, category: u64, groups: u32| {
        BodyDef::circle(s(0.25))
            .position(v(-3.0, y))
            .linear_velocity(v(3.0, 0.0))
            .filter(CollisionFilter { category_bits: category, ..CollisionFilter::DEFAULT })
            .collision_groups(groups)
    };
    let player = w.add_body(walker(0.0, PLAYER, 0)).expect("player");
    let enemy = w.add_body(walker(0.1, ENEMY, 0)).expect("enemy");
    // A player-category body sharing a group bit with the coin's (none) is
    // seen; one sharing a bit with a grouped coin is not (below).
    let (mut seen_player, mut seen_enemy) = (0, 0);
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
        for e in w.sensor_begin_events() {
            assert_eq!(e.sensor, coin);
            seen_player += u32::from(e.visitor == player);
            seen_enemy += u32::from(e.visitor == enemy);
        }
    }
    assert_eq!((seen_player, seen_enemy), (1, 0), "the mask leaves the enemy out");

    let grouped = w
        .add_body(
            BodyDef::circle(s(0.5)).position(v(0.0, 10.0)).static_body().sensor().collision_groups(0b100),
        )
        .expect("grouped coin");
    let member = w.add_body(walker(10.0, PLAYER, 0b100)).expect("member");
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
        assert!(
            w.sensor_begin_events().iter().all(|e| !(e.sensor == grouped && e.visitor == member)),
            "a shared group bit vetoes"
        );
    }

    // A point query at the coin sees it, unless sensors are skipped.
    let mut out = [BodyHandle::default(); 4];
    let n = w.query_point(v(0.0, 0.0), QueryFilter::default(), &mut out);
    assert!(out[..n].contains(&coin));
    let n = w.query_point(v(0.0, 0.0), QueryFilter::default().skip_sensors(true), &mut out);
    assert!(!out[..n].contains(&coin));
    let hit = w.ray_cast(v(0.0, 5.0), v(0.0, -5.0), QueryFilter::default().skip_sensors(true)).expect("ray");
    assert!(hit.is_none_or(|h| h.body != coin));
    let hit = w.ray_cast(v(0.0, 5.0), v(0.0, -5.0), QueryFilter::default()).expect("ray").expect("the coin");
    assert_eq!(hit.body, coin);
}
