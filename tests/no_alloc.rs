//! The step never allocates: a counting global allocator sees zero allocations on
//! this thread across 100 steps of a scene with every kind of body and generator
//! and a collision handler (so, with `std`, the panic guard's snapshot too),
//! a sensor and a floor (so the event lists fill).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use arphysics::{
    BodyDef, FnHandler, GravityForceGenerator, GravityToPointForceGenerator, LinearForceGenerator,
    PolygonPath, Scalar, Targets, Vector2, World, WorldBuffers, WorldDef,
};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

// SAFETY: forwards every call unchanged to the system allocator; it only counts.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_hundred_steps_allocate_nothing() {
    let s = Scalar::from_num::<f64>;
    let mut buffers = WorldBuffers::<64, 256>::new();
    let mut world = World::new(WorldDef::new(s(200.0), s(200.0)), buffers.storage()).expect("world");
    let path = world.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    let mut handles = Vec::new();
    for i in 0..20 {
        let x = s(10.0 + 8.0 * f64::from(i));
        handles.push(world.add_body(BodyDef::circle(s(0.5)).position(Vector2::new(x, s(150.0)))).expect("c"));
        world
            .add_body(BodyDef::polygon(path).position(Vector2::new(x, s(100.0))).angular_velocity(s(1.0)))
            .expect("p");
    }
    world.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-9.81)))).expect("g");
    world
        .add_force_generator(
            LinearForceGenerator::new(Vector2::new(s(3.0), s(0.0)))
                .with_targets(Targets::bodies(&handles[..4]).expect("t")),
        )
        .expect("l");
    world
        .add_force_generator(GravityToPointForceGenerator::new(Vector2::new(s(100.0), s(100.0)), s(1.0)))
        .expect("p");
    // A collision handler: with `std` the world then snapshots itself before every
    // step (the panic guard), into a buffer sized when the handler was added.
    fn begin(_: &mut arphysics::Arbiter, _: &mut arphysics::CallbackContext<'_>) -> bool {
        true
    }
    world.add_collision_handler(0, 0, FnHandler { begin: Some(begin), ..FnHandler::default() }).expect("h");

    // A static sensor zone around some of the boxes and a floor under them:
    // sensor and contact events fill the event lists.
    world
        .add_body(BodyDef::circle(s(20.0)).position(Vector2::new(s(100.0), s(110.0))).static_body().sensor())
        .expect("zone");
    let floor = world.add_path(PolygonPath::rectangle(s(190.0), s(1.0)).expect("floor")).expect("path");
    world
        .add_body(BodyDef::polygon(floor).position(Vector2::new(s(100.0), s(97.0))).static_body())
        .expect("floor");

    let (mut sensor_events, mut contact_events) = (0usize, 0usize);
    COUNTING.with(|c| c.set(true));
    for _ in 0..100 {
        world.step(s(1.0 / 60.0)).expect("step");
        sensor_events += world.sensor_begin_events().len() + world.sensor_end_events().len();
        contact_events += world.contact_begin_events().len() + world.contact_hit_events().len();
    }
    let _ = world.state_hash();
    COUNTING.with(|c| c.set(false));
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0, "allocations during 100 steps");
    assert!(
        sensor_events > 0 && contact_events > 0,
        "{sensor_events} sensor and {contact_events} contact events"
    );
}
