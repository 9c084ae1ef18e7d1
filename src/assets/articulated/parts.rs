//! Moving parts of procedural furniture and appliances: drawers that are real open boxes on
//! prismatic joints, doors and flaps on revolute joints at their hinge line, lids hinged at
//! the back.
//!
//! Every moving part stands a few millimetres clear of the carcass it belongs to (2 mm in
//! front of the carcass face, 3 mm inside drawer openings), so it never touches the body at
//! any joint position: articulated assets pass a self-collision check with filters off.

use crate::assets::procedural::parts::bar_handle;
use crate::assets::{Joint, JointKind, Link, LinkBuilder, Material};
use crate::geometry::GeometryError;
use crate::scene::{Pose, SurfaceRecord};

/// Gap between a moving front and the carcass face behind it, metres.
pub const FRONT_GAP: f64 = 0.002;
/// Side and top clearance of a drawer box in its opening, metres.
pub const DRAWER_CLEARANCE: f64 = 0.003;

/// A rectangular opening in a carcass front, model frame: x from `x0` to `x1`, z from `z0`
/// to `z1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Opening {
    /// Left edge, m.
    pub x0: f64,
    /// Right edge, m.
    pub x1: f64,
    /// Bottom edge, m.
    pub z0: f64,
    /// Top edge, m.
    pub z1: f64,
}

impl Opening {
    /// Width, m.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }
    /// Height, m.
    pub fn height(&self) -> f64 {
        self.z1 - self.z0
    }
}

/// Colours and material of a moving part.
#[derive(Debug, Clone, Copy)]
pub struct Look {
    /// Material of the part.
    pub material: Material,
    /// Colour of the front (door or drawer face).
    pub front: [f64; 3],
    /// Colour of the drawer box or the door's back.
    pub inner: [f64; 3],
    /// Colour of the handle.
    pub handle: [f64; 3],
}

/// A drawer in `opening` of a carcass whose front face is at `y_front`: an open box `depth`
/// deep behind a front panel that overlaps the opening by `overlay` on every side, sliding
/// out along +Y up to 75 % of its depth.
///
/// Returns the drawer link, its prismatic joint to `parent`, and the surface inside the box
/// (id = the drawer's name) so things can be placed in it.
pub fn drawer(
    name: &str,
    parent: &str,
    opening: Opening,
    y_front: f64,
    depth: f64,
    overlay: f64,
    look: Look,
) -> Result<(Link, Joint, SurfaceRecord), GeometryError> {
    let c = DRAWER_CLEARANCE;
    let xc = (opening.x0 + opening.x1) / 2.0;
    let bw = opening.width() - 2.0 * c;
    let bh = (opening.height() - 0.012).max(0.03);
    let bz = 0.004;
    let t = 0.012_f64.min(bw / 6.0);
    let tb = 0.010;
    let ft = 0.018;
    let fw = opening.width() + 2.0 * overlay;
    let fh = opening.height() + 2.0 * overlay;
    let mut b = LinkBuilder::new(name, Pose::from_xyz(xc, y_front, opening.z0), look.material);
    // Front panel, in front of the carcass face.
    b.add_box(
        [0.0, FRONT_GAP + ft / 2.0, opening.height() / 2.0],
        [fw, ft, fh],
        look.front,
    )?;
    // Open box behind it: bottom, two sides, back.
    let y_back = -depth;
    let side_len = depth + FRONT_GAP;
    let side_cy = y_back + side_len / 2.0;
    b.add_box(
        [0.0, side_cy, bz + tb / 2.0],
        [bw, side_len, tb],
        look.inner,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [
                sx * (bw / 2.0 - t / 2.0),
                side_cy,
                bz + tb + (bh - tb) / 2.0,
            ],
            [t, side_len, bh - tb],
            look.inner,
        )?;
    }
    b.add_box(
        [0.0, y_back + t / 2.0, bz + tb + (bh - tb) / 2.0],
        [bw - 2.0 * t, t, bh - tb],
        look.inner,
    )?;
    let handle_len = (fw * 0.4).clamp(0.06, 0.3);
    bar_handle(
        &mut b,
        [0.0, FRONT_GAP + ft, opening.height() / 2.0],
        handle_len,
        false,
        look.handle,
    )?;
    let link = b.finish()?;
    let joint = Joint {
        name: format!("{name}_slide"),
        kind: JointKind::Prismatic,
        parent: parent.to_string(),
        child: name.to_string(),
        axis: drawer_axis(),
        lower: 0.0,
        upper: 0.75 * depth,
        damping: 3.0,
        effort: 100.0,
    };
    let inner_w = bw - 2.0 * t;
    let inner_d = depth - t;
    let surface = SurfaceRecord {
        id: name.to_string(),
        link: name.to_string(),
        center: [
            xc,
            y_front + y_back + t + inner_d / 2.0,
            opening.z0 + bz + tb,
        ],
        size: [inner_w, inner_d],
        clearance: bh - tb,
    };
    Ok((link, joint, surface))
}

