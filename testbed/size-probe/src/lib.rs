//! The engine as a wasm module with every feature used once (each shape kind,
//! a chain, every joint kind but the rope and plain spring, a sensor-free
//! world with gravity, stepping, snapshot and restore, the state hash, a ray
//! cast and a shape cast), and nothing else: `scripts/testbed.sh` builds it
//! to report the engine's own share of the testbed module (issue 20's size
//! aim is for the engine). It exports one function; nothing calls it.
#![deny(unsafe_code)]

use arphysics::{
    BodyDef, Capacities, Capsule, ChainPath, Error, GravityForceGenerator, JointDef, JointKind, PolygonPath,
    QueryFilter, QueryShape, Rect, Scalar, Segment, Transform, Vector2, World, WorldDef,
};

fn s(x: i32) -> Scalar {
    Scalar::from_int(x)
}

fn v(x: i32, y: i32) -> Vector2 {
    Vector2::from_int(x, y)
}

fn exercise() -> Result<u64, Error> {
    let bounds = Rect::from_corners(v(-100, -100), v(100, 100));
    let caps = Capacities { chain_vertices: 64, ..Capacities::for_bodies(64) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps)?;
    w.add_force_generator(GravityForceGenerator::new(v(0, -10)))?;
    let hills = [v(-50, 0), v(-10, -2), v(10, -2), v(50, 0)];
    let chain = w.add_chain(ChainPath::open(&hills)?)?;
    w.add_body(BodyDef::chain(chain))?;
    let square = w.add_path(PolygonPath::rectangle(s(1), s(1))?)?;
    let a = w.add_body(BodyDef::circle(Scalar::HALF).position(v(0, 5)))?;
    let b = w.add_body(BodyDef::polygon(square).position(v(2, 5)))?;
    let c = w.add_body(BodyDef::capsule(Capsule::new(v(0, 0), v(1, 0), Scalar::HALF)?).position(v(4, 5)))?;
    w.add_body(BodyDef::segment(Segment::new(v(-5, 1), v(5, 1))?))?;
    let zero = Vector2::ZERO;
    w.add_joint(JointDef::new(a, zero, b, zero, JointKind::Rod { length: s(2) }))?;
    w.add_joint(JointDef::new(b, zero, c, zero, JointKind::Pivot { limits: None, motor: None }))?;
    w.add_joint(JointDef::new(a, zero, c, zero, JointKind::Weld))?;
    let spring = JointKind::DampedSpring { stiffness: s(10), damping: s(1), rest_length: s(1) };
    w.add_joint(JointDef::new(a, zero, c, zero, spring))?;
    let pull = JointKind::Target { hertz: s(5), damping_ratio: s(1), max_force: s(1000) };
    let target = w.add_joint(JointDef::to_world(a, zero, v(0, 8), pull))?;
    let mut buf = [0u8; 65536];
    let n = w.snapshot(&mut buf)?;
    for k in 0..60 {
        w.set_joint_target(target, v(k / 10, 8))?;
        w.step(Scalar::ONE / 60)?;
    }
    w.restore(buf.get(..n).unwrap_or(&[]))?;
    w.step(Scalar::ONE / 60)?;
    let ray = w.ray_cast(v(0, 20), v(0, -20), QueryFilter::default())?;
    let ball = QueryShape::Circle(Scalar::HALF);
    let cast = w.shape_cast(ball, Transform::default(), v(0, -20), QueryFilter::default())?;
    Ok(w.state_hash() ^ u64::from(ray.is_some()) ^ u64::from(cast.is_some()))
}

/// Runs [`exercise`]; 0 on an error.
// `no_mangle` counts as unsafe code (two libraries exporting one name would
// clash at link time); this module links nothing else that exports `run`.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn run() -> u64 {
    exercise().unwrap_or(0)
}
