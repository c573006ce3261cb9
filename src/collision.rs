//! The collision stage of the step: broad phase, narrow phase, and the arbiter
//! lifecycle with its callbacks (see [`crate::arbiter`] and [`crate::handler`]).
//!
//! Arbiters are kept in an array sorted by the pair key (lower body slot, higher
//! body slot). Each step the broad phase's candidate pairs, sorted the same way, are
//! merged with that array into the other of two buffers: a key in both is an
//! ongoing pair, a key only among the candidates is a new pair, a key only among
//! the arbiters is a pair whose boxes no longer overlap. No hashing, no search, and
//! an order that depends only on body slots.

use managed::ManagedSlice;

use crate::hook::Hook;

use crate::arbiter::{
    mix_friction, mix_restitution, sub_key, Arbiter, ArbiterState, ArbiterStore, ContactPoint, MAX_LINK,
    MAX_SHAPE_INDEX,
};
use crate::arena::Arena;
use crate::body::{shape_aabb, Body, BodyHandle, BodyType, Shape, ShapeStore};
use crate::collide::{
    collide_capsule_circle, collide_capsules, collide_chain_segment_capsule, collide_chain_segment_circle,
    collide_chain_segment_polygon, collide_circles, collide_polygon_capsule, collide_polygon_circle,
    collide_polygons, collide_segment_capsule, collide_segment_circle, collide_segment_polygon, compose_fast,
    dot_below_one, half, rotate_fast, Direction, Manifold, ManifoldPoint,
};
use crate::compound::{is_compound, shape_of, shapes_of, BodyShape, ShapeData, MAX_SHAPES_PER_BODY};
use crate::constraint::{Joint, JointMarker};
use crate::error::Error;
use crate::events::{ContactBeginEvent, ContactHitEvent, Events, TOUCH_DISTANCE};
use crate::geometry::chain::local_rect;
use crate::geometry::{Capsule, ChainSegment, PolygonPath, Segment};
use crate::handler::{CallbackContext, HandlerTable, PostStepQueue};
use crate::index::{
    dedup_sorted, sort_pairs, sweep_sorted, BruteForceIndex, PairSink, Proxy, SortAndSweepIndex,
    SpatialIndex, AUTO_THRESHOLD,
};
use crate::limits::SPECULATIVE_DISTANCE;
use crate::math::scalar::{below_one, mul_below_one, ZERO as ZERO_SCALAR};
use crate::math::{Rect, Scalar, Transform, Vector2};
use crate::solver::{ContactScratch, SolverBody};
use crate::step::StepContext;

/// The broad phase a world uses.
#[derive(Default)]
pub enum Index<'a> {
    /// The default: brute force up to
    /// [`AUTO_THRESHOLD`] proxies, sort-and-sweep
    /// above (on scratch from the world's storage).
    #[default]
    Auto,
    /// Test all pairs.
    BruteForce(BruteForceIndex),
    /// Sort and sweep on its own scratch.
    SortAndSweep(SortAndSweepIndex<'a>),
    /// A game's own index, borrowed or (with `alloc`) boxed.
    Custom(Hook<'a, dyn SpatialIndex + Send + 'a>),
}

impl<'a> Index<'a> {
    /// A game's index, borrowed for the world's lifetime.
    pub fn borrowed(i: &'a mut (dyn SpatialIndex + Send + 'a)) -> Self {
        Self::Custom(Hook::Borrowed(i))
    }

    /// A game's index, owned by the world.
    #[cfg(feature = "alloc")]
    pub fn boxed(i: alloc::boxed::Box<dyn SpatialIndex + Send + 'a>) -> Self {
        Self::Custom(Hook::Boxed(i))
    }
}

/// The broad phase's index and scratch: rebuilt every step, never state.
pub(crate) struct BroadPhase<'a> {
    /// The index the game chose.
    pub(crate) index: Index<'a>,
    /// The automatic index's sort-and-sweep, on scratch from the world's storage.
    pub(crate) auto_sweep: SortAndSweepIndex<'a>,
    /// One proxy per body inside the bounds, in slot order.
    pub(crate) proxies: ManagedSlice<'a, Proxy>,
    /// The body slot of each proxy.
    pub(crate) proxy_bodies: ManagedSlice<'a, u32>,
    /// Candidate pairs of body slots, sorted and deduplicated.
    pub(crate) pairs: ManagedSlice<'a, (u32, u32)>,
    /// Sorted body-slot pairs held by joints whose bodies must not collide.
    pub(crate) joint_pairs: ManagedSlice<'a, (u32, u32)>,
    /// Proxies built this step (`proxies[..live]`).
    pub(crate) live: usize,
    /// Joint-held pairs this step (`joint_pairs[..held]`).
    pub(crate) held: usize,
}

impl BroadPhase<'_> {
    /// The first `n` candidate pairs (as left by [`broad_phase`]).
    pub(crate) fn candidates(&self, n: usize) -> &[(u32, u32)] {
        self.pairs.get(..n.min(self.pairs.len())).unwrap_or(&[])
    }
}

/// True when the filters let shape `sa` of body `a` and shape `sb` of body
/// `b` collide: at least one dynamic body (both infinite-mass bodies ⇒
/// skip), no shared collision-group bit between the bodies (the manual's
/// rule, a veto), and Box2D's category/mask/group rule on the shapes'
/// filters ([`CollisionFilter::accepts`](crate::CollisionFilter::accepts));
/// never two segments or chains.
#[inline(always)]
pub(crate) fn contact_shapes<S: ShapeData>(a: &Body, sa: &S, b: &Body, sb: &S) -> bool {
    (a.body_type == BodyType::Dynamic || b.body_type == BodyType::Dynamic)
        && (a.collision_groups & b.collision_groups) == 0
        && sa.filters().accepts(sb.filters())
        && !both_lines(sa.geometry(), sb.geometry())
}

/// True when both shapes are segments or chains (which never collide).
#[inline]
fn both_lines(a: &Shape, b: &Shape) -> bool {
    let line = |s: &Shape| matches!(s, Shape::Segment(_) | Shape::Chain(_));
    line(a) && line(b)
}

/// True when two one-shape bodies make a pair the engine tracks (see
/// [`wants_shapes`]).
pub(crate) fn wants_pair(a: &Body, b: &Body) -> bool {
    wants_shapes(a, a, b, b)
}

/// True when shape `sa` of body `a` and shape `sb` of body `b` make a pair
/// the engine tracks: a contact pair ([`contact_shapes`]), or a sensor pair: exactly one sensor shape, at least
/// one moving body (a static sensor detects kinematic bodies too), and both
/// filters passed as for a contact pair (the collision groups and the
/// category/mask/group rule). Sensors never detect sensors, and segments
/// never meet segments (neither has an inside to push out of). Sensors do
/// not detect chains (a chain pair is one arbiter per link, not one overlap).
/// Two shapes of one body never pair.
#[inline(always)]
pub(crate) fn wants_shapes<S: ShapeData>(a: &Body, sa: &S, b: &Body, sb: &S) -> bool {
    let (sensor_a, sensor_b) = (sa.senses(), sb.senses());
    if !sensor_a && !sensor_b {
        return contact_shapes(a, sa, b, sb);
    }
    if (sensor_a && sensor_b)
        || matches!(sa.geometry(), Shape::Chain(_))
        || matches!(sb.geometry(), Shape::Chain(_))
    {
        return false;
    }
    let moving = a.body_type != BodyType::Static || b.body_type != BodyType::Static;
    moving
        && !both_lines(sa.geometry(), sb.geometry())
        && (a.collision_groups & b.collision_groups) == 0
        && sa.filters().accepts(sb.filters())
}

/// True when two bodies have a pair of shapes the engine tracks
/// ([`wants_shapes`]; for one-shape bodies [`wants_pair`]).
// Out of line: inlined, its shape copies gave the broad phase's filter
// closure, called once per reported pair, a 3.6 KB stack frame to set up.
#[inline(never)]
fn wants_bodies(a: &Body, b: &Body, shapes: &ShapeStore<'_>) -> bool {
    if !is_compound(a) && !is_compound(b) {
        return wants_pair(a, b);
    }
    let (copy_a, copy_b) = (shape_copies(a, shapes), shape_copies(b, shapes));
    copy_a.iter().any(|sa| copy_b.iter().any(|sb| wants_shapes(a, sa, b, sb)))
}

