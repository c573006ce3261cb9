//! Collision handlers, keyed by collision levels, and post-step callbacks.
//!
//! A [`CollisionHandler`] hears about the collisions between bodies of two
//! collision levels (an unordered pair: a handler for (1, 2) also hears (2, 1)).
//! Pairs without a registered handler go to the default handler, which resolves
//! everything unless the game replaces it
//! ([`World::set_default_collision_handler`](crate::World::set_default_collision_handler)).
//!
//! # When and in what order handlers run
//! All callbacks run on the thread calling `step`, one at a time, in the canonical
//! pair order (by the lower body slot, then the higher): during the narrow phase,
//! `begin`, `pre_solve` and `end` as each pair's state changes; after the solver,
//! `post_solve` for every solved pair in the same order; after the step, the
//! post-step callbacks in the order they were registered, then those they
//! queued, round after round until none is left (see
//! [`CallbackContext::add_post_step_callback`]). The order depends only on the
//! simulation state, never on capacities or addresses.
//!
//! # The post-step queue is never state
//! Every call that can queue a post-step callback drains the queue before it
//! returns: `step` runs it to exhaustion (bounded by [`MAX_POST_STEP_ROUNDS`]),
//! and a game's `remove_body` between steps runs the callbacks its `end`
//! handlers queued before it returns. Between steps the queue is empty, so a
//! snapshot has nothing to miss and `restore` nothing to lose. Its capacity is
//! [`Capacities::post_step_callbacks`](crate::Capacities::post_step_callbacks);
//! a refusal is an `Err` to the callback that asked and a count in the
//! [`StepReport`](crate::StepReport).
//!
//! Callbacks are function pointers in a [`FnHandler`], closures in a
//! [`ClosureHandler`] (borrowed, or boxed with `alloc`), or any type that
//! implements [`CollisionHandler`]. What a game only needs to learn after the
//! step (what began, ended, hit, entered a sensor) it reads from the event
//! lists instead ([`crate::events`]), with no callback at all. Sensor pairs
//! never reach a handler.
//!
//! Handlers cannot change the world during the step: they see the arbiter and the
//! bodies (read-only), and register post-step callbacks through the
//! [`CallbackContext`] to remove bodies or make other changes safely afterwards.
//! Removing a body during a step is impossible by construction.

use managed::ManagedSlice;

use crate::hook::Hook;

use crate::arbiter::Arbiter;
use crate::arena::Arena;
use crate::body::{Body, BodyHandle};
use crate::error::Error;
use crate::world::World;

/// Most collision handlers (level pairs) a world can register.
pub const MAX_COLLISION_HANDLERS: usize = 16;

/// The post-step queue capacity of [`WorldBuffers`](crate::WorldBuffers)
/// unless its `CALLBACKS` parameter says otherwise.
pub const DEFAULT_POST_STEP_CALLBACKS: usize = 64;

/// Most rounds of post-step callbacks one drain runs: the callbacks queued
/// when the drain starts are round 1, those they queue round 2, and so on. A
/// bound so that a callback that always queues another cannot stall the step;
/// a game reaching it has such a loop (or a chain of removals 256 deep).
pub const MAX_POST_STEP_ROUNDS: u32 = 256;

/// A post-step callback: runs once after the step with the world and its key.
///
/// # If it panics
/// With `std` and the panic guard on (the default), a panic restores the world
/// to its state before the step and then unwinds out of
/// [`World::step`](crate::World::step). Without the guard (`no_std`, or
/// [`World::set_panic_guard`](crate::World::set_panic_guard)`(false)`) it unwinds
/// with the world half-stepped: the step itself is complete (counter advanced, broken joints
/// removed), the callbacks before this one ran and the ones after it are dropped from the queue.
/// The world stays memory-safe and usable, but its state
/// is not one any uninterrupted run reaches. The way back is the snapshot taken
/// before the step: [`World::restore`](crate::World::restore) it (a game that
/// catches panics with `std::panic::catch_unwind` should restore before it
/// steps again).
pub type PostStepFn = for<'w> fn(&mut World<'w>, u64);

