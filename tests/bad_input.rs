//! Bad input gets a clear error, and nothing changes: every rejected call leaves
//! the state hash as it was.

use arphysics::math::scalar;
use arphysics::{
    BodyDef, BodyHandle, Error, GravityForceGenerator, PolygonPath, Rect, Rot, Scalar, Vector2, World,
    WorldBuffers, WorldDef, MAX_TIME_STEP, MIN_TIME_STEP,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// A small world with a few bodies and gravity, already stepped once.
fn scene(buffers: &mut WorldBuffers<8, 32>) -> (World<'_>, BodyHandle) {
    let mut w = World::new(WorldDef::new(s(100.0), s(100.0)), buffers.storage()).expect("world");
    let path = w.add_path(PolygonPath::rectangle(s(2.0), s(1.0)).expect("box")).expect("path");
    let a = w.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 50.0))).expect("a");
    w.add_body(BodyDef::polygon(path).position(v(20.0, 50.0))).expect("b");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -9.81))).expect("g");
    w.step(s(1.0 / 60.0)).expect("step");
    (w, a)
}

/// Runs `f` on a fresh scene, checks it returns `expected`, and that the state hash
/// did not move.
fn rejects(expected: Error, f: impl FnOnce(&mut World<'_>, BodyHandle) -> Result<(), Error>) {
    let mut buffers = WorldBuffers::new();
    let (mut w, a) = scene(&mut buffers);
    let before = w.state_hash();
    assert_eq!(f(&mut w, a), Err(expected));
    assert_eq!(w.state_hash(), before, "rejected call changed the world ({expected})");
}

#[test]
fn non_finite_floats_are_rejected_at_the_api_edge() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300] {
        assert_eq!(Vector2::try_from_f64(bad, 1.0, "position"), Err(Error::NotFinite { what: "position" }));
        assert_eq!(scalar::try_from_f64(bad, "dt"), Err(Error::NotFinite { what: "dt" }));
    }
    assert_eq!(scalar::try_from_f32(f32::NAN, "radius"), Err(Error::NotFinite { what: "radius" }));
    assert_eq!(Vector2::try_from_f32(1.5, -2.0, "p"), Ok(v(1.5, -2.0)));
}

#[test]
fn non_positive_radius_mass_or_density_is_rejected() {
    let radius = Error::OutOfRange { what: "radius" };
    rejects(radius, |w, _| w.add_body(BodyDef::circle(s(0.0)).position(v(5.0, 5.0))).map(drop));
    rejects(radius, |w, _| w.add_body(BodyDef::circle(s(-1.0)).position(v(5.0, 5.0))).map(drop));
    rejects(radius, |w, _| w.add_body(BodyDef::circle(s(129.0)).position(v(5.0, 5.0))).map(drop));
    let mass = Error::OutOfRange { what: "mass" };
    rejects(mass, |w, _| w.add_body(BodyDef::circle(s(1.0)).position(v(5.0, 5.0)).mass(s(-2.0))).map(drop));
    let density = Error::OutOfRange { what: "density" };
    rejects(density, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(v(5.0, 5.0)).density(s(0.0))).map(drop)
    });
    rejects(density, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(v(5.0, 5.0)).density(s(-1.0))).map(drop)
    });
}

#[test]
fn out_of_range_materials_and_speeds_are_rejected() {
    let at = v(5.0, 5.0);
    rejects(Error::OutOfRange { what: "friction" }, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(at).friction(s(-0.1))).map(drop)
    });
    rejects(Error::OutOfRange { what: "restitution" }, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(at).restitution(s(1.5))).map(drop)
    });
    rejects(Error::OutOfRange { what: "linear velocity" }, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(at).linear_velocity(v(1e6, 0.0))).map(drop)
    });
    rejects(Error::OutOfRange { what: "angular velocity" }, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(at).angular_velocity(s(-1e5))).map(drop)
    });
    let zero_rot = Rot { c: Scalar::ZERO, s: Scalar::ZERO };
    rejects(Error::OutOfRange { what: "rotation" }, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(at).rotation(zero_rot)).map(drop)
    });
    rejects(Error::OutOfRange { what: "rotation" }, |w, a| w.set_rotation(a, zero_rot));
}

#[test]
fn degenerate_polygons_are_rejected() {
    assert_eq!(PolygonPath::rectangle(s(0.0), s(1.0)), Err(Error::OutOfRange { what: "rectangle side" }));
    assert_eq!(PolygonPath::rectangle(s(1.0), s(-1.0)), Err(Error::OutOfRange { what: "rectangle side" }));
}

#[test]
fn positions_outside_the_bounds_are_rejected() {
    rejects(Error::OutsideBounds, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(v(-1.0, 5.0))).map(drop)
    });
    rejects(Error::OutsideBounds, |w, _| {
        w.add_body(BodyDef::circle(s(1.0)).position(v(5.0, 100.5))).map(drop)
    });
    rejects(Error::OutsideBounds, |w, a| w.set_position(a, v(101.0, 5.0)));
}

