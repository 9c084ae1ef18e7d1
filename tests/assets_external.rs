//! External asset sources against servers and folders the tests make themselves: an HTTP
//! text-to-3D backend on loopback (a good one, one returning garbage, one failing, one too
//! slow), a local mesh folder with a JSON index, and a user library of articulated URDF and
//! SDFormat models, each through the router as a stage would use them.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpListener;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use scenesmith::assets::VisualPart;
use scenesmith::assets::articulated::library::ArticulatedLibrary;
use scenesmith::assets::articulated::self_collisions;
use scenesmith::assets::external::{ExternalError, HttpBackend, MeshFolder};
use scenesmith::assets::procedural::SupportClass;
use scenesmith::assets::router::{RouteRequest, RouterContext, Stage, Strategy, route};
use scenesmith::formats::gltf::GltfBuilder;
use scenesmith::geometry::mesh;
use scenesmith::physics::protocol::{
    AssetModel, AssetsLoad, AssetsLoadArgs, AssetsPush, AssetsPushArgs,
};

/// A block with a nose on its front (-Y here, which glTF export puts at +Z, the glTF front).
fn nosed_block_glb() -> Vec<u8> {
    let mut m = mesh::box_mesh([0.0, 0.0, 0.5], [0.6, 0.4, 1.0]);
    m.append(&mesh::box_mesh([0.0, -0.25, 0.8], [0.1, 0.1, 0.1]));
    let part = VisualPart {
        name: "body".into(),
        mesh: m,
        color: [0.5, 0.3, 0.2, 1.0],
        texture: None,
    };
    let mut b = GltfBuilder::new_embedded();
    let mesh = b.add_mesh("block", &[part]);
    let node = b.add_node("block", Some(mesh), None, vec![]);
    b.add_root(node);
    b.to_glb()
}

#[derive(Clone, Copy)]
enum Mode {
    Glb,
    Garbage,
    Error,
    Slow,
    /// Announces a 4 GiB model.
    Huge,
    /// Streams 8 MiB with no length, until it closes the connection.
    Endless,
}

/// A one-route HTTP server on loopback; returns its URL and the request bodies it saw.
fn serve(mode: Mode) -> (String, Arc<Mutex<Vec<serde_json::Value>>>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}/generate", listener.local_addr().unwrap());
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    std::thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(mut stream) = stream else { continue };
            let mut reader = BufReader::new(stream.try_clone().unwrap());
            let mut len = 0usize;
            loop {
                let mut line = String::new();
                if reader.read_line(&mut line).unwrap_or(0) == 0 || line == "\r\n" {
                    break;
                }
                if let Some(v) = line.to_ascii_lowercase().strip_prefix("content-length:") {
                    len = v.trim().parse().unwrap_or(0);
                }
            }
            let mut body = vec![0u8; len];
            reader.read_exact(&mut body).unwrap();
            if let Ok(v) = serde_json::from_slice(&body) {
                log.lock().unwrap().push(v);
            }
            match mode {
                Mode::Huge => {
                    let head = "HTTP/1.1 200 OK\r\nContent-Type: model/gltf-binary\r\nContent-Length: 4294967296\r\nConnection: close\r\n\r\n";
                    let _ = stream.write_all(head.as_bytes());
                    let _ = stream.write_all(&[0u8; 1024]);
                    continue;
                }
                Mode::Endless => {
                    let head = "HTTP/1.1 200 OK\r\nContent-Type: model/gltf-binary\r\nConnection: close\r\n\r\n";
                    let _ = stream.write_all(head.as_bytes());
                    for _ in 0..128 {
                        if stream.write_all(&[7u8; 65536]).is_err() {
                            break;
                        }
                    }
                    continue;
                }
                _ => {}
            }
            let (status, ctype, payload): (&str, &str, Vec<u8>) = match mode {
                Mode::Glb => ("200 OK", "model/gltf-binary", nosed_block_glb()),
                Mode::Garbage => (
                    "200 OK",
                    "text/plain",
                    b"hello, this is not a model".to_vec(),
                ),
                Mode::Error => (
                    "500 Internal Server Error",
                    "application/json",
                    br#"{"error": "out of GPU memory"}"#.to_vec(),
                ),
                Mode::Slow => {
                    std::thread::sleep(Duration::from_secs(3));
                    ("200 OK", "model/gltf-binary", nosed_block_glb())
                }
                Mode::Huge | Mode::Endless => unreachable!("answered above"),
            };
            let head = format!(
                "HTTP/1.1 {status}\r\nContent-Type: {ctype}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                payload.len()
            );
            let _ = stream.write_all(head.as_bytes());
            let _ = stream.write_all(&payload);
        }
    });
    (url, seen)
}

