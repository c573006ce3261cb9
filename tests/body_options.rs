//! Body options (fixed rotation, damping, gravity scale, Box2D's collision
//! filter), the setters that change a body after creation, kinematic target
//! poses, and the options' place in the snapshot: each against an analytic
//! value or a stated threshold.

use arphysics::limits::{MAX_BODY_DAMPING, MAX_GRAVITY_SCALE};
use arphysics::math::scalar::try_from_f64;
use arphysics::snapshot::PROPS_RECORD;
use arphysics::{
    BodyDef, BodyHandle, BodyType, Capacities, CollisionFilter, Error, GravityForceGenerator,
    GravityToPointForceGenerator, JointDef, JointKind, MassSpec, PolygonPath, Rect, Rot, Scalar, Vector2,
    World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

use std::f64::consts::FRAC_PI_2;

const DT: f64 = 1.0 / 60.0;

fn dt() -> Scalar {
    Scalar::ONE / Scalar::from_num(60)
}

/// A 200 × 200 m world with room for 32 bodies, no generator.
fn world() -> World<'static> {
    let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
    World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(32)).expect("world")
}

fn with_gravity(mut w: World<'static>) -> World<'static> {
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    w
}

/// A static ground box, 80 m wide, top at y = 0.
fn ground(w: &mut World<'static>) -> BodyHandle {
    let path = w.add_path(PolygonPath::rectangle(s(80.0), s(2.0)).expect("box")).expect("path");
    w.add_body(BodyDef::polygon(path).static_body().position(v(0.0, -1.0))).expect("ground")
}

fn step(w: &mut World<'static>, n: u32) {
    for _ in 0..n {
        w.step(dt()).expect("step");
    }
}

// ---- fixed rotation ------------------------------------------------------------

/// A box dropped corner-first on a 30° ramp: free, it tips over; with fixed
/// rotation its rotation stays exactly the identity and its spin exactly 0 on
/// every step, while it lands and slides down.
#[test]
fn a_fixed_rotation_box_on_a_ramp_keeps_its_angle_exactly_zero() {
    let run = |fixed: bool| {
        let mut w = with_gravity(world());
        let ramp = w.add_path(PolygonPath::rectangle(s(40.0), s(2.0)).expect("ramp")).expect("path");
        w.add_body(
            BodyDef::polygon(ramp).static_body().position(v(0.0, 0.0)).angle(s(std::f64::consts::FRAC_PI_6)),
        )
        .expect("ramp");
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
        let b = w
            .add_body(BodyDef::polygon(unit).position(v(0.0, 2.5)).friction(s(0.2)).fixed_rotation(fixed))
            .expect("box");
        let start = w.body(b).expect("live").position();
        let mut max_spin = 0.0f64;
        for _ in 0..180 {
            w.step(dt()).expect("step");
            let body = w.body(b).expect("live");
            if fixed {
                assert_eq!(body.rotation(), Rot::IDENTITY, "rotation changed");
                assert_eq!(body.angular_velocity(), Scalar::ZERO, "spin");
            }
            max_spin = max_spin.max(body.angular_velocity().to_f64().abs());
        }
        let body = *w.body(b).expect("live");
        (body, start, max_spin)
    };
    let (fixed, start, _) = run(true);
    assert!(fixed.is_fixed_rotation());
    assert!(fixed.position().x < start.x - s(1.0), "it slid down the ramp: {:?}", fixed.position());
    let (free, _, spin) = run(false);
    assert!(
        spin > 0.1 && free.angle().to_f64().abs() > 0.05,
        "the free box turns: {spin} {:?}",
        free.angle()
    );
}

/// Impulses and `set_angular_velocity` cannot spin a fixed-rotation body.
#[test]
fn nothing_spins_a_fixed_rotation_body() {
    let mut w = world();
    let b = w.add_body(BodyDef::circle(s(1.0)).fixed_rotation(true).angular_velocity(s(3.0))).expect("b");
    assert_eq!(w.body(b).expect("live").angular_velocity(), Scalar::ZERO, "the def's spin is dropped");
    let body = w.body_mut(b).expect("live");
    body.apply_angular_impulse(s(10.0));
    body.apply_impulse_at(v(0.0, 10.0), v(1.0, 0.0));
    body.set_angular_velocity(s(2.0));
    assert_eq!(body.angular_velocity(), Scalar::ZERO);
    assert_eq!(body.linear_velocity(), v(0.0, 10.0) * body.inv_mass(), "the linear part still acts");
    w.set_fixed_rotation(b, false).expect("live");
    w.body_mut(b).expect("live").set_angular_velocity(s(2.0));
    w.set_fixed_rotation(b, true).expect("live");
    assert_eq!(w.body(b).expect("live").angular_velocity(), Scalar::ZERO, "locking stops the spin");
}

/// A box pinned by a pivot 3 m to its side to a world point: free, it swings
/// down as a pendulum; with fixed rotation it cannot turn about the pivot, so
/// the joint holds it in place (within 1 cm) and its rotation stays exactly
/// the identity: the joint sees its infinite inertia too.
#[test]
fn a_fixed_rotation_body_on_a_pivot_is_held_in_place() {
    let run = |fixed: bool| {
        let mut w = with_gravity(world());
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
        let b = w.add_body(BodyDef::polygon(unit).position(v(3.0, 10.0)).fixed_rotation(fixed)).expect("b");
        let kind = JointKind::Pivot { limits: None, motor: None };
        w.add_joint(JointDef::to_world(b, v(-3.0, 0.0), v(0.0, 10.0), kind)).expect("joint");
        let mut lowest = 10.0f64;
        for _ in 0..120 {
            w.step(dt()).expect("step");
            let body = w.body(b).expect("live");
            if fixed {
                assert_eq!(body.rotation(), Rot::IDENTITY);
                assert!((body.position() - v(3.0, 10.0)).length().to_f64() < 0.01, "{:?}", body.position());
            }
            lowest = lowest.min(body.position().y.to_f64());
        }
        lowest
    };
    assert!(run(true) > 9.99);
    let free = run(false);
    assert!(free < 8.0, "the free box swings down: lowest y {free}");
}

// ---- damping --------------------------------------------------------------------

/// Without other forces a damped body's speed follows e^(−c·t) within 1 %, and
/// its spin likewise with the angular damping (Box2D's 1 / (1 + h·c) per
/// sub-step is e^(−c·h) to O((c·h)²): 0.4 % after 2 s at c = 1 and h = 1/240 s).
#[test]
fn a_damped_body_slows_as_e_to_the_minus_c_t() {
    let mut w = world();
    let (c_lin, c_ang) = (1.0, 0.8);
    let b = w
        .add_body(
            BodyDef::circle(s(0.5))
                .position(v(-90.0, 0.0))
                .linear_velocity(v(10.0, 0.0))
                .angular_velocity(s(5.0))
                .linear_damping(s(c_lin))
                .angular_damping(s(c_ang)),
        )
        .expect("b");
    let mut worst = 0.0f64;
    for i in 1..=120 {
        w.step(dt()).expect("step");
        let t = f64::from(i) * DT;
        let body = w.body(b).expect("live");
        let speed = body.linear_velocity().length().to_f64();
        let spin = body.angular_velocity().to_f64();
        let (e_lin, e_ang) = (10.0 * (-c_lin * t).exp(), 5.0 * (-c_ang * t).exp());
        worst = worst.max((speed / e_lin - 1.0).abs()).max((spin / e_ang - 1.0).abs());
        assert!((speed / e_lin - 1.0).abs() < 0.01, "t = {t}: speed {speed}, e^(-ct) gives {e_lin}");
        assert!((spin / e_ang - 1.0).abs() < 0.01, "t = {t}: spin {spin}, e^(-ct) gives {e_ang}");
    }
    println!("damping: worst relative error {worst:.2e} over 2 s");
    // Undamped bodies are untouched.
    let mut w = world();
    let b = w.add_body(BodyDef::circle(s(0.5)).linear_velocity(v(1.0, 0.0))).expect("b");
    step(&mut w, 30);
    assert_eq!(w.body(b).expect("live").linear_velocity(), v(1.0, 0.0));
}

// ---- gravity scale --------------------------------------------------------------

/// A body falls y = g·s·h²·K(K + 1)/2 after K sub-steps of h (the force is
/// spread evenly over the sub-steps, and each sub-step moves at its new
/// velocity): scale 0.5 falls exactly half as far as scale 1, scale 0 floats,
/// −1 rises. The uniform and the point gravity generators both read the scale.
#[test]
fn gravity_scale_half_falls_half_as_far() {
    for point in [false, true] {
        let mut w = world();
        if point {
            // Far below: the direction is (0, −1) for bodies on the y axis.
            w.add_force_generator(GravityToPointForceGenerator::new(v(0.0, -99.0), s(10.0))).expect("g");
        } else {
            w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("g");
        }
        let scales = [1.0, 0.5, 0.0, -1.0];
        let bodies: Vec<_> = scales
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                // Side by side for the uniform gravity; stacked on the line to
                // the point (far apart) for the point gravity.
                let p = if point { v(0.0, 20.0 * i as f64) } else { v(-60.0 + 40.0 * i as f64, 0.0) };
                w.add_body(BodyDef::circle(s(0.5)).position(p).gravity_scale(s(k))).expect("b")
            })
            .collect();
        let steps = 60u32;
        step(&mut w, steps);
        let k_sub = f64::from(steps * 4);
        let h = DT / 4.0;
        let fall = |scale: f64| 10.0 * scale * h * h * k_sub * (k_sub + 1.0) / 2.0;
        let drops: Vec<f64> = bodies
            .iter()
            .enumerate()
            .map(|(i, &b)| {
                let y0 = if point { 20.0 * i as f64 } else { 0.0 };
                y0 - w.body(b).expect("live").position().y.to_f64()
            })
            .collect();
        for (&k, &d) in scales.iter().zip(&drops) {
            assert!((d - fall(k)).abs() < 1e-6, "point {point}, scale {k}: fell {d}, analytic {}", fall(k));
        }
        assert!((drops[1] / drops[0] - 0.5).abs() < 1e-6, "{drops:?}");
        assert_eq!(drops[2], 0.0);
    }
}

