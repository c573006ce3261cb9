//! Continuous collision: the stage after the solve that keeps fast bodies from
//! passing through others between two steps (Box2D v3's model).
//!
//! Contact points are made only within the constant
//! [`SPECULATIVE_DISTANCE`], whatever the speed (a margin that grew with speed
//! stopped bodies that would have passed beside each other). What a step could
//! skip over is caught here instead, once the solver has moved every body:
//!
//! * A dynamic body is **fast** when, this step, its centre moved more than
//!   half its *core extent* (the least distance from its centre to its
//!   surface: a circle's radius, a polygon's nearest face), counting a turn as
//!   `|angle|·r` (its bounding radius `r`). A slower body cannot tunnel: it
//!   ends less than half its extent inside anything, and the contact pushes it
//!   back out of the side it came from.
//! * Each fast body is swept from its pose at the start of the step to its
//!   pose now against the **static and kinematic** bodies near its path
//!   (`collide::toi`, a closed-form sweep: no iteration, so no cap to
//!   reach). A body marked [`bullet`](crate::BodyDef::bullet) is swept
//!   afterwards, also against the **dynamic** bodies (at their final poses,
//!   other bullets excepted). The earliest impact wins; the body is put back
//!   on its path at that moment, [`TOI_GAP`] short of the surface, and keeps
//!   its velocity, so the next step's contact (within the speculative
//!   distance) stops or bounces it.
//! * A body already within reach of a surface at the start of the step (it
//!   touches the floor it slides on) is swept by its **core** instead, a circle
//!   of a quarter of its core extent at its centre: it cannot pass through the
//!   floor, and it is not held back by it either.
//! * Pairs the game keeps apart are skipped: the collision filter, joints that
//!   do not collide their bodies, and pairs whose arbiter was not solved this
//!   step (`begin` or `pre_solve` said no): a bullet through a one-way
//!   platform goes through.
//!
//! The rotation over the step is not swept: each body's shape is taken at its
//! pose at the start of the step, and the distance to reach is widened by how
//! far a turn can carry its surface (`|angle|·r`), so an impact is never
//! found late, only early by at most that much.
//!
//! Order: the bodies' sweeps against static and kinematic bodies read nothing
//! another sweep writes; bullets come after all of them, in body-slot order,
//! and read only non-bullet bodies. The result depends on the simulation state
//! alone.
//!
//! Near-path candidates come from the broad phase, whose boxes are stretched
//! along each body's motion at its velocity when the step began. A fast body
//! whose box now lies outside its broad-phase box (its velocity changed a lot
//! in the step) is swept against every body whose box meets its path instead.

use crate::arbiter::{ArbiterState, ArbiterStore};
use crate::arena::Arena;
use crate::body::{compute_aabb, Body, BodyType, Shape, ShapeStore};
use crate::collide::{time_of_impact, Swept};
use crate::collision::{contact_shapes, BroadPhase};
use crate::compound::{is_compound, shapes_of};
use crate::geometry::chain::local_rect;
use crate::geometry::PolygonPath;
use crate::index::Proxy;
use crate::limits::SPECULATIVE_DISTANCE;
use crate::math::scalar::{ONE, ZERO};
use crate::math::{Rect, Rot, Scalar, Transform, Vector2};
use crate::solver::SolverBody;

/// How far short of a surface a fast body is put back (m): a quarter of the
/// speculative distance (Box2D v3's linear slop), so that the next step's
/// narrow phase finds the contact.
pub const TOI_GAP: Scalar = Scalar::from_bits(SPECULATIVE_DISTANCE.to_bits() / 4);

/// The share of its core extent a body may move in one step without being
/// swept (Box2D v3's default safety factor).
const SAFETY: Scalar = Scalar::lit("0.5");

/// The core's radius as a share of the core extent.
const CORE: Scalar = Scalar::lit("0.25");

/// What continuous collision did in a step (for the step report).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Outcome {
    /// Pair sweeps computed.
    pub(crate) sweeps: u32,
    /// Fast bodies put back to a time of impact.
    pub(crate) hits: u32,
}

/// Fast-body marks in [`SolverBody::ccd`].
pub(crate) const FAST: u8 = 1;
/// The body's final box left its broad-phase box: swept against every body
/// whose box meets its path.
const SCAN: u8 = 2;

/// The least distance from a body's centre to its surface (m); for a
/// compound body, the least of its solid shapes' (each about its own centre).
fn core_extent(b: &Body, paths: &ShapeStore<'_>) -> Scalar {
    if !is_compound(b) {
        return shape_core_extent(b.shape, paths);
    }
    shapes_of(b, paths)
        .filter(|(_, s)| !s.sensor)
        .map(|(_, s)| shape_core_extent(s.shape, paths))
        .reduce(Scalar::min)
        .unwrap_or(ZERO)
}

