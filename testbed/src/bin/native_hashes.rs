//! Prints, as JSON, the state hash of every testbed scene after given frames,
//! computed natively by the same code the wasm module runs (no input, the
//! default 4 sub-steps, 1/60 s frames). scripts/testbed.sh writes it to
//! web/native-hashes.json; the page shows the native hash next to its own and
//! the browser check compares them.
//!
//! Also the hash at the end of the scripted drag (`drag_script`: a drag, a
//! throw, sub-step changes, a spawn), which the page plays through its
//! controls.
//!
//! Run: `cargo run --release --bin native_hashes [-- --out FILE]`.
//! Hashes are taken every 60 frames up to `live_frames` (600 for the small
//! scenes, the check's frame count for the huge ones) and at `check_frames`.

use std::process::ExitCode;
use std::time::Instant;

use arphysics_testbed::Testbed;

fn main() -> ExitCode {
    let mut out = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--out" => out = args.next(),
            _ => {
                eprintln!("usage: native_hashes [--out FILE]");
                return ExitCode::from(2);
            }
        }
    }
    let mut json = String::from("{\"substeps\":4,\"scenes\":{");
    let count = arphysics_testbed::scenes::all().len();
    for i in 0..count {
        let t0 = Instant::now();
        let mut tb = match Testbed::new(i, 4) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("scene {i}: {}", e.message);
                return ExitCode::FAILURE;
            }
        };
        let scene = tb.scenes()[i];
        let live = if scene.check_frames >= 120 { 600 } else { scene.check_frames };
        let last = live.max(scene.check_frames);
        let mut hashes = Vec::new();
        for f in 1..=last {
            if let Err(e) = tb.step() {
                eprintln!("{}: frame {f}: {}", scene.name, e.message);
                return ExitCode::FAILURE;
            }
            if f % 60 == 0 || f == scene.check_frames {
                hashes.push(format!("\"{f}\":\"{:016x}\"", tb.world().state_hash()));
            }
        }
        eprintln!(
            "{:<14} {:>5} frames in {:>7.1} ms (native, build included), {} bodies",
            scene.name,
            last,
            t0.elapsed().as_secs_f64() * 1e3,
            tb.world().body_count()
        );
        if i > 0 {
            json.push(',');
        }
        json.push_str(&format!(
            "\n\"{}\":{{\"check_frames\":{},\"live_frames\":{},\"hashes\":{{{}}}}}",
            scene.name,
            scene.check_frames,
            live,
            hashes.join(",")
        ));
    }
    // The scripted drag the browser check plays through the page's controls.
    let script = arphysics_testbed::drag_script();
    match Testbed::run_script(&script) {
        Ok(t) => json.push_str(&format!(
            "\n}},\"script\":{{\"scene\":\"{}\",\"frames\":{},\"hash\":\"{:016x}\"}}}}\n",
            script.scene,
            t.frame(),
            t.world().state_hash()
        )),
        Err(e) => {
            eprintln!("the scripted drag: {}", e.message);
            return ExitCode::FAILURE;
        }
    }
    match out {
        Some(path) => {
            if let Err(e) = std::fs::write(&path, &json) {
                eprintln!("native_hashes: cannot write {path}: {e}");
                return ExitCode::FAILURE;
            }
        }
        None => print!("{json}"),
    }
    ExitCode::SUCCESS
}
