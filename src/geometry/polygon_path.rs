//! `PolygonPath`: the shared, immutable geometry of a convex polygon.
//!
//! LAYOUT CONTRACT (other modules rely on it): vertices are stored counter-clockwise,
//! relative to the polygon's centroid (so the body's position is its centre of mass),
//! `normals[i]` is the outward unit normal of the edge `vertices[i] → vertices[i+1]`
//! (wrapping), and only the first `count` entries of both arrays are meaningful.

use crate::error::Error;
use crate::math::scalar::{self, Scalar, ZERO};
use crate::math::Vector2;

/// Most vertices a polygon may have (after the convex hull removed the rest).
pub const MAX_POLYGON_VERTICES: usize = 8;

/// The geometry of a convex polygon, shared by any number of bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PolygonPath {
    pub(crate) vertices: [Vector2; MAX_POLYGON_VERTICES],
    pub(crate) normals: [Vector2; MAX_POLYGON_VERTICES],
    pub(crate) count: usize,
    /// Area in m².
    pub(crate) area: Scalar,
    /// Polar moment of inertia about the centroid for density 1 kg/m², in kg·m².
    pub(crate) unit_inertia: Scalar,
    /// Centroid of the hull in the coordinates the points were given in.
    pub(crate) centroid: Vector2,
    /// Largest distance from the centroid to a vertex (bounding radius), in m.
    pub(crate) radius: Scalar,
}

impl PolygonPath {
    /// An axis-aligned rectangle `width` × `height` metres centred on the origin.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] when a side is not positive.
    pub fn rectangle(width: Scalar, height: Scalar) -> Result<Self, Error> {
        if width <= ZERO || height <= ZERO {
            return Err(Error::OutOfRange {
                what: "rectangle side",
            });
        }
        let (hx, hy) = (
            width.saturating_mul(scalar::HALF),
            height.saturating_mul(scalar::HALF),
        );
        let mut vertices = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        let mut normals = [Vector2::ZERO; MAX_POLYGON_VERTICES];
        vertices[..4].copy_from_slice(&[
            Vector2::new(-hx, -hy),
            Vector2::new(hx, -hy),
            Vector2::new(hx, hy),
            Vector2::new(-hx, hy),
        ]);
        normals[..4].copy_from_slice(&[-Vector2::Y, Vector2::X, Vector2::Y, -Vector2::X]);
        let area = width.saturating_mul(height);
        // I = m (w² + h²) / 12 for density 1.
        let unit_inertia = scalar::div(
            area.saturating_mul(
                width
                    .saturating_mul(width)
                    .saturating_add(height.saturating_mul(height)),
            ),
            scalar::from_int(12),
        );
        Ok(Self {
            vertices,
            normals,
            count: 4,
            area,
            unit_inertia,
            centroid: Vector2::ZERO,
            radius: Vector2::new(hx, hy).length(),
        })
    }

    /// The hull's vertices, counter-clockwise, relative to the centroid (m).
    #[inline]
    #[must_use]
    pub fn vertices(&self) -> &[Vector2] {
        self.vertices.get(..self.count).unwrap_or(&[])
    }

    /// Outward unit normal of each edge `vertices[i] → vertices[i + 1]`.
    #[inline]
    #[must_use]
    pub fn normals(&self) -> &[Vector2] {
        self.normals.get(..self.count).unwrap_or(&[])
    }

    /// Area in m².
    #[inline]
    #[must_use]
    pub fn area(&self) -> Scalar {
        self.area
    }

    /// Moment of inertia about the centroid at density 1 kg/m² (kg·m²).
    #[inline]
    #[must_use]
    pub fn unit_inertia(&self) -> Scalar {
        self.unit_inertia
    }

    /// Centroid of the hull in the coordinates the points were given in (m). The
    /// stored vertices are shifted by it, so a body's position is its centroid.
    #[inline]
    #[must_use]
    pub fn centroid(&self) -> Vector2 {
        self.centroid
    }

    /// Bounding radius: the largest distance from the centroid to a vertex (m).
    #[inline]
    #[must_use]
    pub fn radius(&self) -> Scalar {
        self.radius
    }
}
