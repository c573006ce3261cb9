//! The golden scenes on a bare-metal Cortex-M4: no `std`, no allocator, the
//! engine built with `default-features = false`. Runs the very scene code the
//! host test runs (`tests/golden_scenes/mod.rs`, included below), compares each
//! state hash with the same committed constant, prints the hashes through
//! semihosting and exits with status 0 when every scene matched, 1 otherwise
//! (also on a panic).
//!
//! Run (needs `qemu-system-arm`): `cargo run` or `cargo run --release` in this
//! directory; `scripts/golden-matrix.sh` at the repository root does it for both
//! profiles.

#![no_std]
#![no_main]

use core::panic::PanicInfo;

use cortex_m_rt::entry;
// cortex-m-semihosting's `hprintln!` wraps the format string in `concat!`, so
// its arguments must be passed explicitly (no inline `{name}` captures).
use cortex_m_semihosting::{debug, hprintln};

#[path = "../../../tests/golden_scenes/mod.rs"]
mod golden_scenes;

use golden_scenes::{Outcome, SceneError};

type Scene = (&'static str, fn() -> Result<Outcome, SceneError>, u64);

const SCENES: [Scene; 8] = [
    ("core scene", golden_scenes::core_scene, golden_scenes::GOLDEN_CORE_SCENE),
    ("pyramid", golden_scenes::pyramid, golden_scenes::GOLDEN_PYRAMID),
    ("mixed scene", golden_scenes::mixed, golden_scenes::GOLDEN_MIXED),
    ("long-running scene", golden_scenes::long_running, golden_scenes::GOLDEN_LONG),
    ("every-shape scene", golden_scenes::shapes, golden_scenes::GOLDEN_SHAPES),
    ("compound-body scene", golden_scenes::compound, golden_scenes::GOLDEN_COMPOUND),
    ("banded-tower", golden_scenes::banded_tower, golden_scenes::GOLDEN_BANDED),
    ("pivot net", golden_scenes::pivot_net, golden_scenes::GOLDEN_PIVOT_NET),
];

#[entry]
fn main() -> ! {
    let profile = if cfg!(debug_assertions) { "debug" } else { "release" };
    hprintln!("arphysics golden scenes on thumbv7em-none-eabihf ({})", profile);
    let mut failed = 0u32;
    for (name, run, golden) in SCENES {
        let t0 = centiseconds();
        let result = run();
        let secs = centiseconds().wrapping_sub(t0);
        match result {
            Ok(out) if out.hash == golden => {
                hprintln!("{}: {:#018x} ok ({}.{:02} s)", name, out.hash, secs / 100, secs % 100)
            }
            Ok(out) => {
                failed += 1;
                hprintln!("{}: {:#018x} MISMATCH, committed {:#018x} ({:?})", name, out.hash, golden, out);
            }
            Err(e) => {
                failed += 1;
                hprintln!("{}: FAILED {:?}", name, e);
            }
        }
    }
    let passed = SCENES.len() as u32 - failed;
    hprintln!("golden: {} passed, {} failed", passed, failed);
    debug::exit(if failed == 0 { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    halt()
}

/// The host's clock in centiseconds since QEMU started (semihosting SYS_CLOCK),
/// to report how long each scene took under emulation.
fn centiseconds() -> usize {
    // SAFETY: SYS_CLOCK takes no argument and only returns a number.
    unsafe { cortex_m_semihosting::syscall!(CLOCK) }
}

/// Only reached if the debugger ignored the exit request.
fn halt() -> ! {
    loop {
        cortex_m::asm::bkpt();
    }
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    halt()
}