/// The shapes an arbiter is for, on its body A and body B.
#[inline]
fn arbiter_shapes(
    arb: &Arbiter,
    a: &Body,
    b: &Body,
    shapes: &ShapeStore<'_>,
) -> Option<(BodyShape, BodyShape)> {
    Some((shape_of(a, arb.shape_a(), shapes)?, shape_of(b, arb.shape_b(), shapes)?))
}

/// A body's shapes, copied (a compound pair's cold paths).
fn shape_copies(b: &Body, shapes: &ShapeStore<'_>) -> heapless::Vec<BodyShape, MAX_SHAPES_PER_BODY> {
    shapes_of(b, shapes).map(|(_, s)| s).collect()
}

/// True when an arbiter is a sensor pair: one of its shapes is a sensor; it
/// tracks overlap and is never solved. `None` when a shape is gone.
#[inline]
fn sensor_arbiter(arb: &Arbiter, a: &Body, b: &Body, shapes: &ShapeStore<'_>) -> Option<(bool, bool)> {
    if !is_compound(a) && !is_compound(b) {
        return Some((a.sensor || b.sensor, a.sensor));
    }
    let (sa, sb) = arbiter_shapes(arb, a, b, shapes)?;
    Some((sa.sensor || sb.sensor, sa.sensor))
}

/// What the broad phase found.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Candidates {
    /// Candidate pairs left in `bp.pairs[..count]`, sorted and distinct.
    pub(crate) count: usize,
    /// Pairs left out because the pair buffer was full.
    pub(crate) dropped: usize,
}

/// The broad phase: builds the proxies, runs the index, and leaves the sorted,
/// deduplicated, filtered candidate pairs (as body slot pairs) in
/// `bp.pairs[..n]`. Changes no simulation state.
///
/// When more pairs are found than the buffer holds, the lowest keys are kept
/// and the rest counted as dropped (see [`PairSink`]).
///
/// # Errors
/// [`Error::CapacityFull`] when the bodies do not fit the proxy buffer; with
/// `strict`, also when the pairs do not fit the contact buffer or the merged
/// arbiters would not fit.
pub(crate) fn broad_phase(
    ctx: &StepContext,
    bodies: &Arena<'_, Body>,
    shapes: &ShapeStore<'_>,
    joints: &Arena<'_, Joint, JointMarker>,
    bp: &mut BroadPhase<'_>,
    arbiters: &ArbiterStore<'_>,
) -> Result<Candidates, Error> {
    // Pairs held together by a joint that does not let them collide, sorted.
    let mut held = 0usize;
    for (_, j) in joints.iter() {
        let Some(b) = j.def.body_b else { continue };
        if j.def.collide_connected {
            continue;
        }
        let (x, y) = (j.def.body_a.index(), b.index());
        if let Some(slot) = bp.joint_pairs.get_mut(held) {
            *slot = (x.min(y), x.max(y));
            held = held.saturating_add(1);
        }
    }
    let held_pairs = bp.joint_pairs.get_mut(..held).unwrap_or(&mut []);
    held_pairs.sort_unstable();
    // The automatic index above the threshold sweeps the proxies sorted in
    // place (see `SortAndSweepIndex::sort_in_place`); every other index gets
    // them in slot order.
    let live = bodies.iter().filter(|(_, b)| !b.out_of_bounds).count();
    let in_place = matches!(bp.index, Index::Auto) && live > AUTO_THRESHOLD;
    if live > bp.proxies.len().min(bp.proxy_bodies.len()) {
        return Err(Error::CapacityFull { what: "broad-phase proxy" });
    }
    let n = live;
    bp.live = n;
    bp.held = held;
    let BroadPhase { index, auto_sweep, proxies, proxy_bodies, pairs, joint_pairs, .. } = bp;
    let proxies = proxies.get_mut(..n).unwrap_or(&mut []);
    let slots = proxy_bodies.get_mut(..n).unwrap_or(&mut []);
    // Last step's sorted order serves again when it names exactly the bodies
    // that need a proxy now: as many, each still live and inside the bounds
    // (its entries are distinct by construction). Checked while refilling it.
    let mut presorted = in_place && auto_sweep.sorted_len() == n;
    if presorted {
        for (p, &s) in proxies.iter_mut().zip(slots.iter()) {
            match bodies.get_at(s) {
                Some(b) if !b.out_of_bounds => *p = proxy(ctx, b),
                _ => {
                    presorted = false;
                    break;
                }
            }
        }
    }
    if !presorted {
        let in_bounds = bodies.iter().filter(|(_, b)| !b.out_of_bounds);
        for ((p, slot), (h, b)) in proxies.iter_mut().zip(slots.iter_mut()).zip(in_bounds) {
            *p = proxy(ctx, b);
            *slot = h.index();
        }
    }
    if in_place {
        auto_sweep.sort_in_place(proxies, slots, presorted);
    } else {
        auto_sweep.forget_order();
    }
    let proxies = &*proxies;
    let slots = &*slots;
    let held_pairs = joint_pairs.get(..held).unwrap_or(&[]);
    // The pairs the engine wants, by body slots (a < b): allowed by the
    // manual's filter, not held apart by a joint.
    let accept = |sa: u32, sb: u32| {
        let (Some(a), Some(b)) = (bodies.get_at(sa), bodies.get_at(sb)) else { return false };
        // One-shape bodies (the common case) go straight to `wants_pair`.
        let wanted =
            if !is_compound(a) && !is_compound(b) { wants_pair(a, b) } else { wants_bodies(a, b, shapes) };
        wanted && held_pairs.binary_search(&(sa, sb)).is_err()
    };
    let mut sink = PairSink::new(pairs, slots, ctx.strict_capacity, &accept);
    let custom = matches!(index, Index::Custom(_));
    match index {
        Index::Auto if in_place => {
            let next = sweep_sorted(proxies, auto_sweep.bands(), &mut sink);
            auto_sweep.plan(next);
        }
        Index::Auto => BruteForceIndex.find_pairs(proxies, &mut sink),
        Index::BruteForce(i) => i.find_pairs(proxies, &mut sink),
        Index::SortAndSweep(i) => i.find_pairs(proxies, &mut sink),
        Index::Custom(i) => i.find_pairs(proxies, &mut sink),
    }
    if sink.overflowed {
        return Err(Error::CapacityFull { what: "contact pair" });
    }
    let (reported, dropped) = (sink.len, sink.dropped);
    // The sink keeps body-slot pairs; sort them into key order. The built-in
    // indices report each pair once (and a full sink drops repeats), so only
    // a game's index can leave duplicates to remove.
    let reported = sort_pairs(pairs, reported);
    let unique = if custom { dedup_sorted(reported) } else { reported.len() };
    if ctx.strict_capacity {
        // The merge writes one arbiter per key of the union; check it fits first.
        let union = merged_len(bp.candidates(unique), arbiters.live());
        if union > arbiters.capacity() {
            return Err(Error::CapacityFull { what: "arbiter" });
        }
    }
    Ok(Candidates { count: unique, dropped })
}

