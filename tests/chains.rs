//! Chains (issue 19, part 3): static polylines and loops whose links are
//! one-sided with ghost vertices, so bodies slide across the joins without
//! catching; their mid-phase, queries, continuous collision, snapshots and
//! bad input.

use arphysics::snapshot::ARBITER_MANIFOLDS;
use arphysics::{
    BodyDef, BodyHandle, Capacities, Capsule, ChainPath, Error, GravityForceGenerator, PolygonPath,
    QueryFilter, QueryShape, Rect, Scalar, Transform, Vector2, World, WorldDef,
};

mod common;

use common::{dt, f, s, v, world_with};

/// A 400 × 200 m world with gravity (0, −10) and room for 512 chain points.
fn world() -> World<'static> {
    common::world_with(200.0, 100.0, Capacities { chain_vertices: 512, ..Capacities::for_bodies(256) }, true)
}

/// Flat ground at y = 0 from x = −2 to 98: 100 collinear 1 m links, walked
/// right to left so their front faces up.
fn flat_chain(w: &mut World<'static>) -> BodyHandle {
    let points: Vec<Vector2> = (0..=100).rev().map(|i| v(f64::from(i) - 2.0, 0.0)).collect();
    let chain = w.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain)).expect("ground")
}

/// How a body slid: its height's range (m) and its largest upward speed (m/s)
/// once settled, and how far it went.
struct Slide {
    height_range: f64,
    max_up: f64,
    travelled: f64,
}

/// A frictionless 1 m box set down on the ground at x = 0 and pushed to
/// 4 m/s along +x, stepped for 4 s; measured after the first 0.5 s.
fn slide_box(mut w: World<'static>) -> Slide {
    let path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    let b = w.add_body(BodyDef::polygon(path).position(v(0.0, 0.5)).friction(Scalar::ZERO)).expect("box");
    for _ in 0..30 {
        w.step(dt()).expect("step");
    }
    w.body_mut(b).expect("box").set_linear_velocity(v(4.0, 0.0));
    let x0 = f(w.body(b).expect("box").position().x);
    let (mut lo, mut hi, mut up) = (f64::MAX, f64::MIN, f64::MIN);
    for _ in 0..240 {
        w.step(dt()).expect("step");
        let body = w.body(b).expect("box");
        let y = f(body.position().y);
        lo = lo.min(y);
        hi = hi.max(y);
        up = up.max(f(body.linear_velocity().y));
    }
    let travelled = f(w.body(b).expect("box").position().x) - x0;
    Slide { height_range: hi - lo, max_up: up, travelled }
}

#[test]
fn a_box_slides_over_100_collinear_links_without_catching() {
    let mut w = world();
    flat_chain(&mut w);
    let chain = slide_box(w);
    // The same over a row of 100 static 1 m boxes (tops at y = 0), for
    // comparison only.
    let mut w = world();
    let tile = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("tile")).expect("path");
    for i in 0..100 {
        w.add_body(BodyDef::polygon(tile).position(v(f64::from(i) - 1.5, -0.5)).static_body()).expect("tile");
    }
    let boxes = slide_box(w);
    println!(
        "chain: height range {:.6} m, max upward speed {:.6} m/s, travelled {:.2} m",
        chain.height_range, chain.max_up, chain.travelled
    );
    println!(
        "boxes: height range {:.6} m, max upward speed {:.6} m/s, travelled {:.2} m",
        boxes.height_range, boxes.max_up, boxes.travelled
    );
    assert!(chain.travelled > 15.0, "the box should cross many joins: {:.2} m", chain.travelled);
    assert!(chain.height_range <= 1e-3, "height varied by {:.6} m", chain.height_range);
    assert!(chain.max_up <= 1e-3, "gained {:.6} m/s upward", chain.max_up);
}

#[test]
fn a_box_on_a_long_chain_has_arbiters_for_the_links_under_it_only() {
    let mut w = world();
    flat_chain(&mut w);
    let path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    // Centred over the join at x = 40 (links 57 and 58).
    w.add_body(BodyDef::polygon(path).position(v(40.0, 0.5))).expect("box");
    for _ in 0..30 {
        w.step(dt()).expect("step");
    }
    let links: Vec<u32> = w.arbiters().map(|a| a.link()).collect();
    assert!(!links.is_empty() && links.len() <= 3, "{links:?}");
    assert!(links.windows(2).all(|p| p[0] < p[1]), "in link order: {links:?}");
    assert!(links.iter().all(|&l| (56..=59).contains(&l)), "{links:?}");
}

