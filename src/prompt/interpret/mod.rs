//! From chunks to mentions: who is the subject, what a "with", "has", "each" or preposition
//! attaches to, which phrases name an earlier object ("the table", "it", "the other bin"),
//! per-parent counts, place settings, groups, negation, and which room a clause is about.
//!
//! The rules are small and local (a clause at a time); they are tuned on the dev prompts and
//! written so that a phrase they do not understand is skipped, never misread as something
//! else when avoidable.

use std::ops::Range;

mod attach;
mod objects;

use super::chunk::{Chunk, Head, Item, Np, Pronoun};
use super::mentions::{Count, Group, GroupKind, Mention};
use super::relations::{Relation, RelationKind, Target, landmark_target};
use super::rooms::{self, RoomReading, Scope};
use crate::words::lexicon::Lexicon;
use crate::words::tokens::Token;

/// A reference to (a member or part of) a mention.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Ref {
    m: usize,
    instance: Option<u32>,
    part: Option<String>,
}

impl Ref {
    fn new(m: usize) -> Ref {
        Ref {
            m,
            instance: None,
            part: None,
        }
    }
}

/// How new noun phrases relate to what came before.
#[derive(Debug, Clone, PartialEq)]
enum Ctx {
    /// Contents of the room.
    Room,
    /// "X has/holds/with ...": contents of X, and how they were introduced.
    Holder(Vec<Ref>, Intro),
    /// ", each with/containing ...": per-parent contents.
    Each(Vec<Ref>),
    /// "each setting has", "set for 4 with ...": per place setting of a table.
    Setting(usize),
    /// "a tea set with ...", "supplies including ...": members replacing a generic mention.
    Members(usize),
    /// "X covers Y": Y is what X lies on.
    Cover(Vec<Ref>),
    /// "styled like Y", "inspired by Y": Y gives styles.
    StyleOf(Vec<Ref>),
}

/// How a holder's contents were introduced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Intro {
    /// "X with Y": on X when X carries things, in X when it only contains them.
    With,
    /// "X has Y", "X holding Y"; `true` for "contains".
    Verb(bool),
    /// "X of Y".
    Of,
}

/// A fronted relation ("On the table is a tea set"): preposition class, landmark, target,
/// target instance, and whether the target was "each"/"every" ("Next to every bed stands a
/// locker": one thing per target).
type Fronted = (String, Option<String>, Target, Option<u32>, bool);

/// A preposition waiting for its object.
#[derive(Debug, Clone)]
struct Pending {
    class: String,
    attach: Vec<Ref>,
    zone: bool,
    each: bool,
}

/// State of the clause being read.
#[derive(Debug, Clone)]
struct Clause {
    subject: Vec<Ref>,
    subject_is_room: bool,
    zone: bool,
    zone_relations: Vec<Relation>,
    verb: Option<String>,
    focus: Vec<Ref>,
    ctx: Ctx,
    stack: Vec<Ctx>,
    pending: Option<Pending>,
    negate: bool,
    carry_at_least: bool,
    last_prep_obj: Option<Ref>,
    last_np: Vec<Ref>,
    after_sep: bool,
    sep_was_comma: bool,
    and_partner: Option<Ref>,
    group_open: Option<Group>,
    fronted: Option<Fronted>,
    relative: bool,
    skip_np: bool,
    skip_next: bool,
    room_with: bool,
    rel_scope: bool,
    pronoun_subject: bool,
    of_once: bool,
    list_since_comma: Vec<Ref>,
    /// "Two nightstands each hold ...": what the verb brings is per subject.
    each_subject: bool,
    /// A bare number ("..., eight in total").
    bare_number: Option<u32>,
    /// ", each topped with": the "with" keeps the per-parent context.
    each_with: bool,
    /// The parents of the clause's ", each ...", for a second participle joined by "and"
    /// (", each ringed by four chairs and topped with a caddy").
    distributed: Vec<Ref>,
    /// The phrase at hand is an item of a list that goes on to its last item ("A, B and C"
    /// up to the end of the sentence).
    list_goes_on: bool,
}

impl Clause {
    fn new() -> Clause {
        Clause {
            subject: Vec::new(),
            subject_is_room: false,
            zone: false,
            zone_relations: Vec::new(),
            verb: None,
            focus: Vec::new(),
            ctx: Ctx::Room,
            stack: Vec::new(),
            pending: None,
            negate: false,
            carry_at_least: false,
            last_prep_obj: None,
            last_np: Vec::new(),
            after_sep: false,
            sep_was_comma: false,
            and_partner: None,
            group_open: None,
            fronted: None,
            relative: false,
            skip_np: false,
            skip_next: false,
            room_with: false,
            rel_scope: false,
            pronoun_subject: false,
            of_once: false,
            list_since_comma: Vec::new(),
            each_subject: false,
            bare_number: None,
            each_with: false,
            distributed: Vec::new(),
            list_goes_on: false,
        }
    }
}