/// The narrow phase and the arbiter lifecycle for the `candidates` left by
/// [`broad_phase`]: writes the new sorted arbiter array and runs `begin`,
/// `pre_solve` and `end` in key order.
///
/// # A full arbiter store
/// Keys are visited in order; once the store holds as many arbiters as it can,
/// every later key is skipped: a new candidate pair is not collided (no
/// callbacks), and an existing arbiter is dropped, with `end` if it had begun
/// (so `begin` and `end` still pair up; the pair begins again once there is
/// room). The lowest keys are kept. Returns how many keys were skipped and
/// how many manifolds were recycled.
// The step's parts it works on, each borrowed apart (as the other stages).
#[allow(clippy::too_many_arguments)]
pub(crate) fn update_arbiters(
    ctx: &StepContext,
    candidates: &[(u32, u32)],
    bodies: &Arena<'_, Body>,
    paths: &ShapeStore<'_>,
    arbiters: &mut ArbiterStore<'_>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
    events: &mut Events<'_>,
    scratch: &mut [ContactScratch],
) -> Updated {
    // Whether the solver's scratch still lines up with the live arbiters
    // (read before the merge moves them).
    let built = arbiters.built();
    let (live, next) = arbiters.live_and_next();
    // Each arbiter is built in its output slot (a 304-byte record copied once,
    // not at every hand-over); a dropped one leaves `out` where it was, so
    // the next overwrites it.
    let (mut j, mut out, mut skipped) = (0usize, 0usize, 0usize);
    let mut keys = CandidateKeys::new(candidates, bodies, paths);
    let mut pass = PairPass { ctx, bodies, paths, handlers, post_step, events, recycled: 0 };
    loop {
        let (cand, old) = (keys.peek(), live.get(j));
        let (key, candidate, previous) = match (cand, old) {
            (None, None) => break,
            (Some(k), None) => (k, true, None),
            (None, Some(a)) => (a.key(), false, Some(a)),
            (Some(k), Some(a)) => match k.cmp(&a.key()) {
                core::cmp::Ordering::Less => (k, true, None),
                core::cmp::Ordering::Greater => (a.key(), false, Some(a)),
                core::cmp::Ordering::Equal => (k, true, Some(a)),
            },
        };
        if candidate {
            keys.advance();
        }
        // The previous arbiter's position.
        let at = j;
        if previous.is_some() {
            j = j.saturating_add(1);
        }
        let Some(arb) = next.get_mut(out) else {
            skipped = skipped.saturating_add(1);
            if let Some(p) = previous {
                end_dropped(p, bodies, paths, pass.handlers, pass.post_step, pass.events);
            }
            continue;
        };
        // Each body is looked up once: its handle (the live one in its slot)
        // tells whether the previous arbiter still names it.
        let (Some((ha, ba)), Some((hb, bb))) = (live_at(bodies, key.0), live_at(bodies, key.1)) else {
            continue;
        };
        let link = key_link(key);
        let keep = if !is_compound(ba) && !is_compound(bb) {
            // One shape each: the bodies' own data (the common case).
            update_pair(&mut pass, (link, candidate, previous), arb, (ha, ba, ba, 0), (hb, bb, bb, 0))
        } else {
            // The key's shapes: the lower slot's, then the higher's.
            let (lo, hi) = ((key.2 >> 3) & MAX_SHAPE_INDEX, key.2 & MAX_SHAPE_INDEX);
            let (Some(sx), Some(sy)) = (shape_of(ba, lo, paths), shape_of(bb, hi, paths)) else { continue };
            update_pair(&mut pass, (link, candidate, previous), arb, (ha, ba, &sx, lo), (hb, bb, &sy, hi))
        };
        if keep != Verdict::Drop {
            // Its lane from the last build can be kept (see
            // `solver::colour::build`) when its scratch record is still its
            // own: the arbiter it continues was built at this same position.
            if let Some(s) = scratch.get_mut(out) {
                s.reuse = built && at == out && keep == Verdict::KeepSame;
            }
            out = out.saturating_add(1);
        }
    }
    arbiters.swap_in_next(out);
    Updated { skipped, recycled: pass.recycled }
}

/// What [`update_arbiters`] reports.
pub(crate) struct Updated {
    /// Pairs skipped because the arbiter store was full.
    pub(crate) skipped: usize,
    /// Manifolds carried on from the previous step (see [`recycle`]).
    pub(crate) recycled: usize,
}

/// What [`update_pair`] works with, besides the pair.
struct PairPass<'p, 'b, 's, 'h, 'q, 'e> {
    ctx: &'p StepContext,
    bodies: &'p Arena<'b, Body>,
    paths: &'p ShapeStore<'s>,
    handlers: &'p mut HandlerTable<'h>,
    post_step: &'p mut PostStepQueue<'q>,
    events: &'p mut Events<'e>,
    /// Manifolds recycled so far this step.
    recycled: usize,
}

/// One key's arbiter for this step, written into `arb`: shape `x.2` (index
/// `x.3`) of body `x.1` and shape `y.2` of body `y.1`, lower slot first,
/// for the chain link `key.0`, `key.1` whether the key is a candidate and
/// `key.2` the arbiter it had (see [`update_arbiters`]). Returns whether to
/// keep it.
#[inline(always)]
fn update_pair<S: ShapeData>(
    pass: &mut PairPass<'_, '_, '_, '_, '_, '_>,
    (link, candidate, previous): (u32, bool, Option<&Arbiter>),
    arb: &mut Arbiter,
    x: (BodyHandle, &Body, &S, u32),
    y: (BodyHandle, &Body, &S, u32),
) -> Verdict {
    let PairPass { ctx, bodies, paths, handlers, post_step, events, recycled: recycled_count } = pass;
    let (ha, ba, sx) = (x.0, x.1, x.2);
    let (hb, bb, sy) = (y.0, y.1, y.2);
    if sx.senses() || sy.senses() {
        pair_arbiter(x, y, link, previous, arb);
        // Overlap is judged after the solve ([`touch_events`]); a sensor
        // pair is kept while its boxes meet or it overlaps, never solved.
        arb.solve = false;
        arb.count = 0;
        arb.set_touching(false);
        // A candidate key passed the filters (see `near` below).
        return if candidate || arb.state == ArbiterState::Contact { Verdict::Keep } else { Verdict::Drop };
    }
    // The previous arbiter when it names these same bodies (as
    // [`pair_arbiter`] decides), and the body order the arbiter has.
    let same = same_pair(previous, ha, hb);
    let x_first = match same {
        Some(p) => p.body_a == ha,
        None => first_in_new(sx, sy),
    };
    let (a, b, sa, sb) = if x_first { (ba, bb, sx, sy) } else { (bb, ba, sy, sx) };
    // Contact points only within the speculative distance: the boxes
    // (stretched along the motion for continuous collision) found the
    // pair; the narrow phase runs only when the bodies' own boxes are
    // that close (for compound bodies, the key stream checked the shapes').
    // A candidate key already passed `wants_shapes` for these two shapes
    // (a symmetric test): the broad phase's filter for one-shape bodies, the
    // key stream's for chain links and compound shapes. Nothing between can
    // change what it reads (types, groups, filters, sensor flags, shapes):
    // a force generator reaches a body only through its public methods
    // (velocities, impulses, user data, the bullet flag), and the callbacks
    // of earlier keys see the bodies shared. (Testing it again cost mixed
    // 180 steps about 2.5 M instructions.)
    let near = boxes_within(a.aabb, b.aabb, SPECULATIVE_DISTANCE);
    // A pair whose bodies moved little since its manifold was computed
    // keeps it, written straight into `arb` (see [`recycle`]).
    let recycled = candidate && near && same.is_some_and(|p| recycle(p, a, b, ctx.recycle_distance, arb));
    // `None` where nothing is collided (an empty manifold's worth of
    // stores an arbiter saved: about 14 instructions of each recycled one).
    let manifold = (candidate && near && !recycled).then(|| {
        let arb_link = same.map_or(link.min(MAX_LINK), Arbiter::link);
        collide_body_shapes((a, sa), (b, sb), paths, arb_link, SPECULATIVE_DISTANCE)
    });
    let count = manifold.as_ref().map_or(0, |m| m.count);
    // An ongoing pair that touches has its points, normal, count, mixed
    // material and solve flag all rewritten: only the rest of the record
    // is carried over, and the warm start reads the previous points where
    // they are (no whole-record copy).
    let old = match same {
        Some(p) if recycled || count > 0 => {
            arb.body_a = p.body_a;
            arb.body_b = p.body_b;
            arb.level_a = p.level_a;
            arb.level_b = p.level_b;
            arb.state = p.state;
            arb.steps_and_link = p.steps_and_link;
            arb.flags = p.flags;
            Some(p)
        }
        _ => {
            pair_arbiter(x, y, link, previous, arb);
            None
        }
    };
    let ((fa, ra), (fb, rb)) = (sa.material(), sb.material());
    arb.friction = mix_friction(fa, fb);
    arb.restitution = mix_restitution(ra, rb);
    let mut ctx_cb = CallbackContext { bodies, post_step: post_step.view() };
    let found = if recycled { None } else { Some(manifold.as_ref().unwrap_or(&Manifold::EMPTY)) };
    let kept = lifecycle(arb, old, found, handlers, &mut ctx_cb, ctx.arbiter_persistence, events);
    if recycled {
        *recycled_count = recycled_count.saturating_add(1);
    } else if count > 0 && ctx.recycle_distance != ZERO_SCALAR {
        // Computed: the manifold to keep from now on (none is kept while
        // recycling is off, so no state outside the snapshot builds up).
        arb.rot_a0 = a.rotation;
        arb.rot_b0 = b.rotation;
        arb.set_has_manifold(true);
    } else {
        arb.set_has_manifold(false);
    }
    if kept {
        if arb.count > 0 && arb.state == ArbiterState::Contact && !arb.is_touching() {
            approach(arb, a, b);
        }
        // What its lane was built from is unchanged but the bodies' masses.
        return if recycled && old.is_some_and(|p| p.friction == arb.friction) {
            Verdict::KeepSame
        } else {
            Verdict::Keep
        };
    }
    Verdict::Drop
}

