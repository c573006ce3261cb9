//! The testbed's scenes: the demo's (included from examples/demo/scenes.rs by
//! build.rs), the benchmark scenes (pyramid_20, large_pyramid, rain,
//! joint_grid: the definitions of benches/scenes.rs) and one scene per
//! feature: shapes, joints, sensors.
//!
//! Every scene's world is made by [`crate::scene_world`], which applies the
//! testbed's sub-step count and leaves room for spawned bodies and the drag
//! joint. Capacities are not part of the state, so this room changes no hash.

use arphysics::{
    BodyDef, Capsule, Error, GravityForceGenerator, JointDef, JointKind, MaxTorque, Motor, PolygonPath, Rect,
    Segment, Vector2, World,
};

/// The demo's scenes, as examples/demo/scenes.rs has them.
#[allow(dead_code, unused_imports, clippy::all)]
pub mod demo {
    include!(concat!(env!("OUT_DIR"), "/demo_scenes.rs"));
}

/// A scene as the testbed runs it: a world, and for the demo's scenes what the
/// scene still adds as it runs.
pub enum Running {
    /// A demo scene (it may spawn bodies before a step).
    Demo(demo::Running),
    /// A scene that is only its world.
    Plain(World<'static>),
}

impl Running {
    /// The world.
    pub fn world(&self) -> &World<'static> {
        match self {
            Self::Demo(r) => &r.world,
            Self::Plain(w) => w,
        }
    }

    /// The world, to change.
    pub fn world_mut(&mut self) -> &mut World<'static> {
        match self {
            Self::Demo(r) => &mut r.world,
            Self::Plain(w) => w,
        }
    }

    /// What the scene adds before stepping frame `frame`.
    ///
    /// # Errors
    /// What adding a body can fail with (a world the user filled).
    pub fn before_step(&mut self, frame: u32) -> Result<(), Error> {
        match self {
            Self::Demo(r) => r.before_step(frame),
            Self::Plain(_) => Ok(()),
        }
    }
}

/// How a scene is built.
#[derive(Clone, Copy)]
pub enum Build {
    /// A demo scene (its builder).
    Demo(fn() -> Result<demo::Running, Error>),
    /// A world builder.
    Plain(fn() -> Result<World<'static>, Error>),
}

/// A scene of the testbed.
#[derive(Clone, Copy)]
pub struct Scene {
    /// Its name (unique).
    pub name: &'static str,
    /// One line about it.
    pub about: &'static str,
    /// The region drawn at first, metres (x0, y0, x1, y1). Drawing only.
    pub view: (f64, f64, f64, f64),
    /// Frames the browser check runs it (and the native hashes cover).
    pub check_frames: u32,
    /// Its builder.
    pub build: Build,
}

impl Scene {
    /// Builds it.
    ///
    /// # Errors
    /// What the builder fails with.
    pub fn build(&self) -> Result<Running, Error> {
        Ok(match self.build {
            Build::Demo(f) => Running::Demo(f()?),
            Build::Plain(f) => Running::Plain(f()?),
        })
    }
}

/// Every scene, in picker order.
pub fn all() -> Vec<Scene> {
    let mut v: Vec<Scene> = demo::SCENES
        .iter()
        .map(|s| Scene {
            name: s.name,
            about: s.about,
            view: s.view,
            check_frames: 240,
            build: Build::Demo(s.build),
        })
        .collect();
    v.extend_from_slice(&[
        Scene {
            name: "shapes",
            about: "every shape kind: capsules, segments, rounded boxes, circles and polygons",
            view: (-16.0, -2.0, 16.0, 20.0),
            check_frames: 240,
            build: Build::Plain(shapes),
        },
        Scene {
            name: "joints",
            about: "every joint kind: a pivot chain with limits, a motor, a weld, a rod, a rope, a damped spring",
            view: (-16.0, -2.0, 16.0, 20.0),
            check_frames: 240,
            build: Build::Plain(joints),
        },
        Scene {
            name: "sensors",
            about: "two sensor zones (blue): balls fall through one and settle in the other; the page lists the begin and end events",
            view: (-12.0, -2.0, 12.0, 20.0),
            check_frames: 240,
            build: Build::Plain(sensors),
        },
        Scene {
            name: "pyramid_20",
            about: "benchmark: a 20-row pyramid of 1 m boxes (210 bodies)",
            view: (-22.0, -2.0, 22.0, 22.0),
            check_frames: 120,
            build: Build::Plain(pyramid_20),
        },
        Scene {
            name: "large_pyramid",
            about: "benchmark: a 100-row pyramid (5,050 boxes)",
            view: (-70.0, -3.0, 70.0, 103.0),
            check_frames: 30,
            build: Build::Plain(large_pyramid),
        },
        Scene {
            name: "bench_rain",
            about: "benchmark: 1,000 circles, boxes and triangles falling into a bin",
            view: (-45.0, -3.0, 45.0, 42.0),
            check_frames: 60,
            build: Build::Plain(bench_rain),
        },
        Scene {
            name: "joint_grid",
            about: "benchmark: a 100 × 100 grid of balls on 19,800 pivots, hanging from two corners",
            view: (-110.0, 0.0, 110.0, 155.0),
            check_frames: 20,
            build: Build::Plain(joint_grid),
        },
    ]);
    v
}

// ---- The benchmark scenes: benches/scenes/defs.rs, which `cargo bench` times. ----

/// The definitions `cargo bench --bench scenes` uses, included as they are.
#[allow(dead_code, clippy::all)]
#[path = "../../benches/scenes/defs.rs"]
mod bench;

fn pyramid_20() -> Result<World<'static>, Error> {
    bench::pyramid_20(crate::scene_world)
}

