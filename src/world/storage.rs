//! The storage a world runs on, chosen by the caller: static buffers
//! ([`WorldBuffers`], no allocator needed, can live in a `static`), or with the
//! `alloc` feature heap buffers sized at run time ([`Capacities`]). The engine is
//! the same code on both; nothing ever grows.

use core::mem::size_of;

use managed::ManagedSlice;

use crate::arbiter::Arbiter;
use crate::arena::Slot;
use crate::body::{Body, BodyHandle};
use crate::compound::ShapeSlot;
use crate::constraint::{Joint, JointRow};
#[cfg(feature = "alloc")]
use crate::error::Error;
use crate::events::{
    ContactBeginEvent, ContactEndEvent, ContactHitEvent, JointBrokeEvent, SensorEvent, DEFAULT_EVENTS,
};
use crate::geometry::{ChainNode, PolygonPath};
use crate::handler::{PostStepEntry, DEFAULT_POST_STEP_CALLBACKS, EMPTY_POST_STEP};
use crate::index::Proxy;
use crate::math::{Rect, Vector2};
use crate::solver::{BodyLanes, ContactConstraint, ContactScratch, PivotLanes, SolverBody};

/// How many objects of each kind a world can hold (with the `alloc` feature).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacities {
    /// Bodies.
    pub bodies: usize,
    /// Shared polygon paths.
    pub paths: usize,
    /// Candidate pairs per step and arbiters (pairs of bodies in contact, or kept
    /// for persistence). A stack needs about 2 per body, a dense pile about 4.
    /// A body overlapping a sensor takes one too (see [`BodyDef::sensor`](crate::BodyDef::sensor)).
    pub contacts: usize,
    /// Built-in joints.
    pub joints: usize,
    /// Post-step callbacks that can be queued at once (see
    /// [`CallbackContext::add_post_step_callback`](crate::CallbackContext::add_post_step_callback)).
    /// A game that removes bodies from `begin` needs one per body that can land
    /// in one step.
    pub post_step_callbacks: usize,
    /// Events of each kind one step can report (each of the six lists of
    /// [`crate::events`] holds this many; more are dropped and counted in
    /// [`StepReport::events_dropped`](crate::StepReport::events_dropped)).
    pub events: usize,
    /// Points of all chains together ([`World::add_chain`](crate::World::add_chain)):
    /// a chain of `n` points takes `n`, [`Storage::BYTES_PER_CHAIN_VERTEX`]
    /// (48) bytes each (the point and one box of its link tree). 0 in
    /// [`Capacities::for_bodies`]: a world that uses chains sets it.
    pub chain_vertices: usize,
    /// Shapes of compound bodies ([`World::add_shape`](crate::World::add_shape)):
    /// a body with `n` > 1 shapes takes `n` (its first shape moves here too),
    /// [`Storage::BYTES_PER_SHAPE`] bytes each; a one-shape body takes none.
    /// 0 in [`Capacities::for_bodies`]: a world that uses compound bodies sets it.
    pub shapes: usize,
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
    /// contact, [`Storage::BYTES_PER_JOINT`] per joint,
    /// [`Storage::BYTES_PER_CALLBACK`] per queued callback,
    /// [`Storage::BYTES_PER_EVENT`] per event,
    /// [`Storage::BYTES_PER_CHAIN_VERTEX`] per chain point,
    /// [`Storage::BYTES_PER_SHAPE`] per compound-body shape; saturating.
    #[must_use]
    pub const fn storage_bytes(&self) -> usize {
        match self.checked_storage_bytes() {
            Some(n) => n,
            None => usize::MAX,
        }
    }

    /// As [`Capacities::storage_bytes`], or `None` when the sum overflows `usize`.
    #[must_use]
    pub const fn checked_storage_bytes(&self) -> Option<usize> {
        let parts = [
            self.bodies.checked_mul(Storage::BYTES_PER_BODY),
            self.paths.checked_mul(Storage::BYTES_PER_PATH),
            self.contacts.checked_mul(Storage::BYTES_PER_CONTACT),
            self.joints.checked_mul(Storage::BYTES_PER_JOINT),
            self.post_step_callbacks.checked_mul(Storage::BYTES_PER_CALLBACK),
            self.events.checked_mul(Storage::BYTES_PER_EVENT),
            self.chain_vertices.checked_mul(Storage::BYTES_PER_CHAIN_VERTEX),
            self.shapes.checked_mul(Storage::BYTES_PER_SHAPE),
        ];
        let mut total = 0usize;
        let mut i = 0;
        while i < parts.len() {
            match parts[i] {
                Some(n) => match total.checked_add(n) {
                    Some(t) => total = t,
                    None => return None,
                },
                None => return None,
            }
            i += 1;
        }
        Some(total)
    }

    /// Room for `bodies` bodies, each with its own polygon path, 4 contacts and
    /// 2 joints per body, and one queued post-step callback per body (at least
    /// [`DEFAULT_POST_STEP_CALLBACKS`]); no chain points.
    #[must_use]
    pub fn for_bodies(bodies: usize) -> Self {
        Self {
            bodies,
            paths: bodies,
            contacts: bodies.saturating_mul(4),
            joints: bodies.saturating_mul(2),
            post_step_callbacks: bodies.max(DEFAULT_POST_STEP_CALLBACKS),
            events: bodies.max(DEFAULT_EVENTS),
            chain_vertices: 0,
            shapes: 0,
        }
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
    /// The solver's joint rows (scratch); as long as `joints`.
    pub(crate) joint_rows: ManagedSlice<'a, JointRow>,
    /// The plain pivots' lanes (scratch); as long as `joints`.
    pub(crate) pivot_lanes: ManagedSlice<'a, PivotLanes>,
    /// The automatic index's sort order (scratch), one entry per body.
    pub(crate) sweep_order: ManagedSlice<'a, u32>,
    /// The solver's copy of each body during a step (scratch), one per body.
    pub(crate) solver_bodies: ManagedSlice<'a, SolverBody>,
    /// The contact kernels' copy of each body's velocity (scratch), one per body.
    pub(crate) solver_lanes: ManagedSlice<'a, BodyLanes>,
    /// The solver's contact lanes (scratch); as long as `arbiters`, rounded up
    /// to a whole block of eight.
    pub(crate) contact_constraints: ManagedSlice<'a, ContactConstraint>,
    /// Each arbiter's colour, lane and effective masses in a step (scratch);
    /// as long as `arbiters`.
    pub(crate) contact_scratch: ManagedSlice<'a, ContactScratch>,
    /// The post-step callback queue; its length is the queue's capacity.
    pub(crate) post_step: ManagedSlice<'a, PostStepEntry>,
    pub(crate) contact_begin: ManagedSlice<'a, ContactBeginEvent>,
    pub(crate) contact_end: ManagedSlice<'a, ContactEndEvent>,
    pub(crate) contact_hit: ManagedSlice<'a, ContactHitEvent>,
    pub(crate) sensor_begin: ManagedSlice<'a, SensorEvent>,
    pub(crate) sensor_end: ManagedSlice<'a, SensorEvent>,
    pub(crate) joint_broke: ManagedSlice<'a, JointBrokeEvent>,
    /// The chain slab; its length is the chain-point capacity.
    pub(crate) chain_nodes: ManagedSlice<'a, ChainNode>,
    /// The shape store's slots; its length is the shape capacity.
    pub(crate) shape_slots: ManagedSlice<'a, Slot<ShapeSlot>>,
}