/// The least distance from a shape's centre to its surface (m).
fn shape_core_extent(shape: Shape, paths: &ShapeStore<'_>) -> Scalar {
    match shape {
        Shape::Circle { radius } => radius,
        Shape::Polygon(h) => paths.get(h).map_or(ZERO, PolygonPath::core_extent),
        // The thickness a capsule keeps whatever its length; a segment has none.
        Shape::Capsule(c) => c.radius(),
        Shape::Segment(_) | Shape::Chain(_) => ZERO,
    }
}

/// The swept form of a shape.
fn swept<'p>(shape: &'p Shape, paths: &'p ShapeStore<'_>) -> Option<Swept<'p>> {
    match shape {
        Shape::Circle { radius } => Some(Swept::Circle(*radius)),
        Shape::Polygon(h) => paths.get(*h).map(Swept::Polygon),
        Shape::Capsule(c) => Some(Swept::Capsule(c)),
        Shape::Segment(sg) => Some(Swept::Segment(sg)),
        // Swept link by link (see `Pass::pair`).
        Shape::Chain(_) => None,
    }
}

/// Runs continuous collision after the solve. `solver` holds every body's
/// pose at the start of the step (`p0`, `q0`) and its turn (`angle`); the
/// bodies hold their poses now (still with their start-of-step boxes).
pub(crate) fn run(
    bodies: &mut Arena<'_, Body>,
    paths: &ShapeStore<'_>,
    solver: &mut [SolverBody],
    bp: &BroadPhase<'_>,
    candidates: usize,
    arbiters: &ArbiterStore<'_>,
) -> Outcome {
    let mut out = Outcome::default();
    // Which bodies are fast, and whether a non-bullet, a bullet is: a pass
    // without a fast body of its kind sweeps nothing and is skipped.
    let mut fast = [false; 2];
    for (h, b) in bodies.iter() {
        let Some(sb) = solver.get_mut(h.index() as usize) else { continue };
        sb.ccd = 0;
        sb.toi = ONE;
        if b.body_type != BodyType::Dynamic || b.out_of_bounds {
            continue;
        }
        let d = b.position - sb.p0;
        let motion = d.x.abs() + d.y.abs() + sb.angle.abs() * b.radius;
        if motion > core_extent(b, paths) * SAFETY {
            sb.ccd = FAST;
            if let Some(f) = fast.get_mut(usize::from(b.bullet)) {
                *f = true;
            }
        }
    }
    if fast == [false; 2] {
        return out;
    }
    // A fast body whose box now is outside its broad-phase box was not
    // covered by the candidate pairs.
    let proxies = bp.proxies.get(..bp.live).unwrap_or(&[]);
    let slots = bp.proxy_bodies.get(..bp.live).unwrap_or(&[]);
    for (p, &s) in proxies.iter().zip(slots) {
        let (Some(sb), Some(b)) = (solver.get_mut(s as usize), bodies.get_at(s)) else { continue };
        if sb.ccd & FAST != 0 && !p.aabb.contains_rect(compute_aabb(b, paths)) {
            sb.ccd |= SCAN;
        }
    }
    let held = bp.joint_pairs.get(..bp.held).unwrap_or(&[]);
    for bullets in [false, true] {
        if fast.get(usize::from(bullets)) != Some(&true) {
            continue;
        }
        let pass = Pass { bodies: &*bodies, paths, arbiters, held, bullets };
        // Candidate pairs, each way round. Most candidates have no fast
        // body: tested here, before the call (`pair` tests it again), the
        // non-bullet pass costs fewer calls (mixed 180 steps: 935.6 -> 908.8 M
        // instructions).
        for &(x, y) in bp.candidates(candidates) {
            for (f, o) in [(x, y), (y, x)] {
                if solver.get(f as usize).is_none_or(|s| s.ccd & FAST == 0) {
                    continue;
                }
                if let Some(t) = pass.pair(solver, f, o, false, &mut out.sweeps) {
                    if let Some(sb) = solver.get_mut(f as usize) {
                        sb.toi = sb.toi.min(t);
                    }
                }
            }
        }
        // Bodies whose path left their broad-phase box: every body whose box
        // meets the path (`scan`).
        scan(&pass, proxies, slots, solver, &mut out.sweeps);
        // This pass's impacts: each body back on its path at its earliest one.
        for (h, b) in bodies.iter_mut() {
            let Some(sb) = solver.get(h.index() as usize) else { continue };
            if sb.ccd & FAST == 0 || b.bullet != bullets || sb.toi >= ONE {
                continue;
            }
            let t = sb.toi;
            b.position = sb.p0 + (b.position - sb.p0) * t;
            let (c, s) = (sb.q0.c + (b.rotation.c - sb.q0.c) * t, sb.q0.s + (b.rotation.s - sb.q0.s) * t);
            b.rotation = Rot { c, s }.normalized();
            out.hits = out.hits.saturating_add(1);
        }
    }
    out
}

