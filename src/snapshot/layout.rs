//! The record layouts of a snapshot: where each section starts ([`Layout`]) and
//! how each record decodes (`BodyRecord`, `GeneratorRecord`, `ArbiterRecord`
//! with its `PointRecord`s, `JointRecord`, `ShapeRecord`, and the properties
//! as `Props`).
//!
//! [`Layout::parse`] checks the framing and sizes only: the header, the
//! version, the length (which may be shorter than the buffer), the checksum in
//! the trailer over every byte before it — before any other field is read —
//! and that the sections fill the length exactly. Body, property, arbiter,
//! joint and shape records have a fixed size, so record `i` is read on demand at a computed
//! offset, without copying the buffer; generators vary in size and are read in
//! order. Whether the values make sense for a world is `validate`'s job.

use super::cursor::Cursor;
use super::write::Props;
use super::{
    checksum, invalid, ARBITER_LINKS, ARBITER_MANIFOLDS, ARBITER_RECORD, BODY_RECORD, BULLET,
    COMPOUND_RECORD, FIXED_ROTATION, HEADER, JOINT_RECORD, LINK_MASK, LIVE, MAGIC, MANIFOLD_RECORD,
    OUT_OF_BOUNDS, PROPS_RECORD, SENSOR, SHAPES, SHAPES_SHIFT, SHAPE_RECORD, TRAILER, VERSION,
};
use crate::arbiter::{sub_key, MAX_LINK, MAX_SHAPE_INDEX};
use crate::body::{BodyHandle, BodyType, CollisionFilter, Shape};
use crate::compound::BodyShape;
use crate::constraint::{Joint, JointDef, JointKind, MaxTorque, Motor};
use crate::error::Error;
use crate::force::{
    Generator, GravityForceGenerator, GravityToPointForceGenerator, LinearForceGenerator, Targets,
};
use crate::geometry::{Capsule, ChainHandle, Segment};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Transform, Vector2};
use crate::world::{WorldDef, MAX_FORCE_GENERATORS};

/// Allocator state of an arena in a snapshot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Alloc {
    pub(super) used: u32,
    pub(super) free_head: u32,
    pub(super) len: u32,
}

/// Where everything is in a snapshot buffer. Parsing checks the sizes only.
pub(super) struct Layout<'b> {
    /// The snapshot's bytes before its trailer (checksum verified).
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
    /// Where the arbiters' manifold records are, when the world recycles them.
    pub(super) manifolds_at: Option<usize>,
    /// Where the arbiters' chain links are, when any is not 0.
    pub(super) links_at: Option<usize>,
    pub(super) joints: Alloc,
    pub(super) joints_at: usize,
    /// The shapes section, when the properties count flags one ([`SHAPES`]).
    pub(super) shapes: Option<ShapesAt>,
    /// The world tag of the handles read (0 unless [`Layout::for_world`]).
    pub(super) tag: u16,
}

/// Where the shapes section's parts are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ShapesAt {
    /// The shape store's allocator state.
    pub(super) alloc: Alloc,
    /// The first slot record.
    pub(super) slots_at: usize,
    /// Entries of the compound bodies' list.
    pub(super) compounds: u32,
    /// The first entry of that list.
    pub(super) compounds_at: usize,
}

fn read_alloc(c: &mut Cursor<'_>) -> Result<Alloc, Error> {
    Ok(Alloc { used: c.u32()?, free_head: c.u32()?, len: c.u32()? })
}

/// `n` records of `size` bytes must fit in what is left.
fn skip_records(c: &mut Cursor<'_>, n: u32, size: usize) -> Result<(), Error> {
    let total = (n as usize).checked_mul(size).ok_or_else(|| invalid("truncated"))?;
    c.skip(total)
}

fn read_def(c: &mut Cursor<'_>) -> Result<WorldDef, Error> {
    let bounds = c.rect()?;
    let max_linear_speed = c.scalar()?;
    let max_angular_speed = c.scalar()?;
    let substeps = c.u32()?;
    let contact_hertz = c.scalar()?;
    let contact_damping_ratio = c.scalar()?;
    let contact_push_speed = c.scalar()?;
    let restitution_threshold = c.scalar()?;
    let arbiter_persistence = c.u32()?;
    let contact_recycle_distance = c.scalar()?;
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
        contact_recycle_distance,
        // Like the capacities, a property of the world that restores, not of
        // the state: not encoded; `validate` compares the rest.
        strict_capacity: false,
    })
}

