//! Reading a prompt: one room or a house of rooms; per room the objects with counts,
//! attributes (colours, materials, styles, themes) and spatial relations; what is excluded;
//! how full the room should look.
//!
//! This is the deterministic reader the built-in designer relies on. Vocabulary is data
//! (`src/data/lexicon/*.json`, room words from `src/data/knowledge/`), so adding a noun or a
//! phrase is a data change. The reader does not decide what a room gets beyond what the prompt
//! says; the room plans (`plan`) merge a reading with the room type's knowledge.
//!
//! Pipeline: [`crate::words::tokens`] (words with spans and punctuation) -> `chunk` (noun phrases,
//! prepositions, verbs) -> [`rooms`] (house structure from the first sentence) -> `interpret`
//! (clauses: subjects, holders, per-parent counts, references, relations) -> [`Reading`].

pub mod attributes;
mod chunk;
mod interpret;
pub mod mentions;
mod phrase;
pub mod relations;
pub mod report;
pub mod rooms;

use serde::{Deserialize, Serialize};

pub use attributes::Attributes;
pub use mentions::{Count, Group, GroupKind, Mention, Per};
pub use relations::{Relation, RelationKind, Target};
pub use report::{NounReport, NounStatus};
pub use rooms::{Density, RoomReading, Scope};

use crate::knowledge::knowledge;
use crate::words::{Lexicon, Support, lexicon, tokens};

/// A floor thing that carries things or is sat or slept on, by the lexicon: no other piece
/// carries it, and it is "in" only a container ("tattoo chairs sit in curtained-off stations":
/// a chair is at a station, not on it).
pub(crate) fn piece_of_furniture(lex: &Lexicon, noun: &str) -> bool {
    let Some(e) = lex.lookup(noun) else {
        return false;
    };
    if e.support != Support::Floor {
        return false;
    }
    e.holds || lex.is_kind(noun, "seating") || lex.is_kind(noun, "bed")
}

/// What the reader took from a prompt.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reading {
    /// Room-type key of the (first) room (see `src/data/knowledge/`); `room` when nothing
    /// matched.
    pub room_type: String,
    /// Size factor from words such as "small" (0.8) or "large" (1.3).
    pub size_scale: f64,
    /// Named objects in prompt order, all rooms (see `Mention::room`).
    pub mentions: Vec<Mention>,
    /// One room or a house.
    pub scope: Scope,
    /// The rooms (exactly one for a single-room prompt).
    pub rooms: Vec<RoomReading>,
    /// What the house is ("dental office", "boutique hotel"), for houses.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub house_type: Option<String>,
    /// Styles and themes of the whole prompt.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub styles: Vec<String>,
    /// Density of the whole prompt.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<Density>,
    /// Every noun read and what became of it, in prompt order, once per noun.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nouns: Vec<NounReport>,
    /// What the reader capped or could not do, in words for the user ("40 offices asked
    /// for, 20 built: ...").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// Share of the prompt's words that are English function words ("the", "with", "on"):
    /// about 0.3-0.5 in English prose, near zero in other languages.
    #[serde(default = "one")]
    pub english_share: f64,
}

fn one() -> f64 {
    1.0
}

/// Fewest words before the English share decides anything.
const MIN_WORDS_FOR_LANGUAGE: usize = 6;
/// Below this share of English function words, a prompt is not read as English.
const MIN_ENGLISH_SHARE: f64 = 0.1;

impl Reading {
    /// True when the reader understood something: a room word or an object noun grounded in
    /// the lexicon or WordNet (dropped and unknown words do not count).
    pub fn understood(&self) -> bool {
        self.english_share >= MIN_ENGLISH_SHARE
            && self
                .nouns
                .iter()
                .any(|n| !matches!(n.status, NounStatus::Dropped | NounStatus::Unknown))
    }

    /// What the reader understood, for messages: the nouns it read and what became of them.
    pub fn understanding(&self) -> String {
        if self.english_share < MIN_ENGLISH_SHARE {
            return format!(
                "{:.0} % of its words are English function words",
                100.0 * self.english_share
            );
        }
        if self.nouns.is_empty() {
            return "no noun read".to_string();
        }
        let lines: Vec<String> = self.nouns.iter().take(8).map(NounReport::line).collect();
        format!("read: {}", lines.join(", "))
    }

    /// Indices and mentions of one room.
    pub fn room_mentions(&self, room: usize) -> impl Iterator<Item = (usize, &Mention)> {
        self.mentions
            .iter()
            .enumerate()
            .filter(move |(_, m)| m.room == room)
    }

