//! Capsules, segments and rounded polygons in a world: mass properties against
//! closed forms, resting and rolling against analytic values, queries, the
//! snapshot, and bad input.

use std::f64::consts::PI;

use arphysics::{
    BodyDef, BodyHandle, Capacities, Capsule, Error, MassSpec, PolygonPath, QueryFilter, QueryShape, Rot,
    Scalar, Segment, Shape, Transform, World,
};

mod common;

use common::{dt, f, s, v};

/// A 400 × 200 m world with gravity (0, −10).
fn world() -> World<'static> {
    common::world_with(200.0, 100.0, Capacities::for_bodies(64), true)
}

/// A static ground segment along y = 0 from x = −50 to 50.
fn ground(w: &mut World<'static>) -> BodyHandle {
    let seg = Segment::new(v(-50.0, 0.0), v(50.0, 0.0)).expect("segment");
    w.add_body(BodyDef::segment(seg)).expect("ground")
}

fn step(w: &mut World<'static>, n: u32) {
    for _ in 0..n {
        w.step(dt()).expect("step");
    }
}

fn capsule(x1: f64, y1: f64, x2: f64, y2: f64, r: f64) -> Capsule {
    Capsule::new(v(x1, y1), v(x2, y2), s(r)).expect("capsule")
}

// ---- mass properties -------------------------------------------------------------

/// Polar moment of inertia of a capsule of density `rho` about its centre:
/// the rectangle plus two half discs moved by the parallel-axis theorem.
fn capsule_inertia(rho: f64, length: f64, r: f64) -> f64 {
    let rect_mass = rho * 2.0 * r * length;
    let rect = rect_mass * (length * length + 4.0 * r * r) / 12.0;
    let half_mass = rho * PI * r * r / 2.0;
    let c = 4.0 * r / (3.0 * PI);
    let half = half_mass * r * r / 2.0 - half_mass * c * c + half_mass * (length / 2.0 + c).powi(2);
    rect + 2.0 * half
}

#[test]
fn a_capsule_body_has_the_closed_form_mass_and_inertia() {
    let mut w = world();
    for (length, r, rho) in [(1.0, 0.25, 2.0), (0.0, 0.5, 1.0), (3.0, 0.1, 5.0), (0.4, 1.2, 0.5)] {
        let c = capsule(-length / 2.0, 0.0, length / 2.0, 0.0, r);
        let h = w.add_body(BodyDef::capsule(c).density(s(rho)).position(v(0.0, 10.0))).expect("body");
        let b = w.body(h).expect("body");
        let mass = rho * (PI * r * r + 2.0 * r * length);
        let inertia = capsule_inertia(rho, length, r);
        assert!((f(b.mass()) - mass).abs() <= 1e-8 * mass.max(1.0), "L {length} r {r}: mass {:?}", b.mass());
        assert!(
            (f(b.inertia()) - inertia).abs() <= 1e-6 * inertia.max(1.0),
            "L {length} r {r}: inertia {} vs {inertia}",
            f(b.inertia())
        );
        w.remove_body(h).expect("remove");
    }
}

#[test]
fn a_zero_length_capsule_weighs_what_the_circle_weighs() {
    let mut w = world();
    let c = w.add_body(BodyDef::circle(s(0.7)).density(s(3.0))).expect("circle");
    let k = w.add_body(BodyDef::capsule(capsule(0.0, 0.0, 0.0, 0.0, 0.7)).density(s(3.0))).expect("capsule");
    let (c, k) = (w.body(c).expect("c"), w.body(k).expect("k"));
    assert!((c.mass() - k.mass()).abs() <= Scalar::from_bits(2), "{:?} {:?}", c.mass(), k.mass());
    assert!((c.inertia() - k.inertia()).abs() <= Scalar::from_bits(4), "{:?} {:?}", c.inertia(), k.inertia());
}

#[test]
fn a_dynamic_segment_is_a_thin_rod_and_refuses_a_density() {
    let mut w = world();
    let seg = Segment::new(v(-1.0, 0.0), v(1.0, 0.0)).expect("segment");
    let h =
        w.add_body(BodyDef::segment(seg).body_type(arphysics::BodyType::Dynamic).mass(s(3.0))).expect("rod");
    // I = m L² / 12 = 3 · 4 / 12.
    assert!((f(w.body(h).expect("rod").inertia()) - 1.0).abs() < 1e-9);
    let hash = w.state_hash();
    let by_density = BodyDef::segment(seg).body_type(arphysics::BodyType::Dynamic).density(s(1.0));
    assert!(matches!(w.add_body(by_density), Err(Error::InvalidOperation { .. })));
    // Made static, then dynamic by density: refused too, the world unchanged.
    let g = ground(&mut w);
    let hash2 = w.state_hash();
    assert!(matches!(w.set_dynamic(g, MassSpec::Density(s(1.0))), Err(Error::InvalidOperation { .. })));
    assert_eq!(w.state_hash(), hash2);
    assert_ne!(hash, hash2);
}

