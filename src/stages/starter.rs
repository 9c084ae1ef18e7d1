//! The starter furnisher: places the starter assets (tables, chairs, cabinets, shelves, mugs,
//! plates, books) of one room, from the prompt's mentions or the room type's defaults.
//!
//! Furniture goes on the floor without overlaps: tables in the open middle of the room with
//! chairs around them facing the table, cabinets and shelves with their backs against walls
//! clear of doors (and of windows when taller than the sill). Small objects go on surfaces:
//! a place setting (plate, mug) in front of each chair, books upright on shelf levels, the rest
//! packed on free surface area. The agent-driven stages replace this planner.

use std::collections::BTreeMap;

use rand::RngExt;
use rand::rngs::ChaCha8Rng;

use super::SceneState;
use super::placement::{Footprint, against_wall, find_floor_spot, keep_out_zones, on_surface};
use crate::assets::AssetError;
use crate::assets::procedural::{self, AssetRequest, SupportClass};
use crate::prompt::{self, Reading};
use crate::scene::{ObjectKind, Pose, Support, SurfaceRecord};

/// What the planner did, for the user and the tests.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct StarterReport {
    /// Requested count per category.
    pub requested: BTreeMap<String, u32>,
    /// Placed count per category.
    pub placed: BTreeMap<String, u32>,
    /// Why some requested objects could not be placed.
    pub notes: Vec<String>,
}

/// Gap kept between furniture footprints, metres.
const FURNITURE_GAP: f64 = 0.05;
/// Height above a surface at which small objects are released, metres.
const SURFACE_LIFT: f64 = 0.001;

/// How many of each starter category the room gets.
fn requested_counts(reading: &Reading) -> BTreeMap<String, u32> {
    let mut counts: BTreeMap<String, u32> = BTreeMap::new();
    let negated: Vec<&str> = reading
        .mentions
        .iter()
        .filter(|m| m.negated)
        .filter_map(|m| procedural::resolve_category(&m.category))
        .collect();
    for m in reading.mentions.iter().filter(|m| !m.negated) {
        // Mention categories are canonical nouns; the starter builds only what its
        // generators know.
        let Some(category) = procedural::resolve_category(&m.category) else {
            continue;
        };
        let n = match m.count {
            prompt::Count::Exactly(n) | prompt::Count::AtLeast(n) => n,
            prompt::Count::Several => {
                if m.category == "book" {
                    8
                } else {
                    3
                }
            }
        };
        let e = counts.entry(category.to_string()).or_insert(0);
        *e = (*e).max(n);
    }
    let has_furniture = counts
        .keys()
        .any(|c| procedural::prior(c).is_some_and(|p| p.support == SupportClass::Floor));
    if !has_furniture && let Some(info) = prompt::room_types().get(&reading.room_type) {
        for (noun, n) in &info.defaults {
            if let Some(cat) = procedural::resolve_category(noun) {
                counts.entry(cat.to_string()).or_insert(*n);
            }
        }
    }
    counts.retain(|c, n| *n > 0 && !negated.contains(&c.as_str()));
    // Keep requests within what a room can physically hold.
    for n in counts.values_mut() {
        *n = (*n).min(60);
    }
    counts
}

