//! The contact kernels give the same bits at every SIMD level: the golden
//! scenes hash to the committed constants at [`SimdLevel::Portable`] and at
//! the best level this processor has, and a pile stepped at both levels side by
//! side agrees at every step (the first step that differed would be named).
//!
//! A test binary of its own: the level is a process-wide setting.

mod golden_scenes;

use arphysics::{
    limit_simd_level, simd_level, BodyDef, Capacities, GravityForceGenerator, PolygonPath, Scalar, SimdLevel,
    Vector2, World, WorldDef,
};
use golden_scenes::{
    GOLDEN_BANDED, GOLDEN_COMPOUND, GOLDEN_CORE_SCENE, GOLDEN_LONG, GOLDEN_MIXED, GOLDEN_PIVOT_NET,
    GOLDEN_PYRAMID, GOLDEN_SHAPES,
};

/// The levels to compare: portable, and the best one here (if higher).
fn levels() -> Vec<SimdLevel> {
    limit_simd_level(SimdLevel::Avx2);
    let best = simd_level();
    if best == SimdLevel::Portable {
        vec![SimdLevel::Portable]
    } else {
        vec![SimdLevel::Portable, best]
    }
}

#[test]
fn every_golden_scene_hashes_to_its_constant_at_every_level() {
    type Scene = fn() -> Result<golden_scenes::Outcome, golden_scenes::SceneError>;
    let scenes: [(&str, Scene, u64); 8] = [
        ("core", golden_scenes::core_scene, GOLDEN_CORE_SCENE),
        ("pyramid", golden_scenes::pyramid, GOLDEN_PYRAMID),
        ("mixed", golden_scenes::mixed, GOLDEN_MIXED),
        ("long-running", golden_scenes::long_running, GOLDEN_LONG),
        ("every-shape", golden_scenes::shapes, GOLDEN_SHAPES),
        ("compound-body", golden_scenes::compound, GOLDEN_COMPOUND),
        ("banded-tower", golden_scenes::banded_tower, GOLDEN_BANDED),
        ("pivot net", golden_scenes::pivot_net, GOLDEN_PIVOT_NET),
    ];
    for level in levels() {
        limit_simd_level(level);
        assert_eq!(simd_level(), level);
        for (name, scene, golden) in scenes {
            let out = scene().expect("scene");
            println!("{level:?}: {name} {:#018x}", out.hash);
            assert_eq!(out.hash, golden, "{name} at {level:?}");
        }
    }
    limit_simd_level(SimdLevel::Avx2);
}

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

/// 240 boxes and circles of mixed sizes and masses dropped into a cup (piles,
/// stacks, two-point manifolds), and 30 circles created at one point, whose
/// contacts overflow the colours.
fn pile() -> World<'static> {
    let mut w = World::with_capacities(WorldDef::new(s(200.0), s(200.0)), Capacities::for_bodies(280))
        .expect("world");
    w.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-10.0)))).expect("gravity");
    let floor = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("floor")).expect("path");
    let wall = w.add_path(PolygonPath::rectangle(s(1.0), s(30.0)).expect("wall")).expect("path");
    w.add_body(BodyDef::polygon(floor).position(Vector2::new(s(100.0), s(10.0))).static_body())
        .expect("floor");
    for x in [80.0, 120.0] {
        w.add_body(BodyDef::polygon(wall).position(Vector2::new(s(x), s(25.0))).static_body()).expect("wall");
    }
    let boxes = [
        w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path"),
        w.add_path(PolygonPath::rectangle(s(2.0), s(0.5)).expect("plank")).expect("path"),
    ];
    for i in 0..240u32 {
        let x = 85.0 + f64::from(i % 20) * 1.5;
        let y = 15.0 + f64::from(i / 20) * 1.6;
        let def = match i % 3 {
            0 => BodyDef::circle(s(0.3 + f64::from(i % 5) * 0.1)),
            1 => BodyDef::polygon(boxes[0]).mass(s(1.0 + f64::from(i % 7))),
            _ => BodyDef::polygon(boxes[1]).angle(s(0.1 * f64::from(i % 4))),
        };
        w.add_body(def.position(Vector2::new(s(x), s(y))).restitution(s(0.2 * f64::from(i % 2))))
            .expect("body");
    }
    // A crowd created at one point: more contacts per body than colours.
    for _ in 0..30 {
        w.add_body(BodyDef::circle(s(0.5)).position(Vector2::new(s(100.0), s(60.0)))).expect("crowd");
    }
    w
}

#[test]
fn a_pile_steps_to_the_same_bits_at_every_level_step_by_step() {
    let levels = levels();
    let mut worlds: Vec<World<'static>> = levels.iter().map(|_| pile()).collect();
    for step in 0..300 {
        let mut hashes = Vec::new();
        for (w, &level) in worlds.iter_mut().zip(&levels) {
            limit_simd_level(level);
            w.step(s(1.0 / 60.0)).expect("step");
            hashes.push(w.state_hash());
        }
        assert!(
            hashes.windows(2).all(|p| p[0] == p[1]),
            "levels {levels:?} differ first at step {step}: {hashes:x?}"
        );
    }
    limit_simd_level(SimdLevel::Avx2);
    let stats = worlds[0].stats();
    println!("{levels:?} agree for 300 steps; {stats:?}");
    assert!(stats.peak_overflow_constraints > 0, "the crowd overflows the colours");
}
