//! Small shared utilities.

pub mod base64;
pub mod fsx;
pub mod http_body;
pub mod png;
pub mod xml;
