//! [`LinkBuilder`]: collects the visual parts and convex collision pieces of one link and
//! computes its mass properties.
//!
//! Each collision piece carries a [`Fill`]: the density it is made of and whether it is solid
//! or a closed shell of some wall thickness (a fridge cabinet, a bottle, a television). Mass,
//! centre of mass and inertia then follow from the pieces exactly (see [`super::physical`]).

use super::physical::{self, Fill};
use super::procedural::shapes;
use super::{Contact, Link, Material, Texture, VisualPart};
use crate::geometry::convex::MAX_PIECE_VERTICES;
use crate::geometry::{ConvexPiece, GeometryError, MassProps, TriMesh, mesh};
use crate::scene::Pose;

/// Collects the parts of one link; [`LinkBuilder::finish`] computes its mass properties.
#[derive(Debug, Clone)]
pub struct LinkBuilder {
    pub(crate) name: String,
    pub(crate) model_from_link: Pose,
    pub(crate) visuals: Vec<VisualPart>,
    pub(crate) collisions: Vec<ConvexPiece>,
    pub(crate) fills: Vec<Fill>,
    pub(crate) material: Material,
    density: f64,
    shell: Option<f64>,
}

impl LinkBuilder {
    /// A link named `name` made of `material`, with its frame at `model_from_link`.
    pub fn new(name: &str, model_from_link: Pose, material: Material) -> Self {
        LinkBuilder {
            name: name.to_string(),
            model_from_link,
            visuals: Vec::new(),
            collisions: Vec::new(),
            fills: Vec::new(),
            material,
            density: material.density,
            shell: None,
        }
    }

    /// The link's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Density (kg/m^3) of the collision pieces added from now on; the material's density
    /// until changed (upholstery foam, a glass panel in a wooden door, ...).
    pub fn density(&mut self, kg_per_m3: f64) -> &mut Self {
        self.density = kg_per_m3;
        self
    }

    /// Back to the link material's density for the pieces added from now on.
    pub fn material_density(&mut self) -> &mut Self {
        self.density = self.material.density;
        self
    }

    /// Pieces added from now on are hollow shells of this wall thickness (metres), or solid
    /// with `None`. The collision stays the closed convex piece; only the mass changes.
    pub fn shell(&mut self, wall_thickness: Option<f64>) -> &mut Self {
        self.shell = wall_thickness;
        self
    }

    fn fill(&self) -> Fill {
        Fill {
            density: self.density,
            shell: self.shell,
        }
    }

    fn next_part_name(&self) -> String {
        format!("part_{}", self.visuals.len())
    }

    /// A box part, visual and collision, of full extents `size` centred at `center` (link frame).
    pub fn add_box(
        &mut self,
        center: [f64; 3],
        size: [f64; 3],
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let piece = ConvexPiece::cuboid(center, size)?;
        Ok(self.add_part(mesh::box_mesh(center, size), piece, color))
    }

    /// A vertical cylinder part, visual (smooth-ish) and collision (prism).
    pub fn add_cylinder(
        &mut self,
        center_xy: [f64; 2],
        radius: f64,
        z0: f64,
        z1: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let piece = ConvexPiece::cylinder(center_xy[0], center_xy[1], radius, z0, z1, 16)?;
        let visual = mesh::cylinder_mesh(center_xy[0], center_xy[1], radius, z0, z1, 24);
        Ok(self.add_part(visual, piece, color))
    }

    /// A round rod (cylinder) from `p0` to `p1`: legs at an angle, rails, handles, poles.
    pub fn add_rod(
        &mut self,
        p0: [f64; 3],
        p1: [f64; 3],
        radius: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        self.add_frustum(p0, p1, radius, radius, color)
    }

    /// A frustum from `p0` (radius `r0`) to `p1` (radius `r1`): tapered legs, lamp shades.
    pub fn add_frustum(
        &mut self,
        p0: [f64; 3],
        p1: [f64; 3],
        r0: f64,
        r1: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let segments = if r0.max(r1) > 0.05 { 20 } else { 10 };
        let piece = shapes::frustum_piece(p0, p1, r0, r1, segments)?;
        let visual = shapes::frustum_mesh(p0, p1, r0, r1, segments.max(16));
        Ok(self.add_part(visual, piece, color))
    }

