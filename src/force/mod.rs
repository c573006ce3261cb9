//! Force generators: add velocity to all or a set of bodies every step.
//!
//! A generator is asked [`ForceGenerator::applies_to`] for each dynamic body inside
//! the bounds (in body-slot order), and [`ForceGenerator::apply`] is called for those
//! it accepts, before collisions are resolved. Generators run in the order they
//! were added (slot order). Static and kinematic bodies never reach a generator.
//!
//! The built-ins are plain data (so they can be snapshotted); a game's own
//! generators implement the trait and are stored as `Send` trait objects (so a
//! world can move between threads or sit in a `static`), borrowed (`&'a mut`) or,
//! with `alloc`, boxed.

mod gravity;
mod gravity_to_point;
mod linear;

pub use gravity::GravityForceGenerator;
pub use gravity_to_point::GravityToPointForceGenerator;
pub use linear::LinearForceGenerator;

use crate::hook::Hook;

use crate::arena::{Arena, Handle, Slot};
use crate::step::StepContext;

use crate::body::{Body, BodyHandle};
use crate::math::{Scalar, Vector2};

/// Most bodies a built-in generator's explicit target list can hold.
pub const MAX_TARGETS: usize = 32;

/// A force generator: the manual's `shouldApplyToBody` / `applyToBody`.
///
/// # If it panics
/// With `std` and the panic guard on (the default), a panic restores the world
/// to its state before the step and then unwinds out of
/// [`World::step`](crate::World::step). Without the guard (`no_std`, or
/// [`World::set_panic_guard`](crate::World::set_panic_guard)`(false)`) it unwinds
/// with the world half-stepped: the generators before it have changed the velocities of this step,
/// the bodies after it have not, and nothing has moved yet. The world stays memory-safe and usable,
/// but its state
/// is not one any uninterrupted run reaches. The way back is the snapshot taken
/// before the step: [`World::restore`](crate::World::restore) it (a game that
/// catches panics with `std::panic::catch_unwind` should restore before it
/// steps again).
pub trait ForceGenerator {
    /// Whether to apply to this body this step (default: every body). An area
    /// effect checks the body's position here.
    fn applies_to(&self, handle: BodyHandle, body: &Body) -> bool {
        let _ = (handle, body);
        true
    }

    /// Changes the body's velocity for a step of `dt` seconds, typically with
    /// [`Body::apply_force`], [`Body::apply_linear_impulse`] or
    /// [`Body::add_linear_velocity`].
    fn apply(&mut self, handle: BodyHandle, body: &mut Body, dt: Scalar);
}

/// Which bodies a built-in generator acts on.
// The explicit list is inline (no allocation), which makes that variant the large one.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Targets {
    /// Every dynamic body.
    #[default]
    All,
    /// Dynamic bodies with this collision level.
    Level(u32),
    /// Exactly these bodies (stale handles are ignored).
    Bodies(heapless::Vec<BodyHandle, MAX_TARGETS>),
}

impl Targets {
    /// Targets exactly the given bodies.
    ///
    /// # Errors
    /// [`crate::Error::CapacityFull`] for more than [`MAX_TARGETS`] handles.
    pub fn bodies(handles: &[BodyHandle]) -> Result<Self, crate::Error> {
        heapless::Vec::from_slice(handles)
            .map(Self::Bodies)
            .map_err(|_| crate::Error::CapacityFull { what: "generator target" })
    }

    /// True when the body is targeted.
    #[inline]
    #[must_use]
    pub fn contains(&self, handle: BodyHandle, body: &Body) -> bool {
        match self {
            Self::All => true,
            Self::Level(l) => body.collision_level() == *l,
            Self::Bodies(v) => v.contains(&handle),
        }
    }
}

/// Marker type naming force generators in handles.
#[derive(Debug)]
pub enum GeneratorMarker {}

/// Handle of a force generator in a [`World`](crate::World).
pub type GeneratorHandle = Handle<GeneratorMarker>;

/// Force generators a world can hold. Hooks (generators, handlers, callbacks) are
/// few and may borrow the game's objects, so they live inline in the world with
/// fixed capacities; the bulk data (bodies, paths, arbiters) is in the storage
/// sized by the caller.
pub const MAX_FORCE_GENERATORS: usize = 16;

