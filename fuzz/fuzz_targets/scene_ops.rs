//! No panic on any input: arbitrary worlds, bodies, joints, generators, handlers,
//! custom indexes and constraints, removals with stale handles, and steps with any
//! `dt`. Every call may return `Err`; none may panic (debug assertions and
//! overflow checks are on, see `fuzz/Cargo.toml`).
#![no_main]

use arphysics::{Storage, WorldBuffers};
use arphysics_fuzz::{Input, Outcome, Runner, MAX_OPS};
use libfuzzer_sys::fuzz_target;

fn run(runner: &mut Runner<'_>, input: &Input) {
    let before = runner.world.state_hash();
    let mut last_hash = before;
    for op in input.ops.iter().take(MAX_OPS) {
        let out = runner.apply(op);
        let hash = runner.world.state_hash();
        // A rejected call changes nothing (the crate's contract, `tests/bad_input.rs`).
        // A step that fails still runs no callbacks, so its world is unchanged too.
        if let Outcome::Err(e) = out {
            assert_eq!(hash, last_hash, "{op:?} returned {e:?} but changed the world");
        }
        last_hash = hash;
        if runner.exhausted() {
            break;
        }
    }
}

fuzz_target!(|input: Input| {
    // Heap storage sized by the input, or static buffers (the no-allocator path)
    // when the spec asks for an odd number of paths.
    if input.world.paths.is_multiple_of(2) {
        let storage =
            Storage::with_capacities(input.world.capacities()).expect("small capacities fit the heap");
        if let Ok(mut runner) = Runner::new(&input.world, storage) {
            run(&mut runner, &input);
        }
    } else {
        let mut buffers = Box::new(WorldBuffers::<12, 48, 8>::new());
        let runner = Runner::new(&input.world, buffers.storage());
        if let Ok(mut runner) = runner {
            run(&mut runner, &input);
        }
    }
});