    /// The total count of mention `i`: a per-parent count times the parent's total, a
    /// per-setting count times the table's settings.
    pub fn total(&self, i: usize) -> Count {
        self.total_depth(i, 0)
    }

    fn total_depth(&self, i: usize, depth: usize) -> Count {
        let Some(m) = self.mentions.get(i) else {
            return Count::Several;
        };
        if depth > 4 {
            return m.count;
        }
        match m.per {
            None => m.count,
            Some(Per::Each { parent }) => m.count.times(self.total_depth(parent, depth + 1)),
            Some(Per::Setting { table }) => {
                let Some(t) = self.mentions.get(table) else {
                    return m.count;
                };
                let settings = Count::Exactly(t.place_settings.unwrap_or(1));
                m.count
                    .times(settings)
                    .times(self.total_depth(table, depth + 1))
            }
        }
    }
}

/// Singular form of an English noun.
pub fn singular(word: &str) -> String {
    lexicon().singular(word)
}

/// Reads a prompt.
pub fn read(prompt: &str) -> Reading {
    let lex = lexicon();
    let kb = knowledge();
    let toks = tokens::lex(prompt);
    let mut chunks: Vec<Vec<chunk::Chunk>> = tokens::sentences(&toks)
        .into_iter()
        .map(|r| chunk::chunk_sentence(lex, kb, &toks, r))
        .collect();
    if let Some(first) = chunks.first_mut() {
        rooms::room_named_by_part(lex, &toks, first);
    }
    let st = rooms::structure(lex, &toks, &chunks);
    // List items read as rooms are rooms for the interpreter too.
    if let Some(list) = st.list_sentence.and_then(|i| chunks.get_mut(i)) {
        for (k, np) in &st.coerced {
            if let Some(c) = list.get_mut(*k) {
                c.item = chunk::Item::Np(Box::new(np.clone()));
            }
        }
        // "A student flat with ...": the words before the list name the building.
        for c in list.iter_mut().take(st.head_chunks) {
            if let chunk::Item::Np(np) = &mut c.item
                && matches!(np.head, chunk::Head::Object { .. })
            {
                np.head = chunk::Head::NonObject;
            }
        }
    }
    if st.scope == Scope::House {
        for sentence in &mut chunks {
            rooms::each_by_head(lex, &st.rooms, sentence);
        }
    }
    let mut it = interpret::Interp::new(lex, &toks, st.rooms.clone(), st.scope);
    // The room list's phrases are rooms; what they hold ("a meeting room with a long table")
    // goes in them.
    for ch in &chunks {
        it.sentence(ch);
    }
    let (mut mentions, mut rooms) = finish(lex, &toks, prompt, it);
    let mut nouns = noun_reports(&chunks);
    senses_in_company(lex, &mut mentions, &mut nouns);
    // Density: strong words anywhere apply to every room; the room phrase's own words too.
    let density = toks
        .iter()
        .filter(|t| t.is_word())
        .find_map(|t| lex.density(&t.text).and_then(Density::from_class))
        .or(st.density);
    for r in &mut rooms {
        if r.density.is_none() {
            r.density = density;
        }
        for s in &st.styles {
            if st.scope == Scope::House && !r.styles.contains(s) {
                r.styles.push(s.clone());
            }
        }
    }
    let room_type = rooms
        .first()
        .map_or_else(|| "room".to_string(), |r| r.room_type.clone());
    let size_scale = match st.scope {
        Scope::Room => rooms.first().map_or(st.size_scale, |r| r.size_scale),
        Scope::House => st.size_scale,
    };
    Reading {
        room_type,
        size_scale,
        mentions,
        scope: st.scope,
        rooms,
        house_type: st.house_type,
        styles: st.styles,
        density,
        nouns,
        notes: st.notes,
        english_share: english_share(lex, &toks),
    }
}

