//! Handles and attachments under rollback: handles carry their world, game
//! constraints follow their bodies by handle across removal and restore, and a
//! frozen (out-of-bounds) body is moved by nothing.
//!
//! The regression tests for issue 15, items 2, 4, 5 and 11 (reproducers in the
//! audit's `rollback_trust.rs`).
use arphysics::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}
fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}
fn world() -> World<'static> {
    World::with_capacities(WorldDef::new(s(100.0), s(100.0)), Capacities::for_bodies(16)).unwrap()
}
fn snapshot(w: &World<'_>) -> Vec<u8> {
    let mut buf = vec![0u8; w.snapshot_len()];
    w.snapshot(&mut buf).unwrap();
    buf
}
const DT: f64 = 1.0 / 60.0;

/// A 0.5 m ball at (`x`, 50).
fn ball(w: &mut World<'_>, x: f64) -> BodyHandle {
    w.add_body(BodyDef::circle(s(0.5)).position(v(x, 50.0))).unwrap()
}

// ---- item 5: handles from another world -------------------------------------

/// Error::StaleHandle: "the handle refers to an object that was removed (or
/// never existed in this world)". World B's objects sit in the same slots with
/// the same generations as world A's, so only the world tag tells them apart.
#[test]
fn a_handle_from_another_world_is_stale_everywhere() {
    let build = |user: u64| {
        let mut w = world();
        let path = w.add_path(PolygonPath::rectangle(s(1.0), s(1.0)).unwrap()).unwrap();
        let a = w.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 10.0)).user_data(user)).unwrap();
        let b = w.add_body(BodyDef::polygon(path).position(v(20.0, 10.0))).unwrap();
        let j = w
            .add_joint(JointDef::new(a, v(0.0, 0.0), b, v(0.0, 0.0), JointKind::Rod { length: s(10.0) }))
            .unwrap();
        let g = w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).unwrap();
        let c = w.add_constraint(a, Some(b), Hook::Boxed(Box::new(Kick))).unwrap();
        (w, path, a, b, j, g, c)
    };
    let (mut wa, pa, a, _, ja, ga, ca) = build(111);
    let (_wb, pb, fa, fb, jb, gb, cb) = build(222);
    assert_eq!((a.index(), a.generation()), (fa.index(), fa.generation()), "same slot, same generation");
    assert_ne!(a, fa);
    let before = wa.state_hash();

    assert_eq!(wa.body(fa).err(), Some(Error::StaleHandle));
    assert_eq!(wa.body_mut(fa).err(), Some(Error::StaleHandle));
    assert_eq!(wa.set_position(fa, v(50.0, 50.0)), Err(Error::StaleHandle));
    assert_eq!(wa.set_static(fa), Err(Error::StaleHandle));
    assert_eq!(wa.remove_body(fa).map(|b| b.user_data()), Err(Error::StaleHandle));
    assert_eq!(wa.path(pb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.remove_path(pb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.add_body(BodyDef::polygon(pb).position(v(30.0, 30.0))), Err(Error::StaleHandle));
    assert_eq!(wa.joint(jb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.joint_mut(jb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.remove_joint(jb).err(), Some(Error::StaleHandle));
    let foreign_joint = JointDef::new(fa, v(0.0, 0.0), fb, v(0.0, 0.0), JointKind::Rod { length: s(10.0) });
    assert_eq!(wa.add_joint(foreign_joint), Err(Error::StaleHandle));
    assert_eq!(wa.force_generator_mut(gb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.remove_force_generator(gb).err(), Some(Error::StaleHandle));
    assert_eq!(wa.constraint_is_active(cb), Err(Error::StaleHandle));
    assert_eq!(wa.remove_constraint(cb), Err(Error::StaleHandle));
    assert_eq!(wa.add_constraint(fa, Some(fb), Hook::Boxed(Box::new(Kick))), Err(Error::StaleHandle));
    // Packed and unpacked, it is still world B's handle.
    assert_eq!(wa.body(BodyHandle::from_bits(fa.to_bits())).err(), Some(Error::StaleHandle));

    assert_eq!(wa.state_hash(), before, "nothing changed in world A");
    assert_eq!(wa.body(a).map(Body::user_data), Ok(111));
    assert!(wa.path(pa).is_ok() && wa.joint(ja).is_ok() && wa.force_generator_mut(ga).is_ok());
    assert_eq!(wa.constraint_is_active(ca), Ok(true));
}

/// The audit's reproducer: `remove_body` with world B's handle removed world
/// A's body in that slot.
#[test]
fn removing_with_another_worlds_handle_leaves_the_body() {
    let mut a = world();
    let mut b = world();
    let mine = a.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 10.0)).user_data(111)).unwrap();
    let from_b = b.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0)).user_data(222)).unwrap();
    assert_eq!(a.remove_body(from_b).map(|x| x.user_data()), Err(Error::StaleHandle));
    assert_eq!(a.body(mine).map(Body::user_data), Ok(111));
}

