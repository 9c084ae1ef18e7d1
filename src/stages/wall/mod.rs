//! Wall stage: objects mounted on the walls of one room, placed in wall coordinates (`along_m`
//! from the wall's start, `height_m` of the object's centre), clear of doors, windows, other
//! wall objects and furniture standing in front. `tools.rs` holds the tools, `builtin.rs` the
//! offline designer and critic.

mod builtin;
mod tools;

// The ceiling critic scores requested objects and collisions the way the wall critic does.
pub(crate) use builtin::requested_and_collisions;
pub use builtin::{BuiltinWallCritic, BuiltinWallDesigner};
pub use tools::{categories, toolbox};
