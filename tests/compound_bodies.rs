//! Compound bodies (issue 19, part 2): several shapes on one body, each with
//! its own offset, material, filter and sensor flag; the body's mass data
//! from all of them; arbiters, events, queries and continuous collision per
//! shape.

mod common;

use arphysics::geometry::{compound_mass, MassPart};
use arphysics::{
    BodyDef, BodyHandle, Capacities, Capsule, ChainPath, CollisionFilter, Error, PolygonPath, Rot, ShapeDef,
    Vector2, World, MAX_SHAPES_PER_BODY,
};
use common::{dt, f, s, v, world_with};

fn caps() -> Capacities {
    Capacities { shapes: 32, chain_vertices: 16, ..Capacities::for_bodies(32) }
}

/// An L of two 2 m × 0.2 m arms meeting at a corner (arm A along the body's
/// x axis from the corner, arm B along its y axis), the corner at `corner`,
/// the body turned by `angle`. Returns the body.
fn add_l(w: &mut World<'_>, corner: Vector2, angle: f64) -> BodyHandle {
    let arm_a = w.add_path(PolygonPath::rectangle(s(2.0), s(0.2)).expect("box")).expect("room");
    let arm_b = w.add_path(PolygonPath::rectangle(s(0.2), s(2.0)).expect("box")).expect("room");
    let q = Rot::from_angle(s(angle));
    // Arm A's centre is 1 m along x from the corner; arm B's 1 m along y, i.e.
    // (−1, 1) from arm A's centre.
    let l = w
        .add_body(
            BodyDef::polygon(arm_a).position(corner + q.rotate(v(1.0, 0.0))).rotation(q).friction(s(0.8)),
        )
        .expect("arm a");
    w.add_shape(l, ShapeDef::polygon(arm_b).offset(v(-1.0, 1.0)).friction(s(0.8))).expect("arm b");
    l
}

/// The closed-form mass data of that L at density 1: two 0.4 kg arms, their
/// centres at (1, 0) and (0, 1) from the corner.
fn l_closed_form() -> (f64, (f64, f64), f64) {
    let m = 0.4;
    let own = m * (2.0f64 * 2.0 + 0.2 * 0.2) / 12.0;
    let c = (0.5, 0.5);
    let d2 = 0.5f64 * 0.5 + 0.5 * 0.5;
    (2.0 * m, c, 2.0 * (own + m * d2))
}

#[test]
fn an_l_has_the_mass_of_its_two_arms_about_their_common_centre_and_nothing_moves() {
    let mut w = world_with(50.0, 50.0, caps(), false);
    let corner = v(3.0, 4.0);
    let l = add_l(&mut w, corner, 0.0);
    let b = w.body(l).expect("live");
    let (m, c, i) = l_closed_form();
    assert!((f(b.mass()) - m).abs() < 1e-8, "mass {}", f(b.mass()));
    assert!((f(b.inertia()) - i).abs() < 1e-8, "inertia {} vs {i}", f(b.inertia()));
    let p = b.position();
    assert!((f(p.x) - 3.0 - c.0).abs() < 1e-9 && (f(p.y) - 4.0 - c.1).abs() < 1e-9, "centre {p:?}");
    assert_eq!(b.shape_count(), 2);
    // The arms stay where they were put: arm A's centre at corner + (1, 0).
    let a = w.shape(l, 0).expect("arm a");
    let world_a = p + a.local.p;
    assert_eq!(world_a, corner + v(1.0, 0.0), "arm A did not move (exact at rotation 0)");
    let bshape = w.shape(l, 1).expect("arm b");
    assert_eq!(p + bshape.local.p, corner + v(0.0, 1.0));
    // The same figure from the parts.
    let parts = [
        MassPart { mass: a.mass, centre: a.local.p, inertia: a.inertia },
        MassPart { mass: bshape.mass, centre: bshape.local.p, inertia: bshape.inertia },
    ];
    let (md, centre) = compound_mass(&parts).expect("in range");
    assert_eq!(md.inertia, b.inertia());
    assert!(f(centre.x).abs() < 1e-9 && f(centre.y).abs() < 1e-9, "the parts are about the centre");
}

