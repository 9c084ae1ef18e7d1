//! The placement stages and the state their tools work on.
//!
//! Every stage edits the scene through [`SceneState`]'s few operations (build an asset, add,
//! move or remove an object); [`StageState`] adds the room in focus and its plan.
//!
//! Each placement stage ([`furniture`], [`wall`], [`ceiling`], [`manipuland`]) is a folder of
//! the same shape: `mod.rs` says what the stage does and is its public surface (`toolbox`,
//! `categories`, the built-in designer and critic), `tools.rs` holds its tools, `builtin.rs`
//! its built-in designer and critic; a long tool set goes on in further files of the folder,
//! one concept each. Shared by the stages: the tools every stage has ([`common`]), floor
//! geometry ([`placement`], [`room`]), how much clutter a piece holds ([`clutter`]), the runner
//! ([`run`]) and the checkpoints of `--resume` ([`checkpoint`]).

pub mod ceiling;
pub mod checkpoint;
pub mod clutter;
pub mod common;
pub mod furniture;
pub mod manipuland;
pub mod placement;
pub mod room;
pub mod run;
pub mod wall;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::agents::ToolError;
use crate::assets::procedural::{self, SupportClass};
use crate::assets::router::{self, RouteRequest, RouterContext, Stage, Strategy};
use crate::plan;
use crate::scene::{ObjectKind, Pose, SceneObject, Support};
use crate::state::SceneState;

/// The placement stages, in pipeline order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Hash, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum StageKind {
    /// Rooms and architecture.
    Layout,
    /// Floor furniture.
    Furniture,
    /// Wall-mounted objects.
    Wall,
    /// Ceiling objects.
    Ceiling,
    /// Small objects on surfaces.
    Manipuland,
}

impl StageKind {
    /// The stage's name as used in logs, prompts and `scene.json`.
    pub fn as_str(self) -> &'static str {
        match self {
            StageKind::Layout => "layout",
            StageKind::Furniture => "furniture",
            StageKind::Wall => "wall",
            StageKind::Ceiling => "ceiling",
            StageKind::Manipuland => "manipuland",
        }
    }

    /// The object kind this stage creates.
    pub fn object_kind(self) -> ObjectKind {
        match self {
            StageKind::Layout => ObjectKind::Architecture,
            StageKind::Furniture => ObjectKind::Furniture,
            StageKind::Wall => ObjectKind::Wall,
            StageKind::Ceiling => ObjectKind::Ceiling,
            StageKind::Manipuland => ObjectKind::Manipuland,
        }
    }

    fn router_stage(self) -> Option<Stage> {
        match self {
            StageKind::Layout => None,
            StageKind::Furniture => Some(Stage::Furniture),
            StageKind::Wall => Some(Stage::Wall),
            StageKind::Ceiling => Some(Stage::Ceiling),
            StageKind::Manipuland => Some(Stage::Manipuland),
        }
    }

    fn support(self) -> Option<SupportClass> {
        match self {
            StageKind::Layout => None,
            StageKind::Furniture => Some(SupportClass::Floor),
            StageKind::Wall => Some(SupportClass::Wall),
            StageKind::Ceiling => Some(SupportClass::Ceiling),
            StageKind::Manipuland => Some(SupportClass::Surface),
        }
    }
}

fn stage_for_support(s: SupportClass) -> &'static str {
    match s {
        SupportClass::Floor => "furniture",
        SupportClass::Wall => "wall",
        SupportClass::Ceiling => "ceiling",
        SupportClass::Surface => "manipuland",
    }
}

/// The asset router of this process, configured from the environment once (disk cache,
/// articulated library, mesh folder, text-to-3D backend; see the README's *Assets*).
fn router_context() -> &'static RouterContext {
    static CONTEXT: std::sync::OnceLock<RouterContext> = std::sync::OnceLock::new();
    CONTEXT.get_or_init(RouterContext::from_env)
}

