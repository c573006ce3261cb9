//! Snapshots: restore-then-step equals uninterrupted stepping, bit for bit; bad
//! bytes change nothing; capacities do not matter; the desync locator names the
//! first difference.

use arphysics::snapshot::{diff, Difference, Object};
use arphysics::{
    Arbiter, BodyDef, BodyHandle, CallbackContext, Capacities, Error, FnHandler, GravityForceGenerator,
    JointDef, JointKind, LinearForceGenerator, MaxTorque, Motor, PolygonPath, Rect, Scalar, Targets, Vector2,
    World, WorldDef,
};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;

fn ignore_level_3(_: &mut Arbiter, _: &mut CallbackContext<'_>) -> bool {
    false
}

/// A mixed scene: a small pyramid, circles, a pivot with a motor, a rod, a spring,
/// a handler that ignores some pairs, two generators (one targeted), and a few
/// bodies added and removed so the allocator has a free list.
fn scene(capacity: usize) -> (World<'static>, Vec<BodyHandle>) {
    let bounds = Rect::from_corners(v(-100.0, -50.0), v(100.0, 150.0));
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(capacity))
        .expect("world");
    let ground = w.add_path(PolygonPath::rectangle(s(80.0), s(2.0)).expect("g")).expect("p");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -1.0)).static_body()).expect("ground");
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("b")).expect("p");
    let mut handles = Vec::new();
    for row in 0..5 {
        for j in 0..(5 - row) {
            let x = f64::from(j) - f64::from(5 - row) * 0.5 + 0.5;
            handles
                .push(w.add_body(BodyDef::polygon(unit).position(v(x, 0.5 + f64::from(row)))).expect("box"));
        }
    }
    // Churn: add and remove so slots are reused and generations move.
    let temp: Vec<_> = (0..4)
        .map(|i| w.add_body(BodyDef::circle(s(0.2)).position(v(30.0 + f64::from(i), 40.0))).expect("t"))
        .collect();
    w.remove_body(temp[1]).expect("rm");
    w.remove_body(temp[3]).expect("rm");
    for i in 0..6 {
        let level = if i % 2 == 0 { 3 } else { 0 };
        let c = BodyDef::circle(s(0.3 + 0.05 * f64::from(i)))
            .position(v(-8.0 + 1.3 * f64::from(i), 8.0 + f64::from(i)))
            .restitution(s(0.4))
            .collision_level(level);
        handles.push(w.add_body(c).expect("ball"));
    }
    let wheel = w.add_body(BodyDef::circle(s(1.0)).position(v(15.0, 10.0))).expect("wheel");
    let motor = Motor { speed: s(2.0), max_torque: MaxTorque::Limited(s(30.0)) };
    w.add_joint(JointDef::to_world(
        wheel,
        Vector2::ZERO,
        v(15.0, 10.0),
        JointKind::Pivot { limits: None, motor: Some(motor) },
    ))
    .expect("pivot");
    let bob = w.add_body(BodyDef::circle(s(0.4)).position(v(20.0, 20.0))).expect("bob");
    w.add_joint(JointDef::to_world(bob, Vector2::ZERO, v(22.0, 24.0), JointKind::Rod { length: s(4.0) }))
        .expect("rod");
    let sb = w.add_body(BodyDef::circle(s(0.4)).position(v(-20.0, 20.0))).expect("sb");
    w.add_joint(JointDef::to_world(
        sb,
        Vector2::ZERO,
        v(-20.0, 23.0),
        JointKind::Spring { stiffness: s(40.0), rest_length: s(1.0) },
    ))
    .expect("spring");
    handles.extend([wheel, bob, sb]);
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("g");
    w.add_force_generator(
        LinearForceGenerator::new(v(3.0, 0.0)).with_targets(Targets::bodies(&[bob]).expect("t")),
    )
    .expect("wind");
    w.add_collision_handler(3, 0, FnHandler { begin: Some(ignore_level_3), ..FnHandler::default() })
        .expect("h");
    (w, handles)
}

