//! Writing the canonical encoding (see the module docs for the layout).

use super::hash::Hash64;
use super::{
    Part, Sink, ARBITER_LINKS, ARBITER_MANIFOLDS, ARBITER_RECORD, BODY_RECORD, BULLET, CACHED,
    COMPOUND_RECORD, FIXED_ROTATION, HEADER, JOINT_RECORD, LINK_MASK, LIVE, MAGIC, MANIFOLD_RECORD, NO_LINK,
    OUT_OF_BOUNDS, PROPS_RECORD, SENSOR, SHAPES, SHAPES_SHIFT, SHAPE_RECORD, TOUCHING, TRAILER, VERSION,
};
use crate::arbiter::Arbiter;
use crate::arena::NO_SLOT;
use crate::body::{Body, BodyType, CollisionFilter, Shape};
use crate::compound::{is_compound, BodyShape};
use crate::constraint::{Joint, JointKind, MaxTorque};
use crate::force::{Generator, Targets, MAX_TARGETS};
use crate::geometry::PolygonPath;
use crate::math::Scalar;
use crate::world::{World, WorldDef};

/// The properties of a body that the table holds (everything but its motion).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Props {
    pub(super) shape: Shape,
    pub(super) body_type: BodyType,
    pub(super) mass: Scalar,
    pub(super) inertia: Scalar,
    pub(super) friction: Scalar,
    pub(super) restitution: Scalar,
    pub(super) groups: u32,
    pub(super) level: u32,
    pub(super) user_data: u64,
    pub(super) bullet: bool,
    pub(super) fixed_rotation: bool,
    pub(super) linear_damping: Scalar,
    pub(super) angular_damping: Scalar,
    pub(super) gravity_scale: Scalar,
    pub(super) filter: CollisionFilter,
    pub(super) sensor: bool,
}

impl Props {
    pub(super) fn of(b: &Body) -> Self {
        Self {
            shape: b.shape,
            body_type: b.body_type,
            mass: b.mass.mass,
            inertia: b.mass.inertia,
            friction: b.friction,
            restitution: b.restitution,
            groups: b.collision_groups,
            level: b.collision_level,
            user_data: b.user_data,
            bullet: b.bullet,
            fixed_rotation: b.fixed_rotation,
            linear_damping: b.linear_damping,
            angular_damping: b.angular_damping,
            gravity_scale: b.gravity_scale,
            filter: b.filter,
            sensor: b.sensor,
        }
    }
}

/// Bytes of the world part: step count, settings (96 bytes), paths checksum.
const WORLD_BYTES: usize = 8 + 96 + 8;
/// Bytes of an allocator state (slots used, free head, live count).
const ALLOC_BYTES: usize = 12;
/// Bytes of a generator slot holding the largest generator: generation, link,
/// kind, point and acceleration, then a target list of `MAX_TARGETS` handles.
const MAX_GENERATOR_BYTES: usize = 9 + 24 + 2 + 8 * MAX_TARGETS;

/// What must be known before the first byte is written: the length (in the
/// header) and the number of property records.
pub(super) struct Plan {
    /// Total bytes, trailer included.
    pub(super) len: usize,
    /// Entries of the properties table.
    props: u32,
    /// Compound bodies (the shapes section is written when the shape
    /// store has used a slot).
    compounds: u32,
}

