//! Issue 16's quality scenes: what the lane solver must do at least as well as
//! today's, and better where today's falls short.
//!
//! * a row of five touching equal balls struck by a sixth (momentum transfer
//!   along a chain of contacts);
//! * 100 circles created at one point (push-out speed under extreme overlap);
//! * a two-box stack of growing mass ratio (the heaviest box on top).
//!
//! Each scene prints its metrics beside the thresholds in the quality suite's
//! format (`tests/quality.rs`), e.g.
//!
//! ```text
//! quality cradle_5+1: far ball speed / striker speed 0.93 (≥ 0.8) [Box2D —]
//! ```
//!
//! and then asserts every threshold, which are exactly issue 16's. Scenes today's
//! solver misses are `#[ignore]`d with the measured value in the reason, so `main`
//! stays green until the solver meets them (the cradle passes since the impact
//! pass before the sub-steps, see `solver`, and the 100 circles since deep
//! overlaps are pushed out by motion). Run with
//! `cargo test --release --test quality_issue16 -- --include-ignored --nocapture`
//! to see every line, and
//! `cargo test --release --test quality_issue16 -- --ignored --nocapture mass_ratio_scan`
//! for the largest mass ratio the two-box stack holds.

use arphysics::{BodyDef, BodyHandle, PolygonPath, World};

// ---- units and scene helpers -------------------------------------------------

/// A static `width` × 2 m ground box whose top is y = 0.
fn ground(w: &mut World<'static>, width: f64) -> BodyHandle {
    let path = w.add_path(PolygonPath::rectangle(s(width), s(2.0)).expect("ground")).expect("path");
    w.add_body(BodyDef::polygon(path).position(v(0.0, -1.0)).static_body()).expect("ground body")
}

/// A closed static box of 1 m thick walls, `width` × `height` inside, centred on
/// x = 0 with its floor's top at y = 0.
fn closed_box(w: &mut World<'static>, width: f64, height: f64) {
    let mut wall = |wx: f64, wy: f64, x: f64, y: f64| {
        let path = w.add_path(PolygonPath::rectangle(s(wx), s(wy)).expect("wall")).expect("path");
        w.add_body(BodyDef::polygon(path).position(v(x, y)).static_body()).expect("wall body");
    };
    let (hw, outer) = (width / 2.0, width + 2.0);
    wall(outer, 1.0, 0.0, -0.5);
    wall(outer, 1.0, 0.0, height + 0.5);
    wall(1.0, height, -hw - 0.5, height / 2.0);
    wall(1.0, height, hw + 0.5, height / 2.0);
}

fn add(w: &mut World<'static>, def: BodyDef, x: f64, y: f64) -> BodyHandle {
    w.add_body(def.position(v(x, y))).expect("body")
}

/// One step of [`DT`]; asserts nothing was dropped for lack of room, so a scene
/// never passes by leaving contacts out.
fn step(w: &mut World<'static>) {
    let r = w.step(s(DT)).expect("step");
    assert_eq!((r.pairs_dropped, r.arbiters_dropped), (0, 0), "contact buffers too small for the scene");
}

fn pos(w: &World<'static>, h: BodyHandle) -> (f64, f64) {
    w.body(h).expect("body").position().to_f64()
}

fn vel(w: &World<'static>, h: BodyHandle) -> (f64, f64) {
    w.body(h).expect("body").linear_velocity().to_f64()
}

fn speed(w: &World<'static>, h: BodyHandle) -> f64 {
    let (x, y) = vel(w, h);
    x.hypot(y)
}

// ---- metrics (the quality suite's format) ------------------------------------

mod quality_common;

use quality_common::{check, num, s, steps, v, world_with_contacts, Limit, Metric, DT};

// ---- 1. a row of five balls struck by a sixth ----------------------------------

/// The striker's speed (m/s).
const STRIKER_SPEED: f64 = 4.0;