/// The L turned so that its corner is on top and its arms go down at ±45°
/// stands on the ends of its two arms. Statics fix the two normal forces:
/// the feet are the same distance either side of the centre of mass, so the
/// moments balance only with equal forces (friction acts at the feet's
/// height, its moments cancel). The solver's impulses agree within 1 %, and
/// sum to m·g·dt.
#[test]
fn an_l_standing_on_its_two_feet_has_equal_contact_impulses() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("box")).expect("room");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body().friction(s(0.8)))
        .expect("ground");
    // Arms along −135° and −45°: each foot's lowest corner is 2.1·√2/2 below the corner.
    let l = add_l(&mut w, v(0.0, 1.5), -135f64.to_radians());
    for _ in 0..180 {
        w.step(dt()).expect("step");
    }
    let b = w.body(l).expect("live");
    assert!(f(b.linear_velocity().length()) < 1e-3, "at rest: {:?}", b.linear_velocity());
    let mut per_shape = [0.0f64; 2];
    for arb in w.arbiters().filter(|a| !a.contact_points().is_empty()) {
        let (shape, on_l) =
            if arb.body_a() == l { (arb.shape_a(), true) } else { (arb.shape_b(), arb.body_b() == l) };
        assert!(on_l, "only the L touches the ground");
        let total: f64 = arb.contact_points().iter().map(|p| f(p.total_normal_impulse)).sum();
        per_shape[shape as usize] += total;
    }
    let mg_dt = f(b.mass()) * 10.0 * f(dt());
    let (i0, i1) = (per_shape[0], per_shape[1]);
    assert!(i0 > 0.0 && i1 > 0.0, "both feet carry weight: {per_shape:?}");
    assert!((i0 - i1).abs() / (0.5 * (i0 + i1)) < 0.01, "feet {i0} and {i1} differ by more than 1 %");
    assert!(((i0 + i1) - mg_dt).abs() / mg_dt < 0.01, "sum {} vs m·g·dt {mg_dt}", i0 + i1);
}

/// An impulse off the centre of a free L (no gravity) gives it the angular
/// momentum r × J about its centre of mass, and spinning keeps it (within
/// 1e-6 relative) for 10 s; the centre moves with the linear momentum J.
#[test]
fn a_spinning_l_conserves_angular_momentum() {
    let mut w = world_with(200.0, 200.0, caps(), false);
    let corner = v(0.0, 0.0);
    let l = add_l(&mut w, corner, 0.0);
    let (m, c, i) = l_closed_form();
    let hit = v(2.0, 0.1); // arm A's tip
    let j = v(0.0, 0.5);
    w.body_mut(l).expect("live").apply_impulse_at(j, hit);
    let r = (2.0 - c.0, 0.1 - c.1);
    let expected = r.0 * 0.5 - r.1 * 0.0;
    let b = w.body(l).expect("live");
    let momentum = f(b.inertia()) * f(b.angular_velocity());
    assert!((momentum - expected).abs() / expected < 1e-6, "I·ω = {momentum} vs r×J = {expected}");
    assert!((f(b.inertia()) - i).abs() < 1e-8);
    let p0 = b.position();
    for _ in 0..600 {
        w.step(dt()).expect("step");
    }
    let b = w.body(l).expect("live");
    let after = f(b.inertia()) * f(b.angular_velocity());
    assert!((after - expected).abs() / expected < 1e-6, "after 10 s: {after} vs {expected}");
    let moved = b.position() - p0;
    assert!(
        (f(moved.y) - 10.0 * 0.5 / m).abs() < 1e-3 && f(moved.x).abs() < 1e-6,
        "the centre moved {moved:?}"
    );
}

