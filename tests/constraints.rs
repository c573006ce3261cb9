//! Constraints measured against closed forms: springs, damped springs, rods,
//! chains, pivots with motors and limits, breaking, and bad input.

use std::sync::atomic::{AtomicU32, Ordering};

use arphysics::constraint::Constraint;
use arphysics::{
    Body, BodyDef, BodyHandle, Capacities, Error, GravityForceGenerator, Joint, JointDef, JointHandle,
    JointKind, MaxTorque, Motor, PolygonPath, Scalar, Vector2, World,
};

mod common;

use common::{s, v};

const DT: f64 = 1.0 / 60.0;

fn world(gravity: bool) -> World<'static> {
    common::world_with(200.0, 200.0, Capacities::for_bodies(64), gravity)
}

/// Times between successive upward zero crossings of `f` sampled every `DT`,
/// interpolated linearly.
fn periods(samples: &[f64]) -> Vec<f64> {
    let mut crossings = Vec::new();
    for (i, w) in samples.windows(2).enumerate() {
        if w[0] < 0.0 && w[1] >= 0.0 {
            crossings.push((i as f64 + w[0] / (w[0] - w[1])) * DT);
        }
    }
    crossings.windows(2).map(|c| c[1] - c[0]).collect()
}

/// A 1 kg body on a spring of stiffness `k` to a fixed point, pulled 1 m along x.
fn spring_body(w: &mut World<'_>, k: f64, damping: Option<f64>) -> BodyHandle {
    // A circle of radius 1/√π has area 1: 1 kg at density 1.
    let r = (1.0 / std::f64::consts::PI).sqrt();
    let b = w.add_body(BodyDef::circle(s(r)).position(v(1.0, 0.0))).expect("body");
    let kind = match damping {
        None => JointKind::Spring { stiffness: s(k), rest_length: s(0.0) },
        Some(c) => JointKind::DampedSpring { stiffness: s(k), damping: s(c), rest_length: s(0.0) },
    };
    w.add_joint(JointDef::to_world(b, Vector2::ZERO, v(0.0, 0.0), kind)).expect("spring");
    b
}

