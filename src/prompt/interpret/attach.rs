//! Attaching phrases: prepositions and their objects, verbs (finite or participle), "with",
//! "each", place settings, totals, and features that describe rather than name objects.

use std::ops::Range;

use super::{Clause, Ctx, Interp, Intro, Pending, Ref, is_plural_count, is_room_placement};
use crate::prompt::chunk::{Chunk, Head, Item};
use crate::prompt::mentions::{Count, GroupKind, Per};
use crate::prompt::relations::{Relation, RelationKind, Target, normalize};
use crate::words::lexicon::Support;

impl Interp<'_> {
    pub(super) fn add_relation(&mut self, m: usize, rel: Relation) {
        let mm = &mut self.mentions[m];
        if let Target::Mention(t) = rel.target
            && t == m
        {
            return;
        }
        if !rel.implied {
            // An explicit relation replaces what structure implied, and an explicit support
            // ("on saucers") replaces another support. A "with" grouping stays beside a
            // relation that is no support ("a table with eight chairs beneath a chandelier":
            // the chairs are still the table's).
            let keeps_with = !rel.is_support();
            mm.relations
                .retain(|r| !r.implied || (keeps_with && r.kind == RelationKind::With));
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

    pub(super) fn relate_pending(
        &mut self,
        c: &mut Clause,
        p: &Pending,
        target: Target,
        landmark: Option<&str>,
        tref: Option<Ref>,
    ) {
        self.relate_pending_each(c, p, target, landmark, tref, false);
    }

    pub(super) fn relate_pending_each(
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
            c.fronted = Some((p.class.clone(), lm, target, inst, each_target));
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
                        // "benches on both sides of each table": two per table.
                        let n = if kind == RelationKind::Flanking { 2 } else { 1 };
                        self.mentions[a.m].count = Count::Exactly(n);
                    }
                }
            }
        }
    }

    pub(super) fn prep(&mut self, c: &mut Clause, class: &str, prev: Option<&Item>) {
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
        // "The dentist's stool and the hygienist's stool are parked on either side": the
        // sides are those of the thing named before them, not of one of them.
        let ctx_parent = match ctx_parent {
            Some(p) if c.focus.iter().any(|f| f.m == p) => c
                .focus
                .iter()
                .map(|f| f.m)
                .min()
                .and_then(|first| (0..first).rev().find(|&m| !self.mentions[m].negated)),
            other => other,
        };
        if let Some(kind) = kind {
            if let Some(parent) = ctx_parent {
                // "a lamp on either side": one per side; "the dentist's stool and the
                // hygienist's stool are parked on either side": one each.
                let one_thing = c.focus.len() == 1;
                for f in c.focus.clone() {
                    if kind == RelationKind::Flanking
                        && one_thing
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

    pub(super) fn verb(
        &mut self,
        c: &mut Clause,
        class: &str,
        word: &str,
        chunks: &[Chunk],
        k: usize,
    ) {
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
            // "four benches, each with two stools, arranged in rows facing a whiteboard": a
            // participle after the per-parent list places the parents; what follows is not
            // per parent.
            if let Ctx::Each(parents) = &c.ctx
                && class == "locate"
                && k > 0
                && chunks[k - 1].item == Item::Comma
            {
                c.focus = parents.clone();
                c.ctx = Ctx::Room;
                c.stack.clear();
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
                } else if finite && c.each_subject {
                    // "Two nightstands each hold a lamp": a lamp per nightstand, on it.
                    c.ctx = Ctx::Each(subject);
                } else if finite {
                    c.ctx = Ctx::Holder(subject, Intro::Verb(contains));
                    c.rel_scope = c.rel_scope || c.pronoun_subject;
                } else if let Some(parents) = (c.each_subject && !subject.is_empty())
                    .then(|| subject.clone())
                    .or_else(|| {
                        // ", each ringed by four chairs and topped with a caddy": the second
                        // participle is still about each of them.
                        (!c.distributed.is_empty() && k > 0 && chunks[k - 1].item == Item::And)
                            .then(|| c.distributed.clone())
                    })
                {
                    // "Each table is covered with a cloth", ", every table covered with a
                    // cloth": one per table.
                    c.focus.clone_from(&parents);
                    c.ctx = Ctx::Each(parents);
                    c.stack.clear();
                    c.stack.push(Ctx::Room);
                    c.each_with = matches!(chunks.get(k + 1).map(|x| &x.item), Some(Item::With));
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
            // "Phones are forbidden": the things the clause is about are not there.
            "forbid" => {
                for s in &subject {
                    self.mentions[s.m].negated = true;
                }
            }

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

    pub(super) fn with(&mut self, c: &mut Clause) {
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
        // "a sofa faces a TV stand with a large TV": the "with" is the nearest object's.
        let parent = match c.last_prep_obj.take() {
            Some(po) => vec![po],
            None => c.focus.clone(),
        };
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
    pub(super) fn features_after_with(
        &mut self,
        c: &mut Clause,
        chunks: &[Chunk],
        k: usize,
    ) -> Option<usize> {
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
                        // A proper name the lexicon does not know ("Darth Vader") in a feature.
                        Head::Object {
                            entry: None,
                            head_entry: None,
                            ..
                        } if self.tokens[ch.range.start].capitalized() => {}
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

    pub(super) fn text_of(&self, r: Range<usize>) -> String {
        let toks = &self.tokens[r];
        toks.iter()
            .map(|t| t.raw.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    }

    pub(super) fn each(&mut self, c: &mut Clause, chunks: &[Chunk], k: usize) {
        let after_comma = k == 0 || matches!(chunks[k - 1].item, Item::Comma);
        let next = chunks.get(k + 1).map(|x| &x.item);
        if k > 0
            && matches!(chunks[k - 1].item, Item::Prep(_))
            && let Some(p) = c.pending.take()
        {
            // "..., and at each one a stool": the preposition opens its clause.
            let fronted = k < 2 || matches!(chunks[k - 2].item, Item::And | Item::Comma);
            self.each_as_object(c, &p, next, fronted);
            return;
        }
        // "Two nightstands each hold a lamp": the subject, then "each", then its verb; also
        // after a participle phrase of a plural subject ("Six tables covered with cloths each
        // have two chairs").
        let participles_only = chunks[..k].iter().all(|x| match &x.item {
            Item::Verb(_, w) => w.ends_with("ed") || w.ends_with("ing"),
            _ => true,
        });
        let subject_plural = c
            .subject
            .first()
            .is_some_and(|r| r.instance.is_none() && is_plural_count(self.mentions[r.m].count));
        if !after_comma
            && (c.verb.is_none() || participles_only)
            && matches!(
                chunks.get(k.wrapping_sub(1)).map(|x| &x.item),
                Some(Item::Np(_))
            )
            && matches!(next, Some(Item::Verb(..)))
            && !c.subject.is_empty()
            && (c.last_np.first().map(|r| r.m) == c.subject.first().map(|r| r.m)
                || (c.verb.is_some() && participles_only && subject_plural))
        {
            // The participle was no finite verb: the verb after "each" is.
            c.verb = None;
            c.each_subject = true;
            return;
        }
        if after_comma && next.is_some() {
            // ", each with ...": about the plural phrase of the clause (its subject first),
            // not the last phrase ("tables fill the room, each with two chairs").
            let plural = |refs: &[Ref]| {
                refs.first().is_some_and(|r| {
                    r.instance.is_none() && is_plural_count(self.mentions[r.m].count)
                })
            };
            // "Two tables hold produce bins, each containing three fruits": what "each" holds
            // goes in the plural containers just named.
            let containing = matches!(next, Some(Item::Verb(class, _)) if class == "possess")
                && plural(&c.last_np)
                && c.last_np.iter().all(|r| self.mentions[r.m].container);
            let parents = if containing {
                c.last_np.clone()
            } else {
                [&c.subject, &c.focus, &c.last_np]
                    .into_iter()
                    .find(|refs| plural(refs))
                    .cloned()
                    .unwrap_or_else(|| c.focus.clone())
            };
            if parents.is_empty() {
                return;
            }
            c.distributed = parents.clone();
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
                    // What follows is the first thing of each, not a new list item.
                    c.after_sep = false;
                    // ", each topped with ...": the participle and its "with" both lead in.
                    // ", each made up with ...": a particle may come between.
                    let particle = |j: usize| match chunks.get(j).map(|x| &x.item) {
                        Some(Item::Other(_)) => true,
                        Some(Item::Np(np)) => np.head == Head::NonObject && !np.has_det(),
                        _ => false,
                    };
                    let with_at =
                        |j: usize| matches!(chunks.get(j).map(|x| &x.item), Some(Item::With));
                    c.each_with = (matches!(next, Some(Item::Verb(..)))
                        || self.participle(&chunks[k + 1]))
                        && (with_at(k + 2) || (particle(k + 2) && with_at(k + 3)));
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

    /// "two chairs at each", "a pair of boots beside each one", "at each one a stool and an
    /// inkwell": "each" as the object of a preposition stands for the things last counted
    /// in the plural before the phrases it distributes; those phrases are per thing.
    fn each_as_object(&mut self, c: &mut Clause, p: &Pending, next: Option<&Item>, fronted: bool) {
        let fronted = fronted || p.attach.is_empty();
        let before = if fronted {
            self.mentions.len()
        } else {
            p.attach
                .iter()
                .map(|r| r.m)
                .min()
                .unwrap_or(self.mentions.len())
        };
        let Some(parent) = self.plural_antecedent(before) else {
            return;
        };
        let one = match next {
            Some(Item::Other(w)) => w == "one",
            Some(Item::Np(np)) => {
                np.head == Head::NonObject && np.number == Some(1) && np.det.is_none()
            }
            _ => false,
        };
        c.skip_next = one;
        if fronted {
            // Fronted: what follows is the first thing of each.
            c.ctx = Ctx::Each(vec![Ref::new(parent)]);
            c.stack.clear();
            c.stack.push(Ctx::Room);
            c.after_sep = false;
        } else {
            self.relate_pending_each(
                c,
                p,
                Target::Mention(parent),
                None,
                Some(Ref::new(parent)),
                true,
            );
        }
    }

    /// The latest mention of this room before `before` that is counted in the plural.
    fn plural_antecedent(&self, before: usize) -> Option<usize> {
        (0..before.min(self.mentions.len())).rev().find(|&m| {
            let x = &self.mentions[m];
            x.room == self.room && !x.negated && !x.generic && is_plural_count(x.count)
        })
    }

    pub(super) fn set_for(&mut self, c: &mut Clause, chunks: &[Chunk], k: usize) {
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

    pub(super) fn in_total(&mut self, c: &Clause) {
        // "Tall stools are tucked beneath the benches, eight in total": the subject's count.
        if let Some(n) = c.bare_number
            && let Some(s) = c.subject.first().or(c.focus.first())
        {
            let m = &mut self.mentions[s.m];
            m.count = Count::Exactly(n);
            m.per = None;
            return;
        }
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
