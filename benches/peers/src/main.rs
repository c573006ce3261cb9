//! Peer comparison: Box2D v3's benchmark scenes in arphysics, Box2D v3 (through
//! `boxdd`) and rapier2d, built from one engine-neutral description and run in one
//! process, one engine after another, on one thread.
//!
//! ```text
//! cargo run --release --manifest-path benches/peers/Cargo.toml -- [SCENE...] [mass_ratio]
//!     [--quick] [--engines=arphysics,box2d,rapier] [--budget=SECONDS]
//! ```
//!
//! Per scene and engine: build, warm up, then time samples of consecutive steps and
//! report the median ms/step. Full mode runs Box2D's step count for the scene (a tenth
//! as warm-up, the rest as 9 samples); `--quick` runs 5 warm-up steps and 5 samples
//! of 5 steps. An engine whose projected time for a scene exceeds the budget (default
//! 300 s) runs fewer samples, or none, and the table says so. `mass_ratio` (untimed)
//! runs issue 16's two-box stack at mass ratios 10:1 to 10,000:1 in each engine and
//! reports the largest each holds. With no scene named, everything runs. The
//! progress log goes to stderr; the report (markdown) to stdout.

mod engines;
mod scenes;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Instant, SystemTime, UNIX_EPOCH};

use engines::{ar::Ar, b2::B2, max_speed, rp::Rp, Engine, Which};
use scenes::Scene;

/// Counts live heap bytes so the report can give each Rust engine's memory (Box2D's
/// C allocations bypass it; Box2D reports its own count).
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to `System` unchanged and only counts sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: same contract as the caller's.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            LIVE.fetch_add(layout.size(), Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: same contract as the caller's.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            LIVE.fetch_add(layout.size(), Ordering::Relaxed);
        }
        p
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: same contract as the caller's.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
            LIVE.fetch_add(new_size, Ordering::Relaxed);
        }
        p
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Steps of the quality check on `large_pyramid` (full mode).
const QUALITY_STEPS: usize = 1000;

#[derive(Clone, Copy, Debug)]
struct Plan {
    warmup: usize,
    samples: usize,
    per_sample: usize,
}

impl Plan {
    fn for_scene(scene: &Scene, quick: bool) -> Self {
        if quick {
            Self { warmup: 5, samples: 5, per_sample: 5 }
        } else {
            let warmup = scene.steps / 10;
            Self { warmup, samples: 9, per_sample: (scene.steps - warmup) / 9 }
        }
    }

    fn timed_steps(self) -> usize {
        self.samples * self.per_sample
    }
}

#[derive(Clone, Debug)]
struct Quality {
    steps: usize,
    drift: f64,
    sag: f64,
    max_speed: f64,
}

#[derive(Clone, Debug, Default)]
struct Run {
    /// Median, min, max ms/step (wall clock) over the samples taken.
    median: Option<f64>,
    /// Median thread CPU ms/step over the same samples.
    cpu_median: Option<f64>,
    min: f64,
    max: f64,
    samples: usize,
    /// ms/step over the warm-up (the estimate used against the budget).
    warmup_ms: f64,
    build_s: f64,
    contacts: usize,
    steps_run: usize,
    heap_bytes: usize,
    /// The scene's tracked body (`Scene::top_body`) at the end, to compare engines.
    end: Option<(f64, f64)>,
    quality: Option<Quality>,
    note: Option<String>,
    error: Option<String>,
}

fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1000.0
}

/// CPU time this thread has used, ms (`CLOCK_THREAD_CPUTIME_ID`): on a shared machine
/// it leaves out the time the thread waited for a core.
fn thread_cpu_ms() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &raw mut ts) };
    if rc != 0 {
        return f64::NAN;
    }
    ts.tv_sec as f64 * 1000.0 + ts.tv_nsec as f64 / 1e6
}

/// Median of a sorted, non-empty slice (the upper middle for an even length).
fn median(sorted: &[f64]) -> Option<f64> {
    sorted.get(sorted.len() / 2).copied()
}