/// Snapshots hold index and generation only, so a world of the same settings
/// and capacities restores another's snapshot; the handles it then gives out are
/// its own, and the other world's handles stay foreign.
#[test]
fn a_restore_into_another_world_gives_the_restoring_worlds_handles() {
    let scene = || {
        let mut w = world();
        let a = w.add_body(BodyDef::circle(s(1.0)).position(v(50.0, 50.0))).unwrap();
        let b = w.add_body(BodyDef::circle(s(1.0)).position(v(51.5, 50.0))).unwrap();
        let c = w.add_body(BodyDef::circle(s(1.0)).position(v(48.5, 50.0))).unwrap();
        w.add_joint(JointDef::new(a, v(0.0, 0.0), b, v(0.0, 0.0), JointKind::Rod { length: s(1.5) }))
            .unwrap();
        w.add_force_generator(
            LinearForceGenerator::new(v(1.0, 0.0)).with_targets(Targets::bodies(&[b]).unwrap()),
        )
        .unwrap();
        (w, a, b, c)
    };
    let (mut src, a, b, _) = scene();
    for _ in 0..5 {
        src.step(s(DT)).unwrap();
    }
    let snap = snapshot(&src);
    let (mut dst, da, _, dc) = scene();
    dst.restore(&snap).unwrap();
    assert_eq!(dst.state_hash(), src.state_hash(), "the tag is in neither the snapshot nor the hash");
    assert_eq!(dst.body(a).err(), Some(Error::StaleHandle), "the source world's handle");
    let mine = dst.handle_from_parts::<Body>(b.index(), b.generation());
    let (ha, _) = dst.bodies().next().unwrap();
    assert_eq!(ha, da, "restored bodies carry the restoring world's tag");
    assert_eq!(dst.body(mine).unwrap().position(), src.body(b).unwrap().position());
    // The restored arbiter, joint and generator name the restoring world's bodies.
    assert!(src.arbiter(a, da).is_none(), "another world's handles find nothing");
    assert!(dst.arbiter(da, dc).is_some(), "the arbiter is found by this world's handles");
    assert_eq!(dst.joints().next().map(|(_, j)| j.def().body_a), Some(da));
    for _ in 0..20 {
        src.step(s(DT)).unwrap();
        dst.step(s(DT)).unwrap();
    }
    assert_eq!(
        dst.state_hash(),
        src.state_hash(),
        "the generator and joint still act in the restoring world"
    );
}

/// Peers exchange index and generation: the receiving world rebuilds its own
/// handle from them.
#[test]
fn handle_from_parts_names_the_object_of_this_world_only() {
    let mut w = world();
    let h = w.add_body(BodyDef::circle(s(1.0)).position(v(10.0, 10.0)).user_data(7)).unwrap();
    assert_eq!(w.handle_from_parts::<Body>(h.index(), h.generation()), h);
    assert_eq!(w.body(BodyHandle::from_parts(h.index(), h.generation())).err(), Some(Error::StaleHandle));
    assert_eq!(w.body(w.handle_from_parts(h.index(), h.generation() + 1)).err(), Some(Error::StaleHandle));
    assert!(w.body(BodyHandle::NULL).is_err());
    assert_eq!(BodyHandle::NULL.to_bits(), 0);
}

/// Every handle packs into a `u64` (index 20 bits, world tag 12, generation
/// 32), so a store of more than 2^20 − 1 slots is refused, before allocating.
#[test]
fn a_store_of_more_than_a_million_slots_is_refused() {
    let def = || WorldDef::new(s(100.0), s(100.0));
    let too_many = arena::MAX_SLOTS + 1;
    for caps in [
        Capacities { bodies: too_many, ..Capacities::for_bodies(4) },
        Capacities { paths: too_many, ..Capacities::for_bodies(4) },
        Capacities { joints: too_many, ..Capacities::for_bodies(4) },
    ] {
        assert!(matches!(World::with_capacities(def(), caps), Err(Error::OutOfRange { .. })), "{caps:?}");
    }
}

