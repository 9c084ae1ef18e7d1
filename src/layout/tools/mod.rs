//! The layout stage's tools, with the names the design uses so an LLM designer can drive them:
//! `generate_room_specs`, `resize_room`, `add_adjacency`, `remove_adjacency`,
//! `add_open_connection`, `remove_open_connection`, `set_wall_height`, `add_door`,
//! `remove_door`, `add_window`, `remove_window`, `get_material`, `set_room_materials`,
//! `validate`, `render_ascii`, `observe_scene` (and `render_plan_image` for models with image
//! input). Sizes in metres; rooms by id. Room and
//! material edits are in `rooms`, doors and windows in `openings`, observations in `observe`.

use schemars::JsonSchema;
use serde::Deserialize;

mod observe;
mod openings;
mod rooms;

pub use observe::{AsciiPlan, LayoutObservation, RequestedRoom, RoomInfo, observe};
pub use openings::{Added, DoorArgs, IdArgs, WindowArgs};
pub use rooms::{
    GenerateArgs, HeightArgs, MaterialArgs, PairArgs, ResizeArgs, RoomArg, SetMaterialsArgs,
};

use super::state::LayoutState;
use crate::agents::{Access, CategorySpec, ToolError, Toolbox};

/// The layout critic's categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "room_proportions",
            "rooms have usable shapes (long side at most twice the short side, except corridors) and sizes that fit their use and contents",
        ),
        CategorySpec::new(
            "spatial_flow",
            "every room is reachable from the exterior door; en-suites only through their bedroom; no room only through a bathroom; corridors and hallways serve as hubs; the kitchen is next to the dining room",
        ),
        CategorySpec::new(
            "natural_lighting",
            "rooms people spend time in have windows on exterior walls, sized for the room",
        ),
        CategorySpec::new(
            "material_consistency",
            "floor and wall materials suit each room's use (water-resistant floors in wet rooms) and follow the prompt",
        ),
        CategorySpec::new(
            "prompt_following",
            "every room the prompt names exists with its count; asked-for open plans, heights and materials are there",
        ),
    ]
}

/// No arguments.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct NoArgs {}

pub(super) fn fail(msg: impl Into<String>) -> ToolError {
    ToolError::failed(msg)
}

