use super::*;

#[test]
fn the_task_words_parse_and_every_variation_word_is_read_by_the_prompt_reader() {
    let parsed: serde_json::Value =
        serde_json::from_str(include_str!("../data/tasks.json")).expect("tasks.json parses");
    assert!(parsed["verbs"].as_array().is_some_and(|v| !v.is_empty()));
    let w = analyse::words();
    assert!(!w.styles.is_empty() && !w.colors.is_empty());
    let attributes: serde_json::Value =
        serde_json::from_str(include_str!("../data/asset_attributes.json")).expect("parses");
    for style in &w.styles {
        let key = style.replace([' ', '-'], "_");
        assert!(
            attributes["styles"].get(&key).is_some(),
            "{style} is no asset style"
        );
        let r = crate::prompt::read(&format!("a {style} bedroom with a bed"));
        let nouns: Vec<&str> = r.mentions.iter().map(|m| m.category.as_str()).collect();
        assert_eq!(nouns, ["bed"], "{style}");
    }
    for colour in &w.colors {
        assert!(
            attributes["colors"].get(colour).is_some(),
            "{colour} is no asset colour"
        );
        let r = crate::prompt::read(&format!("a kitchen with a {colour} mug"));
        let mug = r.mentions.iter().find(|m| m.category == "mug");
        assert!(
            mug.is_some_and(|m| !m.attributes.is_empty()),
            "{colour} is not bound to the mug"
        );
    }
}

#[test]
fn a_pick_and_place_task_gives_object_relation_reference_and_start() {
    let t = analyse("Pick up the mug from the dining table and place it on the bookshelf.")
        .expect("reads");
    assert_eq!(t.predicate, Predicate::On);
    assert_eq!(t.target, "mug");
    assert_eq!(t.reference, "bookshelf");
    assert_eq!(t.start.as_deref(), Some("dining table"));
    assert_eq!(t.required, ["mug", "bookshelf", "dining table"]);
    assert!(!t.room_types.is_empty());
}

#[test]
fn relations_words_and_rooms_are_read() {
    let t = analyse("put the red apple into the fruit bowl in the kitchen").expect("reads");
    assert_eq!(
        (t.predicate, t.target.as_str(), t.reference.as_str()),
        (Predicate::Inside, "apple", "fruit bowl")
    );
    assert_eq!(t.target_words, ["red"]);
    assert_eq!(t.room_types, ["kitchen"]);
    let t = analyse("Move the book next to the lamp").expect("reads");
    assert_eq!(t.predicate, Predicate::Near);
    assert_eq!(t.target, "book");
    // The reader's canonical noun for a lamp.
    assert!(
        crate::eval::requirements::name_meets("lamp", &t.reference),
        "{}",
        t.reference
    );
}

#[test]
fn a_task_without_a_goal_or_an_object_is_refused_with_a_reason() {
    assert_eq!(analyse("  "), Err(TaskError::Empty));
    assert!(matches!(
        analyse("pick up the mug"),
        Err(TaskError::NoRelation(_))
    ));
    assert!(matches!(
        analyse("put the happiness on the shelf"),
        Err(TaskError::NotAnObject { .. })
    ));
    assert!(matches!(
        analyse("put the mug on the mug"),
        Err(TaskError::SameObject(_))
    ));
}

#[test]
fn prompts_vary_and_each_reads_back_to_the_required_objects_apart() {
    let t = analyse("place the mug on the shelf").expect("reads");
    let ps = prompts(&t, 8, 7);
    assert_eq!(ps.len(), 8);
    let distinct: std::collections::BTreeSet<&str> = ps.iter().map(|p| p.prompt.as_str()).collect();
    assert!(distinct.len() >= 7, "{ps:#?}");
    assert_eq!(prompts(&t, 8, 7), ps, "deterministic in the seed");
    for p in &ps {
        let reading = crate::prompt::read(&p.prompt);
        for noun in &t.required {
            assert!(
                reading.mentions.iter().any(|m| m.category == *noun
                    || crate::eval::requirements::name_meets(noun, &m.category)),
                "{:?} does not name a {noun}: {:?}",
                p.prompt,
                reading
                    .mentions
                    .iter()
                    .map(|m| &m.category)
                    .collect::<Vec<_>>()
            );
        }
        // The mug starts on something that is not the shelf.
        let mug = reading.mentions.iter().find(|m| m.category == "mug");
        assert!(mug.is_some(), "{}", p.prompt);
    }
}

