//! Grounding nouns in WordNet: is a word a noun at all, does it name a placeable physical
//! thing (a lamp, an apple, a fern) rather than a feeling, a state or an event ("unease",
//! "tension", "scream"), does it name a room or a building, and which family of things the
//! library can build is its nearest hypernym ("chandelier" -> lighting fixture -> ... a
//! ceiling light; "samovar" -> urn).
//!
//! The rules are data (`src/data/lexicon/grounding.json`: anchor synsets, thresholds); the
//! dictionary is [`super::wordnet`]. This module answers questions about words; it does not
//! read phrases (the prompt reader's `phrase` does) and does not know the asset library:
//! callers say which nouns count as a family through a predicate.

use std::collections::{HashSet, VecDeque};
use std::sync::OnceLock;

use serde::Deserialize;

use super::wordnet::{Pos, SynsetId, wordnet};

#[derive(Debug, Deserialize)]
struct RulesFile {
    object_under: Vec<String>,
    not_object_under: Vec<String>,
    placeable_within: Vec<String>,
    room_under: Vec<String>,
    family_stop: Vec<String>,
    count_smoothing: f64,
    min_share: f64,
    min_share_with_evidence: f64,
    room_space_words: Vec<String>,
    room_part_words: Vec<String>,
    min_room_share: f64,
    depiction_under: Vec<String>,
    building_under: Vec<String>,
    document_under: Vec<String>,
    document_family: String,
    animal_under: Vec<String>,
    dwelling_under: Vec<String>,
}

/// Errors loading the grounding rules.
#[derive(Debug, thiserror::Error)]
pub enum GroundError {
    /// The data file does not parse.
    #[error("lexicon/grounding.json does not parse")]
    Parse(#[source] serde_json::Error),
    /// An anchor names no WordNet synset.
    #[error("lexicon/grounding.json names {0:?}, which is no WordNet noun synset")]
    UnknownSynset(String),
}

/// The grounding rules with their anchor synsets resolved.
#[derive(Debug, Default)]
pub struct Rules {
    object_under: Vec<SynsetId>,
    not_object_under: Vec<SynsetId>,
    placeable_within: Vec<SynsetId>,
    room_under: Vec<SynsetId>,
    family_stop: HashSet<SynsetId>,
    count_smoothing: f64,
    /// Object share from which a noun is an object wherever it heads a phrase.
    pub min_share: f64,
    /// Object share from which a counted or listed noun is an object.
    pub min_share_with_evidence: f64,
    room_space_words: Vec<String>,
    room_part_words: Vec<String>,
    /// Room share from which a word the registry does not know is read as a room.
    pub min_room_share: f64,
    depiction_under: Vec<SynsetId>,
    building_under: Vec<SynsetId>,
    document_under: Vec<SynsetId>,
    /// The family printed matter is built as when no family is near along its hypernyms.
    pub document_family: String,
    animal_under: Vec<SynsetId>,
    dwelling_under: Vec<SynsetId>,
}

impl Rules {
    /// Parses the rules and resolves their synset names.
    pub fn parse(text: &str) -> Result<Rules, GroundError> {
        let f: RulesFile = serde_json::from_str(text).map_err(GroundError::Parse)?;
        let wn = wordnet();
        let resolve = |names: &[String]| -> Result<Vec<SynsetId>, GroundError> {
            names
                .iter()
                .map(|n| {
                    wn.synset(n)
                        .ok_or_else(|| GroundError::UnknownSynset(n.clone()))
                })
                .collect()
        };
        Ok(Rules {
            object_under: resolve(&f.object_under)?,
            not_object_under: resolve(&f.not_object_under)?,
            placeable_within: resolve(&f.placeable_within)?,
            room_under: resolve(&f.room_under)?,
            family_stop: resolve(&f.family_stop)?.into_iter().collect(),
            count_smoothing: f.count_smoothing,
            min_share: f.min_share,
            min_share_with_evidence: f.min_share_with_evidence,
            room_space_words: f.room_space_words,
            room_part_words: f.room_part_words,
            min_room_share: f.min_room_share,
            depiction_under: resolve(&f.depiction_under)?,
            building_under: resolve(&f.building_under)?,
            document_under: resolve(&f.document_under)?,
            document_family: f.document_family,
            animal_under: resolve(&f.animal_under)?,
            dwelling_under: resolve(&f.dwelling_under)?,
        })
    }

