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
//! the simulation. Duplicates do not use capacity, and when more distinct pairs
//! are reported than the buffer holds, the lowest keys are kept, whatever the
//! order of the reports (see [`PairSink`]).
//!
//! [`BruteForceIndex`] tests all pairs (the manual's default, fine below ~100
//! moving bodies); [`SortAndSweepIndex`] scales to thousands. A world's default,
//! [`Index::Auto`](crate::Index::Auto), uses brute force up to
//! [`AUTO_THRESHOLD`] proxies and sort-and-sweep above; both report the same pairs,
//! so the simulation is the same bits either way.

mod brute_force;
mod sort_and_sweep;

pub use brute_force::BruteForceIndex;
pub(crate) use sort_and_sweep::sweep_sorted;
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
///
/// # Only what is needed uses capacity
/// The sink drops self-pairs, out-of-range indices and pairs the engine would
/// discard anyway (two bodies that may not collide: both without mass, a shared
/// collision group, a joint that keeps them apart) as they are reported. When
/// its buffer fills it sorts it and removes duplicates; if it is still full,
/// it keeps the pairs with the lowest keys (lower body slot, then higher; the
/// proxies are in slot order, so also lower proxy index, then higher), so
/// which pairs are kept does not depend on the order of the reports. The
/// pairs it had to leave out are counted in
/// [`StepReport::pairs_dropped`](crate::StepReport::pairs_dropped), and the step
/// goes on without them (or, with
/// [`WorldDef::strict_capacity`](crate::WorldDef::strict_capacity), fails).
pub struct PairSink<'s> {
    /// Kept pairs of body slots, `(lower, higher)`.
    pub(crate) pairs: &'s mut [(u32, u32)],
    /// The body slot of each proxy index the index reports.
    pub(crate) slots: &'s [u32],
    pub(crate) len: usize,
    /// The buffer is full, sorted and without duplicates: new pairs are
    /// inserted in order, evicting the highest key.
    pub(crate) sorted_full: bool,
    /// Pairs left out because the buffer was full (an evicted pair that is
    /// reported again counts again).
    pub(crate) dropped: usize,
    /// Stop at the first pair that does not fit (strict capacity).
    pub(crate) strict: bool,
    /// A pair did not fit in strict mode.
    pub(crate) overflowed: bool,
    /// Whether the engine wants the pair of body slots `(a, b)`, `a < b`.
    pub(crate) accept: &'s dyn Fn(u32, u32) -> bool,
}

impl<'s> PairSink<'s> {
    /// A sink writing into `pairs` the body-slot pairs (by `slots`, the body
    /// slot of each proxy) that `accept` wants.
    pub(crate) fn new(
        pairs: &'s mut [(u32, u32)],
        slots: &'s [u32],
        strict: bool,
        accept: &'s dyn Fn(u32, u32) -> bool,
    ) -> Self {
        Self { pairs, slots, len: 0, sorted_full: false, dropped: 0, strict, overflowed: false, accept }
    }
}