// ---- collision filter -------------------------------------------------------------

/// A box dropped on the ground: where it ends (resting on it, or fallen through).
fn lands(ground_filter: CollisionFilter, box_filter: CollisionFilter, groups: (u32, u32)) -> bool {
    let mut w = with_gravity(world());
    let g = ground(&mut w);
    w.set_filter(g, ground_filter).expect("live");
    w.set_collision_groups(g, groups.0).expect("live");
    let b = w
        .add_body(BodyDef::circle(s(0.5)).position(v(0.0, 1.0)).filter(box_filter).collision_groups(groups.1))
        .expect("b");
    step(&mut w, 60);
    let y = w.body(b).expect("live").position().y.to_f64();
    assert!(!(-1.0..=0.4).contains(&y), "either resting on the ground or through it: {y}");
    y > 0.0
}

#[test]
fn category_mask_and_group_index_follow_box2d_combined_with_collision_groups() {
    let f = |category, mask, group| CollisionFilter {
        category_bits: category,
        mask_bits: mask,
        group_index: group,
    };
    let all = CollisionFilter::default();
    assert!(lands(all, all, (0, 0)), "the default collides");
    // The mask must hold the other's category, both ways.
    assert!(!lands(f(0b01, u64::MAX, 0), f(0b10, 0b10, 0), (0, 0)), "the box masks out the ground");
    assert!(!lands(f(0b01, 0b01, 0), f(0b10, u64::MAX, 0), (0, 0)), "the ground masks out the box");
    assert!(lands(f(0b01, 0b10, 0), f(0b10, 0b01, 0), (0, 0)));
    // A shared positive group collides whatever the masks; a negative one never.
    assert!(lands(f(0b01, 0, 3), f(0b10, 0, 3), (0, 0)));
    assert!(!lands(f(0b01, u64::MAX, -3), f(0b10, u64::MAX, -3), (0, 0)));
    // Different groups fall back to the masks.
    assert!(lands(f(1, u64::MAX, -3), f(1, u64::MAX, -4), (0, 0)));
    // The manual's collision groups veto, even over a positive group.
    assert!(!lands(f(1, u64::MAX, 3), f(1, u64::MAX, 3), (0b100, 0b100)));
    assert!(!lands(all, all, (1, 1)));
}

