//! Geometry of the shapes built on segments (issue 19): capsules, segments and
//! rounded polygons. Mass properties against closed forms (and, for a rounded
//! triangle, a numerical integration on a fine grid), the errors, ray casts and
//! bounding boxes against analytic values.

use arphysics::geometry::ray::{
    capsule_contains, polygon_contains, ray_capsule, ray_polygon, ray_segment, ShapeHit,
};
use arphysics::geometry::*;
use arphysics::math::scalar::{self, Scalar};
use arphysics::math::{Rect, Rot, Transform, Vector2};
use arphysics::Error;
use std::f64::consts::PI;

// ---------------------------------------------------------------- helpers

fn s(v: f64) -> Scalar {
    scalar::checked_from_f64(v).expect("test value in range")
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::checked_from_f64(x, y).expect("test value in range")
}

fn f(x: Scalar) -> f64 {
    x.to_f64()
}

/// One step of 2^-32.
const ULP: f64 = 1.0 / 4_294_967_296.0;

fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got}, want {want} (diff {}, tol {tol})", got - want);
}

fn out_of_range(what: &'static str) -> Error {
    Error::OutOfRange { what }
}

fn xf(x: f64, y: f64, angle: f64) -> Transform {
    Transform::new(v(x, y), Rot::from_angle(s(angle)))
}

fn hit(h: Option<ShapeHit>, what: &str) -> (f64, (f64, f64)) {
    let h = h.unwrap_or_else(|| panic!("{what}: expected a hit"));
    (f(h.distance), h.normal.to_f64())
}

fn assert_hit(h: Option<ShapeHit>, distance: f64, normal: (f64, f64), what: &str) {
    let (d, n) = hit(h, what);
    assert_close(d, distance, 1e-7, what);
    assert_close(n.0, normal.0, 1e-7, what);
    assert_close(n.1, normal.1, 1e-7, what);
}

/// Closed-form capsule area and polar inertia about the centroid (density 1).
fn capsule_closed_form(r: f64, l: f64) -> (f64, f64) {
    let area = PI * r * r + 2.0 * r * l;
    let inertia = PI * r * r * (r * r / 2.0 + l * l / 4.0) + r * l * (2.0 * r * r + l * l / 6.0);
    (area, inertia)
}

// ---------------------------------------------------------------- capsule

#[test]
fn capsule_mass_properties_match_the_closed_forms() {
    // Axis along (3, 4)/5 and along x; centred on the origin.
    for &r in &[0.05, 0.1, 0.5, 1.0, 3.7, 20.0] {
        for &l in &[0.0, 0.25, 1.0, 2.0, 10.0, 60.0] {
            for dir in [(1.0, 0.0), (0.6, 0.8)] {
                let half = (dir.0 * l / 2.0, dir.1 * l / 2.0);
                let c = Capsule::new(v(-half.0, -half.1), v(half.0, half.1), s(r)).expect("valid capsule");
                // The stored centres are rounded to 2^-32: use their exact length.
                let (a, b) = (c.center1().to_f64(), c.center2().to_f64());
                let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
                let (area, inertia) = capsule_closed_form(f(c.radius()), len);
                let what = format!("r {r} L {l} dir {dir:?}");
                assert_close(f(c.length()), len, ULP, &format!("{what}: length"));
                assert_close(f(c.area().unwrap()), area, ULP + area * 1e-15, &format!("{what}: area"));
                assert_close(
                    f(c.unit_inertia().unwrap()),
                    inertia,
                    2.0 * ULP + inertia * 1e-15,
                    &format!("{what}: inertia"),
                );
                assert_eq!(c.centroid(), Vector2::ZERO, "{what}: centroid");
            }
        }
    }
}

#[test]
fn zero_length_capsule_is_the_circle_bit_for_bit() {
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    for i in 0..2_000 {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        // Radii from 2^-32 m up to 128 m, biased to small values.
        let bits = (seed >> (i % 25 + 25)) as i64 + 1;
        let r = Scalar::from_bits(bits).min(MAX_CIRCLE_RADIUS);
        let c = Capsule::new(v(0.0, 0.0), v(0.0, 0.0), r).expect("valid");
        assert_eq!(c.area(), circle_area(r), "area at r = {r:?}");
        assert_eq!(c.unit_inertia(), circle_unit_inertia(r), "inertia at r = {r:?}");
        // Off the origin too: only the length matters.
        let c = Capsule::new(v(3.5, -2.25), v(3.5, -2.25), r.min(s(100.0))).expect("valid");
        assert_eq!(c.area(), circle_area(c.radius()));
        assert_eq!(c.unit_inertia(), circle_unit_inertia(c.radius()));
    }
}