fn ctx_with_backend(url: &str, timeout: f64) -> RouterContext {
    let mut ctx = RouterContext::new();
    ctx.backend = Some(HttpBackend::new(url, Duration::from_secs_f64(timeout)));
    ctx
}

#[test]
fn text_to_3d_backend_model_is_canonical_scaled_and_physical() {
    let (url, seen) = serve(Mode::Glb);
    let ctx = ctx_with_backend(&url, 10.0);
    let mut req = RouteRequest::new("an ornate brass sarcophagus", Stage::Furniture, 5);
    req.size = Some([0.9, 0.6, 1.5]);
    let out = route(&req, &ctx).unwrap();
    assert_eq!(out.primary.strategy, Strategy::External);
    assert!(
        out.notes.iter().any(|n| n.contains("external")),
        "{:?}",
        out.notes
    );
    let a = &out.primary.asset;
    let [lo, hi] = a.bounds();
    for (i, want) in [0.9, 0.6, 1.5].iter().enumerate() {
        assert!(
            ((hi[i] - lo[i]) - want).abs() <= 0.1 * want,
            "axis {i}: {:?} {:?}",
            lo,
            hi
        );
    }
    assert!(
        lo[2].abs() < 1e-6 && (lo[0] + hi[0]).abs() < 1e-6,
        "not on the floor, centred"
    );
    // The nose (glTF +Z, the front) now points to +Y: at its height the body reaches further
    // forward than anywhere lower down.
    let verts: Vec<[f64; 3]> = a.links[0]
        .visuals
        .iter()
        .flat_map(|v| v.mesh.positions.iter().copied())
        .collect();
    let h = hi[2];
    let reach = |z0: f64, z1: f64| {
        verts
            .iter()
            .filter(|v| v[2] > z0 * h && v[2] < z1 * h)
            .map(|v| v[1])
            .fold(f64::MIN, f64::max)
    };
    assert!(
        reach(0.72, 0.88) > reach(0.0, 0.6) + 0.05,
        "nose is not in front"
    );
    assert!(a.collision_pieces() >= 1 && a.collision_pieces() <= 128);
    a.validate().unwrap();
    assert_eq!(a.provenance["source"]["kind"], "text_to_3d");
    // The request followed the protocol.
    let body = seen.lock().unwrap()[0].clone();
    assert_eq!(body["protocol"], 1);
    assert_eq!(body["support"], "floor");
    assert_eq!(body["dimensions_m"], serde_json::json!([0.9, 0.6, 1.5]));
    assert!(
        body["description"]
            .as_str()
            .unwrap()
            .contains("sarcophagus")
    );
    // Cached: a second identical request does not reach the server.
    let again = route(&req, &ctx).unwrap();
    assert!(again.cached);
    assert_eq!(seen.lock().unwrap().len(), 1);
}

#[test]
fn garbage_errors_and_timeouts_fall_back_with_the_reason() {
    let (garbage, _) = serve(Mode::Garbage);
    let e = HttpBackend::new(&garbage, Duration::from_secs(5))
        .generate("a thing", SupportClass::Surface, None, 1)
        .unwrap_err();
    assert!(matches!(e, ExternalError::Garbage { .. }), "{e}");
    assert!(
        e.to_string().contains("not a GLB") && e.to_string().contains("hello"),
        "{e}"
    );

    let (failing, _) = serve(Mode::Error);
    let e = HttpBackend::new(&failing, Duration::from_secs(5))
        .generate("a thing", SupportClass::Surface, None, 1)
        .unwrap_err();
    assert!(
        e.to_string().contains("500") && e.to_string().contains("out of GPU memory"),
        "{e}"
    );

    let (slow, _) = serve(Mode::Slow);
    let t0 = std::time::Instant::now();
    let e = HttpBackend::new(&slow, Duration::from_millis(500))
        .generate("a thing", SupportClass::Surface, None, 1)
        .unwrap_err();
    assert!(matches!(e, ExternalError::Timeout { .. }), "{e}");
    assert!(t0.elapsed() < Duration::from_secs(2));

    // A body larger than the limit is refused, announced or not, without reading it all.
    let (huge, _) = serve(Mode::Huge);
    let e = HttpBackend::new(&huge, Duration::from_secs(5))
        .generate("a thing", SupportClass::Surface, None, 1)
        .unwrap_err();
    assert!(e.to_string().contains("exceeds the limit"), "{e}");
    let (endless, _) = serve(Mode::Endless);
    let e = HttpBackend::new(&endless, Duration::from_secs(5))
        .with_max_bytes(1 << 20)
        .generate("a thing", SupportClass::Surface, None, 1)
        .unwrap_err();
    assert!(
        e.to_string().contains("exceeds the limit of 1048576 bytes"),
        "{e}"
    );

    // Through the router: a generic stand-in, and the note says why.
    for url in [&garbage, &slow] {
        let out = route(
            &RouteRequest::new("an alien artifact", Stage::Manipuland, 2),
            &ctx_with_backend(url, 0.5),
        );
        let out = out.unwrap();
        assert_eq!(out.primary.strategy, Strategy::Generic, "{url}");
        let note = out.notes.join(" ");
        assert!(
            note.contains("generic") && note.contains("text-to-3D backend"),
            "{note}"
        );
    }
    // Unreachable backend: the same.
    let out = route(
        &RouteRequest::new("a quantum flux gizmo", Stage::Manipuland, 2),
        &ctx_with_backend("http://127.0.0.1:9/generate", 1.0),
    )
    .unwrap();
    assert_eq!(out.primary.strategy, Strategy::Generic);
}

