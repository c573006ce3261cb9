//! The world's limits: the ranges inside which every quantity stays exact, and
//! the step stage that keeps bodies inside them.
//!
//! Q32.32 holds ±2^31 with 2^-32 resolution, and squared quantities only up to
//! about 46,340. Every limit here is chosen so that what the engine computes from
//! validated input (positions, speeds, inertias, squared relative distances)
//! stays inside that range; inputs beyond a limit are an `Err` at the API edge,
//! and the limits stage (`enforce`) holds moving bodies to the speed limits and the bounds after
//! every step.
//!
//! Every value has one check, called by the constructor (`add_body`, `add_joint`,
//! `add_force_generator`, `World::new`), by its setter and by `restore`: a world's
//! own snapshot therefore always restores, and a rejected value leaves the world
//! unchanged. The table in the crate docs lists every range; the reasons are on
//! the constants below and in [`geometry::mass`](crate::geometry::mass) (mass and
//! moment of inertia: a body is legal only when both are in range, so mass ×
//! size² is bounded, e.g. a 128 m circle weighs at most 122 kg).

use crate::arena::Arena;
use crate::body::ShapeStore;
use crate::body::{compute_aabb, Body, BodyType};
use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::step::StepContext;

/// Largest |coordinate| of the world bounds, in metres (2^20 ≈ 1,048 km).
///
/// Keeping positions within ±2^20 leaves 2^11 of headroom in Q32.32 for a body to
/// move past the bounds in one step before it is frozen, so positions never overflow.
pub const MAX_COORDINATE: Scalar = Scalar::from_int(1 << 20);

/// Largest bounding radius of a body about its centre of mass, in metres: the
/// geometry limits ([`MAX_CIRCLE_RADIUS`](crate::geometry::circle::MAX_CIRCLE_RADIUS),
/// [`MAX_POLYGON_RADIUS`](crate::geometry::polygon_path::MAX_POLYGON_RADIUS)), set so
/// that the unit moment of inertia (∝ r⁴) stays 5× inside Q32.32's range.
pub const MAX_BODY_RADIUS: Scalar = crate::geometry::circle::MAX_CIRCLE_RADIUS;

/// Highest speed limit a world may be configured with, in m/s.
///
/// With the longest time step ([`MAX_TIME_STEP`]) a body
/// moves at most 512 m per step, and squared speeds (≤ 8.4e6) stay exact.
pub const MAX_LINEAR_SPEED_LIMIT: Scalar = Scalar::from_int(2048);

/// Highest angular speed limit a world may be configured with, in rad/s. With
/// inertia ≤ [`MAX_INERTIA`](crate::geometry::mass::MAX_INERTIA) (1e6 kg·m²) the
/// angular momentum stays ≤ 2.6e8, 8× inside Q32.32's range.
pub const MAX_ANGULAR_SPEED_LIMIT: Scalar = Scalar::from_int(256);

/// Largest friction coefficient accepted, on a body and on an arbiter
/// ([`Arbiter::set_friction`](crate::Arbiter::set_friction)).
///
/// Real materials stay below 2; a coefficient of 100 already holds a body on an
/// 89.4° slope, so larger ones only feed the saturating friction bound μ·λn.
pub const MAX_FRICTION: Scalar = Scalar::from_int(100);

/// Largest restitution accepted: 1 (elastic). Above it a collision would add
/// energy at every bounce.
pub const MAX_RESTITUTION: Scalar = crate::math::scalar::ONE;

/// Largest steps an arbiter is kept after its bodies separate
/// ([`WorldDef::arbiter_persistence`](crate::WorldDef::arbiter_persistence)):
/// 256 steps (4 s at 60 Hz).
///
/// A separated arbiter keeps its slot in the arbiter store for that many steps;
/// at `u32::MAX` arbiters would never expire and the store would fill with pairs
/// that no longer touch. Warm starting only helps contacts that flicker for a few
/// steps, so nothing is lost by the bound.
pub const MAX_ARBITER_PERSISTENCE: u32 = 256;

/// The default [`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance):
/// 0.05 m, Box2D v3's (ten times its 5 mm linear slop).
pub const DEFAULT_CONTACT_RECYCLE_DISTANCE: Scalar = Scalar::lit("0.05");

/// The largest [`WorldDef::contact_recycle_distance`](crate::WorldDef::contact_recycle_distance):
/// 0.25 m, five times the default. A manifold kept over more relative motion
/// than that misses new contact points (a box tipping onto a corner) for
/// longer than a game would accept.
pub const MAX_CONTACT_RECYCLE_DISTANCE: Scalar = Scalar::lit("0.25");

