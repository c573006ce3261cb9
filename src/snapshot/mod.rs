//! Snapshots: the whole simulation state in a caller-owned byte buffer, restore,
//! the state hash, and a desync locator.
//!
//! # The encoding
//! One canonical little-endian encoding holds everything that shapes future steps:
//! the step count and world settings, the body allocator and every body, the force
//! generators, the arbiters with their persistence counters and warm-start
//! impulses, and the joints with theirs. It never depends on the target's
//! endianness or pointer width, nor on the world's capacities. Integers are their
//! little-endian bytes; a `Scalar` is its raw 64-bit two's-complement bits.
//!
//! Layout (format [`VERSION`] 5; 4 had neither the contact recycle distance
//! nor the manifold records), in order:
//! 1. framing, [`HEADER`] = 16 bytes: `ARPS`, the version (u32), and the
//!    snapshot's total length in bytes (u64, trailer included);
//! 2. the world: step count, world settings (the contact recycle distance
//!    last), a checksum of the polygon paths;
//! 3. the table of body properties (shape; type with the bullet, sensor and
//!    fixed-rotation flags; mass, inertia, friction, restitution, groups,
//!    level, user data; linear and angular damping, gravity scale; filter
//!    category, mask and group index: [`PROPS_RECORD`] = 118 bytes per run of consecutive bodies
//!    that share them);
//! 4. the body allocator and one 64-byte record per body slot (generation,
//!    free-list link or flags and properties index, position, rotation,
//!    velocities); then, when bit 31 of the properties count is set
//!    ([`SHAPES`]: the world's shape store has used a slot), the shapes
//!    section: the shape store's allocator, one [`SHAPE_RECORD`] per slot it
//!    has used (generation, free-list link or used flag, owner body, next
//!    shape, the shape as the properties record holds one, its frame on the
//!    body, mass, inertia, material, filter, sensor flag), and the compound
//!    bodies' list ([`COMPOUND_RECORD`]: each compound body's slot and first
//!    shape slot, in body-slot order; a body's shape count is its list's
//!    length, and one-shape bodies are in neither);
//! 5. the generator allocator and the force generators;
//! 6. the arbiters (58 bytes each: the pair, state with the touching and kept-manifold flags, steps since separation, and
//!    per contact point its feature id and accumulated normal and friction
//!    impulses); when an arbiter is for a chain link or a shape other than 0,
//!    bit 31 of their count is set ([`ARBITER_LINKS`]) and the records are
//!    followed by each arbiter's sub-key word (u32: the chain link in bits
//!    0–19, the shape index on body A in bits 26–28 and on body B in 29–31);
//!    then, when the world recycles manifolds, bit 30 of the count is set
//!    ([`ARBITER_MANIFOLDS`]) and each arbiter's [`MANIFOLD_RECORD`] follows
//!    (128 bytes: the manifold the next step may carry on, zeros when it
//!    has none);
//! 7. the joint allocator and the joints (160 bytes each: the definition with
//!    its kind as a tag, 0 spring to 5 weld and 6 the target joint, whose
//!    target is the definition's world point, then the reference angle and
//!    the accumulated impulses; the target joint's tag fits the same record,
//!    so the format version did not change for it: a build without it
//!    rejects such a snapshot as an unknown joint kind);
//! 8. the trailer, [`TRAILER`] = 8 bytes: the XXH64 checksum (seed 0) of every
//!    byte before it.
//!
//! Fixed-size records let `restore` check a buffer completely (free lists
//! included) before it changes anything. A live body costs 64 bytes, plus 118 for
//! its properties unless it shares them with the body before it (a pyramid's
//! boxes do), plus, for a compound body, 8 and 126 per shape; an arbiter 58
//! bytes, plus 128 for its manifold while the world recycles them (the
//! default; see [`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance)).
//!
//! # Integrity, length and hashes
//! [`World::restore`] reads the framing, then verifies the checksum over the
//! `length − 8` bytes before the trailer, and only then parses and validates the
//! fields (which it still does in full: a snapshot of another world, or a
//! well-formed one with values out of range, is rejected too). Every single-bit
//! flip and any random overwrite is rejected, and the world is left as it was.
//! The buffer may be longer than the length in the header — a slot of a ring
//! buffer sized once with [`World::max_snapshot_len`] — and the rest is ignored.
//! [`World::snapshot`] encodes in one pass (it counts objects first to write the
//! length, but encodes nothing twice).
//!
//! [`World::state_hash`] is XXH64 (seed 0; the specified xxHash algorithm,
//! identical on every target, big-endian included, through the `twox-hash`
//! crate) over exactly the bytes before the trailer, so it equals the trailer of
//! a snapshot taken in the same state; it is computed without a buffer, at
//! about the cost of writing a snapshot. [`World::state_hashes`] gives one such
//! hash per part of the state ([`StateHashes`]) for locating a desync without
//! exchanging snapshots; [`fn@diff`] then names the object and field.

