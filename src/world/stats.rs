//! [`WorldStats`]: a world's capacities, high-water marks and drop counts, so a
//! game can size its stores.
//!
//! Stats are diagnostics, not state: they are in neither the snapshot nor the
//! state hash, `restore` leaves them as they are, and nothing the engine
//! computes reads them.

use super::storage::Capacities;

/// What a world can hold, the most it has held, and what it had to leave out,
/// since it was created ([`World::stats`](crate::World::stats)).
///
/// Size a game's capacities from the peaks of a demanding session, with a
/// margin: a peak equal to its capacity, or any dropped count above zero, means
/// a store was full.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WorldStats {
    /// The capacities of the world's stores.
    pub capacities: Capacities,
    /// Most bodies alive at once (the body slots ever used).
    pub peak_bodies: usize,
    /// Most candidate pairs the broad phase wanted in one step, kept plus
    /// dropped (compare with [`Capacities::contacts`]).
    pub peak_pairs: usize,
    /// Most arbiters alive after a step.
    pub peak_arbiters: usize,
    /// Most contact constraints the solver worked on in one step.
    pub peak_contact_constraints: usize,
    /// Most contact constraints in the solver's overflow in one step: those
    /// whose bodies had no graph colour left (crowded piles), solved one at a
    /// time instead of eight at once.
    pub peak_overflow_constraints: usize,
    /// Most joints alive at once (the joint slots ever used).
    pub peak_joints: usize,
    /// Most post-step callbacks queued at once.
    pub peak_post_step_callbacks: usize,
    /// Candidate pairs dropped by full pair buffers, over all steps.
    pub pairs_dropped: u64,
    /// Pairs skipped by full arbiter stores, over all steps.
    pub arbiters_dropped: u64,
    /// Post-step callbacks refused by a full queue, over all steps and
    /// `remove_body` calls.
    pub post_step_refused: u64,
    /// Post-step callbacks dropped after the round limit, over all drains.
    pub post_step_dropped: u64,
    /// Events dropped by full event lists, over all steps (see
    /// [`crate::events`]).
    pub events_dropped: u64,
}
