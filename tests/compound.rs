//! Bodies of several shapes (issue 19, part 2), the parts built so far: the
//! mass of several shapes about their common centre; the arbiter's shape
//! indices in the snapshot (the sub-key words after the arbiter records) are
//! refused when they name a shape a body does not have, and a world with
//! chains keeps its encoding.

use arphysics::geometry::{compound_mass, MassPart};
use arphysics::snapshot::{MANIFOLD_RECORD, TRAILER};
use arphysics::{
    BodyDef, Capacities, ChainPath, Error, GravityForceGenerator, MassData, PolygonPath, Rect, Scalar,
    Vector2, World, WorldDef,
};
use twox_hash::XxHash64;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

fn dt() -> Scalar {
    Scalar::ONE / Scalar::from_num(60)
}

/// Balls resting across the joins of a flat chain of 1 m links: arbiters
/// for links past the first, so the snapshot has its sub-key words.
fn chain_world() -> World<'static> {
    let bounds = Rect::from_corners(v(-50.0, -50.0), v(50.0, 50.0));
    let caps = Capacities { chain_vertices: 64, ..Capacities::for_bodies(32) };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let points: Vec<Vector2> = (0..=10).rev().map(|i| v(f64::from(i) - 5.0, 0.0)).collect();
    let chain = w.add_chain(ChainPath::open(&points).expect("path")).expect("room");
    w.add_body(BodyDef::chain(chain)).expect("ground");
    for i in 0..4 {
        let x = f64::from(i) * 2.0 - 3.0;
        w.add_body(BodyDef::circle(s(0.25)).position(v(x, 0.3))).expect("ball");
    }
    for _ in 0..30 {
        w.step(dt()).expect("step");
    }
    w
}

/// Writes `word` as the first arbiter's sub-key word and reseals the
/// checksum (the world has no joints, and recycles contacts by default, so
/// the words are followed by one manifold record per arbiter and then the
/// joint allocator's 12 bytes).
fn with_first_word(snap: &[u8], arbiters: usize, word: u32) -> Vec<u8> {
    let mut bad = snap.to_vec();
    let n = bad.len();
    let first = n - TRAILER - 12 - arbiters * MANIFOLD_RECORD - arbiters * 4;
    bad[first..first + 4].copy_from_slice(&word.to_le_bytes());
    let sum = XxHash64::oneshot(0, &bad[..n - TRAILER]);
    bad[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
    bad
}

#[test]
fn arbiter_shape_indices_a_body_does_not_have_are_refused() {
    let mut w = chain_world();
    let arbiters: Vec<_> = w.arbiters().copied().collect();
    assert!(arbiters.iter().any(|a| a.link() != 0), "some arbiter is for a link past the first");
    assert!(arbiters.iter().all(|a| a.shape_a() == 0 && a.shape_b() == 0), "one-shape bodies");
    assert_eq!(w.joints().count(), 0);
    let mut snap = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut snap).expect("snapshot");
    snap.truncate(n);
    // The words follow the arbiter records (the count's flag is set).
    let first = arbiters.first().expect("an arbiter");
    let resealed = with_first_word(&snap, arbiters.len(), first.link());
    assert_eq!(resealed, snap, "the first word is the first arbiter's link");
    let before = w.state_hash();
    // A shape index on body A, on body B, or a reserved bit: refused, unchanged.
    for word in [first.link() | 1 << 26, first.link() | 1 << 29, first.link() | 1 << 20] {
        let bad = with_first_word(&snap, arbiters.len(), word);
        assert!(matches!(w.restore(&bad), Err(Error::InvalidSnapshot { .. })), "{word:#x}");
        assert_eq!(w.state_hash(), before);
    }
    // The untouched snapshot restores, and stepping on is the same.
    w.restore(&snap).expect("restore");
    assert_eq!(w.state_hash(), before);
}

/// A part: a `w` × `h` box at density 1 centred at (`x`, `y`), its mass data
/// as the engine computes it for a one-shape body.
fn box_part(w: f64, h: f64, x: f64, y: f64) -> MassPart {
    let path = PolygonPath::rectangle(s(w), s(h)).expect("box");
    let m = MassData::from_density(Scalar::ONE, path.area(), path.unit_inertia()).expect("mass");
    MassPart { mass: m.mass, centre: v(x, y), inertia: m.inertia }
}

#[test]
fn two_boxes_side_by_side_have_the_mass_data_of_one_box_twice_as_wide() {
    // Two 1 m × 0.5 m boxes whose sides touch make a 2 m × 0.5 m box: the
    // parallel-axis sum about the common centre is its m(w² + h²)/12.
    let (m, c) = compound_mass(&[box_part(1.0, 0.5, -0.5, 2.0), box_part(1.0, 0.5, 0.5, 2.0)]).expect("mass");
    let whole = box_part(2.0, 0.5, 0.0, 2.0);
    assert_eq!((m.mass, c), (whole.mass, v(0.0, 2.0)));
    let exact = 1.0 * (4.0 + 0.25) / 12.0;
    for got in [m.inertia, whole.inertia] {
        assert!((got.to_num::<f64>() - exact).abs() / exact < 1e-8, "{got} vs {exact}");
    }
    assert!((m.inertia - whole.inertia).abs() <= Scalar::from_bits(4));
}

#[test]
fn an_l_of_two_boxes_has_the_closed_form_inertia_about_its_centre() {
    // A 2 × 0.5 foot and a 0.5 × 1.5 leg standing on its left end: the
    // centre is the area-weighted mean of (0, 0) and (−0.75, 1); each box
    // adds m(w² + h²)/12 + m·d² about it.
    let (foot, leg) = (box_part(2.0, 0.5, 0.0, 0.0), box_part(0.5, 1.5, -0.75, 1.0));
    let (m, c) = compound_mass(&[foot, leg]).expect("mass");
    let (mf, ml) = (1.0_f64, 0.75_f64);
    let (cx, cy) = ((ml * -0.75) / (mf + ml), (ml * 1.0) / (mf + ml));
    let i_foot = mf * (4.0 + 0.25) / 12.0 + mf * (cx * cx + cy * cy);
    let i_leg = ml * (0.25 + 2.25) / 12.0 + ml * ((-0.75 - cx).powi(2) + (1.0 - cy).powi(2));
    assert!((c.x.to_num::<f64>() - cx).abs() < 1e-9 && (c.y.to_num::<f64>() - cy).abs() < 1e-9, "{c:?}");
    let exact = i_foot + i_leg;
    assert!((m.inertia.to_num::<f64>() - exact).abs() / exact < 1e-8, "{} vs {exact}", m.inertia);
    assert_eq!(m.mass, Scalar::lit("1.75"));
}
