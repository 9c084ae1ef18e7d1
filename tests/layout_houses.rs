//! Every house prompt of the dev set through the layout stage (built-in agents): every named
//! room present with its count, the layout valid, every room reachable from outside, en-suites
//! entered only through their bedroom, no room reachable only through a bathroom, per-room
//! prompts carrying their sentences, and the placement inside its time budget.

use std::collections::{BTreeMap, BTreeSet};

use scenesmith::agents::Backend;
use scenesmith::agents::RunLog;
use scenesmith::layout::knowledge::Role;
use scenesmith::layout::stage::{LayoutOutcome, run_layout};
use scenesmith::layout::validate::{door_graph, reachable_from_outside};
use scenesmith::scene::OpeningKind;

fn dev_prompt(id: &str) -> String {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/dev_prompts.jsonl"
    ))
    .unwrap();
    text.lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|v| v["id"] == id)
        .map(|v| v["prompt"].as_str().unwrap().to_string())
        .unwrap_or_else(|| panic!("no dev prompt {id}"))
}

/// Room types (registry keys) with counts each house prompt names.
fn expected(id: &str) -> Vec<(&'static str, usize)> {
    match id {
        "house_01" => vec![("studio_apartment", 1), ("bathroom", 1)],
        "house_03" => vec![("bedroom", 1), ("living_room", 1), ("bathroom", 1)],
        "house_05" => vec![("reception", 1), ("private_office", 1), ("bathroom", 1)],
        "house_07" => vec![("bedroom", 1), ("living_kitchen", 1), ("bathroom", 1)],
        "house_09" => vec![
            ("bedroom", 1),
            ("study_room", 1),
            ("common_room", 1),
            ("bathroom", 1),
        ],
        "house_11" => vec![
            ("master_bedroom", 1),
            ("bedroom", 1),
            ("living_room", 1),
            ("hallway", 1),
            ("bathroom", 1),
        ],
        "house_13" => vec![
            ("dining_room", 1),
            ("kitchen", 1),
            ("bar", 1),
            ("storage_room", 1),
            ("bathroom", 1),
        ],
        "house_15" => vec![
            ("reception", 1),
            ("exam_room", 2),
            ("xray_room", 1),
            ("corridor", 1),
            ("bathroom", 1),
        ],
        "house_17" => vec![
            ("open_office", 1),
            ("meeting_room", 2),
            ("lounge", 1),
            ("kitchen", 1),
            ("reception", 1),
            ("bathroom", 1),
        ],
        "house_19" => vec![
            ("workout_area", 1),
            ("yoga_room", 1),
            ("locker_room", 1),
            ("reception", 1),
            ("office", 1),
            ("storage_room", 1),
            ("bathroom", 1),
        ],
        "house_21" => vec![
            ("master_bedroom", 1),
            ("kids_bedroom", 2),
            ("living_room", 1),
            ("kitchen", 1),
            ("dining_room", 1),
            ("hallway", 1),
            ("bathroom", 2),
        ],
        "house_23" => vec![
            ("reception", 1),
            ("office", 5),
            ("conference_room", 2),
            ("break_room", 1),
            ("server_room", 1),
            ("corridor", 1),
            ("bathroom", 1),
        ],
        "house_25" => vec![
            ("reception", 1),
            ("guest_bedroom", 4),
            ("en_suite", 4),
            ("restaurant", 1),
            ("kitchen", 1),
            ("gym", 1),
            ("lounge", 1),
            ("corridor", 1),
        ],
        other => panic!("no expectation for {other}: add one"),
    }
}

