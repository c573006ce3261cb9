//! Picks a small seed corpus: greedily the inputs that add the most behaviours
//! not seen yet (each kind of op that succeeded, each kind that failed, contacts,
//! joints, snapshots, restores), preferring short inputs; inputs over 2 KB are
//! skipped.
//!
//! `cargo run --release --example pick_seeds -- scene|snapshot N OUT_DIR IN_DIR...`

use std::collections::BTreeSet;

use arbitrary::{Arbitrary, Unstructured};
use arphysics::Storage;
use arphysics_fuzz::{Input, Outcome, Runner, SnapshotInput, MAX_OPS};

fn behaviours(input: &Input) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let Ok(mut r) = Runner::new(
        &input.world,
        Storage::with_capacities(input.world.capacities()).expect("small capacities fit the heap"),
    ) else {
        return seen;
    };
    for op in input.ops.iter().take(MAX_OPS) {
        let name = format!("{op:?}").split(['(', ' ', '{']).next().unwrap_or("?").to_string();
        let out = r.apply(op);
        match out {
            Outcome::Err(e) => {
                let e = format!("{e:?}");
                seen.insert(format!("{name} err {}", e.split(['(', ' ', '{']).next().unwrap_or("?")));
            }
            _ => {
                seen.insert(format!("{name} ok"));
            }
        }
        let arbiters = r.world.arbiters().count();
        if arbiters > 0 {
            seen.insert(format!("arbiters>={}", arbiters.min(8)));
        }
        if r.world.joints().count() > 0 {
            seen.insert("joints".into());
        }
        if r.world.out_of_bounds_bodies().count() > 0 {
            seen.insert("out of bounds".into());
        }
        seen.insert(format!("bodies>={}", r.world.body_count().min(16) / 4 * 4));
        if r.exhausted() {
            break;
        }
    }
    seen
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (kind, n, out) = (&args[0], args[1].parse::<usize>().expect("N"), &args[2]);
    let mut cands = Vec::new();
    for dir in &args[3..] {
        for e in std::fs::read_dir(dir).expect("dir") {
            let path = e.expect("entry").path();
            let bytes = std::fs::read(&path).expect("read");
            if bytes.len() > 2048 {
                continue; // keep the committed corpus small
            }
            let u = Unstructured::new(&bytes);
            let b = if kind == "snapshot" {
                match SnapshotInput::arbitrary_take_rest(u) {
                    Ok(i) => {
                        let mut b = behaviours(&i.scene);
                        b.insert(format!("corruptions {}", i.corruptions.len().min(3)));
                        b
                    }
                    Err(_) => continue,
                }
            } else {
                match Input::arbitrary_take_rest(u) {
                    Ok(i) => behaviours(&i),
                    Err(_) => continue,
                }
            };
            cands.push((path, bytes.len(), b));
        }
    }
    cands.sort_by_key(|c| c.1);
    let mut covered = BTreeSet::new();
    std::fs::create_dir_all(out).expect("out dir");
    for _ in 0..n {
        let best = cands
            .iter()
            .enumerate()
            .map(|(i, c)| (c.2.difference(&covered).count(), std::cmp::Reverse(c.1), i))
            .max();
        let Some((gain, _, i)) = best else { break };
        if gain == 0 {
            break;
        }
        let (path, len, b) = cands.swap_remove(i);
        covered.extend(b);
        let name = path.file_name().expect("name").to_string_lossy().to_string();
        std::fs::copy(&path, format!("{out}/{name}")).expect("copy");
        println!("{name}: {len} bytes, +{gain} behaviours");
    }
    println!("{} behaviours covered", covered.len());
}
