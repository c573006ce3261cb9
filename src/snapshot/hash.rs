//! The state hashes: XXH64 (seed 0) over the canonical encoding, whole and per
//! part.
//!
//! XXH64 is specified byte for byte (it reads its input as little-endian 64-bit
//! lanes), so it is identical on every target, big-endian s390x included. It
//! takes 32 bytes per round instead of FNV-1a's one, which makes hashing the
//! state cost about what writing the snapshot costs. The hashers here collect
//! the many small writes of the encoder into a block before they hand it to
//! `twox-hash`'s streaming XXH64 (which needs no allocator).

use core::hash::Hasher as _;

use super::{Part, Sink};

/// Bytes gathered before they are fed to XXH64.
const BLOCK: usize = 256;

/// Streaming XXH64 (seed 0) fed in blocks; `finish` equals
/// [`super::checksum`] of everything put.
pub(crate) struct Hash64 {
    h: twox_hash::XxHash64,
    block: [u8; BLOCK],
    len: usize,
}

impl Hash64 {
    pub(crate) fn new() -> Self {
        Self { h: twox_hash::XxHash64::with_seed(0), block: [0; BLOCK], len: 0 }
    }

    fn flush(&mut self) {
        if let Some(b) = self.block.get(..self.len) {
            self.h.write(b);
        }
        self.len = 0;
    }

    pub(crate) fn finish(mut self) -> u64 {
        self.flush();
        self.h.finish()
    }
}

impl Sink for Hash64 {
    fn put(&mut self, bytes: &[u8]) {
        if self.len.saturating_add(bytes.len()) > BLOCK {
            self.flush();
            if bytes.len() >= BLOCK {
                self.h.write(bytes);
                return;
            }
        }
        let end = self.len.saturating_add(bytes.len());
        if let Some(dst) = self.block.get_mut(self.len..end) {
            dst.copy_from_slice(bytes);
            self.len = end;
        }
    }
}

/// One 64-bit hash per part of the state, from [`crate::World::state_hashes`].
///
/// Each is XXH64 (seed 0) of the bytes of the canonical encoding that belong to
/// its part, in encoding order; `all` is the hash of the whole encoding, equal to
/// [`crate::World::state_hash`]. When two peers' `all` differ, the parts that
/// differ say where to look:
///
/// | part | bytes of the encoding |
/// |---|---|
/// | `world` | step count, world settings, polygon-path checksum |
/// | `bodies` | the body-properties table; for each live body its flags, properties index, position, rotation and velocities; each shape of a compound body (owner, next shape, shape, frame, mass, material, filter, sensor) and the compound bodies' list heads |
/// | `generators` | each generator slot's kind and parameters (targets included) |
/// | `contacts` | the arbiters: pairs, states, persistence counters, feature ids, warm-start impulses |
/// | `joints` | each joint slot's definition, reference angle and accumulated impulses |
/// | `allocators` | for bodies, generators, joints and (once used) the shape store: slots used, free-list head and live count, and each slot's generation and free-list link |
///
/// A body added or removed changes `bodies` and `allocators`; a body that moved
/// changes `bodies` only. Queued post-step callbacks are not a part: the
/// post-step queue is empty between steps, so it holds no state that a snapshot
/// must carry.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct StateHashes {
    /// The whole encoding: [`crate::World::state_hash`].
    pub all: u64,
    /// Step count, world settings, polygon-path checksum.
    pub world: u64,
    /// Bodies: properties, flags, positions, rotations, velocities.
    pub bodies: u64,
    /// Force generators' kinds and parameters.
    pub generators: u64,
    /// Arbiters (contact pairs) with their persistence and warm-start impulses.
    pub contacts: u64,
    /// Joints' definitions and accumulated impulses.
    pub joints: u64,
    /// Arena allocators: slot counts, free lists, generations.
    pub allocators: u64,
}

impl StateHashes {
    /// The names of the parts (not `all`) whose hashes differ between `self` and
    /// `other`, in the order of the table above.
    pub fn differing<'s>(&'s self, other: &'s Self) -> impl Iterator<Item = &'static str> + 's {
        [
            ("world", self.world, other.world),
            ("bodies", self.bodies, other.bodies),
            ("generators", self.generators, other.generators),
            ("contacts", self.contacts, other.contacts),
            ("joints", self.joints, other.joints),
            ("allocators", self.allocators, other.allocators),
        ]
        .into_iter()
        .filter(|(_, a, b)| a != b)
        .map(|(name, _, _)| name)
    }
}

/// Hashes the whole stream and, separately, the bytes of each part. Bytes are
/// gathered in one block, which goes to the whole hash and to the current part's
/// when it is full or the part changes.
pub(crate) struct PartsHasher {
    all: twox_hash::XxHash64,
    parts: [twox_hash::XxHash64; 6],
    current: Option<usize>,
    block: [u8; BLOCK],
    len: usize,
}

impl PartsHasher {
    pub(crate) fn new() -> Self {
        let h = || twox_hash::XxHash64::with_seed(0);
        Self { all: h(), parts: core::array::from_fn(|_| h()), current: None, block: [0; BLOCK], len: 0 }
    }

    fn flush(&mut self) {
        if let Some(b) = self.block.get(..self.len) {
            self.all.write(b);
            if let Some(h) = self.current.and_then(|i| self.parts.get_mut(i)) {
                h.write(b);
            }
        }
        self.len = 0;
    }

    pub(crate) fn finish(mut self) -> StateHashes {
        self.flush();
        let [world, bodies, generators, contacts, joints, allocators] = self.parts.map(|h| h.finish());
        StateHashes { all: self.all.finish(), world, bodies, generators, contacts, joints, allocators }
    }
}

impl Sink for PartsHasher {
    fn put(&mut self, bytes: &[u8]) {
        if self.len.saturating_add(bytes.len()) > BLOCK {
            self.flush();
            if bytes.len() >= BLOCK {
                self.all.write(bytes);
                if let Some(h) = self.current.and_then(|i| self.parts.get_mut(i)) {
                    h.write(bytes);
                }
                return;
            }
        }
        let end = self.len.saturating_add(bytes.len());
        if let Some(dst) = self.block.get_mut(self.len..end) {
            dst.copy_from_slice(bytes);
            self.len = end;
        }
    }

    fn part(&mut self, part: Part) {
        let next = match part {
            Part::Framing => None,
            Part::World => Some(0),
            Part::Bodies => Some(1),
            Part::Generators => Some(2),
            Part::Contacts => Some(3),
            Part::Joints => Some(4),
            Part::Allocators => Some(5),
        };
        if next != self.current {
            self.flush();
            self.current = next;
        }
    }
}