    /// True for a word that names the space of a room after its type word ("floor" in
    /// "salon floor").
    pub fn is_room_space_word(&self, word: &str) -> bool {
        self.room_space_words.iter().any(|w| w == word)
    }

    /// True for a word that makes a room of the thing before it ("block" in "toilet block",
    /// "quarters" in "staff quarters").
    pub fn is_room_part_word(&self, word: &str) -> bool {
        self.room_part_words.iter().any(|w| w == word)
    }

    fn under_any(&self, s: SynsetId, anchors: &[SynsetId]) -> bool {
        let wn = wordnet();
        anchors.iter().any(|&a| wn.is_a(s, a))
    }

    /// A sense that names a placeable physical thing.
    pub fn placeable(&self, s: SynsetId) -> bool {
        self.under_any(s, &self.object_under)
            && (self.under_any(s, &self.placeable_within)
                || !self.under_any(s, &self.not_object_under))
    }

    /// A sense that pictures something ("photograph", "painting", "statue", "model"): what
    /// it is "of" is its subject, not a thing in the room.
    pub fn depicts(&self, s: SynsetId) -> bool {
        self.under_any(s, &self.depiction_under)
    }

    /// A sense that names written or printed matter ("logbook", "flyer", "invoice"): in a
    /// room, paper.
    pub fn document(&self, s: SynsetId) -> bool {
        self.under_any(s, &self.document_under)
    }

    /// A sense that names an animal: a thing in the room only where the sentence puts it
    /// there, and built from no family.
    pub fn animal(&self, s: SynsetId) -> bool {
        self.under_any(s, &self.animal_under)
    }

    /// A sense that names a room, a building or a place of business.
    pub fn roomlike(&self, s: SynsetId) -> bool {
        self.under_any(s, &self.room_under) && !self.under_any(s, &self.placeable_within)
    }
}

/// The compiled-in rules. A broken data file yields empty rules (no noun grounds); the unit
/// test `compiled_rules_parse` catches that before it ships.
pub fn rules() -> &'static Rules {
    static RULES: OnceLock<Rules> = OnceLock::new();
    RULES.get_or_init(
        || match Rules::parse(include_str!("../data/lexicon/grounding.json")) {
            Ok(r) => r,
            Err(e) => {
                tracing::error!("{e}");
                Rules::default()
            }
        },
    )
}

/// The WordNet lemma of `words`, else of its last word.
fn lemma_or_last(words: &str) -> Option<String> {
    let last = words.rsplit(' ').next().unwrap_or(words);
    noun_lemma(words).or_else(|| noun_lemma(last))
}

/// Whether some sense of `words` (or of its last word) is a whole building or ship: "vessel"
/// of "the bridge of a research vessel", which is a container too.
pub fn can_be_building(words: &str) -> bool {
    some_sense_under(words, &rules().building_under)
}

/// Whether some sense of `words` (or of its last word) is under one of `anchors`.
fn some_sense_under(words: &str, anchors: &[SynsetId]) -> bool {
    let r = rules();
    lemma_or_last(words).is_some_and(|lemma| {
        wordnet()
            .noun_senses(&lemma)
            .iter()
            .any(|s| r.under_any(s.synset, anchors))
    })
}

/// Whether some sense of `words` (or of its last word) is a dwelling ("house", "flat",
/// "cottage"): "a three-bed cottage" counts bedrooms, "a six-bed ward" beds.
pub fn is_dwelling(words: &str) -> bool {
    some_sense_under(words, &rules().dwelling_under)
}

/// Whether `words` name a room or building more often than not (its room and building
/// senses weigh at least the rules' `min_room_share`).
pub fn is_room_word(words: &str) -> bool {
    noun_info(words).is_some_and(|i| i.room_share >= rules().min_room_share)
}

