//! Chains: static polylines and loops of one-sided links with ghost vertices
//! (terrain, a level's outline).
//!
//! A [`ChainPath`] is checked when it is made (at least 2 points, a loop at
//! least 3; every link at least [`MIN_SEGMENT_LENGTH`] long and short enough
//! for a [`Segment`]; every point within the coordinate limits) and copied by
//! [`World::add_chain`](crate::World::add_chain) into the world's chain slab,
//! whose size is [`Capacities::chain_vertices`](crate::Capacities::chain_vertices).
//! The slab is filled in order and never freed (chains are level geometry):
//! a chain of `n` points takes `n` entries, [`CHAIN_BYTES_PER_VERTEX`] bytes
//! each: the point (16 bytes) and one box of the chain's link tree (32 bytes).
//!
//! # The link tree
//! Link `i` runs from point `i` to point `i + 1` (the last link of a loop back
//! to point 0). The links of a chain form an implicit balanced tree in link
//! order: the node for the links `lo..hi` is link `mid = lo + (hi − lo) / 2`,
//! with the subtrees `lo..mid` and `mid + 1..hi`, and its box (stored in the
//! entry of link `mid`) bounds all of them. The mid-phase finds the
//! first link at or after a given one whose box meets a query box in
//! O(log n) per link found (links of a polyline lie next to their
//! neighbours, so the subtrees' boxes are tight), and returns links in
//! increasing order: the mid-phase needs no sort and no scratch.
//!
//! # Ghost vertices and free ends
//! Each link collides on its right side only (outward normal `(d.y, −d.x)`
//! for `d = point2 − point1`; a counter-clockwise loop has its solid inside)
//! and knows its neighbours' far ends (see [`ChainSegment`]). The two ends of
//! an open chain have no neighbour: their ghost is the end point itself, and
//! the end is a free corner (any normal on the link's front side is admitted
//! there, as at a convex join turned all the way).

use managed::ManagedSlice;

use crate::error::Error;
#[cfg(doc)]
use crate::geometry::MIN_SEGMENT_LENGTH;
use crate::geometry::{ChainSegment, Segment};
use crate::math::{Rect, Scalar, Transform, Vector2};

/// Bytes of the chain slab per point: the point and one box of the link tree.
pub const CHAIN_BYTES_PER_VERTEX: usize = core::mem::size_of::<ChainNode>();

/// The most points one chain may have (2^20 − 1, as the slots of a store).
pub const MAX_CHAIN_VERTICES: usize = crate::arena::MAX_SLOTS;

/// A checked polyline or loop, borrowed from the caller until
/// [`World::add_chain`](crate::World::add_chain) copies it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChainPath<'p> {
    points: &'p [Vector2],
    closed: bool,
}

impl<'p> ChainPath<'p> {
    /// An open polyline through `points` (body-local, m): `points.len() − 1`
    /// links, the solid on the left of the direction of travel (walk terrain
    /// right to left to have its surface face up).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `what` `"chain points"` for fewer than 2 (or
    /// more than [`MAX_CHAIN_VERTICES`]) points, or the errors of
    /// [`Segment::new`] for a link (`"segment length"` for one shorter than
    /// [`MIN_SEGMENT_LENGTH`], `"segment size"` for one longer than 256 m or
    /// a point outside the coordinate range).
    pub fn open(points: &'p [Vector2]) -> Result<Self, Error> {
        Self::checked(points, false)
    }

    /// A closed loop through `points` (body-local, m), the last point joined
    /// back to the first: `points.len()` links. Counter-clockwise, its solid
    /// is inside; clockwise, outside (a room that holds bodies).
    ///
    /// # Errors
    /// As [`ChainPath::open`], with at least 3 points.
    pub fn closed(points: &'p [Vector2]) -> Result<Self, Error> {
        Self::checked(points, true)
    }

    fn checked(points: &'p [Vector2], closed: bool) -> Result<Self, Error> {
        let least = if closed { 3 } else { 2 };
        if points.len() < least || points.len() > MAX_CHAIN_VERTICES {
            return Err(Error::OutOfRange { what: "chain points" });
        }
        let path = Self { points, closed };
        for i in 0..path.links() {
            let (a, b) = path.ends(i);
            Segment::new(a, b)?;
        }
        Ok(path)
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> &'p [Vector2] {
        self.points
    }