/// What the designer is told about a routed request besides the asset: the router's notes
/// (generic stand-ins, clamped sizes, fallbacks), the parts of a composite, which this tool
/// does not place, and parts that belong to a later stage.
fn routing_notes(routed: &router::Routed) -> Vec<String> {
    let mut notes = routed.notes.clone();
    for part in &routed.parts {
        notes.push(format!(
            "{} {} go {} the {}: place them with their own call",
            part.count,
            part.category,
            part.role.as_str(),
            routed.primary.category
        ));
    }
    for d in &routed.deferred {
        notes.push(format!(
            "{} \"{}\" belong to the {} stage ({} the {}): ask for them there",
            d.count,
            d.request.description,
            d.request.stage.as_str(),
            d.relation.as_str(),
            routed.primary.category
        ));
    }
    notes
}

/// An asset chosen for a description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RoutedAsset {
    /// Asset id.
    pub asset: String,
    /// Category it was built as.
    pub category: String,
    /// Size (x, y, z), metres.
    pub size: [f64; 3],
    /// What the designer should know: a generic stand-in for an unknown noun, a clamped size,
    /// parts of a composite to place next, parts for a later stage.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// The description's own name for the object when it says more than the category
    /// ("long wedging table" built as a `table`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The plan's noun of the item the description places, when it is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub planned: Option<String>,
}

/// A short description that is a name ("long wedging table", "paint-spattered radio") and
/// says more than `category`; not a sentence an LLM designer wrote. Of a description that
/// goes on after its main phrase ("black grand piano with its lid raised"), the main phrase.
fn object_name(description: &str, category: &str) -> Option<String> {
    let text = description.trim().to_lowercase();
    let mut words: Vec<&str> = text.split_whitespace().collect();
    if words.len() > 5
        && let Some(end) = words.iter().position(|w| router::parse::is_connector(w))
    {
        words.truncate(end);
    }
    let text = words.join(" ");
    let plain = words.iter().all(|w| {
        w.chars()
            .all(|c| c.is_alphabetic() || c == '-' || c == '\'')
    });
    let differs = crate::scene::sanitize_name(&text) != category;
    (plain && differs && (2..=5).contains(&words.len())).then(|| words.join(" "))
}

/// Whether a thing of support class `own` may be placed by the stage of `stage` when the plan
/// puts it there: a small thing standing on the floor (a basket, a crate), a floor thing
/// small enough for a piece of furniture (the surface's own fit check decides), or a small
/// thing the prompt mounts ("a computer on a wall arm", "a projector hangs from the
/// ceiling": fixed where it is put, as wall and ceiling things are).
fn crosses(own: SupportClass, stage: SupportClass) -> bool {
    matches!(
        (own, stage),
        (SupportClass::Surface, SupportClass::Floor)
            | (SupportClass::Floor, SupportClass::Surface)
            | (SupportClass::Surface, SupportClass::Wall)
            | (SupportClass::Surface, SupportClass::Ceiling)
    )
}

/// The state a placement stage's tools work on: the scene, the room (and supporting entity)
/// in focus, and what the room should contain.
#[derive(Debug, Clone)]
pub struct StageState {
    /// Scene and assets.
    pub scene: SceneState,
    /// Which stage.
    pub kind: StageKind,
    /// Room in focus.
    pub room: String,
    /// Supporting entity in focus (manipuland stage), if any.
    pub entity: Option<String>,
    /// What the room should contain.
    pub plan: Arc<plan::RoomPlan>,
    /// Assets requested so far (drives per-request seeds).
    pub requests: u64,
}

impl StageState {
    /// True when `o` counts for the plan item `want`: its noun names it, or it is what the
    /// router builds for the item's description ("wooden play blocks" are the library's
    /// wooden blocks, a variant of the toy block the noun names).
    pub fn is_wanted(scene: &crate::scene::Scene, want: &plan::Want, o: &SceneObject) -> bool {
        // An object placed for another of the plan's nouns is not this one: a music room's
        // three music stands are no microphone stands, though one generator builds both.
        if o.planned.as_deref().is_some_and(|p| p != want.noun) {
            return false;
        }
        crate::assets::router::naming::category_of(&want.description) == Some(scene.built_as(o))
            || crate::assets::router::naming::object_is(scene, &want.noun, o)
    }

    /// The plan's noun for `description` among the things this stage places.
    fn planned_noun(&self, description: &str) -> Option<String> {
        let same = |w: &&plan::Want| w.description.eq_ignore_ascii_case(description.trim());
        let wants: Vec<&plan::Want> = match self.kind {
            StageKind::Layout => Vec::new(),
            StageKind::Furniture => self.plan.furniture.iter().collect(),
            StageKind::Wall => self.plan.wall.iter().collect(),
            StageKind::Ceiling => self.plan.ceiling.iter().collect(),
            StageKind::Manipuland => self.plan.surfaces.iter().flat_map(|g| &g.items).collect(),
        };
        wants.into_iter().find(same).map(|w| w.noun.clone())
    }