impl Storage<'_> {
    /// Bytes per body slot: the body, its broad-phase proxy, the proxy's body
    /// index, the sort-and-sweep order entry and the solver's copy of the body
    /// (its `Scalar` state and its lanes).
    pub const BYTES_PER_BODY: usize = size_of::<Slot<Body>>()
        + size_of::<Proxy>()
        + size_of::<u32>()
        + size_of::<u32>()
        + size_of::<SolverBody>()
        + size_of::<BodyLanes>();
    /// Bytes per chain point: the point and one box of the chain's link tree
    /// (a chain of `n` links costs about `n` of these).
    pub const BYTES_PER_CHAIN_VERTEX: usize = size_of::<ChainNode>();
    /// Bytes per compound-body shape slot.
    pub const BYTES_PER_SHAPE: usize = size_of::<Slot<ShapeSlot>>();
    /// Bytes per polygon path slot.
    pub const BYTES_PER_PATH: usize = size_of::<Slot<PolygonPath>>();
    /// Bytes per contact slot: two arbiters (this step's and the next's), a
    /// candidate pair, the solver's contact lane and its scratch. (Heap storage
    /// rounds the lanes up to a multiple of eight, up to seven more lanes.)
    pub const BYTES_PER_CONTACT: usize = 2 * size_of::<Arbiter>()
        + size_of::<(u32, u32)>()
        + size_of::<ContactConstraint>()
        + size_of::<ContactScratch>();
    /// Bytes per joint slot: the joint, its entry in the non-colliding pairs,
    /// the solver's row for it and an eighth of a block of pivot lanes.
    pub const BYTES_PER_JOINT: usize =
        size_of::<Slot<Joint>>() + size_of::<(u32, u32)>() + size_of::<JointRow>() + size_of::<PivotLanes>();
    /// Bytes per post-step queue slot: the function and its key.
    pub const BYTES_PER_CALLBACK: usize = size_of::<PostStepEntry>();
    /// Bytes per event capacity: one slot in each of the six lists.
    pub const BYTES_PER_EVENT: usize = size_of::<ContactBeginEvent>()
        + size_of::<ContactEndEvent>()
        + size_of::<ContactHitEvent>()
        + 2 * size_of::<SensorEvent>()
        + size_of::<JointBrokeEvent>();

    /// Heap storage with the given capacities. Every buffer is reserved with
    /// `try_reserve`, so capacities the heap cannot hold are an error, never a
    /// panic or an abort. (An operating system that overcommits memory may
    /// still grant a reservation it cannot back; size capacities with
    /// [`Capacities::storage_bytes`].)
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`what: "capacities"`) when the total size overflows
    /// `usize` or exceeds `isize::MAX` bytes; [`Error::OutOfMemory`] when the heap
    /// refuses a buffer.
    #[cfg(feature = "alloc")]
    pub fn with_capacities(c: Capacities) -> Result<Self, Error> {
        fn filled<T>(
            n: usize,
            what: &'static str,
            make: impl FnMut() -> T,
        ) -> Result<alloc::vec::Vec<T>, Error> {
            let mut v = alloc::vec::Vec::new();
            v.try_reserve_exact(n).map_err(|_| Error::OutOfMemory { what })?;
            v.resize_with(n, make);
            Ok(v)
        }
        let fits = c.checked_storage_bytes().is_some_and(|n| isize::try_from(n).is_ok());
        if !fits {
            return Err(Error::OutOfRange { what: "capacities" });
        }
        let empty_proxy = Proxy { aabb: Rect::default(), is_static: false };
        Ok(Self {
            bodies: ManagedSlice::Owned(filled(c.bodies, "body", || Slot::EMPTY)?),
            paths: ManagedSlice::Owned(filled(c.paths, "polygon path", || Slot::EMPTY)?),
            proxies: ManagedSlice::Owned(filled(c.bodies, "broad-phase proxy", || empty_proxy)?),
            proxy_bodies: ManagedSlice::Owned(filled(c.bodies, "broad-phase proxy", || 0)?),
            pairs: ManagedSlice::Owned(filled(c.contacts, "contact pair", || (0, 0))?),
            arbiters: ManagedSlice::Owned(filled(c.contacts, "arbiter", || Arbiter::EMPTY)?),
            arbiters_next: ManagedSlice::Owned(filled(c.contacts, "arbiter", || Arbiter::EMPTY)?),
            joints: ManagedSlice::Owned(filled(c.joints, "joint", || Slot::EMPTY)?),
            joint_pairs: ManagedSlice::Owned(filled(c.joints, "joint", || (0, 0))?),
            joint_rows: ManagedSlice::Owned(filled(c.joints, "joint row", || JointRow::EMPTY)?),
            pivot_lanes: ManagedSlice::Owned(filled(c.joints, "pivot lanes", || [[0; 8]; 4])?),
            sweep_order: ManagedSlice::Owned(filled(c.bodies, "sweep order", || 0)?),
            solver_bodies: ManagedSlice::Owned(filled(c.bodies, "solver body", || SolverBody::EMPTY)?),
            solver_lanes: ManagedSlice::Owned(filled(c.bodies, "solver body", || BodyLanes::EMPTY)?),
            contact_constraints: ManagedSlice::Owned(filled(
                c.contacts.div_ceil(8).saturating_mul(8),
                "contact constraint",
                || ContactConstraint::EMPTY,
            )?),
            contact_scratch: ManagedSlice::Owned(filled(c.contacts, "contact scratch", || {
                ContactScratch::EMPTY
            })?),
            post_step: ManagedSlice::Owned(filled(c.post_step_callbacks, "post-step callback", || {
                EMPTY_POST_STEP
            })?),
            contact_begin: ManagedSlice::Owned(filled(c.events, "event", ContactBeginEvent::default)?),
            contact_end: ManagedSlice::Owned(filled(c.events, "event", ContactEndEvent::default)?),
            contact_hit: ManagedSlice::Owned(filled(c.events, "event", ContactHitEvent::default)?),
            sensor_begin: ManagedSlice::Owned(filled(c.events, "event", SensorEvent::default)?),
            sensor_end: ManagedSlice::Owned(filled(c.events, "event", SensorEvent::default)?),
            joint_broke: ManagedSlice::Owned(filled(c.events, "event", JointBrokeEvent::default)?),
            chain_nodes: ManagedSlice::Owned(filled(c.chain_vertices, "chain vertex", || ChainNode::EMPTY)?),
            shape_slots: ManagedSlice::Owned(filled(c.shapes, "shape", || Slot::EMPTY)?),
        })
    }
}

