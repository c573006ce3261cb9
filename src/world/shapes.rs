//! The compound-body API of [`World`]: add, read and remove a body's shapes
//! (see [`crate::compound`]).

use crate::body::{compute_aabb, shape_radius, BodyHandle, BodyType, CollisionFilter, MassSpec, Shape};
use crate::collision;
use crate::compound::{
    is_compound, shapes_of, BodyShape, ShapeDef, ShapeSlot, MAX_SHAPES_PER_BODY, NO_SHAPE,
};
use crate::error::Error;
use crate::geometry::mass::mul_div_round;
use crate::geometry::{compound_mass, MassData, MassPart};
use crate::limits::{check_friction, check_restitution, MAX_BODY_RADIUS};
use crate::math::scalar::{Scalar, ZERO};
use crate::math::{Rot, Transform, Vector2};

use super::bodies::{centred, dynamic_mass};
use super::World;

/// A body's shapes, gathered to be changed together.
type ShapeList = [BodyShape; MAX_SHAPES_PER_BODY];

impl World<'_> {
    /// Adds a shape to a body, making it a compound body (Box2D's
    /// `b2CreateXShape`, rapier's collider on a parent body). Returns the
    /// shape's index on the body: shapes are numbered in the order they were
    /// added, the body's first shape 0, and contact events and arbiters name
    /// them by these indices.
    ///
    /// The body's mass, centre of mass and moment of inertia become those of
    /// all its shapes (each shape's mass from its density; the body's first
    /// shape keeps the mass it had). The body's position is its centre of
    /// mass, so it moves to the new centre, and every shape's offset, the
    /// built-in joints' anchors on the body with them, by the opposite amount:
    /// nothing moves in the world. Existing contacts carry on.
    ///
    /// # Errors
    /// The world is unchanged on every error.
    /// * [`Error::StaleHandle`] for a removed body or an unknown polygon path;
    /// * [`Error::CapacityFull`] `"shape per body"` past
    ///   [`MAX_SHAPES_PER_BODY`] shapes, `"shape"` when the world's shape
    ///   store ([`Capacities::shapes`](crate::Capacities::shapes)) is full;
    /// * [`Error::InvalidOperation`] for a chain or for a shape on a chain body;
    /// * [`Error::OutOfRange`] for a shape, density, friction or restitution
    ///   outside its range, or a body that grows past the size, mass or
    ///   inertia limits;
    /// * [`Error::OutsideBounds`] when the new centre of mass is outside the world.
    pub fn add_shape(&mut self, h: BodyHandle, def: ShapeDef) -> Result<u32, Error> {
        let body = *self.bodies.get(h).ok_or(Error::StaleHandle)?;
        if matches!(def.shape, Shape::Chain(_)) || matches!(body.shape, Shape::Chain(_)) {
            return Err(Error::InvalidOperation {
                what: "a chain is a body of its own: no shapes beside it",
            });
        }
        let (mut list, n) = self.shape_list(h)?;
        if n >= MAX_SHAPES_PER_BODY {
            return Err(Error::CapacityFull { what: "shape per body" });
        }
        let Some(slot) = list.get_mut(n) else { return Err(Error::CapacityFull { what: "shape per body" }) };
        *slot = self.shape_from_def(&def, body.body_type)?;
        self.place_shapes(h, &mut list, n.saturating_add(1))?;
        Ok(n as u32)
    }

    /// Removes shape `index` of a body; the shapes after it move down one
    /// index. The body's mass data and centre of mass are recomputed (as in
    /// [`add_shape`](World::add_shape)); the contacts of the removed shape
    /// end (`end` called for each that had begun), the others carry on
    /// under their new index. Returns the removed shape.
    ///
    /// # Errors
    /// The world is unchanged on every error. [`Error::StaleHandle`];
    /// [`Error::OutOfRange`] (`"shape index"`) for an index the body does not
    /// have; [`Error::InvalidOperation`] for a body's last shape (remove the
    /// body instead); [`Error::OutOfRange`] when the remaining shapes' mass is
    /// out of range; [`Error::OutsideBounds`] when their centre is outside the world.
    pub fn remove_shape(&mut self, h: BodyHandle, index: u32) -> Result<BodyShape, Error> {
        let (mut list, n) = self.shape_list(h)?;
        let i = index as usize;
        if i >= n {
            return Err(Error::OutOfRange { what: "shape index" });
        }
        if n == 1 {
            return Err(Error::InvalidOperation { what: "remove a body's last shape (remove the body)" });
        }
        let removed = list.get(i).copied().ok_or(Error::OutOfRange { what: "shape index" })?;
        list.copy_within(i.saturating_add(1)..n, i);
        self.place_shapes(h, &mut list, n.saturating_sub(1))?;
        let World { bodies, paths, arbiters, handlers, post_step, .. } = self;
        collision::end_arbiters_of_shape(
            h.index(),
            (index, removed.sensor),
            bodies,
            paths,
            arbiters,
            handlers,
            post_step,
        );
        self.drain_post_step_outside_step();
        Ok(removed)
    }

    /// Shape `index` of a body (0 is its first), with its place on the body.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::OutOfRange`] (`"shape index"`) for an
    /// index the body does not have.
    pub fn shape(&self, h: BodyHandle, index: u32) -> Result<BodyShape, Error> {
        let b = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        shapes_of(b, &self.paths)
            .find(|&(i, _)| i == index)
            .map(|(_, s)| s)
            .ok_or(Error::OutOfRange { what: "shape index" })
    }

    /// Sets the friction coefficient of shape `index` of a body (Box2D's
    /// `b2Shape_SetFriction`); contacts that begin after the change use it (as
    /// [`set_friction`](World::set_friction), which sets every shape's).
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`] for a friction out of
    /// range or an index the body does not have; the world is unchanged on error.
    pub fn set_shape_friction(&mut self, h: BodyHandle, index: u32, mu: Scalar) -> Result<(), Error> {
        check_friction(mu)?;
        self.edit_shape(h, index, |s| s.friction = mu)
    }

    /// Sets the restitution of shape `index` of a body, as
    /// [`set_shape_friction`](World::set_shape_friction).
    ///
    /// # Errors
    /// As [`set_shape_friction`](World::set_shape_friction).
    pub fn set_shape_restitution(&mut self, h: BodyHandle, index: u32, e: Scalar) -> Result<(), Error> {
        check_restitution(e)?;
        self.edit_shape(h, index, |s| s.restitution = e)
    }

    /// Sets the collision filter of shape `index` of a body (Box2D's
    /// `b2Shape_SetFilter`): pairs it no longer collides with separate and end
    /// from the next step.
    ///
    /// # Errors
    /// [`Error::StaleHandle`], [`Error::OutOfRange`] for an index the body
    /// does not have.
    pub fn set_shape_filter(
        &mut self,
        h: BodyHandle,
        index: u32,
        filter: CollisionFilter,
    ) -> Result<(), Error> {
        self.edit_shape(h, index, |s| s.filter = filter)
    }

    /// Sets the density (kg/m²) of shape `index` of a dynamic body (Box2D's
    /// `b2Shape_SetDensity` with the mass updated): the body's mass data and
    /// centre of mass are recomputed from its shapes, as in
    /// [`add_shape`](World::add_shape). On a one-shape body it is
    /// [`set_mass`](World::set_mass) with that density.
    ///
    /// # Errors
    /// [`Error::StaleHandle`]; [`Error::InvalidOperation`] for a static or
    /// kinematic body or a segment (no area); [`Error::OutOfRange`] for a
    /// density, or a resulting mass or inertia, out of range, or an index the
    /// body does not have; [`Error::OutsideBounds`] when the new centre is
    /// outside the world. The world is unchanged on error.
    pub fn set_shape_density(&mut self, h: BodyHandle, index: u32, density: Scalar) -> Result<(), Error> {
        let body = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        if !body.is_dynamic() {
            return Err(Error::InvalidOperation {
                what: "set the density of a static or kinematic body's shape",
            });
        }
        if !is_compound(body) {
            if index != 0 {
                return Err(Error::OutOfRange { what: "shape index" });
            }
            return self.set_mass(h, MassSpec::Density(density));
        }
        let (mut list, n) = self.shape_list(h)?;
        let shape = list.get_mut(index as usize).filter(|_| (index as usize) < n);
        let shape = shape.ok_or(Error::OutOfRange { what: "shape index" })?;
        if matches!(shape.shape, Shape::Segment(_)) {
            return Err(Error::InvalidOperation { what: "a segment has no area: it adds no mass" });
        }
        let (area, unit_inertia, _) = self.shape_geometry(shape.shape)?;
        let part = MassData::from_density(density, area, unit_inertia)?;
        (shape.mass, shape.inertia) = (part.mass, part.inertia);
        self.place_shapes(h, &mut list, n)
    }

    /// Applies `f` to shape `index` of body `h` (a one-shape body's data is
    /// the body's; shape 0's is mirrored on the body).
    fn edit_shape(&mut self, h: BodyHandle, index: u32, f: impl FnOnce(&mut BodyShape)) -> Result<(), Error> {
        let body = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        let mut at = body.shapes;
        if is_compound(body) {
            for _ in 0..index {
                at = self.paths.slots.get_at(at).ok_or(Error::OutOfRange { what: "shape index" })?.next;
            }
        } else if index != 0 {
            return Err(Error::OutOfRange { what: "shape index" });
        }
        let edited = match self.paths.slots.get_at_mut(at) {
            Some(slot) if is_compound(body) => {
                f(&mut slot.data);
                slot.data
            }
            _ if is_compound(body) => return Err(Error::OutOfRange { what: "shape index" }),
            _ => {
                let mut one = BodyShape::of_body(body);
                f(&mut one);
                one
            }
        };
        if index == 0 {
            if let Some(b) = self.bodies.get_mut(h) {
                b.friction = edited.friction;
                b.restitution = edited.restitution;
                b.filter = edited.filter;
            }
        }
        Ok(())
    }

    /// Every shape of a body with its index, in order.
    ///
    /// # Errors
    /// [`Error::StaleHandle`].
    pub fn shapes(&self, h: BodyHandle) -> Result<impl Iterator<Item = (u32, BodyShape)> + '_, Error> {
        let b = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        Ok(shapes_of(b, &self.paths))
    }

    /// A body's shapes, copied out.
    fn shape_list(&self, h: BodyHandle) -> Result<(ShapeList, usize), Error> {
        let b = self.bodies.get(h).ok_or(Error::StaleHandle)?;
        let mut list = [BodyShape::of_body(b); MAX_SHAPES_PER_BODY];
        let mut n = 0usize;
        for ((_, s), dst) in shapes_of(b, &self.paths).zip(list.iter_mut()) {
            *dst = s;
            n = n.saturating_add(1);
        }
        Ok((list, n))
    }

    /// The shape a definition describes, checked, placed about its centroid
    /// (a capsule's or segment's ends made symmetric, the frame moved to their
    /// midpoint), with its mass when its body is dynamic.
    fn shape_from_def(&self, def: &ShapeDef, body_type: BodyType) -> Result<BodyShape, Error> {
        check_friction(def.friction)?;
        check_restitution(def.restitution)?;
        let rotation = Rot::from_direction(Vector2::new(def.rotation.c, def.rotation.s))
            .ok_or(Error::OutOfRange { what: "rotation" })?;
        let (shape, mid) = centred(def.shape);
        let (area, unit_inertia, _) = self.shape_geometry(shape)?;
        let mass = match (body_type, shape) {
            (BodyType::Dynamic, Shape::Segment(_)) | (BodyType::Static | BodyType::Kinematic, _) => {
                MassData::STATIC
            }
            (BodyType::Dynamic, _) => {
                dynamic_mass(shape, MassSpec::Density(def.density), area, unit_inertia)?
            }
        };
        let offset = def.offset + rotation.rotate(mid);
        if offset.x.abs() > MAX_BODY_RADIUS || offset.y.abs() > MAX_BODY_RADIUS {
            return Err(Error::OutOfRange { what: "compound size" });
        }
        Ok(BodyShape {
            shape,
            local: Transform::new(offset, rotation),
            mass: mass.mass,
            inertia: mass.inertia,
            friction: def.friction,
            restitution: def.restitution,
            filter: def.filter,
            sensor: def.sensor,
        })
    }

    /// Makes `list[..n]` the shapes of body `h`: the mass data of their parts
    /// (for a dynamic body), the body moved to their centre and the offsets
    /// (and joint anchors on the body) by the opposite amount, the slots
    /// written. Checks everything before it changes anything.
    pub(super) fn place_shapes(
        &mut self,
        h: BodyHandle,
        list: &mut ShapeList,
        n: usize,
    ) -> Result<(), Error> {
        let shapes = list.get_mut(..n).ok_or(Error::CapacityFull { what: "shape per body" })?;
        let body = *self.bodies.get(h).ok_or(Error::StaleHandle)?;
        let (mass, centre) = if body.body_type == BodyType::Dynamic {
            let mut parts =
                [MassPart { mass: ZERO, centre: Vector2::ZERO, inertia: ZERO }; MAX_SHAPES_PER_BODY];
            let mut k = 0usize;
            for s in shapes.iter().filter(|s| s.mass > ZERO) {
                if let Some(p) = parts.get_mut(k) {
                    *p = MassPart { mass: s.mass, centre: s.local.p, inertia: s.inertia };
                    k = k.saturating_add(1);
                }
            }
            compound_mass(parts.get(..k).unwrap_or(&[]))?
        } else {
            (MassData::STATIC, Vector2::ZERO)
        };
        for s in shapes.iter_mut() {
            s.local.p -= centre;
        }
        let position = body.position + body.rotation.rotate(centre);
        if !self.def.bounds.contains(position) {
            return Err(Error::OutsideBounds);
        }
        let radius = shapes
            .iter()
            .map(|s| s.local.p.length() + shape_radius(s.shape, &self.paths) + Scalar::DELTA)
            .fold(ZERO, Scalar::max);
        if radius > MAX_BODY_RADIUS {
            return Err(Error::OutOfRange { what: "compound size" });
        }
        // Slots: the body's own, reused in order, then new ones.
        let mut old = [NO_SHAPE; MAX_SHAPES_PER_BODY];
        let mut at = body.shapes;
        for o in old.iter_mut() {
            let Some(s) = self.paths.slots.get_at(at) else { break };
            *o = at;
            at = s.next;
        }
        let owner = h.index();
        // Every error leaves the world unchanged: a slot taken and freed
        // again would still move the shape store's free list (which the
        // snapshot and the state hash hold), so the room is checked first.
        let wanted = old.iter().take(shapes.len()).filter(|&&o| o == NO_SHAPE).count();
        if wanted > self.paths.slots.room() {
            return Err(Error::CapacityFull { what: "shape" });
        }
        let mut slots = old;
        for k in 0..shapes.len() {
            let Some(dst) = slots.get_mut(k) else { break };
            if *dst != NO_SHAPE {
                continue;
            }
            let blank = ShapeSlot { owner, next: NO_SHAPE, data: BodyShape::of_body(&body) };
            match self.paths.slots.insert(blank) {
                Ok(handle) => *dst = handle.index(),
                Err(_) => {
                    // Free the slots this call took.
                    for (&new, &was) in slots.iter().zip(old.iter()) {
                        if new != was {
                            self.free_slot(new);
                        }
                    }
                    return Err(Error::CapacityFull { what: "shape" });
                }
            }
        }
        for (k, s) in shapes.iter().enumerate() {
            let next = if k.saturating_add(1) < shapes.len() {
                slots.get(k.saturating_add(1)).copied().unwrap_or(NO_SHAPE)
            } else {
                NO_SHAPE
            };
            let at = slots.get(k).copied().unwrap_or(NO_SHAPE);
            if let Some(slot) = self.paths.slots.get_at_mut(at) {
                *slot = ShapeSlot { owner, next, data: *s };
            }
        }
        // Slots the body no longer needs.
        for &o in old.iter().skip(shapes.len()) {
            self.free_slot(o);
        }
        let first = shapes.first().copied().unwrap_or(BodyShape::of_body(&body));
        let count = u8::try_from(shapes.len()).unwrap_or(1);
        for (_, j) in self.joints.iter_mut() {
            if j.def.body_a == h {
                j.def.anchor_a -= centre;
            }
            if j.def.body_b == Some(h) {
                j.def.anchor_b -= centre;
            }
        }
        let b = self.bodies.get_mut(h).ok_or(Error::StaleHandle)?;
        b.shapes = slots.first().copied().unwrap_or(NO_SHAPE);
        b.shape_count = count;
        b.shape = first.shape;
        b.friction = first.friction;
        b.restitution = first.restitution;
        b.filter = first.filter;
        b.sensor = first.sensor;
        b.mass = mass;
        b.position = position;
        b.radius = radius;
        b.aabb = compute_aabb(b, &self.paths);
        // The body's shapes or its centre moved on it: the manifolds its
        // contacts keep no longer describe it (see `collision::recycle`).
        for a in self.arbiters.live_mut() {
            if a.body_a == h || a.body_b == h {
                a.set_has_manifold(false);
            }
        }
        Ok(())
    }

    /// Frees shape slot `at` (nothing for [`NO_SHAPE`]).
    fn free_slot(&mut self, at: u32) {
        if let Some(handle) = self.paths.slots.handle_at(at) {
            self.paths.slots.remove(handle);
        }
    }

    /// Applies `f` to every shape of a compound body (nothing for a one-shape
    /// body, whose data is the body's).
    pub(super) fn each_shape_mut(&mut self, h: BodyHandle, mut f: impl FnMut(&mut BodyShape)) {
        let mut at = self.bodies.get(h).map_or(NO_SHAPE, |b| b.shapes);
        for _ in 0..MAX_SHAPES_PER_BODY {
            let Some(slot) = self.paths.slots.get_at_mut(at) else { return };
            f(&mut slot.data);
            at = slot.next;
        }
    }

    /// Frees a removed body's shape slots.
    pub(super) fn free_shapes_of(&mut self, first: u32) {
        let mut at = first;
        for _ in 0..MAX_SHAPES_PER_BODY {
            let Some(next) = self.paths.slots.get_at(at).map(|s| s.next) else { return };
            self.free_slot(at);
            at = next;
        }
    }

    /// Recomputes a compound body's shapes' masses for `spec` (a density
    /// for every shape, or a total mass shared in proportion to area) and its
    /// mass data and centre ([`set_dynamic`](World::set_dynamic) and
    /// [`set_mass`](World::set_mass) on a compound body).
    pub(super) fn set_compound_mass(&mut self, h: BodyHandle, spec: MassSpec) -> Result<(), Error> {
        let (mut list, n) = self.shape_list(h)?;
        let density = match spec {
            MassSpec::Density(d) => d,
            MassSpec::Mass(_) => Scalar::ONE,
        };
        let mut total = ZERO;
        for s in list.iter_mut().take(n) {
            let m = if matches!(s.shape, Shape::Segment(_)) {
                MassData::STATIC
            } else {
                let (area, unit_inertia, _) = self.shape_geometry(s.shape)?;
                MassData::from_density(density, area, unit_inertia)?
            };
            (s.mass, s.inertia) = (m.mass, m.inertia);
            total += m.mass;
        }
        if let MassSpec::Mass(m) = spec {
            if total <= ZERO {
                return Err(Error::OutOfRange { what: "mass" });
            }
            for s in list.iter_mut().take(n) {
                let scale = |x: Scalar| mul_div_round(x, m, total).ok_or(Error::OutOfRange { what: "mass" });
                (s.mass, s.inertia) = (scale(s.mass)?, scale(s.inertia)?);
            }
        }
        let old = *self.bodies.get(h).ok_or(Error::StaleHandle)?;
        if let Some(b) = self.bodies.get_mut(h) {
            b.body_type = BodyType::Dynamic;
        }
        let placed = self.place_shapes(h, &mut list, n);
        if placed.is_err() {
            if let Some(b) = self.bodies.get_mut(h) {
                *b = old;
            }
        }
        placed
    }
}
