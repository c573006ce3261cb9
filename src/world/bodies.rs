//! The body and polygon-path API of [`World`]: create, read, move, remove.

use crate::arena::Handle;
use crate::body::{
    compute_aabb, Body, BodyDef, BodyHandle, BodyType, CollisionFilter, MassSpec, PathHandle, Shape,
};
use crate::collision;
use crate::error::Error;
use crate::geometry::circle::{circle_area, circle_unit_inertia};
use crate::geometry::{Capsule, MassData, PolygonPath, Segment};
use crate::limits::{
    check_damping, check_friction, check_gravity_scale, check_restitution, MAX_BODY_RADIUS, MAX_TIME_STEP,
    MIN_TIME_STEP,
};
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::{Rect, Rot, Vector2};

use super::World;

impl World<'_> {
    // ---- polygon paths -------------------------------------------------------

    /// Stores a polygon path for bodies to share.
    ///
    /// # Errors
    /// [`Error::CapacityFull`] when the path store is full.
    pub fn add_path(&mut self, path: PolygonPath) -> Result<PathHandle, Error> {
        self.paths.insert(path).map_err(|_| Error::CapacityFull { what: "path" })
    }

    /// The path behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn path(&self, h: PathHandle) -> Result<&PolygonPath, Error> {
        self.paths.get(h).ok_or(Error::StaleHandle)
    }

    /// Removes a path no body uses any more.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::InvalidOperation`] while a body uses it.
    pub fn remove_path(&mut self, h: PathHandle) -> Result<PolygonPath, Error> {
        if !self.paths.contains(h) {
            return Err(Error::StaleHandle);
        }
        let used = |s: &Shape| *s == Shape::Polygon(h);
        if self.bodies.iter().any(|(_, b)| used(&b.shape))
            || self.paths.slots.iter().any(|(_, s)| used(&s.data.shape))
        {
            return Err(Error::InvalidOperation { what: "remove a path that bodies use" });
        }
        self.paths.remove(h).ok_or(Error::StaleHandle)
    }

    // ---- bodies --------------------------------------------------------------

    /// Creates a body.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a radius, mass, density, friction, restitution,
    /// damping, gravity scale, speed or rotation outside its range; [`Error::StaleHandle`] for an unknown
    /// polygon path; [`Error::OutsideBounds`] when the position is outside the
    /// world; [`Error::CapacityFull`] when the body store is full.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyHandle, Error> {
        let body = self.build_body(&def)?;
        self.bodies.insert(body).map_err(|_| Error::CapacityFull { what: "body" })
    }

    fn build_body(&self, def: &BodyDef) -> Result<Body, Error> {
        if matches!(def.shape, Shape::Chain(_)) && def.body_type != BodyType::Static {
            return Err(Error::InvalidOperation { what: "a chain has no mass: its body must be static" });
        }
        let (shape, offset) = centred(def.shape);
        let (area, unit_inertia, radius) = self.shape_geometry(shape)?;
        let mut body_type = def.body_type;
        let mass = match (body_type, def.mass) {
            (BodyType::Dynamic, MassSpec::Mass(m)) if m == ZERO => {
                body_type = BodyType::Static;
                MassData::STATIC
            }
            (BodyType::Dynamic, spec) => dynamic_mass(shape, spec, area, unit_inertia)?,
            _ => MassData::STATIC,
        };
        check_friction(def.friction)?;
        check_restitution(def.restitution)?;
        check_damping(def.linear_damping)?;
        check_damping(def.angular_damping)?;
        check_gravity_scale(def.gravity_scale)?;
        if def.sensor && def.bullet {
            return Err(Error::InvalidOperation { what: "a sensor cannot be a bullet" });
        }
        let rotation = normalized_rotation(def.rotation)?;
        // A capsule or segment given off its centroid: the body goes to the
        // centroid, so the shape stays where the definition puts it.
        let position = def.position + rotation.rotate(offset);
        if !self.def.bounds.contains(def.position) || !self.def.bounds.contains(position) {
            return Err(Error::OutsideBounds);
        }
        let moving = body_type != BodyType::Static;
        let v = if moving { def.linear_velocity } else { Vector2::ZERO };
        let w = if moving && !def.fixed_rotation { def.angular_velocity } else { ZERO };
        if v.x.abs() > self.def.max_linear_speed
            || v.y.abs() > self.def.max_linear_speed
            || v.length() > self.def.max_linear_speed
        {
            return Err(Error::OutOfRange { what: "linear velocity" });
        }
        if w.abs() > self.def.max_angular_speed {
            return Err(Error::OutOfRange { what: "angular velocity" });
        }
        let mut body = Body {
            position,
            rotation,
            linear_velocity: v,
            angular_velocity: w,
            shape,
            body_type,
            mass,
            friction: def.friction,
            restitution: def.restitution,
            collision_groups: def.collision_groups,
            collision_level: def.collision_level,
            user_data: def.user_data,
            out_of_bounds: false,
            bullet: def.bullet,
            fixed_rotation: def.fixed_rotation,
            linear_damping: def.linear_damping,
            angular_damping: def.angular_damping,
            gravity_scale: def.gravity_scale,
            filter: def.filter,
            sensor: def.sensor,
            radius,
            shapes: crate::compound::NO_SHAPE,
            shape_count: 1,
            aabb: Rect::default(),
            force_dv: Vector2::ZERO,
            force_dw: ZERO,
        };
        body.aabb = compute_aabb(&body, &self.paths);
        Ok(body)
    }

    /// Area (m²), unit moment of inertia (m⁴, per kg/m²) and bounding radius
    /// (m) of a shape, checked against the size limits.
    pub(super) fn shape_geometry(&self, shape: Shape) -> Result<(Scalar, Scalar, Scalar), Error> {
        match shape {
            Shape::Circle { radius } => {
                if radius <= ZERO || radius > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "radius" });
                }
                Ok((circle_area(radius)?, circle_unit_inertia(radius)?, radius))
            }
            Shape::Polygon(h) => {
                let p = self.paths.get(h).ok_or(Error::StaleHandle)?;
                if p.radius() > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "polygon size" });
                }
                Ok((p.area(), p.unit_inertia(), p.radius()))
            }
            Shape::Capsule(c) => {
                // Re-validated: a definition's capsule may have been built
                // with other ends than these re-centred ones.
                let c = Capsule::new(c.center1(), c.center2(), c.radius())?;
                if c.bounding_radius() > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "capsule size" });
                }
                Ok((c.area()?, c.unit_inertia()?, c.bounding_radius()))
            }
            Shape::Segment(s) => {
                let s = Segment::new(s.point1(), s.point2())?;
                if s.bounding_radius() > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "segment size" });
                }
                // No area: a dynamic segment takes its mass outright (see
                // `dynamic_mass`), its inertia that of a thin rod.
                Ok((scalar::ONE, s.rod_unit_inertia(), s.bounding_radius()))
            }
            Shape::Chain(h) => {
                if !self.paths.chains.valid(h) {
                    return Err(Error::StaleHandle);
                }
                Ok((ZERO, ZERO, self.paths.chains.radius(h)))
            }
        }
    }

    /// Removes a body and returns it. Its arbiters end at once: `end` is called
    /// for each pair that had begun (the body is still readable then), in pair
    /// order, and the arbiters are dropped. Safe to call from a post-step callback.
    ///
    /// The built-in joints attached to the body are removed with it (they are
    /// state: a [`restore`](World::restore) to a snapshot taken before brings
    /// them back). The game constraints attached to it
    /// ([`add_constraint`](World::add_constraint)) stay registered but go
    /// *dormant*: they are not solved while the body is gone, and they come back
    /// to life if a restore brings that very body (same handle) back. Only
    /// [`remove_constraint`](World::remove_constraint) removes them.
    ///
    /// Post-step callbacks that those `end` handlers queue run before this call
    /// returns (after the body is gone), drained as the step drains them; called
    /// from a post-step callback or a joint-break callback, it leaves them to the
    /// step's drain instead. Either way nothing stays queued between steps.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn remove_body(&mut self, h: BodyHandle) -> Result<Body, Error> {
        if !self.bodies.contains(h) {
            return Err(Error::StaleHandle);
        }
        let World { bodies, paths, arbiters, handlers, post_step, .. } = self;
        collision::end_arbiters_of(h.index(), bodies, paths, arbiters, handlers, post_step);
        self.remove_joints_of(h);
        let body = self.bodies.remove(h).ok_or(Error::StaleHandle);
        if let Ok(b) = &body {
            self.free_shapes_of(b.shapes);
        }
        self.drain_post_step_outside_step();
        body
    }

    /// Removes every built-in joint attached to `h`.
    fn remove_joints_of(&mut self, h: BodyHandle) {
        for i in 0..self.joints.slots_used() {
            let attached =
                self.joints.get_at(i).is_some_and(|j| j.def.body_a == h || j.def.body_b == Some(h));
            if let (true, Some(jh)) = (attached, self.joints.handle_at(i)) {
                self.joints.remove(jh);
            }
        }
    }

    /// The handle of slot `index` at `generation` in this world: the inverse of
    /// [`Handle::index`] and [`Handle::generation`], for handles that travel
    /// without their world tag (a network message from a peer, whose world
    /// has another tag but the same slots and generations). It resolves only if
    /// that object is alive, like any handle.
    #[must_use]
    pub fn handle_from_parts<T>(&self, index: u32, generation: u32) -> Handle<T> {
        Handle::tagged(index, generation, self.bodies.tag())
    }

    /// The body behind `h`.
    ///
    /// # Errors
    /// [`Error::StaleHandle`] (a removed body's handle never names another body).
    pub fn body(&self, h: BodyHandle) -> Result<&Body, Error> {
        self.bodies.get(h).ok_or(Error::StaleHandle)
    }

    /// The body behind `h`, to change its velocity or apply impulses.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn body_mut(&mut self, h: BodyHandle) -> Result<&mut Body, Error> {
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)
    }

    /// Every body with its handle, in slot order (the engine's canonical order).
    pub fn bodies(&self) -> impl Iterator<Item = (BodyHandle, &Body)> + '_ {
        self.bodies.iter()
    }

    /// Number of bodies.
    #[must_use]
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Bodies frozen after leaving the bounds.
    pub fn out_of_bounds_bodies(&self) -> impl Iterator<Item = BodyHandle> + '_ {
        self.bodies.iter().filter(|(_, b)| b.out_of_bounds).map(|(h, _)| h)
    }

    /// Moves a body (teleport). Brings a frozen body back into play.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::OutsideBounds`] for a point outside the world.
    pub fn set_position(&mut self, h: BodyHandle, p: Vector2) -> Result<(), Error> {
        if !self.def.bounds.contains(p) {
            return Err(Error::OutsideBounds);
        }
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.position = p;
        b.out_of_bounds = false;
        b.aabb = compute_aabb(b, &self.paths);
        Ok(())
    }

    /// Sets a body's rotation.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], or [`Error::OutOfRange`] for a zero rotation.
    pub fn set_rotation(&mut self, h: BodyHandle, q: Rot) -> Result<(), Error> {
        let q = normalized_rotation(q)?;
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.rotation = q;
        b.aabb = compute_aabb(b, &self.paths);
        Ok(())
    }

    /// Sets a body's rotation from an angle in radians.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_angle(&mut self, h: BodyHandle, radians: Scalar) -> Result<(), Error> {
        self.set_rotation(h, Rot::from_angle(radians))
    }

    /// Makes a body static (the manual's `setStatic`): it stops and never moves again.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_static(&mut self, h: BodyHandle) -> Result<(), Error> {
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.body_type = BodyType::Static;
        b.mass = MassData::STATIC;
        b.linear_velocity = Vector2::ZERO;
        b.angular_velocity = ZERO;
        Ok(())
    }

    /// Makes a body kinematic: moved by its velocity alone, which only the game
    /// sets (see [`set_target_transform`](World::set_target_transform)). A
    /// dynamic body keeps its velocity, a static one starts at rest; the mass
    /// data becomes all zeros. Contacts with it are rebuilt from the next step
    /// on, as for [`set_static`](World::set_static): a pair of two bodies that
    /// are now both static or kinematic stops colliding, and its arbiter
    /// separates and ends as any separated pair does.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_kinematic(&mut self, h: BodyHandle) -> Result<(), Error> {
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.body_type = BodyType::Kinematic;
        b.mass = MassData::STATIC;
        if b.fixed_rotation {
            b.angular_velocity = ZERO;
        }
        Ok(())
    }

    /// Makes a body dynamic with the mass `mass` (from a density or given
    /// outright): the way back from [`set_static`](World::set_static) and
    /// [`set_kinematic`](World::set_kinematic). It keeps its velocity (a
    /// static body starts at rest). On a dynamic body it only changes the mass.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::OutOfRange`] for a mass or density
    /// outside its range (a mass of 0 included: use `set_static`). The world is
    /// unchanged on error.
    pub fn set_dynamic(&mut self, h: BodyHandle, mass: MassSpec) -> Result<(), Error> {
        let body = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        if crate::compound::is_compound(body) {
            return self.set_compound_mass(h, mass);
        }
        let shape = body.shape;
        let (area, unit_inertia, _) = self.shape_geometry(shape)?;
        let mass = dynamic_mass(shape, mass, area, unit_inertia)?;
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.body_type = BodyType::Dynamic;
        b.mass = mass;
        Ok(())
    }

    /// Changes a dynamic body's mass (from a density or outright), its moment
    /// of inertia recomputed from its shape.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::InvalidOperation`] for a static or
    /// kinematic body (use [`set_dynamic`](World::set_dynamic)); [`Error::OutOfRange`]
    /// for a mass or density outside its range. The world is unchanged on error.
    pub fn set_mass(&mut self, h: BodyHandle, mass: MassSpec) -> Result<(), Error> {
        if !self.bodies.get(h).ok_or(Error::StaleHandle)?.is_dynamic() {
            return Err(Error::InvalidOperation { what: "set the mass of a static or kinematic body" });
        }
        self.set_dynamic(h, mass)
    }

    /// Sets a body's friction coefficient, [0, [`MAX_FRICTION`](crate::limits::MAX_FRICTION)].
    /// Existing contacts keep the friction they were created with (change
    /// those with [`Arbiter::set_friction`](crate::Arbiter::set_friction)); new ones use it.
    /// On a compound body it sets every shape's.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`]; the world is unchanged on error.
    pub fn set_friction(&mut self, h: BodyHandle, mu: Scalar) -> Result<(), Error> {
        check_friction(mu)?;
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.friction = mu;
        self.each_shape_mut(h, |s| s.friction = mu);
        Ok(())
    }

    /// Sets a body's restitution, [0, 1]; like friction, it applies to contacts
    /// that begin after the change (on a compound body, to every shape).
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`]; the world is unchanged on error.
    pub fn set_restitution(&mut self, h: BodyHandle, e: Scalar) -> Result<(), Error> {
        check_restitution(e)?;
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.restitution = e;
        self.each_shape_mut(h, |s| s.restitution = e);
        Ok(())
    }

    /// Sets a body's linear damping (1/s, see [`BodyDef::linear_damping`]).
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`] outside [0,
    /// [`MAX_BODY_DAMPING`](crate::limits::MAX_BODY_DAMPING)]; the world is
    /// unchanged on error.
    pub fn set_linear_damping(&mut self, h: BodyHandle, c: Scalar) -> Result<(), Error> {
        check_damping(c)?;
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.linear_damping = c;
        Ok(())
    }

    /// Sets a body's angular damping (1/s, see [`BodyDef::angular_damping`]).
    ///
    /// # Errors
    /// As [`set_linear_damping`](World::set_linear_damping).
    pub fn set_angular_damping(&mut self, h: BodyHandle, c: Scalar) -> Result<(), Error> {
        check_damping(c)?;
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.angular_damping = c;
        Ok(())
    }

    /// Sets a body's gravity scale (see [`BodyDef::gravity_scale`]).
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`] outside
    /// ±[`MAX_GRAVITY_SCALE`](crate::limits::MAX_GRAVITY_SCALE); the world is
    /// unchanged on error.
    pub fn set_gravity_scale(&mut self, h: BodyHandle, scale: Scalar) -> Result<(), Error> {
        check_gravity_scale(scale)?;
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.gravity_scale = scale;
        Ok(())
    }

    /// Locks or frees a body's rotation (see [`BodyDef::fixed_rotation`]);
    /// locking stops its spin at once and keeps its angle.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_fixed_rotation(&mut self, h: BodyHandle, on: bool) -> Result<(), Error> {
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.fixed_rotation = on;
        if on {
            b.angular_velocity = ZERO;
        }
        Ok(())
    }

    /// Sets a body's Box2D collision filter (see [`CollisionFilter`]). Pairs it
    /// no longer collides with stop from the next step: their arbiters separate
    /// and end as any separated pair does (no push in between). On a compound
    /// body it sets every shape's.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_filter(&mut self, h: BodyHandle, filter: CollisionFilter) -> Result<(), Error> {
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.filter = filter;
        self.each_shape_mut(h, |s| s.filter = filter);
        Ok(())
    }

    /// Sets a body's collision group bits (the manual's rule: bodies sharing a
    /// bit never collide).
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn set_collision_groups(&mut self, h: BodyHandle, bits: u32) -> Result<(), Error> {
        self.bodies.get_mut(h).ok_or(Error::StaleHandle)?.collision_groups = bits;
        Ok(())
    }

    /// Sets a kinematic (or dynamic) body's velocities so that the next step
    /// of `dt` seconds carries it to `position` (its centre of mass, m) and
    /// `rotation`: Box2D's `b2Body_SetTargetTransform`. Moving several
    /// kinematic bodies this way each step keeps them rigid together (a
    /// container's walls, a platform and its rails), where velocities worked
    /// out by hand drift apart.
    ///
    /// The linear velocity is (target − position) / dt. The angular velocity
    /// is chosen for how the step integrates a rotation (each sub-step of h
    /// turns by atan(ω·h)), so the step turns by the relative angle Δθ:
    /// ω = tan(Δθ / n) / h over n sub-steps. The target is reached to the
    /// rounding of the integration (about 1e-9 m and 1e-9 rad a step;
    /// `tests/body_options.rs` measures it). A fixed-rotation body's rotation is
    /// left alone. A dynamic body gets the same velocities, and contacts and
    /// joints still act on it.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::InvalidTimeStep`] for `dt` outside
    /// [[`MIN_TIME_STEP`], [`MAX_TIME_STEP`]]; [`Error::InvalidOperation`] for a
    /// static or frozen (out of bounds) body; [`Error::OutsideBounds`] for a
    /// target outside the world; [`Error::OutOfRange`] for a zero rotation, or
    /// a target that needs a speed beyond the world's limits (linear speed, the
    /// angular speed limit, an eighth of a turn per step, or the body's rim
    /// speed). The world is unchanged on error.
    pub fn set_target_transform(
        &mut self,
        h: BodyHandle,
        position: Vector2,
        rotation: Rot,
        dt: Scalar,
    ) -> Result<(), Error> {
        if dt < MIN_TIME_STEP || dt > MAX_TIME_STEP {
            return Err(Error::InvalidTimeStep);
        }
        let target_q = normalized_rotation(rotation)?;
        if !self.def.bounds.contains(position) {
            return Err(Error::OutsideBounds);
        }
        let b = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        if !b.moved_by_step() {
            return Err(Error::InvalidOperation { what: "target transform of a static or frozen body" });
        }
        let d = position - b.position;
        let v = Vector2::new(d.x / dt, d.y / dt);
        let vmax = self.def.max_linear_speed;
        if v.x.abs() > vmax || v.y.abs() > vmax || v.length() > vmax {
            return Err(Error::OutOfRange { what: "target transform (linear speed)" });
        }
        let w = if b.fixed_rotation {
            ZERO
        } else {
            // The sub-step as the step computes it (`StepContext::new`).
            let n = self.def.substeps.max(1);
            let sub = dt * Scalar::from_num(n).recip();
            let turn = b.rotation.inv_mul(target_q).angle();
            let per = Rot::from_angle(turn.div_or_zero(Scalar::from_num(n)));
            // tan(Δθ/n) = s / c, with |Δθ/n| ≤ π/4 checked below: c ≥ 0.7.
            let w = (per.s / per.c).div_or_zero(sub);
            let eighth_turn = crate::math::scalar::FRAC_PI_2 * crate::math::scalar::HALF;
            let wmax =
                crate::solver::angular_speed_limit(b, self.def.max_angular_speed.min(eighth_turn / dt));
            if turn.abs() > eighth_turn || w.abs() > wmax {
                return Err(Error::OutOfRange { what: "target transform (angular speed)" });
            }
            w
        };
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.linear_velocity = v;
        b.angular_velocity = w;
        Ok(())
    }
}

