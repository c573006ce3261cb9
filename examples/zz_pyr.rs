use arphysics::*;
use std::time::Instant;
fn main() {
    let s = Scalar::from_num::<f64>;
    let rows = 20;
    let mut w = World::with_capacities(
        WorldDef::with_bounds(Rect::from_corners(Vector2::from_int(-200, -100), Vector2::from_int(200, 300))),
        Capacities::for_bodies(300),
    )
    .unwrap();
    let ground = w.add_path(PolygonPath::rectangle(s(100.0), s(2.0)).unwrap()).unwrap();
    w.add_body(BodyDef::polygon(ground).position(Vector2::new(s(0.0), s(-1.0))).static_body()).unwrap();
    let bp = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).unwrap()).unwrap();
    let mut top = None;
    for i in 0..rows {
        for j in 0..(rows - i) {
            let x = (j as f64) - (rows - i) as f64 * 0.5 + 0.5;
            let y = 0.5 + i as f64;
            top = Some(w.add_body(BodyDef::polygon(bp).position(Vector2::new(s(x), s(y)))).unwrap());
        }
    }
    w.add_force_generator(GravityForceGenerator::new(Vector2::new(s(0.0), s(-10.0)))).unwrap();
    let t0 = Instant::now();
    for _ in 0..600 {
        w.step(s(1.0 / 60.0)).unwrap();
    }
    let el = t0.elapsed();
    let tb = w.body(top.unwrap()).unwrap();
    let maxv = w.bodies().map(|(_, b)| b.linear_velocity().length().to_num::<f64>()).fold(0.0, f64::max);
    println!(
        "{:.3} ms/step; top {:?} (start y {}) ; max speed {maxv:.4}; arbiters {}",
        el.as_secs_f64() * 1000.0 / 600.0,
        tb.position().to_f64(),
        rows as f64 - 0.5,
        w.arbiters().count()
    );
}
