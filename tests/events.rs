//! Issue 18: event lists after the step. Contact begin, end and hit for a ball
//! dropped on the ground on the analytic step, with the analytic hit speed; a
//! resting contact that does not flicker; a jump ends the contact on the step
//! it leaves; full lists are counted, never a panic; the same events after a
//! restore and re-simulation.

use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 240.0;
const SUBSTEPS: f64 = 4.0;
const G: f64 = 9.81;
const R: f64 = 0.25;

fn world<'a>(caps: Capacities) -> World<'a> {
    let def = WorldDef::with_bounds(Rect::from_corners(v(-50.0, -10.0), v(50.0, 50.0)));
    assert_eq!(def.substeps, SUBSTEPS as u32);
    let mut w = World::with_capacities(def, caps).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -G))).expect("gravity");
    w
}

/// A static ground whose top is at y = 0.
fn ground(w: &mut World<'_>) -> BodyHandle {
    let slab = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("slab")).expect("path");
    w.add_body(BodyDef::polygon(slab).position(v(0.0, -0.5)).static_body()).expect("ground")
}

/// The fall after `n` steps from rest: g·h²·N(N+1)/2 with N = n·S sub-steps
/// of h = dt/S (the solver's velocity-then-position update).
fn fallen(n: u32) -> f64 {
    let h = DT / SUBSTEPS;
    let big_n = f64::from(n) * SUBSTEPS;
    G * h * h * big_n * (big_n + 1.0) / 2.0
}

/// A ball whose bottom starts `height` above the ground, released at rest,
/// lands on the first step whose free fall would bring it within
/// TOUCH_DISTANCE of the ground (the solver stops it at the surface within
/// that step): the contact begins on that step, with a hit whose speed is the
/// speed at the start of that step, g·dt·(k−1), within one step's gravity
/// (g·dt = 0.041 m/s) of √(2gh).
#[test]
fn a_dropped_ball_begins_touching_on_the_analytic_step_with_the_analytic_hit_speed() {
    let height = 0.5;
    let touch = TOUCH_DISTANCE.to_f64();
    let k = (1..10_000u32).find(|&n| height - fallen(n) <= touch).expect("lands");
    assert!((height - fallen(k) - touch).abs() > 1e-4, "borderline step");
    // The step before landing is within the speculative distance: the
    // contact exists (in the `Contact` state) before it touches.
    assert!(height - fallen(k - 1) < limits::SPECULATIVE_DISTANCE.to_f64());

    let mut w = world(Capacities::for_bodies(8));
    let g = ground(&mut w);
    let ball = w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + height))).expect("ball");
    let (mut begins, mut hits) = (Vec::new(), Vec::new());
    let mut saw_contact_not_touching = false;
    for n in 1..=k + 120 {
        let report = w.step(s(DT)).expect("step");
        assert_eq!(report.events_dropped, 0);
        assert!(w.contact_end_events().is_empty(), "step {n}: the resting ball flickered");
        for e in w.contact_begin_events() {
            // The circle is body A (circles before polygons); the normal runs
            // from it to the ground.
            assert_eq!((e.body_a, e.body_b), (ball, g));
            assert!((e.normal.y.to_f64() + 1.0).abs() < 1e-6 && e.normal.x.to_f64().abs() < 1e-6);
            begins.push(n);
        }
        for e in w.contact_hit_events() {
            hits.push((n, *e));
        }
        if let Some(arb) = w.arbiter(ball, g) {
            saw_contact_not_touching |= arb.state() == ArbiterState::Contact && !arb.is_touching();
            assert_eq!(arb.is_touching(), n >= k, "step {n}");
        }
    }
    assert!(saw_contact_not_touching, "the speculative contact should exist before touching");
    assert_eq!(begins, vec![k], "contact begin expected on step {k}");
    assert_eq!(hits.len(), 1);
    let (at, hit) = hits[0];
    assert_eq!(at, k);
    assert_eq!((hit.body_a, hit.body_b), (ball, g));
    let speed = hit.speed.to_f64();
    let analytic = (2.0 * G * height).sqrt();
    let start_of_step = G * DT * f64::from(k - 1);
    assert!(
        (speed - start_of_step).abs() < 1e-3,
        "hit speed {speed} vs the start-of-step speed {start_of_step}"
    );
    assert!((speed - analytic).abs() <= G * DT, "hit speed {speed} vs √(2gh) = {analytic}");
    // The point is on the contact: under the ball, at the ground's surface
    // (within the speculative distance: it is the start-of-step midpoint).
    assert!(hit.point.x.to_f64().abs() < 1e-6);
    assert!(hit.point.y.to_f64().abs() < limits::SPECULATIVE_DISTANCE.to_f64());
    assert_eq!(hit.normal, v(0.0, -1.0));
}