/// Each shape has its own material and filter, and contacts and events name
/// the shape: a ball dropped on arm B of a lying L touches shape 1.
#[test]
fn contacts_and_events_name_the_shape_they_touch() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("box")).expect("room");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    // A "⊥"-ish L lying on arm A, arm B pointing up at x = 0.
    let l = add_l(&mut w, v(0.0, 0.1), 0.0);
    let ball = w.add_body(BodyDef::circle(s(0.25)).position(v(0.0, 3.0))).expect("ball");
    let mut seen_b = false;
    for _ in 0..120 {
        w.step(dt()).expect("step");
        for e in w.contact_begin_events() {
            if e.body_a == ball || e.body_b == ball {
                let shape_on_l = if e.body_a == l { e.shape_a } else { e.shape_b };
                assert_eq!(shape_on_l, 1, "the ball lands on arm B");
                seen_b = true;
            }
        }
    }
    assert!(seen_b, "the ball touched the L");
    let top = f(w.body(ball).expect("live").position().y);
    assert!((top - (0.1 + 2.0 + 0.25)).abs() < 0.02, "the ball rests on arm B's top: {top}");
}

/// A sensor shape on a solid body (a character's ground probe) reports its
/// overlap and never pushes; a filtered-out shape does not collide while the
/// body's other shape does.
#[test]
fn sensor_and_filtered_shapes_on_a_solid_body() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("box")).expect("room");
    let g = w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    let body = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("room");
    let c = w.add_body(BodyDef::polygon(body).position(v(0.0, 2.0))).expect("character");
    // A probe circle below the feet, and a wide "shield" that ignores the ground.
    let probe = w.add_shape(c, ShapeDef::circle(s(0.2)).offset(v(0.0, -0.6)).sensor()).expect("probe");
    let no_ground = CollisionFilter { category_bits: 2, mask_bits: !1, group_index: 0 };
    w.add_shape(c, ShapeDef::circle(s(0.4)).offset(v(0.0, -0.3)).filter(no_ground)).expect("shield");
    let mut probe_began = false;
    for _ in 0..120 {
        w.step(dt()).expect("step");
        for e in w.sensor_begin_events() {
            assert_eq!((e.sensor, e.sensor_shape, e.visitor), (c, probe as u8, g));
            probe_began = true;
        }
    }
    assert!(probe_began, "the probe saw the ground");
    // The box stands on its face: the probe and the shield pass into the ground.
    let b = w.body(c).expect("live");
    let base = w.shape(c, 0).expect("box").local.p;
    let bottom = f(b.position().y + base.y) - 0.5;
    assert!(bottom.abs() < 0.02, "the box's face rests on the ground: {bottom}");
}

/// Removing a shape: its contacts end, the others carry on under their new
/// index, the mass and centre come back to the remaining shapes'.
#[test]
fn removing_a_shape_recomputes_the_mass_and_ends_its_contacts() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("box")).expect("room");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    let sq = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("room");
    let b = w.add_body(BodyDef::polygon(sq).position(v(0.0, 0.5))).expect("box");
    let one = *w.body(b).expect("live");
    let wheel = w.add_shape(b, ShapeDef::circle(s(0.5)).offset(v(3.0, 0.0)).density(s(2.0))).expect("wheel");
    assert_eq!(wheel, 1);
    let tail = w.add_shape(b, ShapeDef::circle(s(0.5)).offset(v(-3.0, 0.0))).expect("tail");
    assert_eq!(tail, 2);
    for _ in 0..60 {
        w.step(dt()).expect("step");
    }
    let touching = |w: &World<'_>| -> Vec<u32> {
        let mut v: Vec<u32> = w
            .arbiters()
            .filter(|a| !a.contact_points().is_empty())
            .map(|a| if a.body_a() == b { a.shape_a() } else { a.shape_b() })
            .collect();
        v.sort_unstable();
        v
    };
    assert_eq!(touching(&w), vec![0, 1, 2], "all three shapes rest on the ground");
    let removed = w.remove_shape(b, 1).expect("the wheel");
    assert_eq!(removed.shape, arphysics::Shape::Circle { radius: s(0.5) });
    assert_eq!(touching(&w), vec![0, 1], "the tail is shape 1 now; the wheel's contact ended");
    let after = w.body(b).expect("live");
    assert_eq!(after.shape_count(), 2);
    let expected = f(one.mass()) + std::f64::consts::PI * 0.25;
    assert!((f(after.mass()) - expected).abs() < 1e-6, "mass {} vs {expected}", f(after.mass()));
    for _ in 0..60 {
        w.step(dt()).expect("step");
    }
    assert_eq!(touching(&w), vec![0, 1]);
}

