//! From a prompt to a house brief: which rooms (with counts and en-suite owners), the text
//! about each room, house-wide style, size words, wall height, materials and open connections.
//!
//! The rooms and the clauses about each come from the prompt reader ([`crate::prompt::read`]),
//! the one place that decides whether a prompt is a house and which room a sentence is about;
//! this module adds what the layout needs beyond that (materials, ceiling height, open
//! connections, sentences about the whole house). A prompt that names one room is a one-room
//! house whose text is the whole prompt. It does not size rooms or decide how they connect
//! ([`super::spec`] does).

use serde::{Deserialize, Serialize};

mod words;

use super::knowledge::knowledge;
use crate::prompt::{Reading, Scope};
use words::{house_wide, materials_in, sentences, size_word, tokens, wall_height_in};

/// Most rooms one phrase adds ("forty offices" gives 20).
pub const MAX_PER_MENTION: usize = crate::prompt::rooms::MAX_PER_PHRASE as usize;
/// Most rooms of a house; the rest of a longer list is left out (and reported).
pub const MAX_ROOMS: usize = crate::prompt::rooms::MAX_ROOMS;

/// One room the prompt asks for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomRequest {
    /// Room type (a key of the room registry, [`crate::knowledge::rooms`]).
    pub room_type: String,
    /// The words the prompt uses for it, singular ("exam room").
    pub label: String,
    /// 1-based number among the rooms of the same label, and how many there are.
    pub ordinal: [usize; 2],
    /// Clauses of the prompt about this room, as written.
    pub text: Vec<String>,
    /// Size factor from words such as "small" or "large" next to the room.
    pub size_scale: f64,
    /// For an en-suite bathroom: index of its bedroom in [`HouseBrief::rooms`].
    pub owner: Option<usize>,
    /// Floor material named for this room.
    pub floor_material: Option<String>,
    /// Wall material named for this room.
    pub wall_material: Option<String>,
}

/// What the layout takes from a prompt.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HouseBrief {
    /// The prompt as given.
    pub prompt: String,
    /// The building as the prompt names it ("A boutique hotel"); empty for one room.
    pub head: String,
    /// True when the prompt names several rooms.
    pub is_house: bool,
    /// Every room instance, counts expanded, in prompt order.
    pub rooms: Vec<RoomRequest>,
    /// Style words that apply to the whole house.
    pub style: Vec<String>,
    /// Clauses about the whole house ("wooden floors throughout").
    pub house_text: Vec<String>,
    /// Size factor of the whole house ("a large family home").
    pub size_scale: f64,
    /// Wall height asked for, metres.
    pub wall_height: Option<f64>,
    /// Pairs of rooms (indices) the prompt wants openly connected.
    pub open_pairs: Vec<(usize, usize)>,
    /// House-wide floor material.
    pub floor_material: Option<String>,
    /// House-wide wall material.
    pub wall_material: Option<String>,
    /// Rooms the prompt asks for beyond [`MAX_ROOMS`] (or [`MAX_PER_MENTION`] per phrase)
    /// that were left out.
    #[serde(default)]
    pub left_out: usize,
}

/// Reads the house brief of a prompt through the prompt reader ([`crate::prompt::read`]).
pub fn read(prompt: &str) -> HouseBrief {
    from_reading(prompt, &crate::prompt::read(prompt))
}

