//! `BruteForceIndex`: every proxy against every other.

use super::{proxies_may_touch, PairSink, Proxy, SpatialIndex};

/// Tests all n(n−1)/2 pairs, in index order. Exact and simple; suits scenes of
/// up to about a hundred moving bodies (the manual's guidance).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BruteForceIndex;

impl SpatialIndex for BruteForceIndex {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        for (i, a) in proxies.iter().enumerate() {
            for (j, b) in proxies.iter().enumerate().skip(i.saturating_add(1)) {
                if proxies_may_touch(a, b) && !out.push(i as u32, j as u32) {
                    return;
                }
            }
        }
    }
}