#[test]
fn a_capsule_character_walks_up_a_30_degree_slope_and_over_the_top_without_a_bump() {
    let mut w = world();
    let top = 10.0 * (30f64).to_radians().tan();
    // Right to left: flat top, the slope down, flat ground.
    let points = [v(40.0, top), v(10.0, top), v(0.0, 0.0), v(-10.0, 0.0)];
    let chain = w.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain).friction(s(0.8))).expect("ground");
    let cap = Capsule::new(v(0.0, -0.4), v(0.0, 0.4), s(0.3)).expect("capsule");
    let c = w
        .add_body(BodyDef::capsule(cap).position(v(-5.0, 0.7)).fixed_rotation(true).friction(s(0.8)))
        .expect("character");
    let speed = 3.0;
    let (mut worst_jump, mut last_vy, mut max_vy_after_top) = (f64::MIN, None::<f64>, f64::MIN);
    let mut slope_vy = 0.0;
    let mut reached = false;
    for _ in 0..600 {
        // The character's controller: walk right at 3 m/s.
        let b = w.body_mut(c).expect("character");
        let vy = b.linear_velocity().y;
        b.set_linear_velocity(Vector2::new(s(speed), vy));
        w.step(dt()).expect("step");
        let b = w.body(c).expect("character");
        let (x, vy) = (f(b.position().x), f(b.linear_velocity().y));
        // Around the top join: nothing pushes the character up (its vertical
        // speed may fall, or come back to 0 when it lands after the crest).
        if (8.0..14.0).contains(&x) {
            if let Some(prev) = last_vy.filter(|_| vy > 1e-3) {
                worst_jump = worst_jump.max(vy - prev);
            }
            last_vy = Some(vy);
        }
        if (5.0..8.0).contains(&x) {
            slope_vy = vy;
        }
        if x > 10.5 {
            max_vy_after_top = max_vy_after_top.max(vy);
        }
        if x > 20.0 {
            reached = true;
            let y = f(b.position().y);
            assert!((y - (top + 0.7)).abs() < 0.02, "on the flat top at y {y:.4}");
            break;
        }
    }
    println!("largest rise of vy a step near the top join: {worst_jump:.5} m/s");
    println!("largest vy past the join: {max_vy_after_top:.5} m/s");
    assert!(reached, "the character did not reach the flat top");
    // Threshold: 0.01 m/s a step (gravity alone takes 0.167 m/s a step).
    assert!(worst_jump < 0.01, "vertical speed jumped up by {worst_jump:.4} m/s at the join");
    // Never launched faster upward than it climbed the slope.
    println!("vertical speed on the slope: {slope_vy:.5} m/s");
    assert!(slope_vy > 1.0 && max_vy_after_top <= slope_vy + 0.01, "{slope_vy} {max_vy_after_top}");
}

/// How far from the centre (m, on either axis) a bouncing ball gets in a
/// 10 m square room: a clockwise loop chain, or four static segments.
fn ball_in_room(chain: bool) -> f64 {
    let mut w = world();
    // Clockwise: the links' fronts face in.
    let square = [v(-5.0, -5.0), v(-5.0, 5.0), v(5.0, 5.0), v(5.0, -5.0)];
    if chain {
        let c = w.add_chain(ChainPath::closed(&square).expect("path")).expect("room");
        w.add_body(BodyDef::chain(c).restitution(s(0.9))).expect("room");
    } else {
        for i in 0..4 {
            let seg = arphysics::Segment::new(square[i], square[(i + 1) % 4]).expect("segment");
            w.add_body(BodyDef::segment(seg).restitution(s(0.9))).expect("wall");
        }
    }
    let ball = BodyDef::circle(s(0.25)).linear_velocity(v(17.0, 11.0)).restitution(s(0.9));
    let ball = w.add_body(ball).expect("ball");
    let mut far = 0f64;
    for _ in 0..600 {
        w.step(dt()).expect("step");
        let p = w.body(ball).expect("ball").position();
        far = far.max(f(p.x).abs()).max(f(p.y).abs());
    }
    far
}

