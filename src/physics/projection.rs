//! Native non-penetration projection: move the movable objects to the nearest translations at
//! which no pair penetrates, orientations fixed.
//!
//! ```text
//! minimise  sum_i ||p_i - p0_i||^2
//! s.t.      d_ab + n_ab . (dp_b - dp_a) >= target_ab   for every piece pair near each other
//!           lowest point of each object >= floor_z     (the floor bound)
//!           a . p_xy <= c                              (optional XY regions, e.g. a surface)
//! ```
//! `d_ab` and `n_ab` come from parry3d's contact query on the convex pieces (EPA for
//! penetrating pairs), so each QP (clarabel) is a linearisation around the current poses; the
//! loop re-linearises until no pair penetrates more than `tolerance` (0.1 mm). A trust region
//! bounds each step and an elastic slack keeps every QP feasible. For convex pieces the
//! linearised distance never overestimates the true one once they are apart, so a step that
//! satisfies the QP separates the pair.
//!
//! In `xy_only` mode objects slide on the floor: z only rises to meet the floor bound. A pair
//! of bodies with a nearly vertical penetration normal then gets one row along the shortest
//! horizontal exit instead: the separating axis of the two bodies' footprints (sliding along a
//! vertical normal resolves nothing, and piece rows would fence a chair back that pokes through
//! a table top inside the apron).
//!
//! This module does not touch the scene: it returns per-object translation offsets.

use std::collections::{BTreeMap, BTreeSet};
use std::time::{Duration, Instant};

use nalgebra::{Point3, Vector3};
use parry3d_f64::math::{Pose as PPose, Vector as PVec};
use parry3d_f64::shape::ConvexPolyhedron;
use rayon::prelude::*;
use serde::Serialize;

mod qp;

use qp::qp_step;

use super::PhysicsError;
use super::as_written::posed_objects;
use crate::geometry::penetration::{PosedPiece, exit_direction};
use crate::geometry::polygon;
use crate::scene::Pose;
use crate::state::SceneState;

/// Which free objects may move.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Movable {
    /// Every free object (when the scene has no more than `auto_subset_above` of them; above
    /// that only the ones in collision, widened when they get stuck).
    #[default]
    Auto,
    /// Exactly these object ids.
    Only(BTreeSet<String>),
}

/// A convex region of the XY plane the object's origin must stay in: rows `[a, b, c]` meaning
/// `a x + b y <= c`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct XyRegion {
    /// Half-planes.
    pub halfplanes: Vec<[f64; 3]>,
}

impl XyRegion {
    /// The rectangle of half extents `half` centred at `center` of a frame placed at
    /// `world_from_frame` (only its yaw and translation matter), shrunk by `margin`.
    pub fn rectangle(
        world_from_frame: &Pose,
        center: [f64; 2],
        half: [f64; 2],
        margin: f64,
    ) -> XyRegion {
        let c = world_from_frame.transform_point(&Point3::new(center[0], center[1], 0.0));
        let yaw = world_from_frame.yaw();
        let (s, co) = yaw.sin_cos();
        let axes = [[co, s], [-s, co]];
        let mut halfplanes = Vec::new();
        for (k, axis) in axes.iter().enumerate() {
            let h = (half[k] - margin).max(0.0);
            let along = axis[0] * c.x + axis[1] * c.y;
            halfplanes.push([axis[0], axis[1], along + h]);
            halfplanes.push([-axis[0], -axis[1], -(along - h)]);
        }
        XyRegion { halfplanes }
    }

    /// True when `p` satisfies every half-plane (within `tol`).
    pub fn contains(&self, p: [f64; 2], tol: f64) -> bool {
        self.halfplanes
            .iter()
            .all(|h| h[0] * p[0] + h[1] * p[1] <= h[2] + tol)
    }
}

/// Options of the projection.
#[derive(Debug, Clone)]
pub struct ProjectionOptions {
    /// Gap a penetrating pair is pushed to, metres.
    pub clearance: f64,
    /// Largest penetration accepted at the end, metres.
    pub tolerance: f64,
    /// Largest move per object and axis in one iteration, metres.
    pub trust_region: f64,
    /// Iteration cap.
    pub max_iterations: usize,
    /// Slide in XY only (z rises only to meet the floor bound).
    pub xy_only: bool,
    /// Height of the floor top; `None` turns the floor bound off.
    pub floor_z: Option<f64>,
    /// Which objects may move.
    pub movable: Movable,
    /// Above this many free objects, `Movable::Auto` moves only objects in collision.
    pub auto_subset_above: usize,
    /// Per-object XY regions for the object's origin.
    pub regions: BTreeMap<String, XyRegion>,
    /// Wall-clock limit.
    pub time_limit: Duration,
}

