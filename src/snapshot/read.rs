//! Reading a snapshot: the layout (sections and their offsets), record decoding,
//! validation against a world, and applying it.

use super::write::{paths_checksum, Props};
use super::{
    ARBITER_RECORD, BODY_RECORD, JOINT_RECORD, LINK_MASK, LIVE, MAGIC, NO_LINK, OUT_OF_BOUNDS, PROPS_RECORD,
    TRAILER, VERSION,
};
use crate::arbiter::{Arbiter, ArbiterState};
use crate::arena::NO_SLOT;
use crate::body::compute_aabb;
use crate::body::{Body, BodyHandle, BodyType, Shape};
use crate::constraint::{Joint, JointDef, JointKind, MaxTorque, Motor};
use crate::error::Error;
use crate::force::{
    Generator, GravityForceGenerator, GravityToPointForceGenerator, LinearForceGenerator, Targets,
};
use crate::geometry::circle::MAX_CIRCLE_RADIUS;
use crate::geometry::mass::{MAX_INERTIA, MAX_MASS, MIN_INERTIA, MIN_MASS};
use crate::geometry::MassData;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rect, Rot, Vector2};
use crate::world::{World, WorldDef, MAX_COORDINATE, MAX_FORCE_GENERATORS, MAX_FRICTION};

fn bad(what: &'static str) -> Error {
    Error::InvalidSnapshot { what }
}

/// A bounds-checked little-endian reader.
#[derive(Clone, Copy)]
pub(super) struct Cursor<'b> {
    buf: &'b [u8],
    pos: usize,
}

impl<'b> Cursor<'b> {
    pub(super) fn at(buf: &'b [u8], pos: usize) -> Self {
        Self { buf, pos }
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], Error> {
        let end = self.pos.checked_add(N).ok_or_else(|| bad("truncated"))?;
        let bytes = self.buf.get(self.pos..end).ok_or_else(|| bad("truncated"))?;
        self.pos = end;
        let mut out = [0u8; N];
        out.copy_from_slice(bytes);
        Ok(out)
    }

    pub(super) fn u8(&mut self) -> Result<u8, Error> {
        Ok(self.take::<1>()?[0])
    }
    pub(super) fn u16(&mut self) -> Result<u16, Error> {
        Ok(u16::from_le_bytes(self.take()?))
    }
    pub(super) fn u32(&mut self) -> Result<u32, Error> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    pub(super) fn u64(&mut self) -> Result<u64, Error> {
        Ok(u64::from_le_bytes(self.take()?))
    }
    pub(super) fn bool(&mut self) -> Result<bool, Error> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(bad("a flag is neither 0 nor 1")),
        }
    }
    pub(super) fn scalar(&mut self) -> Result<Scalar, Error> {
        Ok(Scalar::from_bits(i64::from_le_bytes(self.take()?)))
    }
    pub(super) fn vector(&mut self) -> Result<Vector2, Error> {
        Ok(Vector2::new(self.scalar()?, self.scalar()?))
    }
    pub(super) fn rot(&mut self) -> Result<Rot, Error> {
        Ok(Rot { c: self.scalar()?, s: self.scalar()? })
    }
    fn rect(&mut self) -> Result<Rect, Error> {
        Ok(Rect { min: self.vector()?, max: self.vector()? })
    }
    fn skip(&mut self, n: usize) -> Result<(), Error> {
        let end = self.pos.checked_add(n).ok_or_else(|| bad("truncated"))?;
        if end > self.buf.len() {
            return Err(bad("truncated"));
        }
        self.pos = end;
        Ok(())
    }
}

/// Allocator state of an arena in a snapshot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Alloc {
    pub(super) used: u32,
    pub(super) free_head: u32,
    pub(super) len: u32,
}

/// Where everything is in a snapshot buffer. Parsing checks the sizes only.
pub(super) struct Layout<'b> {
    pub(super) buf: &'b [u8],
    pub(super) step_count: u64,
    pub(super) def: WorldDef,
    pub(super) paths: u64,
    pub(super) props_at: usize,
    pub(super) props: u32,
    pub(super) bodies: Alloc,
    pub(super) bodies_at: usize,
    pub(super) generators: Alloc,
    pub(super) generators_at: usize,
    pub(super) arbiters: u32,
    pub(super) arbiters_at: usize,
    pub(super) joints: Alloc,
    pub(super) joints_at: usize,
}

