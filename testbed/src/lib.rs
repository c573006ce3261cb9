//! The arphysics testbed: the engine's scenes, stepped, drawn and played with
//! in a browser (built for `wasm32-unknown-unknown`, see `exports`), and the
//! same code natively (`src/bin/native_hashes.rs`) to print the hashes the page
//! must reproduce.
//!
//! [`Testbed`] is the whole testbed in safe Rust: load a scene, step it, spawn
//! bodies, drag one, roll back 60 frames and re-simulate. It never panics on
//! input: every operation returns a [`Fail`] (an error code and a message).
//! Floats appear only at the edge (mouse coordinates in, drawing out); inputs
//! are turned into `Scalar`s once, when they arrive, and recorded as such, so a
//! replay uses the same bits.

#![deny(unsafe_code)]
#![deny(unsafe_op_in_unsafe_fn)]

pub mod exports;
pub mod scenes;

use std::collections::VecDeque;
use std::sync::atomic::{AtomicU32, Ordering};

use arphysics::{
    BodyDef, BodyHandle, Capacities, Error, JointDef, JointHandle, JointKind, PathHandle, PolygonPath,
    QueryFilter, Rect, Scalar, Shape, Vector2, World, WorldDef,
};

/// Bodies a scene's world has room for beyond what the scene needs (spawned by
/// clicks); the spawn after those fails with "world full".
pub const SPAWN_ROOM: usize = 64;

/// Frames of snapshots kept for rollback.
pub const RING_FRAMES: usize = 60;

/// Bytes of snapshots the rollback ring may hold; a scene whose snapshots are
/// larger keeps fewer frames (joint_grid).
pub const RING_BUDGET: usize = 96 << 20;

/// One frame's time step, 1/60 s (as the demo computes it).
pub fn dt() -> Scalar {
    Scalar::ONE / 60
}

/// Sub-steps for the scenes built next (a world setting: see [`scene_world`]).
static SUBSTEPS: AtomicU32 = AtomicU32::new(4);

/// Floats per record in the draw list: kind, flags, x, y, angle, radius, point
/// count, unused, then up to 8 points (x, y) in world coordinates. Kinds: 0
/// circle, 1 polygon (radius: its rounding), 2 capsule (the two centres), 3
/// segment, 4 the drag's target joint (held point, mouse), 5 another joint (its
/// anchors).
pub const DRAW_STRIDE: usize = 24;

/// A scene's world: its bounds and capacities, with the testbed's sub-step
/// count, room for [`SPAWN_ROOM`] more bodies and one more joint (the drag's
/// target joint). Called by every scene builder (build.rs routes the demo's to it).
///
/// # Errors
/// What [`World::with_capacities`] fails with.
pub fn scene_world(bounds: Rect, mut capacities: Capacities) -> Result<World<'static>, Error> {
    let mut def = WorldDef::with_bounds(bounds);
    def.substeps = SUBSTEPS.load(Ordering::Relaxed);
    capacities.bodies += SPAWN_ROOM;
    capacities.contacts += SPAWN_ROOM * 4;
    capacities.joints += 1;
    World::with_capacities(def, capacities)
}

/// Why an operation failed: a code the page can switch on and a message it shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fail {
    /// Negative: see the `E_*` constants.
    pub code: i32,
    /// What happened, for people.
    pub message: String,
}

/// No scene of that index or name.
pub const E_NO_SCENE: i32 = -1;
/// No scene is loaded.
pub const E_NOT_LOADED: i32 = -2;
/// The engine returned an error (the message names it).
pub const E_ENGINE: i32 = -3;
/// A spawn (or drag target) outside the world's bounds.
pub const E_OUTSIDE: i32 = -4;
/// The world is full.
pub const E_FULL: i32 = -5;
/// Nothing draggable under the point (nothing, or a static body).
pub const E_NOT_DRAGGABLE: i32 = -6;
/// Rollback is not possible yet (no frames recorded).
pub const E_NO_HISTORY: i32 = -7;
/// Rollback re-simulated to a different hash (a determinism bug).
pub const E_MISMATCH: i32 = -8;
/// A parameter out of range (sub-steps, a NaN coordinate, a spawn kind).
pub const E_BAD_INPUT: i32 = -9;

