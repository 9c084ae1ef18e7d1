//! Placement search: axis-aligned rectangles edge to edge, no overlaps, every room next to a
//! room it may be entered from, required pairs sharing a wall long enough for a door.
//!
//! Rooms are placed one at a time (anchors first: the hub or the entrance, then rooms whose
//! parents are placed, larger first; an en-suite right after its bedroom). A new room attaches
//! along an edge of a placed room at 11 evenly spaced positions (plus the two flush alignments
//! and, when re-laying out, the position nearest to where the room was), in both orientations.
//! Candidates are ranked by a local score (adjacency bonus, distance from the centroid, contact
//! length, nearness to the previous position). The search is a limited-discrepancy
//! backtracking over that ranking with a node budget and a wall-clock timeout: it is anytime
//! and keeps the complete layout with the best global score (compactness, preferred
//! neighbours, daylight, entrance on the outside, stability exp(-d/2) against the previous
//! layout). When no layout satisfies the constraints, a relaxed pass only asks rooms to touch.
//!
//! Rectangles here are *cells*: bounded by wall centre lines, so neighbours share an edge and
//! the clear floor is the cell shrunk by half a wall thickness.

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

pub use super::cells::{Outside, Placement, Rect};
use super::knowledge::Role;
use super::spec::{HouseSpec, Link};

/// Positions tried along each edge of a placed room.
pub const POSITIONS_PER_EDGE: usize = 11;
/// Shortest shared wall (centre line) that takes a door, metres.
pub const MIN_SHARED: f64 = 1.2;
const EPS: f64 = 1e-6;
/// Gaps between rooms narrower than this are slivers, metres.
const SLOT: f64 = 1.5;

/// Search settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SearchConfig {
    /// Wall thickness, metres (cells are clear size plus one thickness).
    pub wall_thickness: f64,
    /// Most candidate expansions per pass (keeps the result independent of machine speed).
    pub node_budget: usize,
    /// Wall-clock limit, seconds; the best layout found so far is returned when it passes.
    pub timeout_s: f64,
    /// Children tried per node, best first.
    pub branching: usize,
}

impl Default for SearchConfig {
    fn default() -> Self {
        SearchConfig {
            wall_thickness: super::WALL_THICKNESS,
            node_budget: 1500,
            timeout_s: 20.0,
            branching: 4,
        }
    }
}

/// How the search went.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SearchStats {
    /// Candidate expansions.
    pub nodes: usize,
    /// Complete layouts scored.
    pub leaves: usize,
    /// Wall time, seconds (not serialised: logs and scenes stay byte-identical across runs).
    #[serde(skip)]
    pub seconds: f64,
    /// The wall-clock limit cut the search short.
    pub timed_out: bool,
    /// No layout met every constraint; rooms were only required to touch.
    pub relaxed: bool,
    /// Global score of the kept layout.
    pub score: f64,
    /// Compactness of the kept layout.
    pub compactness: f64,
}

/// Cell size `[x, y]` of a room for orientation `rot` (false: long side along x).
fn cell_size(spec: &HouseSpec, i: usize, rot: bool, t: f64) -> [f64; 2] {
    let s = spec.rooms[i].size;
    if rot {
        [s[1] + t, s[0] + t]
    } else {
        [s[0] + t, s[1] + t]
    }
}