#[test]
fn an_off_centre_capsule_lands_where_the_definition_puts_it() {
    let mut w = world();
    // An upright character capsule, feet at the definition's position.
    let c = capsule(0.0, 0.3, 0.0, 1.5, 0.3);
    let h = w.add_body(BodyDef::capsule(c).position(v(1.0, 2.0))).expect("body");
    let b = w.body(h).expect("body");
    assert_eq!(b.position(), v(1.0, 2.9));
    let Shape::Capsule(stored) = b.shape() else { panic!("not a capsule: {:?}", b.shape()) };
    assert_eq!(stored.center1(), -stored.center2());
    assert_eq!(stored.center2(), v(0.0, 0.6));
    // Rotated by 90°: the offset turns with it.
    let h = w.add_body(BodyDef::capsule(c).position(v(1.0, 2.0)).rotation(Rot { c: s(0.0), s: s(1.0) }));
    assert_eq!(w.body(h.expect("body")).expect("body").position(), v(0.1, 2.0));
}

#[test]
fn a_rounded_rectangle_has_the_area_of_its_outline() {
    let mut w = world();
    let (width, height, r) = (2.0, 1.0, 0.2);
    let path =
        w.add_path(PolygonPath::rounded_rectangle(s(width), s(height), s(r)).expect("path")).expect("add");
    let h = w.add_body(BodyDef::polygon(path).density(s(1.0))).expect("body");
    let area = width * height - (4.0 - PI) * r * r;
    assert!((f(w.body(h).expect("body").mass()) - area).abs() < 1e-7, "{:?}", w.body(h).map(|b| b.mass()));
}

// ---- resting and rolling ----------------------------------------------------------

#[test]
fn a_box_rests_on_a_segment_at_its_half_height() {
    let mut w = world();
    ground(&mut w);
    let path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    let b = w.add_body(BodyDef::polygon(path).position(v(3.0, 0.6))).expect("box");
    step(&mut w, 120);
    let body = w.body(b).expect("box");
    // Resting with the solver's allowed penetration (linear slop 5 mm).
    assert!((f(body.position().y) - 0.5).abs() < 0.006, "y {}", f(body.position().y));
    assert!(f(body.linear_velocity().length()) < 1e-3, "{:?}", body.linear_velocity());
    assert!(f(body.angle()).abs() < 1e-4);
}

#[test]
fn a_rounded_box_rests_on_its_flat_face() {
    let mut w = world();
    ground(&mut w);
    let path =
        w.add_path(PolygonPath::rounded_rectangle(s(1.0), s(0.6), s(0.1)).expect("box")).expect("path");
    let b = w.add_body(BodyDef::polygon(path).position(v(0.0, 0.35))).expect("box");
    step(&mut w, 120);
    let body = w.body(b).expect("box");
    assert!((f(body.position().y) - 0.3).abs() < 0.006, "y {}", f(body.position().y));
    assert!(f(body.angle()).abs() < 1e-4, "angle {}", f(body.angle()));
}

/// Ten horizontal capsules (1 m core, 0.25 m radius) stacked flat on each
/// other stand for 10 s: each stays above the one below with its x within
/// 1 cm and its angle within 0.01 rad, at rest (under 1 mm/s), and each
/// contact's soft-spring overlap stays under 8 mm (the soft contact sinks in
/// in proportion to the weight it carries: 6.0 mm under nine capsules'
/// 63 N at the bottom, 4.0 mm under five; boxes sag the same way).
#[test]
fn a_stack_of_ten_capsules_stands_for_ten_seconds() {
    let mut w = world();
    ground(&mut w);
    let c = capsule(-0.5, 0.0, 0.5, 0.0, 0.25);
    let stack: Vec<BodyHandle> = (0..10)
        .map(|i| {
            w.add_body(BodyDef::capsule(c).position(v(0.0, 0.25 + 0.5 * f64::from(i)))).expect("capsule")
        })
        .collect();
    step(&mut w, 600);
    let mut below = 0.0;
    for (i, h) in stack.iter().enumerate() {
        let b = w.body(*h).expect("capsule");
        let (y, bottom) = (f(b.position().y), f(b.position().y) - 0.25);
        assert!(bottom > below - 0.008 && bottom <= below, "capsule {i}: bottom {bottom}, top below {below}");
        assert!(f(b.position().x).abs() < 0.01, "capsule {i}: x {}", f(b.position().x));
        assert!(f(b.angle()).abs() < 0.01, "capsule {i}: angle {}", f(b.angle()));
        assert!(f(b.linear_velocity().length()) < 1e-3, "capsule {i}: moving {:?}", b.linear_velocity());
        below = y + 0.25;
    }
    assert!(below > 4.9, "the stack stands {below} m tall (5 m unloaded)");
}