/// Rise of a drawer's runners per metre it opens. Runners that climb a little as the drawer
/// comes out (as self-closing runners do) hold a closed drawer shut against its stop when
/// the piece stands a little out of level: on level runners a tilt of 0.001 rad, which point
/// contact on a carpet gives, lets a loaded drawer creep 10 cm open in 5 s.
pub const DRAWER_RUNNER_SLOPE: f64 = 0.015;

/// Unit slide axis of a drawer (child frame): out of the front (+Y), climbing
/// `DRAWER_RUNNER_SLOPE`.
pub fn drawer_axis() -> [f64; 3] {
    let n = (1.0 + DRAWER_RUNNER_SLOPE * DRAWER_RUNNER_SLOPE).sqrt();
    [0.0, 1.0 / n, DRAWER_RUNNER_SLOPE / n]
}

/// Which edge a door turns about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hinge {
    /// Vertical hinge on the left edge (seen from the front); opens to the left.
    Left,
    /// Vertical hinge on the right edge.
    Right,
    /// Horizontal hinge on the bottom edge; the door folds down (ovens, dishwashers).
    Bottom,
}

/// A door covering `opening` (plus `overlay` on every side) in front of a carcass face at
/// `y_front`, turning about its `hinge` edge outward up to `upper` radians. `glass` makes
/// the panel a framed see-through pane.
///
/// The hinge line runs along the door's front outer edge: turning about it, no point of the
/// door ever moves behind the door's closed back face or past its hinge edge, so the door
/// cannot hit the carcass or a neighbouring door at any angle.
#[allow(clippy::too_many_arguments)]
pub fn door(
    name: &str,
    parent: &str,
    opening: Opening,
    y_front: f64,
    overlay: f64,
    thickness: f64,
    hinge: Hinge,
    upper: f64,
    glass: bool,
    look: Look,
) -> Result<(Link, Joint), GeometryError> {
    let w = opening.width() + 2.0 * overlay;
    let h = opening.height() + 2.0 * overlay;
    let (origin_x, sx, axis) = match hinge {
        Hinge::Left => (opening.x0 - overlay, 1.0, [0.0, 0.0, 1.0]),
        Hinge::Right => (opening.x1 + overlay, -1.0, [0.0, 0.0, -1.0]),
        Hinge::Bottom => (opening.x0 - overlay, 1.0, [-1.0, 0.0, 0.0]),
    };
    let mut b = LinkBuilder::new(
        name,
        Pose::from_xyz(
            origin_x,
            y_front + FRONT_GAP + thickness,
            opening.z0 - overlay,
        ),
        look.material,
    );
    let cx = sx * w / 2.0;
    let yc = -thickness / 2.0;
    if glass {
        let f = (w.min(h) * 0.12).clamp(0.025, 0.07);
        b.add_box([cx, yc, f / 2.0], [w, thickness, f], look.front)?;
        b.add_box([cx, yc, h - f / 2.0], [w, thickness, f], look.front)?;
        b.add_box(
            [sx * f / 2.0, yc, h / 2.0],
            [f, thickness, h - 2.0 * f],
            look.front,
        )?;
        b.add_box(
            [sx * (w - f / 2.0), yc, h / 2.0],
            [f, thickness, h - 2.0 * f],
            look.front,
        )?;
        let pane = [w - 2.0 * f, 0.005, h - 2.0 * f];
        b.density(2500.0);
        b.add_part_rgba(
            crate::geometry::mesh::box_mesh([cx, yc, h / 2.0], pane),
            crate::geometry::ConvexPiece::cuboid([cx, yc, h / 2.0], pane)?,
            [0.75, 0.85, 0.9, 0.35],
        );
        b.material_density();
    } else {
        b.add_box([cx, yc, h / 2.0], [w, thickness, h], look.front)?;
    }
    match hinge {
        Hinge::Left | Hinge::Right => {
            let len = (h * 0.18).clamp(0.08, 0.35);
            let z = if h > 1.2 {
                1.0 - (opening.z0 - overlay)
            } else {
                h * 0.5
            };
            let z = z.clamp(len / 2.0 + 0.02, h - len / 2.0 - 0.02);
            bar_handle(&mut b, [sx * (w - 0.045), 0.0, z], len, true, look.handle)?;
        }
        Hinge::Bottom => {
            bar_handle(
                &mut b,
                [cx, 0.0, h - 0.05],
                (w * 0.6).min(0.5),
                false,
                look.handle,
            )?;
        }
    }
    let joint = Joint {
        name: format!("{name}_hinge"),
        kind: JointKind::Revolute,
        parent: parent.to_string(),
        child: name.to_string(),
        axis,
        lower: 0.0,
        upper,
        damping: 0.5,
        effort: 30.0,
    };
    Ok((b.finish()?, joint))
}

