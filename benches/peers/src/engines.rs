//! The three engines behind one small trait: build a [`Scene`], step it, read bodies.

use crate::scenes::{BodyDesc, Scene, ShapeDesc, GRAVITY, SUBSTEPS, TIME_STEP};

/// A body's position and velocity, in metres and m/s.
#[derive(Clone, Copy, Debug, Default)]
pub struct BodyState {
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
}

/// What every engine offers the driver.
pub trait Engine: Sized {
    /// Builds the scene; bodies keep the scene's order.
    fn build(scene: &Scene) -> Result<Self, String>;
    /// One step of [`TIME_STEP`] with [`SUBSTEPS`] sub-steps (or the engine's equivalent).
    fn step(&mut self) -> Result<(), String>;
    /// State of the scene's body `i`.
    fn body(&mut self, i: usize) -> Result<BodyState, String>;
    /// Pairs the engine keeps as contacts (each engine counts in its own way).
    fn contact_count(&mut self) -> usize;
    /// Bytes the engine allocated outside Rust's allocator (Box2D's own count).
    fn native_heap_bytes(&mut self) -> Option<usize> {
        None
    }
}

/// Which engine, for the driver's loops and the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    Arphysics,
    Box2d,
    Rapier,
}

impl Which {
    pub const ALL: [Self; 3] = [Self::Arphysics, Self::Box2d, Self::Rapier];

    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Arphysics => "arphysics",
            Self::Box2d => "Box2D v3",
            Self::Rapier => "rapier2d",
        }
    }

    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Arphysics => "arphysics",
            Self::Box2d => "box2d",
            Self::Rapier => "rapier",
        }
    }
}

// ---- arphysics ----------------------------------------------------------------

pub mod ar {
    use super::{BodyDesc, BodyState, Engine, Scene, ShapeDesc, GRAVITY, SUBSTEPS, TIME_STEP};
    use arphysics::{
        BodyDef, BodyHandle, Capacities, GravityForceGenerator, Index, JointDef, JointKind, PathHandle,
        PolygonPath, Rect, Scalar, Segment, Vector2, World, WorldDef,
    };

    /// The arphysics side: a world on heap storage sized from the scene.
    pub struct Ar {
        pub world: World<'static>,
        bodies: Vec<BodyHandle>,
        dt: Scalar,
    }

    fn err(e: arphysics::Error) -> String {
        format!("arphysics: {e}")
    }

    fn v(x: f64, y: f64) -> Result<Vector2, String> {
        Vector2::try_from_f64(x, y, "scene coordinate").map_err(err)
    }

    fn s(x: f64) -> Result<Scalar, String> {
        arphysics::math::scalar::try_from_f64(x, "scene value").map_err(err)
    }

    /// The shapes of a scene that need polygon paths, each once.
    fn unique_polygons(scene: &Scene) -> Vec<ShapeDesc> {
        let mut out: Vec<ShapeDesc> = Vec::new();
        for b in &scene.bodies {
            let polygon = matches!(b.shape, ShapeDesc::Box { .. } | ShapeDesc::Polygon(_));
            if polygon && !out.contains(&b.shape) {
                out.push(b.shape.clone());
            }
        }
        out
    }

    /// The capacities [`Ar::build`] uses for `scene`.
    #[must_use]
    pub fn capacities(scene: &Scene) -> Capacities {
        let bodies = scene.bodies.len();
        Capacities {
            bodies,
            paths: unique_polygons(scene).len().max(1),
            contacts: bodies.saturating_mul(scene.contacts_per_body).max(16),
            joints: scene.joints.len().max(1),
            post_step_callbacks: 64,
            events: 64,
            chain_vertices: 0,
            shapes: 0,
        }
    }

