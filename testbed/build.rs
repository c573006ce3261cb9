//! Makes the demo's scenes (examples/demo/scenes.rs) usable here without a copy:
//! the file is included as it is, except that the one call creating a scene's
//! world goes through `crate::scene_world`, which applies the testbed's sub-step
//! count and adds room for spawned bodies and the drag joint. Inner doc comments
//! (`//!`) become plain comments so the text can be `include!`d.

use std::{env, fs, path::PathBuf};

const CALL: &str = "World::with_capacities(WorldDef::with_bounds(bounds), capacities)";

fn main() {
    let src = PathBuf::from(env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"))
        .join("../examples/demo/scenes.rs");
    println!("cargo:rerun-if-changed={}", src.display());
    let text = fs::read_to_string(&src).expect("examples/demo/scenes.rs is readable");
    assert_eq!(
        text.matches(CALL).count(),
        1,
        "examples/demo/scenes.rs no longer creates its worlds with `{CALL}`: update testbed/build.rs"
    );
    let text = text.replace(CALL, "crate::scene_world(bounds, capacities)");
    let text: String = text
        .lines()
        .map(|l| match l.strip_prefix("//!") {
            Some(rest) => format!("//{rest}\n"),
            None => format!("{l}\n"),
        })
        .collect();
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets it")).join("demo_scenes.rs");
    fs::write(out, text).expect("OUT_DIR is writable");
}
