//! Snapshot integrity and cheap rollback: every corrupted byte is rejected by the
//! checksum before anything is applied; the state hash is the snapshot's
//! trailer; a snapshot restores from a longer buffer; `max_snapshot_len` bounds
//! every snapshot a world can write; per-part hashes name the part that diverged.

use arphysics::snapshot::{
    diff, Difference, Object, StateHashes, ARBITER_MANIFOLDS, ARBITER_RECORD, JOINT_RECORD, MANIFOLD_RECORD,
    TRAILER,
};
use arphysics::{
    BodyDef, BodyHandle, Capacities, Error, GravityForceGenerator, GravityToPointForceGenerator, JointDef,
    JointHandle, JointKind, LinearForceGenerator, PolygonPath, Rect, Scalar, Targets, Vector2, World,
    WorldDef,
};
use twox_hash::XxHash64;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

const DT: f64 = 1.0 / 60.0;

/// A small scene with every kind of state: boxes resting in contact on a
/// ground, circles, a removed body (a free list), a rod and a spring, gravity
/// and a targeted wind.
struct Scene {
    world: World<'static>,
    bodies: Vec<BodyHandle>,
    joints: Vec<JointHandle>,
}

fn scene() -> Scene {
    let bounds = Rect::from_corners(v(-50.0, -20.0), v(50.0, 80.0));
    let mut w =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(32)).expect("world");
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("g")).expect("p");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("b")).expect("p");
    let mut bodies = Vec::new();
    for row in 0..3 {
        for j in 0..(3 - row) {
            let x = f64::from(j) - f64::from(3 - row) * 0.5 + 0.5;
            bodies
                .push(w.add_body(BodyDef::polygon(unit).position(v(x, 0.5 + f64::from(row)))).expect("box"));
        }
    }
    let temp = w.add_body(BodyDef::circle(s(0.2)).position(v(20.0, 30.0))).expect("temp");
    for i in 0..3 {
        bodies.push(
            w.add_body(BodyDef::circle(s(0.4)).position(v(-6.0 + 1.2 * f64::from(i), 1.0 + f64::from(i))))
                .expect("ball"),
        );
    }
    w.remove_body(temp).expect("rm");
    let bob = w.add_body(BodyDef::circle(s(0.3)).position(v(10.0, 10.0))).expect("bob");
    let sb = w.add_body(BodyDef::circle(s(0.3)).position(v(-10.0, 10.0))).expect("sb");
    bodies.extend([bob, sb]);
    let joints = vec![
        w.add_joint(JointDef::to_world(bob, Vector2::ZERO, v(12.0, 13.0), JointKind::Rod { length: s(3.0) }))
            .expect("rod"),
        w.add_joint(JointDef::to_world(
            sb,
            Vector2::ZERO,
            v(-10.0, 13.0),
            JointKind::Spring { stiffness: s(30.0), rest_length: s(1.0) },
        ))
        .expect("spring"),
    ];
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    w.add_force_generator(
        LinearForceGenerator::new(v(2.0, 0.0)).with_targets(Targets::bodies(&[bob]).expect("t")),
    )
    .expect("wind");
    Scene { world: w, bodies, joints }
}

fn run(w: &mut World<'_>, steps: usize) {
    for _ in 0..steps {
        w.step(s(DT)).expect("step");
    }
}

fn take(w: &World<'_>) -> Vec<u8> {
    let mut buf = vec![0u8; w.snapshot_len()];
    let n = w.snapshot(&mut buf).expect("fits");
    assert_eq!(n, buf.len());
    buf
}

/// SplitMix64: a deterministic generator for the random overwrites.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A snapshot of the scene after 60 steps, and the scene stepped on 5 more (so
/// that a wrongly accepted restore would change its hash).
fn snapshot_and_moved_world() -> (Vec<u8>, Scene) {
    let mut sc = scene();
    run(&mut sc.world, 60);
    assert!(sc.world.arbiters().count() >= 5, "the scene has contacts");
    let snap = take(&sc.world);
    run(&mut sc.world, 5);
    (snap, sc)
}

