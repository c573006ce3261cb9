//! The engine core: the manual's setup, force generators, handles and storage.

use arphysics::{
    Body, BodyDef, BodyHandle, Error, ForceGenerator, Generator, GravityForceGenerator,
    GravityToPointForceGenerator, LinearForceGenerator, Rect, Scalar, Targets, Vector2, World, WorldBuffers,
    WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// The manual's "Setting up a new physics simulation": 320×240 world, a 5 kg ball of
/// radius 5 at (50, 50), gravity (0, −9.81), with `substeps` solver sub-steps.
fn manual_world(buffers: &mut WorldBuffers<16, 64>, substeps: u32) -> (World<'_>, BodyHandle) {
    let mut def = WorldDef::new(s(320.0), s(240.0));
    def.substeps = substeps;
    let mut world = World::new(def, buffers.storage()).expect("valid world");
    let ball = world.add_body(BodyDef::circle(s(5.0)).position(v(50.0, 50.0)).mass(s(5.0))).expect("ball");
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -9.81))).expect("gravity");
    (world, ball)
}

/// Semi-implicit Euler with `k` sub-steps of h = dt/k per step: after n steps
/// (M = k·n sub-steps) v = g·dt·n and y = y0 + g·h²·M(M+1)/2.
fn largest_deviation_from_closed_form(substeps: u32) -> f64 {
    let mut buffers = WorldBuffers::new();
    let (mut world, ball) = manual_world(&mut buffers, substeps);
    let dt = 1.0 / 60.0;
    let h = dt / f64::from(substeps);
    let g = -9.81;
    let mut worst: f64 = 0.0;
    for n in 1..=120u32 {
        world.step(s(dt)).expect("step");
        let m = f64::from(n * substeps);
        let y = 50.0 + g * h * h * m * (m + 1.0) / 2.0;
        let vy = g * dt * f64::from(n);
        let b = world.body(ball).expect("live");
        let (px, py) = b.position().to_f64();
        let (_, bvy) = b.linear_velocity().to_f64();
        worst = worst.max((py - y).abs()).max((px - 50.0).abs()).max((bvy - vy).abs());
    }
    worst
}

#[test]
fn falling_ball_matches_semi_implicit_euler_closed_form() {
    for substeps in [1, 4] {
        let worst = largest_deviation_from_closed_form(substeps);
        println!("{substeps} sub-step(s): largest deviation from the closed form over 2 s: {worst:e} (threshold 1e-6)");
        assert!(worst <= 1e-6, "{substeps}: {worst}");
    }
}

#[test]
fn gravity_accelerates_every_mass_alike_but_a_linear_force_does_not() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(1000.0), s(1000.0)), buffers.storage()).expect("world");
    let light = world.add_body(BodyDef::circle(s(1.0)).position(v(100.0, 500.0)).mass(s(1.0))).expect("b");
    let heavy = world.add_body(BodyDef::circle(s(1.0)).position(v(200.0, 500.0)).mass(s(10.0))).expect("b");
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("g");
    world.add_force_generator(LinearForceGenerator::new(v(20.0, 0.0))).expect("f");
    world.step(s(0.1)).expect("step");
    let (l, h) = (world.body(light).expect("l"), world.body(heavy).expect("h"));
    // Gravity: Δv = g·dt = −1 for both (to the rounding of 0.1 in Q32.32, ~2e-9).
    // Force: Δv = F/m·dt = 2 and 0.2.
    assert_eq!(l.linear_velocity().y, h.linear_velocity().y);
    assert!((l.linear_velocity().y - s(-1.0)).abs() < s(1e-8));
    assert!((l.linear_velocity().x - s(2.0)).abs() < s(1e-6));
    assert!((h.linear_velocity().x - s(0.2)).abs() < s(1e-6));
}

