//! From a prompt to a house brief: which rooms (with counts and en-suite owners), the text
//! about each room, house-wide style, size words, wall height, materials and open connections.
//!
//! This is the layout's adapter onto prompt reading. It works on the prompt's own sentences:
//! the first sentence lists the rooms ("A dental office with a reception, two exam rooms, ...");
//! later sentences and clauses are attributed to the room they start with ("The first exam
//! room has ..."), or, when they name no room, to the room their objects belong in (a dining
//! table goes to the kitchen when there is no dining room). A prompt that names one room is a
//! one-room house whose text is the whole prompt. It does not size rooms or decide how they
//! connect ([`super::spec`] does).

use serde::{Deserialize, Serialize};

mod words;

use super::knowledge::{self, Role, knowledge};
use crate::prompt::singular;
use words::{
    Clause, Mention, Tok, clauses, count_before, determiner_before, house_wide, materials_in,
    mentions, ordinal_before, sentences, size_before, size_word, tokens, wall_height_in,
};

/// Most rooms one phrase adds ("forty offices" gives 20).
pub const MAX_PER_MENTION: usize = 20;
/// Most rooms of a house; the rest of a longer list is left out (and reported).
pub const MAX_ROOMS: usize = 40;

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

/// Index of the room an object noun in `toks` belongs in, by the item table.
fn room_for_items(toks: &[Tok], rooms: &[RoomRequest]) -> Option<usize> {
    let items = &knowledge().house().items_to_rooms;
    for i in 0..toks.len() {
        for n in [2usize, 1] {
            if i + n > toks.len() {
                continue;
            }
            let mut words: Vec<String> = toks[i..i + n].iter().map(|t| t.w.clone()).collect();
            if let Some(last) = words.last_mut() {
                *last = singular(last);
            }
            if let Some(types) = items.get(&words.join(" ")) {
                for ty in types {
                    if let Some(r) = rooms.iter().position(|r| &r.room_type == ty) {
                        return Some(r);
                    }
                }
            }
        }
    }
    None
}

/// The room most visitors are in: the entry, else the first passable room, else the first.
fn main_room(rooms: &[RoomRequest]) -> usize {
    let role = |r: &RoomRequest| knowledge::kind(&r.room_type).role;
    rooms
        .iter()
        .position(|r| role(r) == Role::Entry)
        .or_else(|| rooms.iter().position(|r| matches!(role(r), Role::Public)))
        .unwrap_or(0)
}

/// Where a room is listed: its tokens and the room instances it expands to.
struct Listed {
    mention: Mention,
    count: usize,
    owner_of: Option<usize>,
}

/// Reads the room list of the first sentence: `(head byte end, listed rooms)`.
fn room_list(text: &str, s0: (usize, usize)) -> (usize, Vec<Listed>, Vec<Mention>) {
    let toks = tokens(text, s0.0, s0.1);
    let split = toks.iter().position(|t| {
        matches!(
            t.w.as_str(),
            "with" | "containing" | "featuring" | "comprising" | "including" | "has" | "contains"
        )
    });
    let head_end = split.map(|i| toks[i].start).unwrap_or(s0.1);
    let ms = mentions(&toks);
    let (head, list): (Vec<Mention>, Vec<Mention>) = ms
        .into_iter()
        .partition(|m| split.is_none_or(|s| m.first < s));
    let mut listed: Vec<Listed> = Vec::new();
    for m in list {
        // "the room", "the kitchen" in the list refer to a room, they do not add one.
        let det = determiner_before(&toks, m.first);
        if m.room_type == "room" || det.is_some() {
            continue;
        }
        let kind = knowledge::kind(&m.room_type);
        let after_with = m.first > 0
            && (m.first.saturating_sub(4)..m.first).any(|i| toks[i].w == "with")
            && !(m.first.saturating_sub(4)..m.first).any(|i| toks[i].w == "and");
        let prev_private = listed
            .last()
            .map(|l| knowledge::kind(&l.mention.room_type).role == Role::Private)
            .unwrap_or(false);
        if kind.role == Role::Wet && after_with && prev_private && !listed.is_empty() {
            // "four guest bedrooms with en-suite bathrooms": one each, owned by the bedroom.
            let owner = listed.len() - 1;
            let n = listed[owner].count;
            let mut m = m;
            m.room_type = "en_suite".into();
            listed.push(Listed {
                count: count_before(&toks, m.first)
                    .filter(|c| *c <= n)
                    .unwrap_or(n),
                mention: m,
                owner_of: Some(owner),
            });
            continue;
        }
        let count = count_before(&toks, m.first)
            .unwrap_or(if m.plural { 2 } else { 1 })
            .min(MAX_PER_MENTION);
        if count == 0 {
            continue;
        }
        listed.push(Listed {
            mention: m,
            count,
            owner_of: None,
        });
    }
    (head_end, listed, head)
}

