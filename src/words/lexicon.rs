//! The reader's vocabulary: object nouns with their canonical names, support class and
//! container flags (`src/data/lexicon/objects.json`), and the word classes that shape a
//! phrase — numbers, determiners, quantifiers, prepositions, verbs, colours, materials,
//! styles, density words (`src/data/lexicon/words.json`).
//!
//! This module answers "what is this word (or run of words)?"; it does not decide what a
//! phrase means in context (the prompt reader's `chunk` and `interpret` do).

use std::collections::{BTreeMap, HashMap, HashSet};
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use super::tokens::{Token, TokenKind};

/// Where an object normally stands, which decides the stage that places it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// Stands on the floor (furniture stage).
    Floor,
    /// Mounted on a wall (wall stage).
    Wall,
    /// Hangs from the ceiling (ceiling stage).
    Ceiling,
    /// Rests on a furniture surface or inside a container (manipuland stage).
    Surface,
}

/// One object noun of the lexicon.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NounEntry {
    /// Canonical name: singular, lower case ("coffee table").
    pub noun: String,
    /// Usual support.
    pub support: Support,
    /// Other spellings, plurals and near-synonyms that mean this noun.
    #[serde(default)]
    pub synonyms: Vec<String>,
    /// The broader class ("dining table" is a kind of "table").
    #[serde(default)]
    pub kind_of: Option<String>,
    /// Holds things inside (bowl, bin, refrigerator).
    #[serde(default)]
    pub container: bool,
    /// Carries small objects on a top or on shelves (table, shelf, counter).
    #[serde(default)]
    pub holds: bool,
    /// Names a class rather than a thing (fruit, toy, supplies).
    #[serde(default)]
    pub generic: bool,
    /// A thin covering (rug, mat, tablecloth).
    #[serde(default)]
    pub thin: bool,
    /// Usual parents of a surface object, preferred first.
    #[serde(default)]
    pub rests_on: Vec<String>,
}

/// A style or theme word.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct StyleWord {
    /// `style` (Art Deco, steampunk) or `theme` (Star Wars, Frozen).
    pub kind: String,
    /// Counts only when written with a capital letter ("Frozen" the film, not frozen food).
    #[serde(default)]
    pub cap: bool,
}

#[derive(Debug, Deserialize)]
struct WordsFile {
    numbers: HashMap<String, u32>,
    ordinals: HashMap<String, u32>,
    determiners: HashMap<String, String>,
    quantifiers: HashMap<String, String>,
    groups: HashMap<String, String>,
    group_suffixes: Vec<String>,
    negations: Vec<String>,
    negating_verbs: HashMap<String, String>,
    prepositions: HashMap<String, String>,
    landmarks: HashMap<String, String>,
    verbs: HashMap<String, String>,
    ambiguous_bare: Vec<String>,
    relatives: Vec<String>,
    /// Pronouns, subordinators, auxiliaries and sentence adverbs: English's closed classes.
    closed_class: Vec<String>,
    conjunctions: Vec<String>,
    /// Words that count against what is already there and describe nothing ("two more
    /// music stands", "an extra chair").
    #[serde(default)]
    relative_quantity: Vec<String>,
    setting_nouns: Vec<String>,
    part_nouns: HashMap<String, String>,
    adjectives: Vec<String>,
    size_adjectives: HashMap<String, String>,
    room_sizes: HashMap<String, f64>,
    density: HashMap<String, String>,
    density_room_only: HashMap<String, String>,
    colors: BTreeMap<String, String>,
    materials: HashMap<String, String>,
    style_suffixes: Vec<String>,
    feature_nouns: Vec<String>,
    non_objects: Vec<String>,
    irregular_plurals: HashMap<String, String>,
}

#[derive(Debug, Deserialize)]
struct ObjectsFile {
    objects: Vec<NounEntry>,
}

/// Errors loading the compiled-in lexicon.
#[derive(Debug, thiserror::Error)]
pub enum LexiconError {
    /// A data file does not parse.
    #[error("lexicon file {file} does not parse: {cause}")]
    Parse {
        /// Which file.
        file: &'static str,
        /// The JSON error.
        cause: serde_json::Error,
    },
    /// Two nouns claim the same spelling.
    #[error("the spelling {spelling:?} belongs to both {a:?} and {b:?}")]
    Duplicate {
        /// The spelling.
        spelling: String,
        /// First noun.
        a: String,
        /// Second noun.
        b: String,
    },
}