/// Whether every room-like or physical sense of `words` is a whole building or ship ("hostel",
/// "fire station", "narrowboat"), not a room in one.
pub fn is_building(words: &str) -> bool {
    let wn = wordnet();
    let r = rules();
    let Some(lemma) = lemma_or_last(words) else {
        return false;
    };
    let senses: Vec<SynsetId> = wn
        .noun_senses(&lemma)
        .iter()
        .map(|s| s.synset)
        .filter(|&s| r.roomlike(s) || r.under_any(s, &r.object_under))
        .collect();
    !senses.is_empty() && senses.iter().all(|&s| r.under_any(s, &r.building_under))
}

/// What WordNet says about a noun.
#[derive(Debug, Clone, PartialEq)]
pub struct NounInfo {
    /// The WordNet lemma (base form, words separated by spaces).
    pub lemma: String,
    /// Weight of the placeable senses over all senses, 0..=1.
    pub share: f64,
    /// Placeable senses, heaviest first.
    pub placeable: Vec<SynsetId>,
    /// How many of the first `placeable` senses are the word's usual ones: when WordNet's
    /// concordance tagged the heaviest, those tagged at least [`NEAR_SHARE`] as often as it
    /// ("sack" is a bag; its untagged hammock sense is no usual reading); else all.
    pub usual: usize,
    /// Whether a sense names a room or building.
    pub roomlike: bool,
    /// Weight of the room or building senses over all senses, 0..=1.
    pub room_share: f64,
    /// Lexicographer file of the heaviest sense ("noun.feeling").
    pub lexname: String,
    /// Whether a physical sense is excluded as larger than a room or as the architecture
    /// itself (a building, a ship, a floor).
    pub structure: bool,
    /// Senses that name written or printed matter and no placeable thing, heaviest first
    /// ("logbook": a record book): a sheet or a book where a sentence places one.
    pub documents: Vec<SynsetId>,
}

/// The WordNet noun lemma of a word or multiword phrase ("shelves" -> "shelf"), if it is a
/// noun at all.
pub fn noun_lemma(words: &str) -> Option<String> {
    let wn = wordnet();
    let w = words.trim().to_lowercase();
    if w.is_empty() {
        return None;
    }
    if wn.is_lemma(&w, Pos::Noun) {
        return Some(w);
    }
    // "syringes" is also WordNet's plural of "syrinx": a room prompt names things, so the form
    // most often placeable wins, and of forms about as placeable the more common one
    // ("lenses": lens, not lense).
    let rank = |lemma: &str| {
        let share = noun_info(lemma).map_or(0.0, |i| i.share);
        let count: u32 = wn.noun_senses(lemma).iter().map(|s| s.count).sum();
        (share, count)
    };
    let mut best: Option<(f64, u32, String)> = None;
    for form in wn.base_forms(&w, Pos::Noun) {
        let (share, count) = rank(&form);
        let better = best.as_ref().is_none_or(|(s, c, _)| {
            share > s + NEAR_SHARE || (share > s - NEAR_SHARE && count > *c)
        });
        if better {
            best = Some((share, count, form));
        }
    }
    best.map(|(_, _, form)| form)
}

/// Placeable shares closer than this count as a tie between two base forms of a word.
const NEAR_SHARE: f64 = 0.25;

/// Whether the heaviest placeable sense of `words` pictures something (see
/// [`Rules::depicts`]).
pub fn is_depiction(words: &str) -> bool {
    noun_info(words)
        .and_then(|i| i.placeable.first().copied())
        .is_some_and(|s| rules().depicts(s))
}

