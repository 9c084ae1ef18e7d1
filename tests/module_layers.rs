//! Issue 13, item 2: the top-level modules of `src/` form layers, with no import cycle between
//! them. `SceneState` used to live in `stages`, the last stage of the pipeline, while physics,
//! render, formats, export, eval and layout used it; every module that needed it depended on the
//! stages that come after it, and eleven modules ended up in one knot (physics <-> stages,
//! render <-> stages, formats <-> stages, ...). A module that reaches up for a type or a helper
//! brings that knot back, so this test reads every `crate::<module>` path in `src/` (code, `use`
//! lines with grouped `crate::{a, b::c}` forms, unit tests and doc-comment links alike) and fails
//! on any cycle, naming its modules and one file:line per edge. Cycles among one module's own
//! files are fine: only the first path segment counts.
//!
//! The last five back edges went in the same issue: the tokenizer, lexicon and WordNet moved
//! below the room registry (`words`); the registry's material names are checked by a test in
//! `assets`; the XML tree, base64 and PNG decoding moved to `util`, OBJ text to `geometry`, the
//! glTF reader into `assets`, the asset directory writer to `formats` and the `asset` command to
//! `pipeline`; the room architecture asset and `install_rooms` moved below `render`; and the
//! export tests that build scenes with the pipeline moved to `tests/`. The layers, bottom to
//! top: scene, geometry, util, words, knowledge, prompt, assets, state, agents, formats, physics,
//! eval, plan, render, layout, stages, export, pipeline.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One reference from a file of module `from` to module `to`, first seen at `file:line`.
type Edges = BTreeMap<(String, String), String>;

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level modules `src/lib.rs` declares.
fn top_modules(lib_rs: &str) -> BTreeSet<String> {
    lib_rs
        .lines()
        .filter_map(|l| {
            let l = l.trim();
            let rest = l
                .strip_prefix("pub mod ")
                .or_else(|| l.strip_prefix("mod "))?;
            Some(rest.strip_suffix(';')?.trim().to_string())
        })
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("src/ is readable")
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

fn is_ident_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

fn leading_ident(s: &str) -> &str {
    let s = s.trim_start();
    let end = s.find(|c: char| !is_ident_char(c)).unwrap_or(s.len());
    &s[..end]
}

/// The first segments named after `crate::` in `text`, with their byte offsets: `crate::a::b`
/// gives `a`; `crate::{a::b, c, d::{e, f}}` gives `a`, `c` and `d`.
fn crate_paths(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (at, _) in text.match_indices("crate::") {
        if text[..at].chars().next_back().is_some_and(is_ident_char) {
            continue;
        }
        let rest = text[at + "crate::".len()..].trim_start();
        if let Some(group) = rest.strip_prefix('{') {
            // Items at brace depth 1 of the group, each up to its top-level comma.
            let mut depth = 1;
            let mut item_start = 0;
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' | ',' if depth == 1 => {
                        found.push((at, leading_ident(&group[item_start..i]).to_string()));
                        item_start = i + 1;
                        if c == '}' {
                            break;
                        }
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
        } else {
            found.push((at, leading_ident(rest).to_string()));
        }
    }
    found.retain(|(_, name)| !name.is_empty());
    found
}

/// The module a file under `src/` belongs to: `src/stages/run.rs` and `src/pipeline.rs` give
/// `stages` and `pipeline`; the crate root files give `None`.
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let mut parts = rel.components();
    let first = parts.next()?.as_os_str().to_str()?;
    if parts.next().is_some() {
        return Some(first.to_string());
    }
    let stem = first.strip_suffix(".rs")?;
    (stem != "lib" && stem != "main").then(|| stem.to_string())
}

fn module_graph() -> (BTreeSet<String>, Edges) {
    let src = src_dir();
    let lib_rs = std::fs::read_to_string(src.join("lib.rs")).expect("src/lib.rs");
    let modules = top_modules(&lib_rs);
    assert!(
        modules.len() > 5,
        "src/lib.rs declares its modules: {modules:?}"
    );
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut edges = Edges::new();
    for file in &files {
        let Some(from) = module_of(&src, file) else {
            continue;
        };
        let text = std::fs::read_to_string(file).expect("source file is UTF-8");
        for (at, to) in crate_paths(&text) {
            if to == from || !modules.contains(&to) {
                continue;
            }
            let line = text[..at].lines().count().max(1);
            let place = format!("src/{}:{line}", file.strip_prefix(&src).unwrap().display());
            edges.entry((from.clone(), to)).or_insert(place);
        }
    }
    (modules, edges)
}