const EMPTY_BEGIN: ContactBeginEvent = ContactBeginEvent {
    body_a: BodyHandle::NULL,
    body_b: BodyHandle::NULL,
    normal: Vector2::ZERO,
    shape_a: 0,
    shape_b: 0,
};
const EMPTY_END: ContactEndEvent =
    ContactEndEvent { body_a: BodyHandle::NULL, body_b: BodyHandle::NULL, shape_a: 0, shape_b: 0 };
const EMPTY_HIT: ContactHitEvent = ContactHitEvent {
    body_a: BodyHandle::NULL,
    body_b: BodyHandle::NULL,
    point: Vector2::ZERO,
    normal: Vector2::ZERO,
    speed: crate::math::scalar::ZERO,
    shape_a: 0,
    shape_b: 0,
};
const EMPTY_SENSOR: SensorEvent =
    SensorEvent { sensor: BodyHandle::NULL, visitor: BodyHandle::NULL, sensor_shape: 0, visitor_shape: 0 };

/// Statically sized buffers for a world that needs no allocator: `BODIES` bodies
/// and as many polygon paths, `CONTACTS` candidate pairs and arbiters (a
/// multiple of 8), `JOINTS`
/// built-in joints (default 16), `CALLBACKS` queued post-step callbacks
/// (default [`DEFAULT_POST_STEP_CALLBACKS`], 64), `EVENTS` events of each kind
/// a step reports (default [`DEFAULT_EVENTS`], 64; see [`crate::events`]),
/// `CHAIN_VERTICES` chain points (default 0; see
/// [`World::add_chain`](crate::World::add_chain)), `SHAPES` shapes of compound
/// bodies (default 0; see [`World::add_shape`](crate::World::add_shape)). `new` is `const`, so the
/// buffers can be a `static` (e.g. in a `static_cell::StaticCell`) or a local.
pub struct WorldBuffers<
    const BODIES: usize,
    const CONTACTS: usize,
    const JOINTS: usize = 16,
    const CALLBACKS: usize = DEFAULT_POST_STEP_CALLBACKS,
    const EVENTS: usize = DEFAULT_EVENTS,
    const CHAIN_VERTICES: usize = 0,
    const SHAPES: usize = 0,
