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
//! [`World::state_hash`] is FNV-1a (64-bit) over exactly these bytes.
//!
//! Layout, in order: header (`ARPS`, version, step count, world settings, a
//! checksum of the polygon paths); the table of body properties (shape, type,
//! mass, material, groups, level, user data: 58 bytes per run of consecutive bodies
//! that share them); one 64-byte record per body slot (generation, free-list link
//! and flags, position, rotation, velocities); the force generators; the arbiters
//! (58 bytes each: the pair, state, steps since separation, and per contact point
//! its feature id and accumulated normal and friction impulses); the joints
//! (160 bytes each); the trailer `ARPE`. Fixed-size records let `restore` check a
//! buffer completely (free lists included) before it changes anything.
//!
//! A live body therefore costs 64 bytes, plus 58 for its properties unless it
//! shares them with the body before it (a pyramid's boxes do); an arbiter 58 bytes.
//!
//! # What is not in it
//! Polygon paths are static data: the snapshot carries their checksum, and
//! `restore` refuses a snapshot whose paths differ from the world's. Game hooks —
//! custom force generators, collision handlers, game constraints, callbacks — are
//! not state; a snapshot records which generator slots hold a custom generator and
//! `restore` requires the same slots to hold one. Per-step outputs (the impulses a
//! step reports in `post_solve`, a joint's `step_impulse`) are recomputed by the
//! next step and are not saved.

mod apply;
mod cursor;
mod diff;
mod layout;
mod validate;
mod write;

pub use diff::{diff, Difference, Object};

use crate::error::Error;
use crate::math::{Rect, Rot, Scalar, Vector2};
use crate::world::World;

/// Snapshot format version written by this build.
pub const VERSION: u32 = 1;
const MAGIC: &[u8; 4] = b"ARPS";
const TRAILER: &[u8; 4] = b"ARPE";
/// Bytes of one body record.
pub const BODY_RECORD: usize = 64;
/// Bytes of one body-properties record.
pub const PROPS_RECORD: usize = 58;
/// Bytes of one arbiter record.
pub const ARBITER_RECORD: usize = 58;
/// Bytes of one joint record.
pub const JOINT_RECORD: usize = 160;

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

/// Receives the canonical byte stream (a hasher, a counter, or a buffer).
pub(crate) trait Sink {
    /// Appends bytes.
    fn put(&mut self, bytes: &[u8]);

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
        for _ in 0..n {
            self.u8(0);
        }
    }
}

/// FNV-1a, 64-bit: simple, identical on every target, enough to tell two states
/// apart for a desync check.
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

/// Counts bytes.
struct Counter(usize);

impl Sink for Counter {
    fn put(&mut self, bytes: &[u8]) {
        self.0 = self.0.saturating_add(bytes.len());
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
    /// [`crate::snapshot`]): equal on every target and build for equal states.
    /// Compare it between peers every frame to detect a desync.
    #[must_use]
    pub fn state_hash(&self) -> u64 {
        let mut h = StateHasher::new();
        write::write(self, &mut h);
        h.finish()
    }

    /// Bytes [`World::snapshot`] needs right now.
    #[must_use]
    pub fn snapshot_len(&self) -> usize {
        let mut c = Counter(0);
        write::write(self, &mut c);
        c.0
    }

    /// Writes the state into `buf`; returns the bytes written. Allocates nothing.
    ///
    /// # Errors
    /// [`Error::BufferTooSmall`] with the size needed; `buf` is then untouched.
    pub fn snapshot(&self, buf: &mut [u8]) -> Result<usize, Error> {
        let needed = self.snapshot_len();
        let Some(dst) = buf.get_mut(..needed) else { return Err(Error::BufferTooSmall { needed }) };
        let mut w = Writer { buf: dst, pos: 0 };
        write::write(self, &mut w);
        Ok(w.pos)
    }

    /// Restores a state written by [`World::snapshot`]. Bodies, arbiters, joints
    /// and built-in generators come back exactly, with the same handles; stepping
    /// on gives the same bits as if the world had never left that state.
    ///
    /// The whole buffer is checked before anything changes.
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
    /// other slots). On error the world is unchanged.
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