/// The vocabulary, indexed for lookups.
#[derive(Debug, Default)]
pub struct Lexicon {
    /// Object nouns.
    pub objects: Vec<NounEntry>,
    spellings: HashMap<String, usize>,
    numbers: HashMap<String, u32>,
    ordinals: HashMap<String, u32>,
    determiners: HashMap<String, String>,
    quantifiers: HashMap<String, String>,
    groups: HashMap<String, String>,
    group_suffixes: HashSet<String>,
    negations: HashSet<String>,
    negating_verbs: HashMap<String, String>,
    prepositions: HashMap<String, String>,
    landmarks: HashMap<String, String>,
    verbs: HashMap<String, String>,
    ambiguous_bare: HashSet<String>,
    relatives: HashSet<String>,
    closed_class: HashSet<String>,
    conjunctions: HashSet<String>,
    relative_quantity: HashSet<String>,
    setting_nouns: HashSet<String>,
    part_nouns: HashMap<String, String>,
    adjectives: HashSet<String>,
    size_adjectives: HashMap<String, String>,
    room_sizes: HashMap<String, f64>,
    density: HashMap<String, String>,
    density_room_only: HashMap<String, String>,
    colors: BTreeMap<String, String>,
    materials: HashMap<String, String>,
    style_suffixes: HashSet<String>,
    styles: HashMap<String, StyleWord>,
    feature_nouns: HashSet<String>,
    non_objects: HashSet<String>,
    irregular: HashMap<String, String>,
}

/// Longest phrase (in words) any multi-word table holds.
pub const MAX_PHRASE: usize = 5;

impl Lexicon {
    /// Builds a lexicon from the two JSON documents and the asset attribute file (whose
    /// styles' words are the style words).
    pub fn parse(words: &str, objects: &str, styles: &str) -> Result<Lexicon, LexiconError> {
        let w: WordsFile = serde_json::from_str(words).map_err(|source| LexiconError::Parse {
            file: "lexicon/words.json",
            cause: source,
        })?;
        let o: ObjectsFile =
            serde_json::from_str(objects).map_err(|source| LexiconError::Parse {
                file: "lexicon/objects.json",
                cause: source,
            })?;
        let mut spellings: HashMap<String, usize> = HashMap::new();
        for (i, e) in o.objects.iter().enumerate() {
            for s in std::iter::once(&e.noun).chain(&e.synonyms) {
                if let Some(&j) = spellings.get(s)
                    && j != i
                {
                    return Err(LexiconError::Duplicate {
                        spelling: s.clone(),
                        a: o.objects[j].noun.clone(),
                        b: e.noun.clone(),
                    });
                }
                spellings.insert(s.clone(), i);
                // The tokenizer drops a possessive: "potter's wheel" is read "potter wheel".
                if s.contains('\'') {
                    let read = s.replace("'s ", " ").replace('\'', "");
                    spellings.entry(read).or_insert(i);
                }
            }
        }
        let set = |v: Vec<String>| v.into_iter().collect::<HashSet<String>>();
        Ok(Lexicon {
            objects: o.objects,
            spellings,
            numbers: w.numbers,
            ordinals: w.ordinals,
            determiners: w.determiners,
            quantifiers: w.quantifiers,
            groups: w.groups,
            group_suffixes: set(w.group_suffixes),
            negations: set(w.negations),
            negating_verbs: w.negating_verbs,
            prepositions: w.prepositions,
            landmarks: w.landmarks,
            verbs: w.verbs,
            ambiguous_bare: set(w.ambiguous_bare),
            relatives: set(w.relatives),
            closed_class: set(w.closed_class),
            conjunctions: set(w.conjunctions),
            relative_quantity: set(w.relative_quantity),
            setting_nouns: set(w.setting_nouns),
            part_nouns: w.part_nouns,
            adjectives: set(w.adjectives),
            size_adjectives: w.size_adjectives,
            room_sizes: w.room_sizes,
            density: w.density,
            density_room_only: w.density_room_only,
            colors: w.colors,
            materials: w.materials,
            style_suffixes: set(w.style_suffixes),
            styles: style_words(styles)?,
            feature_nouns: set(w.feature_nouns),
            non_objects: set(w.non_objects),
            irregular: w.irregular_plurals,
        })
    }