    /// True for a loop.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The number of links.
    #[must_use]
    pub fn links(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len().saturating_sub(1)
        }
    }

    fn ends(&self, i: usize) -> (Vector2, Vector2) {
        let n = self.points.len();
        let at = |k: usize| self.points.get(if n == 0 { 0 } else { k % n }).copied().unwrap_or(Vector2::ZERO);
        (at(i), at(i.saturating_add(1)))
    }
}

/// A chain in a world's slab: where its points are, how many, and whether it
/// closes. Made by [`World::add_chain`](crate::World::add_chain); given to
/// [`BodyDef::chain`](crate::BodyDef::chain).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ChainHandle {
    pub(crate) start: u32,
    pub(crate) count: u32,
    pub(crate) closed: bool,
}

impl ChainHandle {
    /// The number of points.
    #[must_use]
    pub fn points(&self) -> usize {
        self.count as usize
    }

    /// The number of links.
    #[must_use]
    pub fn links(&self) -> usize {
        if self.closed {
            self.count as usize
        } else {
            (self.count as usize).saturating_sub(1)
        }
    }

    /// True for a loop.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }
}

/// One entry of the chain slab.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ChainNode {
    point: Vector2,
    bound: Rect,
}

impl ChainNode {
    /// An unused entry.
    pub const EMPTY: Self =
        Self { point: Vector2::ZERO, bound: Rect { min: Vector2::ZERO, max: Vector2::ZERO } };
}

/// The world's chains: the slab and how much of it is used.
pub(crate) struct ChainSlab<'a> {
    nodes: ManagedSlice<'a, ChainNode>,
    used: u32,
}

impl<'a> ChainSlab<'a> {
    pub(crate) fn new(nodes: ManagedSlice<'a, ChainNode>) -> Self {
        Self { nodes, used: 0 }
    }

    /// Entries in use.
    pub(crate) fn used(&self) -> u32 {
        self.used
    }

    /// Entries in all.
    pub(crate) fn capacity(&self) -> usize {
        self.nodes.len()
    }