/// A compound body falls onto a chain and rests on it with both shapes.
#[test]
fn a_compound_body_rests_on_a_chain() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let points: Vec<Vector2> = (0..=8).rev().map(|i| v(f64::from(i) - 4.0, 0.0)).collect();
    let chain = w.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain)).expect("ground");
    let cap = Capsule::new(v(-0.5, 0.0), v(0.5, 0.0), s(0.2)).expect("capsule");
    let b = w.add_body(BodyDef::capsule(cap).position(v(-1.5, 2.0))).expect("body");
    w.add_shape(b, ShapeDef::circle(s(0.3)).offset(v(2.0, 0.1))).expect("wheel");
    for _ in 0..240 {
        w.step(dt()).expect("step");
    }
    let body = w.body(b).expect("live");
    assert!(f(body.linear_velocity().length()) < 1e-2, "at rest");
    let low: Vec<f64> = w
        .shapes(b)
        .expect("live")
        .map(|(_, sh)| {
            let c = body.position() + body.rotation().rotate(sh.local.p);
            match sh.shape {
                arphysics::Shape::Circle { radius } => f(c.y - radius),
                arphysics::Shape::Capsule(k) => f(c.y - k.radius()),
                _ => f64::NAN,
            }
        })
        .collect();
    for y in low {
        assert!(y.abs() < 0.02 && y > -0.02, "each shape rests on the chain: {y}");
    }
}

/// Bad input is a clear error and leaves the world unchanged.
#[test]
fn bad_shapes_are_errors_and_change_nothing() {
    let mut w = world_with(50.0, 50.0, Capacities { shapes: 10, ..caps() }, true);
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 5.0))).expect("body");
    let hash = w.state_hash();
    let bad = [
        (ShapeDef::circle(s(-1.0)), "radius"),
        (ShapeDef::circle(s(0.1)).friction(s(-1.0)), "friction"),
        (ShapeDef::circle(s(0.1)).density(s(0.0)), "density"),
        (ShapeDef::circle(s(0.1)).offset(v(500.0, 0.0)), "compound size"),
    ];
    for (def, what) in bad {
        assert_eq!(w.add_shape(b, def), Err(Error::OutOfRange { what }), "{what}");
        assert_eq!(w.state_hash(), hash, "{what}: the world is unchanged");
    }
    let chain = w.add_chain(ChainPath::open(&[v(-9.0, 0.0), v(9.0, 0.0)]).expect("path")).expect("room");
    let ground = w.add_body(BodyDef::chain(chain)).expect("ground");
    let no_chain = Err(Error::InvalidOperation { what: "a chain is a body of its own: no shapes beside it" });
    assert_eq!(w.add_shape(ground, ShapeDef::circle(s(0.1))), no_chain);
    assert_eq!(w.add_shape(b, ShapeDef::new(arphysics::Shape::Chain(chain))), no_chain);
    // The shape store holds 10: a body of 8 shapes, then the next is refused.
    for k in 1..MAX_SHAPES_PER_BODY {
        w.add_shape(b, ShapeDef::circle(s(0.1)).offset(v(k as f64 * 0.2, 0.0))).expect("room");
    }
    let hash = w.state_hash();
    let ninth = w.add_shape(b, ShapeDef::circle(s(0.1)));
    assert_eq!(ninth, Err(Error::CapacityFull { what: "shape per body" }));
    let other = w.add_body(BodyDef::circle(s(0.5)).position(v(5.0, 5.0))).expect("body");
    let hash2 = w.state_hash();
    assert_ne!(hash, hash2);
    // Two slots left: a second compound body takes both (its first shape moves too)...
    w.add_shape(other, ShapeDef::circle(s(0.1)).offset(v(1.0, 0.0))).expect("room for two");
    let hash3 = w.state_hash();
    let full = w.add_shape(other, ShapeDef::circle(s(0.1)).offset(v(-1.0, 0.0)));
    assert_eq!(full, Err(Error::CapacityFull { what: "shape" }));
    assert_eq!(w.state_hash(), hash3, "unchanged after a full store");
    assert_eq!(w.remove_shape(other, 2), Err(Error::OutOfRange { what: "shape index" }));
    w.remove_shape(other, 1).expect("the added shape");
    assert!(matches!(w.remove_shape(other, 0), Err(Error::InvalidOperation { .. })), "the last shape stays");
    w.remove_body(other).expect("live");
    assert_eq!(w.add_shape(other, ShapeDef::circle(s(0.1))), Err(Error::StaleHandle));
}