fn write_obj(path: &Path, scale: f64) {
    // A block 60 x 40 x 100 (file units) with a nose toward +Z (the OBJ front), Y up.
    let mut m = mesh::box_mesh([0.0, 50.0, 0.0], [60.0, 100.0, 40.0]);
    m.append(&mesh::box_mesh([0.0, 80.0, 25.0], [10.0, 10.0, 10.0]));
    let m = m.scaled([scale; 3]);
    std::fs::write(path, scenesmith::geometry::obj::trimesh_to_obj(&m)).unwrap();
}

#[test]
fn mesh_folder_is_searched_imported_and_used_for_unknown_nouns() {
    let dir = tempfile::tempdir().unwrap();
    write_obj(&dir.path().join("sarc.obj"), 1.0);
    write_obj(&dir.path().join("chest.obj"), 0.5);
    std::fs::write(
        dir.path().join("index.json"),
        r#"{"meshes": [
            {"file": "sarc.obj", "name": "sarcophagus", "description": "painted egyptian sarcophagus", "category": "sarcophagus",
             "units": "cm", "up": "+y", "front": "+z", "material": "stone", "dimensions_m": [0.6, 0.4, 1.0], "license": "CC0"},
            {"file": "chest.obj", "name": "small chest", "description": "small wooden chest", "category": "chest",
             "units": "cm", "up": "+y", "front": "+z", "material": "oak", "dimensions_m": [0.3, 0.2, 0.5]}
        ]}"#,
    )
    .unwrap();
    let folder = MeshFolder::open(dir.path()).unwrap();
    let hits = folder.search("egyptian sarcophagus", None, None);
    assert_eq!(hits[0].1.file, "sarc.obj");
    assert!(folder.search("spaceship", None, None).is_empty());
    // Size breaks ties between equally named entries.
    let a = folder
        .import(&hits[0].1.clone(), SupportClass::Floor, None)
        .unwrap();
    let [lo, hi] = a.bounds();
    assert!(
        ((hi[0] - lo[0]) - 0.6).abs() < 1e-6 && ((hi[2] - lo[2]) - 1.0).abs() < 1e-6,
        "{lo:?} {hi:?}"
    );
    assert!(lo[2].abs() < 1e-9);
    // Mass is the stone density times the enclosed volume of the (scaled) mesh.
    let expected = scenesmith::assets::external::import::expected_mass(&a);
    let stone = scenesmith::assets::material::material("stone").unwrap();
    assert!(
        expected > stone.density * 0.15 && (a.mass() - expected).abs() < 1e-6 * expected,
        "mass {} vs {expected}",
        a.mass()
    );
    assert!(a.collision_pieces() <= 128);

    let mut ctx = RouterContext::new();
    ctx.mesh_folder = Some(folder);
    let out = route(
        &RouteRequest::new("a sarcophagus", Stage::Furniture, 1),
        &ctx,
    )
    .unwrap();
    assert_eq!(out.primary.strategy, Strategy::External);
    assert_eq!(
        out.primary.asset.provenance["source"]["kind"],
        "mesh_folder"
    );
    // Known categories keep using the generators unless external sources are preferred.
    let chest = route(&RouteRequest::new("a chest", Stage::Furniture, 1), &ctx).unwrap();
    assert_eq!(chest.primary.strategy, Strategy::Articulated);
    ctx.prefer_external = true;
    let chest = route(
        &RouteRequest::new("a small wooden chest", Stage::Furniture, 1),
        &ctx,
    )
    .unwrap();
    assert_eq!(chest.primary.strategy, Strategy::External);
}

