//! Bit-identical replay: the same ops applied to worlds of the same definition
//! give the same outcome and the same `state_hash()` after every op, whatever the
//! storage capacity (heap or static buffers).
//!
//! World A has the input's capacities; A2 is a second, identical world; B has far
//! larger capacities on static buffers. A and A2 must agree on everything. B must
//! agree with A until A reports a full store (a legitimate difference): from then
//! on B is no longer compared. A full event list is not such a store: events are
//! the step's output, not state, so B's larger lists only change the step
//! report's count of dropped events, and everything else is still compared.
#![no_main]

use arphysics::{Storage, WorldBuffers};
use arphysics_fuzz::{Input, Op, Outcome, Runner, MAX_OPS};
use libfuzzer_sys::fuzz_target;

/// Larger than any capacity an input can ask for (32 bodies, 16 paths, 128
/// contacts, 32 joints, 64 chain vertices, 32 shapes; 16 events, the default
/// callbacks).
type Big = WorldBuffers<40, 160, 40, 64, 64, 80, 40>;

fuzz_target!(|input: Input| {
    let caps = input.world.capacities();
    let mut big = Box::new(Big::new());
    let a = Runner::new(&input.world, Storage::with_capacities(caps).expect("small capacities fit the heap"));
    let a2 =
        Runner::new(&input.world, Storage::with_capacities(caps).expect("small capacities fit the heap"));
    let b = Runner::new(&input.world, big.storage());
    let (mut a, mut a2, mut b) = match (a, a2, b) {
        (Ok(a), Ok(a2), Ok(b)) => (a, a2, b),
        (a, a2, b) => {
            // The definition alone decides whether a world can be made.
            assert_eq!(a.is_ok(), a2.is_ok());
            assert_eq!(a.is_ok(), b.is_ok(), "world creation depends on capacity");
            return;
        }
    };
    assert_eq!(a.world.state_hash(), b.world.state_hash(), "fresh worlds differ by capacity");
    let mut b_live = true;
    for (i, op) in input.ops.iter().take(MAX_OPS).enumerate() {
        let oa = a.apply(op);
        let oa2 = a2.apply(op);
        assert_eq!(oa, oa2, "op {i} {op:?}: identical worlds returned different outcomes");
        assert_eq!(a.capacity_hit, a2.capacity_hit);
        assert_eq!(
            a.world.state_hash(),
            a2.world.state_hash(),
            "op {i} {op:?}: identical worlds hash differently"
        );
        if b_live {
            let ob = b.apply(op);
            if a.hit_capacity(&oa) {
                // A full store in the small world: from here on the worlds may differ.
                b_live = false;
            } else if oa.without_dropped_events() != ob.without_dropped_events() {
                panic!("op {i} {op:?}: capacity changed the outcome: {oa:?} vs {ob:?}");
            } else {
                assert_eq!(
                    a.world.state_hash(),
                    b.world.state_hash(),
                    "op {i} {op:?}: capacity changed the state"
                );
            }
        }
        if let (Op::Snapshot(_), Outcome::Value(_)) = (op, oa) {
            // The encoding never depends on the capacity.
            assert!(a.snapshots.last() == a2.snapshots.last(), "op {i}: snapshots differ");
            if b_live {
                assert!(a.snapshots.last() == b.snapshots.last(), "op {i}: snapshot depends on capacity");
            }
        }
        if a.exhausted() {
            break;
        }
    }
});
