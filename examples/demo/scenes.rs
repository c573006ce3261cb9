//! The demo's scenes. Everything here is fixed point: positions, sizes and angles
//! are built from integers (centimetres) with `Scalar` arithmetic, and the
//! "random" variety comes from an integer generator, so a scene is the same bits
//! on every machine. Floats appear only in the viewport, which is for drawing.

use arphysics::{
    BodyDef, BodyHandle, Capacities, Capsule, ChainPath, Error, GravityForceGenerator, JointDef, JointKind,
    PathHandle, PolygonPath, Rect, Rot, Scalar, ShapeDef, Vector2, World, WorldDef,
};

/// `n` centimetres (or centiradians), exactly.
pub fn cm(n: i32) -> Scalar {
    Scalar::from_num(n) / 100
}

/// A point given in centimetres.
pub fn at(x: i32, y: i32) -> Vector2 {
    Vector2::new(cm(x), cm(y))
}

/// A small deterministic generator (xorshift32): variety without floats.
pub struct Rng(u32);

impl Rng {
    pub fn new(seed: u32) -> Self {
        Self(seed.max(1))
    }

    /// The next value in `0..n`.
    pub fn below(&mut self, n: u32) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x % n.max(1)
    }

    /// The next value in `lo..=hi`.
    pub fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + self.below((hi - lo + 1) as u32) as i32
    }
}

/// The paths a scene draws its falling shapes from.
pub struct Shapes {
    pub unit_box: PathHandle,
    pub small_box: PathHandle,
    pub triangle: PathHandle,
    pub pentagon: PathHandle,
    pub hexagon: PathHandle,
}

/// A regular polygon with `n` corners on a circle of `radius_cm`.
fn regular(n: i32, radius_cm: i32) -> Result<PolygonPath, Error> {
    let corners: Vec<Vector2> = (0..n)
        .map(|k| {
            Rot::from_angle(Scalar::TAU * k / n + Scalar::FRAC_PI_2)
                .rotate(Vector2::new(cm(radius_cm), cm(0)))
        })
        .collect();
    PolygonPath::new(&corners)
}

impl Shapes {
    pub fn add(w: &mut World<'_>) -> Result<Self, Error> {
        Ok(Self {
            unit_box: w.add_path(PolygonPath::rectangle(cm(100), cm(100))?)?,
            small_box: w.add_path(PolygonPath::rectangle(cm(80), cm(60))?)?,
            triangle: w.add_path(PolygonPath::new(&[at(-55, -35), at(55, -35), at(0, 60)])?)?,
            pentagon: w.add_path(regular(5, 50)?)?,
            hexagon: w.add_path(regular(6, 50)?)?,
        })
    }

    /// A random shape (circle, box, triangle, pentagon or hexagon) at `p`, turned
    /// and spinning a little.
    pub fn random(&self, rng: &mut Rng, p: Vector2) -> BodyDef {
        let def = match rng.below(6) {
            0 | 1 => BodyDef::circle(cm(rng.range(25, 55))),
            2 => BodyDef::polygon(if rng.below(2) == 0 { self.unit_box } else { self.small_box }),
            3 => BodyDef::polygon(self.triangle),
            4 => BodyDef::polygon(self.pentagon),
            _ => BodyDef::polygon(self.hexagon),
        };
        def.position(p).angle(cm(rng.range(-157, 157))).angular_velocity(cm(rng.range(-200, 200)))
    }

    /// A random shape of every kind: those of [`random`](Self::random), plus
    /// capsules (pills and long ones) and rounded boxes (`rounded`, a path).
    pub fn random_any(&self, rng: &mut Rng, p: Vector2, rounded: PathHandle) -> Result<BodyDef, Error> {
        let def = match rng.below(8) {
            0 | 1 => {
                let half = rng.range(10, 60);
                BodyDef::capsule(Capsule::new(at(-half, 0), at(half, 0), cm(rng.range(18, 35)))?)
            }
            2 => BodyDef::polygon(rounded),
            _ => return Ok(self.random(rng, p)),
        };
        Ok(def.position(p).angle(cm(rng.range(-157, 157))).angular_velocity(cm(rng.range(-200, 200))))
    }
}