pub(super) fn room_exists(state: &LayoutState, id: &str) -> Result<(), ToolError> {
    let spec = state.spec().map_err(fail)?;
    if spec.room(id).is_none() {
        return Err(ToolError::bad_args(format!(
            "no room {id:?}; rooms: {}",
            spec.rooms
                .iter()
                .map(|r| r.id.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(())
}

/// The layout stage's tools.
pub fn toolbox() -> Toolbox<LayoutState> {
    let mut t = Toolbox::new();
    t.add("generate_room_specs", "Create the rooms and place them: from the prompt when `rooms` is omitted, or from the given list (room types, counts, optional sizes and contents, en-suites). Replaces the current layout.", Access::Modify, rooms::generate_room_specs);
    t.add("resize_room", "Set a room's clear size (metres) and re-place the house, keeping the other rooms where they were as far as possible.", Access::Modify, rooms::resize_room);
    t.add("add_adjacency", "Require two rooms to share a wall long enough for a door (re-places the house if they do not yet).", Access::Modify, rooms::add_adjacency);
    t.add(
        "remove_adjacency",
        "Drop the requirement that two rooms share a wall.",
        Access::Modify,
        rooms::remove_adjacency,
    );
    t.add("add_open_connection", "Remove the wall between two rooms (open plan); they are moved together if needed. Not for bathrooms or storage.", Access::Modify, rooms::add_open_connection);
    t.add(
        "remove_open_connection",
        "Put the wall back between two openly connected rooms (with a door).",
        Access::Modify,
        rooms::remove_open_connection,
    );
    t.add(
        "set_wall_height",
        "Set the floor-to-ceiling height of every room, metres.",
        Access::Modify,
        rooms::set_wall_height,
    );
    t.add("add_door", "Add a door between two rooms that share a wall (left, center or right along it), or an exterior door (room_b = \"outside\").", Access::Modify, openings::add_door);
    t.add(
        "remove_door",
        "Remove a door by id.",
        Access::Modify,
        openings::remove_door,
    );
    t.add(
        "add_window",
        "Add a window to an outside wall of a room (side, width, sill height).",
        Access::Modify,
        openings::add_window,
    );
    t.add(
        "remove_window",
        "Remove a window by id.",
        Access::Modify,
        openings::remove_window,
    );
    t.add("get_material", "Find the material table entry for words such as \"light hardwood\" or \"polished concrete\": name, colour, friction.", Access::Observe, rooms::get_material);
    t.add(
        "set_room_materials",
        "Set the floor and/or wall material of a room (or \"all\" rooms).",
        Access::Modify,
        rooms::set_room_materials,
    );
    t.add("validate", "Check the layout: every room reachable from the exterior door, en-suites only through their bedroom, no room only through a bathroom, required neighbours, overlaps, doors and windows that fit.", Access::Verify, observe::validate);
    t.add("render_ascii", "The floor plan as text: walls, doors (D, E outside), windows (W), open connections (.), room ids and sizes, and every wall segment with its openings.", Access::Observe, observe::render_ascii);
    t.add("render_plan_image", "A top-down picture of the floor plan (PNG): room names, sizes and materials, walls, doors with their swing, windows.", Access::Observe, observe::render_plan_image);
    t.add("observe_scene", "Every room with position, size, role, neighbours, doors, windows, materials and its prompt; requested rooms vs present; search statistics; validation errors.", Access::Observe, observe::observe_scene);
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::Role as AgentRole;
    use crate::scene::OpeningKind;
    use serde_json::json;

    const FLAT: &str = "A two-bedroom apartment with a master bedroom, a second bedroom, a living room, a hallway, and a bathroom.";

    #[test]
    fn tool_names_are_the_ones_the_design_uses() {
        let t = toolbox();
        for name in [
            "generate_room_specs",
            "resize_room",
            "add_adjacency",
            "remove_adjacency",
            "add_open_connection",
            "remove_open_connection",
            "set_wall_height",
            "add_door",
            "remove_door",
            "add_window",
            "remove_window",
            "get_material",
            "set_room_materials",
            "validate",
            "render_ascii",
            "observe_scene",
            // The plan as a picture, for models with image input.
            "render_plan_image",
        ] {
            assert!(t.spec(name).is_some(), "missing {name}");
        }
        assert_eq!(t.len(), 17);
        // The critic may look and verify, never edit.
        let critic: Vec<&str> = t
            .specs_for(AgentRole::Critic)
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert!(critic.contains(&"validate") && !critic.contains(&"resize_room"));
    }

    #[test]
    fn edits_through_tools() {
        let t = toolbox();
        let mut s = LayoutState::new(FLAT, 1);
        let d = AgentRole::Designer;
        // Nothing generated yet: a clear error.
        let e = t
            .call(
                &mut s,
                d,
                "resize_room",
                json!({"room": "x", "width_m": 3, "depth_m": 3}),
            )
            .unwrap_err();
        assert!(e.message.contains("generate_room_specs"), "{e:?}");
        t.call(&mut s, d, "generate_room_specs", json!({})).unwrap();
        let v = t.call(&mut s, d, "validate", json!({})).unwrap();
        assert_eq!(v["ok"], true, "{v}");
        let obs = t.call(&mut s, d, "observe_scene", json!({})).unwrap();
        assert_eq!(obs["rooms"].as_array().unwrap().len(), 5);
        // Open plan between the living room and the hallway.
        t.call(
            &mut s,
            d,
            "add_open_connection",
            json!({"room_a": "living_room_0", "room_b": "hallway_0"}),
        )
        .unwrap();
        let (rooms, _) = s.rooms();
        assert!(
            rooms
                .iter()
                .flat_map(|r| &r.walls)
                .flat_map(|w| &w.openings)
                .any(|o| o.kind == OpeningKind::Open)
        );
        // Bathrooms keep their walls.
        let e = t
            .call(
                &mut s,
                d,
                "add_open_connection",
                json!({"room_a": "bathroom_0", "room_b": "hallway_0"}),
            )
            .unwrap_err();
        assert_eq!(e.kind, crate::agents::ToolErrorKind::Failed);
        // Materials by words.
        t.call(
            &mut s,
            d,
            "set_room_materials",
            json!({"room": "living_room_0", "floor": "polished concrete"}),
        )
        .unwrap();
        assert_eq!(
            s.spec
                .as_ref()
                .unwrap()
                .room("living_room_0")
                .unwrap()
                .floor_material,
            "concrete"
        );
        // Windows and doors: add and remove.
        let w = t
            .call(&mut s, d, "add_window", json!({"room": "living_room_0"}))
            .unwrap();
        let id = w["id"].as_str().unwrap().to_string();
        t.call(&mut s, d, "remove_window", json!({"id": id}))
            .unwrap();
        let e = t
            .call(
                &mut s,
                d,
                "add_door",
                json!({"room_a": "bathroom_0", "room_b": "nowhere"}),
            )
            .unwrap_err();
        assert_eq!(e.kind, crate::agents::ToolErrorKind::BadArguments);
        let text = t.call(&mut s, d, "render_ascii", json!({})).unwrap();
        assert!(text["text"].as_str().unwrap().contains("living_room_0"));
        // The picture is a PNG (base64 of the signature starts "iVBOR").
        let image = t.call(&mut s, d, "render_plan_image", json!({})).unwrap();
        assert!(
            image["image_png_base64"]
                .as_str()
                .unwrap()
                .starts_with("iVBORw0KGgo")
        );
        t.call(&mut s, d, "set_wall_height", json!({"height_m": 3.0}))
            .unwrap();
        assert!(
            s.rooms()
                .0
                .iter()
                .all(|r| (r.wall_height - 3.0).abs() < 1e-12)
        );
    }
}
