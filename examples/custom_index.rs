//! The manual's custom spatial indexing system: a uniform grid that implements
//! [`SpatialIndex`], on fixed-size arrays (it never allocates), plugged into a
//! world with `set_spatial_index`.
//!
//! An index only answers "which pairs of bounding boxes overlap?"; the engine
//! sorts and deduplicates what it reports, runs the narrow phase and keeps the
//! arbiters. So a correct index (every overlapping pair reported) gives the very
//! same world as the default one: this example steps a pile of 240 mixed bodies
//! with the default index and with the grid, side by side, and checks that the
//! state hashes agree after every step.
//!
//! Run: `cargo run --release --example custom_index`

use std::time::{Duration, Instant};

use arphysics::index::proxies_may_touch;
use arphysics::{
    BodyDef, Capacities, GravityForceGenerator, Index, PairSink, PolygonPath, Proxy, Rect, Scalar,
    SpatialIndex, Vector2, World, WorldDef,
};

/// Grid cells across and down.
const COLS: usize = 32;
const ROWS: usize = 32;
const CELLS: usize = COLS * ROWS;
/// Most (proxy, cell) entries per step, and most proxies. Beyond them the grid
/// still answers, by testing all pairs: an index must never miss a pair.
const MAX_ENTRIES: usize = 4096;
const MAX_PROXIES: usize = 1024;

/// A uniform grid of square cells 2^`LOG2_CELL` m on a side, its corner at
/// `origin`. Each step it bins every proxy into the cells its box covers (a
/// counting sort into `entries`) and tests the pairs that share a cell. A pair
/// that shares several cells is reported once: from the cell holding the lower
/// corner of the two boxes' overlap.
struct UniformGrid {
    origin: Vector2,
    /// Where each cell's entries start in `entries` (a prefix sum), and one more.
    start: [u32; CELLS + 1],
    /// Fill cursor per cell while binning.
    cursor: [u32; CELLS],
    /// Proxy indices, cell by cell, in proxy order within a cell.
    entries: [u32; MAX_ENTRIES],
    /// Each proxy's cell range: (first column, first row, last column, last row).
    ranges: [[u16; 4]; MAX_PROXIES],
    /// Statistics for the curious.
    stats: Stats,
}

#[derive(Default, Debug)]
struct Stats {
    steps: u32,
    pairs: u64,
    most_entries: usize,
    all_pairs_fallbacks: u32,
}

/// 2 m cells: shifting the raw Q32.32 bits right by 32 + 1 divides by 2 m.
const LOG2_CELL: u32 = 1;

impl UniformGrid {
    fn new(origin: Vector2) -> Self {
        Self {
            origin,
            start: [0; CELLS + 1],
            cursor: [0; CELLS],
            entries: [0; MAX_ENTRIES],
            ranges: [[0; 4]; MAX_PROXIES],
            stats: Stats::default(),
        }
    }

    /// The column or row holding coordinate `v` (integer arithmetic on the raw
    /// bits, clamped to the grid: boxes outside it land in the border cells).
    fn cell(v: Scalar, origin: Scalar, count: usize) -> u16 {
        let d = (v - origin).to_bits();
        let c = if d < 0 { 0 } else { (d >> (32 + LOG2_CELL)).min(count as i64 - 1) };
        c as u16
    }

    fn range(&self, p: &Proxy) -> [u16; 4] {
        [
            Self::cell(p.aabb.min.x, self.origin.x, COLS),
            Self::cell(p.aabb.min.y, self.origin.y, ROWS),
            Self::cell(p.aabb.max.x, self.origin.x, COLS),
            Self::cell(p.aabb.max.y, self.origin.y, ROWS),
        ]
    }

    /// Bins the proxies; false when they do not fit the arrays.
    fn bin(&mut self, proxies: &[Proxy]) -> bool {
        if proxies.len() > MAX_PROXIES {
            return false;
        }
        self.start = [0; CELLS + 1];
        let mut total = 0usize;
        for (i, p) in proxies.iter().enumerate() {
            let r = self.range(p);
            self.ranges[i] = r;
            for row in r[1]..=r[3] {
                for col in r[0]..=r[2] {
                    self.start[usize::from(row) * COLS + usize::from(col) + 1] += 1;
                }
            }
            total += usize::from(r[2] - r[0] + 1) * usize::from(r[3] - r[1] + 1);
        }
        if total > MAX_ENTRIES {
            return false;
        }
        self.stats.most_entries = self.stats.most_entries.max(total);
        for c in 0..CELLS {
            self.start[c + 1] += self.start[c];
        }
        self.cursor.copy_from_slice(&self.start[..CELLS]);
        for i in 0..proxies.len() {
            let r = self.ranges[i];
            for row in r[1]..=r[3] {
                for col in r[0]..=r[2] {
                    let c = usize::from(row) * COLS + usize::from(col);
                    self.entries[self.cursor[c] as usize] = i as u32;
                    self.cursor[c] += 1;
                }
            }
        }
        true
    }
}