fn check_house(id: &str) -> LayoutOutcome {
    let prompt = dev_prompt(id);
    let out = run_layout(&prompt, 0, &Backend::Builtin, &mut RunLog::default()).unwrap();
    let spec = out.state.spec.clone().unwrap();

    // Every named room with its count, and nothing else.
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for r in &spec.rooms {
        *counts.entry(r.room_type.clone()).or_default() += 1;
    }
    let want: BTreeMap<String, usize> = expected(id)
        .into_iter()
        .map(|(k, n)| (k.to_string(), n))
        .collect();
    assert_eq!(counts, want, "{id}: rooms");
    assert_eq!(out.rooms.len(), spec.rooms.len());

    // Valid, and reachable from an exterior door by BFS over the built walls.
    assert!(out.validation.ok, "{id}: {:?}", out.validation.errors);
    let g = door_graph(&out.rooms);
    let all = reachable_from_outside(&g, &BTreeSet::new());
    for r in &out.rooms {
        assert!(all.contains(&r.id), "{id}: {} is unreachable", r.id);
    }
    let exterior_doors = out
        .rooms
        .iter()
        .flat_map(|r| &r.walls)
        .filter(|w| w.neighbor.is_none())
        .flat_map(|w| &w.openings)
        .filter(|o| o.kind == OpeningKind::Door)
        .count();
    assert!(exterior_doors >= 1, "{id}: no exterior door");

    // En-suites only through their bedroom.
    for r in spec.rooms.iter().filter(|r| r.owner.is_some()) {
        let links: Vec<&String> = g[&r.id].iter().collect();
        assert_eq!(links, vec![r.owner.as_ref().unwrap()], "{id}: {}", r.id);
    }
    // No room reachable only through a bathroom.
    let wet: BTreeSet<String> = spec
        .rooms
        .iter()
        .filter(|r| r.role == Role::Wet)
        .map(|r| r.id.clone())
        .collect();
    let dry = reachable_from_outside(&g, &wet);
    for r in &spec.rooms {
        assert!(
            dry.contains(&r.id),
            "{id}: {} is reachable only through a bathroom",
            r.id
        );
    }
    // Bathrooms are leaves: one connection each.
    for w in &wet {
        assert_eq!(g[w].len(), 1, "{id}: {w} connects to {:?}", g[w]);
    }

    // Rooms do not overlap and share walls exactly once.
    for w in out.rooms.iter().flat_map(|r| &r.walls) {
        if let Some(m) = &w.mirror_of {
            let owner = out
                .rooms
                .iter()
                .flat_map(|r| &r.walls)
                .find(|x| &x.id == m)
                .unwrap_or_else(|| panic!("{id}: {} mirrors missing {m}", w.id));
            assert!(owner.mirror_of.is_none());
        }
    }

    // Every room has its prompt; the search stayed inside its budget.
    for r in &out.rooms {
        assert!(r.prompt.len() > 10, "{id}: {} has no prompt", r.id);
    }
    let stats = &out.state.stats;
    assert!(!stats.timed_out, "{id}: {stats:?}");
    assert!(stats.seconds < out.state.config.timeout_s);
    assert!(stats.nodes <= out.state.config.node_budget * 2);
    out
}

macro_rules! house_tests {
    ($($name:ident),*) => {$(
        #[test]
        fn $name() {
            check_house(stringify!($name));
        }
    )*};
}

house_tests!(
    house_01, house_03, house_05, house_07, house_09, house_11, house_13, house_17, house_19,
    house_21, house_23
);

#[test]
fn house_15() {
    let out = check_house("house_15");
    let prompt = |id: &str| {
        out.rooms
            .iter()
            .find(|r| r.id == id)
            .map(|r| r.prompt.clone())
            .unwrap()
    };
    // The ordinal sentences reach their rooms.
    assert!(prompt("exam_room_0").contains("cabinet"));
    assert!(prompt("exam_room_1").contains("sink"));
    assert!(!prompt("exam_room_1").contains("cabinet"));
    assert!(prompt("corridor_0").contains("bench"));
    // A corridor is the hub: the private rooms open onto it.
    let spec = out.state.spec.as_ref().unwrap();
    for r in spec.rooms.iter().filter(|r| r.role == Role::Private) {
        assert!(
            out.state.placement.shared(&r.id, "corridor_0") >= 1.2,
            "{} is not on the corridor",
            r.id
        );
    }
}

#[test]
fn house_25() {
    let out = check_house("house_25");
    // Each en-suite gets its own bathroom sentence.
    let ensuites: Vec<&str> = out
        .rooms
        .iter()
        .filter(|r| r.room_type == "en_suite")
        .map(|r| r.prompt.as_str())
        .collect();
    assert_eq!(ensuites.len(), 4);
    assert!(ensuites[0].contains("shower") && ensuites[1].contains("bathtub"));
    // The kitchen is next to the restaurant.
    assert!(out.state.placement.shared("kitchen_0", "restaurant_0") >= 1.2);
}

#[test]
fn single_room_prompts_make_one_room_houses() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/dev_prompts.jsonl"
    ))
    .unwrap();
    let mut n = 0;
    for line in text.lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        if v["category"] == "house" {
            continue;
        }
        let prompt = v["prompt"].as_str().unwrap();
        let b = scenesmith::layout::brief::read(prompt);
        assert!(!b.is_house, "{}: read as a house: {:?}", v["id"], b.rooms);
        assert_eq!(b.rooms.len(), 1, "{}", v["id"]);
        assert_eq!(b.room_prompt(0), prompt.trim());
        n += 1;
    }
    assert!(n >= 60);
}