impl Fail {
    fn new(code: i32, message: impl Into<String>) -> Self {
        Self { code, message: message.into() }
    }
}

impl From<Error> for Fail {
    fn from(e: Error) -> Self {
        let code = match e {
            Error::CapacityFull { .. } => E_FULL,
            Error::OutsideBounds => E_OUTSIDE,
            _ => E_ENGINE,
        };
        Self::new(code, format!("engine: {e}"))
    }
}

/// A drag in progress: a body, the point of it held (body frame), where the
/// mouse is (world) and the engine's target joint pulling the one to the other.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drag {
    /// The body held.
    pub body: BodyHandle,
    /// The point held, in the body's frame.
    pub anchor: Vector2,
    /// The mouse, in the world.
    pub target: Vector2,
    /// The target joint (`JointKind::Target`) from the held point to the mouse.
    pub joint: JointHandle,
}

/// The drag's target joint: a 5 Hz spring, damping ratio 0.7, at most 1,000 N
/// per kilogram of the body held (100 g: it lifts anything, yet a body pinned
/// under others cannot be torn out at any speed). Box2D's samples use the same.
pub const DRAG_HERTZ: Scalar = Scalar::lit("5");
/// The drag's damping ratio.
pub const DRAG_DAMPING_RATIO: Scalar = Scalar::lit("0.7");
/// The drag's force limit per kilogram, N/kg.
pub const DRAG_FORCE_PER_KG: Scalar = Scalar::lit("1000");

/// A user's input, applied to the world when it comes and recorded with the
/// frame it came before, so a rollback replays it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// A body spawned by a click.
    Spawn(Spawn),
    /// Took hold of `body` at `anchor` (body frame), the mouse at `target`.
    DragBegin {
        /// The body.
        body: BodyHandle,
        /// The point held, body frame.
        anchor: Vector2,
        /// The mouse.
        target: Vector2,
    },
    /// The mouse moved to this point (inside the bounds).
    DragMove(Vector2),
    /// Let go.
    DragEnd,
    /// The sub-step count changed.
    Substeps(u32),
}

/// A body spawned by a click.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spawn {
    /// A ball (else a box).
    pub ball: bool,
    /// Where.
    pub at: Vector2,
}

/// A frame of the rollback ring: the state before the frame, the inputs made
/// just before it (already in that state), the drag then and the sensor event
/// counts then.
struct Record {
    frame: u32,
    snapshot: Vec<u8>,
    inputs: Vec<Input>,
    drag: Option<Drag>,
    sensor_totals: [u32; 2],
}

/// Sensor events kept for the page: the last this many.
pub const SENSOR_LOG: usize = 12;

/// A sensor event as the page lists it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorNote {
    /// The frame it happened in (1 = the first step).
    pub frame: u32,
    /// Began (else ended).
    pub begin: bool,
    /// The sensor's slot.
    pub sensor: u32,
    /// The visitor's slot.
    pub visitor: u32,
}

/// The result of a rollback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rollback {
    /// Frames rewound and re-simulated.
    pub frames: u32,
    /// The hash before.
    pub before: u64,
    /// The hash after re-simulating.
    pub after: u64,
}

/// The testbed: one scene at a time.
pub struct Testbed {
    scenes: Vec<scenes::Scene>,
    scene: usize,
    /// The sub-steps the scene was loaded with (a rollback rebuilds it so;
    /// the restore then sets the count of the snapshot).
    loaded_substeps: u32,
    running: scenes::Running,
    spawn_box: PathHandle,
    frame: u32,
    /// Inputs since the last frame (already in the world).
    inputs: Vec<Input>,
    drag: Option<Drag>,
    /// Sensor begin and end events since loading, and the last few.
    sensor_totals: [u32; 2],
    sensor_log: VecDeque<SensorNote>,
    ring: VecDeque<Record>,
    ring_frames: usize,
    /// Whether the user changed the world since the scene was loaded (then no
    /// native hash applies).
    interacted: bool,
    /// The last error a scene's own spawner reported (a world the user filled).
    pub scene_note: Option<String>,
    draw: Vec<f32>,
}