impl SpatialIndex for UniformGrid {
    fn find_pairs(&mut self, proxies: &[Proxy], out: &mut PairSink<'_>) {
        self.stats.steps += 1;
        let before = out.len();
        if !self.bin(proxies) {
            // Too many to bin: still answer correctly, the slow way.
            self.stats.all_pairs_fallbacks += 1;
            for i in 0..proxies.len() {
                for j in i + 1..proxies.len() {
                    if proxies_may_touch(&proxies[i], &proxies[j]) && !out.push(i as u32, j as u32) {
                        return;
                    }
                }
            }
            return;
        }
        for c in 0..CELLS {
            let cell = &self.entries[self.start[c] as usize..self.start[c + 1] as usize];
            for (k, &i) in cell.iter().enumerate() {
                for &j in &cell[k + 1..] {
                    let (a, b) = (&proxies[i as usize], &proxies[j as usize]);
                    if !proxies_may_touch(a, b) {
                        continue;
                    }
                    // Report from one cell only: the one holding the lower corner
                    // of the overlap (the larger of the two boxes' first cells).
                    let (ri, rj) = (self.ranges[i as usize], self.ranges[j as usize]);
                    let home = usize::from(ri[1].max(rj[1])) * COLS + usize::from(ri[0].max(rj[0]));
                    if home == c && !out.push(i, j) {
                        return; // the pair buffer is full: the step reports it
                    }
                }
            }
        }
        self.stats.pairs += (out.len() - before) as u64;
    }
}

/// A bin 40 m wide with 240 boxes, balls, triangles and hexagons dropped into it
/// in a loose grid. Built from integers only (centimetres), so both worlds are
/// the same bits.
fn build<'a>() -> Result<World<'a>, arphysics::Error> {
    let cm = |n: i32| Scalar::from_num(n) / 100;
    let bounds = Rect::from_corners(Vector2::from_int(-32, -8), Vector2::from_int(32, 56));
    let capacities = Capacities {
        bodies: 260,
        paths: 8,
        contacts: 1200,
        joints: 0,
        post_step_callbacks: 64,
        events: 64,
        chain_vertices: 0,
        shapes: 0,
    };
    let mut w = World::with_capacities(WorldDef::with_bounds(bounds), capacities)?;
    w.add_force_generator(GravityForceGenerator::new(Vector2::from_int(0, -10)))?;
    let ground = w.add_path(PolygonPath::rectangle(cm(4400), cm(100))?)?;
    w.add_body(BodyDef::polygon(ground).position(Vector2::new(cm(0), cm(-50))).static_body())?;
    let wall = w.add_path(PolygonPath::rectangle(cm(100), cm(3000))?)?;
    for x in [-2050, 2050] {
        w.add_body(BodyDef::polygon(wall).position(Vector2::new(cm(x), cm(1500))).static_body())?;
    }
    let boxp = w.add_path(PolygonPath::rectangle(cm(90), cm(70))?)?;
    let tri = w.add_path(PolygonPath::new(&[
        Vector2::new(cm(-50), cm(-30)),
        Vector2::new(cm(50), cm(-30)),
        Vector2::new(cm(0), cm(55)),
    ])?)?;
    let hex = w.add_path(PolygonPath::new(&[
        Vector2::new(cm(50), cm(0)),
        Vector2::new(cm(25), cm(43)),
        Vector2::new(cm(-25), cm(43)),
        Vector2::new(cm(-50), cm(0)),
        Vector2::new(cm(-25), cm(-43)),
        Vector2::new(cm(25), cm(-43)),
    ])?)?;
    for i in 0..240 {
        let (col, row) = (i % 20, i / 20);
        let p = Vector2::new(cm(-1850 + 195 * col + 13 * (row % 3)), cm(100 + 170 * row));
        let def = match i % 4 {
            0 => BodyDef::polygon(boxp),
            1 => BodyDef::circle(cm(30 + 5 * (i % 5))),
            2 => BodyDef::polygon(tri),
            _ => BodyDef::polygon(hex),
        };
        w.add_body(def.position(p).angle(cm(17 * (i % 11) - 85)))?;
    }
    Ok(w)
}

fn main() -> Result<(), arphysics::Error> {
    const STEPS: u32 = 300;
    let dt = Scalar::ONE / 60;
    // The grid is the game's object; the world borrows it.
    let mut grid = UniformGrid::new(Vector2::from_int(-32, -8));
    let mut reference = build()?; // the default index (Index::Auto)
    let (mut t_ref, mut t_grid) = (Duration::ZERO, Duration::ZERO);
    {
        let mut custom = build()?;
        custom.set_spatial_index(Index::borrowed(&mut grid));
        for step in 1..=STEPS {
            let t = Instant::now();
            reference.step(dt)?;
            t_ref += t.elapsed();
            let t = Instant::now();
            custom.step(dt)?;
            t_grid += t.elapsed();
            let (a, b) = (reference.state_hash(), custom.state_hash());
            assert_eq!(a, b, "the grid's world diverged at step {step}");
            if step % 60 == 0 {
                println!(
                    "t = {} s: {} contact pairs, state hash {a:#018x} with both indexes",
                    step / 60,
                    reference.arbiters().count()
                );
            }
        }
    }
    let s = &grid.stats;
    println!(
        "{STEPS} steps, {} bodies: the same state hash after every step with the default index and the grid",
        reference.body_count()
    );
    println!(
        "grid: {:.0} candidate pairs per step, at most {} of {MAX_ENTRIES} cell entries used, {} all-pairs fallbacks",
        s.pairs as f64 / f64::from(s.steps),
        s.most_entries,
        s.all_pairs_fallbacks
    );
    println!(
        "stepping time: default index {:.2} ms/step, grid {:.2} ms/step{}",
        t_ref.as_secs_f64() * 1000.0 / f64::from(STEPS),
        t_grid.as_secs_f64() * 1000.0 / f64::from(STEPS),
        if cfg!(debug_assertions) { " (debug build)" } else { "" }
    );
    Ok(())
}
