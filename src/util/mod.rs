//! Small shared utilities.

pub mod base64;
pub mod fsx;
pub mod png;
