//! The collision story: callbacks in order, the arbiter lifecycle, persistence,
//! filtering, custom indexes, post-step callbacks, and bounded tables.

use std::sync::{Arc, Mutex};

use arphysics::handler::{DEFAULT_POST_STEP_CALLBACKS, MAX_COLLISION_HANDLERS};
use arphysics::{
    Arbiter, ArbiterState, BodyDef, BodyHandle, CallbackContext, CollisionHandler, Error, FnHandler,
    GravityForceGenerator, Handler, Index, PairSink, PolygonPath, Proxy, Rect, Scalar, SpatialIndex, Vector2,
    World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;

/// A world 200 m wide centred on the origin, gravity −10, a static floor whose top
/// is at y = 0 (collision level `floor_level`).
fn floor_world(floor_level: u32) -> (World<'static>, BodyHandle) {
    let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), arphysics::Capacities::for_bodies(64))
        .expect("world");
    let floor = w.add_path(PolygonPath::rectangle(s(40.0), s(2.0)).expect("floor")).expect("path");
    let f = w
        .add_body(BodyDef::polygon(floor).position(v(0.0, -1.0)).static_body().collision_level(floor_level))
        .expect("floor");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    (w, f)
}

/// What a recording handler heard, with the step it heard it in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Event {
    Begin(u64),
    PreSolve(u64),
    PostSolve(u64),
    End(u64),
}

/// Records every callback into a shared log; `begin` and `pre_solve` answers are
/// scripted.
struct Recorder {
    log: Arc<Mutex<Vec<Event>>>,
    step: Arc<Mutex<u64>>,
    begin_answer: bool,
    skip_pre_solve_at: Option<u64>,
}

impl Recorder {
    fn now(&self) -> u64 {
        *self.step.lock().expect("step")
    }
    fn push(&self, e: Event) {
        self.log.lock().expect("log").push(e);
    }
}

impl CollisionHandler for Recorder {
    fn begin(&mut self, a: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
        assert_eq!(a.state(), ArbiterState::FirstContact);
        self.push(Event::Begin(self.now()));
        self.begin_answer
    }
    fn pre_solve(&mut self, _: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
        let now = self.now();
        self.push(Event::PreSolve(now));
        self.skip_pre_solve_at != Some(now)
    }
    fn post_solve(&mut self, a: &Arbiter, _: &mut CallbackContext<'_>) {
        assert!(a.total_normal_impulse() >= Scalar::ZERO);
        self.push(Event::PostSolve(self.now()));
    }
    fn end(&mut self, a: &Arbiter, _: &mut CallbackContext<'_>) {
        assert_eq!(a.state(), ArbiterState::Separated);
        self.push(Event::End(self.now()));
    }
}

struct Script {
    world: World<'static>,
    log: Arc<Mutex<Vec<Event>>>,
    step: Arc<Mutex<u64>>,
}

impl Script {
    /// A ball of level 1 above a floor of level 2, with a recorder on (2, 1).
    fn new(ball: BodyDef, begin_answer: bool, skip_pre_solve_at: Option<u64>) -> (Self, BodyHandle) {
        let (mut world, _) = floor_world(2);
        let log = Arc::new(Mutex::new(Vec::new()));
        let step = Arc::new(Mutex::new(0));
        let rec = Recorder { log: log.clone(), step: step.clone(), begin_answer, skip_pre_solve_at };
        // Registered as (2, 1): must fire for the ball (1) on the floor (2) too.
        world.add_collision_handler(2, 1, Handler::boxed(Box::new(rec))).expect("handler");
        let b = world.add_body(ball.collision_level(1)).expect("ball");
        (Self { world, log, step }, b)
    }

    fn run(&mut self, steps: u64) {
        for _ in 0..steps {
            *self.step.lock().expect("step") += 1;
            self.world.step(s(DT)).expect("step");
        }
    }

    fn events(&self) -> Vec<Event> {
        self.log.lock().expect("log").clone()
    }
}