fn read_alloc(c: &mut Cursor<'_>) -> Result<Alloc, Error> {
    Ok(Alloc { used: c.u32()?, free_head: c.u32()?, len: c.u32()? })
}

/// `n` records of `size` bytes must fit in what is left.
fn skip_records(c: &mut Cursor<'_>, n: u32, size: usize) -> Result<(), Error> {
    let total = (n as usize).checked_mul(size).ok_or_else(|| bad("truncated"))?;
    c.skip(total)
}

pub(super) fn read_def(c: &mut Cursor<'_>) -> Result<WorldDef, Error> {
    let bounds = c.rect()?;
    let max_linear_speed = c.scalar()?;
    let max_angular_speed = c.scalar()?;
    let substeps = c.u32()?;
    let contact_hertz = c.scalar()?;
    let contact_damping_ratio = c.scalar()?;
    let contact_push_speed = c.scalar()?;
    let restitution_threshold = c.scalar()?;
    let arbiter_persistence = c.u32()?;
    Ok(WorldDef {
        bounds,
        max_linear_speed,
        max_angular_speed,
        substeps,
        contact_hertz,
        contact_damping_ratio,
        contact_push_speed,
        restitution_threshold,
        arbiter_persistence,
    })
}

impl<'b> Layout<'b> {
    pub(super) fn parse(buf: &'b [u8]) -> Result<Self, Error> {
        let mut c = Cursor::at(buf, 0);
        if &c.take::<4>()? != MAGIC {
            return Err(bad("not a snapshot (no ARPS header)"));
        }
        if c.u32()? != VERSION {
            return Err(bad("another snapshot format version"));
        }
        let step_count = c.u64()?;
        let def = read_def(&mut c)?;
        let paths = c.u64()?;
        let props = c.u32()?;
        let props_at = c.pos;
        skip_records(&mut c, props, PROPS_RECORD)?;
        let bodies = read_alloc(&mut c)?;
        let bodies_at = c.pos;
        skip_records(&mut c, bodies.used, BODY_RECORD)?;
        let generators = read_alloc(&mut c)?;
        if generators.used as usize > MAX_FORCE_GENERATORS {
            return Err(bad("more generator slots than any world has"));
        }
        let generators_at = c.pos;
        for _ in 0..generators.used {
            read_generator(&mut c)?;
        }
        let arbiters = c.u32()?;
        let arbiters_at = c.pos;
        skip_records(&mut c, arbiters, ARBITER_RECORD)?;
        let joints = read_alloc(&mut c)?;
        let joints_at = c.pos;
        skip_records(&mut c, joints.used, JOINT_RECORD)?;
        if &c.take::<4>()? != TRAILER {
            return Err(bad("no ARPE trailer"));
        }
        if c.pos != buf.len() {
            return Err(bad("bytes after the trailer"));
        }
        Ok(Self {
            buf,
            step_count,
            def,
            paths,
            props_at,
            props,
            bodies,
            bodies_at,
            generators,
            generators_at,
            arbiters,
            arbiters_at,
            joints,
            joints_at,
        })
    }

