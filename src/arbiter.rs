//! [`Arbiter`]: the state of the collision between two bodies.
//!
//! The engine keeps one arbiter per pair of bodies that touch, sorted by the pair's
//! canonical key, from step to step. It carries the manual's five states, the
//! contact manifold, the friction and restitution used for this pair (which a
//! `pre_solve` handler may change), and the impulses the solver accumulated, which
//! warm-start the next step and tell a game how hard the bodies hit.
//!
//! # Lifecycle (per step, for each pair)
//! * touching and `NoCollision` or `Separated` → `FirstContact`, the handler's
//!   `begin` runs; it returns `true` → `Contact`, `false` → `Ignoring`;
//! * touching and `Contact` → stays; `pre_solve` decides whether it is solved this
//!   step; touching and `Ignoring` → stays ignored, no callbacks;
//! * not touching and `Contact` or `Ignoring` → `Separated`, and `end` runs (so
//!   `begin` and `end` always come in pairs, as in Chipmunk);
//! * an arbiter is kept for [`WorldDef::arbiter_persistence`] steps after its bodies
//!   stopped touching, counting the step they separated (the manual's
//!   `increaseStepCount`), so a resting contact that flickers keeps its accumulated
//!   impulses; then it is dropped.
//!
//! "Touching" means the narrow phase found at least one contact point within the
//! speculative distance ([`SPECULATIVE_DISTANCE`](crate::limits::SPECULATIVE_DISTANCE),
//! 2 cm) at the start of the step: the same at every speed, so `begin` fires for
//! a pair only once its shapes are that close, never for a fast body that is
//! merely heading their way or passing beside, and `end` once they are farther
//! apart. A body fast enough to cross that distance and more in one step is
//! stopped at the first surface on its way by continuous collision
//! ([`crate::continuous`]) and touches on the next step, so `begin` still comes
//! before anything is resolved.
//!
//! # Sensor pairs
//! A pair with a sensor ([`BodyDef::sensor`](crate::BodyDef::sensor)) has an
//! arbiter too, never solved and with no callbacks: it is in the `Contact`
//! state while the shapes overlap (judged on the poses at the end of the
//! step), with no contact points, and is dropped when they stop. Its events
//! are the sensor events ([`crate::events`]); [`Arbiter::is_touching`] is
//! false for it.
//!
//! [`WorldDef::arbiter_persistence`]: crate::WorldDef::arbiter_persistence

use managed::ManagedSlice;

use crate::body::BodyHandle;
use crate::error::Error;
use crate::limits::{check_friction, check_restitution};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Vector2};

/// The manual's arbiter states.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum ArbiterState {
    /// No collision detected yet (a new arbiter).
    #[default]
    NoCollision = 0,
    /// The bodies collided on this step (seen only inside `begin`).
    FirstContact = 1,
    /// `begin` returned false: not resolved, no callbacks, until they separate.
    Ignoring = 2,
    /// Touching and resolved.
    Contact = 3,
    /// They stopped touching; kept for a few steps.
    Separated = 4,
}

impl ArbiterState {
    /// The state with this discriminant (snapshot decoding).
    pub(crate) fn from_u8(v: u8) -> Option<Self> {
        Some(match v {
            0 => Self::NoCollision,
            1 => Self::FirstContact,
            2 => Self::Ignoring,
            3 => Self::Contact,
            4 => Self::Separated,
            _ => return None,
        })
    }
}