/// Six equal balls (radius 0.5 m, density 1, restitution 1, friction 0), no
/// gravity: five in a row exactly touching (centres 1 m apart on y = 0), the sixth
/// 0.5 m to the left of the row moving right at 4 m/s. After 3 s (the collision
/// is over after about 0.15 s; the far ball has travelled several metres clear),
/// the far ball's speed over the striker's, and the largest speed any other ball
/// kept over the striker's. An ideal elastic chain gives 1 and 0; issue 16 asks
/// ≥ 0.8 and < 0.1.
fn cradle() -> Vec<Metric> {
    const SCENE: &str = "cradle_5+1";
    let mut w = world_with_contacts(6, 24, false);
    let ball = || BodyDef::circle(s(0.5)).friction(s(0.0)).restitution(s(1.0));
    let striker = add(&mut w, ball().linear_velocity(v(STRIKER_SPEED, 0.0)), -1.5, 0.0);
    let row: Vec<_> = (0..5).map(|i| add(&mut w, ball(), f64::from(i), 0.0)).collect();
    for _ in 0..steps(3.0) {
        step(&mut w);
    }
    let far = row[4];
    let others = std::iter::once(striker).chain(row[..4].iter().copied());
    let kept = others.map(|h| speed(&w, h)).fold(0.0, f64::max);
    let velocities: Vec<String> = std::iter::once(striker)
        .chain(row.iter().copied())
        .map(|h| format!("{:+.3}", vel(&w, h).0 / STRIKER_SPEED))
        .collect();
    vec![
        Metric::new(
            SCENE,
            format!("x-velocities / striker speed, striker first: {}", velocities.join(" ")),
            f64::NAN,
            "",
            Limit::Info,
        ),
        Metric::new(
            SCENE,
            "far ball speed / striker speed",
            speed(&w, far) / STRIKER_SPEED,
            "",
            Limit::AtLeast(0.8),
        ),
        Metric::new(
            SCENE,
            "largest other ball speed / striker speed",
            kept / STRIKER_SPEED,
            "",
            Limit::Below(0.1),
        ),
    ]
}

#[test]
fn quality_cradle_five_balls_struck_by_a_sixth() {
    check(&cradle());
}

// ---- 2. 100 circles created at one point ----------------------------------------

/// Circles in the heap.
const HEAP: usize = 100;
/// The golden angle (rad): turns that never repeat.
const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653;
/// How deep two circles may still overlap once separated (m): twice Box2D v3's
/// linear slop (0.005 m), the overlap a soft solver leaves in a resting pile.
const RESTING_OVERLAP: f64 = 0.01;

/// The deepest overlap among every pair of the given circles, all of radius `r` (m).
fn deepest_overlap(w: &World<'static>, circles: &[BodyHandle], r: f64) -> f64 {
    let p: Vec<_> = circles.iter().map(|&h| pos(w, h)).collect();
    let mut worst: f64 = 0.0;
    for i in 0..p.len() {
        for j in i + 1..p.len() {
            let d = (p[i].0 - p[j].0).hypot(p[i].1 - p[j].1);
            worst = worst.max(2.0 * r - d);
        }
    }
    worst
}