fn large_pyramid() -> Result<World<'static>, Error> {
    bench::large_pyramid(crate::scene_world)
}

fn bench_rain() -> Result<World<'static>, Error> {
    bench::rain(crate::scene_world)
}

fn joint_grid() -> Result<World<'static>, Error> {
    bench::joint_grid(crate::scene_world)
}

// ---- The shapes scene. ----

/// Every shape kind: a floor and walls of segments, a segment ramp, a rounded
/// ledge, rows of capsules, rounded boxes, circles and polygons dropped on
/// them. Built from whole centimetres (no float).
fn shapes() -> Result<World<'static>, Error> {
    use demo::{at, cm};
    let bounds = Rect::from_corners(Vector2::from_int(-60, -20), Vector2::from_int(60, 80));
    let caps = arphysics::Capacities {
        bodies: 128,
        paths: 16,
        contacts: 512,
        joints: 0,
        post_step_callbacks: 64,
        events: 64,
        chain_vertices: 0,
        shapes: 8,
    };
    let mut w = crate::scene_world(bounds, caps)?;
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10)))?;
    // Floor and walls: segments, in world coordinates (the body re-centres them).
    for (a, b) in [
        ((-1400, 0), (1400, 0)),
        ((-1400, 0), (-1400, 1600)),
        ((1400, 0), (1400, 1600)),
        ((-1400, 900), (-500, 500)),
    ] {
        w.add_body(BodyDef::segment(Segment::new(at(a.0, a.1), at(b.0, b.1))?).friction(cm(60)))?;
    }
    // A rounded static ledge on the right.
    let ledge = w.add_path(PolygonPath::rounded_rectangle(cm(500), cm(50), cm(20))?)?;
    w.add_body(BodyDef::polygon(ledge).position(at(800, 700)).angle(cm(20)).static_body())?;
    let rounded = w.add_path(PolygonPath::rounded_rectangle(cm(100), cm(60), cm(15))?)?;
    let small = w.add_path(PolygonPath::rounded_rectangle(cm(70), cm(70), cm(30))?)?;
    let hex = w.add_path(PolygonPath::new(&[
        at(50, 0),
        at(25, 43),
        at(-25, 43),
        at(-50, 0),
        at(-25, -43),
        at(25, -43),
    ])?)?;
    // Compound bodies (an L, a hammer, a dumbbell) dropped onto the pins.
    demo::add_compound_toys(&mut w, -450, 450)?;
    // A row of standing capsules (pins) on the floor.
    for k in 0..6 {
        let pin = Capsule::new(at(0, -40), at(0, 40), cm(15))?;
        w.add_body(BodyDef::capsule(pin).position(at(-200 + 90 * k, 56)))?;
    }
    // A stack of rounded boxes.
    for k in 0..5 {
        w.add_body(BodyDef::polygon(rounded).position(at(-900, 31 + 62 * k)))?;
    }
    // A pill rolling down the ramp, and capsules, rounded squares, circles and
    // hexagons falling in a staggered grid.
    w.add_body(BodyDef::capsule(Capsule::new(at(-30, 0), at(30, 0), cm(25))?).position(at(-1250, 1100)))?;
    for row in 0..4 {
        for col in 0..7 {
            let p = at(-600 + 200 * col + 50 * (row % 2), 900 + 160 * row);
            let def = match (row + col) % 4 {
                0 => BodyDef::capsule(Capsule::new(at(-40, 0), at(40, 0), cm(20))?),
                1 => BodyDef::polygon(small),
                2 => BodyDef::circle(cm(35)),
                _ => BodyDef::polygon(hex),
            };
            w.add_body(def.position(p).angle(cm(30 * col - 90)))?;
        }
    }
    Ok(w)
}

