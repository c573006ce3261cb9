//! Records a world every few frames and writes one animated SVG: one group per
//! body with SMIL `<animateTransform>` (a translate and a rotate) running through
//! its recorded poses, joints as one animated path. Static bodies are drawn once.
//!
//! This is the only place the demo uses floats, and only for drawing: positions
//! and rotations are converted with `to_f64` after each recorded step.

use std::collections::HashMap;
use std::fmt::Write as _;

use arphysics::{Body, BodyHandle, Shape, Vector2, World};

/// Width of the picture in pixels; the height follows the scene's view.
const WIDTH: f64 = 960.0;
const TITLE_BAR: f64 = 30.0;

/// What a body looks like: its outline in its own frame, and its colour.
struct Look {
    outline: Outline,
    fill: &'static str,
    is_static: bool,
}

enum Outline {
    Circle(f64),
    /// The core polygon and the rounding radius (0 for a sharp polygon).
    Polygon(Vec<(f64, f64)>, f64),
    /// Two centres and the radius (0 for a segment, drawn as a thin line).
    Capsule((f64, f64), (f64, f64), f64),
    /// A chain's points and whether it closes (drawn as a thin polyline).
    Chain(Vec<(f64, f64)>, bool),
    /// A compound body's shapes, each placed on the body (x, y in m, angle in
    /// degrees).
    Group(Vec<((f64, f64, f64), Outline)>),
}

/// One body's poses: x, y (m) and the angle in degrees, unwrapped so that the
/// interpolation between two samples turns the short way.
struct Track {
    look: Look,
    /// Index of the sample the body first appears in.
    first: usize,
    poses: Vec<(f64, f64, f64)>,
}

pub struct Recorder {
    view: (f64, f64, f64, f64),
    title: String,
    frame_seconds: f64,
    tracks: Vec<Track>,
    by_handle: HashMap<BodyHandle, usize>,
    /// Joint segments per sample: centre A → anchor A → anchor B → centre B (or
    /// the world point).
    joints: Vec<Vec<[(f64, f64); 4]>>,
    samples: usize,
}

fn xy(v: Vector2) -> (f64, f64) {
    v.to_f64()
}

/// The colour of a dynamic body by kind (a compound body's by its first
/// shape); static bodies are grey.
fn colour(h: BodyHandle, body: &Body, world: &World<'_>, jointed: bool) -> (Outline, &'static str) {
    let (first, fill) = shape_colour(body.shape(), body, world, jointed);
    if body.shape_count() < 2 {
        return (first, fill);
    }
    let parts = world
        .shapes(h)
        .into_iter()
        .flatten()
        .map(|(_, s)| {
            let (x, y) = xy(s.local.p);
            let deg = s.local.q.s.to_num::<f64>().atan2(s.local.q.c.to_num::<f64>()).to_degrees();
            ((x, y, deg), shape_colour(s.shape, body, world, jointed).0)
        })
        .collect();
    (Outline::Group(parts), fill)
}

/// The outline of one shape and its colour by kind.
fn shape_colour(shape: Shape, body: &Body, world: &World<'_>, jointed: bool) -> (Outline, &'static str) {
    match shape {
        Shape::Circle { radius } => {
            let fill = if jointed {
                "#5d4037"
            } else if body.restitution().to_num::<f64>() > 0.5 {
                "#e63946"
            } else {
                "#f4a261"
            };
            (Outline::Circle(radius.to_num()), fill)
        }
        Shape::Polygon(path) => {
            let vertices: Vec<(f64, f64)> =
                world.path(path).map(|p| p.vertices().iter().map(|&v| xy(v)).collect()).unwrap_or_default();
            let fill = match (jointed, vertices.len()) {
                (true, _) => "#8d6e63",
                (_, 3) => "#2a9d8f",
                (_, 4) => "#457b9d",
                (_, 5) => "#e9c46a",
                (_, 6) => "#9b72cf",
                _ => "#6c757d",
            };
            let rounding = world.path(path).map_or(0.0, |p| p.rounding().to_num());
            (Outline::Polygon(vertices, rounding), fill)
        }
        Shape::Capsule(c) => {
            let fill = if jointed { "#8d6e63" } else { "#f28482" };
            (Outline::Capsule(xy(c.center1()), xy(c.center2()), c.radius().to_num()), fill)
        }
        Shape::Segment(sg) => (Outline::Capsule(xy(sg.point1()), xy(sg.point2()), 0.0), "#6c757d"),
        Shape::Chain(h) => {
            (Outline::Chain(world.chain_points(h).map(xy).collect(), h.is_closed()), "#6c757d")
        }
    }
}

impl Recorder {
    /// `view` is the drawn region in metres, `frame_seconds` the time between
    /// two recorded samples.
    pub fn new(view: (f64, f64, f64, f64), title: String, frame_seconds: f64) -> Self {
        Self {
            view,
            title,
            frame_seconds,
            tracks: Vec::new(),
            by_handle: HashMap::new(),
            joints: Vec::new(),
            samples: 0,
        }
    }

