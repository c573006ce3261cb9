//! A full store never stops the game (issue 15, items 7 and 9): candidate pairs
//! and arbiters beyond the contact capacity are skipped by a deterministic
//! policy and counted, duplicates from a custom index use no capacity, the
//! strict error stays available, `stats()` reports high-water marks, and
//! capacities the heap cannot hold are an `Err`.

use arphysics::index::proxies_may_touch;
use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}
fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}
const DT: f64 = 1.0 / 60.0;

/// 300 boxes in a wall on the ground and one ball flying into it at 300 m/s,
/// with room for three contacts a body: the resting wall alone makes about
/// 1,100 candidate pairs (each box's neighbours, the diagonal ones within the
/// speculative distance included), and the impact more.
fn wall_and_bullet(strict: bool) -> World<'static> {
    // The wall's far boxes leave at about 43 m/s and tumble along the
    // floor: the farthest reached 180 m while deep overlaps were pushed out
    // by velocity, 242 m since they are pushed out by motion (a tumbling
    // box's deep corner hits no longer add push-out impulse, nor the
    // friction it allowed); the floor spans ±300 m.
    let bounds = Rect::from_corners(v(-290.0, -10.0), v(290.0, 200.0));
    let def = WorldDef { strict_capacity: strict, ..WorldDef::with_bounds(bounds) };
    let mut w = World::with_capacities(def, Capacities { contacts: 3 * 304, ..Capacities::for_bodies(304) })
        .expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let ground = w.add_path(PolygonPath::rectangle(s(200.0), s(2.0)).expect("ground")).expect("path");
    // The floor spans the bounds: boxes kicked far must not fall off its end.
    for x in [0.0, -200.0, 200.0] {
        w.add_body(BodyDef::polygon(ground).position(v(x, -1.0)).static_body()).expect("ground");
    }
    let crate_path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    for row in 0..20 {
        for col in 0..15 {
            let p = v(f64::from(col) * 1.0 + 0.5, f64::from(row) * 1.0 + 0.5);
            w.add_body(BodyDef::polygon(crate_path).position(p).mass(s(1.0))).expect("box");
        }
    }
    w.add_body(BodyDef::circle(s(0.5)).position(v(-20.0, 5.0)).linear_velocity(v(300.0, 0.0)).mass(s(5.0)))
        .expect("ball");
    w
}

#[test]
fn three_hundred_boxes_hit_at_300_m_per_s_step_600_times_and_report_the_drops() {
    let mut w = wall_and_bullet(false);
    let (mut pairs_dropped, mut arbiters_dropped, mut steps_with_drops) = (0u64, 0u64, 0u32);
    for _ in 0..600 {
        let r = w.step(s(DT)).expect("a full store never fails the step");
        pairs_dropped += u64::from(r.pairs_dropped);
        arbiters_dropped += u64::from(r.arbiters_dropped);
        if r.pairs_dropped + r.arbiters_dropped > 0 {
            steps_with_drops += 1;
        }
        assert!(r.candidate_pairs as usize <= w.stats().capacities.contacts);
        assert!(r.arbiters as usize <= w.stats().capacities.contacts);
    }
    let stats = w.stats();
    println!(
        "{steps_with_drops} steps with drops; pairs dropped {pairs_dropped}, arbiters dropped \
         {arbiters_dropped}; {stats:?}"
    );
    assert!(pairs_dropped + arbiters_dropped > 0, "the scene overflows the contact store");
    assert_eq!(stats.pairs_dropped, pairs_dropped, "the stats add up the reports");
    assert_eq!(stats.arbiters_dropped, arbiters_dropped);
    assert!(stats.peak_pairs > stats.capacities.contacts, "the peak says how much room was needed");
    assert_eq!(stats.peak_bodies, 304);
    // Nothing left the world or went through the ground (bodies 0–2).
    for (_, b) in w.bodies().skip(3) {
        assert!(!b.is_out_of_bounds());
        assert!(b.position().y > s(-0.5), "a box fell through the ground: {:?}", b.position().to_f64());
    }
}

#[test]
fn the_strict_mode_fails_the_same_scene_and_changes_nothing() {
    let mut w = wall_and_bullet(true);
    let mut failed = 0;
    for _ in 0..600 {
        let before = w.state_hash();
        match w.step(s(DT)) {
            Ok(_) => {}
            Err(e) => {
                assert!(matches!(e, Error::CapacityFull { .. }), "{e:?}");
                assert_eq!(w.state_hash(), before, "a failed step changes nothing");
                failed += 1;
            }
        }
    }
    println!("strict: {failed} of 600 steps failed");
    assert!(failed > 0);
}