#[test]
fn a_spring_oscillates_with_period_two_pi_root_m_over_k() {
    let mut w = world(false);
    let b = spring_body(&mut w, 100.0, None);
    assert!((w.body(b).expect("b").mass() - s(1.0)).abs() < s(1e-6));
    let mut xs = Vec::new();
    for _ in 0..600 {
        w.step(s(DT)).expect("step");
        xs.push(w.body(b).expect("b").position().x.to_num::<f64>());
    }
    let ps = periods(&xs);
    let measured = ps.iter().sum::<f64>() / ps.len() as f64;
    let expected = 2.0 * std::f64::consts::PI * (1.0f64 / 100.0).sqrt();
    let err = (measured - expected).abs() / expected;
    println!("spring period {measured:.5} s vs 2π√(m/k) = {expected:.5} s: {:.3} % (≤ 1 %)", err * 100.0);
    assert!(err <= 0.01, "{err}");
    // Undamped: the amplitude holds (energy is not eaten by the integrator).
    let last = xs[xs.len() - 60..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(last > 0.97, "amplitude after 10 s: {last}");
}

#[test]
fn a_damped_spring_decays_by_the_analytic_ratio_per_period() {
    let (k, m, zeta) = (100.0, 1.0, 0.1);
    let c = 2.0 * zeta * f64::sqrt(k * m);
    let mut w = world(false);
    let b = spring_body(&mut w, k, Some(c));
    let mut xs = Vec::new();
    for _ in 0..240 {
        w.step(s(DT)).expect("step");
        xs.push(w.body(b).expect("b").position().x.to_num::<f64>());
    }
    // Successive positive peaks.
    let peaks: Vec<f64> =
        xs.windows(3).filter(|p| p[1] > p[0] && p[1] >= p[2] && p[1] > 0.0).map(|p| p[1]).collect();
    let ratio = peaks[2] / peaks[1];
    let expected = (-2.0 * std::f64::consts::PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
    let err = (ratio - expected).abs() / expected;
    println!("damped spring decay per period {ratio:.4} vs {expected:.4}: {:.2} % (≤ 5 %)", err * 100.0);
    assert!(err <= 0.05, "{ratio} vs {expected}");
}

#[test]
fn a_rod_pendulum_keeps_its_length_and_swings_at_the_small_angle_period() {
    let mut w = world(true);
    let length = 2.0;
    let theta0 = 5.0f64.to_radians();
    let pivot = v(0.0, 50.0);
    let bob = w
        .add_body(BodyDef::circle(s(0.1)).position(v(length * theta0.sin(), 50.0 - length * theta0.cos())))
        .expect("bob");
    w.add_joint(JointDef::to_world(bob, Vector2::ZERO, pivot, JointKind::Rod { length: s(length) }))
        .expect("rod");
    let (mut worst, mut xs) = (0.0f64, Vec::new());
    for _ in 0..600 {
        w.step(s(DT)).expect("step");
        let p = w.body(bob).expect("bob").position();
        worst = worst.max(((p - pivot).length().to_num::<f64>() - length).abs());
        xs.push(p.x.to_num::<f64>());
    }
    let ps = periods(&xs);
    let measured = ps.iter().sum::<f64>() / ps.len() as f64;
    let expected = 2.0 * std::f64::consts::PI * (length / 10.0).sqrt();
    let err = (measured - expected).abs() / expected;
    println!("rod pendulum: length error ≤ {worst:.2e} m (≤ 1e-3); period {measured:.4} s vs {expected:.4} s: {:.3} % (≤ 1 %)", err * 100.0);
    assert!(worst <= 1e-3, "{worst}");
    assert!(err <= 0.01, "{err}");
}

/// A chain of 20 rods of 0.5 m between 0.1 m balls hanging from a fixed point,
/// the last ball 10 times as heavy as the others. Returns the bodies.
fn chain(w: &mut World<'_>, top: Vector2, hanging: bool) -> Vec<BodyHandle> {
    let (links, link) = (20, 0.5);
    let mut prev: Option<BodyHandle> = None;
    let mut bodies = Vec::new();
    for i in 0..links {
        let d = link * (f64::from(i) + 1.0);
        let p = if hanging { top - v(0.0, d) } else { top + v(d, 0.0) };
        let density = if i == links - 1 { 10.0 } else { 1.0 };
        let b = w
            .add_body(BodyDef::circle(s(0.1)).position(p).density(s(density)).collision_groups(1))
            .expect("link");
        let rod = JointKind::Rod { length: s(link) };
        let def = match prev {
            None => JointDef::to_world(b, Vector2::ZERO, top, rod),
            Some(p) => JointDef::new(p, Vector2::ZERO, b, Vector2::ZERO, rod),
        };
        w.add_joint(def).expect("rod");
        bodies.push(b);
        prev = Some(b);
    }
    bodies
}

/// Relative error of the chain's length (sum of the link lengths) against 10 m.
fn chain_error(w: &World<'_>, top: Vector2, bodies: &[BodyHandle]) -> f64 {
    let mut len = 0.0;
    let mut p0 = top;
    for b in bodies {
        let p = w.body(*b).expect("link").position();
        len += (p - p0).length().to_num::<f64>();
        p0 = p;
    }
    (len - 10.0).abs() / 10.0
}

#[test]
fn a_hanging_chain_with_a_heavy_end_keeps_its_length_and_comes_to_rest() {
    let mut w = world(true);
    let top = v(0.0, 100.0);
    // Released hanging at its rest spacing: gravity loads every rod at once.
    let bodies = chain(&mut w, top, true);
    let mut worst = 0.0f64;
    for _ in 0..600 {
        w.step(s(DT)).expect("step");
        worst = worst.max(chain_error(&w, top, &bodies));
    }
    let speed = bodies
        .iter()
        .map(|b| w.body(*b).expect("b").linear_velocity().length().to_num::<f64>())
        .fold(0.0, f64::max);
    println!("hanging chain, 10:1 end: length error ≤ {:.3} % (≤ 2 %); largest speed after 10 s {speed:.2e} m/s (≤ 0.01)", worst * 100.0);
    assert!(worst <= 0.02, "{worst}");
    assert!(speed <= 0.01, "{speed}");

    // For the record (not asserted; see the notes on joint softness): the same
    // chain dropped from horizontal, whose whipping end loads the light top links
    // far beyond its weight.
    let mut w = world(true);
    let bodies = chain(&mut w, top, false);
    let mut worst = 0.0f64;
    for _ in 0..600 {
        w.step(s(DT)).expect("step");
        worst = worst.max(chain_error(&w, top, &bodies));
    }
    println!(
        "info: the chain dropped from horizontal stretches up to {:.2} % at peak tension",
        worst * 100.0
    );
}

fn wheel_world() -> (World<'static>, BodyHandle, JointHandle) {
    let mut w = world(false);
    let wheel = w.add_body(BodyDef::circle(s(1.0)).position(v(0.0, 0.0))).expect("wheel");
    let motor = Motor { speed: s(5.0), max_torque: MaxTorque::Limited(s(20.0)) };
    let j = w
        .add_joint(JointDef::to_world(
            wheel,
            Vector2::ZERO,
            v(0.0, 0.0),
            JointKind::Pivot { limits: None, motor: Some(motor) },
        ))
        .expect("pivot");
    (w, wheel, j)
}

#[test]
fn a_pivot_motor_reaches_its_target_speed_at_the_torque_limit() {
    let (mut w, wheel, _) = wheel_world();
    let inertia = w.body(wheel).expect("w").inertia().to_num::<f64>();
    // Torque-limited spin-up: ω(t) = (τ/I)·t until it reaches the target.
    w.step(s(DT)).expect("step");
    let w1 = w.body(wheel).expect("w").angular_velocity().to_num::<f64>();
    assert!((w1 - 20.0 / inertia * DT).abs() < 1e-3, "{w1} vs {}", 20.0 / inertia * DT);
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
    }
    let w2 = w.body(wheel).expect("w").angular_velocity().to_num::<f64>();
    println!("motor: ω = {w2:.6} rad/s (target 5)");
    assert!((w2 - 5.0).abs() < 1e-3, "{w2}");
    // The wheel stays on its axle.
    assert!(w.body(wheel).expect("w").position().length() < s(1e-3));
}

#[test]
fn pivot_limits_hold_under_load() {
    let mut w = world(true);
    let bar = w.add_path(PolygonPath::rectangle(s(4.0), s(0.2)).expect("bar")).expect("p");
    // A 4 m bar pinned at its left end, limited to ±0.5 rad, with a heavy ball at
    // the far end pulling it down.
    let b = w.add_body(BodyDef::polygon(bar).position(v(2.0, 50.0))).expect("bar");
    let limits = Some((s(-0.5), s(0.5)));
    w.add_joint(JointDef::to_world(b, v(-2.0, 0.0), v(0.0, 50.0), JointKind::Pivot { limits, motor: None }))
        .expect("pivot");
    let ball = w.add_body(BodyDef::circle(s(0.3)).position(v(4.0, 50.0)).density(s(20.0))).expect("ball");
    w.add_joint(JointDef::new(b, v(2.0, 0.0), ball, Vector2::ZERO, JointKind::Weld)).expect("weld");
    let (mut worst, mut overshoot) = (0.0f64, 0.0f64);
    for i in 0..600 {
        w.step(s(DT)).expect("step");
        let angle = w.body(b).expect("bar").angle().to_num::<f64>();
        overshoot = overshoot.max(-0.5 - angle);
        if i >= 180 {
            // Under load, resting on the limit (it lands and rebounds for ~2.5 s).
            worst = worst.max((angle + 0.5).abs());
        }
    }
    println!("pivot limit: resting angle within {worst:.4} rad of −0.5 (≤ 0.01); overshoot while landing {overshoot:.4} rad");
    assert!(worst <= 0.01, "{worst}");
}

static BROKEN: AtomicU32 = AtomicU32::new(0);

fn on_break(_: &mut World<'_>, _: JointHandle, joint: Joint) {
    assert!(joint.step_impulse() > s(1.0));
    BROKEN.fetch_add(1, Ordering::SeqCst);
}

#[test]
fn a_breakable_rod_breaks_at_the_first_step_over_its_limit_and_only_once() {
    let mut w = world(true);
    w.set_joint_break_callback(Some(on_break));
    let r = (1.0 / std::f64::consts::PI).sqrt();
    let bob = w.add_body(BodyDef::circle(s(r)).position(v(0.0, 49.0))).expect("bob");
    // Hanging at rest a 1 kg bob needs m·g·dt = 10/60 ≈ 0.167 N·s per step. The rod
    // breaks above 1 N·s: a hanging bob is fine until we load it.
    let rod = w
        .add_joint(
            JointDef::to_world(bob, Vector2::ZERO, v(0.0, 50.0), JointKind::Rod { length: s(1.0) })
                .breakable(s(1.0)),
        )
        .expect("rod");
    for _ in 0..60 {
        assert_eq!(w.step(s(DT)).expect("step").joints_broken, 0);
    }
    let hanging = w.joint(rod).expect("rod").step_impulse().to_num::<f64>();
    assert!((hanging - 10.0 / 60.0).abs() < 0.01, "{hanging}");
    // Yank it: 2 kg·m/s downward; the rod must deliver 2 N·s this step and snaps.
    w.body_mut(bob).expect("bob").apply_linear_impulse(v(0.0, -2.0));
    let report = w.step(s(DT)).expect("step");
    assert_eq!(report.joints_broken, 1);
    assert_eq!(BROKEN.load(Ordering::SeqCst), 1);
    assert_eq!(w.joint(rod).err(), Some(Error::StaleHandle));
    for _ in 0..30 {
        assert_eq!(w.step(s(DT)).expect("step").joints_broken, 0);
    }
    assert_eq!(BROKEN.load(Ordering::SeqCst), 1, "breaks once");
}

/// A game constraint written against the trait: keeps a body above a floor line.
struct KeepAbove {
    floor: Scalar,
}

impl Constraint for KeepAbove {
    fn solve(&mut self, a: &mut Body, _: &mut Body, h: Scalar) {
        let below = self.floor - (a.position().y - a.bounding_radius());
        let vy = a.linear_velocity().y;
        if below > Scalar::ZERO || vy * h < -(a.position().y - a.bounding_radius() - self.floor) {
            // Stop the fall at the line within this sub-step.
            let target = (self.floor - (a.position().y - a.bounding_radius())) / h;
            if vy < target {
                a.apply_linear_impulse(Vector2::new(Scalar::ZERO, (target - vy) * a.mass()));
            }
        }
    }
}

#[test]
fn a_user_constraint_keeps_a_body_above_a_line() {
    let mut w = world(true);
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 10.0))).expect("b");
    let mut keep = KeepAbove { floor: s(2.0) };
    {
        let mut w2 = World::with_capacities(*w.def(), Capacities::for_bodies(4)).expect("w");
        let b2 = w2.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 10.0))).expect("b");
        w2.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("g");
        w2.add_constraint(b2, None, arphysics::Hook::Borrowed(&mut keep)).expect("c");
        for _ in 0..180 {
            w2.step(s(DT)).expect("step");
        }
        let bottom = (w2.body(b2).expect("b").position().y - s(0.5)).to_num::<f64>();
        assert!((bottom - 2.0).abs() < 0.01, "rests on the line: {bottom}");
    }
    // Without it the body falls freely.
    for _ in 0..180 {
        w.step(s(DT)).expect("step");
    }
    assert!(w.body(b).expect("b").position().y < s(0.0));
}

