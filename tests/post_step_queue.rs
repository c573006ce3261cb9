//! The post-step queue is never state between steps (issue 15, items 1 and 8):
//! `step` runs it to exhaustion, a `remove_body` between steps runs what its
//! `end` handlers queued before it returns, so a snapshot taken between steps
//! misses nothing; its capacity is part of `Capacities` and a refusal is counted.

use std::sync::atomic::{AtomicU32, Ordering};

use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}
fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}
const DT: f64 = 1.0 / 60.0;

fn world() -> World<'static> {
    World::with_capacities(WorldDef::new(s(100.0), s(100.0)), Capacities::for_bodies(16)).expect("world")
}

fn remove_key(w: &mut World<'_>, key: u64) {
    let _ = w.remove_body(BodyHandle::from_bits(key));
}

fn end_removes_partner(arb: &Arbiter, ctx: &mut CallbackContext<'_>) {
    for h in [arb.body_a(), arb.body_b()] {
        if ctx.body(h).is_some() {
            let _ = ctx.add_post_step_callback(remove_key, h.to_bits());
        }
    }
}

fn begin_removes_b(arb: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    // The bullet pattern: remove a body after the step.
    let _ = ctx.add_post_step_callback(remove_key, arb.body_b().to_bits());
    true
}

/// A ball that touches nothing, so the scenes' worlds are not empty.
fn add_bystander(w: &mut World<'_>) {
    w.add_body(BodyDef::circle(s(1.0)).position(v(20.0, 20.0)).linear_velocity(v(1.0, 0.5)))
        .expect("bystander");
}

/// Builds `scene` twice, snapshots and restores one, steps both: equal reports
/// and equal hashes. Returns the report.
fn restore_then_step_equals_stepping_on(scene: impl Fn() -> World<'static>) -> StepReport {
    let (mut plain, mut rolled) = (scene(), scene());
    let mut snap = vec![0u8; rolled.snapshot_len()];
    rolled.snapshot(&mut snap).expect("snapshot");
    rolled.restore(&snap).expect("restore");
    assert_eq!(plain.state_hash(), rolled.state_hash());
    let (rp, rr) = (plain.step(s(DT)).expect("step"), rolled.step(s(DT)).expect("step"));
    assert_eq!(rp, rr);
    assert_eq!(plain.state_hash(), rolled.state_hash(), "restoring the current state changed the future");
    rp
}

#[test]
fn restore_drops_queued_post_step_callbacks() {
    let scene = || {
        let mut w = world();
        w.add_collision_handler(0, 0, FnHandler { end: Some(end_removes_partner), ..FnHandler::default() })
            .expect("handler");
        add_bystander(&mut w);
        let a = w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).expect("a");
        w.add_body(BodyDef::circle(s(1.0)).position(v(51.5, 50.0))).expect("b");
        for _ in 0..3 {
            w.step(s(DT)).expect("step");
        }
        w.remove_body(a).expect("remove"); // `end` queues the partner's removal...
        assert_eq!(w.body_count(), 1, "...which ran before remove_body returned");
        w
    };
    restore_then_step_equals_stepping_on(scene);
}

#[test]
fn snapshot_between_frames_misses_queued_callbacks() {
    let scene = || {
        let mut w = world();
        let handler = FnHandler {
            begin: Some(begin_removes_b),
            end: Some(end_removes_partner),
            ..FnHandler::default()
        };
        w.add_collision_handler(0, 0, handler).expect("handler");
        add_bystander(&mut w);
        w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).expect("a");
        w.add_body(BodyDef::circle(s(1.0)).position(v(51.5, 50.0))).expect("b");
        w.add_body(BodyDef::circle(s(1.0)).position(v(48.5, 50.0))).expect("c");
        // begin -> post-step removal -> end -> another removal, in the same step.
        let r = w.step(s(DT)).expect("step");
        assert!(r.post_step_callbacks >= 3, "the second round ran in this step: {r:?}");
        assert_eq!((r.post_step_dropped, r.post_step_refused), (0, 0));
        assert_eq!(w.body_count(), 1, "every removal the chain asked for is done");
        w
    };
    let next = restore_then_step_equals_stepping_on(scene);
    assert_eq!(next.post_step_callbacks, 0, "nothing was left queued");
}

