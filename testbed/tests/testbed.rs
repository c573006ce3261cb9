//! The testbed's behaviour natively: the drag (the engine's target joint)
//! pulls a body to the mouse and throws it, the feature scenes work, rollback re-simulates to the same hash
//! through spawns and drags, and bad input gives error codes, not panics.

use arphysics_testbed::{Testbed, E_BAD_INPUT, E_FULL, E_NOT_DRAGGABLE, E_NO_HISTORY, E_NO_SCENE, E_OUTSIDE};

fn scene(name: &str) -> Testbed {
    let index = Testbed::scene_index(name).expect("the scene exists");
    Testbed::new(index, 4).expect("the scene builds")
}

fn position(t: &Testbed, body: arphysics::BodyHandle) -> (f64, f64) {
    t.world().body(body).expect("alive").position().to_f64()
}

#[test]
fn the_drag_joint_brings_the_held_point_to_the_mouse_holds_it_and_throws() {
    let mut t = scene("pyramid_20");
    // The top box of the pyramid: centre (0, 19.5); hold it at its centre.
    t.drag_begin(0.0, 19.5).expect("the top box is dynamic");
    let body = t.drag().expect("held").body;
    assert_eq!(t.world().joints().count(), 1, "the drag is an engine target joint");
    let j = t.drag().expect("held").joint;
    assert!(matches!(t.world().joint(j).expect("joint").def().kind, arphysics::JointKind::Target { .. }));
    // Lift it 4 m up and 3 m left.
    t.drag_move(-3.0, 23.5).expect("a point");
    for _ in 0..120 {
        t.step().expect("steps");
    }
    let (x, y) = position(&t, body);
    // A 5 Hz spring, damping ratio 0.7: settled after 2 s; gravity sags it by
    // g/ω² = 10/(10π)² ≈ 0.010 m.
    let sag = 10.0 / (10.0 * std::f64::consts::PI).powi(2);
    println!(
        "held at ({x:.4}, {y:.4}) for the mouse at (−3, 23.5): sag {:.4} m vs g/ω² = {sag:.4} m",
        23.5 - y
    );
    assert!((x + 3.0).abs() < 0.002, "x {x}");
    assert!((23.5 - y - sag).abs() < 0.002, "y {y}: hangs g/ω² below the mouse");
    // Throw: sweep the mouse right at 10 m/s for 20 frames, let go.
    for k in 1..=20 {
        t.drag_move(-3.0 + f64::from(k) / 6.0, 23.5).expect("a point");
        t.step().expect("steps");
    }
    t.drag_end();
    assert_eq!(t.world().joints().count(), 0, "released: the joint is removed");
    let vx = t.world().body(body).expect("alive").linear_velocity().x.to_num::<f64>();
    let x0 = position(&t, body).0;
    for _ in 0..10 {
        t.step().expect("steps");
    }
    let flown = position(&t, body).0 - x0;
    println!("thrown at {vx:.2} m/s (the mouse moved at 10), flew {flown:.3} m in 1/6 s");
    assert!(vx > 8.0 && vx < 12.0, "{vx}");
    assert!((flown - vx / 6.0).abs() < 0.05, "{flown}");
}

/// The input of frame `f` in the rollback test: two spawns, then a drag of
/// the first one-shape dynamic body for 40 frames.
fn input(t: &mut Testbed, f: u32) {
    if f == 100 {
        t.spawn(false, -3.0, 12.0).expect("inside");
        t.spawn(true, 3.0, 14.0).expect("inside");
        let (x, y) = t
            .world()
            .bodies()
            // One shape: a compound body's centre (an L's) can be outside it.
            .find(|(_, b)| b.is_dynamic() && b.shape_count() == 1)
            .map(|(_, b)| b.position().to_f64())
            .expect("a dynamic body");
        t.drag_begin(x, y).expect("a dynamic body's centre");
        t.drag_move(x + 1.0, y + 2.0).expect("a point");
    }
    if f == 140 {
        t.drag_end();
    }
}

#[test]
fn rollback_re_simulates_spawns_drags_and_the_scenes_own_spawner_to_the_same_hash() {
    for name in ["default", "rain", "terrain", "chain", "pyramid_20"] {
        let mut t = scene(name);
        for f in 0..150 {
            input(&mut t, f);
            t.step().expect("steps");
        }
        let before = t.world().state_hash();
        let r = t.rollback().expect("the same hash");
        assert_eq!(r.frames, 60);
        assert_eq!((r.before, r.after), (before, t.world().state_hash()));
        // And stepping on from the re-simulated state is the same as from the
        // original: twice the same input gives the same hash.
        t.step().expect("steps");
        let mut again = scene(name);
        for f in 0..151 {
            input(&mut again, f);
            again.step().expect("steps");
        }
        assert_eq!(t.world().state_hash(), again.world().state_hash(), "{name}");
    }
}

