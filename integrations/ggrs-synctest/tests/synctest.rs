//! Runs an arphysics world through ggrs's `SyncTestSession` for 600 frames: every
//! frame ggrs saves the state, advances, then rolls back `CHECK_DISTANCE` frames,
//! re-simulates and compares checksums. The state is an arphysics snapshot, the
//! checksum its `state_hash`; any nondeterminism makes ggrs report a mismatch.

use arphysics::{
    BodyDef, BodyHandle, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World,
    WorldDef,
};
use ggrs::{Config, GgrsRequest, PlayerType, PredictRepeatLast, SessionBuilder};
use serde::{Deserialize, Serialize};

const FRAMES: u32 = 600;
const CHECK_DISTANCE: usize = 7;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
struct Input {
    push: i8,
    jump: bool,
}

struct Physics;

impl Config for Physics {
    type Input = Input;
    type InputPredictor = PredictRepeatLast;
    /// The snapshot bytes.
    type State = Vec<u8>;
    type Address = u8;
}

fn build() -> (World<'static>, [BodyHandle; 2]) {
    let s = Scalar::from_num::<i32>;
    let bounds = Rect::from_corners(Vector2::from_int(-50, -10), Vector2::from_int(50, 90));
    let mut w =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(64)).expect("world");
    let floor = w.add_path(PolygonPath::rectangle(s(80), s(2)).expect("floor")).expect("path");
    w.add_body(BodyDef::polygon(floor).position(Vector2::from_int(0, -1)).static_body()).expect("floor");
    let unit = w.add_path(PolygonPath::rectangle(s(1), s(1)).expect("box")).expect("path");
    for i in 0..20 {
        w.add_body(BodyDef::polygon(unit).position(Vector2::from_int(-10 + i % 10 * 2, 1 + i / 10 * 2)))
            .expect("crate");
    }
    let p0 = w.add_body(BodyDef::circle(s(1)).position(Vector2::from_int(-20, 2))).expect("p0");
    let p1 = w.add_body(BodyDef::circle(s(1)).position(Vector2::from_int(20, 2))).expect("p1");
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10))).expect("gravity");
    (w, [p0, p1])
}

fn scripted(player: u32, frame: u32) -> Input {
    let phase = (frame / (37 + 11 * player)) % 4;
    Input { push: [-1, 0, 1, 0][phase as usize], jump: (frame + 17 * player).is_multiple_of(90) }
}

#[test]
fn six_hundred_frames_under_a_sync_test_session() {
    let (mut world, players) = build();
    let mut session = SessionBuilder::<Physics>::new()
        .with_num_players(2)
        .expect("players")
        .with_check_distance(CHECK_DISTANCE)
        .add_player(PlayerType::Local, 0)
        .expect("p0")
        .add_player(PlayerType::Local, 1)
        .expect("p1")
        .start_synctest_session()
        .expect("session");
    let (mut saves, mut loads, mut advances) = (0u32, 0u32, 0u32);
    for frame in 0..FRAMES {
        for p in 0..2 {
            session.add_local_input(p, scripted(p as u32, frame)).expect("input");
        }
        for request in session.advance_frame().expect("advance") {
            match request {
                GgrsRequest::SaveGameState { cell, frame } => {
                    let mut snap = vec![0u8; world.snapshot_len()];
                    world.snapshot(&mut snap).expect("snapshot");
                    let checksum = u128::from(world.state_hash());
                    cell.save(frame, Some(snap), Some(checksum));
                    saves += 1;
                }
                GgrsRequest::LoadGameState { cell, .. } => {
                    let snap = cell.load().expect("a saved state");
                    world.restore(&snap).expect("restore");
                    loads += 1;
                }
                GgrsRequest::AdvanceFrame { inputs } => {
                    for (h, (input, _)) in players.iter().zip(inputs) {
                        let b = world.body_mut(*h).expect("player");
                        b.apply_linear_impulse(Vector2::from_int(
                            i32::from(input.push) * 2,
                            if input.jump { 30 } else { 0 },
                        ));
                    }
                    world.step(Scalar::from_num(1) / Scalar::from_num(60)).expect("step");
                    advances += 1;
                }
            }
        }
    }
    println!(
        "{FRAMES} frames: {saves} saves, {loads} rollbacks, {advances} advances; final hash {:#018x}",
        world.state_hash()
    );
    // ggrs starts rolling back once it has `CHECK_DISTANCE` + 1 frames behind it.
    assert_eq!(loads, FRAMES - CHECK_DISTANCE as u32 - 1, "ggrs rolled back every frame");
    assert_eq!(advances, FRAMES + loads * CHECK_DISTANCE as u32);
}