    /// Builds (or reuses) the asset for `description` through the asset router (attributes
    /// such as "red oak" choose materials; an unknown noun gets a generic shape of the stage's
    /// support class, or an external mesh when one is configured), refusing objects of another
    /// stage with a reason the designer can act on.
    pub fn route_asset(
        &mut self,
        description: &str,
        size: Option<[f64; 3]>,
    ) -> Result<RoutedAsset, ToolError> {
        let for_stage = |candidates: &[&str], want: SupportClass| {
            candidates
                .iter()
                .any(|c| procedural::prior(c).is_some_and(|p| p.support == want))
        };
        let mut candidates = router::parse::main_categories(description);
        // The plan's noun decides what is built when the router reads the prompt's name for
        // it as something else or not at all ("two-burner hob": a stove; "heavy shears":
        // scissors); the object keeps the name.
        // A variant of the noun's own generator ("wooden blocks": the toy block's wooden
        // variant) is what the words ask for and stays.
        let generator =
            |c: Option<&&str>| c.and_then(|c| procedural::prior(c)).map(|p| &p.generator);
        let mut plan_builds = None;
        if let Some(noun) = self.planned_noun(description) {
            let of_noun = router::parse::main_categories(&noun);
            // A noun the library does not build leaves the description to the router when the
            // router reads a thing in it ("rulers"), not when it reads none ("iron", a
            // material to the router, is planned as a smoothing iron).
            let same_kind = if of_noun.is_empty() {
                router::parse::object_name(description).is_some()
            } else {
                of_noun.first() == candidates.first()
                    || generator(of_noun.first())
                        .is_some_and(|g| generator(candidates.first()) == Some(g))
            };
            if !same_kind {
                candidates = of_noun;
                plan_builds = Some(noun);
            }
        }
        // The object keeps the words it was asked for by as its name, whatever it is built as.
        let asked = description.to_string();
        let mut description = description.to_string();
        // A kind that rests elsewhere has a sibling for this stage ("storage bins" the prompt
        // puts on the floor are floor bins): build that one.
        if let (Some(&first), Some(want)) = (candidates.first(), self.kind.support())
            && !for_stage(&candidates, want)
            && let Some(sibling) = procedural::support_sibling(first, want)
        {
            plan_builds = None;
            let (from, to) = (first.replace('_', " "), sibling.replace('_', " "));
            description = if description.contains(&from) {
                description.replace(&from, &to)
            } else {
                to
            };
            candidates = router::parse::main_categories(&description);
        }
        let description = description.as_str();
        let mut category = candidates.first().copied();
        let mut stage = self
            .kind
            .router_stage()
            .ok_or_else(|| ToolError::failed("the layout stage places no objects".to_string()))?;
        // What the plan calls this description, when the router reads the words as a thing of
        // another stage: the plan's noun decides ("fume hood": a range hood, not a hood to
        // wear), and a thing the plan itself puts here stays here (a basket on the floor).
        let mut planned_as = None;
        // A small thing of no generator that the plan stands on the floor (the room's
        // surfaces had no place for "a flour sack") keeps a small thing's size.
        if category.is_none()
            && self.kind == StageKind::Furniture
            && self.planned_noun(description).is_some_and(|n| {
                crate::words::lexicon()
                    .lookup(&n)
                    .is_some_and(|e| e.support == crate::words::lexicon::Support::Surface)
            })
        {
            stage = Stage::for_support(SupportClass::Surface);
        }
        if let (Some(first), Some(want)) = (category, self.kind.support())
            && let Some(prior) = procedural::prior(first)
            && !for_stage(&candidates, want)
        {
            let noun = self.planned_noun(description);
            let noun_fits = noun
                .as_deref()
                .map(router::parse::main_categories)
                .filter(|c| for_stage(c, want));
            if let (Some(noun), Some(c)) = (noun.as_ref(), noun_fits) {
                category = c.first().copied();
                planned_as = Some(noun.clone());
            } else if noun.is_some() && crosses(prior.support, want) {
                stage = Stage::for_support(prior.support);
            } else {
                return Err(ToolError::failed(format!(
                    "{first} is a {:?} object; place it in the {} stage, not the {} stage",
                    prior.support,
                    stage_for_support(prior.support),
                    self.kind.as_str()
                )));
            }
        }
        // One seed per (scene seed, category, size): identical requests share one asset, so a
        // set of chairs matches.
        let key = format!(
            "{}:{}:{size:?}",
            self.scene.scene.provenance.seed,
            category.unwrap_or(description)
        );
        let h = blake3::hash(key.as_bytes());
        let seed = u64::from_le_bytes(h.as_bytes()[..8].try_into().unwrap_or([0; 8]));
        // The router reads the whole description: attributes, compounds ("fruit bowl": a
        // bowl now, its fruit reported as parts to place), unknown nouns.
        let mut request = RouteRequest::new(description, stage, seed);
        // Words the router cannot read that the plan names ("heavy shears" for scissors):
        // build the plan's noun; the object keeps the words as its name.
        request.category = planned_as.or(plan_builds);
        request.size = size;
        self.requests += 1;
        let routed = router::route(&request, router_context())
            .map_err(|e| ToolError::failed(e.to_string()))?;
        if routed.primary.strategy == Strategy::Generic {
            tracing::info!(
                "no generator knows {description:?}: a generic {} stands in",
                routed.primary.category
            );
        }
        let notes = routing_notes(&routed);
        // The object is called what the description calls it ("manicure table", "bedside
        // table"); its asset keeps the library's category.
        let category = if routed.primary.strategy == Strategy::Generic {
            routed.primary.category.clone()
        } else {
            // Words that name no thing the router knows ("old vinyl"): the plan's noun.
            router::parse::object_name(description)
                .or_else(|| self.planned_noun(&asked))
                .map(|n| crate::scene::sanitize_name(&n))
                .unwrap_or_else(|| routed.primary.category.clone())
        };
        let id = self
            .scene
            .insert_asset(routed.primary.asset.as_ref().clone());
        let [lo, hi] = self.scene.scene.assets[&id].bounds;
        Ok(RoutedAsset {
            asset: id,
            name: object_name(&asked, &category),
            planned: self.planned_noun(&asked),
            category,
            size: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
            notes,
        })
    }

