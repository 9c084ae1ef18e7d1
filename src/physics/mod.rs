//! Physics: Rust-side collision checks and the native non-penetration projection (parry3d +
//! clarabel), the Drake bridge client and its worker pool, gravity settling through the bridge,
//! fallen-object removal, and the post-processing step that ties them together.
//!
//! | module | concept |
//! |---|---|
//! | [`collision`] | penetration depths on posed convex pieces |
//! | [`as_written`] | the pieces at the precision of the written files |
//! | [`projection`] | native projection: iterated linearised signed-distance QPs |
//! | [`drake_projection`] | the Drake projection (SNOPT/IPOPT) through the bridge, the reference |
//! | [`bridge`], [`pool`] | one bridge process; N of them in parallel |
//! | [`protocol`] | the bridge's operations with typed arguments and replies; their JSON Schema |
//! | [`workspace`] | scene files for the bridge: assets plus one directives file per subset |
//! | [`settle`] | gravity settling requests and replies |
//! | [`removal`] | which objects fell, and why |
//! | [`postprocess`] | furniture phase and manipuland phase: project, settle, remove |

pub mod as_written;
pub mod bridge;
pub mod check;
pub mod collision;
pub mod drake_projection;
pub mod groups;
pub mod pool;
pub mod postprocess;
pub mod projection;
pub mod protocol;
pub mod removal;
pub mod settle;
pub mod workspace;

pub use bridge::{Bridge, BridgeConfig, BridgeError};
pub use check::{CheckSummary, check_dir};
pub use pool::BridgePool;

/// What can go wrong in the physics steps.
#[derive(Debug, thiserror::Error)]
pub enum PhysicsError {
    /// The Drake bridge failed (not installed, crashed twice, timed out, reported an error).
    #[error(transparent)]
    Bridge(#[from] BridgeError),
    /// Collision geometry could not be built.
    #[error(transparent)]
    Geometry(#[from] crate::geometry::GeometryError),
    /// Scene files for the bridge could not be written.
    #[error(transparent)]
    Format(#[from] crate::formats::FormatError),
    /// A file or directory of the physics workspace could not be written.
    #[error("physics workspace {path}: {cause}")]
    Io {
        /// The path.
        path: std::path::PathBuf,
        /// OS error.
        cause: std::io::Error,
    },
    /// An object named in a request is not in the scene.
    #[error("object {0:?} is not in the scene")]
    UnknownObject(String),
}