// ---- items 2 and 4: game constraints by handle -------------------------------

struct Kick;
impl Constraint for Kick {
    fn solve(&mut self, _a: &mut Body, b: &mut Body, _h: Scalar) {
        b.set_linear_velocity(v(0.0, 5.0));
    }
}

/// README: "a removed body's handle is an error, never another body". A game
/// constraint made for B must not act on C, which a restore put back in B's slot.
#[test]
fn game_constraint_acts_on_another_body_after_restore() {
    let mut w = world();
    let anchor = ball(&mut w, 10.0);
    let c = ball(&mut w, 30.0);
    let snap = snapshot(&w);
    w.remove_body(c).unwrap();
    let b = ball(&mut w, 60.0); // same slot, new generation
    assert_eq!(b.index(), c.index());
    let k = w.add_constraint(anchor, Some(b), Hook::Boxed(Box::new(Kick))).unwrap();
    w.restore(&snap).unwrap(); // B no longer exists, C is back
    assert!(w.body(b).is_err());
    assert_eq!(w.constraint_is_active(k), Ok(false));
    w.step(s(DT)).unwrap();
    assert_eq!(w.body(c).unwrap().linear_velocity(), Vector2::ZERO, "the constraint made for B moved C");
}

/// The same without a restore: a body that takes a removed body's slot is not
/// driven by the removed body's constraint.
#[test]
fn a_dormant_constraint_ignores_the_body_that_took_its_slot() {
    let mut w = world();
    let anchor = ball(&mut w, 10.0);
    let b = ball(&mut w, 30.0);
    let k = w.add_constraint(anchor, Some(b), Hook::Boxed(Box::new(Kick))).unwrap();
    w.remove_body(b).unwrap();
    let c = ball(&mut w, 60.0);
    assert_eq!(c.index(), b.index());
    w.step(s(DT)).unwrap();
    assert_eq!(w.body(c).unwrap().linear_velocity(), Vector2::ZERO);
    assert_eq!(w.dormant_constraints().collect::<Vec<_>>(), vec![k]);
}

struct Pull;
impl Constraint for Pull {
    fn solve(&mut self, a: &mut Body, b: &mut Body, h: Scalar) {
        let d = b.position() - a.position();
        a.apply_linear_impulse(d * h);
        b.apply_linear_impulse(-(d * h));
    }
}

/// Snapshot docs: restore then stepping gives the same bits as never leaving the
/// state. A speculative frame removed B (and with it, before, B's game
/// constraint); rolling it back must bring the constraint back with B.
#[test]
fn rollback_across_remove_body_loses_game_constraint() {
    let mut w = world();
    let a = ball(&mut w, 10.0);
    let b = ball(&mut w, 20.0);
    let k = w.add_constraint(a, Some(b), Hook::Boxed(Box::new(Pull))).unwrap();
    let snap = snapshot(&w);
    let start = w.body(b).unwrap().position();
    for _ in 0..10 {
        w.step(s(DT)).unwrap();
    }
    let reference = w.state_hash();
    let pulled = start.x - w.body(b).unwrap().position().x;
    assert!(pulled > s(0.1), "the constraint pulled B {pulled} m towards A");
    w.remove_body(b).unwrap(); // a speculative frame that removed B...
    assert_eq!(w.constraint_is_active(k), Ok(false));
    assert_eq!(w.dormant_constraints().collect::<Vec<_>>(), vec![k]);
    w.restore(&snap).unwrap(); // ...is rolled back: B is back
    assert_eq!(w.constraint_is_active(k), Ok(true));
    assert_eq!(w.dormant_constraints().count(), 0);
    for _ in 0..10 {
        w.step(s(DT)).unwrap();
    }
    assert_eq!(w.state_hash(), reference, "re-simulated steps differ from the first run");
}