/// Furnishes `room_id` of `state` according to `reading`.
pub fn furnish_room(
    state: &mut SceneState,
    room_id: &str,
    reading: &Reading,
    rng: &mut ChaCha8Rng,
) -> Result<StarterReport, AssetError> {
    let Some(room) = state.scene.room(room_id).cloned() else {
        return Ok(StarterReport::default());
    };
    let requested = requested_counts(reading);
    let mut report = StarterReport {
        requested: requested.clone(),
        ..Default::default()
    };
    let seed_for = |rng: &mut ChaCha8Rng| rng.random_range(0..u32::MAX as u64);
    // One asset per category: matching sets of chairs, identical mugs.
    let mut asset_of: BTreeMap<String, String> = BTreeMap::new();
    for cat in requested.keys() {
        let id = state.build_asset(&AssetRequest::new(cat, seed_for(rng)))?;
        asset_of.insert(cat.clone(), id);
    }
    let count = |c: &str| requested.get(c).copied().unwrap_or(0);
    let mut occupied: Vec<Footprint> = keep_out_zones(&room);
    let mut placed_tables: Vec<String> = Vec::new();
    let mut table_zones: Vec<Footprint> = Vec::new();
    let mut chairs_left = count("chair");

    // Tables in the open middle, long side along the room's long axis.
    if let Some(table_asset) = asset_of.get("table").cloned() {
        let rec = state.scene.assets[&table_asset].clone();
        let (lo, hi) = crate::geometry::polygon::bounds(&room.floor_polygon);
        let (rw, rd) = (hi[0] - lo[0], hi[1] - lo[1]);
        let yaw = if rw >= rd {
            0.0
        } else {
            std::f64::consts::FRAC_PI_2
        };
        let n = count("table") as usize;
        let cols = (n as f64).sqrt().ceil().max(1.0) as usize;
        let rows = n.div_ceil(cols);
        let mut k = 0;
        'tables: for r in 0..rows {
            for c in 0..cols {
                if k >= n {
                    break 'tables;
                }
                k += 1;
                let x = lo[0] + rw * (c as f64 + 0.5) / cols as f64;
                let y = lo[1] + rd * (r as f64 + 0.5) / rows as f64;
                let yaws = [yaw, yaw + std::f64::consts::FRAC_PI_2];
                // Prefer room for chairs all around; fall back to none.
                let spot = [[0.55, 0.55], [0.0, 0.55], [0.0, 0.0]]
                    .iter()
                    .find_map(|cl| {
                        find_floor_spot(
                            &room.floor_polygon,
                            &occupied,
                            &rec,
                            [x, y],
                            &yaws,
                            *cl,
                            FURNITURE_GAP,
                        )
                    });
                let Some(pose) = spot else {
                    report.notes.push(format!("no free floor for table #{k}"));
                    continue;
                };
                let fp = Footprint::of(&rec, &pose);
                occupied.push(fp);
                // Reserve the chairs' floor too, so wall furniture keeps clear of it.
                let mut zone = fp;
                zone.half[0] += 0.5;
                zone.half[1] += 0.5;
                table_zones.push(zone);
                let id = state.add_object(
                    "table",
                    ObjectKind::Furniture,
                    room_id,
                    &table_asset,
                    pose,
                    Support::Floor {
                        room: room_id.into(),
                    },
                );
                placed_tables.push(id);
            }
        }
    }

    // Chairs around tables, facing them.
    let mut settings: Vec<Setting> = Vec::new();
    if let Some(chair_asset) = asset_of.get("chair").cloned() {
        let chair_rec = state.scene.assets[&chair_asset].clone();
        let chair_w = chair_rec.bounds[1][0] - chair_rec.bounds[0][0];
        let chair_d = chair_rec.bounds[1][1] - chair_rec.bounds[0][1];
        let tables = placed_tables.clone();
        let per_table = if tables.is_empty() {
            0
        } else {
            (chairs_left as usize).div_ceil(tables.len())
        };
        for table_id in &tables {
            let Some(table) = state.scene.object(table_id).cloned() else {
                continue;
            };
            let trec = state.scene.assets[&table.asset].clone();
            let [tlo, thi] = trec.bounds;
            let (tw, td) = (thi[0] - tlo[0], thi[1] - tlo[1]);
            // Seats: along both long sides (x), then the two ends.
            let per_side = ((tw / (chair_w + 0.15)).floor() as usize).max(1);
            let mut seats: Vec<Pose> = Vec::new();
            for side in [-1.0, 1.0] {
                for i in 0..per_side {
                    let x = -tw / 2.0 + tw * (i as f64 + 0.5) / per_side as f64;
                    let y = side * (td / 2.0 + chair_d / 2.0 + 0.04);
                    // Chair +Y faces the table.
                    let yaw = if side < 0.0 {
                        0.0
                    } else {
                        std::f64::consts::PI
                    };
                    seats.push(Pose::from_xyz_yaw(x, y, 0.0, yaw));
                }
            }
            if td >= chair_w + 0.1 {
                for side in [-1.0, 1.0] {
                    let x = side * (tw / 2.0 + chair_d / 2.0 + 0.04);
                    let yaw = if side < 0.0 {
                        -std::f64::consts::FRAC_PI_2
                    } else {
                        std::f64::consts::FRAC_PI_2
                    };
                    seats.push(Pose::from_xyz_yaw(x, 0.0, 0.0, yaw));
                }
            }
            // Fill sides alternately so two chairs face each other.
            let order: Vec<usize> = (0..per_side)
                .flat_map(|i| [i, per_side + i])
                .chain(2 * per_side..seats.len())
                .collect();
            let mut here = 0;
            for idx in order {
                if chairs_left == 0 || here >= per_table {
                    break;
                }
                let pose = table.world_from_object.compose(&seats[idx]);
                let fp = Footprint::of(&chair_rec, &pose);
                if !fp.inside(&room.floor_polygon) || occupied.iter().any(|o| o.overlaps(&fp, 0.02))
                {
                    continue;
                }
                occupied.push(fp);
                state.add_object(
                    "chair",
                    ObjectKind::Furniture,
                    room_id,
                    &chair_asset,
                    pose,
                    Support::Floor {
                        room: room_id.into(),
                    },
                );
                let seat = seats[idx];
                let facing = seat.transform_vector(&nalgebra::Vector3::y());
                let reach = chair_d / 2.0 + 0.04;
                settings.push(Setting {
                    table: table_id.clone(),
                    edge: [
                        seat.translation().x + facing.x * reach,
                        seat.translation().y + facing.y * reach,
                    ],
                    facing: [facing.x, facing.y],
                });
                chairs_left -= 1;
                here += 1;
            }
        }
    }

    // Wall furniture: shelves, cabinets, then chairs that found no table.
    let mut wall_items: Vec<(String, u32)> = Vec::new();
    for cat in ["shelf", "cabinet"] {
        if count(cat) > 0 {
            wall_items.push((cat.to_string(), count(cat)));
        }
    }
    if chairs_left > 0 {
        wall_items.push(("chair".to_string(), chairs_left));
    }
    for (cat, n) in wall_items {
        let asset_id = asset_of[&cat].clone();
        let rec = state.scene.assets[&asset_id].clone();
        let width = rec.bounds[1][0] - rec.bounds[0][0];
        let mut placed = 0;
        'items: for _ in 0..n {
            for wall in &room.walls {
                let len = wall.length();
                let mut along = wall.thickness + width / 2.0;
                while along <= len - wall.thickness - width / 2.0 {
                    let pose = against_wall(wall, &rec, along, 0.01);
                    let fp = Footprint::of(&rec, &pose);
                    if fp.inside(&room.floor_polygon)
                        && !occupied
                            .iter()
                            .chain(&table_zones)
                            .any(|o| o.overlaps(&fp, FURNITURE_GAP))
                    {
                        occupied.push(fp);
                        state.add_object(
                            &cat,
                            ObjectKind::Furniture,
                            room_id,
                            &asset_id,
                            pose,
                            Support::Floor {
                                room: room_id.into(),
                            },
                        );
                        placed += 1;
                        continue 'items;
                    }
                    along += 0.05;
                }
            }
            report
                .notes
                .push(format!("no free wall space for another {cat}"));
            break;
        }
        let _ = placed;
    }

    place_small_objects(
        state,
        room_id,
        &requested,
        &asset_of,
        &settings,
        &mut report,
    );

    for o in state.scene.objects.iter().filter(|o| o.room == room_id) {
        *report.placed.entry(o.category.clone()).or_insert(0) += 1;
    }
    report.placed.remove("room_architecture");
    Ok(report)
}

