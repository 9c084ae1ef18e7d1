//! From chunks to mentions: who is the subject, what a "with", "has", "each" or preposition
//! attaches to, which phrases name an earlier object ("the table", "it", "the other bin"),
//! per-parent counts, place settings, groups, negation, and which room a clause is about.
//!
//! The rules are small and local (a clause at a time); they are tuned on the dev prompts and
//! written so that a phrase they do not understand is skipped, never misread as something
//! else when avoidable.

use std::ops::Range;

use super::chunk::{Chunk, Head, Item, Np, Pronoun};
use super::lexicon::{Lexicon, Support};
use super::mentions::{Count, Group, GroupKind, Mention, Per, phrase_count};
use super::relations::{Relation, RelationKind, Target, landmark_target, normalize};
use super::rooms::{self, RoomReading, Scope};
use super::tokens::Token;

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
    fronted: Option<(String, Option<String>, Target, Option<u32>)>,
    relative: bool,
    skip_np: bool,
    skip_next: bool,
    room_with: bool,
    rel_scope: bool,
    pronoun_subject: bool,
    of_once: bool,
    list_since_comma: Vec<Ref>,
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
        let mut c = Clause::new();
        let mut k = 0;
        while k < chunks.len() {
            let chunk = &chunks[k];
            if let Some(sp) = self.spans.get_mut(self.room) {
                sp.push(chunk.range.clone());
            }
            if c.skip_next && matches!(chunk.item, Item::With | Item::Verb(..) | Item::Prep(_)) {
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
                    if c.of_once {
                        // "a cup of tea and two books": the "of" phrase is over.
                        c.of_once = false;
                        self.pop_ctx(&mut c);
                    }
                    c.sep_was_comma = comma || (c.after_sep && c.sep_was_comma);
                    c.after_sep = true;
                    if self.new_clause_follows(chunks, k) {
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
                    // "a vase of flowers", "shelves of stuffed animals": contents, for the
                    // next phrase only.
                    if let Some(f) = c.focus.first().cloned()
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
        if chunks.get(j).is_some_and(|c| c.item == Item::And) {
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
                Item::Np(_) | Item::With | Item::Prep(_) | Item::And | Item::Of => j += 1,
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
        match &np.head {
            Head::Room { .. } => self.room_np(c, np, next_is_verb),
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
                if c.verb.is_none() && c.subject.is_empty() && np.det.is_some() {
                    // "A seating area in the center features ...": a zone.
                    c.zone = true;
                }
                if let Ctx::StyleOf(targets) = c.ctx.clone() {
                    self.add_styles(&targets, np);
                }
            }
            Head::Object { .. } => self.object_np(c, np, chunk, next_is_verb),
        }
    }

    fn room_np(&mut self, c: &mut Clause, np: &Np, next_is_verb: bool) {
        if let Some(p) = c.pending.take() {
            // "in the back of the room", "in the middle of the room".
            self.relate_pending(c, &p, Target::Room, Some("room"), None);
            return;
        }
        if let Ctx::StyleOf(targets) = c.ctx.clone() {
            self.add_styles(&targets, np);
            return;
        }
        if next_is_verb && c.verb.is_none() {
            if self.scope == Scope::House
                && let Some(i) = rooms::resolve(&self.rooms, np, self.room)
            {
                if i != self.room {
                    // The chunk was recorded under the old room.
                    let moved = self.spans.get_mut(self.room).and_then(Vec::pop);
                    self.room = i;
                    if let (Some(r), Some(sp)) = (moved, self.spans.get_mut(i)) {
                        sp.push(r);
                    }
                }
            }
            c.subject_is_room = true;
            c.ctx = Ctx::Room;
        } else if c.verb.is_none() && c.subject.is_empty() {
            c.subject_is_room = true;
        } else {
            // "a waiting area with four chairs" inside a room: a zone, not a holder.
            c.focus.clear();
            c.last_prep_obj = None;
        }
    }

    fn pronoun_np(&mut self, c: &mut Clause, p: Pronoun) {
        let exclude: Vec<usize> = c
            .pending
            .as_ref()
            .map(|p| p.attach.iter().map(|r| r.m).collect())
            .unwrap_or_default();
        let target = match p {
            Pronoun::EachOther => {
                if let Some(pe) = c.pending.take() {
                    self.relate_pending(c, &pe, Target::EachOther, None, None);
                }
                return;
            }
            Pronoun::It => self
                .recent(|m| !m.negated && !is_plural_count(m.count), &exclude)
                .map(Ref::new),
            Pronoun::Them => self
                .recent(|m| !m.negated && is_plural_count(m.count), &exclude)
                .map(Ref::new),
            Pronoun::One | Pronoun::Other => (if p == Pronoun::Other {
                self.last_one
            } else {
                None
            })
            .or_else(|| {
                c.last_np
                    .first()
                    .map(|r| r.m)
                    .filter(|&m| is_plural_count(self.mentions[m].count))
            })
            .or_else(|| self.recent(|m| matches!(m.count, Count::Exactly(n) if n >= 2), &exclude))
            .map(|m| Ref {
                m,
                instance: Some(if p == Pronoun::One { 0 } else { 1 }),
                part: None,
            }),
        };
        let Some(r) = target else { return };
        if let Some(pe) = c.pending.take() {
            self.relate_pending(c, &pe, Target::Mention(r.m), None, Some(r.clone()));
            return;
        }
        if matches!(p, Pronoun::One | Pronoun::Other) {
            // A new clause about one member: "where one displays ...".
            self.last_one = Some(r.m);
            c.relative = false;
            c.pronoun_subject = true;
            c.subject = vec![r.clone()];
            c.focus = vec![r];
            c.verb = None;
            c.ctx = Ctx::Room;
            c.stack.clear();
        }
    }

    /// Most recent live mention of the current room passing `f`, skipping `exclude`.
    fn recent(&self, f: impl Fn(&Mention) -> bool, exclude: &[usize]) -> Option<usize> {
        (0..self.mentions.len()).rev().find(|&i| {
            self.alive(i)
                && self.mentions[i].room == self.room
                && !exclude.contains(&i)
                && f(&self.mentions[i])
        })
    }

    /// The shelf-like mention a "level" belongs to.
    fn level_parent(&self) -> Option<usize> {
        self.recent(|m| m.attributes.levels.is_some(), &[])
            .or_else(|| {
                self.recent(
                    |m| m.category.contains("shelf") || m.category.contains("rack"),
                    &[],
                )
            })
            .or_else(|| {
                self.recent(
                    |m| self.lex.lookup(&m.category).is_some_and(|e| e.holds),
                    &[],
                )
            })
    }

    fn add_styles(&mut self, targets: &[Ref], np: &Np) {
        let mut styles = np.attrs.styles.clone();
        if styles.is_empty() {
            // "inspired by The Incredibles movie": the capitalised words.
            let words: Vec<String> = np.attrs.modifiers.clone();
            if !words.is_empty() {
                styles.push(words.join(" "));
            }
        }
        for s in styles {
            if targets.is_empty() {
                if let Some(r) = self.rooms.get_mut(self.room)
                    && !r.styles.contains(&s)
                {
                    r.styles.push(s.clone());
                }
            }
            for t in targets {
                let a = &mut self.mentions[t.m].attributes;
                if !a.styles.contains(&s) {
                    a.styles.push(s.clone());
                    a.modifiers.insert(0, format!("{s}-style"));
                }
            }
        }
    }

    fn object_np(&mut self, c: &mut Clause, np: &Np, chunk: &Chunk, next_is_verb: bool) {
        if c.after_sep
            && c.sep_was_comma
            && np.has_det()
            && matches!(c.ctx, Ctx::StyleOf(_) | Ctx::Cover(_))
        {
            if c.stack.is_empty() {
                c.ctx = Ctx::Room;
            } else {
                self.pop_ctx(c);
            }
        }
        if let Ctx::StyleOf(targets) = c.ctx.clone() {
            self.add_styles(&targets, np);
            return;
        }
        // The same noun again inside its own holder: "stacks of plates with at least 20
        // plates", "a pile of lego blocks containing at least 5 blocks" — a count, not a new
        // object.
        if let Ctx::Holder(parents, _) = &c.ctx
            && parents.len() == 1
            && np.number.is_some()
            && self.same_noun(parents[0].m, np)
        {
            let m = parents[0].m;
            self.mentions[m].count = self.count_of(np, c, None);
            return;
        }
        let r = self.resolve_object(c, np, chunk);
        let is_new = r.m + 1 == self.mentions.len()
            && self.mentions[r.m].span
                == [
                    self.tokens[chunk.range.start].start,
                    self.tokens[chunk.range.end - 1].end,
                ];
        if let Some(p) = c.pending.take() {
            if p.class == "surrounded_by" || p.class == "flanked_by" {
                // Inverse: the new phrase surrounds the attach set.
                let kind = if p.class == "surrounded_by" {
                    RelationKind::Around
                } else {
                    RelationKind::Flanking
                };
                for a in &p.attach {
                    let mut rel = Relation::new(kind, Target::Mention(a.m));
                    rel.instance = a.instance;
                    self.add_relation(r.m, rel);
                    if p.each && self.mentions[r.m].per.is_none() {
                        self.mentions[r.m].per = Some(Per::Each { parent: a.m });
                    }
                }
                // What follows ("... in the center") is about the surrounded piece.
                c.focus.clone_from(&p.attach);
                c.last_prep_obj = None;
                c.last_np = vec![r];
                return;
            }
            let each_target = np.det.as_deref() == Some("each");
            self.relate_pending_each(
                c,
                &p,
                Target::Mention(r.m),
                None,
                Some(r.clone()),
                each_target,
            );
            if is_new {
                // "4 teacups on saucers": one saucer each.
                if self.mentions[r.m].count == Count::Several
                    && let Some(a) = p.attach.first()
                    && matches!(
                        self.mentions[a.m].count,
                        Count::Exactly(_) | Count::AtLeast(_)
                    )
                    && p.class == "on"
                {
                    self.mentions[r.m].count = self.mentions[a.m].count;
                }
                if matches!(c.ctx, Ctx::Setting(_) | Ctx::Each(_) | Ctx::Members(_)) {
                    self.apply_ctx(c, &r, np);
                }
                c.last_prep_obj = Some(r.clone());
            } else {
                c.last_prep_obj = None;
            }
            c.last_np = vec![r];
            return;
        }
        if let Ctx::Cover(subj) = c.ctx.clone() {
            for s in subj {
                let mut rel = Relation::new(RelationKind::On, Target::Mention(r.m));
                rel.instance = r.instance;
                self.add_relation(s.m, rel);
            }
            c.last_np = vec![r];
            return;
        }
        // A separator ends a "with" list unless the next phrase is bare ("a monitor,
        // keyboard, and chair") or was joined by "and" (no comma).
        if c.after_sep && c.sep_was_comma && np.has_det() && matches!(c.ctx, Ctx::Each(_)) {
            // ", each with two chairs, a counter with ...": the counter is not per table.
            let keeps = match &np.head {
                Head::Object {
                    entry, canonical, ..
                } => {
                    entry
                        .and_then(|e| self.lex.objects.get(e))
                        .is_none_or(|e| e.support == Support::Surface)
                        || canonical.ends_with("chair")
                        || canonical.ends_with("stool")
                }
                _ => true,
            };
            if !keeps {
                c.ctx = Ctx::Room;
                c.stack.clear();
            }
        }
        if c.after_sep && matches!(c.ctx, Ctx::Holder(..)) && !c.stack.is_empty() {
            let bare = !np.has_det();
            let small = match &np.head {
                Head::Object {
                    entry, head_entry, ..
                } => entry
                    .or(*head_entry)
                    .and_then(|e| self.lex.objects.get(e))
                    .is_none_or(|e| e.support == Support::Surface),
                _ => false,
            };
            let keep = bare || (!c.sep_was_comma && c.fronted.is_none() && small);
            if !keep {
                self.pop_ctx(c);
            }
        }
        if c.verb.is_none()
            && matches!(c.ctx, Ctx::Room)
            && !c.subject_is_room
            && !c.room_with
            && (c.subject.is_empty() || c.after_sep || next_is_verb)
        {
            c.subject.push(r.clone());
        }
        self.apply_ctx(c, &r, np);
        if c.of_once {
            c.of_once = false;
            self.pop_ctx(c);
        }
        if c.zone && matches!(c.ctx, Ctx::Room) && c.verb.is_some() {
            for rel in c.zone_relations.clone() {
                self.add_relation(r.m, rel);
            }
        }
        if let Some((class, lm, target, inst)) = c.fronted.clone()
            && c.verb.is_some()
            && c.stack.is_empty()
            && let Some((kind, t)) = normalize(&class, lm.as_deref(), None, target)
        {
            let mut rel = Relation::new(kind, t);
            rel.instance = inst;
            self.add_relation(r.m, rel);
        }
        if c.negate || np.negated {
            self.mentions[r.m].negated = true;
        }
        if np.negated {
            c.negate = true;
        }
        // Group suffix: "a sofa and coffee table arrangement".
        if np.group_suffix {
            let g = self.new_group(GroupKind::Arrangement);
            let mut members = c.list_since_comma.clone();
            members.push(r.clone());
            for m in &members {
                self.mentions[m.m].group = Some(g);
            }
            c.focus = members;
        } else {
            c.focus = vec![r.clone()];
        }
        // "two treadmills and two exercise bikes along the wall": an and-joined partner shares
        // room placements.
        c.and_partner = if c.after_sep && !c.sep_was_comma {
            c.list_since_comma.last().cloned()
        } else {
            None
        };
        c.list_since_comma.push(r.clone());
        c.last_np = vec![r];
        c.last_prep_obj = None;
        c.after_sep = false;
    }

    /// True when `np` names the same noun as mention `m` (same canonical or same head word).
    fn same_noun(&self, m: usize, np: &Np) -> bool {
        let Head::Object {
            canonical, noun, ..
        } = &np.head
        else {
            return false;
        };
        let mm = &self.mentions[m];
        let last = |s: &str| s.rsplit(' ').next().unwrap_or(s).to_string();
        mm.category == *canonical || last(&mm.noun) == last(noun)
    }

    /// Applies the clause's context to a new content phrase.
    fn apply_ctx(&mut self, c: &mut Clause, r: &Ref, np: &Np) {
        match c.ctx.clone() {
            Ctx::Holder(parents, intro) => {
                let from_with = intro == Intro::With;
                for p in &parents {
                    if p.m == r.m {
                        continue;
                    }
                    let rel = self.implied(r.m, p, intro);
                    self.add_relation(r.m, rel);
                    // "four desks with chairs": one set per parent.
                    let parent_plural = is_plural_count(self.mentions[p.m].count);
                    if from_with
                        && p.instance.is_none()
                        && parent_plural
                        && !np.has_det()
                        && np.plural
                        && self.mentions[r.m].per.is_none()
                    {
                        self.mentions[r.m].per = Some(Per::Each { parent: p.m });
                    }
                }
            }
            Ctx::Each(parents) => {
                for p in &parents {
                    let rel = self.implied(r.m, p, Intro::With);
                    self.add_relation(r.m, rel);
                    self.mentions[r.m].per = Some(Per::Each { parent: p.m });
                }
            }
            Ctx::Setting(table) => {
                let mut rel = Relation::new(RelationKind::On, Target::Mention(table));
                rel.part = Some("setting".into());
                rel.implied = true;
                self.add_relation(r.m, rel);
                self.mentions[r.m].per = Some(Per::Setting { table });
            }
            Ctx::Members(g) => {
                let (rels, group) = (self.mentions[g].relations.clone(), self.mentions[g].group);
                for rel in rels {
                    self.add_relation(r.m, rel);
                }
                if self.mentions[r.m].group.is_none() {
                    self.mentions[r.m].group = group;
                }
                if self.absorbed[g].is_none() {
                    self.absorbed[g] = Some(Some(r.m));
                }
            }
            Ctx::Room | Ctx::Cover(_) | Ctx::StyleOf(_) => {}
        }
        // "a mix of apples and oranges": bare followers join the open group.
        if let Some(g) = np.group.map(|k| (k, ())) {
            let group = self.new_group(g.0);
            self.mentions[r.m].group = Some(group);
            c.group_open = Some(group);
        } else if let Some(g) = c.group_open
            && !np.has_det()
            && self.mentions[r.m].group.is_none()
        {
            self.mentions[r.m].group = Some(g);
        }
        let at_least = np.quant.as_deref() == Some("at_least") || np.plus;
        if at_least {
            c.carry_at_least = true;
        } else if np.number.is_some() && np.quant.is_none() && c.carry_at_least {
            self.mentions[r.m].count = Count::AtLeast(self.mentions[r.m].count.minimum());
        }
    }

    /// The relation a holder implies for its contents: inside a container, on a surface that
    /// holds things, otherwise just "with".
    fn implied(&self, child: usize, parent: &Ref, intro: Intro) -> Relation {
        let cm = &self.mentions[child];
        let pm = &self.mentions[parent.m];
        let small = cm.support == Support::Surface || !cm.known;
        let pe = self.lex.lookup(&pm.category);
        let thin = pe.is_some_and(|e| e.thin);
        let contains = intro == Intro::Verb(true);
        let kind = if small && (pm.container || contains) {
            RelationKind::In
        } else if small && (pe.is_some_and(|e| e.holds) || thin || pm.support == Support::Wall) {
            RelationKind::On
        } else if small && pm.support == Support::Surface {
            RelationKind::On
        } else {
            RelationKind::With
        };
        let mut rel = Relation::new(kind, Target::Mention(parent.m));
        rel.instance = parent.instance;
        rel.part.clone_from(&parent.part);
        rel.implied = true;
        rel
    }

    /// Count of a phrase (pairs multiplied, "at least" carried).
    fn count_of(&self, np: &Np, c: &Clause, noun: Option<&str>) -> Count {
        let mut count = phrase_count(
            np.quant.as_deref(),
            np.number,
            np.plus,
            np.det.as_deref(),
            np.plural,
        );
        if np.group == Some(GroupKind::Pair) {
            let pairs = np.number.unwrap_or(1);
            let tantum =
                noun.is_some_and(|n| self.lex.plurale_tantum(n.rsplit(' ').next().unwrap_or(n)));
            let n = if tantum { pairs } else { pairs * 2 };
            count = match count {
                Count::AtLeast(_) => Count::AtLeast(n),
                _ => Count::Exactly(n),
            };
        }
        if np.number.is_some() && np.quant.is_none() && !np.plus && c.carry_at_least {
            count = Count::AtLeast(count.minimum());
        }
        count
    }

    /// Finds the mention a phrase names, or creates it.
    fn resolve_object(&mut self, c: &Clause, np: &Np, chunk: &Chunk) -> Ref {
        let Head::Object {
            entry,
            noun,
            canonical,
            head_entry,
        } = &np.head
        else {
            return Ref::new(0);
        };
        let instance = if np.other {
            Some(1)
        } else {
            np.ordinal.map(|o| o.saturating_sub(1))
        };
        let another = np.det.as_deref() == Some("another");
        let definite = np.is_definite() || (np.other && !another);
        let existing = |me: &Self| -> Option<usize> {
            let last = |s: &str| s.rsplit(' ').next().unwrap_or(s).to_string();
            let first = |s: &str| s.split(' ').next().unwrap_or(s).to_string();
            let kind_of = entry
                .and_then(|e| me.lex.objects.get(e))
                .and_then(|e| e.kind_of.clone());
            me.recent(|m| m.category == *canonical, &[])
                .or_else(|| {
                    me.recent(
                        |m| last(&m.noun) == last(noun) || last(&m.category) == last(canonical),
                        &[],
                    )
                })
                .or_else(|| {
                    me.recent(
                        |m| {
                            me.lex
                                .lookup(&m.category)
                                .and_then(|e| e.kind_of.as_deref())
                                .is_some_and(|k| k == canonical.as_str())
                        },
                        &[],
                    )
                })
                .or_else(|| {
                    kind_of.as_ref().and_then(|k| {
                        me.recent(
                            |m| {
                                first(&m.category) == first(canonical)
                                    && me
                                        .lex
                                        .lookup(&m.category)
                                        .and_then(|e| e.kind_of.as_deref())
                                        == Some(k.as_str())
                            },
                            &[],
                        )
                    })
                })
        };
        if definite && let Some(m) = existing(self) {
            let a = np.attrs.clone();
            self.mentions[m].attributes.merge(&a);
            return Ref {
                m,
                instance,
                part: None,
            };
        }
        // "next to the stove, and a stove": the forward reference and the object are one.
        if !definite
            && !np.plural
            && let Some(m) = self.recent(
                |m| m.category == *canonical && m.definite && m.count == Count::Exactly(1),
                &[],
            )
        {
            self.mentions[m].definite = false;
            let a = np.attrs.clone();
            self.mentions[m].attributes.merge(&a);
            return Ref::new(m);
        }
        if np.det.as_deref() == Some("another")
            && let Some(m) = self.recent(|m| m.category == *canonical, &[])
        {
            let n = self.mentions[m].count.minimum();
            self.mentions[m].count = match self.mentions[m].count {
                Count::AtLeast(x) => Count::AtLeast(x + 1),
                _ => Count::Exactly(n + 1),
            };
            // What was said about "one X" before was about the first of them.
            for other in &mut self.mentions {
                for rel in &mut other.relations {
                    if rel.target == Target::Mention(m) && rel.instance.is_none() {
                        rel.instance = Some(0);
                    }
                }
            }
            return Ref {
                m,
                instance: Some(n),
                part: None,
            };
        }
        if np.one_word
            && np.number == Some(1)
            && let Some(m) =
                self.recent(|m| m.category == *canonical && m.count.minimum() >= 2, &[])
        {
            return Ref {
                m,
                instance: Some(0),
                part: None,
            };
        }
        let e = entry.or(*head_entry).and_then(|i| self.lex.objects.get(i));
        let count = self.count_of(np, c, Some(noun));
        let span = [
            self.tokens[chunk.range.start].start,
            self.tokens[chunk.range.end - 1].end,
        ];
        let mention = Mention {
            category: canonical.clone(),
            noun: noun.clone(),
            count,
            negated: false,
            known: entry.is_some(),
            head: if entry.is_none() {
                e.map(|e| e.noun.clone())
            } else {
                None
            },
            support: e.map_or(Support::Floor, |e| e.support),
            container: e.is_some_and(|e| e.container),
            generic: entry
                .and_then(|i| self.lex.objects.get(i))
                .is_some_and(|e| e.generic),
            attributes: np.attrs.clone(),
            relations: Vec::new(),
            per: None,
            group: None,
            place_settings: None,
            covers: Vec::new(),
            room: self.room,
            span,
            definite: definite && np.det.as_deref() != Some("each"),
        };
        self.mentions.push(mention);
        self.absorbed.push(None);
        Ref {
            m: self.mentions.len() - 1,
            instance: None,
            part: None,
        }
    }

    // ---- relations ----------------------------------------------------------------------

    fn add_relation(&mut self, m: usize, rel: Relation) {
        let mm = &mut self.mentions[m];
        if let Target::Mention(t) = rel.target
            && t == m
        {
            return;
        }
        if !rel.implied {
            // An explicit relation replaces what structure implied, and an explicit support
            // ("on saucers") replaces another support.
            mm.relations.retain(|r| !r.implied);
            if rel.is_support() {
                mm.relations.retain(|r| !r.is_support());
            }
        } else if mm.relations.iter().any(|r| !r.implied) {
            return;
        }
        if !mm.relations.contains(&rel) {
            mm.relations.push(rel);
        }
    }

    fn relate_pending(
        &mut self,
        c: &mut Clause,
        p: &Pending,
        target: Target,
        landmark: Option<&str>,
        tref: Option<Ref>,
    ) {
        self.relate_pending_each(c, p, target, landmark, tref, false);
    }

    fn relate_pending_each(
        &mut self,
        c: &mut Clause,
        p: &Pending,
        target: Target,
        landmark: Option<&str>,
        tref: Option<Ref>,
        each_target: bool,
    ) {
        let verb = c.verb.as_deref();
        let Some((kind, target)) = normalize(&p.class, landmark, verb, target) else {
            return;
        };
        let mut rel = Relation::new(kind, target);
        if let Some(t) = &tref {
            rel.instance = t.instance;
            rel.part.clone_from(&t.part);
        }
        if p.zone {
            c.zone_relations.push(rel);
            return;
        }
        if p.attach.is_empty() {
            // "On the table is a tea set": fronted, applies to what follows the verb.
            let lm = landmark.map(str::to_string);
            let inst = tref.as_ref().and_then(|t| t.instance);
            c.fronted = Some((p.class.clone(), lm, target, inst));
            return;
        }
        let mut attach = p.attach.clone();
        if is_room_placement(kind, target) {
            // "a shelf with books against the wall": the shelf, not the books.
            attach = attach
                .into_iter()
                .map(|a| {
                    let m = &self.mentions[a.m];
                    let implied_parent = m
                        .relations
                        .iter()
                        .find(|r| r.implied && (r.is_support() || r.kind == RelationKind::With))
                        .and_then(|r| r.target.mention());
                    match implied_parent {
                        Some(par)
                            if m.support == Support::Surface
                                || m.relations.iter().all(|r| r.implied) =>
                        {
                            Ref::new(par)
                        }
                        _ => a,
                    }
                })
                .collect();
            if let Some(partner) = c.and_partner.clone()
                && !attach.contains(&partner)
                && attach.len() == 1
            {
                let (a, b) = (&self.mentions[attach[0].m], &self.mentions[partner.m]);
                if a.support == b.support {
                    attach.push(partner);
                }
            }
        }
        if kind == RelationKind::Flanking {
            // "a nightstand on each side of the bed": one per side.
            for a in &attach {
                let m = &mut self.mentions[a.m];
                if m.count == Count::Exactly(1) && !m.definite {
                    m.count = Count::Exactly(2);
                }
            }
        }
        for a in &attach {
            if let Target::Mention(t) = target
                && p.each
                && self.mentions[a.m].per.is_none()
            {
                self.mentions[a.m].per = Some(Per::Each { parent: t });
            }
            self.add_relation(a.m, rel.clone());
        }
        // "pendant lights hang above each table": one per table.
        if let Target::Mention(t) = target
            && each_target
        {
            for a in &attach {
                if self.mentions[a.m].per.is_none() {
                    self.mentions[a.m].per = Some(Per::Each { parent: t });
                    if self.mentions[a.m].count == Count::Several {
                        self.mentions[a.m].count = Count::Exactly(1);
                    }
                }
            }
        }
    }

    fn prep(&mut self, c: &mut Clause, class: &str, prev: Option<&Item>) {
        // Prepositions without an object.
        let ctx_parent = match &c.ctx {
            Ctx::Holder(p, _) | Ctx::Each(p) => p.first().map(|r| r.m),
            Ctx::Setting(t) => Some(*t),
            _ => None,
        }
        .or_else(|| c.subject.first().map(|r| r.m));
        let kind = match class {
            "on_top" => Some(RelationKind::On),
            "in_front" => Some(RelationKind::InFrontOf),
            "each_side" => Some(RelationKind::Flanking),
            _ => None,
        };
        if let Some(kind) = kind {
            if let Some(parent) = ctx_parent {
                for f in c.focus.clone() {
                    if kind == RelationKind::Flanking
                        && self.mentions[f.m].count == Count::Exactly(1)
                    {
                        self.mentions[f.m].count = Count::Exactly(2);
                    }
                    self.add_relation(f.m, Relation::new(kind, Target::Mention(parent)));
                }
            }
            return;
        }
        let after_verb = matches!(prev, Some(Item::Verb(..)));
        let attach = if after_verb {
            c.focus.clone()
        } else if let Some(po) = c.last_prep_obj.clone() {
            // "facing mirrors on the wall": the new prepositional object takes it.
            vec![po]
        } else if c.zone && c.focus.is_empty() {
            Vec::new()
        } else {
            c.focus.clone()
        };
        let zone = c.zone && c.focus.is_empty() && !after_verb;
        let each = false;
        c.last_prep_obj = None;
        c.pending = Some(Pending {
            class: class.to_string(),
            attach,
            zone,
            each,
        });
    }

    // ---- verbs --------------------------------------------------------------------------

    fn verb(&mut self, c: &mut Clause, class: &str, word: &str, chunks: &[Chunk], k: usize) {
        let contains = word.starts_with("contain");
        let finite = c.verb.is_none()
            && !c.relative
            && (!c.subject.is_empty() || c.subject_is_room || c.zone || c.fronted.is_some());
        if finite {
            c.verb = Some(class.to_string());
            c.stack.clear();
            if !matches!(c.ctx, Ctx::Setting(_)) {
                c.ctx = Ctx::Room;
            }
            if !c.subject.is_empty() {
                c.focus = c.subject.clone();
            }
        } else {
            // A participle or relative clause about the last phrase: "tires stacked in the
            // corner", "shelves holding ten bottles", "the chalkboard, which hangs ...".
            let about = if c.relative {
                c.last_np.clone()
            } else {
                c.focus.clone()
            };
            c.relative = false;
            if !about.is_empty() {
                c.focus = about;
            }
            if c.verb.is_none() && c.subject.is_empty() && !c.subject_is_room {
                c.verb = Some(class.to_string());
            }
        }
        let subject = c.focus.clone();
        let subject_is_room = finite && c.subject_is_room;
        match class {
            "possess" | "display" | "fill_with" | "decorate_with" => {
                if matches!(class, "fill_with" | "decorate_with")
                    && let Some(Chunk {
                        item: Item::Prep(p),
                        ..
                    }) = chunks.get(k + 1)
                    && p == "in"
                {
                    c.skip_next = true;
                }
                if matches!(c.ctx, Ctx::Setting(_)) {
                    // "each setting has ...": stays per setting.
                } else if subject_is_room || subject.is_empty() || (finite && c.zone) {
                    c.ctx = Ctx::Room;
                } else if finite {
                    c.ctx = Ctx::Holder(subject, Intro::Verb(contains));
                    c.rel_scope = c.rel_scope || c.pronoun_subject;
                } else if !matches!(chunks.get(k + 1).map(|x| &x.item), Some(Item::With)) {
                    // "filled with ..." leaves the contents to the "with".
                    self.push_ctx(c, Ctx::Holder(subject, Intro::Verb(contains)));
                }
            }
            "stack" | "pile" => {
                let kind = if class == "stack" {
                    GroupKind::Stack
                } else {
                    GroupKind::Pile
                };
                let g = self.new_group(kind);
                for s in &subject {
                    if self.mentions[s.m].group.is_none() {
                        self.mentions[s.m].group = Some(g);
                    }
                }
            }
            "cover" => c.ctx = Ctx::Cover(subject),

            "styled" | "inspired" => {
                let targets = if subject_is_room || subject.is_empty() {
                    Vec::new()
                } else {
                    subject
                };
                self.push_ctx(c, Ctx::StyleOf(targets));
                // Skip "by" / "like": the next phrase is the style.
                if let Some(Chunk {
                    item: Item::Prep(p),
                    ..
                }) = chunks.get(k + 1)
                    && (p == "by" || p == "near")
                {
                    c.skip_next = true;
                }
            }
            _ => {}
        }
        c.last_prep_obj = None;
    }

    // ---- with, each, settings, totals ---------------------------------------------------

    fn with(&mut self, c: &mut Clause) {
        // "without a rug or lamp, with a bed": the negation ends and the "with" is the
        // room's.
        if std::mem::replace(&mut c.negate, false) {
            c.ctx = Ctx::Room;
            c.stack.clear();
            c.focus.clear();
            return;
        }
        if matches!(c.ctx, Ctx::Setting(_)) {
            return;
        }
        let parent = c.focus.clone();
        if c.subject_is_room && c.verb.is_none() {
            // "A garage with ...": the room is not the subject of later participles.
            c.subject_is_room = false;
            c.room_with = true;
        }
        if parent.is_empty() {
            if !matches!(c.ctx, Ctx::Room) {
                self.pop_ctx(c);
            }
            return;
        }
        let ctx = if parent.len() == 1 && self.mentions[parent[0].m].generic {
            Ctx::Members(parent[0].m)
        } else {
            Ctx::Holder(parent, Intro::With)
        };
        self.push_ctx(c, ctx);
        c.after_sep = false;
        c.last_prep_obj = None;
    }

    /// "with geometric patterns", "with Elsa and Anna bedding": text that describes the
    /// phrase in focus rather than naming objects. Returns the chunk index after it.
    fn features_after_with(&mut self, c: &mut Clause, chunks: &[Chunk], k: usize) -> Option<usize> {
        let owner = c.focus.first()?.m;
        let mut j = k + 1;
        let mut saw_feature = false;
        let mut end_tok = None;
        while let Some(ch) = chunks.get(j) {
            match &ch.item {
                Item::Np(np) => {
                    let det_object =
                        matches!(np.head, Head::Object { .. }) && np.has_det() && j > k + 1;
                    if det_object {
                        break;
                    }
                    match &np.head {
                        Head::Object { noun, .. } => {
                            if self
                                .lex
                                .is_feature_noun(noun.rsplit(' ').next().unwrap_or(noun))
                                || self
                                    .lex
                                    .is_feature_noun(&self.tokens[ch.range.end - 1].text)
                            {
                                saw_feature = true;
                            } else {
                                return None;
                            }
                        }
                        Head::Feature | Head::NonObject => saw_feature = true,
                        Head::Room { .. }
                        | Head::Landmark(_)
                        | Head::Part { .. }
                        | Head::Setting
                        | Head::Pronoun(_) => return None,
                    }
                    end_tok = Some(ch.range.end);
                }
                Item::And | Item::Other(_) => {
                    if matches!(ch.item, Item::Other(_)) {
                        end_tok = Some(ch.range.end);
                    }
                }
                _ => break,
            }
            j += 1;
        }
        if !saw_feature {
            return None;
        }
        // Trailing "and" is not part of the feature.
        let mut last = j;
        while last > k + 1 && matches!(chunks[last - 1].item, Item::And) {
            last -= 1;
        }
        let start = chunks.get(k + 1)?.range.start;
        let end = end_tok?;
        let text = self.text_of(start..end);
        let a = &mut self.mentions[owner].attributes;
        if !a.features.contains(&text) {
            a.features.push(text);
        }
        for ch in &chunks[k + 1..last] {
            if let Some(sp) = self.spans.get_mut(self.room) {
                sp.push(ch.range.clone());
            }
        }
        Some(last)
    }

    fn text_of(&self, r: Range<usize>) -> String {
        let toks = &self.tokens[r];
        toks.iter()
            .map(|t| t.raw.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn each(&mut self, c: &mut Clause, chunks: &[Chunk], k: usize) {
        let after_comma = k == 0 || matches!(chunks[k - 1].item, Item::Comma);
        let next = chunks.get(k + 1).map(|x| &x.item);
        if after_comma && next.is_some() {
            let parents = c.focus.clone();
            if parents.is_empty() {
                return;
            }
            match next {
                Some(Item::Prep(p)) => {
                    c.pending = Some(Pending {
                        class: p.clone(),
                        attach: parents,
                        zone: false,
                        each: true,
                    });
                    c.skip_next = true;
                }
                _ => {
                    c.ctx = Ctx::Each(parents);
                    c.stack.clear();
                    c.stack.push(Ctx::Room);
                    c.skip_next = true;
                }
            }
            return;
        }
        // "two stools each": the phrase before is per parent.
        let parent = match &c.ctx {
            Ctx::Holder(p, _) | Ctx::Each(p) => p.first().map(|r| r.m),
            _ => c.subject.first().map(|r| r.m),
        };
        if let (Some(parent), Some(f)) = (parent, c.last_np.first())
            && parent != f.m
        {
            self.mentions[f.m].per = Some(Per::Each { parent });
        }
    }

    fn set_for(&mut self, c: &mut Clause, chunks: &[Chunk], k: usize) {
        let Some(table) = c
            .focus
            .first()
            .map(|r| r.m)
            .or_else(|| c.last_np.first().map(|r| r.m))
        else {
            return;
        };
        if let Some(Chunk {
            item: Item::Np(np), ..
        }) = chunks.get(k + 1)
            && let Some(n) = np.number
        {
            self.mentions[table].place_settings = Some(n);
            c.skip_np = true;
        }
        self.settings_table = Some(table);
        c.ctx = Ctx::Setting(table);
        c.stack.clear();
    }

    fn in_total(&mut self, c: &Clause) {
        let Some(r) = c.last_np.first() else { return };
        let m = r.m;
        let cat = self.mentions[m].category.clone();
        let room = self.mentions[m].room;
        if let Some(e) = (0..m).rev().find(|&i| {
            self.alive(i) && self.mentions[i].room == room && self.mentions[i].category == cat
        }) {
            self.mentions[e].count = self.mentions[m].count;
            self.absorbed[m] = Some(Some(e));
        }
    }
}

fn is_plural_count(c: Count) -> bool {
    !matches!(c, Count::Exactly(1))
}