#[test]
fn a_bouncing_ball_begins_once_solves_each_touching_step_and_ends_once() {
    // Restitution 0.8: it lands, bounces off, and leaves the floor.
    let ball = BodyDef::circle(s(0.5)).position(v(0.0, 3.0)).restitution(s(0.8));
    let (mut sc, b) = Script::new(ball, true, None);
    let mut left_at = None;
    for _ in 0..120 {
        sc.run(1);
        let events = sc.events();
        if left_at.is_none() && events.iter().any(|e| matches!(e, Event::End(_))) {
            left_at = Some(*sc.step.lock().expect("step"));
            break;
        }
    }
    let events = sc.events();
    let begins: Vec<_> = events.iter().filter(|e| matches!(e, Event::Begin(_))).collect();
    let ends: Vec<_> = events.iter().filter(|e| matches!(e, Event::End(_))).collect();
    assert_eq!(begins.len(), 1, "{events:?}");
    assert_eq!(ends.len(), 1, "{events:?}");
    let (Event::Begin(first), Some(Event::End(last))) = (begins[0], events.last()) else {
        panic!("{events:?}")
    };
    // Every step from begin until the end step has exactly pre_solve then post_solve.
    for step in *first..*last {
        let at: Vec<_> = events
            .iter()
            .filter(|e| matches!(e, Event::PreSolve(t) | Event::PostSolve(t) if *t == step))
            .collect();
        assert_eq!(at, [&Event::PreSolve(step), &Event::PostSolve(step)], "step {step}: {events:?}");
    }
    assert!(sc.world.body(b).expect("ball").linear_velocity().y > s(0.0), "moving up when it separated");
    assert!(left_at.is_some());
}

#[test]
fn begin_returning_false_lets_the_body_pass_through_silently_until_it_separates() {
    let ball = BodyDef::circle(s(0.5)).position(v(0.0, 2.0));
    let (mut sc, b) = Script::new(ball, false, None);
    sc.run(120);
    let events = sc.events();
    assert_eq!(events.iter().filter(|e| matches!(e, Event::Begin(_))).count(), 1, "{events:?}");
    assert!(!events.iter().any(|e| matches!(e, Event::PreSolve(_) | Event::PostSolve(_))), "{events:?}");
    // It fell through the 2 m floor and out the bottom: separated, `end` once.
    assert_eq!(events.iter().filter(|e| matches!(e, Event::End(_))).count(), 1, "{events:?}");
    assert!(sc.world.body(b).expect("ball").position().y < s(-2.0));
}

#[test]
fn pre_solve_returning_false_skips_one_step_only() {
    let ball = BodyDef::circle(s(0.5)).position(v(0.0, 0.5));
    let (mut sc, b) = Script::new(ball, true, Some(31));
    sc.run(30);
    let y30 = sc.world.body(b).expect("ball").position().y;
    assert!((y30 - s(0.5)).abs() < s(0.002), "resting: {y30}");
    sc.run(1); // step 31: not resolved, falls freely into the floor for one step
    let y31 = sc.world.body(b).expect("ball").position().y;
    assert!(y31 < y30 - s(0.001), "sank while unresolved: {y30} → {y31}");
    sc.run(60);
    let y = sc.world.body(b).expect("ball").position().y;
    assert!((y - s(0.5)).abs() < s(0.002), "resolved again: {y}");
    let events = sc.events();
    assert!(events.contains(&Event::PreSolve(31)) && !events.contains(&Event::PostSolve(31)), "{events:?}");
    assert!(events.contains(&Event::PostSolve(32)));
    assert_eq!(events.iter().filter(|e| matches!(e, Event::Begin(_))).count(), 1);
}

#[test]
fn an_arbiter_persists_for_exactly_the_configured_steps_after_separation() {
    for persistence in [0u32, 3, 5] {
        let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
        let mut def = WorldDef::with_bounds(bounds);
        def.arbiter_persistence = persistence;
        let mut w = World::with_capacities(def, arphysics::Capacities::for_bodies(8)).expect("world");
        let floor_path = w.add_path(PolygonPath::rectangle(s(40.0), s(2.0)).expect("p")).expect("p");
        let floor2 =
            w.add_body(BodyDef::polygon(floor_path).position(v(0.0, -1.0)).static_body()).expect("f");
        let ball = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 0.5))).expect("ball");
        w.step(s(DT)).expect("step");
        assert_eq!(w.arbiter(ball, floor2).map(Arbiter::state), Some(ArbiterState::Contact));
        // Lift it clear (teleport), so the separation step is known exactly.
        w.set_position(ball, v(0.0, 50.0)).expect("lift");
        let mut alive_after = 0;
        for _ in 0..10 {
            w.step(s(DT)).expect("step");
            match w.arbiter(ball, floor2) {
                Some(a) => {
                    assert_eq!(a.state(), ArbiterState::Separated);
                    alive_after += 1;
                }
                None => break,
            }
        }
        assert_eq!(alive_after, persistence, "persistence {persistence}");
    }
}

