//! MJCF for MuJoCo: `scene.xml`, `meshes/<asset>/*.obj`, `textures/*.png`.
//!
//! One body per link, named after the object (`mug_0`) for the root link and
//! `<object>/<link>` for the others; free objects get a `<freejoint>` named after the object,
//! welded objects and static architecture hang from the world without a joint. Revolute joints
//! become hinges and prismatic joints slides (`<object>/<joint>`), with range, damping and `ref` at
//! the object's joint position, so the written body poses are the initial configuration.
//!
//! Collision: one mesh geom per convex piece (MuJoCo collides meshes by their convex hull, and
//! every piece already is one), class `collision`, friction from the link's material. Visuals:
//! mesh geoms in class `visual` (`contype=0 conaffinity=0`, group 2) with materials and textures.
//! Inertia comes only from the written `<inertial>` elements (`inertiafromgeom="false"`), so the
//! masses equal the scene's exactly. Self-collision inside an articulated object is excluded pair
//! by pair. The solver options are [`SOLVER`].

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::view::{AssetView, Hold, ObjectView, SceneView};
use super::{ExportError, ExportFile};
use super::{num as fmt_num, nums};
use crate::assets::{JointKind, Link};
use crate::geometry::TriMesh;
use crate::geometry::obj::convex_to_obj;
use crate::scene::Pose;
use crate::util::xml::El;

/// MuJoCo solver and contact options, chosen for objects resting stably on furniture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Step, seconds.
    pub timestep: f64,
    /// `Euler`, `implicitfast`, `implicit` or `RK4`.
    pub integrator: &'static str,
    /// `pyramidal` or `elliptic` friction cones.
    pub cone: &'static str,
    /// Ratio of frictional to normal constraint impedance (higher: less slip).
    pub impratio: f64,
    /// Extra post-solve iterations that remove residual slip (0 = off).
    pub noslip_iterations: u32,
    /// Main solver iterations.
    pub iterations: u32,
    /// Contact `solref` (time constant s, damping ratio).
    pub solref: [f64; 2],
    /// Contact `solimp` (dmin, dmax, width m, midpoint, power).
    pub solimp: [f64; 5],
    /// Contact margin, m (contacts activate this far before touching).
    pub margin: f64,
    /// Contact dimensionality (3: sliding friction, 4: plus torsional, 6: plus rolling).
    pub condim: u32,
    /// Torsional and rolling friction coefficients (used when `condim` is 4 or 6).
    pub spin_roll_friction: [f64; 2],
}

/// The options `scene.xml` is written with (the README states and explains them).
pub const SOLVER: SolverOptions = SolverOptions {
    timestep: 0.002,
    integrator: "implicitfast",
    cone: "elliptic",
    impratio: 10.0,
    noslip_iterations: 0,
    iterations: 100,
    solref: [0.02, 1.0],
    solimp: [0.95, 0.99, 0.001, 0.5, 2.0],
    margin: 0.0,
    condim: 4,
    spin_roll_friction: [0.005, 0.0001],
};

/// Visual geoms live in this geom group (collision geoms in group 3).
pub const VISUAL_GROUP: u32 = 2;
/// Geom group of collision geoms.
pub const COLLISION_GROUP: u32 = 3;

/// MJCF body name of link `li` of an object.
pub fn body_name(o: &ObjectView<'_>, av: &AssetView<'_>, li: usize) -> String {
    if li == 0 {
        o.name.clone()
    } else {
        format!("{}/{}", o.name, av.link_names[li])
    }
}

