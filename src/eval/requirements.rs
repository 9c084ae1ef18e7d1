//! Requirements scoring: a scene against requirements written independently of the prompt
//! reader (`scenesmith eval DIR --requirements FILE`).
//!
//! [`super::coverage`] compares the scene with the reader's own plan, so a noun the reader
//! missed is missing on both sides and that score cannot see it. Here the requirements come
//! from outside (a person, a benchmark's annotations), one JSON object per line:
//!
//! ```text
//! {"object": "chair", "count": ">=4"}
//! {"object": "sofa", "count": "=1", "room": "living room"}
//! {"absent": "tv"}
//! {"room": "bedroom", "count": "=2"}
//! ```
//!
//! Matching is by label only (see [`normalize_label`], [`object_matches`], [`room_matches`]):
//! the scene's categories, room types and the optional prompt names (`SceneObject::name`,
//! `Room::label`) against the requirement's words, through the prompt lexicon's synonyms and
//! `kind_of` chain and the knowledge base's room words. It needs `scene.json` only: no assets,
//! no Drake.

use std::collections::BTreeSet;
use std::fmt::{self, Write as _};
use std::path::Path;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::EvalError;
use crate::formats::FormatError;
use crate::knowledge::knowledge;
use crate::scene::{ObjectKind, Room, Scene, SceneObject};
use crate::words::lexicon::lexicon;

/// File name of the report in a scene directory.
pub const REQUIREMENTS_REPORT_JSON: &str = "requirements_report.json";

/// Version of the report layout.
pub const REQUIREMENTS_REPORT_VERSION: u32 = 1;

/// Ids shown per row of the text table (the JSON report lists them all).
const IDS_SHOWN: usize = 5;

/// How many of something a requirement wants: `=N`, `>=N`, `<=N`, `>N`, `<N` or `several`
/// (two or more). A bare `N` (string or JSON number) means `=N`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CountOp {
    /// Exactly n.
    Eq(u32),
    /// n or more.
    Ge(u32),
    /// n or fewer.
    Le(u32),
    /// More than n.
    Gt(u32),
    /// Fewer than n.
    Lt(u32),
    /// Two or more.
    Several,
}

impl CountOp {
    /// Parses `=2`, `>= 2`, `several`, `3`, ...
    pub fn parse(text: &str) -> Result<CountOp, String> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("several") {
            return Ok(CountOp::Several);
        }
        let (op, rest): (fn(u32) -> CountOp, &str) = if let Some(r) = t.strip_prefix(">=") {
            (CountOp::Ge, r)
        } else if let Some(r) = t.strip_prefix("<=") {
            (CountOp::Le, r)
        } else if let Some(r) = t.strip_prefix('>') {
            (CountOp::Gt, r)
        } else if let Some(r) = t.strip_prefix('<') {
            (CountOp::Lt, r)
        } else if let Some(r) = t.strip_prefix('=') {
            (CountOp::Eq, r)
        } else {
            (CountOp::Eq, t)
        };
        let n: u32 = rest.trim().parse().map_err(|_| {
            format!(
                "\"count\" must be =N, >=N, <=N, >N, <N (N a whole number >= 0) or \"several\", not {text:?}"
            )
        })?;
        let count = op(n);
        if count == CountOp::Lt(0) {
            return Err("\"count\" <0 can never be met".into());
        }
        Ok(count)
    }

    /// Whether `n` things meet the count.
    pub fn met_by(self, n: usize) -> bool {
        let n = n as u64;
        match self {
            CountOp::Eq(k) => n == u64::from(k),
            CountOp::Ge(k) => n >= u64::from(k),
            CountOp::Le(k) => n <= u64::from(k),
            CountOp::Gt(k) => n > u64::from(k),
            CountOp::Lt(k) => n < u64::from(k),
            CountOp::Several => n >= 2,
        }
    }
}

impl fmt::Display for CountOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CountOp::Eq(n) => write!(f, "={n}"),
            CountOp::Ge(n) => write!(f, ">={n}"),
            CountOp::Le(n) => write!(f, "<={n}"),
            CountOp::Gt(n) => write!(f, ">{n}"),
            CountOp::Lt(n) => write!(f, "<{n}"),
            CountOp::Several => f.write_str("several"),
        }
    }
}

/// One requirement. Serialised in the shape it is written in (`{"object": ..., "count": ...}`,
/// `{"absent": ...}`, `{"room": ..., "count": ...}`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Requirement {
    /// A number of objects matching `label`, only in rooms matching `room` when given.
    Object {
        /// Object label as written.
        label: String,
        /// How many.
        count: CountOp,
        /// Room label restricting where the objects are counted.
        room: Option<String>,
    },
    /// No object matches `label` (in rooms matching `room` when given).
    Absent {
        /// Object label as written.
        label: String,
        /// Room label restricting where to look.
        room: Option<String>,
    },
    /// A number of rooms matching `label`.
    Room {
        /// Room label as written.
        label: String,
        /// How many.
        count: CountOp,
    },
}