/// A world's force generators, in the order added (slot order).
pub(crate) type Generators<'a> =
    Arena<'a, Generator<'a>, GeneratorMarker, [Slot<Generator<'a>>; MAX_FORCE_GENERATORS]>;

/// The forces stage: runs the generators, in slot order, and turns their effect
/// into a velocity change per body (`force_dv`, `force_dw`), restoring the
/// velocities, so that the solver spreads it evenly over the sub-steps.
pub(crate) fn apply(ctx: &StepContext, bodies: &mut Arena<'_, Body>, generators: &mut Generators<'_>) {
    // One built-in generator (the common case: gravity) runs in a single pass.
    // With one generator, each body's velocity change depends on that body
    // alone and the generator is called in the same order with the same
    // arguments, and a built-in cannot panic half way; bodies it skips get
    // the zero change `v − v`.
    if generators.len() <= 1 {
        match generators.iter_mut().next().map(|(_, g)| g) {
            None => return single_pass(&mut NoForce, bodies, ctx.dt),
            Some(Generator::Linear(g)) => return single_pass(g, bodies, ctx.dt),
            Some(Generator::Gravity(g)) => return single_pass(g, bodies, ctx.dt),
            Some(Generator::GravityToPoint(g)) => return single_pass(g, bodies, ctx.dt),
            Some(Generator::Custom(_)) => {}
        }
    }
    for (_, b) in bodies.iter_mut() {
        b.force_dv = b.linear_velocity;
        b.force_dw = b.angular_velocity;
    }
    for (_, g) in generators.iter_mut() {
        g.run(bodies, ctx.dt);
    }
    for (_, b) in bodies.iter_mut() {
        let (v0, w0) = (b.force_dv, b.force_dw);
        b.force_dv = b.linear_velocity - v0;
        b.force_dw = b.angular_velocity - w0;
        b.linear_velocity = v0;
        b.angular_velocity = w0;
    }
}

/// The forces stage for a single built-in generator `g`: what [`apply`] does,
/// body by body.
#[inline]
fn single_pass<G: ForceGenerator>(g: &mut G, bodies: &mut Arena<'_, Body>, dt: Scalar) {
    for (h, b) in bodies.iter_mut() {
        if b.is_dynamic() && !b.out_of_bounds && g.applies_to(h, b) {
            let (v0, w0) = (b.linear_velocity, b.angular_velocity);
            g.apply(h, b, dt);
            b.force_dv = b.linear_velocity - v0;
            b.force_dw = b.angular_velocity - w0;
            b.linear_velocity = v0;
            b.angular_velocity = w0;
        } else {
            b.force_dv = Vector2::ZERO;
            b.force_dw = Scalar::ZERO;
        }
    }
}

/// The gravity generators' acceleration `g` times a body's gravity scale, each
/// component clamped to ±[`MAX_ACCELERATION`](crate::limits::MAX_ACCELERATION)
/// (`g` itself when the scale is 1, the same bits as before scales existed).
#[inline]
pub(crate) fn scaled_acceleration(g: Vector2, scale: Scalar) -> Vector2 {
    use crate::limits::MAX_ACCELERATION as A;
    if scale == Scalar::ONE {
        g
    } else {
        let s = g * scale;
        Vector2::new(s.x.clamp(-A, A), s.y.clamp(-A, A))
    }
}

/// No generator: every body's velocity change is zero.
struct NoForce;

impl ForceGenerator for NoForce {
    #[inline]
    fn applies_to(&self, _: BodyHandle, _: &Body) -> bool {
        false
    }

    #[inline]
    fn apply(&mut self, _: BodyHandle, _: &mut Body, _: Scalar) {}
}

/// A force generator stored in a world: one of the built-ins, or a game's own.
pub enum Generator<'a> {
    /// A constant force.
    Linear(LinearForceGenerator),
    /// Uniform gravity.
    Gravity(GravityForceGenerator),
    /// Attraction to a point.
    GravityToPoint(GravityToPointForceGenerator),
    /// A game's own generator.
    Custom(Hook<'a, dyn ForceGenerator + Send + 'a>),
}