    fn record(&self, at: usize, i: u32, size: usize) -> Cursor<'b> {
        Cursor::at(self.buf, at.saturating_add((i as usize).saturating_mul(size)))
    }

    pub(super) fn props(&self, i: u32) -> Result<Props, Error> {
        let mut c = self.record(self.props_at, i, PROPS_RECORD);
        let shape = match c.u8()? {
            0 => Shape::Circle { radius: c.scalar()? },
            1 => Shape::Polygon(crate::body::PathHandle::from_parts(c.u32()?, c.u32()?)),
            _ => return Err(bad("unknown shape")),
        };
        let body_type = match c.u8()? {
            0 => BodyType::Static,
            1 => BodyType::Kinematic,
            2 => BodyType::Dynamic,
            _ => return Err(bad("unknown body type")),
        };
        Ok(Props {
            shape,
            body_type,
            mass: c.scalar()?,
            inertia: c.scalar()?,
            friction: c.scalar()?,
            restitution: c.scalar()?,
            groups: c.u32()?,
            level: c.u32()?,
            user_data: c.u64()?,
        })
    }

    pub(super) fn body(&self, i: u32) -> Result<BodyRecord, Error> {
        let mut c = self.record(self.bodies_at, i, BODY_RECORD);
        let generation = c.u32()?;
        let link = c.u32()?;
        Ok(BodyRecord {
            generation,
            link,
            position: c.vector()?,
            rotation: c.rot()?,
            linear_velocity: c.vector()?,
            angular_velocity: c.scalar()?,
        })
    }

    pub(super) fn generators(&self) -> GeneratorIter<'b> {
        GeneratorIter { c: Cursor::at(self.buf, self.generators_at), left: self.generators.used }
    }

    pub(super) fn arbiter(&self, i: u32) -> Result<ArbiterRecord, Error> {
        let mut c = self.record(self.arbiters_at, i, ARBITER_RECORD);
        let a = BodyHandle::from_parts(c.u32()?, c.u32()?);
        let b = BodyHandle::from_parts(c.u32()?, c.u32()?);
        let state = c.u8()?;
        let steps_separated = c.u32()?;
        let count = c.u8()?;
        let mut points = [(0u16, ZERO, ZERO); 2];
        for p in &mut points {
            *p = (c.u16()?, c.scalar()?, c.scalar()?);
        }
        Ok(ArbiterRecord { a, b, state, steps_separated, count, points })
    }

    pub(super) fn joint(&self, i: u32) -> Result<JointRecord, Error> {
        let mut c = self.record(self.joints_at, i, JOINT_RECORD);
        let generation = c.u32()?;
        let next = c.u32()?;
        let joint = if c.bool()? { Some(read_joint(&mut c)?) } else { None };
        Ok(JointRecord { generation, next, joint })
    }
}

/// One body slot as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct BodyRecord {
    pub(super) generation: u32,
    pub(super) link: u32,
    pub(super) position: Vector2,
    pub(super) rotation: Rot,
    pub(super) linear_velocity: Vector2,
    pub(super) angular_velocity: Scalar,
}

impl BodyRecord {
    pub(super) fn live(&self) -> bool {
        self.link & LIVE != 0
    }
    pub(super) fn out_of_bounds(&self) -> bool {
        self.link & OUT_OF_BOUNDS != 0
    }
    pub(super) fn index(&self) -> u32 {
        self.link & LINK_MASK
    }
}

/// A generator as stored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) enum StoredGenerator {
    /// A free slot.
    Free,
    /// A game's generator (not stored; must be in the world's slot).
    Custom,
    /// A built-in generator.
    Linear(LinearForceGenerator),
    /// A built-in generator.
    Gravity(GravityForceGenerator),
    /// A built-in generator.
    GravityToPoint(GravityToPointForceGenerator),
}

impl StoredGenerator {
    fn into_generator<'a>(self) -> Option<Generator<'a>> {
        match self {
            Self::Free | Self::Custom => None,
            Self::Linear(g) => Some(Generator::Linear(g)),
            Self::Gravity(g) => Some(Generator::Gravity(g)),
            Self::GravityToPoint(g) => Some(Generator::GravityToPoint(g)),
        }
    }

    fn targets(&self) -> Option<&Targets> {
        match self {
            Self::Free | Self::Custom => None,
            Self::Linear(g) => Some(&g.targets),
            Self::Gravity(g) => Some(&g.targets),
            Self::GravityToPoint(g) => Some(&g.targets),
        }
    }
}

/// One generator slot as stored: generation, free-list link, content.
pub(super) type GeneratorRecord = (u32, u32, StoredGenerator);

pub(super) struct GeneratorIter<'b> {
    c: Cursor<'b>,
    left: u32,
}

impl Iterator for GeneratorIter<'_> {
    type Item = Result<GeneratorRecord, Error>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.left == 0 {
            return None;
        }
        self.left = self.left.saturating_sub(1);
        Some(read_generator(&mut self.c))
    }
}

fn read_targets(c: &mut Cursor<'_>) -> Result<Targets, Error> {
    Ok(match c.u8()? {
        0 => Targets::All,
        1 => Targets::Level(c.u32()?),
        2 => {
            let n = c.u8()?;
            let mut v = heapless::Vec::new();
            for _ in 0..n {
                let h = BodyHandle::from_parts(c.u32()?, c.u32()?);
                v.push(h).map_err(|_| bad("too many generator targets"))?;
            }
            Targets::Bodies(v)
        }
        _ => return Err(bad("unknown generator targets")),
    })
}