#[test]
fn capsule_centroid_bound_and_box() {
    let c = Capsule::new(v(1.0, 2.0), v(4.0, 6.0), s(0.5)).unwrap();
    assert_eq!(c.length(), s(5.0));
    assert_eq!(c.centroid(), v(2.5, 4.0));
    // max(|(1,2)|, |(4,6)|) + 0.5 = √52 + 0.5, rounded up.
    let br = f(c.bounding_radius());
    assert!(br >= 52f64.sqrt() + 0.5 && br <= 52f64.sqrt() + 0.5 + ULP, "bounding radius {br}");

    // A 2 m core along x, rotated by 30° and moved to (10, 5): the box is the
    // centres' box grown by r.
    let c = Capsule::new(v(-1.0, 0.0), v(1.0, 0.0), s(0.5)).unwrap();
    let (cs, sn) = ((PI / 6.0).cos(), (PI / 6.0).sin());
    let b = c.aabb(xf(10.0, 5.0, PI / 6.0));
    let (lo, hi) = (b.min.to_f64(), b.max.to_f64());
    assert_close(lo.0, 10.0 - cs - 0.5, 1e-8, "min x");
    assert_close(lo.1, 5.0 - sn - 0.5, 1e-8, "min y");
    assert_close(hi.0, 10.0 + cs + 0.5, 1e-8, "max x");
    assert_close(hi.1, 5.0 + sn + 0.5, 1e-8, "max y");
    // Unrotated: exact.
    let b = c.aabb(Transform::new(v(2.0, 3.0), Rot::IDENTITY));
    assert_eq!(b, Rect { min: v(0.5, 2.5), max: v(3.5, 3.5) });
}

#[test]
fn capsule_errors_name_what_is_wrong() {
    let (a, b) = (v(-1.0, 0.0), v(1.0, 0.0));
    for r in [0.0, -0.5, 128.001] {
        assert_eq!(Capsule::new(a, b, s(r)), Err(out_of_range("capsule radius")), "r = {r}");
    }
    // Half the length + r = 128 exactly is allowed, wherever it is; a hair
    // more is not (a body re-centres the capsule).
    assert!(Capsule::new(v(127.0, 0.0), v(-127.0, 0.0), s(1.0)).is_ok());
    assert!(Capsule::new(v(1000.0, 0.0), v(1254.0, 0.0), s(1.0)).is_ok());
    assert!(Capsule::new(v(0.0, 0.0), v(0.0, 0.0), MAX_CIRCLE_RADIUS).is_ok());
    assert_eq!(Capsule::new(v(0.0, 0.0), v(254.0 + ULP, 0.0), s(1.0)), Err(out_of_range("capsule size")));
    assert_eq!(Capsule::new(v(180.0, 180.0), v(0.0, 0.0), s(1.0)), Err(out_of_range("capsule size")));
    let far = 2f64.powi(20) + 1.0;
    assert_eq!(Capsule::new(v(far, 0.0), v(far, 0.0), s(1.0)), Err(out_of_range("capsule size")));
    assert_eq!(Capsule::new(v(1.0, 0.0), v(1.0, 0.0), s(200.0)), Err(out_of_range("capsule radius")));
}

// ---------------------------------------------------------------- segment

#[test]
fn segment_length_centroid_rod_inertia_and_box() {
    let seg = Segment::new(v(-1.0, -1.0), v(2.0, 3.0)).unwrap();
    assert_eq!(seg.length(), s(5.0));
    assert_eq!(seg.centroid(), v(0.5, 1.0));
    // L² / 12 = 25 / 12, correctly rounded.
    assert_close(f(seg.rod_unit_inertia()), 25.0 / 12.0, ULP / 2.0, "rod inertia");
    assert_close(f(seg.bounding_radius()), 13f64.sqrt(), ULP, "bounding radius");
    assert!(f(seg.bounding_radius()) >= 13f64.sqrt());
    for &l in &[0.001, 0.3, 1.0, 7.5, 100.0, 255.0] {
        let seg = Segment::new(v(-l / 2.0, 0.0), v(l / 2.0, 0.0)).unwrap();
        let len = f(seg.point2().x - seg.point1().x);
        assert_close(f(seg.length()), len, ULP / 2.0, "length");
        assert_close(f(seg.rod_unit_inertia()), len * len / 12.0, ULP / 2.0 + len * len * 1e-16, "rod");
    }

    // Rotated by 30° about the origin, moved to (-3, 2).
    let seg = Segment::new(v(0.0, 0.0), v(2.0, 0.0)).unwrap();
    let b = seg.aabb(xf(-3.0, 2.0, PI / 6.0));
    let (lo, hi) = (b.min.to_f64(), b.max.to_f64());
    assert_close(lo.0, -3.0, 1e-9, "min x");
    assert_close(lo.1, 2.0, 1e-9, "min y");
    assert_close(hi.0, -3.0 + 2.0 * (PI / 6.0).cos(), 1e-8, "max x");
    assert_close(hi.1, 2.0 + 2.0 * (PI / 6.0).sin(), 1e-8, "max y");
}

