//! Geometry: convex hull, polygon and circle mass properties, `MassData`.
//!
//! Hand-computed cases first, then property tests against an independent reference
//! (Andrew's monotone chain in exact integers, mass properties in `f64`).

use arphysics::geometry::*;
use arphysics::math::scalar::{self, Scalar};
use arphysics::math::Vector2;
use arphysics::Error;
use proptest::prelude::*;

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

fn raw(p: Vector2) -> (i128, i128) {
    (i128::from(p.x.to_bits()), i128::from(p.y.to_bits()))
}

fn cross3(o: (i128, i128), a: (i128, i128), b: (i128, i128)) -> i128 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got}, want {want} (tolerance {tol})");
}

/// Strict convex hull by Andrew's monotone chain on raw bits, counter-clockwise,
/// starting at the lowest (then leftmost) point, the order `PolygonPath` uses.
fn reference_hull(points: &[Vector2]) -> Vec<(i128, i128)> {
    let mut p: Vec<(i128, i128)> = points.iter().map(|&q| raw(q)).collect();
    p.sort_unstable();
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<(i128, i128)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(i128, i128)>> =
            if pass == 0 { Box::new(p.iter()) } else { Box::new(p.iter().rev()) };
        for &q in iter {
            while hull.len() >= start + 2 && cross3(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0 {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    let lowest = (0..hull.len()).min_by_key(|&i| (hull[i].1, hull[i].0)).unwrap_or(0);
    hull.rotate_left(lowest);
    hull
}

/// Area, centroid and polar inertia about the centroid of a CCW polygon, in f64.
fn float_mass(vs: &[(f64, f64)]) -> (f64, (f64, f64), f64) {
    let n = vs.len();
    let (mut a2, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (p, q) = (vs[i], vs[(i + 1) % n]);
        let d = p.0 * q.1 - p.1 * q.0;
        a2 += d;
        cx += d * (p.0 + q.0);
        cy += d * (p.1 + q.1);
    }
    let c = (cx / (3.0 * a2), cy / (3.0 * a2));
    let mut i_c = 0.0;
    for i in 0..n {
        let p = (vs[i].0 - c.0, vs[i].1 - c.1);
        let q = (vs[(i + 1) % n].0 - c.0, vs[(i + 1) % n].1 - c.1);
        let d = p.0 * q.1 - p.1 * q.0;
        i_c += d * (p.0 * p.0 + p.0 * q.0 + q.0 * q.0 + p.1 * p.1 + p.1 * q.1 + q.1 * q.1);
    }
    (a2 / 2.0, c, i_c / 12.0)
}

/// Every invariant a successfully built polygon must satisfy for these inputs.
fn check_polygon(poly: &PolygonPath, points: &[Vector2]) {
    let vs = poly.vertices();
    let ns = poly.normals();
    let n = vs.len();
    assert!((3..=MAX_POLYGON_VERTICES).contains(&n));
    assert_eq!(ns.len(), n);
    let c = raw(poly.centroid());
    let rv: Vec<(i128, i128)> = vs.iter().map(|&p| raw(p)).collect();

    // The hull is exactly the reference hull, shifted by the centroid.
    let shifted: Vec<(i128, i128)> = rv.iter().map(|p| (p.0 + c.0, p.1 + c.1)).collect();
    assert_eq!(shifted, reference_hull(points), "hull differs from reference");

    for i in 0..n {
        let (a, b, d) = (rv[i], rv[(i + 1) % n], rv[(i + 2) % n]);
        // Strictly convex and counter-clockwise.
        assert!(cross3(a, b, d) > 0, "turn at vertex {} is not strictly left", i + 1);
        // Contains every input point (exactly: the shift is exact).
        for &p in points {
            let q = (raw(p).0 - c.0, raw(p).1 - c.1);
            assert!(cross3(a, b, q) >= 0, "input point outside edge {i}");
        }
        // Unit normals, perpendicular to their edge, pointing outward.
        let (nx, ny) = (f(ns[i].x), f(ns[i].y));
        let (ex, ey) = (f(vs[(i + 1) % n].x) - f(vs[i].x), f(vs[(i + 1) % n].y) - f(vs[i].y));
        let len = ex.hypot(ey);
        assert_close(nx.hypot(ny), 1.0, 1e-8, "normal length");
        assert_close((nx * ex + ny * ey) / len, 0.0, 1e-8, "normal · edge");
        assert!(nx * ey - ny * ex > 0.0, "normal points inward");
    }

    // Mass properties against f64.
    let fv: Vec<(f64, f64)> = vs.iter().map(|p| (f(p.x), f(p.y))).collect();
    let (area, fc, inertia) = float_mass(&fv);
    assert!(poly.area() > Scalar::ZERO);
    assert_close(f(poly.area()), area, 2.4e-10 + area * 1e-12, "area (shoelace)");
    let scale = fv.iter().fold(1.0f64, |m, p| m.max(p.0.abs()).max(p.1.abs()));
    assert_close(fc.0, 0.0, 1e-12 * scale + 2.4e-10, "recentred centroid x");
    assert_close(fc.1, 0.0, 1e-12 * scale + 2.4e-10, "recentred centroid y");
    assert_close(f(poly.unit_inertia()), inertia, 5e-10 + inertia * 1e-11, "unit inertia");

    // Bounding radius: bounds every vertex, by no more than a rounding step.
    let far = fv.iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max);
    assert!(f(poly.radius()) >= far - 1e-12, "radius does not bound the vertices");
    assert_close(f(poly.radius()), far, 5e-10, "radius");
    assert!(poly.radius() <= MAX_POLYGON_RADIUS);

    // Mass properties are positive wherever they are in range.
    if let Ok(m) = MassData::from_density(scalar::ONE, poly.area(), poly.unit_inertia()) {
        assert!(m.mass > Scalar::ZERO && m.inertia > Scalar::ZERO);
        assert!(m.inv_mass > Scalar::ZERO && m.inv_inertia > Scalar::ZERO);
        assert_eq!(m.mass, poly.area());
        assert_eq!(m.inertia, poly.unit_inertia());
    }
}

/// What `PolygonPath::new` must return for `points`, from the reference hull
/// (`None` when it must succeed, or when only the size limit is in question).
fn expected_error(points: &[Vector2], hull: &[(i128, i128)]) -> Option<Error> {
    if hull.len() < 3 {
        return Some(Error::DegeneratePolygon);
    }
    if hull.len() > MAX_POLYGON_VERTICES {
        return Some(Error::TooManyVertices { count: hull.len(), max: MAX_POLYGON_VERTICES });
    }
    let n = hull.len();
    let area2: i128 = (0..n).map(|i| hull[i].0 * hull[(i + 1) % n].1 - hull[i].1 * hull[(i + 1) % n].0).sum();
    let xs = points.iter().map(|p| i128::from(p.x.to_bits()));
    let ys = points.iter().map(|p| i128::from(p.y.to_bits()));
    let side =
        (xs.clone().max().unwrap() - xs.min().unwrap()).max(ys.clone().max().unwrap() - ys.min().unwrap());
    let min_area2 = i128::from(MIN_POLYGON_AREA.to_bits()) << 33;
    let min_thin2 = 2 * i128::from(MIN_POLYGON_THICKNESS.to_bits()) * side;
    if area2 < min_area2 || area2 < min_thin2 {
        return Some(Error::DegeneratePolygon);
    }
    None
}

fn check_any(points: &[Vector2]) {
    let hull = reference_hull(points);
    let result = PolygonPath::new(points);
    match (expected_error(points, &hull), result) {
        (Some(e), r) => assert_eq!(r, Err(e)),
        (None, Ok(poly)) => {
            check_polygon(&poly, points);
            // Order and repetition of the points change nothing.
            let mut shuffled: Vec<Vector2> = points.iter().rev().copied().collect();
            shuffled.extend_from_slice(points);
            shuffled.rotate_left(points.len() / 3);
            assert_eq!(PolygonPath::new(&shuffled), Ok(poly));
        }
        (None, Err(e)) => {
            // Only the size limit may remain: some vertex is over 128 m from the
            // centroid.
            assert_eq!(e, Error::OutOfRange { what: "polygon size" });
            // Relative to the first vertex, subtracted exactly: absolute raw
            // coordinates reach 2^62, past f64's 2^53 exact integers.
            let (ox, oy) = hull[0];
            let fv: Vec<(f64, f64)> = hull.iter().map(|p| ((p.0 - ox) as f64, (p.1 - oy) as f64)).collect();
            let (_, c, _) = float_mass(&fv);
            let far = fv.iter().map(|p| (p.0 - c.0).hypot(p.1 - c.1) / 2f64.powi(32)).fold(0.0, f64::max);
            assert!(far > 128.0 - 1e-6, "rejected as too large at {far} m");
        }
    }
}

// ---------------------------------------------------------------- polygons

#[test]
fn unit_square_from_messy_points() {
    // Corners in random order, duplicated, with collinear edge midpoints and an
    // interior point.
    let points = [
        v(0.5, 0.0),
        v(1.0, 1.0),
        v(0.0, 0.5),
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(0.5, 0.5),
        v(1.0, 0.0),
        v(0.5, 1.0),
        v(0.0, 1.0),
        v(1.0, 0.5),
        v(0.0, 0.0),
        v(0.25, 0.0),
    ];
    let poly = PolygonPath::new(&points).unwrap();
    assert_eq!(poly.vertices(), &[v(-0.5, -0.5), v(0.5, -0.5), v(0.5, 0.5), v(-0.5, 0.5)]);
    assert_eq!(poly.normals(), &[-Vector2::Y, Vector2::X, Vector2::Y, -Vector2::X]);
    assert_eq!(poly.area(), scalar::ONE);
    assert_eq!(poly.centroid(), v(0.5, 0.5));
    // 1/6 rounded to nearest.
    assert_eq!(poly.unit_inertia(), Scalar::from_bits((1i64 << 32) / 6 + 1));
    assert_close(f(poly.unit_inertia()), 1.0 / 6.0, 1.2e-10, "inertia");
    assert_close(f(poly.radius()), 0.5f64.sqrt(), 2.4e-10, "radius");
    check_polygon(&poly, &points);
}

#[test]
fn right_triangle_matches_closed_form() {
    let points = [v(0.0, 4.0), v(3.0, 0.0), v(0.0, 0.0)];
    let poly = PolygonPath::new(&points).unwrap();
    assert_eq!(poly.area(), scalar::from_int(6));
    assert_close(f(poly.centroid().x), 1.0, 1.2e-10, "centroid x");
    assert_close(f(poly.centroid().y), 4.0 / 3.0, 1.2e-10, "centroid y");
    // Polar moment about the centroid: A (a² + b² + c²) / 36 = 6 · 50 / 36.
    assert_close(f(poly.unit_inertia()), 50.0 / 6.0, 1.2e-10, "inertia");
    assert_eq!(poly.vertices().len(), 3);
    check_polygon(&poly, &points);
}

#[test]
fn off_origin_box_reports_centroid_and_recentres() {
    let points = [v(12.0, 8.0), v(10.0, 5.0), v(12.0, 5.0), v(10.0, 8.0)];
    let poly = PolygonPath::new(&points).unwrap();
    assert_eq!(poly.centroid(), v(11.0, 6.5));
    assert_eq!(poly.vertices(), &[v(-1.0, -1.5), v(1.0, -1.5), v(1.0, 1.5), v(-1.0, 1.5)]);
    assert_eq!(poly.area(), scalar::from_int(6));
    // m (w² + h²) / 12 = 6 · 13 / 12 = 6.5, exactly.
    assert_eq!(poly.unit_inertia(), s(6.5));
    // Same shape anywhere in the Scalar range, bit for bit.
    let far: Vec<Vector2> = points.iter().map(|&p| p + v(2.0e9, -2.0e9)).collect();
    let moved = PolygonPath::new(&far).unwrap();
    assert_eq!(moved.vertices(), poly.vertices());
    assert_eq!(moved.unit_inertia(), poly.unit_inertia());
    assert_eq!(moved.centroid(), v(2.0e9 + 11.0, -2.0e9 + 6.5));
}

#[test]
fn rectangle_agrees_with_new() {
    let (w, h) = (s(2.0), s(3.0));
    let rect = PolygonPath::rectangle(w, h).unwrap();
    let corners = [v(1.0, 1.5), v(-1.0, -1.5), v(-1.0, 1.5), v(1.0, -1.5)];
    assert_eq!(rect, PolygonPath::new(&corners).unwrap());
    assert_eq!(rect.centroid(), Vector2::ZERO);
    assert_eq!(rect.unit_inertia(), s(6.5));

    let at = PolygonPath::rectangle_at(w, h, v(11.0, 6.5)).unwrap();
    assert_eq!(at.centroid(), v(11.0, 6.5));
    assert_eq!(at.vertices(), rect.vertices());
    assert_eq!(at.normals(), rect.normals());
    assert_eq!(
        (at.area(), at.unit_inertia(), at.radius()),
        (rect.area(), rect.unit_inertia(), rect.radius())
    );

    // An odd-bit side loses its last bit so the box stays centred.
    let odd = PolygonPath::rectangle(Scalar::from_bits((1 << 32) + 1), s(1.0)).unwrap();
    assert_eq!(odd.vertices()[1], v(0.5, -0.5));
}

#[test]
fn rectangle_errors() {
    let side = Err(Error::OutOfRange { what: "rectangle side" });
    assert_eq!(PolygonPath::rectangle(s(0.0), s(1.0)), side);
    assert_eq!(PolygonPath::rectangle(s(1.0), s(-1.0)), side);
    assert_eq!(PolygonPath::rectangle(s(300.0), s(1.0)), Err(Error::OutOfRange { what: "polygon size" }));
    assert_eq!(
        PolygonPath::rectangle(Scalar::MAX, Scalar::MAX),
        Err(Error::OutOfRange { what: "polygon size" })
    );
    assert_eq!(
        PolygonPath::rectangle_at(s(2.0), s(2.0), Vector2::new(Scalar::MAX, Scalar::ZERO)),
        Err(Error::OutOfRange { what: "rectangle center" })
    );
    // Too thin to be a polygon.
    assert_eq!(PolygonPath::rectangle(s(100.0), Scalar::from_bits(2)), Err(Error::DegeneratePolygon));
}

#[test]
fn degenerate_inputs_are_errors() {
    assert_eq!(PolygonPath::new(&[]), Err(Error::DegeneratePolygon));
    assert_eq!(PolygonPath::new(&[v(1.0, 1.0)]), Err(Error::DegeneratePolygon));
    assert_eq!(PolygonPath::new(&[v(1.0, 1.0), v(1.0, 1.0), v(1.0, 1.0)]), Err(Error::DegeneratePolygon));
    assert_eq!(PolygonPath::new(&[v(0.0, 0.0), v(1.0, 2.0)]), Err(Error::DegeneratePolygon));
    assert_eq!(PolygonPath::new(&[v(0.0, 0.0), v(2.0, 4.0), v(1.0, 2.0)]), Err(Error::DegeneratePolygon));
    // Collinear to the last bit, in any direction.
    let d = Scalar::from_bits(0x12_3456_789a);
    let line = [Vector2::new(d, -d), Vector2::ZERO, Vector2::new(-d, d), Vector2::new(d, -d)];
    assert_eq!(PolygonPath::new(&line), Err(Error::DegeneratePolygon));
    // Off the line by one step of 2^-32: a valid triangle in exact arithmetic, but
    // far too thin.
    let mut bent = line;
    bent[1] = Vector2::new(Scalar::from_bits(1), Scalar::ZERO);
    assert_eq!(PolygonPath::new(&bent), Err(Error::DegeneratePolygon));
    // Too small.
    assert_eq!(PolygonPath::new(&[v(0.0, 0.0), v(1e-4, 0.0), v(0.0, 1e-4)]), Err(Error::DegeneratePolygon));
}

#[test]
fn nine_gon_is_too_many_vertices() {
    let points: Vec<Vector2> = (0..9)
        .map(|k| {
            let a = core::f64::consts::TAU * f64::from(k) / 9.0;
            v(10.0 * a.cos(), 10.0 * a.sin())
        })
        .collect();
    assert_eq!(PolygonPath::new(&points), Err(Error::TooManyVertices { count: 9, max: 8 }));
    // With a duplicate and interior points the count is still that of the hull.
    let mut more = points.clone();
    more.extend([v(0.0, 0.0), points[3], v(1.0, 2.0)]);
    assert_eq!(PolygonPath::new(&more), Err(Error::TooManyVertices { count: 9, max: 8 }));
    // Eight of them are fine.
    let eight = PolygonPath::new(&points[..8]).unwrap();
    check_polygon(&eight, &points[..8]);
}

#[test]
fn size_limits() {
    let too_large = Err(Error::OutOfRange { what: "polygon size" });
    // Extreme coordinates: rejected before any product can overflow.
    let extreme = [
        Vector2::new(Scalar::MIN, Scalar::MIN),
        Vector2::new(Scalar::MAX, Scalar::MIN),
        Vector2::new(Scalar::MAX, Scalar::MAX),
    ];
    assert_eq!(PolygonPath::new(&extreme), too_large);
    // A 200 m square reaches 141 m from its centre: over the 128 m limit.
    assert_eq!(PolygonPath::rectangle(s(200.0), s(200.0)), too_large);
    // A 180 m square (127.3 m) is fine, and its inertia fits.
    let big = PolygonPath::rectangle(s(180.0), s(180.0)).unwrap();
    assert_close(f(big.unit_inertia()), 180.0f64.powi(4) / 6.0, 1e-6, "inertia of the largest square");
    // Nearly the whole 128 m disc: a regular octagon of radius 127.99 m.
    let oct: Vec<Vector2> = (0..8)
        .map(|k| {
            let a = core::f64::consts::TAU * f64::from(k) / 8.0 + 0.1;
            v(127.99 * a.cos(), 127.99 * a.sin())
        })
        .collect();
    let p = PolygonPath::new(&oct).unwrap();
    check_polygon(&p, &oct);
}

// ---------------------------------------------------------------- circles

#[test]
fn circle_values() {
    let pi = core::f64::consts::PI;
    let one = circle_area(scalar::ONE).unwrap();
    assert_close(f(one), pi, 1.2e-10, "area r = 1");
    assert_close(f(circle_unit_inertia(scalar::ONE).unwrap()), pi / 2.0, 1.2e-10, "inertia r = 1");
    let max_i = circle_unit_inertia(MAX_CIRCLE_RADIUS).unwrap();
    assert_close(f(max_i), pi * 128f64.powi(4) / 2.0, 1e-6, "inertia r = 128");
    assert_close(f(circle_area(MAX_CIRCLE_RADIUS).unwrap()), pi * 128.0 * 128.0, 1.2e-10, "area r = 128");
    let bad = Err(Error::OutOfRange { what: "circle radius" });
    for r in [Scalar::ZERO, s(-1.0), MAX_CIRCLE_RADIUS + Scalar::DELTA, Scalar::MAX] {
        assert_eq!(circle_area(r), bad);
        assert_eq!(circle_unit_inertia(r), bad);
    }
    // The smallest radius: valid, rounds to zero.
    assert_eq!(circle_area(Scalar::DELTA), Ok(Scalar::ZERO));
}

// ---------------------------------------------------------------- mass

#[test]
fn mass_data_from_density_and_mass() {
    let m = MassData::from_density(s(2.0), s(1.0), s(1.0 / 6.0)).unwrap();
    assert_eq!(m.mass, s(2.0));
    assert_eq!(m.inv_mass, s(0.5));
    assert_close(f(m.inertia), 1.0 / 3.0, 2.4e-10, "inertia");
    assert_close(f(m.inv_inertia), 3.0, 1e-8, "inv inertia");

    // The right triangle: 3 kg spread over 6 m² with unit inertia 50/6.
    let tri = PolygonPath::new(&[v(0.0, 0.0), v(3.0, 0.0), v(0.0, 4.0)]).unwrap();
    let m = MassData::from_mass(s(3.0), tri.area(), tri.unit_inertia()).unwrap();
    assert_eq!(m.mass, s(3.0));
    assert_close(f(m.inertia), 3.0 * 25.0 / 18.0, 2.4e-10, "triangle inertia");
    assert_eq!(
        MassData::from_density(s(0.5), tri.area(), tri.unit_inertia()),
        MassData::from_mass(s(3.0), tri.area(), tri.unit_inertia())
    );

    // A disc: I = m r² / 2.
    let r = s(0.25);
    let disc = MassData::from_mass(s(4.0), circle_area(r).unwrap(), circle_unit_inertia(r).unwrap()).unwrap();
    // Only to 1e-8: the unit inertia of a 25 cm disc is 0.006, kept to 2^-32.
    assert_close(f(disc.inertia), 4.0 * 0.0625 / 2.0, 5e-9, "disc inertia");

    assert_eq!(MassData::STATIC, MassData::default());
    assert!(MassData::STATIC.is_static());
    assert!(!m.is_static());
}

#[test]
fn mass_data_errors() {
    let e = |what| Err(Error::OutOfRange { what });
    let (a, i) = (s(1.0), s(1.0 / 6.0));
    assert_eq!(MassData::from_density(s(0.0), a, i), e("density"));
    assert_eq!(MassData::from_density(s(-1.0), a, i), e("density"));
    assert_eq!(MassData::from_density(s(1.0), s(0.0), i), e("area"));
    assert_eq!(MassData::from_density(s(1.0), a, s(0.0)), e("inertia"));
    assert_eq!(MassData::from_density(s(1.0), a, s(-1.0)), e("inertia"));
    // Overflowing and out-of-range products.
    assert_eq!(MassData::from_density(Scalar::MAX, Scalar::MAX, i), e("mass"));
    assert_eq!(MassData::from_density(s(200_000.0), a, i), e("mass"));
    assert_eq!(MassData::from_density(s(1e-4), a, i), e("mass"));
    assert_eq!(MassData::from_density(s(1.0), a, Scalar::MAX), e("inertia"));
    assert_eq!(MassData::from_density(s(1.0), a, s(2e6)), e("inertia"));
    assert_eq!(MassData::from_density(s(1.0), a, s(1e-7)), e("inertia"));
    assert_eq!(MassData::from_mass(s(0.0), a, i), e("mass"));
    assert_eq!(MassData::from_mass(s(-5.0), a, i), e("mass"));
    assert_eq!(MassData::from_mass(MAX_MASS + Scalar::DELTA, a, i), e("mass"));
    assert_eq!(MassData::from_mass(s(1.0), s(-1.0), i), e("area"));
    assert_eq!(MassData::from_mass(s(1.0), a, s(0.0)), e("inertia"));
    assert_eq!(MassData::from_mass(MAX_MASS, Scalar::DELTA, Scalar::MAX), e("inertia"));
    // The limits themselves are accepted.
    assert!(MassData::from_mass(MIN_MASS, a, a).is_ok());
    assert!(MassData::from_mass(MAX_MASS, a, s(10.0)).is_ok());
    assert!(MassData::from_mass(s(1.0), a, MIN_INERTIA).is_ok());
    assert!(MassData::from_mass(s(1.0), a, MAX_INERTIA).is_ok());
}

// ---------------------------------------------------------------- properties

/// Limit L2 of the lane solver (`docs/design/solver-lanes.md` §2.2): a convex
/// hull's bounding radius about its centroid r_b is at most √8 times its radius of
/// gyration ρ_g = √(unit_inertia / area), so r_b² ≤ 8 · unit_inertia / area. The
/// disc has √2, the square √3, and a thin triangle tends to √8 (its far vertex is
/// 2L/3 from the centroid, ρ_g² = L²/18). A fact of geometry, checked on the
/// engine's own numbers: `radius`, `area` and `unit_inertia` of every hull
/// `PolygonPath::new` accepts, with `unit_inertia` allowed the rounding
/// `check_polygon` allows it against the exact value (5e-10 m⁴ + 1e-11 relative;
/// on millimetre hulls that allowance dominates, since their unit inertia is a
/// few ulps). Returns r_b² · area / (8 · unit_inertia), ≤ 1 when it holds.
fn check_radius_of_gyration(points: &[Vector2]) -> Option<f64> {
    let poly = PolygonPath::new(points).ok()?;
    let (r, area, inertia) = (f(poly.radius()), f(poly.area()), f(poly.unit_inertia()));
    let slack = 5e-10 + inertia * 1e-11;
    assert!(
        r * r * area <= 8.0 * (inertia + slack) * (1.0 + 1e-9),
        "r_b = {r} m > √8 · ρ_g = {} m (area {area} m², unit inertia {inertia} m⁴)",
        (8.0 * inertia / area).sqrt()
    );
    Some(r * r * area / (8.0 * inertia))
}

/// A thin triangle comes close to the bound and stays under it; the square sits
/// far inside (3/8 of it).
#[test]
fn radius_of_gyration_bound_is_nearly_reached_by_a_thin_triangle() {
    let thin = [v(0.0, 0.0), v(60.0, 0.0), v(60.0, 0.5)];
    let ratio = check_radius_of_gyration(&thin).expect("thin triangle");
    assert!(ratio > 0.99 && ratio <= 1.0, "thin triangle r_b²/(8 ρ_g²) = {ratio}");
    let square = check_radius_of_gyration(&[v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)]);
    assert_close(square.expect("square"), 3.0 / 8.0, 1e-9, "square r_b²/(8 ρ_g²)");
}

/// Grid points (lots of duplicates and collinear triples) at several scales and
/// far from the origin.
fn grid_points() -> impl Strategy<Value = Vec<Vector2>> {
    (
        prop::collection::vec((-6i64..=6, -6i64..=6), 1..24),
        prop::sample::select(vec![14u32, 20, 26, 32, 37]),
        prop::sample::select(vec![0i64, 1 << 40, -(3 << 61)]),
    )
        .prop_map(|(pts, shift, offset)| {
            pts.into_iter()
                .map(|(x, y)| {
                    Vector2::new(
                        Scalar::from_bits((x << shift) + offset),
                        Scalar::from_bits((y << shift) - offset),
                    )
                })
                .collect()
        })
}

/// Points in general position within ±64 m.
fn free_points() -> impl Strategy<Value = Vec<Vector2>> {
    prop::collection::vec((-(1i64 << 38)..(1 << 38), -(1i64 << 38)..(1 << 38)), 1..14).prop_map(|pts| {
        pts.into_iter().map(|(x, y)| Vector2::new(Scalar::from_bits(x), Scalar::from_bits(y))).collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn hull_of_grid_points(points in grid_points()) {
        check_any(&points);
    }

    #[test]
    fn hull_of_free_points(points in free_points()) {
        check_any(&points);
    }

    #[test]
    fn bounding_radius_is_at_most_root_eight_radii_of_gyration_grid(points in grid_points()) {
        check_radius_of_gyration(&points);
    }

    #[test]
    fn bounding_radius_is_at_most_root_eight_radii_of_gyration_free(points in free_points()) {
        check_radius_of_gyration(&points);
    }

    #[test]
    fn any_bits_give_a_result_not_a_panic(
        pts in prop::collection::vec((any::<i64>(), any::<i64>()), 0..12),
        shift in 0u32..30,
    ) {
        // From the whole range down to ±2 m, so every error and success path is
        // reachable.
        let points: Vec<Vector2> = pts
            .into_iter()
            .map(|(x, y)| Vector2::new(Scalar::from_bits(x >> shift), Scalar::from_bits(y >> shift)))
            .collect();
        if let Ok(poly) = PolygonPath::new(&points) {
            check_polygon(&poly, &points);
        }
    }

    #[test]
    fn circle_matches_float(bits in 1i64..=(128i64 << 32)) {
        let r = Scalar::from_bits(bits);
        let rf = f(r);
        let pi = core::f64::consts::PI;
        let area = f(circle_area(r).unwrap());
        prop_assert!((area - pi * rf * rf).abs() <= 1.2e-10 + 1e-15 * area);
        let inertia = f(circle_unit_inertia(r).unwrap());
        let want = pi * rf.powi(4) / 2.0;
        prop_assert!((inertia - want).abs() <= 2.4e-10 + 1e-14 * want);
    }

    #[test]
    fn mass_data_is_exact_or_an_error(
        d in 1i64..(1i64 << 50), a in 1i64..(1i64 << 50), i in 1i64..(1i64 << 50)
    ) {
        let (d, a, i) = (Scalar::from_bits(d), Scalar::from_bits(a), Scalar::from_bits(i));
        let (mass, inertia) = (f(d) * f(a), f(d) * f(i));
        match MassData::from_density(d, a, i) {
            Ok(m) => {
                prop_assert!((f(m.mass) - mass).abs() <= 1.2e-10 + 1e-15 * mass);
                prop_assert!((f(m.inertia) - inertia).abs() <= 1.2e-10 + 1e-15 * inertia);
                // 1/m in Q32.32 is within one unit of its last place (2⁻³²) of
                // the exact inverse, so the product is within m·2⁻³² of 1 (a
                // fixed 1e-6 failed above about 4,300 kg: 7,189 kg is 1.7e-6).
                let ulp = 1.0 / (1u64 << 32) as f64;
                prop_assert!((f(m.inv_mass) * f(m.mass) - 1.0).abs() <= 1e-12 + f(m.mass) * ulp);
                prop_assert!(m.mass >= MIN_MASS && m.mass <= MAX_MASS);
                prop_assert!(m.inertia >= MIN_INERTIA && m.inertia <= MAX_INERTIA);
            }
            Err(Error::OutOfRange { what: "mass" }) => {
                prop_assert!(!(0.000_999_9..=100_000.000_1).contains(&mass));
            }
            Err(Error::OutOfRange { what: "inertia" }) => {
                prop_assert!(!(0.000_000_999_9..=1_000_000.000_1).contains(&inertia));
            }
            Err(e) => prop_assert!(false, "unexpected {e:?}"),
        }
    }
}

/// Found by proptest: a 192 m triangle at a 1.6e9 m offset whose far vertex is
/// 131.9 m from the centroid must be rejected as too large (the float oracle had
/// lost precision at that offset; the engine's exact integers had not).
#[test]
fn far_offset_triangle_over_the_size_limit_is_rejected() {
    let p = |x: i64, y: i64| Vector2::new(Scalar::from_num(x), Scalar::from_num(y));
    let points = [
        p(-1_610_612_800, 1_610_612_800),
        p(-1_610_612_608, 1_610_612_832),
        p(-1_610_612_800, 1_610_612_768),
    ];
    assert_eq!(PolygonPath::new(&points), Err(Error::OutOfRange { what: "polygon size" }));
    // The same triangle near the origin, 128 m limit: its vertex at (192, 32) is
    // √(128² + 32²) = 131.9 m from the centroid (64, 0).
    let near = [p(0, 0), p(192, 32), p(0, -32)];
    assert_eq!(PolygonPath::new(&near), Err(Error::OutOfRange { what: "polygon size" }));
}
