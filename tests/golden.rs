//! Golden state hashes: canonical scenes stepped N times must hash to committed
//! constants, in debug and release, on every target of the contract
//! (`scripts/golden-matrix.sh` runs this file on x86_64, i686, aarch64, armv7,
//! s390x big-endian and wasm32-wasip1, and the same scenes on a Cortex-M4). A
//! change to a constant must be deliberate and explained in its commit message.
//!
//! The scenes live in `golden_scenes/mod.rs`, which the bare-metal Cortex-M4
//! binary (`cross/cortex-m4`) includes too: no `std`, no allocation.

mod golden_scenes;

use golden_scenes::{
    Outcome, GOLDEN_BANDED, GOLDEN_COMPOUND, GOLDEN_CORE_SCENE, GOLDEN_LONG, GOLDEN_MIXED, GOLDEN_PIVOT_NET,
    GOLDEN_PYRAMID, GOLDEN_SHAPES,
};

fn report(name: &str, steps: u32, out: &Outcome) {
    // The level the contact kernels ran at (the same bits at every level).
    let level = arphysics::simd_level();
    println!("{name} hash after {steps} steps: {:#018x} ({out:?}, kernels {level:?})", out.hash);
}

#[test]
fn core_scene_hash_after_600_steps_is_the_committed_constant() {
    let out = golden_scenes::core_scene().expect("core scene");
    report("core scene", golden_scenes::CORE_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_CORE_SCENE);
}

#[test]
fn pyramid_hash_is_the_committed_constant() {
    let out = golden_scenes::pyramid().expect("pyramid");
    report("pyramid", golden_scenes::PYRAMID_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_PYRAMID);
}

#[test]
fn banded_tower_hash_is_the_committed_constant() {
    let out = golden_scenes::banded_tower().expect("banded tower");
    report("banded-tower", golden_scenes::BANDED_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_BANDED);
}

#[test]
fn pivot_net_hash_is_the_committed_constant() {
    let out = golden_scenes::pivot_net().expect("pivot net");
    report("pivot net", golden_scenes::NET_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_PIVOT_NET);
}

#[test]
fn mixed_scene_hash_after_600_steps_is_the_committed_constant() {
    let out = golden_scenes::mixed().expect("mixed scene");
    report("mixed scene", golden_scenes::MIXED_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_MIXED);
}

#[test]
fn long_running_scene_hash_after_2000_steps_is_the_committed_constant() {
    let out = golden_scenes::long_running().expect("long-running scene");
    report("long-running scene", golden_scenes::LONG_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_LONG);
}

#[test]
fn every_shape_scene_hash_is_the_committed_constant() {
    let out = golden_scenes::shapes().expect("every-shape scene");
    report("every-shape scene", golden_scenes::SHAPES_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_SHAPES);
}

#[test]
fn compound_body_scene_hash_is_the_committed_constant() {
    let out = golden_scenes::compound().expect("compound-body scene");
    report("compound-body scene", golden_scenes::COMPOUND_STEPS, &out);
    assert_eq!(out.hash, GOLDEN_COMPOUND);
}
