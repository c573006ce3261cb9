//! The storage a world runs on, chosen by the caller: static buffers
//! ([`WorldBuffers`], no allocator needed, can live in a `static`), or with the
//! `alloc` feature heap buffers sized at run time ([`Capacities`]). The engine is
//! the same code on both; nothing ever grows.

use core::mem::size_of;

use managed::ManagedSlice;

use crate::arbiter::Arbiter;
use crate::arena::Slot;
use crate::body::Body;
use crate::constraint::Joint;
use crate::geometry::PolygonPath;
use crate::index::Proxy;
use crate::math::{Rect, Vector2};
use crate::solver::{ContactConstraint, SolverBody};

/// How many objects of each kind a world can hold (with the `alloc` feature).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacities {
    /// Bodies.
    pub bodies: usize,
    /// Shared polygon paths.
    pub paths: usize,
    /// Candidate pairs per step and arbiters (pairs of bodies in contact, or kept
    /// for persistence). A stack needs about 2 per body, a dense pile about 4.
    pub contacts: usize,
    /// Built-in joints.
    pub joints: usize,
}

impl Default for Capacities {
    fn default() -> Self {
        Self::for_bodies(1024)
    }
}

impl Capacities {
    /// The bytes of storage these capacities take (the world struct itself, with
    /// its inline hooks, comes on top): [`Storage::BYTES_PER_BODY`] per body,
    /// [`Storage::BYTES_PER_PATH`] per path, [`Storage::BYTES_PER_CONTACT`] per
    /// contact, [`Storage::BYTES_PER_JOINT`] per joint; saturating.
    #[must_use]
    pub const fn storage_bytes(&self) -> usize {
        self.bodies
            .saturating_mul(Storage::BYTES_PER_BODY)
            .saturating_add(self.paths.saturating_mul(Storage::BYTES_PER_PATH))
            .saturating_add(self.contacts.saturating_mul(Storage::BYTES_PER_CONTACT))
            .saturating_add(self.joints.saturating_mul(Storage::BYTES_PER_JOINT))
    }

    /// Room for `bodies` bodies, each with its own polygon path, 4 contacts and
    /// 2 joints per body.
    #[must_use]
    pub fn for_bodies(bodies: usize) -> Self {
        Self { bodies, paths: bodies, contacts: bodies.saturating_mul(4), joints: bodies.saturating_mul(2) }
    }
}

/// The storage a world runs on: one slice per store, each borrowed or owned.
///
/// Opaque (as smoltcp's socket storage is): it is made by
/// [`WorldBuffers::storage`] or, with `alloc`, [`Storage::with_capacities`], which
/// size every buffer consistently, so a world never meets a mismatched set.
pub struct Storage<'a> {
    /// Body slots.
    pub(crate) bodies: ManagedSlice<'a, Slot<Body>>,
    /// Polygon path slots.
    pub(crate) paths: ManagedSlice<'a, Slot<PolygonPath>>,
    /// Broad-phase proxies, one per body (scratch).
    pub(crate) proxies: ManagedSlice<'a, Proxy>,
    /// Body slot of each proxy, one per body (scratch).
    pub(crate) proxy_bodies: ManagedSlice<'a, u32>,
    /// Candidate pairs (scratch); its length is the pair capacity.
    pub(crate) pairs: ManagedSlice<'a, (u32, u32)>,
    /// Arbiters; its length is the arbiter capacity.
    pub(crate) arbiters: ManagedSlice<'a, Arbiter>,
    /// The arbiter buffer the next step writes into; same length as `arbiters`.
    pub(crate) arbiters_next: ManagedSlice<'a, Arbiter>,
    /// Built-in joint slots.
    pub(crate) joints: ManagedSlice<'a, Slot<Joint>>,
    /// Body pairs held by joints that do not collide (scratch); as long as `joints`.
    pub(crate) joint_pairs: ManagedSlice<'a, (u32, u32)>,
    /// The automatic index's sort order (scratch), one entry per body.
    pub(crate) sweep_order: ManagedSlice<'a, u32>,
    /// The solver's copy of each body during a step (scratch), one per body.
    pub(crate) solver_bodies: ManagedSlice<'a, SolverBody>,
    /// The solver's contact constraints (scratch); as long as `arbiters`.
    pub(crate) contact_constraints: ManagedSlice<'a, ContactConstraint>,
}

