//! The stages build what the plan names, even where the asset router reads the prompt's words
//! differently: a piece of a narrower kind still hosts what the plan puts on the broader one
//! (pillows on a king bed), the plan's noun decides a description the router would send to
//! another stage (a full-length mirror on the floor, a fume hood on the wall), a piece named
//! after one plan item does not count for another (a guest chair is no dental chair), a
//! narrower kind counts for its own item (one round rug, not three), and a mirror is one per
//! vanity however large the vanity.

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::{ObjectKind, SceneObject, Support};
use scenesmith::state::SceneState;

fn named<'a>(state: &'a SceneState, word: &str) -> Vec<&'a SceneObject> {
    state
        .scene
        .objects
        .iter()
        .filter(|o| {
            o.category.contains(word) || o.name.as_deref().is_some_and(|n| n.contains(word))
        })
        .collect()
}

fn parent(o: &SceneObject) -> Option<&str> {
    match &o.support {
        Support::Object { parent, .. } => Some(parent.as_str()),
        _ => None,
    }
}

#[test]
fn a_bedroom_puts_pillows_on_its_king_bed_and_stands_its_mirror_on_the_floor() {
    let prompt = "A master bedroom with a king-size bed with four pillows on it, two \
                  nightstands, a vanity table and a full-length mirror.";
    let (state, _) = build_scene(prompt, 0, "bedroom_kinds", &Backend::Builtin).unwrap();
    let bed = named(&state, "bed")
        .into_iter()
        .find(|o| o.kind == ObjectKind::Furniture)
        .expect("the king-size bed is built");
    let pillows = named(&state, "pillow");
    assert_eq!(pillows.len(), 4, "{pillows:?}");
    for p in &pillows {
        assert_eq!(
            parent(p),
            Some(bed.id.as_str()),
            "{} is not on the bed",
            p.id
        );
    }
    let mirrors: Vec<_> = named(&state, "mirror")
        .into_iter()
        .filter(|o| o.kind == ObjectKind::Furniture)
        .collect();
    assert_eq!(
        mirrors.len(),
        1,
        "the full-length mirror stands on the floor: {mirrors:?}"
    );
    assert_eq!(state.scene.built_as(mirrors[0]), "floor_mirror");
    let hand_mirrors = named(&state, "hand_mirror").len();
    assert!(
        hand_mirrors <= 1,
        "{hand_mirrors} hand mirrors on one vanity"
    );
}

#[test]
fn a_guest_chair_is_no_dental_chair_and_a_round_rug_is_the_rug() {
    let prompt = "A dental treatment room with a dental chair, a guest chair, a round rug and a \
                  grandfather clock in the corner.";
    let (state, _) = build_scene(prompt, 0, "dental_kinds", &Backend::Builtin).unwrap();
    let chairs: Vec<String> = named(&state, "chair")
        .iter()
        .filter(|o| o.kind == ObjectKind::Furniture)
        .map(|o| o.name.clone().unwrap_or_else(|| o.category.clone()))
        .collect();
    assert!(
        chairs.iter().any(|c| c.contains("dental")) && chairs.iter().any(|c| c.contains("guest")),
        "both chairs are built: {chairs:?}"
    );
    assert_eq!(named(&state, "rug").len(), 1, "one rug was asked for");
    let clock = named(&state, "grandfather_clock");
    assert_eq!(clock.len(), 1);
    assert_eq!(
        clock[0].kind,
        ObjectKind::Furniture,
        "a longcase clock stands on the floor"
    );
}

#[test]
fn a_fume_hood_is_built_on_the_wall_under_its_own_name() {
    let prompt = "A small science lab with a fume hood, a lab bench and a whiteboard.";
    let (state, _) = build_scene(prompt, 0, "lab_kinds", &Backend::Builtin).unwrap();
    let hoods = named(&state, "fume_hood");
    assert_eq!(hoods.len(), 1, "{hoods:?}");
    assert_eq!(hoods[0].kind, ObjectKind::Wall);
    assert_eq!(state.scene.built_as(hoods[0]), "range_hood");
    assert_eq!(named(&state, "whiteboard").len(), 1);
}
