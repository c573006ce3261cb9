//! Validation: restore validates the whole buffer before it changes anything.
//!
//! [`validate`] reads every record of a parsed [`Layout`] and checks it against
//! the world: same settings and polygon paths, capacities large enough, values in
//! the ranges the engine's limits assume, consistent free lists, arbiters in key
//! order, and only live bodies named by arbiters and joints. It never changes the
//! world, so a rejected snapshot leaves the world as it was, and `apply` cannot
//! fail half-way.

use super::layout::{Alloc, BodyRecord, CachedPoint, GeneratorRecord, Layout, StoredGenerator};
use super::write::{paths_checksum, Props};
use super::{invalid, CACHED, LINK_MASK, NO_LINK, TOUCHING};
use crate::arbiter::{ArbiterState, MAX_STEPS_SEPARATED};
use crate::body::{shape_radius, BodyHandle, BodyType, Shape};
use crate::compound::{BodyShape, MAX_SHAPES_PER_BODY, NO_SHAPE};
use crate::error::Error;
use crate::force::{Generator, Targets};
use crate::geometry::circle::MAX_CIRCLE_RADIUS;
use crate::geometry::mass::{MAX_INERTIA, MAX_MASS, MIN_INERTIA, MIN_MASS};
use crate::geometry::{Capsule, Segment};
use crate::limits::{check_damping, check_friction, check_gravity_scale, check_restitution, MAX_BODY_RADIUS};
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rot, Vector2};
use crate::world::{World, MAX_COORDINATE};

/// Checks a free list: starting at `head`, every link names a free slot below
/// `used`, no slot twice, and it covers exactly `used − len` slots.
fn check_free_list(
    alloc: Alloc,
    retired: u32,
    mut free_at: impl FnMut(u32) -> Result<Option<u32>, Error>,
) -> Result<(), Error> {
    let expected = alloc
        .used
        .checked_sub(alloc.len)
        .and_then(|free| free.checked_sub(retired))
        .ok_or_else(|| invalid("more live objects than slots"))?;
    let mut at = alloc.free_head;
    let mut seen = 0u32;
    while at != NO_LINK {
        if at >= alloc.used || seen >= expected {
            return Err(invalid("broken free list"));
        }
        at = free_at(at)?.ok_or_else(|| invalid("free list through a live or retired slot"))?;
        seen = seen.saturating_add(1);
    }
    if seen != expected {
        return Err(invalid("free list misses free slots"));
    }
    Ok(())
}

fn in_range(v: Scalar, lo: Scalar, hi: Scalar) -> bool {
    v >= lo && v <= hi
}

/// A shape of a body of type `body_type` (a chain only on a static body).
fn check_shape(w: &World<'_>, shape: Shape, body_type: BodyType) -> Result<(), Error> {
    match shape {
        Shape::Circle { radius } => {
            if !in_range(radius, Scalar::DELTA, MAX_CIRCLE_RADIUS) {
                return Err(invalid("circle radius out of range"));
            }
        }
        Shape::Polygon(h) => {
            if w.paths.get(h).is_none() {
                return Err(invalid("a body's polygon path is not in this world"));
            }
        }
        Shape::Capsule(c) => {
            if Capsule::new(c.center1(), c.center2(), c.radius()).is_err() {
                return Err(invalid("capsule out of range"));
            }
        }
        Shape::Segment(sg) => {
            if Segment::new(sg.point1(), sg.point2()).is_err() {
                return Err(invalid("segment out of range"));
            }
        }
        Shape::Chain(h) => {
            if !w.paths.chains.valid(h) || body_type != BodyType::Static {
                return Err(invalid("a body's chain is not in this world"));
            }
        }
    }
    Ok(())
}