/// The side of a spawned box, m, and a ball's radius.
const SPAWN_BOX: Scalar = Scalar::lit("0.8");
const SPAWN_BALL: Scalar = Scalar::lit("0.4");

fn build(scene: &scenes::Scene, substeps: u32) -> Result<(scenes::Running, PathHandle), Fail> {
    if substeps == 0 || substeps > arphysics::limits::MAX_SUBSTEPS {
        return Err(Fail::new(
            E_BAD_INPUT,
            format!("sub-steps must be 1 to {}", arphysics::limits::MAX_SUBSTEPS),
        ));
    }
    SUBSTEPS.store(substeps, Ordering::Relaxed);
    let mut running = scene.build()?;
    // The path of spawned boxes is part of the scene from the start: restore
    // requires the same paths, so it cannot be added later.
    let spawn_box = running.world_mut().add_path(PolygonPath::rectangle(SPAWN_BOX, SPAWN_BOX)?)?;
    Ok((running, spawn_box))
}

impl Testbed {
    /// The testbed with scene `index` loaded at `substeps` sub-steps.
    ///
    /// # Errors
    /// [`E_NO_SCENE`], [`E_BAD_INPUT`] or what building the scene fails with.
    pub fn new(index: usize, substeps: u32) -> Result<Self, Fail> {
        let scenes = scenes::all();
        let scene = scenes.get(index).ok_or_else(|| {
            Fail::new(E_NO_SCENE, format!("no scene number {index} ({} scenes)", scenes.len()))
        })?;
        let (running, spawn_box) = build(scene, substeps)?;
        let per_frame = running.world().snapshot_len().max(1) * 3 / 2;
        let ring_frames = (RING_BUDGET / per_frame).clamp(1, RING_FRAMES);
        Ok(Self {
            scenes,
            scene: index,
            loaded_substeps: substeps,
            running,
            spawn_box,
            frame: 0,
            inputs: Vec::new(),
            drag: None,
            sensor_totals: [0; 2],
            sensor_log: VecDeque::new(),
            ring: VecDeque::new(),
            ring_frames,
            interacted: false,
            scene_note: None,
            draw: Vec::new(),
        })
    }

    /// The scene by name.
    pub fn scene_index(name: &str) -> Option<usize> {
        scenes::all().iter().position(|s| s.name == name)
    }

    /// The scenes.
    pub fn scenes(&self) -> &[scenes::Scene] {
        &self.scenes
    }

    /// The scene loaded.
    pub fn scene(&self) -> usize {
        self.scene
    }

    /// Sub-steps per step now (the world's setting).
    pub fn substeps(&self) -> u32 {
        self.world().def().substeps
    }

    /// Sensor begin and end events since the scene was loaded.
    pub fn sensor_totals(&self) -> [u32; 2] {
        self.sensor_totals
    }

    /// The last [`SENSOR_LOG`] sensor events, oldest first.
    pub fn sensor_log(&self) -> impl Iterator<Item = &SensorNote> {
        self.sensor_log.iter()
    }

