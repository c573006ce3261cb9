//! `SortAndSweepIndex`: proxies sorted along x, swept for overlaps.

use managed::ManagedSlice;

use super::{PairSink, Proxy, SpatialIndex};

/// Sorts the proxies by the left edge of their boxes and sweeps: each proxy is
/// tested only against those that start before it ends along x. O(n log n + k)
/// for n proxies and k overlapping pairs along x; with bodies that move little
/// between steps the sort is an insertion sort of last step's order, close to
/// O(n).
///
/// Deterministic: the order is by (left edge, proxy index), a total order, so the
/// sorted sequence, and the order pairs are reported in, depend only on the boxes,
/// not on the order the sort started from. It reports exactly the pairs the
/// brute-force index reports.
///
/// Needs one `u32` of scratch per proxy, borrowed or (with `alloc`) owned; a
/// world's automatic index uses scratch from its own storage.
pub struct SortAndSweepIndex<'a> {
    order: ManagedSlice<'a, u32>,
    /// Proxies sorted last time (0 = the order must be rebuilt).
    len: usize,
}

impl<'a> SortAndSweepIndex<'a> {
    /// An index for up to `scratch.len()` proxies.
    pub fn new(scratch: impl Into<ManagedSlice<'a, u32>>) -> Self {
        Self { order: scratch.into(), len: 0 }
    }

    /// An index for up to `capacity` proxies on the heap.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`](crate::Error::OutOfMemory) when the allocator
    /// refuses the scratch (never an abort, whatever `capacity` is).
    #[cfg(feature = "alloc")]
    pub fn with_capacity(capacity: usize) -> Result<Self, crate::Error> {
        let mut order = alloc::vec::Vec::new();
        order
            .try_reserve_exact(capacity)
            .map_err(|_| crate::Error::OutOfMemory { what: "sort-and-sweep scratch" })?;
        order.resize(capacity, 0u32);
        Ok(Self::new(order))
    }
}

impl SortAndSweepIndex<'_> {
    /// How many proxies [`sort_in_place`](Self::sort_in_place) left sorted
    /// last step (0: none), for the caller to check before it reuses that
    /// order.
    pub(crate) fn sorted_len(&self) -> usize {
        self.len
    }

    /// The engine's automatic sweep, first half: sorts `proxies` themselves,
    /// and `slots` (the body slot of each) with them, by (left edge, slot).
    ///
    /// With `presorted`, the two are last step's order refilled with this
    /// step's boxes (nearly sorted), and an insertion sort finishes the job in
    /// close to O(n). Otherwise they are in slot order, and are sorted through
    /// the `u32` scratch: the scratch is sorted, then the permutation is
    /// applied in place, cycle by cycle. Either way the sorted proxies lie
    /// contiguous, so [`sweep_sorted`] streams through memory instead of
    /// reading each tested proxy through the order (a cache miss per test on
    /// thousands of proxies). The result is a function of the boxes and slots
    /// alone (a total order), and the pairs the sweep finds do not depend on
    /// the order at all.
    pub(crate) fn sort_in_place(&mut self, proxies: &mut [Proxy], slots: &mut [u32], presorted: bool) {
        let n = proxies.len().min(slots.len());
        let key = |p: &Proxy, s: u32| (p.aabb.min.x, s);
        if presorted {
            for k in 1..n {
                let (Some(&p), Some(&s)) = (proxies.get(k), slots.get(k)) else { break };
                let kk = key(&p, s);
                let mut j = k;
                while j > 0 {
                    let (Some(q), Some(&t)) = (proxies.get(j - 1), slots.get(j - 1)) else { break };
                    if key(q, t) <= kk {
                        break;
                    }
                    j -= 1;
                }
                if j < k {
                    if let (Some(ps), Some(ss)) = (proxies.get_mut(j..=k), slots.get_mut(j..=k)) {
                        ps.rotate_right(1);
                        ss.rotate_right(1);
                    }
                }
            }
        } else {
            let Some(order) = self.order.get_mut(..n) else {
                // Not enough scratch: an insertion sort from slot order.
                self.len = 0;
                return self.sort_in_place(proxies, slots, true);
            };
            for (k, o) in order.iter_mut().enumerate() {
                *o = k as u32;
            }
            order.sort_unstable_by_key(|&i| {
                let i = i as usize;
                proxies.get(i).zip(slots.get(i)).map(|(p, &s)| key(p, s))
            });
            // Position k takes the entry at order[k]; a placed position is
            // marked by order[k] = k.
            for start in 0..n {
                if order.get(start).is_none_or(|&o| o as usize == start) {
                    continue;
                }
                let (Some(&held_p), Some(&held_s)) = (proxies.get(start), slots.get(start)) else { break };
                let mut k = start;
                while let Some(o) = order.get_mut(k) {
                    let src = *o as usize;
                    *o = k as u32;
                    if src == start {
                        if let (Some(p), Some(s)) = (proxies.get_mut(k), slots.get_mut(k)) {
                            (*p, *s) = (held_p, held_s);
                        }
                        break;
                    }
                    let (Some(&p), Some(&s)) = (proxies.get(src), slots.get(src)) else { break };
                    if let (Some(pk), Some(sk)) = (proxies.get_mut(k), slots.get_mut(k)) {
                        (*pk, *sk) = (p, s);
                    }
                    k = src;
                }
            }
        }
        self.len = n;
    }

    /// Forgets the sorted order (the next sort starts from slot order).
    pub(crate) fn forget_order(&mut self) {
        self.len = 0;
    }
}

