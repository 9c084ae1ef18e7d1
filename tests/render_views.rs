//! The views on small known scenes: the plan puts objects where they are and labels them, the
//! corner views see into the room through the cut-away walls, asset previews fill their
//! frame, contact sheets lay images out, and everything is byte-for-byte repeatable.

use scenesmith::assets::architecture::build_room_asset;
use scenesmith::assets::procedural::{self, AssetRequest};
use scenesmith::assets::{Asset, LinkBuilder, material};
use scenesmith::render::image::Image;
use scenesmith::render::plan::{PlanOptions, plan_view};
use scenesmith::render::scene::{RenderScene, Role};
use scenesmith::render::views::{RoomViewOptions, room_views};
use scenesmith::render::{asset_preview, contact_sheet, write_standard_views};
use scenesmith::scene::rectangle_walls;
use scenesmith::scene::{
    ObjectKind, Opening, OpeningKind, Pose, Room, Scene, SceneObject, Support,
};
use scenesmith::state::SceneState;

fn red_box_asset() -> Asset {
    let mut b = LinkBuilder::new(
        "body",
        Pose::IDENTITY,
        material::material_or_default("wood"),
    );
    b.add_box([0.0, 0.0, 0.4], [0.8, 0.8, 0.8], [0.85, 0.03, 0.03])
        .unwrap();
    Asset {
        id: "red_box_test".into(),
        category: "box".into(),
        material: "wood".into(),
        links: vec![b.finish().unwrap()],
        joints: vec![],
        surfaces: vec![],
        is_static: false,
        provenance: serde_json::json!({}),
    }
}

/// A 4 x 3 m room (clear floor from the origin) with a door and a window, and a red box
/// centred at (1, 2).
fn test_state() -> SceneState {
    let mut walls = rectangle_walls("room_0", [0.0, 0.0], 4.0, 3.0, 0.12);
    walls[0].openings.push(Opening {
        id: "door_0".into(),
        kind: OpeningKind::Door,
        center: 3.0,
        width: 0.9,
        bottom: 0.0,
        height: 2.1,
    });
    walls[2].openings.push(Opening {
        id: "window_0".into(),
        kind: OpeningKind::Window,
        center: 2.0,
        width: 1.2,
        bottom: 0.9,
        height: 1.2,
    });
    let room = Room {
        id: "room_0".into(),
        room_type: "study".into(),
        label: None,
        prompt: String::new(),
        floor_polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]],
        wall_height: 2.6,
        walls,
        floor_material: "oak".into(),
        wall_material: "plaster".into(),
    };
    let arch = build_room_asset(&room, "room_0_architecture").unwrap();
    let mut scene = Scene::new("a study with a red box", 0, "test");
    scene.rooms.push(room);
    let mut state = SceneState::new(scene);
    let arch_id = state.insert_asset(arch);
    state.scene.objects.push(SceneObject {
        id: "room_0_architecture".into(),
        category: "room_architecture".into(),
        name: None,
        planned: None,
        kind: ObjectKind::Architecture,
        room: "room_0".into(),
        asset: arch_id,
        world_from_object: Pose::IDENTITY,
        support: Support::World,
        welded: true,
        joint_positions: Default::default(),
    });
    let box_id = state.insert_asset(red_box_asset());
    state.add_object(
        "box",
        ObjectKind::Furniture,
        "room_0",
        &box_id,
        Pose::from_xyz(1.0, 2.0, 0.0),
        Support::Floor {
            room: "room_0".into(),
        },
    );
    state
}

fn is_red(p: [u8; 4]) -> bool {
    p[0] > 120 && p[1] < 60 && p[2] < 60
}

fn count(img: &Image, f: impl Fn([u8; 4]) -> bool) -> usize {
    img.rgba
        .chunks_exact(4)
        .filter(|p| f([p[0], p[1], p[2], p[3]]))
        .count()
}

