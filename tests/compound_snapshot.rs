//! Snapshots, the state hash and restore for compound bodies (issue 19,
//! part 2): the shapes section (the shape store's slots and each compound
//! body's list head) comes back exactly, so restore-then-step equals
//! stepping on, bit for bit, also across `remove_shape`, `add_shape` and
//! `remove_body`; a corrupted section is refused with the world unchanged; a
//! world that never had a compound body writes the bytes it wrote before.
//!
//! These tests do not depend on how the shapes collide (per-shape collision
//! is built elsewhere): only on restore-then-step being stepping on, and on
//! the validation.

use arphysics::snapshot::{
    diff, Difference, Object, ARBITER_LINKS, ARBITER_MANIFOLDS, ARBITER_RECORD, BODY_RECORD, COMPOUND_RECORD,
    HEADER, MANIFOLD_RECORD, PROPS_RECORD, SHAPES, SHAPE_RECORD, TRAILER,
};
use arphysics::{
    BodyDef, BodyHandle, BodyShape, Capacities, Error, PathHandle, PolygonPath, ShapeDef, World,
};
use twox_hash::XxHash64;

mod common;
use common::{dt, s, v, world_with};

/// Bytes of the world part: step count (8), settings (96, the contact
/// recycle distance last), paths checksum (8).
const WORLD_BYTES: usize = 112;
/// Bytes of an allocator state: slots used, free head, live count.
const ALLOC_BYTES: usize = 12;

/// The scene: gravity 10 m/s² down, a static 20 m × 1 m box whose top is at
/// y = 0, and the paths of a 2 m × 0.5 m bar and a 0.5 m × 1.5 m post, in a
/// world with room for 16 bodies and `shapes` shape slots. Every scene adds
/// the same paths in the same order, so one scene restores another's
/// snapshot.
struct Scene {
    w: World<'static>,
    bar: PathHandle,
    post: PathHandle,
}

fn scene(shapes: usize) -> Scene {
    let mut w = world_with(50.0, 50.0, Capacities { shapes, ..Capacities::for_bodies(16) }, true);
    let ground = w.add_path(PolygonPath::rectangle(s(20.0), s(1.0)).expect("box")).expect("path");
    let bar = w.add_path(PolygonPath::rectangle(s(2.0), s(0.5)).expect("bar")).expect("path");
    let post = w.add_path(PolygonPath::rectangle(s(0.5), s(1.5)).expect("post")).expect("path");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    Scene { w, bar, post }
}

impl Scene {
    /// The bar, 2 cm above the ground at `x`, made an L when `compound` by
    /// the post (density 1) standing on its left end.
    fn add_l(&mut self, x: f64, compound: bool) -> BodyHandle {
        let l = self.w.add_body(BodyDef::polygon(self.bar).position(v(x, 0.27))).expect("bar");
        if compound {
            let post = ShapeDef::polygon(self.post).offset(v(-0.75, 1.0));
            assert_eq!(self.w.add_shape(l, post), Ok(1));
        }
        l
    }

    /// A body of eight 0.2 m circles in a row, resting at `x`.
    fn add_row(&mut self, x: f64) -> BodyHandle {
        let row = self.w.add_body(BodyDef::circle(s(0.2)).position(v(x, 0.21))).expect("row");
        for i in 1..8u32 {
            let c = ShapeDef::circle(s(0.2)).offset(v(0.4 * f64::from(i), 0.0));
            assert_eq!(self.w.add_shape(row, c), Ok(i));
        }
        row
    }
}

fn take(w: &World<'_>) -> Vec<u8> {
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("snapshot");
    assert_eq!(n, buf.len(), "snapshot_len is what snapshot writes");
    buf
}

fn step(w: &mut World<'_>, n: usize) {
    for _ in 0..n {
        w.step(dt()).expect("step");
    }
}

/// Every body's position and rotation, as raw bits.
fn poses(w: &World<'_>) -> Vec<(i64, i64, i64, i64)> {
    w.bodies()
        .map(|(_, b)| {
            let (p, q) = (b.position(), b.rotation());
            (p.x.to_bits(), p.y.to_bits(), q.c.to_bits(), q.s.to_bits())
        })
        .collect()
}