/// A disc rolling without slipping down a 30° segment ramp accelerates at
/// (2/3)·g·sin θ: after 1 s it has rolled (1/2)·a·t² = 1.667 m along the ramp.
#[test]
fn a_disc_rolls_down_a_segment_ramp_at_two_thirds_g_sin_theta() {
    let mut w = world();
    let theta = PI / 6.0;
    let (c, sn) = (theta.cos(), theta.sin());
    let seg = Segment::new(v(-20.0 * c, 20.0 * sn), v(20.0 * c, -20.0 * sn)).expect("ramp");
    w.add_body(BodyDef::segment(seg).friction(s(1.0))).expect("ramp");
    // Centre at one radius along the ramp's up normal (sin θ, cos θ) from the
    // point 10 m up the slope.
    let r = 0.5;
    let (px, py) = (-10.0 * c + r * sn, 10.0 * sn + r * c);
    let ball = w.add_body(BodyDef::circle(s(r)).friction(s(1.0)).position(v(px, py))).expect("ball");
    step(&mut w, 60);
    let p = w.body(ball).expect("ball").position();
    let along = (f(p.x) - px) * c - (f(p.y) - py) * sn;
    let expected = 0.5 * (2.0 / 3.0) * 10.0 * sn;
    assert!((along - expected).abs() < 0.02 * expected, "rolled {along} m, expected {expected}");
}

/// A capsule lying on a box has a two-point contact with equal impulses
/// (symmetric about its centre) within 1 %.
#[test]
fn a_capsule_lying_on_a_box_has_two_equal_contact_points() {
    let mut w = world();
    let path = w.add_path(PolygonPath::rectangle(s(4.0), s(1.0)).expect("box")).expect("path");
    w.add_body(BodyDef::polygon(path).static_body().position(v(0.0, 0.5))).expect("table");
    w.add_body(BodyDef::capsule(capsule(-0.5, 0.0, 0.5, 0.0, 0.25)).position(v(0.0, 1.26))).expect("capsule");
    step(&mut w, 120);
    let arb = w.arbiters().find(|a| a.contact_points().len() == 2).expect("a two-point contact");
    let (p, q) = (arb.contact_points()[0].normal_impulse, arb.contact_points()[1].normal_impulse);
    let (p, q) = (f(p), f(q));
    assert!(p > 0.0 && (p - q).abs() <= 0.01 * p.max(q), "impulses {p} {q}");
}

#[test]
fn segments_do_not_collide_with_segments() {
    let mut w = world();
    ground(&mut w);
    let rod = Segment::new(v(-1.0, 0.0), v(1.0, 0.0)).expect("rod");
    let h = w
        .add_body(
            BodyDef::segment(rod).body_type(arphysics::BodyType::Dynamic).mass(s(1.0)).position(v(0.0, 1.0)),
        )
        .expect("rod");
    step(&mut w, 60);
    // Free fall through the ground segment: y = 1 − g t²/2 (sub-stepped
    // Euler falls a little further).
    let y = f(w.body(h).expect("rod").position().y);
    assert!(y < -3.5, "the rod stopped at {y}");
    assert_eq!(w.arbiters().count(), 0);
}

// ---- queries ------------------------------------------------------------------------