/// The interpreter over a whole prompt.
pub(crate) struct Interp<'a> {
    lex: &'a Lexicon,
    tokens: &'a [Token],
    /// Mentions so far.
    pub mentions: Vec<Mention>,
    /// Mentions merged into others (dropped at the end), with their replacement.
    pub absorbed: Vec<Option<Option<usize>>>,
    /// Rooms.
    pub rooms: Vec<RoomReading>,
    /// Token ranges per room.
    pub spans: Vec<Vec<Range<usize>>>,
    scope: Scope,
    room: usize,
    next_group: u32,
    settings_table: Option<usize>,
    last_one: Option<usize>,
    /// "Each X has ...": (first mention of the sentence, the other rooms to copy into, the
    /// first of the room's token ranges that the sentence recorded).
    each_rooms: Option<(usize, Vec<usize>, usize)>,
    /// A sentence has named its room (until then, objects go where they belong).
    focused: bool,
    /// The rooms the last plural room phrase named ("three bedrooms"), for the phrases that
    /// pick among them ("the largest", "the other two"), and those already picked.
    room_group: Vec<usize>,
    picked: Vec<usize>,
    /// How many mentions there were when the group was named.
    group_at: usize,
}

fn is_room_placement(kind: RelationKind, target: Target) -> bool {
    match target {
        Target::Wall | Target::Corner | Target::Window | Target::Entrance | Target::Room => {
            !matches!(kind, RelationKind::On)
        }
        _ => false,
    }
}

