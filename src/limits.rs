//! The world's limits: the ranges inside which every quantity stays exact, and
//! the step stage that keeps bodies inside them.
//!
//! Q32.32 holds ±2^31 with 2^-32 resolution, and squared quantities only up to
//! about 46,340. Every limit here is chosen so that what the engine computes from
//! validated input (positions, speeds, inertias, squared relative distances)
//! stays inside that range; inputs beyond a limit are an `Err` at the API edge,
//! and the limits stage (`enforce`) holds moving bodies to the speed limits and the bounds after
//! every step.

use crate::arena::Arena;
use crate::body::{compute_aabb, Body, BodyType};
use crate::geometry::PolygonPath;
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

/// Largest friction coefficient accepted.
pub const MAX_FRICTION: Scalar = Scalar::from_int(100);

/// Speculative contact distance, in metres (Box2D v3's 4 × linear slop): shapes
/// closer than this get contact points before they touch, so the solver can stop
/// them meeting without overshoot, and "touching" for the callbacks means "within
/// this distance".
pub const SPECULATIVE_DISTANCE: Scalar = Scalar::lit("0.02");

/// Most solver sub-steps per step.
pub const MAX_SUBSTEPS: u32 = 16;

/// The longest time step [`World::step`](crate::World::step) accepts: 0.25 s. Longer steps are never
/// physically meaningful and would let fast bodies move too far in one step.
pub const MAX_TIME_STEP: Scalar = Scalar::lit("0.25");

/// The limits stage: speeds clamped to the world's maxima, bodies whose centre
/// left the bounds frozen, bounding boxes refreshed. Returns how many bodies left
/// the bounds this step.
pub(crate) fn enforce(
    ctx: &StepContext,
    bodies: &mut Arena<'_, Body>,
    paths: &Arena<'_, PolygonPath>,
) -> u32 {
    let (vmax, wmax) = (ctx.max_linear_speed, ctx.max_angular_speed);
    let mut left = 0u32;
    for (_, b) in bodies.iter_mut() {
        if !b.moved_by_step() {
            continue;
        }
        // Components are clamped first so the length cannot saturate.
        let v = b.linear_velocity;
        let v = Vector2::new(v.x.clamp(-vmax, vmax), v.y.clamp(-vmax, vmax));
        // |v|² fits: each component is at most MAX_LINEAR_SPEED_LIMIT (2048).
        b.linear_velocity = if v.length_squared() > vmax * vmax { v.normalize() * vmax } else { v };
        b.angular_velocity = b.angular_velocity.clamp(-wmax, wmax);
        if !ctx.bounds.contains(b.position) {
            b.out_of_bounds = true;
            b.linear_velocity = Vector2::ZERO;
            b.angular_velocity = ZERO;
            left = left.saturating_add(1);
        }
    }
    for (_, b) in bodies.iter_mut() {
        if b.body_type != BodyType::Static {
            b.aabb = compute_aabb(b, paths);
        }
    }
    left
}