#[test]
fn dropping_pairs_is_deterministic_across_identical_worlds() {
    let (mut a, mut b) = (wall_and_bullet(false), wall_and_bullet(false));
    for step in 0..200 {
        assert_eq!(a.step(s(DT)), b.step(s(DT)));
        assert_eq!(a.state_hash(), b.state_hash(), "diverged at step {step}");
    }
}

/// Reports every overlapping pair, twice and in both orders.
struct Twice;
impl SpatialIndex for Twice {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        for i in 0..proxies.len() {
            for j in i + 1..proxies.len() {
                if proxies_may_touch(&proxies[i], &proxies[j]) {
                    out.push(i as u32, j as u32);
                    out.push(j as u32, i as u32);
                }
            }
        }
    }
}

/// Reports every pair (overlapping or not) in reverse order: the kept set when
/// the buffer is full must not depend on the order.
struct Backwards;
impl SpatialIndex for Backwards {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        for i in (0..proxies.len()).rev() {
            for j in (0..i).rev() {
                if proxies_may_touch(&proxies[i], &proxies[j]) {
                    out.push(i as u32, j as u32);
                }
            }
        }
    }
}

fn four_balls(contacts: usize) -> World<'static> {
    let caps = Capacities {
        bodies: 8,
        paths: 1,
        contacts,
        joints: 1,
        post_step_callbacks: 4,
        events: 64,
        chain_vertices: 0,
        shapes: 0,
    };
    let mut w = World::with_capacities(WorldDef::new(s(50.0), s(50.0)), caps).expect("world");
    for x in [10.0, 11.5, 20.0, 21.5] {
        w.add_body(BodyDef::circle(s(1.0)).position(v(x, 10.0))).expect("ball");
    }
    w
}

#[test]
fn duplicate_reports_from_custom_index_use_no_capacity() {
    let mut w = four_balls(3);
    let r = w.step(s(DT)).expect("2 pairs fit in 3");
    assert_eq!((r.candidate_pairs, r.pairs_dropped), (2, 0));
    w.set_spatial_index(Index::boxed(Box::new(Twice)));
    let r = w.step(s(DT)).expect("the same 2 pairs, each reported twice");
    assert_eq!((r.candidate_pairs, r.pairs_dropped, r.arbiters_dropped), (2, 0, 0));
    assert_eq!(r.arbiters, 2);
}

#[test]
fn a_full_pair_buffer_keeps_the_lowest_keys_whatever_the_report_order() {
    // Room for one pair of two: the pair of the lower slots is kept.
    let (mut forward, mut backward) = (four_balls(1), four_balls(1));
    backward.set_spatial_index(Index::boxed(Box::new(Backwards)));
    for _ in 0..10 {
        let (rf, rb) = (forward.step(s(DT)).expect("step"), backward.step(s(DT)).expect("step"));
        assert_eq!(rf, rb);
        assert_eq!((rf.candidate_pairs, rf.pairs_dropped), (1, 1));
        assert_eq!(forward.state_hash(), backward.state_hash());
    }
    let handles: Vec<_> = forward.bodies().map(|(h, _)| h).collect();
    assert!(forward.arbiter(handles[0], handles[1]).is_some(), "the lowest key is kept");
    assert!(forward.arbiter(handles[2], handles[3]).is_none(), "the highest is dropped");
    // The kept pair was resolved, the dropped one was not.
    let gap = |w: &World<'_>, i: usize, j: usize| {
        (w.body(handles[j]).expect("b").position().x - w.body(handles[i]).expect("a").position().x)
            .to_num::<f64>()
    };
    assert!(gap(&forward, 0, 1) > 1.6, "pushed apart: {}", gap(&forward, 0, 1));
    assert!((gap(&forward, 2, 3) - 1.5).abs() < 1e-9, "left overlapping: {}", gap(&forward, 2, 3));
}

#[test]
fn huge_capacities_are_an_error_not_a_panic_or_an_abort() {
    let def = WorldDef::new(s(10.0), s(10.0));
    // The world refuses more slots than a handle can name before it sizes anything.
    let overflow = World::with_capacities(def, Capacities::for_bodies(usize::MAX)).err();
    assert!(matches!(overflow, Some(Error::OutOfRange { .. })), "{overflow:?}");
    // Storage alone checks that the sizes add up.
    let storage = Storage::with_capacities(Capacities::for_bodies(usize::MAX));
    assert_eq!(storage.err(), Some(Error::OutOfRange { what: "capacities" }));
    let too_big = World::with_capacities(def, Capacities::for_bodies(1 << 40));
    assert!(
        matches!(too_big.err(), Some(Error::OutOfMemory { .. } | Error::OutOfRange { .. })),
        "2^40 bodies do not fit the heap"
    );
    let one_buffer = Capacities { post_step_callbacks: 1 << 44, ..Capacities::for_bodies(4) };
    assert!(matches!(World::with_capacities(def, one_buffer).err(), Some(Error::OutOfMemory { .. })));
}
