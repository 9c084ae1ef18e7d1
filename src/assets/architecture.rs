//! Room architecture as geometry: the floor slab and volumetric walls with openings cut
//! through them, built as one static asset per room.
//!
//! A wall with openings becomes boxes: full-height pieces between openings, a lintel above each
//! door, and wall below and above each window. Open connections leave the span empty.

use crate::assets::{Asset, LinkBuilder, Texture, material, textures};
use crate::geometry::{ConvexPiece, GeometryError, mesh, polygon};
use crate::scene::{OpeningKind, Pose, Room, Wall};

/// Floor slab thickness below z = 0, metres.
pub const FLOOR_THICKNESS: f64 = 0.10;

/// One box of a wall in wall coordinates: x along the wall, z up (floor at 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallPiece {
    /// Start along the wall, m.
    pub x0: f64,
    /// End along the wall, m.
    pub x1: f64,
    /// Bottom, m.
    pub z0: f64,
    /// Top, m.
    pub z1: f64,
}

/// Splits a wall of `height` into solid pieces around its openings.
///
/// The wall runs from `-thickness/2` to `length + thickness/2` so neighbouring walls close the
/// corners. Openings are clipped to the wall and sorted; overlapping openings merge.
pub fn wall_pieces(wall: &Wall, height: f64) -> Vec<WallPiece> {
    let len = wall.length();
    let (start, end) = (-wall.thickness / 2.0, len + wall.thickness / 2.0);
    let mut openings: Vec<_> = wall
        .openings
        .iter()
        .map(|o| {
            let (bottom, top) = match o.kind {
                OpeningKind::Open => (0.0, height),
                _ => (o.bottom.max(0.0), (o.bottom + o.height).min(height)),
            };
            (
                (o.center - o.width / 2.0).max(0.0),
                (o.center + o.width / 2.0).min(len),
                bottom,
                top,
            )
        })
        .filter(|(a, b, lo, hi)| b - a > 1e-6 && hi - lo > 1e-6)
        .collect();
    openings.sort_by(|a, b| a.0.total_cmp(&b.0));

    let mut pieces = Vec::new();
    let mut cursor = start;
    for (a, b, bottom, top) in openings {
        if a > cursor + 1e-9 {
            pieces.push(WallPiece {
                x0: cursor,
                x1: a,
                z0: 0.0,
                z1: height,
            });
        }
        let a = a.max(cursor);
        if b <= a {
            continue;
        }
        if bottom > 1e-6 {
            pieces.push(WallPiece {
                x0: a,
                x1: b,
                z0: 0.0,
                z1: bottom,
            });
        }
        if top < height - 1e-6 {
            pieces.push(WallPiece {
                x0: a,
                x1: b,
                z0: top,
                z1: height,
            });
        }
        cursor = b;
    }
    if end > cursor + 1e-9 {
        pieces.push(WallPiece {
            x0: cursor,
            x1: end,
            z0: 0.0,
            z1: height,
        });
    }
    pieces
}

/// The floor slab polygon: the room's clear floor grown to the wall centre lines, so the
/// slabs of neighbouring rooms meet under their shared wall.
fn slab_ring(room: &Room) -> Vec<[f64; 2]> {
    let Some(t) = room.walls.iter().map(|w| w.thickness).reduce(f64::max) else {
        return room.floor_polygon.clone();
    };
    let (lo, hi) = polygon::bounds(&room.floor_polygon);
    let h = t / 2.0;
    vec![
        [lo[0] - h, lo[1] - h],
        [hi[0] + h, lo[1] - h],
        [hi[0] + h, hi[1] + h],
        [lo[0] - h, hi[1] + h],
    ]
}

/// The tileable texture of a room surface material (planks, tiles, carpet, plaster, ...) and
/// the mesh mapped onto it at the texture's real-world repeat. The texture depends on the
/// material name only, so a floor and walls of the same material share one image.
fn textured(mesh: mesh::TriMesh, material: &str) -> (mesh::TriMesh, Texture) {
    let seed = u64::from_le_bytes(
        blake3::hash(material.as_bytes()).as_bytes()[..8]
            .try_into()
            .unwrap_or([0; 8]),
    );
    let surface = textures::surface_texture(material, seed);
    (
        mesh.with_box_uvs(surface.metres_per_repeat),
        surface.texture,
    )
}