/// Placement order: the anchor (hub, else entrance), then repeatedly the room with a placed
/// parent, passable rooms first, larger first; en-suites right after their bedroom.
pub fn order(spec: &HouseSpec) -> Vec<usize> {
    let n = spec.rooms.len();
    let rank = |r: Role| match r {
        Role::Hub => 0,
        Role::Entry => 1,
        Role::Public => 2,
        Role::Private => 3,
        Role::Service => 4,
        Role::Wet => 5,
    };
    let anchor = spec
        .hub()
        .and_then(|h| spec.index(&h.id))
        .or_else(|| spec.index(&spec.entrance))
        .unwrap_or(0);
    let mut out = vec![anchor];
    let mut placed = vec![false; n];
    if n == 0 {
        return Vec::new();
    }
    placed[anchor] = true;
    while out.len() < n {
        let ready = |i: usize| {
            let r = &spec.rooms[i];
            r.parents.is_empty()
                || r.parents
                    .iter()
                    .any(|p| spec.index(p).is_some_and(|j| placed[j]))
        };
        let pick = (0..n)
            .filter(|&i| !placed[i] && spec.rooms[i].owner.is_none())
            .filter(|&i| ready(i))
            .min_by(|&a, &b| {
                let (ra, rb) = (&spec.rooms[a], &spec.rooms[b]);
                rank(ra.role)
                    .cmp(&rank(rb.role))
                    .then(rb.area().total_cmp(&ra.area()))
                    .then(a.cmp(&b))
            })
            .or_else(|| (0..n).find(|&i| !placed[i] && ready(i)))
            .or_else(|| (0..n).find(|&i| !placed[i]));
        let Some(i) = pick else { break };
        placed[i] = true;
        out.push(i);
        // En-suites follow their bedroom so they can share its free walls.
        let id = spec.rooms[i].id.clone();
        for j in 0..n {
            if !placed[j] && spec.rooms[j].owner.as_deref() == Some(id.as_str()) {
                placed[j] = true;
                out.push(j);
            }
        }
    }
    out
}

/// Relations between rooms as index tables (order positions), built once per search.
struct Tables {
    /// Per order position: order positions of the room's parents.
    parents: Vec<Vec<usize>>,
    /// Link between two order positions, if any.
    link: Vec<Vec<Option<Link>>>,
    /// Per order position: whether `parents` contains the other position.
    is_parent: Vec<Vec<bool>>,
}

impl Tables {
    fn new(spec: &HouseSpec, order: &[usize]) -> Tables {
        let n = spec.rooms.len();
        let mut pos_of = vec![0; n];
        for (pos, &i) in order.iter().enumerate() {
            pos_of[i] = pos;
        }
        let pos = |id: &str| spec.index(id).map(|i| pos_of[i]);
        let mut parents = vec![Vec::new(); n];
        let mut is_parent = vec![vec![false; n]; n];
        let mut link = vec![vec![None; n]; n];
        for (k, &i) in order.iter().enumerate() {
            parents[k] = spec.rooms[i]
                .parents
                .iter()
                .filter_map(|p| pos(p))
                .collect();
            for &p in &parents[k] {
                is_parent[k][p] = true;
                is_parent[p][k] = true;
            }
        }
        for a in &spec.adjacency {
            if let (Some(x), Some(y)) = (pos(&a.a), pos(&a.b)) {
                link[x][y] = Some(a.link);
                link[y][x] = Some(a.link);
            }
        }
        Tables {
            parents,
            link,
            is_parent,
        }
    }
}

struct Search<'a> {
    spec: &'a HouseSpec,
    order: Vec<usize>,
    tables: Tables,
    cfg: SearchConfig,
    /// Previous cell per order position.
    previous_cells: Vec<Option<Rect>>,
    previous: Option<&'a Placement>,
    relaxed: bool,
    nodes: usize,
    leaves: usize,
    start: Instant,
    timed_out: bool,
    best: Option<(f64, Vec<Rect>)>,
    /// Cell of each room in order position, as placed so far.
    placed: Vec<Rect>,
}

