//! One linearised step of the projection: the QP of the module doc around the current offsets.
//!
//! The unknowns are each movable body's step (three per body) and one elastic slack per
//! contact row and per region half-plane; the slacks keep every QP feasible, their linear cost
//! keeps them zero whenever the rows can be met inside the trust region.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};
use nalgebra::Vector3;

use super::{Body, ProjectionOptions, Row};

/// Cost of one metre of slack against a squared metre of displacement: high enough that the
/// solver moves objects rather than leave a row unmet.
const SLACK_WEIGHT: f64 = 1e3;

/// One QP step: returns per-body step offsets (zero for fixed bodies), or `None` when the
/// solver failed.
pub(super) fn qp_step(
    bodies: &[Body],
    offsets: &[Vector3<f64>],
    rows: &[Row],
    opts: &ProjectionOptions,
    trust: f64,
) -> Option<Vec<Vector3<f64>>> {
    let regions = region_halfplanes(bodies, opts);
    let vars = Variables::new(bodies, rows.len(), regions.len());
    let at = Linearisation {
        bodies,
        offsets,
        rows,
        regions: &regions,
        vars: &vars,
    };
    let mut g = Constraints::default();
    at.contact_rows(&mut g);
    at.region_rows(&mut g);
    at.slacks_nonnegative(&mut g);
    at.trust_and_floor_bounds(&mut g, opts, trust);
    let x = solve_qp(&vars, offsets, g)?;
    Some(at.steps(&x, opts))
}

/// The half-planes `(body, [a, b, c])` of every movable body's XY region.
fn region_halfplanes(bodies: &[Body], opts: &ProjectionOptions) -> Vec<(usize, [f64; 3])> {
    bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.movable)
        .flat_map(|(i, b)| {
            opts.regions
                .get(&b.id)
                .map(|r| {
                    r.halfplanes
                        .iter()
                        .map(move |h| (i, *h))
                        .collect::<Vec<_>>()
                })
                .unwrap_or_default()
        })
        .collect()
}

/// Where each unknown sits in the QP's vector: the steps of the movable bodies in body order,
/// then the contact slacks, then the region slacks.
struct Variables {
    /// Index among the movable bodies, per body (`None` for a fixed one).
    var_of: Vec<Option<usize>>,
    /// Movable bodies.
    movable: usize,
    contact_rows: usize,
    region_rows: usize,
}

impl Variables {
    fn new(bodies: &[Body], contact_rows: usize, region_rows: usize) -> Variables {
        let mut k = 0;
        let var_of: Vec<Option<usize>> = bodies
            .iter()
            .map(|b| {
                b.movable.then(|| {
                    k += 1;
                    k - 1
                })
            })
            .collect();
        Variables {
            movable: k,
            var_of,
            contact_rows,
            region_rows,
        }
    }

    /// Column of component `k` of movable body `v`'s step.
    fn step(&self, v: usize, k: usize) -> usize {
        3 * v + k
    }

    /// Column of slack `s` (contact slacks first, then region slacks).
    fn slack(&self, s: usize) -> usize {
        3 * self.movable + s
    }

    fn slacks(&self) -> usize {
        self.contact_rows + self.region_rows
    }

    fn len(&self) -> usize {
        3 * self.movable + self.slacks()
    }
}

/// Sparse `G x <= h`, row by row.
#[derive(Default)]
struct Constraints {
    rows: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
    h: Vec<f64>,
}

impl Constraints {
    /// Appends `sum entries <= rhs` (zero coefficients are left out of the matrix).
    fn push(&mut self, entries: &[(usize, f64)], rhs: f64) {
        let row = self.h.len();
        for &(col, val) in entries {
            if val != 0.0 {
                self.rows.push(row);
                self.cols.push(col);
                self.vals.push(val);
            }
        }
        self.h.push(rhs);
    }
}

/// The pair rows and regions at the current offsets, with the columns of their unknowns.
struct Linearisation<'a> {
    bodies: &'a [Body],
    offsets: &'a [Vector3<f64>],
    rows: &'a [Row],
    regions: &'a [(usize, [f64; 3])],
    vars: &'a Variables,
}

