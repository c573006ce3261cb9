//! Replays a `snapshot_restore` input and says which corruption `restore`
//! accepted, where it differs from the original (`snapshot::diff`), and what the
//! world holds after it (`cargo run --example explain_snapshot -- FILE`).

use arbitrary::{Arbitrary, Unstructured};
use arphysics::{Scalar, Storage};
use arphysics_fuzz::{Op, Runner, SnapshotInput, MAX_OPS};

fn main() {
    let path = std::env::args().nth(1).expect("a file");
    let bytes = std::fs::read(path).expect("read");
    let input = SnapshotInput::arbitrary_take_rest(Unstructured::new(&bytes)).expect("decode");
    let spec = &input.scene.world;
    let ops: Vec<&Op> = input.scene.ops.iter().take(MAX_OPS).collect();
    let split = usize::from(input.split) % (ops.len() + 1);
    let mut a = Runner::new(
        spec,
        Storage::with_capacities(spec.capacities()).expect("small capacities fit the heap"),
    )
    .expect("world");
    for op in &ops[..split] {
        let o = a.apply(op);
        println!("{op:?} -> {o:?}");
    }
    let snap = a.take_snapshot();
    println!(
        "snapshot: {} bytes, {} bodies, {} joints",
        snap.len(),
        a.world.body_count(),
        a.world.joints().count()
    );
    for c in input.corruptions.iter().take(8) {
        let mut bad = snap.clone();
        c.apply(&mut bad);
        let d = arphysics::snapshot::diff(&snap, &bad);
        let r = a.world.restore(&bad);
        println!("{c:?}: diff {d:?}, restore {r:?}");
        if r.is_ok() {
            for (h, j) in a.world.joints() {
                println!("  joint {h:?}: {:?}", j.def());
            }
            for (h, b) in a.world.bodies() {
                println!("  body {h:?} at {:?}", b.position());
            }
            for _ in 0..8 {
                let _ = a.world.step(Scalar::ONE / 60);
            }
            a.world.restore(&snap).expect("original");
        }
    }
}
