//! Box2D v3's benchmark scenes (`shared/benchmarks.c`), described once, engine-neutrally,
//! so that every engine builds exactly the same bodies, shapes and joints.
//!
//! Differences from Box2D's own definitions, forced by what all three engines share:
//! * Ground is made of static bodies of one shape each instead of one static body
//!   with several shapes: arphysics has one shape per body, and bodies of at most
//!   128 m radius.
//! * `many_pyramids`: each floor is two 220 m segments (one body each) where Box2D
//!   puts one 440 m segment; the pyramids stand on the same line. (Before arphysics
//!   had segments, the floors were boxes.)
//! * `rain`: Box2D's rain drops 5-body ragdolls ("humans") in groups and recycles
//!   them; ragdolls need capsules and joint limits, so this rain drops 1,000 circles,
//!   boxes and hexagons, all at once from a grid, into a U-shaped container.
//! * `pyramid_20` is not one of Box2D's benchmarks: it is the 20-row pyramid of
//!   arphysics's own `cargo bench --bench pyramid` (Box2D's large pyramid with
//!   20 rows, as in Box2D's debug build).

/// A collision shape, in metres, centred on the body's origin (= centre of mass).
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDesc {
    /// An axis-aligned box of half-extents `hx`, `hy`.
    Box { hx: f64, hy: f64 },
    /// A circle.
    Circle { r: f64 },
    /// A convex polygon, counter-clockwise, centroid at the origin.
    Polygon(Vec<(f64, f64)>),
    /// A segment between two points, relative to the body's origin (static bodies).
    Segment((f64, f64), (f64, f64)),
}

/// One body.
#[derive(Clone, Debug)]
pub struct BodyDesc {
    pub shape: ShapeDesc,
    pub x: f64,
    pub y: f64,
    pub dynamic: bool,
    /// kg/m².
    pub density: f64,
    pub friction: f64,
    /// Bodies with this flag never collide with each other (Box2D's category 2,
    /// mask !2 in the joint grid); they still collide with everything else.
    pub no_self_collision: bool,
}

/// A pivot (revolute) joint between bodies `a` and `b` at a world point.
#[derive(Clone, Copy, Debug)]
pub struct JointDesc {
    pub a: usize,
    pub b: usize,
    pub anchor: (f64, f64),
}

/// A whole scene.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: &'static str,
    pub bodies: Vec<BodyDesc>,
    pub joints: Vec<JointDesc>,
    /// Steps Box2D's benchmark runs for this scene (`benchmark/main.c`).
    pub steps: usize,
    /// World bounds (arphysics needs them): min x, min y, max x, max y.
    pub bounds: (f64, f64, f64, f64),
    /// Candidate pairs/arbiters per body to reserve in arphysics.
    pub contacts_per_body: usize,
    /// Index of the body whose drift and sag the quality check reports (the top box).
    pub top_body: usize,
}

pub const GRAVITY: (f64, f64) = (0.0, -10.0);
pub const TIME_STEP: f64 = 1.0 / 60.0;
pub const SUBSTEPS: u32 = 4;
/// Box2D's default friction, used everywhere.
pub const FRICTION: f64 = 0.6;

pub const NAMES: [&str; 6] =
    ["large_pyramid", "many_pyramids", "pyramid_20", "rain", "joint_grid", "rollback_500"];

/// The scene called `name`, if there is one.
#[must_use]
pub fn by_name(name: &str) -> Option<Scene> {
    match name {
        "large_pyramid" => Some(pyramid("large_pyramid", 100, 500)),
        "pyramid_20" => Some(pyramid("pyramid_20", 20, 1000)),
        "many_pyramids" => Some(many_pyramids()),
        "rain" => Some(rain()),
        "joint_grid" => Some(joint_grid()),
        "rollback_500" => Some(rollback_500()),
        _ => None,
    }
}

fn ground_box(hx: f64, hy: f64, x: f64, y: f64) -> BodyDesc {
    BodyDesc {
        shape: ShapeDesc::Box { hx, hy },
        x,
        y,
        dynamic: false,
        density: 1.0,
        friction: FRICTION,
        no_self_collision: false,
    }
}

fn dynamic(shape: ShapeDesc, x: f64, y: f64) -> BodyDesc {
    BodyDesc { shape, x, y, dynamic: true, density: 1.0, friction: FRICTION, no_self_collision: false }
}

/// Box2D's `CreateLargePyramid` with `base` rows: boxes of 1 m (half-extent 0.5),
/// density 1, on a static ground box 200 × 2 m centred at (0, −1).
fn pyramid(name: &'static str, base: usize, steps: usize) -> Scene {
    let mut bodies = vec![ground_box(100.0, 1.0, 0.0, -1.0)];
    let a = 0.5;
    let shift = a;
    for i in 0..base {
        let y = (2.0 * i as f64 + 1.0) * shift;
        for j in i..base {
            let x = (i as f64 + 1.0) * shift + 2.0 * (j - i) as f64 * shift - a * base as f64;
            bodies.push(dynamic(ShapeDesc::Box { hx: a, hy: a }, x, y));
        }
    }
    let top_body = bodies.len() - 1;
    let top = base as f64 + 10.0;
    Scene {
        name,
        bodies,
        joints: Vec::new(),
        steps,
        bounds: (-150.0, -20.0, 150.0, top + 100.0),
        contacts_per_body: 4,
        top_body,
    }
}

