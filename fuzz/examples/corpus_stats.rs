//! What a corpus exercises: decodes each file as the fuzz targets do, runs it, and
//! counts outcomes per kind of op (`cargo run --release --example corpus_stats -- DIR`).

use std::collections::BTreeMap;

use arbitrary::{Arbitrary, Unstructured};
use arphysics::Storage;
use arphysics_fuzz::{Input, Outcome, Runner, MAX_OPS};

fn main() {
    let mut counts: BTreeMap<String, (u64, u64)> = BTreeMap::new();
    let (mut files, mut worlds, mut max_bodies, mut arbiters, mut steps_ok) = (0, 0, 0, 0u64, 0u64);
    for dir in std::env::args().skip(1) {
        for entry in std::fs::read_dir(&dir).expect("dir") {
            let bytes = std::fs::read(entry.expect("entry").path()).expect("read");
            files += 1;
            let Ok(input) = Input::arbitrary_take_rest(Unstructured::new(&bytes)) else { continue };
            let Ok(mut r) = Runner::new(
                &input.world,
                Storage::with_capacities(input.world.capacities()).expect("small capacities fit the heap"),
            ) else {
                continue;
            };
            worlds += 1;
            for op in input.ops.iter().take(MAX_OPS) {
                let name = format!("{op:?}").split(['(', ' ', '{']).next().unwrap_or("?").to_string();
                let out = r.apply(op);
                let e = counts.entry(name).or_default();
                e.0 += 1;
                if !matches!(out, Outcome::Err(_)) {
                    e.1 += 1;
                }
                match out {
                    Outcome::Step(_) | Outcome::Steps(..) => {
                        steps_ok += 1;
                        arbiters += r.world.arbiters().count() as u64;
                    }
                    _ => {}
                }
                max_bodies = max_bodies.max(r.world.body_count());
                if r.exhausted() {
                    break;
                }
            }
        }
    }
    println!("{files} files, {worlds} valid worlds, most bodies {max_bodies}, {steps_ok} good steps, {arbiters} arbiter-steps");
    for (k, (n, ok)) in counts {
        println!("{k:22} {n:8} calls {ok:8} ok");
    }
}