#[test]
fn segment_errors_name_what_is_wrong() {
    let p = v(3.0, 4.0);
    assert_eq!(Segment::new(p, p), Err(out_of_range("segment length")));
    let short = Vector2::new(p.x + Scalar::from_bits(1 << 11), p.y);
    assert_eq!(Segment::new(p, short), Err(out_of_range("segment length")));
    let shortest = Vector2::new(p.x + MIN_SEGMENT_LENGTH, p.y);
    assert!(Segment::new(p, shortest).is_ok(), "exactly the minimum length is allowed");
    assert!(Segment::new(v(128.0, 0.0), v(-128.0, 0.0)).is_ok(), "256 m exactly is allowed");
    assert!(Segment::new(v(500.0, 0.0), v(500.0, 256.0)).is_ok(), "anywhere in the world");
    assert_eq!(Segment::new(v(0.0, 0.0), v(0.0, 256.0 + ULP)), Err(out_of_range("segment size")));
    assert_eq!(Segment::new(v(182.0, 182.0), v(0.0, 0.0)), Err(out_of_range("segment size")));
    let far = 2f64.powi(20) + 1.0;
    assert_eq!(Segment::new(v(far, 0.0), v(far, 1.0)), Err(out_of_range("segment size")));
}

// ---------------------------------------------------------------- rounded polygons

/// A `w × h` rectangle with corners rounded by `r`, by an independent
/// decomposition: the `w × (h − 2r)` middle, two `(w − 2r) × r` caps and four
/// quarter discs.
fn rounded_rectangle_closed_form(w: f64, h: f64, r: f64) -> (f64, f64) {
    let rect = |a: f64, b: f64| a * b * (a * a + b * b) / 12.0;
    let area = w * h - (4.0 - PI) * r * r;
    let cap_area = (w - 2.0 * r) * r;
    let (cx, cy) = (w / 2.0 - r, h / 2.0 - r);
    let quarter =
        PI * r.powi(4) / 8.0 + 2.0 * r.powi(3) / 3.0 * (cx + cy) + PI * r * r / 4.0 * (cx * cx + cy * cy);
    let inertia = rect(w, h - 2.0 * r)
        + 2.0 * (rect(w - 2.0 * r, r) + cap_area * (h / 2.0 - r / 2.0).powi(2))
        + 4.0 * quarter;
    (area, inertia)
}

#[test]
fn rounded_rectangle_matches_the_closed_forms() {
    for &(w, h, r) in
        &[(2.0, 1.0, 0.1), (2.0, 1.0, 0.45), (1.0, 1.0, 0.25), (4.0, 0.5, 0.2), (30.0, 12.0, 5.0)]
    {
        let p = PolygonPath::rounded_rectangle(s(w), s(h), s(r)).expect("valid");
        let (area, inertia) = rounded_rectangle_closed_form(w, h, r);
        let what = format!("{w} x {h} r {r}");
        assert_close(f(p.area()), area, 2.0 * ULP, &format!("{what}: area"));
        assert_close(f(p.unit_inertia()), inertia, 4.0 * ULP + inertia * 1e-12, &format!("{what}: inertia"));
        assert_eq!(p.centroid(), Vector2::ZERO, "{what}: centroid");
        assert_eq!(p.rounding(), s(r));
        // The core is the rectangle inset by r, exactly.
        let (cx, cy) = (w / 2.0 - r, h / 2.0 - r);
        assert_eq!(p.vertices(), &[v(-cx, -cy), v(cx, -cy), v(cx, cy), v(-cx, cy)][..], "{what}: core");
        assert_close(f(p.radius()), (cx * cx + cy * cy).sqrt() + r, ULP, &format!("{what}: radius"));
        assert!(f(p.radius()) >= (cx * cx + cy * cy).sqrt() + r);
        assert_close(f(p.core_extent()), w.min(h) / 2.0, 1e-9, &format!("{what}: core extent"));
    }
}

