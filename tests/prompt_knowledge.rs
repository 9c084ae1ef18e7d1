//! The knowledge base: every room type of the dev prompts exists, and every entry is
//! well-formed (sizes, materials, known nouns in the right stage, rule targets, counts).

use scenesmith::knowledge::{self, Place};
use scenesmith::prompt;
use scenesmith::words::{self, Support};

fn materials() -> Vec<String> {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("src/data/materials.json").unwrap()).unwrap();
    v["materials"]
        .as_object()
        .unwrap()
        .keys()
        .cloned()
        .collect()
}

#[test]
fn knowledge_base_parses_and_is_large_enough() {
    let kb = knowledge::check_compiled().unwrap();
    assert!(kb.rooms().len() >= 60, "{} room types", kb.rooms().len());
}

#[test]
fn every_dev_prompt_room_type_exists() {
    let kb = knowledge::knowledge();
    // The room types the issue names, as a user would write them.
    for words in [
        "pet store",
        "grocery store",
        "toy store",
        "furniture showroom",
        "hotel lobby",
        "restaurant",
        "bar",
        "private office",
        "conference room",
        "classroom",
        "computer lab",
        "music room",
        "hospital room",
        "waiting room",
        "gym",
        "dance studio",
        "robotics lab",
        "garage",
        "art gallery",
        "bakery",
        "barber shop",
        "pet grooming salon",
        "nursery",
        "wine cellar",
        "museum room",
        "pantry",
        "kitchen",
        "dining room",
        "bedroom",
        "living room",
        "bathroom",
        "closet",
        "playroom",
        "bookstore",
        "pottery store",
        "office",
        "studio apartment",
        "reception",
        "exam room",
        "x-ray room",
        "corridor",
        "hallway",
        "storage room",
        "break room",
        "server room",
        "meeting room",
        "lounge",
        "open office",
        "locker room",
        "yoga room",
        "workout area",
        "common room",
        "study room",
        "living-kitchen",
        "kids bedroom",
        "master bedroom",
        "guest bedroom",
        "library",
        "gaming room",
        "artist studio",
        "home office",
        "teen bedroom",
    ] {
        assert!(
            kb.room_type_of(words).is_some(),
            "no room type for {words:?}"
        );
    }
    // And the reader finds a known type for every room of every dev prompt.
    let dev = std::fs::read_to_string("tests/fixtures/dev_prompts.jsonl").unwrap();
    for line in dev.lines().filter(|l| !l.trim().is_empty()) {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let r = prompt::read(v["prompt"].as_str().unwrap());
        for room in &r.rooms {
            assert!(
                room.room_type != "room" && kb.room(&room.room_type).is_some(),
                "{}: {}",
                v["id"],
                room.room_type
            );
        }
    }
}

#[test]
fn every_entry_is_well_formed() {
    let kb = knowledge::knowledge();
    let lex = words::lexicon();
    let mats = materials();
    let known = |n: &str| lex.lookup(n).is_some_and(|e| e.noun == n);
    let mut problems: Vec<String> = Vec::new();
    for (key, rt) in kb.rooms() {
        let p = |problems: &mut Vec<String>, s: String| problems.push(format!("{key}: {s}"));
        let s = &rt.size;
        if [s.min, s.typical, s.max]
            .iter()
            .flatten()
            .any(|v| !(1.0..=30.0).contains(v))
            || !(1.5..=30.0).contains(&s.typical[1])
        {
            p(&mut problems, format!("size {s:?}"));
        }
        if !(2.2..=6.0).contains(&rt.wall_height) {
            p(&mut problems, format!("wall height {}", rt.wall_height));
        }
        for m in [&rt.floor, &rt.wall] {
            if !mats.contains(m) {
                p(&mut problems, format!("material {m} not in materials.json"));
            }
        }
        if rt.words.is_empty() {
            p(&mut problems, "no words".into());
        }
        let planned: Vec<&str> = rt
            .furniture
            .iter()
            .chain(&rt.wall_items)
            .chain(&rt.ceiling)
            .map(|i| i.noun.as_str())
            .collect();
        for (list, want) in [
            (&rt.furniture, Support::Floor),
            (&rt.wall_items, Support::Wall),
            (&rt.ceiling, Support::Ceiling),
        ] {
            for item in list {
                if !known(&item.noun) {
                    p(&mut problems, format!("unknown noun {}", item.noun));
                    continue;
                }
                let support = lex.lookup(&item.noun).map(|e| e.support);
                let ok = support == Some(want)
                    || (want == Support::Wall && support == Some(Support::Surface));
                if !ok {
                    p(
                        &mut problems,
                        format!("{} is {support:?}, listed as {want:?}", item.noun),
                    );
                }
                if item.count[0] > item.count[1] || item.count[1] == 0 || item.count[1] > 40 {
                    p(
                        &mut problems,
                        format!("{} count {:?}", item.noun, item.count),
                    );
                }
                if let Some(t) = item.place.as_ref().and_then(Place::target)
                    && !planned.contains(&t)
                {
                    p(
                        &mut problems,
                        format!("{} refers to {t}, not in the room", item.noun),
                    );
                }
                if let Some(h) = item.height
                    && !(0.0..rt.wall_height).contains(&h)
                {
                    p(&mut problems, format!("{} height {h}", item.noun));
                }
                if want == Support::Wall
                    && item.height.is_none()
                    && !matches!(item.place, Some(Place::Above(_)))
                {
                    p(
                        &mut problems,
                        format!("wall item {} has no height", item.noun),
                    );
                }
            }
        }
        for rule in &rt.surfaces {
            let holder = lex
                .lookup(&rule.parent)
                .is_some_and(|e| e.holds || e.container);
            if !known(&rule.parent) || !holder {
                p(
                    &mut problems,
                    format!("surface parent {} unknown or holds nothing", rule.parent),
                );
            }
            if rt.extends.is_none() && !planned.contains(&rule.parent.as_str()) {
                p(
                    &mut problems,
                    format!("surface parent {} not in the room", rule.parent),
                );
            }
            if rule.count[0] > rule.count[1] || (rule.items.is_empty() && rule.inside.is_empty()) {
                p(
                    &mut problems,
                    format!("surface rule {} count {:?}", rule.parent, rule.count),
                );
            }
            for it in rule.items.iter().chain(&rule.inside) {
                if !known(it) {
                    p(&mut problems, format!("unknown surface item {it}"));
                } else if lex.lookup(it).map(|e| e.support) == Some(Support::Floor) {
                    p(
                        &mut problems,
                        format!("surface item {it} is a floor object"),
                    );
                }
            }
        }
    }
    for (noun, place) in kb.placements() {
        if !known(noun) {
            problems.push(format!("placement of unknown {noun}"));
        }
        if let Some(t) = place.target()
            && !known(t)
        {
            problems.push(format!("placement {noun} -> unknown {t}"));
        }
    }
    for (parent, (seat, _)) in kb.seats() {
        if !known(parent) || !known(seat) {
            problems.push(format!("seat rule {parent} -> {seat}"));
        }
    }
    for rule in kb.surface_rules() {
        for n in std::iter::once(&rule.parent)
            .chain(&rule.items)
            .chain(&rule.inside)
        {
            if !known(n) {
                problems.push(format!("surface rule noun {n}"));
            }
        }
    }
    assert!(problems.is_empty(), "{problems:#?}");
}