/// One contact point of an arbiter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContactPoint {
    /// World position (m), midway between the surfaces, at the start of the step.
    pub point: Vector2,
    /// Separation along the normal at the start of the step (m; negative = overlap).
    pub separation: Scalar,
    /// Feature id: stays the same while the same features touch.
    pub id: u16,
    /// Accumulated normal impulse (N·s) of the last sub-step, used to warm-start.
    pub normal_impulse: Scalar,
    /// Accumulated friction impulse (N·s) of the last sub-step.
    pub tangent_impulse: Scalar,
    /// Normal impulse applied over the whole step (N·s): how hard they pressed.
    pub total_normal_impulse: Scalar,
    /// Largest single normal impulse in the step (N·s), e.g. for impact sounds.
    pub max_normal_impulse: Scalar,
    // Offsets of the point from each centre of mass when the manifold was
    // computed (derived, kept with it while it is recycled; in the snapshot
    // then, see `collision::recycle`).
    pub(crate) anchor_a: Vector2,
    pub(crate) anchor_b: Vector2,
    // The approach speed along the normal at the start of the step, Q16.16
    // (derived, per step, for the contact hit event; in what was padding).
    pub(crate) approach: i32,
    // The point was carried on from an earlier step's manifold (recycled)
    // rather than computed in this one (derived, per step, set by the
    // lifecycle before the solve reads it: `contact::prepare` gives only a
    // computed manifold the 2×2 block; in what was padding).
    pub(crate) recycled: bool,
    /// The separation when the manifold was last computed (m): a recycled
    /// point's separation is this plus how far its anchored points moved
    /// apart along the normal since. State while the manifold is kept.
    pub(crate) base_separation: Scalar,
}

/// The collision state of a pair of bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Arbiter {
    pub(crate) body_a: BodyHandle,
    pub(crate) body_b: BodyHandle,
    pub(crate) level_a: u32,
    pub(crate) level_b: u32,
    pub(crate) state: ArbiterState,
    /// The steps since separation (bits 0–11, see [`Arbiter::steps_separated`])
    /// and the chain link of a pair with a chain (bits 12–31, 0 otherwise;
    /// part of the key), packed into one word. State:
    /// in the snapshot and the hash (the link where a pair has a chain).
    pub(crate) steps_and_link: u32,
    pub(crate) normal: Vector2,
    pub(crate) points: [ContactPoint; 2],
    pub(crate) count: u8,
    pub(crate) friction: Scalar,
    pub(crate) restitution: Scalar,
    /// Solve this step (derived: set by the lifecycle and `pre_solve`).
    pub(crate) solve: bool,
    /// Bit 0: the bodies touched at the end of the last step (see
    /// [`crate::events`]; for a sensor pair unused, its `Contact` state
    /// means overlapping). Bits 1–3 and 4–6: the index of the shape on body
    /// A and on body B (0 for a body's first shape; part of the key, see
    /// [`Arbiter::key`]). Bit 7: the kept manifold is valid. One byte. State:
    /// in the snapshot and the hash (the shape indices where any is not 0).
    pub(crate) flags: u8,
    /// Body A's and body B's rotations when the manifold was last computed
    /// (valid while [`RECYCLE_FLAG`] is set; with the normal, the points'
    /// ids, anchors and base separations, the kept manifold, which is state:
    /// in the snapshot and the hash while the world recycles manifolds).
    pub(crate) rot_a0: Rot,
    pub(crate) rot_b0: Rot,
}

/// [`Arbiter::flags`]: the manifold cache (`rot_a0`, `rot_b0`, the points'
/// anchors and base separations) is valid.
pub(crate) const RECYCLE_FLAG: u8 = 1 << 7;

/// [`Arbiter::flags`]: touching at the end of the last step.
const TOUCHING_FLAG: u8 = 1;
/// Bits of a shape index in [`Arbiter::flags`].
const SHAPE_BITS: u32 = 3;
/// The most shapes a body can have that arbiters can name: 8 (indices 0–7).
pub const MAX_SHAPE_INDEX: u32 = (1 << SHAPE_BITS) - 1;

/// An arbiter's sub-key (see [`Arbiter::key`]) from its chain link and the
/// shape indices on the lower-slot and the higher-slot body.
#[inline]
pub(crate) const fn sub_key(link: u32, lo: u32, hi: u32) -> u32 {
    (link << (2 * SHAPE_BITS)) | ((lo & MAX_SHAPE_INDEX) << SHAPE_BITS) | (hi & MAX_SHAPE_INDEX)
}

/// Bits of [`Arbiter::steps_and_link`] that count the steps since separation.
const STEP_BITS: u32 = 12;
/// The most steps since separation an arbiter counts (4,095; the persistence
/// is at most 256).
pub const MAX_STEPS_SEPARATED: u32 = (1 << STEP_BITS) - 1;
/// The highest chain link an arbiter can name (2^20 − 1, more than a chain
/// of [`MAX_CHAIN_VERTICES`](crate::geometry::MAX_CHAIN_VERTICES) points has).
pub const MAX_LINK: u32 = u32::MAX >> STEP_BITS;