    /// A leg from `top` down to the floor at `foot_xy`: a rod whose bottom rim just touches
    /// z = 0 however much it leans.
    pub fn add_leg(
        &mut self,
        top: [f64; 3],
        foot_xy: [f64; 2],
        radius: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let (dx, dy) = (top[0] - foot_xy[0], top[1] - foot_xy[1]);
        let horizontal = (dx * dx + dy * dy).sqrt();
        // The end disc is tilted by the lean angle; its lowest point sits r sin(lean) lower.
        let lean_sin = horizontal
            / (horizontal * horizontal + top[2] * top[2])
                .sqrt()
                .max(1e-12);
        self.add_rod(
            [foot_xy[0], foot_xy[1], radius * lean_sin],
            top,
            radius,
            color,
        )
    }

    /// A polyline of rods through `points` (bent tubes: chair frames, handles, hooks).
    pub fn add_tube(
        &mut self,
        points: &[[f64; 3]],
        radius: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        for w in points.windows(2) {
            self.add_rod(w[0], w[1], radius, color)?;
        }
        Ok(self)
    }

    /// An ellipsoid with semi-axes `radii`: fruit, heads, bulbs, cushions.
    pub fn add_ellipsoid(
        &mut self,
        center: [f64; 3],
        radii: [f64; 3],
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let piece = shapes::ellipsoid_piece(center, radii)?;
        Ok(self.add_part(shapes::ellipsoid_mesh(center, radii, 20), piece, color))
    }

    /// A box with rounded edges: cushions, mattresses, appliance bodies.
    pub fn add_rounded_box(
        &mut self,
        center: [f64; 3],
        size: [f64; 3],
        radius: f64,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let piece = shapes::rounded_box_piece(center, size, radius)?;
        Ok(self.add_part(shapes::rounded_box_mesh(center, size, radius), piece, color))
    }

    /// A solid of revolution about +Z through the side profile `(radius, z)` (bottom to top),
    /// collision one frustum per profile segment.
    pub fn add_solid_lathe(
        &mut self,
        profile: &[(f64, f64)],
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        for piece in shapes::solid_lathe_pieces(profile, 16)? {
            self.add_collision(piece);
        }
        Ok(self.add_visual(shapes::solid_lathe_mesh(profile, 32), color))
    }

    /// A solid of revolution like [`Self::add_solid_lathe`], shifted to `(x, y)`.
    pub fn add_solid_lathe_at(
        &mut self,
        xy: [f64; 2],
        profile: &[(f64, f64)],
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let at = Pose::from_xyz(xy[0], xy[1], 0.0);
        for piece in shapes::solid_lathe_pieces(profile, 16)? {
            self.add_collision(piece.transformed(&at));
        }
        Ok(self.add_visual(
            shapes::solid_lathe_mesh(profile, 32).transformed(&at),
            color,
        ))
    }

    /// A hollow vessel (see [`shapes::vessel`]) centred at `(x, y)`, bottom at `z0`.
    pub fn add_vessel(
        &mut self,
        at: [f64; 3],
        outer: &[(f64, f64)],
        wall: f64,
        base: f64,
        sectors: usize,
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let (visual, pieces) = shapes::vessel(outer, wall, base, sectors)?;
        let pose = Pose::from_xyz(at[0], at[1], at[2]);
        for piece in pieces {
            self.add_collision(piece.transformed(&pose));
        }
        Ok(self.add_visual(visual.transformed(&pose), color))
    }