impl<'a> Interp<'a> {
    /// A new interpreter over `tokens` with the rooms of the structure.
    pub fn new(
        lex: &'a Lexicon,
        tokens: &'a [Token],
        rooms: Vec<RoomReading>,
        scope: Scope,
    ) -> Interp<'a> {
        let n = rooms.len().max(1);
        Interp {
            lex,
            tokens,
            mentions: Vec::new(),
            absorbed: Vec::new(),
            rooms,
            spans: vec![Vec::new(); n],
            scope,
            room: 0,
            next_group: 0,
            settings_table: None,
            last_one: None,
            each_rooms: None,
            focused: false,
            room_group: Vec::new(),
            picked: Vec::new(),
            group_at: 0,
        }
    }

    fn alive(&self, i: usize) -> bool {
        self.absorbed.get(i).is_some_and(Option::is_none)
    }

    fn new_group(&mut self, kind: GroupKind) -> Group {
        self.next_group += 1;
        Group {
            kind,
            id: self.next_group,
        }
    }

    /// Reads one sentence.
    pub fn sentence(&mut self, chunks: &[Chunk]) {
        if self.scope == Scope::House
            && let Some(i) = self.fronted_room(chunks)
        {
            // "In the living room, a sofa faces ...", "At the bar, six stools ...".
            self.room = i;
            self.focused = true;
        } else if self.scope == Scope::House
            && !self.focused
            && let Some(i) = self.room_by_items(chunks)
        {
            self.room = i;
        }
        self.sentence_chunks(chunks);
        if let Some((first, rooms, span)) = self.each_rooms.take() {
            self.copy_to_rooms(first, &rooms, span);
        }
    }

    /// The room of a sentence that opens with a place phrase naming one ("In the kitchen,",
    /// "In the family bathroom there is ...", "In the hall stands ...").
    fn fronted_room(&self, chunks: &[Chunk]) -> Option<usize> {
        let [first, second, third, ..] = chunks else {
            return None;
        };
        let (Item::Prep(_), Item::Np(np)) = (&first.item, &second.item) else {
            return None;
        };
        let word = self.tokens.get(third.range.start).map(|t| t.text.as_str());
        let opens = matches!(third.item, Item::Comma | Item::Verb(..)) || word == Some("there");
        if !opens {
            return None;
        }
        if !matches!(np.head, Head::Room { .. }) {
            return None;
        }
        rooms::resolve(&self.rooms, np, self.room).filter(|&i| i != self.room || self.focused)
    }

    /// Before any sentence named its room: the room the sentence's objects belong in (a
    /// dining table goes to the kitchen when the house has no dining room), by the house
    /// table of where objects go.
    fn room_by_items(&self, chunks: &[Chunk]) -> Option<usize> {
        let house = crate::knowledge::rooms::registry().house();
        if chunks
            .iter()
            .any(|c| matches!(&c.item, Item::Np(np) if matches!(np.head, Head::Room { .. })))
        {
            return None;
        }
        chunks.iter().find_map(|c| {
            let Item::Np(np) = &c.item else { return None };
            let Head::Object { canonical, .. } = &np.head else {
                return None;
            };
            house.items_to_rooms.get(canonical)?.iter().find_map(|t| {
                self.rooms
                    .iter()
                    .position(|r| crate::knowledge::rooms::registry().is_a(&r.room_type, t))
            })
        })
    }

    /// Copies the mentions from `first` on into each of `rooms` (references among them
    /// follow the copies), and the room's token ranges from `span` on (the words each room's
    /// own prompt is made of).
    fn copy_to_rooms(&mut self, first: usize, rooms: &[usize], span: usize) {
        let text: Vec<Range<usize>> = self
            .spans
            .get(self.room)
            .map(|s| s.iter().skip(span).cloned().collect())
            .unwrap_or_default();
        for &room in rooms {
            if let Some(sp) = self.spans.get_mut(room) {
                sp.extend(text.iter().cloned());
            }
        }
        let end = self.mentions.len();
        for &room in rooms {
            let base = self.mentions.len();
            for i in first..end {
                let dead = !self.alive(i);
                let mut m = self.mentions[i].clone();
                m.room = room;
                let map = |t: usize| {
                    if (first..end).contains(&t) {
                        base + (t - first)
                    } else {
                        t
                    }
                };
                for r in &mut m.relations {
                    if let Target::Mention(t) = r.target {
                        r.target = Target::Mention(map(t));
                    }
                }
                m.per = match m.per {
                    Some(super::mentions::Per::Each { parent }) => {
                        Some(super::mentions::Per::Each {
                            parent: map(parent),
                        })
                    }
                    Some(super::mentions::Per::Setting { table }) => {
                        Some(super::mentions::Per::Setting { table: map(table) })
                    }
                    None => None,
                };
                self.mentions.push(m);
                // A merged source leaves a dropped copy, so indices stay aligned.
                self.absorbed.push(if dead { Some(None) } else { None });
            }
        }
    }

    fn sentence_chunks(&mut self, chunks: &[Chunk]) {
        let mut c = Clause::new();
        let mut k = 0;
        while k < chunks.len() {
            let chunk = &chunks[k];
            if let Some(sp) = self.spans.get_mut(self.room) {
                sp.push(chunk.range.clone());
            }
            if c.skip_next
                && (matches!(chunk.item, Item::With | Item::Verb(..) | Item::Prep(_))
                    || self.participle(chunk))
            {
                c.skip_next = false;
                k += 1;
                continue;
            }
            c.skip_next = false;
            match &chunk.item {
                Item::Np(np) => self.np(&mut c, np, chunk, chunks, k),
                Item::Prep(class) => self.prep(
                    &mut c,
                    class,
                    chunks.get(k.wrapping_sub(1)).map(|x| &x.item),
                ),
                Item::Verb(class, word) => self.verb(&mut c, class, word, chunks, k),
                Item::With if c.each_with => c.each_with = false,
                Item::With => {
                    if let Some(skip) = self.features_after_with(&mut c, chunks, k) {
                        k = skip;
                        continue;
                    }
                    self.with(&mut c);
                }
                Item::Without => c.negate = true,
                Item::Each => self.each(&mut c, chunks, k),
                Item::Comma | Item::And => {
                    let comma = chunk.item == Item::Comma;
                    if comma {
                        c.group_open = None;
                        c.list_since_comma.clear();
                        if c.rel_scope {
                            // "where one displays X and the other displays Y, pet beds ...":
                            // the relative clause ends here.
                            c.rel_scope = false;
                            c.ctx = Ctx::Room;
                            c.stack.clear();
                        }
                    }
                    c.pending = None;
                    // "five tables, each with two chairs, plus a banquette": an additive
                    // conjunction after a comma ends the per-parent list.
                    if !comma
                        && matches!(c.ctx, Ctx::Each(_))
                        && k > 0
                        && chunks[k - 1].item == Item::Comma
                        && self.additive(chunk)
                    {
                        c.ctx = Ctx::Room;
                        c.stack.clear();
                    }
                    if c.of_once {
                        // "a cup of tea and two books": the "of" phrase is over.
                        c.of_once = false;
                        self.pop_ctx(&mut c);
                    }
                    c.sep_was_comma = comma || (c.after_sep && c.sep_was_comma);
                    c.after_sep = true;
                    // "A printer and a shredder sit on a table": before the clause's verb an
                    // "and" without a comma joins its subject, not a new clause.
                    let joins_subject = !comma && c.verb.is_none() && !c.subject.is_empty();
                    if !joins_subject && self.new_clause_follows(chunks, k) {
                        let room = self.room;
                        c = Clause::new();
                        self.room = room;
                    }
                }
                Item::Relative => c.relative = true,
                Item::InTotal => self.in_total(&c),
                Item::SetFor => self.set_for(&mut c, chunks, k),
                Item::For => {
                    c.skip_np = matches!(chunks.get(k + 1).map(|x| &x.item), Some(Item::Np(np)) if !matches!(np.head, Head::Object { .. }));
                    // "a dining table for six", "a table for eight people": seats for that
                    // many, as a table set for them.
                    let seats = match chunks.get(k + 1).map(|x| &x.item) {
                        Some(Item::Np(np))
                            if !matches!(np.head, Head::Object { .. } | Head::Room { .. }) =>
                        {
                            np.number
                        }
                        // A bare number ending the sentence ("a table for six.").
                        Some(Item::Other(w)) => self.lex.number_word(w),
                        _ => None,
                    };
                    if let Some(n) = seats
                        && let Some(t) = c.last_np.first().map(|r| r.m)
                        && self.mentions[t].category.ends_with("table")
                        && self.mentions[t].place_settings.is_none()
                    {
                        self.mentions[t].place_settings = Some(n);
                    }
                }
                Item::Including => {
                    if let Some(f) = c.last_np.first().cloned() {
                        let ctx = if self.mentions[f.m].generic {
                            Ctx::Members(f.m)
                        } else {
                            Ctx::Holder(vec![f], Intro::With)
                        };
                        self.push_ctx(&mut c, ctx);
                    }
                }
                Item::Of => {
                    // "photographs of classic haircuts", "a statue of a horse": the subject
                    // of a picture, for the next phrase only, is a motif, not an object.
                    if let Some(f) = c.last_np.last().or(c.focus.first()).cloned()
                        && (crate::words::ground::is_depiction(&self.mentions[f.m].noun)
                            || crate::words::ground::is_depiction(&self.mentions[f.m].category))
                    {
                        self.push_ctx(&mut c, Ctx::StyleOf(vec![f]));
                        c.of_once = true;
                    } else if let Some(f) = c.focus.first().cloned()
                        && (self.mentions[f.m].container
                            || self
                                .lex
                                .lookup(&self.mentions[f.m].category)
                                .is_some_and(|e| e.holds))
                    {
                        self.push_ctx(&mut c, Ctx::Holder(vec![f], Intro::Of));
                        c.of_once = true;
                    }
                }
                // "There is no sofa; instead, two armchairs": what follows is there.
                Item::Other(w) if w == "instead" || w == "except" => c.negate = false,
                // "no television, because the aquarium is ...": a reason clause is no longer
                // under the negation.
                Item::Other(w) if matches!(w.as_str(), "because" | "since" | "so") => {
                    c.negate = false;
                }
                Item::Other(_) => {}
            }
            k += 1;
        }
    }

    fn push_ctx(&mut self, c: &mut Clause, ctx: Ctx) {
        let old = std::mem::replace(&mut c.ctx, ctx);
        c.stack.push(old);
    }

    fn pop_ctx(&mut self, c: &mut Clause) {
        if let Some(old) = c.stack.pop() {
            c.ctx = old;
        }
    }

    /// After "," or "and": does a new clause start (a phrase followed by its own verb)?
    fn new_clause_follows(&self, chunks: &[Chunk], k: usize) -> bool {
        let mut j = k + 1;
        // ", and the ...", ", while the ...", ", whereas the ...": a conjunction that joins
        // clauses.
        let contrast = |c: &Chunk| {
            self.tokens
                .get(c.range.start)
                .is_some_and(|t| matches!(t.text.as_str(), "while" | "whilst" | "whereas"))
        };
        if chunks
            .get(j)
            .is_some_and(|c| c.item == Item::And || contrast(c))
        {
            j += 1;
        }
        if !matches!(chunks.get(j).map(|c| &c.item), Some(Item::Np(_))) {
            return false;
        }
        j += 1;
        while let Some(c) = chunks.get(j) {
            match &c.item {
                // A participle ("a bookshelf filled with ...") does not start a clause.
                Item::Verb(class, word) => {
                    return class != "styled"
                        && class != "inspired"
                        && !word.ends_with("ed")
                        && !word.ends_with("ing");
                }
                Item::Np(_) | Item::With | Item::Prep(_) | Item::And | Item::Of | Item::For => {
                    j += 1
                }
                _ => return false,
            }
        }
        false
    }

    // ---- noun phrases -------------------------------------------------------------------

    fn np(&mut self, c: &mut Clause, np: &Np, chunk: &Chunk, chunks: &[Chunk], k: usize) {
        let next_is_verb = matches!(chunks.get(k + 1).map(|x| &x.item), Some(Item::Verb(..)));
        if c.skip_np {
            c.skip_np = false;
            return;
        }
        // "Both suites have ..." after "two guest suites": a word WordNet does not read as a
        // room still names the rooms listed under it.
        let as_room = self.listed_room_word(np, chunk);
        let np = as_room.as_ref().unwrap_or(np);
        // "the largest has ...", "the other two each have ...": a subject that picks among
        // the rooms just counted ("the remaining two": the number may follow on its own).
        let bare_number_then_verb = matches!(
            chunks.get(k + 1).map(|x| &x.item),
            Some(Item::Np(n)) if n.head == Head::NonObject && n.number.is_some() && n.det.is_none()
        ) && matches!(
            chunks.get(k + 2).map(|x| &x.item),
            Some(Item::Verb(..))
        );
        if matches!(
            np.head,
            Head::NonObject | Head::Pronoun(Pronoun::One | Pronoun::Other)
        ) && c.verb.is_none()
            && c.subject.is_empty()
            && (next_is_verb || subject_verb_after(chunks, k) || bare_number_then_verb)
            && let Some(picked) = self.room_pick(np, chunk, chunks.get(k + 1))
        {
            if bare_number_then_verb {
                c.skip_np = true;
            }
            self.furnish_picked(c, &picked);
            return;
        }
        match &np.head {
            Head::Room { .. } => {
                // "a meeting room with a long table", "three guest rooms, each with a bed",
                // "there is a breakfast room ...": a room whose contents follow.
                // "... leads up to the sleeping loft, which holds a bed": so does a relative
                // clause.
                let contents_follow = match chunks.get(k + 1).map(|x| &x.item) {
                    Some(Item::With | Item::Relative) => true,
                    Some(Item::Comma) => matches!(
                        chunks.get(k + 2).map(|x| &x.item),
                        Some(Item::Each | Item::Relative)
                    ),
                    _ => false,
                } || self.existential_before(chunk.range.start);
                let verb_follows = next_is_verb || subject_verb_after(chunks, k);
                // "an open-plan kitchen and living area with a sofa": a second room word that
                // names no room of the reading is part of the room before it.
                let partner = match (
                    k.checked_sub(2).and_then(|j| chunks.get(j)),
                    k.checked_sub(1).and_then(|j| chunks.get(j)),
                ) {
                    (
                        Some(Chunk {
                            item: Item::Np(first),
                            ..
                        }),
                        Some(Chunk {
                            item: Item::And, ..
                        }),
                    ) if matches!(first.head, Head::Room { .. }) && !self.names_a_room(np) => {
                        Some(first.as_ref())
                    }
                    _ => None,
                };
                self.room_np(c, partner.unwrap_or(np), verb_follows, contents_follow);
                self.things_counted_before_room(chunk);
            }
            Head::Landmark(class) => {
                let Some(target) = landmark_target(class) else {
                    return;
                };
                if let Some(p) = c.pending.take() {
                    self.relate_pending(c, &p, target, Some(class), None);
                } else if let Ctx::Cover(subj) = c.ctx.clone() {
                    for r in subj {
                        self.add_relation(r.m, Relation::new(RelationKind::On, target));
                    }
                }
            }
            Head::Part { kind, which } => {
                let parent = if kind == "setting" {
                    self.settings_table
                } else {
                    self.level_parent()
                };
                let Some(m) = parent else { return };
                let part = match (kind.as_str(), np.ordinal, which.as_deref()) {
                    ("setting", ..) => "setting".to_string(),
                    (_, Some(o), _) => format!("level {o}"),
                    (_, None, Some("other")) => "other levels".to_string(),
                    (_, None, Some(w)) => format!("{w} level"),
                    _ => "level".to_string(),
                };
                let r = Ref {
                    m,
                    instance: None,
                    part: Some(part),
                };
                if let Some(p) = c.pending.take() {
                    self.relate_pending(c, &p, Target::Mention(m), None, Some(r));
                } else if c.verb.is_none() {
                    c.subject.push(r.clone());
                    c.focus = vec![r.clone()];
                    if kind == "setting" {
                        c.ctx = Ctx::Setting(m);
                    }
                }
                c.last_np = vec![Ref::new(m)];
            }
            Head::Pronoun(p) => self.pronoun_np(c, *p),
            Head::Setting | Head::Feature => {}
            Head::NonObject => {
                if np.number.is_some() && np.attrs.modifiers.is_empty() && np.det.is_none() {
                    c.bare_number = np.number;
                    // "Tall bookcases, at least eight of them, ...": the count of the plural
                    // phrase before.
                    let of_them = matches!(chunks.get(k + 1).map(|x| &x.item), Some(Item::Of))
                        && matches!(
                            chunks.get(k + 2).map(|x| &x.item),
                            Some(Item::Np(p)) if p.head == Head::Pronoun(super::chunk::Pronoun::Them)
                        );
                    if of_them
                        && let Some(m) =
                            self.recent(|m| !m.negated && is_plural_count(m.count), &[])
                    {
                        let n = np.number.unwrap_or(1);
                        self.mentions[m].count = match np.quant.as_deref() {
                            Some("at_least") => Count::AtLeast(n),
                            Some("more_than" | "more_than_number") => Count::AtLeast(n + 1),
                            _ => Count::Exactly(n),
                        };
                        c.skip_np = false;
                    }
                }
                if c.verb.is_none() && c.subject.is_empty() && np.det.is_some() {
                    // "A seating area in the center features ...": a zone.
                    c.zone = true;
                }
                if let Ctx::StyleOf(targets) = c.ctx.clone() {
                    self.add_styles(&targets, np);
                }
            }
            Head::Object { .. } => {
                c.list_goes_on = list_goes_on(chunks, k);
                self.object_np(c, np, chunk, chunks.get(k + 1).map(|x| &x.item))
            }
        }
    }

    /// A past participle the lexicon has no verb for, read as a phrase that names nothing
    /// ("each fitted with a sink").
    pub(super) fn participle(&self, chunk: &Chunk) -> bool {
        let Item::Np(np) = &chunk.item else {
            return false;
        };
        chunk.range.len() == 1
            && !matches!(np.head, Head::Object { .. } | Head::Room { .. })
            && self.tokens[chunk.range.start].text.ends_with("ed")
    }

    /// "plus", "as well as", "along with": a conjunction that adds to the whole, never one
    /// that continues a list (the "and" of "a chair, a lamp, and a vase").
    fn additive(&self, chunk: &Chunk) -> bool {
        let words: Vec<&str> = self.tokens[chunk.range.clone()]
            .iter()
            .map(|t| t.text.as_str())
            .collect();
        matches!(
            words.as_slice(),
            ["plus"] | ["as", "well", "as"] | ["along", "with"] | ["together", "with"]
        )
    }

    /// A phrase read as no object whose head word is the last word of a room of the house
    /// ("suites" for "guest suite 1"), as a phrase naming that room.
    fn listed_room_word(&self, np: &Np, chunk: &Chunk) -> Option<Np> {
        if self.scope != Scope::House {
            return None;
        }
        // "Each sleeping pod has ...": a thing's noun that a room of the house was made of;
        // "Each cell has ..." after "six monks' cells": its head noun.
        if let Head::Object { noun, entry, .. } = &np.head {
            let each = np.det.as_deref() == Some("each");
            let r = self.rooms.iter().find(|r| {
                entry.is_none()
                    && r.room_type == "room"
                    && (r.words == *noun || (each && rooms::head_names(&r.words, noun)))
            })?;
            let mut room = np.clone();
            room.head = Head::Room {
                key: r.room_type.clone(),
                words: r.words.clone(),
            };
            return Some(room);
        }
        if !matches!(np.head, Head::NonObject) {
            return None;
        }
        let last = self.tokens.get(chunk.range.end.checked_sub(1)?)?;
        if !last.is_word() {
            return None;
        }
        let w = self.lex.singular(&last.text);
        let r = self
            .rooms
            .iter()
            .find(|r| rooms::head_names(&r.words, &w))?;
        let mut room = np.clone();
        room.head = Head::Room {
            key: r.room_type.clone(),
            words: r.words.clone(),
        };
        room.plural = self.lex.is_plural(&last.text);
        Some(room)
    }

    /// True when "there is", "there are" (or "lies", "stand") comes right before `at`.
    fn existential_before(&self, at: usize) -> bool {
        let word = |i: usize| self.tokens.get(i).map(|t| t.text.as_str());
        at >= 2
            && word(at - 2) == Some("there")
            && matches!(
                word(at - 1),
                Some("is" | "are" | "lies" | "lie" | "stands" | "stand" | "sits" | "sit")
            )
    }

    /// Makes room `i` the room that the phrases that follow furnish. A pending "each X"
    /// copy ends here.
    fn switch_room(&mut self, i: usize) {
        if let Some((first, rooms, span)) = self.each_rooms.take() {
            self.copy_to_rooms(first, &rooms, span);
        }
        if i != self.room {
            // The chunk was recorded under the old room.
            let moved = self.spans.get_mut(self.room).and_then(Vec::pop);
            self.room = i;
            if let (Some(r), Some(sp)) = (moved, self.spans.get_mut(i)) {
                sp.push(r);
            }
        }
    }

    /// Whether a room phrase names a room of the reading by its type or its words.
    fn names_a_room(&self, np: &Np) -> bool {
        let Head::Room { key, words } = &np.head else {
            return false;
        };
        self.rooms.iter().any(|r| {
            (key != "room" && r.room_type == *key)
                || r.words == *words
                || r.words.ends_with(&format!(" {words}"))
        })
    }

    /// Keeps the rooms a plural room phrase names ("three bedrooms", "the bedrooms") as the
    /// group that later phrases pick from.
    fn remember_group(&mut self, np: &Np) {
        let Some(i) = rooms::resolve(&self.rooms, np, self.room) else {
            return;
        };
        let (kind, words) = (&self.rooms[i].room_type, &self.rooms[i].words);
        let group: Vec<usize> = (0..self.rooms.len())
            .filter(|&j| self.rooms[j].room_type == *kind && self.rooms[j].words == *words)
            .collect();
        if group.len() > 1 {
            self.room_group = group;
            self.picked.clear();
            self.group_at = self.mentions.len();
        }
    }

    /// The rooms of the last plural room phrase that a subject without a noun picks: "the
    /// largest" (a superlative or comparative: the next room not yet picked), "the first",
    /// "the second" (by position), "the last", "one", and "the other two", "the others",
    /// "the rest", "the remaining ones" (every room not yet picked).
    fn room_pick(&mut self, np: &Np, chunk: &Chunk, next: Option<&Chunk>) -> Option<Vec<usize>> {
        if self.scope != Scope::House || self.room_group.len() < 2 {
            return None;
        }
        // "one has ..., the other ...": only right after the rooms, before any other plural
        // phrase that "one" could pick from; "the other" only after "one" picked a room.
        // "the larger one" picks a room whatever came between.
        let plural_since = self.mentions[self.group_at.min(self.mentions.len())..]
            .iter()
            .any(|m| is_plural_count(m.count));
        let words: Vec<String> = self.tokens[chunk.range.clone()]
            .iter()
            .filter(|t| t.is_word())
            .map(|t| t.text.to_lowercase())
            .collect();
        let graded = |w: &String| crate::words::ground::is_graded_adjective(w);
        match np.head {
            Head::Pronoun(Pronoun::One) if plural_since && !words.iter().any(graded) => {
                return None;
            }
            Head::Pronoun(Pronoun::Other) if self.picked.is_empty() => return None,
            _ => {}
        }
        let number = np.number.or(match next.map(|x| &x.item) {
            Some(Item::Np(n)) => n.number,
            _ => None,
        });
        let open: Vec<usize> = self
            .room_group
            .iter()
            .copied()
            .filter(|r| !self.picked.contains(r))
            .collect();
        let has = |w: &str| words.iter().any(|x| x == w);
        let rest = np.other || has("others") || has("remaining") || has("rest");
        let picked: Vec<usize> = if rest && !has("another") {
            let n = number.map_or(open.len(), |n| n as usize);
            open.into_iter().take(n).collect()
        } else if let Some(o) = np.ordinal {
            self.room_group
                .get(o.saturating_sub(1) as usize)
                .into_iter()
                .copied()
                .collect()
        } else if has("last") {
            self.room_group.last().into_iter().copied().collect()
        } else if words.iter().any(graded) || words.iter().all(|w| w == "one" || w == "another") {
            open.into_iter().take(1).collect()
        } else {
            return None;
        };
        if picked.is_empty() {
            return None;
        }
        self.picked.extend(picked.iter().copied());
        Some(picked)
    }

    /// What follows furnishes the picked rooms: the first, and a copy in each of the others
    /// ("the other two each have a single bed and a desk").
    fn furnish_picked(&mut self, c: &mut Clause, picked: &[usize]) {
        let Some((&first, others)) = picked.split_first() else {
            return;
        };
        self.switch_room(first);
        if !others.is_empty() {
            let span = self
                .spans
                .get(self.room)
                .map_or(0, |s| s.len().saturating_sub(1));
            self.each_rooms = Some((self.mentions.len(), others.to_vec(), span));
        }
        c.subject_is_room = true;
        c.ctx = Ctx::Room;
        c.stack.clear();
        c.focus.clear();
        self.focused = true;
    }

    fn room_np(&mut self, c: &mut Clause, np: &Np, next_is_verb: bool, contents_follow: bool) {
        if self.scope == Scope::House && np.plural {
            self.remember_group(np);
        }
        // "the hall opens into a sitting room with a piano": the piano is the sitting room's.
        if contents_follow
            && c.pending.is_some()
            && self.scope == Scope::House
            && let Some(i) = rooms::resolve(&self.rooms, np, self.room)
            && i != self.room
        {
            c.pending = None;
            self.switch_room(i);
            c.subject_is_room = true;
            c.ctx = Ctx::Room;
            c.stack.clear();
            c.focus.clear();
            return;
        }
        if let Some(p) = c.pending.take() {
            // "in the back of the room", "in the middle of the room".
            self.relate_pending(c, &p, Target::Room, Some("room"), None);
            return;
        }
        if let Ctx::StyleOf(targets) = c.ctx.clone() {
            self.add_styles(&targets, np);
            return;
        }
        if (next_is_verb && c.verb.is_none()) || (contents_follow && self.scope == Scope::House) {
            if self.scope == Scope::House
                && let Some(i) = rooms::resolve(&self.rooms, np, self.room)
            {
                self.switch_room(i);
            }
            // "Each private office has ...", "Both bathrooms have ...", "The bedrooms have
            // ...": the same contents in every such room.
            let every = np.det.as_deref() == Some("each")
                || (np.plural && (np.is_definite() || np.number.is_some()));
            if self.scope == Scope::House && every {
                // "Each private office has ...": the same contents in every such room.
                let same: Vec<usize> = (0..self.rooms.len())
                    .filter(|&i| {
                        let (r, cur) = (&self.rooms[i], &self.rooms[self.room]);
                        // Rooms of no known type are the same kind by their words.
                        i != self.room
                            && r.room_type == cur.room_type
                            && (r.room_type != "room" || r.words == cur.words)
                    })
                    .collect();
                let span = self
                    .spans
                    .get(self.room)
                    .map_or(0, |s| s.len().saturating_sub(1));
                self.each_rooms = Some((self.mentions.len(), same, span));
            }
            c.subject_is_room = true;
            c.ctx = Ctx::Room;
            c.stack.clear();
            c.focus.clear();
            self.focused = true;
        } else if c.verb.is_none() && c.subject.is_empty() {
            c.subject_is_room = true;
        } else {
            // "a waiting area with four chairs" inside a room: a zone, not a holder.
            c.focus.clear();
            c.last_prep_obj = None;
        }
    }
}