impl Linearisation<'_> {
    /// `d + n.(s_b - s_a) + slack >= target` per pair row.
    fn contact_rows(&self, g: &mut Constraints) {
        let vars = self.vars;
        for (s, r) in self.rows.iter().enumerate() {
            let mut e: Vec<(usize, f64)> = Vec::with_capacity(7);
            if let Some(va) = vars.var_of[r.a] {
                e.extend((0..3).map(|k| (vars.step(va, k), r.n[k])));
            }
            if let Some(vb) = vars.var_of[r.b] {
                e.extend((0..3).map(|k| (vars.step(vb, k), -r.n[k])));
            }
            e.push((vars.slack(s), -1.0));
            g.push(&e, r.d - r.target);
        }
    }

    /// `a.(p + offset + step) - slack <= c` per region half-plane (XY only).
    fn region_rows(&self, g: &mut Constraints) {
        let vars = self.vars;
        for (s, (i, hp)) in self.regions.iter().enumerate() {
            let Some(v) = vars.var_of[*i] else { continue };
            let cur = self.bodies[*i].origin0 + self.offsets[*i];
            let e = [
                (vars.step(v, 0), hp[0]),
                (vars.step(v, 1), hp[1]),
                (vars.slack(self.rows.len() + s), -1.0),
            ];
            g.push(&e, hp[2] - hp[0] * cur.x - hp[1] * cur.y);
        }
    }

    fn slacks_nonnegative(&self, g: &mut Constraints) {
        for s in 0..self.vars.slacks() {
            g.push(&[(self.vars.slack(s), -1.0)], 0.0);
        }
    }

    /// Box bounds per step component: the trust region, with z raised to meet the floor (and
    /// pinned to exactly that lift when objects only slide).
    fn trust_and_floor_bounds(&self, g: &mut Constraints, opts: &ProjectionOptions, trust: f64) {
        for (i, b) in self.bodies.iter().enumerate() {
            let Some(v) = self.vars.var_of[i] else {
                continue;
            };
            let lift = match opts.floor_z {
                Some(fz) => fz - (b.lo0.z + self.offsets[i].z),
                None => f64::NEG_INFINITY,
            };
            for k in 0..3 {
                let (mut lo, mut hi) = (-trust, trust);
                if k == 2 {
                    if opts.xy_only {
                        lo = lift.max(0.0);
                        hi = lo;
                    } else {
                        lo = lo.max(lift);
                        hi = hi.max(lift);
                    }
                }
                g.push(&[(self.vars.step(v, k), 1.0)], hi);
                g.push(&[(self.vars.step(v, k), -1.0)], -lo);
            }
        }
    }

    /// Per-body steps from the solution `x`.
    fn steps(&self, x: &[f64], opts: &ProjectionOptions) -> Vec<Vector3<f64>> {
        // A body no row mentions has its exact optimum at its start: return it there, rather
        // than keep the interior-point method's last-digit noise.
        let mut constrained = vec![false; self.bodies.len()];
        for r in self.rows {
            constrained[r.a] = true;
            constrained[r.b] = true;
        }
        for (i, _) in self.regions {
            constrained[*i] = true;
        }
        let vars = self.vars;
        vars.var_of
            .iter()
            .enumerate()
            .map(|(i, v)| match v {
                Some(_)
                    if !constrained[i]
                        && opts.floor_z.is_none_or(|fz| self.bodies[i].lo0.z >= fz) =>
                {
                    -self.offsets[i]
                }
                Some(v) => Vector3::new(
                    x[vars.step(*v, 0)],
                    x[vars.step(*v, 1)],
                    x[vars.step(*v, 2)],
                ),
                None => Vector3::zeros(),
            })
            .collect()
    }
}

