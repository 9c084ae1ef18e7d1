//! Manipuland stage: small objects on the surfaces of one supporting entity (a table top, the
//! levels of a shelf, a counter, a bed). Positions are surface-local: `u` along the surface's
//! width, `v` along its depth (towards the front), from its centre; the stage checks that
//! objects lie within the surface, clear of each other and below the free height above it.
//!
//! `tools.rs` holds the tool set and the single-item tools; where an item fits on a surface is
//! `fit.rs`, which surfaces there are and what rests on them `surface.rs`. Composite tools build
//! stacks (`stack.rs`: items resting on each other at the pitch where they nest), piles
//! (`pile.rs`: layers of loosely packed items), fills (`fill.rs`: items inside a container's
//! cavity surface) and place settings (`settings.rs`: plate, glass and cutlery in front of each
//! seat). `builtin.rs` holds the offline designer and critic.

mod builtin;
mod fill;
mod fit;
mod pile;
mod settings;
mod stack;
mod surface;
mod tools;

pub use builtin::{BuiltinManipulandCritic, BuiltinManipulandDesigner};
pub use surface::spot_again;
pub use tools::{categories, toolbox};
