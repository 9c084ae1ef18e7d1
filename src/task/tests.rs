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