// ---- The joints scene. ----

/// A world for a feature scene: bounds (−60, −20)–(60, 80) m, gravity (0, −10),
/// a floor with its top at y = 0 from −15 to 15 m.
fn feature_world(bodies: usize, joints: usize) -> Result<World<'static>, Error> {
    use demo::{at, cm};
    let bounds = Rect::from_corners(Vector2::from_int(-60, -20), Vector2::from_int(60, 80));
    let mut w = crate::scene_world(bounds, bench::capacities(bodies, joints))?;
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10)))?;
    let floor = w.add_path(PolygonPath::rectangle(cm(3000), cm(100))?)?;
    w.add_body(BodyDef::polygon(floor).position(at(0, -50)).static_body())?;
    Ok(w)
}

/// Every joint kind, left to right: a chain of five planks on pivots with
/// ±30° limits hanging from a world point; a wheel driven by a pivot's motor
/// (2 rad/s, at most 400 N·m) with a box resting on it; two boxes welded into
/// an L hanging from a rod; a ball swinging on a slack rope; a box bobbing on
/// a damped spring. Built from whole centimetres (no float).
fn joints() -> Result<World<'static>, Error> {
    use demo::{at, cm};
    let mut w = feature_world(32, 16)?;
    let plank = w.add_path(PolygonPath::rectangle(cm(100), cm(24))?)?;
    let block = w.add_path(PolygonPath::rectangle(cm(80), cm(80))?)?;
    let pivot = |limits| JointKind::Pivot { limits, motor: None };
    let limits = Some((-demo::cm(52), demo::cm(52)));
    // The chain: planks 1 m long, joined end to end, from (−9, 16) sideways.
    let mut prev = None;
    for k in 0..5 {
        let b = w.add_body(BodyDef::polygon(plank).position(at(-850 + 100 * k, 1600)))?;
        let (near, far) = (at(-50, 0), at(50, 0));
        let j = match prev {
            None => JointDef::to_world(b, near, at(-900, 1600), pivot(None)),
            Some(p) => JointDef::new(p, far, b, near, pivot(limits)),
        };
        w.add_joint(j)?;
        prev = Some(b);
    }
    // The motor: a wheel on a pivot to a world point, turning clockwise, a
    // box dropped on it.
    let wheel = w.add_body(BodyDef::circle(cm(120)).position(at(-300, 400)).friction(cm(90)))?;
    let motor = Motor { speed: -cm(200), max_torque: MaxTorque::Limited(cm(40_000)) };
    w.add_joint(JointDef::to_world(
        wheel,
        Vector2::ZERO,
        at(-300, 400),
        JointKind::Pivot { limits: None, motor: Some(motor) },
    ))?;
    w.add_body(BodyDef::polygon(block).position(at(-300, 700)))?;
    // The weld: an L of two boxes, hung by a rod of 3 m from (3, 15).
    let a = w.add_body(BodyDef::polygon(block).position(at(300, 1200)))?;
    let b = w.add_body(BodyDef::polygon(block).position(at(380, 1200)))?;
    w.add_joint(JointDef::new(a, at(40, 0), b, at(-40, 0), JointKind::Weld))?;
    let c = w.add_body(BodyDef::polygon(block).position(at(300, 1120)))?;
    w.add_joint(JointDef::new(a, at(0, -40), c, at(0, 40), JointKind::Weld))?;
    w.add_joint(JointDef::to_world(a, at(0, 40), at(300, 1500), JointKind::Rod { length: cm(260) }))?;
    // The rope: 4 m from (8, 15), the ball let go 3 m to the side and 1 m
    // below (slack, then taut).
    let ball = w.add_body(BodyDef::circle(cm(40)).position(at(1100, 1400)))?;
    w.add_joint(JointDef::to_world(
        ball,
        Vector2::ZERO,
        at(800, 1500),
        JointKind::Rope { max_length: cm(400) },
    ))?;
    // The damped spring: 20 N/m per kg (ω ≈ 4.5 rad/s), damping ratio ≈ 0.1,
    // rest length 2 m, from (12, 14); the box starts 2 m below its rest point.
    let bob = w.add_body(BodyDef::polygon(block).position(at(1200, 800)))?;
    let m = w.body(bob)?.mass();
    let spring = JointKind::DampedSpring { stiffness: m * 20, damping: m * cm(90), rest_length: cm(200) };
    w.add_joint(JointDef::to_world(bob, Vector2::ZERO, at(1200, 1400), spring))?;
    Ok(w)
}