    fn body_def(b: &BodyDesc, paths: &[(ShapeDesc, PathHandle)]) -> Result<BodyDef, String> {
        let def = match &b.shape {
            ShapeDesc::Circle { r } => BodyDef::circle(s(*r)?),
            ShapeDesc::Segment(a, b) => {
                BodyDef::segment(Segment::new(v(a.0, a.1)?, v(b.0, b.1)?).map_err(err)?)
            }
            shape => {
                let path = paths
                    .iter()
                    .find(|(d, _)| d == shape)
                    .map(|(_, h)| *h)
                    .ok_or_else(|| "arphysics: missing path".to_owned())?;
                BodyDef::polygon(path)
            }
        };
        let mut def = def.position(v(b.x, b.y)?).density(s(b.density)?).friction(s(b.friction)?);
        if !b.dynamic {
            def = def.static_body();
        }
        if b.no_self_collision {
            // Two bodies sharing a group bit never collide.
            def = def.collision_groups(1);
        }
        Ok(def)
    }

    impl Engine for Ar {
        fn build(scene: &Scene) -> Result<Self, String> {
            let (x0, y0, x1, y1) = scene.bounds;
            let bounds = Rect::from_corners(v(x0, y0)?, v(x1, y1)?);
            let mut world =
                World::with_capacities(WorldDef::with_bounds(bounds), capacities(scene)).map_err(err)?;
            debug_assert_eq!(world.def().substeps, SUBSTEPS);
            // The broad phase: the automatic index (brute force up to
            // `index::AUTO_THRESHOLD` proxies, sort-and-sweep along x above, on scratch
            // from the world's storage). Named here so a comparison with another index
            // is a one-line change.
            world.set_spatial_index(Index::Auto);
            let mut paths = Vec::new();
            for shape in unique_polygons(scene) {
                let path = match &shape {
                    ShapeDesc::Box { hx, hy } => PolygonPath::rectangle(s(2.0 * hx)?, s(2.0 * hy)?),
                    ShapeDesc::Polygon(points) => {
                        let pts: Result<Vec<Vector2>, String> =
                            points.iter().map(|&(x, y)| v(x, y)).collect();
                        PolygonPath::new(&pts?)
                    }
                    ShapeDesc::Circle { .. } | ShapeDesc::Segment(..) => continue,
                }
                .map_err(err)?;
                paths.push((shape, world.add_path(path).map_err(err)?));
            }
            let mut bodies = Vec::with_capacity(scene.bodies.len());
            for b in &scene.bodies {
                bodies.push(world.add_body(body_def(b, &paths)?).map_err(err)?);
            }
            for j in &scene.joints {
                let (a, b) = (bodies[j.a], bodies[j.b]);
                let anchor = v(j.anchor.0, j.anchor.1)?;
                let pa = world.body(a).map_err(err)?.position();
                let pb = world.body(b).map_err(err)?.position();
                let kind = JointKind::Pivot { limits: None, motor: None };
                world.add_joint(JointDef::new(a, anchor - pa, b, anchor - pb, kind)).map_err(err)?;
            }
            world.add_force_generator(GravityForceGenerator::new(v(GRAVITY.0, GRAVITY.1)?)).map_err(err)?;
            let dt = Scalar::from_num(1) / Scalar::from_num((1.0 / TIME_STEP).round() as i32);
            Ok(Self { world, bodies, dt })
        }

        fn step(&mut self) -> Result<(), String> {
            self.world.step(self.dt).map(drop).map_err(err)
        }

        fn body(&mut self, i: usize) -> Result<BodyState, String> {
            let b = self.world.body(self.bodies[i]).map_err(err)?;
            let (x, y) = b.position().to_f64();
            let (vx, vy) = b.linear_velocity().to_f64();
            Ok(BodyState { x, y, vx, vy })
        }

        fn contact_count(&mut self) -> usize {
            self.world.arbiters().count()
        }
    }
}

// ---- Box2D v3 (boxdd) -----------------------------------------------------------

pub mod b2 {
    use super::{BodyState, Engine, Scene, ShapeDesc, GRAVITY, SUBSTEPS, TIME_STEP};
    use boxdd::{
        shapes, BodyBuilder, BodyId, BodyType, Filter, Foundation, Position, ShapeDef, SurfaceMaterial, Vec2,
        World, WorldBuilder,
    };

    /// The Box2D side: Box2D's benchmark settings (sleep off, continuous on, one
    /// worker, 4 sub-steps).
    pub struct B2 {
        pub world: World,
        bodies: Vec<BodyId>,
    }