// ---- setters ------------------------------------------------------------------------

/// Every setter checks its input and, on error, leaves the world unchanged
/// (the state hash is the same), stale handles included.
#[test]
fn bad_body_options_are_errors_and_leave_the_world_unchanged() {
    let mut w = with_gravity(world());
    let g = ground(&mut w);
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 3.0))).expect("b");
    let gone = w.add_body(BodyDef::circle(s(0.5)).position(v(5.0, 3.0))).expect("b");
    w.remove_body(gone).expect("live");
    step(&mut w, 5);
    let before = w.state_hash();
    let too_big = MAX_BODY_DAMPING + Scalar::DELTA;
    let out = |what| Err(Error::OutOfRange { what });
    assert_eq!(w.set_linear_damping(b, s(-0.1)), out("damping"));
    assert_eq!(w.set_angular_damping(b, too_big), out("damping"));
    assert_eq!(w.set_gravity_scale(b, MAX_GRAVITY_SCALE + Scalar::DELTA), out("gravity scale"));
    assert_eq!(w.set_gravity_scale(b, -MAX_GRAVITY_SCALE - Scalar::DELTA), out("gravity scale"));
    assert_eq!(w.set_friction(b, s(-1.0)), out("friction"));
    assert_eq!(w.set_restitution(b, s(1.5)), out("restitution"));
    assert_eq!(
        w.set_mass(b, MassSpec::Mass(Scalar::ZERO)).map_err(|e| matches!(e, Error::OutOfRange { .. })),
        Err(true)
    );
    assert_eq!(
        w.set_dynamic(b, MassSpec::Density(s(-1.0))).map_err(|e| matches!(e, Error::OutOfRange { .. })),
        Err(true)
    );
    assert!(matches!(w.set_mass(g, MassSpec::Mass(s(1.0))), Err(Error::InvalidOperation { .. })));
    // NaN and infinities never become a Scalar: the conversion is the error.
    assert_eq!(try_from_f64(f64::NAN, "damping").map(|_| ()), Err(Error::NotFinite { what: "damping" }));
    assert!(try_from_f64(f64::INFINITY, "gravity scale").is_err());
    // A stale handle, for every setter.
    let stale = Err(Error::StaleHandle);
    assert_eq!(w.set_filter(gone, CollisionFilter::default()), stale);
    assert_eq!(w.set_linear_damping(gone, s(1.0)), stale);
    assert_eq!(w.set_angular_damping(gone, s(1.0)), stale);
    assert_eq!(w.set_gravity_scale(gone, s(1.0)), stale);
    assert_eq!(w.set_fixed_rotation(gone, true), stale);
    assert_eq!(w.set_friction(gone, s(1.0)), stale);
    assert_eq!(w.set_restitution(gone, s(0.5)), stale);
    assert_eq!(w.set_mass(gone, MassSpec::Mass(s(1.0))), stale);
    assert_eq!(w.set_dynamic(gone, MassSpec::Mass(s(1.0))), stale);
    assert_eq!(w.set_kinematic(gone), stale);
    assert_eq!(w.set_collision_groups(gone, 1), stale);
    assert_eq!(w.set_target_transform(gone, v(0.0, 0.0), Rot::IDENTITY, dt()), stale);
    // A definition with a bad option is refused too.
    assert_eq!(w.add_body(BodyDef::circle(s(1.0)).linear_damping(s(-1.0))).map(|_| ()), out("damping"));
    assert_eq!(w.add_body(BodyDef::circle(s(1.0)).gravity_scale(s(17.0))).map(|_| ()), out("gravity scale"));
    assert_eq!(w.state_hash(), before, "nothing changed");
    // Good values take effect and are read back.
    w.set_linear_damping(b, s(0.5)).expect("ok");
    w.set_gravity_scale(b, s(-2.0)).expect("ok");
    w.set_friction(b, s(0.9)).expect("ok");
    let body = w.body(b).expect("live");
    assert_eq!((body.linear_damping(), body.gravity_scale(), body.friction()), (s(0.5), s(-2.0), s(0.9)));
    assert_ne!(w.state_hash(), before, "the options are state");
}

