//! Princeton WordNet 3.0 as the reader's lexical database: which parts of speech a word can
//! be, through WordNet's own morphology ("shelves" is a noun, "providing" a verb form,
//! "better" an adjective); the senses of a noun lemma in WordNet order with their tag counts;
//! each noun synset's lexicographer file ("noun.artifact") and its hypernym chain; NLTK-style
//! synset names ("artifact.n.01"), so data files can name anchor synsets readably.
//!
//! The data is an extract in `src/data/wordnet/` (its README gives the formats; regenerate
//! with `python3 scripts/wordnet_data.py`), compiled in and loaded once by [`wordnet`]. The
//! WordNet licence in `src/data/wordnet/LICENSE` goes with every copy.
//!
//! This module answers dictionary questions; it does not pick the sense a prompt means, and it
//! holds no glosses, no verb or adjective synsets and no relation but (instance) hypernymy.
//! [`SynsetId`]s are this extract's own dense numbering, not WordNet byte offsets: name a
//! synset in data by [`WordNet::synset`] instead.

use std::borrow::Cow;
use std::sync::OnceLock;

/// A noun synset of WordNet 3.0 (this extract holds no other synsets).
#[derive(Copy, Clone, Eq, PartialEq, Hash, Ord, PartialOrd, Debug)]
pub struct SynsetId(u32);

impl SynsetId {
    /// Position in the extract's synset table (0-based; ordered as WordNet's data.noun).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A WordNet part of speech.
#[derive(Copy, Clone, Eq, PartialEq, Hash, Debug)]
pub enum Pos {
    /// Noun.
    Noun,
    /// Verb.
    Verb,
    /// Adjective (satellites included).
    Adj,
    /// Adverb.
    Adv,
}

impl Pos {
    /// The letter the data files use (WordNet's `n`, `v`, `a`, `r`).
    fn from_letter(c: char) -> Option<Pos> {
        match c {
            'n' => Some(Pos::Noun),
            'v' => Some(Pos::Verb),
            'a' => Some(Pos::Adj),
            'r' => Some(Pos::Adv),
            _ => None,
        }
    }

    fn bit(self) -> u8 {
        1 << self as u8
    }

    /// Morphy's detachment rules (morphy(7WN)): suffix -> replacement, tried in this order.
    /// They are part of WordNet's algorithm rather than its data, hence here.
    fn rules(self) -> &'static [(&'static str, &'static str)] {
        match self {
            Pos::Noun => &[
                ("s", ""),
                ("ses", "s"),
                ("xes", "x"),
                ("zes", "z"),
                ("ches", "ch"),
                ("shes", "sh"),
                ("men", "man"),
                ("ies", "y"),
            ],
            Pos::Verb => &[
                ("s", ""),
                ("ies", "y"),
                ("es", "e"),
                ("es", ""),
                ("ed", "e"),
                ("ed", ""),
                ("ing", "e"),
                ("ing", ""),
            ],
            Pos::Adj => &[("er", ""), ("est", ""), ("er", "e"), ("est", "e")],
            Pos::Adv => &[],
        }
    }
}

/// One sense of a noun lemma.
#[derive(Copy, Clone, Eq, PartialEq, Debug)]
pub struct Sense {
    /// The synset the lemma names in this sense.
    pub synset: SynsetId,
    /// How often the sense was tagged in WordNet's semantic concordance (cntlist.rev); 0
    /// when never. WordNet orders a lemma's senses by this count where it has one.
    pub count: u32,
}

/// Errors loading the compiled-in WordNet extract.
#[derive(Debug, thiserror::Error)]
pub enum WordNetError {
    /// A file is not a valid zlib stream.
    #[error("wordnet file {file} does not inflate")]
    Inflate {
        /// Which file.
        file: &'static str,
        /// The inflater's complaint.
        source: miniz_oxide::inflate::DecompressError,
    },
    /// A file is not UTF-8.
    #[error("wordnet file {file} is not UTF-8")]
    Utf8 {
        /// Which file.
        file: &'static str,
        /// Where the text stops being UTF-8.
        source: std::string::FromUtf8Error,
    },
    /// A line is not in the documented format (`src/data/wordnet/README.md`).
    #[error("wordnet file {file}, line {line}: {problem}")]
    Line {
        /// Which file.
        file: &'static str,
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        problem: &'static str,
    },
}

/// A byte range of one of the held texts.
#[derive(Copy, Clone, Default, Debug)]
struct Span {
    start: u32,
    end: u32,
}