/// What [`update_pair`] decided for an arbiter.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Verdict {
    /// Dropped.
    Drop,
    /// Kept.
    Keep,
    /// Kept, with its manifold recycled and its friction unchanged: its lane
    /// can be kept if the bodies' masses are too (see `solver::colour::build`).
    KeepSame,
}

/// Cosine of the most either body may turn before its manifold is computed
/// again (0.98: about 11.5°).
const RECYCLE_COS: Scalar = Scalar::lit("0.98");

/// The previous step's manifold carried on to bodies `a`, `b` (in the
/// arbiter's order), written into `arb`, when they moved little since it
/// was computed; false, leaving `arb` alone, to compute it. Contact recycling as Box2D v3 does it (Erin Catto, Box2D
/// v3.2, `physics_world.c`, after PhysX's persistent manifolds): the normal,
/// the anchors and the feature ids carry on, and each point's separation is
/// its value when computed plus how far the two anchored material points
/// (each anchor turned with its body since) have moved apart along the
/// normal, which is how the sub-steps track separation too.
///
/// It carries on while, since the manifold was computed:
/// * each body turned by less than about 11.5° (cos > [`RECYCLE_COS`]): the
///   normal stays in the world frame, and
/// * the first point's anchored points moved apart by less than `distance`
///   (summing |Δx| and |Δy|), counting twice the relative turn at the larger
///   bounding radius (a static body's is 0): no point of either body then
///   moved relative to the other by more than about `distance`.
///
/// Box2D measures the relative pose of the bodies' frames instead; this
/// bound reuses the first point's motion, which the separation needs
/// anyway. A settled 20-row pyramid recycles every manifold and runs 11 %
/// fewer instructions a step (the rollback scene 9 %). Everything it reads is
/// state in the snapshot ([`Arbiter::rot_a0`] and the points' anchors and
/// base separations), so a restore carries on exactly as stepping on does.
#[inline(always)]
fn recycle(p: &Arbiter, a: &Body, b: &Body, distance: Scalar, arb: &mut Arbiter) -> bool {
    if !p.has_manifold() || p.count == 0 || distance == ZERO_SCALAR {
        return false;
    }
    let da = compose_fast(a.rotation, p.rot_a0.inverse());
    let db = compose_fast(b.rotation, p.rot_b0.inverse());
    if da.c <= RECYCLE_COS || db.c <= RECYCLE_COS {
        return false;
    }
    let n = p.normal;
    let [o0, o1] = &p.points;
    let moved = |o: &ContactPoint| {
        let pa = a.position + rotate_fast(da, o.anchor_a);
        let pb = b.position + rotate_fast(db, o.anchor_b);
        (pa, pb, pb - pa)
    };
    let first = moved(o0);
    let d0 = first.2;
    let turn = (da.c * db.s - da.s * db.c).abs();
    let reach = |x: &Body| if x.body_type == BodyType::Static { ZERO_SCALAR } else { x.radius };
    let ext = reach(a).max(reach(b));
    if d0.x.abs() + d0.y.abs() + (ext + ext) * turn >= distance {
        return false;
    }
    // The point as `set_manifold` would write it from the kept one: the
    // warm start from the first previous point with its id (the kept
    // points' own, unless both have one id), the step's totals cleared.
    let point = |dst: &mut ContactPoint,
                 o: &ContactPoint,
                 carry: &ContactPoint,
                 (pa, pb, d): (Vector2, Vector2, Vector2)| {
        // Every field named (no `..`), written into the arbiter in place:
        // built whole and then copied, the points cost the 20-row pyramid
        // 0.9 % more instructions.
        *dst = ContactPoint {
            point: Vector2::new(half(pa.x + pb.x), half(pa.y + pb.y)),
            separation: o.base_separation + along(d, n),
            id: o.id,
            normal_impulse: carry.normal_impulse,
            tangent_impulse: carry.tangent_impulse,
            total_normal_impulse: ZERO_SCALAR,
            max_normal_impulse: ZERO_SCALAR,
            anchor_a: o.anchor_a,
            anchor_b: o.anchor_b,
            approach: 0,
            recycled: true,
            base_separation: o.base_separation,
        };
    };
    let [q0, q1] = &mut arb.points;
    point(q0, o0, o0, first);
    if p.count >= 2 {
        point(q1, o1, if o0.id == o1.id { o0 } else { o1 }, moved(o1));
    } else {
        *q1 = Arbiter::EMPTY.points[0];
    }
    arb.count = p.count.min(2);
    arb.normal = n;
    arb.rot_a0 = p.rot_a0;
    arb.rot_b0 = p.rot_b0;
    true
}

/// `d · n` ([`Vector2::dot`]'s bits): a component for a normal along an
/// axis (a box on a box), the products without the saturation test for any
/// other unit normal.
#[inline(always)]
fn along(d: Vector2, n: Vector2) -> Scalar {
    match Direction::of(n) {
        Direction::PosX => d.x + ZERO_SCALAR,
        Direction::NegX => -d.x + ZERO_SCALAR,
        Direction::PosY => ZERO_SCALAR + d.y,
        Direction::NegY => ZERO_SCALAR + -d.y,
        Direction::Any(n) if below_one(n.x) && below_one(n.y) => dot_below_one(n, d),
        Direction::Any(n) => d.dot(n),
    }
}

/// The candidate keys in order: each candidate body pair's key with link 0,
/// or, for a pair with a chain, one key per link whose box meets the other
/// body's box grown by the speculative distance (the mid-phase: the chain's
/// link tree gives them in increasing order, O(log n) each).
struct CandidateKeys<'c, 'b, 'a> {
    pairs: &'c [(u32, u32)],
    bodies: &'b Arena<'a, Body>,
    shapes: &'b ShapeStore<'a>,
    /// The next pair to expand.
    i: usize,
    /// The key `peek` returns.
    current: Option<ArbiterKey>,
    /// The current pair has that one key (two one-shape bodies, no chain).
    single: bool,
}

/// An arbiter's key: (lower body slot, higher body slot, sub-key; see
/// [`Arbiter::key`]).
pub(crate) type ArbiterKey = (u32, u32, u32);

/// The chain link of a key (see [`Arbiter::key`]).
#[inline]
fn key_link(key: ArbiterKey) -> u32 {
    key.2 >> 6
}

impl<'c, 'b, 'a> CandidateKeys<'c, 'b, 'a> {
    fn new(pairs: &'c [(u32, u32)], bodies: &'b Arena<'a, Body>, shapes: &'b ShapeStore<'a>) -> Self {
        let mut k = Self { pairs, bodies, shapes, i: 0, current: None, single: false };
        k.current = k.key_at_or_after(None);
        k
    }

    fn peek(&self) -> Option<ArbiterKey> {
        self.current
    }

    #[inline(always)]
    fn advance(&mut self) {
        if self.single {
            // The pair's only key: on to the next pair, inline when that is
            // a single-key pair too (the common case).
            self.i = self.i.saturating_add(1);
            if let Some(&(x, y)) = self.pairs.get(self.i) {
                if let (Some(bx), Some(by)) = (self.bodies.get_at(x), self.bodies.get_at(y)) {
                    if single_key(bx) && single_key(by) {
                        self.current = Some((x, y, 0));
                        return;
                    }
                }
            }
            self.current = self.key_at_or_after(None);
            return;
        }
        let after = self.current.map(|k| (k.0, k.1, k.2.saturating_add(1)));
        self.current = self.key_at_or_after(after);
    }