/// Text for metadata: control characters (which XML 1.0 cannot carry) become spaces.
pub(crate) fn plain_text(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

fn pose_attrs(mut el: El, pose: &Pose) -> El {
    let t = pose.translation();
    if t.norm() > 0.0 {
        el = el.attr("pos", nums(&[t.x, t.y, t.z]));
    }
    let q = pose.rotation();
    if q.angle() > 0.0 {
        el = el.attr("quat", nums(&[q.w, q.i, q.j, q.k]));
    }
    el
}

/// OBJ with texture coordinates (flipped to OBJ's upward `v`) and normals.
fn visual_obj(mesh: &TriMesh) -> String {
    let uv = mesh.uvs.len() == mesh.positions.len();
    let nrm = mesh.normals.len() == mesh.positions.len();
    let mut out = String::with_capacity(mesh.positions.len() * 64 + mesh.triangles.len() * 32);
    out.push_str("# scenesmith visual mesh\n");
    for v in &mesh.positions {
        let _ = writeln!(out, "v {:.6} {:.6} {:.6}", v[0], v[1], v[2]);
    }
    if uv {
        for t in &mesh.uvs {
            let _ = writeln!(out, "vt {:.6} {:.6}", t[0], 1.0 - t[1]);
        }
    }
    if nrm {
        for n in &mesh.normals {
            let _ = writeln!(out, "vn {:.6} {:.6} {:.6}", n[0], n[1], n[2]);
        }
    }
    for t in &mesh.triangles {
        let c: Vec<String> = t
            .iter()
            .map(|i| {
                let k = i + 1;
                match (uv, nrm) {
                    (true, true) => format!("{k}/{k}/{k}"),
                    (true, false) => format!("{k}/{k}"),
                    (false, true) => format!("{k}//{k}"),
                    (false, false) => format!("{k}"),
                }
            })
            .collect();
        let _ = writeln!(out, "f {}", c.join(" "));
    }
    out
}

/// Names of an asset's meshes and materials in `<asset>`.
struct AssetMeshes {
    /// Per link, per piece: mesh name.
    collision: Vec<Vec<String>>,
    /// Per link: (mesh, material) of each merged visual mesh.
    visual: Vec<Vec<(String, String)>>,
}

/// Registers a texture once per asset (PNG file + `<texture>`); returns its MJCF name.
fn texture(
    av: &AssetView<'_>,
    t: &crate::assets::Texture,
    textures: &mut BTreeMap<String, String>,
    asset_el: &mut El,
    files: &mut Vec<ExportFile>,
) -> Result<String, ExportError> {
    if let Some(name) = textures.get(&t.name) {
        return Ok(name.clone());
    }
    let a = &av.name;
    let safe = av
        .texture_names
        .get(&t.name)
        .cloned()
        .unwrap_or_else(|| "texture".into());
    let png = crate::util::png::encode_rgba(t.width, t.height, &t.rgba).map_err(|reason| {
        ExportError::Texture {
            asset: av.asset.id.clone(),
            name: t.name.clone(),
            reason,
        }
    })?;
    let file = format!("{a}__{safe}.png");
    files.push(ExportFile {
        path: format!("textures/{file}"),
        bytes: png,
    });
    let name = format!("{a}/{safe}");
    asset_el.push(
        El::new("texture")
            .attr("name", &name)
            .attr("type", "2d")
            .attr("file", file),
    );
    textures.insert(t.name.clone(), name.clone());
    Ok(name)
}

fn asset_meshes(
    av: &AssetView<'_>,
    asset_el: &mut El,
    files: &mut Vec<ExportFile>,
) -> Result<AssetMeshes, ExportError> {
    let a = &av.name;
    let mut collision = Vec::new();
    let mut n = 0usize;
    for link in &av.asset.links {
        let mut names = Vec::new();
        for piece in &link.collisions {
            let name = format!("{a}/c{n:03}");
            let file = format!("{a}/c{n:03}.obj");
            files.push(ExportFile::text(
                format!("meshes/{file}"),
                convex_to_obj(piece),
            ));
            asset_el.push(El::new("mesh").attr("name", &name).attr("file", &file));
            names.push(name);
            n += 1;
        }
        collision.push(names);
    }
    let mut textures: BTreeMap<String, String> = BTreeMap::new();
    let mut material_names = Vec::with_capacity(av.materials.len());
    for (k, m) in av.materials.iter().enumerate() {
        let name = format!("{a}/m{k}");
        let mut el = El::new("material")
            .attr("name", &name)
            .attr("rgba", nums(&m.color))
            .attr("specular", "0.2")
            .attr("shininess", "0.2");
        if let Some(t) = m.texture {
            el = el.attr("texture", texture(av, t, &mut textures, asset_el, files)?);
        }
        asset_el.push(el);
        material_names.push(name);
    }
    let mut visual = Vec::new();
    for (li, groups) in av.visuals.iter().enumerate() {
        let mut parts = Vec::new();
        for (k, g) in groups.iter().enumerate() {
            let stem = format!("{}__v{k}", av.link_names[li]);
            let mesh_name = format!("{a}/{stem}");
            files.push(ExportFile::text(
                format!("meshes/{a}/{stem}.obj"),
                visual_obj(&g.mesh),
            ));
            asset_el.push(
                El::new("mesh")
                    .attr("name", &mesh_name)
                    .attr("file", format!("{a}/{stem}.obj")),
            );
            parts.push((mesh_name, material_names[g.material].clone()));
        }
        visual.push(parts);
    }
    Ok(AssetMeshes { collision, visual })
}

fn inertial(link: &Link) -> El {
    let m = &link.mass;
    let i = &m.inertia;
    let diag = i[0][0].abs() + i[1][1].abs() + i[2][2].abs();
    let off = i[0][1].abs() + i[0][2].abs() + i[1][2].abs();
    let el = El::new("inertial")
        .attr("pos", nums(&m.com))
        .attr("mass", fmt_num(m.mass));
    if off <= 1e-12 * diag {
        el.attr("diaginertia", nums(&[i[0][0], i[1][1], i[2][2]]))
    } else {
        el.attr(
            "fullinertia",
            nums(&[i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]]),
        )
    }
}

