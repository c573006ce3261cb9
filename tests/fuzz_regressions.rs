//! Findings of the fuzz targets in `fuzz/`, reproduced on the stable toolchain
//! with the minimized input written out as API calls. Each test states the
//! contract the finding broke; a failing test here is an open engine bug.

use arphysics::force::Targets;
use arphysics::{BodyDef, BodyHandle, Capacities, GravityForceGenerator, Scalar, Vector2, World, WorldDef};

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// Recomputes a snapshot's checksum trailer (XXH64 of the bytes before it) after
/// an edit, so that the edited fields reach `restore`'s field validation.
fn reseal(snap: &mut [u8]) {
    let n = snap.len();
    let sum = twox_hash::XxHash64::oneshot(0, &snap[..n - 8]);
    snap[n - 8..].copy_from_slice(&sum.to_le_bytes());
}

fn world() -> World<'static> {
    World::with_capacities(WorldDef::new(s(100.0), s(100.0)), Capacities::for_bodies(8)).expect("world")
}

/// Takes a snapshot and restores it into the same world: the state is one
/// snapshot away (DESIGN.md, contract 5), so this must always succeed.
fn round_trip(w: &mut World<'_>) {
    let hash = w.state_hash();
    let mut buf = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut buf).expect("snapshot into snapshot_len() bytes");
    w.restore(&buf).expect("a world restores its own snapshot");
    assert_eq!(w.state_hash(), hash);
}

/// fuzz target `snapshot_restore`: a built-in generator whose target list holds a
/// null (or stale) handle. `Targets::bodies` accepts it ("stale handles are
/// ignored"), `snapshot` writes it, and `restore` rejects the world's own snapshot
/// with `InvalidSnapshot { what: "a null generator target" }`
/// (then in src/snapshot/read.rs, `check_targets`; now src/snapshot/validate.rs).
#[test]
fn a_generator_targeting_a_null_handle_survives_a_snapshot_round_trip() {
    let mut w = world();
    let targets = Targets::bodies(&[BodyHandle::NULL]).expect("one target");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)).with_targets(targets)).expect("gravity");
    round_trip(&mut w);
}

/// The same with a handle that went stale: the body was removed after the
/// generator was given it.
#[test]
fn a_generator_targeting_a_removed_body_survives_a_snapshot_round_trip() {
    let mut w = world();
    let b = w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).expect("body");
    let targets = Targets::bodies(&[b]).expect("one target");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0)).with_targets(targets)).expect("gravity");
    w.remove_body(b).expect("live body");
    round_trip(&mut w);
}

/// A velocity set between steps is clamped by the next step, not by
/// `set_linear_velocity`; a snapshot taken in between must still restore.
#[test]
fn a_body_given_a_huge_velocity_between_steps_survives_a_snapshot_round_trip() {
    let mut w = world();
    let b = w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).expect("body");
    w.body_mut(b).expect("body").set_linear_velocity(v(10_000.0, 0.0));
    round_trip(&mut w);
}

/// The same for spin.
#[test]
fn a_body_given_a_huge_spin_between_steps_survives_a_snapshot_round_trip() {
    let mut w = world();
    let b = w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).expect("body");
    w.body_mut(b).expect("body").set_angular_velocity(s(10_000.0));
    round_trip(&mut w);
}

/// A snapshot whose joint names a body slot far beyond the world's capacity.
/// `restore` must reject it, or accept it and leave a world that steps: the brief
/// of `restore` is "truncated, corrupted or foreign bytes are an `Err`". When it
/// was found it was accepted (joint records were checked with `validate_params`
/// only, not against the snapshot's live bodies; `src/snapshot/validate.rs` now
/// does) and the next step panicked in `Arena::get2_at_mut` (`split_at_mut(j)`
/// with `j` past the slots) called from the joint solver. Found by `snapshot_restore` (a `SetWord`
/// corruption of a pile of boxes joined by rods).
#[test]
fn a_snapshot_whose_joint_names_a_missing_body_is_rejected_or_harmless() {
    let mut w = world();
    let a = w.add_body(BodyDef::circle(s(0.5)).position(v(50.0, 50.0))).expect("a");
    let b = w.add_body(BodyDef::circle(s(0.5)).position(v(51.0, 50.0))).expect("b");
    w.add_joint(arphysics::JointDef::new(
        a,
        Vector2::ZERO,
        b,
        Vector2::ZERO,
        arphysics::JointKind::Rod { length: s(1.0) },
    ))
    .expect("rod");
    let mut snap = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut snap).expect("snapshot");
    // The one joint record is the last 160 bytes before the 8-byte trailer; after
    // its generation (4), free link (4) and live flag (1) comes body A's slot index.
    let at = snap.len() - 8 - 160 + 9;
    assert_eq!(snap[at..at + 4], a.index().to_le_bytes(), "layout of the joint record");
    snap[at..at + 4].copy_from_slice(&1_600_085_855u32.to_le_bytes());
    reseal(&mut snap);
    if w.restore(&snap).is_ok() {
        for _ in 0..2 {
            let _ = w.step(s(1.0 / 60.0));
        }
    }
}