#[test]
fn a_clockwise_loop_holds_a_bouncing_ball() {
    let (chain, segments) = (ball_in_room(true), ball_in_room(false));
    println!("farthest from the centre: chain {chain:.4} m, segments {segments:.4} m");
    // The centre never crosses a wall, and the ball did reach the walls.
    assert!(chain < 5.0 && chain > 4.5, "{chain:.4}");
    // A one-sided link from its front behaves as a segment does.
    assert_eq!(chain, segments);
}

#[test]
fn a_bullet_does_not_tunnel_through_a_chain() {
    let mut w = world();
    flat_chain(&mut w);
    let bullet = w
        .add_body(
            BodyDef::circle(s(0.05)).position(v(10.3, 20.0)).linear_velocity(v(0.0, -200.0)).bullet(true),
        )
        .expect("bullet");
    let mut lowest = f64::MAX;
    for _ in 0..60 {
        w.step(dt()).expect("step");
        lowest = lowest.min(f(w.body(bullet).expect("bullet").position().y));
    }
    assert!(lowest > 0.0, "the bullet went to y {lowest}");
    // And a fast non-bullet body too (continuous collision against static bodies).
    let fast = w
        .add_body(BodyDef::circle(s(0.1)).position(v(30.7, 30.0)).linear_velocity(v(1.0, -150.0)))
        .expect("fast");
    for _ in 0..60 {
        w.step(dt()).expect("step");
        assert!(f(w.body(fast).expect("fast").position().y) > 0.0);
    }
}

#[test]
fn queries_see_chain_links_from_their_front() {
    let mut w = world();
    let ground = flat_chain(&mut w);
    let all = QueryFilter::default();
    let hit = w.ray_cast(v(10.5, 5.0), v(10.5, -5.0), all).expect("ray").expect("hits the ground");
    assert_eq!(hit.body, ground);
    assert!((f(hit.fraction) - 0.5).abs() < 1e-6 && hit.normal == Vector2::Y, "{hit:?}");
    // From behind: one-sided, no hit.
    assert!(w.ray_cast(v(10.5, -5.0), v(10.5, 5.0), all).expect("ray").is_none());
    // A circle cast down lands on it.
    let cast = w
        .shape_cast(
            QueryShape::Circle(s(0.5)),
            Transform::new(v(20.2, 3.0), arphysics::Rot::IDENTITY),
            v(0.0, -6.0),
            all,
        )
        .expect("cast")
        .expect("hits");
    assert!((f(cast.fraction) - 2.5 / 6.0).abs() < 2e-3, "{}", f(cast.fraction));
    assert!((f(cast.normal.y) - 1.0).abs() < 1e-6);
    // A 0.5 m circle 0.4 m above the ground overlaps it; 0.6 m above, not.
    for (y, expected) in [(0.4, 1), (0.6, 0)] {
        let mut out = [BodyHandle::NULL; 4];
        let at = Transform::new(v(3.3, y), arphysics::Rot::IDENTITY);
        let n = w.query_shape(QueryShape::Circle(s(0.5)), at, all, &mut out).expect("query");
        assert_eq!(n, expected, "at y {y}");
        assert!(n == 0 || out[0] == ground);
    }
}

#[test]
fn bad_chains_are_clear_errors_and_change_nothing() {
    let p = |x: f64, y: f64| v(x, y);
    assert_eq!(ChainPath::open(&[p(0.0, 0.0)]), Err(Error::OutOfRange { what: "chain points" }));
    assert_eq!(
        ChainPath::closed(&[p(0.0, 0.0), p(1.0, 0.0)]),
        Err(Error::OutOfRange { what: "chain points" })
    );
    assert_eq!(
        ChainPath::open(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)]),
        Err(Error::OutOfRange { what: "segment length" })
    );
    let bounds = Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0));
    let caps = Capacities { chain_vertices: 5, ..Capacities::for_bodies(8) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    let three = [p(2.0, 0.0), p(1.0, 0.0), p(0.0, 0.0)];
    let chain = w.add_chain(ChainPath::open(&three).expect("path")).expect("room");
    let before = (w.state_hash(), w.chain_vertices());
    assert_eq!(
        w.add_chain(ChainPath::open(&three).expect("path")),
        Err(Error::CapacityFull { what: "chain vertex" })
    );
    assert_eq!((w.state_hash(), w.chain_vertices()), before);
    assert_eq!(before.1, (3, 5));
    let dynamic = BodyDef::chain(chain).body_type(arphysics::BodyType::Dynamic);
    assert!(matches!(w.add_body(dynamic), Err(Error::InvalidOperation { .. })));
    let kinematic = BodyDef::chain(chain).kinematic();
    assert!(matches!(w.add_body(kinematic), Err(Error::InvalidOperation { .. })));
    assert_eq!((w.state_hash(), w.bodies().count()), (before.0, 0));
    // A handle from a bigger world's slab is not in this one.
    let mut big = world();
    let long: Vec<Vector2> = (0..20).map(|i| v(f64::from(-i), 0.0)).collect();
    let far = big.add_chain(ChainPath::open(&long).expect("path")).expect("room");
    assert_eq!(w.add_body(BodyDef::chain(far)), Err(Error::StaleHandle));
}

