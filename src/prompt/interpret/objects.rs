//! Object phrases: which mention a phrase names (new, an earlier one, a member of one), its
//! count, and how the clause's holder relates it (on, in, with, per parent, per setting).

use super::{Clause, Ctx, Interp, Intro, Ref, is_plural_count};
use crate::prompt::chunk::{Chunk, Head, Item, Np, Pronoun};
use crate::prompt::mentions::{Count, GroupKind, Mention, Per, phrase_count};
use crate::prompt::piece_of_furniture;
use crate::prompt::relations::{Relation, RelationKind, Target, normalize};
use crate::words::lexicon::{Lexicon, Support};

impl Interp<'_> {
    pub(super) fn pronoun_np(&mut self, c: &mut Clause, p: Pronoun) {
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
    pub(super) fn recent(&self, f: impl Fn(&Mention) -> bool, exclude: &[usize]) -> Option<usize> {
        (0..self.mentions.len()).rev().find(|&i| {
            self.alive(i)
                && self.mentions[i].room == self.room
                && !exclude.contains(&i)
                && f(&self.mentions[i])
        })
    }

    /// The shelf-like mention a "level" belongs to.
    pub(super) fn level_parent(&self) -> Option<usize> {
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

    pub(super) fn add_styles(&mut self, targets: &[Ref], np: &Np) {
        let mut styles = np.attrs.styles.clone();
        if styles.is_empty() {
            // "inspired by The Incredibles movie": the capitalised words.
            let words: Vec<String> = np.attrs.modifiers.clone();
            if !words.is_empty() {
                styles.push(words.join(" "));
            }
        }
        for s in styles {
            if targets.is_empty()
                && let Some(r) = self.rooms.get_mut(self.room)
                && !r.styles.contains(&s)
            {
                r.styles.push(s.clone());
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

    pub(super) fn object_np(
        &mut self,
        c: &mut Clause,
        np: &Np,
        chunk: &Chunk,
        next: Option<&Item>,
    ) {
        let next_is_verb = matches!(next, Some(Item::Verb(..)));
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
            if c.of_once {
                // "photographs of classic haircuts": one phrase is the subject.
                c.of_once = false;
                self.pop_ctx(c);
            }
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
        if !is_new
            && c.pending.is_none()
            && np.det.as_deref() == Some("each")
            && is_plural_count(self.mentions[r.m].count)
            && self.each_refers_back(c, &r, next)
        {
            return;
        }
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
            // ", each with two chairs, a counter with ...": the counter is not per table;
            // ", each with two monitors, a docking station and a chair.": a list to its end is.
            let keeps = c.list_goes_on
                || match &np.head {
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
            // "bins of yarn under the table": what follows is about the bins.
            c.of_once = false;
            if let Ctx::Holder(holders, _) = &c.ctx {
                c.focus.clone_from(holders);
                self.pop_ctx(c);
                c.last_np = vec![r.clone()];
                c.last_prep_obj = None;
                c.after_sep = false;
                return;
            }
            self.pop_ctx(c);
        }
        if c.zone && matches!(c.ctx, Ctx::Room) && c.verb.is_some() {
            for rel in c.zone_relations.clone() {
                self.add_relation(r.m, rel);
            }
        }
        if let Some((class, lm, target, inst, each)) = c.fronted.clone()
            && c.verb.is_some()
            && c.stack.is_empty()
            && let Some((kind, t)) = normalize(&class, lm.as_deref(), None, target)
        {
            let mut rel = Relation::new(kind, t);
            rel.instance = inst;
            self.add_relation(r.m, rel);
            if each
                && let Target::Mention(parent) = t
                && parent != r.m
                && self.mentions[r.m].per.is_none()
            {
                self.mentions[r.m].per = Some(Per::Each { parent });
            }
        }
        // "There is no television, only a pair of speakers": "only" ends the negation.
        if c.negate && !np.negated && np.quant.as_deref() == Some("exactly") {
            c.negate = false;
        }
        // "no television, because the aquarium is the entertainment": a negation's scope
        // does not reach back to a thing already named.
        if (c.negate && (is_new || !np.is_definite())) || np.negated {
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

    /// "Each desk has a monitor", ", each desk with a chair and a monitor": "each" and a noun
    /// already counted; what the desk has or comes with is per desk. True when the phrase was
    /// taken that way.
    fn each_refers_back(&mut self, c: &mut Clause, r: &Ref, next: Option<&Item>) -> bool {
        match next {
            Some(Item::With) => {
                c.ctx = Ctx::Each(vec![r.clone()]);
                c.stack.clear();
                c.stack.push(Ctx::Room);
                c.each_with = true;
                c.after_sep = false;
                c.last_np = vec![r.clone()];
                true
            }
            // ", every table covered with a cloth": a participle after a finite verb too.
            Some(Item::Verb(_, w))
                if (c.verb.is_none() || (w.ends_with("ed") && c.after_sep))
                    && matches!(c.ctx, Ctx::Room) =>
            {
                c.subject = vec![r.clone()];
                c.focus = vec![r.clone()];
                c.each_subject = true;
                c.last_np = vec![r.clone()];
                c.after_sep = false;
                true
            }
            _ => false,
        }
    }

    /// True when `np` names the same noun as mention `m` (same canonical or same head word).
    pub(super) fn same_noun(&self, m: usize, np: &Np) -> bool {
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
    pub(super) fn apply_ctx(&mut self, c: &mut Clause, r: &Ref, np: &Np) {
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
    pub(super) fn implied(&self, child: usize, parent: &Ref, intro: Intro) -> Relation {
        let cm = &self.mentions[child];
        let pm = &self.mentions[parent.m];
        let small = cm.support == Support::Surface || !cm.known;
        let pe = self.lex.lookup(&pm.category);
        let thin = pe.is_some_and(|e| e.thin);
        let contains = intro == Intro::Verb(true);
        let kind = if small && (pm.container || contains) {
            RelationKind::In
        } else if small
            && (pe.is_some_and(|e| e.holds)
                || thin
                || pm.support == Support::Wall
                || pm.support == Support::Surface)
        {
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
    pub(super) fn count_of(&self, np: &Np, c: &Clause, noun: Option<&str>) -> Count {
        let mut count = phrase_count(
            np.quant.as_deref(),
            np.number,
            np.plus,
            np.det.as_deref(),
            np.plural,
        );
        // "several pairs of tongs": a vague number of pairs is a vague number of things.
        let vague = np.number.is_none()
            && np.det.as_deref() != Some("indefinite")
            && !matches!(count, Count::Exactly(_));
        if np.group == Some(GroupKind::Pair) && !vague {
            let pairs = np.number.unwrap_or(1);
            // "heavy shears" reaches here singularised as "heavy shear".
            let tantum = noun.is_some_and(|n| {
                let last = n.rsplit(' ').next().unwrap_or(n);
                self.lex.plurale_tantum(last) || self.lex.plurale_tantum(&format!("{last}s"))
            });
            let n = if tantum {
                pairs
            } else {
                pairs.saturating_mul(2)
            };
            count = match count {
                Count::AtLeast(_) => Count::AtLeast(n),
                _ => Count::Exactly(n),
            };
        }
        // "two sets of bunk beds": a set of pieces of furniture is one piece.
        if let Some(sets) = np.sets
            && noun.is_some_and(|n| piece_of_furniture(self.lex, n))
        {
            count = Count::Exactly(sets);
        }
        if np.number.is_some() && np.quant.is_none() && !np.plus && c.carry_at_least {
            count = Count::AtLeast(count.minimum());
        }
        count
    }

    /// Finds the mention a phrase names, or creates it.
    pub(super) fn resolve_object(&mut self, c: &Clause, np: &Np, chunk: &Chunk) -> Ref {
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
        // "Glass display cases form a U around the counter": the object of a preposition is
        // not one of the things it places (a display case is a kind of counter).
        let own: Vec<usize> = c
            .pending
            .as_ref()
            .map(|p| p.attach.iter().map(|r| r.m).collect())
            .unwrap_or_default();
        let existing = |me: &Self| -> Option<usize> {
            let last = |s: &str| s.rsplit(' ').next().unwrap_or(s).to_string();
            let first = |s: &str| s.split(' ').next().unwrap_or(s).to_string();
            let kind_of = entry
                .and_then(|e| me.lex.objects.get(e))
                .and_then(|e| e.kind_of.clone());
            // "a sewing machine on a sturdy table ... the cutting table": a word naming a
            // kind of the thing that the earlier one lacks names another one.
            let kinds = kind_words(me.lex, noun);
            let same_kind = |m: &Mention| {
                let theirs: Vec<&str> = m.noun.split(' ').collect();
                kinds.iter().all(|k| theirs.contains(&k.as_str()))
            };
            me.recent(|m| m.category == *canonical && same_kind(m), &own)
                .or_else(|| {
                    me.recent(
                        |m| {
                            (last(&m.noun) == last(noun) || last(&m.category) == last(canonical))
                                && same_kind(m)
                        },
                        &own,
                    )
                })
                .or_else(|| {
                    me.recent(
                        |m| {
                            me.lex
                                .lookup(&m.category)
                                .and_then(|e| e.kind_of.as_deref())
                                .is_some_and(|k| k == canonical.as_str())
                                && same_kind(m)
                        },
                        &own,
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
                                    && same_kind(m)
                            },
                            &own,
                        )
                    })
                })
        };
        // "sixteen desks ..., each desk with a chair": "each" over things already counted
        // refers back to them.
        let each_back = matches!(np.det.as_deref(), Some("each"))
            && existing(self).is_some_and(|m| is_plural_count(self.mentions[m].count));
        if (definite || each_back)
            && let Some(m) = existing(self)
        {
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
                Count::AtLeast(x) => Count::AtLeast(x.saturating_add(1)),
                _ => Count::Exactly(n.saturating_add(1)),
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
}

impl Interp<'_> {
    /// "A six-bed hospital ward", "a twelve-desk classroom": a number joined to an object
    /// noun before a room word counts those things in the room. The room's own reading has
    /// already decided that such a word before a dwelling counts rooms ("a three-bed flat").
    pub(super) fn things_counted_before_room(&mut self, chunk: &Chunk) {
        for t in &self.tokens[chunk.range.clone()] {
            let Some((a, b)) = t.text.split_once('-') else {
                continue;
            };
            let Some(n) = self.lex.number_word(a).filter(|&n| n >= 2) else {
                continue;
            };
            let Some(e) = self.lex.lookup(&self.lex.singular(b)) else {
                continue;
            };
            if self
                .mentions
                .iter()
                .any(|m| m.room == self.room && m.category == e.noun)
            {
                continue;
            }
            self.mentions.push(Mention {
                category: e.noun.clone(),
                noun: self.lex.singular(b),
                count: Count::Exactly(n),
                negated: false,
                known: true,
                head: None,
                support: e.support,
                container: e.container,
                generic: e.generic,
                attributes: Default::default(),
                relations: Vec::new(),
                per: None,
                group: None,
                place_settings: None,
                covers: Vec::new(),
                room: self.room,
                span: [t.start, t.end],
                definite: false,
            });
            self.absorbed.push(None);
        }
    }
}

/// The words before the head of `noun` that name a kind of it ("cutting" of "cutting table",
/// "dining" of "dining chair"): a gerund or a noun WordNet does not also read as an adjective;
/// not a colour, material, size or style word.
fn kind_words(lex: &Lexicon, noun: &str) -> Vec<String> {
    let words: Vec<&str> = noun.split(' ').collect();
    let Some((_, before)) = words.split_last() else {
        return Vec::new();
    };
    before
        .iter()
        .filter(|w| {
            let gerund = w.len() > 5 && w.ends_with("ing");
            let noun_only =
                crate::words::ground::is_noun(w) && !crate::words::ground::is_adjective(w);
            (gerund || noun_only)
                && lex.material(w).is_none()
                && lex.size_adjective(w).is_none()
                && !lex.is_function_word(w)
        })
        .map(|w| w.to_string())
        .collect()
}
