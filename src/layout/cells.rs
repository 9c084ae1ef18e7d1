//! Rooms as cells: axis-aligned rectangles bounded by wall centre lines, a placement of them,
//! and the empty space around it (which parts are open outside, which are courtyards).
//!
//! Neighbouring cells share an edge; a room's clear floor is its cell shrunk by half a wall
//! thickness. Nothing here searches or decides; [`super::search`] places the cells.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

const EPS: f64 = 1e-6;

/// An axis-aligned rectangle, metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Rect {
    /// Low x.
    pub x0: f64,
    /// Low y.
    pub y0: f64,
    /// High x.
    pub x1: f64,
    /// High y.
    pub y1: f64,
}

impl Rect {
    /// A rectangle from its low corner and size.
    pub fn at(x0: f64, y0: f64, w: f64, d: f64) -> Rect {
        Rect {
            x0,
            y0,
            x1: x0 + w,
            y1: y0 + d,
        }
    }

    /// Width along x.
    pub fn w(&self) -> f64 {
        self.x1 - self.x0
    }

    /// Depth along y.
    pub fn d(&self) -> f64 {
        self.y1 - self.y0
    }

    /// Area.
    pub fn area(&self) -> f64 {
        self.w() * self.d()
    }

    /// Centre.
    pub fn center(&self) -> [f64; 2] {
        [(self.x0 + self.x1) / 2.0, (self.y0 + self.y1) / 2.0]
    }

    /// Whether the interiors overlap.
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 - EPS && o.x0 < self.x1 - EPS && self.y0 < o.y1 - EPS && o.y0 < self.y1 - EPS
    }

    /// Length of the boundary the two rectangles share (0 when they do not touch along an
    /// edge).
    pub fn shared(&self, o: &Rect) -> f64 {
        let ox = (self.x1.min(o.x1) - self.x0.max(o.x0)).max(0.0);
        let oy = (self.y1.min(o.y1) - self.y0.max(o.y0)).max(0.0);
        let vertical = (self.x1 - o.x0).abs() < EPS || (o.x1 - self.x0).abs() < EPS;
        let horizontal = (self.y1 - o.y0).abs() < EPS || (o.y1 - self.y0).abs() < EPS;
        let mut s = 0.0;
        if vertical {
            s += oy;
        }
        if horizontal {
            s += ox;
        }
        s
    }

    /// Width of the slot between two rectangles that face each other across a gap narrower
    /// than `max` (a sliver of outside nobody can use), if any.
    pub fn slot(&self, o: &Rect, max: f64) -> Option<f64> {
        let gx = (o.x0 - self.x1).max(self.x0 - o.x1);
        let gy = (o.y0 - self.y1).max(self.y0 - o.y1);
        let ox = self.x1.min(o.x1) - self.x0.max(o.x0);
        let oy = self.y1.min(o.y1) - self.y0.max(o.y0);
        if gx > EPS && gx < max && oy > EPS {
            return Some(gx);
        }
        if gy > EPS && gy < max && ox > EPS {
            return Some(gy);
        }
        None
    }

    /// Bounding box of two rectangles.
    pub fn union(&self, o: &Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }

    /// The rectangle moved by `(dx, dy)`.
    pub fn shifted(&self, dx: f64, dy: f64) -> Rect {
        Rect {
            x0: self.x0 + dx,
            y0: self.y0 + dy,
            x1: self.x1 + dx,
            y1: self.y1 + dy,
        }
    }
}

/// Cells of the rooms by id.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Room id -> cell (wall centre lines).
    pub cells: BTreeMap<String, Rect>,
}

impl Placement {
    /// Bounding box of every cell.
    pub fn bounds(&self) -> Option<Rect> {
        self.cells.values().copied().reduce(|a, b| a.union(&b))
    }

    /// Total cell area over bounding-box area (1 for a perfect rectangle).
    pub fn compactness(&self) -> f64 {
        match self.bounds() {
            Some(b) if b.area() > 0.0 => {
                self.cells.values().map(Rect::area).sum::<f64>() / b.area()
            }
            _ => 0.0,
        }
    }

    /// Length of the room's walls that face the open outside (not a neighbour, not an
    /// enclosed courtyard), metres.
    pub fn exterior_length(&self, id: &str) -> f64 {
        let outside = Outside::of(self);
        super::connect::intervals_with(self, id, &outside)
            .iter()
            .filter(|iv| iv.outside)
            .map(|iv| iv.len())
            .sum()
    }