#[test]
fn zero_rounding_is_the_sharp_polygon_bit_for_bit() {
    let sets: [&[Vector2]; 3] = [
        &[v(0.0, 0.0), v(4.0, 0.0), v(1.0, 3.0)],
        &[v(-1.0, -0.5), v(1.0, -0.5), v(1.0, 0.5), v(-1.0, 0.5), v(0.0, 0.0)],
        &[v(0.3, 0.1), v(2.7, -0.4), v(3.1, 2.2), v(1.0, 3.3), v(-0.8, 1.9), v(-0.2, 0.4)],
    ];
    for pts in sets {
        assert_eq!(PolygonPath::rounded(pts, Scalar::ZERO), PolygonPath::new(pts));
    }
    assert_eq!(
        PolygonPath::rounded_rectangle(s(2.0), s(1.0), Scalar::ZERO),
        PolygonPath::rectangle(s(2.0), s(1.0))
    );
}

/// Distance from `p` to the segment `a`–`b`.
fn dist_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (ex, ey) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * ex + (p.1 - a.1) * ey) / (ex * ex + ey * ey)).clamp(0.0, 1.0);
    ((p.0 - a.0 - t * ex).powi(2) + (p.1 - a.1 - t * ey).powi(2)).sqrt()
}

#[test]
fn rounded_triangle_mass_properties_match_a_numerical_integration() {
    // No edge along a grid line or a diagonal (those would alias the grid).
    let tri = [(0.13, 0.21), (4.07, 0.52), (1.31, 3.17)];
    let r = 0.3;
    let pts: Vec<Vector2> = tri.iter().map(|&(x, y)| v(x, y)).collect();
    let p = PolygonPath::rounded(&pts, s(r)).expect("valid");

    // The core, independently: the triangle shrunk about its incentre by
    // (ρ − r) / ρ, ρ the inradius.
    let side = |i: usize, j: usize| ((tri[i].0 - tri[j].0).powi(2) + (tri[i].1 - tri[j].1).powi(2)).sqrt();
    let (la, lb, lc) = (side(1, 2), side(2, 0), side(0, 1));
    let per = la + lb + lc;
    let inc = (
        (la * tri[0].0 + lb * tri[1].0 + lc * tri[2].0) / per,
        (la * tri[0].1 + lb * tri[1].1 + lc * tri[2].1) / per,
    );
    let area_tri =
        ((tri[1].0 - tri[0].0) * (tri[2].1 - tri[0].1) - (tri[1].1 - tri[0].1) * (tri[2].0 - tri[0].0)) / 2.0;
    let rho = 2.0 * area_tri / per;
    let k = (rho - r) / rho;
    let core: Vec<(f64, f64)> =
        tri.iter().map(|&(x, y)| (inc.0 + k * (x - inc.0), inc.1 + k * (y - inc.1))).collect();
    let c0 = p.centroid().to_f64();
    for (got, want) in p.vertices().iter().zip(&core) {
        let g = got.to_f64();
        assert_close(g.0 + c0.0, want.0, 1e-9, "core x");
        assert_close(g.1 + c0.1, want.1, 1e-9, "core y");
    }

    // Area in closed form: A_core + P_core r + π r².
    let area = k * k * area_tri + k * per * r + PI * r * r;
    assert_close(f(p.area()), area, 2.0 * ULP, "area");

    // Centroid and inertia: midpoint rule on a fine grid over the hull's box,
    // each cell the boundary crosses subdivided 16 × 16.
    let inside = |q: (f64, f64)| {
        let cross = |a: (f64, f64), b: (f64, f64)| (b.0 - a.0) * (q.1 - a.1) - (b.1 - a.1) * (q.0 - a.0);
        let in_core = (0..3).all(|e| cross(core[e], core[(e + 1) % 3]) >= 0.0);
        // Signed distance to the rounded shape (exact within r of it).
        let d = (0..3).map(|e| dist_to_segment(q, core[e], core[(e + 1) % 3])).fold(f64::MAX, f64::min);
        if in_core {
            -d - r
        } else {
            d - r
        }
    };
    let n = 1_000;
    let (x0, x1, y0, y1) = (0.0, 4.2, 0.0, 3.3);
    let (hx, hy) = ((x1 - x0) / n as f64, (y1 - y0) / n as f64);
    let (mut a, mut sx, mut sy, mut ixx) = (0.0, 0.0, 0.0, 0.0);
    // A cell's own second moment about its centre, (hx² + hy²)/12 per unit
    // area, is added with it (exact for the midpoint rule on x² + y²).
    let mut add = |x: f64, y: f64, w: f64, h2: f64| {
        a += w;
        sx += w * x;
        sy += w * y;
        ixx += w * (x * x + y * y + h2 / 12.0);
    };
    for i in 0..n {
        let x = x0 + (i as f64 + 0.5) * hx;
        for j in 0..n {
            let y = y0 + (j as f64 + 0.5) * hy;
            let sd = inside((x, y));
            if sd < -hx {
                add(x, y, 1.0, hx * hx + hy * hy);
            } else if sd <= hx {
                let k = 16;
                for u in 0..k {
                    for w in 0..k {
                        let xs = x - hx / 2.0 + (u as f64 + 0.5) * hx / k as f64;
                        let ys = y - hy / 2.0 + (w as f64 + 0.5) * hy / k as f64;
                        if inside((xs, ys)) <= 0.0 {
                            add(xs, ys, 1.0 / (k * k) as f64, (hx * hx + hy * hy) / (k * k) as f64);
                        }
                    }
                }
            }
        }
    }
    let cell = hx * hy;
    let (gx, gy) = (sx / a, sy / a);
    let inertia = ixx * cell - a * cell * (gx * gx + gy * gy);
    assert_close(a * cell, area, 2e-5, "grid area (checks the grid itself)");
    assert_close(c0.0, gx, 5e-6, "centroid x");
    assert_close(c0.1, gy, 5e-6, "centroid y");
    assert_close(f(p.unit_inertia()), inertia, inertia * 1e-6, "inertia");

    // Tighter: the outline as a polygon with 200,000 chords per corner arc, and
    // its exact polygon moments in f64 (the chords lose ~5e-12 m² of the area).
    let mut outline = Vec::new();
    for i in 0..3 {
        let (a, b, c) = (core[(i + 2) % 3], core[i], core[(i + 1) % 3]);
        let t0 = (-(b.0 - a.0)).atan2(b.1 - a.1); // outward normal of a → b
        let mut t1 = (-(c.0 - b.0)).atan2(c.1 - b.1);
        if t1 < t0 {
            t1 += 2.0 * PI;
        }
        for j in 0..=200_000 {
            let t = t0 + (t1 - t0) * j as f64 / 200_000.0;
            outline.push((b.0 + r * t.cos(), b.1 + r * t.sin()));
        }
    }
    let (mut pa, mut psx, mut psy, mut pi) = (0.0, 0.0, 0.0, 0.0);
    for (i, &(x0, y0)) in outline.iter().enumerate() {
        let (x1, y1) = outline[(i + 1) % outline.len()];
        let d = x0 * y1 - x1 * y0;
        pa += d / 2.0;
        psx += d * (x0 + x1) / 6.0;
        psy += d * (y0 + y1) / 6.0;
        pi += d * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
    }
    let (gx, gy) = (psx / pa, psy / pa);
    assert_close(pa, area, 1e-9, "outline area (checks the outline itself)");
    assert_close(c0.0, gx, 2.0 * ULP, "centroid x against the outline");
    assert_close(c0.1, gy, 2.0 * ULP, "centroid y against the outline");
    assert_close(
        f(p.unit_inertia()),
        pi - pa * (gx * gx + gy * gy),
        4.0 * ULP,
        "inertia against the outline",
    );

    // Not the sharp triangle's centroid: the rounding moves it.
    let sharp = ((tri[0].0 + tri[1].0 + tri[2].0) / 3.0, (tri[0].1 + tri[1].1 + tri[2].1) / 3.0);
    assert!((c0.0 - sharp.0).abs() > 1e-3 || (c0.1 - sharp.1).abs() > 1e-3);
}

