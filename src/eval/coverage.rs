//! Plan coverage: which objects (and how many) the prompt reader planned, and whether the scene
//! has them. The requirements come from the reader ([`crate::prompt::read`]), so this measures
//! how well the scene follows the reader's plan, not the prompt itself: an object the reader
//! missed is missing from both sides. This module only compares the plan with the scene's
//! object categories; [`super::requirements`] scores a scene against requirements written
//! independently of the reader.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::prompt::{Count, Reading};
use crate::scene::{ObjectKind, Scene};

/// One requirement of the reader's plan and how the scene meets it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannedRequirement {
    /// Asset category.
    pub category: String,
    /// `exactly`, `at_least`, `several` or `none` (negated: "no TV").
    pub kind: String,
    /// Number planned (0 for `none`).
    pub required: u32,
    /// Objects of the category in the scene.
    pub present: u32,
    /// Met: `exactly n` needs n, `at_least n` n or more, `several` two or more, `none` zero.
    pub satisfied: bool,
}

/// Coverage of the reader's plan by a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanCoverage {
    /// Per category, in category order.
    pub requirements: Vec<PlannedRequirement>,
    /// Requirements met.
    pub satisfied: usize,
    /// Percent of requirements met (100 when the plan names nothing).
    pub percent: f64,
    /// Percent of the planned object count present: sum(min(present, required)) /
    /// sum(required) over positive requirements.
    pub count_percent: f64,
}

/// Compares the reader's `reading` with the objects of `scene`. Several mentions of one category
/// merge into the largest count; a category both planned and negated counts as planned.
pub fn plan_coverage(reading: &Reading, scene: &Scene) -> PlanCoverage {
    // The reader's nouns ("board game", "sink") name the library's categories ("board_game",
    // "sink_vanity") through the asset router's reading, as when the scene was built.
    // What the router builds for a mention's description counts too: "wooden play blocks"
    // are the library's wooden blocks, a variant of the toy block the noun names.
    let mut built: BTreeMap<&str, Vec<&'static str>> = BTreeMap::new();
    for m in &reading.mentions {
        if let Some(c) = crate::assets::router::naming::category_of(&m.description()) {
            built.entry(m.category.as_str()).or_default().push(c);
        }
    }
    let present_of = |noun: &str| {
        let described = built.get(noun).map(Vec::as_slice).unwrap_or_default();
        scene
            .objects
            .iter()
            .filter(|o| o.kind != ObjectKind::Architecture)
            .filter(|o| {
                crate::assets::router::naming::object_is(scene, noun, o)
                    || described.contains(&scene.built_as(o))
            })
            .count() as u32
    };
    // Within a room, repeated mentions of a category ("a table ... the table") merge into the
    // largest count; across rooms of a house they add up. Per-parent and per-setting counts
    // ("two chairs at each desk", "set for 4") are totals.
    let mut per_room: BTreeMap<(String, usize), Count> = BTreeMap::new();
    let mut negated: Vec<String> = Vec::new();
    for (i, m) in reading.mentions.iter().enumerate() {
        if m.negated {
            negated.push(m.category.clone());
            continue;
        }
        let total = reading.total(i);
        per_room
            .entry((m.category.clone(), m.room))
            .and_modify(|c| {
                if total.minimum() > c.minimum() {
                    *c = total;
                }
            })
            .or_insert(total);
    }
    let mut asked: BTreeMap<String, Count> = BTreeMap::new();
    for ((cat, _), count) in per_room {
        asked
            .entry(cat)
            .and_modify(|c| *c = add_counts(*c, count))
            .or_insert(count);
    }
    let mut requirements = Vec::new();
    for (cat, count) in &asked {
        let have = present_of(cat.as_str());
        let (kind, required, satisfied) = match count {
            Count::Exactly(n) => ("exactly", *n, have == *n),
            Count::AtLeast(n) => ("at_least", *n, have >= *n),
            Count::Several => ("several", count.minimum(), have >= count.minimum()),
        };
        requirements.push(PlannedRequirement {
            category: cat.clone(),
            kind: kind.into(),
            required,
            present: have,
            satisfied,
        });
    }
    negated.sort();
    negated.dedup();
    for cat in negated.into_iter().filter(|c| !asked.contains_key(c)) {
        let have = present_of(cat.as_str());
        requirements.push(PlannedRequirement {
            category: cat,
            kind: "none".into(),
            required: 0,
            present: have,
            satisfied: have == 0,
        });
    }
    let satisfied = requirements.iter().filter(|r| r.satisfied).count();
    let percent = if requirements.is_empty() {
        100.0
    } else {
        100.0 * satisfied as f64 / requirements.len() as f64
    };
    let (got, want) =
        requirements
            .iter()
            .filter(|r| r.required > 0)
            .fold((0u64, 0u64), |(g, w), r| {
                (
                    g + u64::from(r.present.min(r.required)),
                    w + u64::from(r.required),
                )
            });
    PlanCoverage {
        requirements,
        satisfied,
        percent,
        count_percent: if want == 0 {
            100.0
        } else {
            100.0 * got as f64 / want as f64
        },
    }
}