#[test]
fn bad_joints_are_rejected_and_change_nothing() {
    let mut w = world(false);
    let a = w.add_body(BodyDef::circle(s(1.0)).position(v(0.0, 0.0))).expect("a");
    let b = w.add_body(BodyDef::circle(s(1.0)).position(v(5.0, 0.0))).expect("b");
    let g1 = w.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 0.0)).static_body()).expect("g1");
    let g2 = w.add_body(BodyDef::circle(s(1.0)).position(v(15.0, 0.0)).static_body()).expect("g2");
    let gone = w.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 0.0))).expect("gone");
    w.remove_body(gone).expect("removed");
    let rod = |l: f64| JointKind::Rod { length: s(l) };
    let before = w.state_hash();
    let cases = [
        (JointDef::new(a, Vector2::ZERO, b, Vector2::ZERO, rod(0.0)), Error::OutOfRange { what: "length" }),
        (
            JointDef::new(a, Vector2::ZERO, a, Vector2::ZERO, rod(1.0)),
            Error::InvalidOperation { what: "a joint between a body and itself" },
        ),
        (
            JointDef::new(g1, Vector2::ZERO, g2, Vector2::ZERO, rod(1.0)),
            Error::InvalidOperation { what: "a joint between two bodies that cannot move" },
        ),
        (JointDef::new(a, v(1e4, 0.0), b, Vector2::ZERO, rod(1.0)), Error::OutOfRange { what: "anchor" }),
        (JointDef::new(a, Vector2::ZERO, gone, Vector2::ZERO, rod(1.0)), Error::StaleHandle),
        (
            JointDef::new(
                a,
                Vector2::ZERO,
                b,
                Vector2::ZERO,
                JointKind::Spring { stiffness: s(-1.0), rest_length: s(1.0) },
            ),
            Error::OutOfRange { what: "stiffness" },
        ),
        (
            JointDef::new(
                a,
                Vector2::ZERO,
                b,
                Vector2::ZERO,
                JointKind::DampedSpring { stiffness: s(1.0), damping: s(-1.0), rest_length: s(1.0) },
            ),
            Error::OutOfRange { what: "damping" },
        ),
        (
            JointDef::new(
                a,
                Vector2::ZERO,
                b,
                Vector2::ZERO,
                JointKind::Pivot { limits: Some((s(1.0), s(-1.0))), motor: None },
            ),
            Error::OutOfRange { what: "angle limits" },
        ),
        (JointDef::to_world(a, Vector2::ZERO, v(1000.0, 0.0), rod(1.0)), Error::OutsideBounds),
        (
            JointDef::new(a, Vector2::ZERO, b, Vector2::ZERO, rod(1.0)).breakable(s(0.0)),
            Error::OutOfRange { what: "break impulse" },
        ),
    ];
    for (def, err) in cases {
        assert_eq!(w.add_joint(def).err(), Some(err), "{def:?}");
    }
    assert_eq!(w.state_hash(), before);
    assert_eq!(w.joint(JointHandle::NULL).err(), Some(Error::StaleHandle));
    // Removing a body removes its joints.
    let j = w.add_joint(JointDef::new(a, Vector2::ZERO, b, Vector2::ZERO, rod(5.0))).expect("rod");
    w.remove_body(b).expect("b");
    assert_eq!(w.joint(j).err(), Some(Error::StaleHandle));
}