impl fmt::Display for Requirement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let in_room = |room: &Option<String>| {
            room.as_ref()
                .map(|r| format!(" in room {r:?}"))
                .unwrap_or_default()
        };
        match self {
            Requirement::Object { label, count, room } => {
                write!(f, "object {label:?} {count}{}", in_room(room))
            }
            Requirement::Absent { label, room } => write!(f, "absent {label:?}{}", in_room(room)),
            Requirement::Room { label, count } => write!(f, "room {label:?} {count}"),
        }
    }
}

/// The keys a requirement may have, before they are checked against each other.
#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRequirement {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    object: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    absent: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    room: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    count: Option<serde_json::Value>,
}

fn label(key: &str, text: String) -> Result<String, String> {
    let t = text.trim();
    if normalize_label(t).is_empty() {
        return Err(format!("{key:?} is empty"));
    }
    Ok(t.to_string())
}

fn count(value: Option<serde_json::Value>) -> Result<CountOp, String> {
    match value {
        None => Err("\"count\" is missing".into()),
        Some(serde_json::Value::String(s)) => CountOp::parse(&s),
        Some(serde_json::Value::Number(n)) => n
            .as_u64()
            .and_then(|n| u32::try_from(n).ok())
            .map(CountOp::Eq)
            .ok_or_else(|| format!("\"count\" must be a whole number >= 0, not {n}")),
        Some(v) => Err(format!(
            "\"count\" must be a string such as \">=2\" or a number, not {v}"
        )),
    }
}

impl TryFrom<RawRequirement> for Requirement {
    type Error = String;

    fn try_from(raw: RawRequirement) -> Result<Requirement, String> {
        match (raw.object, raw.absent, raw.room) {
            (Some(_), Some(_), _) => Err("has both \"object\" and \"absent\"; use one".into()),
            (Some(object), None, room) => Ok(Requirement::Object {
                label: label("object", object)?,
                count: count(raw.count)?,
                room: room.map(|r| label("room", r)).transpose()?,
            }),
            (None, Some(absent), room) => {
                if raw.count.is_some() {
                    return Err("\"absent\" takes no \"count\" (it means none)".into());
                }
                Ok(Requirement::Absent {
                    label: label("absent", absent)?,
                    room: room.map(|r| label("room", r)).transpose()?,
                })
            }
            (None, None, Some(room)) => Ok(Requirement::Room {
                label: label("room", room)?,
                count: count(raw.count)?,
            }),
            (None, None, None) => Err(
                "needs \"object\" (with \"count\"), \"absent\" or \"room\" (with \"count\")".into(),
            ),
        }
    }
}

impl From<&Requirement> for RawRequirement {
    fn from(r: &Requirement) -> RawRequirement {
        let count = |c: &CountOp| Some(serde_json::Value::String(c.to_string()));
        match r {
            Requirement::Object {
                label,
                count: c,
                room,
            } => RawRequirement {
                object: Some(label.clone()),
                room: room.clone(),
                count: count(c),
                ..RawRequirement::default()
            },
            Requirement::Absent { label, room } => RawRequirement {
                absent: Some(label.clone()),
                room: room.clone(),
                ..RawRequirement::default()
            },
            Requirement::Room { label, count: c } => RawRequirement {
                room: Some(label.clone()),
                count: count(c),
                ..RawRequirement::default()
            },
        }
    }
}

impl Serialize for Requirement {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        RawRequirement::from(self).serialize(s)
    }
}

impl<'de> Deserialize<'de> for Requirement {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Requirement, D::Error> {
        let raw = RawRequirement::deserialize(d)?;
        Requirement::try_from(raw).map_err(serde::de::Error::custom)
    }
}

/// A requirements file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum RequirementsError {
    /// A line of a JSON Lines file (1-based).
    #[error("line {line}: {reason}")]
    Line {
        /// Line number, from 1.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// An element of a JSON array of requirements (1-based).
    #[error("requirement {index}: {reason}")]
    Item {
        /// Position in the array, from 1.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// A JSON value that is not an array of requirements.
    #[error("expected a JSON array of requirements, found {0}")]
    NotAnArray(&'static str),
    /// Nothing but blank lines and comments.
    #[error("no requirements: every line is blank or a comment")]
    Empty,
}

/// serde_json's message without its " at line L column C" tail: one line holds one
/// requirement, so the caller names the line itself.
fn json_reason(e: &serde_json::Error) -> String {
    let text = e.to_string();
    let tail = format!(" at line {} column {}", e.line(), e.column());
    text.strip_suffix(&tail).unwrap_or(&text).to_string()
}

fn json_kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    }
}

fn is_comment_or_blank(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with("//") || t.starts_with('#')
}

