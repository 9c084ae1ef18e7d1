//! SDFormat 1.9 writer with Drake extensions (`xmlns:drake`).
//!
//! One model per asset: links with glTF visuals, convex OBJ collisions declared with
//! `drake:declare_convex` and `drake:proximity_properties`, inertials, revolute/prismatic joints
//! with limits and damping, and a collision filter group that turns off self-collision inside
//! articulated models. URIs are relative to the SDF file, so an asset directory can move.

use crate::assets::material::HYDROELASTIC_MODULUS_PA;
use crate::assets::{Asset, Link};
use crate::formats::gltf::link_visual_gltf;
use crate::geometry::obj::convex_to_obj;
use crate::scene::Pose;
use crate::util::xml::{El, fmt_num, nums};

/// A file of an asset directory: path relative to the directory, and its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct AssetFile {
    /// Relative path, e.g. `model.sdf`, `collision_003.obj`.
    pub name: String,
    /// Content.
    pub bytes: Vec<u8>,
}

/// SDFormat `<pose>` text: `x y z roll pitch yaw` (metres, radians).
pub fn pose_text(pose: &Pose) -> String {
    let t = pose.translation();
    let rpy = pose.rpy();
    nums(&[t.x, t.y, t.z, rpy[0], rpy[1], rpy[2]])
}

/// File name of the n-th collision piece of an asset.
pub fn collision_file_name(n: usize) -> String {
    format!("collision_{n:03}.obj")
}

fn inertial(link: &Link) -> El {
    let m = &link.mass;
    let i = &m.inertia;
    El::new("inertial")
        .child(El::leaf(
            "pose",
            nums(&[m.com[0], m.com[1], m.com[2], 0.0, 0.0, 0.0]),
        ))
        .child(El::leaf("mass", fmt_num(m.mass)))
        .child(
            El::new("inertia")
                .child(El::leaf("ixx", fmt_num(i[0][0])))
                .child(El::leaf("ixy", fmt_num(i[0][1])))
                .child(El::leaf("ixz", fmt_num(i[0][2])))
                .child(El::leaf("iyy", fmt_num(i[1][1])))
                .child(El::leaf("iyz", fmt_num(i[1][2])))
                .child(El::leaf("izz", fmt_num(i[2][2]))),
        )
}