//! # What is not in it
//! Polygon paths and chains are static data: the snapshot carries their
//! checksum (the chains' points folded in when there are any, so a world
//! without chains hashes as before), and `restore` refuses a snapshot whose
//! paths or chains differ from the world's. Game hooks —
//! custom force generators, collision handlers, game constraints, callbacks — are
//! not state; a snapshot records which generator slots hold a custom generator and
//! `restore` requires the same slots to hold one. Per-step outputs (the impulses a
//! step reports in `post_solve`, a joint's `step_impulse`) are recomputed by the
//! next step and are not saved. Queued post-step callbacks need no record: the
//! queue is empty whenever the game can snapshot (`step` and `remove_body` drain
//! it before they return; see [`crate::handler`]). Nor do the diagnostics of
//! [`World::stats`].

mod apply;
mod cursor;
mod diff;
mod hash;
mod layout;
mod validate;
mod write;

pub use diff::{diff, Difference, Object};
pub use hash::StateHashes;

use crate::error::Error;
use crate::math::{Rect, Rot, Scalar, Vector2};
use crate::world::World;
use hash::{Hash64, PartsHasher};

/// Snapshot format version written by this build (2: length in the header,
/// XXH64 checksum trailer; 3: the body options and filter in the properties
/// record; 4: capsule and segment shapes, a
/// 24-byte shape field, and each polygon path's rounding in the paths checksum).
pub const VERSION: u32 = 5;
const MAGIC: &[u8; 4] = b"ARPS";
/// Bytes of the framing that opens a snapshot: `ARPS`, the version (u32) and the
/// snapshot's total length in bytes (u64), trailer included.
pub const HEADER: usize = 16;
/// Bytes of the trailer that closes a snapshot: the XXH64 checksum (seed 0) of
/// every byte before it, little-endian. It equals [`World::state_hash`].
pub const TRAILER: usize = 8;
/// Bytes of one body record.
pub const BODY_RECORD: usize = 64;
/// Bytes of one body-properties record.
///
/// | offset | bytes | field |
/// |---|---|---|
/// | 0 | 1 | shape kind (0 circle, 1 polygon, 2 capsule, 3 segment) |
/// | 1 | 24 | the shape, zero-padded: circle radius; path handle (index u32, generation u32); capsule's second centre (x, y) and radius (the first centre is the second negated); segment's second end (x, y) (the first is its negation); chain (kind 4): first point in the slab (u32), point count (u32), closed (u64, 0 or 1) |
/// | 25 | 1 | body type and flags (see below) |
/// | 26 | 8 × 4 | mass, inertia, friction, restitution |
/// | 58 | 4 + 4 | collision groups, collision level |
/// | 66 | 8 | user data |
/// | 74 | 8 × 3 | linear damping, angular damping, gravity scale |
/// | 98 | 8 + 8 | filter category bits, mask bits |
/// | 114 | 4 | filter group index (i32) |
pub const PROPS_RECORD: usize = 118;
/// Bytes of one arbiter record.
pub const ARBITER_RECORD: usize = 58;
/// Bytes of one arbiter's manifold record (see [`ARBITER_MANIFOLDS`]):
///
/// | offset | bytes | field |
/// |---|---|---|
/// | 0 | 16 | the kept manifold's normal |
/// | 16 | 16 + 16 | body A's and body B's rotations when it was computed |
/// | 48 | 2 × 40 | per point: its offsets from A's and B's centres and its separation when it was computed |
///
/// All zeros for an arbiter without a kept manifold (bit 6 of its state
/// byte clear), and each point's past the arbiter's count.
pub const MANIFOLD_RECORD: usize = 128;
/// Bit 30 of the arbiter count: the arbiter records (and their sub-key
/// words, when there are any) are followed by one [`MANIFOLD_RECORD`] per
/// arbiter, the manifold the next step may carry on rather than compute
/// again. Written exactly when the world recycles manifolds
/// ([`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance)
/// not 0): a world that does not keeps 58 bytes an arbiter.
pub const ARBITER_MANIFOLDS: u32 = 1 << 30;
/// Bit 31 of the arbiter count: the arbiter records are followed by one
/// u32 per arbiter, its chain link (bits 0–19) and the indices of its shapes
/// on body A (bits 26–28) and body B (bits 29–31); bits 20–25 are 0.
/// Written only when some arbiter's link or shape index is not 0 (a pair
/// with a chain or a body of several shapes), so a world of one-shape
/// bodies without chains encodes as before, and one with chains as it did
/// before bodies had several shapes.
pub const ARBITER_LINKS: u32 = 1 << 31;
/// Where an arbiter's shape index on body A starts in its sub-key word (see
/// [`ARBITER_LINKS`]); body B's follows 3 bits higher.
const SHAPES_SHIFT: u32 = 26;
/// Bytes of one joint record.
pub const JOINT_RECORD: usize = 160;
/// Bit 31 of the properties count: the body records are followed by the
/// shapes section (the shape store's allocator state, one [`SHAPE_RECORD`]
/// per slot it has used, then the compound bodies' list heads). Written only
/// when the world's shape store has used a slot, so a world that never had a
/// compound body encodes as before.
pub const SHAPES: u32 = 1 << 31;
/// Bytes of one slot of the shape store in the shapes section.
///
/// | offset | bytes | field |
/// |---|---|---|
/// | 0 | 4 | generation |
/// | 4 | 4 | bit 31 set for a used slot (bits 0–30 then 0); else bits 0–29 the free-list successor |
/// | 8 | 4 | the owner: the body's slot |
/// | 12 | 4 | the next shape's slot of the body's list (`u32::MAX` after its last) |
/// | 16 | 1 + 24 | the shape, as the properties record's first 25 bytes |
/// | 41 | 16 + 16 | its frame on the body: offset (x, y) and rotation (cos, sin) |
/// | 73 | 8 × 4 | mass, inertia, friction, restitution |
/// | 105 | 8 + 8 + 4 | filter category bits, mask bits, group index (i32) |
/// | 125 | 1 | sensor (0 or 1) |
///
/// Every byte after the first 8 of a free slot is zero.
pub const SHAPE_RECORD: usize = 126;
/// Bytes of one entry of the compound bodies' list that closes the shapes
/// section: the body's slot and the slot of its first shape (u32 each), in
/// body-slot order. A body's shape count is the length of its list.
pub const COMPOUND_RECORD: usize = 8;

