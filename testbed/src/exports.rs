//! The functions the page calls: plain `extern "C"` exports, numbers in and
//! out, no bindings generator. Strings and the draw list are in this module's
//! buffers in the wasm memory; the page reads them at the pointer and length
//! these functions return (and re-reads its view of the memory after every call,
//! since the memory may grow).
//!
//! Every function returns a status (0 or more: success; negative: an `E_*`
//! code of the crate root, the message then in [`tb_error_ptr`]/[`tb_error_len`])
//! and never panics on any argument. The release profile aborts on panic, so a
//! bug would trap; the page catches the trap and says so.
//!
//! `#[no_mangle]` is why this module allows `unsafe_code`: exporting a symbol
//! under a fixed name is an unsafe attribute (two such symbols could clash at
//! link time); nothing here dereferences a pointer or has an `unsafe` block.

#![allow(unsafe_code)]

use std::sync::Mutex;

use crate::{Fail, Testbed, DRAW_STRIDE, E_NOT_LOADED};

/// The page's state: the testbed, the last error message, a text buffer.
struct State {
    testbed: Option<Testbed>,
    error: String,
    text: String,
    last_rollback: Option<crate::Rollback>,
}

/// One page, one thread: the lock never waits. (A `Mutex` keeps this safe Rust.)
static STATE: Mutex<State> =
    Mutex::new(State { testbed: None, error: String::new(), text: String::new(), last_rollback: None });

fn with<R>(f: impl FnOnce(&mut State) -> R) -> R {
    // A poisoned lock cannot happen (panics abort); take the state either way.
    let mut guard = STATE.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    f(&mut guard)
}

/// Runs `f` on the loaded testbed; a failure becomes its (negative) code and
/// its message the error text.
fn on_testbed(f: impl FnOnce(&mut Testbed) -> Result<i32, Fail>) -> i32 {
    on_loaded(|t, _, _| f(t))
}

/// [`on_testbed`], with the text buffer and the last rollback to write too.
fn on_loaded(
    f: impl FnOnce(&mut Testbed, &mut String, &mut Option<crate::Rollback>) -> Result<i32, Fail>,
) -> i32 {
    with(|s| {
        let r = match s.testbed.as_mut() {
            Some(t) => f(t, &mut s.text, &mut s.last_rollback),
            None => Err(Fail { code: E_NOT_LOADED, message: "no scene loaded".into() }),
        };
        match r {
            Ok(v) => v,
            Err(e) => {
                s.error = e.message;
                e.code
            }
        }
    })
}

fn json_str(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
}

/// Writes the scene list as JSON into the text buffer and returns its length
/// (read it at [`tb_text_ptr`]): `{"stride":24,"ring":60,"max_substeps":16,
/// "scenes":[{"name":…,"about":…,"view":[x0,y0,x1,y1],"check_frames":N},…],
/// "script":…}` (the scripted drag, see [`crate::Script::to_json`]).
#[no_mangle]
pub extern "C" fn tb_info() -> i32 {
    with(|s| {
        let mut t = String::new();
        t.push_str(&format!(
            "{{\"stride\":{DRAW_STRIDE},\"ring\":{},\"max_substeps\":{},\"scenes\":[",
            crate::RING_FRAMES,
            arphysics::limits::MAX_SUBSTEPS
        ));
        for (i, sc) in crate::scenes::all().iter().enumerate() {
            if i > 0 {
                t.push(',');
            }
            t.push_str("{\"name\":");
            json_str(&mut t, sc.name);
            t.push_str(",\"about\":");
            json_str(&mut t, sc.about);
            let (a, b, c, d) = sc.view;
            t.push_str(&format!(",\"view\":[{a},{b},{c},{d}],\"check_frames\":{}}}", sc.check_frames));
        }
        t.push_str("],\"script\":");
        t.push_str(&crate::drag_script().to_json());
        t.push('}');
        s.text = t;
        s.text.len() as i32
    })
}