impl Default for ProjectionOptions {
    fn default() -> Self {
        ProjectionOptions {
            clearance: 1e-4,
            tolerance: 1e-4,
            trust_region: 0.05,
            max_iterations: 60,
            xy_only: false,
            floor_z: Some(0.0),
            movable: Movable::Auto,
            auto_subset_above: 100,
            regions: BTreeMap::new(),
            time_limit: Duration::from_secs(60),
        }
    }
}

/// How a projection ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProjectionStatus {
    /// Nothing penetrated: nothing moved.
    NothingToDo,
    /// No pair penetrates more than the tolerance.
    Converged,
    /// Stopped at the iteration cap with penetrations left.
    IterationLimit,
    /// Stopped at the wall-clock limit with penetrations left.
    TimeLimit,
}

/// What a projection did.
#[derive(Debug, Clone, Serialize)]
pub struct ProjectionReport {
    /// How it ended.
    pub status: ProjectionStatus,
    /// Linearise-and-solve iterations.
    pub iterations: usize,
    /// Objects allowed to move (after any widening).
    pub movable: usize,
    /// Deepest penetration before, metres.
    pub initial_max_penetration_m: f64,
    /// Deepest penetration after, metres.
    pub max_penetration_m: f64,
    /// Objects that moved more than 1 micrometre.
    pub moved: usize,
    /// Mean displacement over the movable objects, metres.
    pub mean_displacement_m: f64,
    /// Largest displacement, metres.
    pub max_displacement_m: f64,
    /// Pairs still penetrating more than the tolerance: `(a, b, depth_m)`.
    pub unresolved: Vec<(String, String, f64)>,
    /// Wall time, seconds (not written into scene files).
    #[serde(skip)]
    pub seconds: f64,
}

struct Piece {
    /// The hull in world coordinates at the start (parry's GJK for pieces that are apart).
    shape: ConvexPolyhedron,
    /// The same with the axes of the exact separating-axis test (pieces that overlap).
    posed: PosedPiece,
    verts0: Vec<Vector3<f64>>,
    lo0: Vector3<f64>,
    hi0: Vector3<f64>,
    /// Part of a fixed floor slab: left to the floor bound, never a pair row.
    is_floor: bool,
}

struct Body {
    id: String,
    movable: bool,
    /// Free objects that are not movable (yet); may be widened into the movable set.
    free: bool,
    pieces: Vec<Piece>,
    lo0: Vector3<f64>,
    hi0: Vector3<f64>,
    origin0: Vector3<f64>,
}

/// One linearised pair: the rows of the QP come from these.
struct Row {
    a: usize,
    b: usize,
    /// Unit direction from `a` towards `b`: d grows by `n . (dp_b - dp_a)`.
    n: Vector3<f64>,
    d: f64,
    target: f64,
}

/// A penetrating pair measured on the current poses.
struct Measured {
    rows: Vec<Row>,
    /// Deepest penetration per body pair involving a movable body.
    deepest: BTreeMap<(usize, usize), f64>,
    /// Depth below the floor bound per movable body.
    below_floor: BTreeMap<usize, f64>,
}

fn to_vec3(v: PVec) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

fn bounds_of(points: &[Vector3<f64>]) -> (Vector3<f64>, Vector3<f64>) {
    let mut lo = Vector3::repeat(f64::INFINITY);
    let mut hi = Vector3::repeat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    (lo, hi)
}

fn overlap(
    alo: &Vector3<f64>,
    ahi: &Vector3<f64>,
    blo: &Vector3<f64>,
    bhi: &Vector3<f64>,
    margin: f64,
) -> bool {
    (0..3).all(|k| alo[k] - margin <= bhi[k] && blo[k] - margin <= ahi[k])
}

