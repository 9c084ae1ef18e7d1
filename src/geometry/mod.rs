//! Geometry kernel: visual triangle meshes, convex collision pieces, mass properties, 2D
//! polygons. Everything here is in metres, in whatever local frame the caller names.

pub mod convex;
pub mod mass;
pub mod mesh;
pub mod obj;
pub mod penetration;
pub mod polygon;

pub use convex::ConvexPiece;
pub use mass::MassProps;
pub use mesh::TriMesh;

/// What can go wrong building geometry.
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    /// The points do not span a volume (too few, collinear or coplanar).
    #[error("convex hull of {points} points is degenerate (no volume)")]
    DegenerateHull {
        /// How many points were given.
        points: usize,
    },
    /// A coordinate was NaN or infinite.
    #[error("geometry has a non-finite coordinate")]
    NonFinite,
    /// Density must be positive and finite.
    #[error("density {0} kg/m^3 is not positive and finite")]
    InvalidDensity(f64),
    /// Mass properties that no real rigid body has.
    #[error("physically invalid mass properties: {0}")]
    InvalidInertia(String),
    /// A polygon that cannot be a floor (too few vertices, self-intersecting, zero area).
    #[error("invalid polygon: {0}")]
    InvalidPolygon(String),
}
