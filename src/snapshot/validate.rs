//! Validation: restore validates the whole buffer before it changes anything.
//!
//! [`validate`] reads every record of a parsed [`Layout`] and checks it against
//! the world: same settings and polygon paths, capacities large enough, values in
//! the ranges the engine's limits assume, consistent free lists, arbiters in key
//! order, and only live bodies named by arbiters and joints. It never changes the
//! world, so a rejected snapshot leaves the world as it was, and `apply` cannot
//! fail half-way.

use super::layout::{Alloc, BodyRecord, GeneratorRecord, Layout, StoredGenerator};
use super::write::{paths_checksum, Props};
use super::{invalid, NO_LINK, TOUCHING};
use crate::arbiter::{ArbiterState, MAX_STEPS_SEPARATED};
use crate::body::{BodyHandle, BodyType, Shape};
use crate::error::Error;
use crate::force::{Generator, Targets};
use crate::geometry::circle::MAX_CIRCLE_RADIUS;
use crate::geometry::mass::{MAX_INERTIA, MAX_MASS, MIN_INERTIA, MIN_MASS};
use crate::geometry::{Capsule, Segment};
use crate::limits::{check_damping, check_friction, check_gravity_scale, check_restitution};
use crate::math::scalar::{self, Scalar, ZERO};
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

fn check_props(w: &World<'_>, p: &Props) -> Result<(), Error> {
    match p.shape {
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
            if !w.paths.chains.valid(h) || p.body_type != BodyType::Static {
                return Err(invalid("a body's chain is not in this world"));
            }
        }
    }
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
    // A constant: `lit` in an expression would parse the string at run time,
    // once per body.
    const UNIT_TOLERANCE: Scalar = Scalar::lit("0.000001");
    let q = r.rotation;
    let norm = (q.c * q.c) + (q.s * q.s);
    if (norm - scalar::ONE).abs() > UNIT_TOLERANCE {
        return Err(invalid("rotation is not a unit rotation"));
    }
    // Speeds are not limited here: a game may set any velocity between steps,
    // and the step clamps it (see `World::step`), so the snapshot of such a world
    // must restore.
    Ok(())
}

/// Any target list is valid: a stale or null handle never matches a body, which
/// is also what it does in the world the snapshot came from.
fn check_targets(_: &Targets) -> Result<(), Error> {
    Ok(())
}

/// Everything `apply` relies on, checked without changing the world.
pub(super) fn validate(w: &World<'_>, l: &Layout<'_>) -> Result<(), Error> {
    // `strict_capacity`, like the capacities, belongs to the restoring world,
    // not to the state: it is not encoded. The sub-step count is state (a game
    // changes it with `set_substeps`): it comes back with the snapshot, checked
    // as `World::new` checks it. Compare the rest.
    let def = crate::WorldDef { strict_capacity: w.def.strict_capacity, ..l.def };
    if (crate::WorldDef { substeps: w.def.substeps, ..def }) != w.def {
        return Err(Error::SnapshotMismatch { what: "world definition" });
    }
    def.validate().map_err(|_| invalid("sub-steps out of range"))?;
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
        // Every body has one shape, index 0.
        if a.shape_a() != 0 || a.shape_b() != 0 {
            return Err(invalid("an arbiter names a shape its body does not have"));
        }
        if !live_body(l, a.a)? || !live_body(l, a.b)? {
            return Err(invalid("an arbiter names a body that is not in the snapshot"));
        }
        let state =
            ArbiterState::from_u8(a.state & !TOUCHING).ok_or_else(|| invalid("unknown arbiter state"))?;
        let touching_ok = a.state & TOUCHING == 0 || state == ArbiterState::Contact;
        if !matches!(state, ArbiterState::Contact | ArbiterState::Ignoring | ArbiterState::Separated)
            || a.count > 2
            || !touching_ok
        {
            return Err(invalid("an arbiter in a state that does not persist"));
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

/// True when `h` names a live body of the snapshot (same slot and generation).
fn live_body(l: &Layout<'_>, h: BodyHandle) -> Result<bool, Error> {
    if h.index() >= l.bodies.used {
        return Ok(false);
    }
    let r = l.body(h.index())?;
    Ok(r.live() && r.generation == h.generation())
}
