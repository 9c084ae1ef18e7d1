//! The bridge protocol's operations, typed: one [`Op`] per operation, with its argument and
//! reply types. [`super::Bridge::call`] sends `O::Args` and parses `O::Reply`; a reply that does
//! not parse is [`super::BridgeError::BadReply`] naming the operation, never a default value.
//!
//! The Python side (`drake_bridge/protocol.py`) declares one dataclass per argument and reply
//! type and validates both at its boundary. [`schema`] renders these types as JSON Schema into
//! `drake_bridge/protocol.schema.json`; `drake_bridge/tests/test_schema.py` checks the Python
//! dataclasses against that file, and the unit test here checks the file is current
//! (`SCENESMITH_UPDATE_SCHEMA=1 cargo test --lib protocol` rewrites it).
//!
//! Field names and units are the wire's: metres, seconds, kilograms, radians; poses are
//! `{"xyz": [..], "wxyz": [..]}` ([`Pose`]).

mod assets;
mod conformance;
mod robot;
mod scene;
mod sim;

use std::collections::BTreeMap;
use std::path::PathBuf;

use schemars::JsonSchema;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

pub use assets::*;
pub use conformance::*;
pub use robot::*;
pub use scene::*;
pub use sim::*;

use crate::scene::Pose;

/// One bridge operation: its name on the wire, its arguments and its reply.
pub trait Op {
    /// The `op` field of the request.
    const NAME: &'static str;
    /// What the request carries in `args`.
    type Args: Serialize + JsonSchema;
    /// What a successful reply carries in `result`.
    type Reply: DeserializeOwned + JsonSchema;
}

/// Declares a unit type implementing [`Op`].
macro_rules! op {
    ($(#[$doc:meta])* $ty:ident, $name:literal, $args:ty, $reply:ty) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $ty;
        impl $crate::physics::protocol::Op for $ty {
            const NAME: &'static str = $name;
            type Args = $args;
            type Reply = $reply;
        }
    };
}
pub(crate) use op;

/// Free-body poses by model instance and body: `instance -> body -> world_from_body`.
pub type Poses = BTreeMap<String, BTreeMap<String, Pose>>;

/// An axis-aligned box `[min, max]` in world coordinates, metres.
pub type Aabb = [[f64; 3]; 2];

/// The scene files a request is about: a directives file and the `package.xml` its
/// `package://` URIs resolve against (next to the directives when `None`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SceneFiles {
    /// The model directives file.
    pub directives: PathBuf,
    /// The package manifest; `None`: `package.xml` beside the directives, if any.
    #[serde(default)]
    pub package_xml: Option<PathBuf>,
}

impl SceneFiles {
    /// Files of a directives file and its package manifest.
    pub fn new(directives: impl Into<PathBuf>, package_xml: impl Into<PathBuf>) -> SceneFiles {
        SceneFiles {
            directives: directives.into(),
            package_xml: Some(package_xml.into()),
        }
    }
}

/// Hit and miss counts of one of the bridge's plant caches.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CacheStats {
    /// Requests served by an already built plant.
    pub hits: u64,
    /// Requests that built one.
    pub misses: u64,
}

/// Arguments of the operations that take none.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct NoArgs {}

/// Every operation's name, argument schema and reply schema, as written to
/// `drake_bridge/protocol.schema.json`.
pub fn schema() -> Value {
    let mut ops = serde_json::Map::new();
    fn add<O: Op>(ops: &mut serde_json::Map<String, Value>) {
        let settings = schemars::generate::SchemaSettings::draft2020_12().with(|s| {
            s.inline_subschemas = true;
        });
        let args = settings
            .clone()
            .into_generator()
            .into_root_schema_for::<O::Args>();
        let reply = settings.into_generator().into_root_schema_for::<O::Reply>();
        ops.insert(
            O::NAME.to_string(),
            json!({"args": args.to_value(), "reply": reply.to_value()}),
        );
    }
    add::<Ping>(&mut ops);
    add::<Versions>(&mut ops);
    add::<Load>(&mut ops);
    add::<Penetrations>(&mut ops);
    add::<CollisionReport>(&mut ops);
    add::<DropSpheres>(&mut ops);
    add::<Project>(&mut ops);
    add::<Settle>(&mut ops);
    add::<Simulate>(&mut ops);
    add::<AssetsLoad>(&mut ops);
    add::<AssetsDrop>(&mut ops);
    add::<AssetsPush>(&mut ops);
    add::<MujocoCheck>(&mut ops);
    add::<UsdCheck>(&mut ops);
    add::<PolicyEpisode>(&mut ops);
    add::<JudgeTask>(&mut ops);
    add::<EvaluatorTool>(&mut ops);
    json!({
        "protocol": super::bridge::PROTOCOL,
        "generated_by": "scenesmith (src/physics/protocol); SCENESMITH_UPDATE_SCHEMA=1 cargo test --lib protocol rewrites this file",
        "ops": ops,
    })
}

/// Where the schema file lives in the repository.
pub fn schema_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("drake_bridge/protocol.schema.json")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rendered() -> String {
        let mut text = serde_json::to_string_pretty(&schema()).unwrap_or_default();
        text.push('\n');
        text
    }

    #[test]
    fn the_schema_file_is_current() {
        let want = rendered();
        let path = schema_path();
        if std::env::var_os("SCENESMITH_UPDATE_SCHEMA").is_some() {
            std::fs::write(&path, &want).expect("write the schema file");
        }
        let got = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            got == want,
            "{} is stale: run `SCENESMITH_UPDATE_SCHEMA=1 cargo test --lib protocol`",
            path.display()
        );
    }

    #[test]
    fn every_op_has_an_object_schema_for_args_and_reply() {
        let s = schema();
        let ops = s["ops"].as_object().expect("ops");
        assert_eq!(ops.len(), 17);
        for (name, op) in ops {
            for side in ["args", "reply"] {
                assert_eq!(op[side]["type"], "object", "{name} {side}");
            }
        }
    }

    #[test]
    fn a_reply_missing_a_field_does_not_parse() {
        let full = json!({"hits": 1, "misses": 2});
        assert!(serde_json::from_value::<CacheStats>(full).is_ok());
        let missing = json!({"hits": 1});
        assert!(serde_json::from_value::<CacheStats>(missing).is_err());
    }
}