/// Reads the house brief of a prompt.
pub fn read(prompt: &str) -> HouseBrief {
    let text = prompt.trim();
    let sents = sentences(text);
    let first = sents.first().copied().unwrap_or((0, text.len()));
    let (head_end, listed, head_mentions) = room_list(text, first);
    let head_toks = tokens(text, first.0, head_end);
    let k = knowledge();
    let head_has_house_noun = head_toks
        .iter()
        .any(|t| k.house().house_nouns.contains(&t.w));
    let listed_total: usize = listed.iter().map(|l| l.count).sum();
    let head_room = head_mentions
        .iter()
        .find(|m| m.room_type != "room" || head_mentions.len() == 1)
        .cloned();

    let mut brief = HouseBrief {
        prompt: prompt.to_string(),
        head: String::new(),
        is_house: false,
        rooms: Vec::new(),
        style: head_toks
            .iter()
            .filter(|t| k.house().style_words.contains(&t.w))
            .map(|t| t.w.clone())
            .collect(),
        house_text: Vec::new(),
        size_scale: 1.0,
        wall_height: None,
        open_pairs: Vec::new(),
        floor_material: None,
        wall_material: None,
        left_out: 0,
    };

    let add =
        |brief: &mut HouseBrief, m: &Mention, count: usize, owner: Option<usize>, size: f64| {
            let first_index = brief.rooms.len();
            let room_left = MAX_ROOMS.saturating_sub(first_index);
            brief.left_out += count.saturating_sub(room_left);
            for i in 0..count.min(room_left) {
                // An en-suite whose bedroom was left out is left out too.
                let owner = match owner {
                    Some(o) if o + i >= first_index => {
                        brief.left_out += 1;
                        continue;
                    }
                    o => o.map(|o| o + i),
                };
                brief.rooms.push(RoomRequest {
                    room_type: m.room_type.clone(),
                    label: if m.room_type == "en_suite" {
                        "en-suite bathroom".into()
                    } else {
                        m.label.clone()
                    },
                    ordinal: [i + 1, count],
                    text: Vec::new(),
                    size_scale: size,
                    owner,
                    floor_material: None,
                    wall_material: None,
                });
            }
            first_index
        };

    let house =
        listed_total >= 2 || (listed_total == 1 && (head_room.is_some() || head_has_house_noun));
    if !house {
        // One room: its type is the first room word of the prompt (any sentence).
        let all = tokens(text, 0, text.len());
        let m = head_room.or_else(|| mentions(&all).into_iter().find(|m| m.room_type != "room"));
        let m = m.unwrap_or(Mention {
            room_type: "room".into(),
            first: 0,
            last: 0,
            plural: false,
            label: "room".into(),
        });
        let size = size_before(&head_toks, head_toks.len()).unwrap_or(1.0);
        add(&mut brief, &m, 1, None, size);
        brief.rooms[0].text.push(text.to_string());
        for &(s, e) in &sents {
            let toks = tokens(text, s, e);
            if let Some(h) = wall_height_in(&toks) {
                brief.wall_height = Some(h);
            }
            let (f, w) = materials_in(&toks);
            brief.rooms[0].floor_material = f.or(brief.rooms[0].floor_material.take());
            brief.rooms[0].wall_material = w.or(brief.rooms[0].wall_material.take());
        }
        return brief;
    }

    brief.is_house = true;
    brief.size_scale = head_toks
        .iter()
        .find_map(|t| size_word(&t.w))
        .map(|s| if s < 1.0 { 0.9 } else { 1.12 })
        .unwrap_or(1.0);
    brief.head = text[first.0..head_end]
        .trim()
        .trim_end_matches(',')
        .to_string();
    // A head that is itself a room ("A bedroom with an en-suite bathroom") is the first room.
    let first_toks = tokens(text, first.0, first.1);
    let mut starts: Vec<usize> = Vec::new();
    if listed_total == 1
        && let Some(m) = &head_room
        && !head_has_house_noun
    {
        let size = size_before(&first_toks, m.first).unwrap_or(1.0);
        add(&mut brief, m, 1, None, size);
        starts.push(0);
    }
    let head_added = starts.len();
    for l in &listed {
        let mut mention = l.mention.clone();
        let mut owner = l.owner_of.and_then(|o| starts.get(head_added + o).copied());
        // "A bedroom with a bathroom": the bathroom is the bedroom's en-suite.
        if head_added == 1
            && owner.is_none()
            && knowledge::kind(&mention.room_type).role == Role::Wet
            && knowledge::kind(&brief.rooms[0].room_type).role == Role::Private
        {
            mention.room_type = "en_suite".into();
            owner = Some(0);
        }
        let size = size_before(&first_toks, l.mention.first).unwrap_or(1.0);
        let at = add(&mut brief, &mention, l.count, owner, size);
        starts.push(at);
    }
    // "an open-plan kitchen and living room": open connections inside the list.
    for w in listed.windows(2) {
        let (a, b) = (&w[0].mention, &w[1].mention);
        let between: Vec<&str> = first_toks[a.last + 1..b.first]
            .iter()
            .map(|t| t.w.as_str())
            .collect();
        let open_before = (a.first.saturating_sub(3)..a.first).any(|i| {
            matches!(
                first_toks[i].w.as_str(),
                "open-plan" | "open" | "open-concept"
            )
        });
        if open_before && between.contains(&"and") && between.len() <= 3 {
            let ia = brief.rooms.iter().position(|r| r.label == a.label);
            let ib = brief.rooms.iter().position(|r| r.label == b.label);
            if let (Some(ia), Some(ib)) = (ia, ib) {
                brief.open_pairs.push((ia, ib));
            }
        }
    }
    // The first sentence may carry materials and height for the whole house.
    if let Some(h) = wall_height_in(&first_toks) {
        brief.wall_height = Some(h);
    }

    // Later sentences: attribute each clause.
    let mut last_subject: Option<usize> = None;
    for &(s, e) in sents.iter().skip(1) {
        for clause in clauses(text, s, e) {
            attribute(&mut brief, text, &clause, &mut last_subject);
        }
    }
    brief
}

