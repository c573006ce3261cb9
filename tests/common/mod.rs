//! Helpers shared by the test files that build worlds from `f64` figures
//! (`mod common;` in each; a file uses what it needs).
#![allow(dead_code)]

use arphysics::{Capacities, GravityForceGenerator, Rect, Scalar, Vector2, World, WorldDef};

/// `x` in fixed point.
pub fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

/// `(x, y)` in fixed point.
pub fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// `x` as `f64`, to compare with closed forms.
pub fn f(x: Scalar) -> f64 {
    x.to_num()
}

/// A 1/60 s step.
pub fn dt() -> Scalar {
    Scalar::ONE / Scalar::from_num(60)
}

/// A world from (−`hx`, −`hy`) to (`hx`, `hy`) m with `caps`, and gravity (0, −10)
/// if `gravity`.
pub fn world_with(hx: f64, hy: f64, caps: Capacities, gravity: bool) -> World<'static> {
    let bounds = Rect::from_corners(v(-hx, -hy), v(hx, hy));
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    if gravity {
        w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    }
    w
}
