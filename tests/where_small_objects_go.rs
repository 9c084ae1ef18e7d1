//! Where small objects go when the prompt says where: on the floor (the plan gives them a rug,
//! the room's or one added for them), in a pile (a heap over a small patch with a layer on
//! top, not a row; plates and bowls in short stacks), in bins on the floor (floor bins, each
//! with its share), in the sink (its basin, not the shelf behind its doors).

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::Support;

#[test]
fn a_pile_of_blocks_on_the_floor_is_a_heap_on_a_rug() {
    let prompt = "A nursery with a crib, a changing table and a pile of 6 wooden play blocks \
                  on the floor.";
    let (state, _) = build_scene(prompt, 3, "floor_pile", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let rug = objects
        .iter()
        .find(|o| o.category == "rug")
        .expect("a rug holds what lies on the floor");
    let blocks: Vec<_> = objects
        .iter()
        .filter(|o| o.category.contains("block"))
        .collect();
    assert_eq!(blocks.len(), 6, "the counted blocks are all placed");
    for b in &blocks {
        assert!(
            matches!(&b.support, Support::Object { parent, .. } if *parent == rug.id),
            "{} rests on {:?}, not on the rug",
            b.id,
            b.support
        );
    }
    let xyz: Vec<[f64; 3]> = blocks
        .iter()
        .map(|b| {
            let t = b.world_from_object.translation();
            [t.x, t.y, t.z]
        })
        .collect();
    let extent = |k: usize| {
        let lo = xyz.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = xyz.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        hi - lo
    };
    // Six 5 cm blocks: a heap about three blocks across, with at least one block on top.
    assert!(
        extent(0) < 0.3 && extent(1) < 0.3,
        "spread {:.2} x {:.2} m",
        extent(0),
        extent(1)
    );
    assert!(
        extent(2) > 0.03,
        "no second layer: heights differ by {:.3} m",
        extent(2)
    );
}

#[test]
fn bins_the_prompt_puts_on_the_floor_are_floor_bins() {
    use scenesmith::assets::procedural::{SupportClass, support_sibling};
    assert_eq!(
        support_sibling("storage_bin", SupportClass::Floor),
        Some("toy_bin")
    );
    assert_eq!(support_sibling("toy_bin", SupportClass::Floor), None);
    // A kind of the same noun that another generator builds: a shelf on the wall.
    assert_eq!(
        support_sibling("shelf", SupportClass::Wall),
        Some("wall_shelf")
    );
    assert!(scenesmith::assets::router::naming::names(
        "storage bin",
        "toy_bin"
    ));
    assert!(!scenesmith::assets::router::naming::names(
        "storage bin",
        "laundry_basket"
    ));
    // Two bins on the floor holding toys: both built (as the library's floor bins; the objects
    // are called what the prompt calls them), the toys inside them.
    let prompt = "A playroom with two bins. One bin contains 2 teddy bears. The other bin \
                  contains at least 5 wooden blocks.";
    let (state, _) = build_scene(prompt, 1, "floor_bins", &Backend::Builtin).unwrap();
    let bins: Vec<&str> = state
        .scene
        .objects
        .iter()
        .filter(|o| state.scene.built_as(o) == "toy_bin")
        .map(|o| o.id.as_str())
        .collect();
    assert_eq!(bins.len(), 2, "{bins:?}");
    let blocks_in_bins = state
        .scene
        .objects
        .iter()
        .filter(|o| state.scene.built_as(o) == "wooden_block")
        .filter(|o| matches!(&o.support, Support::Object { parent, .. } if bins.contains(&parent.as_str())))
        .count();
    assert!(
        blocks_in_bins >= 5,
        "{blocks_in_bins} wooden blocks in the bins"
    );
    // "2 teddy bears" is an exact count of what the library builds as stuffed animals: the
    // room's defaults add no more of them.
    let bears = state
        .scene
        .objects
        .iter()
        .filter(|o| state.scene.built_as(o) == "stuffed_animal")
        .count();
    assert_eq!(bears, 2);
}

#[test]
fn a_thing_named_with_its_modifiers_is_placed_as_often_as_asked() {
    // The object keeps the prompt's name ("spattered_radio"); the plan calls it a radio.
    assert!(scenesmith::assets::router::naming::names(
        "radio",
        "spattered_radio"
    ));
    assert!(!scenesmith::assets::router::naming::names(
        "radio",
        "radiogram"
    ));
    assert!(!scenesmith::assets::router::naming::names(
        "table",
        "side_table"
    ));
    let prompt = "A pottery studio with a long wedging table and a squat kiln. A \
                  paint-spattered radio rests on the wedging table.";
    let (state, _) = build_scene(prompt, 4, "named_once", &Backend::Builtin).unwrap();
    let count = |noun: &str| {
        state
            .scene
            .objects
            .iter()
            .filter(|o| o.category.ends_with(noun))
            .count()
    };
    assert_eq!(count("radio"), 1, "one radio was asked for");
    assert_eq!(count("kiln"), 1, "one kiln was asked for");
    // The table is built as the library's table and keeps the prompt's name, which a
    // requirement for a "wedging table" reads.
    let table = state
        .scene
        .objects
        .iter()
        .find(|o| o.category == "table")
        .expect("a table");
    assert_eq!(table.name.as_deref(), Some("long wedging table"));
    assert!(scenesmith::eval::requirements::object_matches(
        "wedging table",
        table
    ));
}

#[test]
fn a_pile_of_plates_lies_in_short_stacks() {
    let prompt = "A dining room with a table and a pile of 6 plates on the table.";
    let (state, _) = build_scene(prompt, 2, "plate_pile", &Backend::Builtin).unwrap();
    let plates: Vec<_> = state
        .scene
        .objects
        .iter()
        .filter(|o| o.category == "plate")
        .collect();
    let stacked = plates
        .iter()
        .filter(|o| matches!(&o.support, Support::Object { surface, .. } if surface == "stack"))
        .count();
    let bases = plates.len() - stacked;
    assert!(plates.len() >= 6, "{} plates", plates.len());
    // Six plates nest in stacks of at most four: two bases, the rest on them.
    assert!(
        bases <= plates.len().div_ceil(4) + 1,
        "{bases} plates lie on their own"
    );
}

#[test]
fn dishes_in_the_sink_go_into_its_basin() {
    let prompt = "A kitchen with a sink. The sink contains a mess of dishes with at least 5 \
                  plates, 3 glasses, and 5 bowls.";
    let (state, _) = build_scene(prompt, 0, "sink_mess", &Backend::Builtin).unwrap();
    let in_basin = state
        .scene
        .objects
        .iter()
        .filter(|o| matches!(&o.support, Support::Object { surface, .. } if surface == "basin"))
        .count();
    // The basin is open (not behind the vanity's doors): it is filled first.
    assert!(in_basin >= 3, "{in_basin} objects in the basin");
}

/// What the prompt puts on a shelf stands at hand height, near the middle of its board, not on
/// the bottom board pressed into a corner (where no gripper fits beside it).
#[test]
fn an_asked_for_item_on_a_shelf_stands_at_hand_height_away_from_the_panels() {
    let prompt = "A storage room with a shelf with a red can on it, and a chair.";
    let (state, _) = build_scene(prompt, 0, "shelf_can", &Backend::Builtin).unwrap();
    let scene = &state.scene;
    let can = scene
        .objects
        .iter()
        .find(|o| o.category == "can")
        .expect("a can");
    let Support::Object { parent, surface } = &can.support else {
        panic!("the can stands on {:?}", can.support);
    };
    let shelf = scene.object(parent).expect("its shelf");
    let asset = &scene.assets[&shelf.asset];
    let handy = |z: f64| (z - 0.9).abs();
    let on = asset
        .surfaces
        .iter()
        .find(|s| s.id == *surface)
        .expect("its surface");
    for s in &asset.surfaces {
        assert!(
            handy(on.center[2]) <= handy(s.center[2]) + 1e-9,
            "the can is on {} at {:.2} m, {} at {:.2} m is nearer hand height",
            on.id,
            on.center[2],
            s.id,
            s.center[2]
        );
    }
    // In the surface's frame: the can's centre at least 3.5 cm plus its half-width from
    // every edge.
    let [lo, hi] = scene.assets[&can.asset].bounds;
    let centre = nalgebra::Point3::new((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, 0.0);
    let t = shelf
        .world_from_object
        .inverse()
        .transform_point(&can.world_from_object.transform_point(&centre));
    let half = (hi[0] - lo[0]).max(hi[1] - lo[1]) / 2.0;
    let (du, dv) = (
        on.size[0] / 2.0 - (t.x - on.center[0]).abs(),
        on.size[1] / 2.0 - (t.y - on.center[1]).abs(),
    );
    assert!(
        du >= half + 0.03 && dv >= half + 0.03,
        "the can is {du:.3} / {dv:.3} m from the board's edges (half-width {half:.3})"
    );
}

/// The usual clutter keeps out of a sink's basin (a towel in the sink is no arrangement, and a
/// task "put the cup in the sink" needs it free); what the prompt puts there goes in.
#[test]
fn the_usual_clutter_leaves_a_sinks_basin_free() {
    for (seed, prompt) in [
        (
            0,
            "A large bathroom with a sink, a bathtub, a toilet and a plant.",
        ),
        (
            1,
            "A kitchen with a sink, a counter, a stove and a refrigerator.",
        ),
    ] {
        let (state, _) = build_scene(prompt, seed, "sink_free", &Backend::Builtin).unwrap();
        let in_basin: Vec<&str> = state
            .scene
            .objects
            .iter()
            .filter(|o| match &o.support {
                Support::Object { parent, surface } => {
                    surface == "basin"
                        && state
                            .scene
                            .object(parent)
                            .is_some_and(|p| p.category == "sink")
                }
                _ => false,
            })
            .map(|o| o.id.as_str())
            .collect();
        assert!(
            in_basin.is_empty(),
            "{prompt}: {in_basin:?} in a sink's basin"
        );
        assert!(
            state.scene.objects.iter().any(|o| o.category == "sink"),
            "{prompt}: no sink"
        );
    }
}

/// World axis-aligned box of an object (its asset's bounds, posed).
fn world_box(
    state: &scenesmith::state::SceneState,
    o: &scenesmith::scene::SceneObject,
) -> [[f64; 3]; 2] {
    let [lo, hi] = state.scene.assets[&o.asset].bounds;
    let mut out = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for x in [lo[0], hi[0]] {
        for y in [lo[1], hi[1]] {
            for z in [lo[2], hi[2]] {
                let p = o
                    .world_from_object
                    .transform_point(&nalgebra::Point3::new(x, y, z));
                for k in 0..3 {
                    out[0][k] = out[0][k].min(p[k]);
                    out[1][k] = out[1][k].max(p[k]);
                }
            }
        }
    }
    out
}

/// What stands on a counter keeps out of the wall cabinets over it: the microwave the prompt
/// asks for is placed where it fits under them (or clear of them), not into them and then
/// lost.
#[test]
fn things_on_a_counter_stand_clear_of_the_wall_cabinets_above() {
    let prompt = "A small kitchen with a breakfast table and two chairs, plus a microwave and a \
                  kettle on the counter.";
    let (state, _) = build_scene(prompt, 0, "under_cabinets", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    assert!(
        objects.iter().any(|o| o.category == "microwave"),
        "the microwave is placed"
    );
    let wall: Vec<_> = objects
        .iter()
        .filter(|o| o.kind == scenesmith::scene::ObjectKind::Wall)
        .collect();
    assert!(!wall.is_empty(), "the kitchen has wall pieces");
    let on_counters = objects.iter().filter(
        |o| matches!(&o.support, Support::Object { parent, .. } if parent.contains("counter")),
    );
    for o in on_counters {
        let a = world_box(&state, o);
        for w in &wall {
            let b = world_box(&state, w);
            let overlap = (0..3).all(|k| a[0][k] < b[1][k] - 0.005 && b[0][k] < a[1][k] - 0.005);
            assert!(!overlap, "{} stands in {}", o.id, w.id);
        }
    }
}

#[test]
fn what_no_surface_holds_stands_on_the_floor_and_mounted_things_are_mounted() {
    // Rolled yoga mats are longer than the desk is deep: no surface of the room takes them.
    // Before the floor pass, the twelve mats were lost.
    let prompt = "A small office with a desk, a chair and twelve yoga mats on the desk. A \
                  projector hangs from the ceiling.";
    let (state, _) = build_scene(prompt, 5, "floor_fallback", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let mats: Vec<_> = objects
        .iter()
        .filter(|o| o.category.contains("yoga_mat"))
        .collect();
    assert_eq!(mats.len(), 12, "every asked-for mat is placed");
    for m in &mats {
        assert!(
            matches!(&m.support, Support::Floor { .. }),
            "{} rests on {:?}, not on the floor",
            m.id,
            m.support
        );
    }
    let projector = objects
        .iter()
        .find(|o| o.category == "projector")
        .expect("the projector is placed");
    assert!(
        matches!(projector.support, Support::Ceiling { .. }),
        "the projector rests on {:?}",
        projector.support
    );
}

#[test]
fn a_thing_the_plan_knows_by_another_noun_is_placed_once() {
    // The plan's noun for the gramophone is "record player"; the object is called after the
    // prompt's words. Before the object kept the noun it was placed for, nothing counted the
    // gramophone on the stool as the plan's record player, and the stage and the leftover
    // hosts put four more on the counter and the table.
    let prompt = "An antique shop with a glass counter, a round table and a stool. A gramophone \
                  with a great flared horn sits on the stool.";
    let (state, _) = build_scene(prompt, 3, "planned_noun", &Backend::Builtin).unwrap();
    let gramophones: Vec<_> = state
        .scene
        .objects
        .iter()
        .filter(|o| o.category.contains("gramophone"))
        .collect();
    assert_eq!(
        gramophones.len(),
        1,
        "{:?}",
        gramophones.iter().map(|o| &o.id).collect::<Vec<_>>()
    );
    assert_eq!(gramophones[0].planned.as_deref(), Some("record player"));
}

#[test]
fn a_piece_placed_for_one_plan_noun_does_not_count_for_another() {
    // One generator builds music stands and microphone stands. The music room's usual music
    // stands counted as the prompt's microphone stands, and no microphone stand was placed;
    // "old vinyl" (a material word the library does not build after an adjective) made an
    // object called `old`.
    let prompt = "Hidden in a converted basement, this home recording studio has a warm, \
                  lived-in feel and a faint scent of old vinyl. A wide mixing console sits on a \
                  custom walnut desk, flanked by a pair of studio monitors on tall speaker \
                  stands, with a single swivel chair for the engineer. A drum kit occupies the \
                  far corner beside a bass amplifier and two microphone stands. Four electric \
                  guitars rest in a guitar stand.";
    let (state, _) = build_scene(prompt, 3, "planned_for_another", &Backend::Builtin).unwrap();
    let mics: Vec<_> = state
        .scene
        .objects
        .iter()
        .filter(|o| o.category == "microphone_stand")
        .collect();
    assert_eq!(
        mics.len(),
        2,
        "{:?}",
        state
            .scene
            .objects
            .iter()
            .map(|o| &o.id)
            .collect::<Vec<_>>()
    );
    assert!(
        mics.iter()
            .all(|o| o.planned.as_deref() == Some("microphone stand"))
    );
    assert!(
        state.scene.objects.iter().all(|o| o.category != "old"),
        "{:?}",
        state
            .scene
            .objects
            .iter()
            .map(|o| &o.id)
            .collect::<Vec<_>>()
    );
}

#[test]
fn a_lone_plate_lies_at_a_seat_and_the_fruit_goes_in_its_bowl() {
    let prompt = "A compact mid-century cafe with a dining table with a plate on it, a fruit \
                  bowl with a fruit on it, a chair, and a counter.";
    let (state, _) = build_scene(prompt, 1, "plate_at_seat", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let find = |cat: &str| {
        objects
            .iter()
            .find(|o| o.category == cat)
            .unwrap_or_else(|| panic!("no {cat}"))
    };
    let (table, plate, bowl, fruit) = (
        find("dining_table"),
        find("plate"),
        find("fruit_bowl"),
        find("fruit"),
    );
    assert!(
        matches!(&fruit.support, Support::Object { parent, .. } if *parent == bowl.id),
        "the fruit rests on {:?}, not in its bowl",
        fruit.support
    );
    // At a seat: within 0.3 m of the table top's edge, not in its middle.
    let local = table
        .world_from_object
        .inverse()
        .compose(&plate.world_from_object);
    let p = local.translation();
    let top = &state.scene.assets[&table.asset].surfaces[0];
    let (hw, hd) = (top.size[0] / 2.0, top.size[1] / 2.0);
    let to_edge = (hw - p.x.abs()).min(hd - p.y.abs());
    assert!(
        to_edge < 0.3,
        "the plate lies {to_edge:.2} m in from the edge"
    );
}
