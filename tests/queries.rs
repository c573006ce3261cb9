//! World queries against independent f64 answers (proptest), and bad input.

use arphysics::geometry::PolygonPath;
use arphysics::{
    BodyDef, BodyHandle, Capacities, CollisionFilter, Error, QueryFilter, QueryShape, RayHit, Rect, Rot,
    Scalar, Transform, Vector2, World, WorldDef,
};
use proptest::prelude::*;

fn s(x: f64) -> Scalar {
    Scalar::from_num(x)
}

fn v(x: f64, y: f64) -> Vector2 {
    Vector2::new(s(x), s(y))
}

/// A body as the oracle sees it: a circle (radius) or a box (half extents, angle).
#[derive(Clone, Copy, Debug)]
enum Thing {
    Circle { c: (f64, f64), r: f64 },
    Box { c: (f64, f64), h: (f64, f64), angle: f64 },
}

fn thing() -> impl Strategy<Value = Thing> {
    let c = (-20.0f64..20.0, -20.0f64..20.0);
    prop_oneof![
        (c.clone(), 0.2f64..3.0).prop_map(|(c, r)| Thing::Circle { c, r }),
        (c, (0.2f64..3.0, 0.2f64..3.0), -3.0f64..3.0).prop_map(|(c, h, angle)| Thing::Box { c, h, angle }),
    ]
}

/// Builds the world with one body per thing; returns the handles and the things
/// as the engine stores them (positions and sizes rounded to Q32.32).
fn build(things: &[Thing]) -> (World<'static>, Vec<BodyHandle>, Vec<Thing>) {
    let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
    let mut w =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(64)).expect("world");
    let mut handles = Vec::new();
    let mut stored = Vec::new();
    for (i, t) in things.iter().enumerate() {
        let groups = if i % 5 == 4 { 0b10 } else { 0 };
        match *t {
            Thing::Circle { c, r } => {
                let b = w
                    .add_body(BodyDef::circle(s(r)).position(v(c.0, c.1)).collision_groups(groups))
                    .expect("c");
                let body = w.body(b).expect("b");
                let (x, y) = body.position().to_f64();
                stored.push(Thing::Circle { c: (x, y), r: s(r).to_num() });
                handles.push(b);
            }
            Thing::Box { c, h, angle } => {
                let p =
                    w.add_path(PolygonPath::rectangle(s(2.0 * h.0), s(2.0 * h.1)).expect("box")).expect("p");
                let b = w
                    .add_body(
                        BodyDef::polygon(p).position(v(c.0, c.1)).angle(s(angle)).collision_groups(groups),
                    )
                    .expect("b");
                let body = w.body(b).expect("b");
                let (x, y) = body.position().to_f64();
                let hx = w.path(p).expect("p").vertices()[2].x.to_num::<f64>();
                let hy = w.path(p).expect("p").vertices()[2].y.to_num::<f64>();
                stored.push(Thing::Box { c: (x, y), h: (hx, hy), angle: body.angle().to_num() });
                handles.push(b);
            }
        }
    }
    (w, handles, stored)
}

/// f64 ray entry distance into a thing (origin outside), or None.
fn oracle_ray(t: &Thing, o: (f64, f64), d: (f64, f64), len: f64) -> Option<f64> {
    match *t {
        Thing::Circle { c, r } => {
            let m = (o.0 - c.0, o.1 - c.1);
            let b = m.0 * d.0 + m.1 * d.1;
            let cc = m.0 * m.0 + m.1 * m.1 - r * r;
            if cc <= 0.0 {
                return None; // inside
            }
            let disc = b * b - cc;
            if disc < 0.0 {
                return None;
            }
            let t = -b - disc.sqrt();
            (t >= 0.0 && t <= len).then_some(t)
        }
        Thing::Box { c, h, angle } => {
            let (sn, cs) = angle.sin_cos();
            let rel = (o.0 - c.0, o.1 - c.1);
            let lo = (cs * rel.0 + sn * rel.1, -sn * rel.0 + cs * rel.1);
            let ld = (cs * d.0 + sn * d.1, -sn * d.0 + cs * d.1);
            if lo.0.abs() <= h.0 && lo.1.abs() <= h.1 {
                return None; // inside
            }
            let (mut t0, mut t1) = (0.0f64, len);
            for (p, dd, hh) in [(lo.0, ld.0, h.0), (lo.1, ld.1, h.1)] {
                if dd.abs() < 1e-15 {
                    if p.abs() > hh {
                        return None;
                    }
                } else {
                    let (a, b) = ((-hh - p) / dd, (hh - p) / dd);
                    t0 = t0.max(a.min(b));
                    t1 = t1.min(a.max(b));
                }
            }
            (t0 <= t1).then_some(t0)
        }
    }
}