    /// The world.
    pub fn world(&self) -> &World<'static> {
        self.running.world()
    }

    /// Frames stepped since the scene was loaded.
    pub fn frame(&self) -> u32 {
        self.frame
    }

    /// Whether the user changed the world (spawn, drag) since loading.
    pub fn interacted(&self) -> bool {
        self.interacted
    }

    /// Frames the rollback ring holds at most for this scene.
    pub fn ring_frames(&self) -> usize {
        self.ring_frames
    }

    /// Frames the rollback ring holds now.
    pub fn history(&self) -> usize {
        self.ring.len()
    }

    /// The drag in progress.
    pub fn drag(&self) -> Option<Drag> {
        self.drag
    }

    /// Touching contact pairs.
    pub fn contact_count(&self) -> usize {
        self.world().arbiters().filter(|a| a.is_touching()).count()
    }

    /// Steps one frame: records it in the rollback ring, lets the scene add
    /// what is due, steps (a body held is pulled by its target joint).
    ///
    /// # Errors
    /// What stepping fails with (the world is then as the engine left it).
    pub fn step(&mut self) -> Result<(), Fail> {
        let inputs = std::mem::take(&mut self.inputs);
        let drag = self.drag;
        // The ring: reuse the oldest record's buffer.
        let mut rec = if self.ring.len() >= self.ring_frames { self.ring.pop_front() } else { None }
            .unwrap_or(Record {
                frame: 0,
                snapshot: Vec::new(),
                inputs: Vec::new(),
                drag: None,
                sensor_totals: [0; 2],
            });
        let world = self.running.world();
        rec.snapshot.resize(world.snapshot_len(), 0);
        world.snapshot(&mut rec.snapshot)?;
        rec.frame = self.frame;
        rec.inputs = inputs;
        rec.drag = drag;
        rec.sensor_totals = self.sensor_totals;
        self.ring.push_back(rec);
        let note = step_frame(&mut self.running, self.frame)?;
        if note.is_some() {
            self.scene_note = note;
        }
        self.frame += 1;
        self.note_sensor_events();
        Ok(())
    }

    /// Counts and logs the sensor events of the step just taken.
    fn note_sensor_events(&mut self) {
        let w = self.running.world();
        let frame = self.frame;
        for (begin, list) in [(true, w.sensor_begin_events()), (false, w.sensor_end_events())] {
            for e in list {
                self.sensor_totals[usize::from(!begin)] += 1;
                if self.sensor_log.len() >= SENSOR_LOG {
                    self.sensor_log.pop_front();
                }
                self.sensor_log.push_back(SensorNote {
                    frame,
                    begin,
                    sensor: e.sensor.index(),
                    visitor: e.visitor.index(),
                });
            }
        }
    }

    /// Applies an input to the world now and records it for the next frame.
    fn input(&mut self, input: Input) -> Result<(), Fail> {
        apply_input(self.running.world_mut(), self.spawn_box, &mut self.drag, input)?;
        // Only the last position before a step matters: one move per frame.
        match (input, self.inputs.last_mut()) {
            (Input::DragMove(p), Some(Input::DragMove(last))) => *last = p,
            _ => self.inputs.push(input),
        }
        self.interacted = true;
        Ok(())
    }

    /// Changes the sub-step count of the running world (from the next frame;
    /// recorded, so a rollback replays it).
    ///
    /// # Errors
    /// [`E_BAD_INPUT`] outside 1 to `MAX_SUBSTEPS`.
    pub fn set_substeps(&mut self, n: u32) -> Result<(), Fail> {
        if n == 0 || n > arphysics::limits::MAX_SUBSTEPS {
            return Err(Fail::new(
                E_BAD_INPUT,
                format!("sub-steps must be 1 to {}", arphysics::limits::MAX_SUBSTEPS),
            ));
        }
        if n != self.substeps() {
            self.input(Input::Substeps(n))?;
        }
        Ok(())
    }

    /// Spawns a box (or a ball) at `(x, y)` m, before the next frame.
    ///
    /// # Errors
    /// [`E_BAD_INPUT`] for a non-finite point, [`E_OUTSIDE`] outside the
    /// bounds, [`E_FULL`] when the world is full.
    pub fn spawn(&mut self, ball: bool, x: f64, y: f64) -> Result<(), Fail> {
        let at = Vector2::checked_from_f64(x, y).ok_or_else(|| Fail::new(E_BAD_INPUT, "not a point"))?;
        let b = self.world().bounds();
        let r = SPAWN_BOX; // covers both shapes' extents
        if at.x - r < b.min.x || at.x + r > b.max.x || at.y - r < b.min.y || at.y + r > b.max.y {
            return Err(Fail::new(E_OUTSIDE, "spawn outside the world's bounds"));
        }
        self.input(Input::Spawn(Spawn { ball, at }))
    }

    /// Takes hold of the dynamic body under `(x, y)`: a target joint from that
    /// point of it to the mouse (see [`DRAG_HERTZ`]). A body already held is
    /// let go first.
    ///
    /// # Errors
    /// [`E_NOT_DRAGGABLE`] when no dynamic body is there (a static one is
    /// named as such), [`E_BAD_INPUT`] for a non-finite point, [`E_FULL`] when
    /// the joint store is full.
    pub fn drag_begin(&mut self, x: f64, y: f64) -> Result<(), Fail> {
        let p = Vector2::checked_from_f64(x, y).ok_or_else(|| Fail::new(E_BAD_INPUT, "not a point"))?;
        let w = self.world();
        let mut found = [None::<BodyHandle>; 1].map(|_| BodyHandle::default());
        let n = w.query_point(p, QueryFilter::new().skip_static(true).skip_sensors(true), &mut found);
        let body = if n > 0 { Some(found[0]) } else { None };
        let Some(body) = body.filter(|h| w.body(*h).is_ok_and(|b| b.is_dynamic())) else {
            let any = w.query_point(p, QueryFilter::new(), &mut found);
            return Err(Fail::new(
                E_NOT_DRAGGABLE,
                if any > 0 { "that body is static: it cannot be dragged" } else { "no body there to drag" },
            ));
        };
        let anchor = w.body(body)?.transform().apply_inv(p);
        self.drag_end();
        self.input(Input::DragBegin { body, anchor, target: p })
    }

    /// Moves the held point's target to `(x, y)` (held to the world's bounds:
    /// the mouse may leave them).
    ///
    /// # Errors
    /// [`E_BAD_INPUT`] for a non-finite point; nothing held is not an error.
    pub fn drag_move(&mut self, x: f64, y: f64) -> Result<(), Fail> {
        let p = Vector2::checked_from_f64(x, y).ok_or_else(|| Fail::new(E_BAD_INPUT, "not a point"))?;
        if self.drag.is_none() {
            return Ok(());
        }
        let b = self.world().bounds();
        let p = Vector2::new(p.x.clamp(b.min.x, b.max.x), p.y.clamp(b.min.y, b.max.y));
        self.input(Input::DragMove(p))
    }

    /// Lets go: the target joint is removed and the body flies on with the
    /// speed it had (a throw).
    pub fn drag_end(&mut self) {
        if self.drag.is_some() {
            // Removing a joint that exists cannot fail; a body the scene lost
            // took its joint with it, which is fine too.
            let _ = self.input(Input::DragEnd);
        }
    }

    /// Rewinds as many frames as the ring holds (60, fewer for a huge scene or
    /// early in a run), restores the snapshot and re-simulates them with the
    /// same inputs; the hash must come back the same.
    ///
    /// # Errors
    /// [`E_NO_HISTORY`] with nothing recorded; [`E_MISMATCH`] if the hash
    /// differs (the world is then the re-simulated one); engine errors.
    pub fn rollback(&mut self) -> Result<Rollback, Fail> {
        let Some(first) = self.ring.front() else {
            return Err(Fail::new(E_NO_HISTORY, "nothing to roll back yet: step first"));
        };
        let before = self.world().state_hash();
        let from = first.frame;
        let frames = self.frame - from;
        // The demo scenes' spawners hold a random generator and path handles
        // outside the world: rebuild the scene, run its spawner up to `from`
        // (adding bodies that the restore then replaces) and restore the
        // snapshot into that world. Its handles carry the new world's tag: the
        // recorded drags are re-tagged (same slots and generations).
        let scene = self.scenes[self.scene];
        let (mut fresh, spawn_box) = build(&scene, self.loaded_substeps)?;
        let (drag, sensor_totals) = (first.drag, first.sensor_totals);
        for f in 0..from {
            // Errors here (a full world) are those of the real run; the
            // generator advanced all the same.
            let _ = fresh.before_step(f);
        }
        fresh.world_mut().restore(&self.ring[0].snapshot)?;
        self.running = fresh;
        self.spawn_box = spawn_box;
        // The drag as it was at the first recorded frame, in the new world;
        // the recorded inputs take it from there.
        let w = self.running.world();
        self.drag = drag.map(|d| Drag {
            body: w.handle_from_parts(d.body.index(), d.body.generation()),
            joint: w.handle_from_parts(d.joint.index(), d.joint.generation()),
            ..d
        });
        self.sensor_totals = sensor_totals;
        self.sensor_log.retain(|n| n.frame <= from);
        for k in 0..self.ring.len() {
            let Some(rec) = self.ring.get(k) else { break };
            let (frame, inputs) = (rec.frame, if k > 0 { rec.inputs.clone() } else { Vec::new() });
            for i in inputs {
                apply_input(self.running.world_mut(), self.spawn_box, &mut self.drag, i)?;
            }
            step_frame(&mut self.running, frame)?;
            self.frame = frame + 1;
            self.note_sensor_events();
        }
        for i in self.inputs.clone() {
            apply_input(self.running.world_mut(), self.spawn_box, &mut self.drag, i)?;
        }
        let after = self.world().state_hash();
        let r = Rollback { frames, before, after };
        if before == after {
            Ok(r)
        } else {
            Err(Fail::new(
                E_MISMATCH,
                format!("rollback of {frames} frames re-simulated to {after:016x}, not {before:016x}"),
            ))
        }
    }

    /// The draw list as [`Testbed::draw_list`] last filled it.
    pub fn last_draw_list(&self) -> &[f32] {
        &self.draw
    }

    /// Fills the draw list (see [`DRAW_STRIDE`]) and returns it.
    pub fn draw_list(&mut self) -> &[f32] {
        let mut out = std::mem::take(&mut self.draw);
        out.clear();
        let held = self.drag.map(|d| d.body);
        let w = self.running.world();
        for (h, b) in w.bodies() {
            // A record per shape (a compound body has several, each placed on the body).
            let shapes: Vec<(Shape, arphysics::Transform)> =
                w.shapes(h).map(|it| it.map(|(_, s)| (s.shape, s.local)).collect()).unwrap_or_default();
            for (shape, local) in shapes {
                let xf = b.transform().compose(local);
                let (x, y) = xf.p.to_f32();
                let mut flags = 0u32;
                if b.is_static() {
                    flags |= 1;
                } else if !b.is_dynamic() {
                    flags |= 2;
                }
                if held == Some(h) {
                    flags |= 4;
                }
                if b.is_sensor() {
                    flags |= 8;
                }
                if b.is_out_of_bounds() {
                    flags |= 16;
                }
                let mut rec = [0f32; DRAW_STRIDE];
                rec[1] = flags as f32;
                rec[2] = x;
                rec[3] = y;
                rec[4] = xf.q.angle().to_num::<f32>();
                let points = |pts: &mut dyn Iterator<Item = Vector2>, rec: &mut [f32; DRAW_STRIDE]| {
                    let mut n = 0;
                    for (k, p) in pts.take(8).enumerate() {
                        let (px, py) = xf.apply(p).to_f32();
                        rec[8 + 2 * k] = px;
                        rec[9 + 2 * k] = py;
                        n = k + 1;
                    }
                    rec[6] = n as f32;
                };
                match shape {
                    Shape::Circle { radius } => {
                        rec[0] = 0.0;
                        rec[5] = radius.to_num::<f32>();
                    }
                    Shape::Polygon(p) => {
                        rec[0] = 1.0;
                        if let Ok(path) = w.path(p) {
                            rec[5] = path.rounding().to_num::<f32>();
                            points(&mut path.vertices().iter().copied(), &mut rec);
                        }
                    }
                    Shape::Capsule(c) => {
                        rec[0] = 2.0;
                        rec[5] = c.radius().to_num::<f32>();
                        points(&mut [c.center1(), c.center2()].into_iter(), &mut rec);
                    }
                    Shape::Segment(s) => {
                        rec[0] = 3.0;
                        points(&mut [s.point1(), s.point2()].into_iter(), &mut rec);
                    }
                    // A chain: one segment record per link.
                    Shape::Chain(c) => {
                        rec[0] = 3.0;
                        for i in 0..c.links() as u32 {
                            let Some(link) = w.chain_link(c, i) else { break };
                            let sg = link.segment();
                            points(&mut [sg.point1(), sg.point2()].into_iter(), &mut rec);
                            out.extend_from_slice(&rec);
                        }
                        continue;
                    }
                }
                out.extend_from_slice(&rec);
            }
        }
        // Joints, kind 5: a line between the anchors (world points); the drag's
        // own is drawn last, as kind 4.
        let drag_joint = self.drag.map(|d| d.joint);
        for (h, j) in w.joints() {
            if Some(h) == drag_joint {
                continue;
            }
            let def = j.def();
            let Ok(a) = w.body(def.body_a) else { continue };
            let pa = a.transform().apply(def.anchor_a);
            let pb = match def.body_b {
                Some(h) => match w.body(h) {
                    Ok(b) => b.transform().apply(def.anchor_b),
                    Err(_) => continue,
                },
                None => def.anchor_b,
            };
            let mut rec = [0f32; DRAW_STRIDE];
            rec[0] = 5.0;
            rec[6] = 2.0;
            let ((ax, ay), (bx, by)) = (pa.to_f32(), pb.to_f32());
            rec[8..12].copy_from_slice(&[ax, ay, bx, by]);
            out.extend_from_slice(&rec);
        }
        // The drag, as a last record of kind 4: from the held point to the mouse.
        if let Some(d) = self.drag {
            if let Ok(b) = w.body(d.body) {
                let mut rec = [0f32; DRAW_STRIDE];
                rec[0] = 4.0;
                rec[6] = 2.0;
                let (ax, ay) = b.transform().apply(d.anchor).to_f32();
                let (tx, ty) = d.target.to_f32();
                rec[8..12].copy_from_slice(&[ax, ay, tx, ty]);
                out.extend_from_slice(&rec);
            }
        }
        self.draw = out;
        &self.draw
    }
}