impl Span {
    fn of(text: &str, s: Span) -> &str {
        text.get(s.start as usize..s.end as usize).unwrap_or("")
    }

    fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// A synset's record: lexicographer file and ranges of the shared pointer and lemma lists.
#[derive(Copy, Clone, Default, Debug)]
struct SynsetRec {
    lexfile: u8,
    /// Hypernyms then instance hypernyms, in `WordNet::pointers`.
    pointers: Span,
    /// Where the instance hypernyms start within `pointers`.
    instances_from: u32,
    /// Indices of the noun lemmas in WordNet's order, in `WordNet::synset_lemmas`.
    lemmas: Span,
}

/// The decompressed data files.
struct Texts {
    nouns: String,
    synsets: String,
    words: String,
    exceptions: String,
}

/// The lexical database. Lemmas live in the decompressed file texts, found by binary search
/// over spans, so loading allocates per file rather than per lemma.
#[derive(Default, Debug)]
pub struct WordNet {
    noun_text: String,
    /// Noun lemma spans in `noun_text`, sorted by bytes.
    noun_lemmas: Vec<Span>,
    /// Per noun lemma, its range of `senses`.
    noun_senses: Vec<Span>,
    senses: Vec<Sense>,
    synsets: Vec<SynsetRec>,
    pointers: Vec<SynsetId>,
    synset_lemmas: Vec<u32>,
    lexnames: Vec<String>,
    word_text: String,
    /// Verb, adjective and adverb lemma spans in `word_text`, sorted by bytes.
    words: Vec<Span>,
    /// Per entry of `words`, a bit per [`Pos`].
    word_pos: Vec<u8>,
    exc_text: String,
    /// Per [`Pos`], (inflected form, tab-separated base forms) spans sorted by form.
    exceptions: [Vec<(Span, Span)>; 4],
}

/// Longest noun lemma, in words, that [`WordNet::longest_noun`] tries.
pub const MAX_NOUN_WORDS: usize = 5;

impl WordNet {
    /// Inflates and parses the extract compiled into the binary.
    pub fn compiled() -> Result<WordNet, WordNetError> {
        WordNet::parse(Texts {
            nouns: inflate("nouns", include_bytes!("../data/wordnet/nouns.tsv.zlib"))?,
            synsets: inflate(
                "synsets",
                include_bytes!("../data/wordnet/synsets.tsv.zlib"),
            )?,
            words: inflate("words", include_bytes!("../data/wordnet/words.tsv.zlib"))?,
            exceptions: inflate(
                "exceptions",
                include_bytes!("../data/wordnet/exceptions.tsv.zlib"),
            )?,
        })
    }

    fn parse(t: Texts) -> Result<WordNet, WordNetError> {
        let mut wn = WordNet::default();
        wn.parse_synsets(&t.synsets)?;
        let positions = wn.parse_nouns(&t.nouns)?;
        wn.invert_senses(&positions)?;
        wn.parse_words(&t.words)?;
        wn.parse_exceptions(&t.exceptions)?;
        wn.noun_text = t.nouns;
        wn.word_text = t.words;
        wn.exc_text = t.exceptions;
        Ok(wn)
    }

    /// `lexnames TAB name...`, then per synset `lexfile TAB hypernyms TAB instances`.
    fn parse_synsets(&mut self, text: &str) -> Result<(), WordNetError> {
        const FILE: &str = "synsets";
        let mut lines = numbered_lines(text);
        let (_, _, head) = lines.next().ok_or(line_error(FILE, 1, "empty file"))?;
        let names =
            head.strip_prefix("lexnames\t")
                .ok_or(line_error(FILE, 1, "no lexnames header"))?;
        self.lexnames = names.split('\t').map(str::to_string).collect();
        for (line, _, l) in lines {
            let err = |problem| line_error(FILE, line, problem);
            let mut fields = l.split('\t');
            let (Some(lexfile), Some(hyper), Some(inst), None) =
                (fields.next(), fields.next(), fields.next(), fields.next())
            else {
                return Err(err("not three fields"));
            };
            let lexfile: u8 = lexfile.parse().map_err(|_| err("bad lexfile"))?;
            if usize::from(lexfile) >= self.lexnames.len() {
                return Err(err("lexfile beyond the lexnames"));
            }
            let start = self.pointers.len() as u32;
            push_ids(hyper, &mut self.pointers).map_err(|_| err("bad synset id"))?;
            let instances_from = self.pointers.len() as u32;
            push_ids(inst, &mut self.pointers).map_err(|_| err("bad synset id"))?;
            self.synsets.push(SynsetRec {
                lexfile,
                pointers: span(start as usize, self.pointers.len() - start as usize),
                instances_from,
                lemmas: Span::default(),
            });
        }
        let n = self.synsets.len() as u32;
        if let Some(i) = self.synsets.iter().position(|r| {
            self.pointers
                .get(r.pointers.range())
                .is_none_or(|ps| ps.iter().any(|p| p.0 >= n))
        }) {
            return Err(line_error(FILE, i + 2, "hypernym beyond the synsets"));
        }
        Ok(())
    }

