//! Physics benchmark (run through `scripts/bench_physics`, release build). Prints tables:
//!
//! 1. `projection`: native vs Drake projection on the same scenes (heaps of 10, 50, 200
//!    overlapping objects of mixed shapes; generated rooms with every free object jittered):
//!    wall time, final max penetration and mean displacement, both measured with parry3d on the
//!    resulting poses.
//! 2. `contact`: stacked boxes settled for 5 s under point and hydroelastic contact.
//! 3. `settle`: post-processing of generated rooms (settling per room / per supporting entity
//!    on the bridge pool): wall time, simulated seconds, wall per simulated second.
//! 4. `rooms`: `generate` over dev prompts: COL, mean penetration depth, STB, and the time per
//!    step of the pipeline.
//!
//! Usage: `bench_physics [projection] [contact] [settle] [rooms] [--sizes 10,50,200]
//! [--drake-limit SECONDS] [--prompts N|all]` (no part named: all parts).

#[path = "../../tests/physics_util/mod.rs"]
mod physics_util;

use std::path::Path;
use std::time::Instant;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

use physics_util::{Shape, block, floor, max_penetration, overlapping_heap, place, room};
use scenesmith::agents::Backend;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::BridgePool;
use scenesmith::physics::drake_projection::ProjectSolver;
use scenesmith::physics::drake_projection::{DrakeProjectionOptions, project_drake};
use scenesmith::physics::postprocess::{PostProcessOptions, post_process};
use scenesmith::physics::projection::{ProjectionOptions, apply_offsets, project_objects};
use scenesmith::physics::protocol::{Load, NoArgs, SceneFiles, Simulate, Versions};
use scenesmith::physics::settle::{ContactModel, ContactOptions, SettleOptions, simulate_args};
use scenesmith::pipeline::{GenerateOptions, build_scene, generate};
use scenesmith::scene::{ObjectKind, Pose};
use scenesmith::state::SceneState;

struct Args {
    parts: Vec<String>,
    sizes: Vec<usize>,
    drake_limit: f64,
    prompts: Option<usize>,
}

fn args() -> Args {
    let mut a = Args {
        parts: Vec::new(),
        sizes: vec![10, 50, 200],
        drake_limit: 300.0,
        prompts: Some(12),
    };
    let mut it = std::env::args().skip(1);
    while let Some(x) = it.next() {
        match x.as_str() {
            "--sizes" => {
                a.sizes = it
                    .next()
                    .unwrap_or_default()
                    .split(',')
                    .filter_map(|s| s.parse().ok())
                    .collect()
            }
            "--drake-limit" => {
                a.drake_limit = it.next().and_then(|s| s.parse().ok()).unwrap_or(300.0)
            }
            "--prompts" => {
                a.prompts = match it.next().as_deref() {
                    Some("all") => None,
                    Some(n) => n.parse().ok(),
                    None => Some(12),
                }
            }
            // `cargo bench` appends `--bench` to a harness-less benchmark's arguments.
            "--bench" => {}
            part => a.parts.push(part.to_string()),
        }
    }
    if a.parts.is_empty() {
        a.parts = ["projection", "contact", "settle", "rooms"]
            .map(String::from)
            .to_vec();
    }
    a
}

fn free_and_fixed(state: &SceneState) -> (Vec<String>, Vec<String>) {
    let mut free = Vec::new();
    let mut fixed = Vec::new();
    for o in &state.scene.objects {
        if o.kind == ObjectKind::Architecture || o.welded {
            fixed.push(o.id.clone());
        } else {
            free.push(o.id.clone());
        }
    }
    (free, fixed)
}

fn mean_displacement(a: &SceneState, b: &SceneState, ids: &[String]) -> f64 {
    let d: Vec<f64> = ids
        .iter()
        .filter_map(|id| {
            Some(
                (a.scene.object(id)?.world_from_object.translation()
                    - b.scene.object(id)?.world_from_object.translation())
                .norm(),
            )
        })
        .collect();
    d.iter().sum::<f64>() / d.len().max(1) as f64
}