#[test]
fn groups_sharing_a_bit_and_static_pairs_never_collide() {
    let (mut w, floor) = floor_world(0);
    let a = w.add_body(BodyDef::circle(s(0.5)).position(v(-5.0, 0.5)).collision_groups(0b01)).expect("a");
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(-5.0, 1.4)).collision_groups(0b11)).expect("b");
    let c = w.add_body(BodyDef::circle(s(0.5)).position(v(5.0, 1.4)).collision_groups(0b10)).expect("c");
    let d = w.add_body(BodyDef::circle(s(0.5)).position(v(5.0, 0.5)).collision_groups(0b01)).expect("d");
    let e = w.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 0.5)).static_body()).expect("e");
    for _ in 0..10 {
        w.step(s(DT)).expect("step");
    }
    assert!(w.arbiter(a, b).is_none(), "share bit 0");
    assert!(w.arbiter(c, d).is_some(), "no common bit");
    assert!(w.arbiter(floor, e).is_none(), "both static");
    assert!(w.arbiter(a, floor).is_some());
}

/// A test index that reports every overlapping pair three times, in reverse,
/// swapped, plus self-pairs and out-of-range indices: the engine must produce
/// exactly what the brute-force index produces.
struct SloppyIndex;

impl SpatialIndex for SloppyIndex {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        let n = proxies.len() as u32;
        for i in (0..n).rev() {
            out.push(i, i);
            out.push(i, n + 7);
            for j in 0..i {
                let (a, b) = (&proxies[i as usize], &proxies[j as usize]);
                if arphysics::index::proxies_may_touch(a, b) {
                    out.push(i, j);
                    out.push(j, i);
                    out.push(i, j);
                }
            }
        }
    }
}

fn pile(w: &mut World<'_>) {
    let boxp = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    for i in 0..12 {
        let x = f64::from(i % 4) * 1.1 - 2.0;
        let y = 0.5 + f64::from(i / 4) * 1.5;
        w.add_body(BodyDef::polygon(boxp).position(v(x, y)).angle(s(0.1 * f64::from(i)))).expect("box");
        w.add_body(BodyDef::circle(s(0.3)).position(v(x + 0.4, y + 0.8))).expect("ball");
    }
}

#[test]
fn a_custom_index_gives_the_same_world_as_brute_force_even_when_sloppy() {
    let (mut reference, _) = floor_world(0);
    pile(&mut reference);
    let (mut custom, _) = floor_world(0);
    custom.set_spatial_index(Index::boxed(Box::new(SloppyIndex)));
    pile(&mut custom);
    for step in 0..240 {
        reference.step(s(DT)).expect("step");
        custom.step(s(DT)).expect("step");
        assert_eq!(reference.state_hash(), custom.state_hash(), "diverged at step {step}");
    }
    assert!(reference.arbiters().count() > 10);
}

#[test]
fn in_strict_mode_a_full_pair_buffer_is_an_error_and_changes_nothing() {
    let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
    let mut w = World::with_capacities(
        WorldDef { strict_capacity: true, ..WorldDef::with_bounds(bounds) },
        arphysics::Capacities {
            bodies: 16,
            paths: 4,
            contacts: 2,
            joints: 0,
            post_step_callbacks: 4,
            events: 64,
            chain_vertices: 0,
            shapes: 0,
        },
    )
    .expect("world");
    for i in 0..4 {
        w.add_body(BodyDef::circle(s(0.5)).position(v(f64::from(i) * 0.9, 0.0))).expect("ball");
    }
    let before = w.state_hash();
    assert_eq!(w.step(s(DT)).err(), Some(Error::CapacityFull { what: "contact pair" }));
    assert_eq!(w.state_hash(), before);
}

#[test]
fn the_handler_table_is_bounded_and_rejects_duplicates() {
    let (mut w, _) = floor_world(0);
    w.add_collision_handler(1, 2, FnHandler::default()).expect("first");
    assert!(matches!(
        w.add_collision_handler(2, 1, FnHandler::default()),
        Err(Error::InvalidOperation { .. })
    ));
    for level in 1..MAX_COLLISION_HANDLERS as u32 {
        w.add_collision_handler(100, level, FnHandler::default()).expect("room");
    }
    assert_eq!(
        w.add_collision_handler(7, 7, FnHandler::default()).err(),
        Some(Error::CapacityFull { what: "collision handler" })
    );
    assert!(w.remove_collision_handler(2, 1).is_some());
    w.add_collision_handler(7, 7, FnHandler::default()).expect("room again");
}