impl Plan {
    /// Counts; encodes nothing. Must agree with [`fn@write`] byte for byte (a test
    /// compares it with a counting sink).
    pub(super) fn of(w: &World<'_>) -> Self {
        let (mut props, mut compounds) = (0u32, 0u32);
        let mut last: Option<Props> = None;
        for (_, b) in w.bodies.iter() {
            let p = Props::of(b);
            if last != Some(p) {
                props = props.saturating_add(1);
                last = Some(p);
            }
            compounds = compounds.saturating_add(u32::from(is_compound(b)));
        }
        let generators = (0..w.generators.allocator_state().0)
            .map(|i| generator_bytes(w.generators.get_at(i)))
            .fold(0usize, usize::saturating_add);
        let links = if has_links(w) { w.arbiters.live().len().saturating_mul(4) } else { 0 };
        let manifolds = if w.def.contact_recycle_distance != Scalar::ZERO {
            w.arbiters.live().len().saturating_mul(MANIFOLD_RECORD)
        } else {
            0
        };
        let links = links.saturating_add(manifolds);
        let shapes = match w.paths.slots.allocator_state().0 {
            0 => 0,
            used => shapes_len(used as usize, compounds as usize),
        };
        let len = sections_len(
            props as usize,
            w.bodies.allocator_state().0 as usize,
            generators.saturating_add(links).saturating_add(shapes),
            w.arbiters.live().len(),
            w.joints.allocator_state().0 as usize,
        );
        Self { len, props, compounds }
    }
}

/// Bytes of a shapes section of `slots` shape slots and `compounds`
/// compound bodies.
fn shapes_len(slots: usize, compounds: usize) -> usize {
    (ALLOC_BYTES + 4)
        .saturating_add(slots.saturating_mul(SHAPE_RECORD))
        .saturating_add(compounds.saturating_mul(COMPOUND_RECORD))
}

/// Bytes of a snapshot with these counts (`generator_bytes` includes the
/// optional sections: the arbiters' sub-key words and the shapes).
fn sections_len(
    props: usize,
    body_slots: usize,
    generator_bytes: usize,
    arbiters: usize,
    joints: usize,
) -> usize {
    let records = [
        (props, PROPS_RECORD),
        (body_slots, BODY_RECORD),
        (arbiters, ARBITER_RECORD),
        (joints, JOINT_RECORD),
    ];
    records.iter().fold(
        // header, world, props count, 3 allocators, arbiter count, generators, trailer
        HEADER + WORLD_BYTES + 4 + 3 * ALLOC_BYTES + 4 + TRAILER + generator_bytes,
        |acc, &(n, size)| acc.saturating_add(n.saturating_mul(size)),
    )
}

/// The longest snapshot a world with these capacities can write.
pub(super) fn max_len(w: &World<'_>) -> usize {
    let bodies = w.bodies.capacity();
    let shapes = w.paths.slots.capacity();
    // A world with room for chains or compound bodies may write each
    // arbiter's sub-key word too, and one with room for shapes the shapes
    // section (a compound body has at least one shape slot).
    let links =
        if w.paths.chains.capacity() > 0 || shapes > 0 { w.arbiters.capacity().saturating_mul(4) } else { 0 };
    // Any world may recycle manifolds (`set_contact_recycle_distance`).
    let links = links.saturating_add(w.arbiters.capacity().saturating_mul(MANIFOLD_RECORD));
    let shapes = if shapes > 0 { shapes_len(shapes, shapes.min(bodies)) } else { 0 };
    sections_len(
        bodies,
        bodies,
        w.generators
            .capacity()
            .saturating_mul(MAX_GENERATOR_BYTES)
            .saturating_add(links)
            .saturating_add(shapes),
        w.arbiters.capacity(),
        w.joints.capacity(),
    )
}

/// Bytes of one generator slot.
fn generator_bytes(g: Option<&Generator<'_>>) -> usize {
    let targets = |t: &Targets| match t {
        Targets::All => 1,
        Targets::Level(_) => 5,
        Targets::Bodies(v) => 2 + 8 * v.len(),
    };
    9 + match g {
        None | Some(Generator::Custom(_)) => 0,
        Some(Generator::Linear(g)) => 16 + targets(&g.targets),
        Some(Generator::Gravity(g)) => 16 + targets(&g.targets),
        Some(Generator::GravityToPoint(g)) => 24 + targets(&g.targets),
    }
}

