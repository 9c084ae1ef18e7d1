//! The built-in critics' scores measure the scene: each reason states what was counted, and
//! the counts agree with the scene the stages built.

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::ObjectKind;

#[test]
fn wall_and_ceiling_scores_count_what_hangs_in_the_room() {
    let prompt = "A dining room with a dining table, six chairs, a chandelier, a pendant lamp \
                  and three paintings on the walls.";
    let (state, report) = build_scene(prompt, 2, "critic_scores", &Backend::Builtin).unwrap();
    let count = |kind: ObjectKind| {
        state
            .scene
            .objects
            .iter()
            .filter(|o| o.kind == kind)
            .count()
    };
    let critique = |stage: &str| {
        report
            .stages
            .iter()
            .find(|s| s.stage == stage)
            .and_then(|s| s.critique.clone())
            .unwrap_or_else(|| panic!("no {stage} critique"))
    };
    let ceiling = critique("ceiling");
    let logic = ceiling
        .scores
        .iter()
        .find(|s| s.category == "placement_logic")
        .unwrap();
    let hung = count(ObjectKind::Ceiling);
    assert!(
        hung >= 2,
        "{hung} ceiling objects: the chandelier and the pendant"
    );
    assert!(
        logic
            .reason
            .starts_with(&format!("0 of {hung} ceiling objects hang lower")),
        "{}",
        logic.reason
    );
    assert_eq!(logic.score, 10);

    let wall = critique("wall");
    let aesthetics = wall
        .scores
        .iter()
        .find(|s| s.category == "aesthetics")
        .unwrap();
    let mounted = count(ObjectKind::Wall);
    assert!(
        aesthetics
            .reason
            .starts_with(&format!("{mounted} wall objects, ")),
        "{}",
        aesthetics.reason
    );
    // The score follows the counted crowding: 10 less 3 per crowded pair.
    let crowded: u32 = aesthetics
        .reason
        .split(", ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert_eq!(
        u32::from(aesthetics.score),
        10u32.saturating_sub(3 * crowded)
    );

    // Chairs at the dining table count as seats facing a table-like piece.
    let furniture = critique("furniture");
    let function = furniture
        .scores
        .iter()
        .find(|s| s.category == "functionality")
        .unwrap();
    assert!(
        function.score >= 8,
        "{}: {}",
        function.score,
        function.reason
    );
}