#[test]
fn bad_input_is_an_error_code_and_changes_nothing() {
    assert_eq!(Testbed::new(999, 4).err().map(|e| e.code), Some(E_NO_SCENE));
    assert_eq!(Testbed::new(0, 0).err().map(|e| e.code), Some(E_BAD_INPUT));
    assert_eq!(Testbed::new(0, 17).err().map(|e| e.code), Some(E_BAD_INPUT));
    let mut t = scene("pyramid_20");
    assert_eq!(t.rollback().err().map(|e| e.code), Some(E_NO_HISTORY));
    let hash = t.world().state_hash();
    assert_eq!(t.spawn(false, 5000.0, 0.0).err().map(|e| e.code), Some(E_OUTSIDE));
    assert_eq!(t.spawn(true, f64::NAN, 1.0).err().map(|e| e.code), Some(E_BAD_INPUT));
    assert_eq!(t.drag_begin(0.0, -1.0).err().map(|e| e.code), Some(E_NOT_DRAGGABLE), "the static ground");
    assert_eq!(t.drag_begin(0.0, 300.0).err().map(|e| e.code), Some(E_NOT_DRAGGABLE), "nothing");
    assert_eq!(t.world().state_hash(), hash);
    assert!(!t.interacted());
    // Fill the world: the scene's room is SPAWN_ROOM bodies past its own.
    let mut spawned = 0;
    let full = loop {
        match t.spawn(true, -50.0 + f64::from(spawned % 100), 30.0 + f64::from(spawned / 100)) {
            Ok(()) => spawned += 1,
            Err(e) => break e,
        }
    };
    assert_eq!(full.code, E_FULL);
    assert!(spawned >= arphysics_testbed::SPAWN_ROOM as i32);
    t.step().expect("a full world steps");
}

#[test]
fn the_joints_scene_keeps_every_joint_and_its_motor_turns_the_wheel() {
    use arphysics::JointKind;
    let mut t = scene("joints");
    for _ in 0..240 {
        t.step().expect("steps");
    }
    let w = t.world();
    let (mut kinds, mut worst_gap) = (Vec::new(), 0.0f64);
    for (_, j) in w.joints() {
        let d = j.def();
        let a = w.body(d.body_a).expect("a");
        let pa = a.transform().apply(d.anchor_a).to_f64();
        let pb = match d.body_b {
            Some(h) => w.body(h).expect("b").transform().apply(d.anchor_b).to_f64(),
            None => d.anchor_b.to_f64(),
        };
        let dist = ((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2)).sqrt();
        match d.kind {
            JointKind::Pivot { motor, .. } => {
                worst_gap = worst_gap.max(dist);
                if motor.is_some() {
                    let spin = a.angular_velocity().to_num::<f64>();
                    println!("motor: wheel spins at {spin:.3} rad/s (target −2)");
                    assert!((spin + 2.0).abs() < 0.05, "{spin}");
                }
            }
            JointKind::Weld => worst_gap = worst_gap.max(dist),
            JointKind::Rod { length } => {
                println!("rod: {dist:.4} m (2.6)");
                assert!((dist - length.to_num::<f64>()).abs() < 0.02, "{dist}");
            }
            JointKind::Rope { max_length } => {
                println!("rope: {dist:.4} m (≤ 4)");
                assert!(dist <= max_length.to_num::<f64>() + 0.02, "{dist}");
            }
            _ => {}
        }
        kinds.push(std::mem::discriminant(&d.kind));
    }
    println!("pivots and welds: anchors at most {worst_gap:.4} m apart (≤ 0.02)");
    assert!(worst_gap < 0.02);
    kinds.dedup();
    assert!(kinds.len() >= 5, "pivot, weld, rod, rope, damped spring: {kinds:?}");
    assert!(w.bodies().all(|(_, b)| !b.is_out_of_bounds()));
}

#[test]
fn the_sensors_scene_reports_begin_and_end_events_and_rollback_keeps_their_count() {
    let mut t = scene("sensors");
    for _ in 0..240 {
        t.step().expect("steps");
    }
    let [begins, ends] = t.sensor_totals();
    println!(
        "sensors: {begins} begin and {ends} end events in 240 frames; last: {:?}",
        t.sensor_log().last()
    );
    // Twelve balls fall through the zone in mid-air (a begin and an end each)
    // and most come to rest in the pit (a begin each).
    assert!(begins >= 12 + 6, "{begins}");
    assert!(ends >= 12, "{ends}");
    assert!(begins > ends);
    let r = t.rollback().expect("same hash");
    assert_eq!(r.before, r.after);
    assert_eq!(t.sensor_totals(), [begins, ends], "a rollback re-counts the frames it re-simulates once");
}

#[test]
fn the_scripted_drag_replays_to_the_same_hash_and_rolls_back() {
    let script = arphysics_testbed::drag_script();
    let mut a = Testbed::run_script(&script).expect("plays");
    let b = Testbed::run_script(&script).expect("plays");
    assert_eq!(a.world().state_hash(), b.world().state_hash());
    assert_eq!(a.substeps(), 4);
    // The drag changed the world: a run without it differs.
    let mut plain = scene(script.scene);
    for _ in 0..a.frame() {
        plain.step().expect("steps");
    }
    assert_ne!(plain.world().state_hash(), a.world().state_hash());
    // The JSON the page reads has every action.
    let json = script.to_json();
    assert_eq!(json.matches('[').count(), script.actions.len() + 1);
    // Rollback across the sub-step changes and the throw.
    let r = a.rollback().expect("same hash");
    assert_eq!(r.before, r.after);
    // 60 frames back is before the second change: roll back a run stopped
    // right after the throw, across the change to 8 sub-steps too.
    let mut t = scene(script.scene);
    for act in script.actions.iter().take_while(|x| !matches!(x, arphysics_testbed::Action::Spawn(..))) {
        t.play(*act).expect("plays");
    }
    t.step().expect("steps");
    assert_eq!(t.substeps(), 8);
    let r = t.rollback().expect("same hash across a sub-step change");
    assert_eq!(r.before, r.after);
    assert_eq!(r.after, t.world().state_hash());
    assert_eq!(t.substeps(), 8);
}
