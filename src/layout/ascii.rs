//! A text floor plan of built rooms: walls, doors, windows and open connections on a character
//! grid (north up), each room labelled with its id and clear size, followed by a legend of
//! every wall segment with its openings. Needs nothing but the rooms, so any agent can read it.

use std::fmt::Write as _;

use crate::geometry::polygon;
use crate::scene::{OpeningKind, Room, Wall};

/// Metres per character column.
const SX: f64 = 0.25;
/// Metres per character row (characters are about twice as tall as wide).
const SY: f64 = 0.5;

/// Characters used on the plan.
pub const LEGEND: &str =
    "legend: # wall, D door, E exterior door, W window, . open connection (no wall), north is up";

struct Grid {
    cells: Vec<Vec<char>>,
    x0: f64,
    y1: f64,
}

impl Grid {
    fn col(&self, x: f64) -> usize {
        ((x - self.x0) / SX).round().max(0.0) as usize
    }
    fn row(&self, y: f64) -> usize {
        ((self.y1 - y) / SY).round().max(0.0) as usize
    }
    fn put(&mut self, r: usize, c: usize, ch: char) {
        if let Some(cell) = self.cells.get_mut(r).and_then(|row| row.get_mut(c)) {
            // Openings win over walls; walls over blanks.
            let rank = |c: char| match c {
                ' ' => 0,
                '#' => 1,
                _ => 2,
            };
            if rank(ch) >= rank(*cell) {
                *cell = ch;
            }
        }
    }
    fn text(&mut self, r: usize, c: usize, s: &str, max: usize) {
        for (k, ch) in s.chars().take(max).enumerate() {
            if let Some(cell) = self.cells.get_mut(r).and_then(|row| row.get_mut(c + k))
                && *cell == ' '
            {
                *cell = ch;
            }
        }
    }
}

/// Points along a wall centre line from `a` to `b` metres (wall coordinates), world XY.
fn along(w: &Wall, a: f64, b: f64) -> Vec<[f64; 2]> {
    let len = w.length().max(1e-9);
    let dir = [(w.end[0] - w.start[0]) / len, (w.end[1] - w.start[1]) / len];
    let step = SX.min(SY) / 2.0;
    let n = ((b - a) / step).ceil().max(1.0) as usize;
    (0..=n)
        .map(|k| {
            let s = a + (b - a) * k as f64 / n as f64;
            [w.start[0] + dir[0] * s, w.start[1] + dir[1] * s]
        })
        .collect()
}

fn side(w: &Wall) -> &'static str {
    let (dx, dy) = (w.end[0] - w.start[0], w.end[1] - w.start[1]);
    if dx.abs() >= dy.abs() {
        if dx > 0.0 { "south" } else { "north" }
    } else if dy > 0.0 {
        "east"
    } else {
        "west"
    }
}

/// The floor plan of `rooms` as text.
pub fn render(rooms: &[Room]) -> String {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for w in rooms.iter().flat_map(|r| &r.walls) {
        for p in [w.start, w.end] {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    if !lo[0].is_finite() {
        return "(no rooms)\n".to_string();
    }
    let cols = ((hi[0] - lo[0]) / SX).round() as usize + 1;
    let rows = ((hi[1] - lo[1]) / SY).round() as usize + 1;
    let mut g = Grid {
        cells: vec![vec![' '; cols]; rows],
        x0: lo[0],
        y1: hi[1],
    };
    for w in rooms.iter().flat_map(|r| &r.walls) {
        for p in along(w, 0.0, w.length()) {
            let (r, c) = (g.row(p[1]), g.col(p[0]));
            g.put(r, c, '#');
        }
        for o in &w.openings {
            let ch = match o.kind {
                OpeningKind::Door if w.neighbor.is_none() => 'E',
                OpeningKind::Door => 'D',
                OpeningKind::Window => 'W',
                OpeningKind::Open => '.',
            };
            let (a, b) = (o.center - o.width / 2.0, o.center + o.width / 2.0);
            let (a, b) = if o.kind == OpeningKind::Open {
                (a + w.thickness, b - w.thickness)
            } else {
                (a, b)
            };
            for p in along(w, a.max(0.0), b.min(w.length())) {
                let (r, c) = (g.row(p[1]), g.col(p[0]));
                g.put(r, c, ch);
            }
        }
    }
    for room in rooms {
        let (rl, rh) = polygon::bounds(&room.floor_polygon);
        let width = ((rh[0] - rl[0]) / SX).floor() as usize;
        let c = g.col(rl[0]) + 1;
        let mid = g.row((rl[1] + rh[1]) / 2.0);
        let max = width.saturating_sub(1);
        g.text(mid.saturating_sub(1), c, &room.id, max);
        g.text(
            mid,
            c,
            &format!("{:.1}x{:.1}m", rh[0] - rl[0], rh[1] - rl[1]),
            max,
        );
        g.text(mid + 1, c, &room.floor_material, max);
    }
    let mut out = String::new();
    for row in &g.cells {
        let line: String = row.iter().collect();
        out.push_str(line.trim_end());
        out.push('\n');
    }
    let _ = writeln!(out, "{LEGEND}");
    for room in rooms {
        let (rl, rh) = polygon::bounds(&room.floor_polygon);
        let _ = writeln!(
            out,
            "{} ({}): {:.2} x {:.2} m at ({:.2}, {:.2}), floor {}, walls {}, height {:.2} m",
            room.id,
            room.room_type,
            rh[0] - rl[0],
            rh[1] - rl[1],
            rl[0],
            rl[1],
            room.floor_material,
            room.wall_material,
            room.wall_height
        );
        for w in &room.walls {
            let to = match (&w.neighbor, &w.mirror_of) {
                (None, _) => "exterior".to_string(),
                (Some(n), Some(m)) => format!("shared with {n}, built as {m}"),
                (Some(n), None) => format!("shared with {n}"),
            };
            let openings: Vec<String> = w
                .openings
                .iter()
                .map(|o| match o.kind {
                    OpeningKind::Door => {
                        format!("{} door {:.2} m wide at {:.2} m", o.id, o.width, o.center)
                    }
                    OpeningKind::Window => format!(
                        "{} window {:.2} m wide at {:.2} m, sill {:.2} m",
                        o.id, o.width, o.center, o.bottom
                    ),
                    OpeningKind::Open => format!("{} open connection", o.id),
                })
                .collect();
            let _ = writeln!(
                out,
                "  {} {} {:.2} m, {}{}",
                w.id,
                side(w),
                w.length(),
                to,
                if openings.is_empty() {
                    String::new()
                } else {
                    format!(": {}", openings.join("; "))
                }
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::{brief, state};

    #[test]
    fn plan_shows_rooms_doors_and_windows() {
        let state = state::LayoutState::from_prompt(
            "A one-bedroom apartment with a bedroom, a living room, and a bathroom.",
            3,
        );
        let (rooms, _) = state.rooms();
        let text = render(&rooms);
        for r in &rooms {
            assert!(text.contains(&r.id), "{text}");
        }
        let plan: String = text
            .lines()
            .take_while(|l| !l.starts_with("legend"))
            .collect();
        assert!(
            plan.contains('D') && plan.contains('E') && plan.contains('W'),
            "{text}"
        );
        assert!(text.contains("exterior") && text.contains("shared with"));
        let _ = brief::read("");
    }
}