    /// `lemma TAB sense...`, a sense being `id[,count[,position]]`. Returns each sense's
    /// position among its synset's words, for [`WordNet::invert_senses`].
    fn parse_nouns(&mut self, text: &str) -> Result<Vec<u8>, WordNetError> {
        const FILE: &str = "nouns";
        let mut positions = Vec::new();
        let n = self.synsets.len() as u32;
        let mut prev = "";
        for (line, start, l) in numbered_lines(text) {
            let err = |problem| line_error(FILE, line, problem);
            let (lemma, senses) = l.split_once('\t').ok_or(err("no tab"))?;
            if lemma <= prev {
                return Err(err("lemmas not sorted"));
            }
            prev = lemma;
            self.noun_lemmas.push(span(start, lemma.len()));
            let first = self.senses.len() as u32;
            for sense in senses.split(' ') {
                let mut f = sense.split(',');
                let num = |s: Option<&str>| s.map_or(Ok(0), str::parse::<u32>);
                let id = f.next().map(str::parse::<u32>);
                let (Some(Ok(id)), Ok(count), Ok(pos), None) =
                    (id, num(f.next()), num(f.next()), f.next())
                else {
                    return Err(err("bad sense"));
                };
                if id >= n {
                    return Err(err("sense beyond the synsets"));
                }
                let pos = u8::try_from(pos).map_err(|_| err("bad position"))?;
                self.senses.push(Sense {
                    synset: SynsetId(id),
                    count,
                });
                positions.push(pos);
            }
            self.noun_senses.push(Span {
                start: first,
                end: self.senses.len() as u32,
            });
        }
        Ok(positions)
    }

    /// Builds each synset's lemma list from the lemma index, in WordNet's word order.
    fn invert_senses(&mut self, positions: &[u8]) -> Result<(), WordNetError> {
        let mut starts = vec![0u32; self.synsets.len() + 1];
        for s in &self.senses {
            starts[s.synset.index() + 1] += 1;
        }
        for i in 1..starts.len() {
            starts[i] += starts[i - 1];
        }
        let mut fill = starts.clone();
        let mut slots = vec![(0u8, 0u32); self.senses.len()];
        for (lemma, range) in self.noun_senses.iter().enumerate() {
            for k in range.range() {
                let s = self.senses[k].synset.index();
                slots[fill[s] as usize] = (positions[k], lemma as u32);
                fill[s] += 1;
            }
        }
        for (i, rec) in self.synsets.iter_mut().enumerate() {
            rec.lemmas = Span {
                start: starts[i],
                end: starts[i + 1],
            };
            if rec.lemmas.start == rec.lemmas.end {
                return Err(line_error("synsets", i + 2, "synset without a noun lemma"));
            }
            slots[rec.lemmas.range()].sort_unstable();
        }
        self.synset_lemmas = slots.into_iter().map(|(_, lemma)| lemma).collect();
        Ok(())
    }

    /// `lemma TAB parts of speech` (letters among `v`, `a`, `r`).
    fn parse_words(&mut self, text: &str) -> Result<(), WordNetError> {
        const FILE: &str = "words";
        let mut prev = "";
        for (line, start, l) in numbered_lines(text) {
            let err = |problem| line_error(FILE, line, problem);
            let (lemma, letters) = l.split_once('\t').ok_or(err("no tab"))?;
            if lemma <= prev {
                return Err(err("lemmas not sorted"));
            }
            prev = lemma;
            let mut bits = 0;
            for c in letters.chars() {
                bits |= Pos::from_letter(c).ok_or(err("bad part of speech"))?.bit();
            }
            self.words.push(span(start, lemma.len()));
            self.word_pos.push(bits);
        }
        Ok(())
    }