/// The brief of a prompt the reader has read: its rooms (counts expanded, en-suites with
/// their owners), the text about each, and what the text says about the whole house
/// (materials, ceiling height, open connections, clauses "throughout").
pub fn from_reading(prompt: &str, reading: &Reading) -> HouseBrief {
    let text = prompt.trim();
    let sents = sentences(text);
    let k = knowledge();
    let mut brief = HouseBrief {
        prompt: prompt.to_string(),
        head: String::new(),
        is_house: reading.scope == Scope::House,
        rooms: Vec::new(),
        style: Vec::new(),
        house_text: Vec::new(),
        size_scale: 1.0,
        wall_height: None,
        open_pairs: Vec::new(),
        floor_material: None,
        wall_material: None,
        left_out: reading
            .notes
            .iter()
            .filter_map(|n| {
                let (asked, rest) = n.split_once(' ')?;
                let built: usize = rest.split(", ").nth(1)?.split(' ').next()?.parse().ok()?;
                asked.parse::<usize>().ok().map(|a| a.saturating_sub(built))
            })
            .sum(),
    };
    for &(s, e) in &sents {
        if let Some(h) = wall_height_in(&tokens(text, s, e)) {
            brief.wall_height = Some(h);
        }
    }
    // Ordinals among rooms with the same words ("exam room" 2 of 4).
    let same_words = |i: usize| {
        let w = &reading.rooms[i].words;
        let all: Vec<usize> = (0..reading.rooms.len())
            .filter(|&j| reading.rooms[j].words == *w && reading.rooms[j].parent.is_none())
            .collect();
        let pos = all.iter().position(|&j| j == i).map_or(1, |p| p + 1);
        [pos, all.len().max(1)]
    };
    for (i, r) in reading.rooms.iter().enumerate() {
        let en_suite = r.room_type == "en_suite";
        brief.rooms.push(RoomRequest {
            room_type: r.room_type.clone(),
            label: if en_suite {
                "en-suite bathroom".to_string()
            } else {
                r.words.clone()
            },
            ordinal: if r.parent.is_some() {
                [1, 1]
            } else {
                same_words(i)
            },
            text: Vec::new(),
            size_scale: r.size_scale,
            owner: r.parent,
            floor_material: None,
            wall_material: None,
        });
    }
    if brief.rooms.is_empty() {
        brief.rooms.push(RoomRequest {
            room_type: "room".into(),
            label: "room".into(),
            ordinal: [1, 1],
            text: Vec::new(),
            size_scale: 1.0,
            owner: None,
            floor_material: None,
            wall_material: None,
        });
    }
    if !brief.is_house {
        brief.rooms[0].text.push(text.to_string());
        brief.rooms[0].size_scale = reading.size_scale;
        for &(s, e) in &sents {
            let (f, w) = materials_in(&tokens(text, s, e));
            brief.rooms[0].floor_material = f.or(brief.rooms[0].floor_material.take());
            brief.rooms[0].wall_material = w.or(brief.rooms[0].wall_material.take());
        }
        return brief;
    }
    let first = sents.first().copied().unwrap_or((0, text.len()));
    let head_toks = tokens(text, first.0, first.1);
    brief.size_scale = head_toks
        .iter()
        .take_while(|t| !matches!(t.w.as_str(), "with" | "includes" | "has" | "features"))
        .find_map(|t| size_word(&t.w))
        .map(|s| if s < 1.0 { 0.9 } else { 1.12 })
        .unwrap_or(1.0);
    brief.head = reading
        .house_type
        .as_deref()
        .filter(|h| !crate::words::lexicon().is_non_object(h))
        .map(with_article)
        .unwrap_or_default();
    brief.style = reading.styles.clone();
    brief.style.extend(
        head_toks
            .iter()
            .filter(|t| k.house().style_words.contains(&t.w))
            .map(|t| t.w.clone()),
    );
    // Sentences about the whole house ("The floors are hardwood throughout.").
    let mut house_wide_texts: Vec<String> = Vec::new();
    let mut house_wide_raw: Vec<String> = Vec::new();
    let labels = label_words(&brief.rooms);
    for &(s, e) in sents.iter().skip(1) {
        let toks = tokens(text, s, e);
        let words: Vec<String> = toks.iter().map(|t| crate::prompt::singular(&t.w)).collect();
        let named = rooms_named(&words, &labels);
        // "The home office contains ...": a room's sentence, though "home" names a house.
        let about_a_room = named.first().is_some_and(|&(at, _)| at <= 1);
        if house_wide(&toks) && !about_a_room {
            // A sentence that names rooms ("The clinic comprises a waiting room, two
            // treatment rooms ...", "The flat has no dining table, and the kitchen has an
            // island") reaches the rooms it names (every room of a named label), not all.
            let named_labels: Vec<&Vec<String>> = named.iter().map(|&(_, r)| &labels[r]).collect();
            let names_rooms = !named.is_empty();
            let (f, w) = materials_in(&toks);
            brief.floor_material = f.or(brief.floor_material.take());
            brief.wall_material = w.or(brief.wall_material.take());
            let t = text[s..e].trim().to_string();
            brief.style.extend(
                toks.iter()
                    .filter(|t| k.house().style_words.contains(&t.w))
                    .map(|t| t.w.clone()),
            );
            house_wide_texts.push(t.trim_end_matches(['.', '!', '?', ';']).to_string());
            house_wide_raw.push(t.clone());
            if names_rooms {
                for (room, label) in brief.rooms.iter_mut().zip(&labels) {
                    if named_labels.contains(&label) {
                        room.text.push(t.clone());
                    }
                }
            } else {
                brief.house_text.push(t);
            }
        }
    }
    // Each room's own clauses, as the reader attributed them.
    for (i, r) in reading.rooms.iter().enumerate() {
        for part in r
            .text
            .split(" ... ")
            .map(str::trim)
            .filter(|p| !p.is_empty())
        {
            let bare = part.trim_end_matches(['.', '!', '?', ';']);
            if house_wide_texts.iter().any(|h| h.contains(bare)) {
                continue;
            }
            // House-wide sentences inside a longer part are the house's, not the room's.
            let mut own = part.to_string();
            for h in house_wide_raw.iter().chain(&house_wide_texts) {
                own = own.replacen(h.as_str(), " ", 1);
            }
            let own = own
                .split_whitespace()
                .filter(|w| !matches!(*w, "." | "!" | "?" | ";"))
                .collect::<Vec<_>>()
                .join(" ");
            let part = own.trim_start_matches(['.', '!', '?', ';', ' ']);
            if part.is_empty() {
                continue;
            }
            let toks = tokens(part, 0, part.len());
            let (f, w) = materials_in(&toks);
            let room = &mut brief.rooms[i];
            room.floor_material = f.or(room.floor_material.take());
            room.wall_material = w.or(room.wall_material.take());
            room.text.push(capitalise(part));
        }
    }
    brief.open_pairs = open_pairs(text, &sents, &brief.rooms);
    brief
}