fn read_generator(c: &mut Cursor<'_>) -> Result<GeneratorRecord, Error> {
    let generation = c.u32()?;
    let next = c.u32()?;
    let g = match c.u8()? {
        0 => StoredGenerator::Free,
        1 => StoredGenerator::Linear(LinearForceGenerator { force: c.vector()?, targets: read_targets(c)? }),
        2 => StoredGenerator::Gravity(GravityForceGenerator {
            gravity: c.vector()?,
            targets: read_targets(c)?,
        }),
        3 => StoredGenerator::GravityToPoint(GravityToPointForceGenerator {
            point: c.vector()?,
            acceleration: c.scalar()?,
            targets: read_targets(c)?,
        }),
        4 => StoredGenerator::Custom,
        _ => return Err(bad("unknown generator kind")),
    };
    Ok((generation, next, g))
}

/// One arbiter as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ArbiterRecord {
    pub(super) a: BodyHandle,
    pub(super) b: BodyHandle,
    pub(super) state: u8,
    pub(super) steps_separated: u32,
    pub(super) count: u8,
    pub(super) points: [(u16, Scalar, Scalar); 2],
}

impl ArbiterRecord {
    pub(super) fn key(&self) -> (u32, u32) {
        let (a, b) = (self.a.index(), self.b.index());
        (a.min(b), a.max(b))
    }
}

/// One joint slot as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct JointRecord {
    pub(super) generation: u32,
    pub(super) next: u32,
    pub(super) joint: Option<Joint>,
}

fn read_joint(c: &mut Cursor<'_>) -> Result<Joint, Error> {
    let body_a = BodyHandle::from_parts(c.u32()?, c.u32()?);
    let has_b = c.bool()?;
    let hb = BodyHandle::from_parts(c.u32()?, c.u32()?);
    let anchor_a = c.vector()?;
    let anchor_b = c.vector()?;
    let collide_connected = c.bool()?;
    let breakable = c.bool()?;
    let break_value = c.scalar()?;
    let reference = c.rot()?;
    let impulse = c.vector()?;
    let angular_impulse = c.scalar()?;
    let motor_impulse = c.scalar()?;
    let limit_impulse = c.scalar()?;
    let kind = match c.u8()? {
        0 => JointKind::Spring { stiffness: c.scalar()?, rest_length: c.scalar()? },
        1 => {
            JointKind::DampedSpring { stiffness: c.scalar()?, damping: c.scalar()?, rest_length: c.scalar()? }
        }
        2 => JointKind::Rod { length: c.scalar()? },
        3 => JointKind::Rope { max_length: c.scalar()? },
        4 => {
            let has_limits = c.bool()?;
            let (lo, hi) = (c.scalar()?, c.scalar()?);
            let has_motor = c.bool()?;
            let speed = c.scalar()?;
            let unlimited = c.bool()?;
            let torque = c.scalar()?;
            let max_torque = if unlimited { MaxTorque::Unlimited } else { MaxTorque::Limited(torque) };
            JointKind::Pivot {
                limits: has_limits.then_some((lo, hi)),
                motor: has_motor.then_some(Motor { speed, max_torque }),
            }
        }
        5 => JointKind::Weld,
        _ => return Err(bad("unknown joint kind")),
    };
    let def = JointDef {
        body_a,
        anchor_a,
        body_b: has_b.then_some(hb),
        anchor_b,
        kind,
        break_impulse: breakable.then_some(break_value),
        collide_connected,
    };
    let mut j = Joint::restored(def, reference);
    j.impulse = impulse;
    j.angular_impulse = angular_impulse;
    j.motor_impulse = motor_impulse;
    j.limit_impulse = limit_impulse;
    Ok(j)
}

// ---- validation ------------------------------------------------------------

/// Checks a free list: starting at `head`, every link names a free slot below
/// `used`, no slot twice, and it covers exactly `used − len` slots.
fn check_free_list(
    alloc: Alloc,
    mut free_at: impl FnMut(u32) -> Result<Option<u32>, Error>,
) -> Result<(), Error> {
    let expected = alloc.used.checked_sub(alloc.len).ok_or_else(|| bad("more live objects than slots"))?;
    let mut at = alloc.free_head;
    let mut seen = 0u32;
    while at != NO_LINK {
        if at >= alloc.used || seen >= expected {
            return Err(bad("broken free list"));
        }
        at = free_at(at)?.ok_or_else(|| bad("free list through a live slot"))?;
        seen = seen.saturating_add(1);
    }
    if seen != expected {
        return Err(bad("free list misses free slots"));
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
                return Err(bad("circle radius out of range"));
            }
        }
        Shape::Polygon(h) => {
            if w.paths.get(h).is_none() {
                return Err(bad("a body's polygon path is not in this world"));
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
        return Err(bad("mass out of range"));
    }
    if !in_range(p.friction, ZERO, MAX_FRICTION) || !in_range(p.restitution, ZERO, scalar::ONE) {
        return Err(bad("material out of range"));
    }
    Ok(())
}