/// The sweeps of the bodies whose path left their broad-phase box (marked
/// [`SCAN`]) against every body whose box meets the path and that the pass
/// can stop them against, each body's earliest impact kept in its `toi`.
///
/// Every such pair is swept once whichever loop is outside, and the earliest
/// impact does not depend on the order, so the loop over the fewer bodies is
/// outside: the scanning bodies (a few bodies knocked far off their course),
/// or the targets (in the non-bullet pass only static and kinematic bodies).
/// With the scanning bodies always outside this was quadratic: Box2D's joint
/// grid (10,000 pivoted circles hung from 7 static ones, hundreds of them
/// whipped off course in a step) spent 11.8 % of its step here, 2.0 % now;
/// a variant of it with 8,500 bodies to scan, 71 %.
fn scan(pass: &Pass<'_, '_>, proxies: &[Proxy], slots: &[u32], solver: &mut [SolverBody], sweeps: &mut u32) {
    let bodies = pass.bodies;
    let scanning = |f: u32, solver: &[SolverBody]| {
        let scans = solver.get(f as usize).is_some_and(|sb| sb.ccd & SCAN != 0);
        scans && bodies.get_at(f).is_some_and(|b| b.bullet == pass.bullets)
    };
    let target = |o: u32| bodies.get_at(o).is_some_and(|b| pass.can_stop_against(b));
    // Most steps scan nothing: count the scanning bodies first, and only then
    // the targets (which reads every body).
    let scans = slots.iter().filter(|&&s| scanning(s, solver)).count();
    if scans == 0 {
        return;
    }
    let targets = slots.iter().filter(|&&s| target(s)).count();
    if targets == 0 {
        return;
    }
    let path_of = |p: &Proxy, f: u32| {
        bodies.get_at(f).map(|b| p.aabb.union(compute_aabb(b, pass.paths)).expand(SPECULATIVE_DISTANCE))
    };
    let mut sweep = |f: u32, o: u32, solver: &mut [SolverBody]| {
        if let Some(t) = pass.pair(solver, f, o, true, sweeps) {
            if let Some(sb) = solver.get_mut(f as usize) {
                sb.toi = sb.toi.min(t);
            }
        }
    };
    if scans <= targets {
        for (p, &f) in proxies.iter().zip(slots) {
            if !scanning(f, solver) {
                continue;
            }
            let Some(path) = path_of(p, f) else { continue };
            for (q, &o) in proxies.iter().zip(slots) {
                if o != f && q.aabb.overlaps(path) {
                    sweep(f, o, solver);
                }
            }
        }
    } else {
        for (q, &o) in proxies.iter().zip(slots) {
            if !target(o) {
                continue;
            }
            for (p, &f) in proxies.iter().zip(slots) {
                if o == f || !scanning(f, solver) {
                    continue;
                }
                if path_of(p, f).is_some_and(|path| q.aabb.overlaps(path)) {
                    sweep(f, o, solver);
                }
            }
        }
    }
}

/// One pass's view: the non-bullet fast bodies against static and kinematic
/// bodies, or the bullets against every non-bullet body.
struct Pass<'p, 'a> {
    bodies: &'p Arena<'a, Body>,
    paths: &'p ShapeStore<'a>,
    arbiters: &'p ArbiterStore<'a>,
    /// Body-slot pairs a joint keeps from colliding, sorted.
    held: &'p [(u32, u32)],
    bullets: bool,
}

impl Pass<'_, '_> {
    /// Whether this pass sweeps its fast bodies against `b` at all (the
    /// first test of [`pair`](Self::pair) on the target).
    fn can_stop_against(&self, b: &Body) -> bool {
        !b.out_of_bounds
            && match b.body_type {
                BodyType::Static | BodyType::Kinematic => true,
                BodyType::Dynamic => self.bullets && !b.bullet,
            }
    }

