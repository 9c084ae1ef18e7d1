//! Furniture stage: floor-standing furniture of one room. Its tools (`tools.rs`: on top of the
//! shared ones in [`super::common`]) place objects at coordinates, against walls, in corners, in
//! the open middle, around a table and facing a target; every placement is checked against the
//! floor, the other furniture and the keep-out zones of doors and windows. `builtin.rs` holds the
//! offline designer and critic, which work through the same tools an LLM would call.

mod builtin;
mod tools;

pub use builtin::{BuiltinFurnitureCritic, BuiltinFurnitureDesigner};
pub use tools::{categories, toolbox};