#[test]
fn jointed_bodies_do_not_collide_unless_asked() {
    for collide in [false, true] {
        let mut w = world(false);
        // Two 0.5 m balls whose centres a rod holds 0.6 m apart: they overlap.
        let a = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 0.0))).expect("a");
        let b = w.add_body(BodyDef::circle(s(0.5)).position(v(0.6, 0.0))).expect("b");
        let rod = JointKind::Rod { length: s(0.6) };
        w.add_joint(JointDef::new(a, Vector2::ZERO, b, Vector2::ZERO, rod).collide_connected(collide))
            .expect("rod");
        w.step(s(DT)).expect("step");
        assert_eq!(w.arbiter(a, b).is_some(), collide, "collide_connected = {collide}");
    }
}

/// Mechanical energy (J) of `bodies` under gravity (0, −10): kinetic, linear
/// and angular, plus potential above y = 0.
fn mechanical_energy(w: &World<'_>, bodies: &[BodyHandle]) -> f64 {
    bodies
        .iter()
        .map(|h| {
            let b = w.body(*h).expect("body");
            let (m, i) = (b.mass().to_num::<f64>(), b.inertia().to_num::<f64>());
            let (vel, spin) = (b.linear_velocity(), b.angular_velocity().to_num::<f64>());
            let speed2 = vel.x.to_num::<f64>().powi(2) + vel.y.to_num::<f64>().powi(2);
            0.5 * m * speed2 + 0.5 * i * spin * spin + m * 10.0 * b.position().y.to_num::<f64>()
        })
        .sum()
}