// ---- The sensors scene. ----

/// Two sensor zones: a 6 × 2 m one in mid-air that a column of balls falls
/// through (a begin and an end event each) and a 4 × 1.5 m one on the floor
/// where some of them settle (a begin, no end); slippery boxes slide down a
/// ramp towards it.
fn sensors() -> Result<World<'static>, Error> {
    use demo::{at, cm};
    let mut w = feature_world(64, 0)?;
    let zone = w.add_path(PolygonPath::rectangle(cm(600), cm(200))?)?;
    w.add_body(BodyDef::polygon(zone).position(at(0, 800)).static_body().sensor())?;
    let pit = w.add_path(PolygonPath::rectangle(cm(400), cm(150))?)?;
    w.add_body(BodyDef::polygon(pit).position(at(0, 75)).static_body().sensor())?;
    let ramp = w.add_path(PolygonPath::rectangle(cm(800), cm(30))?)?;
    w.add_body(BodyDef::polygon(ramp).position(at(-700, 500)).angle(-cm(40)).static_body())?;
    for k in 0..12 {
        let x = -200 + 35 * (k % 12);
        w.add_body(BodyDef::circle(cm(30)).position(at(x, 1300 + 90 * k)))?;
    }
    let block = w.add_path(PolygonPath::rectangle(cm(60), cm(60))?)?;
    for k in 0..4 {
        let def = BodyDef::polygon(block).position(at(-1000 + 90 * k, 760 - 40 * k)).angle(-cm(40));
        w.add_body(def.friction(cm(5)))?;
    }
    Ok(w)
}