#[test]
fn every_single_bit_flip_of_a_snapshot_is_rejected_and_changes_nothing() {
    let (snap, mut sc) = snapshot_and_moved_world();
    let w = &mut sc.world;
    let before = w.state_hash();
    let mut bad = snap.clone();
    for i in 0..snap.len() {
        for bit in 0..8 {
            bad[i] ^= 1 << bit;
            let result = w.restore(&bad);
            assert!(
                matches!(result, Err(Error::InvalidSnapshot { .. })),
                "flip of bit {bit} of byte {i} of {}: {result:?}",
                snap.len()
            );
            assert_eq!(w.state_hash(), before, "a rejected restore changed the world (byte {i}, bit {bit})");
            bad[i] ^= 1 << bit;
        }
    }
    // The untouched snapshot still restores: the flips were what was rejected.
    w.restore(&snap).expect("the original restores");
}

#[test]
fn random_overwrites_of_a_snapshot_are_rejected_and_change_nothing() {
    let (snap, mut sc) = snapshot_and_moved_world();
    let w = &mut sc.world;
    let before = w.state_hash();
    let mut rng = Rng(0x5eed_0fa1_1b17_e000);
    for trial in 0..5_000 {
        let mut bad = snap.clone();
        let at = rng.below(snap.len());
        let n = 1 + rng.below(16);
        for b in bad.iter_mut().skip(at).take(n) {
            *b = rng.next() as u8;
        }
        if bad == snap {
            continue;
        }
        assert!(w.restore(&bad).is_err(), "trial {trial}: {n} bytes at {at} accepted");
        assert_eq!(w.state_hash(), before, "trial {trial} changed the world");
    }
}

#[test]
fn the_state_hash_is_the_xxh64_trailer_of_the_snapshot() {
    let (snap, sc) = snapshot_and_moved_world();
    let n = snap.len();
    assert_eq!(&snap[..4], b"ARPS");
    assert_eq!(u32::from_le_bytes(snap[4..8].try_into().unwrap()), arphysics::snapshot::VERSION);
    assert_eq!(u64::from_le_bytes(snap[8..16].try_into().unwrap()), n as u64, "the header holds the length");
    let trailer = u64::from_le_bytes(snap[n - TRAILER..].try_into().unwrap());
    assert_eq!(trailer, XxHash64::oneshot(0, &snap[..n - TRAILER]), "the trailer is XXH64 of the rest");
    let now = take(&sc.world);
    let now_trailer = u64::from_le_bytes(now[now.len() - TRAILER..].try_into().unwrap());
    assert_eq!(sc.world.state_hash(), now_trailer, "state_hash equals the trailer of a snapshot taken now");
    assert_eq!(sc.world.state_hashes().all, sc.world.state_hash());
    assert_ne!(trailer, now_trailer, "five steps later the state differs");
}

#[test]
fn a_snapshot_restores_from_a_longer_zero_or_garbage_padded_buffer() {
    let mut reference = scene();
    run(&mut reference.world, 40);
    let snap = take(&reference.world);
    let expected = reference.world.state_hash();
    let mut rng = Rng(7);
    let paddings: [Vec<u8>; 3] =
        [vec![0; 1000], vec![0xff; 3], (0..5000).map(|_| rng.next() as u8).collect()];
    for pad in paddings {
        let mut other = scene();
        run(&mut other.world, 7);
        let mut buf = snap.clone();
        buf.extend_from_slice(&pad);
        other.world.restore(&buf).expect("a longer buffer restores");
        assert_eq!(other.world.state_hash(), expected);
        assert_eq!(diff(&buf, &snap), Ok(None), "diff reads a padded buffer too");
        run(&mut other.world, 30);
        let mut r = scene();
        run(&mut r.world, 70);
        assert_eq!(other.world.state_hash(), r.world.state_hash(), "steps on as if never interrupted");
    }
    // A ring-buffer slot of the largest size: written in place, bytes after the
    // snapshot left as they were.
    let mut slot = vec![0xEE; reference.world.max_snapshot_len()];
    let n = reference.world.snapshot(&mut slot).expect("the largest slot fits");
    assert_eq!(n, snap.len());
    assert_eq!(&slot[..n], &snap[..]);
    assert!(slot[n..].iter().all(|b| *b == 0xEE), "snapshot writes only its own bytes");
    // A length beyond the buffer is truncation.
    assert!(matches!(reference.world.restore(&snap[..n - 1]), Err(Error::InvalidSnapshot { .. })));
}