> {
    bodies: [Slot<Body>; BODIES],
    paths: [Slot<PolygonPath>; BODIES],
    proxies: [Proxy; BODIES],
    proxy_bodies: [u32; BODIES],
    pairs: [(u32, u32); CONTACTS],
    arbiters: [Arbiter; CONTACTS],
    arbiters_next: [Arbiter; CONTACTS],
    joints: [Slot<Joint>; JOINTS],
    joint_pairs: [(u32, u32); JOINTS],
    joint_rows: [JointRow; JOINTS],
    pivot_lanes: [PivotLanes; JOINTS],
    sweep_order: [u32; BODIES],
    solver_bodies: [SolverBody; BODIES],
    solver_lanes: [BodyLanes; BODIES],
    contact_constraints: [ContactConstraint; CONTACTS],
    contact_scratch: [ContactScratch; CONTACTS],
    post_step: [PostStepEntry; CALLBACKS],
    contact_begin: [ContactBeginEvent; EVENTS],
    contact_end: [ContactEndEvent; EVENTS],
    contact_hit: [ContactHitEvent; EVENTS],
    sensor_begin: [SensorEvent; EVENTS],
    sensor_end: [SensorEvent; EVENTS],
    joint_broke: [JointBrokeEvent; EVENTS],
    chain_nodes: [ChainNode; CHAIN_VERTICES],
    shape_slots: [Slot<ShapeSlot>; SHAPES],
}