/// The unit rotation in the direction of `q`, or an error for (0, 0).
fn normalized_rotation(q: Rot) -> Result<Rot, Error> {
    Rot::from_direction(Vector2::new(q.c, q.s)).ok_or(Error::OutOfRange { what: "rotation" })
}

#[cfg(all(test, feature = "alloc"))]
mod tests {
    use crate::arena::NO_SLOT;
    use crate::{BodyDef, Capacities, Scalar, Vector2, World, WorldDef};

    fn circle_at(x: i32) -> BodyDef {
        BodyDef::circle(Scalar::ONE).position(Vector2::new(Scalar::from(x), Scalar::from(10)))
    }

    /// A slot retired after its last generation (see `arena.rs`) is state like
    /// any other: a snapshot holds it, a restore keeps it out of use, and the
    /// next body takes another slot in both worlds.
    #[test]
    fn a_retired_body_slot_survives_a_snapshot_round_trip() {
        let def = || WorldDef::new(Scalar::from(100), Scalar::from(100));
        let mut w = World::with_capacities(def(), Capacities::for_bodies(4)).expect("world");
        let first = w.add_body(circle_at(10)).expect("room");
        let keep = w.add_body(circle_at(20)).expect("room");
        w.remove_body(first).expect("live");
        // Slot 0 is free; pretend it has served 2^32 - 2 bodies since.
        w.bodies.write_slot(0, u32::MAX, NO_SLOT, None, false);
        let last = w.add_body(circle_at(30)).expect("room");
        assert_eq!((last.index(), last.generation()), (0, u32::MAX));
        w.remove_body(last).expect("live");
        assert_eq!(w.bodies.retired(), 1);

        let mut buf = alloc::vec![0u8; w.snapshot_len()];
        w.snapshot(&mut buf).expect("fits");
        let mut other = World::with_capacities(def(), Capacities::for_bodies(4)).expect("world");
        other.restore(&buf).expect("a retired slot is a valid state");
        assert_eq!(other.state_hash(), w.state_hash());
        assert_eq!(other.bodies.retired(), 1);
        let (a, b) = (w.add_body(circle_at(40)).expect("room"), other.add_body(circle_at(40)).expect("room"));
        assert_eq!((a.index(), a.generation()), (2, 1), "the retired slot 0 is skipped");
        assert_eq!((b.index(), b.generation()), (2, 1));
        assert_eq!(w.body(keep).map(|b| b.position().x), Ok(Scalar::from(20)));
        assert!(w.body(last).is_err() && w.body(first).is_err());
    }
}