impl Arbiter {
    pub(crate) const EMPTY: Self = Self {
        body_a: BodyHandle::NULL,
        body_b: BodyHandle::NULL,
        level_a: 0,
        level_b: 0,
        state: ArbiterState::NoCollision,
        steps_and_link: 0,
        normal: Vector2::ZERO,
        points: [ContactPoint {
            point: Vector2::ZERO,
            separation: ZERO,
            id: 0,
            normal_impulse: ZERO,
            tangent_impulse: ZERO,
            total_normal_impulse: ZERO,
            max_normal_impulse: ZERO,
            anchor_a: Vector2::ZERO,
            anchor_b: Vector2::ZERO,
            approach: 0,
            recycled: false,
            base_separation: ZERO,
        }; 2],
        count: 0,
        friction: ZERO,
        restitution: ZERO,
        solve: false,
        flags: 0,
        rot_a0: Rot::IDENTITY,
        rot_b0: Rot::IDENTITY,
    };

    /// The canonical key of the arbiter: (lower body slot, higher body slot,
    /// sub-key). The sub-key is `link << 6 | lower body's shape << 3 |
    /// higher body's shape`: the chain link (0 for a pair without a chain,
    /// at most [`MAX_LINK`], 20 bits) then the two shape indices (at most
    /// [`MAX_SHAPE_INDEX`], 3 bits each), 26 bits in all. A pair of
    /// one-shape bodies has sub-key 0 and a chain pair its link shifted,
    /// so their order is the order they had before bodies had several shapes.
    #[inline]
    pub(crate) fn key(&self) -> (u32, u32, u32) {
        let (a, b) = self.pair();
        let (sa, sb) = (self.shape_a(), self.shape_b());
        let (lo, hi) = if self.body_a.index() <= self.body_b.index() { (sa, sb) } else { (sb, sa) };
        (a, b, sub_key(self.link(), lo, hi))
    }

    /// The index of the shape on body A this arbiter is for (0 for a body's
    /// first shape).
    #[inline]
    #[must_use]
    pub fn shape_a(&self) -> u32 {
        u32::from(self.flags >> 1) & MAX_SHAPE_INDEX
    }

    /// The index of the shape on body B this arbiter is for.
    #[inline]
    #[must_use]
    pub fn shape_b(&self) -> u32 {
        u32::from(self.flags >> (1 + SHAPE_BITS)) & MAX_SHAPE_INDEX
    }

    /// The shape indices on bodies A and B as bytes (each at most 7).
    #[inline]
    pub(crate) fn shape_bytes(&self) -> (u8, u8) {
        let mask = MAX_SHAPE_INDEX as u8;
        ((self.flags >> 1) & mask, (self.flags >> (1 + SHAPE_BITS)) & mask)
    }

    /// Sets the shape indices on bodies A and B (each at most
    /// [`MAX_SHAPE_INDEX`], masked).
    #[inline]
    pub(crate) fn set_shapes(&mut self, a: u32, b: u32) {
        let (a, b) = ((a & MAX_SHAPE_INDEX) as u8, (b & MAX_SHAPE_INDEX) as u8);
        self.flags = (self.flags & TOUCHING_FLAG) | (a << 1) | (b << (1 + SHAPE_BITS));
    }

    /// Whether the manifold cache (`rot_a0`, `rot_b0`, the normal, the
    /// points' ids, anchors and base separations) holds the pair's last
    /// computed manifold (see `collision::recycle`).
    #[inline]
    pub(crate) fn has_manifold(&self) -> bool {
        self.flags & RECYCLE_FLAG != 0
    }

    /// Marks the manifold cache valid or not.
    #[inline]
    pub(crate) fn set_has_manifold(&mut self, on: bool) {
        self.flags = (self.flags & !RECYCLE_FLAG) | if on { RECYCLE_FLAG } else { 0 };
    }

    /// Sets whether the bodies touched at the end of the step.
    #[inline]
    pub(crate) fn set_touching(&mut self, on: bool) {
        self.flags = (self.flags & !TOUCHING_FLAG) | u8::from(on);
    }