/// A scene being simulated: its world and what it still adds as it runs.
pub struct Running {
    pub world: World<'static>,
    spawn: Option<Spawner>,
}

/// Adds a random shape every `every` frames from `start` until `count` are in.
struct Spawner {
    shapes: Shapes,
    rng: Rng,
    start: u32,
    every: u32,
    count: u32,
    /// x range (cm) and height (cm) where shapes appear.
    x: (i32, i32),
    y: i32,
    /// Extra: a cannonball at this frame, from (x, y) cm with velocity (m/s).
    cannonball: Option<(u32, Vector2, Vector2)>,
    /// Draw from every shape kind, rounded boxes from this path
    /// ([`Shapes::random_any`]).
    any_kind: Option<PathHandle>,
}

impl Running {
    /// Called before stepping frame `frame` (0-based): adds what is due.
    pub fn before_step(&mut self, frame: u32) -> Result<(), Error> {
        let Some(s) = &mut self.spawn else { return Ok(()) };
        if let Some((when, p, v)) = s.cannonball {
            if frame == when {
                self.world.add_body(
                    BodyDef::circle(cm(90)).position(p).linear_velocity(v).density(Scalar::from_num(8)),
                )?;
            }
        }
        if frame >= s.start
            && (frame - s.start).is_multiple_of(s.every)
            && (frame - s.start) / s.every < s.count
        {
            let p = at(s.rng.range(s.x.0, s.x.1), s.y);
            let def = match s.any_kind {
                Some(rounded) => s.shapes.random_any(&mut s.rng, p, rounded)?,
                None => s.shapes.random(&mut s.rng, p),
            };
            self.world.add_body(def)?;
        }
        Ok(())
    }
}

/// A scene: how to build it, how long to run it and what part of it to draw.
pub struct Scene {
    pub name: &'static str,
    pub about: &'static str,
    /// Simulated seconds.
    pub seconds: u32,
    /// The region drawn, in metres: (x0, y0, x1, y1). Drawing only.
    pub view: (f64, f64, f64, f64),
    pub build: fn() -> Result<Running, Error>,
}

pub const SCENES: &[Scene] = &[
    Scene {
        name: "default",
        about: "a pyramid, a chain on pivots with a wrecking ball, falling mixed shapes, a bouncing ball",
        seconds: 6,
        view: (-21.0, -1.0, 21.0, 22.0),
        build: lively,
    },
    Scene {
        name: "pyramid",
        about: "the 20-row pyramid (210 boxes) standing still, then a cannonball at 3 s",
        seconds: 8,
        view: (-22.0, -1.0, 22.0, 22.0),
        build: pyramid,
    },
    Scene {
        name: "chain",
        about: "a 24-link chain swinging from a pivot, and a rope bridge catching boxes",
        seconds: 8,
        view: (-12.0, -1.0, 20.0, 21.0),
        build: chain,
    },
    Scene {
        name: "rain",
        about: "150 mixed shapes raining onto two slippery ramps and into a bin",
        seconds: 10,
        view: (-15.0, -1.0, 15.0, 27.0),
        build: rain,
    },
    Scene {
        name: "terrain",
        about: "capsules, rounded boxes and every other shape raining onto hills of one chain",
        seconds: 10,
        view: (-21.0, -1.0, 21.0, 24.0),
        build: terrain,
    },
];

/// A world with gravity (0, −10), room for `bodies` bodies and `joints` joints,
/// bounds a little larger than anything the scenes reach.
fn world(bodies: usize, joints: usize) -> Result<World<'static>, Error> {
    let bounds = Rect::from_corners(Vector2::from_int(-60, -20), Vector2::from_int(60, 80));
    let capacities = Capacities {
        bodies,
        paths: 16,
        contacts: bodies * 4,
        joints,
        post_step_callbacks: 64,
        events: 64,
        chain_vertices: 64,
        shapes: 16,
    };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), capacities)?;
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10)))?;
    Ok(w)
}