/// Body type in both directions, with the mass recomputed from the shape.
#[test]
fn a_body_changes_type_both_ways_with_its_mass_recomputed() {
    let mut w = with_gravity(world());
    let b = w.add_body(BodyDef::circle(s(1.0)).position(v(0.0, 50.0)).static_body()).expect("b");
    step(&mut w, 10);
    assert_eq!(w.body(b).expect("live").position(), v(0.0, 50.0), "static stays");
    // Static → dynamic: density 2 on a unit circle gives m = 2π, I = m·r²/2 = π.
    w.set_dynamic(b, MassSpec::Density(s(2.0))).expect("dynamic");
    let body = w.body(b).expect("live");
    assert_eq!(body.body_type(), BodyType::Dynamic);
    assert!((body.mass().to_f64() - 2.0 * std::f64::consts::PI).abs() < 1e-6, "{:?}", body.mass());
    assert!((body.inertia().to_f64() - std::f64::consts::PI).abs() < 1e-6, "{:?}", body.inertia());
    step(&mut w, 30);
    let vy = w.body(b).expect("live").linear_velocity().y.to_f64();
    assert!((vy + 10.0 * 0.5).abs() < 1e-6, "falls at g: {vy}");
    // Dynamic → kinematic: keeps its velocity, no gravity, no mass.
    w.set_kinematic(b).expect("kinematic");
    step(&mut w, 30);
    let body = w.body(b).expect("live");
    assert_eq!(
        (body.body_type(), body.mass(), body.inv_mass()),
        (BodyType::Kinematic, Scalar::ZERO, Scalar::ZERO)
    );
    assert!((body.linear_velocity().y.to_f64() - vy).abs() < 1e-9, "coasts at {vy}");
    // Kinematic → dynamic with an explicit mass; a new mass later.
    w.set_dynamic(b, MassSpec::Mass(s(3.0))).expect("dynamic");
    assert_eq!(w.body(b).expect("live").mass(), s(3.0));
    w.set_mass(b, MassSpec::Mass(s(6.0))).expect("mass");
    let body = w.body(b).expect("live");
    assert_eq!(body.mass(), s(6.0));
    assert!((body.inertia().to_f64() - 3.0).abs() < 1e-6, "I = m r^2 / 2 for r = 1: {:?}", body.inertia());
    // And static again.
    w.set_static(b).expect("static");
    assert_eq!(w.body(b).expect("live").body_type(), BodyType::Static);
}