/// A game's reaction to collisions. Every method has a default that resolves
/// the collision, so implement only what you need.
///
/// # If it panics
/// With `std` and the panic guard on (the default), a panic restores the world
/// to its state before the step and then unwinds out of
/// [`World::step`](crate::World::step). Without the guard (`no_std`, or
/// [`World::set_panic_guard`](crate::World::set_panic_guard)`(false)`) it unwinds
/// with the world half-stepped: a panic in `begin`, `pre_solve` or `end` leaves some arbiters of
/// this step updated and others not, before the solver; one in `post_solve` leaves the bodies moved
/// and the impulses stored, with the step counter not advanced and the post-step queue not run. The
/// world stays memory-safe and usable, but its state
/// is not one any uninterrupted run reaches. The way back is the snapshot taken
/// before the step: [`World::restore`](crate::World::restore) it (a game that
/// catches panics with `std::panic::catch_unwind` should restore before it
/// steps again).
pub trait CollisionHandler {
    /// The bodies started touching. Return `false` to ignore this collision (no
    /// resolution, no further callbacks) until they separate.
    fn begin(&mut self, arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        let _ = (arbiter, ctx);
        true
    }

    /// Before this step's resolution. Return `false` to skip it for this step
    /// only. May change the arbiter's friction or restitution for this step.
    fn pre_solve(&mut self, arbiter: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        let _ = (arbiter, ctx);
        true
    }

    /// After resolution: the impulses of this step are in the arbiter.
    fn post_solve(&mut self, arbiter: &Arbiter, ctx: &mut CallbackContext<'_>) {
        let _ = (arbiter, ctx);
    }

    /// The bodies stopped touching (also called when one of them is removed while
    /// touching, so `begin` and `end` always pair up).
    fn end(&mut self, arbiter: &Arbiter, ctx: &mut CallbackContext<'_>) {
        let _ = (arbiter, ctx);
    }
}

/// The handler that resolves everything (the manual's default).
#[derive(Clone, Copy, Debug, Default)]
pub struct ResolveAll;

impl CollisionHandler for ResolveAll {}