    fn err(e: boxdd::Error) -> String {
        format!("Box2D: {e}")
    }

    /// Box2D's process-wide foundation (one unit per metre).
    fn foundation() -> Result<&'static Foundation, String> {
        Foundation::initialize_default().map_err(err)
    }

    impl Engine for B2 {
        fn build(scene: &Scene) -> Result<Self, String> {
            let f = foundation()?;
            let def = WorldBuilder::from(f.world_def())
                .gravity(Vec2::new(GRAVITY.0 as f32, GRAVITY.1 as f32))
                .enable_sleep(false)
                .build()
                .map_err(err)?;
            let mut world = f.create_world(def).map_err(err)?;
            let mut bodies = Vec::with_capacity(scene.bodies.len());
            for b in &scene.bodies {
                let def = BodyBuilder::from(f.body_def())
                    .body_type(if b.dynamic { BodyType::Dynamic } else { BodyType::Static })
                    .position(Position::new(b.x as f32, b.y as f32))
                    .enable_sleep(false)
                    .build()
                    .map_err(err)?;
                let id = world.create_body(def).map_err(err)?;
                let material = SurfaceMaterial::new().with_friction(b.friction as f32).map_err(err)?;
                let mut shape_def = ShapeDef::builder().density(b.density as f32).material(material);
                if b.no_self_collision {
                    // Box2D's joint grid: category 2, collides with everything but 2.
                    let mut filter = Filter::new();
                    filter.category_bits = 2;
                    filter.mask_bits = !2;
                    shape_def = shape_def.filter(filter);
                }
                let shape_def = shape_def.build().map_err(err)?;
                let mut body = world.body(id).map_err(err)?;
                match &b.shape {
                    ShapeDesc::Box { hx, hy } => {
                        let p = shapes::box_polygon(*hx as f32, *hy as f32).map_err(err)?;
                        body.create_polygon(&shape_def, &p).map_err(err)?;
                    }
                    ShapeDesc::Circle { r } => {
                        let c = shapes::circle(Vec2::new(0.0, 0.0), *r as f32).map_err(err)?;
                        body.create_circle(&shape_def, &c).map_err(err)?;
                    }
                    ShapeDesc::Polygon(points) => {
                        let pts = points.iter().map(|&(x, y)| Vec2::new(x as f32, y as f32));
                        let p = shapes::polygon_from_points(pts, 0.0).map_err(err)?;
                        body.create_polygon(&shape_def, &p).map_err(err)?;
                    }
                    ShapeDesc::Segment(a, c) => {
                        let (p, q) = (Vec2::new(a.0 as f32, a.1 as f32), Vec2::new(c.0 as f32, c.1 as f32));
                        body.create_segment_between(&shape_def, p, q).map_err(err)?;
                    }
                }
                bodies.push(id);
            }
            for j in &scene.joints {
                world
                    .revolute(bodies[j.a], bodies[j.b])
                    .anchor_world(Position::new(j.anchor.0 as f32, j.anchor.1 as f32))
                    .build()
                    .map_err(err)?;
            }
            Ok(Self { world, bodies })
        }

        fn step(&mut self) -> Result<(), String> {
            self.world.step(TIME_STEP as f32, SUBSTEPS as i32).map(drop).map_err(err)
        }

        fn body(&mut self, i: usize) -> Result<BodyState, String> {
            let b = self.world.body(self.bodies[i]).map_err(err)?;
            let p = b.position().map_err(err)?;
            let v = b.linear_velocity().map_err(err)?;
            Ok(BodyState { x: f64::from(p.x), y: f64::from(p.y), vx: f64::from(v.x), vy: f64::from(v.y) })
        }

        fn contact_count(&mut self) -> usize {
            self.world.counters().map(|c| c.contact_count.max(0) as usize).unwrap_or(0)
        }

        /// Bytes Box2D has allocated, process-wide (its own counter; one world lives at a time).
        fn native_heap_bytes(&mut self) -> Option<usize> {
            self.world.counters().ok().and_then(|c| usize::try_from(c.byte_count).ok())
        }
    }
}