    /// Adds an object of the routed asset to the room in focus, under the description's
    /// name; returns its id.
    pub fn add_routed(
        &mut self,
        routed: &RoutedAsset,
        kind: ObjectKind,
        pose: Pose,
        support: Support,
    ) -> String {
        let room = self.room.clone();
        let id = self
            .scene
            .add_object(&routed.category, kind, &room, &routed.asset, pose, support);
        if let Some(o) = self
            .scene
            .scene
            .objects
            .iter_mut()
            .rev()
            .find(|o| o.id == id)
        {
            o.name = routed.name.clone();
            o.planned = routed.planned.clone();
        }
        id
    }

    /// The room in focus.
    pub fn room(&self) -> Result<&crate::scene::Room, ToolError> {
        self.scene
            .scene
            .room(&self.room)
            .ok_or_else(|| ToolError::failed(format!("room {} does not exist", self.room)))
    }

    /// Objects of the room in focus (architecture excluded).
    pub fn room_objects(&self) -> impl Iterator<Item = &SceneObject> {
        self.scene
            .scene
            .objects
            .iter()
            .filter(|o| o.room == self.room && o.kind != ObjectKind::Architecture)
    }
}

#[cfg(test)]
mod tests {
    use super::object_name;

    #[test]
    fn an_object_is_named_by_its_main_phrase() {
        assert_eq!(
            object_name("long wedging table", "table").as_deref(),
            Some("long wedging table")
        );
        // A description that goes on names the object by the phrase before its parts.
        assert_eq!(
            object_name("black grand piano with its lid raised", "piano").as_deref(),
            Some("black grand piano")
        );
        // "of" joins one name; a name no longer than the category's says nothing more.
        assert_eq!(object_name("chest of drawers", "chest_of_drawers"), None);
        assert_eq!(
            object_name("pegboard displaying a pair of scissors", "pegboard"),
            None
        );
        assert_eq!(object_name("table", "table"), None);
    }
}