    /// A hollow vessel stretched by `scale_xy` in x and y (oval baskets, toilet bowls).
    #[allow(clippy::too_many_arguments)]
    pub fn add_vessel_scaled(
        &mut self,
        at: [f64; 3],
        outer: &[(f64, f64)],
        wall: f64,
        base: f64,
        sectors: usize,
        scale_xy: [f64; 2],
        color: [f64; 3],
    ) -> Result<&mut Self, GeometryError> {
        let (visual, pieces) = shapes::vessel(outer, wall, base, sectors)?;
        let pose = Pose::from_xyz(at[0], at[1], at[2]);
        let s = [scale_xy[0], scale_xy[1], 1.0];
        for piece in pieces {
            let pts: Vec<[f64; 3]> = piece
                .vertices
                .iter()
                .map(|v| [v[0] * s[0], v[1] * s[1], v[2]])
                .collect();
            self.add_collision(ConvexPiece::from_points(&pts)?.transformed(&pose));
        }
        Ok(self.add_visual(visual.scaled(s).transformed(&pose), color))
    }

    /// A visual-only box (small details: knobs, screens, buttons, labels).
    pub fn add_detail(&mut self, center: [f64; 3], size: [f64; 3], color: [f64; 3]) -> &mut Self {
        self.add_visual(mesh::box_mesh(center, size), color)
    }

    /// A part whose visual is `visual` and whose collision is the convex `piece`.
    pub fn add_part(&mut self, visual: TriMesh, piece: ConvexPiece, color: [f64; 3]) -> &mut Self {
        self.add_collision(piece);
        self.add_visual(visual, color)
    }

    /// A part with a see-through or tinted visual (`rgba`, alpha < 1 blends) and a collision.
    pub fn add_part_rgba(
        &mut self,
        visual: TriMesh,
        piece: ConvexPiece,
        rgba: [f64; 4],
    ) -> &mut Self {
        self.add_collision(piece);
        self.add_visual_rgba(visual, rgba)
    }

    /// A visual-only mesh (link frame).
    pub fn add_visual(&mut self, mesh: TriMesh, color: [f64; 3]) -> &mut Self {
        self.add_visual_rgba(mesh, [color[0], color[1], color[2], 1.0])
    }

    /// A visual-only mesh with an RGBA colour.
    pub fn add_visual_rgba(&mut self, mesh: TriMesh, rgba: [f64; 4]) -> &mut Self {
        let name = self.next_part_name();
        self.visuals.push(VisualPart {
            name,
            mesh,
            color: rgba,
            texture: None,
        });
        self
    }

    /// A visual-only textured mesh (link frame); the mesh must carry `uvs`.
    pub fn add_textured_visual(&mut self, mesh: TriMesh, texture: Texture) -> &mut Self {
        let name = self.next_part_name();
        self.visuals.push(VisualPart {
            name,
            mesh,
            color: [1.0, 1.0, 1.0, 1.0],
            texture: Some(texture),
        });
        self
    }

    /// A collision-only convex piece (link frame), filled as currently set.
    pub fn add_collision(&mut self, piece: ConvexPiece) -> &mut Self {
        self.collisions.push(piece);
        self.fills.push(self.fill());
        self
    }

    /// Number of collision pieces so far.
    pub fn piece_count(&self) -> usize {
        self.collisions.len()
    }

    /// Computes mass properties from the pieces and their fills and returns the link, its
    /// collision pieces simplified for contact ([`ConvexPiece::simplified`]): the mass is the
    /// solid's as modelled, the contact geometry what the physics engines can carry.
    pub fn finish(self) -> Result<Link, GeometryError> {
        let mass = if self
            .fills
            .iter()
            .all(|f| f.shell.is_none() && f.density == self.material.density)
        {
            MassProps::from_pieces(&self.collisions, self.material.density)?
        } else {
            physical::mass_props(&self.collisions, &self.fills)?
        };
        Ok(Link {
            name: self.name,
            model_from_link: self.model_from_link,
            visuals: self.visuals,
            collisions: self
                .collisions
                .iter()
                .map(|p| p.simplified(MAX_PIECE_VERTICES))
                .collect(),
            mass,
            contact: Contact::from(&self.material),
        })
    }

    /// Returns the link without mass properties (static architecture).
    pub fn finish_static(self) -> Link {
        Link {
            name: self.name,
            model_from_link: self.model_from_link,
            visuals: self.visuals,
            collisions: self.collisions,
            mass: MassProps {
                mass: 1.0,
                com: [0.0; 3],
                inertia: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            },
            contact: Contact::from(&self.material),
        }
    }
}