/// Per-shape material after creation: friction of one shape changes the
/// friction of that shape's contacts only; a denser shape pulls the centre of
/// mass towards itself by the closed form.
#[test]
fn shape_material_and_density_can_change_after_creation() {
    let mut w = world_with(50.0, 50.0, caps(), true);
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("box")).expect("room");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body().friction(s(0.5)))
        .expect("ground");
    let sq = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("room");
    let b = w.add_body(BodyDef::polygon(sq).position(v(0.0, 0.5)).friction(s(0.5))).expect("box");
    w.add_shape(b, ShapeDef::polygon(sq).offset(v(2.0, 0.0)).friction(s(0.5))).expect("second box");
    // Two equal unit boxes 2 m apart: the centre is midway.
    let x0 = f(w.body(b).expect("live").position().x);
    assert!((x0 - 1.0).abs() < 1e-9, "centre {x0}");
    w.set_shape_friction(b, 1, s(0.0)).expect("shape 1");
    for _ in 0..30 {
        w.step(dt()).expect("step");
    }
    for arb in w.arbiters().filter(|a| !a.contact_points().is_empty()) {
        let shape = if arb.body_a() == b { arb.shape_a() } else { arb.shape_b() };
        // √(0.5 · μ) as Box2D mixes friction: 0.5 for shape 0, 0 for shape 1.
        let expected = if shape == 1 { 0.0 } else { 0.5 };
        assert!((f(arb.friction()) - expected).abs() < 1e-6, "shape {shape}: {}", f(arb.friction()));
    }
    assert_eq!(w.shape(b, 1).map(|s| s.friction), Ok(s(0.0)));
    assert_eq!(w.body(b).map(|b| b.friction()), Ok(s(0.5)), "shape 0's friction is the body's");
    // Shape 1 three times as dense: the centre moves to 3/4 of the way, the
    // mass to 4 kg. (The shapes stay where they are.)
    let before = w.body(b).expect("live").position();
    let right = before + w.shape(b, 1).expect("shape 1").local.p;
    w.set_shape_density(b, 1, s(3.0)).expect("denser");
    let body = w.body(b).expect("live");
    assert!((f(body.mass()) - 4.0).abs() < 1e-6);
    let offset = f(body.position().x - before.x);
    assert!((offset - 0.5 * f(body.rotation().c)).abs() < 0.01, "centre moved by {offset}");
    let right_after = body.position() + body.rotation().rotate(w.shape(b, 1).expect("shape 1").local.p);
    assert!(f((right_after - right).length()) < 0.05, "the shape stayed put (up to the body's tilt)");
    // Bad input.
    assert_eq!(w.set_shape_friction(b, 2, s(0.1)), Err(Error::OutOfRange { what: "shape index" }));
    assert!(w.set_shape_friction(b, 0, s(-1.0)).is_err());
    assert_eq!(w.set_shape_density(b, 5, s(1.0)), Err(Error::OutOfRange { what: "shape index" }));
    assert!(w.set_shape_density(b, 0, s(0.0)).is_err());
}