/// The movable and fixed participants of a projection, built from the scene: `free` objects may
/// move, `fixed` ones are obstacles (architecture always is).
fn build_bodies(
    state: &SceneState,
    free: &[String],
    fixed: &[String],
) -> Result<Vec<Body>, PhysicsError> {
    let wanted: BTreeSet<&str> = free.iter().chain(fixed).map(String::as_str).collect();
    for id in &wanted {
        if state.scene.object(id).is_none() {
            return Err(PhysicsError::UnknownObject(id.to_string()));
        }
    }
    let free_set: BTreeSet<&str> = free.iter().map(String::as_str).collect();
    let mut scene = state.scene.clone();
    scene.objects.retain(|o| wanted.contains(o.id.as_str()));
    let posed = posed_objects(&scene, &state.assets);
    let mut bodies = Vec::new();
    for (obj, p) in scene.objects.iter().zip(posed) {
        let is_free = free_set.contains(obj.id.as_str()) && !p.is_static;
        let mut pieces = Vec::new();
        let mut all = Vec::new();
        for posed in p.pieces {
            let points: Vec<PVec> = posed
                .vertices
                .iter()
                .map(|v| PVec::new(v.x, v.y, v.z))
                .collect();
            let Some(shape) = ConvexPolyhedron::from_convex_hull(&points) else {
                continue;
            };
            let verts0 = posed.vertices.clone();
            all.extend_from_slice(&verts0);
            pieces.push(Piece {
                shape,
                lo0: posed.lo,
                hi0: posed.hi,
                posed,
                verts0,
                is_floor: false,
            });
        }
        if pieces.is_empty() {
            continue;
        }
        let (lo0, hi0) = bounds_of(&all);
        bodies.push(Body {
            id: obj.id.clone(),
            movable: is_free,
            free: is_free,
            pieces,
            lo0,
            hi0,
            origin0: obj.world_from_object.translation(),
        });
    }
    Ok(bodies)
}

/// Projects `free` objects of `state` away from each other and from the `fixed` ones; returns
/// the translation offset of every free object that moved, and a report.
pub fn project_objects(
    state: &SceneState,
    free: &[String],
    fixed: &[String],
    opts: &ProjectionOptions,
) -> Result<(BTreeMap<String, Vector3<f64>>, ProjectionReport), PhysicsError> {
    let mut bodies = build_bodies(state, free, fixed)?;
    let report_and_offsets = solve(&mut bodies, opts);
    Ok(report_and_offsets)
}

/// Applies translation offsets to the objects of `state`.
pub fn apply_offsets(state: &mut SceneState, offsets: &BTreeMap<String, Vector3<f64>>) {
    for o in &mut state.scene.objects {
        if let Some(d) = offsets.get(&o.id) {
            let t = o.world_from_object.translation() + d;
            o.world_from_object = o.world_from_object.with_translation(t);
        }
    }
}

fn measure(
    bodies: &[Body],
    offsets: &[Vector3<f64>],
    opts: &ProjectionOptions,
    margin: f64,
) -> Measured {
    let mut below_floor = BTreeMap::new();
    if let Some(fz) = opts.floor_z {
        for (i, b) in bodies.iter().enumerate().filter(|(_, b)| b.movable) {
            let depth = fz - (b.lo0.z + offsets[i].z);
            if depth > 0.0 {
                below_floor.insert(i, depth);
            }
        }
    }
    // Candidate pairs by their bounds, then the pieces of each pair in parallel; the rows are
    // merged in pair order, so the result does not depend on the thread count.
    let pairs: Vec<(usize, usize)> = (0..bodies.len())
        .flat_map(|i| (i + 1..bodies.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let (a, b) = (&bodies[i], &bodies[j]);
            (a.movable || b.movable)
                && overlap(
                    &(a.lo0 + offsets[i]),
                    &(a.hi0 + offsets[i]),
                    &(b.lo0 + offsets[j]),
                    &(b.hi0 + offsets[j]),
                    margin,
                )
        })
        .collect();
    let measured: Vec<(Vec<Row>, Option<f64>)> = pairs
        .par_iter()
        .map(|&(i, j)| measure_pair(bodies, offsets, opts, margin, i, j))
        .collect();
    let mut rows = Vec::new();
    let mut deepest = BTreeMap::new();
    for (&(i, j), (pair_rows, depth)) in pairs.iter().zip(measured) {
        rows.extend(pair_rows);
        if let Some(d) = depth {
            deepest.insert((i, j), d);
        }
    }
    Measured {
        rows,
        deepest,
        below_floor,
    }
}