struct BodyCtx<'v, 'a> {
    view: &'v SceneView<'a>,
    object: &'v ObjectView<'a>,
    meshes: &'v AssetMeshes,
}

fn link_body(ctx: &BodyCtx<'_, '_>, li: usize, parent_from_link: &Pose) -> El {
    let o = ctx.object;
    let av = ctx.view.asset_of(o);
    let link = &av.asset.links[li];
    let name = body_name(o, av, li);
    let mut body = pose_attrs(El::new("body").attr("name", &name), parent_from_link);
    if li == 0 && o.hold == Hold::Free {
        body.push(El::new("freejoint").attr("name", &o.name));
    }
    if let Some(ji) = av.parent_joint[li] {
        let j = &av.asset.joints[ji];
        let q = super::view::joint_position(o.object, av.asset, ji);
        let kind = match j.kind {
            JointKind::Revolute => "hinge",
            JointKind::Prismatic => "slide",
        };
        body.push(
            El::new("joint")
                .attr("name", format!("{}/{}", o.name, av.joint_names[ji]))
                .attr("type", kind)
                .attr("axis", nums(&j.axis))
                .attr("range", nums(&[j.lower, j.upper]))
                .attr("damping", fmt_num(j.damping))
                .attr("ref", fmt_num(q)),
        );
    }
    if o.hold != Hold::Static {
        body.push(inertial(link));
    }
    for (k, mesh) in ctx.meshes.collision[li].iter().enumerate() {
        let mu = link.contact.mu_dynamic;
        let [spin, roll] = SOLVER.spin_roll_friction;
        body.push(
            El::new("geom")
                .attr("name", format!("{name}/c{k:03}"))
                .attr("class", "collision")
                .attr("mesh", mesh)
                .attr("friction", nums(&[mu, spin, roll])),
        );
    }
    for (k, (mesh, material)) in ctx.meshes.visual[li].iter().enumerate() {
        body.push(
            El::new("geom")
                .attr("name", format!("{name}/v{k}"))
                .attr("class", "visual")
                .attr("mesh", mesh)
                .attr("material", material),
        );
    }
    for c in av.children(li) {
        let parent_from_child = o.model_from_links[li]
            .inverse()
            .compose(&o.model_from_links[c]);
        body.push(link_body(ctx, c, &parent_from_child));
    }
    body
}

fn defaults() -> El {
    let s = &SOLVER;
    El::new("default")
        .child(El::new("mesh").attr("inertia", "shell"))
        .child(
            El::new("default").attr("class", "collision").child(
                El::new("geom")
                    .attr("type", "mesh")
                    .attr("group", COLLISION_GROUP)
                    .attr("contype", "1")
                    .attr("conaffinity", "1")
                    .attr("condim", s.condim)
                    .attr("solref", nums(&s.solref))
                    .attr("solimp", nums(&s.solimp))
                    .attr("margin", fmt_num(s.margin))
                    .attr("rgba", "0.8 0.3 0.3 0.5"),
            ),
        )
        .child(
            El::new("default").attr("class", "visual").child(
                El::new("geom")
                    .attr("type", "mesh")
                    .attr("group", VISUAL_GROUP)
                    .attr("contype", "0")
                    .attr("conaffinity", "0"),
            ),
        )
}

/// Arena size for `<size memory>`, MB. MuJoCo's default is sized from the model and ran out of
/// memory on dense shelves (about 500 contacts) with pyramidal cones; the chosen options use
/// about 1 MB per 1,400 constraint rows, so 32 MB plus 32 kB per collision piece leaves more
/// than ten times the measured peak.
fn arena_mb(view: &SceneView<'_>) -> usize {
    let pieces: usize = view
        .objects
        .iter()
        .map(|o| view.asset_of(o).asset.collision_pieces())
        .sum();
    32 + pieces.div_ceil(32)
}