/// Parses a requirements file: JSON Lines, one requirement per non-blank line, lines starting
/// with `//` or `#` are comments. A file whose first non-comment line starts with `[` is read
/// as one JSON array of requirements instead. At least one requirement is needed.
pub fn parse_requirements(text: &str) -> Result<Vec<Requirement>, RequirementsError> {
    let first = text
        .lines()
        .enumerate()
        .find(|(_, l)| !is_comment_or_blank(l));
    let Some((first_line, first_text)) = first else {
        return Err(RequirementsError::Empty);
    };
    if first_text.trim_start().starts_with('[') {
        let rest: String = text.lines().skip(first_line).collect::<Vec<_>>().join("\n");
        let value: serde_json::Value =
            serde_json::from_str(&rest).map_err(|e| RequirementsError::Line {
                line: first_line + e.line(),
                reason: json_reason(&e),
            })?;
        let reqs = requirements_from_value(&value)?;
        if reqs.is_empty() {
            return Err(RequirementsError::Empty);
        }
        return Ok(reqs);
    }
    let mut reqs = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if is_comment_or_blank(line) {
            continue;
        }
        let r = serde_json::from_str::<Requirement>(line.trim()).map_err(|e| {
            RequirementsError::Line {
                line: i + 1,
                reason: json_reason(&e),
            }
        })?;
        reqs.push(r);
    }
    Ok(reqs)
}

/// Requirements held in a JSON value (an array of requirement objects), e.g. a list per prompt
/// inside a test fixture. An empty array gives no requirements.
pub fn requirements_from_value(
    value: &serde_json::Value,
) -> Result<Vec<Requirement>, RequirementsError> {
    let items = value
        .as_array()
        .ok_or_else(|| RequirementsError::NotAnArray(json_kind(value)))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            Requirement::deserialize(item).map_err(|e| RequirementsError::Item {
                index: i + 1,
                reason: json_reason(&e),
            })
        })
        .collect()
}

/// A label as compared: lower case, `_` and `-` read as spaces, runs of spaces collapsed, the
/// last word in the singular ("Dining_Chairs" -> "dining chair").
pub fn normalize_label(text: &str) -> String {
    // "ship's wheel" reads as "ship wheel", as the prompt reader reads it.
    let lower = text
        .to_lowercase()
        .replace(['\u{2019}'], "'")
        .replace("'s ", " ")
        .replace(['_', '-', '\''], " ");
    let mut words: Vec<String> = lower.split_whitespace().map(str::to_string).collect();
    if let Some(last) = words.last_mut() {
        *last = crate::prompt::singular(last);
    }
    words.join(" ")
}

/// A label read for matching: its normal form, the lexicon's canonical noun for it, and the
/// canonical nouns of every broader kind it is (`dining chair` -> `chair` -> `seating`).
#[derive(Debug)]
struct Noun {
    normal: String,
    canonical: String,
    broader: BTreeSet<String>,
}

impl Noun {
    fn read(text: &str) -> Noun {
        let lex = lexicon();
        let normal = normalize_label(text);
        let raw = text.trim().to_lowercase();
        // "t-shirt" is listed with its hyphen; the normal form drops it.
        let entry = lex.lookup(&normal).or_else(|| lex.lookup(&raw));
        let canonical = entry.map_or_else(|| normal.clone(), |e| e.noun.clone());
        let mut broader = BTreeSet::new();
        let mut next = entry.and_then(|e| e.kind_of.clone());
        while let Some(kind) = next {
            let e = lex.lookup(&kind);
            let noun = e.map_or_else(|| normalize_label(&kind), |e| e.noun.clone());
            // A cycle in the data ends the walk instead of looping.
            if noun == canonical || !broader.insert(noun) {
                break;
            }
            next = e.and_then(|e| e.kind_of.clone());
        }
        // A compound the lexicon does not list is a kind of its head noun: a "clawfoot tub"
        // is a tub, and a tub a bathtub.
        if entry.is_none()
            && let Some((_, last)) = normal.rsplit_once(' ')
        {
            let head = Noun::read(last);
            broader.insert(head.canonical);
            broader.extend(head.broader);
        }
        Noun {
            normal,
            canonical,
            broader,
        }
    }

    /// An object called `self` meets a requirement for `label`: the same words, the same
    /// lexicon entry, a narrower kind of it, or a compound whose head is the label (a
    /// "bentwood chair" is a "chair").
    fn is_a(&self, label: &Noun) -> bool {
        self.normal == label.normal
            || self.canonical == label.canonical
            || self.broader.contains(&label.canonical)
            || self.normal.ends_with(&format!(" {}", label.normal))
    }
}

/// Whether an object called `name` meets an object requirement for `label` (the rule of
/// [`object_matches`], on names alone).
pub fn name_meets(label: &str, name: &str) -> bool {
    Noun::read(name).is_a(&Noun::read(label))
}

/// Whether `object` meets an object requirement for `label`: its category or its prompt
/// `name` normalises to the label, names the same lexicon entry ("couch" and "sofa"), or is a
/// narrower kind of it through the lexicon's `kind_of` chain (a "dining chair" is a "chair";
/// a plain "chair" is not a "dining chair"). Architecture never matches.
pub fn object_matches(label: &str, object: &SceneObject) -> bool {
    object_matches_noun(&Noun::read(label), object)
}

