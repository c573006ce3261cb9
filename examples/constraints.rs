//! Every kind of constraint, and one written by the game against the trait:
//! a spring and a damped spring bobbing, a rod pendulum, a rope, a motorised wheel
//! on a pivot, a door on a pivot with angle limits, a welded pair, a breakable rod
//! that snaps when a weight drops on it, and a "keep above the floor" constraint.
//!
//! Run: `cargo run --example constraints`

use arphysics::constraint::Constraint;
use arphysics::{
    Body, BodyDef, GravityForceGenerator, Hook, Joint, JointDef, JointHandle, JointKind, MaxTorque, Motor,
    PolygonPath, Rect, Scalar, Vector2, World, WorldBuffers, WorldDef,
};

/// A game constraint: never let the body's bottom go below `floor` (m).
struct KeepAboveFloor {
    floor: Scalar,
}

impl Constraint for KeepAboveFloor {
    fn solve(&mut self, a: &mut Body, _world: &mut Body, h: Scalar) {
        // Highest downward speed that still stops at the floor within this sub-step.
        let gap = a.position().y - a.bounding_radius() - self.floor;
        let slowest = -gap / h;
        let vy = a.linear_velocity().y;
        if vy < slowest {
            a.apply_linear_impulse(Vector2::new(Scalar::ZERO, (slowest - vy) * a.mass()));
        }
    }
}

fn snapped(_: &mut World<'_>, h: JointHandle, joint: Joint) {
    println!(
        "  the breakable rod {h:?} snapped: {:.2} N·s in one step",
        joint.step_impulse().to_num::<f64>()
    );
}

