//! Physics: Rust-side collision checks (parry3d) and the Drake bridge client.

pub mod bridge;
pub mod collision;

pub use bridge::{Bridge, BridgeConfig, BridgeError};