/// The strongly connected components with more than one module (Tarjan).
fn cycles(modules: &BTreeSet<String>, edges: &Edges) -> Vec<Vec<String>> {
    struct Tarjan<'a> {
        next: BTreeMap<&'a str, Vec<&'a str>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            self.on_stack.insert(v);
            for w in self.next.get(v).cloned().unwrap_or_default() {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let lw = self.low[w];
                    let lv = self.low.get_mut(v).unwrap();
                    *lv = (*lv).min(lw);
                } else if self.on_stack.contains(w) {
                    let iw = self.index[w];
                    let lv = self.low.get_mut(v).unwrap();
                    *lv = (*lv).min(iw);
                }
            }
            if self.low[v] == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack.remove(w);
                    component.push(w.to_string());
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort();
                    self.found.push(component);
                }
            }
        }
    }
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (from, to) in edges.keys() {
        next.entry(from).or_default().push(to);
    }
    let mut t = Tarjan {
        next,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for m in modules {
        if !t.index.contains_key(m.as_str()) {
            t.visit(m);
        }
    }
    t.found
}

/// One shortest cycle through `start` inside `component`, as its modules in order.
fn one_cycle(start: &str, component: &[String], edges: &Edges) -> Vec<String> {
    let inside = |m: &str| component.iter().any(|c| c == m);
    let mut came_from: BTreeMap<String, String> = BTreeMap::new();
    let mut frontier = vec![start.to_string()];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for v in &frontier {
            for (from, to) in edges.keys() {
                if from != v || !inside(to) {
                    continue;
                }
                if to == start {
                    let mut path = vec![v.clone()];
                    while let Some(p) = came_from.get(path.last().unwrap()) {
                        path.push(p.clone());
                    }
                    path.reverse();
                    return path;
                }
                if !came_from.contains_key(to) && to != start {
                    came_from.insert(to.clone(), v.clone());
                    next.push(to.clone());
                }
            }
        }
        frontier = next;
    }
    vec![start.to_string()]
}

#[test]
fn top_level_modules_have_no_import_cycle() {
    let (modules, edges) = module_graph();
    let knots = cycles(&modules, &edges);
    if knots.is_empty() {
        return;
    }
    let mut report = String::new();
    for component in &knots {
        report += &format!("\nmodules in one cycle: {}\n", component.join(", "));
        let cycle = one_cycle(&component[0], component, &edges);
        report += "  for example:\n";
        for (i, from) in cycle.iter().enumerate() {
            let to = &cycle[(i + 1) % cycle.len()];
            let place = &edges[&(from.clone(), to.clone())];
            report += &format!("    {from} -> {to}  ({place})\n");
        }
        report += "  every edge inside it:\n";
        for ((from, to), place) in &edges {
            if component.contains(from) && component.contains(to) {
                report += &format!("    {from} -> {to}  ({place})\n");
            }
        }
    }
    panic!(
        "the top-level modules of src/ must form layers (issue 13 item 2); move the type or \
         function to the lower module that owns its concept:{report}"
    );
}

#[test]
fn crate_paths_are_read_in_every_form() {
    let text = "use crate::scene::Pose;\n\
                /// See [`crate::physics::check_dir`].\n\
                use crate::{assets::{Asset, AssetError}, geometry,\n    render::plan::draw};\n\
                let x = crate :: not_a_path; let y = mycrate::other; $crate::util::f();";
    let names: Vec<String> = crate_paths(text).into_iter().map(|(_, n)| n).collect();
    assert_eq!(
        names,
        ["scene", "physics", "assets", "geometry", "render", "util"]
    );
}

#[test]
fn a_cycle_is_found_and_a_layered_graph_passes() {
    let modules: BTreeSet<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
    let mut edges = Edges::new();
    edges.insert(("a".into(), "b".into()), "src/a.rs:1".into());
    edges.insert(("b".into(), "c".into()), "src/b.rs:1".into());
    assert!(cycles(&modules, &edges).is_empty());
    edges.insert(("c".into(), "a".into()), "src/c.rs:1".into());
    let knots = cycles(&modules, &edges);
    assert_eq!(knots, vec![vec!["a", "b", "c"]]);
    assert_eq!(one_cycle("a", &knots[0], &edges), ["a", "b", "c"]);
}