/// A box resting on a body that turns static then dynamic again: the contact
/// keeps working through the change (it holds the box up throughout).
#[test]
fn a_pair_keeps_colliding_across_type_changes() {
    let mut w = with_gravity(world());
    ground(&mut w);
    let unit = w.add_path(PolygonPath::rectangle(s(2.0), s(1.0)).expect("box")).expect("path");
    let base = w.add_body(BodyDef::polygon(unit).position(v(0.0, 0.5))).expect("base");
    let top = w.add_body(BodyDef::polygon(unit).position(v(0.0, 1.5))).expect("top");
    step(&mut w, 60);
    w.set_kinematic(base).expect("k");
    w.body_mut(base).expect("live").set_linear_velocity(Vector2::ZERO);
    step(&mut w, 60);
    w.set_dynamic(base, MassSpec::Density(s(1.0))).expect("d");
    step(&mut w, 60);
    let y = w.body(top).expect("live").position().y.to_f64();
    assert!((y - 1.5).abs() < 0.03, "the top box still rests on the base: {y}");
}

// ---- kinematic target pose ------------------------------------------------------------

/// Four kinematic walls of a 10 m box container, driven each step by
/// `set_target_transform` to the poses of one rigid frame that turns at
/// 0.5 rad/s and drifts at (1, 0.5) m/s, with balls rattling inside: each wall
/// reaches its target within 1e-6 m and 1e-6 rad, and the walls' poses
/// relative to the first stay the initial ones within 1e-6 m and 1e-6 rad.
#[test]
fn kinematic_walls_moved_by_targets_stay_rigid() {
    let mut w = with_gravity(world());
    let wall = w.add_path(PolygonPath::rectangle(s(10.0), s(0.5)).expect("wall")).expect("path");
    // Offsets and angles of the walls in the container's frame.
    let frame = [(0.0, -5.0, 0.0), (0.0, 5.0, 0.0), (-5.0, 0.0, FRAC_PI_2), (5.0, 0.0, FRAC_PI_2)];
    let pose = |t: f64, (x, y, a): (f64, f64, f64)| {
        let (c, sn) = ((0.5 * t).cos(), (0.5 * t).sin());
        let centre = (1.0 * t, 0.5 * t);
        (v(centre.0 + c * x - sn * y, centre.1 + sn * x + c * y), Rot::from_angle(s(a + 0.5 * t)))
    };
    let walls: Vec<_> = frame
        .iter()
        .map(|&f| {
            let (p, q) = pose(0.0, f);
            w.add_body(BodyDef::polygon(wall).kinematic().position(p).rotation(q)).expect("wall")
        })
        .collect();
    for i in 0..6 {
        w.add_body(BodyDef::circle(s(0.4)).position(v(-2.0 + 0.8 * f64::from(i), 0.0))).expect("ball");
    }
    let rel = |w: &World<'_>, i: usize| {
        let (a, b) = (w.body(walls[0]).expect("live"), w.body(walls[i]).expect("live"));
        (a.rotation().inv_rotate(b.position() - a.position()), a.rotation().inv_mul(b.rotation()).angle())
    };
    let initial: Vec<_> = (1..4).map(|i| rel(&w, i)).collect();
    let (mut worst_reach, mut worst_rigid) = (0.0f64, 0.0f64);
    for k in 1..=120 {
        let t = f64::from(k) * DT;
        for (&h, &f) in walls.iter().zip(&frame) {
            let (p, q) = pose(t, f);
            w.set_target_transform(h, p, q, dt()).expect("target");
        }
        w.step(dt()).expect("step");
        for (&h, &f) in walls.iter().zip(&frame) {
            let (p, q) = pose(t, f);
            let b = w.body(h).expect("live");
            let dp = (b.position() - p).length().to_f64();
            let da = b.rotation().inv_mul(q).angle().to_f64().abs();
            worst_reach = worst_reach.max(dp).max(da);
        }
        for (i, &(p0, a0)) in (1..4).zip(&initial) {
            let (p, a) = rel(&w, i);
            worst_rigid = worst_rigid.max((p - p0).length().to_f64()).max((a - a0).to_f64().abs());
        }
    }
    println!("kinematic targets: reach error {worst_reach:.2e}, rigidity error {worst_rigid:.2e}");
    assert!(worst_reach < 1e-6, "target missed by {worst_reach}");
    assert!(worst_rigid < 1e-6, "walls moved apart by {worst_rigid}");
}

