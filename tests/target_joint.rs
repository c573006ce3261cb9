//! The target (mouse) joint measured against closed forms: the critically
//! damped approach, the force limit, the sag under gravity; snapshots
//! mid-drag; bad input; and `World::set_substeps`.

use arphysics::{BodyDef, BodyHandle, Capacities, Error, JointDef, JointHandle, JointKind, Vector2, World};

mod common;

use common::{f, s, v};

const DT: f64 = 1.0 / 60.0;
const TAU: f64 = std::f64::consts::TAU;

fn world(gravity: bool) -> World<'static> {
    common::world_with(200.0, 200.0, Capacities::for_bodies(64), gravity)
}

fn target(hertz: f64, damping_ratio: f64, max_force: f64) -> JointKind {
    JointKind::Target { hertz: s(hertz), damping_ratio: s(damping_ratio), max_force: s(max_force) }
}

/// A ball of `mass` kg at `at`, dragged by its centre towards `to`.
fn dragged(
    w: &mut World<'_>,
    mass: f64,
    at: Vector2,
    to: Vector2,
    kind: JointKind,
) -> (BodyHandle, JointHandle) {
    let b = w.add_body(BodyDef::circle(s(0.5)).mass(s(mass)).position(at)).expect("body");
    let j = w.add_joint(JointDef::to_world(b, Vector2::ZERO, to, kind)).expect("target joint");
    (b, j)
}

#[test]
fn a_critically_damped_target_joint_follows_the_analytic_approach() {
    let (hertz, x0) = (1.0, 5.0);
    let omega = TAU * hertz;
    for mass in [0.5, 40.0] {
        let mut w = world(false);
        let (b, _) = dragged(&mut w, mass, v(x0, 0.0), v(0.0, 0.0), target(hertz, 1.0, 1e6));
        let mut worst = 0.0f64;
        for i in 1..=180 {
            w.step(s(DT)).expect("step");
            let t = i as f64 * DT;
            let expected = x0 * (1.0 + omega * t) * (-omega * t).exp();
            let x = f(w.body(b).expect("b").position().x);
            worst = worst.max((x - expected).abs());
        }
        println!(
            "{mass} kg, critically damped at {hertz} Hz from {x0} m: worst |x − x0·(1+ωt)·e^(−ωt)| over 3 s = {worst:.4} m ({:.2} % of x0, ≤ 2 %)",
            100.0 * worst / x0
        );
        assert!(worst <= 0.02 * x0, "{mass} kg: {worst}");
    }
}

#[test]
fn the_force_limit_bounds_the_acceleration_and_the_body_still_arrives() {
    // A stiff spring far from its target: the force limit holds the whole way,
    // so the body accelerates at F/m along the line to the target and arrives
    // after √(2d/a), as a body under a constant force does.
    let (mass, max_force) = (80.0, 40.0);
    let a_max = max_force / mass;
    let (from, to) = (v(-10.0, 0.0), v(10.0, 5.0));
    let d = f((to - from).length());
    let mut w = world(false);
    let (b, j) = dragged(&mut w, mass, from, to, target(5.0, 0.7, max_force));
    let mut last = w.body(b).expect("b").linear_velocity();
    let (mut worst, mut arrival) = (0.0f64, None);
    for i in 1..=(12.0 / DT) as usize {
        w.step(s(DT)).expect("step");
        let vel = w.body(b).expect("b").linear_velocity();
        worst = worst.max(f((vel - last).length()) / DT);
        last = vel;
        // The joint's impulse over a step is the force times dt, at most.
        assert!(f(w.joint(j).expect("j").step_impulse()) <= max_force * DT * 1.001);
        let miss = f((w.body(b).expect("b").position() - to).length());
        if arrival.is_none() && miss <= 0.05 {
            arrival = Some(i as f64 * DT);
        }
    }
    let expected = (2.0 * d / a_max).sqrt();
    let arrival = arrival.expect("the body never came within 5 cm of the target");
    println!(
        "{mass} kg dragged with at most {max_force} N: peak acceleration {worst:.5} m/s² (F/m = {a_max}, ≤ +0.5 %); \
         within 5 cm of the target after {arrival:.3} s vs √(2d/a) = {expected:.3} s (≤ 2 %)"
    );
    assert!(worst <= a_max * 1.005, "{worst} > {a_max}");
    assert!(worst >= a_max * 0.95, "the limit should be reached: {worst}");
    assert!((arrival - expected).abs() <= 0.02 * expected, "{arrival} vs {expected}");
}