/// Adds a spawned body.
fn apply_spawn(w: &mut World<'static>, spawn_box: PathHandle, s: Spawn) -> Result<BodyHandle, Error> {
    let def = if s.ball { BodyDef::circle(SPAWN_BALL) } else { BodyDef::polygon(spawn_box) };
    w.add_body(def.position(s.at))
}

/// Applies an input to the world, updating the drag in progress. Handles in
/// the input are taken by slot and generation, so an input recorded in one
/// world replays in the rebuilt world of a rollback.
fn apply_input(
    w: &mut World<'static>,
    spawn_box: PathHandle,
    drag: &mut Option<Drag>,
    input: Input,
) -> Result<(), Fail> {
    match input {
        Input::Spawn(s) => {
            apply_spawn(w, spawn_box, s).map_err(|e| match e {
                Error::CapacityFull { what } => Fail::new(E_FULL, format!("the world is full ({what})")),
                e => Fail::from(e),
            })?;
        }
        Input::DragBegin { body, anchor, target } => {
            let body = w.handle_from_parts(body.index(), body.generation());
            let max_force = (w.body(body)?.mass() * DRAG_FORCE_PER_KG).min(arphysics::limits::MAX_FORCE);
            let kind = JointKind::Target { hertz: DRAG_HERTZ, damping_ratio: DRAG_DAMPING_RATIO, max_force };
            let joint = w.add_joint(JointDef::to_world(body, anchor, target, kind)).map_err(|e| match e {
                Error::CapacityFull { .. } => Fail::new(E_FULL, "no room for the drag joint"),
                e => Fail::from(e),
            })?;
            *drag = Some(Drag { body, anchor, target, joint });
        }
        Input::DragMove(p) => {
            if let Some(d) = drag {
                w.set_joint_target(d.joint, p)?;
                d.target = p;
            }
        }
        Input::DragEnd => {
            if let Some(d) = drag.take() {
                // Gone already only if its body was removed: nothing to do then.
                let _ = w.remove_joint(d.joint);
            }
        }
        Input::Substeps(n) => w.set_substeps(n)?,
    }
    Ok(())
}

