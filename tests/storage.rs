//! One engine on two kinds of storage: static buffers (no allocator, a world in a
//! `static`) and heap buffers sized at run time (a 20,000-body world built and
//! stepped on a 2 MiB thread stack, so nothing large ever lands on the stack).

use std::sync::Mutex;

use arphysics::{BodyDef, GravityForceGenerator, Scalar, Vector2, World, WorldBuffers, WorldDef};
use static_cell::StaticCell;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

static BUFFERS: StaticCell<WorldBuffers<32, 128>> = StaticCell::new();
static WORLD: Mutex<Option<World<'static>>> = Mutex::new(None);

#[test]
fn a_world_on_static_buffers_lives_in_a_static() {
    let buffers: &'static mut WorldBuffers<32, 128> = BUFFERS.init(WorldBuffers::new());
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let ball =
        world.add_body(BodyDef::circle(s(1.0)).position(Vector2::new(s(50.0), s(90.0)))).expect("ball");
    world.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-10.0)))).expect("g");
    *WORLD.lock().expect("lock") = Some(world);

    let mut guard = WORLD.lock().expect("lock");
    let world = guard.as_mut().expect("set");
    for _ in 0..10 {
        world.step(s(0.1)).expect("step");
    }
    // Four sub-steps of h = 0.025 s, M = 40 in all: y = 90 − g·h²·M(M+1)/2 = 84.875.
    let y = world.body(ball).expect("ball").position().y;
    assert!((y - s(84.875)).abs() < s(1e-6), "{y}");
}

#[test]
fn twenty_thousand_bodies_on_a_two_mebibyte_stack() {
    let result = std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(|| {
            let def = WorldDef::new(s(2000.0), s(2000.0));
            let mut world =
                World::with_capacities(def, arphysics::Capacities::for_bodies(20_000)).expect("world");
            for i in 0..20_000u32 {
                let (x, y) = (f64::from(i % 200) * 10.0 + 5.0, f64::from(i / 200) * 10.0 + 500.0);
                world.add_body(BodyDef::circle(s(1.0)).position(Vector2::new(s(x), s(y)))).expect("body");
            }
            world.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-10.0)))).expect("g");
            for _ in 0..3 {
                world.step(s(1.0 / 60.0)).expect("step");
            }
            (world.body_count(), world.step_count())
        })
        .expect("thread")
        .join()
        .expect("no stack overflow");
    assert_eq!(result, (20_000, 3));
}

#[test]
fn a_sort_and_sweep_index_too_large_to_allocate_is_an_error_not_an_abort() {
    use arphysics::index::SortAndSweepIndex;
    assert!(matches!(
        SortAndSweepIndex::with_capacity(usize::MAX),
        Err(arphysics::Error::OutOfMemory { what: "sort-and-sweep scratch" })
    ));
    assert!(SortAndSweepIndex::with_capacity(1000).is_ok());
}