    /// Singular form of an English noun: irregular table first, then suffix rules.
    pub fn singular(&self, word: &str) -> String {
        if let Some((head, last)) = word.rsplit_once('-')
            && !last.is_empty()
            && !head.is_empty()
        {
            return format!("{head}-{}", self.singular(last));
        }
        if let Some(s) = self.irregular.get(word) {
            return s.clone();
        }
        let single = singular_rules(word);
        // "atlas", "canvas", "clothes": a noun WordNet lists as written whose stripped form
        // is no noun stays as it is.
        let wn = super::wordnet::wordnet();
        if single != word
            && wn.is_lemma(word, super::wordnet::Pos::Noun)
            && !wn.is_lemma(&single, super::wordnet::Pos::Noun)
        {
            return word.to_string();
        }
        single
    }

    /// True when the word is written in a plural form ("chairs", "shelves").
    pub fn is_plural(&self, word: &str) -> bool {
        if let Some(s) = self.irregular.get(word) {
            return s != word;
        }
        self.singular(word) != word
    }

    /// True for nouns that only exist in the plural ("scissors", "jeans").
    /// A singular the lexicon lists for the word wins over WordNet ("glasses": glass, though
    /// WordNet also has "glasses" for spectacles).
    pub fn plurale_tantum(&self, word: &str) -> bool {
        match self.irregular.get(word) {
            Some(s) => s == word,
            None => wordnet_plurale_tantum(word),
        }
    }

    /// The entry a spelling names.
    pub fn entry(&self, spelling: &str) -> Option<&NounEntry> {
        self.spellings
            .get(spelling)
            .and_then(|&i| self.objects.get(i))
    }

    /// The entry of a canonical noun or any spelling of it.
    pub fn lookup(&self, noun: &str) -> Option<&NounEntry> {
        let noun = noun.trim().to_lowercase();
        self.entry(&noun).or_else(|| {
            let words: Vec<&str> = noun.split(' ').collect();
            let sing: Vec<String> = words.iter().map(|w| self.singular(w)).collect();
            self.entry(&sing.join(" "))
        })
    }

    /// Whether `noun` is a kind of `of` along the lexicon's `kind_of` chain (at most four steps:
    /// "armchair" -> "chair" -> "seating").
    pub fn is_kind(&self, noun: &str, of: &str) -> bool {
        let mut kind = self.lookup(noun).and_then(|e| e.kind_of.as_deref());
        for _ in 0..4 {
            match kind {
                Some(k) if k == of => return true,
                Some(k) => kind = self.lookup(k).and_then(|e| e.kind_of.as_deref()),
                None => return false,
            }
        }
        false
    }

    /// Index of an entry by spelling.
    pub fn entry_index(&self, spelling: &str) -> Option<usize> {
        self.spellings.get(spelling).copied()
    }

    /// The longest object noun starting at `tokens[at]`: (words used, entry index, plural).
    /// Tries the words as written, then with the last word singular, then all words singular.
    pub fn noun_at(&self, tokens: &[Token], at: usize) -> Option<(usize, usize, bool)> {
        self.noun_at_most(tokens, at, MAX_PHRASE)
    }