/// The rows of one body pair and its deepest penetration (`None` when nothing penetrates).
fn measure_pair(
    bodies: &[Body],
    offsets: &[Vector3<f64>],
    opts: &ProjectionOptions,
    margin: f64,
    i: usize,
    j: usize,
) -> (Vec<Row>, Option<f64>) {
    let (a, b) = (&bodies[i], &bodies[j]);
    let (oa, ob) = (offsets[i], offsets[j]);
    let mut rows = Vec::new();
    let mut deepest: Option<f64> = None;
    let mut slide_out = false;
    for pa in a.pieces.iter().filter(|p| !p.is_floor) {
        for pb in b.pieces.iter().filter(|p| !p.is_floor) {
            if !overlap(
                &(pa.lo0 + oa),
                &(pa.hi0 + oa),
                &(pb.lo0 + ob),
                &(pb.hi0 + ob),
                margin,
            ) {
                continue;
            }
            // Overlapping pieces: exact depth and direction by the separating-axis
            // test (parry's EPA is unreliable for deep overlaps), run only when GJK
            // says the hulls intersect (the full SAT is the costly part); pieces
            // apart: GJK distance.
            let pose_a = PPose::from_translation(PVec::new(oa.x, oa.y, oa.z));
            let pose_b = PPose::from_translation(PVec::new(ob.x, ob.y, ob.z));
            let overlap_dir = if overlap(
                &(pa.lo0 + oa),
                &(pa.hi0 + oa),
                &(pb.lo0 + ob),
                &(pb.hi0 + ob),
                0.0,
            ) && parry3d_f64::query::intersection_test(
                &pose_a, &pa.shape, &pose_b, &pb.shape,
            )
            .map_or(true, |i| i.intersecting)
            {
                exit_direction(&pa.posed, &oa, &pb.posed, &ob)
            } else {
                None
            };
            let (d, d_row, n, minimum_axis) = match overlap_dir {
                Some(exit) => (-exit.depth, -exit.exit_depth, exit.axis, exit.minimum_axis),
                None => {
                    let Ok(Some(c)) =
                        parry3d_f64::query::contact(&pose_a, &pa.shape, &pose_b, &pb.shape, margin)
                    else {
                        continue;
                    };
                    // Touching counts as apart here; the SAT saw no overlap.
                    let d = c.dist.max(0.0);
                    let n = to_vec3(c.normal1);
                    (d, d, n, n)
                }
            };
            if d < 0.0 {
                deepest = Some(deepest.unwrap_or(0.0f64).max(-d));
            }
            let target = if d < -opts.tolerance {
                opts.clearance
            } else {
                d.min(opts.clearance)
            };
            // Sliding cannot resolve what only a vertical move would (a chair back through a
            // table top): judged on the minimum translation, not the exit chosen for it.
            let horizontal = minimum_axis.xy().norm();
            if opts.xy_only && d < -opts.tolerance && horizontal < 0.5 {
                // Sliding along a vertical normal resolves nothing: the pair gets one
                // row for the whole bodies below.
                slide_out = true;
                continue;
            } else if n.norm() < 0.5 || !n.iter().all(|v| v.is_finite()) {
                continue;
            }
            if d_row >= target + margin {
                continue;
            }
            rows.push(Row {
                a: i,
                b: j,
                n,
                d: d_row,
                target,
            });
        }
    }
    if slide_out {
        // One body slides out of the other's footprint along the shortest horizontal
        // exit. Piece rows would fence it in: a chair back through a table top cannot
        // cross the apron sideways, so it leaves the table's whole footprint.
        rows.clear();
        let band = |body: &Body, o: &Vector3<f64>, other: &Body, oo: &Vector3<f64>| {
            let (zlo, zhi) = (other.lo0.z + oo.z, other.hi0.z + oo.z);
            body.pieces
                .iter()
                .filter(|p| !p.is_floor && p.lo0.z + o.z < zhi && p.hi0.z + o.z > zlo)
                .flat_map(|p| p.verts0.iter().copied())
                .collect::<Vec<_>>()
        };
        if let Some((n, depth)) =
            xy_separation(&band(a, &oa, b, &ob), &oa, &band(b, &ob, a, &oa), &ob)
        {
            rows.push(Row {
                a: i,
                b: j,
                n,
                d: -depth,
                target: opts.clearance,
            });
        }
    }
    (rows, deepest)
}