#[test]
fn bad_time_steps_are_rejected() {
    for dt in [
        Scalar::ZERO,
        Scalar::DELTA,
        MIN_TIME_STEP - Scalar::DELTA,
        s(-0.1),
        MAX_TIME_STEP + Scalar::DELTA,
        Scalar::MAX,
        Scalar::MIN,
    ] {
        rejects(Error::InvalidTimeStep, |w, _| w.step(dt).map(drop));
    }
}

/// Limit L3 of the lane solver (`docs/design/solver-lanes.md` §2.2): the shortest
/// accepted step is 2^-16 s, so the sub-step's inverse stays ≤ 2^20 per second.
#[test]
fn the_shortest_time_step_is_two_to_the_minus_sixteen() {
    assert_eq!(MIN_TIME_STEP, Scalar::from_num(1.0 / 65_536.0));
    let mut buffers = WorldBuffers::<8, 32>::new();
    let (mut w, _) = scene(&mut buffers);
    w.step(MIN_TIME_STEP).expect("the shortest step is accepted");
    w.step(MIN_TIME_STEP + Scalar::DELTA).expect("a longer one too");
    w.step(MAX_TIME_STEP).expect("and the longest");
}

#[test]
fn stale_handles_are_rejected_everywhere() {
    let mut buffers = WorldBuffers::<8, 32>::new();
    let (mut w, a) = scene(&mut buffers);
    w.remove_body(a).expect("live");
    let before = w.state_hash();
    let results = [
        w.body(a).map(drop),
        w.body_mut(a).map(drop),
        w.set_position(a, v(1.0, 1.0)),
        w.set_angle(a, s(1.0)),
        w.set_static(a),
        w.remove_body(a).map(drop),
        w.body(BodyHandle::NULL).map(drop),
    ];
    assert!(results.iter().all(|r| *r == Err(Error::StaleHandle)), "{results:?}");
    assert_eq!(w.state_hash(), before);
    // A stale path handle in a body definition.
    let mut buffers = WorldBuffers::<8, 32>::new();
    let (mut w, _) = scene(&mut buffers);
    let p = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    w.remove_path(p).expect("unused path");
    let before = w.state_hash();
    assert_eq!(w.add_body(BodyDef::polygon(p).position(v(5.0, 5.0))).err(), Some(Error::StaleHandle));
    assert_eq!(w.path(p).err(), Some(Error::StaleHandle));
    assert_eq!(w.state_hash(), before);
}

#[test]
fn invalid_world_definitions_are_rejected() {
    let mut buffers = WorldBuffers::<8, 32>::new();
    let cases = [
        (WorldDef::new(s(0.0), s(10.0)), "world size"),
        (WorldDef::new(s(-5.0), s(10.0)), "world size"),
        (WorldDef::new(s(3e6), s(10.0)), "world bounds"),
        (WorldDef::with_bounds(Rect::from_corners(v(-2e6, 0.0), v(0.0, 1.0))), "world bounds"),
    ];
    for (def, what) in cases {
        assert_eq!(World::new(def, buffers.storage()).err(), Some(Error::OutOfRange { what }));
    }
    let mut def = WorldDef::new(s(10.0), s(10.0));
    def.max_linear_speed = s(5000.0);
    assert_eq!(
        World::new(def, buffers.storage()).err(),
        Some(Error::OutOfRange { what: "max_linear_speed" })
    );
    type Tweak = fn(&mut WorldDef);
    let settings: [(Tweak, &str); 7] = [
        (|d| d.substeps = 0, "substeps"),
        (|d| d.substeps = u32::MAX, "substeps"),
        (|d| d.contact_hertz = -Scalar::ONE, "contact_hertz"),
        (|d| d.contact_damping_ratio = Scalar::MAX, "contact_damping_ratio"),
        (|d| d.contact_push_speed = -Scalar::ONE, "contact_push_speed"),
        (|d| d.restitution_threshold = Scalar::MIN, "restitution_threshold"),
        (|d| d.max_angular_speed = Scalar::ZERO, "max_angular_speed"),
    ];
    for (tweak, what) in settings {
        let mut def = WorldDef::new(s(10.0), s(10.0));
        tweak(&mut def);
        assert_eq!(World::new(def, buffers.storage()).err(), Some(Error::OutOfRange { what }));
    }
}

#[test]
fn errors_describe_themselves() {
    let text = Error::OutOfRange { what: "radius" }.to_string();
    assert!(text.contains("radius"), "{text}");
    let text = Error::CapacityFull { what: "body" }.to_string();
    assert!(text.contains("body store is full"), "{text}");
}
