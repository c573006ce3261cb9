//! `SortAndSweepIndex`: proxies sorted along x, swept for overlaps.

use managed::ManagedSlice;

use super::{proxies_may_touch, PairSink, Proxy, SpatialIndex};

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
                if proxies_may_touch(a, b) && !out.push(i, j) {
                    return;
                }
            }
        }
    }
}