impl Search<'_> {
    fn out_of_budget(&mut self) -> bool {
        if self.nodes >= self.cfg.node_budget {
            return true;
        }
        if self.start.elapsed() > Duration::from_secs_f64(self.cfg.timeout_s) {
            self.timed_out = true;
            return true;
        }
        false
    }

    /// Whether `cell` for the room at order position `k` meets the constraints against the
    /// rooms placed so far.
    fn admissible(&self, k: usize, cell: &Rect) -> bool {
        if self.placed.iter().any(|p| p.overlaps(cell)) {
            return false;
        }
        if !self.placed.is_empty() && !self.placed.iter().any(|p| p.shared(cell) > EPS) {
            return false;
        }
        if self.relaxed {
            return true;
        }
        // Required pairs with rooms already placed.
        for (pos, p) in self.placed.iter().enumerate() {
            if self.tables.link[k][pos].is_some_and(|l| l != Link::Preferred)
                && p.shared(cell) < MIN_SHARED - EPS
            {
                return false;
            }
        }
        // At least one placed parent with a door-long wall.
        let mut any_parent = false;
        for &p in &self.tables.parents[k] {
            if p < k {
                if self.placed[p].shared(cell) >= MIN_SHARED - EPS {
                    return true;
                }
                any_parent = true;
            }
        }
        !any_parent
    }

    fn local_score(&self, k: usize, cell: &Rect, rot: bool) -> f64 {
        let room = &self.spec.rooms[self.order[k]];
        let mut score = 1.0;
        let mut contact = 0.0;
        let (mut cx, mut cy, mut a) = (0.0, 0.0, 0.0);
        for (pos, p) in self.placed.iter().enumerate() {
            let c = p.center();
            cx += c[0] * p.area();
            cy += c[1] * p.area();
            a += p.area();
            let shared = p.shared(cell);
            contact += shared;
            if shared <= EPS {
                if p.slot(cell, SLOT).is_some() {
                    score -= 1.5;
                }
                continue;
            }
            // Flush corners make clean walls (no slivers of wall between rooms).
            let flush = [
                (p.x0 - cell.x0).abs(),
                (p.x1 - cell.x1).abs(),
                (p.y0 - cell.y0).abs(),
                (p.y1 - cell.y1).abs(),
            ]
            .iter()
            .filter(|d| **d < EPS)
            .count();
            score += 0.4 * flush as f64;
            if shared < MIN_SHARED - EPS {
                continue;
            }
            if self.tables.is_parent[k][pos] {
                score += 2.0;
            }
            match self.tables.link[k][pos] {
                Some(Link::Preferred) => score += 1.0,
                Some(_) => score += 2.0,
                None => {}
            }
        }
        // Compact: close to the centroid, much contact.
        if a > 0.0 {
            let c = cell.center();
            score -= 0.15 * (c[0] - cx / a).hypot(c[1] - cy / a);
        }
        score += 1.5 * contact / (2.0 * (cell.w() + cell.d()));
        if let Some(prev) = self.previous_cells[k] {
            let (c, pc) = (cell.center(), prev.center());
            score += 4.0 * (-(c[0] - pc[0]).hypot(c[1] - pc[1]) / 2.0).exp();
            let prev_rot = (prev.w() < prev.d()) != (room.size[0] < room.size[1]);
            if prev_rot == rot {
                score += 0.5;
            }
        }
        score
    }

    /// Ranked admissible cells for the room at order position `k`.
    fn candidates(&self, k: usize) -> Vec<(f64, Rect)> {
        let i = self.order[k];
        let t = self.cfg.wall_thickness;
        let prev = self.previous_cells[k];
        let mut seen: std::collections::HashSet<[i64; 4]> = std::collections::HashSet::new();
        let mut out: Vec<(f64, Rect)> = Vec::new();
        let square = (self.spec.rooms[i].size[0] - self.spec.rooms[i].size[1]).abs() < EPS;
        let rots: &[bool] = if square { &[false] } else { &[false, true] };
        for &rot in rots {
            let [w, d] = cell_size(self.spec, i, rot, t);
            let mut push = |cell: Rect| {
                let key = [cell.x0, cell.y0, cell.x1, cell.y1].map(|v| (v * 1e4).round() as i64);
                if !seen.insert(key) {
                    return;
                }
                if self.admissible(k, &cell) {
                    out.push((self.local_score(k, &cell, rot), cell));
                }
            };
            if self.placed.is_empty() {
                let origin = prev.map(|p| [p.x0, p.y0]).unwrap_or([0.0, 0.0]);
                push(Rect::at(origin[0], origin[1], w, d));
                continue;
            }
            for p in &self.placed {
                // Along the north and south edges x varies; along east and west y varies.
                let along = |lo: f64, hi: f64, size: f64, prev_lo: Option<f64>| -> Vec<f64> {
                    let m = MIN_SHARED.min(hi - lo).min(size);
                    let (a, b) = (lo - size + m, hi - m);
                    let mut v: Vec<f64> = (0..POSITIONS_PER_EDGE)
                        .map(|j| {
                            if POSITIONS_PER_EDGE == 1 || b <= a {
                                a
                            } else {
                                a + (b - a) * j as f64 / (POSITIONS_PER_EDGE - 1) as f64
                            }
                        })
                        .collect();
                    v.push(lo);
                    v.push(hi - size);
                    if let Some(pl) = prev_lo {
                        v.push(pl.clamp(a.min(b), b.max(a)));
                    }
                    v
                };
                for x in along(p.x0, p.x1, w, prev.map(|r| r.x0)) {
                    push(Rect::at(x, p.y1, w, d));
                    push(Rect::at(x, p.y0 - d, w, d));
                }
                for y in along(p.y0, p.y1, d, prev.map(|r| r.y0)) {
                    push(Rect::at(p.x1, y, w, d));
                    push(Rect::at(p.x0 - w, y, w, d));
                }
            }
        }
        out.sort_by(|a, b| {
            b.0.total_cmp(&a.0)
                .then(a.1.x0.total_cmp(&b.1.x0))
                .then(a.1.y0.total_cmp(&b.1.y0))
        });
        out
    }

    fn global_score(&self) -> f64 {
        let mut placement = Placement::default();
        for (pos, cell) in self.placed.iter().enumerate() {
            placement
                .cells
                .insert(self.spec.rooms[self.order[pos]].id.clone(), *cell);
        }
        global_score(self.spec, &placement, self.previous)
    }

    /// Limited-discrepancy descent: at most `disc` non-best choices on the way down.
    fn descend(&mut self, k: usize, disc: usize) {
        if k == self.order.len() {
            self.leaves += 1;
            let s = self.global_score();
            if self.best.as_ref().is_none_or(|(b, _)| s > *b + 1e-9) {
                self.best = Some((s, self.placed.clone()));
            }
            return;
        }
        if self.out_of_budget() {
            return;
        }
        self.nodes += 1;
        let cands = self.candidates(k);
        for (j, (_, cell)) in cands.into_iter().take(self.cfg.branching).enumerate() {
            if j > 0 && disc == 0 {
                break;
            }
            self.placed.push(cell);
            self.descend(k + 1, if j == 0 { disc } else { disc - 1 });
            self.placed.pop();
            if self.out_of_budget() {
                return;
            }
        }
    }
}