/// A resting ball that jumps at 2 m/s ends its contact on the step it leaves,
/// though its arbiter persists for a few steps (the double-jump bug of the
/// issue: the arbiter alone said "grounded").
#[test]
fn a_jump_ends_the_contact_on_the_step_it_leaves_the_ground() {
    let mut w = world(Capacities::for_bodies(8));
    let g = ground(&mut w);
    let ball = w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + 0.001))).expect("ball");
    let mut begun = 0;
    for _ in 0..240 {
        w.step(s(DT)).expect("step");
        begun += w.contact_begin_events().len();
        assert!(w.contact_end_events().is_empty());
    }
    assert_eq!(begun, 1);
    assert!(w.arbiter(ball, g).expect("resting").is_touching());
    // Up at 2 m/s: in one step it rises 2·dt − g·dt²·(S+1)/(2S) ≈ 8.2 mm,
    // more than TOUCH_DISTANCE from where it rested.
    w.body_mut(ball).expect("ball").set_linear_velocity(v(0.0, 2.0));
    w.step(s(DT)).expect("step");
    assert_eq!(
        w.contact_end_events(),
        &[ContactEndEvent { body_a: ball, body_b: g, shape_a: 0, shape_b: 0 }]
    );
    assert!(w.contact_begin_events().is_empty());
    let arb = w.arbiter(ball, g).expect("the arbiter persists");
    assert!(!arb.is_touching());
    // It lands again later: one begin, after the end.
    let mut landed = 0;
    for _ in 0..240 {
        w.step(s(DT)).expect("step");
        landed += w.contact_begin_events().len();
    }
    assert_eq!(landed, 1);
}

#[test]
fn the_hit_threshold_is_settable_and_checked() {
    let mut w = world(Capacities::for_bodies(8));
    assert_eq!(w.hit_event_threshold(), Scalar::ONE);
    assert!(matches!(w.set_hit_event_threshold(s(-0.5)), Err(Error::OutOfRange { .. })));
    assert_eq!(w.hit_event_threshold(), Scalar::ONE);
    // A 0.5 m drop lands at about 3.1 m/s: no hit above 5 m/s.
    w.set_hit_event_threshold(s(5.0)).expect("threshold");
    ground(&mut w);
    w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + 0.5))).expect("ball");
    let (mut begins, mut hits) = (0, 0);
    for _ in 0..240 {
        w.step(s(DT)).expect("step");
        begins += w.contact_begin_events().len();
        hits += w.contact_hit_events().len();
    }
    assert_eq!((begins, hits), (1, 0));
}

/// Five balls land on the same step with room for two events a list: two
/// begins and two hits are kept (the lowest pair keys), the other six are
/// counted in the report and the stats, and nothing panics.
#[test]
fn a_full_event_list_is_counted_in_the_report() {
    let mut w = world(Capacities { events: 2, ..Capacities::for_bodies(16) });
    let g = ground(&mut w);
    let balls: Vec<_> = (0..5)
        .map(|i| w.add_body(BodyDef::circle(s(R)).position(v(f64::from(i) - 2.0, R + 0.5))).expect("ball"))
        .collect();
    let mut dropped = 0;
    let mut landing = None;
    for n in 0..240 {
        let report = w.step(s(DT)).expect("step");
        assert!(w.contact_begin_events().len() <= 2 && w.contact_hit_events().len() <= 2);
        if report.events_dropped > 0 {
            assert!(landing.is_none());
            landing = Some(n);
            assert_eq!(report.events_dropped, 6);
            let kept: Vec<_> = w.contact_begin_events().iter().map(|e| e.body_a).collect();
            assert_eq!(kept, balls[..2].to_vec());
            assert!(w.contact_begin_events().iter().all(|e| e.body_b == g));
        }
        dropped += report.events_dropped;
    }
    assert!(landing.is_some());
    assert_eq!(dropped, 6);
    assert_eq!(w.stats().events_dropped, 6);
    assert_eq!(w.stats().capacities.events, 2);
}

/// Everything the events of one step hold, for comparing runs.
#[derive(Debug, PartialEq, Eq, Clone)]
struct StepEvents {
    begin: Vec<ContactBeginEvent>,
    end: Vec<ContactEndEvent>,
    hit: Vec<ContactHitEvent>,
    sensor_begin: Vec<SensorEvent>,
    sensor_end: Vec<SensorEvent>,
    joint_broke: Vec<JointBrokeEvent>,
}

fn events(w: &World<'_>) -> StepEvents {
    StepEvents {
        begin: w.contact_begin_events().to_vec(),
        end: w.contact_end_events().to_vec(),
        hit: w.contact_hit_events().to_vec(),
        sensor_begin: w.sensor_begin_events().to_vec(),
        sensor_end: w.sensor_end_events().to_vec(),
        joint_broke: w.joint_broke_events().to_vec(),
    }
}