#[test]
fn gravity_to_point_pulls_towards_the_point_and_targets_filter() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let a = world.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 50.0))).expect("a");
    let b = world.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 80.0))).expect("b");
    let c = world.add_body(BodyDef::circle(s(1.0)).position(v(80.0, 50.0)).collision_level(7)).expect("c");
    let targets = Targets::bodies(&[a, b]).expect("fits");
    world
        .add_force_generator(GravityToPointForceGenerator::new(v(50.0, 50.0), s(3.0)).with_targets(targets))
        .expect("g");
    world
        .add_force_generator(LinearForceGenerator::new(v(0.0, 5.0)).with_targets(Targets::Level(7)))
        .expect("l");
    world.step(s(0.25)).expect("step");
    let va = world.body(a).expect("a").linear_velocity();
    let vb = world.body(b).expect("b").linear_velocity();
    let vc = world.body(c).expect("c").linear_velocity();
    assert!((va - v(0.75, 0.0)).length() < s(1e-6), "{va:?}");
    assert!((vb - v(0.0, -0.75)).length() < s(1e-6), "{vb:?}");
    // c is only in the level-7 linear force: Δv = F/m·dt with m = π·1²·1.
    let expected = 5.0 / std::f64::consts::PI * 0.25;
    assert!((vc.y.to_num::<f64>() - expected).abs() < 1e-6 && vc.x == Scalar::ZERO, "{vc:?}");
}

/// A user generator: wind that only blows inside an area (the manual's example of
/// `shouldApplyToBody`).
struct AreaWind {
    area: Rect,
    force: Vector2,
    calls: u32,
}

impl ForceGenerator for AreaWind {
    fn applies_to(&self, _: BodyHandle, body: &Body) -> bool {
        self.area.contains(body.position())
    }
    fn apply(&mut self, _: BodyHandle, body: &mut Body, dt: Scalar) {
        self.calls += 1;
        body.apply_force(self.force, dt);
    }
}

#[test]
fn a_user_generator_as_a_trait_object_sees_only_the_bodies_it_accepts() {
    let mut wind =
        AreaWind { area: Rect::from_corners(v(0.0, 0.0), v(50.0, 100.0)), force: v(10.0, 0.0), calls: 0 };
    {
        let mut buffers = WorldBuffers::<16, 64>::new();
        let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
        let inside = world.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 50.0)).mass(s(2.0))).expect("b");
        let outside =
            world.add_body(BodyDef::circle(s(1.0)).position(v(90.0, 50.0)).mass(s(2.0))).expect("b");
        let ground = world
            .add_body(BodyDef::circle(s(1.0)).position(v(20.0, 10.0)).static_body())
            .expect("static body");
        world.add_force_generator(Generator::borrowed(&mut wind)).expect("wind");
        for _ in 0..3 {
            world.step(s(0.1)).expect("step");
        }
        assert!((world.body(inside).expect("b").linear_velocity().x - s(1.5)).abs() < s(1e-6));
        assert_eq!(world.body(outside).expect("b").linear_velocity(), Vector2::ZERO);
        assert_eq!(world.body(ground).expect("b").position(), v(20.0, 10.0));
    }
    assert_eq!(wind.calls, 3, "one dynamic body inside, three steps; static bodies never offered");
}

#[test]
fn a_removed_bodys_handle_is_an_error_not_another_body() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let a = world.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 10.0))).expect("a");
    world.remove_body(a).expect("removed");
    let b = world.add_body(BodyDef::circle(s(2.0)).position(v(20.0, 20.0))).expect("b");
    assert_eq!(a.index(), b.index(), "slot reused");
    assert_eq!(world.body(a).err(), Some(Error::StaleHandle));
    assert_eq!(world.remove_body(a).err(), Some(Error::StaleHandle));
    assert_eq!(world.body(b).expect("b").position(), v(20.0, 20.0));
}

#[test]
fn polygon_bodies_share_one_path_without_copying_vertices() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let path = world.add_path(arphysics::PolygonPath::rectangle(s(2.0), s(1.0)).expect("box")).expect("path");
    let a = world.add_body(BodyDef::polygon(path).position(v(10.0, 10.0))).expect("a");
    let b = world.add_body(BodyDef::polygon(path).position(v(30.0, 10.0)).density(s(3.0))).expect("b");
    // A body stores a handle, not the vertices: it is smaller than the path itself.
    assert!(core::mem::size_of::<Body>() < core::mem::size_of::<arphysics::PolygonPath>());
    assert!((world.body(a).expect("a").mass() - s(2.0)).abs() < s(1e-9));
    assert!((world.body(b).expect("b").mass() - s(6.0)).abs() < s(1e-9));
    // I = m(w² + h²)/12 = 2·5/12.
    assert!((world.body(a).expect("a").inertia() - s(10.0 / 12.0)).abs() < s(1e-6));
    assert!(matches!(world.remove_path(path), Err(Error::InvalidOperation { .. })));
    world.remove_body(a).expect("a");
    world.remove_body(b).expect("b");
    assert!(world.remove_path(path).is_ok());
    let aabb = world.body(a).map(|b| b.aabb());
    assert_eq!(aabb.err(), Some(Error::StaleHandle));
}