/// A seat at a table: where the table edge is in front of it and which way the sitter faces,
/// both in the table's frame.
struct Setting {
    table: String,
    edge: [f64; 2],
    facing: [f64; 2],
}

/// A rectangle in a surface's own coordinates (relative to the surface centre).
#[derive(Debug, Clone, Copy)]
struct Rect {
    u: f64,
    v: f64,
    hu: f64,
    hv: f64,
}

impl Rect {
    fn overlaps(&self, o: &Rect, gap: f64) -> bool {
        (self.u - o.u).abs() < self.hu + o.hu + gap && (self.v - o.v).abs() < self.hv + o.hv + gap
    }
}

struct SurfaceSlot {
    parent: String,
    surface: SurfaceRecord,
    world_from_parent: Pose,
    used: Vec<Rect>,
}

impl SurfaceSlot {
    /// First free spot (raster scan from the back-left) for an item of half extents
    /// `(hu, hv)` and height `h`.
    fn find(&self, hu: f64, hv: f64, h: f64) -> Option<Rect> {
        if h > self.surface.clearance - 0.005 {
            return None;
        }
        let (su, sv) = (
            self.surface.size[0] / 2.0 - 0.01,
            self.surface.size[1] / 2.0 - 0.01,
        );
        if hu > su || hv > sv {
            return None;
        }
        let step = 0.01;
        let mut v = -sv + hv;
        while v <= sv - hv + 1e-9 {
            let mut u = -su + hu;
            while u <= su - hu + 1e-9 {
                let r = Rect { u, v, hu, hv };
                if !self.used.iter().any(|o| o.overlaps(&r, 0.01)) {
                    return Some(r);
                }
                u += step;
            }
            v += step;
        }
        None
    }
}