#[test]
fn a_chain_of_removals_deeper_than_the_round_limit_is_cut_and_counted() {
    use arphysics::handler::MAX_POST_STEP_ROUNDS;
    let n = MAX_POST_STEP_ROUNDS as usize + 40;
    let def = WorldDef::new(s(1000.0), s(100.0));
    let mut w = World::with_capacities(def, Capacities::for_bodies(n)).expect("world");
    w.add_collision_handler(0, 0, FnHandler { end: Some(end_removes_partner), ..FnHandler::default() })
        .expect("handler");
    // A row of touching balls: removing one ends its pair with the next, whose
    // `end` queues the next's removal, one round per ball.
    let first = w.add_body(BodyDef::circle(s(1.0)).position(v(2.0, 50.0))).expect("ball");
    for i in 1..n {
        w.add_body(BodyDef::circle(s(1.0)).position(v(2.0 + 1.9 * i as f64, 50.0))).expect("ball");
    }
    w.step(s(DT)).expect("step");
    assert_eq!(w.arbiters().count(), n - 1);
    w.remove_body(first).expect("remove");
    // The first removal happens at once; each round removes one more ball.
    let removed = 1 + MAX_POST_STEP_ROUNDS as usize;
    assert_eq!(w.body_count(), n - removed);
    // Left queued after the last round, and counted: the next ball's removal
    // and the ball just removed (readable during `end`, so named too).
    assert_eq!(w.stats().post_step_dropped, 2);
    let r = w.step(s(DT)).expect("step");
    assert_eq!(r.post_step_callbacks, 0, "the cut chain does not leak into the next step");
}

static REFUSED_SEEN: AtomicU32 = AtomicU32::new(0);

std::thread_local! {
    /// Removals the queue took, in this test's thread (the world calls its
    /// callbacks in the thread that steps it).
    static ACCEPTED: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
}

fn begin_removes_the_ball(arb: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
    if let Some((ball, _ground)) = arb.bodies_by_level(1) {
        if ctx.add_post_step_callback(remove_key, ball.to_bits()).is_err() {
            REFUSED_SEEN.fetch_add(1, Ordering::Relaxed);
        } else {
            ACCEPTED.set(ACCEPTED.get() + 1);
        }
    }
    true
}

/// 1,000 balls in 10 rows of 100 falling onto the ground; `begin` with the
/// ground removes the ball. Returns the world after `steps` steps and the sum
/// of the reports' refusals.
fn thousand_balls(post_step_callbacks: usize, steps: u32) -> (World<'static>, u32) {
    let caps = Capacities { post_step_callbacks, ..Capacities::for_bodies(1001) };
    let mut w = World::with_capacities(WorldDef::new(s(120.0), s(60.0)), caps).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let ground = w.add_path(PolygonPath::rectangle(s(110.0), s(2.0)).expect("ground")).expect("path");
    w.add_body(BodyDef::polygon(ground).position(v(60.0, 1.0)).static_body()).expect("ground");
    w.add_collision_handler(0, 1, FnHandler { begin: Some(begin_removes_the_ball), ..FnHandler::default() })
        .expect("handler");
    for row in 0..10 {
        for col in 0..100 {
            let p = v(10.5 + f64::from(col), 4.0 + 4.0 * f64::from(row));
            w.add_body(BodyDef::circle(s(0.4)).position(p).collision_level(1)).expect("ball");
        }
    }
    let mut refused = 0;
    for _ in 0..steps {
        refused += w.step(s(DT)).expect("step").post_step_refused;
    }
    (w, refused)
}

#[test]
fn a_thousand_balls_landing_are_all_removed_by_their_begin_callbacks() {
    let (w, refused) = thousand_balls(Capacities::for_bodies(1001).post_step_callbacks, 300);
    assert_eq!(refused, 0);
    assert_eq!(w.body_count(), 1, "only the ground is left");
    let stats = w.stats();
    assert!(stats.peak_post_step_callbacks >= 100, "a row lands at once: {stats:?}");
    assert!(stats.peak_post_step_callbacks <= stats.capacities.post_step_callbacks);
}

#[test]
fn a_small_queue_refuses_what_does_not_fit_and_the_report_counts_it() {
    REFUSED_SEEN.store(0, Ordering::Relaxed);
    ACCEPTED.set(0);
    // The old fixed queue: 64.
    let (w, refused) = thousand_balls(arphysics::handler::DEFAULT_POST_STEP_CALLBACKS, 300);
    let seen = REFUSED_SEEN.load(Ordering::Relaxed);
    let removed = 1000 - (w.body_count() - 1);
    println!("queue of 64: {refused} refused, {removed} balls removed, {} never", w.body_count() - 1);
    assert!(refused > 0, "a row of 100 does not fit 64");
    assert_eq!(refused, seen, "every Err the callbacks saw is in a step report");
    assert_eq!(w.stats().post_step_refused, u64::from(seen));
    assert_eq!(w.stats().peak_post_step_callbacks, 64);
    // A refused removal is not retried: every ball removed is one whose
    // removal the queue took (a ball the queue refused is removed only if
    // it leaves the ground and lands again, and that begin is accepted).
    assert_eq!(removed as u32, ACCEPTED.get(), "a removal the queue refused ran");
}
