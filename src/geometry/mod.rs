//! Shapes and their mass properties: [`PolygonPath`] (convex hull, area, centroid,
//! moment of inertia), circles, and [`MassData`].

pub mod circle;
pub mod mass;
pub mod polygon_path;

pub use mass::MassData;
pub use polygon_path::{PolygonPath, MAX_POLYGON_VERTICES};