fn run_engine<E: Engine>(scene: &Scene, plan: Plan, budget_s: f64, quality_steps: Option<usize>) -> Run {
    let mut r = Run::default();
    match run_inner::<E>(scene, plan, budget_s, quality_steps, &mut r) {
        Ok(()) => r,
        Err(e) => Run { error: Some(e), ..r },
    }
}

/// One step, counted; an error names the step it happened in.
fn step<E: Engine>(e: &mut E, r: &mut Run) -> Result<(), String> {
    e.step().map_err(|m| format!("{m} (in step {})", r.steps_run + 1))?;
    r.steps_run += 1;
    Ok(())
}

fn run_inner<E: Engine>(
    scene: &Scene,
    plan: Plan,
    budget_s: f64,
    quality_steps: Option<usize>,
    r: &mut Run,
) -> Result<(), String> {
    let heap0 = LIVE.load(Ordering::Relaxed);
    let t = Instant::now();
    let mut e = E::build(scene)?;
    r.build_s = t.elapsed().as_secs_f64();
    let top0 = e.body(scene.top_body)?;

    let t = Instant::now();
    for _ in 0..plan.warmup {
        step(&mut e, r)?;
    }
    r.warmup_ms = ms_since(t) / plan.warmup.max(1) as f64;

    // Fit the samples into the budget.
    let budget_ms = budget_s * 1000.0;
    let sample_ms = r.warmup_ms * plan.per_sample as f64;
    let affordable = if sample_ms > 0.0 { (budget_ms / sample_ms).floor() as usize } else { plan.samples };
    let samples = plan.samples.min(affordable);
    if samples < plan.samples {
        r.note = Some(if samples == 0 {
            format!(
                "not timed: {} steps at ≈{:.0} ms/step (warm-up) would take ≈{:.0} s > budget {budget_s:.0} s",
                plan.timed_steps(),
                r.warmup_ms,
                r.warmup_ms * plan.timed_steps() as f64 / 1000.0
            )
        } else {
            format!("{samples} of {} samples (budget {budget_s:.0} s)", plan.samples)
        });
    }

    let mut times = Vec::with_capacity(samples);
    let mut cpu = Vec::with_capacity(samples);
    for _ in 0..samples {
        let c = thread_cpu_ms();
        let t = Instant::now();
        for _ in 0..plan.per_sample {
            step(&mut e, r)?;
        }
        times.push(ms_since(t) / plan.per_sample as f64);
        cpu.push((thread_cpu_ms() - c) / plan.per_sample as f64);
    }
    times.sort_by(f64::total_cmp);
    cpu.sort_by(f64::total_cmp);
    r.samples = times.len();
    if let (Some(lo), Some(hi)) = (times.first(), times.last()) {
        r.min = *lo;
        r.max = *hi;
    }
    r.median = median(&times);
    r.cpu_median = median(&cpu);

    if let Some(q) = quality_steps {
        let per_step = r.median.unwrap_or(r.warmup_ms);
        let more = q.saturating_sub(r.steps_run);
        if per_step * more as f64 <= budget_ms {
            for _ in 0..more {
                step(&mut e, r)?;
            }
            let top = e.body(scene.top_body)?;
            r.quality = Some(Quality {
                steps: r.steps_run,
                drift: top.x - top0.x,
                sag: top0.y - top.y,
                max_speed: max_speed(&mut e, scene)?,
            });
        } else {
            let extra = format!("quality check skipped: {more} more steps exceed the budget");
            r.note = Some(r.note.take().map_or(extra.clone(), |n| format!("{n}; {extra}")));
        }
    }
    let end = e.body(scene.top_body)?;
    r.end = Some((end.x, end.y));
    r.contacts = e.contact_count();
    r.heap_bytes =
        e.native_heap_bytes().unwrap_or_else(|| LIVE.load(Ordering::Relaxed).saturating_sub(heap0));
    Ok(())
}

fn machine() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info
        .lines()
        .find_map(|l| l.strip_prefix("model name").and_then(|r| r.split_once(':')).map(|(_, m)| m.trim()))
        .unwrap_or("unknown CPU")
        .to_owned();
    let cores = info.lines().filter(|l| l.starts_with("processor")).count();
    format!("{model}, {cores} cores (/proc/cpuinfo)")
}