    /// Records the world as it is now.
    pub fn sample(&mut self, world: &World<'_>) {
        let jointed: Vec<BodyHandle> =
            world.joints().flat_map(|(_, j)| [Some(j.def().body_a), j.def().body_b]).flatten().collect();
        for (h, b) in world.bodies() {
            let i = match self.by_handle.get(&h) {
                Some(&i) => i,
                None => {
                    let (outline, fill) = colour(h, b, world, jointed.contains(&h));
                    let fill = if b.is_static() { "#9aa0a6" } else { fill };
                    self.tracks.push(Track {
                        look: Look { outline, fill, is_static: b.is_static() },
                        first: self.samples,
                        poses: Vec::new(),
                    });
                    self.by_handle.insert(h, self.tracks.len() - 1);
                    self.tracks.len() - 1
                }
            };
            let (x, y) = xy(b.position());
            let q = b.rotation();
            let mut deg = q.s.to_num::<f64>().atan2(q.c.to_num::<f64>()).to_degrees();
            let track = &mut self.tracks[i];
            if let Some(&(_, _, last)) = track.poses.last() {
                deg += ((last - deg) / 360.0).round() * 360.0;
            }
            track.poses.push((x, y, deg));
        }
        let mut segments = Vec::new();
        for (_, j) in world.joints() {
            let d = j.def();
            let Ok(a) = world.body(d.body_a) else { continue };
            let pa = a.transform().apply(d.anchor_a);
            let (pb, cb) = match d.body_b.and_then(|h| world.body(h).ok()) {
                Some(b) => (b.transform().apply(d.anchor_b), b.position()),
                None => (d.anchor_b, d.anchor_b),
            };
            segments.push([xy(a.position()), xy(pa), xy(pb), xy(cb)]);
        }
        self.joints.push(segments);
        self.samples += 1;
    }

