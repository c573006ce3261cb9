//! Contact recycling (`WorldDef::contact_recycle_distance`): settled pairs keep
//! their manifolds, the kept separations follow the bodies, a body that moves
//! or turns gets its manifold computed again, and the physics stays that of a
//! world that computes every manifold.

use arphysics::limits::DEFAULT_CONTACT_RECYCLE_DISTANCE;
use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;

/// A column of `n` unit boxes on a static ground under gravity (0, −10),
/// recycling at `distance`.
fn column(n: usize, distance: Scalar) -> World<'static> {
    let bounds = Rect::from_corners(v(-50.0, -10.0), v(50.0, 90.0));
    let def = WorldDef { contact_recycle_distance: distance, ..WorldDef::with_bounds(bounds) };
    let mut w = World::with_capacities(def, Capacities::for_bodies(64)).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("ground")).expect("path");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground body");
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    for i in 0..n {
        w.add_body(BodyDef::polygon(unit).position(v(0.0, 0.5 + i as f64))).expect("box");
    }
    w
}

/// Steps `a` and `b` once each and requires them to agree: the same number
/// of recycled manifolds and the same state hash (`what` names the step in
/// a failure). Returns `a`'s number of recycled manifolds.
fn step_alike(a: &mut World<'_>, b: &mut World<'_>, what: &str) -> u32 {
    let (ra, rb) = (a.step(s(DT)).expect("step"), b.step(s(DT)).expect("step"));
    assert_eq!(ra.manifolds_recycled, rb.manifolds_recycled, "{what}");
    assert_eq!(a.state_hash(), b.state_hash(), "{what}");
    ra.manifolds_recycled
}

fn top_y(w: &World<'_>) -> f64 {
    w.bodies().map(|(_, b)| b.position().y.to_num::<f64>()).fold(f64::MIN, f64::max)
}