    /// `pos TAB inflected TAB base [TAB base...]`, sorted by part of speech, then form.
    fn parse_exceptions(&mut self, text: &str) -> Result<(), WordNetError> {
        const FILE: &str = "exceptions";
        for (line, start, l) in numbered_lines(text) {
            let err = |problem| line_error(FILE, line, problem);
            let mut parts = l.splitn(3, '\t');
            let (Some(letter), Some(form), Some(bases)) =
                (parts.next(), parts.next(), parts.next())
            else {
                return Err(err("not three fields"));
            };
            let mut letters = letter.chars();
            let (Some(pos), None) = (letters.next().and_then(Pos::from_letter), letters.next())
            else {
                return Err(err("bad part of speech"));
            };
            let list = &mut self.exceptions[pos as usize];
            if list.last().is_some_and(|&(k, _)| Span::of(text, k) >= form) {
                return Err(err("forms not sorted"));
            }
            let form_start = start + letter.len() + 1;
            let bases_start = form_start + form.len() + 1;
            list.push((span(form_start, form.len()), span(bases_start, bases.len())));
        }
        Ok(())
    }

    /// Number of noun synsets.
    pub fn synset_count(&self) -> usize {
        self.synsets.len()
    }

    /// Number of noun lemmas.
    pub fn noun_lemma_count(&self) -> usize {
        self.noun_lemmas.len()
    }

    /// Every noun lemma, sorted by bytes (words separated by spaces or as WordNet writes
    /// them).
    pub fn noun_lemmas(&self) -> impl Iterator<Item = &str> {
        self.noun_lemmas
            .iter()
            .map(|&s| Span::of(&self.noun_text, s))
    }

    fn noun_index(&self, lemma: &str) -> Option<usize> {
        find(&self.noun_text, &self.noun_lemmas, lemma)
    }

    /// Is `lemma` (exactly, not inflected) a lemma of `pos`? Case, underscores and runs of
    /// spaces do not matter.
    pub fn is_lemma(&self, lemma: &str, pos: Pos) -> bool {
        self.is_normal_lemma(&normalize(lemma), pos)
    }

    fn is_normal_lemma(&self, lemma: &str, pos: Pos) -> bool {
        match pos {
            Pos::Noun => self.noun_index(lemma).is_some(),
            _ => find(&self.word_text, &self.words, lemma)
                .and_then(|i| self.word_pos.get(i))
                .is_some_and(|bits| bits & pos.bit() != 0),
        }
    }

    /// Can `word`, in any inflected form, be `pos`? ("shelves", Noun), ("providing", Verb).
    pub fn has_pos(&self, word: &str, pos: Pos) -> bool {
        !self.base_forms(word, pos).is_empty()
    }

    /// The base forms of `word` as `pos`, by WordNet's morphy: the word itself if it is a
    /// lemma, its exception-list entries ("knives" -> "knife", "ran" -> "run"), then the
    /// detachment rules ("providing" -> "provide"), keeping only lemmas of `pos`, each once,
    /// in that order. A run of words is tried whole and with the exceptions of its last word
    /// ("kitchen knives" -> "kitchen knife"); the rules reach the last word anyway. Empty when
    /// the word cannot be `pos`. Note that a plural can itself be a lemma: "glasses" gives
    /// ["glasses" (spectacles), "glass"].
    pub fn base_forms(&self, word: &str, pos: Pos) -> Vec<String> {
        let w = normalize(word);
        let mut out: Vec<String> = Vec::new();
        let mut keep = |candidate: Cow<'_, str>| {
            if !candidate.is_empty()
                && !out.iter().any(|o| *o == candidate)
                && self.is_normal_lemma(&candidate, pos)
            {
                out.push(candidate.into_owned());
            }
        };
        keep(Cow::Borrowed(&w));
        for base in self.exception_bases(&w, pos) {
            keep(Cow::Borrowed(base));
        }
        for (suffix, ending) in pos.rules() {
            if let Some(stem) = w.strip_suffix(suffix)
                && !stem.is_empty()
                && !stem.ends_with(' ')
            {
                keep(Cow::Owned(format!("{stem}{ending}")));
            }
        }
        if let Some((head, last)) = w.rsplit_once(' ') {
            for base in self.exception_bases(last, pos) {
                keep(Cow::Owned(format!("{head} {base}")));
            }
        }
        out
    }