fn count_post_step(w: &mut World<'_>, key: u64) {
    // Remove the body named by the key: safe here, after the step.
    let _ = w.remove_body(BodyHandle::from_bits(key));
}

fn schedule_many(_: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    let mut full = None;
    for key in 0..(DEFAULT_POST_STEP_CALLBACKS as u64 + 5) {
        if let Err(e) = ctx.add_post_step_callback(count_post_step, 1_000_000 + key) {
            full = Some(e);
        }
        // The same key twice runs once.
        assert_eq!(ctx.add_post_step_callback(count_post_step, 1_000_000), Ok(false));
    }
    assert_eq!(full, Some(Error::CapacityFull { what: "post-step callback" }));
    true
}

#[test]
fn the_post_step_queue_is_bounded_and_runs_each_key_once() {
    let (mut w, _) = floor_world(2);
    w.add_collision_handler(1, 2, FnHandler { begin: Some(schedule_many), ..FnHandler::default() })
        .expect("h");
    w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 0.5)).collision_level(1)).expect("ball");
    let report = w.step(s(DT)).expect("step");
    assert_eq!(report.post_step_callbacks, DEFAULT_POST_STEP_CALLBACKS as u32);
    assert_eq!(report.post_step_refused, 5, "the refusals are in the report");
    assert_eq!(w.step(s(DT)).expect("step").post_step_callbacks, 0, "the queue is emptied");
}

#[test]
fn removing_a_body_in_a_post_step_callback_ends_its_arbiters() {
    let (mut w, floor) = floor_world(2);
    let log = Arc::new(Mutex::new(Vec::new()));
    let step = Arc::new(Mutex::new(0));
    let rec = Recorder { log: log.clone(), step, begin_answer: true, skip_pre_solve_at: None };
    w.add_collision_handler(1, 2, Handler::boxed(Box::new(rec))).expect("h");
    let ball = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 0.5)).collision_level(1)).expect("ball");
    for _ in 0..5 {
        w.step(s(DT)).expect("step");
    }
    assert!(w.arbiter(ball, floor).is_some());
    count_post_step(&mut w, ball.to_bits());
    assert!(w.body(ball).is_err());
    assert!(w.arbiters().next().is_none(), "its arbiter went with it");
    let events = log.lock().expect("log").clone();
    assert_eq!(events.iter().filter(|e| matches!(e, Event::End(_))).count(), 1, "end on removal: {events:?}");
    w.step(s(DT)).expect("the world steps on");
}

fn bouncy(a: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
    a.set_restitution(s(1.0)).expect("1 is a legal restitution");
    true
}

fn slippery(a: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
    a.set_friction(s(0.0)).expect("0 is a legal friction");
    true
}

#[test]
fn pre_solve_changes_to_restitution_and_friction_are_honoured() {
    // A dead ball (e = 0) bounces when pre_solve raises the pair's restitution to 1.
    let (mut w, _) = floor_world(2);
    w.add_collision_handler(1, 2, FnHandler { pre_solve: Some(bouncy), ..FnHandler::default() }).expect("h");
    let ball = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 5.5)).collision_level(1)).expect("ball");
    let mut peak_after_bounce = f64::MIN;
    let mut bounced = false;
    for _ in 0..180 {
        w.step(s(DT)).expect("step");
        let b = w.body(ball).expect("ball");
        bounced |= b.linear_velocity().y > s(1.0);
        if bounced {
            peak_after_bounce = peak_after_bounce.max(b.position().y.to_num::<f64>());
        }
    }
    // Dropped from 5 m above the floor (bottom at 5.0): an elastic bounce climbs back near it.
    assert!(bounced && peak_after_bounce - 0.5 > 4.5, "peak {peak_after_bounce}");

    // A box on a 0.25 rad ramp with μ = 0.6 sticks, unless pre_solve zeroes the friction.
    for (handler, expect_slide) in
        [(None, false), (Some(slippery as arphysics::handler::ArbiterFilterFn), true)]
    {
        let (mut w, _) = floor_world(0);
        let ramp = w.add_path(PolygonPath::rectangle(s(30.0), s(1.0)).expect("ramp")).expect("p");
        let angle = s(0.25);
        w.add_body(
            BodyDef::polygon(ramp).position(v(0.0, 10.0)).angle(angle).static_body().collision_level(2),
        )
        .expect("ramp");
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("p");
        // On the ramp's upper face: 1 m above its centre line along the normal.
        let (sin, cos) = (0.25f64.sin(), 0.25f64.cos());
        let b = w
            .add_body(
                BodyDef::polygon(unit)
                    .position(v(-sin * 1.0, 10.0 + cos * 1.0))
                    .angle(angle)
                    .collision_level(1),
            )
            .expect("box");
        if let Some(f) = handler {
            w.add_collision_handler(1, 2, FnHandler { pre_solve: Some(f), ..FnHandler::default() })
                .expect("h");
        }
        let start = w.body(b).expect("box").position();
        for _ in 0..60 {
            w.step(s(DT)).expect("step");
        }
        let moved = (w.body(b).expect("box").position() - start).length().to_num::<f64>();
        // Frictionless: ½·g·sin θ·t² ≈ 1.24 m in 1 s.
        assert_eq!(moved > 0.5, expect_slide, "moved {moved} m (handler: {})", handler.is_some());
    }
}

