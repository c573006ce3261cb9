//! A panicking hook leaves the world exactly as before the step (with `std` and
//! the panic guard on, the default), and the next step equals a world that
//! never saw the panic.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};

use arphysics::{
    Arbiter, BodyDef, CallbackContext, Capacities, FnHandler, ForceGenerator, Generator,
    GravityForceGenerator, Rect, Scalar, Vector2, World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: Scalar = Scalar::lit("0.016666666");

/// A pile of circles falling onto a static ground box: contacts, arbiters,
/// warm-start impulses, everything a half-done step would leave half-updated.
fn pile<'a>() -> World<'a> {
    let mut w = World::with_capacities(
        WorldDef::with_bounds(Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0))),
        Capacities::for_bodies(32),
    )
    .expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    w.add_body(BodyDef::circle(s(15.0)).position(v(20.0, -10.0)).static_body()).expect("ground");
    for i in 0..12 {
        let x = 16.0 + f64::from(i % 4) * 1.1;
        let y = 5.3 + f64::from(i / 4) * 1.05;
        w.add_body(BodyDef::circle(s(0.5)).position(v(x, y))).expect("ball");
    }
    w
}

static PANIC_IN_PRE_SOLVE: AtomicBool = AtomicBool::new(false);

fn pre_solve(_: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
    assert!(!PANIC_IN_PRE_SOLVE.load(Ordering::SeqCst), "the game's pre_solve panics");
    true
}

/// Steps `w` once with a hook set to panic; returns whether the step panicked.
fn step_panicking(w: &mut World<'_>) -> bool {
    catch_unwind(AssertUnwindSafe(|| w.step(DT))).is_err()
}

#[test]
fn a_panicking_collision_handler_leaves_the_world_as_before_the_step() {
    let handler = FnHandler { pre_solve: Some(pre_solve), ..FnHandler::default() };
    let (mut world, mut reference) = (pile(), pile());
    world.add_collision_handler(0, 0, handler).expect("handler");
    reference.add_collision_handler(0, 0, handler).expect("handler");
    for _ in 0..40 {
        world.step(DT).expect("step");
        reference.step(DT).expect("step");
    }
    assert!(world.arbiters().count() > 0, "the balls touch: pre_solve runs");
    let before = world.state_hash();
    PANIC_IN_PRE_SOLVE.store(true, Ordering::SeqCst);
    let panicked = step_panicking(&mut world);
    PANIC_IN_PRE_SOLVE.store(false, Ordering::SeqCst);
    assert!(panicked, "the hook panicked out of step");
    assert_eq!(world.state_hash(), before, "the world is exactly as before the step");
    for _ in 0..20 {
        world.step(DT).expect("step");
        reference.step(DT).expect("step");
    }
    assert_eq!(world.state_hash(), reference.state_hash(), "and its future is the uninterrupted one");
}

static PANIC_IN_GENERATOR: AtomicBool = AtomicBool::new(false);

/// Pushes every body up a little, and panics half-way through the bodies when
/// told to: some bodies then carry this step's push, the others not.
struct Updraft {
    seen: u32,
}

impl ForceGenerator for Updraft {
    fn apply(&mut self, _: arphysics::BodyHandle, body: &mut arphysics::Body, _: Scalar) {
        body.add_linear_velocity(v(0.0, 0.1));
        self.seen += 1;
        assert!(
            !(PANIC_IN_GENERATOR.load(Ordering::SeqCst) && self.seen % 12 == 6),
            "the game's generator panics"
        );
    }
}

#[test]
fn a_panicking_force_generator_leaves_the_world_as_before_the_step() {
    let (mut a, mut b) = (Updraft { seen: 0 }, Updraft { seen: 0 });
    let (mut world, mut reference) = (pile(), pile());
    world.add_force_generator(Generator::borrowed(&mut a)).expect("generator");
    reference.add_force_generator(Generator::borrowed(&mut b)).expect("generator");
    for _ in 0..30 {
        world.step(DT).expect("step");
        reference.step(DT).expect("step");
    }
    let before = world.state_hash();
    PANIC_IN_GENERATOR.store(true, Ordering::SeqCst);
    let panicked = step_panicking(&mut world);
    PANIC_IN_GENERATOR.store(false, Ordering::SeqCst);
    assert!(panicked, "the generator panicked out of step");
    assert_eq!(world.state_hash(), before, "no body kept a velocity change of the broken step");
    world.step(DT).expect("step");
    reference.step(DT).expect("step");
    assert_eq!(world.state_hash(), reference.state_hash());
}

static PANIC_IN_POST_STEP: AtomicBool = AtomicBool::new(false);

fn remove_then_panic(w: &mut World<'_>, key: u64) {
    let _ = w.remove_body(arphysics::BodyHandle::from_bits(key));
    assert!(!PANIC_IN_POST_STEP.load(Ordering::SeqCst), "the game's post-step callback panics");
}

fn begin_removes_b(arb: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    let b = arb.body_b();
    if ctx.body(b).is_some_and(|body| body.is_dynamic()) {
        let _ = ctx.add_post_step_callback(remove_then_panic, b.to_bits());
    }
    true
}

#[test]
fn a_panicking_post_step_callback_leaves_the_world_as_before_the_step() {
    let mut world = pile();
    world
        .add_collision_handler(0, 0, FnHandler { begin: Some(begin_removes_b), ..FnHandler::default() })
        .expect("h");
    PANIC_IN_POST_STEP.store(true, Ordering::SeqCst);
    let mut panicked = false;
    for _ in 0..60 {
        let (before, bodies) = (world.state_hash(), world.body_count());
        if step_panicking(&mut world) {
            panicked = true;
            // The callback removed a body before it panicked: it is back, and
            // everything else is as before the step.
            assert_eq!(world.body_count(), bodies);
            assert_eq!(world.state_hash(), before);
            break;
        }
    }
    PANIC_IN_POST_STEP.store(false, Ordering::SeqCst);
    assert!(panicked, "a ball touched and its removal callback panicked");
    world.step(DT).expect("the world steps on after the panic");
}

static PANIC_UNGUARDED: AtomicBool = AtomicBool::new(false);

fn post_solve_unguarded(_: &Arbiter, _: &mut CallbackContext<'_>) {
    assert!(!PANIC_UNGUARDED.load(Ordering::SeqCst), "the game's post_solve panics");
}

#[test]
fn without_the_guard_a_panicking_hook_leaves_the_world_half_stepped() {
    let handler = FnHandler { post_solve: Some(post_solve_unguarded), ..FnHandler::default() };
    let (mut world, mut reference) = (pile(), pile());
    for w in [&mut world, &mut reference] {
        w.add_collision_handler(0, 0, handler).expect("handler");
        w.set_panic_guard(false);
        for _ in 0..40 {
            w.step(DT).expect("step");
        }
    }
    let before = world.state_hash();
    PANIC_UNGUARDED.store(true, Ordering::SeqCst);
    let panicked = step_panicking(&mut world);
    PANIC_UNGUARDED.store(false, Ordering::SeqCst);
    assert!(panicked);
    // `post_solve` runs after the bodies moved and before the step counter
    // advances: a state no uninterrupted run has.
    assert_ne!(world.state_hash(), before, "the bodies moved");
    world.step(DT).expect("step");
    reference.step(DT).expect("step");
    assert_ne!(world.state_hash(), reference.state_hash(), "the future is not the uninterrupted one");
}
