//! Every setter checks its value exactly as the constructor and `restore` do, so
//! whatever a world holds snapshots into bytes its own `restore` accepts; every
//! setting has a documented range and an error naming it; the limits table says
//! exactly which bodies are legal.

use arphysics::force::Targets;
use arphysics::geometry::mass::{MAX_INERTIA, MAX_MASS, MIN_INERTIA, MIN_MASS};
use arphysics::limits::{
    MAX_ACCELERATION, MAX_ARBITER_PERSISTENCE, MAX_COORDINATE, MAX_DAMPING, MAX_FORCE, MAX_FRICTION,
    MAX_JOINT_LENGTH, MAX_MOTOR_SPEED, MAX_STIFFNESS,
};
use arphysics::{
    Arbiter, BodyDef, BodyHandle, CallbackContext, Capacities, Error, FnHandler, GeneratorMut,
    GravityForceGenerator, GravityToPointForceGenerator, JointDef, JointHandle, JointKind,
    LinearForceGenerator, MaxTorque, Motor, Rot, Scalar, Vector2, World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}
fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}
fn out_of_range(what: &'static str) -> Result<(), Error> {
    Err(Error::OutOfRange { what })
}

struct Scene {
    w: World<'static>,
    a: BodyHandle,
    b: BodyHandle,
    pivot: JointHandle,
    gens: [arphysics::GeneratorHandle; 3],
}

fn scene() -> Scene {
    let mut w =
        World::with_capacities(WorldDef::new(s(100.0), s(100.0)), Capacities::for_bodies(40)).expect("world");
    let a = w.add_body(BodyDef::circle(s(0.5)).position(v(10.0, 50.0))).expect("a");
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(11.0, 50.0))).expect("b");
    let pivot = w
        .add_joint(JointDef::to_world(
            a,
            v(0.0, 0.0),
            v(10.0, 50.0),
            JointKind::Pivot { limits: None, motor: None },
        ))
        .expect("pivot");
    let gens = [
        w.add_force_generator(LinearForceGenerator::new(v(1.0, 0.0))).expect("linear"),
        w.add_force_generator(GravityForceGenerator::new(v(0.0, -9.81))).expect("gravity"),
        w.add_force_generator(GravityToPointForceGenerator::new(v(50.0, 50.0), s(1.0))).expect("point"),
    ];
    Scene { w, a, b, pivot, gens }
}

/// Snapshot, restore into the same world: `Ok`, and the state hash unchanged.
#[track_caller]
fn assert_round_trips(w: &mut World<'_>, what: &str) {
    let before = w.state_hash();
    let mut buf = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut buf).expect("snapshot");
    assert_eq!(w.restore(&buf), Ok(()), "{what}: the world's own snapshot must restore");
    assert_eq!(w.state_hash(), before, "{what}: the restored state hashes the same");
    w.step(s(1.0 / 60.0)).expect("the world steps on");
}