/// The order a net's joints are made in.
#[derive(Clone, Copy, Debug)]
enum NetOrder {
    /// Body by body, each one's right then lower joint (Box2D's joint grid).
    Interleaved,
    /// Every horizontal joint, then every vertical one.
    HorizontalFirst,
    /// Every vertical joint, then every horizontal one.
    VerticalFirst,
}

/// A net of `n` × `n` circles 1 m apart, each joined to its right and lower
/// neighbours by `kind` (made in `order`), hung by its two top corners and
/// released at rest. Over 300 steps: its kinetic plus potential energy above
/// the start at most, in units of its weight × 1 m, and the fastest body
/// (m/s).
fn hung_net(n: usize, kind: JointKind, order: NetOrder) -> (f64, f64) {
    let mut w = common::world_with(100.0, 100.0, Capacities::for_bodies(n * n), true);
    let mut ids = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let x = j as f64 - n as f64 / 2.0;
            let mut def = BodyDef::circle(s(0.4)).position(v(x, 60.0 - i as f64)).collision_groups(1);
            if i == 0 && (j == 0 || j == n - 1) {
                def = def.static_body();
            }
            ids.push(w.add_body(def).expect("body"));
        }
    }
    let (mut both, mut horizontal, mut vertical) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..n {
        for j in 0..n {
            let a = ids[i * n + j];
            if j + 1 < n {
                let def = JointDef::new(a, v(0.5, 0.0), ids[i * n + j + 1], v(-0.5, 0.0), kind);
                both.push(def);
                horizontal.push(def);
            }
            if i + 1 < n {
                let def = JointDef::new(a, v(0.0, -0.5), ids[(i + 1) * n + j], v(0.0, 0.5), kind);
                both.push(def);
                vertical.push(def);
            }
        }
    }
    let defs = match order {
        NetOrder::Interleaved => both,
        NetOrder::HorizontalFirst => horizontal.into_iter().chain(vertical).collect(),
        NetOrder::VerticalFirst => vertical.into_iter().chain(horizontal).collect(),
    };
    for def in defs {
        w.add_joint(def).expect("joint");
    }
    let weight: f64 = ids.iter().map(|h| w.body(*h).expect("body").mass().to_num::<f64>() * 10.0).sum();
    let start = mechanical_energy(&w, &ids);
    let (mut most, mut fastest) = (f64::MIN, 0.0f64);
    for _ in 0..300 {
        w.step(s(DT)).expect("step");
        most = most.max(mechanical_energy(&w, &ids) - start);
        for h in &ids {
            fastest = fastest.max(w.body(*h).expect("body").linear_velocity().length().to_num::<f64>());
        }
    }
    (most / weight, fastest)
}

