//! The apply step of a restore: writes a snapshot that `validate` accepted into
//! the world. Arenas are rewritten slot by slot with their generations and free
//! lists, so handles, slot reuse and iteration order come back exactly; derived
//! body data (radius, bounding box, inverse mass) is recomputed from the record
//! (a compound body's radius and box from its shapes, restored first).

use super::layout::{BodyRecord, GeneratorRecord, Layout, StoredGenerator};
use super::write::Props;
use super::{CACHED, NO_LINK, TOUCHING};
use crate::arbiter::{Arbiter, ArbiterState};
use crate::arena::NO_SLOT;
use crate::body::{body_radius, compute_aabb};
use crate::body::{Body, BodyHandle};
use crate::compound::{ShapeSlot, MAX_SHAPES_PER_BODY, NO_SHAPE};
use crate::geometry::MassData;
use crate::math::scalar::{Scalar, ZERO};
use crate::world::World;

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
    w.def.substeps = l.def.substeps;
    w.def.contact_recycle_distance = l.def.contact_recycle_distance;
    // The shape store first: a compound body's radius and box come from it.
    let slots = &mut w.paths.slots;
    match l.shapes {
        Some(section) => {
            for i in 0..section.alloc.used {
                let Ok(r) = l.shape(i) else { continue };
                let next_free = if r.data.is_some() { NO_SLOT } else { slot_link(r.link) };
                let slot = r.data.map(|data| ShapeSlot { owner: r.owner, next: r.next, data });
                slots.write_slot(i, r.generation, next_free, slot, false);
            }
            slots.finish_restore(section.alloc.used, slot_link(section.alloc.free_head), section.alloc.len);
        }
        None => slots.finish_restore(0, NO_SLOT, 0),
    }
    // Bodies, each compound body's list head and count from the list that
    // follows the shape slots (in body-slot order, as the bodies are).
    let mut recips = Recips::new();
    let mut compounds = Compounds { l, next: 0 };
    // A properties record is for a run of consecutive bodies: each is read
    // once for its run.
    let mut props: Option<(u32, Props)> = None;
    for i in 0..l.bodies.used {
        let Ok(r) = l.body(i) else { continue };
        if r.live() {
            let p = match props {
                Some((at, p)) if at == r.index() => p,
                _ => {
                    let Ok(p) = l.props(r.index()) else { continue };
                    props = Some((r.index(), p));
                    p
                }
            };
            let mut body = body_from(&p, &r, &mut recips);
            if let Some((head, count)) = compounds.of(i) {
                body.shapes = head;
                body.shape_count = count;
            }
            body.radius = body_radius(&body, &w.paths);
            body.aabb = compute_aabb(&body, &w.paths);
            w.bodies.write_slot(i, r.generation, NO_SLOT, Some(body), false);
        } else {
            w.bodies.write_slot(i, r.generation, slot_link(r.index()), None, false);
        }
    }
    w.bodies.finish_restore(l.bodies.used, slot_link(l.bodies.free_head), l.bodies.len);
    // Generators (a game's generators stay in their slots).
    for (i, rec) in l.generators().enumerate() {
        let Ok(GeneratorRecord { generation, next, generator: g }) = rec else { continue };
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
            state: ArbiterState::from_u8(a.state & !(TOUCHING | CACHED)).unwrap_or(ArbiterState::Separated),
            count: a.count,
            ..Arbiter::EMPTY
        };
        arb.set_touching(a.state & TOUCHING != 0);
        arb.set_steps_and_link(a.steps_separated, a.link());
        arb.set_shapes(a.shape_a(), a.shape_b());
        for (p, stored) in arb.points.iter_mut().zip(a.points) {
            p.id = stored.id;
            p.normal_impulse = stored.normal_impulse;
            p.tangent_impulse = stored.tangent_impulse;
        }
        if a.state & CACHED != 0 {
            let m = a.manifold;
            arb.normal = m.normal;
            (arb.rot_a0, arb.rot_b0) = (m.rot_a, m.rot_b);
            for (p, cached) in arb.points.iter_mut().zip(m.points) {
                p.anchor_a = cached.anchor_a;
                p.anchor_b = cached.anchor_b;
                p.base_separation = cached.separation;
            }
            arb.set_has_manifold(true);
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

/// The compound bodies' list of a validated snapshot, read in body-slot order.
struct Compounds<'l, 'b> {
    l: &'l Layout<'b>,
    /// The next entry not yet passed.
    next: u32,
}

impl Compounds<'_, '_> {
    /// The first shape slot and the shape count of body slot `body`, when
    /// it is a compound body; `body` must grow from call to call.
    fn of(&mut self, body: u32) -> Option<(u32, u8)> {
        let section = self.l.shapes?;
        while self.next < section.compounds {
            let (b, head) = self.l.compound(self.next).ok()?;
            if b > body {
                return None;
            }
            self.next = self.next.saturating_add(1);
            if b == body {
                let mut count = 0u8;
                let mut at = head;
                while at != NO_SHAPE && usize::from(count) < MAX_SHAPES_PER_BODY {
                    at = self.l.shape(at).map_or(NO_SHAPE, |r| r.next);
                    count = count.saturating_add(1);
                }
                return Some((head, count));
            }
        }
        None
    }
}

/// `x.recip()`, remembered for a few recent values: the bodies of one shape
/// share their mass and inertia, and a division costs as much as dozens of
/// products. A memo of a pure function: the same bits as dividing each time.
struct Recips {
    args: [Scalar; 8],
    recips: [Scalar; 8],
}

impl Recips {
    /// Empty: every entry is 0, whose reciprocal is 0 by `recip`'s convention.
    fn new() -> Self {
        Self { args: [ZERO; 8], recips: [ZERO; 8] }
    }

    fn recip(&mut self, x: Scalar) -> Scalar {
        // Fibonacci hashing of the bits to one of the eight entries.
        let k = ((x.to_bits() as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 61) as usize;
        match (self.args.get_mut(k), self.recips.get_mut(k)) {
            (Some(a), Some(r)) => {
                if *a != x {
                    *a = x;
                    *r = x.recip();
                }
                *r
            }
            _ => x.recip(),
        }
    }
}

fn body_from(p: &Props, r: &BodyRecord, recips: &mut Recips) -> Body {
    let mut b = Body::ground();
    b.position = r.position;
    b.rotation = r.rotation;
    b.linear_velocity = r.linear_velocity;
    b.angular_velocity = r.angular_velocity;
    b.shape = p.shape;
    b.body_type = p.body_type;
    b.mass = MassData {
        mass: p.mass,
        inv_mass: recips.recip(p.mass),
        inertia: p.inertia,
        inv_inertia: recips.recip(p.inertia),
    };
    b.friction = p.friction;
    b.restitution = p.restitution;
    b.collision_groups = p.groups;
    b.collision_level = p.level;
    b.user_data = p.user_data;
    b.bullet = p.bullet;
    b.fixed_rotation = p.fixed_rotation;
    b.linear_damping = p.linear_damping;
    b.angular_damping = p.angular_damping;
    b.gravity_scale = p.gravity_scale;
    b.filter = p.filter;
    b.sensor = p.sensor;
    b.out_of_bounds = r.out_of_bounds();
    b
}