    /// [`Lexicon::noun_at`] with at most `max` words.
    pub fn noun_at_most(
        &self,
        tokens: &[Token],
        at: usize,
        max: usize,
    ) -> Option<(usize, usize, bool)> {
        for len in (1..=max.min(MAX_PHRASE)).rev() {
            let Some(words) = words_at(tokens, at, len) else {
                continue;
            };
            let raw = words.join(" ");
            let last = words[len - 1];
            // "a chest of drawers", "two chests of drawers": the word before "of" counts.
            let counted = match words.iter().position(|w| *w == "of") {
                Some(p) if p > 0 => words[0],
                _ => last,
            };
            let plural = self.is_plural(counted) && !self.plurale_tantum(counted);
            let mut sing: Vec<String> = words.iter().map(|w| w.to_string()).collect();
            sing[len - 1] = self.singular(last);
            if let Some(i) = self.entry_index(&raw) {
                // "glasses", "shelves" as synonyms are plural even though listed verbatim;
                // so is a spelling whose last word singular is the same entry ("robotic arms",
                // though WordNet also lists "arms").
                let singular_too = counted == last
                    && sing[len - 1] != last
                    && self.entry_index(&sing.join(" ")) == Some(i);
                return Some((
                    len,
                    i,
                    plural || singular_too || self.entry_plural_spelling(i, &raw),
                ));
            }
            if let Some(i) = self.entry_index(&sing.join(" ")) {
                // The lexicon knows it only with the last word singular: that word was a
                // plural ("robotic arms", though WordNet also lists "arms").
                return Some((len, i, plural || counted == last));
            }
            let all: Vec<String> = words.iter().map(|w| self.singular(w)).collect();
            if let Some(i) = self.entry_index(&all.join(" ")) {
                // "loaves of bread": the first word carries the number.
                let any_plural = words
                    .iter()
                    .any(|w| self.is_plural(w) && !self.plurale_tantum(w));
                return Some((len, i, plural || any_plural));
            }
        }
        // "a fridge-freezer", "a sofa-bed": two nouns the lexicon knows, joined by a hyphen,
        // name a thing of the last one's kind.
        let w = words_at(tokens, at, 1)?.first().copied()?;
        let (first, last) = w.rsplit_once('-')?;
        let known = |x: &str| {
            self.entry_index(x)
                .or_else(|| self.entry_index(&self.singular(x)))
        };
        known(first)?;
        let i = known(last)?;
        Some((1, i, self.is_plural(last) && !self.plurale_tantum(last)))
    }

    fn entry_plural_spelling(&self, _i: usize, raw: &str) -> bool {
        let counted = match raw.split_once(" of ") {
            Some((first, _)) => first.split(' ').next().unwrap_or(first),
            None => raw.rsplit(' ').next().unwrap_or(raw),
        };
        self.is_plural(counted) && !self.plurale_tantum(counted)
    }