fn object_matches_noun(label: &Noun, object: &SceneObject) -> bool {
    object.kind != ObjectKind::Architecture
        && std::iter::once(&object.category)
            .chain(object.name.as_ref())
            .any(|n| Noun::read(n).is_a(label))
}

/// The knowledge base's room type a label names ("examination room" -> `exam_room`), read as
/// written, in normal form, or as a type key.
fn room_type_key(text: &str) -> Option<String> {
    let kb = knowledge();
    let raw = text.trim().to_lowercase();
    let normal = normalize_label(text);
    if let Some(k) = kb.room_type_of(&raw).or_else(|| kb.room_type_of(&normal)) {
        return Some(k.to_string());
    }
    let key = normal.replace(' ', "_");
    kb.room(&key).map(|_| key)
}

/// Whether `room` meets a room requirement for `label`: its room type or its prompt `label`
/// normalises to the label, or both name the same room type of the knowledge base ("exam
/// room", "examination room" and `exam_room`).
pub fn room_matches(label: &str, room: &Room) -> bool {
    room_name_meets(label, &room.room_type, false)
        || room
            .label
            .as_ref()
            .is_some_and(|l| room_name_meets(label, l, true))
}

/// Whether a room called `name` (its type key, or its label when `label_words`) meets a room
/// requirement for `label`: the same words, the same room type, or a label whose head is the
/// requirement (a "teenager bedroom" is a "bedroom"; type keys such as `living_kitchen` are
/// no compounds).
pub fn room_name_meets(label: &str, name: &str, label_words: bool) -> bool {
    let normal = normalize_label(label);
    let key = room_type_key(label);
    let mut n = normalize_label(name);
    // One of several rooms of a kind is numbered ("dormitory 2"): a dormitory.
    if label_words
        && let Some((head, number)) = n.rsplit_once(' ')
        && number.chars().all(|c| c.is_ascii_digit())
    {
        n = head.to_string();
    }
    // "kitchen-diner" is a kitchen.
    let raw = name.trim().to_lowercase();
    let hyphen_part = label_words
        && !normal.contains(' ')
        && raw.contains('-')
        && raw
            .split(['-', ' '])
            .any(|p| crate::prompt::singular(p) == normal);
    n == normal
        || label_words && n.ends_with(&format!(" {normal}"))
        || hyphen_part
        || key.is_some() && room_type_key(name) == key
}

/// One requirement and what the scene has.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RequirementResult {
    /// The requirement as written.
    pub requirement: Requirement,
    /// Objects (object and absent requirements) or rooms (room requirements) that match.
    pub found: usize,
    /// Their ids, in scene order.
    pub ids: Vec<String>,
    /// Met.
    pub met: bool,
    /// Why nothing could be found, when the reason is not the scene's content (no room
    /// matches the room label).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// Met out of total.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Tally {
    /// Requirements met.
    pub met: usize,
    /// Requirements.
    pub total: usize,
}

impl Tally {
    fn add(&mut self, met: bool) {
        self.total += 1;
        self.met += usize::from(met);
    }

    /// Percent met (`None` without requirements).
    pub fn percent(&self) -> Option<f64> {
        (self.total > 0).then(|| 100.0 * self.met as f64 / self.total as f64)
    }
}

/// Totals per kind of requirement.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RequirementsSummary {
    /// Object count requirements: the label-based count score.
    pub objects: Tally,
    /// Absence requirements.
    pub absents: Tally,
    /// Room count requirements.
    pub rooms: Tally,
    /// Every requirement.
    pub all: Tally,
}

/// A scene scored against requirements (`requirements_report.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RequirementsReport {
    /// [`REQUIREMENTS_REPORT_VERSION`].
    pub version: u32,
    /// The scene's prompt, for the reader of the report.
    pub prompt: String,
    /// One row per requirement, in file order.
    pub rows: Vec<RequirementResult>,
    /// Totals.
    pub summary: RequirementsSummary,
}

/// Objects that may count for a requirement restricted to rooms matching `room`, or a note
/// when no room matches.
fn candidates<'a>(scene: &'a Scene, room: Option<&str>) -> (Vec<&'a SceneObject>, Option<String>) {
    let all = scene
        .objects
        .iter()
        .filter(|o| o.kind != ObjectKind::Architecture);
    let Some(room) = room else {
        return (all.collect(), None);
    };
    let rooms: BTreeSet<&str> = scene
        .rooms
        .iter()
        .filter(|r| room_matches(room, r))
        .map(|r| r.id.as_str())
        .collect();
    let note = rooms
        .is_empty()
        .then(|| format!("no room matches {room:?}"));
    (
        all.filter(|o| rooms.contains(o.room.as_str())).collect(),
        note,
    )
}