const URDF: &str = r#"<?xml version="1.0"?>
<robot name="cabinet">
  <material name="white"><color rgba="0.9 0.9 0.9 1"/></material>
  <link name="base">
    <inertial><origin xyz="0 0 0.45"/><mass value="20"/><inertia ixx="1.5" ixy="0" ixz="0" iyy="1.5" iyz="0" izz="1.2"/></inertial>
    <visual><origin xyz="0 -0.05 0.45"/><geometry><box size="0.8 0.5 0.9"/></geometry><material name="white"/></visual>
    <collision><origin xyz="-0.39 -0.05 0.45"/><geometry><box size="0.02 0.5 0.9"/></geometry></collision>
    <collision><origin xyz="0.39 -0.05 0.45"/><geometry><box size="0.02 0.5 0.9"/></geometry></collision>
    <collision><origin xyz="0 -0.05 0.01"/><geometry><box size="0.76 0.5 0.02"/></geometry></collision>
    <collision><origin xyz="0 -0.05 0.89"/><geometry><box size="0.76 0.5 0.02"/></geometry></collision>
    <collision><origin xyz="0 -0.29 0.45"/><geometry><box size="0.76 0.02 0.86"/></geometry></collision>
  </link>
  <link name="door">
    <inertial><origin xyz="0.4 -0.01 0.45"/><mass value="3"/><inertia ixx="0.2" ixy="0" ixz="0" iyy="0.36" iyz="0" izz="0.16"/></inertial>
    <visual><origin xyz="0.4 -0.01 0.45"/><geometry><box size="0.8 0.02 0.9"/></geometry></visual>
    <collision><origin xyz="0.4 -0.01 0.45"/><geometry><box size="0.8 0.02 0.9"/></geometry></collision>
  </link>
  <link name="knob">
    <visual><geometry><sphere radius="0.02"/></geometry></visual>
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="door"/><origin xyz="-0.4 0.222 0"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="1.5" effort="10" velocity="1"/><dynamics damping="0.4"/>
  </joint>
  <joint name="knob_fixed" type="fixed">
    <parent link="door"/><child link="knob"/><origin xyz="0.72 0.02 0.6"/>
  </joint>
</robot>
"#;

const SDF: &str = r#"<?xml version="1.0"?>
<sdf version="1.9"><model name="drawer_box">
  <link name="carcass"><pose>0 0 0 0 0 0</pose>
    <inertial><pose>0 0 0.2 0 0 0</pose><mass>8</mass><inertia><ixx>0.3</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.3</iyy><iyz>0</iyz><izz>0.3</izz></inertia></inertial>
    <collision name="bottom"><pose>0 0 0.01 0 0 0</pose><geometry><box><size>0.5 0.5 0.02</size></box></geometry></collision>
    <collision name="top"><pose>0 0 0.39 0 0 0</pose><geometry><box><size>0.5 0.5 0.02</size></box></geometry></collision>
    <collision name="left"><pose>-0.24 0 0.2 0 0 0</pose><geometry><box><size>0.02 0.5 0.36</size></box></geometry></collision>
    <collision name="right"><pose>0.24 0 0.2 0 0 0</pose><geometry><box><size>0.02 0.5 0.36</size></box></geometry></collision>
    <visual name="v"><pose>0 0 0.2 0 0 0</pose><geometry><box><size>0.5 0.5 0.4</size></box></geometry><material><diffuse>0.6 0.4 0.2 1</diffuse></material></visual>
  </link>
  <link name="drawer"><pose>0 0.0 0.2 0 0 0</pose>
    <inertial><mass>1</mass><inertia><ixx>0.01</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.01</iyy><iyz>0</iyz><izz>0.01</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.4 0.44 0.3</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>0.4 0.44 0.3</size></box></geometry></visual>
  </link>
  <joint name="slide" type="prismatic"><parent>carcass</parent><child>drawer</child>
    <pose>0 0.22 0 0 0 0</pose>
    <axis><xyz>0 1 0</xyz><limit><lower>0</lower><upper>0.35</upper><effort>50</effort></limit><dynamics><damping>3</damping></dynamics></axis>
  </joint>
</model></sdf>
"#;