#[test]
fn max_snapshot_len_bounds_a_world_filled_to_capacity() {
    let caps = Capacities { bodies: 40, paths: 2, contacts: 30, joints: 12, ..Capacities::for_bodies(40) };
    let bounds = Rect::from_corners(v(-200.0, -20.0), v(200.0, 200.0));
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), caps).expect("world");
    let max = w.max_snapshot_len();
    assert!(w.snapshot_len() <= max);
    // Every body slot, each with its own properties (distinct user data), apart
    // so nothing touches yet.
    let mut bodies = Vec::new();
    for i in 0..caps.bodies {
        let def = BodyDef::circle(s(0.4)).position(v(-190.0 + 9.0 * i as f64, 100.0)).user_data(i as u64);
        bodies.push(w.add_body(def).expect("body"));
    }
    assert!(w.add_body(BodyDef::circle(s(0.4))).is_err(), "the body store is full");
    // Every generator slot, each with the longest target list.
    let targets: Vec<BodyHandle> =
        bodies.iter().copied().cycle().take(arphysics::force::MAX_TARGETS).collect();
    let mut generators = 0;
    while w
        .add_force_generator(
            GravityToPointForceGenerator::new(v(0.0, 0.0), s(0.001))
                .with_targets(Targets::bodies(&targets).expect("t")),
        )
        .is_ok()
    {
        generators += 1;
    }
    assert_eq!(generators, arphysics::force::MAX_FORCE_GENERATORS);
    // Every joint slot.
    for (i, b) in bodies.iter().take(caps.joints).enumerate() {
        let anchor = v(-190.0 + 9.0 * i as f64, 102.0);
        w.add_joint(JointDef::to_world(*b, Vector2::ZERO, anchor, JointKind::Rod { length: s(2.0) }))
            .expect("joint");
    }
    // Nothing touches: the snapshot is the largest but for the contact store,
    // whose every arbiter would also write its manifold record (the world
    // recycles contacts, the default; the bound allows for them in any world).
    let per_arbiter = ARBITER_RECORD + MANIFOLD_RECORD;
    let len = w.snapshot_len();
    assert_eq!(max - len, caps.contacts * per_arbiter, "everything else is at its maximum");
    assert_eq!(take(&w).len(), len);
    // Touching pairs fill the contact store: the largest snapshot is the bound.
    for pair in bodies.chunks(2).skip(caps.joints / 2).take(caps.contacts) {
        let p = w.body(pair[0]).expect("live").position();
        w.set_position(pair[1], p + v(0.5, 0.0)).expect("inside");
    }
    w.step(s(DT)).expect("step");
    let arbiters = w.arbiters().count();
    assert!(arbiters > 0, "the moved bodies touch");
    let len = w.snapshot_len();
    assert!(len <= max);
    assert_eq!(max - len, (caps.contacts - arbiters) * per_arbiter);
}

fn hashes(w: &World<'_>) -> StateHashes {
    w.state_hashes()
}

fn differing(a: &StateHashes, b: &StateHashes) -> Vec<&'static str> {
    a.differing(b).collect()
}

