//! TEMPORARY: stand-ins for the helpers' functions until their branches merge.
#![allow(missing_docs, clippy::missing_errors_doc, clippy::must_use_candidate, dead_code)]
use crate::collide::Manifold;
use crate::error::Error;
use crate::geometry::ray::ShapeHit;
use crate::geometry::{Capsule, PolygonPath, Segment};
use crate::math::{Rect, Scalar, Transform, Vector2};

impl Capsule {
    pub fn new(center1: Vector2, center2: Vector2, radius: Scalar) -> Result<Self, Error> {
        Ok(Self { center1, center2, radius })
    }
    pub fn length(&self) -> Scalar {
        (self.center2 - self.center1).length()
    }
    pub fn centroid(&self) -> Vector2 {
        Vector2::ZERO
    }
    pub fn area(&self) -> Result<Scalar, Error> {
        Ok(Scalar::ONE)
    }
    pub fn unit_inertia(&self) -> Result<Scalar, Error> {
        Ok(Scalar::ONE)
    }
    pub fn bounding_radius(&self) -> Scalar {
        self.radius
    }
    pub fn aabb(&self, xf: Transform) -> Rect {
        Rect::from_center(xf.p, Vector2::new(self.radius, self.radius))
    }
}
impl Segment {
    pub fn new(point1: Vector2, point2: Vector2) -> Result<Self, Error> {
        Ok(Self { point1, point2 })
    }
    pub fn length(&self) -> Scalar {
        (self.point2 - self.point1).length()
    }
    pub fn centroid(&self) -> Vector2 {
        Vector2::ZERO
    }
    pub fn rod_unit_inertia(&self) -> Scalar {
        Scalar::ONE
    }
    pub fn bounding_radius(&self) -> Scalar {
        Scalar::ONE
    }
    pub fn aabb(&self, xf: Transform) -> Rect {
        Rect::from_center(xf.p, Vector2::new(Scalar::ONE, Scalar::ONE))
    }
}
impl PolygonPath {
    pub fn rounded(points: &[Vector2], _radius: Scalar) -> Result<Self, Error> {
        Self::new(points)
    }
    pub fn rounded_rectangle(width: Scalar, height: Scalar, _radius: Scalar) -> Result<Self, Error> {
        Self::rectangle(width, height)
    }
}
pub fn ray_capsule(_o: Vector2, _d: Vector2, _l: Scalar, _c: &Capsule, _xf: Transform) -> Option<ShapeHit> {
    None
}
pub fn ray_segment(_o: Vector2, _d: Vector2, _l: Scalar, _c: &Segment, _xf: Transform) -> Option<ShapeHit> {
    None
}
pub fn capsule_contains(_c: &Capsule, _xf: Transform, _p: Vector2) -> bool {
    false
}
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