/// The room a mention in a later sentence refers to.
fn resolve(brief: &HouseBrief, toks: &[Tok], m: &Mention, subject: Option<usize>) -> Option<usize> {
    let det = determiner_before(toks, m.first);
    if det.as_deref() == Some("its")
        && let Some(owner) = subject
        && let Some(i) = brief.rooms.iter().position(|r| r.owner == Some(owner))
    {
        return Some(i);
    }
    let same: Vec<usize> = brief
        .rooms
        .iter()
        .enumerate()
        .filter(|(_, r)| r.room_type == m.room_type || r.label == m.label)
        .map(|(i, _)| i)
        .collect();
    // A bathroom mentioned in a house with only en-suites, etc.: same role as a fallback.
    let same = if same.is_empty() && m.room_type == "bathroom" {
        brief
            .rooms
            .iter()
            .enumerate()
            .filter(|(_, r)| r.room_type == "en_suite")
            .map(|(i, _)| i)
            .collect()
    } else {
        same
    };
    if same.is_empty() {
        return None;
    }
    match ordinal_before(toks, m.first) {
        Some(usize::MAX) => same.last().copied(),
        Some(n) => same.get(n - 1).or(same.last()).copied(),
        None => same
            .iter()
            .copied()
            .find(|&i| brief.rooms[i].text.is_empty())
            .or(same.first().copied()),
    }
}