    /// Every point in use, in slab order.
    pub(crate) fn points(&self) -> impl Iterator<Item = Vector2> + '_ {
        self.nodes.iter().take(self.used as usize).map(|n| n.point)
    }

    /// Copies `path` into the slab and builds its tree.
    pub(crate) fn add(&mut self, path: &ChainPath<'_>) -> Result<ChainHandle, Error> {
        let start = self.used as usize;
        let n = path.points.len();
        let end = start.checked_add(n).filter(|&e| e <= self.nodes.len());
        let (Some(end), Ok(count)) = (end, u32::try_from(n)) else {
            return Err(Error::CapacityFull { what: "chain vertex" });
        };
        let nodes = self.nodes.get_mut(start..end).unwrap_or(&mut []);
        for (node, p) in nodes.iter_mut().zip(path.points) {
            *node = ChainNode { point: *p, bound: Rect { min: *p, max: *p } };
        }
        let h = ChainHandle { start: start as u32, count, closed: path.closed };
        self.used = end as u32;
        self.build(h);
        Ok(h)
    }

    /// True when `h` lies within the used slab and has enough points.
    pub(crate) fn valid(&self, h: ChainHandle) -> bool {
        let least = if h.closed { 3 } else { 2 };
        h.count >= least && h.start.checked_add(h.count).is_some_and(|e| e <= self.used)
    }

    /// Recomputes the boxes of `h`'s tree.
    pub(crate) fn build(&mut self, h: ChainHandle) {
        if self.valid(h) {
            self.build_range(h, 0, h.links() as u32);
        }
    }

    fn build_range(&mut self, h: ChainHandle, lo: u32, hi: u32) -> Option<Rect> {
        if lo >= hi {
            return None;
        }
        let mid = lo + (hi - lo) / 2;
        let (a, b) = self.ends(h, mid)?;
        let mut bound = Rect { min: a.min(b), max: a.max(b) };
        if let Some(left) = self.build_range(h, lo, mid) {
            bound = bound.union(left);
        }
        if let Some(right) = self.build_range(h, mid + 1, hi) {
            bound = bound.union(right);
        }
        if let Some(node) = self.nodes.get_mut(h.start.saturating_add(mid) as usize) {
            node.bound = bound;
        }
        Some(bound)
    }

    fn point(&self, h: ChainHandle, k: u32) -> Option<Vector2> {
        let k = if h.count == 0 { 0 } else { k % h.count };
        self.nodes.get(h.start.checked_add(k)? as usize).map(|n| n.point)
    }

    /// The ends of link `i` (body-local).
    fn ends(&self, h: ChainHandle, i: u32) -> Option<(Vector2, Vector2)> {
        if i as usize >= h.links() {
            return None;
        }
        Some((self.point(h, i)?, self.point(h, i.checked_add(1)?)?))
    }

    /// The body-local box of the whole chain.
    pub(crate) fn local_bounds(&self, h: ChainHandle) -> Option<Rect> {
        let links = h.links() as u32;
        if !self.valid(h) || links == 0 {
            return None;
        }
        self.nodes.get(h.start.saturating_add(links / 2) as usize).map(|n| n.bound)
    }

    /// The largest distance of a point from the body's origin (m, saturating).
    pub(crate) fn radius(&self, h: ChainHandle) -> Scalar {
        let mut r2 = Scalar::ZERO;
        for k in 0..h.count {
            if let Some(p) = self.point(h, k) {
                r2 = r2.max(p.length_squared());
            }
        }
        r2.sqrt()
    }

    /// The world box of the chain placed by `xf`.
    pub(crate) fn aabb(&self, h: ChainHandle, xf: Transform) -> Option<Rect> {
        self.local_bounds(h).map(|b| transform_rect(b, xf))
    }

    /// Link `i` with its ghost vertices (a free end's ghost is its own end).
    pub(crate) fn link(&self, h: ChainHandle, i: u32) -> Option<ChainSegment> {
        let (p1, p2) = self.ends(h, i)?;
        let last = (h.links() as u32).saturating_sub(1);
        let ghost1 = if h.closed {
            self.point(h, i.wrapping_add(h.count.saturating_sub(1)))?
        } else if i == 0 {
            p1
        } else {
            self.point(h, i - 1)?
        };
        let ghost2 = if h.closed || i < last { self.point(h, i.checked_add(2)?)? } else { p2 };
        Some(ChainSegment { ghost1, segment: Segment { point1: p1, point2: p2 }, ghost2 })
    }

    /// The first link at or after `from` whose box meets `query` (body-local),
    /// or `None`.
    pub(crate) fn next_link(&self, h: ChainHandle, from: u32, query: Rect) -> Option<u32> {
        if !self.valid(h) {
            return None;
        }
        self.search(h, 0, h.links() as u32, from, query)
    }

    fn search(&self, h: ChainHandle, lo: u32, hi: u32, from: u32, q: Rect) -> Option<u32> {
        if lo >= hi || hi <= from {
            return None;
        }
        let mid = lo + (hi - lo) / 2;
        let node = self.nodes.get(h.start.checked_add(mid)? as usize)?;
        if !node.bound.overlaps(q) {
            return None;
        }
        if let Some(k) = self.search(h, lo, mid, from, q) {
            return Some(k);
        }
        if mid >= from {
            let (a, b) = self.ends(h, mid)?;
            if (Rect { min: a.min(b), max: a.max(b) }).overlaps(q) {
                return Some(mid);
            }
        }
        self.search(h, mid + 1, hi, from, q)
    }
}

/// The world box of a body-local box placed by `xf` (its four corners').
pub(crate) fn transform_rect(r: Rect, xf: Transform) -> Rect {
    corners_box(r, |p| xf.apply(p))
}

/// The body-local box that holds a world box `r` seen from a body placed by
/// `xf`.
pub(crate) fn local_rect(r: Rect, xf: Transform) -> Rect {
    corners_box(r, |p| xf.apply_inv(p))
}