#[test]
fn a_settled_column_recycles_its_manifolds_and_stands_as_one_that_computes_them() {
    let mut kept = column(10, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    let mut computed = column(10, Scalar::ZERO);
    let (mut recycled, mut pairs) = (0u64, 0u64);
    for step in 0..600 {
        let r = kept.step(s(DT)).expect("step");
        let c = computed.step(s(DT)).expect("step");
        assert_eq!(c.manifolds_recycled, 0, "distance 0 computes every manifold");
        if step >= 300 {
            recycled += u64::from(r.manifolds_recycled);
            pairs += u64::from(r.arbiters);
        }
    }
    // Settled: every touching pair (10 of them) carries its manifold on.
    assert!(recycled * 10 >= pairs * 9, "recycled {recycled} of {pairs} pair-steps");
    // The column stands the same: top within 1 mm of the computing world's,
    // at rest, and within the stacking threshold of its height (9.5 m).
    let (a, b) = (top_y(&kept), top_y(&computed));
    assert!((a - b).abs() < 1e-3, "top {a} against {b}");
    assert!((a - 9.5).abs() < 0.05, "top {a}");
    for (_, body) in kept.bodies() {
        let vel = body.linear_velocity();
        assert!(vel.x.abs() < s(0.01) && vel.y.abs() < s(0.01), "at rest: {vel:?}");
    }
}

#[test]
fn kept_separations_follow_the_bodies_and_a_moved_body_is_collided_again() {
    // One box resting on the ground.
    let mut w = column(1, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
    }
    let r = w.step(s(DT)).expect("step");
    assert_eq!(r.manifolds_recycled, 1, "the resting box keeps its manifold");
    let (h, b) = w.bodies().find(|(_, b)| b.position().y > s(0.0)).expect("box");
    let resting = b.position();
    let sep_before: Vec<Scalar> = w
        .arbiters()
        .flat_map(|a| a.contact_points().iter().map(|p| p.separation).collect::<Vec<_>>())
        .collect();
    // Lift it 1 cm (within the recycle distance, 5 cm): the kept manifold's
    // separations follow, 1 cm larger each, computed without the narrow phase.
    w.set_position(h, resting + v(0.0, 0.01)).expect("lift");
    w.body_mut(h).expect("box").set_linear_velocity(Vector2::ZERO);
    let r = w.step(s(DT)).expect("step");
    assert_eq!(r.manifolds_recycled, 1);
    let sep_after: Vec<Scalar> = w
        .arbiters()
        .flat_map(|a| a.contact_points().iter().map(|p| p.separation).collect::<Vec<_>>())
        .collect();
    assert_eq!(sep_before.len(), 2);
    for (before, after) in sep_before.iter().zip(&sep_after) {
        let grew = (*after - *before).to_num::<f64>();
        assert!((grew - 0.01).abs() < 1e-6, "separation grew {grew} m, expected 0.01");
    }
    // Lift it 10 cm, past the distance: computed again, and with the box
    // 10 cm up the pair is beyond the speculative distance: no points.
    let p = w.body(h).expect("box").position();
    w.set_position(h, p + v(0.0, 0.1)).expect("lift");
    w.body_mut(h).expect("box").set_linear_velocity(Vector2::ZERO);
    let r = w.step(s(DT)).expect("step");
    assert_eq!(r.manifolds_recycled, 0, "moved past the distance: collided again");
    assert_eq!(w.arbiters().map(|a| a.contact_points().len()).sum::<usize>(), 0);
}

#[test]
fn a_turned_body_is_collided_again() {
    let mut w = column(1, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
    }
    let (h, b) = w.bodies().find(|(_, b)| b.position().y > s(0.0)).expect("box");
    // Turn it 3°: its corners move 2.6 cm relative to the ground, and twice
    // the turn at its radius (0.71 m) is past 5 cm.
    let p = b.position();
    w.set_angle(h, s(3f64.to_radians())).expect("turn");
    w.set_position(h, p).expect("place");
    let r = w.step(s(DT)).expect("step");
    assert_eq!(r.manifolds_recycled, 0);
}

#[test]
fn the_recycle_distance_is_checked_and_restored_with_the_snapshot() {
    let mut w = column(3, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    assert!(w.set_contact_recycle_distance(s(-0.01)).is_err());
    assert!(w.set_contact_recycle_distance(s(0.3)).is_err());
    assert_eq!(w.def().contact_recycle_distance, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    for _ in 0..60 {
        w.step(s(DT)).expect("step");
    }
    let mut snap = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut snap).expect("snapshot");
    // Turned off after the snapshot, then rolled back: recycling comes back
    // with the snapshot, and the future is the one stepping on gives.
    let mut on = column(3, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    for _ in 0..60 {
        on.step(s(DT)).expect("step");
    }
    assert_eq!(on.state_hash(), w.state_hash());
    w.set_contact_recycle_distance(Scalar::ZERO).expect("off");
    w.step(s(DT)).expect("step");
    w.restore(&snap).expect("restore");
    assert_eq!(w.def().contact_recycle_distance, DEFAULT_CONTACT_RECYCLE_DISTANCE);
    for step in 0..30 {
        step_alike(&mut w, &mut on, &format!("step {step}"));
    }
}

#[test]
fn turning_recycling_on_after_a_restore_steps_as_the_world_that_never_restored() {
    // With recycling off no manifold is kept (none would be in the
    // snapshot), so a restored world and one stepped on agree once it is
    // turned on.
    let mut on = column(5, Scalar::ZERO);
    let mut restored = column(5, Scalar::ZERO);
    for _ in 0..60 {
        on.step(s(DT)).expect("step");
        restored.step(s(DT)).expect("step");
    }
    let mut snap = vec![0u8; restored.snapshot_len()];
    restored.snapshot(&mut snap).expect("snapshot");
    restored.step(s(DT)).expect("step");
    restored.restore(&snap).expect("restore");
    for w in [&mut on, &mut restored] {
        w.set_contact_recycle_distance(DEFAULT_CONTACT_RECYCLE_DISTANCE).expect("on");
    }
    for step in 0..30 {
        step_alike(&mut on, &mut restored, &format!("step {step}"));
    }
}

/// A 4 × 1.5 m box driven flat into a wall (e = 0.5, both points of its
/// manifold touching at once): the step that reports the hit ends with the
/// box on the face, and the box leaves at half the speed, square. A new
/// manifold is computed, not recycled, so its two points take the 2×2
/// block: solved one at a time, the first point's impulse turns the box and
/// the second's throws the first corner off the face, and at 2,048 m/s the
/// box had left the wall 0.32 m before its impact step ended (so no hit was
/// reported).
#[test]
fn a_flat_impact_ends_its_step_on_the_face_and_bounces_back_square() {
    for speed in [8.0, 60.0, 400.0, 2048.0] {
        let bounds = Rect::from_corners(v(-3000.0, -50.0), v(50.0, 50.0));
        let def = WorldDef { max_linear_speed: s(2048.0), ..WorldDef::with_bounds(bounds) };
        let mut w = World::with_capacities(def, Capacities::for_bodies(4)).expect("world");
        let wall = w.add_path(PolygonPath::rectangle(s(1.0), s(10.0)).expect("wall")).expect("path");
        w.add_body(BodyDef::polygon(wall).position(v(10.0, 0.0)).static_body()).expect("wall body");
        let shape = w.add_path(PolygonPath::rectangle(s(4.0), s(1.5)).expect("box")).expect("path");
        let car = w
            .add_body(BodyDef::polygon(shape).linear_velocity(v(speed, 0.0)).restitution(s(0.5)))
            .expect("box");
        let mut hits = 0;
        for _ in 0..120 {
            w.step(s(DT)).expect("step");
            let x = w.body(car).expect("box").position().x.to_num::<f64>();
            // The face is at 7.5; slower boxes overlap it by up to a step's
            // travel before the contact pushes them out (8 m/s: 0.1 m).
            assert!(x < 7.75, "{speed} m/s: into the wall (x {x})");
            if let Some(hit) = w.contact_hit_events().first() {
                hits += 1;
                let at = hit.speed.to_num::<f64>();
                assert!((at - speed).abs() < 0.01 * speed, "{speed} m/s: hit at {at}");
                assert!((x - 7.5).abs() < 0.05, "{speed} m/s: the hit step ends at x {x}");
            }
        }
        assert_eq!(hits, 1, "{speed} m/s: one hit");
        let b = w.body(car).expect("box");
        let (vx, spin) = (b.linear_velocity().x.to_num::<f64>(), b.angular_velocity().to_num::<f64>());
        assert!((vx + 0.5 * speed).abs() < 0.01 * speed, "{speed} m/s: leaves at {vx}");
        // Square: its corners (0.75 m off the centre line) turn at under
        // 0.5 % of the impact speed.
        assert!(spin.abs() * 0.75 < 0.005 * speed, "{speed} m/s: spins at {spin} rad/s");
    }
}

/// A settled pair whose manifold is recycled keeps the lane the solver built
/// for it last step (only the per-step fields are written again), so long as
/// its masses and friction are unchanged. Each change below, made between
/// steps, must rebuild the lanes it touches: the world that made it steps
/// exactly as a copy restored from a snapshot taken just after it (a restore
/// rebuilds every lane), and differently from a world that did not make it.
/// Removing a body moves the arbiters after its own down the list: none of
/// them may take a lane built for another.
#[test]
fn kept_lanes_step_as_rebuilt_ones_across_mass_friction_and_type_changes() {
    use arphysics::{BodyHandle, MassSpec};
    type Change = fn(&mut World<'static>, &[BodyHandle]);
    let changes: [(&str, Change); 8] = [
        // Every other arbiter moves down the list, and its lane with it.
        ("removal", |w, b| {
            w.remove_body(b[6]).expect("remove");
        }),
        ("mass", |w, b| w.set_mass(b[2], MassSpec::Mass(s(7.0))).expect("mass")),
        ("friction", |w, b| w.set_friction(b[3], s(0.05)).expect("friction")),
        ("restitution", |w, b| w.set_restitution(b[1], s(0.4)).expect("restitution")),
        ("fixed rotation", |w, b| w.set_fixed_rotation(b[4], true).expect("fixed")),
        ("static", |w, b| w.set_static(b[3]).expect("static")),
        ("dynamic", |w, b| w.set_dynamic(b[3], MassSpec::Density(s(2.0))).expect("dynamic")),
        ("density", |w, b| w.set_mass(b[0], MassSpec::Density(s(3.0))).expect("density")),
    ];
    let build = || {
        let mut w = column(0, DEFAULT_CONTACT_RECYCLE_DISTANCE);
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
        // A box on its own, made first: its pair with the ground comes first
        // in key order.
        let alone = w.add_body(BodyDef::polygon(unit).position(v(-10.0, 0.5))).expect("box");
        // The column leans slightly, so that friction and turning matter.
        let mut boxes: Vec<BodyHandle> = (0..6)
            .map(|i| {
                let def = BodyDef::polygon(unit).position(v(0.02 * f64::from(i), 0.5 + f64::from(i)));
                w.add_body(def).expect("box")
            })
            .collect();
        boxes.push(alone);
        (w, boxes)
    };
    let (mut w, boxes) = build();
    for _ in 0..120 {
        w.step(s(DT)).expect("step");
    }
    let restored_from = |w: &World<'static>| {
        let mut snap = vec![0u8; w.snapshot_len()];
        w.snapshot(&mut snap).expect("snapshot");
        let (mut copy, _) = build();
        copy.restore(&snap).expect("restore");
        copy
    };
    for (name, change) in changes {
        let mut unchanged = restored_from(&w);
        change(&mut w, &boxes);
        let mut restored = restored_from(&w);
        for step in 0..20 {
            let recycled = step_alike(&mut w, &mut restored, &format!("{name}: step {step}"));
            unchanged.step(s(DT)).expect("step");
            assert!(recycled > 0, "{name}: step {step} recycled nothing");
        }
        assert_ne!(w.state_hash(), unchanged.state_hash(), "{name}: the change changed nothing");
    }
}

/// A box sliding on the ground keeps its manifold for most steps (it moves
/// 1 to 4 cm a step) with its friction at the cap. Its friction changed
/// before every step, the world steps exactly as one that rebuilds every
/// lane (restoring itself from a snapshot after each change).
#[test]
fn a_friction_change_rebuilds_a_kept_lane() {
    let build = || {
        let mut w = column(0, DEFAULT_CONTACT_RECYCLE_DISTANCE);
        let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
        let def = BodyDef::polygon(unit).position(v(0.0, 0.5)).linear_velocity(v(2.5, 0.0)).friction(s(0.05));
        let slider = w.add_body(def).expect("slider");
        (w, slider)
    };
    let (mut kept, slider) = build();
    let (mut rebuilt, _) = build();
    let mut snap = Vec::new();
    let mut recycled = 0;
    for step in 0..60 {
        let mu = s(if step % 2 == 0 { 0.05 } else { 0.07 });
        kept.set_friction(slider, mu).expect("friction");
        // (A restore hands out new handles: the slider is the last body.)
        let last = rebuilt.bodies().map(|(h, _)| h).last().expect("slider");
        rebuilt.set_friction(last, mu).expect("friction");
        snap.resize(rebuilt.snapshot_len(), 0);
        rebuilt.snapshot(&mut snap).expect("snapshot");
        rebuilt.restore(&snap).expect("restore");
        recycled += step_alike(&mut kept, &mut rebuilt, &format!("step {step}"));
    }
    let vx = kept.body(slider).expect("slider").linear_velocity().x.to_num::<f64>();
    assert!(vx > 0.3, "still sliding after 1 s ({vx} m/s)");
    assert!(recycled >= 20, "the slide kept its manifold in {recycled} of 60 steps");
}