// ---- rapier2d --------------------------------------------------------------------

pub mod rp {
    use super::{BodyState, Engine, Scene, ShapeDesc, GRAVITY, SUBSTEPS, TIME_STEP};
    use rapier2d::prelude::*;

    /// The rapier side: default integration parameters (4 solver iterations, i.e.
    /// 4 TGS-soft sub-steps, 1 PGS and 1 stabilisation iteration each), sleeping off.
    pub struct Rp {
        pub world: PhysicsWorld,
        bodies: Vec<RigidBodyHandle>,
    }

    impl Engine for Rp {
        fn build(scene: &Scene) -> Result<Self, String> {
            let mut world = PhysicsWorld::new();
            world.gravity = Vector::new(GRAVITY.0 as f32, GRAVITY.1 as f32);
            world.integration_parameters.dt = TIME_STEP as f32;
            world.integration_parameters.num_solver_iterations = SUBSTEPS as usize;
            let mut bodies = Vec::with_capacity(scene.bodies.len());
            for b in &scene.bodies {
                let body = if b.dynamic {
                    RigidBodyBuilder::dynamic().can_sleep(false)
                } else {
                    RigidBodyBuilder::fixed()
                }
                .translation(Vector::new(b.x as f32, b.y as f32));
                let collider = match &b.shape {
                    ShapeDesc::Box { hx, hy } => ColliderBuilder::cuboid(*hx as f32, *hy as f32),
                    ShapeDesc::Circle { r } => ColliderBuilder::ball(*r as f32),
                    ShapeDesc::Polygon(points) => {
                        let pts: Vec<Vector> =
                            points.iter().map(|&(x, y)| Vector::new(x as f32, y as f32)).collect();
                        ColliderBuilder::convex_polyline(pts)
                            .ok_or_else(|| "rapier: bad polygon".to_owned())?
                    }
                    ShapeDesc::Segment(a, c) => ColliderBuilder::segment(
                        Vector::new(a.0 as f32, a.1 as f32),
                        Vector::new(c.0 as f32, c.1 as f32),
                    ),
                };
                let mut collider =
                    collider.density(b.density as f32).friction(b.friction as f32).restitution(0.0);
                if b.no_self_collision {
                    collider = collider.collision_groups(InteractionGroups::new(
                        Group::GROUP_2,
                        !Group::GROUP_2,
                        InteractionTestMode::And,
                    ));
                }
                let (h, _) = world.insert(body, collider);
                bodies.push(h);
            }
            for j in &scene.joints {
                let (a, b) = (bodies[j.a], bodies[j.b]);
                let anchor = Vector::new(j.anchor.0 as f32, j.anchor.1 as f32);
                let pa = world.bodies[a].translation();
                let pb = world.bodies[b].translation();
                let joint = RevoluteJointBuilder::new().local_anchor1(anchor - pa).local_anchor2(anchor - pb);
                world.impulse_joints.insert(a, b, joint, true);
            }
            Ok(Self { world, bodies })
        }

        fn step(&mut self) -> Result<(), String> {
            self.world.step();
            Ok(())
        }

        fn body(&mut self, i: usize) -> Result<BodyState, String> {
            let b = self.world.bodies.get(self.bodies[i]).ok_or_else(|| "rapier: stale body".to_owned())?;
            let p = b.translation();
            let v = b.linvel();
            Ok(BodyState { x: f64::from(p.x), y: f64::from(p.y), vx: f64::from(v.x), vy: f64::from(v.y) })
        }

        fn contact_count(&mut self) -> usize {
            self.world.narrow_phase.contact_pairs().filter(|p| p.has_any_active_contact()).count()
        }
    }
}

/// The largest speed of the scene's dynamic bodies, m/s.
pub fn max_speed<E: Engine>(e: &mut E, scene: &Scene) -> Result<f64, String> {
    let mut m = 0.0f64;
    for (i, b) in scene.bodies.iter().enumerate() {
        if b.dynamic {
            let s = e.body(i)?;
            m = m.max(s.vx.hypot(s.vy));
        }
    }
    Ok(m)
}