#[test]
fn the_spin_damping_slows_a_held_body_by_the_soft_rows_closed_form() {
    // Held at its centre, a spinning body keeps its place and only its spin
    // is damped: a soft row with no bias (0.5 Hz, ζ = 0.1) scales the spin by
    // (1 − s_m) each sub-step, s_m = a/(1 + a), a = hω(2ζ + hω), ω = 2π·0.5
    // (the warm start and the relax sweep cancel out exactly).
    let w0 = 5.0;
    let mut w = world(false);
    let b = w
        .add_body(BodyDef::circle(s(0.5)).mass(s(3.0)).position(v(1.0, 2.0)).angular_velocity(s(w0)))
        .expect("body");
    w.add_joint(JointDef::to_world(b, Vector2::ZERO, v(1.0, 2.0), target(5.0, 0.7, 1e4))).expect("joint");
    let (h, omega, zeta) = (DT / 4.0, TAU * 0.5, 0.1);
    let a = h * omega * (2.0 * zeta + h * omega);
    let per_substep = 1.0 - a / (1.0 + a);
    let mut worst = 0.0f64;
    for i in 1..=120 {
        w.step(s(DT)).expect("step");
        let spin = f(w.body(b).expect("b").angular_velocity());
        let expected = w0 * per_substep.powi(4 * i);
        worst = worst.max((spin - expected).abs() / expected);
    }
    let p = w.body(b).expect("b").position();
    let spin = f(w.body(b).expect("b").angular_velocity());
    println!(
        "spin damping: {w0} rad/s → {spin:.4} rad/s in 2 s (closed form {:.4}; worst {:.3} % off, ≤ 1 %); centre moved {:.1e} m",
        w0 * per_substep.powi(480),
        worst * 100.0,
        f((p - v(1.0, 2.0)).length())
    );
    assert!(worst <= 0.01, "{worst}");
    assert!(f((p - v(1.0, 2.0)).length()) < 1e-6);
}

#[test]
fn a_body_held_under_gravity_sags_by_g_over_omega_squared() {
    for (hertz, mass) in [(2.0, 1.0), (4.0, 25.0)] {
        let omega = TAU * hertz;
        let mut w = world(true);
        let (b, _) = dragged(&mut w, mass, v(0.0, 10.0), v(0.0, 10.0), target(hertz, 1.0, 1e6));
        for _ in 0..300 {
            w.step(s(DT)).expect("step");
        }
        let sag = 10.0 - f(w.body(b).expect("b").position().y);
        // m·g/k with k = m·ω²: the same for every mass.
        let expected = 10.0 / (omega * omega);
        let err = (sag - expected).abs() / expected;
        println!(
            "{mass} kg held at {hertz} Hz: sag {sag:.5} m vs m·g/(m·ω²) = {expected:.5} m: {:.2} % (≤ 1 %)",
            err * 100.0
        );
        assert!(err <= 0.01, "{sag} vs {expected}");
    }
}

/// Moves the target along a circle, deterministically from the step count.
fn drag_step(w: &mut World<'_>, j: JointHandle, i: u32) {
    let a = f64::from(i) * 0.1;
    w.set_joint_target(j, v(3.0 * a.cos(), 3.0 * a.sin())).expect("target");
    w.step(s(DT)).expect("step");
}