#[test]
fn rounded_polygon_errors() {
    let tri = [v(0.0, 0.0), v(4.0, 0.0), v(1.0, 3.0)];
    assert_eq!(PolygonPath::rounded(&tri, s(-0.1)), Err(out_of_range("rounding radius")));
    // Inradius 12 / (4 + √10 + √18) ≈ 1.052: the core vanishes at it.
    assert!(PolygonPath::rounded(&tri, s(1.0)).is_ok());
    assert_eq!(PolygonPath::rounded(&tri, s(1.06)), Err(out_of_range("rounding radius")));
    assert_eq!(PolygonPath::rounded(&tri, s(5.0)), Err(out_of_range("rounding radius")));
    // A 2 × 1 box: the core is a segment at r = 0.5 and reversed beyond it.
    assert!(PolygonPath::rounded_rectangle(s(2.0), s(1.0), s(0.499)).is_ok());
    for r in [0.5, 0.6, 3.0] {
        assert_eq!(
            PolygonPath::rounded_rectangle(s(2.0), s(1.0), s(r)),
            Err(out_of_range("rounding radius")),
            "r = {r}"
        );
    }
    assert_eq!(PolygonPath::rounded_rectangle(s(0.0), s(1.0), s(0.1)), Err(out_of_range("rectangle side")));
    // The hull's own errors come first.
    assert_eq!(PolygonPath::rounded(&[v(0.0, 0.0), v(1.0, 0.0)], s(0.1)), Err(Error::DegeneratePolygon));
}

