//! The testbed's behaviour natively: the drag spring pulls a body to the mouse
//! (softly, with a bounded stretch), rollback re-simulates to the same hash
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
fn the_drag_spring_brings_the_held_point_to_the_mouse_and_holds_it_there() {
    let mut t = scene("pyramid_20");
    // The top box of the pyramid: centre (0, 19.5); hold it at its centre.
    t.drag_begin(0.0, 19.5).expect("the top box is dynamic");
    let body = t.drag().expect("held").body;
    // Lift it 4 m up and 3 m left: farther than the stretch limit, so the pull
    // is bounded and the box travels over several frames.
    t.drag_move(-3.0, 23.5).expect("a point");
    for _ in 0..10 {
        t.step().expect("steps");
    }
    let (x, y) = position(&t, body);
    let early = ((x + 3.0).powi(2) + (y - 23.5).powi(2)).sqrt();
    assert!(early > 0.5, "a soft spring takes more than 10 frames to cover 5 m (left {early} m)");
    for _ in 0..110 {
        t.step().expect("steps");
    }
    let (x, y) = position(&t, body);
    // A 3 Hz spring, damping ratio 0.7: settled after 2 s; gravity sags it by
    // g/ω² = 10/355 ≈ 0.03 m.
    assert!((x + 3.0).abs() < 0.05, "x {x}");
    assert!((y - 23.5).abs() < 0.06 && y < 23.5, "y {y}: hangs a little below the mouse");
    // Let go: it falls.
    t.drag_end();
    for _ in 0..30 {
        t.step().expect("steps");
    }
    assert!(position(&t, body).1 < y - 1.0, "released, it falls");
    // The spring is added for each step and removed after it.
    assert_eq!(t.world().joints().count(), 0);
}

/// The input of frame `f` in the rollback test: two spawns, then a drag of
/// the first dynamic body for 40 frames.
fn input(t: &mut Testbed, f: u32) {
    if f == 100 {
        t.spawn(false, -3.0, 12.0).expect("inside");
        t.spawn(true, 3.0, 14.0).expect("inside");
        let (x, y) = t
            .world()
            .bodies()
            .find(|(_, b)| b.is_dynamic())
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
