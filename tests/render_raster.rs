//! The rasterizer against hand-computed expectations: where geometry lands, what colour it
//! gets, which surface wins the depth test, textures, labels, and byte-for-byte determinism.

use std::sync::Arc;

use scenesmith::assets::Texture;
use scenesmith::geometry::mesh::box_mesh;
use scenesmith::render::Camera;
use scenesmith::render::image::{Image, linear_to_srgb_u8};
use scenesmith::render::labels::{self, Label};
use scenesmith::render::raster::{DrawItem, Lighting, RasterOptions, render};
use scenesmith::render::scene::{RenderMesh, Role};
use scenesmith::scene::Pose;

fn box_at(center: [f64; 3], size: [f64; 3], color: [f64; 3], object: usize) -> RenderMesh {
    let mut m = RenderMesh::from_trimesh(
        &box_mesh(center, size),
        &Pose::IDENTITY,
        [color[0], color[1], color[2], 1.0],
        None,
    );
    m.object = Some(object);
    m
}

fn px(img: &Image, x: u32, y: u32) -> [u8; 4] {
    img.pixel(x, y).unwrap()
}

/// sRGB byte of a lit surface: intensity from the default lights for a face with normal
/// `n`, seen along `view` (both unit).
fn expected_lit(base: f32, n: [f32; 3], view: [f32; 3], l: &Lighting) -> u8 {
    let k = l.key_dir;
    let kn = (k[0] * k[0] + k[1] * k[1] + k[2] * k[2]).sqrt();
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let hemi = 0.5 + 0.5 * n[2];
    let i = l.ambient_ground
        + (l.ambient_sky - l.ambient_ground) * hemi
        + l.key * (dot(n, k) / kn).max(0.0)
        + l.fill * dot(n, view).max(0.0);
    linear_to_srgb_u8(base * i)
}

#[test]
fn red_box_on_grey_floor_lands_where_and_how_expected_top_down() {
    let floor = box_at([0.0, 0.0, -0.05], [4.0, 4.0, 0.1], [0.5, 0.5, 0.5], 0);
    // Box footprint x in [0.5, 1.0], y in [-0.5, 0.0]; 0.4 m tall.
    let red = box_at([0.75, -0.25, 0.2], [0.5, 0.5, 0.4], [0.8, 0.05, 0.05], 1);
    let cam = Camera::top_down([-2.0, -2.0], [2.0, 2.0], 5.0).unwrap();
    let mut opts = RasterOptions::new(400, 400);
    opts.edges = false;
    let out = render(
        &[DrawItem::new(&floor), DrawItem::new(&red)],
        &cam,
        &opts,
        2,
    )
    .unwrap();
    let img = &out.image;
    // 100 px per metre, x = 0 at column 200, y = 0 at row 200 (+y up).
    let l = Lighting::default();
    let up = [0.0, 0.0, 1.0];
    let red_top = [
        expected_lit(0.8, up, up, &l),
        expected_lit(0.05, up, up, &l),
        expected_lit(0.05, up, up, &l),
    ];
    let grey = expected_lit(0.5, up, up, &l);
    for (x, y) in [(255, 205), (295, 245), (252, 202), (298, 248), (275, 225)] {
        let p = px(img, x, y);
        for c in 0..3 {
            assert!(
                (i32::from(p[c]) - i32::from(red_top[c])).abs() <= 1,
                "({x}, {y}): {p:?} vs {red_top:?}"
            );
        }
    }
    for (x, y) in [
        (247, 225),
        (303, 225),
        (275, 197),
        (275, 253),
        (100, 100),
        (300, 300),
    ] {
        let p = px(img, x, y);
        assert!(
            p[..3]
                .iter()
                .all(|&c| (i32::from(c) - i32::from(grey)).abs() <= 1),
            "({x}, {y}): {p:?}, expected grey {grey}"
        );
    }
    // Coverage: the box's top is 50 x 50 pixels.
    let cov = out.coverage[1];
    assert!((cov.pixels - 2500.0).abs() < 60.0, "{cov:?}");
    assert!((cov.centroid[0] - 275.0).abs() < 0.6 && (cov.centroid[1] - 225.0).abs() < 0.6);
}