/// A world with chain terrain and a few bodies of every kind on it.
fn busy_world() -> World<'static> {
    let mut w = world();
    let hills: Vec<Vector2> =
        (0..=40).rev().map(|i| v(f64::from(i) - 20.0, (f64::from(i) * 0.7).sin() * 1.5)).collect();
    let chain = w.add_chain(ChainPath::open(&hills).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain)).expect("hills");
    let rounded = w.add_path(PolygonPath::rounded_rectangle(s(0.8), s(0.5), s(0.1)).expect("p")).expect("p");
    for i in 0..12 {
        let x = f64::from(i) * 2.7 - 15.0;
        let def = match i % 3 {
            0 => BodyDef::capsule(Capsule::new(v(-0.3, 0.1), v(0.3, -0.1), s(0.2)).expect("capsule")),
            1 => BodyDef::polygon(rounded),
            _ => BodyDef::circle(s(0.3)),
        };
        w.add_body(def.position(v(x, 4.0 + f64::from(i % 2))).angular_velocity(s(1.0))).expect("body");
    }
    w
}

#[test]
fn restore_then_step_equals_stepping_on_with_chains() {
    let mut w = busy_world();
    for _ in 0..90 {
        w.step(dt()).expect("step");
    }
    assert!(w.arbiters().any(|a| a.link() != 0), "some arbiter is for a link past the first");
    assert!(w.snapshot_len() <= w.max_snapshot_len());
    let mut snap = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut snap).expect("snapshot");
    for _ in 0..60 {
        w.step(dt()).expect("step");
    }
    let on = w.state_hash();
    w.restore(&snap).expect("restore");
    for _ in 0..60 {
        w.step(dt()).expect("step");
    }
    assert_eq!(w.state_hash(), on);
    // Into a fresh world with the same chains: the same future.
    let mut other = busy_world();
    other.restore(&snap).expect("restore");
    for _ in 0..60 {
        other.step(dt()).expect("step");
    }
    assert_eq!(other.state_hash(), on);
    // A world whose chain differs refuses it, unchanged.
    let mut wrong = world();
    let points = [v(5.0, 0.0), v(0.0, 0.0)];
    let c = wrong.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    wrong.add_body(BodyDef::chain(c)).expect("ground");
    let before = wrong.state_hash();
    assert!(wrong.restore(&snap).is_err());
    assert_eq!(wrong.state_hash(), before);
    // A flipped bit in the arbiters' links (just before the joints) is refused.
    let mut bad = snap.clone();
    let len = w.snapshot_len();
    if let Some(b) = bad.get_mut(len / 2) {
        *b ^= 0x10;
    }
    assert!(w.restore(&bad).is_err());
}

#[test]
fn a_world_without_chains_encodes_as_before() {
    // No arbiter has a link: no link section, the count's top bit clear.
    let mut w = world();
    let floor = w.add_path(PolygonPath::rectangle(s(20.0), s(1.0)).expect("floor")).expect("path");
    w.add_body(BodyDef::polygon(floor).position(v(0.0, -0.5)).static_body()).expect("floor");
    w.add_body(BodyDef::circle(s(0.5)).position(v(0.0, 0.6))).expect("ball");
    for _ in 0..10 {
        w.step(dt()).expect("step");
    }
    assert!(w.arbiters().count() == 1 && w.arbiters().all(|a| a.link() == 0));
    let mut snap = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut snap).expect("snapshot");
    // header 16, world 112, props count and 2 props, body alloc and 2 bodies,
    // generator alloc and 1 gravity slot, arbiter count and 1 arbiter, no
    // link words, then (the default world recycles contacts) the arbiter's
    // 128-byte manifold record, joint alloc, trailer.
    let count_at = 16 + 112 + 4 + 2 * 118 + 12 + 2 * 64 + 12 + (9 + 16 + 1);
    let expected = count_at + 4 + 58 + 128 + 12 + 8;
    assert_eq!(n, expected);
    let count = u32::from_le_bytes(snap[count_at..count_at + 4].try_into().expect("4 bytes"));
    assert_eq!(count, 1 | ARBITER_MANIFOLDS, "the links bit (31) clear, the manifolds bit (30) set");
}