fn check_props(w: &World<'_>, p: &Props) -> Result<(), Error> {
    check_shape(w, p.shape, p.body_type)?;
    let ok_mass = match p.body_type {
        BodyType::Dynamic => {
            in_range(p.mass, MIN_MASS, MAX_MASS) && in_range(p.inertia, MIN_INERTIA, MAX_INERTIA)
        }
        _ => p.mass == ZERO && p.inertia == ZERO,
    };
    if !ok_mass {
        return Err(invalid("mass out of range"));
    }
    check_friction(p.friction)
        .and(check_restitution(p.restitution))
        .map_err(|_| invalid("material out of range"))?;
    check_damping(p.linear_damping)
        .and(check_damping(p.angular_damping))
        .map_err(|_| invalid("damping out of range"))?;
    check_gravity_scale(p.gravity_scale).map_err(|_| invalid("gravity scale out of range"))?;
    Ok(())
}

fn check_motion(r: &BodyRecord) -> Result<(), Error> {
    let far = MAX_COORDINATE + Scalar::from_int(4096);
    let p = r.position;
    if p.x.abs() > far || p.y.abs() > far {
        return Err(invalid("position out of range"));
    }
    if !is_unit(r.rotation) {
        return Err(invalid("rotation is not a unit rotation"));
    }
    // Speeds are not limited here: a game may set any velocity between steps,
    // and the step clamps it (see `World::step`), so the snapshot of such a world
    // must restore.
    Ok(())
}

/// True when `q` is a rotation: cos² + sin² within 1e-6 of 1.
fn is_unit(q: Rot) -> bool {
    // A constant: `lit` in an expression would parse the string at run time,
    // once per body.
    const UNIT_TOLERANCE: Scalar = Scalar::lit("0.000001");
    let norm = (q.c * q.c) + (q.s * q.s);
    (norm - scalar::ONE).abs() <= UNIT_TOLERANCE
}

/// One shape of a compound body: the shape as a properties record's (no
/// chain: a chain is a body of its own), a frame within a body's size, mass
/// and inertia of at most a body's (0 for a segment or on a static body),
/// the material in range.
fn check_body_shape(w: &World<'_>, d: &BodyShape) -> Result<(), Error> {
    if matches!(d.shape, Shape::Chain(_)) {
        return Err(invalid("a chain among a body's shapes"));
    }
    check_shape(w, d.shape, BodyType::Dynamic)?;
    let p = d.local.p;
    if p.x.abs() > MAX_BODY_RADIUS || p.y.abs() > MAX_BODY_RADIUS || !is_unit(d.local.q) {
        return Err(invalid("a shape's frame on its body out of range"));
    }
    if !in_range(d.mass, ZERO, MAX_MASS) || !in_range(d.inertia, ZERO, MAX_INERTIA) {
        return Err(invalid("a shape's mass out of range"));
    }
    check_friction(d.friction)
        .and(check_restitution(d.restitution))
        .map_err(|_| invalid("material out of range"))
}