/// Largest acceleration a built-in force generator applies, per component,
/// m/s² (2^14 ≈ 1,670 g): [`GravityForceGenerator`](crate::GravityForceGenerator)'s
/// gravity and [`GravityToPointForceGenerator`](crate::GravityToPointForceGenerator)'s
/// acceleration.
///
/// In the longest step (0.25 s) one generator changes a velocity by at most
/// 4,096 m/s per component, twice the highest speed limit: it can turn a body at
/// top speed around in one step, and the heaviest body's momentum after the
/// forces stays below 1e5 kg · (2,048 + 5,793) m/s ≈ 7.9e8 kg·m/s, 2.7× inside
/// Q32.32's range.
pub const MAX_ACCELERATION: Scalar = Scalar::from_int(1 << 14);

/// Largest force a [`LinearForceGenerator`](crate::LinearForceGenerator) applies,
/// per component, N: [`MAX_MASS`](crate::geometry::mass::MAX_MASS) ×
/// [`MAX_ACCELERATION`] ≈ 1.6e9 N, the force that gives the heaviest body the
/// largest acceleration.
///
/// The momentum it adds in the longest step (F·dt ≤ 4.1e8 N·s) stays inside
/// Q32.32's range whatever the mass. On a light body the velocity change F·dt/m
/// can exceed the speed limits; it saturates and the step clamps the speed, as it
/// does for any velocity a game sets.
pub const MAX_FORCE: Scalar = Scalar::from_int(1_638_400_000);

/// Largest spring stiffness, N/m (1e6).
///
/// The spring force k·(ℓ − ℓ₀) stays exact for stretches up to 2,147 m, twice
/// the longest joint ([`MAX_JOINT_LENGTH`]). Springs are explicit forces, stable
/// only while k·h² < m: at 1e6 N/m and a 1/240 s sub-step only bodies above
/// 17 kg stay stable, so stiffer springs are never useful (use a rod).
pub const MAX_STIFFNESS: Scalar = Scalar::from_int(1_000_000);

/// Largest spring damping, N·s/m (1e5).
///
/// At a relative speed of 4,096 m/s (two bodies at the highest speed limit) the
/// damping force is 4.1e8 N, 5× inside Q32.32's range. An explicit damper is
/// stable only while c·h < 2m, so a larger damping is never useful.
pub const MAX_DAMPING: Scalar = Scalar::from_int(100_000);

/// Longest joint: a rod's or rope's length and a spring's rest length, m (1,024 =
/// 8 × [`MAX_BODY_RADIUS`]). Squared anchor distances up to this length stay
/// inside Q32.32's range for squared quantities (1,024² ≈ 1e6).
pub const MAX_JOINT_LENGTH: Scalar = Scalar::from_int(1024);

/// Fastest relative spin a pivot's motor may target, rad/s (512 = 2 ×
/// [`MAX_ANGULAR_SPEED_LIMIT`]): the largest ωB − ωA two bodies can have under
/// the highest spin limit; a faster target could never be reached.
pub const MAX_MOTOR_SPEED: Scalar = Scalar::from_int(512);

/// Highest frequency of a target joint's spring, Hz (1,000, the contacts' own
/// limit): ω = 2π·1,000 keeps h·ω and the soft coefficients exact at any
/// sub-step, and a spring that stiff already follows its target within a
/// sub-step at 240 Hz.
pub const MAX_TARGET_HERTZ: Scalar = Scalar::from_int(1000);

/// Largest damping ratio of a target joint (100, the contacts' own limit):
/// far past critical (1) the spring only creeps towards its target.
pub const MAX_DAMPING_RATIO: Scalar = Scalar::from_int(100);

/// Largest linear or angular damping of a body, 1/s
/// ([`BodyDef::linear_damping`](crate::BodyDef::linear_damping)).
///
/// Damping scales a velocity by 1 / (1 + h·c) each sub-step; with the longest
/// sub-step (0.25 s) h·c ≤ 256 stays exact and the factor ≥ 1/257 stays far
/// above Q32.32's resolution. A damping of 1,024 /s already stops a body within
/// a few milliseconds, so a larger one is never useful.
pub const MAX_BODY_DAMPING: Scalar = Scalar::from_int(1024);

/// Largest |gravity scale| of a body
/// ([`BodyDef::gravity_scale`](crate::BodyDef::gravity_scale)): 16. The gravity
/// generators clamp the scaled acceleration to ±[`MAX_ACCELERATION`] per
/// component, so a scale never takes a step outside the range that limit keeps.
pub const MAX_GRAVITY_SCALE: Scalar = Scalar::from_int(16);

/// A body's linear or angular damping: [0, [`MAX_BODY_DAMPING`]] (bodies, restore).
pub(crate) fn check_damping(c: Scalar) -> Result<(), Error> {
    check_range(c, ZERO, MAX_BODY_DAMPING, "damping")
}