    /// The time of impact of fast body `f` against body `o`, if this pass
    /// sweeps that pair and they meet on the way. `filter` applies the
    /// broad phase's pair filter (the candidate pairs have passed it).
    fn pair(&self, solver: &[SolverBody], f: u32, o: u32, filter: bool, sweeps: &mut u32) -> Option<Scalar> {
        let (sf, so) = (solver.get(f as usize)?, solver.get(o as usize)?);
        let (bf, bo) = (self.bodies.get_at(f)?, self.bodies.get_at(o)?);
        // Sensors never stop anything, and are never stopped (for compound
        // bodies, shape by shape below).
        if sf.ccd & FAST == 0 || bf.bullet != self.bullets || !self.can_stop_against(bo) {
            return None;
        }
        // The target's pose to sweep against: static and kinematic bodies move
        // (or not) from their pose at the start of the step; a dynamic one
        // (bullets only, bullets excepted) stands at its final pose.
        let (xo, motion_o, turn_o) = match bo.body_type {
            BodyType::Static | BodyType::Kinematic => {
                (Transform::new(so.p0, so.q0), bo.position - so.p0, so.angle)
            }
            BodyType::Dynamic => (bo.transform(), Vector2::ZERO, ZERO),
        };
        let key = (f.min(o), f.max(o));
        if filter && self.held.binary_search(&key).is_ok() {
            return None;
        }
        // A pair the game chose not to solve this step is not stopped either:
        // one of its arbiters refused (`begin` said no, or `pre_solve` did for
        // points it has) and none is solved (a chain or compound bodies have
        // several). An arbiter without points carries no such choice: one kept
        // after its bodies parted, beside a link the body left, must not let it
        // pass through another link.
        let live = self.arbiters.live();
        let first = live.partition_point(|a| a.pair() < key);
        let pair = live.get(first..).unwrap_or(&[]).iter().take_while(|a| a.pair() == key);
        let (mut solved, mut refused) = (false, false);
        for a in pair {
            solved |= a.solve;
            refused |= a.state == ArbiterState::Ignoring || (a.count > 0 && !a.solve);
        }
        if refused && !solved {
            return None;
        }
        let xf = Transform::new(sf.p0, sf.q0);
        let d = (bf.position - sf.p0) - motion_o;
        let reach_o = turn_o.abs() * bo.radius;
        let gap = TOI_GAP + reach_o + sf.angle.abs() * bf.radius;
        // One shape of the fast body (at `xs`, core radius `core`) against one
        // of the target's (at `xt`).
        let sweep = |shape_o: Swept<'_>,
                     xt: Transform,
                     shape_f: Swept<'_>,
                     xs: Transform,
                     core: Scalar,
                     sweeps: &mut u32| {
            *sweeps = sweeps.saturating_add(1);
            let t = time_of_impact(shape_o, xt, shape_f, xs, d, gap)?;
            if t > ZERO {
                return Some(t);
            }
            // Within reach already: sweep the core, which does not turn.
            let core = Swept::Circle(core);
            *sweeps = sweeps.saturating_add(1);
            time_of_impact(shape_o, xt, core, xs, d, TOI_GAP + reach_o).filter(|&t| t > ZERO)
        };
        let (cf, co) = (is_compound(bf), is_compound(bo));
        // The filters, per shape pair (the candidate pairs of one-shape
        // bodies have passed them).
        let check = filter || cf || co;
        let mut best = None::<Scalar>;
        let mut earliest = |t: Option<Scalar>| {
            if let Some(t) = t {
                best = Some(best.map_or(t, |b: Scalar| b.min(t)));
            }
        };
        for (_, sh_f) in shapes_of(bf, self.paths) {
            if sh_f.sensor {
                continue;
            }
            let Some(shape_f) = swept(&sh_f.shape, self.paths) else { continue };
            let xs = sh_f.world(xf, cf);
            let core = shape_core_extent(sh_f.shape, self.paths) * CORE;
            for (_, sh_o) in shapes_of(bo, self.paths) {
                if sh_o.sensor || (check && !contact_shapes(bf, &sh_f, bo, &sh_o)) {
                    continue;
                }
                let xt = sh_o.world(xo, co);
                let Shape::Chain(h) = sh_o.shape else {
                    let Some(shape_o) = swept(&sh_o.shape, self.paths) else { continue };
                    earliest(sweep(shape_o, xt, shape_f, xs, core, sweeps));
                    continue;
                };
                // A chain: each link near the path whose front the body starts in
                // front of (links are one-sided), the earliest impact.
                let r = Vector2::new(bf.radius, bf.radius);
                let path = Rect::from_center(sf.p0, r).union(Rect::from_center(bf.position, r)).expand(gap);
                let query = local_rect(path, xt);
                let start = xt.apply_inv(xs.p);
                let mut link = 0u32;
                while let Some(k) = self.paths.chains.next_link(h, link, query) {
                    link = k.saturating_add(1);
                    let Some(l) = self.paths.chains.link(h, k) else { break };
                    let (p1, p2) = (l.segment().point1(), l.segment().point2());
                    if (p2 - p1).cross(start - p1) > ZERO {
                        continue;
                    }
                    let seg = l.segment();
                    earliest(sweep(Swept::Segment(&seg), xt, shape_f, xs, core, sweeps));
                    if k == u32::MAX {
                        break;
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gap_is_a_quarter_of_the_speculative_distance() {
        assert_eq!(TOI_GAP, Scalar::lit("0.005"));
    }
}