#[test]
fn perspective_camera_maps_a_known_point_to_the_expected_pixel() {
    // 90 degree vertical field of view: at depth 5 m, half the image height spans 5 m.
    let cam = Camera::look_at([0.0, -5.0, 1.5], [0.0, 0.0, 1.5], [0.0, 0.0, 1.0], 90.0).unwrap();
    let (w, h) = (320u32, 240u32);
    let p = cam.project([1.0, 0.0, 2.5], w, h).unwrap();
    // x = 160 + (1 / 5) * 120, y = 120 - (1 / 5) * 120.
    assert!(
        (p[0] - 184.0).abs() < 1e-9 && (p[1] - 96.0).abs() < 1e-9,
        "{p:?}"
    );
    assert!((p[2] - 5.0).abs() < 1e-12);
    // A small cube there renders centred on that pixel.
    let cube = box_at([1.0, 0.0, 2.5], [0.1, 0.1, 0.1], [0.9, 0.9, 0.1], 0);
    let mut opts = RasterOptions::new(w, h);
    opts.edges = false;
    let out = render(&[DrawItem::new(&cube)], &cam, &opts, 1).unwrap();
    let c = out.coverage[0];
    assert!(c.pixels > 4.0, "{c:?}");
    assert!(
        (c.centroid[0] - 184.0).abs() < 0.8 && (c.centroid[1] - 96.0).abs() < 0.8,
        "{c:?}"
    );
    let mid = px(&out.image, 184, 96);
    assert!(mid[0] > 150 && mid[2] < 100, "{mid:?}");
}

#[test]
fn the_nearer_object_hides_the_farther_one_in_either_draw_order() {
    let cam = Camera::look_at([0.0, -4.0, 0.5], [0.0, 0.0, 0.5], [0.0, 0.0, 1.0], 50.0).unwrap();
    let near = box_at([0.0, -1.0, 0.5], [0.6, 0.2, 0.6], [0.9, 0.05, 0.05], 0);
    let far = box_at([0.0, 1.0, 0.5], [1.5, 0.2, 1.5], [0.05, 0.05, 0.9], 1);
    let opts = RasterOptions::new(200, 150);
    for items in [
        [DrawItem::new(&near), DrawItem::new(&far)],
        [DrawItem::new(&far), DrawItem::new(&near)],
    ] {
        let out = render(&items, &cam, &opts, 2).unwrap();
        let centre = px(&out.image, 100, 75);
        assert!(centre[0] > 150 && centre[2] < 60, "centre {centre:?}");
        // The far box shows around the near one.
        let side = px(&out.image, 121, 75);
        assert!(side[2] > 150 && side[0] < 60, "side {side:?}");
        assert!(out.coverage[0].pixels > 500.0 && out.coverage[1].pixels > 500.0);
    }
}

#[test]
fn a_textured_quad_shows_its_texture_repeated() {
    // 4x4 texels in 2x2 blocks: red, green / blue, white (top row first).
    let colors = [[255u8, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255]];
    let mut rgba = Vec::new();
    for y in 0..4 {
        for x in 0..4 {
            let c = colors[(y / 2) * 2 + x / 2];
            rgba.extend_from_slice(&[c[0], c[1], c[2], 255]);
        }
    }
    let tex = Texture {
        name: "checker".into(),
        width: 4,
        height: 4,
        rgba: Arc::new(rgba),
    };
    // Quad x, y in [-1, 1] at z = 0; uv spans 0..2, so the texture repeats twice each way.
    let quad = RenderMesh {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: vec![[0.0, 2.0], [2.0, 2.0], [2.0, 0.0], [0.0, 0.0]],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        color: [1.0, 1.0, 1.0],
        texture: Some(tex),
        object: Some(0),
        role: Role::Object,
    };
    let cam = Camera::top_down([-1.0, -1.0], [1.0, 1.0], 3.0).unwrap();
    let mut opts = RasterOptions::new(160, 160);
    opts.edges = false;
    let item = DrawItem {
        unlit: true,
        ..DrawItem::new(&quad)
    };
    let out = render(&[item], &cam, &opts, 1).unwrap();
    // Each texture copy covers 80 x 80 px; its blocks are 40 x 40 px. Sample block centres.
    for (ox, oy) in [(0u32, 0u32), (80, 0), (0, 80), (80, 80)] {
        for (k, c) in colors.iter().enumerate() {
            let (bx, by) = ((k % 2) as u32, (k / 2) as u32);
            let p = px(&out.image, ox + bx * 40 + 20, oy + by * 40 + 20);
            assert_eq!(&p[..3], c, "copy ({ox}, {oy}) block {k}");
        }
    }
}