    /// [`Placement::exterior_length`] of every room.
    pub fn exterior_lengths(&self) -> BTreeMap<String, f64> {
        let outside = Outside::of(self);
        self.cells
            .keys()
            .map(|id| {
                let len = super::connect::intervals_with(self, id, &outside)
                    .iter()
                    .filter(|iv| iv.outside)
                    .map(|iv| iv.len())
                    .sum();
                (id.clone(), len)
            })
            .collect()
    }

    /// Shared boundary length of two rooms, metres.
    pub fn shared(&self, a: &str, b: &str) -> f64 {
        match (self.cells.get(a), self.cells.get(b)) {
            (Some(x), Some(y)) => x.shared(y),
            _ => 0.0,
        }
    }

    /// Mean distance the centres of the rooms in both placements moved, metres.
    pub fn mean_displacement(&self, other: &Placement, except: &[&str]) -> f64 {
        let moved: Vec<f64> = self
            .cells
            .iter()
            .filter(|(k, _)| !except.contains(&k.as_str()))
            .filter_map(|(k, r)| {
                other.cells.get(k).map(|o| {
                    let (a, b) = (r.center(), o.center());
                    (a[0] - b[0]).hypot(a[1] - b[1])
                })
            })
            .collect();
        if moved.is_empty() {
            0.0
        } else {
            moved.iter().sum::<f64>() / moved.len() as f64
        }
    }
}

/// The empty space of a placement on the grid of every cell edge coordinate: which empty
/// pieces connect to the far outside and which are enclosed courtyards (holes).
#[derive(Debug, Clone)]
pub struct Outside {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Per grid cell (row-major, x fastest): 0 covered by a room, 1 open outside, 2 hole.
    state: Vec<u8>,
}

impl Outside {
    /// The outside of `p`.
    pub fn of(p: &Placement) -> Outside {
        let mut xs: Vec<f64> = Vec::new();
        let mut ys: Vec<f64> = Vec::new();
        for r in p.cells.values() {
            xs.extend([r.x0, r.x1]);
            ys.extend([r.y0, r.y1]);
        }
        let dedup = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v.dedup_by(|a, b| (*a - *b).abs() < EPS);
            if let (Some(lo), Some(hi)) = (v.first().copied(), v.last().copied()) {
                v.insert(0, lo - 1.0);
                v.push(hi + 1.0);
            }
        };
        dedup(&mut xs);
        dedup(&mut ys);
        let (nx, ny) = (xs.len().saturating_sub(1), ys.len().saturating_sub(1));
        let mut state = vec![2u8; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let c = [(xs[i] + xs[i + 1]) / 2.0, (ys[j] + ys[j + 1]) / 2.0];
                if p.cells
                    .values()
                    .any(|r| r.x0 < c[0] && c[0] < r.x1 && r.y0 < c[1] && c[1] < r.y1)
                {
                    state[j * nx + i] = 0;
                }
            }
        }
        // Flood the empty cells connected to the border.
        let mut stack: Vec<usize> = (0..state.len())
            .filter(|&k| {
                let (i, j) = (k % nx, k / nx);
                (i == 0 || j == 0 || i + 1 == nx || j + 1 == ny) && state[k] == 2
            })
            .collect();
        while let Some(k) = stack.pop() {
            if state[k] != 2 {
                continue;
            }
            state[k] = 1;
            let (i, j) = (k % nx, k / nx);
            if i > 0 {
                stack.push(k - 1);
            }
            if i + 1 < nx {
                stack.push(k + 1);
            }
            if j > 0 {
                stack.push(k - nx);
            }
            if j + 1 < ny {
                stack.push(k + nx);
            }
        }
        Outside { xs, ys, state }
    }

    /// Whether a point is empty and connected to the far outside.
    pub fn is_open(&self, p: [f64; 2]) -> bool {
        let (nx, ny) = (
            self.xs.len().saturating_sub(1),
            self.ys.len().saturating_sub(1),
        );
        let find = |v: &[f64], x: f64| -> Option<usize> {
            if v.len() < 2 || x <= v[0] || x >= v[v.len() - 1] {
                return None;
            }
            Some(v.partition_point(|&e| e <= x) - 1)
        };
        match (find(&self.xs, p[0]), find(&self.ys, p[1])) {
            (Some(i), Some(j)) if i < nx && j < ny => self.state[j * nx + i] == 1,
            _ => true,
        }
    }

    /// Area of the enclosed courtyards, m^2.
    pub fn hole_area(&self) -> f64 {
        let nx = self.xs.len().saturating_sub(1);
        self.state
            .iter()
            .enumerate()
            .filter(|(_, s)| **s == 2)
            .map(|(k, _)| {
                let (i, j) = (k % nx, k / nx);
                (self.xs[i + 1] - self.xs[i]) * (self.ys[j + 1] - self.ys[j])
            })
            .sum()
    }
}