/// Scores `scene` against `reqs`. Architecture objects never count.
pub fn score(scene: &Scene, reqs: &[Requirement]) -> RequirementsReport {
    let mut summary = RequirementsSummary::default();
    let mut rows = Vec::with_capacity(reqs.len());
    for req in reqs {
        let (ids, note, met) = match req {
            Requirement::Object { label, count, room } => {
                let (ids, note) = matching_objects(scene, label, room.as_deref());
                let met = count.met_by(ids.len());
                summary.objects.add(met);
                (ids, note, met)
            }
            Requirement::Absent { label, room } => {
                let (ids, note) = matching_objects(scene, label, room.as_deref());
                let met = ids.is_empty();
                summary.absents.add(met);
                (ids, note, met)
            }
            Requirement::Room { label, count } => {
                let ids: Vec<String> = scene
                    .rooms
                    .iter()
                    .filter(|r| room_matches(label, r))
                    .map(|r| r.id.clone())
                    .collect();
                let met = count.met_by(ids.len());
                summary.rooms.add(met);
                (ids, None, met)
            }
        };
        summary.all.add(met);
        rows.push(RequirementResult {
            requirement: req.clone(),
            found: ids.len(),
            ids,
            met,
            note,
        });
    }
    RequirementsReport {
        version: REQUIREMENTS_REPORT_VERSION,
        prompt: scene.provenance.prompt.clone(),
        rows,
        summary,
    }
}

fn matching_objects(
    scene: &Scene,
    label: &str,
    room: Option<&str>,
) -> (Vec<String>, Option<String>) {
    let noun = Noun::read(label);
    let (objects, note) = candidates(scene, room);
    let ids = objects
        .into_iter()
        .filter(|o| object_matches_noun(&noun, o))
        .map(|o| o.id.clone())
        .collect();
    (ids, note)
}