/// What WordNet says about the noun `words` (any inflection), if it is a noun.
pub fn noun_info(words: &str) -> Option<NounInfo> {
    let wn = wordnet();
    let r = rules();
    let lemma = noun_lemma(words)?;
    let senses = wn.noun_senses(&lemma);
    if senses.is_empty() {
        return None;
    }
    let mut total = 0.0;
    let mut placed = 0.0;
    let mut placeable: Vec<(f64, usize, SynsetId)> = Vec::new();
    let mut roomlike = false;
    let mut roomed = 0.0;
    let mut heaviest: Option<(f64, SynsetId)> = None;
    let mut structure = false;
    let mut documents: Vec<(f64, usize, SynsetId)> = Vec::new();
    for (rank, s) in senses.iter().enumerate() {
        let w = f64::from(s.count) + r.count_smoothing;
        total += w;
        if r.placeable(s.synset) {
            placed += w;
            placeable.push((w, rank, s.synset));
        } else if r.under_any(s.synset, &r.object_under) {
            structure = true;
        } else if r.document(s.synset) {
            documents.push((w, rank, s.synset));
        }
        if r.roomlike(s.synset) {
            roomlike = true;
            roomed += w;
        }
        if heaviest.is_none_or(|(hw, _)| w > hw) {
            heaviest = Some((w, s.synset));
        }
    }
    placeable.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let top = placeable.first().map_or(0.0, |p| p.0 - r.count_smoothing);
    let usual = if top > 0.0 {
        placeable
            .iter()
            .take_while(|p| p.0 - r.count_smoothing >= NEAR_SHARE * top)
            .count()
    } else {
        placeable.len()
    };
    documents.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    Some(NounInfo {
        lemma,
        share: if total > 0.0 { placed / total } else { 0.0 },
        placeable: placeable.into_iter().map(|(_, _, s)| s).collect(),
        usual,
        roomlike,
        room_share: if total > 0.0 { roomed / total } else { 0.0 },
        lexname: heaviest.map_or_else(String::new, |(_, s)| wn.lexname(s).to_string()),
        structure,
        documents: documents.into_iter().map(|(_, _, s)| s).collect(),
    })
}

/// True when the heaviest placeable sense of `words` is an animal ("cat", "fox", "bee").
pub fn is_animal(words: &str) -> bool {
    noun_info(words)
        .and_then(|i| i.placeable.first().copied())
        .is_some_and(|s| rules().animal(s))
}

/// True when WordNet knows `word` as a noun (any inflection).
pub fn is_noun(word: &str) -> bool {
    wordnet().has_pos(word, Pos::Noun)
}

/// True when WordNet knows `word` as an adjective.
pub fn is_adjective(word: &str) -> bool {
    wordnet().has_pos(word, Pos::Adj)
}

/// The adjective `word` is a form of, by WordNet's morphy ("largest" -> "large", "bigger"
/// -> "big", "best" -> "good"); `None` when it is no adjective.
pub fn adjective_base(word: &str) -> Option<String> {
    wordnet().base_forms(word, Pos::Adj).into_iter().next()
}

/// A comparative or superlative of an adjective ("larger", "biggest", "happier"): WordNet's
/// exception list, else the adjective left when "-er"/"-est" comes off ("large", "big",
/// "happy"). WordNet lists some comparatives as lemmas of their own ("larger").
pub fn is_graded_adjective(word: &str) -> bool {
    if adjective_base(word).is_some_and(|b| b != word) {
        return true;
    }
    let stem = word
        .strip_suffix("est")
        .or_else(|| word.strip_suffix("er"))
        .filter(|s| s.len() >= 2);
    let Some(stem) = stem else {
        return false;
    };
    let mut candidates = vec![stem.to_string(), format!("{stem}e")];
    let b = stem.as_bytes();
    if b.len() >= 3 && b[b.len() - 1] == b[b.len() - 2] {
        candidates.push(stem[..stem.len() - 1].to_string());
    }
    if let Some(s) = stem.strip_suffix('i') {
        candidates.push(format!("{s}y"));
    }
    candidates.iter().any(|c| is_adjective(c))
}

/// The part of speech a word has when it is not a noun ("stylish": adjective, "creating":
/// verb, "dimly": adverb); `None` for nouns and for words WordNet does not know.
pub fn only_other_pos(word: &str) -> Option<&'static str> {
    let wn = wordnet();
    if wn.has_pos(word, Pos::Noun) {
        return None;
    }
    [
        (Pos::Adj, "adjective"),
        (Pos::Verb, "verb"),
        (Pos::Adv, "adverb"),
    ]
    .into_iter()
    .find(|(p, _)| wn.has_pos(word, *p))
    .map(|(_, name)| name)
}

/// True when WordNet knows `word` in any part of speech.
pub fn is_word(word: &str) -> bool {
    let wn = wordnet();
    [Pos::Noun, Pos::Verb, Pos::Adj, Pos::Adv]
        .into_iter()
        .any(|p| wn.has_pos(word, p))
}