/// Three compound bodies (several shapes on one body) with their left end
/// at (x, y) cm: an L of two boxes, a hammer (a capsule handle and a box
/// head, the head eight times as dense), and a dumbbell (a capsule bar and a
/// ball at each end).
pub fn add_compound_toys(w: &mut World<'_>, x: i32, y: i32) -> Result<(), Error> {
    let arm = w.add_path(PolygonPath::rectangle(cm(160), cm(30))?)?;
    let leg = w.add_path(PolygonPath::rectangle(cm(30), cm(130))?)?;
    let l = w.add_body(BodyDef::polygon(arm).position(at(x + 80, y)).angle(cm(20)))?;
    w.add_shape(l, ShapeDef::polygon(leg).offset(at(-65, 80)))?;
    let head = w.add_path(PolygonPath::rounded_rectangle(cm(40), cm(80), cm(8))?)?;
    let handle = Capsule::new(at(-70, 0), at(70, 0), cm(8))?;
    let hammer = w.add_body(BodyDef::capsule(handle).position(at(x + 300, y + 100)).angle(cm(-40)))?;
    w.add_shape(hammer, ShapeDef::polygon(head).offset(at(85, 0)).density(cm(800)))?;
    let bar = Capsule::new(at(-60, 0), at(60, 0), cm(10))?;
    let dumbbell = w.add_body(BodyDef::capsule(bar).position(at(x + 550, y + 50)).angle(cm(10)))?;
    for side in [-1, 1] {
        w.add_shape(dumbbell, ShapeDef::circle(cm(30)).offset(at(side * 75, 0)).restitution(cm(30)))?;
    }
    Ok(())
}

/// A static box `w` × `h` cm centred at (x, y) cm, turned by `angle` centiradians.
fn wall(w: &mut World<'_>, size: (i32, i32), centre: (i32, i32), angle: i32) -> Result<BodyHandle, Error> {
    let path = w.add_path(PolygonPath::rectangle(cm(size.0), cm(size.1))?)?;
    w.add_body(BodyDef::polygon(path).position(at(centre.0, centre.1)).angle(cm(angle)).static_body())
}

/// Ground with its top at y = 0 from x = −`half` to `half` m, and side walls
/// `height` m tall.
fn floor_and_walls(w: &mut World<'_>, half: i32, height: i32) -> Result<(), Error> {
    wall(w, (2 * half * 100 + 200, 100), (0, -50), 0)?;
    wall(w, (100, height * 100), (-half * 100 - 50, height * 50), 0)?;
    wall(w, (100, height * 100), (half * 100 + 50, height * 50), 0)?;
    Ok(())
}

/// A pyramid of 1 m boxes, `rows` at the base, centred on x (cm).
fn add_pyramid(w: &mut World<'_>, unit: PathHandle, rows: i32, x: i32) -> Result<(), Error> {
    for row in 0..rows {
        let count = rows - row;
        for j in 0..count {
            // Centres 1 m apart, the row centred: x + (j − (count − 1)/2) m.
            let cx = x + 100 * j - 50 * (count - 1);
            w.add_body(BodyDef::polygon(unit).position(at(cx, 50 + 100 * row)))?;
        }
    }
    Ok(())
}

