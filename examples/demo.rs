//! See it work: builds a scene, steps it at 1/60 s, and writes an animated SVG
//! of it (open it in a browser). Prints the stepping speed (wall clock around
//! `World::step` only) and the final state hash, which is the same on every
//! machine, in debug and release.
//!
//! Run: `cargo run --release --example demo [SCENE] [--out FILE.svg] [--seconds N] [--every K]`
//! * `SCENE`: `default` (a pyramid, a chain on pivots, falling mixed shapes, a
//!   bouncing ball), `pyramid`, `chain` or `rain`; `--list` lists them.
//! * `--out`: where to write the picture (default `docs/demo-SCENE.svg` in the
//!   crate).
//! * `--seconds`: simulated time (default per scene, 6 s for `default`).
//! * `--every`: record every K-th step, K dividing 60 (default 2: a 30 Hz
//!   animation; SMIL interpolates between the records).
//!
//! The scenes are built in fixed point from integers; floats are used only to
//! draw (`to_f64`) and to report timings.

#[path = "demo/scenes.rs"]
mod scenes;
#[path = "demo/svg.rs"]
mod svg;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use arphysics::Scalar;

use scenes::SCENES;

struct Options {
    scene: String,
    out: Option<PathBuf>,
    seconds: Option<u32>,
    every: u32,
}

fn usage() -> String {
    let mut u =
        String::from("usage: demo [SCENE] [--out FILE.svg] [--seconds N] [--every K] [--list]\nscenes:\n");
    for s in SCENES {
        u.push_str(&format!("  {:<8} {} ({} s)\n", s.name, s.about, s.seconds));
    }
    u
}

fn parse() -> Result<Option<Options>, String> {
    let mut o = Options { scene: "default".into(), out: None, seconds: None, every: 2 };
    let mut args = std::env::args().skip(1);
    let mut named = false;
    while let Some(a) = args.next() {
        let mut value = |what: &str| args.next().ok_or(format!("{what} needs a value"));
        match a.as_str() {
            "--list" | "--help" | "-h" => {
                print!("{}", usage());
                return Ok(None);
            }
            "--out" => o.out = Some(PathBuf::from(value("--out")?)),
            "--seconds" => {
                let n = value("--seconds")?.parse().map_err(|_| "--seconds takes a whole number")?;
                if !(1..=120).contains(&n) {
                    return Err("--seconds must be 1 to 120".into());
                }
                o.seconds = Some(n);
            }
            "--every" => {
                let n = value("--every")?.parse().map_err(|_| "--every takes a whole number")?;
                if !(1..=60).contains(&n) || 60 % n != 0 {
                    return Err("--every must divide 60 (1, 2, 3, 4, 5, 6, 10, 12, 15, 20, 30 or 60)".into());
                }
                o.every = n;
            }
            s if s.starts_with('-') => return Err(format!("unknown option {s}")),
            s if !named => {
                o.scene = s.to_string();
                named = true;
            }
            s => return Err(format!("one scene at a time (got {s} too)")),
        }
    }
    Ok(Some(o))
}

fn run(o: &Options) -> Result<(), Box<dyn std::error::Error>> {
    let scene = SCENES
        .iter()
        .find(|s| s.name == o.scene)
        .ok_or_else(|| format!("no scene named {:?}\n{}", o.scene, usage()))?;
    let seconds = o.seconds.unwrap_or(scene.seconds);
    let steps = seconds * 60;
    let dt = Scalar::ONE / 60;

    let mut running = (scene.build)()?;
    let title = format!("arphysics · {} · {} s at 60 Hz, fixed point (Q32.32)", scene.name, seconds);
    let mut recorder = svg::Recorder::new(scene.view, title, f64::from(o.every) / 60.0);
    recorder.sample(&running.world);
    let mut stepping = Duration::ZERO;
    let mut most_bodies = 0;
    for frame in 0..steps {
        running.before_step(frame)?;
        let t = Instant::now();
        running.world.step(dt)?;
        stepping += t.elapsed();
        most_bodies = most_bodies.max(running.world.body_count());
        if (frame + 1) % o.every == 0 {
            recorder.sample(&running.world);
        }
    }
    let world = &running.world;
    let secs = stepping.as_secs_f64();
    println!(
        "scene {}: {} bodies, {} joints, {} contact pairs at the end",
        scene.name,
        most_bodies,
        world.joints().count(),
        world.arbiters().count()
    );
    println!(
        "{steps} steps in {secs:.3} s of stepping: {:.0} steps/s ({:.3} ms/step){}",
        f64::from(steps) / secs,
        secs * 1000.0 / f64::from(steps),
        if cfg!(debug_assertions) { " (debug build)" } else { "" }
    );
    println!("final state hash {:#018x}", world.state_hash());

    let out = o.out.clone().unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs").join(format!("demo-{}.svg", scene.name))
    });
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let picture = recorder.svg(&format!("final state hash {:#018x}", world.state_hash()));
    std::fs::write(&out, &picture)?;
    println!("wrote {} ({} KB): open it in a browser", out.display(), picture.len().div_ceil(1024));
    Ok(())
}

fn main() -> ExitCode {
    match parse() {
        Ok(None) => ExitCode::SUCCESS,
        Ok(Some(o)) => match run(&o) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("demo: {e}");
                ExitCode::FAILURE
            }
        },
        Err(e) => {
            eprintln!("demo: {e}\n{}", usage());
            ExitCode::from(2)
        }
    }
}
