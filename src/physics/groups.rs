//! Groups of objects close enough to touch: the stability islands and the furniture phase's
//! settle subsets are simulated apart because objects of different groups cannot touch
//! without first moving farther than the gap.

use std::collections::BTreeMap;

use super::as_written::posed_objects;
use super::collision::PosedObject;
use crate::state::SceneState;

/// Objects closer than this (collision bounds) share a group, metres.
pub const ISLAND_GAP_M: f64 = 0.02;

/// Whether two axis-aligned boxes come within `gap` of each other.
pub fn near(a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3]), gap: f64) -> bool {
    (0..3).all(|k| a.0[k] - gap <= b.1[k] && b.0[k] - gap <= a.1[k])
}

/// Union-find root with path halving.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// `ids` grouped: two share a group when they are linked (pairs of indices into `ids`) or
/// their collision bounds come within `gap` of each other. Ids in the given order within a
/// group, largest group first.
pub fn groups_near(
    state: &SceneState,
    ids: &[&str],
    links: &[(usize, usize)],
    gap: f64,
) -> Vec<Vec<String>> {
    let posed: Vec<PosedObject> = posed_objects(&state.scene, &state.assets);
    let bounds: BTreeMap<&str, ([f64; 3], [f64; 3])> =
        posed.iter().map(|p| (p.id.as_str(), p.bounds)).collect();
    let mut parent: Vec<usize> = (0..ids.len()).collect();
    let join = |parent: &mut Vec<usize>, a: usize, b: usize| {
        let (ra, rb) = (root(parent, a), root(parent, b));
        if ra != rb {
            parent[ra.max(rb)] = ra.min(rb);
        }
    };
    for &(i, j) in links {
        join(&mut parent, i, j);
    }
    for i in 0..ids.len() {
        for j in i + 1..ids.len() {
            let (Some(a), Some(b)) = (bounds.get(ids[i]), bounds.get(ids[j])) else {
                continue;
            };
            if near(a, b, gap) {
                join(&mut parent, i, j);
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    for (i, id) in ids.iter().enumerate() {
        let r = root(&mut parent, i);
        groups.entry(r).or_default().push(id.to_string());
    }
    let mut out: Vec<Vec<String>> = groups.into_values().collect();
    // Largest first: the pool starts the longest simulations first.
    out.sort_by_key(|g| std::cmp::Reverse(g.len()));
    out
}