    /// The body pair: (lower body slot, higher body slot).
    #[inline]
    pub(crate) fn pair(&self) -> (u32, u32) {
        let (a, b) = (self.body_a.index(), self.body_b.index());
        if a <= b {
            (a, b)
        } else {
            (b, a)
        }
    }

    /// For a body against a chain, the chain's link this arbiter is for
    /// (link `i` runs from the chain's point `i` to the next); 0 otherwise.
    #[inline]
    #[must_use]
    pub fn link(&self) -> u32 {
        self.steps_and_link >> STEP_BITS
    }

    /// Sets the chain link (at most [`MAX_LINK`]) and the steps since
    /// separation (at most [`MAX_STEPS_SEPARATED`]), saturating.
    #[inline]
    pub(crate) fn set_steps_and_link(&mut self, steps: u32, link: u32) {
        self.steps_and_link = (link.min(MAX_LINK) << STEP_BITS) | steps.min(MAX_STEPS_SEPARATED);
    }

    /// The first body. Bodies are ordered as in the manual: circles before
    /// polygons, then by slot. The normal points from A to B.
    #[inline]
    #[must_use]
    pub fn body_a(&self) -> BodyHandle {
        self.body_a
    }

    /// The second body.
    #[inline]
    #[must_use]
    pub fn body_b(&self) -> BodyHandle {
        self.body_b
    }

    /// Both bodies, `(a, b)`.
    #[inline]
    #[must_use]
    pub fn bodies(&self) -> (BodyHandle, BodyHandle) {
        (self.body_a, self.body_b)
    }

    /// The collision levels of bodies A and B.
    #[inline]
    #[must_use]
    pub fn levels(&self) -> (u32, u32) {
        (self.level_a, self.level_b)
    }

    /// The body with collision level `level` and the other one, e.g. to tell the
    /// player from the bullet in a handler registered for both levels. `None` when
    /// neither body has that level.
    #[must_use]
    pub fn bodies_by_level(&self, level: u32) -> Option<(BodyHandle, BodyHandle)> {
        if self.level_a == level {
            Some((self.body_a, self.body_b))
        } else if self.level_b == level {
            Some((self.body_b, self.body_a))
        } else {
            None
        }
    }

    /// The state.
    #[inline]
    #[must_use]
    pub fn state(&self) -> ArbiterState {
        self.state
    }

    /// True while in the first step of a collision (inside `begin`).
    #[inline]
    #[must_use]
    pub fn is_first_contact(&self) -> bool {
        self.state == ArbiterState::FirstContact
    }

    /// True when the bodies touched at the end of the last step: a contact
    /// point at most [`TOUCH_DISTANCE`](crate::events::TOUCH_DISTANCE) apart
    /// (not merely within the speculative distance). What the contact begin
    /// and end events report (see [`crate::events`]); false for a sensor pair.
    #[inline]
    #[must_use]
    pub fn is_touching(&self) -> bool {
        self.flags & TOUCHING_FLAG != 0
    }

    /// Unit normal from A to B.
    #[inline]
    #[must_use]
    pub fn normal(&self) -> Vector2 {
        self.normal
    }

    /// The contact points (none once separated).
    #[inline]
    #[must_use]
    pub fn contact_points(&self) -> &[ContactPoint] {
        self.points.get(..usize::from(self.count)).unwrap_or(&[])
    }

    /// Friction coefficient used for this pair.
    #[inline]
    #[must_use]
    pub fn friction(&self) -> Scalar {
        self.friction
    }

    /// Changes the friction for this pair; from `pre_solve`, it applies to this
    /// step. The range is a body's: [0, [`MAX_FRICTION`](crate::limits::MAX_FRICTION)]
    /// (100), checked by the same function as [`World::add_body`](crate::World::add_body)
    /// and [`World::restore`](crate::World::restore).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"friction"` outside that range; the arbiter is
    /// unchanged.
    pub fn set_friction(&mut self, mu: Scalar) -> Result<(), Error> {
        check_friction(mu)?;
        self.friction = mu;
        Ok(())
    }

    /// Restitution used for this pair.
    #[inline]
    #[must_use]
    pub fn restitution(&self) -> Scalar {
        self.restitution
    }