/// The body-type byte of a properties record: bits 0–1 the type (0 static,
/// 1 kinematic, 2 dynamic), bit 4 (0x10) the bullet flag, bit 5 (0x20) the
/// sensor flag (never both), bit 6 (0x40) the fixed-rotation flag; the other
/// bits are zero.
const BULLET: u8 = 1 << 4;
/// The sensor flag of the body-type byte.
const SENSOR: u8 = 1 << 5;
/// The fixed-rotation flag of the body-type byte.
const FIXED_ROTATION: u8 = 1 << 6;
/// The state byte of an arbiter record: bits 0–5 the [`ArbiterState`](crate::ArbiterState),
/// bit 7 set while the pair touches (for contact begin and end events; only in
/// the `Contact` state).
const TOUCHING: u8 = 1 << 7;
/// Bit 6 of an arbiter's state byte: its [`MANIFOLD_RECORD`] holds the
/// manifold the next step may carry on; only with at least one point.
const CACHED: u8 = 1 << 6;
/// The link field of a body record: bit 31 live, bit 30 out of bounds, bits 0–29
/// the free-list successor (free slot) or the properties index (live slot).
const LIVE: u32 = 1 << 31;
const OUT_OF_BOUNDS: u32 = 1 << 30;
const LINK_MASK: u32 = (1 << 30) - 1;
/// "No successor" in a 30-bit link.
const NO_LINK: u32 = LINK_MASK;

