//! Canonical encoding of the simulation state and the 64-bit state hash.
//!
//! Every value that shapes future steps is written in one canonical order as
//! little-endian bytes: integers as their LE bytes, `Scalar`s as their raw 64-bit
//! two's-complement bits, booleans as one byte. The encoding never depends on the
//! target's endianness, pointer width, or the world's capacities. The state hash is
//! FNV-1a (64-bit) over exactly these bytes, so two peers whose hashes differ have
//! different states, and equal states always hash equal.

use crate::arbiter::Arbiter;
use crate::arena::{Arena, SlotStorage};
use crate::body::{Body, Shape};
use crate::math::{Rect, Rot, Scalar, Vector2};

/// Receives the canonical byte stream (a hasher, or a snapshot buffer).
pub(crate) trait Sink {
    /// Appends bytes.
    fn put(&mut self, bytes: &[u8]);

    fn u8(&mut self, v: u8) {
        self.put(&[v]);
    }
    fn u32(&mut self, v: u32) {
        self.put(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.put(&v.to_le_bytes());
    }
    fn bool(&mut self, v: bool) {
        self.u8(u8::from(v));
    }
    fn scalar(&mut self, v: Scalar) {
        self.put(&v.to_bits().to_le_bytes());
    }
    fn vector(&mut self, v: Vector2) {
        self.scalar(v.x);
        self.scalar(v.y);
    }
    fn rot(&mut self, q: Rot) {
        self.scalar(q.c);
        self.scalar(q.s);
    }
    fn rect(&mut self, r: Rect) {
        self.vector(r.min);
        self.vector(r.max);
    }
}

/// FNV-1a, 64-bit: simple, fast enough for per-frame desync checks, and identical
/// on every target.
pub(crate) struct StateHasher(u64);

impl StateHasher {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    pub(crate) fn new() -> Self {
        Self(Self::OFFSET)
    }

    pub(crate) fn finish(&self) -> u64 {
        self.0
    }
}

impl Sink for StateHasher {
    fn put(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(Self::PRIME);
        }
    }
}

/// Writes one body's state.
pub(crate) fn encode_body(s: &mut impl Sink, b: &Body) {
    s.vector(b.position);
    s.rot(b.rotation);
    s.vector(b.linear_velocity);
    s.scalar(b.angular_velocity);
    match b.shape {
        Shape::Circle { radius } => {
            s.u8(0);
            s.scalar(radius);
        }
        Shape::Polygon(h) => {
            s.u8(1);
            s.u32(h.index());
            s.u32(h.generation());
        }
    }
    s.u8(b.body_type as u8);
    s.scalar(b.mass.mass);
    s.scalar(b.mass.inv_mass);
    s.scalar(b.mass.inertia);
    s.scalar(b.mass.inv_inertia);
    s.scalar(b.friction);
    s.scalar(b.restitution);
    s.u32(b.collision_groups);
    s.u32(b.collision_level);
    s.u64(b.user_data);
    s.bool(b.out_of_bounds);
}

/// Writes one arbiter's persistent state: the pair, the lifecycle, the manifold
/// and the accumulated impulses that warm-start the next step.
pub(crate) fn encode_arbiter(s: &mut impl Sink, a: &Arbiter) {
    for h in [a.body_a, a.body_b] {
        s.u32(h.index());
        s.u32(h.generation());
    }
    s.u32(a.level_a);
    s.u32(a.level_b);
    s.u8(a.state as u8);
    s.u32(a.steps_separated);
    s.vector(a.normal);
    s.scalar(a.friction);
    s.scalar(a.restitution);
    s.u8(a.count);
    for p in a.contact_points() {
        s.vector(p.point);
        s.scalar(p.separation);
        s.put(&p.id.to_le_bytes());
        s.scalar(p.normal_impulse);
        s.scalar(p.tangent_impulse);
        s.scalar(p.total_normal_impulse);
        s.scalar(p.max_normal_impulse);
    }
}

/// Writes one joint: its definition and the impulses that warm-start it.
pub(crate) fn encode_joint(s: &mut impl Sink, j: &crate::constraint::Joint) {
    use crate::constraint::{JointKind, MaxTorque};
    let d = &j.def;
    s.u32(d.body_a.index());
    s.u32(d.body_a.generation());
    match d.body_b {
        Some(b) => {
            s.u8(1);
            s.u32(b.index());
            s.u32(b.generation());
        }
        None => s.u8(0),
    }
    s.vector(d.anchor_a);
    s.vector(d.anchor_b);
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
            match limits {
                Some((lo, hi)) => {
                    s.u8(1);
                    s.scalar(lo);
                    s.scalar(hi);
                }
                None => s.u8(0),
            }
            match motor {
                Some(m) => {
                    s.u8(1);
                    s.scalar(m.speed);
                    match m.max_torque {
                        MaxTorque::Limited(t) => {
                            s.u8(0);
                            s.scalar(t);
                        }
                        MaxTorque::Unlimited => s.u8(1),
                    }
                }
                None => s.u8(0),
            }
        }
        JointKind::Weld => s.u8(5),
    }
    match d.break_impulse {
        Some(x) => {
            s.u8(1);
            s.scalar(x);
        }
        None => s.u8(0),
    }
    s.rot(j.reference);
    s.vector(j.impulse);
    s.scalar(j.angular_impulse);
    s.scalar(j.motor_impulse);
    s.scalar(j.limit_impulse);
    s.scalar(j.step_impulse);
}

/// Writes an arena's allocator state and each used slot (generation, free-list
/// link, and the value through `f` when live), so handles and slot reuse survive
/// a round trip.
pub(crate) fn encode_arena<T, K, St: SlotStorage<T>, S: Sink>(
    s: &mut S,
    arena: &Arena<'_, T, K, St>,
    mut f: impl FnMut(&mut S, &T),
) {
    let (used, free_head, len) = arena.allocator_state();
    s.u32(used);
    s.u32(free_head);
    s.u32(len);
    for i in 0..used {
        let (generation, next_free) = arena.slot_meta(i).unwrap_or((0, 0));
        s.u32(generation);
        s.u32(next_free);
        match arena.get_at(i) {
            Some(v) => {
                s.u8(1);
                f(s, v);
            }
            None => s.u8(0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        let mut h = StateHasher::new();
        assert_eq!(h.finish(), 0xcbf2_9ce4_8422_2325);
        h.put(b"a");
        assert_eq!(h.finish(), 0xaf63_dc4c_8601_ec8c);
        let mut h = StateHasher::new();
        h.put(b"foobar");
        assert_eq!(h.finish(), 0x8594_4171_f739_67e8);
    }
}
