//! A two-player lockstep/rollback loop in one process: the reason arphysics
//! computes bit-identical worlds.
//!
//! Each peer owns a world and a ball it steers. Every frame it reads its own input,
//! sends it to the other peer (which receives it `DELAY` frames later), predicts
//! the other player's input (the last one it saw), saves a snapshot and steps.
//! When a late input arrives that differs from the prediction, the peer restores
//! the snapshot of that frame and re-simulates up to the present with the true
//! inputs. At the end both peers know every input, and their state hashes agree.
//!
//! Run: `cargo run --release --example rollback`

use std::collections::VecDeque;

use arphysics::{
    BodyDef, BodyHandle, Capacities, GravityForceGenerator, PolygonPath, Rect, Scalar, Vector2, World,
    WorldDef,
};

const FRAMES: u32 = 600;
const DELAY: u32 = 3;
/// Snapshots kept: a late input may rewind at most this many frames.
const WINDOW: usize = 16;

/// One player's input for one frame: −1, 0 or +1 to push left or right, and jump.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Input {
    push: i8,
    jump: bool,
}

/// A deterministic "player": changes its mind every now and then.
fn scripted_input(player: u32, frame: u32) -> Input {
    let phase = (frame / (37 + 11 * player)) % 4;
    Input { push: [-1, 0, 1, 0][phase as usize], jump: (frame + 17 * player).is_multiple_of(90) }
}

fn build() -> Result<(World<'static>, [BodyHandle; 2]), arphysics::Error> {
    let s = Scalar::from_num::<i32>;
    let bounds = Rect::from_corners(Vector2::from_int(-50, -10), Vector2::from_int(50, 90));
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(64))?;
    let floor = w.add_path(PolygonPath::rectangle(s(80), s(2))?)?;
    w.add_body(BodyDef::polygon(floor).position(Vector2::from_int(0, -1)).static_body())?;
    for x in [-40, 40] {
        let wall = w.add_path(PolygonPath::rectangle(s(2), s(40))?)?;
        w.add_body(BodyDef::polygon(wall).position(Vector2::from_int(x, 20)).static_body())?;
    }
    // A pile of crates for the players to push around.
    let unit = w.add_path(PolygonPath::rectangle(s(1), s(1))?)?;
    for i in 0..20 {
        w.add_body(BodyDef::polygon(unit).position(Vector2::from_int(-10 + i % 10 * 2, 1 + i / 10 * 2)))?;
    }
    let p0 = w.add_body(BodyDef::circle(s(1)).position(Vector2::from_int(-20, 2)))?;
    let p1 = w.add_body(BodyDef::circle(s(1)).position(Vector2::from_int(20, 2)))?;
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10)))?;
    Ok((w, [p0, p1]))
}

fn apply(w: &mut World<'_>, players: [BodyHandle; 2], inputs: [Input; 2]) -> Result<(), arphysics::Error> {
    for (h, i) in players.into_iter().zip(inputs) {
        let b = w.body_mut(h)?;
        b.apply_linear_impulse(Vector2::from_int(i32::from(i.push) * 2, if i.jump { 30 } else { 0 }));
    }
    w.step(Scalar::from_num(1) / Scalar::from_num(60)).map(drop)
}

struct Peer {
    me: usize,
    world: World<'static>,
    players: [BodyHandle; 2],
    /// Inputs by frame: mine are known, the other's are known or predicted.
    inputs: Vec<[Input; 2]>,
    /// Which of the other player's inputs are confirmed.
    confirmed: Vec<bool>,
    /// (frame, snapshot taken before stepping that frame).
    snapshots: VecDeque<(u32, Vec<u8>)>,
    rollbacks: u32,
    resimulated: u32,
}

impl Peer {
    fn new(me: usize) -> Result<Self, arphysics::Error> {
        let (world, players) = build()?;
        Ok(Self {
            me,
            world,
            players,
            inputs: Vec::new(),
            confirmed: Vec::new(),
            snapshots: VecDeque::new(),
            rollbacks: 0,
            resimulated: 0,
        })
    }