/// Writes everything but the trailer (the caller hashes or checksums what was
/// written). `plan` is [`Plan::of`] the same world.
pub(super) fn write(w: &World<'_>, plan: &Plan, s: &mut impl Sink) {
    s.part(Part::Framing);
    s.put(MAGIC);
    s.u32(VERSION);
    s.u64(plan.len as u64);
    s.part(Part::World);
    s.u64(w.step_count);
    write_def(s, &w.def);
    s.u64(paths_checksum(w));

    // The properties table: a new entry whenever a live body's properties differ
    // from the previous live body's.
    s.part(Part::Bodies);
    let with_shapes = w.paths.slots.allocator_state().0 > 0;
    s.u32(plan.props | if with_shapes { SHAPES } else { 0 });
    let mut last: Option<Props> = None;
    for (_, b) in w.bodies.iter() {
        let p = Props::of(b);
        if last != Some(p) {
            let mut rec = Record::<PROPS_RECORD>::default();
            write_props(&mut rec, &p);
            s.put(&rec.bytes);
            last = Some(p);
        }
    }

    // Body slots: generation and free-list link are the allocator's, the rest
    // the body's.
    s.part(Part::Allocators);
    let (used, free_head, len) = w.bodies.allocator_state();
    s.u32(used);
    s.u32(link(free_head));
    s.u32(len);
    let mut index = 0u32;
    last = None;
    for i in 0..used {
        let (generation, next_free) = w.bodies.slot_meta(i).unwrap_or((0, NO_SLOT));
        s.part(Part::Allocators);
        s.u32(generation);
        match w.bodies.get_at(i) {
            Some(b) => {
                s.part(Part::Bodies);
                let p = Props::of(b);
                if last.is_some() && last != Some(p) {
                    index = index.saturating_add(1);
                }
                last = Some(p);
                let flags = if b.out_of_bounds { LIVE | OUT_OF_BOUNDS } else { LIVE };
                // The record after its generation.
                let mut rec = Record::<{ BODY_RECORD - 4 }>::default();
                rec.u32(flags | (index & LINK_MASK));
                rec.vector(b.position);
                rec.rot(b.rotation);
                rec.vector(b.linear_velocity);
                rec.scalar(b.angular_velocity);
                s.put(&rec.bytes);
            }
            None => {
                s.u32(link(next_free));
                s.zeros(56);
            }
        }
    }
    if with_shapes {
        write_shapes(w, plan, s);
    }

    s.part(Part::Allocators);
    let (used, free_head, len) = w.generators.allocator_state();
    s.u32(used);
    s.u32(link(free_head));
    s.u32(len);
    for i in 0..used {
        let (generation, next_free) = w.generators.slot_meta(i).unwrap_or((0, NO_SLOT));
        s.part(Part::Allocators);
        s.u32(generation);
        s.u32(link(next_free));
        s.part(Part::Generators);
        match w.generators.get_at(i) {
            None => s.u8(0),
            Some(Generator::Linear(g)) => {
                s.u8(1);
                s.vector(g.force);
                write_targets(s, &g.targets);
            }
            Some(Generator::Gravity(g)) => {
                s.u8(2);
                s.vector(g.gravity);
                write_targets(s, &g.targets);
            }
            Some(Generator::GravityToPoint(g)) => {
                s.u8(3);
                s.vector(g.point);
                s.scalar(g.acceleration);
                write_targets(s, &g.targets);
            }
            Some(Generator::Custom(_)) => s.u8(4),
        }
    }

    s.part(Part::Contacts);
    let live = w.arbiters.live();
    let links = has_links(w);
    let recycles = w.def.contact_recycle_distance != Scalar::ZERO;
    let flags = if links { ARBITER_LINKS } else { 0 } | if recycles { ARBITER_MANIFOLDS } else { 0 };
    s.u32(live.len() as u32 | flags);
    for a in live {
        let mut rec = Record::<ARBITER_RECORD>::default();
        for h in [a.body_a, a.body_b] {
            rec.u32(h.index());
            rec.u32(h.generation());
        }
        let cached = recycles && a.has_manifold() && a.count > 0;
        rec.u8(a.state as u8 | if a.is_touching() { TOUCHING } else { 0 } | if cached { CACHED } else { 0 });
        rec.u32(a.steps_separated());
        rec.u8(a.count);
        for (k, p) in a.points.iter().enumerate() {
            // Unused point slots are written as zeros so equal states encode equally.
            if k < usize::from(a.count) {
                rec.u16(p.id);
                rec.scalar(p.normal_impulse);
                rec.scalar(p.tangent_impulse);
            } else {
                rec.zeros(18);
            }
        }
        s.put(&rec.bytes);
    }
    if links {
        for a in live {
            s.u32(sub_word(a));
        }
    }
    // The manifolds the next step may carry on (see `collision::recycle`).
    if recycles {
        for a in live {
            let mut rec = Record::<MANIFOLD_RECORD>::default();
            if a.has_manifold() && a.count > 0 {
                rec.vector(a.normal);
                rec.rot(a.rot_a0);
                rec.rot(a.rot_b0);
                for p in a.points.iter().take(usize::from(a.count)) {
                    rec.vector(p.anchor_a);
                    rec.vector(p.anchor_b);
                    rec.scalar(p.base_separation);
                }
            }
            s.put(&rec.bytes);
        }
    }

    s.part(Part::Allocators);
    let (used, free_head, len) = w.joints.allocator_state();
    s.u32(used);
    s.u32(link(free_head));
    s.u32(len);
    for i in 0..used {
        let (generation, next_free) = w.joints.slot_meta(i).unwrap_or((0, NO_SLOT));
        let mut rec = Record::<JOINT_RECORD>::default();
        rec.u32(generation);
        rec.u32(link(next_free));
        match w.joints.get_at(i) {
            Some(j) => {
                rec.u8(1);
                write_joint(&mut rec, j);
            }
            None => rec.u8(0),
        }
        let (slot, joint) = rec.bytes.split_at(8);
        s.part(Part::Allocators);
        s.put(slot);
        s.part(Part::Joints);
        s.put(joint);
    }
}