/// Whether the noun phrase chunk `k` is an item of a list that runs on to its last item and
/// the end of the sentence: only phrases, commas and "and" follow, the last after an "and"
/// ("two monitors, a docking station and a task chair.").
fn list_goes_on(chunks: &[Chunk], k: usize) -> bool {
    let mut and_then_np = false;
    let mut after_and = false;
    for c in &chunks[k + 1..] {
        match &c.item {
            // "... and two chairs facing each other across it": after the last item, a
            // phrase about it (a preposition, a participle, what they face) ends the list.
            _ if and_then_np => {
                let about_last = match &c.item {
                    Item::Prep(_) | Item::Other(_) => true,
                    Item::Verb(_, w) => w.ends_with("ing") || w.ends_with("ed"),
                    Item::Np(np) => {
                        matches!(np.head, Head::Pronoun(_) | Head::Landmark(_)) || np.is_definite()
                    }
                    _ => false,
                };
                if !about_last {
                    return false;
                }
            }
            Item::Np(_) => and_then_np |= after_and,
            Item::And => after_and = true,
            Item::Comma => {}
            _ => return false,
        }
    }
    and_then_np
}

/// Whether the phrase at `k` is the subject of a verb after a short insertion: "The boot room
/// beside it holds ...", "The bakery itself has ...", "the two bedrooms each have ...".
fn subject_verb_after(chunks: &[Chunk], k: usize) -> bool {
    let item = |j: usize| chunks.get(j).map(|x| &x.item);
    let mut j = k + 1;
    for _ in 0..3 {
        match item(j) {
            Some(Item::Verb(..)) => return j > k + 1,
            Some(Item::Each) => j += 1,
            // "the larger one also holds": "also" and "then" read as conjunctions.
            Some(Item::And) if matches!(item(j + 1), Some(Item::Verb(..))) => j += 1,
            // "The parlor, by contrast, feels formal": an aside between commas that names
            // nothing.
            Some(Item::Comma) if j == k + 1 => match aside_end(chunks, j) {
                Some(end) => j = end + 1,
                None => return false,
            },
            Some(Item::Other(w)) if matches!(w.as_str(), "itself" | "themselves" | "alone") => {
                j += 1
            }
            Some(Item::Prep(_)) => match item(j + 1) {
                Some(Item::Np(np))
                    if matches!(np.head, Head::Pronoun(_) | Head::Landmark(_))
                        || np.is_definite() =>
                {
                    j += 2
                }
                _ => return false,
            },
            _ => return false,
        }
    }
    matches!(item(j), Some(Item::Verb(..)))
}

/// The closing comma of an aside that opens with the comma at `open` and names no thing
/// (", by contrast,", ", however,", ", on the other hand,"): at most four chunks, each a
/// preposition, a word of no class or a noun phrase that names nothing.
fn aside_end(chunks: &[Chunk], open: usize) -> Option<usize> {
    for j in open + 1..(open + 6).min(chunks.len()) {
        match &chunks[j].item {
            Item::Comma => return (j > open + 1).then_some(j),
            Item::Prep(_) | Item::Other(_) => {}
            Item::Np(np) if np.head == Head::NonObject => {}
            _ => return None,
        }
    }
    None
}

fn is_plural_count(c: Count) -> bool {
    !matches!(c, Count::Exactly(1))
}