/// The verdict on a noun heading a phrase.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// A placeable thing.
    Object,
    /// A placeable thing only when the phrase counts or lists it.
    NeedsEvidence,
    /// Not a placeable thing; the reason names what it is ("feeling", "state").
    NotObject(String),
    /// Rarely a placeable thing ("board": mostly a committee): one only where the sentence
    /// places it; the reason says what it mostly is.
    Rarely(String),
}

/// Whether the noun `words` names a placeable thing.
pub fn verdict(words: &str) -> Verdict {
    let r = rules();
    match noun_info(words) {
        None => match only_other_pos(words.rsplit(' ').next().unwrap_or(words)) {
            Some(pos) => {
                Verdict::NotObject(format!("an {pos}, not a noun").replace("an verb", "a verb"))
            }
            None => Verdict::NotObject("a word the dictionary does not know".to_string()),
        },
        Some(info) if info.share >= r.min_share => Verdict::Object,
        Some(info) if info.share >= r.min_share_with_evidence => Verdict::NeedsEvidence,
        // "shelves hold logbooks", "a stack of flyers": written matter is paper where the
        // sentence places it; "a love of poetry" places nothing.
        Some(info) if info.placeable.is_empty() && !info.documents.is_empty() => {
            Verdict::Rarely("written matter: a thing only where the sentence places it".to_string())
        }
        // "a jar of dog treats": food written in the plural is counted pieces, a thing where
        // the phrase counts or lists them ("a love of food", "treat" alone name none).
        Some(info)
            if info.placeable.is_empty()
                && info.lexname == "noun.food"
                && words.rsplit(' ').next() != info.lemma.rsplit(' ').next() =>
        {
            Verdict::NeedsEvidence
        }
        Some(info) if info.placeable.is_empty() && info.structure => Verdict::NotObject(
            "a building, vessel or structure, or part of the architecture: nothing placed in \
             a room"
                .to_string(),
        ),
        Some(info) if info.placeable.is_empty() => Verdict::NotObject(format!(
            "{} word, no physical thing",
            with_article(info.lexname.trim_start_matches("noun."))
        )),
        Some(info) => Verdict::Rarely(format!(
            "mostly {} word ({:.0} % of its uses name a thing)",
            with_article(info.lexname.trim_start_matches("noun.")),
            100.0 * info.share
        )),
    }
}

/// "an event", "a feeling".
fn with_article(word: &str) -> String {
    let vowel = word.starts_with(['a', 'e', 'i', 'o', 'u']);
    format!("{} {word}", if vowel { "an" } else { "a" })
}

/// The nearest family of a noun along its hypernyms.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// The family noun, as the `known` predicate accepted it.
    pub noun: String,
    /// Hypernym steps from the noun's sense to the family (0: a synonym).
    pub distance: u32,
    /// Lemmas along the way, from the noun's sense to the family's synset.
    pub via: Vec<String>,
}

/// The nearest noun `known` accepts along the hypernyms of `lemma`'s senses that pass
/// `sense_ok` (heaviest sense first on ties), never above the `family_stop` synsets.
/// Farthest hypernym step a family may be from the noun: beyond it the kinship is too loose
/// to build from (a bell is no kind of game controller, though "doorbell > push button >
/// switch > control" leads there).
const MAX_FAMILY_STEPS: u32 = 2;