/// The error for bytes that are not a valid snapshot; `what` says which check failed.
fn invalid(what: &'static str) -> Error {
    Error::InvalidSnapshot { what }
}

/// The checksum of a snapshot's bytes before its trailer: XXH64 with seed 0.
pub(crate) fn checksum(bytes: &[u8]) -> u64 {
    twox_hash::XxHash64::oneshot(0, bytes)
}

/// Which per-part hash ([`StateHashes`]) the bytes written next belong to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Part {
    /// Magic, version and length: in the whole hash only.
    Framing,
    World,
    Bodies,
    Generators,
    Contacts,
    Joints,
    Allocators,
}

/// Receives the canonical byte stream (a hasher, a counter, or a buffer).
pub(crate) trait Sink {
    /// Appends bytes.
    fn put(&mut self, bytes: &[u8]);

    /// The bytes that follow belong to `part` (only the per-part hasher cares).
    fn part(&mut self, _part: Part) {}

    fn u8(&mut self, v: u8) {
        self.put(&[v]);
    }
    fn u16(&mut self, v: u16) {
        self.put(&v.to_le_bytes());
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
    fn zeros(&mut self, n: usize) {
        const Z: [u8; 64] = [0; 64];
        let mut left = n;
        while left > 0 {
            let k = left.min(Z.len());
            self.put(&Z[..k]);
            left -= k;
        }
    }
}

/// Writes into a slice that is known to be long enough.
struct Writer<'b> {
    buf: &'b mut [u8],
    pos: usize,
}

impl Sink for Writer<'_> {
    fn put(&mut self, bytes: &[u8]) {
        let end = self.pos.saturating_add(bytes.len());
        if let Some(dst) = self.buf.get_mut(self.pos..end) {
            dst.copy_from_slice(bytes);
        }
        self.pos = end;
    }
}