/// A chain of `links` links `len` cm long hanging from the world point `from`
/// (cm), laid out towards `dir` (±1 along x), each joined to the next by a pivot.
/// Returns the last link.
fn add_chain(
    w: &mut World<'_>,
    from: (i32, i32),
    links: i32,
    len: i32,
    dir: i32,
) -> Result<BodyHandle, Error> {
    let link = w.add_path(PolygonPath::rectangle(cm(len), cm(24))?)?;
    let half = Vector2::new(cm(len / 2), cm(0));
    // The link's end towards the anchor, in its own frame.
    let (near, far) = if dir > 0 { (-half, half) } else { (half, -half) };
    let mut prev: Option<BodyHandle> = None;
    for i in 0..links {
        let cx = from.0 + dir * (len * i + len / 2);
        let body =
            w.add_body(BodyDef::polygon(link).position(at(cx, from.1)).density(Scalar::from_num(2)))?;
        let pivot = JointKind::Pivot { limits: None, motor: None };
        match prev {
            None => w.add_joint(JointDef::to_world(body, near, at(from.0, from.1), pivot))?,
            Some(p) => w.add_joint(JointDef::new(p, far, body, near, pivot))?,
        };
        prev = Some(body);
    }
    prev.ok_or(Error::InvalidOperation { what: "a chain needs a link" })
}

/// Hangs a ball of `radius` cm on the far end of `last`, a link `len` cm long
/// laid out towards `dir`.
fn add_end_ball(w: &mut World<'_>, last: BodyHandle, len: i32, dir: i32, radius: i32) -> Result<(), Error> {
    let end = w.body(last)?.position() + Vector2::new(cm(dir * (len / 2 + radius)), cm(0));
    let ball = w.add_body(BodyDef::circle(cm(radius)).position(end).density(Scalar::from_num(20)))?;
    let far = Vector2::new(cm(dir * len / 2), cm(0));
    let near = Vector2::new(cm(-dir * radius), cm(0));
    w.add_joint(JointDef::new(last, far, ball, near, JointKind::Pivot { limits: None, motor: None }))?;
    Ok(())
}

/// The lively mix.
fn lively() -> Result<Running, Error> {
    let mut w = world(160, 32)?;
    floor_and_walls(&mut w, 20, 16)?;
    let shapes = Shapes::add(&mut w)?;
    // A pyramid on the right…
    add_pyramid(&mut w, shapes.unit_box, 7, 1100)?;
    // …and a wrecking ball on a chain of 12 links hanging from (4, 11) m, laid out
    // horizontally to the left: it swings down into the pyramid.
    let last = add_chain(&mut w, (400, 1100), 12, 80, -1)?;
    add_end_ball(&mut w, last, 80, -1, 60)?;
    // A bouncy ball between the pyramid and the wall.
    w.add_body(BodyDef::circle(cm(60)).position(at(1720, 1400)).restitution(cm(90)).friction(cm(20)))?;
    // Falling shapes on the left: a 5 × 5 block of them, jittered…
    let mut rng = Rng::new(2024);
    for row in 0..5 {
        for col in 0..5 {
            let p = at(-1850 + 260 * col + rng.range(-30, 30), 300 + 260 * row + rng.range(-30, 30));
            w.add_body(shapes.random(&mut rng, p))?;
        }
    }
    // …and more raining in over the first three seconds.
    let spawn = Spawner {
        shapes,
        rng,
        start: 30,
        every: 8,
        count: 20,
        x: (-1800, 0),
        y: 2000,
        cannonball: None,
        any_kind: None,
    };
    Ok(Running { world: w, spawn: Some(spawn) })
}

/// The benchmark pyramid, then a cannonball.
fn pyramid() -> Result<Running, Error> {
    let mut w = world(240, 0)?;
    wall(&mut w, (4400, 100), (0, -50), 0)?;
    let shapes = Shapes::add(&mut w)?;
    add_pyramid(&mut w, shapes.unit_box, 20, 0)?;
    let cannonball = Some((180, at(-2000, 300), Vector2::from_int(30, 4)));
    let spawn = Spawner {
        shapes,
        rng: Rng::new(1),
        start: 0,
        every: 1,
        count: 0,
        x: (0, 0),
        y: 0,
        cannonball,
        any_kind: None,
    };
    Ok(Running { world: w, spawn: Some(spawn) })
}