fn nearest(lemma: &str, senses: &[SynsetId], known: &dyn Fn(&str) -> bool) -> Option<Family> {
    let wn = wordnet();
    let r = rules();
    let mut best: Option<(u32, usize, Family)> = None;
    for (rank, &start) in senses.iter().enumerate() {
        // Breadth first, remembering the path for the report.
        let mut queue: VecDeque<(SynsetId, u32, Vec<String>)> = VecDeque::new();
        let mut seen: HashSet<SynsetId> = HashSet::new();
        queue.push_back((start, 0, Vec::new()));
        while let Some((s, d, path)) = queue.pop_front() {
            if !seen.insert(s) || r.family_stop.contains(&s) || d > MAX_FAMILY_STEPS {
                continue;
            }
            if best.as_ref().is_some_and(|(bd, _, _)| d > *bd) {
                break;
            }
            let mut via = path.clone();
            via.push(wn.lemmas(s).next().unwrap_or_default().replace('_', " "));
            if let Some(found) = wn
                .lemmas(s)
                .map(|l| l.replace('_', " "))
                .find(|l| l != lemma && known(l))
            {
                let better = best
                    .as_ref()
                    .is_none_or(|(bd, br, _)| (d, rank) < (*bd, *br));
                if better {
                    best = Some((
                        d,
                        rank,
                        Family {
                            noun: found,
                            distance: d,
                            via: via.clone(),
                        },
                    ));
                }
                continue;
            }
            for &h in wn.hypernyms(s) {
                queue.push_back((h, d + 1, via.clone()));
            }
        }
    }
    best.map(|(_, _, f)| f)
}

/// The nearest family `known` accepts along the hypernyms of the placeable senses of
/// `words` ("samovar" -> "urn" when the library builds urns).
///
/// Written matter with no placeable sense walks up from its document senses, and is the
/// rules' `document_family` (paper) when no family is near.
pub fn family(words: &str, known: &dyn Fn(&str) -> bool) -> Option<Family> {
    let info = noun_info(words)?;
    if info.placeable.first().is_some_and(|&s| rules().animal(s)) {
        // A cat is no whip (cat-o'-nine-tails) and no tractor (Caterpillar).
        return None;
    }
    if !info.placeable.is_empty() {
        return nearest(&info.lemma, &info.placeable[..info.usual], known);
    }
    let paper = &rules().document_family;
    nearest(&info.lemma, &info.documents, known).or_else(|| {
        (!info.documents.is_empty() && known(paper)).then(|| Family {
            noun: paper.clone(),
            distance: 0,
            via: vec![info.lemma.clone(), paper.clone()],
        })
    })
}

/// Hypernym steps within which two senses keep company: siblings and cousins ("smoothing
/// iron" and "sewing machine" are both home appliances).
const COMPANY_STEPS: u32 = 2;

/// A sense and its hypernyms up to [`COMPANY_STEPS`] links away, short of the `family_stop`
/// synsets (everything is an artifact: that is no company).
fn near_kin(s: SynsetId) -> HashSet<SynsetId> {
    let wn = wordnet();
    let stop = &rules().family_stop;
    let mut out = HashSet::new();
    let mut frontier = vec![s];
    for _ in 0..=COMPANY_STEPS {
        let mut next = Vec::new();
        for x in frontier {
            if !stop.contains(&x) && out.insert(x) {
                next.extend_from_slice(wn.hypernyms(x));
            }
        }
        frontier = next;
    }
    out
}

/// A noun's sense as the other things of its text choose it.
#[derive(Debug, Clone, PartialEq)]
pub struct SenseInCompany {
    /// A lemma of the chosen sense that ends in the noun and names no other placeable thing
    /// ("smoothing iron").
    pub lemma: String,
    /// The family the chosen sense is built as, if any is near.
    pub family: Option<Family>,
}