/// Two doors side by side covering `opening`: the left one hinged on the left edge, the right
/// one on the right edge, meeting in the middle with a 3 mm gap (their inner edges do not
/// overlay each other). Named `door_left` and `door_right`.
#[allow(clippy::too_many_arguments)]
pub fn door_pair(
    parent: &str,
    opening: Opening,
    y_front: f64,
    overlay: f64,
    thickness: f64,
    upper: f64,
    glass: bool,
    look: Look,
) -> Result<[(Link, Joint); 2], GeometryError> {
    let mid = (opening.x0 + opening.x1) / 2.0;
    let half_gap = 0.0015;
    let left = Opening {
        x1: mid - half_gap - overlay,
        ..opening
    };
    let right = Opening {
        x0: mid + half_gap + overlay,
        ..opening
    };
    Ok([
        door(
            "door_left",
            parent,
            left,
            y_front,
            overlay,
            thickness,
            Hinge::Left,
            upper,
            glass,
            look,
        )?,
        door(
            "door_right",
            parent,
            right,
            y_front,
            overlay,
            thickness,
            Hinge::Right,
            upper,
            glass,
            look,
        )?,
    ])
}

/// A lid lying on top of a box whose top is at `z_top`, spanning x in `[x0, x1]` and y in
/// `[y0, y1]`, hinged along its back top edge (y0) and opening upward up to `upper` radians;
/// like a door, it never moves below its closed underside.
#[allow(clippy::too_many_arguments)]
pub fn lid(
    name: &str,
    parent: &str,
    x: [f64; 2],
    y: [f64; 2],
    z_top: f64,
    thickness: f64,
    upper: f64,
    look: Look,
) -> Result<(Link, Joint), GeometryError> {
    let w = x[1] - x[0];
    let d = y[1] - y[0];
    let mut b = LinkBuilder::new(
        name,
        Pose::from_xyz(x[0], y[0], z_top + FRONT_GAP + thickness),
        look.material,
    );
    b.add_box(
        [w / 2.0, d / 2.0, -thickness / 2.0],
        [w, d, thickness],
        look.front,
    )?;
    let joint = Joint {
        name: format!("{name}_hinge"),
        kind: JointKind::Revolute,
        parent: parent.to_string(),
        child: name.to_string(),
        axis: [1.0, 0.0, 0.0],
        lower: 0.0,
        upper,
        damping: 0.3,
        effort: 20.0,
    };
    Ok((b.finish()?, joint))
}