/// The shapes section: the shape store's allocator state and slots, then
/// each compound body's slot and first shape slot.
fn write_shapes(w: &World<'_>, plan: &Plan, s: &mut impl Sink) {
    let slots = &w.paths.slots;
    s.part(Part::Allocators);
    let (used, free_head, len) = slots.allocator_state();
    s.u32(used);
    s.u32(link(free_head));
    s.u32(len);
    for i in 0..used {
        let (generation, next_free) = slots.slot_meta(i).unwrap_or((0, NO_SLOT));
        let mut rec = Record::<SHAPE_RECORD>::default();
        rec.u32(generation);
        match slots.get_at(i) {
            Some(slot) => {
                rec.u32(LIVE);
                rec.u32(slot.owner);
                rec.u32(slot.next);
                write_body_shape(&mut rec, &slot.data);
            }
            None => rec.u32(link(next_free)),
        }
        let (meta, shape) = rec.bytes.split_at(8);
        s.part(Part::Allocators);
        s.put(meta);
        s.part(Part::Bodies);
        s.put(shape);
    }
    s.u32(plan.compounds);
    for (h, b) in w.bodies.iter().filter(|(_, b)| is_compound(b)) {
        s.u32(h.index());
        s.u32(b.shapes);
    }
}

fn write_body_shape(s: &mut impl Sink, d: &BodyShape) {
    write_shape(s, d.shape);
    s.vector(d.local.p);
    s.rot(d.local.q);
    s.scalar(d.mass);
    s.scalar(d.inertia);
    s.scalar(d.friction);
    s.scalar(d.restitution);
    write_filter(s, &d.filter);
    s.bool(d.sensor);
}

/// True when an arbiter is for a chain link or a shape other than 0 (the
/// sub-key words are then written after the arbiter records).
fn has_links(w: &World<'_>) -> bool {
    w.arbiters.live().iter().any(|a| sub_word(a) != 0)
}