// ---------------------------------------------------------------- ray casts

#[test]
fn ray_against_capsule() {
    // Core from (-1, 0) to (1, 0), r = 0.5, placed at (10, 5) turned by 90°: the
    // core runs from (10, 4) to (10, 6).
    let c = Capsule::new(v(-1.0, 0.0), v(1.0, 0.0), s(0.5)).unwrap();
    let t = xf(10.0, 5.0, PI / 2.0);
    let (x, y) = (v(1.0, 0.0), v(0.0, 1.0));
    // Side: from (7, 5.5) along +x hits x = 9.5.
    assert_hit(ray_capsule(v(7.0, 5.5), x, s(10.0), &c, t), 2.5, (-1.0, 0.0), "side");
    // Cap end, straight along the axis: from (10, 0) up hits y = 3.5.
    assert_hit(ray_capsule(v(10.0, 0.0), y, s(10.0), &c, t), 3.5, (0.0, -1.0), "cap along axis");
    // Cap end, off axis: x = 10.3 meets the lower circle at y = 4 − √(0.25 − 0.09) = 3.6.
    let (d, n) = hit(ray_capsule(v(10.3, 0.0), y, s(10.0), &c, t), "cap off axis");
    assert_close(d, 3.6, 1e-7, "cap off axis distance");
    assert_close(n.0, 0.6, 1e-7, "cap normal x");
    assert_close(n.1, -0.8, 1e-7, "cap normal y");
    // From inside: no hit; too short, and a miss.
    assert!(ray_capsule(v(10.2, 5.0), x, s(10.0), &c, t).is_none(), "inside");
    assert!(ray_capsule(v(7.0, 5.5), x, s(2.4), &c, t).is_none(), "short");
    assert!(ray_capsule(v(7.0, 6.6), x, s(10.0), &c, t).is_none(), "passes above");
    // Parallel to the side, just outside it: misses.
    assert!(ray_capsule(v(10.6, 0.0), y, s(10.0), &c, t).is_none(), "parallel outside");
    assert!(capsule_contains(&c, t, v(10.4, 6.2)) && !capsule_contains(&c, t, v(10.4, 6.4)));
    // A zero-length capsule is a circle.
    let dot = Capsule::new(v(0.0, 0.0), v(0.0, 0.0), s(1.0)).unwrap();
    assert_hit(ray_capsule(v(-5.0, 0.0), x, s(10.0), &dot, Transform::IDENTITY), 4.0, (-1.0, 0.0), "circle");
}

#[test]
fn ray_against_segment() {
    // From (1, 1) to (3, 1) in the body, which sits at (0, 2): the world segment
    // runs from (1, 3) to (3, 3).
    let seg = Segment::new(v(1.0, 1.0), v(3.0, 1.0)).unwrap();
    let t = Transform::new(v(0.0, 2.0), Rot::IDENTITY);
    let (up, down) = (v(0.0, 1.0), v(0.0, -1.0));
    assert_hit(ray_segment(v(2.0, 0.0), up, s(10.0), &seg, t), 3.0, (0.0, -1.0), "from below");
    assert_hit(ray_segment(v(2.0, 7.0), down, s(10.0), &seg, t), 4.0, (0.0, 1.0), "from above");
    // Slanted, through the end point (3, 3) exactly.
    let diag = v(0.6, 0.8);
    assert_hit(ray_segment(v(1.5, 1.0), diag, s(10.0), &seg, t), 2.5, (0.0, -1.0), "through the end");
    // Along the segment's own line (end on): no thickness, no hit.
    assert!(ray_segment(v(-2.0, 3.0), v(1.0, 0.0), s(10.0), &seg, t).is_none(), "end on");
    assert!(ray_segment(v(3.5, 0.0), up, s(10.0), &seg, t).is_none(), "beside");
    assert!(ray_segment(v(2.0, 0.0), up, s(2.9), &seg, t).is_none(), "short");
    assert!(ray_segment(v(2.0, 0.0), down, s(10.0), &seg, t).is_none(), "away");
    // Rotated body: the segment from (0, 0) to (2, 0) turned by 90° at the origin
    // runs up the y axis; a ray from (-4, 1) along +x hits it at 4 with normal -x.
    let seg = Segment::new(v(0.0, 0.0), v(2.0, 0.0)).unwrap();
    assert_hit(
        ray_segment(v(-4.0, 1.0), v(1.0, 0.0), s(10.0), &seg, xf(0.0, 0.0, PI / 2.0)),
        4.0,
        (-1.0, 0.0),
        "rot",
    );
}

