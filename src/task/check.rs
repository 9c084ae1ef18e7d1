//! Whether a generated scene suits a task: the objects it needs are there, and the goal does
//! not already hold.

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use super::{NEAR_M, Predicate, TaskSpec};
use crate::eval::requirements::object_matches;
use crate::scene::{Scene, SceneObject, Support};

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

/// Checks `scene` against `spec`: missing required objects, and the pairs for which the goal
/// already holds.
pub fn check_scene(spec: &TaskSpec, scene: &Scene) -> SceneCheck {
    let matching = |label: &str| -> Vec<&SceneObject> {
        scene
            .objects
            .iter()
            .filter(|o| object_matches(label, o))
            .collect()
    };
    let missing = spec
        .required
        .iter()
        .filter(|r| matching(r).is_empty())
        .cloned()
        .collect();
    let targets = matching(&spec.target);
    let references = matching(&spec.reference);
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