/// 100 circles of radius 0.5 (density 1, friction 0.6) created at one point on
/// the floor (their lowest points touching it) of a closed static box 40 m wide
/// and 20 m tall inside, 10 s, with or without gravity. The push-out speed is
/// the world's default `contact_push_speed` (3 m/s).
///
/// The circles are turned by the golden angle one after the other. Exactly
/// coincident centres have no direction between them, and the engine takes
/// the first circle's x axis (as Chipmunk does; Box2D v3 gives no normal and
/// never separates them): at one rotation all 4,950 pairs would push along one
/// line, and without gravity 100 circles in a line longer than the box stay
/// squeezed between its walls for good (0.73 m of overlap at 10 s).
///
/// Without gravity every speed comes from the push-out, which is what issue 16
/// bounds: no body's centre may ever move faster than twice the push speed.
/// With gravity the heap is also a pile: circles pushed out upwards land on
/// top of others and fall or roll back down (7.7 m/s measured, the speed of a
/// 3 m fall), so its largest speed is reported, not bounded. At 10 s every pair overlaps by
/// at most [`RESTING_OVERLAP`] either way.
fn heap_at_one_point(gravity: bool) -> Vec<Metric> {
    let scene = if gravity { "100_circles_at_one_point_gravity" } else { "100_circles_at_one_point" };
    const R: f64 = 0.5;
    // Every pair overlaps at first: 4,950 pairs + 100 with the floor, and room
    // for the walls.
    let mut w = world_with_contacts(HEAP + 4, HEAP * HEAP / 2 + 4 * HEAP, gravity);
    let push_speed = w.def().contact_push_speed.to_f64();
    closed_box(&mut w, 40.0, 20.0);
    // Turned by the golden angle one after the other (see above).
    let circles: Vec<_> = (0..HEAP)
        .map(|i| add(&mut w, BodyDef::circle(s(R)).angle(s(GOLDEN_ANGLE * i as f64)), 0.0, R))
        .collect();
    let (mut fastest, mut fastest_at): (f64, f64) = (0.0, 0.0);
    let mut separated_at = None;
    for i in 1..=steps(10.0) {
        step(&mut w);
        for &c in &circles {
            let sp = speed(&w, c);
            if sp > fastest {
                (fastest, fastest_at) = (sp, i as f64 * DT);
            }
        }
        if separated_at.is_none() && deepest_overlap(&w, &circles, R) <= RESTING_OVERLAP {
            separated_at = Some(i as f64 * DT);
        }
    }
    let spread = circles.iter().map(|&c| pos(&w, c).0.abs()).fold(0.0, f64::max);
    let fastest_limit = if gravity { Limit::Info } else { Limit::AtMost(2.0 * push_speed) };
    vec![
        Metric::new(scene, "largest speed at any step", fastest, "m/s", fastest_limit),
        Metric::new(scene, "largest speed reached at", fastest_at, "s", Limit::Info),
        Metric::new(
            scene,
            "deepest pair overlap at 10 s",
            deepest_overlap(&w, &circles, R),
            "m",
            Limit::AtMost(RESTING_OVERLAP),
        ),
        Metric::new(scene, "first separated at", separated_at.unwrap_or(f64::INFINITY), "s", Limit::Info),
        Metric::new(scene, "pile width at 10 s (farthest centre from x = 0)", spread, "m", Limit::Info),
    ]
}

// Heavy in debug builds (4,950 pairs at first), as the other heavy scenes are.
// Deep overlaps are pushed out by moving the bodies, not by velocity (see the
// solver's contact kernel, `DEEP_OVERLAP`): 18.5 m/s before (60.6 m/s with
// every circle at one rotation).
#[test]
#[cfg_attr(debug_assertions, ignore = "quality scene: run with --release")]
fn quality_hundred_circles_at_one_point_separate_gently() {
    check(&heap_at_one_point(false));
}

// With gravity: 18.5 m/s before the deep push-out by motion (42.0 m/s with
// every circle at one rotation).
#[test]
#[cfg_attr(debug_assertions, ignore = "quality scene: run with --release")]
fn quality_hundred_circles_at_one_point_under_gravity() {
    check(&heap_at_one_point(true));
}

// ---- 2b. deep overlaps, one at a time ------------------------------------------

/// Two equal circles of radius 0.5 created with their centres 0.2 m apart (0.8 m
/// of overlap), no gravity: they separate within 0.75 s (0.5 s measured: 0.7 m
/// moved out at the push speed, then the spring's last 10 cm), never faster
/// relative to each other than the push speed, and the move out of the deep
/// overlap keeps their centre of mass where it was (the two bodies share each
/// move by their mass ratios).
#[test]
fn two_deeply_overlapping_circles_separate_slowly_about_their_centre_of_mass() {
    let mut w = world_with_contacts(2, 4, false);
    let push = w.def().contact_push_speed.to_f64();
    let a = add(&mut w, BodyDef::circle(s(0.5)), 0.0, 0.0);
    let b = add(&mut w, BodyDef::circle(s(0.5)), 0.2, 0.0);
    let mut separated_at = None;
    let mut fastest: f64 = 0.0;
    for i in 1..=steps(1.0) {
        step(&mut w);
        let (va, vb) = (vel(&w, a), vel(&w, b));
        fastest = fastest.max((vb.0 - va.0).hypot(vb.1 - va.1));
        let (pa, pb) = (pos(&w, a), pos(&w, b));
        let mid = ((pa.0 + pb.0) / 2.0, (pa.1 + pb.1) / 2.0);
        assert!((mid.0 - 0.1).abs() < 1e-5 && mid.1.abs() < 1e-5, "step {i}: centre of mass {mid:?}");
        if separated_at.is_none() && (pb.0 - pa.0).hypot(pb.1 - pa.1) >= 1.0 - RESTING_OVERLAP {
            separated_at = Some(i as f64 * DT);
        }
    }
    println!(
        "two circles 0.8 m deep: separated at {separated_at:?} s, fastest relative speed {fastest:.3} m/s"
    );
    assert!(separated_at.is_some_and(|t| t <= 0.75), "separated at {separated_at:?}");
    assert!(fastest <= push, "relative speed {fastest} m/s above the push speed {push}");
}