fn check_motion(r: &BodyRecord) -> Result<(), Error> {
    let far = MAX_COORDINATE + Scalar::from_int(4096);
    let p = r.position;
    if p.x.abs() > far || p.y.abs() > far {
        return Err(bad("position out of range"));
    }
    let q = r.rotation;
    let norm = (q.c * q.c) + (q.s * q.s);
    if (norm - scalar::ONE).abs() > Scalar::lit("0.000001") {
        return Err(bad("rotation is not a unit rotation"));
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
    if l.def != w.def {
        return Err(Error::SnapshotMismatch { what: "world definition" });
    }
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
    let mut live = 0u32;
    for i in 0..l.bodies.used {
        let r = l.body(i)?;
        if r.live() {
            if r.generation == 0 {
                return Err(bad("a live body with generation 0"));
            }
            if r.index() >= l.props {
                return Err(bad("a body's properties index is out of range"));
            }
            check_motion(&r)?;
            live = live.saturating_add(1);
        } else if r.out_of_bounds() {
            return Err(bad("flags on a free slot"));
        }
    }
    if live != l.bodies.len {
        return Err(bad("live body count does not match"));
    }
    check_free_list(l.bodies, |i| {
        let r = l.body(i)?;
        Ok((!r.live()).then(|| r.index()))
    })?;
    // Generators.
    let mut live = 0u32;
    for (i, rec) in l.generators().enumerate() {
        let (generation, _, g) = rec?;
        let world_custom = matches!(w.generators.get_at(i as u32), Some(Generator::Custom(_)));
        if let Some(t) = g.targets() {
            check_targets(t)?;
        }
        if g != StoredGenerator::Free {
            live = live.saturating_add(1);
            if generation == 0 {
                return Err(bad("a live generator with generation 0"));
            }
        }
        let snapshot_custom = g == StoredGenerator::Custom;
        if snapshot_custom != world_custom {
            return Err(Error::SnapshotMismatch { what: "custom force generators are in other slots" });
        }
    }
    if live != l.generators.len {
        return Err(bad("live generator count does not match"));
    }
    check_free_list(l.generators, |i| {
        let (_, next, g) = l.generators().nth(i as usize).ok_or_else(|| bad("truncated"))??;
        Ok((g == StoredGenerator::Free).then_some(next))
    })?;
    // Arbiters: sorted by key, at most two points, a state that persists.
    if l.arbiters as usize > w.arbiters.capacity() {
        return Err(Error::SnapshotMismatch { what: "more arbiters than this world holds" });
    }
    let mut last: Option<(u32, u32)> = None;
    for i in 0..l.arbiters {
        let a = l.arbiter(i)?;
        let key = a.key();
        if a.a.index() == a.b.index() || last.is_some_and(|k| k >= key) {
            return Err(bad("arbiters out of order"));
        }
        last = Some(key);
        if !live_body(l, a.a)? || !live_body(l, a.b)? {
            return Err(bad("an arbiter names a body that is not in the snapshot"));
        }
        let state = ArbiterState::from_u8(a.state).ok_or_else(|| bad("unknown arbiter state"))?;
        if !matches!(state, ArbiterState::Contact | ArbiterState::Ignoring | ArbiterState::Separated)
            || a.count > 2
        {
            return Err(bad("an arbiter in a state that does not persist"));
        }
    }
    // Joints.
    if l.joints.used as usize > w.joints.capacity() || l.joints.used > NO_LINK {
        return Err(Error::SnapshotMismatch { what: "more joints than this world holds" });
    }
    let mut live = 0u32;
    for i in 0..l.joints.used {
        let r = l.joint(i)?;
        if let Some(j) = &r.joint {
            if r.generation == 0 {
                return Err(bad("a live joint with generation 0"));
            }
            crate::constraint::validate_params(&j.def).map_err(|_| bad("joint parameters out of range"))?;
            let b_live = match j.def.body_b {
                Some(b) => live_body(l, b)? && b.index() != j.def.body_a.index(),
                None => true,
            };
            if !live_body(l, j.def.body_a)? || !b_live {
                return Err(bad("a joint names a body that is not in the snapshot"));
            }
            live = live.saturating_add(1);
        }
    }
    if live != l.joints.len {
        return Err(bad("live joint count does not match"));
    }
    check_free_list(l.joints, |i| {
        let r = l.joint(i)?;
        Ok(r.joint.is_none().then_some(r.next))
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

// ---- apply -------------------------------------------------------------------

fn slot_link(link: u32) -> u32 {
    if link == NO_LINK {
        NO_SLOT
    } else {
        link
    }
}

/// Writes a validated snapshot into the world. Cannot fail: every read was
/// checked by `validate` (a failed read here leaves that slot empty).
pub(super) fn apply(w: &mut World<'_>, l: &Layout<'_>) {
    w.step_count = l.step_count;
    // Bodies.
    for i in 0..l.bodies.used {
        let Ok(r) = l.body(i) else { continue };
        if r.live() {
            let Ok(p) = l.props(r.index()) else { continue };
            let mut body = body_from(&p, &r);
            body.radius = match p.shape {
                Shape::Circle { radius } => radius,
                Shape::Polygon(h) => w.paths.get(h).map_or(ZERO, |path| path.radius()),
            };
            body.aabb = compute_aabb(&body, &w.paths);
            w.bodies.write_slot(i, r.generation, NO_SLOT, Some(body), false);
        } else {
            w.bodies.write_slot(i, r.generation, slot_link(r.index()), None, false);
        }
    }
    w.bodies.finish_restore(l.bodies.used, slot_link(l.bodies.free_head), l.bodies.len);
    // Generators (a game's generators stay in their slots).
    for (i, rec) in l.generators().enumerate() {
        let Ok((generation, next, g)) = rec else { continue };
        let i = i as u32;
        match g {
            StoredGenerator::Free => w.generators.write_slot(i, generation, slot_link(next), None, false),
            StoredGenerator::Custom => w.generators.write_slot(i, generation, NO_SLOT, None, true),
            builtin => w.generators.write_slot(i, generation, NO_SLOT, builtin.into_generator(), false),
        }
    }
    w.generators.finish_restore(l.generators.used, slot_link(l.generators.free_head), l.generators.len);
    // Arbiters.
    w.arbiters.clear();
    for i in 0..l.arbiters {
        let Ok(a) = l.arbiter(i) else { continue };
        let level = |h: BodyHandle| w.bodies.get(h).map_or(0, |b| b.collision_level);
        let mut arb = Arbiter {
            body_a: a.a,
            body_b: a.b,
            level_a: level(a.a),
            level_b: level(a.b),
            state: ArbiterState::from_u8(a.state).unwrap_or(ArbiterState::Separated),
            steps_separated: a.steps_separated,
            count: a.count,
            ..Arbiter::EMPTY
        };
        for (p, (id, normal, tangent)) in arb.points.iter_mut().zip(a.points) {
            p.id = id;
            p.normal_impulse = normal;
            p.tangent_impulse = tangent;
        }
        w.arbiters.push(arb);
    }
    // Joints.
    for i in 0..l.joints.used {
        let Ok(r) = l.joint(i) else { continue };
        let next = if r.joint.is_some() { NO_SLOT } else { slot_link(r.next) };
        w.joints.write_slot(i, r.generation, next, r.joint, false);
    }
    w.joints.finish_restore(l.joints.used, slot_link(l.joints.free_head), l.joints.len);
    w.post_step.clear();
}

pub(super) fn body_from(p: &Props, r: &BodyRecord) -> Body {
    let mut b = Body::ground();
    b.position = r.position;
    b.rotation = r.rotation;
    b.linear_velocity = r.linear_velocity;
    b.angular_velocity = r.angular_velocity;
    b.shape = p.shape;
    b.body_type = p.body_type;
    b.mass = MassData {
        mass: p.mass,
        inv_mass: p.mass.recip(),
        inertia: p.inertia,
        inv_inertia: p.inertia.recip(),
    };
    b.friction = p.friction;
    b.restitution = p.restitution;
    b.collision_groups = p.groups;
    b.collision_level = p.level;
    b.user_data = p.user_data;
    b.out_of_bounds = r.out_of_bounds();
    b
}