/// Runs `f` on the world; it must fail with `expected` and leave the state as it was.
#[track_caller]
fn assert_rejected(
    w: &mut World<'_>,
    expected: Result<(), Error>,
    f: impl FnOnce(&mut World<'_>) -> Result<(), Error>,
) {
    let before = w.state_hash();
    assert_eq!(f(w), expected);
    assert_eq!(w.state_hash(), before, "a rejected value changed the world");
}

/// The audit's reproducer: a negative torque limit used to be stored and then
/// made the world's own snapshot unrestorable.
#[test]
fn set_motor_rejects_negative_torque_and_the_snapshot_still_restores() {
    let Scene { mut w, pivot, .. } = scene();
    let bad = Some(Motor { speed: s(1.0), max_torque: MaxTorque::Limited(s(-5.0)) });
    assert_rejected(&mut w, out_of_range("max torque"), |w| w.joint_mut(pivot)?.set_motor(bad));
    assert_round_trips(&mut w, "after a rejected motor");
}

#[test]
fn joint_setters_round_trip_their_extreme_legal_values() {
    let Scene { mut w, pivot, .. } = scene();
    let motors = [
        Some(Motor { speed: MAX_MOTOR_SPEED, max_torque: MaxTorque::Limited(Scalar::ZERO) }),
        Some(Motor { speed: -MAX_MOTOR_SPEED, max_torque: MaxTorque::Limited(Scalar::MAX) }),
        Some(Motor { speed: Scalar::ZERO, max_torque: MaxTorque::Unlimited }),
        None,
    ];
    for m in motors {
        w.joint_mut(pivot).expect("pivot").set_motor(m).expect("legal motor");
        assert_round_trips(&mut w, &format!("motor {m:?}"));
    }
    for (m, what) in [
        (Motor { speed: MAX_MOTOR_SPEED + Scalar::DELTA, max_torque: MaxTorque::Unlimited }, "motor speed"),
        (Motor { speed: -MAX_MOTOR_SPEED - Scalar::DELTA, max_torque: MaxTorque::Unlimited }, "motor speed"),
        (Motor { speed: Scalar::MIN, max_torque: MaxTorque::Unlimited }, "motor speed"),
        (Motor { speed: Scalar::ZERO, max_torque: MaxTorque::Limited(-Scalar::DELTA) }, "max torque"),
    ] {
        assert_rejected(&mut w, out_of_range(what), |w| w.joint_mut(pivot)?.set_motor(Some(m)));
    }
}

#[test]
fn body_setters_round_trip_their_extreme_values() {
    let Scene { mut w, a, b, .. } = scene();
    let bounds = w.bounds();
    // Velocities are stored as given (the step clamps them) and restore.
    for (lin, ang) in [
        (Vector2::new(Scalar::MAX, Scalar::MIN), Scalar::MAX),
        (Vector2::new(Scalar::MIN, Scalar::MAX), Scalar::MIN),
    ] {
        let body = w.body_mut(b).expect("b");
        body.set_linear_velocity(lin);
        body.set_angular_velocity(ang);
        body.set_user_data(u64::MAX);
        assert_round_trips(&mut w, "extreme velocities");
    }
    for p in [bounds.min, bounds.max, Vector2::new(bounds.min.x, bounds.max.y)] {
        w.set_position(b, p).expect("a corner of the bounds");
        assert_round_trips(&mut w, "position at a corner");
    }
    for q in [
        Rot { c: Scalar::MAX, s: Scalar::DELTA },
        Rot { c: Scalar::DELTA, s: Scalar::MIN },
        Rot { c: Scalar::MIN, s: Scalar::MIN },
        Rot { c: -Scalar::DELTA, s: Scalar::ZERO },
    ] {
        w.set_rotation(b, q).expect("any non-zero direction");
        assert_round_trips(&mut w, "extreme rotation");
    }
    for angle in [Scalar::MAX, Scalar::MIN, Scalar::ZERO] {
        w.set_angle(b, angle).expect("any angle");
        assert_round_trips(&mut w, "extreme angle");
    }
    // A static body holding a pivot to the world: the joint stays, the world restores.
    w.set_static(a).expect("static");
    assert_round_trips(&mut w, "a static body with a joint");
    assert_rejected(&mut w, Err(Error::OutsideBounds), |w| w.set_position(b, v(-1.0, 0.0)));
    assert_rejected(&mut w, out_of_range("rotation"), |w| {
        w.set_rotation(b, Rot { c: Scalar::ZERO, s: Scalar::ZERO })
    });
}

#[test]
fn generator_setters_round_trip_their_extreme_legal_values_and_reject_the_rest() {
    let Scene { mut w, a, b, gens: hs, .. } = scene();
    let max_targets: Vec<BodyHandle> =
        (0..arphysics::force::MAX_TARGETS).map(|i| if i % 2 == 0 { a } else { b }).collect();
    for sign in [1.0, -1.0] {
        let k = s(sign);
        let GeneratorMut::Linear(g) = w.force_generator_mut(hs[0]).expect("linear") else { panic!("linear") };
        g.set_force(Vector2::new(MAX_FORCE * k, -MAX_FORCE * k)).expect("legal force");
        g.set_targets(Targets::bodies(&max_targets).expect("32 targets"));
        let GeneratorMut::Gravity(g) = w.force_generator_mut(hs[1]).expect("gravity") else {
            panic!("gravity")
        };
        g.set_gravity(Vector2::new(MAX_ACCELERATION * k, -MAX_ACCELERATION * k)).expect("legal gravity");
        g.set_targets(Targets::Level(u32::MAX));
        let GeneratorMut::GravityToPoint(g) = w.force_generator_mut(hs[2]).expect("point") else {
            panic!("point")
        };
        g.set_point(Vector2::new(MAX_COORDINATE * k, -MAX_COORDINATE * k)).expect("legal point");
        g.set_acceleration(MAX_ACCELERATION * k).expect("legal acceleration");
        assert_round_trips(&mut w, "extreme generators");
    }
    let over = |m: Scalar| Vector2::new(Scalar::ZERO, m + Scalar::DELTA);
    assert_rejected(&mut w, out_of_range("force"), |w| match w.force_generator_mut(hs[0])? {
        GeneratorMut::Linear(g) => g.set_force(over(MAX_FORCE)),
        _ => Ok(()),
    });
    assert_rejected(&mut w, out_of_range("gravity"), |w| match w.force_generator_mut(hs[1])? {
        GeneratorMut::Gravity(g) => g.set_gravity(-over(MAX_ACCELERATION)),
        _ => Ok(()),
    });
    assert_rejected(&mut w, out_of_range("point"), |w| match w.force_generator_mut(hs[2])? {
        GeneratorMut::GravityToPoint(g) => g.set_point(over(MAX_COORDINATE)),
        _ => Ok(()),
    });
    assert_rejected(&mut w, out_of_range("acceleration"), |w| match w.force_generator_mut(hs[2])? {
        GeneratorMut::GravityToPoint(g) => g.set_acceleration(Scalar::MIN),
        _ => Ok(()),
    });
    // The constructors' values are checked when the world takes them.
    let huge = Vector2::new(Scalar::MAX, Scalar::ZERO);
    let n = w.state_hash();
    assert_eq!(
        w.add_force_generator(LinearForceGenerator::new(huge)).err(),
        Some(Error::OutOfRange { what: "force" })
    );
    assert_eq!(
        w.add_force_generator(GravityForceGenerator::new(huge)).err(),
        Some(Error::OutOfRange { what: "gravity" })
    );
    assert_eq!(
        w.add_force_generator(GravityToPointForceGenerator::new(huge, Scalar::ZERO)).err(),
        Some(Error::OutOfRange { what: "point" })
    );
    assert_eq!(
        w.add_force_generator(GravityToPointForceGenerator::new(Vector2::ZERO, Scalar::MAX)).err(),
        Some(Error::OutOfRange { what: "acceleration" })
    );
    assert_eq!(w.state_hash(), n);
}

fn arbiter_extremes(a: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
    let (mu, e) = (a.friction(), a.restitution());
    let rejected = [
        a.set_friction(MAX_FRICTION + Scalar::DELTA) == out_of_range("friction"),
        a.set_friction(-Scalar::DELTA) == out_of_range("friction"),
        a.set_friction(Scalar::MAX) == out_of_range("friction"),
        a.set_restitution(Scalar::ONE + Scalar::DELTA) == out_of_range("restitution"),
        a.set_restitution(-Scalar::DELTA) == out_of_range("restitution"),
    ];
    assert!(rejected.iter().all(|r| *r), "illegal arbiter values must be errors: {rejected:?}");
    assert_eq!((a.friction(), a.restitution()), (mu, e), "a rejected value changed the arbiter");
    a.set_friction(MAX_FRICTION).expect("the largest friction");
    a.set_restitution(Scalar::ONE).expect("elastic");
    a.set_friction(Scalar::ZERO).expect("no friction");
    a.set_restitution(Scalar::ZERO).expect("no bounce");
    a.set_friction(MAX_FRICTION).expect("the largest friction");
    true
}

#[test]
fn arbiter_setters_accept_a_bodys_range_and_reject_the_rest() {
    let Scene { mut w, a, b, .. } = scene();
    w.remove_body(a).expect("clear the pivot");
    let h = FnHandler { pre_solve: Some(arbiter_extremes), ..FnHandler::default() };
    w.set_default_collision_handler(Some(h.into()));
    w.set_position(b, v(50.0, 50.0)).expect("b");
    w.add_body(BodyDef::circle(s(0.5)).position(v(50.0, 50.9))).expect("touching b");
    for _ in 0..3 {
        w.step(s(1.0 / 60.0)).expect("steps");
    }
    assert!(w.arbiters().next().is_some(), "the pair touched");
    assert_round_trips(&mut w, "after pre_solve set extreme materials");
}

#[test]
fn settings_outside_their_ranges_are_errors_naming_them() {
    let mut def = WorldDef::new(s(100.0), s(100.0));
    def.arbiter_persistence = MAX_ARBITER_PERSISTENCE;
    assert!(World::with_capacities(def, Capacities::for_bodies(4)).is_ok(), "256 steps is legal");
    def.arbiter_persistence = u32::MAX;
    assert_eq!(
        World::with_capacities(def, Capacities::for_bodies(4)).err(),
        Some(Error::OutOfRange { what: "arbiter_persistence" })
    );

    let Scene { mut w, a, b, .. } = scene();
    let joint = |kind| JointDef::new(a, Vector2::ZERO, b, Vector2::ZERO, kind);
    let legal = [
        JointKind::Spring { stiffness: MAX_STIFFNESS, rest_length: MAX_JOINT_LENGTH },
        JointKind::DampedSpring { stiffness: Scalar::ZERO, damping: MAX_DAMPING, rest_length: Scalar::ZERO },
        JointKind::Rod { length: MAX_JOINT_LENGTH },
        JointKind::Pivot {
            limits: None,
            motor: Some(Motor { speed: -MAX_MOTOR_SPEED, max_torque: MaxTorque::Unlimited }),
        },
    ];
    for kind in legal {
        w.add_joint(joint(kind)).unwrap_or_else(|e| panic!("{kind:?} is legal: {e:?}"));
        assert_round_trips(&mut w, "extreme joint parameters");
    }
    let d = Scalar::DELTA;
    let illegal = [
        (JointKind::Spring { stiffness: MAX_STIFFNESS + d, rest_length: Scalar::ZERO }, "stiffness"),
        (JointKind::Spring { stiffness: Scalar::ONE, rest_length: MAX_JOINT_LENGTH + d }, "rest length"),
        (JointKind::Spring { stiffness: Scalar::ONE, rest_length: -d }, "rest length"),
        (
            JointKind::DampedSpring {
                stiffness: Scalar::ONE,
                damping: MAX_DAMPING + d,
                rest_length: Scalar::ONE,
            },
            "damping",
        ),
        (JointKind::Rope { max_length: MAX_JOINT_LENGTH + d }, "length"),
        (
            JointKind::Pivot {
                limits: None,
                motor: Some(Motor { speed: MAX_MOTOR_SPEED + d, max_torque: MaxTorque::Unlimited }),
            },
            "motor speed",
        ),
    ];
    for (kind, what) in illegal {
        let before = w.state_hash();
        assert_eq!(w.add_joint(joint(kind)).err(), Some(Error::OutOfRange { what }), "{kind:?}");
        assert_eq!(w.state_hash(), before);
    }
}

#[test]
fn a_static_body_ignores_the_mass_it_is_given() {
    let Scene { mut w, .. } = scene();
    let h = w
        .add_body(BodyDef::circle(s(1.0)).position(v(80.0, 80.0)).static_body().mass(s(5.0)))
        .expect("static");
    let body = w.body(h).expect("static");
    assert_eq!((body.mass(), body.inv_mass(), body.inertia()), (Scalar::ZERO, Scalar::ZERO, Scalar::ZERO));
    let h = w
        .add_body(BodyDef::circle(s(1.0)).position(v(90.0, 80.0)).kinematic().mass(Scalar::MAX))
        .expect("kin");
    assert_eq!(w.body(h).expect("kinematic").mass(), Scalar::ZERO);
}

/// The limits table: mass in [MIN_MASS, MAX_MASS], radius in [1 cm, 128 m] and
/// the moment of inertia (m·r²/2 for a circle) in [MIN_INERTIA, MAX_INERTIA].
fn circle(w: &mut World<'_>, radius: f64, mass: f64) -> Result<(), Error> {
    let h = w.add_body(BodyDef::circle(s(radius)).position(v(500.0, 500.0)).mass(s(mass)))?;
    w.remove_body(h).map(drop)
}

#[test]
fn every_circle_the_limits_table_calls_legal_is_accepted() {
    let mut w = World::with_capacities(WorldDef::new(s(1000.0), s(1000.0)), Capacities::for_bodies(4))
        .expect("world");
    let (i_min, i_max) = (MIN_INERTIA.to_num::<f64>(), MAX_INERTIA.to_num::<f64>());
    let (m_min, m_max) = (MIN_MASS.to_num::<f64>(), MAX_MASS.to_num::<f64>());
    let (r_min, r_max) = (0.01, 128.0);
    // The corners of the legal region, 1 % inside (the unit inertia of a small
    // circle is rounded to a few steps of 2^-32).
    for m in [m_min, m_max] {
        let lo = (2.0 * i_min / m).sqrt().max(r_min) * 1.01;
        let hi = (2.0 * i_max / m).sqrt().min(r_max) * 0.99;
        for r in [lo, hi] {
            assert_eq!(circle(&mut w, r, m), Ok(()), "r = {r} m, m = {m} kg is legal by the table");
        }
    }
    for r in [r_min * 1.01, r_max] {
        let lo = (2.0 * i_min / (r * r)).max(m_min) * 1.01;
        let hi = (2.0 * i_max / (r * r)).min(m_max) * 0.99;
        for m in [lo, hi] {
            assert_eq!(circle(&mut w, r, m), Ok(()), "r = {r} m, m = {m} kg is legal by the table");
        }
    }
    // The table's own examples.
    assert_eq!(circle(&mut w, 128.0, 122.0), Ok(()));
    assert_eq!(circle(&mut w, 0.01, 0.021), Ok(()));
}

#[test]
fn every_circle_outside_the_limits_table_is_an_error_naming_the_parameter() {
    let mut w = World::with_capacities(WorldDef::new(s(1000.0), s(1000.0)), Capacities::for_bodies(4))
        .expect("world");
    // The audit's pair: legal by radius and mass alone, but not by inertia.
    assert_eq!(circle(&mut w, 128.0, 1000.0), out_of_range("inertia"));
    assert_eq!(circle(&mut w, 0.01, 0.001), out_of_range("inertia"));
    assert_eq!(circle(&mut w, 128.0, 123.0), out_of_range("inertia"));
    assert_eq!(circle(&mut w, 0.01, 0.0199), out_of_range("inertia"));
    assert_eq!(circle(&mut w, 128.001, 1.0), out_of_range("radius"));
    assert_eq!(circle(&mut w, 1.0, 0.000_999), out_of_range("mass"));
    assert_eq!(circle(&mut w, 1.0, 100_001.0), out_of_range("mass"));
    assert_eq!(circle(&mut w, 4.48, 100_000.0), out_of_range("inertia"));
}