/// A force generator in a world, to change its parameters
/// ([`World::force_generator_mut`](crate::World::force_generator_mut)): the
/// built-ins through their checked setters (a generator in a world cannot be
/// replaced by one that was never checked), a game's own as its trait object.
pub enum GeneratorMut<'g, 'a> {
    /// A constant force.
    Linear(&'g mut LinearForceGenerator),
    /// Uniform gravity.
    Gravity(&'g mut GravityForceGenerator),
    /// Attraction to a point.
    GravityToPoint(&'g mut GravityToPointForceGenerator),
    /// A game's own generator.
    Custom(&'g mut (dyn ForceGenerator + Send + 'a)),
}

impl<'a> Generator<'a> {
    /// The checks of a built-in's parameters, made by
    /// [`World::add_force_generator`](crate::World::add_force_generator) and by
    /// `restore` (the setters call the same per-value checks).
    pub(crate) fn validate(&self) -> Result<(), crate::Error> {
        match self {
            Self::Linear(g) => g.validate(),
            Self::Gravity(g) => g.validate(),
            Self::GravityToPoint(g) => g.validate(),
            Self::Custom(_) => Ok(()),
        }
    }

    /// The generator, to change its parameters through checked setters.
    pub(crate) fn as_mut(&mut self) -> GeneratorMut<'_, 'a> {
        match self {
            Self::Linear(g) => GeneratorMut::Linear(g),
            Self::Gravity(g) => GeneratorMut::Gravity(g),
            Self::GravityToPoint(g) => GeneratorMut::GravityToPoint(g),
            Self::Custom(g) => GeneratorMut::Custom(&mut **g),
        }
    }

    /// A game's generator, borrowed for the world's lifetime.
    pub fn borrowed(g: &'a mut (dyn ForceGenerator + Send + 'a)) -> Self {
        Self::Custom(Hook::Borrowed(g))
    }

    /// A game's generator, owned by the world.
    #[cfg(feature = "alloc")]
    pub fn boxed(g: alloc::boxed::Box<dyn ForceGenerator + Send + 'a>) -> Self {
        Self::Custom(Hook::Boxed(g))
    }

    /// The generator as a trait object.
    pub fn as_dyn_mut(&mut self) -> &mut (dyn ForceGenerator + Send + 'a) {
        match self {
            Self::Linear(g) => g,
            Self::Gravity(g) => g,
            Self::GravityToPoint(g) => g,
            Self::Custom(g) => &mut **g,
        }
    }

    /// Runs the generator over every candidate body for one step. The
    /// built-ins are called directly (their `applies_to` and `apply` inlined
    /// into the loop), a game's generator through its trait object.
    pub(crate) fn run(&mut self, bodies: &mut Arena<'_, Body>, dt: Scalar) {
        match self {
            Self::Linear(g) => run_over(g, bodies, dt),
            Self::Gravity(g) => run_over(g, bodies, dt),
            Self::GravityToPoint(g) => run_over(g, bodies, dt),
            Self::Custom(g) => run_over(&mut **g, bodies, dt),
        }
    }
}

/// Calls `g` on every dynamic body inside the bounds that it accepts, in slot
/// order.
#[inline]
fn run_over<G: ForceGenerator + ?Sized>(g: &mut G, bodies: &mut Arena<'_, Body>, dt: Scalar) {
    for (h, b) in bodies.iter_mut() {
        if b.is_dynamic() && !b.out_of_bounds && g.applies_to(h, b) {
            g.apply(h, b, dt);
        }
    }
}

impl From<LinearForceGenerator> for Generator<'_> {
    fn from(g: LinearForceGenerator) -> Self {
        Self::Linear(g)
    }
}
impl From<GravityForceGenerator> for Generator<'_> {
    fn from(g: GravityForceGenerator) -> Self {
        Self::Gravity(g)
    }
}
impl From<GravityToPointForceGenerator> for Generator<'_> {
    fn from(g: GravityToPointForceGenerator) -> Self {
        Self::GravityToPoint(g)
    }
}
