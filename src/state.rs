//! The scene being built and the built assets its objects instantiate: what every stage edits
//! (build an asset, add, move or remove an object) and what the writers, checks, renderers and
//! metrics read. It sits above [`crate::assets`] and below everything that uses a whole scene.

use std::collections::BTreeMap;

use crate::assets::architecture;
use crate::assets::procedural::{self, AssetRequest};
use crate::assets::{Asset, AssetError};
use crate::geometry::GeometryError;
use crate::scene::{ObjectKind, Pose, Room, Scene, SceneObject, Support};

/// The scene being built and the assets it uses.
#[derive(Debug, Clone)]
pub struct SceneState {
    /// The scene model.
    pub scene: Scene,
    /// Built assets by id (architecture included).
    pub assets: BTreeMap<String, Asset>,
}

impl SceneState {
    /// State around an empty scene.
    pub fn new(scene: Scene) -> SceneState {
        SceneState {
            scene,
            assets: BTreeMap::new(),
        }
    }

    /// Builds (or reuses) the asset a request describes and registers it with the scene.
    pub fn build_asset(&mut self, request: &AssetRequest) -> Result<String, AssetError> {
        let asset = procedural::build(request)?;
        Ok(self.insert_asset(asset))
    }

    /// Registers an already built asset; returns its id.
    pub fn insert_asset(&mut self, asset: Asset) -> String {
        let id = asset.id.clone();
        self.scene
            .assets
            .entry(id.clone())
            .or_insert_with(|| asset.record());
        self.assets.entry(id.clone()).or_insert(asset);
        id
    }

    /// Adds an object instantiating `asset_id`; returns the new object's id.
    pub fn add_object(
        &mut self,
        category: &str,
        kind: ObjectKind,
        room: &str,
        asset_id: &str,
        world_from_object: Pose,
        support: Support,
    ) -> String {
        let id = self.scene.ids.allocate(category);
        self.scene.objects.push(SceneObject {
            id: id.clone(),
            category: category.to_string(),
            name: None,
            planned: None,
            kind,
            room: room.to_string(),
            asset: asset_id.to_string(),
            world_from_object,
            support,
            welded: kind.welded_by_default(),
            joint_positions: BTreeMap::new(),
        });
        id
    }

    /// Removes an object (and everything resting on it) from the scene, recording why.
    pub fn remove_object(&mut self, id: &str, stage: &str, reason: &str) {
        let mut doomed = vec![id.to_string()];
        let mut i = 0;
        while i < doomed.len() {
            let parent = doomed[i].clone();
            for o in &self.scene.objects {
                if matches!(&o.support, Support::Object { parent: p, .. } if *p == parent)
                    && !doomed.contains(&o.id)
                {
                    doomed.push(o.id.clone());
                }
            }
            i += 1;
        }
        for d in &doomed {
            if let Some(pos) = self.scene.objects.iter().position(|o| &o.id == d) {
                let o = self.scene.objects.remove(pos);
                let why = if d == id {
                    reason.to_string()
                } else {
                    format!("its support {id} was removed: {reason}")
                };
                self.scene.removed.push(crate::scene::Removal {
                    object: o.id,
                    category: o.category,
                    stage: stage.to_string(),
                    reason: why,
                });
            }
        }
    }

    /// Drops assets no object uses any more.
    pub fn prune_assets(&mut self) {
        let used: std::collections::BTreeSet<_> =
            self.scene.objects.iter().map(|o| o.asset.clone()).collect();
        self.assets.retain(|k, _| used.contains(k));
        self.scene.assets.retain(|k, _| used.contains(k));
    }
}

/// Adds the rooms to the scene, each with its static architecture object.
pub fn install_rooms(state: &mut SceneState, rooms: &[Room]) -> Result<(), GeometryError> {
    for room in rooms {
        state.scene.ids.reserve(&room.id);
        state.scene.rooms.push(room.clone());
    }
    for room in rooms {
        let arch_id = format!("{}_architecture", room.id);
        let asset = architecture::build_room_asset(room, &arch_id)?;
        let asset_id = state.insert_asset(asset);
        state.scene.ids.reserve(&arch_id);
        state.scene.objects.push(SceneObject {
            id: arch_id,
            category: "room_architecture".into(),
            name: None,
            planned: None,
            kind: ObjectKind::Architecture,
            room: room.id.clone(),
            asset: asset_id,
            world_from_object: Pose::IDENTITY,
            support: Support::World,
            welded: true,
            joint_positions: BTreeMap::new(),
        });
    }
    Ok(())
}
