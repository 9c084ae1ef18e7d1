//! The room's usual clutter, sized to the furniture built: a bedroom that names four pieces
//! still has its drawers and wardrobe filled, both nightstands carry things, what is put away
//! rests on enclosed surfaces only, and a minimalist room has less.

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::{ObjectKind, Support};
use scenesmith::stages::clutter::is_enclosed;

const BEDROOM: &str = "A bedroom with a bed, two nightstands, and a wardrobe.";

fn small_objects(prompt: &str, name: &str) -> (scenesmith::state::SceneState, usize) {
    let (state, _) = build_scene(prompt, 1, name, &Backend::Builtin).expect("the scene builds");
    let n = state
        .scene
        .objects
        .iter()
        .filter(|o| o.kind == ObjectKind::Manipuland)
        .count();
    (state, n)
}

#[test]
fn a_bedroom_that_names_four_pieces_is_furnished_inside_and_out() {
    let (state, n) = small_objects(BEDROOM, "dense_bedroom");
    let scene = &state.scene;
    assert!(n >= 30, "{n} small objects");
    let on = |parent_id: &str| {
        scene
            .objects
            .iter()
            .filter(|o| matches!(&o.support, Support::Object { parent, .. } if parent == parent_id))
            .count()
    };
    for stand in scene.objects.iter().filter(|o| o.category == "nightstand") {
        assert!(on(&stand.id) >= 2, "{} holds {}", stand.id, on(&stand.id));
    }
    // Clothes are put away: every one rests in a drawer or behind a door.
    let mut stored = 0;
    for o in scene
        .objects
        .iter()
        .filter(|o| scene.built_as(o) == "folded_clothes")
    {
        // A stacked one rests on the one below: follow the stack down to its base.
        let mut base = o;
        let (parent, surface) = loop {
            let Support::Object { parent, surface } = &base.support else {
                panic!("{} rests on {:?}", base.id, base.support)
            };
            let p = scene.object(parent).expect("its parent is in the scene");
            if p.kind != ObjectKind::Manipuland {
                break (p, surface.clone());
            }
            base = p;
        };
        let rec = &scene.assets[&parent.asset];
        let s = rec
            .surfaces
            .iter()
            .find(|s| s.id == surface)
            .expect("the surface exists");
        assert!(
            is_enclosed(rec, s),
            "{} lies on {}/{surface}",
            o.id,
            parent.id
        );
        stored += 1;
    }
    assert!(stored >= 4, "{stored} clothes put away");
}

#[test]
fn a_minimalist_bedroom_has_less() {
    let (_, usual) = small_objects(BEDROOM, "usual_bedroom");
    let (_, minimal) = small_objects(
        "A minimalist bedroom with a bed, two nightstands, and a wardrobe.",
        "minimal_bedroom",
    );
    assert!(minimal < usual, "minimalist {minimal}, usual {usual}");
}

#[test]
fn a_bathroom_fills_its_counter_and_its_wall_cabinet() {
    let (state, n) = small_objects(
        "A bathroom with a bathtub, a vanity and a medicine cabinet.",
        "dense_bathroom",
    );
    let scene = &state.scene;
    let on = |kind: ObjectKind, surface_prefix: &str| {
        scene
            .objects
            .iter()
            .filter(|o| match &o.support {
                Support::Object { parent, surface } => {
                    surface.starts_with(surface_prefix)
                        && scene.object(parent).is_some_and(|p| p.kind == kind)
                }
                _ => false,
            })
            .count()
    };
    assert!(n >= 20, "{n} small objects");
    // A wall-mounted cabinet is a supporting entity like furniture.
    assert!(
        on(ObjectKind::Wall, "shelf") >= 1,
        "nothing in the medicine cabinet"
    );
    // The counter beside the basin, not the wet basin, takes the toiletries.
    assert!(on(ObjectKind::Furniture, "top_") >= 2);
    // "toilet paper" is paper on a roll, never a second toilet.
    assert!(
        scene
            .objects
            .iter()
            .filter(|o| o.category == "toilet")
            .count()
            <= 1
    );
}