    /// The first key at `at` = (pair, first sub-key to look at) or after it
    /// (the pair's next shape pair or link), else the first key of the
    /// following pairs.
    fn key_at_or_after(&mut self, at: Option<(u32, u32, u32)>) -> Option<ArbiterKey> {
        if let Some((x, y, from)) = at {
            if let Some(sub) = self.next_sub(x, y, from) {
                return Some((x, y, sub));
            }
            self.i = self.i.saturating_add(1);
        }
        loop {
            let &(x, y) = self.pairs.get(self.i)?;
            let (Some(bx), Some(by)) = (self.bodies.get_at(x), self.bodies.get_at(y)) else {
                self.i = self.i.saturating_add(1);
                continue;
            };
            self.single = single_key(bx) && single_key(by);
            if self.single {
                return Some((x, y, 0));
            }
            if let Some(sub) = self.next_sub_expanded(bx, by, 0) {
                return Some((x, y, sub));
            }
            self.i = self.i.saturating_add(1);
        }
    }

    /// The first sub-key at or after `from` of the pair `(x, y)`: for two
    /// one-shape bodies 0 (only from 0); for a pair with a chain, the links
    /// near the other body, each with the other body's shapes the filters
    /// let meet the chain; for compound bodies, the shape pairs (lower slot's
    /// shape outer) the filters want whose boxes are within the speculative
    /// distance.
    #[inline]
    fn next_sub(&self, x: u32, y: u32, from: u32) -> Option<u32> {
        let (bx, by) = (self.bodies.get_at(x)?, self.bodies.get_at(y)?);
        if single_key(bx) && single_key(by) {
            return (from == 0).then_some(0);
        }
        self.next_sub_expanded(bx, by, from)
    }

    /// [`CandidateKeys::next_sub`] for a pair with a chain or a compound body.
    #[inline(never)]
    fn next_sub_expanded(&self, bx: &Body, by: &Body, from: u32) -> Option<u32> {
        let (link0, lo0, hi0) = (from >> (2 * 3), (from >> 3) & MAX_SHAPE_INDEX, from & MAX_SHAPE_INDEX);
        let chain_low = matches!(bx.shape, Shape::Chain(_));
        if chain_low || matches!(by.shape, Shape::Chain(_)) {
            let (chain, other) = if chain_low { (bx, by) } else { (by, bx) };
            let Shape::Chain(h) = chain.shape else { return None };
            let chain_shape = BodyShape::of_body(chain);
            // The other body's shape index sits in the lower or higher field,
            // the chain's (always 0) in the other: a `from` past a key has a
            // nonzero chain field, and starts at the next index (or link).
            let (mut link, mut first) = if chain_low {
                if lo0 > 0 {
                    (link0.checked_add(1)?, 0)
                } else {
                    (link0, hi0)
                }
            } else {
                (link0, lo0.saturating_add(u32::from(hi0 > 0)))
            };
            let query = local_rect(other.aabb.expand(SPECULATIVE_DISTANCE), chain.transform());
            loop {
                let l = self.shapes.chains.next_link(h, link, query)?;
                if l != link {
                    first = 0;
                }
                for (i, s) in shapes_of(other, self.shapes).skip(first as usize) {
                    if wants_shapes(chain, &chain_shape, other, &s) {
                        return Some(if chain_low { sub_key(l, 0, i) } else { sub_key(l, i, 0) });
                    }
                }
                link = l.checked_add(1)?;
                first = 0;
            }
        }
        if !is_compound(bx) && !is_compound(by) {
            return (from == 0).then_some(0);
        }
        if link0 != 0 {
            return None;
        }
        let (xx, xy) = (bx.transform(), by.transform());
        for (i, sx) in shapes_of(bx, self.shapes).skip(lo0 as usize) {
            let first = if i == lo0 { hi0 } else { 0 };
            let mut box_x = None;
            for (j, sy) in shapes_of(by, self.shapes).skip(first as usize) {
                if !wants_shapes(bx, &sx, by, &sy) {
                    continue;
                }
                let bxs = *box_x.get_or_insert_with(|| shape_box(bx, &sx, xx, self.shapes));
                if boxes_within(bxs, shape_box(by, &sy, xy, self.shapes), SPECULATIVE_DISTANCE) {
                    return Some(sub_key(0, i, j));
                }
            }
        }
        None
    }
}

/// True when a body has one shape and is not a chain: a pair of two such
/// bodies has one key.
#[inline]
fn single_key(b: &Body) -> bool {
    !is_compound(b) && !matches!(b.shape, Shape::Chain(_))
}

/// The world box of shape `s` of body `b` at the body's transform `xf`.
#[inline]
fn shape_box(b: &Body, s: &BodyShape, xf: Transform, shapes: &ShapeStore<'_>) -> Rect {
    if is_compound(b) {
        shape_aabb(s.shape, xf.compose(s.local), ZERO_SCALAR, shapes)
    } else {
        b.aabb
    }
}

/// Calls `end` for an arbiter dropped from a full store, if it had begun and
/// its bodies still exist.
fn end_dropped(
    arb: &Arbiter,
    bodies: &Arena<'_, Body>,
    shapes: &ShapeStore<'_>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
    events: &mut Events<'_>,
) {
    let begun = matches!(arb.state, ArbiterState::Contact | ArbiterState::Ignoring);
    let (Some(a), Some(b)) = (bodies.get(arb.body_a), bodies.get(arb.body_b)) else { return };
    if !begun {
        return;
    }
    let (sensor, a_is_sensor) = sensor_arbiter(arb, a, b, shapes).unwrap_or((false, false));
    if sensor {
        events.sensor(false, arb, a_is_sensor);
        return;
    }
    if arb.is_touching() {
        events.end(arb);
    }
    let mut ended = *arb;
    ended.state = ArbiterState::Separated;
    ended.count = 0;
    if let Some(h) = handlers.get(ended.level_a, ended.level_b) {
        let mut ctx = CallbackContext { bodies, post_step: post_step.view() };
        h.end(&ended, &mut ctx);
    }
}

/// Calls `post_solve` for every arbiter solved this step, in key order.
pub(crate) fn post_solve(
    bodies: &Arena<'_, Body>,
    arbiters: &ArbiterStore<'_>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
) {
    if handlers.is_empty() {
        return;
    }
    for arb in arbiters.live() {
        if !arb.solve {
            continue;
        }
        if let Some(h) = handlers.get(arb.level_a, arb.level_b) {
            let mut ctx = CallbackContext { bodies, post_step: post_step.view() };
            h.post_solve(arb, &mut ctx);
        }
    }
}

/// Records each contact point's approach speed along the normal at the start
/// of the step (for a hit event, should the pair begin touching this step),
/// in Q16.16 (saturated: ±32,768 m/s is twice any relative speed a world
/// allows).
fn approach(arb: &mut Arbiter, a: &Body, b: &Body) {
    let n = arb.normal;
    let count = usize::from(arb.count);
    for p in arb.points.iter_mut().take(count) {
        let dv = b.velocity_at_offset(p.anchor_b) - a.velocity_at_offset(p.anchor_a);
        let speed = (-dv.dot(n)).to_bits() >> 16;
        p.approach = i32::try_from(speed).unwrap_or(if speed < 0 { i32::MIN } else { i32::MAX });
    }
}

/// The fastest approach of an arbiter's points (m/s) and where.
fn fastest_approach(arb: &Arbiter) -> (Scalar, Vector2) {
    let (mut best, mut at) = (i32::MIN, Vector2::ZERO);
    for p in arb.points.iter().take(usize::from(arb.count)) {
        if p.approach > best {
            (best, at) = (p.approach, p.point);
        }
    }
    (Scalar::from_bits(i64::from(best) << 16), at)
}