impl<
        const BODIES: usize,
        const CONTACTS: usize,
        const JOINTS: usize,
        const CALLBACKS: usize,
        const EVENTS: usize,
        const CHAIN_VERTICES: usize,
        const SHAPES: usize,
    > WorldBuffers<BODIES, CONTACTS, JOINTS, CALLBACKS, EVENTS, CHAIN_VERTICES, SHAPES>
{
    /// Empty buffers.
    ///
    /// `CONTACTS` must be a multiple of 8 (the contact solver works in blocks
    /// of eight lanes); any other value fails to compile.
    #[must_use]
    pub const fn new() -> Self {
        const { assert!(CONTACTS.is_multiple_of(8), "WorldBuffers: CONTACTS must be a multiple of 8") };
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
            joint_rows: [JointRow::EMPTY; JOINTS],
            pivot_lanes: [[[0; 8]; 4]; JOINTS],
            sweep_order: [0; BODIES],
            solver_bodies: [SolverBody::EMPTY; BODIES],
            solver_lanes: [BodyLanes::EMPTY; BODIES],
            contact_constraints: [ContactConstraint::EMPTY; CONTACTS],
            contact_scratch: [ContactScratch::EMPTY; CONTACTS],
            post_step: [EMPTY_POST_STEP; CALLBACKS],
            contact_begin: [EMPTY_BEGIN; EVENTS],
            contact_end: [EMPTY_END; EVENTS],
            contact_hit: [EMPTY_HIT; EVENTS],
            sensor_begin: [EMPTY_SENSOR; EVENTS],
            sensor_end: [EMPTY_SENSOR; EVENTS],
            joint_broke: [JointBrokeEvent::EMPTY; EVENTS],
            chain_nodes: [ChainNode::EMPTY; CHAIN_VERTICES],
            shape_slots: [Slot::EMPTY; SHAPES],
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
            joint_rows: ManagedSlice::Borrowed(&mut self.joint_rows[..]),
            pivot_lanes: ManagedSlice::Borrowed(&mut self.pivot_lanes[..]),
            sweep_order: ManagedSlice::Borrowed(&mut self.sweep_order[..]),
            solver_bodies: ManagedSlice::Borrowed(&mut self.solver_bodies[..]),
            solver_lanes: ManagedSlice::Borrowed(&mut self.solver_lanes[..]),
            contact_constraints: ManagedSlice::Borrowed(&mut self.contact_constraints[..]),
            contact_scratch: ManagedSlice::Borrowed(&mut self.contact_scratch[..]),
            post_step: ManagedSlice::Borrowed(&mut self.post_step[..]),
            contact_begin: ManagedSlice::Borrowed(&mut self.contact_begin[..]),
            contact_end: ManagedSlice::Borrowed(&mut self.contact_end[..]),
            contact_hit: ManagedSlice::Borrowed(&mut self.contact_hit[..]),
            sensor_begin: ManagedSlice::Borrowed(&mut self.sensor_begin[..]),
            sensor_end: ManagedSlice::Borrowed(&mut self.sensor_end[..]),
            joint_broke: ManagedSlice::Borrowed(&mut self.joint_broke[..]),
            chain_nodes: ManagedSlice::Borrowed(&mut self.chain_nodes[..]),
            shape_slots: ManagedSlice::Borrowed(&mut self.shape_slots[..]),
        }
    }
}

impl<
        const BODIES: usize,
        const CONTACTS: usize,
        const JOINTS: usize,
        const CALLBACKS: usize,
        const EVENTS: usize,
        const CHAIN_VERTICES: usize,
        const SHAPES: usize,
    > Default for WorldBuffers<BODIES, CONTACTS, JOINTS, CALLBACKS, EVENTS, CHAIN_VERTICES, SHAPES>
{
    fn default() -> Self {
        Self::new()
    }
}