/// Every file of the MJCF export, paths relative to `export/mujoco/`.
pub fn files(view: &SceneView<'_>) -> Result<Vec<ExportFile>, ExportError> {
    let mut files = Vec::new();
    let mut asset_el = El::new("asset");
    let mut meshes = Vec::with_capacity(view.assets.len());
    for av in &view.assets {
        meshes.push(asset_meshes(av, &mut asset_el, &mut files)?);
    }

    let (lo, hi) = view.bounds().unwrap_or(([0.0; 3], [1.0; 3]));
    let center = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    let extent = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2))
        .sqrt()
        .max(0.1)
        / 2.0;
    let mut world = El::new("worldbody").child(
        El::new("light")
            .attr("name", "sun")
            .attr("directional", "true")
            .attr("pos", nums(&[center[0], center[1], hi[2] + 2.0]))
            .attr("dir", "0.3 0.2 -1")
            .attr("castshadow", "false"),
    );
    let mut contact = El::new("contact");
    for o in &view.objects {
        let av = view.asset_of(o);
        let ctx = BodyCtx {
            view,
            object: o,
            meshes: &meshes[o.asset],
        };
        world.push(link_body(&ctx, 0, &o.world_from_links[0]));
        if o.hold != Hold::Static {
            let n = av.asset.links.len();
            for a in 0..n {
                for b in a + 1..n {
                    contact.push(
                        El::new("exclude")
                            .attr("body1", body_name(o, av, a))
                            .attr("body2", body_name(o, av, b)),
                    );
                }
            }
        }
    }

    let s = &SOLVER;
    let scene = view.scene;
    let mut root = El::new("mujoco")
        .attr("model", &scene.package_name)
        .child(
            El::new("compiler")
                .attr("angle", "radian")
                .attr("meshdir", "meshes")
                .attr("texturedir", "textures")
                .attr("autolimits", "true")
                .attr("inertiafromgeom", "false"),
        )
        .child(
            El::new("option")
                .attr("timestep", fmt_num(s.timestep))
                .attr("integrator", s.integrator)
                .attr("cone", s.cone)
                .attr("impratio", fmt_num(s.impratio))
                .attr("iterations", s.iterations)
                .attr("noslip_iterations", s.noslip_iterations),
        )
        .child(El::new("size").attr("memory", format!("{}M", arena_mb(view))))
        .child(
            El::new("statistic")
                .attr("center", nums(&center))
                .attr("extent", fmt_num(extent)),
        )
        .child(
            El::new("visual").child(
                El::new("headlight")
                    .attr("ambient", "0.35 0.35 0.35")
                    .attr("diffuse", "0.5 0.5 0.5"),
            ),
        )
        .child(
            El::new("custom")
                .child(
                    El::new("text")
                        .attr("name", "scenesmith/prompt")
                        .attr("data", plain_text(&scene.provenance.prompt)),
                )
                .child(El::new("text").attr("name", "scenesmith/generator").attr(
                    "data",
                    format!(
                        "scenesmith {} seed {}",
                        scene.provenance.tool_version, scene.provenance.seed
                    ),
                )),
        )
        .child(defaults())
        .child(asset_el)
        .child(world);
    if contact != El::new("contact") {
        root.push(contact);
    }
    files.insert(0, ExportFile::text("scene.xml", root.to_document()));
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visual_obj_flips_v_and_keeps_normals() {
        let mesh = crate::geometry::mesh::box_mesh([0.0; 3], [1.0; 3]).with_box_uvs(1.0);
        let obj = visual_obj(&mesh);
        assert_eq!(obj.matches("\nvt ").count(), mesh.positions.len());
        assert_eq!(obj.matches("\nvn ").count(), mesh.positions.len());
        let back = crate::geometry::obj::parse_obj(&obj).unwrap();
        assert_eq!(back.triangles.len(), mesh.triangles.len());
        // parse_obj flips v back to the top-left convention.
        let mut a: Vec<_> = mesh.uvs.iter().map(|u| [u[0], u[1]]).collect();
        let mut b: Vec<_> = back.uvs.iter().map(|u| [u[0], u[1]]).collect();
        a.sort_by(|x, y| x.partial_cmp(y).unwrap());
        b.sort_by(|x, y| x.partial_cmp(y).unwrap());
        a.dedup();
        b.dedup();
        for (x, y) in a.iter().zip(&b) {
            assert!((x[0] - y[0]).abs() < 1e-6 && (x[1] - y[1]).abs() < 1e-6);
        }
    }
}