/// The horizontal direction `n` (unit, from `a` towards `b`) along which the vertical prisms over
/// the two pieces' footprints overlap least, and that overlap (metres, positive when they
/// overlap): moving `b` by `overlap` along `n` (or `a` against it) separates the footprints.
/// `None` when the footprints are already apart or degenerate.
fn xy_separation(
    verts_a: &[Vector3<f64>],
    offset_a: &Vector3<f64>,
    verts_b: &[Vector3<f64>],
    offset_b: &Vector3<f64>,
) -> Option<(Vector3<f64>, f64)> {
    let footprint = |verts: &[Vector3<f64>], o: &Vector3<f64>| {
        let pts: Vec<[f64; 2]> = verts.iter().map(|v| [v.x + o.x, v.y + o.y]).collect();
        polygon::convex_hull(&pts)
    };
    let (ha, hb) = (footprint(verts_a, offset_a), footprint(verts_b, offset_b));
    if ha.len() < 2 || hb.len() < 2 {
        return None;
    }
    let project = |hull: &[[f64; 2]], u: [f64; 2]| {
        hull.iter()
            .map(|p| p[0] * u[0] + p[1] * u[1])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    };
    let mut best: Option<([f64; 2], f64)> = None;
    for hull in [&ha, &hb] {
        for k in 0..hull.len() {
            let (p, q) = (hull[k], hull[(k + 1) % hull.len()]);
            let len = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
            if len < 1e-12 {
                continue;
            }
            let u = [(q[1] - p[1]) / len, -(q[0] - p[0]) / len];
            let (alo, ahi) = project(&ha, u);
            let (blo, bhi) = project(&hb, u);
            // b forwards along u, or backwards.
            let (forward, backward) = (ahi - blo, bhi - alo);
            if forward <= 0.0 || backward <= 0.0 {
                return None;
            }
            let (dir, depth) = if forward <= backward {
                (u, forward)
            } else {
                ([-u[0], -u[1]], backward)
            };
            if best.is_none_or(|(_, d)| depth < d) {
                best = Some((dir, depth));
            }
        }
    }
    best.map(|(u, depth)| (Vector3::new(u[0], u[1], 0.0), depth))
}

fn max_depth(m: &Measured) -> f64 {
    m.deepest
        .values()
        .chain(m.below_floor.values())
        .copied()
        .fold(0.0, f64::max)
}

/// Fallback step when a QP fails: push each penetrating pair apart along its normal.
fn push_out_step(bodies: &[Body], rows: &[Row], opts: &ProjectionOptions) -> Vec<Vector3<f64>> {
    let mut step = vec![Vector3::zeros(); bodies.len()];
    for r in rows.iter().filter(|r| r.d < r.target) {
        let need = r.target - r.d;
        let (ma, mb) = (bodies[r.a].movable, bodies[r.b].movable);
        let share = if ma && mb { 0.5 } else { 1.0 };
        let mut n = r.n;
        if opts.xy_only {
            n.z = 0.0;
        }
        if ma {
            step[r.a] -= n * need * share;
        }
        if mb {
            step[r.b] += n * need * share;
        }
    }
    for s in &mut step {
        for k in 0..3 {
            s[k] = s[k].clamp(-opts.trust_region, opts.trust_region);
        }
    }
    step
}

/// After convergence the early, slack-heavy steps may have pushed objects further than
/// needed: re-solve around the feasible point (pairs apart may close up to the clearance) and
/// keep each step only while it lowers the cost and stays within the tolerance.
fn polish(bodies: &[Body], offsets: &mut [Vector3<f64>], opts: &ProjectionOptions) {
    let cost = |o: &[Vector3<f64>]| -> f64 {
        bodies
            .iter()
            .zip(o)
            .filter(|(b, _)| b.movable)
            .map(|(_, d)| d.norm_squared())
            .sum()
    };
    for _ in 0..5 {
        let trust = opts.trust_region;
        let m = measure(bodies, offsets, opts, 2.0 * trust + opts.clearance);
        let Some(step) = qp_step(bodies, offsets, &m.rows, opts, trust) else {
            return;
        };
        let trial: Vec<Vector3<f64>> = offsets.iter().zip(&step).map(|(o, s)| o + s).collect();
        let gain = cost(offsets) - cost(&trial);
        if gain <= 1e-10 || max_depth(&measure(bodies, &trial, opts, 0.0)) > opts.tolerance {
            return;
        }
        offsets.copy_from_slice(&trial);
    }
}