/// Writes `requirements_report.json` into `dir` atomically.
pub fn write_report(dir: &Path, report: &RequirementsReport) -> Result<(), EvalError> {
    let path = dir.join(REQUIREMENTS_REPORT_JSON);
    let mut text = serde_json::to_string_pretty(report).map_err(|e| FormatError::SceneJson {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    text.push('\n');
    crate::util::fsx::write_scene_file(dir, REQUIREMENTS_REPORT_JSON, text.as_bytes())
        .map_err(FormatError::from)?;
    Ok(())
}

fn found_text(row: &RequirementResult) -> String {
    let mut s = row.found.to_string();
    if !row.ids.is_empty() {
        let shown: Vec<&str> = row.ids.iter().take(IDS_SHOWN).map(String::as_str).collect();
        let _ = write!(s, ": {}", shown.join(", "));
        if row.ids.len() > IDS_SHOWN {
            let _ = write!(s, ", +{} more", row.ids.len() - IDS_SHOWN);
        }
    }
    if let Some(note) = &row.note {
        let _ = write!(s, " ({note})");
    }
    s
}

fn tally_text(t: &Tally) -> String {
    match t.percent() {
        Some(p) => format!("{} / {} met ({p:.0} %)", t.met, t.total),
        None => "none".into(),
    }
}

/// The report as a text table (requirement, found, met) and its summary.
pub fn table(report: &RequirementsReport) -> String {
    let mut rows: Vec<[String; 3]> = vec![["requirement".into(), "found".into(), "met".into()]];
    for r in &report.rows {
        rows.push([
            r.requirement.to_string(),
            found_text(r),
            if r.met { "yes" } else { "no" }.into(),
        ]);
    }
    let w0 = rows.iter().map(|r| r[0].chars().count()).max().unwrap_or(0);
    let w1 = rows.iter().map(|r| r[1].chars().count()).max().unwrap_or(0);
    let mut out = String::new();
    for [a, b, c] in &rows {
        let _ = writeln!(out, "  {a:<w0$}  {b:<w1$}  {c}");
    }
    let s = &report.summary;
    let _ = writeln!(
        out,
        "  objects  {}, the label-based count score",
        tally_text(&s.objects)
    );
    let _ = writeln!(out, "  absents  {}", tally_text(&s.absents));
    let _ = writeln!(out, "  rooms    {}", tally_text(&s.rooms));
    let _ = writeln!(out, "  all      {}", tally_text(&s.all));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Pose, Support};

    fn object(id: &str, category: &str, room: &str) -> SceneObject {
        SceneObject {
            id: id.into(),
            category: category.into(),
            name: None,
            planned: None,
            kind: ObjectKind::Furniture,
            room: room.into(),
            asset: "a".into(),
            world_from_object: Pose::IDENTITY,
            support: Support::World,
            welded: false,
            joint_positions: Default::default(),
        }
    }

    fn room(id: &str, room_type: &str) -> Room {
        Room {
            id: id.into(),
            room_type: room_type.into(),
            label: None,
            prompt: String::new(),
            floor_polygon: vec![],
            wall_height: 2.5,
            walls: vec![],
            floor_material: "wood".into(),
            wall_material: "plaster".into(),
        }
    }

    /// A living room and a bedroom: a sofa, three dining chairs, a plain chair, a TV in the
    /// living room, seven books, and the rooms' architecture.
    fn scene() -> Scene {
        let mut s = Scene::new("a small flat", 0, "t");
        s.rooms.push(room("living_room_0", "living_room"));
        s.rooms.push(room("bedroom_0", "bedroom"));
        for (id, cat, r) in [
            (
                "living_room_0_architecture",
                "room_architecture",
                "living_room_0",
            ),
            ("bedroom_0_architecture", "room_architecture", "bedroom_0"),
            ("sofa_0", "sofa", "living_room_0"),
            ("dining_chair_0", "dining_chair", "living_room_0"),
            ("dining_chair_1", "dining_chair", "living_room_0"),
            ("dining_chair_2", "dining_chair", "living_room_0"),
            ("chair_0", "chair", "bedroom_0"),
            ("tv_0", "tv", "living_room_0"),
        ] {
            s.objects.push(object(id, cat, r));
        }
        for i in 0..7 {
            s.objects
                .push(object(&format!("book_{i}"), "book", "bedroom_0"));
        }
        for o in s
            .objects
            .iter_mut()
            .filter(|o| o.category == "room_architecture")
        {
            o.kind = ObjectKind::Architecture;
        }
        s
    }

    fn one(line: &str) -> Requirement {
        let r = parse_requirements(line).unwrap_or_else(|e| panic!("{line}: {e}"));
        assert_eq!(r.len(), 1);
        r.into_iter().next().expect("one requirement")
    }

    fn line_error(text: &str) -> (usize, String) {
        match parse_requirements(text) {
            Err(RequirementsError::Line { line, reason }) => (line, reason),
            other => panic!("{text}: expected a line error, got {other:?}"),
        }
    }

    fn found(s: &Scene, line: &str) -> (usize, bool) {
        let r = score(s, &[one(line)]);
        (r.rows[0].found, r.rows[0].met)
    }

    #[test]
    fn every_count_operator_parses_and_counts() {
        let cases: [(&str, CountOp, [bool; 4]); 9] = [
            // met by 0, 1, 2, 3
            ("=2", CountOp::Eq(2), [false, false, true, false]),
            (">=2", CountOp::Ge(2), [false, false, true, true]),
            ("<=1", CountOp::Le(1), [true, true, false, false]),
            (">1", CountOp::Gt(1), [false, false, true, true]),
            ("<2", CountOp::Lt(2), [true, true, false, false]),
            ("several", CountOp::Several, [false, false, true, true]),
            ("Several", CountOp::Several, [false, false, true, true]),
            ("3", CountOp::Eq(3), [false, false, false, true]),
            (" >= 2 ", CountOp::Ge(2), [false, false, true, true]),
        ];
        for (text, op, met) in cases {
            assert_eq!(CountOp::parse(text), Ok(op), "{text}");
            for (n, m) in met.iter().enumerate() {
                assert_eq!(op.met_by(n), *m, "{text} with {n}");
            }
        }
        for bad in ["", "~2", "=-1", ">=two", "= 2.5", "<0", "several2"] {
            assert!(CountOp::parse(bad).is_err(), "{bad:?} parsed");
        }
        // A JSON number is an exact count; the written form round-trips.
        assert_eq!(
            one(r#"{"object": "chair", "count": 4}"#),
            one(r#"{"object": "chair", "count": "=4"}"#)
        );
        for op in ["=2", ">=2", "<=2", ">2", "<2", "several"] {
            assert_eq!(
                CountOp::parse(&CountOp::parse(op).unwrap().to_string()),
                CountOp::parse(op)
            );
        }
    }

    #[test]
    fn the_three_shapes_parse_and_serialise_as_written() {
        let text = r#"
# comment
// another comment

{"object": "chair", "count": ">=4", "room": "kitchen"}
{"absent": "tv"}
{"absent": "tv", "room": "bedroom"}
{"room": "bedroom", "count": "several"}
"#;
        let reqs = parse_requirements(text).unwrap();
        assert_eq!(
            reqs,
            vec![
                Requirement::Object {
                    label: "chair".into(),
                    count: CountOp::Ge(4),
                    room: Some("kitchen".into())
                },
                Requirement::Absent {
                    label: "tv".into(),
                    room: None
                },
                Requirement::Absent {
                    label: "tv".into(),
                    room: Some("bedroom".into())
                },
                Requirement::Room {
                    label: "bedroom".into(),
                    count: CountOp::Several
                },
            ]
        );
        let json = serde_json::to_value(&reqs).unwrap();
        assert_eq!(
            json[0],
            serde_json::json!({"object": "chair", "room": "kitchen", "count": ">=4"})
        );
        assert_eq!(json[1], serde_json::json!({"absent": "tv"}));
        assert_eq!(requirements_from_value(&json).unwrap(), reqs);
        assert_eq!(
            reqs[0].to_string(),
            r#"object "chair" >=4 in room "kitchen""#
        );
    }

    #[test]
    fn a_bad_line_is_named_with_its_number_and_reason() {
        let prefix = "# header\n{\"absent\": \"tv\"}\n\n";
        for (bad, says) in [
            (r#"{"object": "chair"}"#, "\"count\" is missing"),
            (r#"{"object": "chair", "count": "~3"}"#, "\"count\" must be"),
            (r#"{"object": "chair", "count": -1}"#, "whole number"),
            (
                r#"{"object": "chair", "count": [2]}"#,
                "\"count\" must be a string",
            ),
            (
                r#"{"objects": "chair", "count": "=1"}"#,
                "unknown field `objects`",
            ),
            (r#"{"object": "chair", "absent": "tv"}"#, "both"),
            (r#"{"absent": "tv", "count": "=0"}"#, "no \"count\""),
            (r#"{"room": "kitchen"}"#, "\"count\" is missing"),
            (r#"{"count": "=1"}"#, "needs \"object\""),
            (r#"{"object": " _ ", "count": "=1"}"#, "\"object\" is empty"),
            (r#"{"object": 3, "count": "=1"}"#, "invalid type"),
            (r#"{"object": "chair", "count": "=1""#, "EOF"),
            ("chair >= 2", "expected"),
            ("[1, 2]", "expected"),
        ] {
            let (line, reason) = line_error(&format!("{prefix}{bad}\n"));
            assert_eq!(line, 4, "{bad}: {reason}");
            assert!(reason.contains(says), "{bad}: {reason:?} lacks {says:?}");
            assert!(!reason.contains("at line 1"), "{reason}");
        }
        let shown = parse_requirements("\n{\"room\": 1}")
            .unwrap_err()
            .to_string();
        assert!(shown.starts_with("line 2: "), "{shown}");
        assert!(matches!(
            parse_requirements("# nothing\n\n// here\n"),
            Err(RequirementsError::Empty)
        ));
    }

    #[test]
    fn an_embedded_array_reads_like_the_lines() {
        let v = serde_json::json!([
            {"object": "couch", "count": "=1"},
            {"room": "bedroom", "count": ">=1"}
        ]);
        let reqs = requirements_from_value(&v).unwrap();
        assert_eq!(reqs.len(), 2);
        assert!(
            requirements_from_value(&serde_json::json!([]))
                .unwrap()
                .is_empty()
        );
        let bad = serde_json::json!([{"absent": "tv"}, {"absent": "tv", "colour": "red"}]);
        match requirements_from_value(&bad) {
            Err(RequirementsError::Item { index: 2, reason }) => {
                assert!(reason.contains("unknown field `colour`"), "{reason}")
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            requirements_from_value(&serde_json::json!({"absent": "tv"})),
            Err(RequirementsError::NotAnArray("an object"))
        ));
        // A file holding one array, after comment lines; a syntax error names the file line.
        let file = "# per prompt\n[\n  {\"object\": \"couch\", \"count\": \"=1\"},\n  {\"room\": \"bedroom\", \"count\": \">=1\"}\n]\n";
        assert_eq!(parse_requirements(file).unwrap(), reqs);
        let (line, _) =
            line_error("# per prompt\n[\n  {\"absent\": \"tv\"},\n  {\"absent\" \"tv\"}\n]\n");
        assert_eq!(line, 4);
        assert!(matches!(
            parse_requirements("[]"),
            Err(RequirementsError::Empty)
        ));
    }

    #[test]
    fn labels_are_normalised() {
        assert_eq!(normalize_label("  Dining_Chairs "), "dining chair");
        assert_eq!(normalize_label("coffee-tables"), "coffee table");
        assert_eq!(normalize_label("EXAM   ROOMS"), "exam room");
        let s = scene();
        assert_eq!(
            found(&s, r#"{"object": "Dining Chairs", "count": "=3"}"#),
            (3, true)
        );
        assert_eq!(
            found(&s, r#"{"object": "BOOKS", "count": "several"}"#),
            (7, true)
        );
    }

    #[test]
    fn synonyms_name_the_same_entry() {
        let s = scene();
        // "couch" is the lexicon's synonym of the sofa; "television" of the tv.
        assert_eq!(
            found(&s, r#"{"object": "couch", "count": "=1"}"#),
            (1, true)
        );
        assert_eq!(
            found(&s, r#"{"object": "television", "count": "=1"}"#),
            (1, true)
        );
        // A prompt name on the object counts too.
        let mut s = s;
        s.objects.push(SceneObject {
            name: Some("treasure chest".into()),
            planned: None,
            ..object("box_0", "box", "bedroom_0")
        });
        assert_eq!(
            found(&s, r#"{"object": "treasure chest", "count": "=1"}"#),
            (1, true)
        );
        assert_eq!(found(&s, r#"{"object": "box", "count": "=1"}"#), (1, true));
    }

    #[test]
    fn a_narrower_kind_meets_the_broader_label_not_the_other_way() {
        let s = scene();
        let r = score(&s, &[one(r#"{"object": "chair", "count": "=4"}"#)]);
        assert!(r.rows[0].met, "{:?}", r.rows[0]);
        assert_eq!(
            r.rows[0].ids,
            [
                "dining_chair_0",
                "dining_chair_1",
                "dining_chair_2",
                "chair_0"
            ]
        );
        // The plain chair is not a dining chair.
        assert_eq!(
            found(&s, r#"{"object": "dining chair", "count": "=4"}"#),
            (3, false)
        );
        // "kitchen chair" is a synonym of "dining chair".
        assert_eq!(
            found(&s, r#"{"object": "kitchen chairs", "count": ">2"}"#),
            (3, true)
        );
    }

    #[test]
    fn a_compound_the_lexicon_lacks_is_a_kind_of_its_head() {
        // "tub" is a synonym of "bathtub"; the lexicon does not list "clawfoot tub".
        assert!(name_meets("bathtub", "clawfoot_tub"));
        assert!(name_meets("tub", "clawfoot tub"));
        // Not the other way, and not through a word before the head.
        assert!(!name_meets("clawfoot tub", "bathtub"));
        assert!(!name_meets("bathtub", "tub brush"));
    }

    #[test]
    fn absent_and_room_restrictions() {
        let s = scene();
        let r = score(
            &s,
            &[
                one(r#"{"absent": "tv"}"#),
                one(r#"{"absent": "tv", "room": "bedroom"}"#),
                one(r#"{"object": "chair", "count": "=1", "room": "bedroom"}"#),
                one(r#"{"object": "sofa", "count": "=1", "room": "family room"}"#),
                one(r#"{"object": "sofa", "count": "=1", "room": "kitchen"}"#),
                one(r#"{"absent": "bathtub"}"#),
            ],
        );
        let met: Vec<bool> = r.rows.iter().map(|x| x.met).collect();
        assert_eq!(met, [false, true, true, true, false, true]);
        assert_eq!(r.rows[0].ids, ["tv_0"]);
        assert_eq!(
            r.rows[4].note.as_deref(),
            Some("no room matches \"kitchen\"")
        );
        assert_eq!(r.summary.absents, Tally { met: 2, total: 3 });
        assert_eq!(r.summary.objects, Tally { met: 2, total: 3 });
        assert_eq!(r.summary.all, Tally { met: 4, total: 6 });
        assert_eq!(r.summary.rooms, Tally::default());
    }

    #[test]
    fn rooms_match_by_type_label_and_knowledge_words() {
        let mut s = scene();
        s.rooms.push(room("exam_room_0", "exam_room"));
        s.rooms.push(Room {
            label: Some("master bedroom".into()),
            ..room("bedroom_1", "bedroom")
        });
        // One of several rooms of a kind, numbered.
        s.rooms.push(Room {
            label: Some("bunk room 2".into()),
            ..room("dorm_room_1", "dorm_room")
        });
        for (line, want) in [
            (r#"{"room": "bunk room", "count": "=1"}"#, (1, true)),
            (r#"{"room": "exam room", "count": "=1"}"#, (1, true)),
            (r#"{"room": "Examination Rooms", "count": "=1"}"#, (1, true)),
            (r#"{"room": "exam_room", "count": "=1"}"#, (1, true)),
            (r#"{"room": "bedrooms", "count": "=2"}"#, (2, true)),
            (r#"{"room": "master bedroom", "count": "=1"}"#, (1, true)),
            (r#"{"room": "sitting room", "count": "=1"}"#, (1, true)),
            (r#"{"room": "kitchen", "count": ">=1"}"#, (0, false)),
        ] {
            assert_eq!(found(&s, line), want, "{line}");
        }
        let r = score(&s, &[one(r#"{"room": "bedroom", "count": "=2"}"#)]);
        assert_eq!(r.rows[0].ids, ["bedroom_0", "bedroom_1"]);
        assert_eq!(r.summary.rooms, Tally { met: 1, total: 1 });
    }

    #[test]
    fn architecture_never_counts() {
        let s = scene();
        assert_eq!(
            found(&s, r#"{"object": "room architecture", "count": "=0"}"#),
            (0, true)
        );
        assert_eq!(found(&s, r#"{"absent": "room_architecture"}"#), (0, true));
        let all: usize = score(&s, &[one(r#"{"object": "book", "count": ">=0"}"#)]).rows[0].found;
        assert_eq!(all, 7);
    }

    #[test]
    fn the_table_shows_five_ids_and_the_summary() {
        let s = scene();
        let r = score(
            &s,
            &[
                one(r#"{"object": "book", "count": "=7"}"#),
                one(r#"{"absent": "sofa"}"#),
                one(r#"{"room": "bedroom", "count": "=1"}"#),
            ],
        );
        let t = table(&r);
        assert!(
            t.contains("7: book_0, book_1, book_2, book_3, book_4, +2 more"),
            "{t}"
        );
        assert!(t.contains(r#"absent "sofa""#), "{t}");
        assert!(t.contains("1: sofa_0"), "{t}");
        assert!(
            t.contains("objects  1 / 1 met (100 %), the label-based count score"),
            "{t}"
        );
        assert!(t.contains("absents  0 / 1 met (0 %)"), "{t}");
        assert!(t.contains("all      2 / 3 met (67 %)"), "{t}");
        let lines: Vec<&str> = t.lines().collect();
        assert!(lines[1].ends_with("yes") && lines[2].ends_with("no"), "{t}");
    }
}