/// Signature of a `begin` or `pre_solve` function.
pub type ArbiterFilterFn = fn(&mut Arbiter, &mut CallbackContext<'_>) -> bool;
/// Signature of a `post_solve` or `end` function.
pub type ArbiterEventFn = fn(&Arbiter, &mut CallbackContext<'_>);

/// A handler made of plain functions, any of them absent (the manual's
/// `addCollisionHandler(level1, level2, begin, preSolve, postSolve, end)` with
/// `NULL`s). Needs no allocation and no borrow.
#[derive(Clone, Copy, Debug, Default)]
pub struct FnHandler {
    /// `begin`, or resolve.
    pub begin: Option<ArbiterFilterFn>,
    /// `pre_solve`, or resolve.
    pub pre_solve: Option<ArbiterFilterFn>,
    /// `post_solve`, or nothing.
    pub post_solve: Option<ArbiterEventFn>,
    /// `end`, or nothing.
    pub end: Option<ArbiterEventFn>,
}

impl CollisionHandler for FnHandler {
    fn begin(&mut self, a: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        self.begin.is_none_or(|f| f(a, ctx))
    }
    fn pre_solve(&mut self, a: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        self.pre_solve.is_none_or(|f| f(a, ctx))
    }
    fn post_solve(&mut self, a: &Arbiter, ctx: &mut CallbackContext<'_>) {
        if let Some(f) = self.post_solve {
            f(a, ctx);
        }
    }
    fn end(&mut self, a: &Arbiter, ctx: &mut CallbackContext<'_>) {
        if let Some(f) = self.end {
            f(a, ctx);
        }
    }
}

/// A `begin` or `pre_solve` closure of a [`ClosureHandler`]: borrowed for
/// the world's lifetime, or (with `alloc`) boxed.
pub type FilterHook<'a> = Hook<'a, dyn FnMut(&mut Arbiter, &mut CallbackContext<'_>) -> bool + Send + 'a>;

/// A `post_solve` or `end` closure of a [`ClosureHandler`].
pub type EventHook<'a> = Hook<'a, dyn FnMut(&Arbiter, &mut CallbackContext<'_>) + Send + 'a>;

/// [`FnHandler`] with closures: each callback optional, each a closure that
/// may capture the game's state. With `alloc`, box them
/// (`Hook::Boxed(Box::new(|arb, ctx| ...))`) and the handler converts into a
/// [`Handler`] with `.into()`; without, borrow them
/// (`Hook::Borrowed(&mut closure)`) and register the handler with
/// [`Handler::borrowed`]. A missing `begin` or `pre_solve` means "resolve".
///
/// Since the event lists ([`crate::events`]) tell a game after the step what
/// began, ended and hit, closures are for what must happen inside the step:
/// deciding in `pre_solve` whether a pair is solved (a one-way platform),
/// or changing its friction.
#[derive(Default)]
pub struct ClosureHandler<'a> {
    /// Called when the pair first touches; false ignores it until it separates.
    pub begin: Option<FilterHook<'a>>,
    /// Called every step while touching; false skips the solve this step.
    pub pre_solve: Option<FilterHook<'a>>,
    /// Called after the solve for every solved pair.
    pub post_solve: Option<EventHook<'a>>,
    /// Called when the pair stops touching.
    pub end: Option<EventHook<'a>>,
}

impl core::fmt::Debug for ClosureHandler<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ClosureHandler")
            .field("begin", &self.begin.is_some())
            .field("pre_solve", &self.pre_solve.is_some())
            .field("post_solve", &self.post_solve.is_some())
            .field("end", &self.end.is_some())
            .finish()
    }
}

impl CollisionHandler for ClosureHandler<'_> {
    fn begin(&mut self, a: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        self.begin.as_mut().is_none_or(|f| f(a, ctx))
    }

    fn pre_solve(&mut self, a: &mut Arbiter, ctx: &mut CallbackContext<'_>) -> bool {
        self.pre_solve.as_mut().is_none_or(|f| f(a, ctx))
    }

    fn post_solve(&mut self, a: &Arbiter, ctx: &mut CallbackContext<'_>) {
        if let Some(f) = self.post_solve.as_mut() {
            f(a, ctx);
        }
    }

    fn end(&mut self, a: &Arbiter, ctx: &mut CallbackContext<'_>) {
        if let Some(f) = self.end.as_mut() {
            f(a, ctx);
        }
    }
}

#[cfg(feature = "alloc")]
impl<'a> From<ClosureHandler<'a>> for Handler<'a> {
    /// Boxes the closure handler (the world owns it).
    fn from(h: ClosureHandler<'a>) -> Self {
        Self::Custom(Hook::Boxed(alloc::boxed::Box::new(h)))
    }
}

/// A collision handler stored in a world.
pub enum Handler<'a> {
    /// Plain functions.
    Functions(FnHandler),
    /// A game's handler object, borrowed or (with `alloc`) boxed.
    Custom(Hook<'a, dyn CollisionHandler + Send + 'a>),
}

impl<'a> Handler<'a> {
    /// A game's handler, borrowed for the world's lifetime.
    pub fn borrowed(h: &'a mut (dyn CollisionHandler + Send + 'a)) -> Self {
        Self::Custom(Hook::Borrowed(h))
    }

    /// A game's handler, owned by the world.
    #[cfg(feature = "alloc")]
    pub fn boxed(h: alloc::boxed::Box<dyn CollisionHandler + Send + 'a>) -> Self {
        Self::Custom(Hook::Boxed(h))
    }

    /// The handler as a trait object.
    pub fn as_dyn_mut(&mut self) -> &mut (dyn CollisionHandler + Send + 'a) {
        match self {
            Self::Functions(f) => f,
            Self::Custom(h) => &mut **h,
        }
    }
}

impl From<FnHandler> for Handler<'_> {
    fn from(f: FnHandler) -> Self {
        Self::Functions(f)
    }
}