impl PairSink<'_> {
    /// Reports that proxies `a` and `b` (indices into the slice given to
    /// [`SpatialIndex::find_pairs`]) may overlap, in either order. Returns
    /// `false` only when the step will fail anyway (a strict world whose pair
    /// buffer is full), so the index can stop early; otherwise keep reporting,
    /// so the engine can keep the lowest keys.
    // Inline: the automatic sweep calls it once per overlapping pair (mixed,
    // 700 a step; the 100-row pyramid, 19,000), and the call cost about as
    // much as the tests: inlined, mixed 941.3 -> 937.9 M instructions for 180
    // steps, the 100-row pyramid 2,516.2 -> 2,512.8 M for 20. (Its full-buffer
    // insertion kept out of line as a cold function gave back most of it:
    // 940.2 M, 2,515.5 M.)
    #[inline(always)]
    pub fn push(&mut self, a: u32, b: u32) -> bool {
        if a == b || self.overflowed {
            return !self.overflowed;
        }
        let (Some(&a), Some(&b)) = (self.slots.get(a as usize), self.slots.get(b as usize)) else {
            return true; // out of range
        };
        let pair = if a < b { (a, b) } else { (b, a) };
        if !(self.accept)(pair.0, pair.1) {
            return true;
        }
        if !self.sorted_full && self.len >= self.pairs.len() {
            self.compact();
        }
        if !self.sorted_full {
            if let Some(slot) = self.pairs.get_mut(self.len) {
                *slot = pair;
                self.len = self.len.saturating_add(1);
            }
            return true;
        }
        let kept = self.pairs.get_mut(..self.len).unwrap_or(&mut []);
        let Err(at) = kept.binary_search(&pair) else { return true }; // a duplicate
        if self.strict {
            self.overflowed = true;
            return false;
        }
        self.dropped = self.dropped.saturating_add(1);
        if at < kept.len() {
            // Lower than the highest kept key: it takes its place.
            kept.copy_within(at..kept.len().saturating_sub(1), at.saturating_add(1));
            if let Some(slot) = kept.get_mut(at) {
                *slot = pair;
            }
        }
        true
    }

    /// Sorts the buffer and removes duplicates; still full, it switches to
    /// ordered insertion.
    fn compact(&mut self) {
        let kept = self.pairs.get_mut(..self.len).unwrap_or(&mut []);
        kept.sort_unstable();
        self.len = dedup_sorted(kept);
        self.sorted_full = self.len >= self.pairs.len();
    }

    /// Pairs kept so far (after the duplicates removed when the buffer filled).
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when nothing was kept yet.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Sorts `pairs[..len]` by (lower slot, higher slot), the order of the
/// tuples, and returns it.
///
/// When the rest of `pairs` has room for one entry per slot up to the
/// largest lower slot, the pairs are first moved into one bucket per lower
/// slot in place (a counting sort, O(len + slots), with the buckets' bounds
/// kept in that room), then each bucket, a handful of pairs, is sorted by
/// the higher slot. Otherwise the library's sort does it. Either way the
/// result is the same sorted slice.
pub(crate) fn sort_pairs(pairs: &mut [(u32, u32)], len: usize) -> &mut [(u32, u32)] {
    let len = len.min(pairs.len());
    let (data, rest) = pairs.split_at_mut(len);
    let top = data.iter().fold(0u32, |m, p| m.max(p.0)) as usize;
    let Some(buckets) = rest.get_mut(..=top) else {
        data.sort_unstable_by_key(|&(a, b)| (u64::from(a) << 32) | u64::from(b));
        return data;
    };
    // Each bucket's (next free position, end).
    buckets.fill((0, 0));
    for p in data.iter() {
        if let Some(b) = buckets.get_mut(p.0 as usize) {
            b.1 = b.1.wrapping_add(1);
        }
    }
    let mut end = 0u32;
    for b in buckets.iter_mut() {
        (b.0, end) = (end, end.wrapping_add(b.1));
        b.1 = end;
    }
    // Fill bucket after bucket: the pair at a bucket's next free position
    // stays if it belongs there, or is swapped to its own bucket's.
    for d in 0..buckets.len() {
        while let Some(&(h, e)) = buckets.get(d) {
            let Some(&x) = data.get(h as usize).filter(|_| h < e) else { break };
            let to = x.0 as usize;
            if to == d {
                if let Some(b) = buckets.get_mut(d) {
                    b.0 = h.wrapping_add(1);
                }
                continue;
            }
            let Some(b) = buckets.get_mut(to) else { break };
            let t = b.0;
            b.0 = t.wrapping_add(1);
            let Some(&y) = data.get(t as usize) else { break };
            if let Some(at_h) = data.get_mut(h as usize) {
                *at_h = y;
            }
            if let Some(at_t) = data.get_mut(t as usize) {
                *at_t = x;
            }
        }
    }
    // Each bucket by the higher slot.
    let mut start = 0usize;
    for &(_, e) in buckets.iter() {
        let e = e as usize;
        if let Some(bucket) = data.get_mut(start..e) {
            if bucket.len() <= 16 {
                insertion_sort(bucket);
            } else {
                bucket.sort_unstable();
            }
        }
        start = e;
    }
    data
}

/// Sorts a short slice (one bucket of [`sort_pairs`]).
fn insertion_sort(v: &mut [(u32, u32)]) {
    for k in 1..v.len() {
        let Some(&x) = v.get(k) else { break };
        let mut j = k;
        while let Some(&y) = v.get(j.wrapping_sub(1)) {
            if y <= x {
                break;
            }
            if let Some(slot) = v.get_mut(j) {
                *slot = y;
            }
            j -= 1;
        }
        if let Some(slot) = v.get_mut(j) {
            *slot = x;
        }
    }
}