/// A pile of 300 mixed bodies dropped into a box: enough proxies that the
/// automatic index sorts and sweeps.
fn big_pile(w: &mut World<'_>) {
    let unit = w.add_path(PolygonPath::rectangle(s(0.8), s(0.6)).expect("box")).expect("p");
    let wall = w.add_path(PolygonPath::rectangle(s(1.0), s(30.0)).expect("wall")).expect("p");
    for x in [-16.0, 16.0] {
        w.add_body(BodyDef::polygon(wall).position(v(x, 14.0)).static_body()).expect("wall");
    }
    for i in 0..300 {
        let (x, y) = (f64::from(i % 25) * 1.2 - 14.4, 2.0 + f64::from(i / 25) * 1.4);
        let def = if i % 3 == 0 {
            BodyDef::circle(s(0.35)).position(v(x, y))
        } else {
            BodyDef::polygon(unit).position(v(x + 0.1, y)).angle(s(0.2 * f64::from(i % 7)))
        };
        w.add_body(def).expect("body");
    }
}

#[test]
fn sort_and_sweep_gives_the_same_world_as_brute_force() {
    let mk = |index: Option<Index<'static>>| {
        let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
        let mut w =
            World::with_capacities(WorldDef::with_bounds(bounds), arphysics::Capacities::for_bodies(400))
                .expect("world");
        let floor = w.add_path(PolygonPath::rectangle(s(40.0), s(2.0)).expect("floor")).expect("path");
        w.add_body(BodyDef::polygon(floor).position(v(0.0, -1.0)).static_body()).expect("floor");
        w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
        if let Some(i) = index {
            w.set_spatial_index(i);
        }
        big_pile(&mut w);
        w
    };
    let mut brute = mk(Some(Index::BruteForce(arphysics::BruteForceIndex)));
    let mut auto = mk(None);
    let mut sweep = mk(Some(Index::SortAndSweep(
        arphysics::index::SortAndSweepIndex::with_capacity(400).expect("scratch"),
    )));
    for step in 0..180 {
        brute.step(s(DT)).expect("step");
        auto.step(s(DT)).expect("step");
        sweep.step(s(DT)).expect("step");
        let h = brute.state_hash();
        assert_eq!(auto.state_hash(), h, "automatic index diverged at step {step}");
        assert_eq!(sweep.state_hash(), h, "sort-and-sweep diverged at step {step}");
    }
    assert!(brute.arbiters().count() > 300);
}

#[test]
fn a_resting_boxs_total_normal_impulse_over_a_step_is_its_weight_times_the_step() {
    // At rest the floor carries the weight: over a step of dt it delivers
    // m·g·dt, however the solver splits it into sub-steps and sweeps.
    let (mut w, floor) = floor_world(0);
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    let b = w.add_body(BodyDef::polygon(unit).position(v(0.0, 0.5))).expect("box");
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
    }
    let m = w.body(b).expect("box").mass().to_num::<f64>();
    let arb = w.arbiter(b, floor).expect("touching");
    let total = arb.total_normal_impulse().to_num::<f64>();
    let expected = m * 10.0 * DT;
    assert!((total - expected).abs() <= 0.01 * expected, "total {total} N·s, weight × dt {expected} N·s");
}
