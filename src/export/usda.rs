//! Building blocks of text USD (`.usda`): string literals, numbers, tuples, arrays and an
//! indenting writer for prims. Names passed to [`Usda::open`] must already be valid
//! identifiers (the export view's names are `[a-z0-9_]`).

use std::fmt::Write as _;

use nalgebra::UnitQuaternion;

use super::num;
use crate::scene::Pose;

/// A USDA string literal: quotes, backslashes and control characters escaped, everything else
/// (unicode included) verbatim.
pub(crate) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                // Three octal digits: never swallows a following digit.
                let _ = write!(out, "\\{:03o}", c as u32);
            }
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// `(a, b, c)` with full precision.
pub(crate) fn tuple(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| num(*x)).collect();
    format!("({})", parts.join(", "))
}

/// A quaternion as USD writes it: `(w, x, y, z)`.
pub(crate) fn quat(q: &UnitQuaternion<f64>) -> String {
    tuple(&[q.w, q.i, q.j, q.k])
}

/// A coordinate at micrometre precision (the precision of the OBJ collision files Drake reads),
/// trailing zeros trimmed.
pub(crate) fn micro(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    match s {
        "" | "-0" => "0".to_string(),
        s => s.to_string(),
    }
}

/// `[(x, y, z), ...]` at micrometre precision.
pub(crate) fn points(pts: &[[f64; 3]]) -> String {
    let mut out = String::with_capacity(pts.len() * 30 + 2);
    out.push('[');
    for (i, p) in pts.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        let _ = write!(out, "({}, {}, {})", micro(p[0]), micro(p[1]), micro(p[2]));
    }
    out.push(']');
    out
}

/// `[(u, v), ...]` at micrometre precision.
pub(crate) fn points2(pts: &[[f64; 2]]) -> String {
    let mut out = String::with_capacity(pts.len() * 20 + 2);
    out.push('[');
    for (i, p) in pts.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        let _ = write!(out, "({}, {})", micro(p[0]), micro(p[1]));
    }
    out.push(']');
    out
}

/// Face counts and flat indices of a triangle list.
pub(crate) fn faces(triangles: &[[u32; 3]]) -> (String, String) {
    let counts = format!("[{}]", vec!["3"; triangles.len()].join(", "));
    let mut idx = String::with_capacity(triangles.len() * 15 + 2);
    idx.push('[');
    for (i, t) in triangles.iter().enumerate() {
        if i > 0 {
            idx.push_str(", ");
        }
        let _ = write!(idx, "{}, {}, {}", t[0], t[1], t[2]);
    }
    idx.push(']');
    (counts, idx)
}

/// An indenting USDA writer.
#[derive(Debug, Default)]
pub(crate) struct Usda {
    out: String,
    depth: usize,
}

impl Usda {
    /// A layer starting with `#usda 1.0` and the given layer metadata lines.
    pub(crate) fn layer(metadata: &[String]) -> Self {
        let mut w = Usda::default();
        w.out.push_str("#usda 1.0\n(\n");
        for m in metadata {
            let _ = writeln!(w.out, "    {m}");
        }
        w.out.push_str(")\n");
        w
    }

    /// One line at the current depth.
    pub(crate) fn line(&mut self, text: &str) {
        self.out.push('\n');
        for _ in 0..self.depth {
            self.out.push_str("    ");
        }
        self.out.push_str(text);
    }

    /// `def Xform "name" ( metadata ) {` (the header is e.g. `def Xform`, `over`); opens a block.
    pub(crate) fn open(&mut self, header: &str, name: &str, metadata: &[String]) {
        self.out.push('\n');
        self.line(&format!("{header} \"{name}\""));
        if !metadata.is_empty() {
            self.out.push_str(" (");
            self.depth += 1;
            for m in metadata {
                self.line(m);
            }
            self.depth -= 1;
            self.line(")");
        }
        self.line("{");
        self.depth += 1;
    }

    /// Closes the innermost block.
    pub(crate) fn close(&mut self) {
        self.depth = self.depth.saturating_sub(1);
        self.line("}");
    }

    /// Translate + orient xform ops for `parent_from_prim` (nothing for the identity).
    pub(crate) fn xform(&mut self, parent_from_prim: &Pose) {
        let t = parent_from_prim.translation();
        let q = parent_from_prim.rotation();
        if t.norm() == 0.0 && q.angle() == 0.0 {
            return;
        }
        self.line(&format!(
            "double3 xformOp:translate = {}",
            tuple(&[t.x, t.y, t.z])
        ));
        self.line(&format!("quatd xformOp:orient = {}", quat(&q)));
        self.line("uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\"]");
    }

    /// The finished text.
    pub(crate) fn finish(mut self) -> String {
        self.out.push('\n');
        self.out
    }
}

/// `prepend apiSchemas = [...]` metadata, or nothing for an empty list.
pub(crate) fn api_schemas(names: &[&str]) -> Option<String> {
    if names.is_empty() {
        return None;
    }
    let q: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    Some(format!("prepend apiSchemas = [{}]", q.join(", ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quote_escapes_what_usda_needs() {
        assert_eq!(quote("a \"b\" \\ c"), "\"a \\\"b\\\" \\\\ c\"");
        assert_eq!(quote("x\ny\u{1}2"), "\"x\\ny\\0012\"");
        assert_eq!(quote("tür 漢字 .. @"), "\"tür 漢字 .. @\"");
    }

    #[test]
    fn micro_trims() {
        assert_eq!(micro(0.5), "0.5");
        assert_eq!(micro(-0.0000001), "0");
        assert_eq!(micro(2.0), "2");
        assert_eq!(micro(-1.25), "-1.25");
    }

    #[test]
    fn writer_nests_blocks() {
        let mut w = Usda::layer(&["upAxis = \"Z\"".into()]);
        w.open("def Xform", "World", &["kind = \"group\"".into()]);
        w.line("float a = 1");
        w.close();
        let text = w.finish();
        assert!(text.starts_with("#usda 1.0\n(\n    upAxis = \"Z\"\n)\n"));
        assert!(
            text.contains("def Xform \"World\" (\n    kind = \"group\"\n)\n{\n    float a = 1\n}")
        );
    }
}
