//! Event lists: what happened during the last step, read after
//! [`World::step`](crate::World::step) without callbacks.
//!
//! Six lists, each a slice read with its accessor on the world:
//!
//! | list | accessor | when |
//! |---|---|---|
//! | [`ContactBeginEvent`] | [`World::contact_begin_events`](crate::World::contact_begin_events) | two bodies started touching |
//! | [`ContactEndEvent`] | [`World::contact_end_events`](crate::World::contact_end_events) | two bodies stopped touching |
//! | [`ContactHitEvent`] | [`World::contact_hit_events`](crate::World::contact_hit_events) | they started touching faster than the hit threshold |
//! | [`SensorEvent`] | [`World::sensor_begin_events`](crate::World::sensor_begin_events) | a body started overlapping a sensor |
//! | [`SensorEvent`] | [`World::sensor_end_events`](crate::World::sensor_end_events) | a body stopped overlapping a sensor |
//! | [`JointBrokeEvent`] | [`World::joint_broke_events`](crate::World::joint_broke_events) | a breakable joint broke (and was removed) |
//!
//! # Meaning
//! * **Touching** is judged on the poses at the end of the step (what the
//!   game reads after `step`): a pair touches when one of its contact points,
//!   carried along with the bodies' motion during the step, is at most
//!   [`TOUCH_DISTANCE`] (5 mm, Box2D's linear slop) apart. An arbiter within
//!   the speculative distance (2 cm) that has not closed the gap does not
//!   touch, and an arbiter kept for a few steps after separation
//!   ([`WorldDef::arbiter_persistence`](crate::WorldDef::arbiter_persistence))
//!   does not either, so a contact-based "grounded" check built on these
//!   events is right. Pairs whose `begin` handler returned false (the
//!   `Ignoring` state) and sensor pairs never touch; a pair whose `pre_solve`
//!   skips the solve (a one-way platform) does, while its shapes meet.
//! * **Hit** events are Box2D's: on the step a pair begins touching, when the
//!   approach speed (the relative normal velocity at the contact point before
//!   the step's solve) exceeds the world's threshold
//!   ([`World::set_hit_event_threshold`](crate::World::set_hit_event_threshold),
//!   default [`DEFAULT_HIT_EVENT_THRESHOLD`], 1 m/s), with the point of the
//!   fastest approach and the normal.
//! * **Sensor** events report true overlap (a separation below zero, no
//!   speculative margin) of a sensor body and a non-sensor body, judged on
//!   the poses at the end of the step. Sensors never detect sensors.
//! * A pair ended because the arbiter store was full also ends its touch or
//!   overlap (an end event). Removing a body between steps ends its pairs
//!   without events (the game removed it; it knows).
//!
//! # Order
//! Each contact and sensor list is sorted by the pair's canonical key (lower
//! body slot, then higher), the joint list by joint slot: functions of the
//! simulation state alone, the same on every peer. The lists are cleared when
//! a step starts (a step that fails with an error leaves them as they were).
//!
//! # Capacity
//! Each list holds at most [`Capacities::events`](crate::Capacities::events)
//! events (the `EVENTS` parameter of [`WorldBuffers`](crate::WorldBuffers)).
//! Events past that are dropped, never a panic and never an allocation, and
//! counted in [`StepReport::events_dropped`](crate::StepReport::events_dropped).
//! Which survive is deterministic: events are found in pair-key order (the
//! ends of pairs that lost their contact points in the narrow phase first,
//! then those found on the final poses), and a full list keeps the first.
//!
//! # Rollback
//! What the events are computed from (the arbiters' touching flags, the
//! sensor overlaps, the joints) is simulation state, in the snapshot and the
//! state hash: after a [`restore`](crate::World::restore), stepping again
//! yields the same events.

use managed::ManagedSlice;

use crate::arbiter::Arbiter;
use crate::body::BodyHandle;
use crate::constraint::JointHandle;
use crate::math::{Scalar, Vector2};

/// Contact points at most this far apart (m) at the end of a step make their
/// pair touch (Box2D's linear slop).
pub const TOUCH_DISTANCE: Scalar = Scalar::lit("0.005");

/// The default hit-event threshold (m/s), Box2D's.
pub const DEFAULT_HIT_EVENT_THRESHOLD: Scalar = Scalar::ONE;

/// The default capacity of each event list
/// ([`Capacities::for_bodies`](crate::Capacities::for_bodies) takes the larger
/// of this and the body count).
pub const DEFAULT_EVENTS: usize = 64;