fn main() -> Result<(), arphysics::Error> {
    let s = Scalar::from_num::<f64>;
    let v = |x: f64, y: f64| Vector2::new(s(x), s(y));
    // The game's constraint object outlives the world that borrows it.
    let mut keep = KeepAboveFloor { floor: s(5.0) };
    let mut buffers = WorldBuffers::<32, 128, 16>::new();
    let mut world = World::new(
        WorldDef::with_bounds(Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0))),
        buffers.storage(),
    )?;
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)))?;
    world.set_joint_break_callback(Some(snapped));
    let floor = world.add_path(PolygonPath::rectangle(s(90.0), s(2.0))?)?;
    world.add_body(BodyDef::polygon(floor).position(v(0.0, -1.0)).static_body())?;

    // A spring and a damped spring hanging from the ceiling (rest length 2 m).
    let spring_bob = world.add_body(BodyDef::circle(s(0.3)).position(v(-20.0, 20.0)))?;
    world.add_joint(JointDef::to_world(
        spring_bob,
        Vector2::ZERO,
        v(-20.0, 23.0),
        JointKind::Spring { stiffness: s(20.0), rest_length: s(2.0) },
    ))?;
    let damped_bob = world.add_body(BodyDef::circle(s(0.3)).position(v(-16.0, 20.0)))?;
    world.add_joint(JointDef::to_world(
        damped_bob,
        Vector2::ZERO,
        v(-16.0, 23.0),
        JointKind::DampedSpring { stiffness: s(20.0), damping: s(1.0), rest_length: s(2.0) },
    ))?;

    // A rod pendulum and a rope (slack until it pulls taut).
    let pendulum = world.add_body(BodyDef::circle(s(0.3)).position(v(-10.0, 20.0)))?;
    world.add_joint(JointDef::to_world(
        pendulum,
        Vector2::ZERO,
        v(-12.0, 23.0),
        JointKind::Rod { length: s(3.6) },
    ))?;
    let on_rope = world.add_body(BodyDef::circle(s(0.3)).position(v(-6.0, 22.0)))?;
    world.add_joint(JointDef::to_world(
        on_rope,
        Vector2::ZERO,
        v(-6.0, 23.0),
        JointKind::Rope { max_length: s(4.0) },
    ))?;

    // A wheel driven by a torque-limited motor, and a door limited to ±45°.
    let wheel = world.add_body(BodyDef::circle(s(1.0)).position(v(0.0, 20.0)))?;
    let motor = Motor { speed: s(3.0), max_torque: MaxTorque::Limited(s(50.0)) };
    world.add_joint(JointDef::to_world(
        wheel,
        Vector2::ZERO,
        v(0.0, 20.0),
        JointKind::Pivot { limits: None, motor: Some(motor) },
    ))?;
    let door_shape = world.add_path(PolygonPath::rectangle(s(3.0), s(0.2))?)?;
    let door = world.add_body(BodyDef::polygon(door_shape).position(v(7.5, 20.0)))?;
    let limits = Some((s(-std::f64::consts::FRAC_PI_4), s(std::f64::consts::FRAC_PI_4)));
    world.add_joint(JointDef::to_world(
        door,
        v(-1.5, 0.0),
        v(6.0, 20.0),
        JointKind::Pivot { limits, motor: None },
    ))?;

    // Two boxes welded into an L, falling as one.
    let unit = world.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    let l1 = world.add_body(BodyDef::polygon(unit).position(v(14.0, 20.0)))?;
    let l2 = world.add_body(BodyDef::polygon(unit).position(v(15.0, 21.0)))?;
    world.add_joint(JointDef::new(l1, v(0.5, 0.5), l2, v(-0.5, -0.5), JointKind::Weld))?;

    // A breakable rod holding a box; a heavy ball dropped on it snaps the rod.
    let held = world.add_body(BodyDef::polygon(unit).position(v(22.0, 20.0)))?;
    world.add_joint(
        JointDef::to_world(held, Vector2::ZERO, v(22.0, 23.0), JointKind::Rod { length: s(3.0) })
            .breakable(s(3.0)),
    )?;
    world.add_body(BodyDef::circle(s(0.4)).position(v(22.0, 30.0)).density(s(30.0)))?;

    // The game's own constraint: a ball that never sinks below y = 5.
    let floater = world.add_body(BodyDef::circle(s(0.5)).position(v(30.0, 20.0)))?;
    world.add_constraint(floater, None, Hook::Borrowed(&mut keep))?;

    for step in 1..=240 {
        let report = world.step(s(1.0 / 60.0))?;
        if report.joints_broken > 0 {
            println!("step {step}: {} joint(s) broke", report.joints_broken);
        }
    }
    let y = |h| world.body(h).map(|b: &Body| b.position().y.to_num::<f64>());
    println!("after 4 s:");
    let sag = world.body(damped_bob)?.mass().to_num::<f64>() * 10.0 / 20.0;
    println!(
        "  spring bob at y = {:.2} (still bouncing), damped bob at y = {:.2} (at rest: 23 − 2 − m·g/k = {:.2})",
        y(spring_bob)?,
        y(damped_bob)?,
        21.0 - sag
    );
    let swing = (world.body(pendulum)?.position() - v(-12.0, 23.0)).length().to_num::<f64>();
    println!("  pendulum rod length {swing:.4} m (3.6)");
    println!("  rope bob {:.2} m below its anchor (≤ 4)", 23.0 - y(on_rope)?);
    println!(
        "  wheel spins at {:.3} rad/s (motor target 3)",
        world.body(wheel)?.angular_velocity().to_num::<f64>()
    );
    println!("  door hangs at {:.3} rad (limit −0.785)", world.body(door)?.angle().to_num::<f64>());
    let gap = (world.body(l2)?.position() - world.body(l1)?.position()).length().to_num::<f64>();
    println!("  welded boxes landed {gap:.4} m apart (√2 = 1.4142)");
    println!("  the held box fell to the floor, y = {:.2}, after its rod snapped", y(held)?);
    println!("  the floater rests at y = {:.3} (floor 5 + radius 0.5)", y(floater)?);
    Ok(())
}