/// The shapes section (see [`super::SHAPES`]): the store fits this world;
/// every used slot is a valid shape owned by a live body; the free list is
/// whole; each compound body (listed once, in slot order) has a list of 1 to
/// [`MAX_SHAPES_PER_BODY`] of its own slots ending in `NO_SHAPE`, whose first
/// shape is the one the body's properties hold, within the size limit; and
/// the lists together hold every used slot, so each exactly once.
fn check_shapes(w: &World<'_>, l: &Layout<'_>) -> Result<(), Error> {
    let Some(section) = l.shapes else { return Ok(()) };
    let alloc = section.alloc;
    if alloc.used == 0 {
        return Err(invalid("a shapes section without shapes"));
    }
    if alloc.used as usize > w.paths.slots.capacity() {
        return Err(Error::CapacityFull { what: "shape" });
    }
    let (mut live, mut retired) = (0u32, 0u32);
    for i in 0..alloc.used {
        let r = l.shape(i)?;
        let Some(d) = r.data else {
            if r.generation == 0 {
                retired = retired.saturating_add(1);
            }
            continue;
        };
        if r.generation == 0 {
            return Err(invalid("a used shape slot with generation 0"));
        }
        if !live_slot(l, r.owner)? {
            return Err(invalid("a shape's owner is not a live body"));
        }
        check_body_shape(w, &d)?;
        live = live.saturating_add(1);
    }
    if live != alloc.len {
        return Err(invalid("used shape count does not match"));
    }
    check_free_list(alloc, retired, |i| {
        let r = l.shape(i)?;
        Ok((r.data.is_none() && r.generation != 0).then_some(r.link & LINK_MASK))
    })?;
    let (mut listed, mut last) = (0u32, None);
    for k in 0..section.compounds {
        let (body, head) = l.compound(k)?;
        if last.is_some_and(|b| b >= body) {
            return Err(invalid("compound bodies out of order"));
        }
        last = Some(body);
        if !live_slot(l, body)? {
            return Err(invalid("a compound body that is not live"));
        }
        let p = l.props(l.body(body)?.index())?;
        let mut radius = ZERO;
        let n = walk_list(l, body, head, |i, d| {
            let mirrored = d.shape == p.shape
                && d.friction == p.friction
                && d.restitution == p.restitution
                && d.filter == p.filter
                && d.sensor == p.sensor;
            if i == 0 && !mirrored {
                return Err(invalid("a body's first shape differs from its properties"));
            }
            let r = d.local.p.length() + shape_radius(d.shape, &w.paths) + Scalar::DELTA;
            radius = radius.max(r);
            Ok(())
        })?;
        if radius > MAX_BODY_RADIUS {
            return Err(invalid("a compound body larger than a body may be"));
        }
        listed = listed.saturating_add(n);
    }
    if listed != live {
        return Err(invalid("a used shape slot is in no body's list"));
    }
    Ok(())
}

/// Walks the shape list of body slot `body` from slot `head`, calling `each`
/// with each shape's index and data: every slot used and owned by the body,
/// 1 to [`MAX_SHAPES_PER_BODY`] of them, the last followed by `NO_SHAPE` (so
/// the list has no cycle). Returns the body's shape count.
fn walk_list(
    l: &Layout<'_>,
    body: u32,
    head: u32,
    mut each: impl FnMut(u32, &BodyShape) -> Result<(), Error>,
) -> Result<u32, Error> {
    let used = l.shapes.map_or(0, |s| s.alloc.used);
    let mut at = head;
    let mut n = 0u32;
    while at != NO_SHAPE {
        if n as usize >= MAX_SHAPES_PER_BODY {
            return Err(invalid("a shape list is cyclic or longer than 8 shapes"));
        }
        if at >= used {
            return Err(invalid("a shape list names a slot the store has not used"));
        }
        let r = l.shape(at)?;
        let Some(d) = r.data else { return Err(invalid("a shape list through a free slot")) };
        if r.owner != body {
            return Err(invalid("a shape list through another body's shape"));
        }
        each(n, &d)?;
        n = n.saturating_add(1);
        at = r.next;
    }
    if n == 0 {
        return Err(invalid("a compound body without shapes"));
    }
    Ok(n)
}

/// The shape count of body slot `body` in a snapshot whose shapes section
/// `check_shapes` accepted: its list's length, 1 for a body not listed.
fn shape_count(l: &Layout<'_>, body: u32) -> Result<u32, Error> {
    let Some(section) = l.shapes else { return Ok(1) };
    let (mut lo, mut hi) = (0u32, section.compounds);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        let (b, head) = l.compound(mid)?;
        match b.cmp(&body) {
            core::cmp::Ordering::Equal => return walk_list(l, body, head, |_, _| Ok(())),
            core::cmp::Ordering::Less => lo = mid + 1,
            core::cmp::Ordering::Greater => hi = mid,
        }
    }
    Ok(1)
}

/// Any target list is valid: a stale or null handle never matches a body, which
/// is also what it does in the world the snapshot came from.
fn check_targets(_: &Targets) -> Result<(), Error> {
    Ok(())
}