/// Minimises `sum ||offset + step||^2 + SLACK_WEIGHT * sum slack` subject to `g`; the
/// solution vector, or `None` when clarabel does not solve it.
fn solve_qp(vars: &Variables, offsets: &[Vector3<f64>], g: Constraints) -> Option<Vec<f64>> {
    let n = vars.len();
    let mut p_i = Vec::new();
    let mut q = vec![0.0; n];
    for (i, v) in vars.var_of.iter().enumerate() {
        if let Some(v) = v {
            for k in 0..3 {
                p_i.push(vars.step(*v, k));
                q[vars.step(*v, k)] = 2.0 * offsets[i][k];
            }
        }
    }
    for s in 0..vars.slacks() {
        q[vars.slack(s)] = SLACK_WEIGHT;
    }
    let p = CscMatrix::new_from_triplets(n, n, p_i.clone(), p_i, vec![2.0; 3 * vars.movable]);
    let m = g.h.len();
    let a = CscMatrix::new_from_triplets(m, n, g.rows, g.cols, g.vals);
    let cones = [NonnegativeConeT(m)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .build()
        .ok()?;
    let mut solver = DefaultSolver::new(&p, &q, &a, &g.h, &cones, settings).ok()?;
    solver.solve();
    matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    )
    .then(|| solver.solution.x.clone())
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;
    use parry3d_f64::math::Vector as PVec;
    use parry3d_f64::shape::ConvexPolyhedron;

    use super::qp_step;
    use crate::geometry::convex::ConvexPiece;
    use crate::geometry::penetration::PosedPiece;
    use crate::physics::projection::{
        Body, Piece, ProjectionOptions, ProjectionStatus, Row, XyRegion, max_depth, measure, solve,
    };
    use crate::scene::Pose;

    const TARGET: f64 = 1e-4;

    /// An axis-aligned box of half extents `half` centred at `center`; `free` bodies may move.
    fn box_body(id: &str, center: [f64; 3], half: [f64; 3], free: bool) -> Body {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|c| {
                let sign = |bit: usize| if c & bit == 0 { -1.0 } else { 1.0 };
                [sign(1) * half[0], sign(2) * half[1], sign(4) * half[2]]
            })
            .collect();
        let piece = ConvexPiece::from_points(&corners).expect("a box spans a volume");
        let posed = PosedPiece::new(&piece, &Pose::from_xyz(center[0], center[1], center[2]));
        let points: Vec<PVec> = posed
            .vertices
            .iter()
            .map(|v| PVec::new(v.x, v.y, v.z))
            .collect();
        let shape = ConvexPolyhedron::from_convex_hull(&points).expect("a box has a hull");
        let (lo0, hi0) = (posed.lo, posed.hi);
        Body {
            id: id.to_string(),
            movable: free,
            free,
            pieces: vec![Piece {
                shape,
                verts0: posed.vertices.clone(),
                lo0,
                hi0,
                posed,
                is_floor: false,
            }],
            lo0,
            hi0,
            origin0: Vector3::from(center),
        }
    }

    /// A 20 cm cube standing on the floor at `(x, y)`.
    fn cube_on_floor(id: &str, x: f64, y: f64, free: bool) -> Body {
        box_body(id, [x, y, 0.1], [0.1; 3], free)
    }

    /// The pair row "`b` is `depth` into `a` along `n`" with the default target gap.
    fn row(a: usize, b: usize, n: Vector3<f64>, depth: f64) -> Row {
        Row {
            a,
            b,
            n,
            d: -depth,
            target: TARGET,
        }
    }

    fn no_floor() -> ProjectionOptions {
        ProjectionOptions {
            floor_z: None,
            ..ProjectionOptions::default()
        }
    }

    fn step(bodies: &[Body], rows: &[Row], opts: &ProjectionOptions) -> Vec<Vector3<f64>> {
        let offsets = vec![Vector3::zeros(); bodies.len()];
        qp_step(bodies, &offsets, rows, opts, opts.trust_region).expect("the QP solves")
    }

    #[test]
    fn a_fixed_body_gets_no_step_and_the_movable_one_meets_the_row_minimally() {
        let bodies = [
            box_body("fixed", [0.0, 0.0, 1.0], [0.1; 3], false),
            box_body("free", [0.18, 0.0, 1.0], [0.1; 3], true),
        ];
        let s = step(&bodies, &[row(0, 1, Vector3::x(), 0.02)], &no_floor());
        assert_eq!(s[0], Vector3::zeros());
        let need = 0.02 + TARGET;
        assert!(s[1].x >= need - 1e-6, "row unmet: {}", s[1].x);
        assert!(
            s[1].x <= need + 1e-5,
            "moved further than needed: {}",
            s[1].x
        );
        assert!(s[1].y.abs() < 1e-6 && s[1].z.abs() < 1e-6, "{s:?}");
    }

    #[test]
    fn two_movable_bodies_share_the_separation() {
        let bodies = [
            box_body("a", [0.0, 0.0, 1.0], [0.1; 3], true),
            box_body("b", [0.18, 0.0, 1.0], [0.1; 3], true),
        ];
        let s = step(&bodies, &[row(0, 1, Vector3::x(), 0.02)], &no_floor());
        let half = (0.02 + TARGET) / 2.0;
        assert!((s[0].x + half).abs() < 1e-5, "{s:?}");
        assert!((s[1].x - half).abs() < 1e-5, "{s:?}");
    }

    #[test]
    fn a_step_stays_inside_the_trust_region() {
        let bodies = [
            box_body("fixed", [0.0, 0.0, 1.0], [0.1; 3], false),
            box_body("free", [0.0, 0.0, 1.0], [0.1; 3], true),
        ];
        let n = Vector3::new(1.0, 1.0, 1.0).normalize();
        let opts = no_floor();
        let s = step(&bodies, &[row(0, 1, n, 0.5)], &opts);
        let bound = opts.trust_region + 1e-7;
        assert!(s[1].iter().all(|v| v.abs() <= bound), "{:?}", s[1]);
        // Slack takes the rest: the body goes as far as it may along the row.
        assert!(
            s[1].iter().all(|v| *v > opts.trust_region - 1e-4),
            "{:?}",
            s[1]
        );
    }

    #[test]
    fn a_body_resting_on_the_floor_that_no_row_mentions_is_not_moved() {
        let bodies = [cube_on_floor("cube", 0.0, 0.0, true)];
        let s = step(&bodies, &[], &ProjectionOptions::default());
        assert_eq!(s[0], Vector3::zeros());
    }

    #[test]
    fn a_body_no_row_mentions_goes_back_exactly_to_its_start() {
        let bodies = [cube_on_floor("cube", 0.0, 0.0, true)];
        let offsets = [Vector3::new(0.013, -0.007, 0.002)];
        let opts = ProjectionOptions::default();
        let s = qp_step(&bodies, &offsets, &[], &opts, opts.trust_region).expect("solves");
        assert_eq!(s[0], -offsets[0]);
    }

    #[test]
    fn a_body_below_the_floor_is_lifted_past_the_trust_region() {
        let bodies = [box_body("sunk", [0.0, 0.0, -0.1], [0.1; 3], true)];
        let opts = ProjectionOptions::default();
        let s = step(&bodies, &[], &opts);
        assert!(s[0].z >= 0.2 - 1e-7, "not lifted to the floor: {}", s[0].z);
        assert!(s[0].z > opts.trust_region);
        assert!(s[0].xy().norm() < 1e-6, "{:?}", s[0]);
    }

    #[test]
    fn xy_only_slides_without_rising() {
        let bodies = [
            cube_on_floor("fixed", 0.0, 0.0, false),
            cube_on_floor("free", 0.15, 0.0, true),
        ];
        let opts = ProjectionOptions {
            xy_only: true,
            ..ProjectionOptions::default()
        };
        // A normal that leans upwards: a vertical move would be cheaper, but is not allowed.
        let n = Vector3::new(0.6, 0.0, 0.8);
        let s = step(&bodies, &[row(0, 1, n, 0.02)], &opts);
        // Pinned by an equality bound: only the interior-point method's last digits remain.
        assert!(s[1].z.abs() < 1e-9, "rose: {:?}", s[1]);
        assert!(
            n.dot(&s[1]) >= 0.02 + TARGET - 1e-6,
            "row unmet: {:?}",
            s[1]
        );
    }

    #[test]
    fn a_region_keeps_the_origin_inside_and_the_row_is_met_another_way() {
        let bodies = [
            box_body("fixed", [0.0, 0.0, 1.0], [0.1; 3], false),
            box_body("free", [0.0, 0.0, 1.0], [0.1; 3], true),
        ];
        // The cheapest exit is diagonal (+x and +y); the region forbids any +x.
        let region = XyRegion {
            halfplanes: vec![[1.0, 0.0, 0.0]],
        };
        let mut opts = no_floor();
        opts.regions.insert("free".to_string(), region.clone());
        let n = Vector3::new(1.0, 1.0, 0.0).normalize();
        let s = step(&bodies, &[row(0, 1, n, 0.02)], &opts);
        let origin = bodies[1].origin0 + s[1];
        assert!(region.contains([origin.x, origin.y], 1e-6), "{origin:?}");
        assert!(
            n.dot(&s[1]) >= 0.02 + TARGET - 1e-6,
            "row unmet: {:?}",
            s[1]
        );

        let free = step(&bodies, &[row(0, 1, n, 0.02)], &no_floor());
        assert!(
            free[1].x > 0.01,
            "without the region it would go +x: {free:?}"
        );
    }

    #[test]
    fn one_step_does_not_deepen_the_deepest_penetration() {
        let bodies = [
            cube_on_floor("a", 0.0, 0.0, true),
            cube_on_floor("b", 0.15, 0.03, true),
        ];
        let opts = ProjectionOptions::default();
        let zero = vec![Vector3::zeros(); bodies.len()];
        let margin = 2.0 * opts.trust_region + opts.clearance;
        let before = measure(&bodies, &zero, &opts, margin);
        let s = qp_step(&bodies, &zero, &before.rows, &opts, opts.trust_region).expect("solves");
        let depth_before = max_depth(&measure(&bodies, &zero, &opts, 0.0));
        let depth_after = max_depth(&measure(&bodies, &s, &opts, 0.0));
        assert!(depth_before > 0.04, "the cubes overlap: {depth_before}");
        assert!(
            depth_after < depth_before,
            "{depth_after} >= {depth_before}"
        );
    }

    #[test]
    fn two_overlapping_cubes_come_apart_sideways_without_sinking() {
        let mut bodies = [
            cube_on_floor("a", 0.0, 0.0, true),
            cube_on_floor("b", 0.15, 0.0, true),
        ];
        let opts = ProjectionOptions::default();
        let (offsets, report) = solve(&mut bodies, &opts);
        assert_eq!(report.status, ProjectionStatus::Converged);
        assert!(report.initial_max_penetration_m > 0.04);
        assert!(report.max_penetration_m <= opts.tolerance, "{report:?}");
        let after: Vec<Vector3<f64>> = bodies
            .iter()
            .map(|b| offsets.get(&b.id).copied().unwrap_or_default())
            .collect();
        assert!(max_depth(&measure(&bodies, &after, &opts, 0.0)) <= opts.tolerance);
        for o in offsets.values() {
            // The floor bound holds exactly; the exit is sideways (the linearised normals may
            // tilt by a few micrometres of rise).
            assert!(o.z >= -1e-9, "sank into the floor: {o:?}");
            assert!(o.z < 1e-3 && o.x.abs() > 0.02, "not a sideways exit: {o:?}");
        }
    }

    #[test]
    fn a_fixed_cube_never_moves() {
        let mut bodies = [
            cube_on_floor("fixed", 0.0, 0.0, false),
            cube_on_floor("free", 0.15, 0.0, true),
        ];
        let opts = ProjectionOptions::default();
        let (offsets, report) = solve(&mut bodies, &opts);
        assert!(!offsets.contains_key("fixed"), "{offsets:?}");
        assert_eq!(report.status, ProjectionStatus::Converged);
        let moved = offsets.get("free").copied().unwrap_or_default();
        assert!(
            moved.x >= 0.05 - 1e-6,
            "free cube not pushed out: {moved:?}"
        );
    }

    #[test]
    fn a_lone_cube_resting_on_the_floor_is_left_alone() {
        let mut bodies = [cube_on_floor("cube", 0.0, 0.0, true)];
        let (offsets, report) = solve(&mut bodies, &ProjectionOptions::default());
        assert_eq!(report.status, ProjectionStatus::NothingToDo);
        assert!(offsets.is_empty(), "{offsets:?}");
    }
}
