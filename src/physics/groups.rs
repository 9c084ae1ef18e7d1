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

/// Groups of at most this many objects are simulated together with other small groups.
pub const SMALL_GROUP: usize = 3;

/// Most objects in one bin of small groups.
pub const BIN_OBJECTS: usize = 12;

/// `groups` (largest first) with the small ones (at most [`SMALL_GROUP`] objects) packed
/// together, in order, into bins of at most [`BIN_OBJECTS`]: groups that cannot touch each
/// other simulate in one plant as they would apart, and each request costs the bridge a
/// plant build (about 20 ms per model file) and a round trip, most of the time of a lone
/// chair's simulation. Larger groups stay alone, so a slow one runs beside the others.
/// Largest first again.
pub fn pack_small_groups(groups: Vec<Vec<String>>) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = Vec::new();
    let mut bin: Vec<String> = Vec::new();
    for g in groups {
        if g.len() > SMALL_GROUP {
            out.push(g);
            continue;
        }
        if bin.len() + g.len() > BIN_OBJECTS {
            out.push(std::mem::take(&mut bin));
        }
        bin.extend(g);
    }
    if !bin.is_empty() {
        out.push(bin);
    }
    out.sort_by_key(|g| std::cmp::Reverse(g.len()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn group(prefix: &str, n: usize) -> Vec<String> {
        (0..n).map(|i| format!("{prefix}_{i}")).collect()
    }

    #[test]
    fn small_groups_share_bins_and_large_ones_stay_alone() {
        let mut groups = vec![group("bookcase", 30), group("desk", 4)];
        groups.extend((0..20).map(|i| group(&format!("chair{i}"), 1)));
        groups.push(group("pair", 2));
        let packed = pack_small_groups(groups);
        assert_eq!(packed[0], group("bookcase", 30));
        assert!(packed.contains(&group("desk", 4)));
        // 22 objects of small groups in bins of at most 12: two bins, nothing lost or doubled.
        let bins: Vec<&Vec<String>> = packed
            .iter()
            .filter(|g| g[0].starts_with("chair"))
            .collect();
        assert_eq!(bins.len(), 2);
        assert!(bins.iter().all(|b| b.len() <= BIN_OBJECTS));
        let mut all: Vec<&String> = packed.iter().flatten().collect();
        assert_eq!(all.len(), 30 + 4 + 20 + 2);
        all.sort();
        all.dedup();
        assert_eq!(all.len(), 56);
        // A pair is never split across bins.
        let with_pair: Vec<&Vec<String>> = packed
            .iter()
            .filter(|g| g.iter().any(|id| id.starts_with("pair")))
            .collect();
        assert_eq!(with_pair.len(), 1);
        assert!(packed.windows(2).all(|w| w[0].len() >= w[1].len()));
    }
}