/// Where the text buffer is.
#[no_mangle]
pub extern "C" fn tb_text_ptr() -> u32 {
    with(|s| s.text.as_ptr() as usize as u32)
}

/// Where the last error message is.
#[no_mangle]
pub extern "C" fn tb_error_ptr() -> u32 {
    with(|s| s.error.as_ptr() as usize as u32)
}

/// The last error message's length in bytes (UTF-8).
#[no_mangle]
pub extern "C" fn tb_error_len() -> u32 {
    with(|s| s.error.len() as u32)
}

/// Loads scene `index` at `substeps` sub-steps (replacing the current one only
/// if that succeeds).
#[no_mangle]
pub extern "C" fn tb_load(index: u32, substeps: u32) -> i32 {
    with(|s| match Testbed::new(index as usize, substeps) {
        Ok(t) => {
            s.testbed = Some(t);
            s.last_rollback = None;
            0
        }
        Err(e) => {
            s.error = e.message;
            e.code
        }
    })
}

/// Steps `frames` frames (at most 600 per call); returns the frames stepped.
#[no_mangle]
pub extern "C" fn tb_step(frames: u32) -> i32 {
    on_testbed(|t| {
        let n = frames.min(600);
        for _ in 0..n {
            t.step()?;
        }
        Ok(n as i32)
    })
}

/// Frames stepped since the scene was loaded.
#[no_mangle]
pub extern "C" fn tb_frame() -> i32 {
    on_testbed(|t| Ok(t.frame() as i32))
}

/// Bodies in the world.
#[no_mangle]
pub extern "C" fn tb_body_count() -> i32 {
    on_testbed(|t| Ok(t.world().body_count() as i32))
}

/// Touching contact pairs.
#[no_mangle]
pub extern "C" fn tb_contact_count() -> i32 {
    on_testbed(|t| Ok(t.contact_count() as i32))
}

/// Joints in the world.
#[no_mangle]
pub extern "C" fn tb_joint_count() -> i32 {
    on_testbed(|t| Ok(t.world().joints().count() as i32))
}

/// The state hash's low 32 bits (read [`tb_hash_hi`] too).
#[no_mangle]
pub extern "C" fn tb_hash_lo() -> u32 {
    with(|s| s.testbed.as_ref().map_or(0, |t| t.world().state_hash() as u32))
}

/// The state hash's high 32 bits.
#[no_mangle]
pub extern "C" fn tb_hash_hi() -> u32 {
    with(|s| s.testbed.as_ref().map_or(0, |t| (t.world().state_hash() >> 32) as u32))
}

/// 1 if the user spawned or dragged since loading (no native hash applies), else 0.
#[no_mangle]
pub extern "C" fn tb_interacted() -> i32 {
    on_testbed(|t| Ok(i32::from(t.interacted())))
}

/// Frames the rollback ring holds now.
#[no_mangle]
pub extern "C" fn tb_history() -> i32 {
    on_testbed(|t| Ok(t.history() as i32))
}

/// Frames the rollback ring can hold for this scene (60, fewer for a huge one).
#[no_mangle]
pub extern "C" fn tb_ring_frames() -> i32 {
    on_testbed(|t| Ok(t.ring_frames() as i32))
}

/// Fills the draw list; returns the number of records ([`DRAW_STRIDE`] `f32`s
/// each, at [`tb_draw_ptr`]).
#[no_mangle]
pub extern "C" fn tb_draw() -> i32 {
    on_testbed(|t| Ok((t.draw_list().len() / DRAW_STRIDE) as i32))
}

/// Where the draw list [`tb_draw`] filled is (valid until the next call to `tb_draw`).
#[no_mangle]
pub extern "C" fn tb_draw_ptr() -> u32 {
    with(|s| s.testbed.as_mut().map_or(0, |t| t.last_draw_list().as_ptr() as usize as u32))
}

