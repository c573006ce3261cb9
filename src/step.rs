//! The step pipeline.
//!
//! `World::step(dt)` runs these stages in this order, each a function below:
//!
//! 1. **validate**: `dt` in (0, [`MAX_TIME_STEP`]]; nothing changes on error.
//! 2. **forces**: each force generator, in the order added, over the dynamic bodies
//!    it accepts (slot order). Semi-implicit Euler: velocities change first.
//! 3. **clamp**: speeds limited to the world's maxima.
//! 4. **integrate**: positions advance with the new velocities, x += v·dt and
//!    q ← q·(1 + i·ω·dt) renormalised.
//! 5. **bounds**: a body whose centre left the bounds is frozen and reported.
//!
//! Every loop runs in body-slot order, a function of simulation history alone.

use crate::error::Error;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;
use crate::world::{compute_aabb, StepReport, World};
use crate::MAX_TIME_STEP;

impl World<'_> {
    /// Advances the simulation by `dt` seconds.
    ///
    /// # Errors
    /// [`Error::InvalidTimeStep`] when `dt ≤ 0` or `dt > MAX_TIME_STEP`; the world
    /// is then unchanged.
    pub fn step(&mut self, dt: Scalar) -> Result<StepReport, Error> {
        if dt <= ZERO || dt > MAX_TIME_STEP {
            return Err(Error::InvalidTimeStep);
        }
        self.apply_forces(dt);
        self.clamp_velocities(dt);
        let left_bounds = self.integrate_positions(dt);
        self.step_count = self.step_count.wrapping_add(1);
        Ok(StepReport { left_bounds })
    }

    fn apply_forces(&mut self, dt: Scalar) {
        let used = self.generators.slots_used();
        for i in 0..used {
            if let Some(g) = self.generators.get_at_mut(i) {
                g.run(&mut self.bodies, dt);
            }
        }
    }

    /// Limits every moving body's speed. Components are clamped first so the
    /// length that follows cannot saturate; angular speed is also limited to a
    /// quarter turn per step, which keeps the rotation update accurate.
    fn clamp_velocities(&mut self, dt: Scalar) {
        let vmax = self.def.max_linear_speed;
        let quarter_turn = scalar::div(scalar::FRAC_PI_2.saturating_mul(scalar::HALF), dt);
        let wmax = self.def.max_angular_speed.min(quarter_turn);
        for (_, b) in self.bodies.iter_mut() {
            if !b.is_awake_mover() {
                continue;
            }
            let v = b.linear_velocity;
            let v = Vector2::new(
                scalar::clamp(v.x, -vmax, vmax),
                scalar::clamp(v.y, -vmax, vmax),
            );
            let (dir, len) = v.normalize_and_length();
            b.linear_velocity = if len > vmax { dir * vmax } else { v };
            b.angular_velocity = scalar::clamp(b.angular_velocity, -wmax, wmax);
        }
    }

    /// Advances positions and rotations; freezes bodies that left the bounds.
    /// Returns how many left this step.
    fn integrate_positions(&mut self, dt: Scalar) -> u32 {
        let bounds = self.def.bounds;
        let mut left = 0u32;
        for (_, b) in self.bodies.iter_mut() {
            if !b.is_awake_mover() {
                continue;
            }
            b.position += b.linear_velocity * dt;
            b.rotation = b.rotation.integrate(b.angular_velocity.saturating_mul(dt));
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
}
