//! Readable, stable identifiers: a name plus a base-36 counter (`chair_0`, `chair_a`, `chair_10`).
//!
//! The same sequence of requests always yields the same ids, so two runs with the same prompt and
//! seed name their objects identically. Names are reduced to `[a-z0-9_]` so an id is safe as a
//! file name, an SDFormat/MJCF/USD name and a Drake model instance name.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// Lowercase `[a-z0-9_]` form of a free-text name; never empty, never starts with a digit.
///
/// Anything else (spaces, quotes, unicode, `..`, `/`) becomes `_`, and runs of `_` collapse, so
/// the result can never name a path outside the directory it is joined to.
pub fn sanitize_name(raw: &str) -> String {
    let mut out = String::with_capacity(raw.len());
    for c in raw.chars() {
        let c = c.to_ascii_lowercase();
        if c.is_ascii_lowercase() || c.is_ascii_digit() {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let trimmed = out.trim_matches('_');
    let mut name = if trimmed.is_empty() {
        "object".to_string()
    } else {
        trimmed.to_string()
    };
    if name.starts_with(|c: char| c.is_ascii_digit()) {
        name.insert_str(0, "n_");
    }
    // Keep names short enough for every consumer (USD prim names, file names).
    if name.len() > 48 {
        name.truncate(48);
        while name.ends_with('_') {
            name.pop();
        }
    }
    name
}

/// `n` written in base 36 with digits `0-9a-z`.
pub fn base36(mut n: u64) -> String {
    const DIGITS: &[u8; 36] = b"0123456789abcdefghijklmnopqrstuvwxyz";
    if n == 0 {
        return "0".to_string();
    }
    let mut buf = Vec::new();
    while n > 0 {
        buf.push(DIGITS[(n % 36) as usize]);
        n /= 36;
    }
    buf.reverse();
    String::from_utf8(buf).unwrap_or_default()
}

/// Hands out `name_<base36 counter>` ids, one counter per name.
#[derive(Debug, Clone, Default, Serialize, Deserialize, PartialEq)]
pub struct IdAllocator {
    next: BTreeMap<String, u64>,
}

impl IdAllocator {
    /// An allocator with no ids handed out.
    pub fn new() -> Self {
        Self::default()
    }

    /// The next id for `name` (sanitised first).
    pub fn allocate(&mut self, name: &str) -> String {
        let base = sanitize_name(name);
        let counter = self.next.entry(base.clone()).or_insert(0);
        let id = format!("{base}_{}", base36(*counter));
        *counter += 1;
        id
    }

    /// Marks an existing id as used so later allocations never repeat it (used when a scene is
    /// loaded from `scene.json` and then edited).
    pub fn reserve(&mut self, id: &str) {
        if let Some((base, suffix)) = id.rsplit_once('_')
            && let Ok(n) = u64::from_str_radix(suffix, 36)
        {
            let counter = self.next.entry(base.to_string()).or_insert(0);
            *counter = (*counter).max(n + 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base36_counts_like_the_design_says() {
        assert_eq!(base36(0), "0");
        assert_eq!(base36(10), "a");
        assert_eq!(base36(35), "z");
        assert_eq!(base36(36), "10");
    }

    #[test]
    fn allocator_is_per_name_and_stable() {
        let mut ids = IdAllocator::new();
        assert_eq!(ids.allocate("Chair"), "chair_0");
        assert_eq!(ids.allocate("chair"), "chair_1");
        assert_eq!(ids.allocate("coffee table"), "coffee_table_0");
        for _ in 2..10 {
            ids.allocate("chair");
        }
        assert_eq!(ids.allocate("chair"), "chair_a");
    }

    #[test]
    fn reserve_skips_used_ids() {
        let mut ids = IdAllocator::new();
        ids.reserve("mug_b");
        assert_eq!(ids.allocate("mug"), "mug_c");
    }

    #[test]
    fn sanitize_defuses_paths_and_unicode() {
        assert_eq!(sanitize_name("../../etc/passwd"), "etc_passwd");
        assert_eq!(
            sanitize_name("  Grandma's \"Chair\" ☕ "),
            "grandma_s_chair"
        );
        assert_eq!(sanitize_name("3d printer"), "n_3d_printer");
        assert_eq!(sanitize_name("☕"), "object");
    }
}