    /// The picture, with `note` at the top right.
    pub fn svg(&self, note: &str) -> String {
        let (x0, y0, x1, y1) = self.view;
        let k = WIDTH / (x1 - x0);
        let height = ((y1 - y0) * k).round();
        let dur = self.frame_seconds * (self.samples.max(2) - 1) as f64;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH} {h}" width="{WIDTH}" height="{h}" font-family="sans-serif">"##,
            h = height + TITLE_BAR
        );
        let _ = writeln!(s, r##"<rect width="100%" height="100%" fill="#fbfaf6"/>"##);
        let _ =
            writeln!(s, r##"<text x="10" y="20" font-size="15" fill="#333">{}</text>"##, escape(&self.title));
        let _ = writeln!(
            s,
            r##"<text x="{x}" y="20" font-size="13" fill="#666" text-anchor="end">{}</text>"##,
            escape(note),
            x = WIDTH - 10.0
        );
        // Progress bar: how far through the recording the animation is.
        let _ = writeln!(
            s,
            r##"<rect x="0" y="{y}" width="0" height="3" fill="#457b9d"><animate attributeName="width" values="0;{WIDTH}" dur="{dur}s" repeatCount="indefinite"/></rect>"##,
            y = TITLE_BAR - 3.0,
            dur = num(dur, 3)
        );
        // World → picture: x right, y up, metres to pixels.
        let _ = writeln!(
            s,
            r##"<g transform="matrix({k} 0 0 {mk} {tx} {ty})" stroke="#222" stroke-width="{sw}" stroke-linejoin="round">"##,
            k = num(k, 4),
            mk = num(-k, 4),
            tx = num(-k * x0, 3),
            ty = num(k * y1 + TITLE_BAR, 3),
            sw = num(1.2 / k, 4)
        );
        for t in self.tracks.iter().filter(|t| t.look.is_static) {
            let (x, y, a) = t.poses[0];
            let _ = writeln!(
                s,
                r#"<g transform="translate({} {}) rotate({})">{}</g>"#,
                num(x, 3),
                num(y, 3),
                num(a, 2),
                shape(&t.look.outline, t.look.fill)
            );
        }
        for t in self.tracks.iter().filter(|t| !t.look.is_static) {
            self.write_body(&mut s, t, dur);
        }
        self.write_joints(&mut s, dur);
        s.push_str("</g>\n</svg>\n");
        s
    }

    fn write_body(&self, s: &mut String, t: &Track, dur: f64) {
        // Pad to the whole recording: the first pose before the body appears, the
        // last after it disappears.
        let last = t.first + t.poses.len();
        let pose = |i: usize| t.poses[i.clamp(t.first, last - 1) - t.first];
        let moves = t.poses.iter().any(|p| (p.0, p.1, p.2) != (t.poses[0].0, t.poses[0].1, t.poses[0].2));
        if !moves {
            let (x, y, a) = t.poses[0];
            let _ =
                write!(s, r#"<g transform="translate({} {}) rotate({})">"#, num(x, 2), num(y, 2), num(a, 1));
        } else {
            let translate: Vec<String> =
                (0..self.samples).map(|i| format!("{} {}", num(pose(i).0, 2), num(pose(i).1, 2))).collect();
            let rotate: Vec<String> = (0..self.samples).map(|i| num(pose(i).2, 1)).collect();
            let _ = write!(
                s,
                r#"<g><animateTransform attributeName="transform" type="translate" values="{}" dur="{d}s" repeatCount="indefinite"/><animateTransform attributeName="transform" type="rotate" additive="sum" values="{}" dur="{d}s" repeatCount="indefinite"/>"#,
                translate.join(";"),
                rotate.join(";"),
                d = num(dur, 3)
            );
        }
        if t.first > 0 || last < self.samples {
            // Visible only while it exists.
            let n = (self.samples.max(2) - 1) as f64;
            let mut values = vec!["hidden"];
            let mut times = vec!["0".to_string()];
            if t.first > 0 {
                values.push("visible");
                times.push(num(t.first as f64 / n, 4));
            } else {
                values[0] = "visible";
            }
            if last < self.samples {
                values.push("hidden");
                times.push(num(last as f64 / n, 4));
            }
            let _ = write!(
                s,
                r#"<animate attributeName="visibility" values="{}" keyTimes="{}" calcMode="discrete" dur="{}s" repeatCount="indefinite"/>"#,
                values.join(";"),
                times.join(";"),
                num(dur, 3)
            );
        }
        let _ = writeln!(s, "{}</g>", shape(&t.look.outline, t.look.fill));
    }

    fn write_joints(&self, s: &mut String, dur: f64) {
        if self.joints.iter().all(Vec::is_empty) {
            return;
        }
        let paths: Vec<String> = self
            .joints
            .iter()
            .map(|segs| {
                let mut d = String::new();
                for seg in segs {
                    for (i, p) in seg.iter().enumerate() {
                        let _ =
                            write!(d, "{}{} {}", if i == 0 { "M" } else { "L" }, num(p.0, 2), num(p.1, 2));
                    }
                }
                d
            })
            .collect();
        let _ = writeln!(
            s,
            r##"<path fill="none" stroke="#1d1d1d" stroke-width="0.06" stroke-linecap="round" d="{}"><animate attributeName="d" values="{}" dur="{}s" repeatCount="indefinite"/></path>"##,
            paths[0],
            paths.join(";"),
            num(dur, 3)
        );
        // The fixed world points the joints hang from.
        let mut fixed = String::new();
        for seg in self.joints.first().into_iter().flatten() {
            if seg[2] == seg[3] {
                let _ = write!(
                    fixed,
                    r#"<circle cx="{}" cy="{}" r="0.15"/>"#,
                    num(seg[3].0, 2),
                    num(seg[3].1, 2)
                );
            }
        }
        let _ = writeln!(s, r##"<g fill="#222">{fixed}</g>"##);
    }
}

/// The body's outline in its own frame.
fn shape(outline: &Outline, fill: &str) -> String {
    match outline {
        Outline::Group(parts) => parts
            .iter()
            .map(|((x, y, a), o)| {
                format!(
                    r#"<g transform="translate({} {}) rotate({})">{}</g>"#,
                    num(*x, 3),
                    num(*y, 3),
                    num(*a, 1),
                    shape(o, fill)
                )
            })
            .collect(),
        Outline::Circle(r) => {
            format!(r#"<circle r="{r}" fill="{f}"/><path d="M0 0H{r}"/>"#, r = num(*r, 3), f = fill)
        }
        Outline::Polygon(v, rounding) => {
            let points: Vec<String> = v.iter().map(|p| format!("{},{}", num(p.0, 3), num(p.1, 3))).collect();
            // A rounded polygon is its core stroked with round joins, 2r wide.
            let stroke = if *rounding > 0.0 {
                format!(
                    r#" stroke="{}" stroke-width="{}" stroke-linejoin="round""#,
                    fill,
                    num(2.0 * rounding, 3)
                )
            } else {
                String::new()
            };
            format!(r#"<polygon points="{}" fill="{}"{stroke}/>"#, points.join(" "), fill)
        }
        Outline::Capsule(a, b, r) => {
            // A capsule is its core segment stroked with round caps, 2r wide;
            // a segment a thin line.
            let width = if *r > 0.0 { 2.0 * r } else { 0.08 };
            let cap = if *r > 0.0 { "round" } else { "butt" };
            format!(
                r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="{}" stroke-linecap="{cap}"/>"#,
                num(a.0, 3),
                num(a.1, 3),
                num(b.0, 3),
                num(b.1, 3),
                fill,
                num(width, 3)
            )
        }
        Outline::Chain(v, closed) => {
            let points: Vec<String> = v.iter().map(|p| format!("{},{}", num(p.0, 3), num(p.1, 3))).collect();
            let tag = if *closed { "polygon" } else { "polyline" };
            format!(
                r#"<{tag} points="{}" fill="none" stroke="{}" stroke-width="0.08" stroke-linejoin="round"/>"#,
                points.join(" "),
                fill
            )
        }
    }
}

/// `x` with at most `decimals` decimals, trailing zeros dropped, no "-0".
fn num(x: f64, decimals: usize) -> String {
    let mut t = format!("{x:.decimals$}");
    if t.contains('.') {
        while t.ends_with('0') {
            t.pop();
        }
        if t.ends_with('.') {
            t.pop();
        }
    }
    if t == "-0" {
        t = "0".to_string();
    }
    t
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