impl World<'_> {
    /// A 64-bit hash of the canonical encoding of the state (see
    /// [`crate::snapshot`]): XXH64 (seed 0) of the bytes [`World::snapshot`]
    /// would write before its trailer, so it equals the trailer of a snapshot
    /// taken now. Equal on every target and build for equal states; computed
    /// without a buffer, in about the time a snapshot takes. Compare it between
    /// peers every frame to detect a desync, and [`World::state_hashes`] to see
    /// which part diverged.
    #[must_use]
    pub fn state_hash(&self) -> u64 {
        let plan = write::Plan::of(self);
        let mut h = Hash64::new();
        write::write(self, &plan, &mut h);
        h.finish()
    }

    /// One hash per part of the state (world settings and step count, bodies,
    /// generators, contacts, joints, allocators), over the same encoding as
    /// [`World::state_hash`] (which is [`StateHashes::all`]). Peers that disagree
    /// on the state hash can exchange these few words to learn which part
    /// diverged before they exchange whole snapshots for [`fn@diff`].
    #[must_use]
    pub fn state_hashes(&self) -> StateHashes {
        let plan = write::Plan::of(self);
        let mut h = PartsHasher::new();
        write::write(self, &plan, &mut h);
        h.finish()
    }

    /// Bytes [`World::snapshot`] writes right now (counted from the number of
    /// objects, without encoding anything).
    #[must_use]
    pub fn snapshot_len(&self) -> usize {
        write::Plan::of(self).len
    }

    /// The longest snapshot this world can ever write: every body slot used, each
    /// body with its own properties, every generator slot holding a generator
    /// with the most targets, the contact store full (with each arbiter's
    /// sub-key word when the world has room for chains or compound bodies),
    /// every shape slot used and every joint slot used.
    /// It depends on the capacities only, so a game can allocate its rollback
    /// ring buffer once (`frames × max_snapshot_len()`); [`World::restore`]
    /// accepts the longer buffer.
    #[must_use]
    pub fn max_snapshot_len(&self) -> usize {
        write::max_len(self)
    }

    /// Writes the state into `buf` in one pass and returns the bytes written
    /// ([`World::snapshot_len`]); bytes of `buf` after those are left alone.
    /// Allocates nothing.
    ///
    /// Nothing is pending between steps: the post-step queue is empty whenever
    /// `step` or `remove_body` has returned, so the snapshot misses no queued
    /// callback. [`World::stats`] (diagnostics) is not in it.
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] with the size needed; `buf` is then untouched.
    pub fn snapshot(&self, buf: &mut [u8]) -> Result<usize, Error> {
        let plan = write::Plan::of(self);
        let needed = plan.len;
        let Some(dst) = buf.get_mut(..needed) else { return Err(Error::BufferTooSmall { needed }) };
        let (body, trailer) = dst.split_at_mut(needed.saturating_sub(TRAILER));
        let mut w = Writer { buf: body, pos: 0 };
        write::write(self, &plan, &mut w);
        trailer.copy_from_slice(&checksum(body).to_le_bytes());
        Ok(needed)
    }

    /// Restores a state written by [`World::snapshot`]. Bodies, arbiters, joints
    /// and built-in generators come back exactly, with the same handles; stepping
    /// on gives the same bits as if the world had never left that state. There
    /// is no queued post-step callback to lose (the queue is empty between
    /// steps); [`World::stats`] is left as it is.
    ///
    /// `buf` may be longer than the snapshot it holds (a ring-buffer slot of
    /// [`World::max_snapshot_len`] bytes): the length in the header says where it
    /// ends, and whatever follows is ignored. Before anything else is read, the
    /// checksum in the trailer is verified, so any corrupted byte (every
    /// single-bit flip, for instance) is rejected; then every field is validated
    /// against the world, and only then is anything changed.
    ///
    /// A snapshot holds slot indices and generations, not the world tag
    /// handles carry (see [`crate::arena`]): a world of the same settings and
    /// capacities can restore another world's snapshot, and the handles it then
    /// gives out (and those in its arbiters, joints and generators) are its own.
    ///
    /// Game constraints ([`World::add_constraint`]) are not in the snapshot and
    /// stay registered through a restore; each is active exactly when its bodies,
    /// by handle, are in the restored state: one whose body was removed after the
    /// snapshot comes back to life with it, one whose body did not exist yet is
    /// dormant. Built-in joints are in the snapshot and come back with it.
    ///
    /// # Errors
    /// [`Error::InvalidSnapshot`] for truncated, corrupted or foreign bytes;
    /// [`Error::SnapshotMismatch`] for a snapshot of another world (other settings
    /// or paths, more objects than this world's capacities, custom generators in
    /// other slots); [`Error::CapacityFull`] (`"shape"`) for a snapshot whose
    /// compound bodies' shapes used more slots than this world's shape store
    /// ([`Capacities::shapes`](crate::Capacities::shapes)) has. On error the
    /// world is unchanged.
    pub fn restore(&mut self, buf: &[u8]) -> Result<(), Error> {
        // The snapshot holds no world tag: its handles become this world's.
        let layout = layout::Layout::parse(buf)?.for_world(self.bodies.tag());
        validate::validate(self, &layout)?;
        apply::apply(self, &layout);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_checksum_is_xxh64_with_the_published_test_vectors() {
        // From the xxHash reference implementation (XXH64, seed 0).
        assert_eq!(checksum(b""), 0xef46_db37_51d8_e999);
        assert_eq!(checksum(b"a"), 0xd24e_c4f1_a98c_6e5b);
        assert_eq!(checksum(b"abc"), 0x44bc_2cf5_ad77_0999);
    }

    #[test]
    fn the_block_hasher_equals_the_one_shot_hash_whatever_the_pieces() {
        let data: [u8; 1000] = core::array::from_fn(|i| (i * 31 % 251) as u8);
        for piece in [1, 3, 8, 31, 64, 255, 256, 257, 999] {
            let mut h = Hash64::new();
            for chunk in data.chunks(piece) {
                h.put(chunk);
            }
            assert_eq!(h.finish(), checksum(&data), "pieces of {piece}");
        }
    }
}