/// A dormant constraint stays registered (and counts against the capacity)
/// until the game removes it.
#[test]
fn only_remove_constraint_removes_a_game_constraint() {
    let mut w = world();
    let a = ball(&mut w, 10.0);
    let b = ball(&mut w, 20.0);
    let k = w.add_constraint(a, Some(b), Hook::Boxed(Box::new(Pull))).unwrap();
    let to_point = w.add_constraint(b, None, Hook::Boxed(Box::new(Kick))).unwrap();
    w.remove_body(b).unwrap();
    for _ in 0..3 {
        w.step(s(DT)).unwrap();
    }
    assert_eq!(w.body(a).unwrap().linear_velocity(), Vector2::ZERO, "a dormant constraint is not solved");
    assert_eq!(w.dormant_constraints().collect::<Vec<_>>(), vec![k, to_point]);
    assert_eq!(w.remove_constraint(k), Ok(()));
    assert_eq!(w.constraint_is_active(k), Err(Error::StaleHandle));
    assert_eq!(w.dormant_constraints().collect::<Vec<_>>(), vec![to_point]);
}

// ---- item 11: frozen bodies ----------------------------------------------------

/// Body::is_out_of_bounds: a frozen body is not moved and keeps zero velocity.
/// The audit's spring pushed one to 377,480 m/s.
#[test]
fn frozen_body_is_pushed_by_joint_without_limit() {
    let mut w = world();
    let a =
        w.add_body(BodyDef::circle(s(0.5)).position(v(99.0, 50.0)).linear_velocity(v(100.0, 0.0))).unwrap();
    let b = ball(&mut w, 90.0);
    let spring = JointKind::Spring { stiffness: s(100.0), rest_length: s(1000.0) };
    w.add_joint(JointDef::new(a, v(0.0, 0.0), b, v(0.0, 0.0), spring)).unwrap();
    w.step(s(DT)).unwrap();
    assert!(w.body(a).unwrap().is_out_of_bounds(), "100 m/s from 99 m leaves the 100 m world");
    let frozen_at = w.body(a).unwrap().position();
    for _ in 0..200 {
        w.step(s(DT)).unwrap();
    }
    let body = w.body(a).unwrap();
    assert!(body.is_out_of_bounds());
    assert_eq!(body.linear_velocity(), Vector2::ZERO);
    assert_eq!(body.angular_velocity(), Scalar::ZERO);
    assert_eq!(body.position(), frozen_at);
    // The other end is held as by a fixed point: pushed away (rest length
    // 1000 m) until it leaves the world too, never faster than the speed limit.
    let other = w.body(b).unwrap();
    assert!(other.linear_velocity().length() <= w.def().max_linear_speed);
}

struct Drag;
impl Constraint for Drag {
    fn solve(&mut self, a: &mut Body, _b: &mut Body, h: Scalar) {
        a.apply_linear_impulse(v(-50.0, 30.0) * h);
        a.apply_angular_impulse(s(20.0) * h);
        a.set_linear_velocity(v(-3.0, 0.0));
    }
}

/// A frozen body attached to a moving one by a pivot, and driven by a game
/// constraint, stays where it froze; the pivot holds the other body to it.
#[test]
fn a_frozen_body_is_moved_by_neither_pivot_nor_game_constraint() {
    let mut w = world();
    w.add_force_generator(GravityForceGenerator::new(v(0.0, -10.0))).unwrap();
    let a =
        w.add_body(BodyDef::circle(s(0.5)).position(v(99.5, 50.0)).linear_velocity(v(60.0, 0.0))).unwrap();
    w.step(s(DT)).unwrap();
    assert!(w.body(a).unwrap().is_out_of_bounds());
    let frozen_at = w.body(a).unwrap().position();
    let b = ball(&mut w, 98.0);
    let pivot = JointKind::Pivot { limits: None, motor: None };
    w.add_joint(JointDef::new(a, v(-1.5, 0.0), b, v(0.0, 0.0), pivot)).unwrap();
    w.add_constraint(a, Some(b), Hook::Boxed(Box::new(Drag))).unwrap();
    for _ in 0..120 {
        w.step(s(DT)).unwrap();
    }
    let frozen = w.body(a).unwrap();
    assert_eq!(frozen.position(), frozen_at);
    assert_eq!(frozen.linear_velocity(), Vector2::ZERO);
    assert_eq!(frozen.angular_velocity(), Scalar::ZERO);
    // B hangs on the pivot, at the anchor 1.5 m left of the frozen body.
    let anchor = frozen_at + v(-1.5, 0.0);
    let off = (w.body(b).unwrap().position() - anchor).length();
    assert!(off < s(0.05), "B is {off} m from the pivot on the frozen body");
}