/// The same for an arbiter: a snapshot whose arbiter names a body slot beyond
/// the world's capacity (arbiter records' body handles are checked for order only).
#[test]
fn a_snapshot_whose_arbiter_names_a_missing_body_is_rejected_or_harmless() {
    let mut w = world();
    w.add_body(BodyDef::circle(s(0.5)).position(v(50.0, 50.0))).expect("a");
    w.add_body(BodyDef::circle(s(0.5)).position(v(50.9, 50.0))).expect("b");
    w.step(s(1.0 / 60.0)).expect("step");
    assert_eq!(w.arbiters().count(), 1, "the two circles overlap");
    let mut snap = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut snap).expect("snapshot");
    // No joints: the trailer (8 bytes) follows the joint allocator (12 bytes),
    // which follows the arbiter's 128-byte manifold record (the world recycles
    // contacts, the default), which follows the one 58-byte arbiter record:
    // body A (index, generation), then body B.
    let at = snap.len() - 8 - 12 - 128 - 58 + 8;
    assert_eq!(snap[at..at + 4], 1u32.to_le_bytes(), "layout of the arbiter record");
    snap[at..at + 4].copy_from_slice(&1_000_000u32.to_le_bytes());
    reseal(&mut snap);
    if w.restore(&snap).is_ok() {
        for _ in 0..2 {
            let _ = w.step(s(1.0 / 60.0));
        }
    }
}

/// `WorldDef::substeps` is documented as "1 to `MAX_SUBSTEPS`", and out-of-range
/// input is an `Err` that names the parameter (README, Limits), but `World::new`
/// does not check it (src/world.rs, `WorldDef::validate`): 0 is silently run as
/// 1, and `u32::MAX` is accepted, after which one `step` runs 4,294,967,295
/// sub-steps (src/solver.rs, `solve_and_integrate`: `for substep in 0..n`), a hang.
/// The fuzz targets keep `substeps` below 20 so they can run at all.
#[test]
fn substeps_outside_one_to_max_substeps_are_rejected() {
    for n in [0, arphysics::world::MAX_SUBSTEPS + 1, u32::MAX] {
        let mut def = WorldDef::new(s(100.0), s(100.0));
        def.substeps = n;
        let r = World::with_capacities(def, Capacities::for_bodies(8));
        assert!(r.is_err(), "substeps = {n} was accepted");
    }
}

/// `WorldDef::restitution_threshold` is not checked by `World::new`
/// (src/world.rs, `WorldDef::validate`), and the restitution pass negates it with
/// a raw `-` (src/solver.rs:320, `cp.relative_velocity > -threshold`). With
/// `Scalar::MIN` the first bouncy contact panics with "attempt to negate with
/// overflow" in a debug build and wraps in a release build (debug and release
/// differ). Found by `scene_ops` (a pile of bouncy boxes in a world whose
/// restitution threshold was `Scalar::MIN`).
#[test]
fn a_minimum_restitution_threshold_is_rejected_or_harmless() {
    let mut def = WorldDef::new(s(100.0), s(100.0));
    def.restitution_threshold = Scalar::MIN;
    let Ok(mut w) = World::with_capacities(def, Capacities::for_bodies(8)) else { return };
    let floor = w.add_path(arphysics::PolygonPath::rectangle(s(20.0), s(1.0)).expect("floor")).expect("path");
    w.add_body(BodyDef::polygon(floor).position(v(50.0, 0.5)).static_body()).expect("floor");
    let ball =
        BodyDef::circle(s(0.5)).position(v(50.0, 2.0)).linear_velocity(v(0.0, -5.0)).restitution(s(0.5));
    w.add_body(ball).expect("ball");
    for _ in 0..30 {
        w.step(s(1.0 / 60.0)).expect("step");
    }
}

/// fuzz target `scene_ops` (CI, twelfth session): a one-shape body becoming
/// compound takes two slots of the shape store (its own shape and the new one).
/// With one left, `add_shape` returned `CapacityFull { what: "shape" }` but had
/// taken the free slot and given it back, which moved the store's free list
/// (in the snapshot and the state hash): "the world is unchanged on every
/// error" broke, and the world then stepped apart from one that never tried.
/// The shape store's room is now checked before any slot is taken
/// (src/world/shapes.rs, `place_shapes`).
#[test]
fn a_shape_store_one_slot_short_refuses_and_changes_nothing() {
    use arphysics::{Error, ShapeDef};
    let make = || {
        let caps = Capacities { shapes: 1, ..Capacities::for_bodies(4) };
        let mut w = World::with_capacities(WorldDef::new(s(100.0), s(100.0)), caps).expect("world");
        w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
        let b = w.add_body(BodyDef::circle(s(0.5)).position(v(50.0, 50.0))).expect("room");
        (w, b)
    };
    let (mut tried, b) = make();
    let (mut untouched, _) = make();
    let hash = tried.state_hash();
    let full = tried.add_shape(b, ShapeDef::circle(s(0.2)).offset(v(0.6, 0.0)));
    assert_eq!(full, Err(Error::CapacityFull { what: "shape" }));
    assert_eq!(tried.state_hash(), hash, "unchanged after a refusal");
    assert_eq!(tried.state_hash(), untouched.state_hash());
    let dt = s(1.0 / 60.0);
    for _ in 0..30 {
        tried.step(dt).expect("step");
        untouched.step(dt).expect("step");
    }
    assert_eq!(tried.state_hash(), untouched.state_hash(), "the two step alike");
    // Still a lone circle falling from rest: 0.5 s of gravity, about 1.25 m.
    let y = tried.body(b).expect("live").position().y.to_num::<f64>();
    assert!((48.6..48.8).contains(&y), "fell to y = {y}");
}