fn attribute(
    brief: &mut HouseBrief,
    text: &str,
    clause: &Clause,
    last_subject: &mut Option<usize>,
) {
    let toks = &clause.toks;
    let body = text[clause.start..clause.end]
        .trim()
        .trim_start_matches([',', ';'])
        .trim();
    let body = body
        .strip_prefix("and ")
        .or_else(|| body.strip_prefix("And "))
        .unwrap_or(body)
        .trim()
        .to_string();
    let ms: Vec<Mention> = mentions(toks)
        .into_iter()
        .filter(|m| m.room_type != "room" || toks.len() < 4)
        .collect();
    let (floor, wall) = materials_in(toks);
    if let Some(h) = wall_height_in(toks) {
        brief.wall_height = Some(h);
    }
    // Subject: a room word in the first few words; else any room word; else by objects.
    let subject = ms
        .iter()
        .find(|m| m.first <= 3)
        .and_then(|m| resolve(brief, toks, m, *last_subject));
    if subject.is_none() && house_wide(toks) {
        brief.floor_material = floor.or(brief.floor_material.take());
        brief.wall_material = wall.or(brief.wall_material.take());
        brief.style.extend(
            toks.iter()
                .filter(|t| knowledge().house().style_words.contains(&t.w))
                .map(|t| t.w.clone()),
        );
        brief.house_text.push(body);
        return;
    }
    let target = subject
        .or_else(|| {
            ms.iter()
                .find_map(|m| resolve(brief, toks, m, *last_subject))
        })
        .or_else(|| room_for_items(toks, &brief.rooms))
        .unwrap_or_else(|| main_room(&brief.rooms));
    // "The kitchen is open to the dining room", "opens onto the living room".
    let w: Vec<&str> = toks.iter().map(|t| t.w.as_str()).collect();
    let opens = w.windows(2).any(|p| {
        matches!(p[0], "open" | "opens" | "open-plan")
            && matches!(p[1], "to" | "onto" | "into" | "with")
    });
    if opens {
        for m in ms.iter().skip(1) {
            if let Some(other) = resolve(brief, toks, m, *last_subject)
                && other != target
                && !brief.open_pairs.contains(&(target, other))
            {
                brief.open_pairs.push((target, other));
            }
        }
    }
    // Size words right after the subject ("The kitchen is large").
    if let Some(m) = ms.iter().find(|m| m.first <= 3)
        && toks
            .get(m.last + 1)
            .is_some_and(|t| matches!(t.w.as_str(), "is" | "feels"))
        && let Some(s) = toks.get(m.last + 2).and_then(|t| size_word(&t.w))
    {
        brief.rooms[target].size_scale = s;
    }
    let room = &mut brief.rooms[target];
    room.floor_material = floor.or(room.floor_material.take());
    room.wall_material = wall.or(room.wall_material.take());
    let mut body = body;
    if let Some(c) = body.chars().next() {
        let upper: String = c.to_uppercase().collect();
        body.replace_range(..c.len_utf8(), &upper);
    }
    room.text.push(body);
    if subject.is_some() && room.owner.is_none() {
        *last_subject = Some(target);
    }
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
}