/// Two bodies started touching this step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContactBeginEvent {
    /// The arbiter's first body (the normal points from it to `body_b`).
    pub body_a: BodyHandle,
    /// The arbiter's second body.
    pub body_b: BodyHandle,
    /// The contact normal, from A to B.
    pub normal: Vector2,
    /// The index of the touching shape on body A (0: the body's first shape;
    /// see [`Arbiter::shape_a`](crate::Arbiter::shape_a)).
    pub shape_a: u8,
    /// The index of the touching shape on body B.
    pub shape_b: u8,
}

/// Two bodies stopped touching this step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContactEndEvent {
    /// The arbiter's first body.
    pub body_a: BodyHandle,
    /// The arbiter's second body.
    pub body_b: BodyHandle,
    /// The index of the shape on body A (0: the body's first shape).
    pub shape_a: u8,
    /// The index of the shape on body B.
    pub shape_b: u8,
}

/// Two bodies started touching this step, approaching faster than the
/// world's hit threshold (Box2D's hit event).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContactHitEvent {
    /// The arbiter's first body.
    pub body_a: BodyHandle,
    /// The arbiter's second body.
    pub body_b: BodyHandle,
    /// The contact point of the fastest approach, at the start of the step (m).
    pub point: Vector2,
    /// The contact normal, from A to B.
    pub normal: Vector2,
    /// The approach speed along the normal before the step's solve (m/s, > 0).
    pub speed: Scalar,
    /// The index of the touching shape on body A (0: the body's first shape).
    pub shape_a: u8,
    /// The index of the touching shape on body B.
    pub shape_b: u8,
}

/// A body started or stopped overlapping a sensor this step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SensorEvent {
    /// The sensor body.
    pub sensor: BodyHandle,
    /// The body that entered or left it.
    pub visitor: BodyHandle,
    /// The index of the sensor's shape (0: the body's first shape).
    pub sensor_shape: u8,
    /// The index of the visitor's shape.
    pub visitor_shape: u8,
}

/// A breakable joint broke this step and was removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JointBrokeEvent {
    /// The joint's handle (stale now).
    pub joint: JointHandle,
    /// Its first body.
    pub body_a: BodyHandle,
    /// Its second body (`None` for a joint to a world point).
    pub body_b: Option<BodyHandle>,
}

impl JointBrokeEvent {
    /// An unused slot.
    pub const EMPTY: Self = Self { joint: JointHandle::NULL, body_a: BodyHandle::NULL, body_b: None };
}

impl Default for JointBrokeEvent {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// One fixed-capacity list.
pub(crate) struct EventList<'a, T> {
    buf: ManagedSlice<'a, T>,
    len: usize,
}

impl<'a, T: Copy> EventList<'a, T> {
    pub(crate) fn new(buf: ManagedSlice<'a, T>) -> Self {
        Self { buf, len: 0 }
    }

    pub(crate) fn capacity(&self) -> usize {
        self.buf.len()
    }

    /// The events, in order.
    pub(crate) fn as_slice(&self) -> &[T] {
        self.buf.get(..self.len).unwrap_or(&[])
    }

    /// Appends; false (and nothing changes) when full.
    fn push(&mut self, e: T) -> bool {
        match self.buf.get_mut(self.len) {
            Some(slot) => {
                *slot = e;
                self.len = self.len.saturating_add(1);
                true
            }
            None => false,
        }
    }

    /// Sorts the events by `key` (distinct keys: a total, deterministic order).
    fn sort_by_key<K: Ord>(&mut self, key: impl FnMut(&T) -> K) {
        let n = self.len;
        if let Some(s) = self.buf.get_mut(..n) {
            s.sort_unstable_by_key(key);
        }
    }
}

/// The canonical key of a pair of bodies.
fn pair_key(a: BodyHandle, b: BodyHandle) -> (u32, u32) {
    let (x, y) = (a.index(), b.index());
    (x.min(y), x.max(y))
}

/// The world's event lists and the hit threshold.
pub(crate) struct Events<'a> {
    pub(crate) contact_begin: EventList<'a, ContactBeginEvent>,
    pub(crate) contact_end: EventList<'a, ContactEndEvent>,
    pub(crate) contact_hit: EventList<'a, ContactHitEvent>,
    pub(crate) sensor_begin: EventList<'a, SensorEvent>,
    pub(crate) sensor_end: EventList<'a, SensorEvent>,
    pub(crate) joint_broke: EventList<'a, JointBrokeEvent>,
    /// Approach speed above which a begin is also a hit (m/s).
    pub(crate) hit_threshold: Scalar,
    /// Events dropped since the lists were cleared.
    pub(crate) dropped: u32,
}