/// The 1, 5 and 15 minute load averages (the machine is shared).
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".to_owned())
}

/// Today's date (UTC), from the civil-from-days algorithm.
fn today() -> String {
    let secs = SystemTime::now().duration_since(UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

fn fmt_ms(r: Option<&Run>) -> String {
    match r {
        None => "–".to_owned(),
        Some(r) if r.error.is_some() => "error".to_owned(),
        Some(r) => match r.median {
            Some(m) => format!("{m:.3}"),
            None => format!("(≈{:.0}, warm-up only)", r.warmup_ms),
        },
    }
}

fn fmt_cpu(r: Option<&Run>) -> String {
    match r.and_then(|r| r.cpu_median) {
        Some(m) => format!("{m:.3}"),
        None => "–".to_owned(),
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.1}×", a / b),
        _ => "–".to_owned(),
    }
}

fn memory_report(large: &Scene) {
    // The solver's records are internal; `Storage` publishes the bytes per slot,
    // and the solver's share is what remains beside the public records.
    use arphysics::{Arbiter, Body, Proxy, Slot, Storage};
    use std::mem::size_of;
    let body = size_of::<Slot<Body>>();
    // Broad-phase scratch: the proxy, its body slot, the sweep order.
    let proxy = size_of::<Proxy>() + 2 * size_of::<u32>();
    let arbiter = size_of::<Arbiter>();
    let pair = size_of::<(u32, u32)>();
    let path = Storage::BYTES_PER_PATH;
    let joint = Storage::BYTES_PER_JOINT;
    let per_body = Storage::BYTES_PER_BODY;
    let per_contact = Storage::BYTES_PER_CONTACT;
    let solver_body = per_body.saturating_sub(body + proxy);
    let constraint = per_contact.saturating_sub(2 * arbiter + pair);
    let c = engines::ar::capacities(large);
    let total = c.bodies * per_body + c.paths * path + c.contacts * per_contact + c.joints * joint;
    let world = size_of::<arphysics::World<'static>>();
    println!("\n## arphysics memory (record sizes on this target)\n");
    println!("| record | bytes |");
    println!("|---|---|");
    println!("| `Slot<Body>` | {body} |");
    println!("| broad-phase scratch per body (`Proxy` + body slot `u32` + sweep order `u32`) | {proxy} |");
    println!("| solver's copy of the body (the rest of `Storage::BYTES_PER_BODY`) | {solver_body} |");
    println!("| **per body** (`Storage::BYTES_PER_BODY`) | **{per_body}** |");
    println!("| `Arbiter` | {arbiter} |");
    println!("| solver's contact constraint (the rest of `Storage::BYTES_PER_CONTACT`) | {constraint} |");
    println!(
        "| **per contact** (2 × `Arbiter`: current and next buffer, + candidate pair + constraint) | **{per_contact}** |"
    );
    println!("| per shared polygon path (`Storage::BYTES_PER_PATH`) | {path} |");
    println!("| per joint (`Storage::BYTES_PER_JOINT`) | {joint} |");
    println!("| `World` itself (inline hooks, handles to the stores) | {world} |");
    println!(
        "\nlarge_pyramid storage: Capacities {{ bodies: {}, paths: {}, contacts: {}, joints: {} }} → \
         {} × {per_body} + {} × {path} + {} × {per_contact} + {} × {joint} = {total} bytes ({:.2} MiB)",
        c.bodies,
        c.paths,
        c.contacts,
        c.joints,
        c.bodies,
        c.paths,
        c.contacts,
        c.joints,
        total as f64 / (1024.0 * 1024.0)
    );
}

/// The two-box stack at every ratio of [`scenes::MASS_RATIOS`]: the top box's sink
/// after [`scenes::MASS_RATIO_STEPS`] steps (m), or why the run failed.
fn mass_ratio_scan<E: Engine>() -> Vec<Result<f64, String>> {
    scenes::MASS_RATIOS
        .iter()
        .map(|&ratio| {
            let scene = scenes::two_box_stack(ratio);
            let mut e = E::build(&scene)?;
            let y0 = e.body(scene.top_body)?.y;
            for _ in 0..scene.steps {
                e.step()?;
            }
            Ok(y0 - e.body(scene.top_body)?.y)
        })
        .collect()
}

/// The largest ratio that holds with every smaller one holding too, if any.
fn largest_ratio_held(sinks: &[Result<f64, String>]) -> Option<f64> {
    scenes::MASS_RATIOS
        .iter()
        .zip(sinks)
        .take_while(|(_, s)| s.as_ref().is_ok_and(|&s| s <= scenes::MASS_RATIO_MAX_SINK))
        .last()
        .map(|(r, _)| *r)
}

fn mass_ratio_report(engines: &[Which]) {
    let scans: Vec<(Which, Vec<Result<f64, String>>)> = engines
        .iter()
        .map(|&w| {
            eprintln!("two_box_stack / {}: {} ratios…", w.label(), scenes::MASS_RATIOS.len());
            let scan = match w {
                Which::Arphysics => mass_ratio_scan::<Ar>(),
                Which::Box2d => mass_ratio_scan::<B2>(),
                Which::Rapier => mass_ratio_scan::<Rp>(),
            };
            (w, scan)
        })
        .collect();
    println!(
        "\n## Quality: two-box stack mass ratio (issue 16)\n\n\
         A 1 kg box of 1 m on the ground, a 1 m box of `ratio` kg on it, friction 0.6, {} steps \
         (10 s): the top box's sink (m). It holds when the sink is ≤ {} m.\n",
        scenes::MASS_RATIO_STEPS,
        scenes::MASS_RATIO_MAX_SINK
    );
    let header: Vec<&str> = scans.iter().map(|(w, _)| w.label()).collect();
    println!("| top : bottom mass | {} |", header.join(" | "));
    println!("|---|{}", "---|".repeat(scans.len()));
    for (i, ratio) in scenes::MASS_RATIOS.iter().enumerate() {
        let cells: Vec<String> = scans
            .iter()
            .map(|(_, scan)| match scan.get(i) {
                Some(Ok(sink)) => {
                    let mark = if *sink <= scenes::MASS_RATIO_MAX_SINK { "" } else { " ✗" };
                    format!("{sink:.4}{mark}")
                }
                Some(Err(e)) => format!("error: {e}"),
                None => "–".to_owned(),
            })
            .collect();
        println!("| {ratio}:1 | {} |", cells.join(" | "));
    }
    let held: Vec<String> = scans
        .iter()
        .map(|(_, scan)| largest_ratio_held(scan).map_or_else(|| "none".to_owned(), |r| format!("{r}:1")))
        .collect();
    println!("| **largest ratio held** | {} |", held.join(" | "));
}

struct Args {
    scenes: Vec<String>,
    /// Run the two-box stack mass-ratio scan (`mass_ratio`; on by default).
    mass_ratio: bool,
    quick: bool,
    engines: Vec<Which>,
    budget_s: f64,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        scenes: Vec::new(),
        mass_ratio: false,
        quick: false,
        engines: Which::ALL.to_vec(),
        budget_s: 300.0,
    };
    for arg in std::env::args().skip(1) {
        if arg == "--quick" {
            a.quick = true;
        } else if let Some(v) = arg.strip_prefix("--budget=") {
            a.budget_s = v.parse().map_err(|_| format!("bad --budget value {v:?}"))?;
        } else if let Some(v) = arg.strip_prefix("--engines=") {
            a.engines = Which::ALL.iter().copied().filter(|w| v.split(',').any(|k| k == w.key())).collect();
            if a.engines.is_empty() {
                return Err(format!("no engine in {v:?} (arphysics, box2d, rapier)"));
            }
        } else if arg == "-h" || arg == "--help" {
            return Err(String::new());
        } else if scenes::NAMES.contains(&arg.as_str()) {
            a.scenes.push(arg);
        } else if arg == "mass_ratio" {
            a.mass_ratio = true;
        } else {
            return Err(format!("unknown argument {arg:?}"));
        }
    }
    if a.scenes.is_empty() && !a.mass_ratio {
        a.scenes = scenes::NAMES.iter().map(|s| (*s).to_owned()).collect();
        a.mass_ratio = true;
    }
    Ok(a)
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("{e}");
            }
            eprintln!(
                "usage: peers [SCENE...] [mass_ratio] [--quick] [--engines=arphysics,box2d,rapier] [--budget=SECONDS]\n\
                 scenes: {}; mass_ratio: the two-box stack scan (all run when none is named)",
                scenes::NAMES.join(", ")
            );
            std::process::exit(2);
        }
    };
    let started = Instant::now();
    let load_start = load_average();
    let mut rows = Vec::new();
    for name in &args.scenes {
        let Some(scene) = scenes::by_name(name) else { continue };
        let plan = Plan::for_scene(&scene, args.quick);
        let quality = (scene.name == "large_pyramid").then_some(if args.quick {
            plan.warmup + plan.timed_steps()
        } else {
            QUALITY_STEPS
        });
        let mut runs: Vec<(Which, Run)> = Vec::new();
        for &w in &args.engines {
            eprintln!(
                "[{:>6.1} s] {} / {}: warm-up {} steps, {} samples of {} steps…",
                started.elapsed().as_secs_f64(),
                scene.name,
                w.label(),
                plan.warmup,
                plan.samples,
                plan.per_sample
            );
            let r = match w {
                Which::Arphysics => run_engine::<Ar>(&scene, plan, args.budget_s, quality),
                Which::Box2d => run_engine::<B2>(&scene, plan, args.budget_s, quality),
                Which::Rapier => run_engine::<Rp>(&scene, plan, args.budget_s, quality),
            };
            eprintln!(
                "           → median {} ms/step (build {:.2} s, {} steps{}{})",
                fmt_ms(Some(&r)),
                r.build_s,
                r.steps_run,
                r.note.as_deref().map(|n| format!("; {n}")).unwrap_or_default(),
                r.error.as_deref().map(|e| format!("; ERROR {e}")).unwrap_or_default(),
            );
            runs.push((w, r));
        }
        rows.push((scene, plan, runs));
    }

    let find = |runs: &[(Which, Run)], w: Which| runs.iter().find(|(k, _)| *k == w).map(|(_, r)| r.clone());

    println!("# arphysics peer comparison\n");
    println!("- date: {} (UTC)", today());
    println!("- machine: {}", machine());
    println!("- load average at start / end: {load_start} / {}", load_average());
    println!(
        "- mode: {}; one thread; step 1/60 s, 4 sub-steps, gravity (0, −10), sleeping off everywhere",
        if args.quick {
            "--quick (5 warm-up steps, 5 samples of 5 steps)"
        } else {
            "full (Box2D's step count per scene: a tenth warm-up, then 9 samples)"
        }
    );
    // `--features avx2` builds Box2D with its AVX2 solver (boxdd's `simd-avx2`);
    // the Rust engines follow RUSTFLAGS (e.g. `-C target-cpu=native`).
    let box2d_build = if cfg!(feature = "avx2") { "AVX2 build (`simd-avx2`)" } else { "default SSE2 build" };
    let rust_cpu = if cfg!(target_feature = "avx2") {
        "Rust code built with AVX2 enabled (target-cpu)"
    } else {
        "Rust code for the default x86-64 target (SSE2; arphysics dispatches its contact kernels to AVX2 at run time)"
    };
    println!(
        "- engines: arphysics (Q32.32 fixed point, `Index::Auto` = sort-and-sweep broad phase, 4 sub-steps); \
         Box2D v3 via boxdd 0.6 (vendored C, {box2d_build}, 1 worker, continuous on, 4 sub-steps); \
         rapier2d 0.36 (f32, default features, IntegrationParameters default: 4 solver iterations \
         = 4 sub-steps, 1 PGS + 1 stabilisation iteration each); {rust_cpu}"
    );
    println!("- ms/step = wall clock, median over the samples; ratio = arphysics ÷ peer (how many times slower arphysics is)\n");
    println!("| scene | bodies | arphysics ms/step | Box2D v3 ms/step | rapier2d ms/step | ratio vs Box2D | ratio vs rapier |");
    println!("|---|---|---|---|---|---|---|");
    for (scene, _, runs) in &rows {
        let a = find(runs, Which::Arphysics);
        let b = find(runs, Which::Box2d);
        let r = find(runs, Which::Rapier);
        let dynamic = scene.bodies.iter().filter(|b| b.dynamic).count();
        println!(
            "| {} | {dynamic} | {} | {} | {} | {} | {} |",
            scene.name,
            fmt_ms(a.as_ref()),
            fmt_ms(b.as_ref()),
            fmt_ms(r.as_ref()),
            ratio(a.as_ref().and_then(|x| x.median), b.as_ref().and_then(|x| x.median)),
            ratio(a.as_ref().and_then(|x| x.median), r.as_ref().and_then(|x| x.median))
        );
    }

    println!("\nThe same samples in thread CPU time (leaves out the time the thread waited for a core on this shared machine):\n");
    println!("| scene | bodies | arphysics CPU ms/step | Box2D v3 CPU ms/step | rapier2d CPU ms/step | ratio vs Box2D | ratio vs rapier |");
    println!("|---|---|---|---|---|---|---|");
    for (scene, _, runs) in &rows {
        let a = find(runs, Which::Arphysics);
        let b = find(runs, Which::Box2d);
        let r = find(runs, Which::Rapier);
        let dynamic = scene.bodies.iter().filter(|b| b.dynamic).count();
        println!(
            "| {} | {dynamic} | {} | {} | {} | {} | {} |",
            scene.name,
            fmt_cpu(a.as_ref()),
            fmt_cpu(b.as_ref()),
            fmt_cpu(r.as_ref()),
            ratio(a.as_ref().and_then(|x| x.cpu_median), b.as_ref().and_then(|x| x.cpu_median)),
            ratio(a.as_ref().and_then(|x| x.cpu_median), r.as_ref().and_then(|x| x.cpu_median))
        );
    }

    println!("\n## Details\n");
    println!("| scene | engine | median | min | max | samples × steps | warm-up ms/step | build s | contacts at end | tracked body at end (x, y) | heap MiB at end | note |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (scene, plan, runs) in &rows {
        for (w, r) in runs {
            let heap = format!("{:.1}", r.heap_bytes as f64 / 1_048_576.0);
            let end = r.end.map(|(x, y)| format!("({x:.2}, {y:.2})")).unwrap_or_default();
            let note = match (&r.error, &r.note) {
                (Some(e), _) => format!("ERROR: {e}"),
                (None, Some(n)) => n.clone(),
                (None, None) => String::new(),
            };
            println!(
                "| {} | {} | {} | {:.3} | {:.3} | {} × {} | {:.3} | {:.2} | {} | {end} | {heap} | {note} |",
                scene.name,
                w.label(),
                fmt_ms(Some(r)),
                r.min,
                r.max,
                r.samples,
                plan.per_sample,
                r.warmup_ms,
                r.build_s,
                r.contacts,
            );
        }
    }

    let quality: Vec<_> = rows
        .iter()
        .flat_map(|(s, _, runs)| runs.iter().map(move |(w, r)| (s, w, r)))
        .filter_map(|(s, w, r)| r.quality.as_ref().map(|q| (s.name, *w, q.clone())))
        .collect();
    if !quality.is_empty() {
        println!("\n## Quality: large_pyramid (top box starts at (0, 99.5))\n");
        println!("| engine | steps | top-box drift x (m) | top-box sag (m) | largest speed (m/s) |");
        println!("|---|---|---|---|---|");
        for (_, w, q) in &quality {
            println!("| {} | {} | {:+.4} | {:.4} | {:.4} |", w.label(), q.steps, q.drift, q.sag, q.max_speed);
        }
    }

    if args.mass_ratio {
        mass_ratio_report(&args.engines);
    }

    if let Some(large) = scenes::by_name("large_pyramid") {
        memory_report(&large);
    }
    println!("\ntotal run time: {:.1} s", started.elapsed().as_secs_f64());
}
