//! The step pipeline.
//!
//! `World::step(dt)` runs these stages in this order, each a function:
//!
//! 1. **validate**: `dt` in (0, [`MAX_TIME_STEP`]].
//! 2. **broad phase**: proxies and candidate pairs ([`crate::index`]). Every
//!    capacity the step needs is checked here, before anything changes, so a step
//!    either fails with an error and leaves the world as it was, or completes.
//! 3. **forces**: each force generator, in the order added, over the dynamic
//!    bodies it accepts (slot order). The velocity change is spread over the
//!    sub-steps by the solver.
//! 4. **narrow phase and arbiter lifecycle**: manifolds, states, and the `begin`,
//!    `pre_solve` and `end` callbacks in canonical pair order ([`crate::collision`]).
//! 5. **solve and integrate**: the sub-stepped soft contact solver, which also
//!    advances positions ([`crate::solver`]), then the restitution pass.
//! 6. **limits**: speeds clamped to the world's maxima; bodies whose centre left the
//!    bounds are frozen and reported; bounding boxes refreshed.
//! 7. **post_solve callbacks**, in canonical pair order.
//! 8. **broken joints** are removed, in joint-slot order, each handed to the
//!    break callback.
//! 9. **post-step callbacks**, once per key, in registration order, with
//!    `&mut World`: the safe place to remove bodies. Callbacks registered while
//!    these run (or outside a step) run after the next step.
//!
//! Every loop runs in body-slot or pair-key order, functions of the simulation
//! history alone.

use crate::error::Error;
use crate::math::scalar::{Scalar, ZERO};
use crate::math::Vector2;
use crate::world::{compute_aabb, StepReport, World};
use crate::MAX_TIME_STEP;

impl World<'_> {
    /// Advances the simulation by `dt` seconds.
    ///
    /// # Errors
    /// [`Error::InvalidTimeStep`] when `dt ≤ 0` or `dt > MAX_TIME_STEP`;
    /// [`Error::CapacityFull`] when the candidate pairs or arbiters do not fit the
    /// contact buffers. On error the world is unchanged.
    pub fn step(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        if dt <= ZERO || dt > MAX_TIME_STEP {
            return Err(Error::InvalidTimeStep);
        }
        let npairs = self.broad_phase(dt)?;
        self.apply_forces(dt);
        self.update_arbiters(npairs, dt);
        self.solve_and_integrate(dt);
        let left_bounds = self.enforce_limits(dt);
        self.post_solve_callbacks();
        self.step_count = self.step_count.wrapping_add(1);
        let joints_broken = self.remove_broken_joints();
        let post_step_callbacks = self.run_post_step_callbacks();
        Ok(StepReport {
            left_bounds,
            arbiters: self.contacts.arbiter_count as u32,
            post_step_callbacks,
            joints_broken,
        })
    }

    /// Runs the generators and turns their effect into a pending velocity change
    /// (restoring the velocities), which the solver spreads over the sub-steps.
    fn apply_forces(&mut self, dt: Scalar) {
        for (_, b) in self.bodies.iter_mut() {
            b.pending_v = b.linear_velocity;
            b.pending_w = b.angular_velocity;
        }
        let used = self.generators.slots_used();
        for i in 0..used {
            if let Some(g) = self.generators.get_at_mut(i) {
                g.run(&mut self.bodies, dt);
            }
        }
        for (_, b) in self.bodies.iter_mut() {
            let (v0, w0) = (b.pending_v, b.pending_w);
            b.pending_v = b.linear_velocity - v0;
            b.pending_w = b.angular_velocity - w0;
            b.linear_velocity = v0;
            b.angular_velocity = w0;
        }
    }

    /// Speed limits, bounds and bounding boxes. Returns how many bodies left the
    /// bounds this step.
    fn enforce_limits(&mut self, dt: Scalar) -> u32 {
        let bounds = self.def.bounds;
        let vmax = self.def.max_linear_speed;
        let wmax = self.angular_limit(dt);
        let mut left = 0u32;
        for (_, b) in self.bodies.iter_mut() {
            if !b.is_awake_mover() {
                continue;
            }
            // Components are clamped first so the length cannot saturate.
            let v = b.linear_velocity;
            let v = Vector2::new(v.x.clamp(-vmax, vmax), v.y.clamp(-vmax, vmax));
            // |v|² fits: each component is at most MAX_LINEAR_SPEED_LIMIT (2048).
            b.linear_velocity = if v.length_squared() > vmax * vmax { v.normalize() * vmax } else { v };
            b.angular_velocity = b.angular_velocity.clamp(-wmax, wmax);
            if !bounds.contains(b.position) {
                b.out_of_bounds = true;
                b.linear_velocity = Vector2::ZERO;
                b.angular_velocity = ZERO;
                left = left.saturating_add(1);
            }
        }
        let used = self.bodies.slots_used();
        for i in 0..used {
            let aabb = match self.bodies.get_at(i) {
                Some(b) if b.body_type != crate::BodyType::Static => compute_aabb(b, &self.paths),
                _ => continue,
            };
            if let Some(b) = self.bodies.get_at_mut(i) {
                b.aabb = aabb;
            }
        }
        left
    }

    /// Removes the joints that broke this step, in slot order, handing each to
    /// the break callback. Returns how many broke.
    fn remove_broken_joints(&mut self) -> u32 {
        let mut broken = 0u32;
        for i in 0..self.joints.slots_used() {
            if !self.joints.get_at(i).is_some_and(|j| j.broken) {
                continue;
            }
            let Some(h) = self.joints.handle_at(i) else { continue };
            if let Some(joint) = self.joints.remove(h) {
                broken = broken.saturating_add(1);
                if let Some(f) = self.break_callback {
                    f(self, h, joint);
                }
            }
        }
        broken
    }

    fn run_post_step_callbacks(&mut self) -> u32 {
        let queue = core::mem::take(&mut self.post_step);
        let mut ran = 0u32;
        for (f, key) in queue {
            f(self, key);
            ran = ran.saturating_add(1);
        }
        ran
    }
}