/// The words of each room's label.
fn label_words(rooms: &[RoomRequest]) -> Vec<Vec<String>> {
    rooms
        .iter()
        .map(|r| r.label.split(' ').map(str::to_string).collect())
        .collect()
}

/// The rooms whose labels a sentence's singular words name, as (word position, room), in
/// order; each room once.
fn rooms_named(w: &[String], labels: &[Vec<String>]) -> Vec<(usize, usize)> {
    let mut found: Vec<(usize, usize)> = Vec::new();
    for i in 0..w.len() {
        for (r, l) in labels.iter().enumerate() {
            if l.is_empty() || i + l.len() > w.len() {
                continue;
            }
            if w[i..i + l.len()] == l[..] && !found.iter().any(|&(_, x)| x == r) {
                found.push((i, r));
                break;
            }
        }
    }
    found.sort();
    found
}

/// Pairs of rooms the prompt opens to each other: "an open-plan kitchen and living room",
/// "the kitchen is open to the dining room", "opens onto the terrace".
fn open_pairs(text: &str, sents: &[(usize, usize)], rooms: &[RoomRequest]) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = Vec::new();
    let labels = label_words(rooms);
    for &(s, e) in sents {
        let toks = tokens(text, s, e);
        let w: Vec<String> = toks.iter().map(|t| crate::prompt::singular(&t.w)).collect();
        let found = rooms_named(&w, &labels);
        let open_word = |i: usize| {
            matches!(
                toks[i].w.as_str(),
                "open-plan" | "open-concept" | "open" | "opens"
            )
        };
        for pair in found.windows(2) {
            let ((ia, a), (ib, b)) = (pair[0], pair[1]);
            if ia + labels[a].len() > ib {
                continue;
            }
            // Before the first room, or in its own name ("open-plan kitchen").
            let before_a = (ia.saturating_sub(3)..ia + labels[a].len()).any(open_word);
            let between: Vec<&str> = w[ia + labels[a].len()..ib]
                .iter()
                .map(String::as_str)
                .collect();
            let plan = before_a && between.contains(&"and") && between.len() <= 3;
            let opens = between
                .iter()
                .any(|x| matches!(*x, "open" | "opens" | "open-plan"))
                && between
                    .iter()
                    .any(|x| matches!(*x, "to" | "onto" | "into" | "with"));
            let (a, b) = (a.min(b), a.max(b));
            if (plan || opens) && a != b && !out.contains(&(a, b)) {
                out.push((a, b));
            }
        }
    }
    out
}