fn run(w: &mut World<'_>, steps: usize) {
    for _ in 0..steps {
        w.step(s(DT)).expect("step");
    }
}

fn take(w: &World<'_>) -> Vec<u8> {
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("fits");
    assert_eq!(n, buf.len());
    buf
}

#[test]
fn restore_then_step_equals_uninterrupted_stepping() {
    let (mut reference, _) = scene(64);
    let (mut replay, _) = scene(64);
    run(&mut reference, 90);
    run(&mut replay, 90);
    let snap = take(&replay);
    assert_eq!(reference.state_hash(), replay.state_hash());
    // Wander off: more steps, a body added, one removed, a generator changed.
    run(&mut replay, 37);
    replay.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 100.0))).expect("new body");
    replay.restore(&snap).expect("restore");
    assert_eq!(replay.state_hash(), reference.state_hash(), "restored state hashes equal");
    for step in 0..240 {
        reference.step(s(DT)).expect("step");
        replay.step(s(DT)).expect("step");
        assert_eq!(replay.state_hash(), reference.state_hash(), "diverged {step} steps after restore");
    }
    assert!(reference.arbiters().count() > 5, "the scene has live contacts");
}

#[test]
fn handles_survive_a_round_trip_across_adds_and_removes() {
    let (mut w, handles) = scene(64);
    run(&mut w, 30);
    let snap = take(&w);
    let before: Vec<_> = handles.iter().map(|h| w.body(*h).expect("live").position()).collect();
    // Remove half the bodies, add others into the freed slots.
    for h in handles.iter().step_by(2) {
        w.remove_body(*h).expect("rm");
    }
    let newcomers: Vec<_> = (0..5)
        .map(|i| w.add_body(BodyDef::circle(s(0.2)).position(v(f64::from(i), 60.0))).expect("new"))
        .collect();
    run(&mut w, 10);
    w.restore(&snap).expect("restore");
    for (h, p) in handles.iter().zip(before) {
        assert_eq!(w.body(*h).expect("same handle, same body").position(), p);
    }
    for h in newcomers {
        assert_eq!(w.body(h).err(), Some(Error::StaleHandle), "bodies added after the snapshot are gone");
    }
    // The next body created gets the same slot as it would have at snapshot time.
    let (mut fresh, _) = scene(64);
    run(&mut fresh, 30);
    let a = fresh.add_body(BodyDef::circle(s(0.2)).position(v(0.0, 70.0))).expect("a");
    let b = w.add_body(BodyDef::circle(s(0.2)).position(v(0.0, 70.0))).expect("b");
    // Two worlds: same slot and generation, each world's own tag.
    assert_eq!((a.index(), a.generation()), (b.index(), b.generation()));
}

#[test]
fn snapshot_size_per_body_and_per_arbiter() {
    let (mut w, _) = scene(64);
    run(&mut w, 120);
    let len = w.snapshot_len();
    let bodies = w.body_count();
    let arbiters = w.arbiters().count();
    println!("snapshot: {len} bytes for {bodies} bodies, {arbiters} arbiters, {} joints", w.joints().count());
    println!(
        "per body {} bytes (+{} per distinct run of properties), per arbiter {} bytes",
        arphysics::snapshot::BODY_RECORD,
        arphysics::snapshot::PROPS_RECORD,
        arphysics::snapshot::ARBITER_RECORD
    );
    const { assert!(arphysics::snapshot::BODY_RECORD <= 64 && arphysics::snapshot::ARBITER_RECORD <= 64) };
    // A pyramid of identical boxes shares one properties record.
    let bounds = Rect::from_corners(v(-100.0, -50.0), v(100.0, 150.0));
    let mut p =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(300)).expect("w");
    let unit = p.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("b")).expect("p");
    for i in 0..200 {
        p.add_body(
            BodyDef::polygon(unit).position(v(f64::from(i % 20) * 1.5 - 15.0, f64::from(i / 20) * 1.5)),
        )
        .expect("b");
    }
    let empty =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(300)).expect("w");
    let per_body =
        (p.snapshot_len() - empty.snapshot_len() - arphysics::snapshot::PROPS_RECORD) as f64 / 200.0;
    println!("200 identical boxes: {per_body} bytes per body");
    assert!(per_body <= 64.0, "{per_body}");
}