#[test]
fn plan_shows_the_box_where_it_stands_with_dark_walls_and_its_label() {
    let state = test_state();
    let rs = RenderScene::from_state(&state).unwrap();
    let opts = PlanOptions::default();
    let img = plan_view(&rs, &opts).unwrap();
    // Bounds: walls reach 0.12 m beyond the clear floor, plus the margin on every side.
    let m = opts.margin_m + 0.12;
    let ppm = f64::from(img.width) / (4.0 + 2.0 * m);
    assert!((ppm - opts.max_px_per_m).abs() < 1.0, "{ppm}");
    let to_px = |x: f64, y: f64| -> (u32, u32) {
        (
            ((x + m) * ppm).round() as u32,
            (f64::from(img.height) - (y + m) * ppm).round() as u32,
        )
    };
    // The box covers x 0.6..1.4, y 1.6..2.4: red near its corners (the label sits at its centre).
    for (x, y) in [(0.7, 1.7), (1.3, 1.7), (0.7, 2.3), (1.3, 2.3)] {
        let (px, py) = to_px(x, y);
        assert!(
            is_red(img.pixel(px, py).unwrap()),
            "({x}, {y}) -> ({px}, {py})"
        );
    }
    let (px, py) = to_px(2.5, 1.0);
    assert!(!is_red(img.pixel(px, py).unwrap()));
    // Walls are dark: the middle of the east wall (x = 4.06).
    let (px, py) = to_px(4.06, 1.5);
    let w = img.pixel(px, py).unwrap();
    assert!(w[0] < 70 && w[1] < 70 && w[2] < 70, "wall {w:?}");
    // The window across the north wall is light blue.
    let (px, py) = to_px(2.0, 3.025);
    let g = img.pixel(px, py).unwrap();
    assert!(g[2] > 200 && g[0] < 220, "window {g:?}");
    // The box's label: dark text on a light box around the box centre.
    let (cx, cy) = to_px(1.0, 2.0);
    let (mut ink, mut paper) = (0, 0);
    for y in cy - 10..cy + 10 {
        for x in cx - 40..cx + 40 {
            let p = img.pixel(x, y).unwrap();
            if p[0] < 110 && p[1] < 110 && p[2] < 110 {
                ink += 1;
            }
            if p[..3].iter().all(|&c| c > 215) {
                paper += 1;
            }
        }
    }
    assert!(ink > 25 && paper > 150, "label ink {ink}, box {paper}");
}

#[test]
fn corner_views_see_the_box_through_cut_away_walls() {
    let state = test_state();
    let rs = RenderScene::from_state(&state).unwrap();
    let opts = RoomViewOptions {
        width: 320,
        height: 240,
        ..Default::default()
    };
    let views = room_views(&rs, 0, &opts).unwrap();
    assert_eq!(views.len(), 4);
    for (name, img) in &views {
        assert!(name.starts_with("room_0_view_"), "{name}");
        assert_eq!((img.width, img.height), (320, 240));
        let red = count(img, is_red);
        assert!(
            red > 300,
            "{name}: only {red} red pixels: the box is hidden"
        );
    }
    // The walls exist and are not all cut: the architecture has four wall meshes.
    let walls = rs
        .meshes
        .iter()
        .filter(|m| matches!(m.role, Role::Wall { .. }))
        .count();
    assert!(walls >= 4);
}

#[test]
fn standard_views_are_written_and_repeatable() {
    let state = test_state();
    let dir = tempfile::tempdir().unwrap();
    let files = write_standard_views(dir.path(), &state).unwrap();
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "top.png",
            "room_0_view_0.png",
            "room_0_view_1.png",
            "room_0_view_2.png",
            "room_0_view_3.png"
        ]
    );
    for f in &files {
        assert!(f.starts_with(dir.path().join("renders")));
        let bytes = std::fs::read(f).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
    }
    let again = tempfile::tempdir().unwrap();
    let files2 = write_standard_views(again.path(), &state).unwrap();
    for (a, b) in files.iter().zip(&files2) {
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{}",
            a.display()
        );
    }
}

#[test]
fn asset_preview_fills_the_frame_on_a_neutral_background() {
    let chair = procedural::build(&AssetRequest::new("chair", 3)).unwrap();
    let img = asset_preview(&chair, 240, 180).unwrap();
    assert_eq!((img.width, img.height), (240, 180));
    let bg = img.pixel(0, 0).unwrap();
    assert!(
        bg[0] == bg[1] || (i32::from(bg[0]) - i32::from(bg[2])).abs() < 6,
        "{bg:?}"
    );
    // Non-background pixels span most of one image axis and are roughly centred.
    let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
    for y in 0..img.height {
        for x in 0..img.width {
            if img.pixel(x, y).unwrap() != bg {
                x0 = x0.min(x);
                y0 = y0.min(y);
                x1 = x1.max(x);
                y1 = y1.max(y);
            }
        }
    }
    let (w, h) = (f64::from(x1 - x0), f64::from(y1 - y0));
    assert!(
        w / 240.0 > 0.7 || h / 180.0 > 0.7,
        "object box {x0},{y0}..{x1},{y1}"
    );
    let (cx, cy) = (f64::from(x0 + x1) / 2.0, f64::from(y0 + y1) / 2.0);
    assert!(
        (cx - 120.0).abs() < 15.0 && (cy - 90.0).abs() < 15.0,
        "centre ({cx}, {cy})"
    );
    assert!(asset_preview(&chair, 0, 10).is_err());
}