/// Article for a label ("an exam room", "a bedroom").
pub fn with_article(label: &str) -> String {
    let vowel = label
        .chars()
        .next()
        .is_some_and(|c| "aeiou".contains(c.to_ascii_lowercase()));
    let xray = label.starts_with("x-");
    format!("{} {label}", if vowel || xray { "an" } else { "a" })
}

impl HouseBrief {
    /// The prompt of room `i`: for a one-room prompt the prompt itself; in a house, what the
    /// room is, the sentences about it, and the house-wide sentences and style.
    pub fn room_prompt(&self, i: usize) -> String {
        let Some(r) = self.rooms.get(i) else {
            return String::new();
        };
        if !self.is_house {
            return self.prompt.trim().to_string();
        }
        let mut what = with_article(&r.label);
        if r.ordinal[1] > 1 {
            what.push_str(&format!(" ({} of {})", r.ordinal[0], r.ordinal[1]));
        }
        if let Some(o) = r.owner.and_then(|o| self.rooms.get(o)) {
            let mut owner = o.label.clone();
            if o.ordinal[1] > 1 {
                owner.push_str(&format!(" {}", o.ordinal[0]));
            }
            what.push_str(&format!(" belonging to the {owner}"));
        }
        let head = self.head.trim();
        let mut out = if head.is_empty() {
            format!("{}.", capitalise(&what))
        } else {
            let mut h = head.to_string();
            if let Some(c) = h.chars().next() {
                let lower: String = c.to_lowercase().collect();
                h.replace_range(..c.len_utf8(), &lower);
            }
            format!("{} in {h}.", capitalise(&what))
        };
        for t in r.text.iter().chain(&self.house_text) {
            out.push(' ');
            out.push_str(t.trim());
            if !t.trim_end().ends_with(['.', '!', '?']) {
                out.push('.');
            }
        }
        if !self.style.is_empty() {
            let mut style = self.style.clone();
            style.dedup();
            out.push_str(&format!(" Style: {}.", style.join(", ")));
        }
        out
    }
}