/// The bytes of a shape field: a kind and three 8-byte words.
const SHAPE_BYTES: usize = 25;

/// A shape field ([`SHAPE_BYTES`]): the kind (1 byte) and three words,
/// zero-padded (the start of a properties record, and of a shape record's
/// data).
fn read_shape(c: &mut Cursor<'_>) -> Result<Shape, Error> {
    // What each kind does not use must be zero.
    let (shape, used) = match c.u8()? {
        0 => (Shape::Circle { radius: c.scalar()? }, 8),
        1 => (Shape::Polygon(c.handle()?), 8),
        2 => {
            let h = c.vector()?;
            (Shape::Capsule(Capsule { center1: -h, center2: h, radius: c.scalar()? }), 24)
        }
        3 => {
            let h = c.vector()?;
            (Shape::Segment(Segment { point1: -h, point2: h }), 16)
        }
        4 => {
            let (start, count) = (c.u32()?, c.u32()?);
            let closed = match c.u64()? {
                0 => false,
                1 => true,
                _ => return Err(invalid("unknown chain kind")),
            };
            (Shape::Chain(ChainHandle { start, count, closed }), 16)
        }
        _ => return Err(invalid("unknown shape")),
    };
    for _ in used / 8..(SHAPE_BYTES - 1) / 8 {
        if c.u64()? != 0 {
            return Err(invalid("shape padding not zero"));
        }
    }
    Ok(shape)
}