/// The events stage, after the solve, continuous collision and the limits
/// (the poses the game will read): each contact arbiter's touching flag and
/// each sensor pair's overlap brought up to date, with their begin, end and
/// hit events; sensor pairs that do not overlap are dropped. `solver` holds
/// every body's pose at the start of the step.
pub(crate) fn touch_events(
    bodies: &Arena<'_, Body>,
    paths: &ShapeStore<'_>,
    solver: &[SolverBody],
    arbiters: &mut ArbiterStore<'_>,
    events: &mut Events<'_>,
) {
    let mut drop_any = false;
    for arb in arbiters.live_mut() {
        // By slot: the lifecycle wrote every arbiter with live handles, and
        // no stage since removes a body (continuous collision and the limits
        // move them, freeze them at the most).
        let (Some(a), Some(b)) = (bodies.get_at(arb.body_a.index()), bodies.get_at(arb.body_b.index()))
        else {
            continue;
        };
        let Some((sensor, a_is_sensor)) = sensor_arbiter(arb, a, b, paths) else { continue };
        if sensor {
            let overlap = overlapping(arb, a, b, paths);
            let was = arb.state == ArbiterState::Contact;
            if overlap != was {
                events.sensor(overlap, arb, a_is_sensor);
            }
            arb.state = if overlap { ArbiterState::Contact } else { ArbiterState::NoCollision };
            arb.reset_steps_separated();
            drop_any |= !overlap;
            continue;
        }
        let now = arb.state == ArbiterState::Contact && arb.count > 0 && {
            let start = |h: BodyHandle| solver.get(h.index() as usize);
            match (start(arb.body_a), start(arb.body_b)) {
                (Some(sa), Some(sb)) => separation_now(arb, (a, sa), (b, sb)) <= TOUCH_DISTANCE,
                _ => false,
            }
        };
        if now && !arb.is_touching() {
            let (shape_a, shape_b) = arb.shape_bytes();
            events.begin(ContactBeginEvent {
                body_a: arb.body_a,
                body_b: arb.body_b,
                normal: arb.normal,
                shape_a,
                shape_b,
            });
            let (speed, point) = fastest_approach(arb);
            if speed > events.hit_threshold {
                events.hit(ContactHitEvent {
                    body_a: arb.body_a,
                    body_b: arb.body_b,
                    point,
                    normal: arb.normal,
                    speed,
                    shape_a,
                    shape_b,
                });
            }
        } else if !now && arb.is_touching() {
            events.end(arb);
        }
        arb.set_touching(now);
    }
    if drop_any {
        // Only sensor arbiters are in `NoCollision` after the lifecycle.
        arbiters.retain(|arb| arb.state != ArbiterState::NoCollision);
    }
    events.sort();
}

/// The least separation of an arbiter's contact points now (m), each point
/// carried along with its bodies' motion since the start of the step: the
/// centre's displacement plus the turn of the point's offset, linearised
/// (dθ × r; off by |r|·dθ²/2, under a millimetre for a 1 m body turning less
/// than 0.045 rad a step) with the normal kept, as Box2D's relax iterations
/// estimate it. Stops at the first point within [`TOUCH_DISTANCE`].
fn separation_now(arb: &Arbiter, a: (&Body, &SolverBody), b: (&Body, &SolverBody)) -> Scalar {
    // A body's displacement and turn since the start of the step (a body put
    // back by continuous collision turned the same fraction of the way).
    let motion = |(body, start): (&Body, &SolverBody)| {
        if !body.moved_by_step() {
            return (Vector2::ZERO, Scalar::ZERO);
        }
        let turn = if start.toi < Scalar::ONE { start.angle * start.toi } else { start.angle };
        (body.position - start.p0, turn)
    };
    let ((dpa, ta), (dpb, tb)) = (motion(a), motion(b));
    let n = arb.normal;
    // A normal off the axes, and a turn below a radian, have parts below 1:
    // their products skip the saturation test (`mul_below_one`, the same bits
    // as `*`, which rounds the same exact product the same way; the events
    // stage on mixed 180 steps 23.9 -> 23.0 M instructions).
    let mul_n = below_one(n.x) && below_one(n.y);
    let mul_t = below_one(ta) && below_one(tb);
    let mut least = Scalar::MAX;
    for p in arb.points.iter().take(usize::from(arb.count)) {
        let (ra, rb) = (p.anchor_a, p.anchor_b);
        let (turn_a, turn_b) = if mul_t {
            (
                Vector2::new(-mul_below_one(ta, ra.y), mul_below_one(ta, ra.x)),
                Vector2::new(-mul_below_one(tb, rb.y), mul_below_one(tb, rb.x)),
            )
        } else {
            (Vector2::cross_sv(ta, ra), Vector2::cross_sv(tb, rb))
        };
        let d = (dpb + turn_b) - (dpa + turn_a);
        let along = if mul_n { mul_below_one(n.x, d.x) + mul_below_one(n.y, d.y) } else { d.dot(n) };
        least = least.min(p.separation + along);
        if least <= TOUCH_DISTANCE {
            break;
        }
    }
    least
}

/// True when an arbiter's two shapes overlap now (a separation below zero;
/// no margin). Frozen bodies overlap nothing.
fn overlapping(arb: &Arbiter, a: &Body, b: &Body, paths: &ShapeStore<'_>) -> bool {
    if a.out_of_bounds || b.out_of_bounds || !a.aabb.overlaps(b.aabb) {
        return false;
    }
    let Some((sa, sb)) = arbiter_shapes(arb, a, b, paths) else { return false };
    if !wants_shapes(a, &sa, b, &sb) {
        return false;
    }
    let m = collide_body_shapes((a, &sa), (b, &sb), paths, arb.link(), Scalar::ZERO);
    m.points().iter().any(|p| p.separation < Scalar::ZERO)
}

/// Ends and drops every arbiter of body slot `index` (before the body is
/// removed), calling `end` for those that had begun.
pub(crate) fn end_arbiters_of(
    index: u32,
    bodies: &Arena<'_, Body>,
    shapes: &ShapeStore<'_>,
    arbiters: &mut ArbiterStore<'_>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
) {
    arbiters.retain(|arb| {
        if arb.body_a.index() != index && arb.body_b.index() != index {
            return true;
        }
        let sensor = match (bodies.get(arb.body_a), bodies.get(arb.body_b)) {
            (Some(a), Some(b)) => sensor_arbiter(arb, a, b, shapes).is_some_and(|(s, _)| s),
            _ => false,
        };
        end_if_begun(arb, sensor, bodies, handlers, post_step);
        false
    });
}

/// Calls `end` for an arbiter about to be dropped, if it is a contact pair
/// (not `sensor`) that had begun.
fn end_if_begun(
    arb: &Arbiter,
    sensor: bool,
    bodies: &Arena<'_, Body>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
) {
    if !sensor && matches!(arb.state, ArbiterState::Contact | ArbiterState::Ignoring) {
        let mut ended = *arb;
        ended.state = ArbiterState::Separated;
        if let Some(h) = handlers.get(ended.level_a, ended.level_b) {
            let mut ctx = CallbackContext { bodies, post_step: post_step.view() };
            h.end(&ended, &mut ctx);
        }
    }
}

/// Ends and drops the arbiters of shape `shape` of body slot `index` (the
/// shape was removed; `removed_sensor` its sensor flag), calling `end` for
/// those that had begun, and moves the body's later shapes' arbiters down
/// one index. The arbiters stay in key
/// order: the indices map in order.
pub(crate) fn end_arbiters_of_shape(
    index: u32,
    (shape, removed_sensor): (u32, bool),
    bodies: &Arena<'_, Body>,
    shapes: &ShapeStore<'_>,
    arbiters: &mut ArbiterStore<'_>,
    handlers: &mut HandlerTable<'_>,
    post_step: &mut PostStepQueue<'_>,
) {
    arbiters.retain_mut(|arb| {
        let on_a = arb.body_a.index() == index;
        let on_b = arb.body_b.index() == index;
        if !on_a && !on_b {
            return true;
        }
        let (sa, sb) = (arb.shape_a(), arb.shape_b());
        if (on_a && sa == shape) || (on_b && sb == shape) {
            // The other side's shape (the removed one is gone from the list).
            let (other, other_shape) = if on_a { (arb.body_b, sb) } else { (arb.body_a, sa) };
            let sensor = removed_sensor
                || bodies.get(other).and_then(|o| shape_of(o, other_shape, shapes)).is_some_and(|s| s.sensor);
            end_if_begun(arb, sensor, bodies, handlers, post_step);
            return false;
        }
        let down = |on: bool, s: u32| if on && s > shape { s - 1 } else { s };
        arb.set_shapes(down(on_a, sa), down(on_b, sb));
        true
    });
}