fn place_small_objects(
    state: &mut SceneState,
    room_id: &str,
    requested: &BTreeMap<String, u32>,
    asset_of: &BTreeMap<String, String>,
    settings: &[Setting],
    report: &mut StarterReport,
) {
    // Every furniture surface of the room, shelves before tops.
    let mut slots: Vec<SurfaceSlot> = Vec::new();
    for o in
        state.scene.objects.iter().filter(|o| {
            o.room == room_id && o.kind == ObjectKind::Furniture && o.category != "chair"
        })
    {
        let rec = &state.scene.assets[&o.asset];
        for s in &rec.surfaces {
            // Cabinet interiors stay empty until something asks for them.
            if o.category == "cabinet" && s.id != "top" {
                continue;
            }
            slots.push(SurfaceSlot {
                parent: o.id.clone(),
                surface: s.clone(),
                world_from_parent: o.world_from_object,
                used: Vec::new(),
            });
        }
    }
    let mut left: BTreeMap<String, u32> = requested
        .iter()
        .filter(|(c, _)| procedural::prior(c).is_some_and(|p| p.support == SupportClass::Surface))
        .map(|(c, n)| (c.clone(), *n))
        .collect();

    // Place settings: a plate in front of each chair, a mug to its right.
    for setting in settings {
        let Some(slot_idx) = slots
            .iter()
            .position(|s| s.parent == setting.table && s.surface.id == "top")
        else {
            continue;
        };
        let f = setting.facing;
        let right = [f[1], -f[0]];
        for (cat, offset_in, offset_right) in [("plate", 0.2, 0.0), ("mug", 0.12, 0.2)] {
            if left.get(cat).copied().unwrap_or(0) == 0 {
                continue;
            }
            let asset_id = &asset_of[cat];
            let rec = &state.scene.assets[asset_id];
            let [lo, hi] = rec.bounds;
            let half = ((hi[0] - lo[0]) / 2.0).max((hi[1] - lo[1]) / 2.0);
            let slot = &slots[slot_idx];
            let p = [
                setting.edge[0] + f[0] * offset_in + right[0] * offset_right,
                setting.edge[1] + f[1] * offset_in + right[1] * offset_right,
            ];
            let r = Rect {
                u: p[0] - slot.surface.center[0],
                v: p[1] - slot.surface.center[1],
                hu: half,
                hv: half,
            };
            let (su, sv) = (slot.surface.size[0] / 2.0, slot.surface.size[1] / 2.0);
            if r.u.abs() + r.hu > su
                || r.v.abs() + r.hv > sv
                || slot.used.iter().any(|o| o.overlaps(&r, 0.01))
            {
                continue;
            }
            let pose = on_surface(
                &slot.world_from_parent,
                &slot.surface,
                r.u,
                r.v,
                0.0,
                SURFACE_LIFT,
            );
            let parent = slot.parent.clone();
            let surface = slot.surface.id.clone();
            slots[slot_idx].used.push(r);
            state.add_object(
                cat,
                ObjectKind::Manipuland,
                room_id,
                asset_id,
                pose,
                Support::Object { parent, surface },
            );
            if let Some(n) = left.get_mut(cat) {
                *n -= 1;
            }
        }
    }

    // Everything else: first free spot, books preferring shelves, others preferring tops.
    for (cat, n) in left.clone() {
        let asset_id = asset_of[&cat].clone();
        let rec = state.scene.assets[&asset_id].clone();
        let [lo, hi] = rec.bounds;
        let (hu, hv, h) = ((hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0, hi[2] - lo[2]);
        let mut order: Vec<usize> = (0..slots.len()).collect();
        let prefers_shelf = cat == "book";
        order.sort_by_key(|&i| {
            let is_shelf = slots[i].surface.id.starts_with("shelf");
            (is_shelf != prefers_shelf, i)
        });
        let mut placed = 0;
        'item: for _ in 0..n {
            for &i in &order {
                if let Some(r) = slots[i].find(hu, hv, h) {
                    let slot = &slots[i];
                    let pose = on_surface(
                        &slot.world_from_parent,
                        &slot.surface,
                        r.u,
                        r.v,
                        0.0,
                        SURFACE_LIFT,
                    );
                    let (parent, surface) = (slot.parent.clone(), slot.surface.id.clone());
                    slots[i].used.push(r);
                    state.add_object(
                        &cat,
                        ObjectKind::Manipuland,
                        room_id,
                        &asset_id,
                        pose,
                        Support::Object { parent, surface },
                    );
                    placed += 1;
                    continue 'item;
                }
            }
            break;
        }
        if placed < n {
            report.notes.push(format!(
                "placed {placed} of {n} {cat} objects: no more free surface area"
            ));
        }
    }
}
