//! The testbed's scenes: the demo's (included from examples/demo/scenes.rs by
//! build.rs), the benchmark scenes (pyramid_20, large_pyramid, rain,
//! joint_grid: the definitions of benches/scenes.rs) and a shapes scene.
//!
//! Every scene's world is made by [`crate::scene_world`], which applies the
//! testbed's sub-step count and leaves room for spawned bodies and the drag
//! joint. Capacities are not part of the state, so this room changes no hash.

use arphysics::{BodyDef, Capsule, Error, GravityForceGenerator, PolygonPath, Rect, Segment, Vector2, World};

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