/// Removes adjacent duplicates of a sorted slice in place; returns the new length.
pub(crate) fn dedup_sorted(v: &mut [(u32, u32)]) -> usize {
    let mut n = 0usize;
    for k in 0..v.len() {
        let Some(&x) = v.get(k) else { break };
        if n == 0 || v.get(n.wrapping_sub(1)) != Some(&x) {
            if let Some(slot) = v.get_mut(n) {
                *slot = x;
            }
            n = n.saturating_add(1);
        }
    }
    n
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Proxy index = body slot.
    const IDENTITY: [u32; 32] = {
        let mut s = [0u32; 32];
        let mut k = 0;
        while k < 32 {
            s[k] = k as u32;
            k += 1;
        }
        s
    };

    /// The pairs a sink of `cap` slots keeps from `reports`, and how many it
    /// dropped. (These tests use `Vec`: they run with `std`, the default.)
    #[cfg(feature = "std")]
    fn kept(cap: usize, reports: &[(u32, u32)]) -> (std::vec::Vec<(u32, u32)>, usize) {
        let mut buf = std::vec![(0u32, 0u32); cap];
        let accept = |_: u32, _: u32| true;
        let mut sink = PairSink::new(&mut buf, &IDENTITY, false, &accept);
        for &(a, b) in reports {
            assert!(sink.push(a, b), "a lenient sink never asks the index to stop");
        }
        let (n, dropped) = (sink.len, sink.dropped);
        let mut out = buf[..n].to_vec();
        out.sort_unstable();
        out.dedup();
        (out, dropped)
    }

    #[test]
    #[cfg(feature = "std")]
    fn a_full_sink_keeps_the_lowest_distinct_keys_in_any_report_order() {
        let pairs: std::vec::Vec<(u32, u32)> = (0..12u32).map(|k| (k % 5, 5 + k)).collect();
        let mut lowest = pairs.clone();
        lowest.sort_unstable();
        lowest.truncate(5);
        let mut orders = std::vec![pairs.clone()];
        let mut reversed = pairs.clone();
        reversed.reverse();
        orders.push(reversed);
        // Every pair three times, swapped, interleaved.
        orders.push(pairs.iter().flat_map(|&(a, b)| [(b, a), (a, b), (a, b)]).collect());
        for reports in orders {
            let (got, dropped) = kept(5, &reports);
            assert_eq!(got, lowest, "reports {reports:?}");
            assert!(dropped >= 7, "12 distinct pairs in 5 slots drop at least 7: {dropped}");
        }
    }

    #[test]
    #[cfg(feature = "std")]
    fn duplicates_and_self_pairs_use_no_capacity() {
        let reports = [(1, 2), (2, 1), (3, 3), (1, 2), (0, 4), (4, 0), (1, 2)];
        assert_eq!(kept(2, &reports), (std::vec![(0, 4), (1, 2)], 0));
    }

    #[test]
    fn sort_pairs_sorts_with_or_without_room() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for len in [0usize, 1, 2, 7, 20, 40] {
            let mut pairs = [(0u32, 0u32); 64];
            for p in pairs.iter_mut().take(len) {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                // Few lower slots (long buckets) and some duplicates.
                let (a, b) = ((x % 5) as u32 * 3, (x >> 8) as u32 % 24);
                *p = (a.min(b), a.max(b));
            }
            let mut expected = pairs;
            expected[..len].sort_unstable();
            // 64 slots leave room for the buckets; a slice of `len` has none.
            for room in [64, len] {
                let mut got = pairs;
                let sorted = sort_pairs(&mut got[..room], len);
                assert_eq!(sorted, &expected[..len], "len {len}, room {room}");
            }
        }
    }

    #[test]
    fn a_strict_sink_stops_at_the_first_pair_that_does_not_fit() {
        let mut buf = [(0u32, 0u32); 1];
        let accept = |_: u32, _: u32| true;
        let mut sink = PairSink::new(&mut buf, &IDENTITY, true, &accept);
        assert!(sink.push(0, 1));
        assert!(sink.push(1, 0), "a duplicate fits");
        assert!(!sink.push(0, 2));
        assert!(sink.overflowed);
    }
}