/// An arbiter's sub-key word as stored (see [`ARBITER_LINKS`]).
fn sub_word(a: &Arbiter) -> u32 {
    a.link() | (a.shape_a() << SHAPES_SHIFT) | (a.shape_b() << (SHAPES_SHIFT + 3))
}

/// A free-list link in the 30-bit form.
fn link(next: u32) -> u32 {
    if next == NO_SLOT {
        NO_LINK
    } else {
        next & LINK_MASK
    }
}

pub(super) fn write_def(s: &mut impl Sink, d: &WorldDef) {
    s.rect(d.bounds);
    s.scalar(d.max_linear_speed);
    s.scalar(d.max_angular_speed);
    s.u32(d.substeps);
    s.scalar(d.contact_hertz);
    s.scalar(d.contact_damping_ratio);
    s.scalar(d.contact_push_speed);
    s.scalar(d.restitution_threshold);
    s.u32(d.arbiter_persistence);
    s.scalar(d.contact_recycle_distance);
}

/// The shape kind and the 24-byte shape field, zero-padded.
#[inline]
fn write_shape(s: &mut impl Sink, shape: Shape) {
    match shape {
        Shape::Circle { radius } => {
            s.u8(0);
            s.scalar(radius);
            s.u64(0);
            s.u64(0);
        }
        Shape::Polygon(h) => {
            s.u8(1);
            s.u32(h.index());
            s.u32(h.generation());
            s.u64(0);
            s.u64(0);
        }
        Shape::Capsule(c) => {
            // Stored centred: the first centre is the second negated.
            s.u8(2);
            s.vector(c.center2());
            s.scalar(c.radius());
        }
        Shape::Segment(sg) => {
            s.u8(3);
            s.vector(sg.point2());
            s.u64(0);
        }
        Shape::Chain(h) => {
            s.u8(4);
            s.u32(h.start);
            s.u32(h.count);
            s.u64(u64::from(h.closed));
            s.u64(0);
        }
    }
}

fn write_filter(s: &mut impl Sink, f: &CollisionFilter) {
    s.u64(f.category_bits);
    s.u64(f.mask_bits);
    s.u32(f.group_index as u32);
}

#[inline]
fn write_props(s: &mut impl Sink, p: &Props) {
    write_shape(s, p.shape);
    let fixed = if p.fixed_rotation { FIXED_ROTATION } else { 0 };
    let sensor = if p.sensor { SENSOR } else { 0 };
    s.u8(p.body_type as u8 | if p.bullet { BULLET } else { 0 } | sensor | fixed);
    s.scalar(p.mass);
    s.scalar(p.inertia);
    s.scalar(p.friction);
    s.scalar(p.restitution);
    s.u32(p.groups);
    s.u32(p.level);
    s.u64(p.user_data);
    s.scalar(p.linear_damping);
    s.scalar(p.angular_damping);
    s.scalar(p.gravity_scale);
    write_filter(s, &p.filter);
}

fn write_targets(s: &mut impl Sink, t: &Targets) {
    match t {
        Targets::All => s.u8(0),
        Targets::Level(l) => {
            s.u8(1);
            s.u32(*l);
        }
        Targets::Bodies(v) => {
            s.u8(2);
            s.u8(v.len() as u8);
            for h in v {
                s.u32(h.index());
                s.u32(h.generation());
            }
        }
    }
}

/// A fixed-size record of `N` bytes being assembled (zero-padded), then
/// handed to the sink in one piece: its fields land at constant offsets of a
/// local array (no bounds checks once inlined), and the sink sees one call
/// per record instead of one per field. Joints (`JOINT_RECORD`), and the
/// bodies, properties and arbiters, whose records are always full.
struct Record<const N: usize> {
    bytes: [u8; N],
    pos: usize,
}

impl<const N: usize> Default for Record<N> {
    #[inline]
    fn default() -> Self {
        Self { bytes: [0; N], pos: 0 }
    }
}