#[test]
fn rays_and_points_find_capsules_and_segments() {
    let mut w = world();
    let g = ground(&mut w);
    let k =
        w.add_body(BodyDef::capsule(capsule(-1.0, 0.0, 1.0, 0.0, 0.5)).position(v(10.0, 5.0))).expect("k");
    // A ray along y = 5 from the left enters the capsule's cap at x = 8.5.
    let hit = w.ray_cast(v(0.0, 5.0), v(20.0, 5.0), QueryFilter::default()).expect("ray").expect("a hit");
    assert_eq!(hit.body, k);
    assert!((f(hit.point.x) - 8.5).abs() < 1e-6, "{:?}", hit.point);
    assert!((f(hit.normal.x) + 1.0).abs() < 1e-6, "{:?}", hit.normal);
    // Straight down onto its flat side at x = 10.7: enters at y = 5.5.
    let hit = w.ray_cast(v(10.7, 9.0), v(10.7, 1.0), QueryFilter::default()).expect("ray").expect("a hit");
    assert!((f(hit.point.y) - 5.5).abs() < 1e-6 && f(hit.normal.y) > 0.999, "{hit:?}");
    // The ground segment is hit from above and from below.
    let down = w.ray_cast(v(-5.0, 3.0), v(-5.0, -3.0), QueryFilter::default()).expect("ray").expect("hit");
    let up = w.ray_cast(v(-5.0, -3.0), v(-5.0, 3.0), QueryFilter::default()).expect("ray").expect("hit");
    assert_eq!((down.body, up.body), (g, g));
    assert!(f(down.normal.y) > 0.999 && f(up.normal.y) < -0.999, "{down:?} {up:?}");
    assert!((f(down.fraction) - 0.5).abs() < 1e-6);
    let mut out = [BodyHandle::NULL; 4];
    assert_eq!(w.query_point(v(11.2, 5.3), QueryFilter::default(), &mut out), 1);
    assert_eq!(out[0], k);
    assert_eq!(w.query_point(v(11.4, 5.4), QueryFilter::default(), &mut out), 0);
    // A capsule-shaped query over the ground finds it; a segment query
    // crossing the capsule finds it.
    let probe = QueryShape::Capsule(capsule(-1.0, 0.0, 1.0, 0.0, 0.2));
    let n =
        w.query_shape(probe, Transform::new(v(0.0, 0.1), Rot::IDENTITY), QueryFilter::default(), &mut out);
    assert_eq!((n.expect("query"), out[0]), (1, g));
    let probe = QueryShape::Segment(Segment::new(v(0.0, -1.0), v(0.0, 1.0)).expect("segment"));
    let n =
        w.query_shape(probe, Transform::new(v(10.0, 5.0), Rot::IDENTITY), QueryFilter::default(), &mut out);
    assert_eq!((n.expect("query"), out[0]), (1, k));
}

// ---- snapshot ------------------------------------------------------------------------

#[test]
fn restore_then_step_equals_stepping_on_with_every_shape() {
    let mut w = world();
    ground(&mut w);
    let rounded = w.add_path(PolygonPath::rounded_rectangle(s(0.8), s(0.5), s(0.1)).expect("p")).expect("p");
    for i in 0..8 {
        let x = f64::from(i) * 1.3 - 5.0;
        let def = match i % 3 {
            0 => BodyDef::capsule(capsule(-0.3, 0.1, 0.3, -0.1, 0.2)),
            1 => BodyDef::polygon(rounded),
            _ => BodyDef::circle(s(0.3)),
        };
        w.add_body(def.position(v(x, 2.0 + f64::from(i % 2))).angular_velocity(s(1.0))).expect("body");
    }
    step(&mut w, 30);
    let mut snap = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut snap).expect("snapshot");
    step(&mut w, 60);
    let on = w.state_hash();
    w.restore(&snap).expect("restore");
    step(&mut w, 60);
    assert_eq!(w.state_hash(), on);
}

// ---- bad input ------------------------------------------------------------------------

#[test]
fn bad_shapes_are_clear_errors() {
    let p = v(1.0, 1.0);
    assert_eq!(Segment::new(p, p), Err(Error::OutOfRange { what: "segment length" }));
    assert_eq!(Capsule::new(p, v(2.0, 1.0), s(-0.1)), Err(Error::OutOfRange { what: "capsule radius" }));
    assert_eq!(Capsule::new(p, v(2.0, 1.0), s(0.0)), Err(Error::OutOfRange { what: "capsule radius" }));
    assert_eq!(
        PolygonPath::rounded_rectangle(s(1.0), s(1.0), s(0.6)),
        Err(Error::OutOfRange { what: "rounding radius" })
    );
    assert_eq!(
        PolygonPath::rounded(&[v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)], s(-0.1)),
        Err(Error::OutOfRange { what: "rounding radius" })
    );
    // A rounding larger than the triangle's inradius (0.293 m) allows.
    assert_eq!(
        PolygonPath::rounded(&[v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)], s(0.3)),
        Err(Error::OutOfRange { what: "rounding radius" })
    );
    assert_eq!(Segment::new(v(0.0, 0.0), v(300.0, 0.0)), Err(Error::OutOfRange { what: "segment size" }));
    assert_eq!(
        Capsule::new(v(0.0, 0.0), v(200.0, 0.0), s(40.0)),
        Err(Error::OutOfRange { what: "capsule size" })
    );
}

// ---- shape casts ----------------------------------------------------------------------