/// Open-vocabulary things whose sense the other things of the prompt choose: "an iron" beside
/// a sewing machine and an ironing board is a smoothing iron, not the golf club the word
/// alone is built as. The mention is renamed to the chosen sense's own lemma, which the asset
/// router grounds the same way, and takes that sense's family (or none: a stand-in).
fn senses_in_company(lex: &Lexicon, mentions: &mut [Mention], nouns: &mut [NounReport]) {
    let mut company: Vec<String> = Vec::new();
    for m in mentions.iter().filter(|m| !m.negated) {
        if !company.contains(&m.category) {
            company.push(m.category.clone());
        }
    }
    let company: Vec<&str> = company.iter().map(String::as_str).collect();
    let known = |n: &str| lex.lookup(n).is_some();
    for m in mentions.iter_mut().filter(|m| !m.known) {
        let Some(sense) = crate::words::ground::sense_in_company(&m.category, &company, &known)
        else {
            continue;
        };
        let entry = sense.family.as_ref().and_then(|f| lex.lookup(&f.noun));
        if m.parent().is_none() {
            m.support = entry.map_or(m.support, |e| e.support);
        }
        m.container = entry.is_some_and(|e| e.container);
        for r in nouns.iter_mut().filter(|r| r.noun == m.category) {
            r.lemma = Some(sense.lemma.clone());
            r.family = entry.map(|e| e.noun.clone());
            r.status = if entry.is_some() {
                NounStatus::Routed
            } else {
                NounStatus::StandIn
            };
            r.reason = Some(format!(
                "read as {} by the things around it{}",
                sense.lemma,
                sense
                    .family
                    .as_ref()
                    .map(|f| format!("; WordNet: {}", f.via.join(" > ")))
                    .unwrap_or_default()
            ));
        }
        m.head = entry.map(|e| e.noun.clone());
        m.category = sense.lemma;
    }
}

/// Share of the words that are English function words (1 for prompts too short to tell).
fn english_share(lex: &Lexicon, toks: &[tokens::Token]) -> f64 {
    let words: Vec<&str> = toks
        .iter()
        .filter(|t| t.kind == tokens::TokenKind::Word)
        .map(|t| t.text.as_str())
        .collect();
    if words.len() < MIN_WORDS_FOR_LANGUAGE {
        return 1.0;
    }
    let function = words.iter().filter(|w| lex.is_function_word(w)).count();
    function as f64 / words.len() as f64
}

/// Every noun phrase head of the prompt and what the reader made of it, once per noun.
fn noun_reports(chunks: &[Vec<chunk::Chunk>]) -> Vec<NounReport> {
    let mut out: Vec<NounReport> = Vec::new();
    for c in chunks.iter().flatten() {
        let chunk::Item::Np(np) = &c.item else {
            continue;
        };
        let r = match (&np.report, &np.head) {
            (Some(r), _) => r.clone(),
            (
                None,
                chunk::Head::Object {
                    entry: Some(_),
                    noun,
                    canonical,
                    ..
                },
            ) => NounReport {
                noun: noun.clone(),
                lemma: None,
                status: NounStatus::Lexicon,
                family: Some(canonical.clone()),
                reason: None,
            },
            (None, chunk::Head::Room { key, words }) => NounReport {
                noun: words.clone(),
                lemma: None,
                status: NounStatus::Room,
                family: Some(key.clone()),
                reason: None,
            },
            _ => continue,
        };
        if !out.iter().any(|o| o.noun == r.noun && o.status == r.status) {
            out.push(r);
        }
    }
    out
}