    /// The exception-list bases of an inflected form (unfiltered).
    fn exception_bases(&self, form: &str, pos: Pos) -> impl Iterator<Item = &str> {
        let list = &self.exceptions[pos as usize];
        let bases = list
            .binary_search_by(|&(k, _)| Span::of(&self.exc_text, k).cmp(form))
            .ok()
            .and_then(|i| list.get(i))
            .map_or("", |&(_, b)| Span::of(&self.exc_text, b));
        bases.split('\t').filter(|b| !b.is_empty())
    }

    /// The senses of a noun lemma (exactly, not inflected: see [`WordNet::base_forms`]) in
    /// WordNet's sense order; empty when it is no noun.
    pub fn noun_senses(&self, lemma: &str) -> &[Sense] {
        self.noun_index(&normalize(lemma))
            .and_then(|i| self.noun_senses.get(i))
            .and_then(|r| self.senses.get(r.range()))
            .unwrap_or(&[])
    }

    /// The lexicographer file of a synset ("noun.artifact", "noun.feeling", "noun.food").
    pub fn lexname(&self, s: SynsetId) -> &str {
        self.synsets
            .get(s.index())
            .and_then(|r| self.lexnames.get(usize::from(r.lexfile)))
            .map_or("", String::as_str)
    }

    /// Direct hypernyms, instance hypernyms included (after the plain ones), in WordNet order.
    pub fn hypernyms(&self, s: SynsetId) -> &[SynsetId] {
        self.synsets
            .get(s.index())
            .and_then(|r| self.pointers.get(r.pointers.range()))
            .unwrap_or(&[])
    }

    /// Instance hypernyms only: non-empty when the synset is a named individual ("paris.n.01"
    /// is an instance of "national_capital.n.01").
    pub fn instance_hypernyms(&self, s: SynsetId) -> &[SynsetId] {
        self.synsets
            .get(s.index())
            .and_then(|r| {
                self.pointers
                    .get(r.instances_from as usize..r.pointers.end as usize)
            })
            .unwrap_or(&[])
    }

    /// Every hypernym of `s`, transitively (instance hypernyms included), with its distance
    /// in links, breadth-first: nearest first, then in WordNet's pointer order. `s` itself is
    /// not included. A synset reachable along two paths is listed once, at the shorter one.
    pub fn ancestors(&self, s: SynsetId) -> Vec<(SynsetId, u32)> {
        let mut out: Vec<(SynsetId, u32)> = Vec::new();
        let mut next = 0;
        let mut current = (s, 0);
        loop {
            for &h in self.hypernyms(current.0) {
                // Hypernym closures hold a few dozen synsets at most; a scan beats a set.
                if h != s && !out.iter().any(|&(a, _)| a == h) {
                    out.push((h, current.1 + 1));
                }
            }
            match out.get(next) {
                Some(&c) => current = c,
                None => return out,
            }
            next += 1;
        }
    }

    /// Is `s` the synset `ancestor` or one of its hyponyms (instances included)?
    pub fn is_a(&self, s: SynsetId, ancestor: SynsetId) -> bool {
        s == ancestor || self.ancestors(s).iter().any(|&(a, _)| a == ancestor)
    }

    /// The noun lemmas of a synset in WordNet's order (lower case, spaces between words).
    pub fn lemmas(&self, s: SynsetId) -> impl ExactSizeIterator<Item = &str> {
        let ids = self
            .synsets
            .get(s.index())
            .and_then(|r| self.synset_lemmas.get(r.lemmas.range()))
            .unwrap_or(&[]);
        ids.iter().map(|&i| self.noun_lemma(i as usize))
    }

    fn noun_lemma(&self, i: usize) -> &str {
        self.noun_lemmas
            .get(i)
            .map_or("", |&s| Span::of(&self.noun_text, s))
    }

    /// The synset an NLTK-style name denotes: "artifact.n.01" is the first noun sense of
    /// "artifact"; underscores stand for spaces ("lighting_fixture.n.01"). Only nouns (`n`).
    pub fn synset(&self, name: &str) -> Option<SynsetId> {
        let mut parts = name.rsplitn(3, '.');
        let (Some(number), Some("n"), Some(lemma)) = (parts.next(), parts.next(), parts.next())
        else {
            return None;
        };
        let number: usize = number.parse().ok()?;
        let sense = self.noun_senses(lemma).get(number.checked_sub(1)?)?;
        Some(sense.synset)
    }

