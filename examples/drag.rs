//! Dragging and throwing a body with a target (mouse) joint, as a game's
//! cursor or a grabbing hand would: a 2 kg crate resting on the ground is
//! picked up at its centre, carried to the right, swung up and let go, then
//! flies and lands. The joint is a 5 Hz spring (damping ratio 0.7) with a
//! force limit of 1,000 N per kilogram; the game moves its target each frame
//! with `World::set_joint_target` and removes the joint to let go. (Held off
//! its centre a body swings about the held point like a pendulum; the joint's
//! spin damping, Box2D v3's, settles it over a few seconds.)
//!
//! Prints the crate's track and checks its own run: the point held hangs
//! g/ω² below the cursor, the crate leaves the hand at the cursor's speed, and
//! it flies on as a thrown body does.
//!
//! Run: `cargo run --example drag`

use arphysics::{
    BodyDef, Capacities, Error, GravityForceGenerator, JointDef, JointKind, PolygonPath, Scalar, Vector2,
    World, WorldDef,
};

fn v(x: f64, y: f64) -> Result<Vector2, Error> {
    Vector2::try_from_f64(x, y, "point")
}

fn main() -> Result<(), Error> {
    let s = Scalar::from_num::<f64>;
    let mut world = World::with_capacities(WorldDef::new(s(60.0), s(30.0)), Capacities::for_bodies(8))?;
    world.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)?))?;
    let slab = world.add_path(PolygonPath::rectangle(s(60.0), s(1.0))?)?;
    world.add_body(BodyDef::polygon(slab).position(v(30.0, 0.5)?).static_body())?;
    let square = world.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    let crate_ = world.add_body(BodyDef::polygon(square).position(v(10.0, 1.5)?).mass(s(2.0)))?;
    let dt = Scalar::from_num(1) / 60;

    // Press on the crate: the anchor is the point pressed in the crate's
    // frame (here its centre), the target the cursor.
    let mut cursor = (10.0, 1.5);
    let anchor = world.body(crate_)?.transform().apply_inv(v(cursor.0, cursor.1)?);
    let mass = world.body(crate_)?.mass();
    let kind = JointKind::Target { hertz: s(5.0), damping_ratio: s(0.7), max_force: mass * 1000 };
    let grab = world.add_joint(JointDef::to_world(crate_, anchor, v(cursor.0, cursor.1)?, kind))?;

    // Lift it 3 m and hold it there for 4 s: the point held settles g/ω² below
    // the cursor (ω = 2π·5 Hz), whatever the mass.
    cursor = (10.0, 4.5);
    world.set_joint_target(grab, v(cursor.0, cursor.1)?)?;
    for _ in 0..240 {
        world.step(dt)?;
    }
    let held = world.body(crate_)?.transform().apply(anchor).to_f64();
    let sag = 10.0 / (std::f64::consts::TAU * 5.0).powi(2);
    println!(
        "held: the point held at ({:.4}, {:.4}) under the cursor at {cursor:?}: {:.4} m below (g/ω² = {sag:.4} m)",
        held.0,
        held.1,
        cursor.1 - held.1
    );
    assert!((held.0 - cursor.0).abs() < 0.002 && (cursor.1 - held.1 - sag).abs() < 0.002);

    // Swing: the cursor moves right and up at (12, 6) m/s for a third of a
    // second, then lets go.
    for _ in 0..20 {
        cursor = (cursor.0 + 0.2, cursor.1 + 0.1);
        world.set_joint_target(grab, v(cursor.0, cursor.1)?)?;
        world.step(dt)?;
    }
    world.remove_joint(grab)?;
    let (vx, vy) = world.body(crate_)?.linear_velocity().to_f64();
    println!("let go at ({:.2}, {:.2}) m/s; the cursor moved at (12, 6)", vx, vy);
    assert!((vx - 12.0).abs() < 2.0 && (vy - 6.0).abs() < 2.0);

    // Flight: a thrown body's centre follows the parabola until it lands.
    let (x0, y0) = world.body(crate_)?.position().to_f64();
    println!("{:>6} {:>9} {:>9} {:>11}", "t (s)", "x", "y", "parabola y");
    let mut worst = 0.0f64;
    for n in 1..=24 {
        world.step(dt)?;
        let t = f64::from(n) / 60.0;
        let (x, y) = world.body(crate_)?.position().to_f64();
        let parabola = y0 + vy * t - 5.0 * t * t;
        worst = worst.max((y - parabola).abs());
        if n % 6 == 0 {
            println!("{t:>6.3} {x:>9.3} {y:>9.3} {parabola:>11.3}");
        }
        assert!((x - (x0 + vx * t)).abs() < 0.01);
    }
    println!("flight: worst distance from the parabola {worst:.4} m (semi-implicit Euler's h·g·t/2 at most)");
    assert!(worst < 0.02);
    for _ in 0..240 {
        world.step(dt)?;
    }
    let (x, y) = world.body(crate_)?.position().to_f64();
    println!("landed at ({x:.2}, {y:.2}), {:.1} m from where it was picked up", x - 10.0);
    assert!(y < 2.1 && x > 15.0);
    Ok(())
}