/// Bouncing balls, a sensor they fall through and a breakable rope: the events
/// of 300 steps after a snapshot are the same, step for step, after a restore
/// and re-simulation. The snapshot is taken with contacts touching, balls
/// inside the sensor and the joint not yet broken.
#[test]
fn events_are_identical_after_restore_and_resimulation() {
    let mut w = world(Capacities::for_bodies(32));
    let g = ground(&mut w);
    let zone =
        w.add_body(BodyDef::circle(s(1.5)).position(v(0.0, 1.0)).static_body().sensor()).expect("zone");
    for i in 0..12 {
        let x = f64::from(i % 4) * 0.6 - 1.0;
        let y = 0.5 + f64::from(i / 4) * 0.7;
        w.add_body(BodyDef::circle(s(R)).position(v(x, y)).restitution(s(0.6))).expect("ball");
    }
    // A bob on a rope to a world point, which breaks when a heavy ball lands on it.
    let bob = w.add_body(BodyDef::circle(s(0.3)).position(v(6.0, 2.0))).expect("bob");
    let rope = JointDef::to_world(bob, Vector2::ZERO, v(6.0, 4.0), JointKind::Rope { max_length: s(2.0) })
        .breakable(s(0.8));
    let rope = w.add_joint(rope).expect("rope");
    w.add_body(BodyDef::circle(s(0.3)).position(v(6.0, 8.0)).density(s(20.0))).expect("anvil");
    // A second zone that a ball falls through after the snapshot.
    let gate =
        w.add_body(BodyDef::circle(s(1.0)).position(v(3.0, 3.0)).static_body().sensor()).expect("gate");
    w.add_body(BodyDef::circle(s(R)).position(v(3.0, 20.0))).expect("late ball");
    let _ = (g, zone, gate);
    for _ in 0..60 {
        w.step(s(1.0 / 60.0)).expect("step");
    }
    assert!(w.arbiters().any(Arbiter::is_touching), "nothing touches at the snapshot");
    assert!(w.joint(rope).is_ok(), "the rope broke before the snapshot");
    let mut buf = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut buf).expect("snapshot");
    let run = |w: &mut World<'_>| {
        (0..300)
            .map(|_| {
                w.step(s(1.0 / 60.0)).expect("step");
                events(w)
            })
            .collect::<Vec<_>>()
    };
    let first = run(&mut w);
    let hash = w.state_hash();
    let count = |f: fn(&StepEvents) -> usize| first.iter().map(f).sum::<usize>();
    assert!(count(|e| e.begin.len()) > 0 && count(|e| e.end.len()) > 0 && count(|e| e.hit.len()) > 0);
    assert!(count(|e| e.sensor_begin.len()) > 0 && count(|e| e.sensor_end.len()) > 0);
    assert_eq!(count(|e| e.joint_broke.len()), 1, "the rope should break once");
    let broke = first.iter().flat_map(|e| e.joint_broke.iter()).next().expect("broke");
    assert_eq!(*broke, JointBrokeEvent { joint: rope, body_a: bob, body_b: None });
    w.restore(&buf).expect("restore");
    let second = run(&mut w);
    assert_eq!(w.state_hash(), hash);
    for (n, (a, b)) in first.iter().zip(&second).enumerate() {
        assert_eq!(a, b, "step {n} after the snapshot");
    }
}

/// Closures where function pointers were: a `begin` closure that counts into a
/// local (borrowed: no allocator needed) and a boxed `pre_solve` that captures
/// the ground and lets a ball fall through it (a one-way floor).
#[test]
fn closure_handlers_capture_the_game_state() {
    let mut begun = 0u32;
    {
        let mut count = |_: &mut Arbiter, _: &mut CallbackContext<'_>| {
            begun += 1;
            true
        };
        let mut handler =
            ClosureHandler { begin: Some(Hook::Borrowed(&mut count)), ..ClosureHandler::default() };
        let mut w = world(Capacities::for_bodies(8));
        w.add_collision_handler(0, 0, Handler::borrowed(&mut handler)).expect("handler");
        ground(&mut w);
        w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + 0.2))).expect("ball");
        for _ in 0..120 {
            w.step(s(DT)).expect("step");
        }
    }
    assert_eq!(begun, 1);

    let mut w = world(Capacities::for_bodies(8));
    let floor = ground(&mut w);
    let pass_through = move |arb: &mut Arbiter, _: &mut CallbackContext<'_>| {
        let (a, b) = arb.bodies();
        a != floor && b != floor
    };
    let handler =
        ClosureHandler { pre_solve: Some(Hook::Boxed(Box::new(pass_through))), ..ClosureHandler::default() };
    w.add_collision_handler(0, 0, handler).expect("handler");
    let ball = w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + 0.2))).expect("ball");
    for _ in 0..240 {
        w.step(s(DT)).expect("step");
    }
    assert!(w.body(ball).expect("ball").position().y < s(-1.0), "the ball should fall through");
}

/// The lists are cleared when a step starts; a step that fails (a bad `dt`)
/// leaves them as they were.
#[test]
fn the_lists_are_cleared_by_each_step_and_kept_by_a_failed_one() {
    let mut w = world(Capacities::for_bodies(8));
    ground(&mut w);
    w.add_body(BodyDef::circle(s(R)).position(v(0.0, R + 0.001))).expect("ball");
    w.step(s(DT)).expect("step");
    assert_eq!(w.contact_begin_events().len(), 1);
    assert!(matches!(w.step(Scalar::ZERO), Err(Error::InvalidTimeStep)));
    assert_eq!(w.contact_begin_events().len(), 1, "a failed step keeps the lists");
    w.step(s(DT)).expect("step");
    assert!(w.contact_begin_events().is_empty(), "resting: nothing new");
}