/// The placeable sense of `words` that the other things of its text (`company`: their
/// nouns) keep company with, when it is not the sense the noun is built as by itself.
///
/// A sense's support is the number of company nouns whose main sense (their heaviest
/// placeable one) lies within a few hypernym links of it (word-sense choice by conceptual neighbourhood): in a sewing room with a sewing
/// machine, "iron" is the smoothing iron, a home appliance like the machine, not the golf
/// club its first sense would build. `None` when no one sense has more support than each other,
/// when the supported senses build the same family as the noun alone, or when no lemma of
/// the chosen sense ends in the noun's own last word and names it alone (the name of the
/// object must still say what the prompt said).
pub fn sense_in_company(
    words: &str,
    company: &[&str],
    known: &dyn Fn(&str) -> bool,
) -> Option<SenseInCompany> {
    let info = noun_info(words)?;
    if info.placeable.len() < 2 {
        return None;
    }
    let kin_of_company: Vec<HashSet<SynsetId>> = company
        .iter()
        .filter(|c| noun_lemma(c).as_deref() != Some(info.lemma.as_str()))
        .filter_map(|c| noun_info(c)?.placeable.first().copied())
        .map(near_kin)
        .collect();
    let support: Vec<usize> = info
        .placeable
        .iter()
        .map(|&s| {
            let kin = near_kin(s);
            kin_of_company
                .iter()
                .filter(|c| !c.is_disjoint(&kin))
                .count()
        })
        .collect();
    let best = support.iter().copied().max().unwrap_or(0);
    if best == 0 {
        return None;
    }
    let mut at_best = info
        .placeable
        .iter()
        .zip(&support)
        .filter(|&(_, &n)| n == best);
    let (Some((&chosen, _)), None) = (at_best.next(), at_best.next()) else {
        return None;
    };
    let family = nearest(&info.lemma, &[chosen], known);
    let alone = nearest(&info.lemma, &info.placeable[..info.usual], known);
    if family.as_ref().map(|f| &f.noun) == alone.as_ref().map(|f| &f.noun) {
        return None;
    }
    let last = info.lemma.rsplit(' ').next().unwrap_or(&info.lemma);
    let suffix = format!(" {last}");
    let wn = wordnet();
    let lemma = wn
        .lemmas(chosen)
        .map(|l| l.replace('_', " "))
        .find(|l| l.ends_with(&suffix) && noun_info(l).is_some_and(|i| i.placeable == [chosen]))?;
    Some(SenseInCompany { lemma, family })
}

/// Whether the noun `words` may be read as a kind of the noun `word`: WordNet does not know
/// `words`, or one of its placeable senses has a sense of `word` among its hypernyms ("kitchen
/// table" is a table; "smoothing iron" is no iron of the golf-club or metal kind: it is a
/// home appliance).
pub fn is_kind_of_word(words: &str, word: &str) -> bool {
    let Some(info) = noun_info(words) else {
        return true;
    };
    let Some(lemma) = noun_lemma(word) else {
        return false;
    };
    let wn = wordnet();
    let senses: Vec<SynsetId> = wn.noun_senses(&lemma).iter().map(|s| s.synset).collect();
    info.placeable
        .iter()
        .any(|&s| wn.ancestors(s).iter().any(|(a, _)| senses.contains(a)))
}