/// Global score of a complete placement: compactness, preferred neighbours, daylight for rooms
/// that want windows, the entrance on the outside, and stability against `previous`.
pub fn global_score(spec: &HouseSpec, placement: &Placement, previous: Option<&Placement>) -> f64 {
    let mut score = 10.0 * placement.compactness();
    let pairs: Vec<_> = spec.adjacency.iter().collect();
    if !pairs.is_empty() {
        let ok = pairs
            .iter()
            .filter(|p| placement.shared(&p.a, &p.b) >= MIN_SHARED - EPS)
            .count();
        score += 2.0 * ok as f64 / pairs.len() as f64;
    }
    let exterior = placement.exterior_lengths();
    let ext = |id: &str| exterior.get(id).copied().unwrap_or(0.0);
    let want: Vec<_> = spec.rooms.iter().filter(|r| r.windows).collect();
    if !want.is_empty() {
        let lit = want.iter().filter(|r| ext(&r.id) >= MIN_SHARED).count();
        score += 3.0 * lit as f64 / want.len() as f64;
    }
    if ext(&spec.entrance) < MIN_SHARED {
        score -= 5.0;
    }
    // Slots too narrow to walk through between rooms.
    let cells: Vec<&Rect> = placement.cells.values().collect();
    for (i, a) in cells.iter().enumerate() {
        for b in &cells[i + 1..] {
            if a.slot(b, SLOT).is_some() {
                score -= 2.0;
            }
        }
    }
    // Enclosed courtyards: unlit, unreachable pockets.
    let holes = Outside::of(placement).hole_area();
    if holes > 0.0 {
        score -= 3.0 + holes;
    }
    if let Some(b) = placement.bounds() {
        let aspect = b.w().max(b.d()) / b.w().min(b.d()).max(EPS);
        score -= 0.5 * (aspect - 2.0).max(0.0);
    }
    if let Some(prev) = previous {
        let common: Vec<f64> = placement
            .cells
            .iter()
            .filter_map(|(k, r)| {
                prev.cells.get(k).map(|p| {
                    let (a, b) = (r.center(), p.center());
                    (-(a[0] - b[0]).hypot(a[1] - b[1]) / 2.0).exp()
                })
            })
            .collect();
        if !common.is_empty() {
            score += 12.0 * common.iter().sum::<f64>() / common.len() as f64;
        }
    }
    score
}

