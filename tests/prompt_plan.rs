//! Room programs for every room of every dev prompt: non-empty, every explicitly requested
//! object planned with at least its count, negations obeyed, rule targets present, the same
//! reading always giving the same plan.

use scenesmith::plan::{Arrangement, plan_house_room};
use scenesmith::prompt::{self, Count, Per};

#[test]
fn plans_cover_every_requested_object() {
    let dev = std::fs::read_to_string("tests/fixtures/dev_prompts.jsonl").unwrap();
    let mut rooms = 0;
    for line in dev.lines().filter(|l| !l.trim().is_empty()) {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let id = v["id"].as_str().unwrap();
        let r = prompt::read(v["prompt"].as_str().unwrap());
        for room in 0..r.rooms.len() {
            rooms += 1;
            let plan = plan_house_room(&r, room);
            assert_eq!(plan, plan_house_room(&r, room), "{id}: not deterministic");
            assert!(!plan.furniture.is_empty(), "{id} room {room}: no furniture");
            let nouns: Vec<&str> = plan.all_wants().map(|w| w.noun.as_str()).collect();
            for (i, m) in r.room_mentions(room) {
                if m.negated {
                    assert!(
                        !nouns.contains(&m.category.as_str()),
                        "{id}: excluded {} planned",
                        m.category
                    );
                    continue;
                }
                if m.generic && !m.covers.is_empty() {
                    let covered: u32 = m
                        .covers
                        .iter()
                        .map(|&c| plan.count_of(&r.mentions[c].category))
                        .sum();
                    assert!(
                        covered >= r.total(i).minimum(),
                        "{id}: {} covers {covered}",
                        m.category
                    );
                    continue;
                }
                let want: u32 = match r.total(i) {
                    Count::Exactly(n) | Count::AtLeast(n) => n,
                    Count::Several => 2,
                };
                let got: u32 = plan
                    .all_wants()
                    .filter(|w| w.explicit && w.noun == m.category)
                    .map(|w| w.count)
                    .sum();
                assert!(
                    got >= want.min(120),
                    "{id} room {room}: {} planned {got}, asked {:?} ({:?})",
                    m.category,
                    r.total(i),
                    m.per
                );
                let at_least = matches!(r.total(i), Count::AtLeast(_));
                if at_least {
                    assert!(
                        plan.all_wants().any(|w| w.noun == m.category && w.at_least),
                        "{id}: {} lost 'at least'",
                        m.category
                    );
                }
            }
            // Targets of arrangements are in the plan.
            let planned: Vec<&str> = plan
                .furniture
                .iter()
                .chain(&plan.wall)
                .chain(&plan.ceiling)
                .map(|w| w.noun.as_str())
                .collect();
            for w in plan.furniture.iter().chain(&plan.wall).chain(&plan.ceiling) {
                if let Some(t) = w.arrangement.target()
                    && !matches!(w.arrangement, Arrangement::Facing { .. } if t == w.noun)
                {
                    assert!(
                        planned.contains(&t),
                        "{id}: {} refers to {t}, not planned: {planned:?}",
                        w.noun
                    );
                }
            }
            for s in &plan.surfaces {
                assert!(
                    s.parent == "floor"
                        || s.parent == "any"
                        || planned.contains(&s.parent.as_str()),
                    "{id}: surface parent {} not planned",
                    s.parent
                );
                assert!(!s.items.is_empty());
            }
        }
    }
    assert!(rooms >= 73 + 60, "{rooms} rooms planned");
}

#[test]
fn per_parent_and_settings_resolve_to_totals() {
    let r = prompt::read("A restaurant with four dining tables, each surrounded by four chairs.");
    let plan = plan_house_room(&r, 0);
    assert_eq!(plan.count_of("chair"), 16);
    let r = prompt::read(
        "A restaurant with exactly 4 tables and 8 chairs. Each table is set for 2 people with a plate, a glass, a fork, and a knife.",
    );
    assert!(
        r.mentions
            .iter()
            .any(|m| matches!(m.per, Some(Per::Setting { .. })))
    );
    let plan = plan_house_room(&r, 0);
    assert_eq!(plan.count_of("plate"), 8);
    assert_eq!(plan.count_of("chair"), 8);
    let g = plan.surfaces.iter().find(|s| s.place_settings).unwrap();
    assert_eq!(g.parent, "table");
}

#[test]
fn house_rooms_get_their_own_programs() {
    let r = prompt::read(
        "A boutique hotel with a reception, four guest bedrooms with en-suite bathrooms, a restaurant, a kitchen, a gym, a lounge, and a corridor. The first guest bedroom has a bed with two nightstands and its bathroom has a toilet, a sink, and a shower.",
    );
    assert_eq!(r.rooms.len(), 14);
    let bath = r
        .rooms
        .iter()
        .position(|x| x.room_type == "en_suite" && x.parent == Some(1))
        .unwrap();
    let plan = plan_house_room(&r, bath);
    assert!(
        plan.furniture
            .iter()
            .any(|w| w.noun == "shower" && w.explicit)
    );
    // The en-suite of the second bedroom got nothing explicit: defaults only.
    let other = r
        .rooms
        .iter()
        .position(|x| x.room_type == "en_suite" && x.parent == Some(2))
        .unwrap();
    let plan = plan_house_room(&r, other);
    assert!(plan.requested().is_empty());
    assert!(plan.furniture.iter().any(|w| w.noun == "toilet"));
}