/// One frame: the scene's additions, then the step. Returns the scene's note
/// if its spawner failed (the step still happens).
fn step_frame(running: &mut scenes::Running, frame: u32) -> Result<Option<String>, Fail> {
    let note = running.before_step(frame).err().map(|e| format!("scene spawner: {e}"));
    running.world_mut().step(dt())?;
    Ok(note)
}

/// One action of a scripted input sequence: what the page's mouse and
/// controls do, as data, so the native build and the page can play the same
/// sequence and compare hashes (coordinates in metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Step this many frames.
    Step(u32),
    /// Press on (x, y): take hold of the body there.
    DragBegin(f64, f64),
    /// Move the mouse to (x, y).
    DragMove(f64, f64),
    /// Release.
    DragEnd,
    /// Spawn a ball (true) or a box at (x, y).
    Spawn(bool, f64, f64),
    /// Change the sub-step count.
    Substeps(u32),
}

/// A scripted input sequence on a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    /// The scene's name.
    pub scene: &'static str,
    /// The actions, in order.
    pub actions: Vec<Action>,
}

/// The scripted drag the browser check plays and compares with the native
/// build: on pyramid_20, take the top box, lift it slowly for 40 frames, go
/// to 8 sub-steps, sweep it right fast and let go (a throw), spawn a ball,
/// back to 4 sub-steps. Coordinates are simple sums of f64, printed in the
/// page's info as the shortest decimal that reads back to the same f64.
pub fn drag_script() -> Script {
    let mut a = vec![Action::Step(30), Action::DragBegin(0.0, 19.5)];
    for k in 1..=40 {
        let k = f64::from(k);
        a.push(Action::DragMove(-0.1 * k, 19.5 + 0.12 * k));
        a.push(Action::Step(1));
    }
    a.push(Action::Substeps(8));
    for k in 1..=15 {
        a.push(Action::DragMove(-4.0 + 0.6 * f64::from(k), 24.3));
        a.push(Action::Step(1));
    }
    a.extend_from_slice(&[
        Action::DragEnd,
        Action::Spawn(true, 5.0, 12.0),
        Action::Step(60),
        Action::Substeps(4),
        Action::Step(30),
    ]);
    Script { scene: "pyramid_20", actions: a }
}