/// Handlers by unordered level pair, plus the default.
pub(crate) struct HandlerTable<'a> {
    entries: heapless::Vec<((u32, u32), Handler<'a>), MAX_COLLISION_HANDLERS>,
    default: Option<Handler<'a>>,
}

fn level_key(a: u32, b: u32) -> (u32, u32) {
    if a <= b {
        (a, b)
    } else {
        (b, a)
    }
}

impl<'a> HandlerTable<'a> {
    pub(crate) const fn new() -> Self {
        Self { entries: heapless::Vec::new(), default: None }
    }

    pub(crate) fn add(&mut self, a: u32, b: u32, h: Handler<'a>) -> Result<(), Error> {
        let key = level_key(a, b);
        if self.entries.iter().any(|(k, _)| *k == key) {
            return Err(Error::InvalidOperation { what: "a handler is already registered for these levels" });
        }
        self.entries.push((key, h)).map_err(|_| Error::CapacityFull { what: "collision handler" })
    }

    pub(crate) fn remove(&mut self, a: u32, b: u32) -> Option<Handler<'a>> {
        let key = level_key(a, b);
        let i = self.entries.iter().position(|(k, _)| *k == key)?;
        // `remove` (not `swap_remove`) keeps registration order, which lookups rely on.
        Some(self.entries.remove(i).1)
    }

    pub(crate) fn set_default(&mut self, h: Option<Handler<'a>>) -> Option<Handler<'a>> {
        core::mem::replace(&mut self.default, h)
    }

    /// The handler for a level pair: the registered one, else the default, else
    /// `None` (resolve everything, no callbacks).
    pub(crate) fn get(&mut self, a: u32, b: u32) -> Option<&mut (dyn CollisionHandler + Send + 'a)> {
        let key = level_key(a, b);
        let found = self.entries.iter_mut().find(|(k, _)| *k == key).map(|(_, h)| h);
        found.or(self.default.as_mut()).map(Handler::as_dyn_mut)
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.entries.is_empty() && self.default.is_none()
    }
}

/// A queued post-step callback: the function and its key.
pub(crate) type PostStepEntry = (PostStepFn, u64);

fn idle(_: &mut World<'_>, _: u64) {}

/// An unused queue slot (for static buffers).
pub(crate) const EMPTY_POST_STEP: PostStepEntry = (idle, 0);

/// Where the queue stands: pending entries are `slots[head..len]`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct QueueState {
    head: usize,
    len: usize,
    /// Most entries pending at once (diagnostics, for `stats()`).
    pub(crate) peak: usize,
    /// Callbacks refused because the queue was full since the counter was
    /// last taken (diagnostics, for the step report).
    pub(crate) refused: u32,
}

/// The queue of post-step callbacks, one per key, in registration order (a
/// FIFO over a fixed slice whose length is the capacity,
/// [`Capacities::post_step_callbacks`](crate::Capacities::post_step_callbacks)).
///
/// It is empty whenever the game can snapshot: the step drains it before it
/// returns, and so does a `remove_body` called between steps (see
/// [`CallbackContext::add_post_step_callback`]). So it is not state, and is in
/// neither the snapshot nor the hash.
pub(crate) struct PostStepQueue<'a> {
    slots: ManagedSlice<'a, PostStepEntry>,
    pub(crate) state: QueueState,
}

impl<'a> PostStepQueue<'a> {
    pub(crate) fn new(slots: ManagedSlice<'a, PostStepEntry>) -> Self {
        Self { slots, state: QueueState::default() }
    }