#[test]
fn ray_against_rounded_box() {
    // 2 × 2 box, corners rounded by 0.5: core corners at (±0.5, ±0.5).
    let p = PolygonPath::rounded_rectangle(s(2.0), s(2.0), s(0.5)).unwrap();
    let id = Transform::IDENTITY;
    // A face: from (5, 0.2) along -x meets x = 1.
    assert_hit(ray_polygon(v(5.0, 0.2), v(-1.0, 0.0), s(10.0), &p, id), 4.0, (1.0, 0.0), "face");
    // The corner arc, on the diagonal: at (0.5, 0.5) + 0.5 (1, 1)/√2.
    let h = 0.5_f64.sqrt();
    let dir = v(-h, -h);
    let want = (3.0 - 0.5) * 2f64.sqrt() - 0.5;
    assert_hit(ray_polygon(v(3.0, 3.0), dir, s(10.0), &p, id), want, (h, h), "corner diagonal");
    // Where the sharp box would be hit at 4, the arc is hit later: at y = 0.95,
    // x = 0.5 + √(0.25 − 0.45²).
    let x = 0.5 + (0.25f64 - 0.45 * 0.45).sqrt();
    let (d, n) = hit(ray_polygon(v(5.0, 0.95), v(-1.0, 0.0), s(10.0), &p, id), "corner arc");
    assert_close(d, 5.0 - x, 1e-7, "corner arc distance");
    assert_close(n.0, (x - 0.5) / 0.5, 1e-6, "arc normal x");
    assert_close(n.1, 0.9, 1e-6, "arc normal y");
    // It misses the rounded corner where the sharp box would be hit.
    assert!(ray_polygon(v(5.0, 0.99), v(-1.0, -0.02), s(4.2), &p, id).is_none(), "misses the cut corner");
    // Placed: moved to (10, 0) and turned by 90° (a square stays a square).
    let t = xf(10.0, 0.0, PI / 2.0);
    assert_hit(ray_polygon(v(10.2, 5.0), v(0.0, -1.0), s(10.0), &p, t), 4.0, (0.0, 1.0), "placed face");
    // Inside: no hit; contains follows the arcs.
    assert!(ray_polygon(v(0.9, 0.0), v(1.0, 0.0), s(10.0), &p, id).is_none(), "inside");
    assert!(polygon_contains(&p, id, v(0.8, 0.8)));
    assert!(!polygon_contains(&p, id, v(0.9, 0.9)), "the cut-off corner is outside");
    assert!(polygon_contains(&p, id, v(1.0, 0.0)) && !polygon_contains(&p, id, v(1.01, 0.0)));
}