#[test]
fn a_target_transform_out_of_reach_is_an_error() {
    let mut w = world();
    let fixed = w.add_body(BodyDef::circle(s(1.0)).static_body()).expect("b");
    let k = w.add_body(BodyDef::circle(s(1.0)).kinematic()).expect("b");
    let before = w.state_hash();
    assert!(matches!(
        w.set_target_transform(fixed, v(1.0, 0.0), Rot::IDENTITY, dt()),
        Err(Error::InvalidOperation { .. })
    ));
    // 60 m in 1/60 s is 3,600 m/s, beyond the default 400 m/s limit.
    assert!(matches!(
        w.set_target_transform(k, v(60.0, 0.0), Rot::IDENTITY, dt()),
        Err(Error::OutOfRange { .. })
    ));
    // Half a turn in one step is beyond an eighth of a turn.
    assert!(matches!(
        w.set_target_transform(k, v(0.0, 0.0), Rot::from_angle(s(3.0)), dt()),
        Err(Error::OutOfRange { .. })
    ));
    assert_eq!(w.set_target_transform(k, v(500.0, 0.0), Rot::IDENTITY, dt()), Err(Error::OutsideBounds));
    assert_eq!(
        w.set_target_transform(k, v(0.0, 0.0), Rot::IDENTITY, Scalar::ZERO),
        Err(Error::InvalidTimeStep)
    );
    assert_eq!(w.state_hash(), before);
}