fn capitalise(s: &str) -> String {
    let mut out = s.to_string();
    if let Some(c) = s.chars().next() {
        let upper: String = c.to_uppercase().collect();
        out.replace_range(..c.len_utf8(), &upper);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Any text reads into at least one room without panicking, and every sentence ends
        /// up somewhere.
        #[test]
        fn any_text_reads(text in "\\PC{0,300}") {
            let b = read(&text);
            prop_assert!(!b.rooms.is_empty() && b.rooms.len() <= MAX_ROOMS);
            for i in 0..b.rooms.len() {
                let _ = b.room_prompt(i);
            }
        }

        #[test]
        fn house_like_text_reads(words in proptest::collection::vec(
            prop_oneof!["a", "two", "the", "with", "and", "kitchen", "bedroom", "bathrooms",
                "en-suite", "first", "its", "has", "corridor", ",", ".", "open to", "marble",
                "floors", "3 m", "ceilings", "forty", "offices", "X-ray room"], 0..60)) {
            let text = words.join(" ");
            let b = read(&text);
            prop_assert!(!b.rooms.is_empty() && b.rooms.len() <= MAX_ROOMS);
            for r in &b.rooms {
                if let Some(o) = r.owner {
                    prop_assert!(o < b.rooms.len());
                }
            }
            let spec = crate::layout::spec::house_spec(&b);
            prop_assert_eq!(spec.rooms.len(), b.rooms.len());
        }
    }

    #[test]
    fn huge_houses_are_capped_and_say_so() {
        let b = read("An office building with 40 offices, 30 meeting rooms and a corridor.");
        assert_eq!(b.rooms.len(), MAX_ROOMS);
        assert!(b.left_out > 0);
    }

    fn types(b: &HouseBrief) -> Vec<&str> {
        b.rooms.iter().map(|r| r.room_type.as_str()).collect()
    }

    #[test]
    fn dental_office_rooms_counts_and_ordinals() {
        let b = read(
            "A dental office with a reception-waiting area, two exam rooms, an X-ray room, a \
             corridor, and a bathroom. The reception-waiting area has a reception desk with a \
             computer and three chairs. The first exam room has a dental chair and a cabinet. \
             The second exam room has a dental chair and a sink. The X-ray room has an X-ray \
             machine. The corridor has a bench. The bathroom has a toilet and a sink.",
        );
        assert!(b.is_house);
        assert_eq!(
            types(&b),
            [
                "reception",
                "exam_room",
                "exam_room",
                "xray_room",
                "corridor",
                "bathroom"
            ]
        );
        assert!(b.rooms[1].text[0].contains("cabinet"));
        assert!(b.rooms[2].text[0].contains("sink"));
        assert!(b.rooms[4].text[0].contains("bench"));
        let p = b.room_prompt(2);
        assert!(
            p.starts_with("An exam room (2 of 2) in a dental office."),
            "{p}"
        );
    }

    #[test]
    fn en_suites_belong_to_their_bedrooms_and_get_their_clause() {
        let b = read(
            "A boutique hotel with a reception, four guest bedrooms with en-suite bathrooms, a \
             restaurant, a kitchen, a gym, a lounge, and a corridor. The first guest bedroom has \
             a bed with two nightstands and its bathroom has a toilet, a sink, and a shower. The \
             second guest bedroom has a bed and a desk and its bathroom has a toilet, a sink, and \
             a bathtub.",
        );
        let en: Vec<&RoomRequest> = b
            .rooms
            .iter()
            .filter(|r| r.room_type == "en_suite")
            .collect();
        assert_eq!(en.len(), 4);
        let beds: Vec<usize> = (0..b.rooms.len())
            .filter(|&i| b.rooms[i].room_type == "guest_bedroom")
            .collect();
        assert_eq!(beds.len(), 4);
        let owners: Vec<usize> = en.iter().filter_map(|r| r.owner).collect();
        assert_eq!(owners, beds);
        assert!(en[0].text[0].contains("shower"), "{:?}", en[0].text);
        assert!(!b.rooms[beds[0]].text[0].contains("shower"));
        assert!(en[1].text[0].contains("bathtub"));
        assert_eq!(b.rooms.len(), 14);
    }

    #[test]
    fn head_room_is_the_building_only_with_a_list() {
        let b = read(
            "A small restaurant with a dining area, a kitchen, a bar, a storage room, and a bathroom.",
        );
        assert_eq!(
            types(&b),
            ["dining_room", "kitchen", "bar", "storage_room", "bathroom"]
        );
        let b = read(
            "A restaurant with four dining tables, each surrounded by four chairs. A bar counter runs along one wall with six bar stools in front.",
        );
        assert!(!b.is_house);
        assert_eq!(types(&b), ["restaurant"]);
        let b = read("A bedroom with an en-suite bathroom.");
        assert_eq!(types(&b), ["bedroom", "en_suite"]);
        assert_eq!(b.rooms[1].owner, Some(0));
    }

    #[test]
    fn unassigned_items_go_where_they_belong() {
        let b = read(
            "An apartment with a kitchen, a living room and a bedroom. There is a dining table with four chairs. The floors are hardwood throughout.",
        );
        let kitchen = b.rooms.iter().find(|r| r.room_type == "kitchen").unwrap();
        assert!(kitchen.text.iter().any(|t| t.contains("dining table")));
        assert_eq!(b.floor_material.as_deref(), Some("oak"));
    }

    #[test]
    fn materials_heights_and_open_plans() {
        let b = read(
            "A house with an open-plan kitchen and living room, a bedroom and a bathroom. The \
             bathroom has marble floors. The house has 3 m ceilings.",
        );
        assert_eq!(b.wall_height, Some(3.0));
        let bath = b.rooms.iter().find(|r| r.room_type == "bathroom").unwrap();
        assert_eq!(bath.floor_material.as_deref(), Some("marble"));
        assert_eq!(b.open_pairs, vec![(0, 1)]);
    }

    /// "Each treatment room has ..." furnishes both treatment rooms' prompts; a sentence that
    /// lists the rooms is the layout's and no room's prompt repeats it, so every room's plan
    /// holds its own contents (not the first room's).
    #[test]
    fn each_room_sentences_reach_every_such_room_and_room_lists_stay_out() {
        let prompt = "This physiotherapy clinic is calm and clean. The clinic comprises a waiting \
                      room, two treatment rooms and a staff room. The waiting room is lined with \
                      eight padded chairs. Each treatment room has a treatment table and a \
                      rolling stool. The staff room offers a kettle and a small fridge.";
        let b = read(prompt);
        assert_eq!(
            types(&b),
            ["waiting_room", "exam_room", "exam_room", "break_room"]
        );
        // "The home office ..." is the room's sentence ("home" also names a house), and a
        // house-wide sentence appears once in each room's prompt.
        let b2 = read(
            "An apartment with a living room and a home office. The home office contains a \
             standing desk. A few houseplants are scattered throughout.",
        );
        let office = b2.room_prompt(1);
        assert!(office.contains("standing desk"), "{office}");
        assert_eq!(office.matches("houseplants").count(), 1, "{office}");
        assert!(!b2.room_prompt(0).contains("standing desk"));
        // A house sentence that names one room reaches that room, negation and all.
        let b3 = read(
            "A small apartment with a kitchen, a living room and a bedroom. The apartment has \
             no dining table, and the kitchen has a small island.",
        );
        let kitchen =
            crate::layout::spec::room_plan("kitchen", &b3.room_prompt(0), Some(&b3.prompt));
        assert!(kitchen.furniture.iter().any(|w| w.noun == "kitchen island"));
        assert!(kitchen.excluded.iter().any(|n| n == "dining table"));
        assert!(!b3.room_prompt(2).contains("island"));
        // A room's prompt that still names the other rooms plans the room's own contents.
        let text = "A staff room in a clinic. The clinic comprises a waiting room with eight \
                    chairs and a staff room. The staff room offers a kettle.";
        let plan = crate::layout::spec::room_plan("break_room", text, Some(text));
        assert_eq!(plan.room_type, "break_room");
        assert!(plan.all_wants().any(|w| w.explicit && w.noun == "kettle"));
        assert!(!plan.all_wants().any(|w| w.explicit && w.noun == "chair"));
        for i in 0..b.rooms.len() {
            let p = b.room_prompt(i);
            assert_eq!(p.matches("comprises").count(), 1, "room {i}: {p}");
            let plan = crate::layout::spec::room_plan(&b.rooms[i].room_type, &p, Some(&b.prompt));
            let nouns: Vec<&str> = plan
                .all_wants()
                .filter(|w| w.explicit)
                .map(|w| w.noun.as_str())
                .collect();
            let own: &[&str] = match i {
                0 => &["chair"],
                1 | 2 => &["table", "stool"],
                _ => &["kettle", "refrigerator"],
            };
            for n in own {
                assert!(
                    nouns.iter().any(|x| x.contains(n)),
                    "room {i} lacks {n}: {nouns:?}\n{p}"
                );
            }
            let foreign = ["kettle", "table"];
            let others = foreign.iter().filter(|f| !own.contains(f));
            for f in others {
                assert!(
                    !nouns.iter().any(|x| x.contains(f)),
                    "room {i} has {f}: {nouns:?}"
                );
            }
        }
    }
}
