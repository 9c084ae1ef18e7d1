//! Ceiling stage: objects hanging from the ceiling of one room (lights, fans, mobiles), placed
//! at room coordinates or above a piece of furniture, with head room kept over the walkable
//! floor. `tools.rs` holds the tools, `builtin.rs` the offline designer and critic.

mod builtin;
mod tools;

pub use builtin::{BuiltinCeilingCritic, BuiltinCeilingDesigner};
pub use tools::{categories, toolbox};