/// A body's gravity scale: [−[`MAX_GRAVITY_SCALE`], [`MAX_GRAVITY_SCALE`]]
/// (bodies, restore).
pub(crate) fn check_gravity_scale(s: Scalar) -> Result<(), Error> {
    check_range(s, -MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE, "gravity scale")
}

/// `Ok` when `lo ≤ v ≤ hi`, else [`Error::OutOfRange`] naming `what`: the one
/// range check every constructor, setter and `restore` calls.
pub(crate) fn check_range(v: Scalar, lo: Scalar, hi: Scalar, what: &'static str) -> Result<(), Error> {
    if v >= lo && v <= hi {
        Ok(())
    } else {
        Err(Error::OutOfRange { what })
    }
}

/// A friction coefficient: [0, [`MAX_FRICTION`]] (bodies, arbiters, restore).
pub(crate) fn check_friction(mu: Scalar) -> Result<(), Error> {
    check_range(mu, ZERO, MAX_FRICTION, "friction")
}

/// A restitution: [0, [`MAX_RESTITUTION`]] (bodies, arbiters, restore).
pub(crate) fn check_restitution(e: Scalar) -> Result<(), Error> {
    check_range(e, ZERO, MAX_RESTITUTION, "restitution")
}

/// Each component of `v` in [−`max`, `max`].
pub(crate) fn check_components(v: Vector2, max: Scalar, what: &'static str) -> Result<(), Error> {
    check_range(v.x, -max, max, what)?;
    check_range(v.y, -max, max, what)
}

/// Speculative contact distance, in metres (Box2D v3's 4 × linear slop): shapes
/// closer than this get contact points before they touch, so the solver can stop
/// them meeting without overshoot, and "touching" for the callbacks means "within
/// this distance". It is the same at every speed: a margin that grew with speed
/// made contact points between bodies that would pass beside each other (ghost
/// hits). What one step could carry a fast body through is caught by continuous
/// collision ([`crate::continuous`]).
pub const SPECULATIVE_DISTANCE: Scalar = Scalar::lit("0.02");

/// Most solver sub-steps per step.
pub const MAX_SUBSTEPS: u32 = 16;

/// The longest time step [`World::step`](crate::World::step) accepts: 0.25 s. Longer steps are never
/// physically meaningful and would let fast bodies move too far in one step.
pub const MAX_TIME_STEP: Scalar = Scalar::lit("0.25");

/// The shortest time step [`World::step`](crate::World::step) accepts: 2^-16 s
/// (about 15 µs, 65,536 steps per second).
///
/// With up to [`MAX_SUBSTEPS`] (16 = 2^4) sub-steps the sub-step h is at least
/// 2^-20 s, so its inverse 1/h ≤ 2^20 per second fits the solver's rate format
/// with room to spare (the contact solver's 32-bit formats are derived from this
/// bound, `docs/design/solver-lanes.md` §2.2, limit L3). Without it, 1/h would
/// saturate Q32.32 for steps below about 2^-27 s and the speculative thresholds
/// and softness would be silently wrong. No game steps this finely: 2^-16 s is
/// 1,000 times shorter than a 60 Hz frame.
pub const MIN_TIME_STEP: Scalar = Scalar::from_bits(1 << 16);

/// The limits stage: speeds clamped to the world's maxima, bodies whose centre
/// left the bounds frozen, bounding boxes refreshed. Returns how many bodies left
/// the bounds this step.
pub(crate) fn enforce(ctx: &StepContext, bodies: &mut Arena<'_, Body>, paths: &ShapeStore<'_>) -> u32 {
    let (vmax, wmax) = (ctx.max_linear_speed, ctx.max_angular_speed);
    let mut left = 0u32;
    // |v|² is compared with vmax² (it fits: each component is clamped to at
    // most MAX_LINEAR_SPEED_LIMIT, 2048, first).
    let vmax2 = vmax * vmax;
    // One pass: each body's clamps, freeze and box depend on that body alone.
    for (_, b) in bodies.iter_mut() {
        if b.body_type == BodyType::Static {
            continue;
        }
        if !b.out_of_bounds {
            // Components are clamped first so the length cannot saturate.
            let v = b.linear_velocity;
            let v = Vector2::new(v.x.clamp(-vmax, vmax), v.y.clamp(-vmax, vmax));
            b.linear_velocity = if v.length_squared() > vmax2 { v.normalize() * vmax } else { v };
            b.angular_velocity = b.angular_velocity.clamp(-wmax, wmax);
            if !ctx.bounds.contains(b.position) {
                b.out_of_bounds = true;
                b.linear_velocity = Vector2::ZERO;
                b.angular_velocity = ZERO;
                left = left.saturating_add(1);
            }
        }
        b.aabb = compute_aabb(b, paths);
    }
    left
}