/// Box2D's `CreateManyPyramids`: 20 × 20 pyramids of 10 rows (22,000 boxes), 20
/// floors 11 m apart, 20 pyramids per floor.
fn many_pyramids() -> Scene {
    let base_count = 10usize;
    let extent = 0.5;
    let rows = 20usize;
    let columns = 20usize;
    let ground_dy = 2.0 * extent * (base_count as f64 + 1.0); // 11 m
    let ground_width = 2.0 * extent * columns as f64 * (base_count as f64 + 1.0); // 220 m
    let base_width = 2.0 * extent * base_count as f64;
    let mut bodies = Vec::new();
    let mut ground_y = 0.0;
    for _ in 0..rows {
        // Box2D's floor is one segment from −groundWidth to groundWidth; here two
        // (an arphysics body is at most 128 m in radius), on the same line.
        for x in [-0.5 * ground_width, 0.5 * ground_width] {
            let half = 0.5 * ground_width;
            let mut floor = ground_box(half, 0.0, x, ground_y);
            floor.shape = ShapeDesc::Segment((-half, 0.0), (half, 0.0));
            bodies.push(floor);
        }
        ground_y += ground_dy;
    }
    let mut base_y = 0.0;
    for _ in 0..rows {
        for j in 0..columns {
            let center_x = -0.5 * ground_width + j as f64 * (base_width + 2.0 * extent) + 2.0 * extent;
            for i in 0..base_count {
                let y = (2.0 * i as f64 + 1.0) * extent + base_y;
                for k in i..base_count {
                    let x = (i as f64 + 1.0) * extent + 2.0 * (k - i) as f64 * extent + center_x - 0.5;
                    bodies.push(dynamic(ShapeDesc::Box { hx: extent, hy: extent }, x, y));
                }
            }
        }
        base_y += ground_dy;
    }
    let top_body = bodies.len() - 1;
    Scene {
        name: "many_pyramids",
        bodies,
        joints: Vec::new(),
        steps: 200,
        bounds: (-160.0, -20.0, 160.0, 320.0),
        contacts_per_body: 4,
        top_body,
    }
}

/// 1,000 bodies (circles r 0.4, boxes 0.8 m, hexagons r 0.45, in turn) in a grid of
/// 40 × 25 with 1.25 m spacing, from 3 m to 33 m above the floor of a U container
/// 60 m wide with 30 m walls; they all fall at once.
fn rain() -> Scene {
    let mut bodies = bin(30.0, 30.0);
    let hexagon: Vec<(f64, f64)> = (0..6)
        .map(|k| {
            let t = std::f64::consts::PI / 3.0 * f64::from(k);
            (0.45 * t.cos(), 0.45 * t.sin())
        })
        .collect();
    let mut n = 0usize;
    for row in 0..25 {
        for col in 0..40 {
            let x = -24.375 + 1.25 * f64::from(col);
            let y = 3.0 + 1.25 * f64::from(row);
            let shape = match n % 3 {
                0 => ShapeDesc::Circle { r: 0.4 },
                1 => ShapeDesc::Box { hx: 0.4, hy: 0.4 },
                _ => ShapeDesc::Polygon(hexagon.clone()),
            };
            bodies.push(dynamic(shape, x, y));
            n += 1;
        }
    }
    falling("rain", bodies)
}

/// A static U container on y = 0: a floor 2·`half_width` m wide inside (1 m
/// thick) and walls of `height` m (1 m thick) at its ends.
fn bin(half_width: f64, height: f64) -> Vec<BodyDesc> {
    let wall_x = half_width + 0.5;
    vec![
        ground_box(half_width + 1.0, 0.5, 0.0, -0.5),         // floor
        ground_box(0.5, height / 2.0, -wall_x, height / 2.0), // left wall
        ground_box(0.5, height / 2.0, wall_x, height / 2.0),  // right wall
    ]
}

/// A scene of bodies falling into a bin: 1,000 steps, 6 pairs per body, the last
/// body tracked.
fn falling(name: &'static str, bodies: Vec<BodyDesc>) -> Scene {
    let top_body = bodies.len() - 1;
    Scene {
        name,
        bodies,
        joints: Vec::new(),
        steps: 1000,
        bounds: (-100.0, -50.0, 100.0, 150.0),
        contacts_per_body: 6,
        top_body,
    }
}