impl<'b> Layout<'b> {
    /// Parses the snapshot at the start of `buf`; bytes after its length are
    /// ignored.
    pub(super) fn parse(buf: &'b [u8]) -> Result<Self, Error> {
        let mut c = Cursor::at(buf, 0);
        if &c.take::<4>()? != MAGIC {
            return Err(invalid("not a snapshot (no ARPS header)"));
        }
        if c.u32()? != VERSION {
            return Err(invalid("another snapshot format version"));
        }
        let len = usize::try_from(c.u64()?).map_err(|_| invalid("truncated"))?;
        if len < HEADER + TRAILER {
            return Err(invalid("length shorter than a snapshot"));
        }
        let whole = buf.get(..len).ok_or_else(|| invalid("truncated"))?;
        let (buf, trailer) = whole.split_at(len - TRAILER);
        let mut sum = [0u8; TRAILER];
        sum.copy_from_slice(trailer);
        if u64::from_le_bytes(sum) != checksum(buf) {
            return Err(invalid("checksum mismatch (corrupted bytes)"));
        }
        let mut c = Cursor::at(buf, HEADER);
        let step_count = c.u64()?;
        let def = read_def(&mut c)?;
        let paths = c.u64()?;
        let props = c.u32()?;
        let (props, with_shapes) = (props & !SHAPES, props & SHAPES != 0);
        let props_at = c.pos();
        skip_records(&mut c, props, PROPS_RECORD)?;
        let bodies = read_alloc(&mut c)?;
        let bodies_at = c.pos();
        skip_records(&mut c, bodies.used, BODY_RECORD)?;
        let shapes = if with_shapes {
            let alloc = read_alloc(&mut c)?;
            let slots_at = c.pos();
            skip_records(&mut c, alloc.used, SHAPE_RECORD)?;
            let compounds = c.u32()?;
            let compounds_at = c.pos();
            skip_records(&mut c, compounds, COMPOUND_RECORD)?;
            Some(ShapesAt { alloc, slots_at, compounds, compounds_at })
        } else {
            None
        };
        let generators = read_alloc(&mut c)?;
        if generators.used as usize > MAX_FORCE_GENERATORS {
            return Err(invalid("more generator slots than any world has"));
        }
        let generators_at = c.pos();
        for _ in 0..generators.used {
            read_generator(&mut c)?;
        }
        let arbiters = c.u32()?;
        let (with_links, with_manifolds) = (arbiters & ARBITER_LINKS != 0, arbiters & ARBITER_MANIFOLDS != 0);
        let arbiters = arbiters & !(ARBITER_LINKS | ARBITER_MANIFOLDS);
        if with_manifolds != (def.contact_recycle_distance != ZERO) {
            return Err(invalid(
                "manifold records where the world does not recycle them, or none where it does",
            ));
        }
        let arbiters_at = c.pos();
        skip_records(&mut c, arbiters, ARBITER_RECORD)?;
        let links_at = with_links.then(|| c.pos());
        if with_links {
            skip_records(&mut c, arbiters, 4)?;
        }
        let manifolds_at = with_manifolds.then(|| c.pos());
        if with_manifolds {
            skip_records(&mut c, arbiters, MANIFOLD_RECORD)?;
        }
        let joints = read_alloc(&mut c)?;
        let joints_at = c.pos();
        skip_records(&mut c, joints.used, JOINT_RECORD)?;
        if c.pos() != buf.len() {
            return Err(invalid("the sections do not fill the length in the header"));
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
            links_at,
            manifolds_at,
            joints,
            joints_at,
            shapes,
            tag: 0,
        })
    }

    /// The same layout, reading handles as the world with tag `tag` issues
    /// them (a restore reads with its own world's tag).
    pub(super) fn for_world(self, tag: u16) -> Self {
        Self { tag, ..self }
    }

    /// A cursor over record `i` of `N` bytes from offset `at`: over exactly
    /// its bytes, so that the record's reads, at fixed offsets of a slice of
    /// known length, need no bounds checks once inlined; "truncated" when it
    /// is not all in the buffer (`parse` checked that every record is).
    // A missing record fails here, not at its first read as it did when the
    // cursor was over no bytes: only then is the length the reads see a
    // constant. With `props`, `body` and `arbiter` inlined, a restore of the
    // rollback bench's 503 bodies and 974 arbiters went 180 → 139 µs (the
    // records' `Result`s were copied out of line).
    #[inline]
    fn record<const N: usize>(&self, at: usize, i: u32) -> Result<Cursor<'b>, Error> {
        let start = at.saturating_add((i as usize).saturating_mul(N));
        let bytes =
            self.buf.get(start..).and_then(<[u8]>::first_chunk::<N>).ok_or_else(|| invalid("truncated"))?;
        Ok(Cursor::at(bytes, 0).tagged(self.tag))
    }

    /// Whether properties record `i` is for fixed-rotation bodies: its kind
    /// byte alone, for a check made on every body (parsing the whole record
    /// for it cost the rollback bench's restore about 9 µs of 139).
    #[inline]
    pub(super) fn fixed_rotation(&self, i: u32) -> Result<bool, Error> {
        let mut c = self.record::<PROPS_RECORD>(self.props_at, i)?;
        c.skip(SHAPE_BYTES)?;
        Ok(c.u8()? & FIXED_ROTATION != 0)
    }

    #[inline(always)]
    pub(super) fn props(&self, i: u32) -> Result<Props, Error> {
        let mut c = self.record::<PROPS_RECORD>(self.props_at, i)?;
        let shape = read_shape(&mut c)?;
        let kind = c.u8()?;
        if kind & (BULLET | SENSOR) == BULLET | SENSOR {
            return Err(invalid("a sensor marked bullet"));
        }
        let body_type = match kind & !(BULLET | SENSOR | FIXED_ROTATION) {
            0 => BodyType::Static,
            1 => BodyType::Kinematic,
            2 => BodyType::Dynamic,
            _ => return Err(invalid("unknown body type")),
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
            bullet: kind & BULLET != 0,
            fixed_rotation: kind & FIXED_ROTATION != 0,
            linear_damping: c.scalar()?,
            angular_damping: c.scalar()?,
            gravity_scale: c.scalar()?,
            filter: CollisionFilter {
                category_bits: c.u64()?,
                mask_bits: c.u64()?,
                group_index: c.u32()? as i32,
            },
            sensor: kind & SENSOR != 0,
        })
    }

    #[inline]
    pub(super) fn body(&self, i: u32) -> Result<BodyRecord, Error> {
        let mut c = self.record::<BODY_RECORD>(self.bodies_at, i)?;
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
        GeneratorIter {
            c: Cursor::at(self.buf, self.generators_at).tagged(self.tag),
            left: self.generators.used,
        }
    }

    #[inline(always)]
    pub(super) fn arbiter(&self, i: u32) -> Result<ArbiterRecord, Error> {
        let mut c = self.record::<ARBITER_RECORD>(self.arbiters_at, i)?;
        let a = c.handle()?;
        let b = c.handle()?;
        let state = c.u8()?;
        let steps_separated = c.u32()?;
        let count = c.u8()?;
        let mut points = [PointRecord { id: 0, normal_impulse: ZERO, tangent_impulse: ZERO }; 2];
        for p in &mut points {
            *p = PointRecord { id: c.u16()?, normal_impulse: c.scalar()?, tangent_impulse: c.scalar()? };
        }
        let mut c = match self.manifolds_at {
            Some(at) => self.record::<MANIFOLD_RECORD>(at, i)?,
            None => Cursor::at(&[0; MANIFOLD_RECORD], 0),
        };
        let normal = c.vector()?;
        let (rot_a, rot_b) = (c.rot()?, c.rot()?);
        let mut cached =
            [CachedPoint { anchor_a: Vector2::ZERO, anchor_b: Vector2::ZERO, separation: ZERO }; 2];
        for p in &mut cached {
            *p = CachedPoint { anchor_a: c.vector()?, anchor_b: c.vector()?, separation: c.scalar()? };
        }
        let manifold = CachedManifold { normal, rot_a, rot_b, points: cached };
        let sub = match self.links_at {
            Some(at) => self.record::<4>(at, i)?.u32()?,
            None => 0,
        };
        Ok(ArbiterRecord { a, b, state, steps_separated, count, points, manifold, sub })
    }

    pub(super) fn joint(&self, i: u32) -> Result<JointRecord, Error> {
        let mut c = self.record::<JOINT_RECORD>(self.joints_at, i)?;
        let generation = c.u32()?;
        let next = c.u32()?;
        let joint = if c.bool()? { Some(read_joint(&mut c)?) } else { None };
        Ok(JointRecord { generation, next, joint })
    }

    /// Slot `i` of the shape store (the shapes section must be there).
    pub(super) fn shape(&self, i: u32) -> Result<ShapeRecord, Error> {
        let at = self.shapes.map_or(usize::MAX, |s| s.slots_at);
        let mut c = self.record::<SHAPE_RECORD>(at, i)?;
        let generation = c.u32()?;
        let link = c.u32()?;
        if link & LIVE == 0 {
            if link & !LINK_MASK != 0 || c.take::<{ SHAPE_RECORD - 8 }>()? != [0; SHAPE_RECORD - 8] {
                return Err(invalid("a free shape slot holds data"));
            }
            return Ok(ShapeRecord { generation, link, owner: 0, next: 0, data: None });
        }
        if link != LIVE {
            return Err(invalid("flags on a used shape slot"));
        }
        let owner = c.u32()?;
        let next = c.u32()?;
        let shape = read_shape(&mut c)?;
        let local = Transform::new(c.vector()?, c.rot()?);
        let data = BodyShape {
            shape,
            local,
            mass: c.scalar()?,
            inertia: c.scalar()?,
            friction: c.scalar()?,
            restitution: c.scalar()?,
            filter: CollisionFilter {
                category_bits: c.u64()?,
                mask_bits: c.u64()?,
                group_index: c.u32()? as i32,
            },
            sensor: c.bool()?,
        };
        Ok(ShapeRecord { generation, link, owner, next, data: Some(data) })
    }

    /// Entry `k` of the compound bodies' list: the body's slot and the slot
    /// of its first shape.
    pub(super) fn compound(&self, k: u32) -> Result<(u32, u32), Error> {
        let at = self.shapes.map_or(usize::MAX, |s| s.compounds_at);
        let mut c = self.record::<COMPOUND_RECORD>(at, k)?;
        Ok((c.u32()?, c.u32()?))
    }
}