fn shapes_of(w: &World<'_>, h: BodyHandle) -> Vec<(u32, BodyShape)> {
    w.shapes(h).expect("live body").collect()
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().expect("4 bytes"))
}

fn put_u32(b: &mut [u8], at: usize, x: u32) {
    b[at..at + 4].copy_from_slice(&x.to_le_bytes());
}

/// Recomputes the checksum in the trailer.
fn reseal(b: &mut [u8]) {
    let n = b.len();
    let sum = XxHash64::oneshot(0, &b[..n - TRAILER]);
    b[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
}

/// Where the shapes section's parts are in a snapshot that has one.
struct Section {
    /// The shape store's allocator state.
    alloc_at: usize,
    /// The first slot record, and how many there are.
    slots_at: usize,
    used: u32,
    /// The compound bodies' list, and its length.
    list_at: usize,
    compounds: u32,
}

impl Section {
    fn of(snap: &[u8]) -> Self {
        let count_at = HEADER + WORLD_BYTES;
        let props = u32_at(snap, count_at);
        assert_ne!(props & SHAPES, 0, "the properties count flags a shapes section");
        let bodies_at = count_at + 4 + (props & !SHAPES) as usize * PROPS_RECORD;
        let body_slots = u32_at(snap, bodies_at) as usize;
        let alloc_at = bodies_at + ALLOC_BYTES + body_slots * BODY_RECORD;
        let used = u32_at(snap, alloc_at);
        let slots_at = alloc_at + ALLOC_BYTES;
        let count_at = slots_at + used as usize * SHAPE_RECORD;
        Self { alloc_at, slots_at, used, list_at: count_at + 4, compounds: u32_at(snap, count_at) }
    }

    /// Offset of field `offset` of slot `i`'s record.
    fn slot(&self, i: u32, offset: usize) -> usize {
        self.slots_at + i as usize * SHAPE_RECORD + offset
    }

    /// The offset of the list entry of body slot `body` (its head follows
    /// 4 bytes on).
    fn entry(&self, snap: &[u8], body: u32) -> usize {
        (0..self.compounds as usize)
            .map(|k| self.list_at + k * COMPOUND_RECORD)
            .find(|&at| u32_at(snap, at) == body)
            .expect("a compound body")
    }

    /// The slots of body slot `body`'s list, in shape order.
    fn list(&self, snap: &[u8], body: u32) -> Vec<u32> {
        let mut at = u32_at(snap, self.entry(snap, body) + 4);
        let mut out = Vec::new();
        while at != u32::MAX {
            out.push(at);
            at = u32_at(snap, self.slot(at, 12));
        }
        out
    }
}

/// Field offsets in a shape record.
const OWNER: usize = 8;
const NEXT: usize = 12;
const FRICTION: usize = 16 + 25 + 32 + 16;

/// Restores `bad` into `w`, which must refuse it as an invalid snapshot and
/// stay exactly as it was; returns the reason.
fn refused(w: &mut World<'_>, bad: &[u8]) -> &'static str {
    let (hash, bytes) = (w.state_hash(), take(w));
    let what = match w.restore(bad) {
        Err(Error::InvalidSnapshot { what }) => what,
        other => panic!("expected an invalid snapshot, got {other:?}"),
    };
    assert_eq!(w.state_hash(), hash, "{what}: the world is unchanged");
    assert_eq!(take(w), bytes, "{what}: the world is unchanged");
    what
}

#[test]
fn restore_then_step_equals_stepping_on_for_an_l_resting_on_a_box() {
    let mut sc = scene(16);
    let l = sc.add_l(0.0, true);
    let w = &mut sc.w;
    // Density 1: 2 × 0.5 + 0.5 × 1.5 = 1.75 kg.
    let mass = w.body(l).expect("live").mass().to_num::<f64>();
    assert!((mass - 1.75).abs() < 1e-6, "mass {mass}");
    step(w, 30);
    assert!(w.arbiters().count() > 0, "snapshot mid-contact");
    let snap = take(w);
    let hash = w.state_hash();
    assert_eq!(snap[snap.len() - TRAILER..], hash.to_le_bytes(), "the hash is the trailer");
    let shapes = shapes_of(w, l);
    assert_eq!(shapes.len(), 2);
    let body = *w.body(l).expect("live");
    step(w, 60);
    let (hash_on, poses_on) = (w.state_hash(), poses(w));
    // Resting: after 1.5 s on the box the L has stopped falling.
    let vy = w.body(l).expect("live").linear_velocity().y.to_num::<f64>();
    assert!(vy.abs() < 0.05, "vertical speed {vy} m/s");

    w.restore(&snap).expect("restore");
    assert_eq!(w.state_hash(), hash);
    assert_eq!(take(w), snap, "restore then snapshot gives the same bytes");
    assert_eq!(shapes_of(w, l), shapes);
    // Derived data too: shape count, bounding radius, box.
    assert_eq!(*w.body(l).expect("live"), body);
    assert_eq!(w.body(l).expect("live").shape_count(), 2);
    step(w, 60);
    assert_eq!(w.state_hash(), hash_on);
    assert_eq!(poses(w), poses_on);

    // A fresh world of the same settings restores it too and steps the same.
    let mut other = scene(16);
    other.w.restore(&snap).expect("restore into another world");
    assert_eq!(other.w.state_hash(), hash);
    step(&mut other.w, 60);
    assert_eq!(other.w.state_hash(), hash_on);
    assert_eq!(poses(&other.w), poses_on);
}

#[test]
fn restore_comes_back_across_remove_shape_add_shape_and_remove_body() {
    let (mut sc, l, row, snap) = l_and_row();
    let hash = sc.w.state_hash();
    let (l_shapes, row_shapes) = (shapes_of(&sc.w, l), shapes_of(&sc.w, row));
    step(&mut sc.w, 60);
    let (hash_on, poses_on) = (sc.w.state_hash(), poses(&sc.w));

    for round in 0..3 {
        sc.w.restore(&snap).expect("restore");
        let w = &mut sc.w;
        match round {
            // The post goes, and its slot is reused by a new body's shape.
            0 => {
                w.remove_shape(l, 1).expect("remove the post");
                let ball = w.add_body(BodyDef::circle(s(0.3)).position(v(6.0, 2.0))).expect("ball");
                w.add_shape(ball, ShapeDef::circle(s(0.2)).offset(v(0.5, 0.0))).expect("room");
            }
            // Shapes move down an index and the L grows.
            1 => {
                w.remove_shape(row, 0).expect("remove the first circle");
                w.add_shape(l, ShapeDef::circle(s(0.25)).offset(v(0.75, 0.5))).expect("room");
            }
            // A compound body goes, with its slots.
            _ => {
                w.remove_body(row).expect("remove the row");
            }
        }
        step(w, 7);
        assert_ne!(w.state_hash(), hash);
        w.restore(&snap).expect("restore");
        assert_eq!(w.state_hash(), hash, "round {round}");
        assert_eq!(take(w), snap, "round {round}");
        assert_eq!(shapes_of(w, l), l_shapes, "round {round}");
        assert_eq!(shapes_of(w, row), row_shapes, "round {round}");
        step(w, 60);
        assert_eq!(w.state_hash(), hash_on, "round {round}");
        assert_eq!(poses(w), poses_on, "round {round}");
    }
}

#[test]
fn a_snapshot_from_before_the_first_shape_empties_the_shape_store() {
    let mut sc = scene(16);
    let l = sc.add_l(0.0, false);
    step(&mut sc.w, 10);
    let snap = take(&sc.w);
    assert_eq!(u32_at(&snap, HEADER + WORLD_BYTES) & SHAPES, 0, "no shapes section");
    let post = ShapeDef::polygon(sc.post).offset(v(-0.75, 1.0));
    sc.w.add_shape(l, post).expect("room");
    step(&mut sc.w, 10);
    sc.w.restore(&snap).expect("restore");
    assert_eq!(take(&sc.w), snap);
    assert_eq!(sc.w.shapes(l).expect("live").count(), 1);
    // The store is as new: the same shape added again gives what a world
    // that never had it gives.
    let mut fresh = scene(16);
    let fl = fresh.add_l(0.0, false);
    step(&mut fresh.w, 10);
    assert_eq!(take(&fresh.w), snap);
    for (sc, h) in [(&mut sc, l), (&mut fresh, fl)] {
        let post = ShapeDef::polygon(sc.post).offset(v(-0.75, 1.0));
        sc.w.add_shape(h, post).expect("room");
        step(&mut sc.w, 30);
    }
    assert_eq!(take(&sc.w), take(&fresh.w));
}

#[test]
fn a_world_that_never_had_a_compound_body_encodes_as_before() {
    // The same one-shape scene with and without room for shapes: the same
    // bytes (the golden tests pin those bytes' hashes).
    let mut a = scene(0);
    let mut b = scene(16);
    for sc in [&mut a, &mut b] {
        sc.add_l(0.0, false);
        step(&mut sc.w, 30);
    }
    let snap = take(&a.w);
    assert_eq!(u32_at(&snap, HEADER + WORLD_BYTES) & SHAPES, 0, "no shapes section");
    assert_eq!(take(&b.w), snap);
    assert_eq!(a.w.state_hash(), b.w.state_hash());
}

/// The L (body slot 1) and the row (slot 2), resting after 20 steps, and
/// their snapshot.
fn l_and_row() -> (Scene, BodyHandle, BodyHandle, Vec<u8>) {
    let mut sc = scene(16);
    let l = sc.add_l(-3.0, true);
    let row = sc.add_row(2.0);
    step(&mut sc.w, 20);
    let snap = take(&sc.w);
    (sc, l, row, snap)
}

#[test]
fn the_shapes_section_has_its_documented_size_within_max_snapshot_len() {
    let (sc, l, row, snap) = l_and_row();
    let sec = Section::of(&snap);
    // Two shapes of the L and eight of the row; slots used, none free.
    assert_eq!((sec.used, sec.compounds), (10, 2));
    assert_eq!(
        &snap[sec.alloc_at..sec.alloc_at + 12],
        [10u32, u32::MAX >> 2, 10].map(u32::to_le_bytes).concat()
    );
    assert_eq!(sec.list(&snap, l.index()).len(), 2);
    assert_eq!(sec.list(&snap, row.index()).len(), 8);
    // The generators follow the list.
    let generators_at = sec.list_at + 2 * COMPOUND_RECORD;
    assert_eq!(u32_at(&snap, generators_at), 1, "one generator slot used");
    assert!(snap.len() <= sc.w.max_snapshot_len(), "{} > {}", snap.len(), sc.w.max_snapshot_len());
    // Every shape slot used, by eight L's: still within the bound.
    let mut full = scene(16);
    for i in 0..8 {
        full.add_l(f64::from(i) * 2.5 - 10.0, true);
    }
    step(&mut full.w, 20);
    let snap = take(&full.w);
    assert_eq!(Section::of(&snap).used, 16);
    assert!(snap.len() <= full.w.max_snapshot_len(), "{} > {}", snap.len(), full.w.max_snapshot_len());
}

/// The scene the corruption tests start from ([`l_and_row`]) with its
/// snapshot's shapes section.
fn resting_pair() -> (Scene, BodyHandle, BodyHandle, Vec<u8>, Section) {
    let (sc, l, row, snap) = l_and_row();
    let sec = Section::of(&snap);
    (sc, row, l, snap, sec)
}

#[test]
fn broken_shape_lists_are_refused_with_the_world_unchanged() {
    let (mut sc, row, l, snap, sec) = resting_pair();
    let (row_list, l_list) = (sec.list(&snap, row.index()), sec.list(&snap, l.index()));
    let corrupt = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut bad = snap.clone();
        f(&mut bad);
        reseal(&mut bad);
        bad
    };
    // A cycle: the post's next is the bar.
    let bad = corrupt(&|b| put_u32(b, sec.slot(l_list[1], NEXT), l_list[0]));
    assert!(refused(&mut sc.w, &bad).contains("cyclic"));
    // An owner that is not a live body (a slot never used), or not the
    // list's body (the ground).
    for owner in [15, 0] {
        let bad = corrupt(&|b| put_u32(b, sec.slot(l_list[1], OWNER), owner));
        refused(&mut sc.w, &bad);
    }
    // A ninth shape: the L's post followed by the row's circles, now the
    // L's (the L is listed first).
    let bad = corrupt(&|b| {
        put_u32(b, sec.slot(l_list[1], NEXT), row_list[0]);
        for &slot in &row_list {
            put_u32(b, sec.slot(slot, OWNER), l.index());
        }
    });
    assert!(refused(&mut sc.w, &bad).contains("longer than 8"));
    // A slot in two lists: the L's list starting at the row's first slot,
    // or taking the row's second after its bar.
    let bad = corrupt(&|b| put_u32(b, sec.entry(&snap, l.index()) + 4, row_list[0]));
    assert!(refused(&mut sc.w, &bad).contains("another body's shape"));
    let bad = corrupt(&|b| put_u32(b, sec.slot(l_list[0], NEXT), row_list[1]));
    assert!(refused(&mut sc.w, &bad).contains("another body's shape"));
    // A used slot in no list: the L's list ends after the bar.
    let bad = corrupt(&|b| put_u32(b, sec.slot(l_list[0], NEXT), u32::MAX));
    assert!(refused(&mut sc.w, &bad).contains("in no body's list"));
    // A list through a slot the store has not used.
    let bad = corrupt(&|b| put_u32(b, sec.slot(l_list[0], NEXT), sec.used));
    refused(&mut sc.w, &bad);
    // The same body listed twice, and a one-shape body listed.
    let bad = corrupt(&|b| put_u32(b, sec.list_at + COMPOUND_RECORD, l.index()));
    assert!(refused(&mut sc.w, &bad).contains("out of order"));
    let bad = corrupt(&|b| put_u32(b, sec.list_at, 0));
    refused(&mut sc.w, &bad);
    // The first shape's friction no longer the body's.
    let bad = corrupt(&|b| b[sec.slot(l_list[0], FRICTION) + 4] ^= 0x01);
    assert!(refused(&mut sc.w, &bad).contains("first shape differs"));
    // A friction out of range on another shape.
    let bad = corrupt(&|b| b[sec.slot(l_list[1], FRICTION) + 7] = 0x7f);
    refused(&mut sc.w, &bad);
    // A flipped bit anywhere in the section, not resealed: the checksum.
    for at in [sec.alloc_at, sec.slot(l_list[1], 20), sec.list_at + 5] {
        let mut bad = snap.clone();
        bad[at] ^= 0x10;
        assert!(refused(&mut sc.w, &bad).contains("checksum"));
    }
    // The snapshot itself restores.
    sc.w.restore(&snap).expect("restore");
}

#[test]
fn arbiter_shape_indices_must_be_below_their_bodys_shape_count() {
    let (mut sc, _row, l, snap, _sec) = resting_pair();
    let arbiters: Vec<_> = sc.w.arbiters().copied().collect();
    // The L's last arbiter: a larger shape index on it keeps the key order.
    let k = arbiters.iter().rposition(|a| a.body_a() == l || a.body_b() == l).expect("the L touches");
    let on_a = arbiters[k].body_a() == l;
    // From the end (no joints): the joint allocator, the manifold records
    // (the scene recycles contacts, the default), the sub-key words when
    // some arbiter has a link or shape index, the records, their count.
    let words = arbiters.iter().any(|a| a.link() != 0 || a.shape_a() != 0 || a.shape_b() != 0);
    let record = ARBITER_RECORD + if words { 4 } else { 0 } + MANIFOLD_RECORD;
    let count_at = snap.len() - TRAILER - ALLOC_BYTES - arbiters.len() * record - 4;
    assert_eq!(u32_at(&snap, count_at) & ARBITER_LINKS != 0, words);
    assert_ne!(u32_at(&snap, count_at) & ARBITER_MANIFOLDS, 0, "the manifold records follow");
    let with_word = |shape: u32| {
        let mut bad = snap.clone();
        // The words go between the records and the manifold records.
        let words_at = count_at + 4 + arbiters.len() * ARBITER_RECORD;
        if u32_at(&bad, count_at) & ARBITER_LINKS == 0 {
            put_u32(&mut bad, count_at, arbiters.len() as u32 | ARBITER_LINKS | ARBITER_MANIFOLDS);
            bad.splice(words_at..words_at, vec![0u8; 4 * arbiters.len()]);
            let len = bad.len() as u64;
            bad[8..16].copy_from_slice(&len.to_le_bytes());
        }
        let at = words_at + 4 * k;
        let word = u32_at(&bad, at) & !(0x3f << 26);
        put_u32(&mut bad, at, word | shape << if on_a { 26 } else { 29 });
        reseal(&mut bad);
        bad
    };
    // The L has two shapes: index 2 is refused, index 1 is accepted.
    assert!(refused(&mut sc.w, &with_word(2)).contains("shape its body does not have"));
    assert!(refused(&mut sc.w, &with_word(7)).contains("shape its body does not have"));
    if arbiters.iter().all(|a| a.shape_a() == 0 && a.shape_b() == 0) {
        sc.w.restore(&with_word(1)).expect("a shape the L has");
        let a = sc.w.arbiters().nth(k).expect("restored");
        assert_eq!(if on_a { a.shape_a() } else { a.shape_b() }, 1);
    }
}

#[test]
fn a_world_without_room_for_the_shapes_refuses_them_unchanged() {
    let (sc, _row, _l, snap, _sec) = resting_pair();
    let mut small = scene(9);
    let (hash, bytes) = (small.w.state_hash(), take(&small.w));
    assert_eq!(small.w.restore(&snap), Err(Error::CapacityFull { what: "shape" }));
    assert_eq!(small.w.state_hash(), hash);
    assert_eq!(take(&small.w), bytes);
    // Ten slots are enough.
    let mut exact = scene(10);
    exact.w.restore(&snap).expect("room for ten shapes");
    assert_eq!(exact.w.state_hash(), sc.w.state_hash());
}

#[test]
fn diff_names_the_shape_slot_and_field_that_differ() {
    let (_sc, _row, l, snap, sec) = resting_pair();
    let post = sec.list(&snap, l.index())[1];
    let mut other = snap.clone();
    other[sec.slot(post, FRICTION) + 4] ^= 0x01;
    reseal(&mut other);
    assert_eq!(diff(&snap, &other), Ok(Some(Difference { object: Object::Shape(post), field: "friction" })));
    let mut other = snap.clone();
    put_u32(&mut other, sec.entry(&snap, l.index()) + 4, post);
    reseal(&mut other);
    assert_eq!(
        diff(&snap, &other),
        Ok(Some(Difference { object: Object::Body(l.index()), field: "first shape slot" }))
    );
    assert_eq!(diff(&snap, &snap), Ok(None));
}

#[test]
fn a_shape_s_material_is_in_the_bodies_part_of_the_state_hashes() {
    // Two L's that differ only in the post's friction: the body properties
    // (which mirror the bar) are equal, the shapes section is not.
    let hashes = |mu: f64| {
        let mut sc = scene(16);
        let l = sc.w.add_body(BodyDef::polygon(sc.bar).position(v(0.0, 0.27))).expect("bar");
        let post = ShapeDef::polygon(sc.post).offset(v(-0.75, 1.0)).friction(s(mu));
        sc.w.add_shape(l, post).expect("room");
        sc.w.state_hashes()
    };
    let (a, b) = (hashes(0.6), hashes(0.3));
    assert_ne!(a.all, b.all);
    assert_eq!(a.differing(&b).collect::<Vec<_>>(), ["bodies"]);
}
