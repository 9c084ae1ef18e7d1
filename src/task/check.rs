//! Whether a generated scene suits a task: the objects it needs are there, and the goal does
//! not already hold.

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use super::{FLOOR, NEAR_M, Predicate, TaskSpec};
use crate::eval::requirements::{normalize_label, object_matches};
use crate::scene::{ObjectKind, Scene, SceneObject, Support};

/// The check of one scene against a task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneCheck {
    /// Required nouns with no object in the scene.
    pub missing: Vec<String>,
    /// Objects that could be the one to move.
    pub targets: Vec<String>,
    /// Objects that could be the reference.
    pub references: Vec<String>,
    /// (target, reference) pairs for which the goal already holds.
    pub goal_holds_for: Vec<(String, String)>,
    /// Targets for which the goal holds with no reference: the ones a policy may be bound to
    /// (a book on a full bookshelf already is on it; the one on the desk is not).
    pub bindable: Vec<String>,
}

impl SceneCheck {
    /// Usable for the task: nothing missing, and the goal false at the start for at least
    /// one object to move.
    pub fn passed(&self) -> bool {
        self.missing.is_empty() && !self.bindable.is_empty()
    }

    /// Why not, in words (empty when it passed).
    pub fn reason(&self) -> String {
        let mut why = Vec::new();
        if !self.missing.is_empty() {
            why.push(format!("missing {}", self.missing.join(", ")));
        } else if self.bindable.is_empty() {
            let pairs: Vec<String> = self
                .goal_holds_for
                .iter()
                .map(|(t, r)| format!("{t} and {r}"))
                .collect();
            why.push(format!("the goal already holds for {}", pairs.join(", ")));
        }
        why.join("; ")
    }
}

/// World-frame bounding box of an object's asset.
fn world_box(scene: &Scene, o: &SceneObject) -> Option<([f64; 3], [f64; 3])> {
    let [lo, hi] = scene.assets.get(&o.asset)?.bounds;
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for k in 0..8 {
        let c = Point3::new(
            if k & 1 == 0 { lo[0] } else { hi[0] },
            if k & 2 == 0 { lo[1] } else { hi[1] },
            if k & 4 == 0 { lo[2] } else { hi[2] },
        );
        let p = o.world_from_object.transform_point(&c);
        for a in 0..3 {
            min[a] = min[a].min(p[a]);
            max[a] = max[a].max(p[a]);
        }
    }
    Some((min, max))
}