/// The nearest room word `known` accepts along the hypernyms of the room-like senses of
/// `words` ("bakehouse" -> "bakery", "pantry" -> "storeroom").
pub fn room_family(words: &str, known: &dyn Fn(&str) -> bool) -> Option<Family> {
    let info = noun_info(words)?;
    let wn = wordnet();
    let r = rules();
    let senses: Vec<SynsetId> = wn
        .noun_senses(&info.lemma)
        .iter()
        .map(|s| s.synset)
        .filter(|&s| r.roomlike(s))
        .collect();
    nearest(&info.lemma, &senses, known)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compiled_rules_parse() {
        let r = Rules::parse(include_str!("../data/lexicon/grounding.json")).unwrap();
        assert!(!r.object_under.is_empty() && !r.family_stop.is_empty());
        assert!(r.min_share > r.min_share_with_evidence);
    }

    #[test]
    fn abstract_words_are_no_objects() {
        for w in [
            "unease",
            "scream",
            "tension",
            "juxtaposition",
            "chaos",
            "atmosphere",
            "taste",
            "despite",
            "elegance",
            "calm",
            "warmth",
            "design",
            "storage",
            "touch",
        ] {
            assert!(
                matches!(verdict(w), Verdict::NotObject(_) | Verdict::Rarely(_)),
                "{w}: {:?} {:?}",
                verdict(w),
                noun_info(w)
            );
        }
        for w in ["stylish", "practical", "somber", "providing", "dimly"] {
            assert!(only_other_pos(w).is_some(), "{w}");
            assert!(matches!(verdict(w), Verdict::NotObject(_)), "{w}");
        }
    }

    #[test]
    fn things_are_objects() {
        for w in [
            "chandelier",
            "samovar",
            "gramophone",
            "typewriter",
            "fern",
            "apple",
            "dartboard",
            "printers",
            "shelves",
            "vases",
            // Under enclosure, an area of a structure, in WordNet; `placeable_within`.
            "birdcage",
            "playpen",
            "terrarium",
            "kiln",
        ] {
            assert_eq!(verdict(w), Verdict::Object, "{w}: {:?}", noun_info(w));
            assert!(!is_room_word(w), "{w}");
        }
        // The same anchors keep the rooms and pits of that branch out.
        for w in ["crypt", "dining area"] {
            assert_ne!(verdict(w), Verdict::Object, "{w}");
        }
    }

    #[test]
    fn families_along_the_hypernyms() {
        let known = |n: &str| ["lighting fixture", "printer", "bucket", "machine"].contains(&n);
        let f = family("chandelier", &known).unwrap();
        assert_eq!(f.noun, "lighting fixture");
        assert_eq!(f.distance, 1);
        let f = family("wine cooler", &known).unwrap();
        assert_eq!(f.noun, "bucket");
        // A synonym is a family at distance 0.
        let f = family("printing machine", &known).unwrap();
        assert_eq!((f.noun.as_str(), f.distance), ("printer", 0));
        assert!(family("unease", &known).is_none());
        // Never above the stop synsets: nothing is a kind of "artifact" here.
        assert!(family("chandelier", &|n: &str| n == "artifact").is_none());
    }

    #[test]
    fn graded_adjectives_by_exception_or_by_their_base() {
        for w in ["larger", "biggest", "happier", "older", "smaller"] {
            assert!(is_graded_adjective(w), "{w}");
        }
        for w in ["other", "another", "water", "corner", "best-seller"] {
            assert!(!is_graded_adjective(w), "{w}");
        }
    }

    #[test]
    fn a_compound_is_a_kind_of_its_last_word_unless_wordnet_says_otherwise() {
        assert!(is_kind_of_word("kitchen table", "table"));
        // WordNet: a machine tool, no kind of press.
        assert!(!is_kind_of_word("drill press", "press"));
        assert!(is_kind_of_word("filter coffee stand", "stand"));
        assert!(!is_kind_of_word("smoothing iron", "iron"));
    }

    #[test]
    fn the_company_chooses_the_sense() {
        let known = |n: &str| n == "golf club";
        // Alone, an iron is built as its golf-club sense.
        assert_eq!(family("iron", &known).unwrap().noun, "golf club");
        // Beside a sewing machine it is a smoothing iron, a home appliance like the machine,
        // with no family near: a stand-in called by its own name.
        let s = sense_in_company("iron", &["sewing machine", "iron", "quilt"], &known).unwrap();
        assert_eq!(s.lemma, "smoothing iron");
        assert!(s.family.is_none());
        // Company that supports the sense it is built as anyway changes nothing, nor does
        // company that supports no sense, nor a word with one placeable sense.
        assert!(sense_in_company("iron", &["putter"], &known).is_none());
        assert!(sense_in_company("iron", &["quilt", "armchair"], &known).is_none());
        assert!(sense_in_company("samovar", &["sewing machine"], &known).is_none());
    }

    #[test]
    fn rooms_along_the_hypernyms() {
        let known = |n: &str| ["bakery", "storeroom", "shop"].contains(&n);
        assert_eq!(room_family("bakehouse", &known).unwrap().noun, "bakery");
        assert_eq!(room_family("pantry", &known).unwrap().noun, "storeroom");
        assert_eq!(room_family("pharmacy", &known).unwrap().noun, "shop");
        assert!(room_family("chair", &known).is_none());
        assert!(rules().is_room_space_word("floor"));
    }

    #[test]
    fn a_family_comes_from_the_usual_senses() {
        // "sack": WordNet tags only its bag sense; its hammock sense (a bed) is no usual
        // reading, so a flour sack is not built as a bed.
        let known = |n: &str| ["bed", "bag"].contains(&n);
        assert_eq!(family("sack", &known).unwrap().noun, "bag");
        let beds_only = |n: &str| n == "bed";
        assert!(family("sack", &beds_only).is_none());
        // A word whose senses WordNet never tagged keeps them all.
        let info = noun_info("samovar").unwrap();
        assert_eq!(info.usual, info.placeable.len());
    }
}