/// The box of the four corners of `r` mapped by `map`.
fn corners_box(r: Rect, map: impl Fn(Vector2) -> Vector2) -> Rect {
    let corners = [r.min, Vector2::new(r.max.x, r.min.y), r.max, Vector2::new(r.min.x, r.max.y)];
    let first = map(r.min);
    corners
        .into_iter()
        .map(map)
        .fold(Rect { min: first, max: first }, |b, p| Rect { min: b.min.min(p), max: b.max.max(p) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slab on caller storage: these tests also run without `alloc`.
    fn slab(nodes: &mut [ChainNode]) -> ChainSlab<'_> {
        ChainSlab::new(ManagedSlice::Borrowed(nodes))
    }

    #[test]
    fn bad_paths_are_refused() {
        let p = |x: i32, y: i32| Vector2::from_int(x, y);
        assert_eq!(ChainPath::open(&[p(0, 0)]), Err(Error::OutOfRange { what: "chain points" }));
        assert_eq!(ChainPath::closed(&[p(0, 0), p(1, 0)]), Err(Error::OutOfRange { what: "chain points" }));
        assert_eq!(
            ChainPath::open(&[p(0, 0), p(1, 0), p(1, 0)]),
            Err(Error::OutOfRange { what: "segment length" })
        );
        // A loop's closing link counts too.
        assert_eq!(
            ChainPath::closed(&[p(0, 0), p(1, 0), p(0, 1), p(0, 0)]),
            Err(Error::OutOfRange { what: "segment length" })
        );
        let mut nodes = [ChainNode::EMPTY; 3];
        let mut s = slab(&mut nodes);
        let four = [p(0, 0), p(1, 0), p(2, 0), p(3, 0)];
        let path = ChainPath::open(&four).expect("valid");
        assert_eq!(s.add(&path), Err(Error::CapacityFull { what: "chain vertex" }));
        assert_eq!(s.used(), 0);
    }

    #[test]
    fn the_tree_finds_exactly_the_links_a_box_meets_in_order() {
        // A zigzag of 37 links.
        let points: [Vector2; 38] = core::array::from_fn(|i| Vector2::from_int(i as i32, (i % 2) as i32));
        let mut nodes = [ChainNode::EMPTY; 40];
        let mut s = slab(&mut nodes);
        let h = s.add(&ChainPath::open(&points).expect("valid")).expect("room");
        for (x0, x1) in [(0, 0), (3, 7), (-5, 2), (30, 50), (12, 12)] {
            let q = Rect { min: Vector2::from_int(x0, 0), max: Vector2::from_int(x1, 1) };
            let (mut found, mut n_found) = ([0u32; 37], 0);
            let mut from = 0;
            while let Some(k) = s.next_link(h, from, q) {
                found[n_found] = k;
                n_found += 1;
                from = k + 1;
            }
            let (mut expected, mut n_expected) = ([0u32; 37], 0);
            for i in (0..37u32).filter(|&i| (i as i32) <= x1 && (i as i32 + 1) >= x0) {
                expected[n_expected] = i;
                n_expected += 1;
            }
            assert_eq!(found[..n_found], expected[..n_expected], "{x0}..{x1}");
        }
        let b = s.local_bounds(h).expect("valid");
        assert_eq!((b.min, b.max), (Vector2::from_int(0, 0), Vector2::from_int(37, 1)));
    }

    #[test]
    fn links_know_their_neighbours_and_free_ends() {
        let pts = [Vector2::from_int(0, 0), Vector2::from_int(1, 0), Vector2::from_int(2, 1)];
        let mut nodes = [ChainNode::EMPTY; 8];
        let mut s = slab(&mut nodes);
        let open = s.add(&ChainPath::open(&pts).expect("valid")).expect("room");
        let l0 = s.link(open, 0).expect("link");
        assert_eq!((l0.ghost1, l0.ghost2), (pts[0], pts[2]));
        let l1 = s.link(open, 1).expect("link");
        assert_eq!((l1.ghost1, l1.ghost2), (pts[0], pts[2]));
        assert!(s.link(open, 2).is_none());
        let closed = s.add(&ChainPath::closed(&pts).expect("valid")).expect("room");
        let l2 = s.link(closed, 2).expect("link");
        assert_eq!(
            (l2.ghost1, l2.segment.point1, l2.segment.point2, l2.ghost2),
            (pts[1], pts[2], pts[0], pts[1])
        );
        assert_eq!(s.used(), 6);
    }
}
