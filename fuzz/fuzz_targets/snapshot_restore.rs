//! Snapshot and restore: restore-then-step equals uninterrupted stepping, bit for
//! bit, in the same world and in a larger one; corrupted or truncated snapshots are
//! an `Err` that leaves the world unchanged, or (if the bytes happen to be valid) an
//! `Ok` after which the world still steps without panicking.
#![no_main]

use arphysics::{Error, Scalar, Storage, WorldBuffers};
use arphysics_fuzz::{Op, Outcome, Runner, SnapshotInput, MAX_OPS};
use libfuzzer_sys::fuzz_target;

/// Larger than any capacity an input can ask for (as `replay_equal`'s).
type Big = WorldBuffers<40, 160, 40, 64, 64, 80, 40>;

/// Runs `ops` and records each outcome with the state hash after it, and whether
/// it found a store full.
fn record(r: &mut Runner<'_>, ops: &[&Op]) -> Vec<(Outcome, u64, bool)> {
    let mut out = Vec::new();
    for op in ops {
        let o = r.apply(op);
        out.push((o, r.world.state_hash(), r.hit_capacity(&o)));
        if r.exhausted() {
            break;
        }
    }
    out
}

fuzz_target!(|input: SnapshotInput| {
    let spec = &input.scene.world;
    let ops: Vec<&Op> = input.scene.ops.iter().take(MAX_OPS).collect();
    let split = usize::from(input.split) % (ops.len() + 1);
    let (before, after) = ops.split_at(split);
    // After the snapshot: only ops whose effect the snapshot captures.
    let after: Vec<&Op> = after.iter().copied().filter(|op| op.is_state_op()).collect();

    let Ok(mut a) = Runner::new(
        spec,
        Storage::with_capacities(spec.capacities()).expect("small capacities fit the heap"),
    ) else {
        return;
    };
    let mut big = Box::new(Big::new());
    let mut b = Runner::new(spec, big.storage()).expect("a larger world of a valid definition");
    // Restore brings back the state, not the last step's outputs.
    a.state_only_queries = true;
    b.state_only_queries = true;
    let mut same = true;
    for op in before {
        let (oa, ob) = (a.apply(op), b.apply(op));
        // Events dropped by the smaller event list are output, not state.
        same &= oa.without_dropped_events() == ob.without_dropped_events() && !a.hit_capacity(&oa);
    }

    // Snapshot, run on, rewind, run again: the same outcomes and hashes.
    let snap = a.take_snapshot();
    let (hash, marks) = (a.world.state_hash(), a.marks());
    let first = record(&mut a, &after);
    let removed_generator = after
        .iter()
        .zip(&first)
        .any(|(op, (o, ..))| matches!(op, Op::RemoveGenerator(_)) && *o == Outcome::Done);
    match a.world.restore(&snap) {
        Ok(()) => assert_eq!(a.world.state_hash(), hash, "restore did not bring back the snapshot's state"),
        // A game generator removed since the snapshot: its slot no longer holds one.
        Err(Error::SnapshotMismatch { .. }) if removed_generator => return,
        Err(e) => panic!("restoring the world's own snapshot failed: {e:?}"),
    }
    a.rewind(marks);
    let second = record(&mut a, &after);
    assert_eq!(first.len(), second.len());
    for (i, (x, y)) in first.iter().zip(&second).enumerate() {
        assert_eq!(x, y, "op {i} after the snapshot ({:?}) differs after restore", after[i]);
    }

    // Restore into a larger world that took the same calls, then a detour.
    if same {
        for _ in 0..input.detour % 8 {
            let _ = b.world.step(Scalar::ONE / 60);
        }
        match b.world.restore(&snap) {
            Ok(()) => {}
            Err(e) => panic!("a larger world with the same calls rejects the snapshot: {e:?}"),
        }
        assert_eq!(b.world.state_hash(), hash, "restore into a larger world");
        b.rewind(marks);
        let third = record(&mut b, &after);
        for (i, (x, y)) in first.iter().zip(&third).enumerate() {
            if x.2 {
                // A full store in the small world: the larger one may differ from here.
                break;
            }
            // The larger world's event list may keep events the small one dropped.
            assert_eq!(
                x.0.without_dropped_events(),
                y.0.without_dropped_events(),
                "op {i} after the snapshot ({:?}) differs in the larger world",
                after[i]
            );
            assert_eq!(x.1, y.1, "op {i} after the snapshot ({:?}) differs in the larger world", after[i]);
        }
    }

    // Corrupted snapshots: Err and unchanged, or Ok and still sound. Each is
    // tried as corrupted (the checksum rejects it) and resealed (its checksum
    // recomputed, so the field validation behind the checksum is fuzzed too).
    for (c, reseal) in input.corruptions.iter().take(8).flat_map(|c| [(c, false), (c, true)]) {
        let mut bad = snap.clone();
        c.apply(&mut bad);
        if reseal {
            arphysics_fuzz::reseal(&mut bad);
        }
        let (hash, bytes) = (a.world.state_hash(), a.take_snapshot());
        match a.world.restore(&bad) {
            Err(_) => {
                assert_eq!(a.world.state_hash(), hash, "a rejected restore changed the world");
                assert!(a.take_snapshot() == bytes, "a rejected restore changed the world");
            }
            Ok(()) => {
                // Whatever was accepted must be a world the engine can run.
                let _ = a.take_snapshot();
                for _ in 0..8 {
                    let _ = a.world.step(Scalar::ONE / 60);
                }
                for (_, body) in a.world.bodies() {
                    let _ = (body.angle(), body.velocity_at(body.position()));
                }
                a.world.restore(&snap).expect("the original snapshot restores after a corrupted one");
            }
        }
    }
});