#[test]
fn contact_sheet_lays_out_images_with_captions() {
    let a = Image::new(100, 50, [200, 30, 30, 255]);
    let b = Image::new(80, 60, [30, 30, 200, 255]);
    let c = Image::new(100, 60, [30, 200, 30, 255]);
    let sheet = contact_sheet(
        &[("red".into(), a), ("blue".into(), b), ("green".into(), c)],
        2,
    )
    .unwrap();
    // Two columns of 100-px cells, two rows of 60-px cells plus captions.
    assert!(sheet.width >= 200 && sheet.width < 260, "{}", sheet.width);
    assert!(sheet.height > 120 && sheet.height < 220, "{}", sheet.height);
    let find = |rgb: [u8; 3]| count(&sheet, |p| p[..3] == rgb);
    assert_eq!(find([200, 30, 30]), 100 * 50);
    assert_eq!(find([30, 30, 200]), 80 * 60);
    assert_eq!(find([30, 200, 30]), 100 * 60);
    // Captions are dark text on white.
    assert!(count(&sheet, |p| p[0] < 80 && p[1] < 80 && p[2] < 80) > 50);
    assert!(contact_sheet(&[], 3).is_err());
}

/// Two rooms side by side: room_0 as in [`test_state`], room_1 east of it (walls back to
/// back), with a green box.
fn two_room_state() -> SceneState {
    let mut state = test_state();
    let walls = rectangle_walls("room_1", [4.24, 0.0], 3.0, 3.0, 0.12);
    let room = Room {
        id: "room_1".into(),
        room_type: "hall".into(),
        label: None,
        prompt: String::new(),
        floor_polygon: vec![[4.24, 0.0], [7.24, 0.0], [7.24, 3.0], [4.24, 3.0]],
        wall_height: 2.6,
        walls,
        floor_material: "oak".into(),
        wall_material: "plaster".into(),
    };
    let arch = build_room_asset(&room, "room_1_architecture").unwrap();
    state.scene.rooms.push(room);
    let arch_id = state.insert_asset(arch);
    state.scene.objects.push(SceneObject {
        id: "room_1_architecture".into(),
        category: "room_architecture".into(),
        name: None,
        planned: None,
        kind: ObjectKind::Architecture,
        room: "room_1".into(),
        asset: arch_id,
        world_from_object: Pose::IDENTITY,
        support: Support::World,
        welded: true,
        joint_positions: Default::default(),
    });
    let mut green = red_box_asset();
    green.id = "green_box_test".into();
    for v in &mut green.links[0].visuals {
        v.color = [0.03, 0.7, 0.05, 1.0];
    }
    let id = state.insert_asset(green);
    state.add_object(
        "box",
        ObjectKind::Furniture,
        "room_1",
        &id,
        Pose::from_xyz(5.7, 1.5, 0.0),
        Support::Floor {
            room: "room_1".into(),
        },
    );
    state
}

fn is_green(p: [u8; 4]) -> bool {
    p[1] > 120 && p[0] < 90 && p[2] < 90
}

#[test]
fn each_room_view_shows_its_own_room_and_the_plan_shows_both() {
    let state = two_room_state();
    let rs = RenderScene::from_state(&state).unwrap();
    let opts = RoomViewOptions {
        width: 320,
        height: 240,
        labels: false,
        ..Default::default()
    };
    for (room, own, other) in [
        (
            0,
            is_red as fn([u8; 4]) -> bool,
            is_green as fn([u8; 4]) -> bool,
        ),
        (1, is_green, is_red),
    ] {
        let views = room_views(&rs, room, &opts).unwrap();
        assert_eq!(views.len(), 4);
        for (name, img) in &views {
            assert!(name.starts_with(&format!("room_{room}_view_")), "{name}");
            assert!(count(img, own) > 300, "{name}: its own box is not visible");
            assert_eq!(count(img, other), 0, "{name}: shows the other room's box");
        }
    }
    let plan = plan_view(&rs, &PlanOptions::default()).unwrap();
    assert!(count(&plan, is_red) > 1000 && count(&plan, is_green) > 1000);
    assert!(plan.width > plan.height, "{}x{}", plan.width, plan.height);
}

#[test]
fn room_views_by_id_and_top_view_from_a_state() {
    let state = test_state();
    let opts = RoomViewOptions {
        width: 160,
        height: 120,
        labels: false,
        ..Default::default()
    };
    let views = scenesmith::render::room_views_of(&state, "room_0", &opts).unwrap();
    assert_eq!(views.len(), 4);
    let err = scenesmith::render::room_views_of(&state, "attic_9", &opts).unwrap_err();
    assert!(err.to_string().contains("attic_9"), "{err}");
    let top = scenesmith::render::top_view(&state).unwrap();
    assert!(count(&top, is_red) > 1000);
}
