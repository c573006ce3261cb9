//! TEMPORARY: stand-ins for the helpers' functions until their branches merge.
#![allow(missing_docs, clippy::missing_errors_doc, clippy::must_use_candidate, dead_code)]
use crate::collide::Manifold;
use crate::geometry::{Capsule, PolygonPath, Segment};
use crate::math::{Scalar, Transform};

pub fn collide_capsule_circle(
    _c: &Capsule,
    _xa: Transform,
    _r: Scalar,
    _xb: Transform,
    _m: Scalar,
) -> Manifold {
    Manifold::EMPTY
}
pub fn collide_segment_circle(
    _c: &Segment,
    _xa: Transform,
    _r: Scalar,
    _xb: Transform,
    _m: Scalar,
) -> Manifold {
    Manifold::EMPTY
}
pub fn collide_capsules(_a: &Capsule, _xa: Transform, _b: &Capsule, _xb: Transform, _m: Scalar) -> Manifold {
    Manifold::EMPTY
}
pub fn collide_segment_capsule(
    _a: &Segment,
    _xa: Transform,
    _b: &Capsule,
    _xb: Transform,
    _m: Scalar,
) -> Manifold {
    Manifold::EMPTY
}
pub fn collide_polygon_capsule(
    _a: &PolygonPath,
    _xa: Transform,
    _b: &Capsule,
    _xb: Transform,
    _m: Scalar,
) -> Manifold {
    Manifold::EMPTY
}
pub fn collide_segment_polygon(
    _a: &Segment,
    _xa: Transform,
    _b: &PolygonPath,
    _xb: Transform,
    _m: Scalar,
) -> Manifold {
    Manifold::EMPTY
}
