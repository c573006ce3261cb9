//! The body and polygon-path API of [`World`]: create, read, move, remove.

use crate::arena::Handle;
use crate::body::{compute_aabb, Body, BodyDef, BodyHandle, BodyType, MassSpec, PathHandle, Shape};
use crate::collision;
use crate::error::Error;
use crate::geometry::circle::{circle_area, circle_unit_inertia};
use crate::geometry::{MassData, PolygonPath};
use crate::limits::{check_friction, check_restitution, MAX_BODY_RADIUS};
use crate::math::scalar::{Scalar, ZERO};
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
        if self.bodies.iter().any(|(_, b)| b.shape == Shape::Polygon(h)) {
            return Err(Error::InvalidOperation { what: "remove a path that bodies use" });
        }
        self.paths.remove(h).ok_or(Error::StaleHandle)
    }

    // ---- bodies --------------------------------------------------------------

    /// Creates a body.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a radius, mass, density, friction, restitution,
    /// speed or rotation outside its range; [`Error::StaleHandle`] for an unknown
    /// polygon path; [`Error::OutsideBounds`] when the position is outside the
    /// world; [`Error::CapacityFull`] when the body store is full.
    pub fn add_body(&mut self, def: BodyDef) -> Result<BodyHandle, Error> {
        let body = self.build_body(&def)?;
        self.bodies.insert(body).map_err(|_| Error::CapacityFull { what: "body" })
    }

    fn build_body(&self, def: &BodyDef) -> Result<Body, Error> {
        let (area, unit_inertia, radius) = match def.shape {
            Shape::Circle { radius } => {
                if radius <= ZERO || radius > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "radius" });
                }
                (circle_area(radius)?, circle_unit_inertia(radius)?, radius)
            }
            Shape::Polygon(h) => {
                let p = self.paths.get(h).ok_or(Error::StaleHandle)?;
                if p.radius() > MAX_BODY_RADIUS {
                    return Err(Error::OutOfRange { what: "polygon size" });
                }
                (p.area(), p.unit_inertia(), p.radius())
            }
        };
        let mut body_type = def.body_type;
        let mass = match (body_type, def.mass) {
            (BodyType::Dynamic, MassSpec::Mass(m)) if m == ZERO => {
                body_type = BodyType::Static;
                MassData::STATIC
            }
            (BodyType::Dynamic, MassSpec::Mass(m)) => MassData::from_mass(m, area, unit_inertia)?,
            (BodyType::Dynamic, MassSpec::Density(d)) => MassData::from_density(d, area, unit_inertia)?,
            _ => MassData::STATIC,
        };
        check_friction(def.friction)?;
        check_restitution(def.restitution)?;
        if def.sensor && def.bullet {
            return Err(Error::InvalidOperation { what: "a sensor cannot be a bullet" });
        }
        let rotation = normalized_rotation(def.rotation)?;
        if !self.def.bounds.contains(def.position) {
            return Err(Error::OutsideBounds);
        }
        let moving = body_type != BodyType::Static;
        let v = if moving { def.linear_velocity } else { Vector2::ZERO };
        let w = if moving { def.angular_velocity } else { ZERO };
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
            position: def.position,
            rotation,
            linear_velocity: v,
            angular_velocity: w,
            shape: def.shape,
            body_type,
            mass,
            friction: def.friction,
            restitution: def.restitution,
            collision_groups: def.collision_groups,
            collision_level: def.collision_level,
            user_data: def.user_data,
            out_of_bounds: false,
            bullet: def.bullet,
            sensor: def.sensor,
            radius,
            aabb: Rect::default(),
            force_dv: Vector2::ZERO,
            force_dw: ZERO,
        };
        body.aabb = compute_aabb(&body, &self.paths);
        Ok(body)
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
        let World { bodies, arbiters, handlers, post_step, .. } = self;
        collision::end_arbiters_of(h.index(), bodies, arbiters, handlers, post_step);
        self.remove_joints_of(h);
        let body = self.bodies.remove(h).ok_or(Error::StaleHandle);
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