#[test]
fn per_part_hashes_name_only_the_part_that_diverged() {
    let (mut a, mut b) = (scene(), scene());
    run(&mut a.world, 30);
    run(&mut b.world, 30);
    let base = hashes(&a.world);
    assert_eq!(base, hashes(&b.world));
    assert_eq!(base.all, a.world.state_hash());

    // One body's velocity: the bodies part only.
    let victim = b.bodies[2];
    let vel = b.world.body(victim).expect("live").linear_velocity();
    b.world.body_mut(victim).expect("live").set_linear_velocity(vel + v(0.0, 1e-6));
    assert_eq!(differing(&base, &hashes(&b.world)), ["bodies"]);
    assert_ne!(hashes(&b.world).all, base.all);
    b.world.body_mut(victim).expect("live").set_linear_velocity(vel);
    assert_eq!(hashes(&b.world), base, "put back, equal again");

    // A body's user data (a property): bodies only.
    b.world.body_mut(victim).expect("live").set_user_data(99);
    assert_eq!(differing(&base, &hashes(&b.world)), ["bodies"]);
    b.world.body_mut(victim).expect("live").set_user_data(0);

    // A generator added: generators and their allocator.
    let g = b.world.add_force_generator(GravityForceGenerator::new(v(0.0, -1.0))).expect("g");
    assert_eq!(differing(&base, &hashes(&b.world)), ["generators", "allocators"]);
    b.world.remove_force_generator(g).expect("rm");

    // A joint removed: joints and their allocator.
    let mut c = scene();
    run(&mut c.world, 30);
    c.world.remove_joint(c.joints[1]).expect("rm");
    assert_eq!(differing(&base, &hashes(&c.world)), ["joints", "allocators"]);

    // One warm-start impulse of one arbiter (edited in the bytes, checksum
    // recomputed): contacts only.
    let mut snap = take(&a.world);
    let n = snap.len();
    let joints_used = a.world.joints().count();
    // The contacts part ends with one manifold record per arbiter (the scene
    // recycles contacts, the default; no chains, so no sub-key words).
    let contacts_end = n - TRAILER - 12 - joints_used * JOINT_RECORD;
    let first_arbiter = contacts_end - a.world.arbiters().count() * (ARBITER_RECORD + MANIFOLD_RECORD);
    let normal_impulse = first_arbiter + 8 + 8 + 1 + 4 + 1 + 2;
    snap[normal_impulse] ^= 1;
    let sum = XxHash64::oneshot(0, &snap[..n - TRAILER]);
    snap[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
    let mut d = scene();
    d.world.restore(&snap).expect("an edited, resealed snapshot is valid");
    assert_eq!(differing(&base, &hashes(&d.world)), ["contacts"]);
    let found = diff(&take(&a.world), &snap).expect("valid").expect("differs");
    assert!(matches!(found, Difference { object: Object::Arbiter(..), field: "normal impulse" }), "{found}");

    // A step: the world part (step count) and the motion.
    run(&mut b.world, 1);
    let after = differing(&base, &hashes(&b.world));
    assert!(after.contains(&"world") && after.contains(&"bodies"), "{after:?}");
}

/// Four boxes resting on a ground (three in a row, one on top), and a static
/// sensor over the row: its overlap is an arbiter without contact points, so
/// without a kept manifold. No joints, no chains.
fn resting_boxes() -> World<'static> {
    let bounds = Rect::from_corners(v(-50.0, -20.0), v(50.0, 80.0));
    let mut w =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(16)).expect("world");
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).expect("gravity");
    let ground = w.add_path(PolygonPath::rectangle(s(40.0), s(1.0)).expect("g")).expect("p");
    w.add_body(BodyDef::polygon(ground).position(v(0.0, -0.5)).static_body()).expect("ground");
    let unit = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).expect("b")).expect("p");
    for i in 0..3 {
        w.add_body(BodyDef::polygon(unit).position(v(f64::from(i), 0.5))).expect("box");
    }
    w.add_body(BodyDef::polygon(unit).position(v(0.5, 1.5))).expect("top");
    w.add_body(BodyDef::polygon(unit).position(v(2.0, 1.2)).static_body().sensor()).expect("sensor");
    w
}