/// Spawns a box (`kind` 0) or a ball (`kind` 1) at (x, y) m.
#[no_mangle]
pub extern "C" fn tb_spawn(kind: u32, x: f64, y: f64) -> i32 {
    on_testbed(|t| {
        if kind > 1 {
            return Err(Fail { code: crate::E_BAD_INPUT, message: format!("no spawn kind {kind}") });
        }
        t.spawn(kind == 1, x, y).map(|()| 0)
    })
}

/// Takes hold of the dynamic body at (x, y) m.
#[no_mangle]
pub extern "C" fn tb_drag_begin(x: f64, y: f64) -> i32 {
    on_testbed(|t| t.drag_begin(x, y).map(|()| 0))
}

/// Moves the mouse target of the drag to (x, y) m.
#[no_mangle]
pub extern "C" fn tb_drag_move(x: f64, y: f64) -> i32 {
    on_testbed(|t| t.drag_move(x, y).map(|()| 0))
}

/// Lets go of the body held.
#[no_mangle]
pub extern "C" fn tb_drag_end() -> i32 {
    on_testbed(|t| {
        t.drag_end();
        Ok(0)
    })
}

/// Changes the running world's sub-step count (1 to 16), from the next frame.
#[no_mangle]
pub extern "C" fn tb_set_substeps(n: u32) -> i32 {
    on_testbed(|t| t.set_substeps(n).map(|()| 0))
}

/// The running world's sub-step count.
#[no_mangle]
pub extern "C" fn tb_substeps() -> i32 {
    on_testbed(|t| Ok(t.substeps() as i32))
}

/// Writes the sensor events as JSON into the text buffer and returns its
/// length: `{"begin":N,"end":M,"log":[[frame,begin 0|1,sensor slot,visitor slot],…]}`
/// (totals since loading, the last few events oldest first).
#[no_mangle]
pub extern "C" fn tb_sensor_events() -> i32 {
    on_loaded(|t, text, _| {
        let [begin, end] = t.sensor_totals();
        let log: Vec<String> = t
            .sensor_log()
            .map(|n| format!("[{},{},{},{}]", n.frame, u8::from(n.begin), n.sensor, n.visitor))
            .collect();
        *text = format!("{{\"begin\":{begin},\"end\":{end},\"log\":[{}]}}", log.join(","));
        Ok(text.len() as i32)
    })
}

/// Rewinds up to 60 frames and re-simulates them; returns the frames rewound
/// (the hashes before and after are in [`tb_rollback_hash`]). [`crate::E_MISMATCH`]
/// if the hash came back different.
#[no_mangle]
pub extern "C" fn tb_rollback() -> i32 {
    on_loaded(|t, _, last| {
        let r = t.rollback()?;
        *last = Some(r);
        Ok(r.frames as i32)
    })
}

/// Word `k` of the last successful rollback's hashes: 0/1 the low/high half
/// of the hash before, 2/3 of the hash after.
#[no_mangle]
pub extern "C" fn tb_rollback_hash(k: u32) -> u32 {
    with(|s| {
        s.last_rollback.map_or(0, |r| match k {
            0 => r.before as u32,
            1 => (r.before >> 32) as u32,
            2 => r.after as u32,
            3 => (r.after >> 32) as u32,
            _ => 0,
        })
    })
}

/// The note the scene's own spawner left, if it failed (a world the user
/// filled): its length, the text in the text buffer.
#[no_mangle]
pub extern "C" fn tb_scene_note() -> i32 {
    with(|s| {
        let note = s.testbed.as_ref().and_then(|t| t.scene_note.clone()).unwrap_or_default();
        s.text = note;
        s.text.len() as i32
    })
}

/// For testing the page's trap handling: panics (which aborts: a trap).
#[no_mangle]
pub extern "C" fn tb_debug_trap() {
    // Reached only by a deliberate call from the page's self-test.
    std::process::abort();
}