#[test]
fn a_net_of_pivots_hung_by_two_corners_never_gains_energy() {
    // Box2D's joint grid, smaller, hung by its corners and released at rest:
    // it can only turn the height it loses into motion and into the stretch
    // of its soft joints, whose damping dissipates, so its kinetic plus
    // potential energy never rises above the start (within 0.01 × its weight
    // × 1 m). Plain pivots are solved in lanes, in colours; pivots with
    // limits one at a time, in slot order; each net made in three orders.
    // With the relax pass in the reverse of the biased pass's order (the
    // solver before 2026-12-03), four of the six nets gained 116 to 161 ×
    // weight × 1 m, their fastest bodies at 134 to 172 m/s; only the
    // interleaved order held.
    let plain = JointKind::Pivot { limits: None, motor: None };
    let limited = JointKind::Pivot { limits: Some((s(-3.0), s(3.0))), motor: None };
    for (name, kind) in [("plain pivots", plain), ("limited pivots", limited)] {
        for order in [NetOrder::Interleaved, NetOrder::HorizontalFirst, NetOrder::VerticalFirst] {
            let (most, fastest) = hung_net(24, kind, order);
            println!(
                "24 × 24 net of {name}, {order:?}: energy above the start at most {most:.5} × weight × 1 m (≤ 0.01); fastest body {fastest:.2} m/s"
            );
            assert!(most <= 0.01, "{name}, {order:?}: energy gained, {most} × weight × 1 m");
        }
    }
}
