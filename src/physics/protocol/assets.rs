//! Checks of single asset models in Drake: `assets_load`, `assets_drop`, `assets_push`
//! (`drake_bridge/asset_checks.py`).

use std::collections::BTreeMap;
use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::op;

op!(
    /// Loads each model with strict parsing and summarises it (or names why it failed).
    AssetsLoad, "assets_load", AssetsLoadArgs, AssetsLoadReply
);
op!(
    /// Drops each model onto a floor and reports how far it tipped and slid.
    AssetsDrop, "assets_drop", AssetsDropArgs, AssetsDropReply
);
op!(
    /// Welds each model down, pushes every joint towards its upper limit and reports where the
    /// joints got and how deep the model's links went into each other.
    AssetsPush, "assets_push", AssetsPushArgs, AssetsPushReply
);

/// One model file to check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetModel {
    /// Name of its model instance (unique in the request).
    pub name: String,
    /// Its SDFormat file.
    pub sdf: PathBuf,
    /// Horizontal extent, metres (spaces the grid the models are laid out on).
    #[serde(default)]
    pub footprint: Option<f64>,
    /// Force or torque per joint for `assets_push`, instead of the one scaled from the weight.
    #[serde(default)]
    pub efforts: Option<BTreeMap<String, f64>>,
}

/// Arguments of `assets_load`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsLoadArgs {
    /// The models (at least one).
    pub models: Vec<AssetModel>,
}

/// A one-degree-of-freedom joint of an asset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetJoint {
    /// Joint name.
    pub name: String,
    /// `revolute` or `prismatic`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Lower limit (radians or metres).
    pub lower: f64,
    /// Upper limit.
    pub upper: f64,
}

/// What Drake made of one model; the counts are `None` when it failed to load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetSummary {
    /// It loaded.
    pub ok: bool,
    /// Why it did not.
    pub error: Option<String>,
    /// Bodies.
    pub bodies: Option<usize>,
    /// Total mass, kg.
    pub mass: Option<f64>,
    /// Revolute and prismatic joints.
    pub joints: Option<Vec<AssetJoint>>,
    /// Geometries with the proximity role.
    pub collision_geometries: Option<usize>,
}

/// Reply to `assets_load`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsLoadReply {
    /// Per model name.
    pub models: BTreeMap<String, AssetSummary>,
}

fn default_drop_duration() -> f64 {
    2.0
}
fn default_push_duration() -> f64 {
    1.0
}
fn default_time_step() -> f64 {
    1e-3
}
fn default_force_scale() -> f64 {
    2.0
}

/// Arguments of `assets_drop`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsDropArgs {
    /// The models (at least one).
    pub models: Vec<AssetModel>,
    /// Simulated time, seconds (0 to 30).
    #[serde(default = "default_drop_duration")]
    pub duration: f64,
    /// Time step, seconds (1e-4 to 1e-2).
    #[serde(default = "default_time_step")]
    pub time_step: f64,
}

/// How one dropped model ended.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DropOutcome {
    /// Angle of its z axis from the world's, radians.
    pub tilt_rad: f64,
    /// Rotation from its start, radians.
    pub rotation_rad: f64,
    /// Horizontal travel, metres.
    pub horizontal_m: f64,
    /// Vertical travel (negative: down), metres.
    pub vertical_m: f64,
}

/// Reply to `assets_drop`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsDropReply {
    /// Simulated time, seconds.
    pub duration: f64,
    /// Time step, seconds.
    pub time_step: f64,
    /// Per model name.
    pub models: BTreeMap<String, DropOutcome>,
}

/// Arguments of `assets_push`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsPushArgs {
    /// The models (at least one).
    pub models: Vec<AssetModel>,
    /// Simulated time, seconds (0 to 30).
    #[serde(default = "default_push_duration")]
    pub duration: f64,
    /// Time step, seconds (1e-4 to 1e-2).
    #[serde(default = "default_time_step")]
    pub time_step: f64,
    /// Default effort: this many times the moving link's weight (times its lever arm for a
    /// revolute joint).
    #[serde(default = "default_force_scale")]
    pub force_scale: f64,
}

/// Where one pushed joint got.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PushedJoint {
    /// `revolute` or `prismatic`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Position at the end (radians or metres).
    pub position: f64,
    /// Lower limit.
    pub lower: f64,
    /// Upper limit.
    pub upper: f64,
    /// Force or torque applied.
    pub effort: f64,
}

/// One pushed model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PushOutcome {
    /// Per joint name.
    pub joints: BTreeMap<String, PushedJoint>,
    /// Deepest contact between two of its own links during the run, metres.
    pub self_penetration_m: f64,
    /// The frames of that contact.
    pub self_penetration_pair: Option<[String; 2]>,
}

/// Reply to `assets_push`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssetsPushReply {
    /// Simulated time, seconds.
    pub duration: f64,
    /// Time step, seconds.
    pub time_step: f64,
    /// Per model name.
    pub models: BTreeMap<String, PushOutcome>,
}