/// Signed distance from a point to a thing's surface (negative inside).
fn oracle_distance(t: &Thing, p: (f64, f64)) -> f64 {
    match *t {
        Thing::Circle { c, r } => (p.0 - c.0).hypot(p.1 - c.1) - r,
        Thing::Box { c, h, angle } => {
            let (sn, cs) = angle.sin_cos();
            let rel = (p.0 - c.0, p.1 - c.1);
            let l = (cs * rel.0 + sn * rel.1, -sn * rel.0 + cs * rel.1);
            let q = (l.0.abs() - h.0, l.1.abs() - h.1);
            q.0.max(0.0).hypot(q.1.max(0.0)) + q.0.max(q.1).min(0.0)
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn ray_casts_match_f64_answers(
        things in prop::collection::vec(thing(), 1..12),
        from in (-30.0f64..30.0, -30.0f64..30.0),
        to in (-30.0f64..30.0, -30.0f64..30.0),
    ) {
        let (w, handles, stored) = build(&things);
        let (fx, tx) = (v(from.0, from.1), v(to.0, to.1));
        let (f, t) = (fx.to_f64(), tx.to_f64());
        let len = (t.0 - f.0).hypot(t.1 - f.1);
        prop_assume!(len > 1e-3);
        let d = ((t.0 - f.0) / len, (t.1 - f.1) / len);
        let filter = QueryFilter::default();
        let mut expected: Vec<(f64, usize)> =
            stored.iter().enumerate().filter_map(|(i, th)| oracle_ray(th, f, d, len).map(|t| (t / len, i))).collect();
        expected.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Skip grazing or near-tie cases, where rounding may legitimately decide.
        let near_edge = stored.iter().any(|th| {
            let hit = oracle_ray(th, f, d, len);
            let grazing = oracle_ray(th, f, d, len * (1.0 + 1e-6)).is_some() != hit.is_some();
            grazing || oracle_distance(th, f).abs() < 1e-6
        });
        let tie = expected.windows(2).any(|p| (p[1].0 - p[0].0).abs() < 1e-6);
        prop_assume!(!near_edge && !tie);
        let got = w.ray_cast(fx, tx, filter).expect("ray");
        match (got, expected.first()) {
            (None, None) => {}
            (Some(hit), Some(&(frac, i))) => {
                prop_assert_eq!(hit.body, handles[i]);
                prop_assert!((hit.fraction.to_num::<f64>() - frac).abs() < 1e-6, "{} vs {frac}", hit.fraction);
                let n = hit.normal.length().to_num::<f64>();
                prop_assert!((n - 1.0).abs() < 1e-6);
            }
            (g, e) => prop_assert!(false, "engine {g:?} vs oracle {e:?}"),
        }
        // All hits, nearest first.
        let mut out = [RayHit { body: BodyHandle::NULL, point: Vector2::ZERO, normal: Vector2::ZERO, fraction: Scalar::ZERO }; 16];
        let n = w.ray_cast_all(fx, tx, filter, &mut out).expect("ray");
        prop_assert_eq!(n, expected.len());
        for (hit, (frac, i)) in out.iter().zip(&expected) {
            prop_assert_eq!(hit.body, handles[*i]);
            prop_assert!((hit.fraction.to_num::<f64>() - frac).abs() < 1e-6);
        }
        // Groups: bodies sharing bit 1 (every fifth) are skipped.
        let filtered = QueryFilter { groups: 0b10, ..QueryFilter::default() };
        let n2 = w.ray_cast_all(fx, tx, filtered, &mut out).expect("ray");
        prop_assert_eq!(n2, expected.iter().filter(|(_, i)| i % 5 != 4).count());
    }

    #[test]
    fn point_and_shape_queries_match_f64_answers(
        things in prop::collection::vec(thing(), 1..12),
        p in (-25.0f64..25.0, -25.0f64..25.0),
        r in 0.1f64..4.0,
    ) {
        let (w, handles, stored) = build(&things);
        let px = v(p.0, p.1);
        let pf = px.to_f64();
        let rr = s(r).to_num::<f64>();
        prop_assume!(stored.iter().all(|t| {
            let d = oracle_distance(t, pf);
            d.abs() > 1e-6 && (d - rr).abs() > 1e-6
        }));
        let mut out = [BodyHandle::NULL; 16];
        let n = w.query_point(px, QueryFilter::default(), &mut out);
        let inside: Vec<BodyHandle> =
            stored.iter().zip(&handles).filter(|(t, _)| oracle_distance(t, pf) < 0.0).map(|(_, h)| *h).collect();
        prop_assert_eq!(&out[..n], &inside[..]);
        // A circle of radius r at p overlaps exactly the things closer than r.
        let xf = Transform::new(px, Rot::IDENTITY);
        let n = w.query_shape(QueryShape::Circle(s(r)), xf, QueryFilter::default(), &mut out).expect("q");
        let near: Vec<BodyHandle> =
            stored.iter().zip(&handles).filter(|(t, _)| oracle_distance(t, pf) <= rr).map(|(_, h)| *h).collect();
        prop_assert_eq!(&out[..n], &near[..]);
    }
}

#[test]
fn box_queries_see_overlapping_bounding_boxes_in_slot_order() {
    let things = [
        Thing::Circle { c: (0.0, 0.0), r: 1.0 },
        Thing::Box { c: (5.0, 0.0), h: (1.0, 1.0), angle: 0.0 },
        Thing::Circle { c: (10.0, 0.0), r: 1.0 },
    ];
    let (w, h, _) = build(&things);
    let mut out = [BodyHandle::NULL; 4];
    let n = w
        .query_aabb(Rect::from_corners(v(0.5, -0.1), v(4.2, 0.1)), QueryFilter::default(), &mut out)
        .expect("q");
    assert_eq!(&out[..n], &[h[0], h[1]]);
    // A point-sized box is allowed; more hits than the buffer reports the count.
    let mut one = [BodyHandle::NULL; 1];
    let n = w
        .query_aabb(Rect::from_corners(v(-20.0, -20.0), v(20.0, 20.0)), QueryFilter::default(), &mut one)
        .expect("q");
    assert_eq!((n, one[0]), (3, h[0]));
    let n = w
        .query_aabb(Rect { min: v(10.0, 0.0), max: v(10.0, 0.0) }, QueryFilter::default(), &mut out)
        .expect("q");
    assert_eq!(&out[..n], &[h[2]]);
}

#[test]
fn bad_queries_are_clear_errors() {
    let (w, _, _) = build(&[Thing::Circle { c: (0.0, 0.0), r: 1.0 }]);
    assert_eq!(
        w.ray_cast(v(1.0, 1.0), v(1.0, 1.0), QueryFilter::default()),
        Err(Error::OutOfRange { what: "ray length" })
    );
    let inverted = Rect { min: v(1.0, 1.0), max: v(0.0, 2.0) };
    let mut out = [BodyHandle::NULL; 2];
    assert_eq!(
        w.query_aabb(inverted, QueryFilter::default(), &mut out),
        Err(Error::OutOfRange { what: "query box" })
    );
    let xf = Transform::IDENTITY;
    assert_eq!(
        w.query_shape(QueryShape::Circle(s(0.0)), xf, QueryFilter::default(), &mut out),
        Err(Error::OutOfRange { what: "radius" })
    );
    // A ray from inside a body does not report it; the same ray from outside does.
    assert_eq!(w.ray_cast(v(0.0, 0.0), v(5.0, 0.0), QueryFilter::default()), Ok(None));
    let hit = w.ray_cast(v(-5.0, 0.0), v(5.0, 0.0), QueryFilter::default()).expect("ray").expect("hit");
    assert!((hit.fraction - s(0.4)).abs() < s(1e-9) && hit.normal == v(-1.0, 0.0));
}

/// Category, mask and an excluded body, honoured by every query alike: three
/// circles of radius 1 on the x axis (categories 1, 2 and 4; the third masks
/// out category 8), and a player at the origin casting through them.
#[test]
fn queries_honour_category_mask_and_an_excluded_body() {
    let bounds = Rect::from_corners(v(-100.0, -100.0), v(100.0, 100.0));
    let mut w =
        World::with_capacities(WorldDef::with_bounds(bounds), Capacities::for_bodies(8)).expect("world");
    let filter =
        |category, mask| CollisionFilter { category_bits: category, mask_bits: mask, group_index: 0 };
    let player = w.add_body(BodyDef::circle(s(1.0)).static_body().filter(filter(1, u64::MAX))).expect("b");
    let coin = w
        .add_body(BodyDef::circle(s(1.0)).static_body().position(v(5.0, 0.0)).filter(filter(2, u64::MAX)))
        .expect("b");
    let wall = w
        .add_body(BodyDef::circle(s(1.0)).static_body().position(v(10.0, 0.0)).filter(filter(4, !8)))
        .expect("b");
    let all = QueryFilter::default();
    let (from, to) = (v(0.0, 0.0), v(20.0, 0.0));
    // A ray from behind the player, through all three.
    let hit = |f: QueryFilter| w.ray_cast(v(-5.0, 0.0), to, f).expect("ray").map(|h| h.body);
    assert_eq!(hit(all), Some(player));
    assert_eq!(hit(all.exclude(player)), Some(coin), "the excluded body is skipped");
    assert_eq!(hit(all.exclude(player).mask(!2)), Some(wall), "coins masked out");
    assert_eq!(hit(all.mask(4)), Some(wall));
    assert_eq!(hit(all.mask(4).category(8)), None, "the wall masks out category 8");
    assert_eq!(hit(all.mask(0)), None);
    let mut hits = [RayHit {
        body: BodyHandle::NULL,
        point: Vector2::ZERO,
        normal: Vector2::ZERO,
        fraction: Scalar::ZERO,
    }; 4];
    assert_eq!(w.ray_cast_all(from, to, all.exclude(coin), &mut hits).expect("ray"), 1);
    assert_eq!(hits[0].body, wall);
    // Point, box and shape queries.
    let mut out = [BodyHandle::NULL; 4];
    assert_eq!(w.query_point(v(5.0, 0.0), all, &mut out), 1);
    assert_eq!(w.query_point(v(5.0, 0.0), all.exclude(coin), &mut out), 0);
    assert_eq!(w.query_point(v(5.0, 0.0), all.mask(1 | 4), &mut out), 0);
    let area = Rect::from_corners(v(-2.0, -2.0), v(12.0, 2.0));
    assert_eq!(w.query_aabb(area, all, &mut out).expect("q"), 3);
    let n = w.query_aabb(area, all.mask(2 | 4).category(8), &mut out).expect("q");
    assert_eq!(&out[..n], &[coin], "the wall refuses category 8, the player is not in the mask");
    let n = w.query_aabb(area, all.exclude(wall), &mut out).expect("q");
    assert_eq!(&out[..n], &[player, coin]);
    let xf = Transform::new(v(7.5, 0.0), Rot::IDENTITY);
    let n = w.query_shape(QueryShape::Circle(s(2.0)), xf, all, &mut out).expect("q");
    assert_eq!(&out[..n], &[coin, wall]);
    let n = w.query_shape(QueryShape::Circle(s(2.0)), xf, all.exclude(coin), &mut out).expect("q");
    assert_eq!(&out[..n], &[wall]);
    let n = w.query_shape(QueryShape::Circle(s(2.0)), xf, all.mask(2), &mut out).expect("q");
    assert_eq!(&out[..n], &[coin]);
}