impl Script {
    /// The script as JSON: `{"scene":…,"actions":[["step",30],["begin",x,y],
    /// ["move",x,y],["end"],["spawn",0|1,x,y],["substeps",n],…]}`.
    pub fn to_json(&self) -> String {
        let actions: Vec<String> = self
            .actions
            .iter()
            .map(|a| match *a {
                Action::Step(n) => format!("[\"step\",{n}]"),
                Action::DragBegin(x, y) => format!("[\"begin\",{x},{y}]"),
                Action::DragMove(x, y) => format!("[\"move\",{x},{y}]"),
                Action::DragEnd => "[\"end\"]".to_string(),
                Action::Spawn(ball, x, y) => format!("[\"spawn\",{},{x},{y}]", u8::from(ball)),
                Action::Substeps(n) => format!("[\"substeps\",{n}]"),
            })
            .collect();
        format!("{{\"scene\":\"{}\",\"actions\":[{}]}}", self.scene, actions.join(","))
    }
}

impl Testbed {
    /// Plays one scripted action as the page's controls would.
    ///
    /// # Errors
    /// What the control fails with.
    pub fn play(&mut self, action: Action) -> Result<(), Fail> {
        match action {
            Action::Step(n) => (0..n).try_for_each(|_| self.step()),
            Action::DragBegin(x, y) => self.drag_begin(x, y),
            Action::DragMove(x, y) => self.drag_move(x, y),
            Action::DragEnd => {
                self.drag_end();
                Ok(())
            }
            Action::Spawn(ball, x, y) => self.spawn(ball, x, y),
            Action::Substeps(n) => self.set_substeps(n),
        }
    }

    /// Loads the script's scene at 4 sub-steps and plays it.
    ///
    /// # Errors
    /// [`E_NO_SCENE`] or what an action fails with.
    pub fn run_script(script: &Script) -> Result<Self, Fail> {
        let index = Self::scene_index(script.scene)
            .ok_or_else(|| Fail::new(E_NO_SCENE, format!("no scene named {}", script.scene)))?;
        let mut t = Self::new(index, 4)?;
        for a in &script.actions {
            t.play(*a)?;
        }
        Ok(t)
    }
}
