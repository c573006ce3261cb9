//! The quality suites' harness (`tests/quality.rs`, `tests/quality_issue16.rs`):
//! a metric is a measured number with the limit it must meet, printed as one
//! line with Box2D's figure beside it where one is known, and asserted after
//! every line of a scene is printed.
// Each suite uses part of the harness.
#![allow(dead_code)]

use arphysics::{Capacities, GravityForceGenerator, Rect, Scalar, Vector2, World, WorldDef};

/// The time step of every scene (s).
pub const DT: f64 = 1.0 / 60.0;
/// Gravity (m/s², downwards).
pub const G: f64 = 10.0;

pub fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

pub fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// A world of ±1000 m with room for `bodies` bodies, 8 paths and `contacts`
/// candidate pairs and arbiters, with gravity (0, −10) when `gravity` is true.
pub fn world_with_contacts(bodies: usize, contacts: usize, gravity: bool) -> World<'static> {
    let bounds = Rect::from_corners(v(-1000.0, -1000.0), v(1000.0, 1000.0));
    let mut w = World::with_capacities(
        WorldDef::with_bounds(bounds),
        Capacities {
            bodies,
            paths: 8,
            contacts,
            joints: 0,
            post_step_callbacks: 64,
            events: 64,
            chain_vertices: 0,
            shapes: 0,
        },
    )
    .expect("world");
    if gravity {
        w.add_force_generator(GravityForceGenerator::new(v(0.0, -G))).expect("gravity");
    }
    w
}

/// Steps for `seconds` of simulated time.
pub fn steps(seconds: f64) -> usize {
    (seconds / DT).round() as usize
}

/// What a metric must satisfy.
#[derive(Clone, Copy, Debug)]
pub enum Limit {
    /// value ≤ bound.
    AtMost(f64),
    /// value < bound.
    Below(f64),
    /// value ≥ bound.
    AtLeast(f64),
    /// |value − target| ≤ tolerance.
    Near { target: f64, tolerance: f64 },
    /// Printed for information, not asserted.
    Info,
}

impl Limit {
    pub fn holds(self, value: f64) -> bool {
        match self {
            Self::AtMost(b) => value <= b,
            Self::Below(b) => value < b,
            Self::AtLeast(b) => value >= b,
            Self::Near { target, tolerance } => (value - target).abs() <= tolerance,
            Self::Info => true,
        }
    }

    pub fn describe(self) -> String {
        match self {
            Self::AtMost(b) => format!("≤ {}", num(b)),
            Self::Below(b) => format!("< {}", num(b)),
            Self::AtLeast(b) => format!("≥ {}", num(b)),
            Self::Near { target, tolerance } => format!("{} ± {}", num(target), num(tolerance)),
            Self::Info => "info".to_string(),
        }
    }
}

/// One measured number of one scene.
#[derive(Clone, Debug)]
pub struct Metric {
    pub scene: &'static str,
    pub what: String,
    pub value: f64,
    pub unit: &'static str,
    pub limit: Limit,
    pub box2d: Option<&'static str>,
}

impl Metric {
    pub fn new(
        scene: &'static str,
        what: impl Into<String>,
        value: f64,
        unit: &'static str,
        limit: Limit,
    ) -> Self {
        Self { scene, what: what.into(), value, unit, limit, box2d: None }
    }

    pub fn box2d(mut self, figure: &'static str) -> Self {
        self.box2d = Some(figure);
        self
    }

    pub fn passes(&self) -> bool {
        self.limit.holds(self.value)
    }

    /// The value and its unit; nothing for a NaN value, which marks a metric
    /// whose text says it all.
    pub fn value_text(&self) -> String {
        if self.value.is_nan() {
            String::new()
        } else if self.unit.is_empty() {
            num(self.value)
        } else {
            format!("{} {}", num(self.value), self.unit)
        }
    }

    /// `quality <scene>: <what> <value> <unit> (<limit>) [Box2D <figure>]`.
    pub fn line(&self) -> String {
        let verdict = if self.passes() { "" } else { "  <-- FAILS" };
        format!(
            "quality {}: {} {} ({}) [Box2D {}]{verdict}",
            self.scene,
            self.what,
            self.value_text(),
            self.limit.describe(),
            self.box2d.unwrap_or("—"),
        )
    }
}

/// A number printed compactly: 4 decimals, or scientific when tiny.
pub fn num(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-3 {
        let t = format!("{x:.3e}");
        match t.split_once('e') {
            Some((mantissa, exp)) => {
                format!("{}e{exp}", mantissa.trim_end_matches('0').trim_end_matches('.'))
            }
            None => t,
        }
    } else {
        let t = format!("{x:.4}");
        let t = t.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" {
            "0".to_string()
        } else {
            t.to_string()
        }
    }
}

/// Prints every metric, then asserts they all hold (so one failure still shows
/// all the numbers).
pub fn check(metrics: &[Metric]) {
    for m in metrics {
        println!("{}", m.line());
    }
    let failed: Vec<String> = metrics.iter().filter(|m| !m.passes()).map(Metric::line).collect();
    assert!(failed.is_empty(), "quality thresholds missed:\n{}", failed.join("\n"));
}