/// Box2D's `CreateJointGrid`: 100 × 100 circles (radius 0.4) at 1 m spacing, body
/// (k, i) at (k, −i), each joined by a revolute joint to the body above and to the
/// one on its left at the midpoint; the 7 middle bodies of the top row are static;
/// the circles do not collide with each other.
/// The scene of `benches/rollback.rs` (not one of Box2D's): 500 circles (r 0.4 m),
/// 0.8 m boxes, triangles and hexagons (radius 0.45 m), in turn, dropped from a
/// 25 × 20 grid 1.25 m apart into a U container 40 m wide inside, 20 m tall walls.
/// Its ms/step × 8 is the stepping part of issue 16's rollback target (< 2 ms for a
/// restore and 8 steps), here beside the peers' figure for the same 8 steps.
fn rollback_500() -> Scene {
    let mut bodies = bin(20.0, 20.0);
    let regular = |n: u32, r: f64| -> Vec<(f64, f64)> {
        (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * f64::from(k) / f64::from(n) + std::f64::consts::FRAC_PI_2;
                (r * t.cos(), r * t.sin())
            })
            .collect()
    };
    for k in 0..500usize {
        let (row, col) = (k / 25, k % 25);
        let x = -15.0 + 1.25 * col as f64 + if row % 2 == 0 { 0.0 } else { 0.3 };
        let y = 2.0 + 1.25 * row as f64;
        let shape = match k % 4 {
            0 => ShapeDesc::Circle { r: 0.4 },
            1 => ShapeDesc::Box { hx: 0.4, hy: 0.4 },
            2 => ShapeDesc::Polygon(regular(3, 0.45)),
            _ => ShapeDesc::Polygon(regular(6, 0.45)),
        };
        bodies.push(dynamic(shape, x, y));
    }
    falling("rollback_500", bodies)
}

fn joint_grid() -> Scene {
    let n = 100usize;
    let mut bodies = Vec::with_capacity(n * n);
    let mut joints = Vec::with_capacity(2 * n * n);
    for k in 0..n {
        for i in 0..n {
            let index = bodies.len();
            let is_static_at = |k: usize, i: usize| k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0;
            let is_static = is_static_at(k, i);
            let (x, y) = (k as f64, -(i as f64));
            bodies.push(BodyDesc {
                shape: ShapeDesc::Circle { r: 0.4 },
                x,
                y,
                dynamic: !is_static,
                density: 1.0,
                friction: FRICTION,
                no_self_collision: true,
            });
            if i > 0 {
                joints.push(JointDesc { a: index - 1, b: index, anchor: (x, y + 0.5) });
            }
            // Box2D also joins the static top-row bodies to each other; such joints
            // do nothing, and arphysics refuses them, so they are left out (6 of 19,800).
            if k > 0 && !(is_static_at(k - 1, i) && is_static) {
                joints.push(JointDesc { a: index - n, b: index, anchor: (x - 0.5, y) });
            }
        }
    }
    Scene {
        name: "joint_grid",
        bodies,
        joints,
        steps: 500,
        // The grid swings down to about −140 m (its diagonal) and sideways.
        bounds: (-200.0, -300.0, 300.0, 100.0),
        contacts_per_body: 4,
        top_body: (n / 2) * n + n - 1, // the bottom of the middle column
    }
}

/// Top-to-bottom mass ratios the two-box stack is tried at, smallest first
/// (issue 16).
pub const MASS_RATIOS: [f64; 7] = [10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10000.0];
/// How far the top box may sink for the stack to hold, m (issue 16).
pub const MASS_RATIO_MAX_SINK: f64 = 0.05;
/// Steps the stack is run for: 10 s.
pub const MASS_RATIO_STEPS: usize = 600;

/// Issue 16's two-box stack (as `tests/quality_issue16.rs` builds it): a 1 m box
/// of density 1 (1 kg) resting on a static 100 × 2 m ground and a 1 m box of
/// density `ratio` resting on it, both exactly touching, friction 0.6. The
/// tracked body is the top box; it holds when it sinks at most
/// [`MASS_RATIO_MAX_SINK`] in [`MASS_RATIO_STEPS`] steps.
#[must_use]
pub fn two_box_stack(ratio: f64) -> Scene {
    let unit = ShapeDesc::Box { hx: 0.5, hy: 0.5 };
    let bodies = vec![
        ground_box(50.0, 1.0, 0.0, -1.0),
        dynamic(unit.clone(), 0.0, 0.5),
        BodyDesc { density: ratio, ..dynamic(unit, 0.0, 1.5) },
    ];
    Scene {
        name: "two_box_stack",
        bodies,
        joints: Vec::new(),
        steps: MASS_RATIO_STEPS,
        bounds: (-100.0, -20.0, 100.0, 100.0),
        contacts_per_body: 4,
        top_body: 2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn body_counts_match_box2d() {
        assert_eq!(by_name("large_pyramid").map(|s| s.bodies.len()), Some(5050 + 1));
        assert_eq!(by_name("pyramid_20").map(|s| s.bodies.len()), Some(210 + 1));
        assert_eq!(by_name("many_pyramids").map(|s| s.bodies.len()), Some(22_000 + 40));
        assert_eq!(by_name("rain").map(|s| s.bodies.len()), Some(1000 + 3));
        assert_eq!(by_name("rollback_500").map(|s| s.bodies.len()), Some(500 + 3));
        let grid = by_name("joint_grid");
        assert_eq!(grid.as_ref().map(|s| s.bodies.len()), Some(10_000));
        assert_eq!(grid.map(|s| s.joints.len()), Some(2 * 100 * 99 - 6));
    }
}