    /// The NLTK-style name of a synset: its first lemma, with underscores for spaces, and the
    /// synset's sense number for that lemma ("sofa.n.01" for the synset of "couch" too).
    pub fn name(&self, s: SynsetId) -> String {
        let lemma = self.lemmas(s).next().unwrap_or("");
        let number = self
            .noun_senses(lemma)
            .iter()
            .position(|x| x.synset == s)
            .map_or(0, |i| i + 1);
        format!("{}.n.{number:02}", lemma.replace(' ', "_"))
    }

    /// The longest run of words starting at `words[0]` (up to [`MAX_NOUN_WORDS`]) that is a
    /// noun lemma once its last word is reduced to a base form: (words used, lemma).
    /// ["wine", "coolers", "in"] -> (2, "wine cooler"). The lemma is the first of
    /// [`WordNet::base_forms`], so a plural that is itself a lemma stays ("glasses").
    pub fn longest_noun(&self, words: &[&str]) -> Option<(usize, String)> {
        (1..=words.len().min(MAX_NOUN_WORDS)).rev().find_map(|n| {
            let phrase = words.get(..n)?.join(" ");
            let lemma = self.base_forms(&phrase, Pos::Noun).into_iter().next()?;
            Some((n, lemma))
        })
    }
}

/// The compiled-in WordNet, loaded on first use. A file that does not load is logged once
/// and leaves an empty database (every word unknown); `compiled_wordnet_parses` keeps that
/// from shipping.
pub fn wordnet() -> &'static WordNet {
    static WORDNET: OnceLock<WordNet> = OnceLock::new();
    WORDNET.get_or_init(|| {
        WordNet::compiled().unwrap_or_else(|e| {
            tracing::error!("{e}; WordNet lookups will find nothing");
            WordNet::default()
        })
    })
}

fn inflate(file: &'static str, bytes: &[u8]) -> Result<String, WordNetError> {
    let raw = miniz_oxide::inflate::decompress_to_vec_zlib(bytes)
        .map_err(|source| WordNetError::Inflate { file, source })?;
    String::from_utf8(raw).map_err(|source| WordNetError::Utf8 { file, source })
}

fn line_error(file: &'static str, line: usize, problem: &'static str) -> WordNetError {
    WordNetError::Line {
        file,
        line,
        problem,
    }
}

/// Lines with their 1-based number and byte offset.
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, usize, &str)> {
    text.split_inclusive('\n')
        .scan(0, |offset, l| {
            let start = *offset;
            *offset += l.len();
            Some((start, l.strip_suffix('\n').unwrap_or(l)))
        })
        .enumerate()
        .map(|(i, (start, l))| (i + 1, start, l))
}

/// Appends the space-separated synset ids of `list`.
fn push_ids(list: &str, into: &mut Vec<SynsetId>) -> Result<(), std::num::ParseIntError> {
    for id in list.split(' ').filter(|s| !s.is_empty()) {
        into.push(SynsetId(id.parse()?));
    }
    Ok(())
}

fn span(start: usize, len: usize) -> Span {
    Span {
        start: start as u32,
        end: (start + len) as u32,
    }
}

/// Index of `key` among sorted spans of `text`.
fn find(text: &str, spans: &[Span], key: &str) -> Option<usize> {
    spans.binary_search_by(|&s| Span::of(text, s).cmp(key)).ok()
}