/// A small deterministic generator (xorshift).
fn next(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// Area, centroid and polar inertia about the centroid of the points within `r`
/// of the convex polygon `core` (counter-clockwise), from its outline as a
/// polygon with `chords` chords per corner arc, in f64.
fn outline_moments(core: &[(f64, f64)], r: f64, chords: usize) -> (f64, (f64, f64), f64) {
    let n = core.len();
    let mut outline = Vec::new();
    for i in 0..n {
        let (a, b, c) = (core[(i + n - 1) % n], core[i], core[(i + 1) % n]);
        let t0 = (-(b.0 - a.0)).atan2(b.1 - a.1);
        let mut t1 = (-(c.0 - b.0)).atan2(c.1 - b.1);
        if t1 < t0 {
            t1 += 2.0 * PI;
        }
        for j in 0..=chords {
            let t = t0 + (t1 - t0) * j as f64 / chords as f64;
            outline.push((b.0 + r * t.cos(), b.1 + r * t.sin()));
        }
    }
    let (mut pa, mut psx, mut psy, mut pi) = (0.0, 0.0, 0.0, 0.0);
    for (i, &(x0, y0)) in outline.iter().enumerate() {
        let (x1, y1) = outline[(i + 1) % outline.len()];
        let d = x0 * y1 - x1 * y0;
        pa += d / 2.0;
        psx += d * (x0 + x1) / 6.0;
        psy += d * (y0 + y1) / 6.0;
        pi += d * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
    }
    let g = (psx / pa, psy / pa);
    (pa, g, pi - pa * (g.0 * g.0 + g.1 * g.1))
}

#[test]
fn random_rounded_polygons_match_their_outlines() {
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut checked = 0;
    for case in 0..120 {
        let scale = [0.5, 3.0, 20.0][case % 3];
        let mut unit = || (next(&mut seed) >> 11) as f64 / (1u64 << 53) as f64;
        let count = 3 + case % 6;
        let pts: Vec<Vector2> =
            (0..count).map(|_| v(scale * (unit() - 0.5) + 7.0, scale * (unit() - 0.5) - 3.0)).collect();
        let r = scale * 0.2 * unit();
        let Ok(hull) = PolygonPath::new(&pts) else { continue };
        match PolygonPath::rounded(&pts, s(r)) {
            Err(e) => assert_eq!(e, out_of_range("rounding radius"), "case {case}"),
            Ok(p) => {
                checked += 1;
                let c = p.centroid().to_f64();
                // Core in the input coordinates, and its outline's moments.
                let core: Vec<(f64, f64)> =
                    p.vertices().iter().map(|q| (f(q.x) + c.0, f(q.y) + c.1)).collect();
                let (area, g, inertia) = outline_moments(&core, f(p.rounding()), 20_000);
                let what = format!("case {case} scale {scale} r {r}");
                let size = scale * scale;
                assert_close(f(p.area()), area, 1e-9 * size + 2.0 * ULP, &format!("{what}: area"));
                assert_close(c.0, g.0, 1e-9 * scale + 2.0 * ULP, &format!("{what}: centroid x"));
                assert_close(c.1, g.1, 1e-9 * scale + 2.0 * ULP, &format!("{what}: centroid y"));
                assert_close(
                    f(p.unit_inertia()),
                    inertia,
                    1e-9 * size * size + 8.0 * ULP,
                    &format!("{what}: inertia"),
                );
                // Inside the hull, and the faces where the hull's are: both ends
                // of each core edge lie r inside the hull's face line.
                assert!(p.area() <= hull.area(), "{what}: rounded area exceeds the hull's");
                assert_eq!(p.normals().len(), hull.normals().len(), "{what}: faces");
                let hc = hull.centroid().to_f64();
                let n = core.len();
                let hv: Vec<(f64, f64)> =
                    hull.vertices().iter().map(|q| (f(q.x) + hc.0, f(q.y) + hc.1)).collect();
                for i in 0..n {
                    let (a, b) = (hv[i], hv[(i + 1) % n]);
                    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
                    let hn = ((b.1 - a.1) / len, (a.0 - b.0) / len);
                    for q in [core[i], core[(i + 1) % n]] {
                        let depth = hn.0 * (a.0 - q.0) + hn.1 * (a.1 - q.1);
                        assert_close(depth, f(p.rounding()), 1e-9, &format!("{what}: face {i}"));
                    }
                }
            }
        }
    }
    assert!(checked > 60, "only {checked} cases were valid");
}

#[test]
fn extreme_inputs_never_panic() {
    let mut seed = 0x1234_5678_9ABC_DEF1u64;
    for case in 0..3_000 {
        let mut raw = |bits: u32| Scalar::from_bits((next(&mut seed) as i64) >> (64 - bits));
        let b = [30, 36, 40, 41, 44, 64][case % 6];
        let pts = [
            Vector2::new(raw(b), raw(b)),
            Vector2::new(raw(b), raw(b)),
            Vector2::new(raw(b), raw(b)),
            Vector2::new(raw(b), raw(b)),
        ];
        let r = raw([8, 20, 33, 38, 40, 64][case % 6]).abs();
        let _ = PolygonPath::rounded(&pts, r);
        let _ = PolygonPath::rounded_rectangle(raw(b), raw(b), r);
        if let Ok(c) = Capsule::new(pts[0], pts[1], r) {
            let _ = (c.area(), c.unit_inertia(), c.length(), c.bounding_radius(), c.centroid());
            let t = Transform::new(pts[2], Rot::from_angle(raw(34)));
            let _ = c.aabb(t);
            let _ = ray_capsule(pts[3], v(0.6, 0.8), raw(b).abs(), &c, t);
            let _ = capsule_contains(&c, t, pts[3]);
        }
        if let Ok(sg) = Segment::new(pts[0], pts[1]) {
            let _ = (sg.length(), sg.rod_unit_inertia(), sg.bounding_radius(), sg.centroid());
            let t = Transform::new(pts[2], Rot::from_angle(raw(34)));
            let _ = ray_segment(pts[3], v(0.6, -0.8), raw(b).abs(), &sg, t);
        }
        if let Ok(p) = PolygonPath::rounded(&pts, r) {
            let t = Transform::new(pts[2], Rot::from_angle(raw(34)));
            let _ = ray_polygon(pts[3], v(-0.8, 0.6), raw(b).abs(), &p, t);
            let _ = polygon_contains(&p, t, pts[3]);
        }
    }
}