    /// Longest phrase at `at` found in a multi-word table: (words used, value).
    fn phrase_at<'a, T>(
        &self,
        table: &'a HashMap<String, T>,
        tokens: &[Token],
        at: usize,
        max: usize,
    ) -> Option<(usize, &'a T)> {
        for len in (1..=max).rev() {
            if let Some(words) = words_at(tokens, at, len)
                && let Some(v) = table.get(&words.join(" "))
            {
                return Some((len, v));
            }
        }
        None
    }

    /// A preposition (possibly several words) at `at`: (words used, class).
    pub fn preposition_at(&self, tokens: &[Token], at: usize) -> Option<(usize, &str)> {
        self.phrase_at(&self.prepositions, tokens, at, 6)
            .map(|(n, v)| (n, v.as_str()))
    }

    /// A quantifier phrase at `at` ("at least", "a couple of"): (words used, class).
    pub fn quantifier_at(&self, tokens: &[Token], at: usize) -> Option<(usize, &str)> {
        self.phrase_at(&self.quantifiers, tokens, at, 4)
            .map(|(n, v)| (n, v.as_str()))
    }

    /// A style or theme (possibly several words) at `at`, honouring the capital-letter rule.
    pub fn style_at(&self, tokens: &[Token], at: usize) -> Option<(usize, &StyleWord)> {
        let (n, s) = self.phrase_at(&self.styles, tokens, at, 4)?;
        if s.cap && !tokens[at].capitalized() {
            return None;
        }
        Some((n, s))
    }

    /// A colour at `at`, joining two words with a hyphen when the pair is a colour
    /// ("navy blue"): (words used, canonical colour name, hex).
    pub fn color_at(&self, tokens: &[Token], at: usize) -> Option<(usize, String, &str)> {
        if let Some(words) = words_at(tokens, at, 2) {
            let joined = words.join("-");
            if let Some(hex) = self.colors.get(&joined) {
                return Some((2, joined, hex.as_str()));
            }
        }
        let w = tokens.get(at)?.text.as_str();
        self.colors
            .get(w)
            .map(|hex| (1, w.to_string(), hex.as_str()))
    }

    /// A number written as digits or a word ("3", "three"), without a token.
    pub fn number_word(&self, w: &str) -> Option<u32> {
        w.parse().ok().or_else(|| self.numbers.get(w).copied())
    }

    /// Number word or digits.
    pub fn number(&self, token: &Token) -> Option<u32> {
        match token.kind {
            TokenKind::Number(n) => Some(n),
            TokenKind::Word => self.numbers.get(&token.text).copied().or_else(|| {
                // "twenty-four"
                let (a, b) = token.text.split_once('-')?;
                let tens = *self.numbers.get(a)?;
                let ones = *self.numbers.get(b)?;
                (tens >= 20 && tens % 10 == 0 && ones < 10).then_some(tens + ones)
            }),
            TokenKind::Punct(_) => None,
        }
    }

    /// Ordinal word ("first", "3rd").
    pub fn ordinal(&self, word: &str) -> Option<u32> {
        self.ordinals.get(word).copied()
    }

    /// Determiner class (`indefinite`, `definite`, `possessive`, `several`, `each`, ...).
    pub fn determiner(&self, word: &str) -> Option<&str> {
        self.determiners.get(word).map(String::as_str)
    }

    /// Group word class (`stack`, `pile`, `pair`, ...).
    pub fn group(&self, word: &str) -> Option<&str> {
        self.groups.get(word).map(String::as_str)
    }

    /// "arrangement", "set-up": words that turn a noun list into one group.
    pub fn is_group_suffix(&self, word: &str) -> bool {
        self.group_suffixes.contains(word)
    }

    /// "no", "without", "not".
    pub fn is_negation(&self, word: &str) -> bool {
        self.negations.contains(word)
    }

    /// A verb phrase at `at` that rejects what follows it ("decided against televisions",
    /// "got rid of the rugs"): the number of words it takes.
    pub fn negating_verb_at(&self, tokens: &[Token], at: usize) -> Option<usize> {
        self.phrase_at(&self.negating_verbs, tokens, at, 4)
            .map(|(n, _)| n)
    }

    /// Landmark class (`wall`, `corner`, `center`, ...).
    pub fn landmark(&self, word: &str) -> Option<&str> {
        self.landmarks.get(word).map(String::as_str)
    }

    /// Verb class (`possess`, `locate`, `hang`, ...).
    pub fn verb(&self, word: &str) -> Option<&str> {
        self.verbs.get(word).map(String::as_str)
    }

    /// Words that are nouns only with a determiner or in a list ("can", "set").
    pub fn is_ambiguous_bare(&self, word: &str) -> bool {
        self.ambiguous_bare.contains(word)
    }

    /// "which", "that", "where".
    pub fn is_relative(&self, word: &str) -> bool {
        self.relatives.contains(word)
    }

    /// "and", "or", "plus".
    pub fn is_conjunction(&self, word: &str) -> bool {
        self.conjunctions.contains(word)
    }

    /// "more", "extra", "additional": counts against what is there, describes nothing.
    pub fn is_relative_quantity(&self, word: &str) -> bool {
        self.relative_quantity.contains(word)
    }

    /// "people", "guests" (a table set for N people).
    pub fn is_setting_noun(&self, word: &str) -> bool {
        self.setting_nouns.contains(word)
    }

    /// Part of a piece of furniture ("level", "setting").
    pub fn part(&self, word: &str) -> Option<&str> {
        self.part_nouns.get(word).map(String::as_str)
    }

    /// Plain descriptive adjective.
    pub fn is_adjective(&self, word: &str) -> bool {
        self.adjectives.contains(word)
    }

    /// Size class of an adjective (`small`, `large`, `long`, ...).
    pub fn size_adjective(&self, word: &str) -> Option<&str> {
        self.size_adjectives.get(word).map(String::as_str)
    }

    /// Room size factor of a word ("small" 0.8, "spacious" 1.35).
    pub fn room_size(&self, word: &str) -> Option<f64> {
        self.room_sizes.get(word).copied()
    }

    /// Density class of a word anywhere in the prompt.
    pub fn density(&self, word: &str) -> Option<&str> {
        self.density.get(word).map(String::as_str)
    }

    /// Density class of a word that counts only when it describes the room ("a clean room").
    pub fn density_room_only(&self, word: &str) -> Option<&str> {
        self.density_room_only.get(word).map(String::as_str)
    }

    /// Material table name of a material word ("wooden" -> "wood").
    pub fn material(&self, word: &str) -> Option<&str> {
        self.materials.get(word).map(String::as_str)
    }

    /// "themed", "style", "inspired".
    pub fn is_style_suffix(&self, word: &str) -> bool {
        self.style_suffixes.contains(word)
    }

    /// Nouns naming a feature of an object rather than an object ("patterns", "fittings").
    pub fn is_feature_noun(&self, word: &str) -> bool {
        self.feature_nouns.contains(word)
    }

    /// Nouns that are never objects ("area", "people", "theme").
    pub fn is_non_object(&self, word: &str) -> bool {
        self.non_objects.contains(word)
    }

    /// True for any function word: nothing the open-vocabulary rule may take as a noun.
    pub fn is_function_word(&self, word: &str) -> bool {
        self.determiners.contains_key(word)
            || self.numbers.contains_key(word)
            || self.ordinals.contains_key(word)
            || self.prepositions.contains_key(word)
            || self.verbs.contains_key(word)
            || self.relatives.contains(word)
            || self.closed_class.contains(word)
            || self.conjunctions.contains(word)
            || self.negations.contains(word)
            || matches!(
                word,
                "with"
                    | "of"
                    | "for"
                    | "there"
                    | "it"
                    | "them"
                    | "they"
                    | "each"
                    | "here"
                    | "also"
                    | "very"
                    | "too"
                    | "so"
                    | "as"
                    | "than"
                    | "such"
                    | "if"
                    | "when"
                    | "to"
                    | "neatly"
                    | "nicely"
                    | "together"
                    | "is"
                    | "are"
                    | "and"
                    | "or"
            )
    }
}