#[test]
fn a_full_contact_store_with_chain_links_degrades_and_keeps_stepping() {
    // Room for 8 arbiters; 12 boxes resting across joins want about 24.
    let bounds = Rect::from_corners(v(-50.0, -50.0), v(150.0, 50.0));
    let caps = Capacities { contacts: 8, chain_vertices: 128, ..Capacities::for_bodies(32) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    flat_chain(&mut w);
    let path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("box")).expect("path");
    for i in 0..12 {
        w.add_body(BodyDef::polygon(path).position(v(f64::from(i) * 3.0 + 1.0, 0.6))).expect("box");
    }
    let mut dropped = 0;
    for _ in 0..60 {
        let report = w.step(dt()).expect("a full store never stops the step");
        assert!(report.arbiters as usize <= 8);
        dropped += report.arbiters_dropped;
    }
    assert!(dropped > 0, "the store was never full");
    // The boxes that kept their arbiters (the lowest keys) rest on the chain.
    let resting = w.bodies().filter(|(_, b)| (f(b.position().y) - 0.5).abs() < 0.01).count();
    assert!(resting >= 3, "{resting} boxes rest on the chain");
}

#[test]
fn bodies_share_a_chain_at_their_own_poses() {
    let mut w = world();
    // One 4 m ledge, used by two bodies: at x = 0 and, turned upside down, at
    // x = 10 (its front then faces down).
    let ledge = [v(2.0, 0.0), v(0.0, 0.0), v(-2.0, 0.0)];
    let chain = w.add_chain(ChainPath::open(&ledge).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain).position(v(0.0, 0.0))).expect("ledge");
    w.add_body(BodyDef::chain(chain).position(v(10.0, 0.0)).angle(s(std::f64::consts::PI))).expect("ledge");
    assert_eq!(w.chain_vertices().0, 3, "shared, not copied");
    let a = w.add_body(BodyDef::circle(s(0.25)).position(v(0.5, 2.0))).expect("ball");
    let b = w.add_body(BodyDef::circle(s(0.25)).position(v(10.5, 2.0))).expect("ball");
    for _ in 0..120 {
        w.step(dt()).expect("step");
    }
    let (ya, yb) = (f(w.body(a).expect("a").position().y), f(w.body(b).expect("b").position().y));
    assert!((ya - 0.25).abs() < 0.01, "rests on the first ledge: {ya}");
    assert!(yb < -1.0, "falls through the back of the turned ledge: {yb}");
}

/// A chain added after the bodies that touch it has the higher slot of each
/// pair: the candidate keys step past each link (a fuzzed world once looped
/// forever here) and the balls rest on it as on a chain added first.
#[test]
fn a_chain_in_a_higher_slot_than_the_bodies_on_it() {
    let mut w = world_with(50.0, 50.0, Capacities { chain_vertices: 16, ..Capacities::for_bodies(8) }, true);
    let balls: Vec<_> = (0..3)
        .map(|i| w.add_body(BodyDef::circle(s(0.25)).position(v(f64::from(i) - 1.0, 0.3))).expect("ball"))
        .collect();
    let points: Vec<Vector2> = (0..=6).rev().map(|i| v(f64::from(i) - 3.0, 0.0)).collect();
    let chain = w.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    let ground = w.add_body(BodyDef::chain(chain)).expect("ground");
    assert!(balls.iter().all(|b| b.index() < ground.index()), "the chain has the higher slot");
    for _ in 0..120 {
        w.step(dt()).expect("step");
    }
    for b in balls {
        let y = f(w.body(b).expect("live").position().y);
        assert!((y - 0.25).abs() < 0.01, "a ball rests on the chain: {y}");
    }
}
