//! `SortAndSweepIndex`: proxies sorted along x, swept for overlaps.

use managed::ManagedSlice;

use super::{PairSink, Proxy, SpatialIndex};
use crate::Scalar;

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
    /// The bands the automatic sweep sorted by last time.
    bands: Bands,
    /// The bands the last sweep chose for the next sort.
    planned: Bands,
}

impl<'a> SortAndSweepIndex<'a> {
    /// An index for up to `scratch.len()` proxies.
    pub fn new(scratch: impl Into<ManagedSlice<'a, u32>>) -> Self {
        Self { order: scratch.into(), len: 0, bands: Bands::ONE, planned: Bands::ONE }
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

    /// The bands [`sort_in_place`](Self::sort_in_place) sorted by last time.
    pub(crate) fn bands(&self) -> Bands {
        self.bands
    }

    /// The bands the next [`sort_in_place`](Self::sort_in_place) sorts by
    /// (as [`sweep_sorted`] chose them from this step's boxes).
    pub(crate) fn plan(&mut self, bands: Bands) {
        self.planned = bands;
    }

    /// The engine's automatic sweep, first half: sorts `proxies` themselves,
    /// and `slots` (the body slot of each) with them, by (band of the lower
    /// edge, left edge, slot), in the bands last step's sweep chose (see
    /// [`plan`](Self::plan)), or without `presorted` in bands chosen from
    /// these boxes.
    ///
    /// With `presorted`, the two are last step's order refilled with this
    /// step's boxes (nearly sorted), and an insertion sort finishes the job in
    /// close to O(n), unless the bands changed height. Otherwise they are
    /// sorted through the `u32` scratch: the scratch is sorted, then the
    /// permutation is applied in place, cycle by cycle. Either way the sorted
    /// proxies lie contiguous, so [`sweep_sorted`] streams through memory
    /// instead of reading each tested proxy through the order (a cache miss
    /// per test on thousands of proxies). The result is a function of the
    /// boxes, the slots and the bands (a total order), and the pairs the sweep
    /// finds do not depend on the order at all.
    pub(crate) fn sort_in_place(&mut self, proxies: &mut [Proxy], slots: &mut [u32], presorted: bool) {
        // A sort from slot order costs more than a look at the boxes.
        let n = proxies.len().min(slots.len());
        let bands = if presorted { self.planned } else { Bands::choose(proxies.get(..n).unwrap_or(&[])) };
        let presorted = presorted && bands.shift == self.bands.shift;
        self.bands = bands;
        if bands == Bands::ONE {
            self.sort_by(proxies, slots, presorted, |p, s| (p.aabb.min.x, s));
        } else {
            self.sort_by(proxies, slots, presorted, |p, s| (bands.of(p.aabb.min.y), p.aabb.min.x, s));
        }
    }

    /// [`sort_in_place`](Self::sort_in_place) by `key`.
    fn sort_by<K: Ord>(
        &mut self,
        proxies: &mut [Proxy],
        slots: &mut [u32],
        presorted: bool,
        key: impl Fn(&Proxy, u32) -> K + Copy,
    ) {
        let n = proxies.len().min(slots.len());
        if presorted {
            for k in 1..n {
                // Mostly in order already: a look at the two keys, no copy.
                if let (Some(q), Some(&t), Some(p), Some(&s)) =
                    (proxies.get(k - 1), slots.get(k - 1), proxies.get(k), slots.get(k))
                {
                    if key(q, t) <= key(p, s) {
                        continue;
                    }
                }
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
                return self.sort_by(proxies, slots, true, key);
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

/// How many horizontal bands the automatic sweep sorts the proxies into.
pub(crate) const BANDS: usize = 128;

/// How deep, in boxes on average, the boxes must be stacked along x for the
/// automatic sweep to sort them into bands: below, a plain sweep along x
/// meets few enough boxes.
const DEEP: i128 = 16;

/// Horizontal bands, each `2^shift` raw units of y tall, that the automatic
/// sweep sorts the proxies into (by their lower edge) before their left
/// edge: a sweep along x then meets only the boxes of its own band, and of
/// the bands above that its box reaches, instead of every box in its x range
/// (a stack's whole column). Or a single band, a plain sweep along x, when
/// the boxes are not stacked deep (see `DEEP`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Bands {
    /// log2 of a band's height in raw units (0: a single band).
    shift: u32,
    /// The (global) number of band 0.
    base: i64,
}

impl Bands {
    /// A single band.
    const ONE: Self = Self { shift: 0, base: 0 };

    /// The band `y` lies in; below band 0 is band 0, above the last band the
    /// last. Nondecreasing in `y`, which is all the sweep needs.
    #[inline(always)]
    pub(crate) fn of(self, y: Scalar) -> usize {
        if self.shift == 0 {
            return 0;
        }
        // `shift` ≥ 1: the difference cannot overflow.
        let b = (y.to_bits() >> self.shift).wrapping_sub(self.base);
        b.clamp(0, BANDS as i64 - 1) as usize
    }

    /// Bands for `proxies` (see [`Extents::bands`]).
    fn measure(proxies: &[Proxy]) -> Self {
        let mut e = Extents::new();
        for p in proxies {
            e.add(p);
        }
        e.bands(proxies.len(), 0)
    }

    /// Bands for `proxies` when they are stacked more than `DEEP` deep,
    /// otherwise a single band.
    fn choose(proxies: &[Proxy]) -> Self {
        let mut e = Extents::new();
        for p in proxies {
            e.add(p);
        }
        if e.deeper_than(DEEP) {
            e.bands(proxies.len(), 0)
        } else {
            Self::ONE
        }
    }
}

/// The boxes' extents, summed for choosing [`Bands`].
struct Extents {
    /// Lowest and highest lower edge, and the heights' sum (raw).
    lo: i64,
    hi: i64,
    heights: i64,
    /// Leftmost left edge, rightmost right edge, and the widths' sum (raw).
    left: i64,
    right: i64,
    widths: i64,
}

impl Extents {
    fn new() -> Self {
        Self { lo: i64::MAX, hi: i64::MIN, heights: 0, left: i64::MAX, right: i64::MIN, widths: 0 }
    }

    #[inline(always)]
    fn add(&mut self, p: &Proxy) {
        let (bottom, top) = (p.aabb.min.y.to_bits(), p.aabb.max.y.to_bits());
        self.lo = self.lo.min(bottom);
        self.hi = self.hi.max(bottom);
        self.heights = self.heights.saturating_add(top.saturating_sub(bottom).max(0));
        self.left = self.left.min(p.aabb.min.x.to_bits());
        self.add_x(p);
    }

    /// The right edge and width of `p` (all [`deeper_than`](Self::deeper_than)
    /// needs once `left` is known).
    #[inline(always)]
    fn add_x(&mut self, p: &Proxy) {
        let (l, r) = (p.aabb.min.x.to_bits(), p.aabb.max.x.to_bits());
        self.right = self.right.max(r);
        self.widths = self.widths.saturating_add(r.saturating_sub(l).max(0));
    }

    /// True when the boxes are stacked more than `depth` deep along x on
    /// average: their widths add up to more than `depth` times the x range
    /// they cover.
    fn deeper_than(&self, depth: i128) -> bool {
        i128::from(self.widths) > depth * (i128::from(self.right) - i128::from(self.left))
    }

    /// Bands for `n` boxes: about as tall as the boxes are on average (the
    /// power of two at most that; `last`'s height when within a factor of
    /// two, so the order is not resorted from scratch for a small change),
    /// or taller when needed to fit every lower edge into [`BANDS`] bands.
    fn bands(&self, n: usize, last: u32) -> Bands {
        let n = i64::try_from(n).unwrap_or(i64::MAX).max(1);
        let average = (self.heights / n).max(1) as u64;
        let mut shift = (u64::BITS - 1 - average.leading_zeros()).max(1);
        if last > 0 && last.abs_diff(shift) <= 1 {
            shift = last;
        }
        while shift < 62 && (self.hi >> shift).saturating_sub(self.lo >> shift) >= BANDS as i64 {
            shift = shift.saturating_add(1);
        }
        Bands { shift, base: self.lo >> shift }
    }
}

/// The engine's automatic sweep, second half: reports every overlapping pair
/// of `proxies`, which [`SortAndSweepIndex::sort_in_place`] sorted by
/// `bands` (band of the lower edge, then left edge). Reports the same pairs
/// as any other index, each once.
///
/// A proxy meets the later proxies of its own band up to its right edge, as
/// in a plain sweep, and in each higher band its box reaches, the proxies
/// from its left edge less that band's widest box up to its right edge (a
/// binary search, then a scan). A pair in two bands is found from the lower
/// one only.
///
/// Returns the bands for the next step's sort (see [`SortAndSweepIndex::plan`]):
/// bands once the boxes are stacked more than `DEEP` deep along x (as
/// [`Bands::choose`] decides for a sort from scratch), a single band again
/// once they are stacked less than half that deep. One measure with a gap
/// between the two thresholds: the 20-row pyramid (stacked 2.1 deep on its
/// wide ground, but meeting 17.5 boxes per proxy in a plain sweep) switched
/// mode every step when the plain sweep went by the boxes it met, and
/// resorted from scratch each time (1,042.7 M instructions for 200 steps;
/// 1,023.4 M always plain, 1,026.3 M always banded).
pub(crate) fn sweep_sorted(proxies: &[Proxy], bands: Bands, out: &mut PairSink<'_>) -> Bands {
    if bands == Bands::ONE {
        // The x extents for the choice (sorted by left edge, the first
        // proxy's is the leftmost).
        let mut extents = Extents::new();
        extents.left = proxies.first().map_or(i64::MAX, |p| p.aabb.min.x.to_bits());
        for (k, a) in proxies.iter().enumerate() {
            let first = k.saturating_add(1);
            if !scan(a, k, proxies.get(first..).unwrap_or(&[]), first, out) {
                return bands;
            }
            extents.add_x(a);
        }
        return if extents.deeper_than(DEEP) { Bands::measure(proxies) } else { Bands::ONE };
    }
    let mut extents = Extents::new();
    // Where each band starts (`start[b]..start[b + 1]`), and its widest box.
    let mut start = [0u32; BANDS + 1];
    let mut widest = [0i64; BANDS];
    for p in proxies {
        extents.add(p);
        let b = bands.of(p.aabb.min.y);
        if let Some(s) = start.get_mut(b.saturating_add(1)) {
            *s = s.saturating_add(1);
        }
        if let Some(w) = widest.get_mut(b) {
            *w = (*w).max(p.aabb.max.x.to_bits().saturating_sub(p.aabb.min.x.to_bits()));
        }
    }
    let mut total = 0u32;
    for s in start.iter_mut() {
        total = total.saturating_add(*s);
        *s = total;
    }
    for band in 0..BANDS {
        let (Some(&s), Some(&end)) = (start.get(band), start.get(band.saturating_add(1))) else { break };
        let (s, end) = (s as usize, end as usize);
        let Some(own) = proxies.get(s..end) else { continue };
        // The band above starts where this one ends.
        let above_end = start.get(band.saturating_add(2)).map_or(end, |&e| e as usize);
        let above = proxies.get(end..above_end).unwrap_or(&[]);
        let reach = widest.get(band.saturating_add(1)).copied().unwrap_or(0);
        // In the band above, the first proxy that can reach the present
        // one's left edge: nondecreasing along this band, so found by
        // stepping on.
        let mut next = 0usize;
        for (i, a) in own.iter().enumerate() {
            let k = s.saturating_add(i);
            let first = k.saturating_add(1);
            if !scan(a, k, own.get(i.saturating_add(1)..).unwrap_or(&[]), first, out) {
                return bands;
            }
            let top = bands.of(a.aabb.max.y);
            if top <= band {
                continue;
            }
            let from = a.aabb.min.x.to_bits().saturating_sub(reach);
            while let Some(b) = above.get(next) {
                if b.aabb.min.x.to_bits() >= from {
                    break;
                }
                next = next.saturating_add(1);
            }
            let row = above.get(next..).unwrap_or(&[]);
            if !scan(a, k, row, end.saturating_add(next), out) {
                return bands;
            }
            // Bands further up (a tall box): a binary search each.
            for higher in band.saturating_add(2)..=top {
                let (Some(&s), Some(&e), Some(&w)) =
                    (start.get(higher), start.get(higher.saturating_add(1)), widest.get(higher))
                else {
                    break;
                };
                let Some(row) = proxies.get(s as usize..e as usize) else { continue };
                let from = a.aabb.min.x.to_bits().saturating_sub(w);
                let skip = row.partition_point(|b| b.aabb.min.x.to_bits() < from);
                let row = row.get(skip..).unwrap_or(&[]);
                if !scan(a, k, row, (s as usize).saturating_add(skip), out) {
                    return bands;
                }
            }
        }
    }
    if extents.deeper_than(DEEP / 2) {
        extents.bands(proxies.len(), bands.shift)
    } else {
        Bands::ONE
    }
}

/// Tests proxy `a` (index `k`) against `row`, sorted by left edge, whose
/// first proxy has index `first`, up to `a`'s right edge. Returns `false`
/// when the sink asks to stop.
#[inline(always)]
fn scan(a: &Proxy, k: usize, row: &[Proxy], first: usize, out: &mut PairSink<'_>) -> bool {
    let (k, right) = (k as u32, a.aabb.max.x);
    let mut j = first as u32;
    for b in row {
        if b.aabb.min.x > right {
            return true;
        }
        if touches_later(a, b) && !out.push(k, j) {
            return false;
        }
        j = j.wrapping_add(1);
    }
    true
}

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

/// The sort key: left edge, then proxy index.
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

    /// Boxes from a xorshift stream, some static, many sharing a left edge,
    /// their left edges in `0..wide`.
    fn boxes(seed: u64, wide: i32, out: &mut [Proxy; N]) {
        let mut x = seed;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 40) as i32
        };
        for p in out.iter_mut() {
            let (x0, y0, w, h) = (next() % wide, next(), next() % 6, next() % 6);
            let min = Vector2::new(Scalar::from_num(x0), Scalar::from_num(y0));
            let max = Vector2::new(Scalar::from_num(x0 + w), Scalar::from_num(y0 + h));
            *p = Proxy { aabb: Rect { min, max }, is_static: next() % 5 == 0 };
        }
    }

    /// The sorted pairs of body slots a sink keeps from `find`, each of which
    /// `find` must report once: the engine removes repeats only for a game's
    /// own index (`collision::broad_phase`), so a built-in index that
    /// reported a pair twice would solve it twice.
    fn pairs(slots: &[u32], find: impl FnOnce(&mut PairSink<'_>), out: &mut [(u32, u32); N * N]) -> usize {
        let accept = |_: u32, _: u32| true;
        let mut sink = PairSink::new(out, slots, false, &accept);
        find(&mut sink);
        let n = sink.len;
        let kept = &mut out[..n];
        kept.sort_unstable();
        let unique = super::super::dedup_sorted(kept);
        assert_eq!(unique, n, "a pair reported more than once");
        unique
    }

    #[test]
    fn the_in_place_sweep_finds_the_brute_force_pairs_from_any_start() {
        let mut scratch = [0u32; N];
        let mut index = SortAndSweepIndex::new(&mut scratch[..]);
        // The game-selectable sweep (`Index::SortAndSweep`), which keeps its
        // own order between calls.
        let mut plain_scratch = [0u32; N];
        let mut plain = SortAndSweepIndex::new(&mut plain_scratch[..]);
        let (mut expected, mut got) = ([(0u32, 0u32); N * N], [(0u32, 0u32); N * N]);
        for seed in 1..80u64 {
            let mut original = [Proxy { aabb: Rect::default(), is_static: false }; N];
            // Spread out (a plain sweep), or stacked deep (bands).
            let wide = if seed % 2 == 0 { 40 } else { 3 };
            boxes(seed * 7919, wide, &mut original);
            // Body slots are spread out, in increasing order like the engine's.
            let mut slots = [0u32; N];
            for (k, s) in slots.iter_mut().enumerate() {
                *s = 3 * k as u32 + (seed as u32 % 3);
            }
            let n_expected = pairs(&slots, |s| BruteForceIndex.find_pairs(&original, s), &mut expected);
            let n_plain = pairs(&slots, |s| plain.find_pairs(&original, s), &mut got);
            assert_eq!(&got[..n_plain], &expected[..n_expected], "seed {seed}: plain sweep");
            let (mut proxies, mut sorted_slots) = (original, slots);
            // From slot order: the scratch sort and the in-place permutation.
            index.sort_in_place(&mut proxies, &mut sorted_slots, false);
            assert_eq!(index.bands() == Bands::ONE, wide == 40, "seed {seed}: banded when stacked");
            for w in proxies.windows(2).zip(sorted_slots.windows(2)) {
                let ((a, b), (sa, sb)) = ((w.0[0], w.0[1]), (w.1[0], w.1[1]));
                let band = |p: &Proxy| index.bands().of(p.aabb.min.y);
                assert!(
                    (band(&a), a.aabb.min.x, sa) < (band(&b), b.aabb.min.x, sb),
                    "seed {seed}: not sorted"
                );
            }
            // Each proxy travelled with its slot.
            for (p, s) in proxies.iter().zip(&sorted_slots) {
                let k = slots.iter().position(|t| t == s).unwrap_or(usize::MAX);
                assert_eq!(Some(p), original.get(k), "seed {seed}");
            }
            let mut next = Bands::ONE;
            let n_got = pairs(&sorted_slots, |s| next = sweep_sorted(&proxies, index.bands(), s), &mut got);
            assert_eq!(&got[..n_got], &expected[..n_expected], "seed {seed}");
            assert_eq!(next == Bands::ONE, wide == 40, "seed {seed}: bands planned when stacked");
            index.plan(next);
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
            let n_got = pairs(&sorted_slots, |s| _ = sweep_sorted(&proxies, index.bands(), s), &mut got);
            assert_eq!(&got[..n_got], &expected[..n_expected], "seed {seed}, nudged");
            for w in proxies.windows(2).zip(sorted_slots.windows(2)) {
                let ((a, b), (sa, sb)) = ((w.0[0], w.0[1]), (w.1[0], w.1[1]));
                let band = |p: &Proxy| index.bands().of(p.aabb.min.y);
                assert!(
                    (band(&a), a.aabb.min.x, sa) < (band(&b), b.aabb.min.x, sb),
                    "seed {seed}: nudged, not sorted"
                );
            }
        }
    }
}