/// A 1 m box created 0.6 m deep in a static ground, gravity on: moved out by at
/// most 0.2 m per sub-step, it is out to the spring's range within two steps,
/// rests on the surface at 1 s, and never moves faster than the push speed.
#[test]
fn a_box_created_deep_in_the_ground_is_moved_out_without_being_thrown() {
    let mut w = world_with_contacts(2, 4, true);
    let push = w.def().contact_push_speed.to_f64();
    ground(&mut w, 20.0);
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    let b = add(&mut w, BodyDef::polygon(unit), 0.0, 0.5 - 0.6);
    let mut fastest: f64 = 0.0;
    for i in 1..=steps(1.0) {
        step(&mut w);
        fastest = fastest.max(speed(&w, b));
        if i == 2 {
            let depth = 0.5 - pos(&w, b).1;
            assert!(depth <= 0.1, "still {depth} m deep after two steps");
        }
    }
    let depth = 0.5 - pos(&w, b).1;
    println!("box 0.6 m deep: {depth:.4} m deep at 1 s, fastest {fastest:.3} m/s");
    assert!(depth.abs() <= RESTING_OVERLAP, "{depth} m deep at 1 s");
    assert!(fastest <= push, "{fastest} m/s above the push speed {push}");
}

// ---- 3. two-box stack mass ratio ------------------------------------------------

/// How far the top box may sink in 10 s (m).
const MAX_SINK: f64 = 0.05;

/// A 1 m box of density 1 (1 kg) resting on the ground and a 1 m box of density
/// `ratio` on it, both exactly touching, friction 0.6. Steps 10 s and returns
/// (how far the top box's centre sank by 10 s, the most it sank at any step) (m).
fn two_box_sink(ratio: f64) -> (f64, f64) {
    let mut w = world_with_contacts(3, 12, true);
    ground(&mut w, 100.0);
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    add(&mut w, BodyDef::polygon(unit), 0.0, 0.5);
    let top = add(&mut w, BodyDef::polygon(unit).density(s(ratio)), 0.0, 1.5);
    let y0 = pos(&w, top).1;
    let mut deepest: f64 = 0.0;
    for _ in 0..steps(10.0) {
        step(&mut w);
        deepest = deepest.max(y0 - pos(&w, top).1);
    }
    (y0 - pos(&w, top).1, deepest)
}

/// The ratios issue 16 asks about, smallest first.
const RATIOS: [f64; 7] = [10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10000.0];

fn mass_ratio_100() -> Vec<Metric> {
    const SCENE: &str = "two_box_stack";
    let (sink, deepest) = two_box_sink(100.0);
    vec![
        Metric::new(SCENE, "100:1 top sink at 10 s", sink, "m", Limit::AtMost(MAX_SINK)),
        Metric::new(SCENE, "100:1 top largest sink", deepest, "m", Limit::Info),
    ]
}

#[test]
fn quality_two_box_stack_holds_100_to_1() {
    check(&mass_ratio_100());
}

/// Prints the sink of the two-box stack at each of [`RATIOS`] and the largest
/// ratio that holds (sink at 10 s ≤ 0.05 m, and every smaller ratio holds too).
/// Asserts nothing: the figure goes beside Box2D's in `benches/peers`' report.
#[test]
#[ignore = "prints the mass-ratio scan: run with --release -- --ignored --nocapture"]
fn mass_ratio_scan() {
    let mut largest = None;
    let mut all_held = true;
    println!("| top : bottom mass | sink at 10 s (m) | largest sink (m) | holds (≤ {MAX_SINK} m) |");
    println!("|---|---|---|---|");
    for ratio in RATIOS {
        let (sink, deepest) = two_box_sink(ratio);
        let holds = sink <= MAX_SINK;
        all_held &= holds;
        if all_held {
            largest = Some(ratio);
        }
        println!("| {ratio}:1 | {} | {} | {} |", num(sink), num(deepest), if holds { "yes" } else { "no" });
    }
    match largest {
        Some(r) => println!("largest ratio held: {r}:1"),
        None => println!("largest ratio held: none of {RATIOS:?}"),
    }
}