/// The engine's automatic sweep, second half: reports every overlapping pair
/// of `proxies`, which [`SortAndSweepIndex::sort_in_place`] sorted by left
/// edge. Reports the same pairs as any other index.
pub(crate) fn sweep_sorted(proxies: &[Proxy], out: &mut PairSink<'_>) {
    for (k, a) in proxies.iter().enumerate() {
        let first = k.saturating_add(1);
        let Some(rest) = proxies.get(first..) else { continue };
        for (j, b) in rest.iter().enumerate() {
            if b.aabb.min.x > a.aabb.max.x {
                break;
            }
            if touches_later(a, b) && !out.push(k as u32, first.saturating_add(j) as u32) {
                return;
            }
        }
    }
}

/// The sort key: left edge, then proxy index.
/// [`proxies_may_touch`](super::proxies_may_touch) for a `b` met after `a` in the sweep, where
/// `b.min.x ≤ a.max.x` is already known: the same answer, with the y overlap
/// (the test that rejects most candidates in a stack, whose columns share their
/// x range) first.
#[inline(always)]
fn touches_later(a: &Proxy, b: &Proxy) -> bool {
    let (a_box, b_box) = (a.aabb, b.aabb);
    a_box.min.y <= b_box.max.y
        && b_box.min.y <= a_box.max.y
        && a_box.min.x <= b_box.max.x
        && !(a.is_static && b.is_static)
}

fn key(proxies: &[Proxy], i: u32) -> (crate::Scalar, u32) {
    (proxies.get(i as usize).map_or(crate::Scalar::MAX, |p| p.aabb.min.x), i)
}