#[test]
fn restore_mid_drag_then_step_equals_stepping_on() {
    let mut w = world(true);
    w.add_body(BodyDef::circle(s(1.0)).static_body().position(v(0.0, -5.0))).expect("ground");
    let (_, j) = dragged(&mut w, 2.0, v(3.0, 0.0), v(3.0, 0.0), target(3.0, 0.5, 60.0));
    for i in 0..40 {
        drag_step(&mut w, j, i);
    }
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("snapshot");
    let at_snapshot = w.state_hash();
    for i in 40..100 {
        drag_step(&mut w, j, i);
    }
    let on = w.state_hash();
    w.restore(&buf[..n]).expect("restore");
    assert_eq!(w.state_hash(), at_snapshot);
    for i in 40..100 {
        drag_step(&mut w, j, i);
    }
    assert_eq!(w.state_hash(), on, "restore mid-drag then step differs from stepping on");

    // The target is in the hash: moving it changes the hash, moving it back
    // restores it.
    let before = w.state_hash();
    let t = w.joint_target(j).expect("target");
    w.set_joint_target(j, t + v(1.0, 0.0)).expect("move");
    assert_ne!(w.state_hash(), before);
    w.set_joint_target(j, t).expect("back");
    assert_eq!(w.state_hash(), before);

    // A corrupted joint record is rejected and the world is unchanged.
    let mut bad = buf[..n].to_vec();
    let at = n - 8 - 30; // inside the last joint record, before the trailer
    bad[at] ^= 0x40;
    assert!(w.restore(&bad).is_err());
    assert_eq!(w.state_hash(), before);
}

#[test]
fn bad_input_errors_and_leaves_the_world_unchanged() {
    let mut w = world(true);
    let ground = w.add_body(BodyDef::circle(s(1.0)).static_body().position(v(0.0, -5.0))).expect("ground");
    let (b, j) = dragged(&mut w, 1.0, v(0.0, 0.0), v(1.0, 1.0), target(5.0, 0.7, 100.0));
    let other = w.add_body(BodyDef::circle(s(0.5)).position(v(5.0, 0.0))).expect("other");
    let pivot = w
        .add_joint(JointDef::to_world(
            other,
            Vector2::ZERO,
            v(5.0, 1.0),
            JointKind::Pivot { limits: None, motor: None },
        ))
        .expect("pivot");
    let before = w.state_hash();
    let check = |w: &World<'_>| assert_eq!(w.state_hash(), before, "an error changed the world");

    // Moving the target.
    assert_eq!(w.set_joint_target(j, v(500.0, 0.0)), Err(Error::OutsideBounds));
    check(&w);
    assert!(matches!(w.set_joint_target(pivot, v(1.0, 1.0)), Err(Error::InvalidOperation { .. })));
    check(&w);
    assert!(matches!(w.joint_target(pivot), Err(Error::InvalidOperation { .. })));
    assert_eq!(w.joint_target(j), Ok(v(1.0, 1.0)));

    // Creating one.
    let add = |w: &mut World<'_>, kind| w.add_joint(JointDef::to_world(b, Vector2::ZERO, v(1.0, 1.0), kind));
    for (kind, what) in [
        (target(0.0, 1.0, 10.0), "hertz"),
        (target(-1.0, 1.0, 10.0), "hertz"),
        (target(1000.5, 1.0, 10.0), "hertz"),
        (target(5.0, -0.1, 10.0), "damping ratio"),
        (target(5.0, 100.5, 10.0), "damping ratio"),
        (target(5.0, 1.0, -1.0), "max force"),
    ] {
        assert_eq!(add(&mut w, kind), Err(Error::OutOfRange { what }), "{kind:?}");
        check(&w);
    }
    let kind = target(5.0, 1.0, 10.0);
    assert_eq!(
        w.add_joint(JointDef::to_world(b, Vector2::ZERO, v(0.0, 500.0), kind)),
        Err(Error::OutsideBounds)
    );
    assert!(matches!(
        w.add_joint(JointDef::new(b, Vector2::ZERO, other, Vector2::ZERO, kind)),
        Err(Error::InvalidOperation { .. })
    ));
    // On a static body: nothing to drag.
    assert!(matches!(
        w.add_joint(JointDef::to_world(ground, Vector2::ZERO, v(1.0, 1.0), kind)),
        Err(Error::InvalidOperation { .. })
    ));
    check(&w);
    // The limits themselves are accepted.
    let edge = target(1000.0, 100.0, 0.0);
    let e = w.add_joint(JointDef::to_world(other, Vector2::ZERO, v(5.0, 0.0), edge)).expect("edge values");
    w.remove_joint(e).expect("remove");

    // A removed joint.
    w.remove_joint(j).expect("remove");
    let after = w.state_hash();
    assert_eq!(w.set_joint_target(j, v(1.0, 1.0)), Err(Error::StaleHandle));
    assert_eq!(w.joint_target(j), Err(Error::StaleHandle));
    assert_eq!(w.state_hash(), after);
}