/// One slot of the shape store as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ShapeRecord {
    pub(super) generation: u32,
    /// [`LIVE`] for a used slot; else the free-list successor.
    pub(super) link: u32,
    /// The owner's body slot (a used slot only).
    pub(super) owner: u32,
    /// The body's next shape slot (a used slot only).
    pub(super) next: u32,
    /// The shape (a used slot only).
    pub(super) data: Option<BodyShape>,
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
    pub(super) fn into_generator<'a>(self) -> Option<Generator<'a>> {
        match self {
            Self::Free | Self::Custom => None,
            Self::Linear(g) => Some(Generator::Linear(g)),
            Self::Gravity(g) => Some(Generator::Gravity(g)),
            Self::GravityToPoint(g) => Some(Generator::GravityToPoint(g)),
        }
    }

    pub(super) fn targets(&self) -> Option<&Targets> {
        match self {
            Self::Free | Self::Custom => None,
            Self::Linear(g) => Some(&g.targets),
            Self::Gravity(g) => Some(&g.targets),
            Self::GravityToPoint(g) => Some(&g.targets),
        }
    }
}

/// One generator slot as stored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct GeneratorRecord {
    pub(super) generation: u32,
    /// The free-list successor (a free slot only).
    pub(super) next: u32,
    pub(super) generator: StoredGenerator,
}

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
                let h = c.handle()?;
                v.push(h).map_err(|_| invalid("too many generator targets"))?;
            }
            Targets::Bodies(v)
        }
        _ => return Err(invalid("unknown generator targets")),
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
        _ => return Err(invalid("unknown generator kind")),
    };
    Ok(GeneratorRecord { generation, next, generator: g })
}