/// Everything `apply` relies on, checked without changing the world.
pub(super) fn validate(w: &World<'_>, l: &Layout<'_>) -> Result<(), Error> {
    // `strict_capacity`, like the capacities, belongs to the restoring world,
    // not to the state: it is not encoded. The sub-step count and the contact
    // recycle distance are state (a game changes them with `set_substeps` and
    // `set_contact_recycle_distance`): they come back with the snapshot,
    // checked as `World::new` checks them. Compare the rest.
    let def = crate::WorldDef { strict_capacity: w.def.strict_capacity, ..l.def };
    let settable = crate::WorldDef {
        substeps: w.def.substeps,
        contact_recycle_distance: w.def.contact_recycle_distance,
        ..def
    };
    if settable != w.def {
        return Err(Error::SnapshotMismatch { what: "world definition" });
    }
    def.validate().map_err(|_| invalid("sub-steps or contact recycle distance out of range"))?;
    if l.paths != paths_checksum(w) {
        return Err(Error::SnapshotMismatch { what: "polygon paths" });
    }
    for i in 0..l.props {
        check_props(w, &l.props(i)?)?;
    }
    // Bodies.
    if l.bodies.used as usize > w.bodies.capacity() || l.bodies.used > NO_LINK {
        return Err(Error::SnapshotMismatch { what: "more bodies than this world holds" });
    }
    let (mut live, mut retired) = (0u32, 0u32);
    for i in 0..l.bodies.used {
        let r = l.body(i)?;
        if !r.live() && r.generation == 0 {
            // A slot retired after its last generation (arena.rs).
            retired = retired.saturating_add(1);
        }
        if r.live() {
            if r.generation == 0 {
                return Err(invalid("a live body with generation 0"));
            }
            if r.index() >= l.props {
                return Err(invalid("a body's properties index is out of range"));
            }
            check_motion(&r)?;
            // The world stops a fixed-rotation body's spin whenever it locks
            // it, and the solver reads the spin from both the body and its
            // own copy, so a snapshot that says otherwise is not one it wrote.
            if r.angular_velocity != ZERO && l.fixed_rotation(r.index())? {
                return Err(invalid("a fixed-rotation body that spins"));
            }
            live = live.saturating_add(1);
        } else if r.out_of_bounds() {
            return Err(invalid("flags on a free slot"));
        }
    }
    if live != l.bodies.len {
        return Err(invalid("live body count does not match"));
    }
    check_free_list(l.bodies, retired, |i| {
        let r = l.body(i)?;
        Ok((!r.live() && r.generation != 0).then(|| r.index()))
    })?;
    check_shapes(w, l)?;
    // Generators.
    let (mut live, mut retired) = (0u32, 0u32);
    for (i, rec) in l.generators().enumerate() {
        let GeneratorRecord { generation, generator: g, .. } = rec?;
        if g == StoredGenerator::Free && generation == 0 {
            retired = retired.saturating_add(1);
        }
        let world_custom = matches!(w.generators.get_at(i as u32), Some(Generator::Custom(_)));
        if let Some(t) = g.targets() {
            check_targets(t)?;
        }
        if let Some(g) = g.clone().into_generator() {
            g.validate().map_err(|_| invalid("generator parameters out of range"))?;
        }
        if g != StoredGenerator::Free {
            live = live.saturating_add(1);
            if generation == 0 {
                return Err(invalid("a live generator with generation 0"));
            }
        }
        let snapshot_custom = g == StoredGenerator::Custom;
        if snapshot_custom != world_custom {
            return Err(Error::SnapshotMismatch { what: "custom force generators are in other slots" });
        }
    }
    if live != l.generators.len {
        return Err(invalid("live generator count does not match"));
    }
    check_free_list(l.generators, retired, |i| {
        let GeneratorRecord { generation, next, generator: g } =
            l.generators().nth(i as usize).ok_or_else(|| invalid("truncated"))??;
        Ok((g == StoredGenerator::Free && generation != 0).then_some(next))
    })?;
    // Arbiters: sorted by key, at most two points, a state that persists.
    if l.arbiters as usize > w.arbiters.capacity() {
        return Err(Error::SnapshotMismatch { what: "more arbiters than this world holds" });
    }
    let mut last: Option<(u32, u32, u32)> = None;
    for i in 0..l.arbiters {
        let a = l.arbiter(i)?;
        let key = a.key();
        if a.a.index() == a.b.index() || last.is_some_and(|k| k >= key) {
            return Err(invalid("arbiters out of order"));
        }
        last = Some(key);
        if a.link() != 0 && w.paths.chains.used() == 0 {
            return Err(invalid("a chain link in a world without chains"));
        }
        if !a.sub_is_canonical() || a.steps_separated > MAX_STEPS_SEPARATED {
            return Err(invalid("an arbiter's link or steps since separation out of range"));
        }
        if !live_body(l, a.a)? || !live_body(l, a.b)? {
            return Err(invalid("an arbiter names a body that is not in the snapshot"));
        }
        if a.shape_a() >= shape_count(l, a.a.index())? || a.shape_b() >= shape_count(l, a.b.index())? {
            return Err(invalid("an arbiter names a shape its body does not have"));
        }
        let state = ArbiterState::from_u8(a.state & !(TOUCHING | CACHED))
            .ok_or_else(|| invalid("unknown arbiter state"))?;
        let touching_ok = a.state & TOUCHING == 0 || state == ArbiterState::Contact;
        if !matches!(state, ArbiterState::Contact | ArbiterState::Ignoring | ArbiterState::Separated)
            || a.count > 2
            || !touching_ok
        {
            return Err(invalid("an arbiter in a state that does not persist"));
        }
        // A cached manifold has points and was computed at unit rotations;
        // without one (and past the count) its bytes are zeros, so that
        // equal worlds encode equally.
        let m = a.manifold;
        let zero = |p: &CachedPoint| {
            p.anchor_a == Vector2::ZERO && p.anchor_b == Vector2::ZERO && p.separation == ZERO
        };
        let cached_ok = if a.state & CACHED != 0 {
            a.count > 0
                && is_unit(m.rot_a)
                && is_unit(m.rot_b)
                && m.points.iter().skip(usize::from(a.count)).all(zero)
        } else {
            m.normal == Vector2::ZERO
                && m.rot_a == Rot { c: ZERO, s: ZERO }
                && m.rot_b == Rot { c: ZERO, s: ZERO }
                && m.points.iter().all(zero)
        };
        if !cached_ok {
            return Err(invalid("an arbiter's cached manifold is out of range"));
        }
    }
    // Joints.
    if l.joints.used as usize > w.joints.capacity() || l.joints.used > NO_LINK {
        return Err(Error::SnapshotMismatch { what: "more joints than this world holds" });
    }
    let (mut live, mut retired) = (0u32, 0u32);
    for i in 0..l.joints.used {
        let r = l.joint(i)?;
        if r.joint.is_none() && r.generation == 0 {
            retired = retired.saturating_add(1);
        }
        if let Some(j) = &r.joint {
            if r.generation == 0 {
                return Err(invalid("a live joint with generation 0"));
            }
            crate::constraint::validate_params(&j.def)
                .map_err(|_| invalid("joint parameters out of range"))?;
            let b_live = match j.def.body_b {
                Some(b) => live_body(l, b)? && b.index() != j.def.body_a.index(),
                None => true,
            };
            if !live_body(l, j.def.body_a)? || !b_live {
                return Err(invalid("a joint names a body that is not in the snapshot"));
            }
            live = live.saturating_add(1);
        }
    }
    if live != l.joints.len {
        return Err(invalid("live joint count does not match"));
    }
    check_free_list(l.joints, retired, |i| {
        let r = l.joint(i)?;
        Ok((r.joint.is_none() && r.generation != 0).then_some(r.next))
    })?;
    Ok(())
}

/// True when body slot `i` of the snapshot is live.
fn live_slot(l: &Layout<'_>, i: u32) -> Result<bool, Error> {
    Ok(i < l.bodies.used && l.body(i)?.live())
}

/// True when `h` names a live body of the snapshot (same slot and generation).
fn live_body(l: &Layout<'_>, h: BodyHandle) -> Result<bool, Error> {
    if h.index() >= l.bodies.used {
        return Ok(false);
    }
    let r = l.body(h.index())?;
    Ok(r.live() && r.generation == h.generation())
}