    /// Changes the restitution for this pair; from `pre_solve`, it applies to
    /// this step. The range is a body's: [0, 1], checked by the same function as
    /// [`World::add_body`](crate::World::add_body) and
    /// [`World::restore`](crate::World::restore).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] with `"restitution"` outside [0, 1]; the arbiter is
    /// unchanged.
    pub fn set_restitution(&mut self, e: Scalar) -> Result<(), Error> {
        check_restitution(e)?;
        self.restitution = e;
        Ok(())
    }

    /// Total normal impulse over the last step, summed over the contact points
    /// (N·s): what a game uses to compute damage.
    #[must_use]
    pub fn total_normal_impulse(&self) -> Scalar {
        self.contact_points().iter().fold(ZERO, |acc, p| acc + p.total_normal_impulse)
    }

    /// Steps since the bodies stopped touching (0 while touching).
    #[inline]
    #[must_use]
    pub fn steps_separated(&self) -> u32 {
        self.steps_and_link & MAX_STEPS_SEPARATED
    }

    /// The manual's `increaseStepCount`: adds one to the steps since separation
    /// (saturating at [`MAX_STEPS_SEPARATED`]) and returns the new count. The
    /// engine calls it for arbiters that are not touching; a custom lifecycle
    /// may too.
    pub fn increase_step_count(&mut self) -> u32 {
        self.set_steps_and_link(self.steps_separated().saturating_add(1), self.link());
        self.steps_separated()
    }

    /// Sets the steps since separation to 0.
    #[inline]
    pub(crate) fn reset_steps_separated(&mut self) {
        self.steps_and_link &= !MAX_STEPS_SEPARATED;
    }
}

/// The friction of a pair: the geometric mean √(μa·μb), so a frictionless body
/// slides on anything (Box2D's rule).
#[must_use]
pub fn mix_friction(a: Scalar, b: Scalar) -> Scalar {
    // Equal coefficients, the common case, mix to themselves without a root.
    if a == b {
        return a.max(ZERO);
    }
    (a * b).sqrt()
}

/// The restitution of a pair: the larger of the two, so a bouncy ball bounces on
/// a dead floor (Box2D's rule).
#[must_use]
pub fn mix_restitution(a: Scalar, b: Scalar) -> Scalar {
    a.max(b)
}

/// The world's arbiters: the live ones, sorted by pair key, in one buffer, and a
/// second buffer of the same length that the next step's merge writes into
/// before the two swap (so a step never copies the array back).
pub(crate) struct ArbiterStore<'a> {
    live: ManagedSlice<'a, Arbiter>,
    next: ManagedSlice<'a, Arbiter>,
    count: usize,
    /// The live arbiters are where the solver's last constraint build found
    /// them (see [`ArbiterStore::built`]). Not state: a cache's validity.
    built: bool,
}

impl<'a> ArbiterStore<'a> {
    /// An empty store on two buffers of equal length.
    pub(crate) fn new(live: ManagedSlice<'a, Arbiter>, next: ManagedSlice<'a, Arbiter>) -> Self {
        Self { live, next, count: 0, built: false }
    }

    /// How many arbiters fit.
    pub(crate) fn capacity(&self) -> usize {
        self.live.len().min(self.next.len())
    }

    /// How many are live.
    pub(crate) fn len(&self) -> usize {
        self.count
    }

    /// The live arbiters, in key order.
    pub(crate) fn live(&self) -> &[Arbiter] {
        self.live.get(..self.count).unwrap_or(&[])
    }

    /// The live arbiters, in key order, to update in place.
    pub(crate) fn live_mut(&mut self) -> &mut [Arbiter] {
        let n = self.count;
        self.live.get_mut(..n).unwrap_or(&mut [])
    }

    /// The live arbiters and the buffer the next set is written into.
    pub(crate) fn live_and_next(&mut self) -> (&[Arbiter], &mut [Arbiter]) {
        let n = self.count;
        (self.live.get(..n).unwrap_or(&[]), &mut self.next)
    }

    /// Makes the first `count` arbiters written into the next buffer the live set.
    pub(crate) fn swap_in_next(&mut self, count: usize) {
        core::mem::swap(&mut self.live, &mut self.next);
        self.count = count.min(self.live.len());
        self.built = false;
    }