impl Storage<'_> {
    /// Bytes per body slot: the body, its broad-phase proxy, the proxy's body
    /// index, the sort-and-sweep order entry and the solver's copy of the body.
    pub const BYTES_PER_BODY: usize = size_of::<Slot<Body>>()
        + size_of::<Proxy>()
        + size_of::<u32>()
        + size_of::<u32>()
        + size_of::<SolverBody>();
    /// Bytes per polygon path slot.
    pub const BYTES_PER_PATH: usize = size_of::<Slot<PolygonPath>>();
    /// Bytes per contact slot: two arbiters (this step's and the next's), a
    /// candidate pair and the solver's contact constraint.
    pub const BYTES_PER_CONTACT: usize =
        2 * size_of::<Arbiter>() + size_of::<(u32, u32)>() + size_of::<ContactConstraint>();
    /// Bytes per joint slot: the joint and its entry in the non-colliding pairs.
    pub const BYTES_PER_JOINT: usize = size_of::<Slot<Joint>>() + size_of::<(u32, u32)>();

    /// Heap storage with the given capacities.
    #[cfg(feature = "alloc")]
    #[must_use]
    pub fn with_capacities(c: Capacities) -> Self {
        fn buf<T>(n: usize) -> alloc::vec::Vec<Slot<T>> {
            let mut v = alloc::vec::Vec::with_capacity(n);
            v.resize_with(n, || Slot::EMPTY);
            v
        }
        fn plain<T: Clone>(n: usize, v: T) -> alloc::vec::Vec<T> {
            alloc::vec![v; n]
        }
        let empty_proxy = Proxy { aabb: Rect::default(), is_static: false };
        Self {
            bodies: ManagedSlice::Owned(buf(c.bodies)),
            paths: ManagedSlice::Owned(buf(c.paths)),
            proxies: ManagedSlice::Owned(plain(c.bodies, empty_proxy)),
            proxy_bodies: ManagedSlice::Owned(plain(c.bodies, 0)),
            pairs: ManagedSlice::Owned(plain(c.contacts, (0, 0))),
            arbiters: ManagedSlice::Owned(plain(c.contacts, Arbiter::EMPTY)),
            arbiters_next: ManagedSlice::Owned(plain(c.contacts, Arbiter::EMPTY)),
            joints: ManagedSlice::Owned(buf(c.joints)),
            joint_pairs: ManagedSlice::Owned(plain(c.joints, (0, 0))),
            sweep_order: ManagedSlice::Owned(plain(c.bodies, 0)),
            solver_bodies: ManagedSlice::Owned(plain(c.bodies, SolverBody::EMPTY)),
            contact_constraints: ManagedSlice::Owned(plain(c.contacts, ContactConstraint::EMPTY)),
        }
    }
}

/// Statically sized buffers for a world that needs no allocator: `BODIES` bodies
/// and as many polygon paths, `CONTACTS` candidate pairs and arbiters, `JOINTS`
/// built-in joints (default 16). `new` is `const`, so the buffers can be a
/// `static` (e.g. in a `static_cell::StaticCell`) or a local.
pub struct WorldBuffers<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize = 16> {
    bodies: [Slot<Body>; BODIES],
    paths: [Slot<PolygonPath>; BODIES],
    proxies: [Proxy; BODIES],
    proxy_bodies: [u32; BODIES],
    pairs: [(u32, u32); CONTACTS],
    arbiters: [Arbiter; CONTACTS],
    arbiters_next: [Arbiter; CONTACTS],
    joints: [Slot<Joint>; JOINTS],
    joint_pairs: [(u32, u32); JOINTS],
    sweep_order: [u32; BODIES],
    solver_bodies: [SolverBody; BODIES],
    contact_constraints: [ContactConstraint; CONTACTS],
}

impl<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize> WorldBuffers<BODIES, CONTACTS, JOINTS> {
    /// Empty buffers.
    #[must_use]
    pub const fn new() -> Self {
        let empty_proxy = Proxy { aabb: Rect { min: Vector2::ZERO, max: Vector2::ZERO }, is_static: false };
        Self {
            bodies: [Slot::EMPTY; BODIES],
            paths: [Slot::EMPTY; BODIES],
            proxies: [empty_proxy; BODIES],
            proxy_bodies: [0; BODIES],
            pairs: [(0, 0); CONTACTS],
            arbiters: [Arbiter::EMPTY; CONTACTS],
            arbiters_next: [Arbiter::EMPTY; CONTACTS],
            joints: [Slot::EMPTY; JOINTS],
            joint_pairs: [(0, 0); JOINTS],
            sweep_order: [0; BODIES],
            solver_bodies: [SolverBody::EMPTY; BODIES],
            contact_constraints: [ContactConstraint::EMPTY; CONTACTS],
        }
    }

    /// The buffers as a world's storage.
    pub fn storage(&mut self) -> Storage<'_> {
        Storage {
            bodies: ManagedSlice::Borrowed(&mut self.bodies[..]),
            paths: ManagedSlice::Borrowed(&mut self.paths[..]),
            proxies: ManagedSlice::Borrowed(&mut self.proxies[..]),
            proxy_bodies: ManagedSlice::Borrowed(&mut self.proxy_bodies[..]),
            pairs: ManagedSlice::Borrowed(&mut self.pairs[..]),
            arbiters: ManagedSlice::Borrowed(&mut self.arbiters[..]),
            arbiters_next: ManagedSlice::Borrowed(&mut self.arbiters_next[..]),
            joints: ManagedSlice::Borrowed(&mut self.joints[..]),
            joint_pairs: ManagedSlice::Borrowed(&mut self.joint_pairs[..]),
            sweep_order: ManagedSlice::Borrowed(&mut self.sweep_order[..]),
            solver_bodies: ManagedSlice::Borrowed(&mut self.solver_bodies[..]),
            contact_constraints: ManagedSlice::Borrowed(&mut self.contact_constraints[..]),
        }
    }
}

impl<const BODIES: usize, const CONTACTS: usize, const JOINTS: usize> Default
    for WorldBuffers<BODIES, CONTACTS, JOINTS>
{
    fn default() -> Self {
        Self::new()
    }
}