/// Runs one pair's lifecycle for this step (`old`: where the previous
/// points are, see [`set_manifold`]). Returns whether to keep the arbiter.
#[inline(always)]
fn lifecycle(
    arb: &mut Arbiter,
    old: Option<&Arbiter>,
    m: Option<&Manifold>,
    handlers: &mut HandlerTable<'_>,
    ctx: &mut CallbackContext<'_>,
    persistence: u32,
    events: &mut Events<'_>,
) -> bool {
    arb.solve = false;
    // `None`: the points are already in `arb` (a recycled manifold).
    if m.is_none_or(|m| m.count > 0) {
        if let Some(m) = m {
            set_manifold(arb, old, m);
        }
        arb.reset_steps_separated();
        if matches!(arb.state, ArbiterState::NoCollision | ArbiterState::Separated) {
            arb.state = ArbiterState::FirstContact;
            let resolve = handlers.get(arb.level_a, arb.level_b).is_none_or(|h| h.begin(arb, ctx));
            arb.state = if resolve { ArbiterState::Contact } else { ArbiterState::Ignoring };
        }
        if arb.state == ArbiterState::Contact {
            // No handler at all (the common case): solved, without the lookup.
            arb.solve = handlers.is_empty()
                || handlers.get(arb.level_a, arb.level_b).is_none_or(|h| h.pre_solve(arb, ctx));
        }
        return true;
    }
    // Not touching (or its boxes no longer overlap).
    arb.count = 0;
    if arb.is_touching() {
        arb.set_touching(false);
        events.end(arb);
    }
    if matches!(arb.state, ArbiterState::Contact | ArbiterState::Ignoring) {
        arb.state = ArbiterState::Separated;
        if let Some(h) = handlers.get(arb.level_a, arb.level_b) {
            h.end(arb, ctx);
        }
    }
    if arb.state == ArbiterState::NoCollision {
        // A new pair that did not touch: nothing to remember.
        return false;
    }
    arb.increase_step_count() <= persistence
}

/// Copies a manifold into the arbiter, carrying the accumulated impulses of
/// points whose feature id persists (warm starting) from the points of `old`
/// (the previous step's record, when the caller did not copy it into `arb`)
/// or else of `arb` itself. Written in place: the impulses carried over are
/// read before any point is overwritten, and each point is then written
/// whole (a point past the manifold's count is cleared).
fn set_manifold(arb: &mut Arbiter, old: Option<&Arbiter>, m: &Manifold) {
    let src = m.points();
    let prev: &Arbiter = old.unwrap_or(&*arb);
    // The first of the previous step's points (at most its count) with
    // this feature id: its impulses, else none (zero).
    let [o0, o1] = &prev.points;
    let old_count = prev.count;
    let carry = |id: u16| {
        if old_count >= 1 && o0.id == id {
            (o0.normal_impulse, o0.tangent_impulse)
        } else if old_count >= 2 && o1.id == id {
            (o1.normal_impulse, o1.tangent_impulse)
        } else {
            (ZERO_SCALAR, ZERO_SCALAR)
        }
    };
    let new_point = |s: &ManifoldPoint, (normal_impulse, tangent_impulse): (Scalar, Scalar)| ContactPoint {
        point: s.point,
        separation: s.separation,
        id: s.id,
        normal_impulse,
        tangent_impulse,
        total_normal_impulse: ZERO_SCALAR,
        max_normal_impulse: ZERO_SCALAR,
        anchor_a: s.anchor_a,
        anchor_b: s.anchor_b,
        approach: 0,
        recycled: false,
        base_separation: s.separation,
    };
    let empty = Arbiter::EMPTY.points[0];
    let p0 = src.first().map_or(empty, |s| new_point(s, carry(s.id)));
    let p1 = src.get(1).map_or(empty, |s| new_point(s, carry(s.id)));
    arb.points = [p0, p1];
    arb.count = m.count.min(2) as u8;
    arb.normal = m.normal;
}

/// The live body in slot `index` and its handle.
#[inline]
fn live_at<'b>(bodies: &'b Arena<'_, Body>, index: u32) -> Option<(BodyHandle, &'b Body)> {
    bodies.entry_at(index)
}

/// The previous arbiter when it names bodies `ha` and `hb` (in either order):
/// the pair's arbiter carries on with its body order.
#[inline(always)]
fn same_pair(previous: Option<&Arbiter>, ha: BodyHandle, hb: BodyHandle) -> Option<&Arbiter> {
    previous.filter(|p| (p.body_a == ha && p.body_b == hb) || (p.body_a == hb && p.body_b == ha))
}

/// Whether shape `sx` (of the key's lower slot) is body A of a new arbiter:
/// the manual's order, the shape of the smaller kind first (circles before
/// polygons), the key order breaking ties.
#[inline(always)]
fn first_in_new<S: ShapeData>(sx: &S, sy: &S) -> bool {
    sy.geometry().kind_rank() >= sx.geometry().kind_rank()
}

/// Writes the arbiter for shape `x.3` of live body `x` and shape `y.3` of
/// live body `y` (lower slot first) into `out`: the previous one if it names
/// these same bodies (a body removed and a new one in its slot has a new
/// handle; the key already matched the shapes), else a new one with the
/// bodies in canonical order.
fn pair_arbiter<S: ShapeData>(
    x: (BodyHandle, &Body, &S, u32),
    y: (BodyHandle, &Body, &S, u32),
    link: u32,
    previous: Option<&Arbiter>,
    out: &mut Arbiter,
) {
    let ((ha, a, sa, ia), (hb, b, sb, ib)) = (x, y);
    if let Some(p) = same_pair(previous, ha, hb) {
        *out = *p;
        return;
    }
    let ((first, fa, fi), (second, fb, si)) =
        if first_in_new(sa, sb) { ((ha, a, ia), (hb, b, ib)) } else { ((hb, b, ib), (ha, a, ia)) };
    *out = Arbiter {
        body_a: first,
        body_b: second,
        level_a: fa.collision_level,
        level_b: fb.collision_level,
        ..Arbiter::EMPTY
    };
    out.set_shapes(fi, si);
    out.set_steps_and_link(0, link);
}

/// A body's broad-phase proxy: its box grown by the speculative distance and
/// stretched along the path it takes this step at its present velocity, for
/// continuous collision's candidate pairs (see [`crate::continuous`]). The
/// stretch only finds pairs; contact points are made only within the
/// speculative distance of the bodies' own boxes.
///
/// The path is `v·dt` in the direction of motion, widened on every side by how
/// far a turn can carry the surface (|ω|·r·dt). Speeds are taken at most at
/// the world's limits, which the step enforces: a velocity a game set far above
/// them cannot inflate the boxes.
///
/// Growing a box whose corners are in order by a margin ≥ 0 never collapses
/// it, and growing it by `s` then `t` (both ≥ 0) is growing it by `s + t` when
/// that sum does not overflow (saturating subtraction and addition of
/// non-negative amounts), so such a box is grown once, inline, to the same
/// bits as `expand(SPECULATIVE_DISTANCE).expand(turn)`.
// Always inlined into `broad_phase`'s two refill loops: out of line it was a
// call per body each step, its box returned through the stack.
#[inline(always)]
fn proxy(ctx: &StepContext, b: &Body) -> Proxy {
    let is_static = b.body_type == BodyType::Static;
    let bx = b.aabb;
    let in_order = bx.min.x <= bx.max.x && bx.min.y <= bx.max.y;
    let grown = |margin: Scalar| {
        let m = Vector2::new(margin, margin);
        Rect { min: bx.min - m, max: bx.max + m }
    };
    if !b.moved_by_step() {
        let aabb = if in_order { grown(SPECULATIVE_DISTANCE) } else { bx.expand(SPECULATIVE_DISTANCE) };
        return Proxy { aabb, is_static };
    }
    let (vmax, wmax) = (ctx.max_linear_speed, ctx.max_angular_speed);
    let v = b.linear_velocity;
    let (dx, dy) = (v.x.clamp(-vmax, vmax) * ctx.dt, v.y.clamp(-vmax, vmax) * ctx.dt);
    let turn = b.angular_velocity.abs().min(wmax) * b.radius * ctx.dt;
    let mut aabb = match SPECULATIVE_DISTANCE.checked_add(turn) {
        Some(margin) if in_order && turn >= Scalar::ZERO => grown(margin),
        _ => bx.expand(SPECULATIVE_DISTANCE).expand(turn),
    };
    aabb.min += Vector2::new(dx.min(Scalar::ZERO), dy.min(Scalar::ZERO));
    aabb.max += Vector2::new(dx.max(Scalar::ZERO), dy.max(Scalar::ZERO));
    Proxy { aabb, is_static }
}