/// A word or phrase as the data writes lemmas: lower case, single spaces, no underscores.
fn normalize(word: &str) -> Cow<'_, str> {
    let clean = !word.starts_with(' ')
        && !word.ends_with(' ')
        && !word.contains("  ")
        && word
            .chars()
            .all(|c| !c.is_uppercase() && c != '_' && (c == ' ' || !c.is_whitespace()));
    if clean {
        return Cow::Borrowed(word);
    }
    let lower = word.to_lowercase().replace('_', " ");
    Cow::Owned(lower.split_whitespace().collect::<Vec<_>>().join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wn() -> &'static WordNet {
        wordnet()
    }

    fn id(name: &str) -> SynsetId {
        wn().synset(name)
            .unwrap_or_else(|| panic!("{name} names no synset"))
    }

    /// Does some noun sense of `lemma` fall under `ancestor`?
    fn has_sense_under(lemma: &str, ancestor: &str) -> bool {
        let a = id(ancestor);
        wn().noun_senses(lemma)
            .iter()
            .any(|s| wn().is_a(s.synset, a))
    }

    fn chain(s: SynsetId) -> String {
        let mut out = vec![format!("{} [{}]", wn().name(s), wn().lexname(s))];
        out.extend(
            wn().ancestors(s)
                .iter()
                .map(|&(a, d)| format!("{d}:{}", wn().name(a))),
        );
        out.join(" > ")
    }

    #[test]
    fn compiled_wordnet_parses() {
        let start = std::time::Instant::now();
        let w = WordNet::compiled().unwrap();
        // Release load time is measured separately; this line shows the debug cost.
        println!("WordNet::compiled() took {:?}", start.elapsed());
        // The sizes of WordNet 3.0's noun index and data.noun.
        assert_eq!(w.noun_lemma_count(), 117_798);
        assert_eq!(w.synset_count(), 82_115);
        assert!(w.words.len() > 30_000, "{} other lemmas", w.words.len());
        assert!(w.exceptions.iter().all(|e| !e.is_empty()));
    }

    #[test]
    fn every_synset_name_round_trips() {
        // Also checks that every synset has a lemma listing it among its senses.
        for i in 0..wn().synset_count() as u32 {
            let s = SynsetId(i);
            assert_eq!(wn().synset(&wn().name(s)), Some(s), "{}", wn().name(s));
        }
    }

    #[test]
    fn a_bad_line_is_reported_with_its_file_and_number() {
        let texts = Texts {
            nouns: "thing\t0\n".into(),
            synsets: "lexnames\tadj.all\n0\t\t\n0\t7\t\n".into(),
            words: String::new(),
            exceptions: String::new(),
        };
        let e = WordNet::parse(texts).unwrap_err();
        assert!(
            matches!(
                e,
                WordNetError::Line {
                    file: "synsets",
                    line: 3,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn chandelier_is_a_lighting_fixture_and_an_artifact() {
        let senses = wn().noun_senses("chandelier");
        assert_eq!(senses.len(), 1);
        // cntlist.rev: chandelier%1:06:00:: tagged 3 times.
        assert_eq!(senses[0].count, 3);
        assert_eq!(wn().lexname(senses[0].synset), "noun.artifact");
        for a in ["lighting_fixture.n.01", "fixture.n.01", "artifact.n.01"] {
            assert!(has_sense_under("chandelier", a), "{a}");
        }
        let near: Vec<(String, u32)> = wn()
            .ancestors(senses[0].synset)
            .iter()
            .take(3)
            .map(|&(a, d)| (wn().name(a), d))
            .collect();
        assert_eq!(
            near,
            [
                ("lighting_fixture.n.01".to_string(), 1),
                ("fixture.n.01".to_string(), 2),
                ("artifact.n.01".to_string(), 3)
            ]
        );
    }

    #[test]
    fn ancestors_are_nearest_first_and_reach_entity() {
        let entity = id("entity.n.01");
        for w in ["chandelier", "printer", "tension", "paris", "sofa", "space"] {
            for s in wn().noun_senses(w) {
                let anc = wn().ancestors(s.synset);
                assert!(anc.windows(2).all(|p| p[0].1 <= p[1].1), "{w}");
                // Not necessarily last: with two parents, entity.n.01 can be nearer along
                // one path than object.n.01 is along the other (space.n.02).
                assert!(anc.iter().any(|&(a, _)| a == entity), "{w}");
            }
        }
    }

    #[test]
    fn a_printer_is_a_machine_in_one_sense_and_a_person_in_another() {
        assert!(has_sense_under("printer", "machine.n.01"));
        assert!(has_sense_under("printer", "person.n.01"));
        assert_eq!(wn().lexname(id("printer.n.01")), "noun.person");
    }

    #[test]
    fn abstract_prompt_words_have_no_artifact_sense() {
        for w in [
            "unease",
            "scream",
            "tension",
            "juxtaposition",
            "chaos",
            "atmosphere",
        ] {
            assert!(!wn().noun_senses(w).is_empty(), "{w} is a noun");
            assert!(!has_sense_under(w, "artifact.n.01"), "{w}");
        }
        // Not artifacts, yet physical: a force, a location, a physical phenomenon, a region
        // and a gas. "Under physical_entity" alone does not make a thing one can place.
        assert!(!has_sense_under("unease", "physical_entity.n.01"));
        assert!(!has_sense_under("scream", "physical_entity.n.01"));
        for w in ["tension", "juxtaposition", "chaos", "atmosphere"] {
            assert!(has_sense_under(w, "physical_entity.n.01"), "{w}");
        }
        assert_eq!(wn().lexname(id("juxtaposition.n.02")), "noun.location");
        assert_eq!(wn().lexname(id("tension.n.04")), "noun.phenomenon");
    }

    #[test]
    fn lexnames_are_not_the_hierarchy() {
        // "seating.n.01" (room for sitting) is filed in noun.artifact but sits under
        // relation.n.01, and the methamphetamine sense of "glass" under drug.n.01.
        for s in ["seating.n.01", "glass.n.05"] {
            assert_eq!(wn().lexname(id(s)), "noun.artifact");
            assert!(!wn().is_a(id(s), id("artifact.n.01")), "{s}");
        }
    }

    #[test]
    fn style_words_are_adjectives_not_nouns() {
        for w in ["stylish", "practical", "warm"] {
            assert!(wn().is_lemma(w, Pos::Adj), "{w}");
            assert!(!wn().has_pos(w, Pos::Noun), "{w}");
        }
        // "warm" is also a verb and an adverb; "cozy" is also a noun (a tea cosy).
        assert!(wn().is_lemma("warm", Pos::Verb) && wn().is_lemma("warm", Pos::Adv));
        assert!(has_sense_under("cozy", "artifact.n.01"));
        assert!(wn().has_pos("warmer", Pos::Adj));
    }

    #[test]
    fn morphy_finds_base_forms() {
        let b = |w: &str, pos| wn().base_forms(w, pos);
        assert_eq!(b("shelves", Pos::Noun), ["shelf"]);
        assert_eq!(b("knives", Pos::Noun), ["knife"]);
        // "glasses" is a lemma of its own (spectacles) before the plural of "glass".
        assert_eq!(b("glasses", Pos::Noun), ["glasses", "glass"]);
        assert_eq!(b("providing", Pos::Verb), ["provide"]);
        assert_eq!(b("creating", Pos::Verb), ["create"]);
        assert_eq!(b("ran", Pos::Verb), ["run"]);
        assert_eq!(b("better", Pos::Adj), ["better", "good", "well"]);
        assert_eq!(b("better", Pos::Adv), ["better", "well"]);
        assert_eq!(b("Coffee_Tables", Pos::Noun), ["coffee table"]);
        // An exception on the last word of a phrase.
        assert_eq!(b("carving knives", Pos::Noun), ["carving knife"]);
        assert!(wn().has_pos("reflecting", Pos::Verb));
        assert!(!wn().has_pos("providing", Pos::Noun));
        assert!(b("xyzzy", Pos::Noun).is_empty());
    }

    #[test]
    fn sofa_and_couch_share_a_synset() {
        let sofa = wn().noun_senses("sofa")[0].synset;
        assert_eq!(wn().noun_senses("couch")[0].synset, sofa);
        assert_eq!(wn().name(sofa), "sofa.n.01");
        assert_eq!(wn().synset("couch.n.01"), Some(sofa));
        assert_eq!(
            wn().lemmas(sofa).collect::<Vec<_>>(),
            ["sofa", "couch", "lounge"]
        );
    }

    #[test]
    fn multiword_nouns() {
        for w in ["coffee table", "wine cooler", "dining table"] {
            assert!(wn().is_lemma(w, Pos::Noun), "{w}");
            assert!(has_sense_under(w, "artifact.n.01"), "{w}");
        }
        let n = |ws: &[&str]| wn().longest_noun(ws);
        assert_eq!(
            n(&["wine", "coolers", "in"]),
            Some((2, "wine cooler".into()))
        );
        assert_eq!(n(&["Dining", "tables"]), Some((2, "dining table".into())));
        // WordNet spells it "wineglass": "wine glasses" is no lemma, "wine" is.
        assert_eq!(n(&["wine", "glasses"]), Some((1, "wine".into())));
        assert_eq!(n(&["with", "a"]), None);
    }

    #[test]
    fn instances_are_marked() {
        let paris = id("paris.n.01");
        assert!(!wn().instance_hypernyms(paris).is_empty());
        assert!(wn().is_a(paris, id("city.n.01")));
        assert!(wn().instance_hypernyms(id("sofa.n.01")).is_empty());
    }

    #[test]
    fn print_hypernym_chains() {
        // Not a check: run with --nocapture to see what the hierarchy says.
        for w in [
            "chandelier",
            "printer",
            "tension",
            "atmosphere",
            "wine cooler",
            "cozy",
        ] {
            for s in wn().noun_senses(w) {
                println!("{w} ({}): {}", s.count, chain(s.synset));
            }
        }
    }
}