/// Every free object of a generated room moved by up to 4 cm in XY (and small objects up to
/// 1 cm down), so objects overlap each other, walls and their supports.
fn jittered(prompt: &str, seed: u64) -> SceneState {
    let (mut state, _) =
        build_scene(prompt, seed, "bench", &Backend::Builtin).expect("dev prompt builds");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for o in &mut state.scene.objects {
        if o.kind == ObjectKind::Architecture || o.welded {
            continue;
        }
        let mut t = o.world_from_object.translation();
        t.x += rng.random_range(-0.04..0.04);
        t.y += rng.random_range(-0.04..0.04);
        if o.kind == ObjectKind::Manipuland {
            t.z -= rng.random_range(0.0..0.01);
        }
        o.world_from_object = o.world_from_object.with_translation(t);
    }
    state
}

fn projection_part(a: &Args, pool: &BridgePool) {
    println!(
        "\n## Projection: native (clarabel QPs) vs Drake (SNOPT, per-pair DistanceConstraint)\n"
    );
    println!(
        "| scene | free objects | initial max pen. (mm) | native time (s) | native final pen. (mm) | native mean disp. (mm) | Drake solver | Drake time (s) | Drake final pen. (mm) | Drake mean disp. (mm) | speed-up |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut scenes: Vec<(String, SceneState)> = a
        .sizes
        .iter()
        .map(|n| (format!("heap of {n}"), overlapping_heap(*n, 7)))
        .collect();
    for (id, seed) in [
        ("object_density_25", 1),
        ("house_21", 2),
        ("object_density_10", 3),
    ] {
        let prompt = dev_prompt(id);
        scenes.push((format!("{id}, jittered"), jittered(&prompt, seed)));
    }
    for (name, state) in scenes {
        let (free, fixed) = free_and_fixed(&state);
        let initial = max_penetration(&state);
        let opts = ProjectionOptions::default();
        let t = Instant::now();
        let (offsets, report) =
            project_objects(&state, &free, &fixed, &opts).expect("native projection");
        let native_s = t.elapsed().as_secs_f64();
        let mut native = state.clone();
        apply_offsets(&mut native, &offsets);
        let native_pen = max_penetration(&native);
        let native_disp = mean_displacement(&native, &state, &free);

        let dir = tempfile::tempdir().expect("temp dir");
        write_scene_dir(dir.path(), &state).expect("scene written");
        let directives = dir.path().join("scene.dmd.yaml");
        let package = dir.path().join("package.xml");
        // Build the plant once first, so the timing is the solve.
        let _ = pool.call::<Load>(&SceneFiles::new(&directives, &package));
        let dopts = DrakeProjectionOptions {
            solver: ProjectSolver::Snopt,
            time_limit: a.drake_limit,
            ..DrakeProjectionOptions::default()
        };
        let drake = project_drake(pool, &directives, &package, &dopts);
        let (dsolver, dtime, dpen, ddisp) = match drake {
            Ok(r) => {
                let mut by_drake = state.clone();
                for o in &mut by_drake.scene.objects {
                    let root = &state.scene.assets[&o.asset].root_link;
                    if let Some(p) = r.poses.get(&o.id).and_then(|b| b.get(root)) {
                        o.world_from_object = *p;
                    }
                }
                let status = r
                    .attempts
                    .first()
                    .map_or("", |a| a.status.as_str())
                    .replace("SolutionResult.", "");
                (
                    format!("{} ({status})", r.solver),
                    r.wall_s,
                    max_penetration(&by_drake),
                    mean_displacement(&by_drake, &state, &free),
                )
            }
            Err(e) => (format!("error: {e}"), f64::NAN, f64::NAN, f64::NAN),
        };
        println!(
            "| {name} | {} | {:.1} | {:.3} | {:.3} | {:.1} | {dsolver} | {:.2} | {:.3} | {:.1} | {:.0}x |",
            free.len(),
            initial * 1e3,
            native_s,
            native_pen * 1e3,
            native_disp * 1e3,
            dtime,
            dpen * 1e3,
            ddisp * 1e3,
            dtime / native_s
        );
        eprintln!(
            "  {name}: native {:?} in {} iterations",
            report.status, report.iterations
        );
    }
}

fn contact_part(pool: &BridgePool) {
    println!(
        "\n## Contact model: 3 stacks of 3 boxes (0.10 x 0.08 x 0.06 m, 0.4 kg), 5 s at 1 ms\n"
    );
    println!(
        "| contact | max penetration at 5 s (mm) | max drift (mm) | max rotation (rad) | at rest | ms/step |"
    );
    println!("|---|---|---|---|---|---|");
    let mut state = room(3.0, 3.0);
    let b = block("box", Shape::Box([0.10, 0.08, 0.06]), "wood");
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    for s in 0..3 {
        for k in 0..3 {
            place(
                &mut state,
                &b,
                ObjectKind::Manipuland,
                Pose::from_xyz_yaw(
                    1.0 + 0.4 * s as f64,
                    1.5,
                    k as f64 * 0.061 + 0.0005,
                    rng.random_range(-0.2..0.2),
                ),
                floor(),
            );
        }
    }
    let dir = tempfile::tempdir().expect("temp dir");
    write_scene_dir(dir.path(), &state).expect("scene written");
    for model in [ContactModel::Point, ContactModel::AsWritten] {
        let (name, contact) = (model.label(), ContactOptions { model });
        let opts = SettleOptions {
            max_time: 5.0,
            stop_at_rest: false,
            contact,
            ..SettleOptions::default()
        };
        let args = simulate_args(
            &dir.path().join("scene.dmd.yaml"),
            &dir.path().join("package.xml"),
            &opts,
        );
        match pool.call::<Simulate>(&args).map_err(|e| e.to_string()) {
            Ok(r) => {
                let drift = r
                    .motion
                    .values()
                    .map(|m| m.displacement_m)
                    .fold(0.0, f64::max);
                let rot = r
                    .motion
                    .values()
                    .map(|m| m.rotation_rad)
                    .fold(0.0, f64::max);
                println!(
                    "| {name} | {:.2} | {:.1} | {:.3} | {} | {:.2} |",
                    r.max_penetration_m * 1e3,
                    drift * 1e3,
                    rot,
                    r.at_rest,
                    r.ms_per_step
                );
            }
            Err(e) => println!("| {name} | error: {e} | | | | |"),
        }
    }
}

fn dev_prompt(id: &str) -> String {
    dev_prompts()
        .into_iter()
        .find(|(i, _)| i == id)
        .map(|(_, p)| p)
        .unwrap_or_else(|| panic!("no dev prompt {id}"))
}

fn dev_prompts() -> Vec<(String, String)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/dev_prompts.jsonl");
    let text = std::fs::read_to_string(path).expect("dev prompts");
    text.lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .map(|v| {
            (
                v["id"].as_str().unwrap_or_default().to_string(),
                v["prompt"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect()
}

/// An ~80-object room: two shelves of books, a table set with plates and mugs, chairs.
const BIG_ROOM: &str = "A large library with three shelves holding 50 books, a cabinet, a table with \
                        12 plates and 12 mugs, and six chairs.";

fn settle_part(pool: &BridgePool) {
    println!(
        "\n## Settling (post-processing) of generated rooms, bridge pool of {} workers\n",
        pool.size()
    );
    println!(
        "| room | objects | free furniture | small objects | subsets | simulated s (sum) | furniture settle wall (s) | small-object settle wall (s) | post-process total (s) | wall s per simulated s | ms/step (mean) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut rooms: Vec<(String, String)> = [
        "object_density_25",
        "object_density_15",
        "house_21",
        "object_density_10",
    ]
    .iter()
    .map(|id| (id.to_string(), dev_prompt(id)))
    .collect();
    rooms.push(("~80-object library".into(), BIG_ROOM.into()));
    for (name, prompt) in rooms {
        let (mut state, _) = build_scene(&prompt, 0, "bench", &Backend::Builtin).expect("builds");
        let objects = state
            .scene
            .objects
            .iter()
            .filter(|o| o.kind != ObjectKind::Architecture)
            .count();
        let furn = state
            .scene
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::Furniture)
            .count();
        let small = state
            .scene
            .objects
            .iter()
            .filter(|o| o.kind == ObjectKind::Manipuland)
            .count();
        let t = Instant::now();
        let r = match post_process(&mut state, Some(pool), &PostProcessOptions::default()) {
            Ok(r) => r,
            Err(e) => {
                println!("| {name} | {objects} | error: {e} |");
                continue;
            }
        };
        let total = t.elapsed().as_secs_f64();
        let subsets: Vec<_> = r
            .furniture
            .settle
            .iter()
            .chain(&r.manipuland.settle)
            .collect();
        let sim: f64 = subsets.iter().map(|s| s.sim_time).sum();
        let wall: f64 = subsets.iter().map(|s| s.wall_s).sum();
        let ms: f64 =
            subsets.iter().map(|s| s.ms_per_step).sum::<f64>() / subsets.len().max(1) as f64;
        println!(
            "| {name} | {objects} | {furn} | {small} | {} | {:.2} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            subsets.len(),
            sim,
            r.furniture.settle_seconds,
            r.manipuland.settle_seconds,
            total,
            wall / sim.max(1e-9),
            ms
        );
    }
}

fn rooms_part(a: &Args) {
    println!("\n## Generated rooms (`generate`, starter furnisher, post-processing, metrics)\n");
    println!(
        "| prompt | objects | removed | COL % | pen. pairs | mean depth (mm) | STB % | MD (mm) | XD (m) | post-process (s) | metrics (s) | total (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut prompts = dev_prompts();
    // Prompts with the most objects first, so a short run still covers the heavy rooms.
    let mut sized: Vec<(usize, (String, String))> = prompts
        .drain(..)
        .map(|p| {
            let n = build_scene(&p.1, 0, "count", &Backend::Builtin)
                .map(|(s, _)| s.scene.objects.len())
                .unwrap_or(0);
            (n, p)
        })
        .collect();
    sized.sort_by(|x, y| y.0.cmp(&x.0).then(x.1.0.cmp(&y.1.0)));
    let take = a.prompts.unwrap_or(sized.len()).min(sized.len());
    let root = tempfile::tempdir().expect("temp dir");
    let (mut objects, mut colliding, mut free, mut stable, mut depths) =
        (0usize, 0usize, 0usize, 0usize, Vec::new());
    let mut per_room_col = Vec::new();
    for (_, (id, prompt)) in sized.into_iter().take(take) {
        let out = root.path().join(&id);
        // The physics steps only: no renders, no exports.
        let r = generate(&GenerateOptions {
            render: false,
            exports: scenesmith::export::ExportSet::none(),
            ..GenerateOptions::new(prompt.clone(), out)
        });
        let s = match r {
            Ok(s) => s,
            Err(e) => {
                println!("| {id} | error: {e} |");
                continue;
            }
        };
        let m = &s.metrics;
        let removed = s.post_process.furniture.removed.len()
            + s.post_process.manipuland.removed.len()
            + s.post_process.removed_penetrating.len();
        objects += m.col.objects;
        colliding += m.col.colliding.len();
        depths.extend(m.col.pairs.iter().map(|p| p.2));
        per_room_col.push(m.col.percent);
        let (stb, md, xd) = match &m.stb {
            Some(st) => {
                free += st.free_objects;
                stable += st.stable;
                (
                    format!("{:.1}", st.percent),
                    format!("{:.2}", st.md_mm),
                    format!("{:.4}", st.xd_m),
                )
            }
            None => ("-".into(), "-".into(), "-".into()),
        };
        let t = |k: &str| s.timings.get(k).copied().unwrap_or(f64::NAN);
        println!(
            "| {id} | {} | {removed} | {:.2} | {} | {:.2} | {stb} | {md} | {xd} | {:.1} | {:.1} | {:.1} |",
            m.col.objects,
            m.col.percent,
            m.col.pairs.len(),
            m.col.mean_depth_mm,
            t("post_process"),
            t("metrics"),
            t("total")
        );
    }
    let mean_depth = if depths.is_empty() {
        0.0
    } else {
        depths.iter().sum::<f64>() / depths.len() as f64
    };
    println!(
        "\nOver {} rooms, {objects} objects: COL {:.2} % (mean of per-room COL {:.2} %), mean penetration depth {:.2} mm over {} pairs; STB {:.1} % of {free} free objects.",
        per_room_col.len(),
        100.0 * colliding as f64 / objects.max(1) as f64,
        per_room_col.iter().sum::<f64>() / per_room_col.len().max(1) as f64,
        mean_depth,
        depths.len(),
        100.0 * stable as f64 / free.max(1) as f64
    );
}

fn main() {
    let a = args();
    let pool = BridgePool::from_env();
    if let Err(e) = pool.start_all() {
        eprintln!("the Drake bridge did not start: {e}");
        std::process::exit(1);
    }
    let drake_version = pool
        .call::<Versions>(&NoArgs {})
        .map_or_else(|_| "?".to_string(), |v| v.drake);
    println!(
        "# bench_physics: drake {}, {} bridge workers, {} cores",
        drake_version,
        pool.size(),
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(0)
    );
    for part in &a.parts {
        match part.as_str() {
            "projection" => projection_part(&a, &pool),
            "contact" => contact_part(&pool),
            "settle" => settle_part(&pool),
            "rooms" => rooms_part(&a),
            other => eprintln!("unknown part {other:?}; parts: projection contact settle rooms"),
        }
    }
}