/// A change made to a body through the world's setters.
type Change = fn(&mut World<'static>, BodyHandle);

// ---- snapshot ---------------------------------------------------------------------------

fn optioned(w: &mut World<'static>) -> Vec<BodyHandle> {
    let f = CollisionFilter { category_bits: 0b100, mask_bits: 0xF0F0, group_index: -7 };
    let defs = [
        BodyDef::circle(s(0.5)).position(v(0.0, 5.0)).fixed_rotation(true).linear_damping(s(0.25)),
        BodyDef::circle(s(0.5)).position(v(2.0, 5.0)).angular_damping(s(3.0)).gravity_scale(s(-0.5)),
        BodyDef::circle(s(0.5)).position(v(4.0, 5.0)).filter(f).angular_velocity(s(2.0)),
        BodyDef::circle(s(0.5)).position(v(6.0, 5.0)).kinematic().fixed_rotation(true),
    ];
    defs.iter().map(|d| w.add_body(*d).expect("b")).collect()
}

/// Every option survives a snapshot round trip, is in the state hash, and
/// restore-then-step equals stepping on.
#[test]
fn body_options_round_trip_through_a_snapshot() {
    let mut a = with_gravity(world());
    ground(&mut a);
    let hs = optioned(&mut a);
    step(&mut a, 10);
    let mut buf = vec![0u8; a.snapshot_len()];
    a.snapshot(&mut buf).expect("fits");
    let mut b = with_gravity(world());
    ground(&mut b);
    b.restore(&buf).expect("restore");
    assert_eq!(a.state_hash(), b.state_hash());
    for &h in &hs {
        let hb = b.handle_from_parts(h.index(), h.generation());
        let (x, y) = (a.body(h).expect("live"), b.body(hb).expect("live"));
        assert_eq!(x, y);
        assert_eq!(
            (x.is_fixed_rotation(), x.linear_damping(), x.angular_damping(), x.gravity_scale(), x.filter()),
            (y.is_fixed_rotation(), y.linear_damping(), y.angular_damping(), y.gravity_scale(), y.filter())
        );
    }
    step(&mut a, 30);
    step(&mut b, 30);
    assert_eq!(a.state_hash(), b.state_hash(), "restore-then-step equals stepping on");
    // Each option changes the hash.
    let base = a.state_hash();
    let h = hs[1];
    let changes: [Change; 6] = [
        |w, h| w.set_fixed_rotation(h, true).expect("ok"),
        |w, h| w.set_linear_damping(h, s(0.75)).expect("ok"),
        |w, h| w.set_angular_damping(h, s(0.75)).expect("ok"),
        |w, h| w.set_gravity_scale(h, s(0.75)).expect("ok"),
        |w, h| {
            w.set_filter(h, CollisionFilter { category_bits: 2, ..CollisionFilter::default() }).expect("ok")
        },
        |w, h| w.set_filter(h, CollisionFilter { group_index: 1, ..CollisionFilter::default() }).expect("ok"),
    ];
    for change in changes {
        let mut c = with_gravity(world());
        ground(&mut c);
        let mut buf = vec![0u8; a.snapshot_len()];
        a.snapshot(&mut buf).expect("fits");
        c.restore(&buf).expect("restore");
        assert_eq!(c.state_hash(), base);
        let hc = c.handle_from_parts(h.index(), h.generation());
        change(&mut c, hc);
        assert_ne!(c.state_hash(), base, "the option is in the hash");
    }
}

/// Recomputes a snapshot's checksum trailer after an edit.
fn reseal(snap: &mut [u8]) {
    let n = snap.len();
    let sum = twox_hash::XxHash64::oneshot(0, &snap[..n - 8]);
    snap[n - 8..].copy_from_slice(&sum.to_le_bytes());
}

/// Out-of-range option values in a well-formed snapshot (checksum valid) are
/// rejected, and the world is left as it was.
#[test]
fn a_snapshot_with_bad_body_options_is_rejected() {
    let mut a = world();
    a.add_body(BodyDef::circle(s(0.5))).expect("b");
    let mut good = vec![0u8; a.snapshot_len()];
    a.snapshot(&mut good).expect("fits");
    // The first properties record: after the framing (16), the world (112:
    // step count 8, settings 96 with the contact recycle distance, paths
    // checksum 8) and the record count (4).
    let rec = 16 + 112 + 4;
    assert_eq!(good.len(), rec + PROPS_RECORD + 12 + 64 + 12 + 4 + 12 + 8, "one record of each");
    let edits: [(usize, Vec<u8>, &str); 8] = [
        (rec, vec![4], "an unknown shape kind"),
        (rec + 9, vec![1], "a circle's shape padding not zero"),
        (rec + 25, vec![2 | 0x08], "an unknown flag (0x08)"),
        (rec + 25, vec![2 | 0x80], "an unknown flag"),
        (rec + 74, s(-1.0).to_bits().to_le_bytes().to_vec(), "negative linear damping"),
        (rec + 82, (MAX_BODY_DAMPING + Scalar::DELTA).to_bits().to_le_bytes().to_vec(), "angular damping"),
        (rec + 90, s(16.5).to_bits().to_le_bytes().to_vec(), "gravity scale"),
        (rec + 90, s(-17.0).to_bits().to_le_bytes().to_vec(), "negative gravity scale"),
    ];
    let mut w = world();
    let before = w.state_hash();
    for (at, bytes, what) in edits {
        let mut snap = good.clone();
        snap[at..at + bytes.len()].copy_from_slice(&bytes);
        reseal(&mut snap);
        assert!(matches!(w.restore(&snap), Err(Error::InvalidSnapshot { .. })), "{what} accepted");
        assert_eq!(w.state_hash(), before, "{what}: the world changed");
    }
    // The fixed-rotation bit on a body that spins: the world never writes one.
    let mut spinning = world();
    spinning.add_body(BodyDef::circle(s(0.5)).angular_velocity(s(1.0))).expect("b");
    let mut spun = vec![0u8; spinning.snapshot_len()];
    spinning.snapshot(&mut spun).expect("fits");
    w.restore(&spun).expect("a free body may spin");
    let spin_hash = w.state_hash();
    spun[rec + 25] |= 0x40;
    reseal(&mut spun);
    match w.restore(&spun) {
        Err(Error::InvalidSnapshot { what }) => assert!(what.contains("fixed-rotation"), "{what}"),
        other => panic!("a spinning fixed-rotation body accepted: {other:?}"),
    }
    assert_eq!(w.state_hash(), spin_hash, "the world changed");
    // A valid edit: the fixed-rotation bit and a filter restore as written.
    let mut snap = good.clone();
    snap[rec + 25] |= 0x40;
    snap[rec + 98..rec + 106].copy_from_slice(&0x8u64.to_le_bytes());
    snap[rec + 114..rec + 118].copy_from_slice(&(-2i32).to_le_bytes());
    reseal(&mut snap);
    w.restore(&snap).expect("valid");
    let (_, b) = w.bodies().next().expect("one body");
    assert!(b.is_fixed_rotation());
    assert_eq!(b.filter(), CollisionFilter { category_bits: 8, mask_bits: u64::MAX, group_index: -2 });
}

/// The desync locator names each new field.
#[test]
fn the_desync_locator_names_the_body_options() {
    let mut a = world();
    let h = a.add_body(BodyDef::circle(s(0.5))).expect("b");
    let snap = |w: &World<'_>| {
        let mut buf = vec![0u8; w.snapshot_len()];
        w.snapshot(&mut buf).expect("fits");
        buf
    };
    let base = snap(&a);
    let cases: [(Change, &str); 5] = [
        (|w, h| w.set_fixed_rotation(h, true).expect("ok"), "fixed rotation"),
        (|w, h| w.set_linear_damping(h, s(1.0)).expect("ok"), "linear damping"),
        (|w, h| w.set_angular_damping(h, s(1.0)).expect("ok"), "angular damping"),
        (|w, h| w.set_gravity_scale(h, s(2.0)).expect("ok"), "gravity scale"),
        (
            |w, h| {
                w.set_filter(h, CollisionFilter { mask_bits: 3, ..CollisionFilter::default() }).expect("ok")
            },
            "collision filter",
        ),
    ];
    for (change, field) in cases {
        let mut b = world();
        b.restore(&base).expect("restore");
        let hb = b.handle_from_parts(h.index(), h.generation());
        change(&mut b, hb);
        let d = arphysics::snapshot::diff(&base, &snap(&b)).expect("parse").expect("a difference");
        assert_eq!(d.field, field);
    }
}