#[test]
fn articulated_library_loads_urdf_and_sdf_and_serves_the_router() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("models")).unwrap();
    std::fs::write(dir.path().join("models/cabinet.urdf"), URDF).unwrap();
    std::fs::write(dir.path().join("models/drawer_box.sdf"), SDF).unwrap();
    std::fs::write(
        dir.path().join("index.json"),
        r#"{"models": [
          {"file": "models/cabinet.urdf", "name": "white cabinet", "description": "white kitchen cabinet with a hinged door", "category": "cabinet", "dimensions_m": [0.8, 0.5, 0.9], "license": "CC0"},
          {"file": "models/drawer_box.sdf", "name": "drawer box", "description": "small box with one drawer", "category": "nightstand", "dimensions_m": [0.5, 0.5, 0.4]}
        ]}"#,
    )
    .unwrap();
    let lib = ArticulatedLibrary::open(dir.path()).unwrap();
    assert_eq!(
        lib.search("white cabinet with door", None, None)[0].1.file,
        "models/cabinet.urdf"
    );

    let cab = lib.load(&lib.entries()[0].clone(), None, 0).unwrap();
    // The fixed knob merged into the door; one revolute joint.
    assert_eq!(cab.links.len(), 2);
    assert_eq!(cab.joints.len(), 1);
    assert_eq!(cab.joints[0].kind.as_str(), "revolute");
    let [lo, hi] = cab.bounds();
    assert!(lo[2].abs() < 1e-9 && (lo[0] + hi[0]).abs() < 1e-9 && (lo[1] + hi[1]).abs() < 1e-9);
    assert!(
        (cab.mass() - (20.0 + 3.0 + 4.0 / 3.0 * std::f64::consts::PI * 0.02f64.powi(3) * 500.0))
            .abs()
            < 0.1,
        "{}",
        cab.mass()
    );
    // Scaled to a requested size: uniform, joints follow.
    let big = lib
        .load(&lib.entries()[1].clone(), Some([1.0, 1.0, 0.8]), 0)
        .unwrap();
    let [lo, hi] = big.bounds();
    assert!(((hi[2] - lo[2]) - 0.8).abs() < 0.01, "{lo:?} {hi:?}");
    assert!(
        (big.joints[0].upper - 0.7).abs() < 1e-6,
        "prismatic limit scales: {}",
        big.joints[0].upper
    );
    // SDFormat joint pose moved the drawer's frame onto the joint: its zero pose is unchanged.
    let drawer = lib.load(&lib.entries()[1].clone(), None, 0).unwrap();
    let q = std::collections::BTreeMap::from([("slide".to_string(), 0.2)]);
    assert!(self_collisions(&drawer, &Default::default(), 1e-4).is_empty());
    let poses = scenesmith::assets::link_poses(&drawer, &q);
    assert!(
        (poses[1].translation().y - drawer.links[1].model_from_link.translation().y - 0.2).abs()
            < 1e-9
    );

    // Written as SDFormat, the imported model loads in Drake and its door opens to its limit.
    let out_dir = tempfile::tempdir().unwrap();
    for f in scenesmith::formats::sdf::asset_files(&cab) {
        std::fs::write(out_dir.path().join(&f.name), &f.bytes).unwrap();
    }
    let sdf = out_dir.path().join("model.sdf");
    let mut bridge = scenesmith::physics::Bridge::from_env().unwrap();
    let models = vec![AssetModel {
        name: "cab".into(),
        sdf,
        footprint: None,
        efforts: None,
    }];
    let loaded = bridge
        .call::<AssetsLoad>(&AssetsLoadArgs {
            models: models.clone(),
        })
        .unwrap();
    assert!(loaded.models["cab"].ok, "{loaded:?}");
    let pushed = bridge
        .call::<AssetsPush>(&AssetsPushArgs {
            models,
            duration: 1.0,
            time_step: 1e-3,
            force_scale: 2.0,
        })
        .unwrap();
    let cab = &pushed.models["cab"];
    let q = cab.joints["hinge"].position;
    assert!((q - 1.5).abs() < 0.05, "{pushed:?}");
    assert!(cab.self_penetration_m < 1e-3, "{pushed:?}");

    let mut ctx = RouterContext::new();
    ctx.library = Some(lib);
    let out = route(
        &RouteRequest::new("a white kitchen cabinet", Stage::Furniture, 0),
        &ctx,
    )
    .unwrap();
    assert_eq!(out.primary.strategy, Strategy::Articulated);
    assert_eq!(
        out.primary.asset.provenance["source"]["kind"],
        "articulated_library"
    );
    // Broken models are reported with their file name.
    std::fs::write(
        dir.path().join("models/cabinet.urdf"),
        "<robot><joint name='j' type='ball'/></robot>",
    )
    .unwrap();
    let lib = ArticulatedLibrary::open(dir.path()).unwrap();
    let e = lib
        .load(&lib.entries()[0].clone(), None, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cabinet.urdf") && e.contains("ball"), "{e}");
}