/// Gap between two boxes, metres (0 when they overlap).
fn gap(a: ([f64; 3], [f64; 3]), b: ([f64; 3], [f64; 3])) -> f64 {
    (0..3)
        .map(|k| (a.0[k] - b.1[k]).max(b.0[k] - a.1[k]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Whether `t` rests on or in `r`, directly or on something that does.
fn supported_by(scene: &Scene, t: &SceneObject, r: &SceneObject) -> bool {
    let mut at = t;
    for _ in 0..4 {
        let Support::Object { parent, .. } = &at.support else {
            return false;
        };
        if *parent == r.id {
            return true;
        }
        match scene.object(parent) {
            Some(p) => at = p,
            None => return false,
        }
    }
    false
}

/// Whether the goal of `spec` holds between `t` and `r` in `scene`.
pub fn goal_holds(spec: &TaskSpec, scene: &Scene, t: &SceneObject, r: &SceneObject) -> bool {
    match spec.predicate {
        Predicate::On | Predicate::Inside => supported_by(scene, t, r),
        Predicate::Near => match (world_box(scene, t), world_box(scene, r)) {
            (Some(a), Some(b)) => gap(a, b) <= NEAR_M,
            _ => false,
        },
    }
}

/// Highest floor covering (a rug, a mat) that still counts as the floor, metres.
const FLOOR_COVERING_M: f64 = 0.03;

/// Whether `o` rests on the floor, or on a floor covering that does.
fn on_floor(scene: &Scene, o: &SceneObject) -> bool {
    match &o.support {
        Support::Floor { .. } => true,
        Support::Object { parent, .. } => scene.object(parent).is_some_and(|p| {
            matches!(p.support, Support::Floor { .. })
                && scene
                    .assets
                    .get(&p.asset)
                    .is_some_and(|a| a.bounds[1][2] - a.bounds[0][2] <= FLOOR_COVERING_M)
        }),
        _ => false,
    }
}

/// Whether `o` stands in a room of type `room_type`.
fn in_room_of_type(scene: &Scene, o: &SceneObject, room_type: &str) -> bool {
    scene
        .rooms
        .iter()
        .any(|r| r.id == o.room && r.room_type == room_type)
}

/// Checks `scene` against `spec`: missing required objects, and the pairs for which the goal
/// already holds. For a task across rooms only objects in the start room may be moved and only
/// references in the goal room count (a missing one is named with its room).
pub fn check_scene(spec: &TaskSpec, scene: &Scene) -> SceneCheck {
    let room_of = |label: &str| -> Option<&str> {
        let x = spec.across.as_ref()?;
        if label == spec.reference || spec.reference_on.as_deref() == Some(label) {
            Some(x.goal_room.as_str())
        } else {
            Some(x.start_room.as_str())
        }
    };
    let matching = |label: &str| -> Vec<&SceneObject> {
        let room = room_of(label);
        scene
            .objects
            .iter()
            .filter(|o| object_matches(label, o))
            .filter(|o| room.is_none_or(|t| in_room_of_type(scene, o, t)))
            .collect()
    };
    let mut missing: Vec<String> = spec
        .required
        .iter()
        .filter(|r| matching(r).is_empty())
        .map(|r| match room_of(r) {
            Some(t) => format!("{r} in the {}", t.replace('_', " ")),
            None => r.clone(),
        })
        .collect();
    let mut targets = matching(&spec.target);
    // Where the task says the object starts, or the reference stands: on or in such an object.
    let on_a = |o: &SceneObject, host: &str| {
        matching(host)
            .iter()
            .any(|h| h.id != o.id && supported_by(scene, o, h))
    };
    let start_object = spec.start.as_deref().filter(|s| *s != FLOOR);
    if let Some(start) = start_object {
        targets.retain(|o| on_a(o, start));
    }
    // Best candidates first: the task's own noun before narrower kinds that share its head
    // (a "can" before a "trash can"), and small objects before furniture.
    let rank = |o: &SceneObject, noun: &str| {
        (
            normalize_label(&o.category) != normalize_label(noun),
            o.kind != ObjectKind::Manipuland,
        )
    };
    targets.sort_by_key(|o| rank(o, &spec.target));
    if spec.start.as_deref() == Some(FLOOR) {
        targets.retain(|o| on_floor(scene, o));
    }
    let mut references = matching(&spec.reference);
    if let Some(host) = &spec.reference_on {
        references.retain(|o| on_a(o, host));
    }
    references.sort_by_key(|o| rank(o, &spec.reference));
    if missing.is_empty() {
        // Everything is there, but not where the task says.
        if targets.is_empty() {
            missing.push(match start_object {
                Some(start) => format!("{} on or in the {start}", spec.target),
                None => format!("{} on the floor", spec.target),
            });
        }
        if let (true, Some(host)) = (references.is_empty(), &spec.reference_on) {
            missing.push(format!("{} on the {host}", spec.reference));
        }
    }
    let mut goal_holds_for = Vec::new();
    for t in &targets {
        for r in &references {
            if t.id != r.id && goal_holds(spec, scene, t, r) {
                goal_holds_for.push((t.id.clone(), r.id.clone()));
            }
        }
    }
    let bindable = targets
        .iter()
        .filter(|t| !goal_holds_for.iter().any(|(id, _)| *id == t.id))
        .map(|o| o.id.clone())
        .collect();
    SceneCheck {
        missing,
        targets: targets.iter().map(|o| o.id.clone()).collect(),
        references: references.iter().map(|o| o.id.clone()).collect(),
        goal_holds_for,
        bindable,
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::scene::{Pose, Room};
    use crate::task::analyse;

    /// A kitchen and a living room, a table in each, a mug on each table.
    fn two_room_scene() -> Scene {
        let mut s = Scene::new("a house", 1, "scene_test");
        for (i, t) in ["kitchen", "living_room"].iter().enumerate() {
            let x = 4.0 * i as f64;
            s.rooms.push(Room {
                id: format!("{t}_0"),
                room_type: t.to_string(),
                label: None,
                prompt: String::new(),
                floor_polygon: vec![[x, 0.0], [x + 4.0, 0.0], [x + 4.0, 4.0], [x, 4.0]],
                wall_height: 2.5,
                walls: vec![],
                floor_material: "wood".into(),
                wall_material: "plaster".into(),
            });
            let object = |id: String, category: &str, kind, support| SceneObject {
                id,
                category: category.into(),
                name: None,
                planned: None,
                kind,
                room: format!("{t}_0"),
                asset: format!("{category}_a"),
                world_from_object: Pose::from_xyz_yaw(x + 2.0, 2.0, 0.0, 0.0),
                support,
                welded: false,
                joint_positions: BTreeMap::new(),
            };
            s.objects.push(object(
                format!("table_{i}"),
                "table",
                ObjectKind::Furniture,
                Support::Floor {
                    room: format!("{t}_0"),
                },
            ));
            s.objects.push(object(
                format!("mug_{i}"),
                "mug",
                ObjectKind::Manipuland,
                Support::Object {
                    parent: format!("table_{i}"),
                    surface: "top".into(),
                },
            ));
        }
        s
    }

    #[test]
    fn across_rooms_only_the_start_rooms_objects_move_and_only_the_goal_rooms_references_count() {
        let spec = analyse("bring the mug from the kitchen to the table in the living room")
            .expect("reads");
        let mut scene = two_room_scene();
        let ids = |v: &[String]| v.join(",");
        // mug_0 on table_0 in the kitchen, mug_1 on table_1 in the living room.
        let check = check_scene(&spec, &scene);
        assert_eq!(ids(&check.targets), "mug_0");
        // mug_1 is on the living room's table already, but it is not the one to move.
        assert!(
            check.goal_holds_for.is_empty(),
            "{:?}",
            check.goal_holds_for
        );
        assert_eq!(ids(&check.references), "table_1");
        assert!(check.passed(), "{}", check.reason());
        // Without a table in the living room the scene lacks the reference there.
        scene.objects.retain(|o| o.id != "table_1");
        let check = check_scene(&spec, &scene);
        assert_eq!(check.missing, ["table in the living room"]);
        assert!(!check.passed());
    }

    #[test]
    fn the_object_must_start_where_the_task_says_and_the_reference_stand_where_it_says() {
        let scene = two_room_scene();
        // The mugs stand on tables; the task wants one from a shelf.
        let spec = analyse("move the mug from the shelf to the table").expect("reads");
        let mut with_shelf = scene.clone();
        let mut shelf = with_shelf.objects[0].clone();
        shelf.id = "shelf_0".into();
        shelf.category = "shelf".into();
        with_shelf.objects.push(shelf);
        let check = check_scene(&spec, &with_shelf);
        assert_eq!(check.missing, ["mug on or in the shelf"]);
        // The reference must stand on what the task says.
        let spec = analyse("put the table on a mug on the shelf").expect("reads");
        assert_eq!(spec.reference_on.as_deref(), Some("shelf"));
        let check = check_scene(&spec, &with_shelf);
        assert!(check.references.is_empty(), "{:?}", check.references);
        assert!(
            check.missing.iter().any(|m| m == "mug on the shelf"),
            "{:?}",
            check.missing
        );
    }

    #[test]
    fn an_object_on_a_rug_is_on_the_floor_one_on_a_table_is_not() {
        let spec = analyse("pick a mug from the floor and put it on the table").expect("reads");
        let mut scene = two_room_scene();
        // Both mugs stand on tables.
        assert_eq!(check_scene(&spec, &scene).missing, ["mug on the floor"]);
        let mut rug = scene.objects[0].clone();
        rug.id = "rug_0".into();
        rug.category = "rug".into();
        rug.asset = "rug_a".into();
        scene.objects.push(rug);
        scene.assets.insert(
            "rug_a".into(),
            crate::scene::AssetRecord {
                id: "rug_a".into(),
                category: "rug".into(),
                sdf: "assets/rug_a/model.sdf".into(),
                root_link: "body".into(),
                links: vec!["body".into()],
                joints: vec![],
                bounds: [[-1.0, -0.7, 0.0], [1.0, 0.7, 0.012]],
                mass: 2.0,
                collision_pieces: 1,
                material: "fabric".into(),
                surfaces: vec![],
                provenance: serde_json::json!({}),
            },
        );
        if let Support::Object { parent, .. } = &mut scene.objects[1].support {
            *parent = "rug_0".into();
        }
        let check = check_scene(&spec, &scene);
        assert!(check.passed(), "{}", check.reason());
        assert_eq!(check.targets, ["mug_0"]);
    }

    #[test]
    fn the_tasks_own_noun_ranks_before_a_narrower_kind_and_small_objects_before_furniture() {
        let spec = analyse("put the can on the table").expect("reads");
        let mut scene = two_room_scene();
        let mut bin = scene.objects[0].clone();
        bin.id = "trash_can_0".into();
        bin.category = "trash_can".into();
        let mut can = scene.objects[1].clone();
        can.id = "can_0".into();
        can.category = "can".into();
        // Away from the table, so the goal does not hold for it.
        can.support = Support::Floor {
            room: can.room.clone(),
        };
        scene.objects.insert(0, bin);
        scene.objects.push(can);
        let check = check_scene(&spec, &scene);
        assert_eq!(
            check.targets.first().map(String::as_str),
            Some("can_0"),
            "{:?}",
            check.targets
        );
        assert_eq!(check.bindable.first().map(String::as_str), Some("can_0"));
    }
}