/// Renders an asset: `model.sdf`, one `<link>.gltf` + `<link>.bin` per link with visuals, and
/// one `collision_NNN.obj` per convex piece (numbered across links).
pub fn asset_files(asset: &Asset) -> Vec<AssetFile> {
    let mut files = Vec::new();
    let mut model = El::new("model").attr("name", &asset.id);
    if asset.is_static {
        model.push(El::leaf("static", "true"));
    }
    let mut piece_no = 0usize;
    for link in &asset.links {
        let mut el = El::new("link").attr("name", &link.name);
        el.push(El::leaf("pose", pose_text(&link.model_from_link)));
        if !asset.is_static {
            el.push(inertial(link));
        }
        if !link.visuals.is_empty() {
            let gltf_name = format!("{}.gltf", link.name);
            let bin_name = format!("{}.bin", link.name);
            let g = link_visual_gltf(&link.name, &link.visuals, &bin_name);
            files.push(AssetFile {
                name: gltf_name.clone(),
                bytes: g.gltf.into_bytes(),
            });
            files.push(AssetFile {
                name: bin_name,
                bytes: g.bin,
            });
            for (name, bytes) in g.images {
                if !files.iter().any(|f| f.name == name) {
                    files.push(AssetFile { name, bytes });
                }
            }
            el.push(El::new("visual").attr("name", "visual").child(
                El::new("geometry").child(El::new("mesh").child(El::leaf("uri", &gltf_name))),
            ));
        }
        for piece in &link.collisions {
            let file = collision_file_name(piece_no);
            files.push(AssetFile {
                name: file.clone(),
                bytes: convex_to_obj(piece).into_bytes(),
            });
            el.push(
                El::new("collision")
                    .attr("name", format!("collision_{piece_no:03}"))
                    .child(
                        El::new("geometry").child(
                            El::new("mesh")
                                .child(El::leaf("uri", &file))
                                .child(El::new("drake:declare_convex")),
                        ),
                    )
                    .child(
                        El::new("drake:proximity_properties")
                            .child(El::new("drake:compliant_hydroelastic"))
                            .child(El::leaf(
                                "drake:hydroelastic_modulus",
                                fmt_num(HYDROELASTIC_MODULUS_PA),
                            ))
                            .child(El::leaf(
                                "drake:mu_dynamic",
                                fmt_num(link.contact.mu_dynamic),
                            ))
                            .child(El::leaf("drake:mu_static", fmt_num(link.contact.mu_static)))
                            .child(El::leaf(
                                "drake:hunt_crossley_dissipation",
                                fmt_num(link.contact.hunt_crossley_dissipation),
                            )),
                    ),
            );
            piece_no += 1;
        }
        model.push(el);
    }
    for joint in &asset.joints {
        model.push(
            El::new("joint")
                .attr("name", &joint.name)
                .attr("type", joint.kind.as_str())
                .child(El::leaf("parent", &joint.parent))
                .child(El::leaf("child", &joint.child))
                .child(El::leaf("pose", "0 0 0 0 0 0"))
                .child(
                    El::new("axis")
                        .child(El::leaf("xyz", nums(&joint.axis)))
                        .child(
                            El::new("limit")
                                .child(El::leaf("lower", fmt_num(joint.lower)))
                                .child(El::leaf("upper", fmt_num(joint.upper)))
                                .child(El::leaf("effort", fmt_num(joint.effort))),
                        )
                        .child(
                            El::new("dynamics").child(El::leaf("damping", fmt_num(joint.damping))),
                        ),
                ),
        );
    }
    if asset.links.len() > 1 {
        let group = "no_self_collision";
        model.push(
            El::new("drake:collision_filter_group")
                .attr("name", group)
                .children(
                    asset
                        .links
                        .iter()
                        .map(|l| El::leaf("drake:member", &l.name)),
                )
                .child(El::leaf("drake:ignored_collision_filter_group", group)),
        );
    }
    let sdf = El::new("sdf")
        .attr("version", "1.9")
        .attr("xmlns:drake", "http://drake.mit.edu")
        .child(model);
    files.insert(
        0,
        AssetFile {
            name: "model.sdf".into(),
            bytes: sdf.to_document().into_bytes(),
        },
    );
    files
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    fn text_of(files: &[AssetFile], name: &str) -> String {
        String::from_utf8(files.iter().find(|f| f.name == name).unwrap().bytes.clone()).unwrap()
    }

    #[test]
    fn cabinet_sdf_has_joint_filter_and_convex_collisions() {
        let asset = build(&AssetRequest::new("cabinet", 1)).unwrap();
        let files = asset_files(&asset);
        let sdf = text_of(&files, "model.sdf");
        assert!(sdf.contains("<sdf version=\"1.9\" xmlns:drake=\"http://drake.mit.edu\">"));
        assert!(sdf.contains("<joint name=\"door_hinge\" type=\"revolute\">"));
        assert!(sdf.contains("<drake:collision_filter_group name=\"no_self_collision\">"));
        assert_eq!(
            sdf.matches("<drake:declare_convex/>").count(),
            asset.collision_pieces()
        );
        assert_eq!(
            files.iter().filter(|f| f.name.ends_with(".obj")).count(),
            asset.collision_pieces()
        );
        assert_eq!(sdf.matches("<inertial>").count(), 2);
        assert!(sdf.contains("<drake:mu_dynamic>0.4</drake:mu_dynamic>"));
    }

    #[test]
    fn every_collider_declares_the_compliant_contact_model() {
        let asset = build(&AssetRequest::new("mug", 1)).unwrap();
        let sdf = text_of(&asset_files(&asset), "model.sdf");
        let pieces = asset.collision_pieces();
        assert_eq!(
            sdf.matches("<drake:compliant_hydroelastic/>").count(),
            pieces
        );
        assert_eq!(
            sdf.matches("<drake:hydroelastic_modulus>100000000</drake:hydroelastic_modulus>")
                .count(),
            pieces
        );
        // The material table's 0.5 to 3 s/m is raised to the minimum that rests.
        let table = crate::assets::material::material(&asset.material).unwrap();
        assert!(table.hunt_crossley_dissipation < 10.0);
        assert_eq!(
            sdf.matches("<drake:hunt_crossley_dissipation>10</drake:hunt_crossley_dissipation>")
                .count(),
            pieces
        );
    }

    #[test]
    fn single_link_asset_has_no_filter_group() {
        let asset = build(&AssetRequest::new("mug", 1)).unwrap();
        let sdf = text_of(&asset_files(&asset), "model.sdf");
        assert!(!sdf.contains("collision_filter_group"));
        assert!(sdf.contains("<uri>body.gltf</uri>"));
    }
}
