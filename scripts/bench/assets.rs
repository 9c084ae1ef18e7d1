//! Asset library benchmarks (run by `scripts/bench_assets`, which adds the `vhacdx` column):
//!
//! 1. procedural library throughput: every category built from scratch (cold), routed again
//!    through a warm in-memory cache, and read back from a warm disk cache by a fresh router;
//! 2. V-HACD (parry3d, as used for imported meshes) on three meshes of 5k-50k triangles:
//!    time and hull count. The meshes are written as OBJ to the directory given as the first
//!    argument so the same files can be fed to other decomposers.

use std::path::PathBuf;
use std::time::Instant;

use scenesmith::assets::cache::AssetCache;
use scenesmith::assets::external::vhacd::{self, VhacdOptions};
use scenesmith::assets::procedural::{self, AssetRequest};
use scenesmith::assets::router::{RouteRequest, RouterContext, Stage, route};
use scenesmith::geometry::TriMesh;
use scenesmith::geometry::mesh::recompute_normals;
use scenesmith::geometry::obj::trimesh_to_obj;

/// A closed tube of radius `r` around a closed curve sampled at `n` points, `sides` around.
fn tube(curve: impl Fn(f64) -> [f64; 3], n: usize, sides: usize, r: f64) -> TriMesh {
    use nalgebra::Vector3;
    let p = |t: f64| Vector3::from(curve(t));
    let mut m = TriMesh::new();
    for i in 0..n {
        let t = i as f64 / n as f64;
        let c = p(t);
        let tangent = (p(t + 1e-4) - p(t - 1e-4)).normalize();
        let helper = if tangent.z.abs() < 0.9 {
            Vector3::z()
        } else {
            Vector3::x()
        };
        let nrm = tangent.cross(&helper).normalize();
        let bin = tangent.cross(&nrm);
        for k in 0..sides {
            let a = std::f64::consts::TAU * k as f64 / sides as f64;
            let q = c + (nrm * a.cos() + bin * a.sin()) * r;
            m.positions.push([q.x, q.y, q.z]);
        }
    }
    for i in 0..n {
        for k in 0..sides {
            let a = (i * sides + k) as u32;
            let b = (i * sides + (k + 1) % sides) as u32;
            let c = (((i + 1) % n) * sides + (k + 1) % sides) as u32;
            let d = (((i + 1) % n) * sides + k) as u32;
            m.triangles.push([a, b, c]);
            m.triangles.push([a, c, d]);
        }
    }
    recompute_normals(&mut m);
    m
}

/// Splits every triangle into four (shared edge midpoints are duplicated; fine for V-HACD).
fn subdivide(m: &TriMesh) -> TriMesh {
    let mut out = TriMesh::new();
    for t in &m.triangles {
        let v = t.map(|i| nalgebra::Vector3::from(m.positions[i as usize]));
        let mid = |a: usize, b: usize| (v[a] + v[b]) * 0.5;
        let pts = [v[0], v[1], v[2], mid(0, 1), mid(1, 2), mid(2, 0)];
        let base = out.positions.len() as u32;
        for p in pts {
            out.positions.push([p.x, p.y, p.z]);
        }
        for tri in [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]] {
            out.triangles.push(tri.map(|k| base + k));
        }
    }
    recompute_normals(&mut out);
    out
}

fn merged_visual(category: &str) -> TriMesh {
    let a = procedural::build(&AssetRequest::new(category, 0)).expect("builds");
    let mut m = TriMesh::new();
    for l in &a.links {
        for v in &l.visuals {
            let mut p = v.mesh.transformed(&l.model_from_link);
            p.uvs.clear();
            m.append(&p);
        }
    }
    m
}