/// A long chain with a ball, and a bridge of planks pinned at both ends.
fn chain() -> Result<Running, Error> {
    let mut w = world(120, 64)?;
    wall(&mut w, (3800, 100), (200, -50), 0)?;
    let shapes = Shapes::add(&mut w)?;
    let last = add_chain(&mut w, (0, 1800), 24, 40, -1)?;
    add_end_ball(&mut w, last, 40, -1, 50)?;
    // A bridge: 16 planks from (2, 8) m to (18, 8) m, its last plank pinned to the
    // world too.
    let last = add_chain(&mut w, (200, 800), 16, 100, 1)?;
    let pivot = JointKind::Pivot { limits: None, motor: None };
    w.add_joint(JointDef::to_world(last, at(50, 0), at(1800, 800), pivot))?;
    // Posts under the bridge's ends.
    wall(&mut w, (60, 800), (170, 400), 0)?;
    wall(&mut w, (60, 800), (1830, 400), 0)?;
    let spawn = Spawner {
        shapes,
        rng: Rng::new(7),
        start: 20,
        every: 12,
        count: 24,
        x: (400, 1600),
        y: 1800,
        cannonball: None,
        any_kind: None,
    };
    Ok(Running { world: w, spawn: Some(spawn) })
}

/// Shapes raining onto slippery ramps and into a bin.
fn rain() -> Result<Running, Error> {
    let mut w = world(170, 0)?;
    floor_and_walls(&mut w, 14, 10)?;
    let ramp = w.add_path(PolygonPath::rectangle(cm(1000), cm(40))?)?;
    for (x, y, angle) in [(-600, 1600, -35), (600, 900, 35)] {
        w.add_body(
            BodyDef::polygon(ramp).position(at(x, y)).angle(cm(angle)).friction(cm(10)).static_body(),
        )?;
    }
    let shapes = Shapes::add(&mut w)?;
    let spawn = Spawner {
        shapes,
        rng: Rng::new(99),
        start: 0,
        every: 4,
        count: 150,
        x: (-1100, 1100),
        y: 2500,
        cannonball: None,
        any_kind: None,
    };
    Ok(Running { world: w, spawn: Some(spawn) })
}

/// Rolling hills of one static chain (its links one-sided, nothing catches
/// at the joins), a rounded ledge, and every shape kind raining down: capsules
/// roll and slide, rounded boxes tumble, the sharp shapes settle in the
/// hollows.
fn terrain() -> Result<Running, Error> {
    let mut w = world(200, 0)?;
    // Heights (cm) of the hills' corners, 2 m apart from x = −20 m.
    const HEIGHTS: [i32; 21] =
        [900, 600, 350, 180, 100, 90, 140, 260, 300, 220, 120, 60, 40, 80, 180, 320, 360, 300, 420, 650, 900];
    // Walked right to left, so the links' solid side is below them.
    let points: Vec<Vector2> =
        HEIGHTS.iter().enumerate().rev().map(|(i, &h)| at(-2000 + 200 * i as i32, h)).collect();
    let hills = w.add_chain(ChainPath::open(&points)?)?;
    w.add_body(BodyDef::chain(hills).friction(cm(50)))?;
    let ledge = w.add_path(PolygonPath::rounded_rectangle(cm(400), cm(60), cm(25))?)?;
    w.add_body(BodyDef::polygon(ledge).position(at(-900, 900)).angle(cm(-25)).static_body())?;
    let rounded = w.add_path(PolygonPath::rounded_rectangle(cm(90), cm(70), cm(15))?)?;
    add_compound_toys(&mut w, 200, 1200)?;
    let shapes = Shapes::add(&mut w)?;
    let spawn = Spawner {
        shapes,
        rng: Rng::new(19),
        start: 0,
        every: 5,
        count: 120,
        x: (-1800, 1800),
        y: 2200,
        cannonball: None,
        any_kind: Some(rounded),
    };
    Ok(Running { world: w, spawn: Some(spawn) })
}