#[test]
fn set_substeps_is_range_checked_in_the_hash_and_rolled_back_by_restore() {
    let mut w = world(true);
    w.add_body(BodyDef::circle(s(1.0)).static_body().position(v(0.0, -5.0))).expect("ground");
    let (_, j) = dragged(&mut w, 2.0, v(3.0, 0.0), v(3.0, 0.0), target(3.0, 0.5, 60.0));
    let before = w.state_hash();
    for n in [0, arphysics::limits::MAX_SUBSTEPS + 1] {
        assert_eq!(w.set_substeps(n), Err(Error::OutOfRange { what: "substeps" }));
        assert_eq!(w.state_hash(), before);
        assert_eq!(w.def().substeps, 4);
    }
    for i in 0..20 {
        drag_step(&mut w, j, i);
    }
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("snapshot");
    // Stepping on with 8 sub-steps from frame 30.
    let run = |w: &mut World<'_>| {
        for i in 20..60 {
            if i == 30 {
                w.set_substeps(8).expect("substeps");
            }
            drag_step(w, j, i);
        }
        w.state_hash()
    };
    let on = run(&mut w);
    assert_eq!(w.def().substeps, 8);
    // The restore brings back 4 sub-steps: the replay matches.
    w.restore(&buf[..n]).expect("restore");
    assert_eq!(w.def().substeps, 4);
    assert_eq!(run(&mut w), on);
    // And the count shapes the steps: the same run with 4 throughout differs.
    w.restore(&buf[..n]).expect("restore");
    for i in 20..60 {
        drag_step(&mut w, j, i);
    }
    assert_ne!(w.state_hash(), on);
}

#[test]
fn a_snapshot_with_a_bad_target_joint_record_is_rejected_even_with_a_valid_checksum() {
    use arphysics::snapshot::TRAILER;
    use twox_hash::XxHash64;
    let mut w = world(true);
    let (_, j) = dragged(&mut w, 2.0, v(3.0, 0.0), v(4.0, 1.0), target(3.0, 0.5, 60.0));
    for _ in 0..10 {
        w.step(s(DT)).expect("step");
    }
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("snapshot");
    buf.truncate(n);
    let before = w.state_hash();
    // The kind's parameters as written: tag 6, then hertz, damping ratio and
    // force limit as raw little-endian bits.
    let mut params = vec![6u8];
    for x in [3.0, 0.5, 60.0] {
        params.extend_from_slice(&s(x).to_bits().to_le_bytes());
    }
    let at = buf
        .windows(params.len())
        .position(|win| win == params.as_slice())
        .expect("the target joint's record");
    let reseal = |b: &mut Vec<u8>| {
        let sum = XxHash64::oneshot(0, &b[..n - TRAILER]);
        b[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
    };
    let mut cases = Vec::new();
    // Hertz 0, a negative damping ratio, a negative force limit, an unknown kind.
    for (offset, bytes) in [
        (1, s(0.0).to_bits().to_le_bytes().to_vec()),
        (9, s(-1.0).to_bits().to_le_bytes().to_vec()),
        (17, s(-1.0).to_bits().to_le_bytes().to_vec()),
        (0, vec![7u8]),
    ] {
        let mut bad = buf.clone();
        bad[at + offset..at + offset + bytes.len()].copy_from_slice(&bytes);
        reseal(&mut bad);
        cases.push(bad);
    }
    for bad in &cases {
        let r = w.restore(bad);
        assert!(matches!(r, Err(Error::InvalidSnapshot { .. })), "{r:?}");
        assert_eq!(w.state_hash(), before, "a rejected snapshot changed the world");
    }
    // The untouched one, resealed the same way, restores.
    let mut good = buf.clone();
    reseal(&mut good);
    w.restore(&good).expect("restores");
    assert_eq!(w.joint_target(j), Ok(v(4.0, 1.0)));
}