/// Two rooms' counts of one category together.
fn add_counts(a: Count, b: Count) -> Count {
    match (a, b) {
        (Count::Exactly(x), Count::Exactly(y)) => Count::Exactly(x + y),
        (Count::Several, Count::Several) => Count::Several,
        _ => Count::AtLeast(a.minimum() + b.minimum()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Pose, SceneObject, Support};

    fn scene_with(cats: &[&str]) -> Scene {
        let mut s = Scene::new("p", 0, "t");
        for (i, c) in cats.iter().enumerate() {
            s.objects.push(SceneObject {
                id: format!("{c}_{i}"),
                category: c.to_string(),
                name: None,
                planned: None,
                kind: ObjectKind::Furniture,
                room: "r".into(),
                asset: "a".into(),
                world_from_object: Pose::IDENTITY,
                support: Support::World,
                welded: false,
                joint_positions: Default::default(),
            });
        }
        s
    }

    #[test]
    fn exact_at_least_several_and_negated() {
        let reading = crate::prompt::read(
            "A kitchen with four chairs, at least 3 mugs, some books and no cabinet.",
        );
        let scene = scene_with(&[
            "chair", "chair", "chair", "mug", "mug", "mug", "mug", "book",
        ]);
        let c = plan_coverage(&reading, &scene);
        let by: BTreeMap<_, _> = c
            .requirements
            .iter()
            .map(|r| (r.category.as_str(), r))
            .collect();
        assert!(!by["chair"].satisfied && by["chair"].present == 3);
        assert!(by["mug"].satisfied);
        assert!(!by["book"].satisfied && by["book"].required == 2);
        assert!(by["cabinet"].satisfied && by["cabinet"].kind == "none");
        assert_eq!(c.satisfied, 2);
        assert!((c.percent - 50.0).abs() < 1e-9);
        // 3 of 4 chairs, 3 of 3 mugs, 1 of 2 books.
        assert!((c.count_percent - 100.0 * 7.0 / 9.0).abs() < 1e-9);
    }
}

#[cfg(test)]
mod house_tests {
    use super::*;

    #[test]
    fn rooms_of_a_house_add_up_and_per_parent_counts_multiply() {
        assert_eq!(
            add_counts(Count::Exactly(2), Count::Exactly(3)),
            Count::Exactly(5)
        );
        assert_eq!(
            add_counts(Count::Several, Count::Exactly(1)),
            Count::AtLeast(3)
        );
        let reading = crate::prompt::read("An office with two desks, each with a chair.");
        let scene = Scene::new("p", 0, "t");
        let c = plan_coverage(&reading, &scene);
        let chair = c
            .requirements
            .iter()
            .find(|r| r.category == "chair")
            .expect("chairs are planned");
        assert_eq!(chair.required, 2, "{:?}", c.requirements);
    }
}