#[test]
fn a_recycling_world_writes_one_manifold_record_per_arbiter_and_checks_them() {
    let mut w = resting_boxes();
    let default = arphysics::limits::DEFAULT_CONTACT_RECYCLE_DISTANCE;
    assert_ne!(default, Scalar::ZERO, "recycling is the default");
    run(&mut w, 120);
    let snap = take(&w);
    let (n, k) = (snap.len(), w.arbiters().count());
    assert!(k >= 6, "the boxes rest in contact ({k} arbiters)");
    // From the end (no joints, no chains, so no sub-key words): the joint
    // allocator, one manifold record per arbiter, the arbiter records, their
    // count.
    let manifolds_at = n - TRAILER - 12 - k * MANIFOLD_RECORD;
    let records_at = manifolds_at - k * ARBITER_RECORD;
    let count = u32::from_le_bytes(snap[records_at - 4..records_at].try_into().unwrap());
    assert_eq!(count, k as u32 | ARBITER_MANIFOLDS, "bit 30 set, bit 31 clear");
    let state = |i: usize| snap[records_at + i * ARBITER_RECORD + 16];
    assert!((0..k).any(|i| state(i) & 0x40 != 0), "resting contacts keep their manifolds");
    let bare = (0..k).find(|&i| state(i) & 0x40 == 0).expect("the sensor's arbiter keeps none");
    let bare_at = manifolds_at + bare * MANIFOLD_RECORD;
    assert!(snap[bare_at..bare_at + MANIFOLD_RECORD].iter().all(|&b| b == 0), "its record is zeros");

    // The same world with recycling off: the 58-byte records only, and 128
    // bytes an arbiter shorter.
    let mut off = resting_boxes();
    off.restore(&snap).expect("restore");
    assert_eq!(off.state_hash(), w.state_hash());
    off.set_contact_recycle_distance(Scalar::ZERO).expect("0 turns recycling off");
    let plain = take(&off);
    assert_eq!(n, plain.len() + k * MANIFOLD_RECORD);
    let plain_records = plain.len() - TRAILER - 12 - k * ARBITER_RECORD;
    assert_eq!(plain_records, records_at, "the same offset: the world part is the same size");
    assert_eq!(u32::from_le_bytes(plain[plain_records - 4..plain_records].try_into().unwrap()), k as u32);
    // The records are the same but for the kept-manifold bit.
    let mut unflagged = snap[records_at..manifolds_at].to_vec();
    for i in 0..k {
        unflagged[i * ARBITER_RECORD + 16] &= !0x40;
    }
    assert_eq!(unflagged, plain[plain_records..plain_records + k * ARBITER_RECORD]);

    // Non-zero bytes in the manifold record of the arbiter without a kept
    // manifold (checksum recomputed): refused, the world (stepped on, so an
    // accepted restore would show) unchanged.
    run(&mut w, 5);
    let (hash, bytes) = (w.state_hash(), take(&w));
    // The normal's x, body A's rotation's cosine, the second point's separation.
    for offset in [0, 16, 48 + 40 + 32] {
        let mut bad = snap.clone();
        bad[bare_at + offset] = 1;
        let sum = XxHash64::oneshot(0, &bad[..n - TRAILER]);
        bad[n - TRAILER..].copy_from_slice(&sum.to_le_bytes());
        match w.restore(&bad) {
            Err(Error::InvalidSnapshot { what }) => assert!(what.contains("manifold"), "{what}"),
            other => panic!("a manifold without the flag accepted (byte {offset}): {other:?}"),
        }
        assert_eq!(w.state_hash(), hash, "byte {offset}: the world changed");
        assert_eq!(take(&w), bytes, "byte {offset}: the world changed");
    }
    // The untouched snapshot restores.
    w.restore(&snap).expect("restore");
    assert_eq!(take(&w), snap);
}