#[test]
fn what_a_house_prompt_counts_in_one_room_no_other_room_adds_by_default() {
    let plans = |text: &str| -> Vec<(String, scenesmith::plan::RoomPlan)> {
        let brief = scenesmith::layout::brief::read(text);
        (0..brief.rooms.len())
            .map(|i| {
                let r = &brief.rooms[i];
                let plan = scenesmith::layout::spec::room_plan(
                    &r.room_type,
                    &brief.room_prompt(i),
                    Some(text),
                );
                (r.room_type.clone(), plan)
            })
            .collect()
    };
    let flat = plans(
        "A flat with two bedrooms and a bathroom. The first bedroom holds a double bed with two \
         nightstands, while the second bedroom has a single bed and a desk.",
    );
    let nightstands: u32 = flat.iter().map(|(_, p)| p.count_of("nightstand")).sum();
    assert_eq!(nightstands, 2, "the prompt's two, none by default besides");
    // What makes a room stays in every room of its kind.
    let beds = flat
        .iter()
        .filter(|(t, p)| t == "bedroom" && p.count_of("bed") >= 1)
        .count();
    assert_eq!(beds, 2);
    assert!(
        flat.iter()
            .any(|(t, p)| t == "bathroom" && p.count_of("toilet") == 1)
    );
    let hotel = plans(
        "A hotel floor with a lobby, a corridor and two guest rooms. The lobby has a console \
         table and a vase of lilies.",
    );
    let vases: u32 = hotel.iter().map(|(_, p)| p.count_of("vase")).sum();
    assert_eq!(vases, 1, "{hotel:#?}");
}

#[test]
fn lounge_seating_is_no_seat_at_a_set_table() {
    let r =
        prompt::read("A living room with two armchairs, a big sofa and a dining table for six.");
    let plan = plan_house_room(&r, 0);
    let at_table: u32 = plan
        .furniture
        .iter()
        .filter(|w| matches!(&w.arrangement, Arrangement::Around { parent } if parent == "dining table"))
        .map(|w| {
            assert!(!w.noun.contains("sofa") && !w.noun.contains("armchair"), "{w:?}");
            w.count
        })
        .sum();
    assert_eq!(at_table, 6, "{plan:#?}");
    assert_eq!(plan.count_of("armchair"), 2);
}

#[test]
fn a_floor_thing_set_into_the_wall_stands_against_it() {
    let r = prompt::read(
        "A living room built around a huge aquarium set into the wall, with a painting on the \
         wall beside it and a cabinet on the wall.",
    );
    let plan = plan_house_room(&r, 0);
    let aquarium = plan.furniture.iter().find(|w| w.noun == "aquarium");
    assert!(
        aquarium.is_some_and(|w| w.arrangement == Arrangement::AgainstWall),
        "{plan:#?}"
    );
    assert!(!plan.wall.iter().any(|w| w.noun == "aquarium"), "{plan:#?}");
    // A wall thing stays on the wall, and a floor thing with a wall-mounted kind is hung.
    assert!(plan.wall.iter().any(|w| w.noun == "painting"), "{plan:#?}");
    assert!(
        plan.wall.iter().any(|w| w.noun.contains("cabinet")),
        "{plan:#?}"
    );
}

#[test]
fn a_broader_negation_keeps_the_things_the_prompt_names() {
    let r = prompt::read(
        "A smithy. A rack holds at least six hammers of different weights, and there is no \
         power tool of any kind.",
    );
    let plan = plan_house_room(&r, 0);
    assert!(plan.count_of("hammer") >= 6, "{plan:#?}");
    assert_eq!(plan.count_of("weight"), 0, "{plan:#?}");
    // The same thing named and excluded stays excluded.
    let r = prompt::read("A bedroom with a bed and a lamp. There is no lamp.");
    assert_eq!(plan_house_room(&r, 0).count_of("lamp"), 0);
}

#[test]
fn what_one_room_of_a_house_excludes_no_other_room_adds_by_default() {
    let r = prompt::read(
        "The house has a kitchen, a living room and a bedroom. The kitchen has a stove and a \
         table. The living room has a sofa and an armchair. The bedroom has a bed. Nobody has \
         ever put a television in here.",
    );
    for i in 0..r.rooms.len() {
        let plan = plan_house_room(&r, i);
        assert_eq!(plan.count_of("tv"), 0, "room {i}: {plan:#?}");
    }
    // A room that asks for it still has it.
    let r = prompt::read(
        "The flat has a kitchen and a dining room. The kitchen has no table. The dining room \
         has a big table with four chairs.",
    );
    let tables: u32 = (0..r.rooms.len())
        .map(|i| plan_house_room(&r, i).count_of("table"))
        .sum();
    assert!(tables >= 1, "{:?}", r.mentions);
}
