//! Renderer benchmark (run through `scripts/bench_render`): times the plan, a room view and
//! PNG encoding on generated scenes, and a room view of a furnished room refined to ~100k
//! triangles, at 1280x960. Prints a table; the best of several runs is reported.

use std::time::Instant;

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::render::plan::{PlanOptions, plan_view};
use scenesmith::render::scene::{RenderMesh, RenderScene};
use scenesmith::render::views::{RoomViewOptions, room_views};

/// Splits triangles into four (midpoints), one mesh at a time round-robin, until the scene
/// has at least `target` triangles (same shapes, denser meshes).
fn refine(rs: &mut RenderScene, target: usize) {
    let mut i = 0;
    while rs.triangle_count() < target && !rs.meshes.is_empty() {
        let k = i % rs.meshes.len();
        rs.meshes[k] = split4(&rs.meshes[k]);
        i += 1;
    }
}

fn split4(m: &RenderMesh) -> RenderMesh {
    let mut out = m.clone();
    out.triangles.clear();
    let mid = |a: u32, b: u32, out: &mut RenderMesh| -> u32 {
        let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
        let (na, nb) = (m.normals[a as usize], m.normals[b as usize]);
        out.positions.push([
            (pa[0] + pb[0]) / 2.0,
            (pa[1] + pb[1]) / 2.0,
            (pa[2] + pb[2]) / 2.0,
        ]);
        let n = [
            (na[0] + nb[0]) / 2.0,
            (na[1] + nb[1]) / 2.0,
            (na[2] + nb[2]) / 2.0,
        ];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-12);
        out.normals.push([n[0] / l, n[1] / l, n[2] / l]);
        if !m.uvs.is_empty() {
            let (ua, ub) = (m.uvs[a as usize], m.uvs[b as usize]);
            out.uvs.push([(ua[0] + ub[0]) / 2.0, (ua[1] + ub[1]) / 2.0]);
        }
        (out.positions.len() - 1) as u32
    };
    for t in &m.triangles {
        let ab = mid(t[0], t[1], &mut out);
        let bc = mid(t[1], t[2], &mut out);
        let ca = mid(t[2], t[0], &mut out);
        out.triangles
            .extend([[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]);
    }
    out
}

/// CPU time of this process (all threads), seconds, from /proc (10 ms ticks).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name (which is in parentheses): utime is the 12th, stime 13th.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

/// Best wall time over `runs`, mean CPU time per run, and the last result.
fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let mut best = f64::INFINITY;
    let mut last = None;
    let c0 = cpu_seconds();
    for _ in 0..runs {
        let t0 = Instant::now();
        let v = f();
        best = best.min(t0.elapsed().as_secs_f64());
        last = Some(v);
    }
    let cpu = (cpu_seconds() - c0) / runs as f64;
    (best, cpu, last.expect("runs >= 1"))
}

fn main() {
    let prompts = [
        (
            "kitchen",
            "A kitchen with a table, four chairs, plates and mugs, a cabinet and a shelf with books",
        ),
        (
            "office",
            "A private office with a desk and office chair, a shelf with books against the wall, and two guest chairs facing the desk.",
        ),
        (
            "dining",
            "A dining room with a table set for 4 people. Each setting has a plate, a glass, a fork, and a knife.",
        ),
        (
            "library",
            "A library with four shelves full of books, a reading table with chairs and mugs",
        ),
    ];
    let runs = 5;
    println!(
        "threads: {}, load average: {}",
        rayon::current_num_threads(),
        std::fs::read_to_string("/proc/loadavg")
            .unwrap_or_default()
            .trim()
    );
    println!(
        "| scene | objects | triangles | view | size | render wall s (best of {runs}) | render CPU s (mean) | png s |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, prompt) in prompts {
        let (state, _) = match build_scene(prompt, 0, name, &Backend::Builtin) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        let objects = state.scene.objects.len();
        let mut rs = match RenderScene::from_state(&state) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        for refined in [false, true] {
            if refined {
                refine(&mut rs, 100_000);
            }
            let label = if refined {
                format!("{name} (refined)")
            } else {
                name.to_string()
            };
            let tris = rs.triangle_count();
            let opts = RoomViewOptions::default();
            let (t, cpu, views) = best_of(runs, || room_views(&rs, 0, &opts));
            let views = views.unwrap_or_default();
            let n = views.len().max(1) as f64;
            let (tp, _, _) = best_of(runs, || {
                views
                    .iter()
                    .map(|(_, i)| i.encode_png().map(|b| b.len()).unwrap_or(0))
                    .sum::<usize>()
            });
            println!(
                "| {label} | {objects} | {tris} | room view (mean of {n}) | {}x{} | {:.3} | {:.3} | {:.3} |",
                opts.width,
                opts.height,
                t / n,
                cpu / n,
                tp / n
            );
            let (tplan, cpu, img) = best_of(runs, || plan_view(&rs, &PlanOptions::default()));
            let (w, h) = img.as_ref().map(|i| (i.width, i.height)).unwrap_or((0, 0));
            let (tpng, _, _) = best_of(runs, || {
                img.as_ref().map(|i| i.encode_png().map(|b| b.len()))
            });
            println!(
                "| {label} | {objects} | {tris} | plan | {w}x{h} | {tplan:.3} | {cpu:.3} | {tpng:.3} |"
            );
        }
    }
}