/// A thing WordNet names in the plural ("shears", "secateurs", "goggles", "tongs",
/// "glasses"): the plural is its own lemma with a physical sense, so "a pair of" it is one.
fn wordnet_plurale_tantum(word: &str) -> bool {
    word.ends_with('s')
        && super::wordnet::wordnet().is_lemma(word, super::wordnet::Pos::Noun)
        && super::ground::noun_info(word)
            .is_some_and(|i| i.lemma == word && !i.placeable.is_empty())
}

#[derive(Debug, Deserialize)]
struct StyleFile {
    styles: BTreeMap<String, StyleEntry>,
}

#[derive(Debug, Deserialize)]
struct StyleEntry {
    words: Vec<String>,
}

/// The style words of the asset styles (one home: `src/data/asset_attributes.json`); themes
/// the table does not name are read from markers ("pirate-themed", "inspired by ...") and
/// proper names, without any table.
fn style_words(text: &str) -> Result<HashMap<String, StyleWord>, LexiconError> {
    let f: StyleFile = serde_json::from_str(text).map_err(|source| LexiconError::Parse {
        file: "asset_attributes.json",
        cause: source,
    })?;
    let wn = super::wordnet::wordnet();
    let mut out = HashMap::new();
    for e in f.styles.values() {
        for w in &e.words {
            // A word that is only an adjective ("eclectic") or no ordinary word at all
            // ("steampunk") cannot be misread; one that is also a noun or verb ("space",
            // "frozen", "modern") is a style only when capitalised.
            let ordinary = w.split(' ').any(|x| {
                wn.has_pos(x, super::wordnet::Pos::Noun) || wn.has_pos(x, super::wordnet::Pos::Verb)
            });
            out.insert(
                w.clone(),
                StyleWord {
                    kind: "style".to_string(),
                    cap: ordinary,
                },
            );
        }
    }
    Ok(out)
}