impl SpatialIndex for SortAndSweepIndex<'_> {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        let n = proxies.len();
        if n > self.order.len() {
            // More proxies than scratch: fall back to testing every pair (correct,
            // just slower) rather than miss any.
            self.len = 0;
            return super::BruteForceIndex.find_pairs(proxies, out);
        }
        let Some(order) = self.order.get_mut(..n) else { return };
        if self.len != n {
            for (k, slot) in order.iter_mut().enumerate() {
                *slot = k as u32;
            }
            order.sort_unstable_by_key(|&i| key(proxies, i));
        } else {
            // Insertion sort from last step's order: nearly sorted already.
            for k in 1..n {
                let mut j = k;
                while j > 0 {
                    let (Some(&a), Some(&b)) = (order.get(j - 1), order.get(j)) else { break };
                    if key(proxies, a) <= key(proxies, b) {
                        break;
                    }
                    order.swap(j - 1, j);
                    j -= 1;
                }
            }
        }
        self.len = n;
        for (k, &i) in order.iter().enumerate() {
            let Some(a) = proxies.get(i as usize) else { continue };
            for &j in order.iter().skip(k.saturating_add(1)) {
                let Some(b) = proxies.get(j as usize) else { continue };
                if b.aabb.min.x > a.aabb.max.x {
                    break;
                }
                if touches_later(a, b) && !out.push(i, j) {
                    return;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::index::BruteForceIndex;
    use crate::math::{Rect, Scalar, Vector2};

    const N: usize = 96;

    /// Boxes from a xorshift stream, some static, many sharing a left edge.
    fn boxes(seed: u64, out: &mut [Proxy; N]) {
        let mut x = seed;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 40) as i32
        };
        for p in out.iter_mut() {
            let (x0, y0, w, h) = (next(), next(), next() % 6, next() % 6);
            let min = Vector2::new(Scalar::from_num(x0), Scalar::from_num(y0));
            let max = Vector2::new(Scalar::from_num(x0 + w), Scalar::from_num(y0 + h));
            *p = Proxy { aabb: Rect { min, max }, is_static: next() % 5 == 0 };
        }
    }

    /// The sorted pairs of body slots a sink keeps from `find`.
    fn pairs(slots: &[u32], find: impl FnOnce(&mut PairSink<'_>), out: &mut [(u32, u32); N * N]) -> usize {
        let accept = |_: u32, _: u32| true;
        let mut sink = PairSink::new(out, slots, false, &accept);
        find(&mut sink);
        let n = sink.len;
        let kept = &mut out[..n];
        kept.sort_unstable();
        super::super::dedup_sorted(kept)
    }

    #[test]
    fn the_in_place_sweep_finds_the_brute_force_pairs_from_any_start() {
        let mut scratch = [0u32; N];
        let mut index = SortAndSweepIndex::new(&mut scratch[..]);
        let (mut expected, mut got) = ([(0u32, 0u32); N * N], [(0u32, 0u32); N * N]);
        for seed in 1..40u64 {
            let mut original = [Proxy { aabb: Rect::default(), is_static: false }; N];
            boxes(seed * 7919, &mut original);
            // Body slots are spread out, in increasing order like the engine's.
            let mut slots = [0u32; N];
            for (k, s) in slots.iter_mut().enumerate() {
                *s = 3 * k as u32 + (seed as u32 % 3);
            }
            let n_expected = pairs(&slots, |s| BruteForceIndex.find_pairs(&original, s), &mut expected);
            let (mut proxies, mut sorted_slots) = (original, slots);
            // From slot order: the scratch sort and the in-place permutation.
            index.sort_in_place(&mut proxies, &mut sorted_slots, false);
            for w in proxies.windows(2).zip(sorted_slots.windows(2)) {
                let ((a, b), (sa, sb)) = ((w.0[0], w.0[1]), (w.1[0], w.1[1]));
                assert!((a.aabb.min.x, sa) < (b.aabb.min.x, sb), "seed {seed}: not sorted");
            }
            // Each proxy travelled with its slot.
            for (p, s) in proxies.iter().zip(&sorted_slots) {
                let k = slots.iter().position(|t| t == s).unwrap_or(usize::MAX);
                assert_eq!(Some(p), original.get(k), "seed {seed}");
            }
            let n_got = pairs(&sorted_slots, |s| sweep_sorted(&proxies, s), &mut got);
            assert_eq!(&got[..n_got], &expected[..n_expected], "seed {seed}");
            // Nudge the sorted boxes and sort again from that order.
            for (k, p) in proxies.iter_mut().enumerate() {
                let dx = Scalar::from_num((k % 7) as i32 - 3);
                p.aabb.min.x += dx;
                p.aabb.max.x += dx;
            }
            let moved = proxies;
            let moved_slots = sorted_slots;
            index.sort_in_place(&mut proxies, &mut sorted_slots, true);
            let n_expected = pairs(&moved_slots, |s| BruteForceIndex.find_pairs(&moved, s), &mut expected);
            let n_got = pairs(&sorted_slots, |s| sweep_sorted(&proxies, s), &mut got);
            assert_eq!(&got[..n_got], &expected[..n_expected], "seed {seed}, nudged");
            for w in proxies.windows(2).zip(sorted_slots.windows(2)) {
                let ((a, b), (sa, sb)) = ((w.0[0], w.0[1]), (w.1[0], w.1[1]));
                assert!((a.aabb.min.x, sa) < (b.aabb.min.x, sb), "seed {seed}: nudged, not sorted");
            }
        }
    }
}