/// One arbiter as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ArbiterRecord {
    pub(super) a: BodyHandle,
    pub(super) b: BodyHandle,
    pub(super) state: u8,
    pub(super) steps_separated: u32,
    pub(super) count: u8,
    pub(super) points: [PointRecord; 2],
    /// The cached manifold (all zeros without the [`CACHED`](super::CACHED) flag).
    pub(super) manifold: CachedManifold,
    /// The sub-key word (see [`ARBITER_LINKS`]): the chain link and the
    /// shape indices (0 when the pair has no section).
    pub(super) sub: u32,
}

/// An arbiter's cached manifold as stored (see `collision::recycle`): the
/// normal, both bodies' rotations when it was computed and its points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CachedManifold {
    pub(super) normal: Vector2,
    pub(super) rot_a: Rot,
    pub(super) rot_b: Rot,
    pub(super) points: [CachedPoint; 2],
}

/// A cached manifold point: its offsets from body A's and body B's centres
/// and its separation when the manifold was computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CachedPoint {
    pub(super) anchor_a: Vector2,
    pub(super) anchor_b: Vector2,
    pub(super) separation: Scalar,
}

/// One contact point of an arbiter as stored: its feature id and its
/// accumulated (warm-start) impulses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PointRecord {
    pub(super) id: u16,
    pub(super) normal_impulse: Scalar,
    pub(super) tangent_impulse: Scalar,
}

impl ArbiterRecord {
    /// The key [`Arbiter::key`](crate::arbiter::Arbiter) gives the arbiter.
    pub(super) fn key(&self) -> (u32, u32, u32) {
        let (a, b) = (self.a.index(), self.b.index());
        let (lo, hi) =
            if a <= b { (self.shape_a(), self.shape_b()) } else { (self.shape_b(), self.shape_a()) };
        (a.min(b), a.max(b), sub_key(self.link(), lo, hi))
    }

    /// The chain link: the sub-key word's bits 0–19.
    pub(super) fn link(&self) -> u32 {
        self.sub & MAX_LINK
    }

    /// The shape index on body A.
    pub(super) fn shape_a(&self) -> u32 {
        (self.sub >> SHAPES_SHIFT) & MAX_SHAPE_INDEX
    }

    /// The shape index on body B.
    pub(super) fn shape_b(&self) -> u32 {
        (self.sub >> (SHAPES_SHIFT + 3)) & MAX_SHAPE_INDEX
    }

    /// True when the sub-key word's unused bits (20–25) are 0.
    pub(super) fn sub_is_canonical(&self) -> bool {
        self.sub & !(MAX_LINK | (u32::MAX << SHAPES_SHIFT)) == 0
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
    let body_a = c.handle()?;
    let has_b = c.bool()?;
    let hb: BodyHandle = c.handle()?;
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
        6 => JointKind::Target { hertz: c.scalar()?, damping_ratio: c.scalar()?, max_force: c.scalar()? },
        _ => return Err(invalid("unknown joint kind")),
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
