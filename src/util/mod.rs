//! Small shared utilities.

pub mod fsx;