#[test]
fn a_task_across_rooms_names_both_rooms_and_writes_houses_that_keep_them_apart() {
    let t =
        analyse("bring the water bottle from the kitchen to the coffee table in the living room")
            .expect("reads");
    assert_eq!(
        (t.predicate, t.target.as_str(), t.reference.as_str()),
        (Predicate::On, "water bottle", "coffee table")
    );
    let across = t.across.clone().expect("a task across rooms");
    assert_eq!(
        (across.start_room.as_str(), across.goal_room.as_str()),
        ("kitchen", "living_room")
    );
    assert_eq!(t.start, None, "a room is no start object");
    // One room named, or the same room twice: no house.
    for one in [
        "put the red apple into the fruit bowl in the kitchen",
        "take the mug from the kitchen to the shelf in the kitchen",
    ] {
        let t = analyse(one).expect("reads");
        assert_eq!(
            (t.across.as_ref(), t.room_types.as_slice()),
            (None, &["kitchen".to_string()][..]),
            "{one}"
        );
    }
    for p in prompts(&t, 4, 3) {
        assert_eq!(p.room_type, "house");
        let brief = crate::layout::brief::read(&p.prompt);
        let types: Vec<&str> = brief.rooms.iter().map(|r| r.room_type.as_str()).collect();
        assert_eq!(types, ["kitchen", "living_room"], "{}", p.prompt);
        assert!(
            brief.rooms.iter().all(|r| r.size_scale > 1.0),
            "{}: {:?}",
            p.prompt,
            brief.rooms.iter().map(|r| r.size_scale).collect::<Vec<_>>()
        );
        // The bottle is said of the kitchen, the coffee table of the living room.
        let said = |i: usize, noun: &str| {
            let text = brief.room_prompt(i);
            crate::prompt::read(&text)
                .mentions
                .iter()
                .any(|m| !m.negated && m.category == noun)
        };
        assert!(
            said(0, "water bottle") && !said(0, "coffee table"),
            "{}",
            p.prompt
        );
        assert!(
            said(1, "coffee table") && !said(1, "water bottle"),
            "{}",
            p.prompt
        );
    }
}

#[test]
fn an_object_from_the_floor_starts_on_the_floor_in_every_prompt() {
    let t = analyse("pick a cup from the floor and place it in the sink").expect("reads");
    assert_eq!(t.start.as_deref(), Some(FLOOR));
    assert_eq!(
        t.required,
        ["cup", "sink"],
        "the floor is no object to require"
    );
    for p in prompts(&t, 4, 1) {
        assert!(p.prompt.contains("cup on the floor"), "{}", p.prompt);
        let reading = crate::prompt::read(&p.prompt);
        let cup = reading
            .mentions
            .iter()
            .find(|m| m.category == "cup")
            .expect("a cup");
        assert!(
            cup.relations
                .iter()
                .any(|r| r.target == crate::prompt::relations::Target::Floor),
            "{}: {:?}",
            p.prompt,
            cup.relations
        );
    }
}

#[test]
fn where_the_reference_stands_is_required_and_written_into_every_prompt() {
    let t = analyse("pick a fruit from the fruit bowl and place it on a plate on the dining table")
        .expect("reads");
    assert_eq!(
        (t.target.as_str(), t.reference.as_str(), t.start.as_deref()),
        ("fruit", "plate", Some("fruit bowl"))
    );
    assert_eq!(t.reference_on.as_deref(), Some("dining table"));
    assert_eq!(t.required, ["fruit", "plate", "fruit bowl", "dining table"]);
    for p in prompts(&t, 4, 2) {
        assert!(
            p.prompt.contains("a dining table with a plate on it"),
            "{}",
            p.prompt
        );
    }
}
