//! Spatial indexing: which pairs of bodies might touch this step (the broad phase).
//!
//! The manual lets games plug in their own indexing system. Here a
//! [`SpatialIndex`] only answers "which pairs of bounding boxes overlap?": the
//! arbiter lifecycle, the narrow phase and the callbacks live once, in the engine,
//! so a custom index cannot get them wrong.
//!
//! # Contract
//! Each step the engine passes the index one [`Proxy`] per body that can collide
//! (slot order: bodies inside the bounds), with its bounding box already enlarged by
//! the speculative margin. The index must report, through [`PairSink::push`], every
//! pair of proxies whose boxes overlap (touching counts). It may also report pairs
//! that do not overlap (false positives cost only time), but never miss one (a
//! false negative is a missed collision). Reporting a pair twice, in either order,
//! is harmless, and so is reporting a proxy with itself or an index out of range:
//! the engine drops self-pairs and out-of-range indices, sorts the pairs into the
//! canonical order and removes duplicates, so the order of reports cannot change
//! the simulation. An index should still report in a deterministic order, so that
//! which pairs fit when the pair buffer is full does not vary.
//!
//! [`BruteForceIndex`] tests all pairs (the manual's default, fine below ~100
//! moving bodies); [`SortAndSweepIndex`] scales to thousands. A world's default,
//! [`Index::Auto`](crate::Index::Auto), uses brute force up to
//! [`AUTO_THRESHOLD`] proxies and sort-and-sweep above; both report the same pairs,
//! so the simulation is the same bits either way.

mod brute_force;
mod sort_and_sweep;

pub use brute_force::BruteForceIndex;
pub use sort_and_sweep::SortAndSweepIndex;

use crate::math::Rect;

/// Above this many proxies the automatic index sorts and sweeps instead of
/// testing every pair (measured: the two cross over at about this size).
pub const AUTO_THRESHOLD: usize = 64;

/// One collidable body as the index sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Proxy {
    /// Bounding box (m), enlarged by the speculative margin.
    pub aabb: Rect,
    /// True for static bodies: two static proxies never need to be paired.
    pub is_static: bool,
}

/// Where an index reports candidate pairs: indices into the proxy slice.
pub struct PairSink<'s> {
    pub(crate) pairs: &'s mut [(u32, u32)],
    pub(crate) len: usize,
    pub(crate) overflowed: bool,
}

impl PairSink<'_> {
    /// Reports that proxies `a` and `b` (indices into the slice given to
    /// [`SpatialIndex::find_pairs`]) may overlap. Returns `false` once the pair
    /// buffer is full (the step will then fail with
    /// [`Error::CapacityFull`](crate::Error::CapacityFull) and change nothing), so
    /// the index can stop early.
    pub fn push(&mut self, a: u32, b: u32) -> bool {
        if a == b {
            return true;
        }
        let pair = if a < b { (a, b) } else { (b, a) };
        match self.pairs.get_mut(self.len) {
            Some(slot) => {
                *slot = pair;
                self.len = self.len.saturating_add(1);
                true
            }
            None => {
                self.overflowed = true;
                false
            }
        }
    }

    /// Pairs reported so far.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when nothing was reported yet.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// A broad phase. Implement it to bring your own (grid, tree, sweep…); see the
/// module docs for the contract.
pub trait SpatialIndex {
    /// Reports every pair of `proxies` whose boxes overlap into `out`.
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>);
}

/// True when the two proxies need a pair: boxes overlap and not both static.
#[inline]
#[must_use]
pub fn proxies_may_touch(a: &Proxy, b: &Proxy) -> bool {
    !(a.is_static && b.is_static) && a.aabb.overlaps(b.aabb)
}