fn main() {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "target/bench_assets".into()),
    );
    std::fs::create_dir_all(&out).expect("output directory");
    let cats = procedural::categories();

    // 1. Procedural library.
    let t0 = Instant::now();
    for (k, c) in cats.iter().enumerate() {
        procedural::build(&AssetRequest::new(c, 1000 + k as u64)).expect("builds");
    }
    let cold = t0.elapsed().as_secs_f64();
    let ctx = RouterContext::new();
    let reqs: Vec<RouteRequest> = cats
        .iter()
        .map(|c| {
            let stage = Stage::for_support(procedural::prior(c).expect("prior").support);
            let mut r = RouteRequest::new(&c.replace('_', " "), stage, 7);
            r.category = Some(c.to_string());
            r
        })
        .collect();
    let t0 = Instant::now();
    for r in &reqs {
        route(r, &ctx).expect("routes");
    }
    let routed_cold = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let rounds = 20;
    for _ in 0..rounds {
        for r in &reqs {
            route(r, &ctx).expect("routes");
        }
    }
    let warm = t0.elapsed().as_secs_f64() / rounds as f64;
    let disk = tempfile::tempdir().expect("temp dir");
    let mut fill = RouterContext::new();
    fill.cache = AssetCache::on_disk(disk.path());
    for r in &reqs {
        route(r, &fill).expect("routes");
    }
    let mut fresh = RouterContext::new();
    fresh.cache = AssetCache::on_disk(disk.path());
    let t0 = Instant::now();
    for r in &reqs {
        route(r, &fresh).expect("routes");
    }
    let from_disk = t0.elapsed().as_secs_f64();
    let n = cats.len() as f64;
    println!(
        "| procedural library ({} categories) | time | assets/s |",
        cats.len()
    );
    println!("|---|---|---|");
    println!(
        "| build, cold (generator only) | {cold:.3} s | {:.0} |",
        n / cold
    );
    println!(
        "| route, cold (parse + build + validate + cache) | {routed_cold:.3} s | {:.0} |",
        n / routed_cold
    );
    println!(
        "| route, cached in memory | {:.5} s | {:.0} |",
        warm,
        n / warm
    );
    println!(
        "| route, cached on disk (fresh process view) | {from_disk:.3} s | {:.0} |",
        n / from_disk
    );
    println!();

    // 2. V-HACD on three meshes.
    let torus = tube(
        |t| {
            let a = std::f64::consts::TAU * t;
            [0.3 * a.cos(), 0.3 * a.sin(), 0.15]
        },
        100,
        50,
        0.1,
    );
    let mut sofa = merged_visual("l_shaped_sofa");
    while sofa.triangles.len() < 5000 {
        sofa = subdivide(&sofa);
    }
    let knot = tube(
        |t| {
            let a = std::f64::consts::TAU * t;
            [
                0.1 * (a.sin() + 2.0 * (2.0 * a).sin()),
                0.1 * (a.cos() - 2.0 * (2.0 * a).cos()),
                0.1 * (-(3.0 * a).sin()) + 0.2,
            ]
        },
        390,
        64,
        0.04,
    );
    println!("| mesh | triangles | parry3d V-HACD time | hulls | hull volume / mesh volume |");
    println!("|---|---|---|---|---|");
    for (name, mesh) in [
        ("torus", &torus),
        ("l_shaped_sofa", &sofa),
        ("trefoil_knot", &knot),
    ] {
        std::fs::write(out.join(format!("{name}.obj")), trimesh_to_obj(mesh)).expect("write OBJ");
        let t0 = Instant::now();
        let hulls = vhacd::decompose(
            mesh,
            VhacdOptions {
                resolution: 64,
                concavity: 0.01,
                max_hulls: 64,
            },
        );
        let dt = t0.elapsed().as_secs_f64();
        let hv: f64 = hulls.iter().map(|h| h.volume()).sum();
        let mv = scenesmith::geometry::mesh::enclosed_volume(mesh);
        println!(
            "| {name} | {} | {dt:.3} s | {} | {:.3} |",
            mesh.triangles.len(),
            hulls.len(),
            hv / mv
        );
    }
}