fn solve(
    bodies: &mut [Body],
    opts: &ProjectionOptions,
) -> (BTreeMap<String, Vector3<f64>>, ProjectionReport) {
    let t0 = Instant::now();
    let mut offsets = vec![Vector3::zeros(); bodies.len()];
    if let Some(fz) = opts.floor_z {
        for b in bodies.iter_mut().filter(|b| !b.free) {
            for p in &mut b.pieces {
                p.is_floor = p.hi0.z <= fz + 1e-6;
            }
        }
    }
    let free_count = bodies.iter().filter(|b| b.free).count();
    match &opts.movable {
        Movable::Only(ids) => {
            for b in bodies.iter_mut() {
                b.movable = b.free && ids.contains(&b.id);
            }
        }
        Movable::Auto if free_count > opts.auto_subset_above => {
            let all = measure(bodies, &offsets, opts, 0.0);
            let colliding: BTreeSet<usize> = all
                .deepest
                .iter()
                .filter(|(_, d)| **d > opts.tolerance)
                .flat_map(|((a, b), _)| [*a, *b])
                .collect();
            for (i, b) in bodies.iter_mut().enumerate() {
                b.movable = b.free && colliding.contains(&i);
            }
        }
        Movable::Auto => {}
    }
    // Penetration also counts between a movable body and a free-but-fixed one; measure() only
    // skips pairs where neither moves, so mark candidates for widening by tracking `free`.
    let initial = measure(bodies, &offsets, opts, 0.0);
    let initial_depth = max_depth(&initial);
    let mut status = ProjectionStatus::NothingToDo;
    let mut iterations = 0;
    if initial_depth > opts.tolerance {
        status = ProjectionStatus::IterationLimit;
        let mut trust = opts.trust_region;
        loop {
            let margin = 2.0 * trust + opts.clearance;
            let m = measure(bodies, &offsets, opts, margin);
            let depth = max_depth(&m);
            if depth <= opts.tolerance {
                status = ProjectionStatus::Converged;
                polish(bodies, &mut offsets, opts);
                break;
            }
            if iterations >= opts.max_iterations {
                // Stuck: let the free-but-fixed neighbours of penetrating pairs move too, once.
                let widen: Vec<usize> = m
                    .deepest
                    .iter()
                    .filter(|(_, d)| **d > opts.tolerance)
                    .flat_map(|((a, b), _)| [*a, *b])
                    .filter(|i| bodies[*i].free && !bodies[*i].movable)
                    .collect();
                if widen.is_empty() || iterations >= 2 * opts.max_iterations {
                    break;
                }
                for i in widen {
                    bodies[i].movable = true;
                }
            }
            if t0.elapsed() > opts.time_limit {
                status = ProjectionStatus::TimeLimit;
                break;
            }
            iterations += 1;
            let step = qp_step(bodies, &offsets, &m.rows, opts, trust)
                .unwrap_or_else(|| push_out_step(bodies, &m.rows, opts));
            for (o, s) in offsets.iter_mut().zip(&step) {
                *o += s;
            }
            // Deep overlaps need big steps; shallow ones small steps for accurate normals.
            trust = (2.0 * depth).clamp(0.005, opts.trust_region);
        }
    }
    let last = measure(bodies, &offsets, opts, 0.0);
    let mut unresolved: Vec<(String, String, f64)> = last
        .deepest
        .iter()
        .filter(|(_, d)| **d > opts.tolerance)
        .map(|((a, b), d)| (bodies[*a].id.clone(), bodies[*b].id.clone(), *d))
        .chain(
            last.below_floor
                .iter()
                .filter(|(_, d)| **d > opts.tolerance)
                .map(|(i, d)| (bodies[*i].id.clone(), "floor".to_string(), *d)),
        )
        .collect();
    unresolved.sort_by(|x, y| y.2.total_cmp(&x.2));
    let movable: Vec<usize> = (0..bodies.len()).filter(|i| bodies[*i].movable).collect();
    let disp: Vec<f64> = movable.iter().map(|i| offsets[*i].norm()).collect();
    let out: BTreeMap<String, Vector3<f64>> = bodies
        .iter()
        .zip(&offsets)
        .filter(|(_, o)| o.norm() > 0.0)
        .map(|(b, o)| (b.id.clone(), *o))
        .collect();
    let report = ProjectionReport {
        status,
        iterations,
        movable: movable.len(),
        initial_max_penetration_m: initial_depth,
        max_penetration_m: max_depth(&last),
        moved: disp.iter().filter(|d| **d > 1e-6).count(),
        mean_displacement_m: if disp.is_empty() {
            0.0
        } else {
            disp.iter().sum::<f64>() / disp.len() as f64
        },
        max_displacement_m: disp.iter().copied().fold(0.0, f64::max),
        unresolved,
        seconds: t0.elapsed().as_secs_f64(),
    };
    (out, report)
}