#[test]
fn mass_zero_or_set_static_makes_a_body_static() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("g");
    let a = world.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 50.0)).mass(Scalar::ZERO)).expect("a");
    let b = world.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 50.0))).expect("b");
    world.set_static(b).expect("b");
    let k = world
        .add_body(BodyDef::circle(s(1.0)).position(v(30.0, 50.0)).kinematic().linear_velocity(v(1.0, 0.0)))
        .expect("k");
    for _ in 0..10 {
        world.step(s(0.1)).expect("step");
    }
    assert!(world.body(a).expect("a").is_static());
    assert_eq!(world.body(a).expect("a").position(), v(10.0, 50.0));
    assert_eq!(world.body(b).expect("b").position(), v(20.0, 50.0));
    // Kinematic: moves with its velocity, ignores gravity.
    let kp = world.body(k).expect("k").position();
    assert!((kp - v(31.0, 50.0)).length() < s(1e-6), "{kp:?}");
}

#[test]
fn a_body_leaving_the_bounds_is_frozen_and_reported() {
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let a = world
        .add_body(BodyDef::circle(s(1.0)).position(v(50.0, 1.0)).linear_velocity(v(0.0, -30.0)))
        .expect("a");
    let r = world.step(s(0.1)).expect("step");
    assert_eq!(r.left_bounds, 1);
    let b = *world.body(a).expect("a");
    assert!(b.is_out_of_bounds());
    assert_eq!(b.linear_velocity(), Vector2::ZERO);
    assert_eq!(world.out_of_bounds_bodies().collect::<Vec<_>>(), vec![a]);
    let frozen_at = b.position();
    assert_eq!(world.step(s(0.1)).expect("step").left_bounds, 0);
    assert_eq!(world.body(a).expect("a").position(), frozen_at);
    world.set_position(a, v(50.0, 50.0)).expect("back");
    assert!(!world.body(a).expect("a").is_out_of_bounds());
}

#[test]
fn speeds_are_clamped_to_the_world_limits() {
    let mut def = WorldDef::new(s(10_000.0), s(10_000.0));
    def.max_linear_speed = s(100.0);
    let mut buffers = WorldBuffers::<16, 64>::new();
    let mut world = World::new(def, buffers.storage()).expect("world");
    let a = world.add_body(BodyDef::circle(s(1.0)).position(v(5000.0, 5000.0))).expect("a");
    world.add_force_generator(LinearForceGenerator::new(v(1e6, 1e6))).expect("f");
    world.body_mut(a).expect("a").set_angular_velocity(s(1000.0));
    world.step(s(0.001)).expect("step");
    let b = world.body(a).expect("a");
    let speed = b.linear_velocity().length();
    assert!(speed <= s(100.0) && speed > s(99.999), "{speed}");
    assert_eq!(b.angular_velocity(), s(200.0), "default angular limit");
    // At a long step the quarter-turn-per-step limit is the tighter one: (π/4)/0.01.
    world.body_mut(a).expect("a").set_angular_velocity(s(1000.0));
    world.step(s(0.01)).expect("step");
    let w = world.body(a).expect("a").angular_velocity().to_num::<f64>();
    assert!((w - std::f64::consts::FRAC_PI_4 / 0.01).abs() < 1e-6, "{w}");
}

#[test]
fn full_stores_are_errors() {
    let mut buffers = WorldBuffers::<2, 8>::new();
    let mut world = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    world.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 10.0))).expect("1");
    world.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 10.0))).expect("2");
    let before = world.state_hash();
    assert_eq!(
        world.add_body(BodyDef::circle(s(1.0)).position(v(30.0, 10.0))).err(),
        Some(Error::CapacityFull { what: "body" })
    );
    assert_eq!(world.state_hash(), before, "a failed add changes nothing");
    for _ in 0..arphysics::world::MAX_FORCE_GENERATORS {
        world.add_force_generator(GravityForceGenerator::new(v(0.0, -1.0))).expect("g");
    }
    let before = world.state_hash();
    assert!(matches!(
        world.add_force_generator(GravityForceGenerator::new(v(0.0, -1.0))),
        Err(Error::CapacityFull { what: "force generator" })
    ));
    assert_eq!(world.state_hash(), before);
}