#[test]
fn a_small_buffer_reports_the_size_needed_and_is_left_alone() {
    let (w, _) = scene(64);
    let needed = w.snapshot_len();
    let mut small = vec![0xAAu8; needed - 1];
    assert_eq!(w.snapshot(&mut small), Err(Error::BufferTooSmall { needed }));
    assert!(small.iter().all(|b| *b == 0xAA));
}

#[test]
fn truncated_corrupted_or_foreign_bytes_are_rejected_and_change_nothing() {
    let (mut w, _) = scene(64);
    run(&mut w, 60);
    let snap = take(&w);
    run(&mut w, 5);
    let before = w.state_hash();
    // Truncated at every length.
    for cut in (0..snap.len()).step_by(97).chain([snap.len() - 1]) {
        assert!(w.restore(&snap[..cut]).is_err(), "truncated at {cut}");
        assert_eq!(w.state_hash(), before);
    }
    // Foreign bytes.
    assert!(matches!(w.restore(b"not a snapshot at all"), Err(Error::InvalidSnapshot { .. })));
    // Corrupted bytes: the checksum rejects every one (see
    // tests/snapshot_integrity.rs for every bit of every byte).
    for i in (0..snap.len()).step_by(7) {
        let mut bad = snap.clone();
        bad[i] ^= 0x5A;
        assert!(w.restore(&bad).is_err(), "corrupted byte {i} accepted");
        assert_eq!(w.state_hash(), before, "a rejected restore changed the world (byte {i})");
    }
    // A snapshot of another world (different paths) does not fit this one.
    let bounds = Rect::from_corners(v(-100.0, -50.0), v(100.0, 150.0));
    let other = World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(8)).expect("w");
    let foreign = take(&other);
    assert_eq!(w.restore(&foreign), Err(Error::SnapshotMismatch { what: "polygon paths" }));
    assert_eq!(w.state_hash(), before);
}

#[test]
fn results_do_not_depend_on_capacities() {
    let (mut small, _) = scene(48);
    let (mut large, _) = scene(4000);
    for step in 0..200 {
        small.step(s(DT)).expect("step");
        large.step(s(DT)).expect("step");
        assert_eq!(small.state_hash(), large.state_hash(), "step {step}");
    }
    // And a snapshot moves between them.
    let snap = take(&small);
    large.restore(&snap).expect("fits a larger world");
    assert_eq!(large.state_hash(), small.state_hash());
}

#[test]
fn the_desync_locator_names_the_first_differing_body_and_field() {
    let (mut a, _) = scene(64);
    let (mut b, handles) = scene(64);
    run(&mut a, 20);
    run(&mut b, 20);
    assert_eq!(diff(&take(&a), &take(&b)), Ok(None));
    // A peer applies a tiny impulse the other did not.
    let victim = handles[7];
    b.body_mut(victim).expect("live").apply_linear_impulse(v(0.0, 1e-6));
    let found = diff(&take(&a), &take(&b)).expect("valid");
    assert_eq!(found, Some(Difference { object: Object::Body(victim.index()), field: "linear velocity.y" }));
    println!("desync located: {}", found.expect("found"));
    // A moment later it has spread; the locator still names the earliest object.
    run(&mut a, 3);
    run(&mut b, 3);
    let found = diff(&take(&a), &take(&b)).expect("valid").expect("differs");
    println!("three steps later: {found}");
    assert!(matches!(found.object, Object::Body(_)));
    assert!(diff(b"junk", &take(&a)).is_err());
}