impl<'a> Events<'a> {
    pub(crate) fn new(
        contact_begin: ManagedSlice<'a, ContactBeginEvent>,
        contact_end: ManagedSlice<'a, ContactEndEvent>,
        contact_hit: ManagedSlice<'a, ContactHitEvent>,
        sensor_begin: ManagedSlice<'a, SensorEvent>,
        sensor_end: ManagedSlice<'a, SensorEvent>,
        joint_broke: ManagedSlice<'a, JointBrokeEvent>,
    ) -> Self {
        Self {
            contact_begin: EventList::new(contact_begin),
            contact_end: EventList::new(contact_end),
            contact_hit: EventList::new(contact_hit),
            sensor_begin: EventList::new(sensor_begin),
            sensor_end: EventList::new(sensor_end),
            joint_broke: EventList::new(joint_broke),
            hit_threshold: DEFAULT_HIT_EVENT_THRESHOLD,
            dropped: 0,
        }
    }

    /// The smallest list's capacity.
    pub(crate) fn capacity(&self) -> usize {
        self.contact_begin
            .capacity()
            .min(self.contact_end.capacity())
            .min(self.contact_hit.capacity())
            .min(self.sensor_begin.capacity())
            .min(self.sensor_end.capacity())
            .min(self.joint_broke.capacity())
    }

    /// Empties every list (the start of a step).
    pub(crate) fn clear(&mut self) {
        self.contact_begin.len = 0;
        self.contact_end.len = 0;
        self.contact_hit.len = 0;
        self.sensor_begin.len = 0;
        self.sensor_end.len = 0;
        self.joint_broke.len = 0;
        self.dropped = 0;
    }

    fn count(&mut self, kept: bool) {
        if !kept {
            self.dropped = self.dropped.saturating_add(1);
        }
    }

    pub(crate) fn begin(&mut self, e: ContactBeginEvent) {
        let kept = self.contact_begin.push(e);
        self.count(kept);
    }

    /// The end event of arbiter `arb`.
    pub(crate) fn end(&mut self, arb: &Arbiter) {
        let (shape_a, shape_b) = arb.shape_bytes();
        let kept = self.contact_end.push(ContactEndEvent {
            body_a: arb.body_a,
            body_b: arb.body_b,
            shape_a,
            shape_b,
        });
        self.count(kept);
    }

    pub(crate) fn hit(&mut self, e: ContactHitEvent) {
        let kept = self.contact_hit.push(e);
        self.count(kept);
    }

    /// A sensor event of arbiter `arb`, whose sensor is body A when
    /// `sensor_is_a`.
    pub(crate) fn sensor(&mut self, begin: bool, arb: &Arbiter, sensor_is_a: bool) {
        let (a, b) = arb.shape_bytes();
        let e = if sensor_is_a {
            SensorEvent { sensor: arb.body_a, visitor: arb.body_b, sensor_shape: a, visitor_shape: b }
        } else {
            SensorEvent { sensor: arb.body_b, visitor: arb.body_a, sensor_shape: b, visitor_shape: a }
        };
        let list = if begin { &mut self.sensor_begin } else { &mut self.sensor_end };
        let kept = list.push(e);
        self.count(kept);
    }

    pub(crate) fn joint_broke(&mut self, e: JointBrokeEvent) {
        let kept = self.joint_broke.push(e);
        self.count(kept);
    }

    /// Puts the pair lists in pair-key order (ends found during the narrow
    /// phase and after the solve are appended in two runs).
    pub(crate) fn sort(&mut self) {
        self.contact_begin.sort_by_key(|e| (pair_key(e.body_a, e.body_b), e.shape_a, e.shape_b));
        self.contact_end.sort_by_key(|e| (pair_key(e.body_a, e.body_b), e.shape_a, e.shape_b));
        self.contact_hit.sort_by_key(|e| (pair_key(e.body_a, e.body_b), e.shape_a, e.shape_b));
        self.sensor_begin.sort_by_key(|e| (pair_key(e.sensor, e.visitor), e.sensor_shape, e.visitor_shape));
        self.sensor_end.sort_by_key(|e| (pair_key(e.sensor, e.visitor), e.sensor_shape, e.visitor_shape));
    }
}