/// `len` consecutive word tokens at `at` (None when a punctuation token or the end intervenes).
pub fn words_at(tokens: &[Token], at: usize, len: usize) -> Option<Vec<&str>> {
    let slice = tokens.get(at..at + len)?;
    if slice.iter().any(|t| !t.is_word()) {
        return None;
    }
    Some(slice.iter().map(|t| t.text.as_str()).collect())
}

/// Suffix rules for regular English plurals.
fn singular_rules(word: &str) -> String {
    const SUFFIX: [(&str, &str); 10] = [
        ("shelves", "shelf"),
        ("knives", "knife"),
        ("leaves", "leaf"),
        ("loaves", "loaf"),
        ("ches", "ch"),
        ("shes", "sh"),
        ("sses", "ss"),
        ("xes", "x"),
        ("oes", "o"),
        ("ies", "y"),
    ];
    for (plural, single) in SUFFIX {
        if let Some(stem) = word.strip_suffix(plural)
            && (stem.len() > 1 || plural.len() >= 6)
        {
            return format!("{stem}{single}");
        }
    }
    if word.ends_with("ss") || word.ends_with("us") || word.ends_with("is") || word.len() <= 3 {
        return word.to_string();
    }
    word.strip_suffix('s').unwrap_or(word).to_string()
}

/// The compiled-in lexicon. A broken data file yields an empty lexicon here; the unit test
/// `compiled_lexicon_parses` catches that before it ships.
pub fn lexicon() -> &'static Lexicon {
    static LEX: OnceLock<Lexicon> = OnceLock::new();
    LEX.get_or_init(|| {
        Lexicon::parse(
            include_str!("../data/lexicon/words.json"),
            include_str!("../data/lexicon/objects.json"),
            include_str!("../data/asset_attributes.json"),
        )
        .unwrap_or_default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::words::tokens::lex;

    #[test]
    fn compiled_lexicon_parses() {
        let r = Lexicon::parse(
            include_str!("../data/lexicon/words.json"),
            include_str!("../data/lexicon/objects.json"),
            include_str!("../data/asset_attributes.json"),
        );
        let lex = r.unwrap();
        assert!(lex.objects.len() >= 400, "{} nouns", lex.objects.len());
        for e in &lex.objects {
            assert_eq!(e.noun, e.noun.to_lowercase());
            if let Some(k) = &e.kind_of {
                assert!(!k.is_empty());
            }
        }
    }

    #[test]
    fn singular_forms() {
        let l = lexicon();
        for (p, s) in [
            ("shelves", "shelf"),
            ("libraries", "library"),
            ("glass", "glass"),
            ("glasses", "glass"),
            ("bus", "bus"),
            ("benches", "bench"),
            ("potatoes", "potato"),
            ("boxes", "box"),
            ("shoes", "shoe"),
            ("loaves", "loaf"),
            ("t-shirts", "t-shirt"),
            ("scissors", "scissors"),
            ("vases", "vase"),
        ] {
            assert_eq!(l.singular(p), s, "{p}");
        }
        assert!(l.plurale_tantum("scissors"));
        assert!(l.is_plural("chairs") && !l.is_plural("glass"));
    }

    #[test]
    fn multi_word_nouns_and_synonyms() {
        let l = lexicon();
        let t = lex("two bedside tables and loaves of bread and an x-ray machine");
        let (n, i, plural) = l.noun_at(&t, 1).unwrap();
        assert_eq!(
            (n, l.objects[i].noun.as_str(), plural),
            (2, "nightstand", true)
        );
        let (n, i, _) = l.noun_at(&t, 4).unwrap();
        assert_eq!((n, l.objects[i].noun.as_str()), (3, "bread loaf"));
        let (n, i, _) = l.noun_at(&t, 9).unwrap();
        assert_eq!((n, l.objects[i].noun.as_str()), (2, "x-ray machine"));
        assert_eq!(l.lookup("Couch").unwrap().noun, "sofa");
        assert_eq!(l.lookup("fridges").unwrap().noun, "refrigerator");
        assert_eq!(l.lookup("TV").unwrap().noun, "tv");
        assert_eq!(l.lookup("television").unwrap().support, Support::Surface);
    }
}