/// The contact manifold of shape `sa` of body `a` and shape `sb` of body
/// `b`, in canonical order (normal from A to B), with points reported up to
/// `margin` apart; anchors about the bodies' centres of mass.
#[inline]
fn collide_body_shapes<S: ShapeData>(
    (a, sa): (&Body, &S),
    (b, sb): (&Body, &S),
    paths: &ShapeStore<'_>,
    link: u32,
    margin: Scalar,
) -> Manifold {
    if !S::PLACED {
        return collide_bodies(a, b, paths, link, margin);
    }
    collide_compound((a, sa), (b, sb), paths, link, margin)
}

/// The contact manifold of two one-shape bodies in canonical order (normal
/// from A to B), with points reported up to `margin` apart.
#[inline]
fn collide_bodies(a: &Body, b: &Body, paths: &ShapeStore<'_>, link: u32, margin: Scalar) -> Manifold {
    // Two polygons (most pairs) straight to their pair function: the same
    // call `collide_canonical` makes, without building both `ShapeRef`s on
    // the stack and dispatching on them.
    match (&a.shape, &b.shape) {
        (Shape::Polygon(ha), Shape::Polygon(hb)) => {
            return match (paths.get(*ha), paths.get(*hb)) {
                (Some(pa), Some(pb)) => collide_polygons(pa, a.transform(), pb, b.transform(), margin),
                _ => Manifold::EMPTY,
            };
        }
        (Shape::Circle { radius }, Shape::Polygon(h)) => {
            return match paths.get(*h) {
                Some(p) => flip(collide_polygon_circle(p, b.transform(), *radius, a.transform(), margin)),
                None => Manifold::EMPTY,
            };
        }
        _ => {}
    }
    match (ShapeRef::of(&a.shape, paths, link), ShapeRef::of(&b.shape, paths, link)) {
        (Some(sa), Some(sb)) => collide_canonical(sa, a.transform(), sb, b.transform(), margin),
        _ => Manifold::EMPTY,
    }
}

/// [`collide_body_shapes`] when a body is compound.
#[inline(never)]
fn collide_compound<S: ShapeData>(
    (a, sa): (&Body, &S),
    (b, sb): (&Body, &S),
    paths: &ShapeStore<'_>,
    link: u32,
    margin: Scalar,
) -> Manifold {
    let (Some(ra), Some(rb)) =
        (ShapeRef::of(sa.geometry(), paths, link), ShapeRef::of(sb.geometry(), paths, link))
    else {
        return Manifold::EMPTY;
    };
    let (xa, xb) = (sa.place(a.transform()), sb.place(b.transform()));
    let mut m = collide_canonical(ra, xa, rb, xb, margin);
    // The pair functions give anchors about the shapes' frames.
    let (da, db) = (xa.p - a.position, xb.p - b.position);
    for p in m.points.iter_mut().take(m.count) {
        p.anchor_a += da;
        p.anchor_b += db;
    }
    m
}

/// A shape with its polygon path looked up: what the pair functions take.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ShapeRef<'p> {
    /// A circle of this radius about the origin of its transform.
    Circle(Scalar),
    /// A capsule.
    Capsule(&'p Capsule),
    /// A convex (possibly rounded) polygon.
    Polygon(&'p PolygonPath),
    /// A segment.
    Segment(&'p Segment),
    /// One link of a chain, with its ghost vertices.
    ChainLink(ChainSegment),
}

impl<'p> ShapeRef<'p> {
    /// The body's shape (for a chain, its link `link`); `None` for a polygon
    /// whose path is gone or a link the chain does not have.
    #[inline]
    pub(crate) fn of(shape: &'p Shape, paths: &'p ShapeStore<'_>, link: u32) -> Option<Self> {
        Some(match shape {
            Shape::Circle { radius } => Self::Circle(*radius),
            Shape::Capsule(c) => Self::Capsule(c),
            Shape::Polygon(h) => Self::Polygon(paths.get(*h)?),
            Shape::Segment(s) => Self::Segment(s),
            Shape::Chain(h) => Self::ChainLink(paths.chains.link(*h, link)?),
        })
    }

    /// [`Shape::kind_rank`] of the shape.
    #[inline]
    pub(crate) fn rank(&self) -> u8 {
        match self {
            Self::Circle(_) => 0,
            Self::Capsule(_) => 1,
            Self::Polygon(_) => 2,
            Self::Segment(_) => 3,
            Self::ChainLink(_) => 4,
        }
    }
}

/// The contact manifold of two shapes in any order (normal from `a` to `b`).
pub(crate) fn collide_shapes(
    a: ShapeRef<'_>,
    xa: Transform,
    b: ShapeRef<'_>,
    xb: Transform,
    margin: Scalar,
) -> Manifold {
    if b.rank() < a.rank() {
        flip(collide_canonical(b, xb, a, xa, margin))
    } else {
        collide_canonical(a, xa, b, xb, margin)
    }
}

/// The contact manifold of two shapes in canonical order (`a.rank() ≤
/// b.rank()`, see [`Shape::kind_rank`]); the functions that take the
/// higher-ranked shape first are flipped so the normal runs from A to B.
#[inline]
fn collide_canonical(
    a: ShapeRef<'_>,
    xa: Transform,
    b: ShapeRef<'_>,
    xb: Transform,
    margin: Scalar,
) -> Manifold {
    use ShapeRef as S;
    match (a, b) {
        (S::Circle(ra), S::Circle(rb)) => collide_circles(ra, xa, rb, xb, margin),
        (S::Polygon(pa), S::Polygon(pb)) => collide_polygons(pa, xa, pb, xb, margin),
        // The pair functions take the polygon first: computed that way, then
        // flipped so the normal runs from the circle (A) to the polygon (B).
        (S::Circle(r), S::Polygon(p)) => flip(collide_polygon_circle(p, xb, r, xa, margin)),
        (S::Circle(r), S::Capsule(c)) => flip(collide_capsule_circle(c, xb, r, xa, margin)),
        (S::Circle(r), S::Segment(sg)) => flip(collide_segment_circle(sg, xb, r, xa, margin)),
        (S::Capsule(ca), S::Capsule(cb)) => collide_capsules(ca, xa, cb, xb, margin),
        (S::Capsule(c), S::Polygon(p)) => flip(collide_polygon_capsule(p, xb, c, xa, margin)),
        (S::Capsule(c), S::Segment(sg)) => flip(collide_segment_capsule(sg, xb, c, xa, margin)),
        (S::Polygon(p), S::Segment(sg)) => flip(collide_segment_polygon(sg, xb, p, xa, margin)),
        (S::Circle(r), S::ChainLink(l)) => flip(collide_chain_segment_circle(&l, xb, r, xa, margin)),
        (S::Capsule(c), S::ChainLink(l)) => flip(collide_chain_segment_capsule(&l, xb, c, xa, margin)),
        (S::Polygon(p), S::ChainLink(l)) => flip(collide_chain_segment_polygon(&l, xb, p, xa, margin)),
        // Not canonical (a caller's mistake) or two segments, which never
        // collide (as in Box2D): the pair filters drop those pairs first.
        _ => Manifold::EMPTY,
    }
}

fn flip(mut m: Manifold) -> Manifold {
    m.normal = -m.normal;
    for p in m.points.iter_mut() {
        core::mem::swap(&mut p.anchor_a, &mut p.anchor_b);
    }
    m
}

/// True when boxes `a` and `b` are at most `d` apart on both axes.
#[inline]
fn boxes_within(a: Rect, b: Rect, d: Scalar) -> bool {
    b.min.x - a.max.x <= d && a.min.x - b.max.x <= d && b.min.y - a.max.y <= d && a.min.y - b.max.y <= d
}

/// Size of the union of two key-sorted lists, counted by body pair (a
/// chain pair's links after the first are counted only as the arbiters hold
/// them: strict capacity is approximate for chains).
fn merged_len(pairs: &[(u32, u32)], arbiters: &[Arbiter]) -> usize {
    let (mut i, mut j, mut n) = (0usize, 0usize, 0usize);
    while i < pairs.len() || j < arbiters.len() {
        match (pairs.get(i), arbiters.get(j).map(Arbiter::pair)) {
            (Some(p), Some(k)) if *p == k => {
                i = i.saturating_add(1);
                j = j.saturating_add(1);
            }
            (Some(p), Some(k)) if *p < k => i = i.saturating_add(1),
            (Some(_), None) => i = i.saturating_add(1),
            _ => j = j.saturating_add(1),
        }
        n = n.saturating_add(1);
    }
    n
}