#[test]
fn a_thin_single_sided_part_is_lit_from_behind_too() {
    // One triangle pair facing +z, seen from below: two-sided lighting keeps it bright.
    let quad = RenderMesh {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: vec![],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        color: [0.6, 0.6, 0.6],
        texture: None,
        object: Some(0),
        role: Role::Object,
    };
    let above = Camera::look_at([0.0, -0.5, 3.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 40.0).unwrap();
    let below = Camera::look_at([0.0, -0.5, -3.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 40.0).unwrap();
    let mut opts = RasterOptions::new(64, 64);
    opts.edges = false;
    let a = render(&[DrawItem::new(&quad)], &above, &opts, 1).unwrap();
    let b = render(&[DrawItem::new(&quad)], &below, &opts, 1).unwrap();
    let (pa, pb) = (px(&a.image, 32, 32), px(&b.image, 32, 32));
    // From below only the hemisphere ambient differs (ground vs sky) and the key light is
    // behind; the fill from the eye still lights the face.
    assert!(pb[0] > 90, "seen from below: {pb:?} (from above {pa:?})");
}

#[test]
fn labels_draw_ink_inside_their_box_and_nothing_elsewhere() {
    let mut img = Image::new(200, 100, [90, 120, 90, 255]);
    let before = img.clone();
    let ls = vec![Label {
        text: "table_0".into(),
        anchor: [100.0, 50.0],
        priority: 1.0,
        size_px: 14.0,
        target: None,
    }];
    let placed = labels::place(&ls, 200, 100, &[]).unwrap();
    let r = placed[0].rect;
    assert!(
        r[0] < 100.0 && r[2] > 100.0 && r[1] < 50.0 && r[3] > 50.0,
        "{r:?}"
    );
    labels::draw(&mut img, &ls, &placed).unwrap();
    let mut dark = 0;
    for y in 0..100u32 {
        for x in 0..200u32 {
            let (p, q) = (px(&img, x, y), px(&before, x, y));
            let inside = f64::from(x) >= r[0].floor() - 1.0
                && f64::from(x) <= r[2].ceil() + 1.0
                && f64::from(y) >= r[1].floor() - 1.0
                && f64::from(y) <= r[3].ceil() + 1.0;
            if !inside {
                assert_eq!(p, q, "pixel ({x}, {y}) outside the label changed");
            } else if p[0] < 60 && p[1] < 60 {
                dark += 1;
            }
        }
    }
    // Text ink (dark on a light box) where the label is.
    assert!(dark > 40, "{dark} dark pixels");
}

#[test]
fn the_same_input_gives_the_same_png_bytes() {
    let floor = box_at([0.0, 0.0, -0.05], [4.0, 4.0, 0.1], [0.5, 0.5, 0.5], 0);
    let a = box_at([0.3, 0.2, 0.4], [0.5, 0.7, 0.8], [0.6, 0.4, 0.2], 1);
    let cam = Camera::look_at([3.0, -3.0, 2.0], [0.0, 0.0, 0.3], [0.0, 0.0, 1.0], 45.0).unwrap();
    let opts = RasterOptions::new(300, 200);
    let items = [DrawItem::new(&floor), DrawItem::new(&a)];
    let one = render(&items, &cam, &opts, 2)
        .unwrap()
        .image
        .encode_png()
        .unwrap();
    let two = render(&items, &cam, &opts, 2)
        .unwrap()
        .image
        .encode_png()
        .unwrap();
    assert_eq!(one, two);
    assert_eq!(&one[1..4], b"PNG");
}

#[test]
fn bad_sizes_and_cameras_are_errors() {
    let cam = Camera::top_down([0.0, 0.0], [1.0, 1.0], 1.0).unwrap();
    assert!(render(&[], &cam, &RasterOptions::new(0, 10), 0).is_err());
    assert!(render(&[], &cam, &RasterOptions::new(100_000, 10), 0).is_err());
    assert!(Camera::look_at([0.0; 3], [0.0; 3], [0.0, 0.0, 1.0], 60.0).is_err());
    assert!(Camera::look_at([0.0; 3], [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], 60.0).is_err());
    assert!(Camera::look_at([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.0).is_err());
}

#[test]
fn the_floor_is_darker_under_furniture() {
    use scenesmith::render::raster::render_with_shadow;
    use scenesmith::render::shadow::FloorShadow;
    let floor = box_at([0.0, 0.0, -0.05], [4.0, 4.0, 0.1], [0.6, 0.6, 0.6], 0);
    let table_top = box_at([0.5, 0.5, 0.72], [1.0, 0.8, 0.04], [0.5, 0.3, 0.2], 1);
    let shadow = FloorShadow::build(
        &[DrawItem::new(&table_top)],
        [-2.0, -2.0],
        [2.0, 2.0],
        0.0,
        0.02,
        0.1,
        0.5,
    )
    .unwrap();
    let cam = Camera::top_down([-2.0, -2.0], [2.0, 2.0], 5.0).unwrap();
    let mut opts = RasterOptions::new(200, 200);
    opts.edges = false;
    // Only the floor is drawn, so the shadow under the (undrawn) table top is in view.
    let item = DrawItem {
        receives_shadow: true,
        ..DrawItem::new(&floor)
    };
    let out = render_with_shadow(&[item], &cam, &opts, 2, Some(&shadow)).unwrap();
    // 50 px per metre: the table top covers x 0..1, y 0.1..0.9 -> columns 100..150, rows 55..95.
    let under = px(&out.image, 125, 75)[0];
    let open = px(&out.image, 40, 160)[0];
    let plain = render(&[DrawItem::new(&floor)], &cam, &opts, 2).unwrap();
    assert_eq!(
        px(&plain.image, 40, 160)[0],
        open,
        "the open floor is unchanged"
    );
    assert!(
        f32::from(under) < f32::from(open) * 0.85,
        "under {under}, open {open}"
    );
    assert_eq!(px(&plain.image, 125, 75)[0], open);
}
