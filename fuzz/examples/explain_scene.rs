//! Replays a `scene_ops` input op by op, printing each outcome, and after each
//! restore the joints and arbiters that name bodies not in the world
//! (`cargo run --example explain_scene -- FILE`).

use arbitrary::{Arbitrary, Unstructured};
use arphysics::{Storage, WorldBuffers};
use arphysics_fuzz::{Input, Op, Runner, MAX_OPS};

fn main() {
    let path = std::env::args().nth(1).expect("a file");
    let bytes = std::fs::read(path).expect("read");
    let input = Input::arbitrary_take_rest(Unstructured::new(&bytes)).expect("decode");
    println!("{:?}", input.world);
    // The storage `scene_ops` uses: heap for an even `paths`, static buffers for odd.
    let mut buffers = Box::new(WorldBuffers::<12, 48, 8>::new());
    let storage = if input.world.paths.is_multiple_of(2) {
        Storage::with_capacities(input.world.capacities()).expect("small capacities fit the heap")
    } else {
        buffers.storage()
    };
    let mut r = Runner::new(&input.world, storage).expect("world");
    for op in input.ops.iter().take(MAX_OPS) {
        let o = r.apply(op);
        println!("{op:?} -> {o:?}");
        if matches!(op, Op::Restore(..)) {
            let w = &r.world;
            for (h, j) in w.joints() {
                let d = j.def();
                if w.body(d.body_a).is_err() || d.body_b.is_some_and(|b| w.body(b).is_err()) {
                    println!("  joint {h:?} names a missing body: {d:?}");
                }
            }
            for a in w.arbiters() {
                if w.body(a.body_a()).is_err() || w.body(a.body_b()).is_err() {
                    println!("  arbiter {:?} names a missing body", a.bodies());
                }
            }
        }
    }
}