impl<const N: usize> Sink for Record<N> {
    #[inline]
    fn put(&mut self, b: &[u8]) {
        let end = self.pos.saturating_add(b.len());
        if let Some(dst) = self.bytes.get_mut(self.pos..end) {
            dst.copy_from_slice(b);
        }
        self.pos = end;
    }
}

fn write_joint(s: &mut impl Sink, j: &Joint) {
    let d = &j.def;
    s.u32(d.body_a.index());
    s.u32(d.body_a.generation());
    match d.body_b {
        Some(b) => {
            s.u8(1);
            s.u32(b.index());
            s.u32(b.generation());
        }
        None => {
            s.u8(0);
            s.zeros(8);
        }
    }
    s.vector(d.anchor_a);
    s.vector(d.anchor_b);
    s.bool(d.collide_connected);
    match d.break_impulse {
        Some(x) => {
            s.u8(1);
            s.scalar(x);
        }
        None => {
            s.u8(0);
            s.zeros(8);
        }
    }
    s.rot(j.reference);
    s.vector(j.impulse);
    s.scalar(j.angular_impulse);
    s.scalar(j.motor_impulse);
    s.scalar(j.limit_impulse);
    match d.kind {
        JointKind::Spring { stiffness, rest_length } => {
            s.u8(0);
            s.scalar(stiffness);
            s.scalar(rest_length);
        }
        JointKind::DampedSpring { stiffness, damping, rest_length } => {
            s.u8(1);
            s.scalar(stiffness);
            s.scalar(damping);
            s.scalar(rest_length);
        }
        JointKind::Rod { length } => {
            s.u8(2);
            s.scalar(length);
        }
        JointKind::Rope { max_length } => {
            s.u8(3);
            s.scalar(max_length);
        }
        JointKind::Pivot { limits, motor } => {
            s.u8(4);
            let (lo, hi) = limits.unwrap_or((Scalar::ZERO, Scalar::ZERO));
            s.bool(limits.is_some());
            s.scalar(lo);
            s.scalar(hi);
            s.bool(motor.is_some());
            let (speed, torque) = motor.map_or((Scalar::ZERO, None), |m| match m.max_torque {
                MaxTorque::Limited(t) => (m.speed, Some(t)),
                MaxTorque::Unlimited => (m.speed, None),
            });
            s.scalar(speed);
            s.bool(torque.is_none());
            s.scalar(torque.unwrap_or(Scalar::ZERO));
        }
        JointKind::Weld => s.u8(5),
        JointKind::Target { hertz, damping_ratio, max_force } => {
            s.u8(6);
            s.scalar(hertz);
            s.scalar(damping_ratio);
            s.scalar(max_force);
        }
    }
}

/// XXH64 over the polygon paths (allocator state and every path's data), which
/// the snapshot carries instead of the paths themselves.
pub(super) fn paths_checksum(w: &World<'_>) -> u64 {
    let mut h = Hash64::new();
    let (used, free_head, len) = w.paths.allocator_state();
    h.u32(used);
    h.u32(free_head);
    h.u32(len);
    for i in 0..used {
        let (generation, next_free) = w.paths.slot_meta(i).unwrap_or((0, NO_SLOT));
        h.u32(generation);
        h.u32(next_free);
        match w.paths.get_at(i) {
            Some(p) => {
                h.u8(1);
                write_path(&mut h, p);
            }
            None => h.u8(0),
        }
    }
    // The chains' points, when there are any (a world without chains keeps
    // the checksum it had before chains existed).
    if w.paths.chains.used() > 0 {
        h.u32(w.paths.chains.used());
        for p in w.paths.chains.points() {
            h.vector(p);
        }
    }
    h.finish()
}

fn write_path(s: &mut impl Sink, p: &PolygonPath) {
    s.u32(p.count as u32);
    for v in p.vertices() {
        s.vector(*v);
    }
    for n in p.normals() {
        s.vector(*n);
    }
    s.scalar(p.area);
    s.scalar(p.unit_inertia);
    s.vector(p.centroid);
    s.scalar(p.radius);
    s.scalar(p.rounding);
}
