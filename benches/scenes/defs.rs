//! Box2D v3's benchmark scenes as `cargo bench --bench scenes` builds them,
//! shared with the browser testbed (`testbed/src/scenes.rs`), which includes
//! this file with `#[path]`: the same definitions, so the testbed shows what
//! the benchmarks time. Each scene takes the function that makes its world.

use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, JointDef, JointKind, PathHandle, PolygonPath, Rect, Scalar,
    Vector2, World, WorldDef,
};

/// `x` in fixed point.
pub fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

/// `(x, y)` in fixed point.
pub fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// Makes a scene's world from its bounds and capacities: `cargo bench` uses
/// [`plain_world`], the testbed its own (its sub-step count, room to spawn).
pub type MakeWorld = fn(Rect, Capacities) -> Result<World<'static>, arphysics::Error>;

/// `World::with_capacities` with the default settings.
pub fn plain_world(bounds: Rect, caps: Capacities) -> Result<World<'static>, arphysics::Error> {
    World::with_capacities(WorldDef::with_bounds(bounds), caps)
}

/// Capacities for `bodies` bodies and `joints` joints: 16 paths, 4 pairs a body,
/// 64 callbacks and events, no chains (the testbed's feature scenes use them too).
pub fn capacities(bodies: usize, joints: usize) -> Capacities {
    Capacities {
        bodies,
        paths: 16,
        contacts: bodies * 4,
        joints,
        post_step_callbacks: 64,
        events: 64,
        chain_vertices: 0,
        shapes: 0,
    }
}

/// A world for `bodies` bodies and `joints` joints, gravity (0, −10).
fn world(make: MakeWorld, bodies: usize, joints: usize) -> Result<World<'static>, arphysics::Error> {
    let bounds = Rect::from_corners(v(-1000.0, -100.0), v(1000.0, 1000.0));
    let mut w = make(bounds, capacities(bodies, joints))?;
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)))?;
    Ok(w)
}

/// A pyramid of `rows` rows of 1 m boxes with its base centred on `x0`; all
/// boxes share one polygon path.
fn pyramid_at(
    w: &mut World<'_>,
    unit: PathHandle,
    rows: u32,
    x0: f64,
    y0: f64,
) -> Result<(), arphysics::Error> {
    for row in 0..rows {
        let count = rows - row;
        for j in 0..count {
            let x = x0 + f64::from(j) - f64::from(count) * 0.5 + 0.5;
            w.add_body(BodyDef::polygon(unit).position(v(x, y0 + 0.5 + f64::from(row))))?;
        }
    }
    Ok(())
}

/// Static ground boxes covering [−half, half] at y ∈ [−2, 0] (a body is at most
/// 256 m across, so a wide ground is several boxes).
fn ground(w: &mut World<'_>, half: f64) -> Result<(), arphysics::Error> {
    let piece = w.add_path(PolygonPath::rectangle(s(100.0), s(2.0))?)?;
    let mut x = -half + 50.0;
    while x < half {
        w.add_body(BodyDef::polygon(piece).position(v(x, -1.0)).static_body())?;
        x += 100.0;
    }
    Ok(())
}

pub fn large_pyramid(make: MakeWorld) -> Result<World<'static>, arphysics::Error> {
    let mut w = world(make, 5100, 0)?;
    ground(&mut w, 100.0)?;
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    pyramid_at(&mut w, unit, 100, 0.0, 0.0)?;
    Ok(w)
}

pub fn many_pyramids(make: MakeWorld) -> Result<World<'static>, arphysics::Error> {
    let mut w = world(make, 20 * 20 * 55 + 128, 0)?;
    ground(&mut w, 250.0)?;
    // 20 × 20 pyramids of 10 rows: 20 side by side on each of 20 shelves,
    // the shelves segments as in Box2D (two 250 m ones each: a body is at most
    // 256 m across).
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    for k in 0..20 {
        let y0 = f64::from(k) * 14.0;
        if k > 0 {
            for x in [-125.0, 125.0] {
                let shelf = arphysics::Segment::new(v(-125.0, 0.0), v(125.0, 0.0))?;
                w.add_body(BodyDef::segment(shelf).position(v(x, y0)))?;
            }
        }
        for i in 0..20 {
            pyramid_at(&mut w, unit, 10, -228.0 + f64::from(i) * 24.0, y0)?;
        }
    }
    Ok(w)
}

pub fn pyramid_20(make: MakeWorld) -> Result<World<'static>, arphysics::Error> {
    let mut w = world(make, 260, 0)?;
    ground(&mut w, 100.0)?;
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0))?)?;
    pyramid_at(&mut w, unit, 20, 0.0, 0.0)?;
    Ok(w)
}

pub fn rain(make: MakeWorld) -> Result<World<'static>, arphysics::Error> {
    let mut w = world(make, 1100, 0)?;
    ground(&mut w, 50.0)?;
    let wall = w.add_path(PolygonPath::rectangle(s(2.0), s(60.0))?)?;
    for x in [-41.0, 41.0] {
        w.add_body(BodyDef::polygon(wall).position(v(x, 30.0)).static_body())?;
    }
    let unit = w.add_path(PolygonPath::rectangle(s(0.8), s(0.8))?)?;
    let tri = w.add_path(PolygonPath::new(&[v(-0.5, -0.4), v(0.5, -0.4), v(0.0, 0.5)])?)?;
    for i in 0..1000 {
        let (x, y) = (f64::from(i % 50) * 1.5 - 37.0, 10.0 + f64::from(i / 50) * 1.5);
        let def = match i % 3 {
            0 => BodyDef::circle(s(0.4)),
            1 => BodyDef::polygon(unit),
            _ => BodyDef::polygon(tri),
        };
        w.add_body(def.position(v(x, y)))?;
    }
    Ok(w)
}

pub fn joint_grid(make: MakeWorld) -> Result<World<'static>, arphysics::Error> {
    let n = 100usize;
    let mut w = world(make, n * n + 8, 2 * n * n)?;
    let mut ids = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let mut def =
                BodyDef::circle(s(0.4)).position(v(j as f64 - 50.0, 150.0 - i as f64)).collision_groups(1);
            if i == 0 && (j == 0 || j == n - 1) {
                def = def.static_body();
            }
            ids.push(w.add_body(def)?);
        }
    }
    let pivot = JointKind::Pivot { limits: None, motor: None };
    for i in 0..n {
        for j in 0..n {
            let a = ids[i * n + j];
            if j + 1 < n {
                w.add_joint(JointDef::new(a, v(0.5, 0.0), ids[i * n + j + 1], v(-0.5, 0.0), pivot))?;
            }
            if i + 1 < n {
                w.add_joint(JointDef::new(a, v(0.0, -0.5), ids[(i + 1) * n + j], v(0.0, 0.5), pivot))?;
            }
        }
    }
    Ok(w)
}
