//! Golden state hash: a fixed scene stepped 600 times must hash to a committed
//! constant, in debug and release, on every target. A change to this constant must
//! be deliberate and explained in its commit message.

use arphysics::{
    BodyDef, GravityForceGenerator, GravityToPointForceGenerator, LinearForceGenerator, PolygonPath, Scalar,
    Targets, Vector2, World, WorldBuffers, WorldDef,
};

/// Only exact constants (no float conversion) so the scene itself cannot vary.
fn q(num: i32, den: i32) -> Scalar {
    Scalar::from_num(num) / Scalar::from_num(den)
}

fn core_scene(buffers: &mut WorldBuffers<32, 128>) -> World<'_> {
    let mut w = World::new(WorldDef::new(q(320, 1), q(240, 1)), buffers.storage()).expect("world");
    let tall = w.add_path(PolygonPath::rectangle(q(1, 2), q(3, 1)).expect("box")).expect("path");
    let square = w.add_path(PolygonPath::rectangle(q(2, 1), q(2, 1)).expect("box")).expect("path");
    let mut targets = Vec::new();
    for i in 0..8 {
        let x = q(20 + 30 * i, 1);
        let c = w
            .add_body(BodyDef::circle(q(1 + i, 4)).position(Vector2::new(x, q(200, 1))).mass(q(1 + i, 1)))
            .expect("circle");
        targets.push(c);
        w.add_body(
            BodyDef::polygon(if i % 2 == 0 { tall } else { square })
                .position(Vector2::new(x, q(120, 1)))
                .angle(q(i, 3))
                .angular_velocity(q(i - 4, 2))
                .linear_velocity(Vector2::new(q(i, 1), q(3, 1))),
        )
        .expect("polygon");
    }
    w.add_body(BodyDef::circle(q(5, 1)).position(Vector2::new(q(160, 1), q(20, 1))).static_body())
        .expect("static");
    w.add_force_generator(GravityForceGenerator::new(Vector2::new(q(0, 1), q(-981, 100)))).expect("gravity");
    w.add_force_generator(
        LinearForceGenerator::new(Vector2::new(q(7, 2), q(0, 1)))
            .with_targets(Targets::bodies(&targets[..3]).expect("t")),
    )
    .expect("wind");
    w.add_force_generator(GravityToPointForceGenerator::new(Vector2::new(q(160, 1), q(120, 1)), q(4, 1)))
        .expect("attractor");
    w
}

#[test]
fn core_scene_hash_after_600_steps_is_the_committed_constant() {
    let mut buffers = WorldBuffers::new();
    let mut w = core_scene(&mut buffers);
    let dt = q(1, 60);
    for _ in 0..600 {
        w.step(dt).expect("step");
    }
    let hash = w.state_hash();
    println!("core scene hash after 600 steps: {hash:#018x}");
    assert_eq!(hash, GOLDEN_CORE_SCENE);
}

/// Committed golden value; see the commit that last changed it for why.
const GOLDEN_CORE_SCENE: u64 = 0x45e9_5aa0_bfe4_5b0f;