    /// Simulates `frame` with the inputs known or predicted now.
    fn advance(&mut self, frame: u32) -> Result<(), arphysics::Error> {
        let mut snap = vec![0u8; self.world.snapshot_len()];
        self.world.snapshot(&mut snap)?;
        self.snapshots.push_back((frame, snap));
        if self.snapshots.len() > WINDOW {
            self.snapshots.pop_front();
        }
        apply(&mut self.world, self.players, self.inputs[frame as usize])
    }

    fn local_frame(&mut self, frame: u32) -> Result<Input, arphysics::Error> {
        let mine = scripted_input(self.me as u32, frame);
        // Predict the other player: the last input we have for them.
        let predicted = self.inputs.last().map(|i| i[1 - self.me]).unwrap_or_default();
        let mut both = [Input::default(); 2];
        both[self.me] = mine;
        both[1 - self.me] = predicted;
        self.inputs.push(both);
        self.confirmed.push(false);
        self.advance(frame)?;
        Ok(mine)
    }

    /// The other player's true input for `frame` arrives.
    fn remote_input(&mut self, frame: u32, input: Input, now: u32) -> Result<(), arphysics::Error> {
        let other = 1 - self.me;
        let f = frame as usize;
        self.confirmed[f] = true;
        if self.inputs[f][other] == input {
            return Ok(());
        }
        // Misprediction: fix this frame and re-predict the later unconfirmed ones.
        self.inputs[f][other] = input;
        for later in f + 1..self.inputs.len() {
            if !self.confirmed[later] {
                self.inputs[later][other] = input;
            }
        }
        let Some(pos) = self.snapshots.iter().position(|(sf, _)| *sf == frame) else {
            panic!("input for frame {frame} arrived later than the rollback window");
        };
        self.world.restore(&self.snapshots[pos].1)?;
        self.snapshots.truncate(pos);
        self.rollbacks += 1;
        for g in frame..=now {
            self.advance(g)?;
            self.resimulated += 1;
        }
        Ok(())
    }
}

fn main() -> Result<(), arphysics::Error> {
    let mut peers = [Peer::new(0)?, Peer::new(1)?];
    // Messages in flight: (arrival frame, to peer, input frame, input).
    let mut wire: VecDeque<(u32, usize, u32, Input)> = VecDeque::new();
    for frame in 0..FRAMES {
        for (me, peer) in peers.iter_mut().enumerate() {
            let mine = peer.local_frame(frame)?;
            // Some packets are slower than others: a jitter of up to 2 frames.
            let jitter = (frame * 7 + me as u32 * 3) % 3;
            wire.push_back((frame + DELAY + jitter, 1 - me, frame, mine));
        }
        // Deliver what has arrived, in send order per peer.
        let (due, rest): (Vec<_>, Vec<_>) = wire.drain(..).partition(|m| m.0 <= frame);
        wire = rest.into();
        for (_, to, input_frame, input) in due {
            peers[to].remote_input(input_frame, input, frame)?;
        }
    }
    // Drain the wire: every input arrives, then both peers have the same history.
    let last = FRAMES - 1;
    for (_, to, input_frame, input) in wire.drain(..) {
        peers[to].remote_input(input_frame, input, last)?;
    }
    let (h0, h1) = (peers[0].world.state_hash(), peers[1].world.state_hash());
    for p in &peers {
        println!(
            "peer {}: {} frames, {} rollbacks, {} frames re-simulated, final hash {:#018x}",
            p.me,
            FRAMES,
            p.rollbacks,
            p.resimulated,
            p.world.state_hash()
        );
    }
    // And a third world stepped once with the true inputs, never rolled back.
    let (mut truth, players) = build()?;
    for frame in 0..FRAMES {
        apply(&mut truth, players, [scripted_input(0, frame), scripted_input(1, frame)])?;
    }
    println!("reference (no rollback):                 final hash {:#018x}", truth.state_hash());
    assert!(h0 == h1 && h1 == truth.state_hash(), "peers desynced");
    println!("both peers agree with the reference, bit for bit");
    Ok(())
}