/// A circle, a capsule and a box cast down onto the ground segment stop at
/// their half heights above it: fraction (5 − h) / 10, normal up.
#[test]
fn shapes_cast_onto_a_segment_stop_where_they_touch() {
    let mut w = world();
    let g = ground(&mut w);
    let square = PolygonPath::rectangle(s(1.0), s(1.0)).expect("box");
    let cases = [
        (QueryShape::Circle(s(0.5)), 0.5),
        (QueryShape::Capsule(capsule(-0.6, 0.0, 0.6, 0.0, 0.3)), 0.3),
        (QueryShape::Capsule(capsule(0.0, -0.6, 0.0, 0.6, 0.3)), 0.9),
        (QueryShape::Polygon(&square), 0.5),
    ];
    for (shape, h) in cases {
        let xf = Transform::new(v(2.0, 5.0), Rot::IDENTITY);
        let hit =
            w.shape_cast(shape, xf, v(0.0, -10.0), QueryFilter::default()).expect("cast").expect("a hit");
        let expected = (5.0 - h) / 10.0;
        assert_eq!(hit.body, g);
        assert!(
            (f(hit.fraction) - expected).abs() < 1e-4,
            "{shape:?}: fraction {} vs {expected}",
            f(hit.fraction)
        );
        assert!(f(hit.normal.y) > 0.999, "{shape:?}: normal {:?}", hit.normal);
        assert!(f(hit.point.y).abs() < 0.011, "{shape:?}: point {:?}", hit.point);
    }
    // Cast sideways, parallel to the ground: no hit.
    let xf = Transform::new(v(2.0, 5.0), Rot::IDENTITY);
    let miss = w.shape_cast(QueryShape::Circle(s(0.5)), xf, v(10.0, 0.0), QueryFilter::default());
    assert_eq!(miss, Ok(None));
    // Starting in contact: fraction 0.
    let xf = Transform::new(v(2.0, 0.2), Rot::IDENTITY);
    let hit = w.shape_cast(QueryShape::Circle(s(0.5)), xf, v(0.0, -1.0), QueryFilter::default());
    assert_eq!(hit.expect("cast").map(|h| h.fraction), Some(Scalar::ZERO));
}

/// A capsule cast sideways into a wall of boxes stops at the nearest one.
#[test]
fn a_capsule_cast_stops_at_the_nearest_wall() {
    let mut w = world();
    let path = w.add_path(PolygonPath::rectangle(s(1.0), s(4.0)).expect("wall")).expect("path");
    let near = w.add_body(BodyDef::polygon(path).static_body().position(v(6.0, 2.0))).expect("near");
    w.add_body(BodyDef::polygon(path).static_body().position(v(9.0, 2.0))).expect("far");
    let c = capsule(0.0, -0.5, 0.0, 0.5, 0.4);
    let xf = Transform::new(v(0.0, 2.0), Rot::IDENTITY);
    let hit = w.shape_cast(QueryShape::Capsule(c), xf, v(20.0, 0.0), QueryFilter::default()).expect("cast");
    let hit = hit.expect("a hit");
    // Touches when its right side (x + 0.4) reaches the wall's face at 5.5.
    assert_eq!(hit.body, near);
    assert!((f(hit.fraction) - 5.1 / 20.0).abs() < 1e-4, "fraction {}", f(hit.fraction));
    assert!(f(hit.normal.x) < -0.999, "normal {:?}", hit.normal);
    // Excluding it, the far wall.
    let hit = w.shape_cast(QueryShape::Capsule(c), xf, v(20.0, 0.0), QueryFilter::default().exclude(near));
    assert!((f(hit.expect("cast").expect("hit").fraction) - 8.1 / 20.0).abs() < 1e-4);
}

// ---- continuous collision ------------------------------------------------------------

/// A capsule and a ball shot at 300 m/s at a thin ground segment (5 m a
/// step, far more than their size) stop on it: continuous collision sweeps
/// every shape.
#[test]
fn fast_capsules_and_balls_do_not_tunnel_through_a_segment() {
    let mut w = world();
    ground(&mut w);
    let k = w
        .add_body(
            BodyDef::capsule(capsule(-0.4, 0.0, 0.4, 0.0, 0.1))
                .position(v(-3.0, 40.0))
                .linear_velocity(v(0.0, -300.0)),
        )
        .expect("capsule");
    let b = w
        .add_body(BodyDef::circle(s(0.1)).position(v(3.0, 40.0)).linear_velocity(v(0.0, -300.0)))
        .expect("b");
    step(&mut w, 120);
    for h in [k, b] {
        let y = f(w.body(h).expect("body").position().y);
        assert!(y > 0.0 && y < 0.2, "{h:?} ended at y = {y}");
    }
}