/// Builds the static architecture asset of a room: link `floor` (slab) and link `walls` (the
/// walls this room owns; rooms are axis-aligned rectangles). Floors and walls are textured
/// with their room's materials (wood planks, tiles, carpet, plaster, marble, ...).
pub fn build_room_asset(room: &Room, asset_id: &str) -> Result<Asset, GeometryError> {
    let floor_mat = material::material_or_default(&room.floor_material);
    let wall_mat = material::material_or_default(&room.wall_material);

    let mut floor = LinkBuilder::new("floor", Pose::IDENTITY, floor_mat);
    let ring = slab_ring(room);
    for part in polygon::convex_parts(&ring)? {
        floor.add_collision(ConvexPiece::prism(&part, -FLOOR_THICKNESS, 0.0)?);
        let (visual, texture) = textured(
            mesh::prism_mesh(&part, -FLOOR_THICKNESS, 0.0),
            &room.floor_material,
        );
        floor.add_textured_visual(visual, texture);
    }

    let mut walls = LinkBuilder::new("walls", Pose::IDENTITY, wall_mat);
    let mut wall_pieces_built = 0usize;
    // A neighbour's wall seen from this room is built by the neighbour.
    for wall in room.walls.iter().filter(|w| w.mirror_of.is_none()) {
        let world_from_wall = wall.world_from_wall();
        let half_t = wall.thickness / 2.0;
        for p in wall_pieces(wall, room.wall_height) {
            let center = [(p.x0 + p.x1) / 2.0, 0.0, (p.z0 + p.z1) / 2.0];
            let size = [p.x1 - p.x0, 2.0 * half_t, p.z1 - p.z0];
            let piece = ConvexPiece::cuboid(center, size)?.transformed(&world_from_wall);
            walls.add_collision(piece);
            wall_pieces_built += 1;
            let (visual, texture) = textured(
                mesh::box_mesh(center, size).transformed(&world_from_wall),
                &room.wall_material,
            );
            walls.add_textured_visual(visual, texture);
        }
    }

    Ok(Asset {
        id: asset_id.to_string(),
        category: "room_architecture".into(),
        material: room.wall_material.clone(),
        // A room enclosed by rooms listed before it owns no wall.
        links: if wall_pieces_built > 0 {
            vec![floor.finish_static(), walls.finish_static()]
        } else {
            vec![floor.finish_static()]
        },
        joints: vec![],
        surfaces: vec![],
        is_static: true,
        provenance: serde_json::json!({
            "strategy": "architecture",
            "room": room.id,
            "license": "CC0-1.0 (generated by scenesmith)",
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Opening;

    fn wall_with(openings: Vec<Opening>) -> Wall {
        Wall {
            id: "w".into(),
            start: [0.0, 0.0],
            end: [5.0, 0.0],
            thickness: 0.1,
            neighbor: None,
            openings,
            mirror_of: None,
        }
    }

    #[test]
    fn door_leaves_a_lintel() {
        let w = wall_with(vec![Opening {
            id: "door_0".into(),
            kind: OpeningKind::Door,
            center: 2.0,
            width: 0.9,
            bottom: 0.0,
            height: 2.1,
        }]);
        let pieces = wall_pieces(&w, 2.7);
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        let lintel = pieces
            .iter()
            .find(|p| p.z0 > 0.0)
            .expect("a lintel above the door");
        assert!((lintel.z0 - 2.1).abs() < 1e-12 && (lintel.z1 - 2.7).abs() < 1e-12);
        assert!((lintel.x0 - 1.55).abs() < 1e-12 && (lintel.x1 - 2.45).abs() < 1e-12);
        // Nothing solid inside the doorway.
        assert!(
            !pieces
                .iter()
                .any(|p| p.x0 < 2.0 && p.x1 > 2.0 && p.z0 < 1.0)
        );
    }

    #[test]
    fn window_leaves_wall_below_and_above() {
        let w = wall_with(vec![Opening {
            id: "window_0".into(),
            kind: OpeningKind::Window,
            center: 3.0,
            width: 1.2,
            bottom: 0.9,
            height: 1.2,
        }]);
        let pieces = wall_pieces(&w, 2.7);
        assert_eq!(pieces.len(), 4);
        assert!(
            pieces
                .iter()
                .any(|p| p.z0 == 0.0 && (p.z1 - 0.9).abs() < 1e-12)
        );
        assert!(pieces.iter().any(|p| (p.z0 - 2.1).abs() < 1e-12));
    }

    #[test]
    fn open_connection_is_empty_full_height() {
        let w = wall_with(vec![Opening {
            id: "open_0".into(),
            kind: OpeningKind::Open,
            center: 2.5,
            width: 2.0,
            bottom: 0.0,
            height: 2.7,
        }]);
        let pieces = wall_pieces(&w, 2.7);
        assert_eq!(pieces.len(), 2);
        assert!(
            pieces
                .iter()
                .all(|p| p.x1 <= 1.5 + 1e-9 || p.x0 >= 3.5 - 1e-9)
        );
    }
}