    /// The queue as callbacks see it.
    pub(crate) fn view(&mut self) -> QueueView<'_> {
        QueueView { slots: &mut self.slots, state: &mut self.state }
    }

    /// Callbacks waiting to run.
    pub(crate) fn pending(&self) -> usize {
        self.state.len.saturating_sub(self.state.head)
    }

    /// The oldest pending callback, taken off the queue.
    pub(crate) fn pop(&mut self) -> Option<PostStepEntry> {
        let QueueState { head, len, .. } = &mut self.state;
        if *head >= *len {
            return None;
        }
        let entry = self.slots.get(*head).copied();
        *head = head.saturating_add(1);
        if *head >= *len {
            (*head, *len) = (0, 0);
        }
        entry
    }

    /// Drops every pending callback; returns how many there were.
    pub(crate) fn clear(&mut self) -> usize {
        let dropped = self.pending();
        (self.state.head, self.state.len) = (0, 0);
        dropped
    }
}

/// A borrowed view of the post-step queue, for [`CallbackContext`].
pub(crate) struct QueueView<'q> {
    slots: &'q mut [PostStepEntry],
    state: &'q mut QueueState,
}

impl QueueView<'_> {
    /// Queues `f(world, key)` unless a pending callback has this key: `Ok(true)`
    /// when queued, `Ok(false)` when already pending.
    fn push(&mut self, f: PostStepFn, key: u64) -> Result<bool, Error> {
        let QueueState { head, len, peak, refused } = &mut *self.state;
        let pending = self.slots.get(*head..*len).unwrap_or(&[]);
        if pending.iter().any(|(_, k)| *k == key) {
            return Ok(false);
        }
        if *len >= self.slots.len() && *head > 0 {
            // Full at the end but run entries at the front: move the pending
            // ones down.
            self.slots.copy_within(*head..*len, 0);
            *len = len.saturating_sub(*head);
            *head = 0;
        }
        let Some(slot) = self.slots.get_mut(*len) else {
            *refused = refused.saturating_add(1);
            return Err(Error::CapacityFull { what: "post-step callback" });
        };
        *slot = (f, key);
        *len = len.saturating_add(1);
        *peak = (*peak).max(len.saturating_sub(*head));
        Ok(true)
    }
}

/// What a collision callback may look at and do during a step.
pub struct CallbackContext<'c> {
    pub(crate) bodies: &'c Arena<'c, Body>,
    pub(crate) post_step: QueueView<'c>,
}

impl CallbackContext<'_> {
    /// A body, read-only (for its collision level, user data, velocity…).
    #[must_use]
    pub fn body(&self, h: BodyHandle) -> Option<&Body> {
        self.bodies.get(h)
    }

    /// Schedules `f(world, key)` to run once after this step (the manual's
    /// `addPostStepCallback`): the safe place to remove bodies. Returns
    /// `Ok(false)` when a callback with this key is already pending (it still
    /// runs once).
    ///
    /// # When it runs
    /// Queued during a step (from `begin`, `pre_solve`, `post_solve` or `end`),
    /// it runs after the step's stages and the joint-break callbacks, in
    /// registration order. Callbacks queued while those run (directly, or by an
    /// `end` handler that a `remove_body` inside them triggers) run in the same
    /// step, after the ones already queued, round after round until the queue is
    /// empty, for at most [`MAX_POST_STEP_ROUNDS`] rounds; whatever is still
    /// queued then is dropped and counted in
    /// [`StepReport::post_step_dropped`](crate::StepReport::post_step_dropped).
    /// Queued outside a step (an `end` handler run by a game's
    /// [`World::remove_body`]), it runs, drained the same way, before that
    /// `remove_body` returns.
    ///
    /// So the queue is always empty when `step` or `remove_body` returns: it is
    /// never state between steps, and a snapshot taken there misses nothing.
    ///
    /// # Errors
    /// [`Error::CapacityFull`] when the queue
    /// ([`Capacities::post_step_callbacks`](crate::Capacities::post_step_callbacks),
    /// or `WorldBuffers`' `CALLBACKS`) is full; the refusal is also counted in
    /// [`StepReport::post_step_refused`](crate::StepReport::post_step_refused).
    /// `begin` runs once per contact, so a game that removes bodies from `begin`
    /// should size the queue for every body that can land in one step.
    pub fn add_post_step_callback(&mut self, f: PostStepFn, key: u64) -> Result<bool, Error> {
        self.post_step.push(f, key)
    }
}