/// Places every room of `spec`; `previous` keeps rooms where they were (for edits).
pub fn place(
    spec: &HouseSpec,
    previous: Option<&Placement>,
    cfg: &SearchConfig,
) -> (Placement, SearchStats) {
    let start = Instant::now();
    let order = order(spec);
    let mut stats = SearchStats::default();
    let mut result: Option<Vec<Rect>> = None;
    for relaxed in [false, true] {
        let tables = Tables::new(spec, &order);
        let previous_cells = order
            .iter()
            .map(|&i| previous.and_then(|p| p.cells.get(&spec.rooms[i].id).copied()))
            .collect();
        let mut s = Search {
            spec,
            order: order.clone(),
            tables,
            cfg: *cfg,
            previous_cells,
            previous,
            relaxed,
            nodes: 0,
            leaves: 0,
            start,
            timed_out: false,
            best: None,
            placed: Vec::new(),
        };
        // Discrepancy budgets 0, 1, 2, ...: the greedy layout first, then its neighbours.
        for disc in 0..=order.len() {
            s.descend(0, disc);
            if s.out_of_budget() {
                break;
            }
        }
        stats.nodes += s.nodes;
        stats.leaves += s.leaves;
        stats.timed_out |= s.timed_out;
        if let Some((score, cells)) = s.best {
            stats.relaxed = relaxed;
            stats.score = score;
            result = Some(cells);
            break;
        }
    }
    let cells = result.unwrap_or_else(|| row_fallback(spec, &order, cfg.wall_thickness));
    let mut placement = Placement::default();
    for (pos, cell) in cells.into_iter().enumerate() {
        placement
            .cells
            .insert(spec.rooms[order[pos]].id.clone(), cell);
    }
    if stats.leaves == 0 {
        stats.relaxed = true;
        stats.score = global_score(spec, &placement, previous);
    }
    stats.compactness = placement.compactness();
    stats.seconds = start.elapsed().as_secs_f64();
    (placement, stats)
}

/// Last resort when even touching layouts ran out of budget: rooms in a row along x.
fn row_fallback(spec: &HouseSpec, order: &[usize], t: f64) -> Vec<Rect> {
    let mut x = 0.0;
    order
        .iter()
        .map(|&i| {
            let [w, d] = cell_size(spec, i, false, t);
            let r = Rect::at(x, 0.0, w, d);
            x += w;
            r
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::{brief, spec};

    #[test]
    fn rect_contact() {
        let a = Rect::at(0.0, 0.0, 4.0, 3.0);
        let b = Rect::at(4.0, 1.0, 2.0, 4.0);
        assert!((a.shared(&b) - 2.0).abs() < 1e-12);
        assert!(!a.overlaps(&b));
        assert!(a.overlaps(&Rect::at(3.9, 1.0, 2.0, 4.0)));
        assert_eq!(a.shared(&Rect::at(4.0, 3.0, 1.0, 1.0)), 0.0, "corners only");
    }

    #[test]
    fn places_a_flat_without_overlaps_and_with_parents_adjacent() {
        let spec = spec::house_spec(&brief::read(
            "A two-bedroom apartment with a master bedroom, a second bedroom, a living room, a hallway, and a bathroom.",
        ));
        let (p, stats) = place(&spec, None, &SearchConfig::default());
        assert!(!stats.relaxed, "{stats:?}");
        let ids: Vec<&String> = p.cells.keys().collect();
        for (i, a) in ids.iter().enumerate() {
            for b in &ids[i + 1..] {
                assert!(!p.cells[*a].overlaps(&p.cells[*b]), "{a} overlaps {b}");
            }
        }
        for r in &spec.rooms {
            if r.parents.is_empty() {
                continue;
            }
            assert!(
                r.parents
                    .iter()
                    .any(|q| p.shared(&r.id, q) >= MIN_SHARED - 1e-9),
                "{} is not next to any of {:?}",
                r.id,
                r.parents
            );
        }
        assert!(stats.compactness > 0.6, "{stats:?}");
    }
}