/// The mass data of a dynamic body of `shape` (its `area` and `unit_inertia`
/// from [`World::shape_geometry`]). A segment has no area: it takes a mass
/// outright, as a thin rod (its "area" is 1 and its unit inertia L²/12 per kg).
pub(super) fn dynamic_mass(
    shape: Shape,
    spec: MassSpec,
    area: Scalar,
    unit_inertia: Scalar,
) -> Result<MassData, Error> {
    match (shape, spec) {
        (Shape::Segment(_), MassSpec::Density(_)) => {
            Err(Error::InvalidOperation { what: "a segment has no area: give a dynamic segment a mass" })
        }
        (_, MassSpec::Mass(m)) => MassData::from_mass(m, area, unit_inertia),
        (_, MassSpec::Density(d)) => MassData::from_density(d, area, unit_inertia),
    }
}

/// `shape` placed about its centroid, and the centroid's offset (body-local)
/// from where the shape was given. Circles and polygons are always about
/// their centroid; a capsule's centres and a segment's ends are made exactly
/// symmetric (`end1 = −end2`), the first end moving by at most 2^-32 m when
/// their sum is odd in the last bit.
pub(crate) fn centred(shape: Shape) -> (Shape, Vector2) {
    // ⌊(a + b) / 2⌋ on the raw bits, without overflow.
    let mid = |a: Scalar, b: Scalar| {
        let sum = i128::from(a.to_bits()) + i128::from(b.to_bits());
        Scalar::from_bits(i64::try_from(sum >> 1).unwrap_or(0))
    };
    let halves = |p: Vector2, q: Vector2| {
        let m = Vector2::new(mid(p.x, q.x), mid(p.y, q.y));
        (q - m, m)
    };
    match shape {
        Shape::Capsule(c) => {
            let (h, m) = halves(c.center1(), c.center2());
            (Shape::Capsule(Capsule { center1: -h, center2: h, radius: c.radius() }), m)
        }
        Shape::Segment(s) => {
            let (h, m) = halves(s.point1(), s.point2());
            (Shape::Segment(Segment { point1: -h, point2: h }), m)
        }
        other => (other, Vector2::ZERO),
    }
}