    /// Whether each live arbiter is at the position it had when the solver
    /// last built its constraints (the solver's per-arbiter scratch then
    /// still describes it: see `solver::colour::build`). Every change of the
    /// positions clears it (a merge, a removal, a restore); only
    /// [`ArbiterStore::mark_built`] sets it.
    pub(crate) fn built(&self) -> bool {
        self.built
    }

    /// Notes that the solver has just built the constraints of the live
    /// arbiters, in their present positions.
    pub(crate) fn mark_built(&mut self) {
        self.built = true;
    }

    /// Keeps the live arbiters for which `keep` returns true, in order.
    pub(crate) fn retain(&mut self, mut keep: impl FnMut(&Arbiter) -> bool) {
        self.retain_mut(|arb| keep(arb));
    }

    /// As [`ArbiterStore::retain`], `keep` also changing the arbiters it keeps
    /// (without changing their order).
    pub(crate) fn retain_mut(&mut self, mut keep: impl FnMut(&mut Arbiter) -> bool) {
        let mut out = 0usize;
        for k in 0..self.count {
            let Some(mut arb) = self.live.get(k).copied() else { break };
            if !keep(&mut arb) {
                continue;
            }
            if let Some(slot) = self.live.get_mut(out) {
                *slot = arb;
            }
            out = out.saturating_add(1);
        }
        if out != self.count {
            self.built = false;
        }
        self.count = out;
    }

    /// Empties the live set (a restore refills it with [`ArbiterStore::push`]).
    pub(crate) fn clear(&mut self) {
        self.count = 0;
        self.built = false;
    }

    /// Appends an arbiter to the live set, which must stay in key order (a
    /// restore checks that first); false, changing nothing, when full.
    pub(crate) fn push(&mut self, arb: Arbiter) -> bool {
        if self.count >= self.capacity() {
            return false;
        }
        match self.live.get_mut(self.count) {
            Some(slot) => {
                *slot = arb;
                self.count = self.count.saturating_add(1);
                self.built = false;
                true
            }
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_arbiter_is_304_bytes_and_packs_its_link_with_the_step_count() {
        // 256 before manifolds were kept: the two rotations and two base
        // separations add 48.
        assert_eq!(core::mem::size_of::<Arbiter>(), 304);
        let mut a = Arbiter::EMPTY;
        a.set_steps_and_link(3, MAX_LINK);
        assert_eq!((a.steps_separated(), a.link()), (3, MAX_LINK));
        assert_eq!(a.increase_step_count(), 4);
        a.reset_steps_separated();
        assert_eq!((a.steps_separated(), a.link()), (0, MAX_LINK));
        a.set_steps_and_link(MAX_STEPS_SEPARATED, 7);
        assert_eq!(a.increase_step_count(), MAX_STEPS_SEPARATED, "saturates");
        assert_eq!(a.link(), 7);
    }

    #[test]
    fn the_flags_byte_holds_touching_and_both_shape_indices() {
        let mut a = Arbiter::EMPTY;
        a.body_a = BodyHandle::from_parts(5, 0);
        a.body_b = BodyHandle::from_parts(2, 0);
        a.set_touching(true);
        a.set_shapes(6, 1);
        a.set_steps_and_link(9, MAX_LINK);
        assert!(a.is_touching());
        assert_eq!((a.shape_a(), a.shape_b()), (6, 1));
        // Body B has the lower slot: its shape comes first in the sub-key.
        assert_eq!(a.key(), (2, 5, (MAX_LINK << 6) | (1 << 3) | 6));
        assert!(a.key().2 < (1 << 26));
        a.set_touching(false);
        assert_eq!((a.is_touching(), a.shape_a(), a.shape_b()), (false, 6, 1));
        // A one-shape pair's key is its chain link shifted, order kept.
        let mut b = Arbiter::EMPTY;
        b.body_a = BodyHandle::from_parts(2, 0);
        b.body_b = BodyHandle::from_parts(5, 0);
        b.set_steps_and_link(0, 3);
        assert_eq!(b.key(), (2, 5, 3 << 6));
    }
}