/// Support overrides, generic covers, merged mentions dropped, room texts.
fn finish(
    lex: &Lexicon,
    toks: &[tokens::Token],
    prompt: &str,
    it: interpret::Interp<'_>,
) -> (Vec<Mention>, Vec<RoomReading>) {
    let interpret::Interp {
        mut mentions,
        absorbed,
        mut rooms,
        spans,
        ..
    } = it;
    // Index remapping: absorbed mentions point at their replacement.
    let n = mentions.len();
    let mut new_index: Vec<Option<usize>> = vec![None; n];
    let mut next = 0;
    for (i, slot) in new_index.iter_mut().enumerate() {
        if absorbed.get(i).is_some_and(Option::is_none) {
            *slot = Some(next);
            next += 1;
        }
    }
    let resolve = |mut i: usize| -> Option<usize> {
        for _ in 0..8 {
            if let Some(j) = new_index.get(i).copied().flatten() {
                return Some(j);
            }
            match absorbed.get(i).copied().flatten().flatten() {
                Some(r) => i = r,
                None => return None,
            }
        }
        None
    };
    for m in &mut mentions {
        m.relations.retain_mut(|r| {
            if let Target::Mention(t) = r.target {
                match resolve(t) {
                    Some(j) => r.target = Target::Mention(j),
                    None => return false,
                }
            }
            if let Some(Target::Mention(t)) = r.second {
                r.second = resolve(t).map(Target::Mention);
            }
            true
        });
        m.per = match m.per {
            Some(Per::Each { parent }) => resolve(parent).map(|parent| Per::Each { parent }),
            Some(Per::Setting { table }) => resolve(table).map(|table| Per::Setting { table }),
            None => None,
        };
    }
    let mut out: Vec<Mention> = mentions
        .into_iter()
        .enumerate()
        .filter(|(i, _)| new_index[*i].is_some())
        .map(|(_, m)| m)
        .collect();
    // Self-references created by merging.
    for (i, m) in out.iter_mut().enumerate() {
        m.relations.retain(|r| r.target != Target::Mention(i));
        if matches!(m.per, Some(Per::Each { parent }) if parent == i) {
            m.per = None;
        }
    }
    // Whether each mention can carry or hold another thing (a table, a shelf, a box; not "a
    // station", a part of the room). `None` for a noun the lexicon does not know: that carries
    // only small things.
    let holders: Vec<Option<(bool, bool)>> = out
        .iter()
        .map(|m| {
            lex.lookup(&m.category)
                .map(|e| (e.holds || e.support == Support::Surface, e.container))
        })
        .collect();
    // Support from relations: on the wall, from the ceiling, on another object, or placed on
    // the floor of the room.
    for m in &mut out {
        let explicit = |k: RelationKind, t: Target| {
            m.relations
                .iter()
                .any(|r| r.kind == k && r.target == t && !r.implied)
        };
        let mounted = m
            .attributes
            .adjectives
            .iter()
            .any(|a| a == "wall-mounted" || a == "mounted");
        if m.relations.iter().any(|r| r.kind == RelationKind::Hanging) {
            m.support = Support::Ceiling;
        } else if explicit(RelationKind::On, Target::Wall) || mounted {
            m.support = Support::Wall;
        } else if m.relations.iter().any(|r| {
            r.is_support()
                && r.kind != RelationKind::With
                && r.target.mention().is_none_or(|t| {
                    let small = || !piece_of_furniture(lex, &m.category);
                    match holders.get(t).copied().flatten() {
                        // A big thing is in a container ("a chair in the station" is at it).
                        Some((holds, container)) if r.kind == RelationKind::In => {
                            container || (holds && small())
                        }
                        Some((holds, container)) => holds || container,
                        None => small(),
                    }
                })
        }) && m.support == Support::Floor
        {
            let parent_small = true;
            if parent_small
                && lex
                    .lookup(&m.category)
                    .is_none_or(|e| !e.holds || e.support != Support::Floor)
            {
                m.support = Support::Surface;
            }
        } else if m.support == Support::Surface
            && !m
                .relations
                .iter()
                .any(|r| r.is_support() || r.target == Target::Floor)
            && m.relations.iter().any(|r| {
                !r.implied
                    && matches!(
                        r.target,
                        Target::Wall
                            | Target::Corner
                            | Target::Room
                            | Target::Window
                            | Target::Entrance
                    )
            })
        {
            // "a printer sits in the corner": on the floor.
            m.support = Support::Floor;
        }
    }
    // Generic mentions count their specific kinds in the same place ("at least 6 fruits" in
    // the bowl with the apples and oranges).
    let parents: Vec<Option<usize>> = out.iter().map(Mention::parent).collect();
    for g in 0..out.len() {
        if !out[g].generic {
            continue;
        }
        let cat = out[g].category.clone();
        let covers: Vec<usize> = (0..out.len())
            .filter(|&i| {
                i != g
                    && out[i].room == out[g].room
                    && parents[i] == parents[g]
                    && parents[g].is_some()
            })
            .filter(|&i| {
                let mut k = lex.lookup(&out[i].category).and_then(|e| e.kind_of.clone());
                for _ in 0..3 {
                    match k {
                        Some(ref x) if *x == cat => return true,
                        Some(ref x) => k = lex.lookup(x).and_then(|e| e.kind_of.clone()),
                        None => return false,
                    }
                }
                false
            })
            .collect();
        out[g].covers = covers;
    }
    // Room texts from their token ranges.
    for (i, r) in rooms.iter_mut().enumerate() {
        let mut ranges: Vec<std::ops::Range<usize>> = spans.get(i).cloned().unwrap_or_default();
        ranges.sort_by_key(|r| r.start);
        let mut parts: Vec<(usize, usize)> = Vec::new();
        for rg in ranges {
            if rg.is_empty() || rg.end > toks.len() {
                continue;
            }
            let (a, b) = (toks[rg.start].start, toks[rg.end - 1].end);
            match parts.last_mut() {
                Some(last) if a <= last.1 + 2 => last.1 = last.1.max(b),
                _ => parts.push((a, b)),
            }
        }
        r.text = parts
            .iter()
            .filter_map(|&(a, b)| prompt.get(a..b))
            .collect::<Vec<_>>()
            .join(" ... ");
        if rooms_len_is_one(&spans) {
            r.text = prompt.trim().to_string();
        }
    }
    (out, rooms)
}

fn rooms_len_is_one<T>(spans: &[T]) -> bool {
    spans.len() == 1
}

#[cfg(test)]
mod tests;
