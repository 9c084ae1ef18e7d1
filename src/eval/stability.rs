//! STB, MD, XD, MR: how far the free objects move when the scene is simulated.
//!
//! The scene is split into *islands*: free objects that rest on each other (the support
//! relation) or whose collision bounds come within [`ISLAND_GAP_M`] of each other, each with the
//! architecture and the welded objects near it. Objects of different islands cannot touch
//! without first moving more than the STB threshold, so simulating the islands one by one
//! gives the verdicts of one big simulation; the islands run in parallel on the bridge pool,
//! and each stops at rest on its own, so a piece that keeps rocking in one corner does not keep
//! the whole scene simulating (Drake's cost per step grows faster than the body count).

use std::collections::BTreeMap;

use super::{EvalError, Stability, StabilityOptions, Unstable};
use crate::physics::as_written::posed_objects;
use crate::physics::groups::{ISLAND_GAP_M, groups_near, near, pack_small_groups};
use crate::physics::protocol::{Simulate, VerdictBound};
use crate::physics::settle::{SettleOptions, SettleReply, simulate_args};
use crate::physics::workspace::{Role, Workspace};
use crate::physics::{BridgePool, PhysicsError};
use crate::scene::{ObjectKind, SceneObject, Support};
use crate::state::SceneState;

/// Welded objects within this distance of an island's bounds are simulated with it, metres.
const WELDED_REACH_M: f64 = 0.05;

fn is_free(o: &SceneObject) -> bool {
    !o.welded && matches!(o.kind, ObjectKind::Furniture | ObjectKind::Manipuland)
}

/// The islands of free objects (ids in scene order), largest first.
pub fn islands(state: &SceneState) -> Vec<Vec<String>> {
    let free: Vec<&SceneObject> = state.scene.objects.iter().filter(|o| is_free(o)).collect();
    let index: BTreeMap<&str, usize> = free
        .iter()
        .enumerate()
        .map(|(i, o)| (o.id.as_str(), i))
        .collect();
    let mut links = Vec::new();
    for (i, o) in free.iter().enumerate() {
        if let Support::Object { parent: p, .. } = &o.support
            && let Some(&j) = index.get(p.as_str())
        {
            links.push((i, j));
        }
    }
    let ids: Vec<&str> = free.iter().map(|o| o.id.as_str()).collect();
    groups_near(state, &ids, &links, ISLAND_GAP_M)
}

/// The subset scene of one island: its objects free, the architecture and the welded objects
/// near it welded.
fn island_members(state: &SceneState, island: &[String]) -> BTreeMap<String, Role> {
    let posed = posed_objects(&state.scene, &state.assets);
    let bounds: BTreeMap<&str, ([f64; 3], [f64; 3])> =
        posed.iter().map(|p| (p.id.as_str(), p.bounds)).collect();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for id in island {
        if let Some(b) = bounds.get(id.as_str()) {
            for k in 0..3 {
                lo[k] = lo[k].min(b.0[k]);
                hi[k] = hi[k].max(b.1[k]);
            }
        }
    }
    let mut members: BTreeMap<String, Role> = BTreeMap::new();
    for o in &state.scene.objects {
        let welded_near = o.kind != ObjectKind::Architecture
            && !is_free(o)
            && bounds
                .get(o.id.as_str())
                .is_some_and(|b| near(b, &(lo, hi), WELDED_REACH_M));
        if o.kind == ObjectKind::Architecture || welded_near {
            members.insert(o.id.clone(), Role::Welded);
        }
    }
    for id in island {
        members.insert(id.clone(), Role::Free);
    }
    members
}

/// Runs the stability simulation of `state`, island by island on the pool.
pub fn stability(
    state: &SceneState,
    pool: &BridgePool,
    opts: &StabilityOptions,
) -> Result<Stability, EvalError> {
    let mut all = stabilities(state, pool, std::slice::from_ref(opts))?;
    Ok(all.remove(0))
}

/// The stability simulation under each of `opts` (contact models, say), all islands of all
/// of them in one batch over the pool, largest islands first, so a slow island under one
/// model runs beside the others instead of after them.
pub fn stabilities(
    state: &SceneState,
    pool: &BridgePool,
    opts: &[StabilityOptions],
) -> Result<Vec<Stability>, EvalError> {
    let islands = islands(state);
    if islands.is_empty() {
        return Ok(opts.iter().map(|o| verdicts(o, 0, &[])).collect());
    }
    // Small islands simulate together (see `pack_small_groups`); a bin's reply holds the
    // motion of each of its objects, and the verdicts are per object.
    let bins = pack_small_groups(islands.clone());
    let mut workspace = Workspace::new(state)?;
    let mut directives = Vec::new();
    for bin in &bins {
        directives.push(workspace.write_subset(state, &island_members(state, bin))?);
    }
    // (option index, bin index) of each request, in submission order (largest bins first).
    let mut slots = Vec::new();
    let mut requests = Vec::new();
    for i in 0..bins.len() {
        for (k, o) in opts.iter().enumerate() {
            requests.push(simulate_args(
                &directives[i],
                &workspace.package_xml(),
                &settle_options(o),
            ));
            slots.push((k, i));
        }
    }
    let mut results: Vec<Vec<Option<SettleReply>>> = opts
        .iter()
        .map(|_| bins.iter().map(|_| None).collect())
        .collect();
    for ((k, i), reply) in slots.into_iter().zip(pool.call_all::<Simulate>(&requests)) {
        let r = reply.map_err(PhysicsError::from)?;
        tracing::info!(
            "STB ({:?}) {} of {} ({} free): {:.2} s simulated{} in {:.1} s wall ({:.1} ms/step, plant {:.1} s)",
            opts[k].contact.model,
            if islands.contains(&bins[i]) {
                "island"
            } else {
                "bin"
            },
            bins[i][0],
            bins[i].len(),
            r.sim_time,
            if r.at_rest {
                ", at rest"
            } else if r.bounded {
                ", verdicts fixed"
            } else {
                ""
            },
            r.wall_s,
            r.ms_per_step,
            r.build_s
        );
        results[k][i] = Some(r);
    }
    Ok(opts
        .iter()
        .zip(results)
        .map(|(o, rs)| {
            let rs: Vec<SettleReply> = rs.into_iter().flatten().collect();
            verdicts(o, islands.len(), &rs)
        })
        .collect())
}

fn settle_options(opts: &StabilityOptions) -> SettleOptions {
    SettleOptions {
        max_time: opts.duration_s,
        time_step: opts.time_step_s,
        stop_at_rest: opts.stop_at_rest,
        rest_speed: opts.rest_speed,
        rest_angular_speed: opts.rest_angular_speed,
        rest_time: opts.rest_time,
        contact: opts.contact,
        wall_limit: 3600.0,
        verdict: Some(VerdictBound {
            max_displacement_m: opts.max_displacement_m,
            max_rotation_rad: opts.max_rotation_rad,
        }),
        ..SettleOptions::default()
    }
}

/// STB and the motion statistics from the islands' results.
fn verdicts(opts: &StabilityOptions, islands: usize, results: &[SettleReply]) -> Stability {
    let mut unstable = Vec::new();
    let (mut n, mut sum_d, mut sum_r, mut max_d) = (0usize, 0.0, 0.0, 0.0f64);
    let (mut timed_out, mut diverged) = (0, 0);
    for result in results {
        // An island the wall-clock cap stopped before the duration was not shown stable:
        // every object in it counts as unstable, whatever it did in the time simulated.
        // So was an island whose simulation diverged: its objects flew off to non-finite
        // poses (the motion is what they did before).
        let cut_short = (result.timed_out && !result.at_rest) || result.diverged;
        timed_out += usize::from(result.timed_out && !result.at_rest && !result.diverged);
        diverged += usize::from(result.diverged);
        // After an island stopped early, the most the remaining time could add: at the rest
        // speeds after a stop at rest, at each object's own pace after a bounded stop.
        let left = (opts.duration_s - result.sim_time).max(0.0);
        for (id, m) in &result.motion {
            let (extra_d, extra_r) = if result.at_rest {
                (left * opts.rest_speed, left * opts.rest_angular_speed)
            } else if result.bounded {
                (left * m.speed_bound, left * m.angular_speed_bound)
            } else {
                (0.0, 0.0)
            };
            n += 1;
            sum_d += m.displacement_m;
            sum_r += m.rotation_rad;
            max_d = max_d.max(m.displacement_m);
            let (d, r) = (m.displacement_m + extra_d, m.rotation_rad + extra_r);
            if cut_short || !(d < opts.max_displacement_m && r < opts.max_rotation_rad) {
                unstable.push(Unstable {
                    id: id.clone(),
                    displacement_m: d,
                    rotation_rad: r,
                });
            }
        }
    }
    unstable.sort_by(|a, b| a.id.cmp(&b.id));
    let mean = |s: f64| if n == 0 { 0.0 } else { s / n as f64 };
    Stability {
        options: *opts,
        free_objects: n,
        stable: n - unstable.len(),
        percent: if n == 0 {
            100.0
        } else {
            100.0 * (n - unstable.len()) as f64 / n as f64
        },
        md_mm: 1e3 * mean(sum_d),
        xd_m: max_d,
        mr_rad: mean(sum_r),
        at_rest_at_end: results.iter().all(|r| r.at_rest),
        simulated_s: results.iter().map(|r| r.sim_time).fold(0.0, f64::max),
        islands,
        timed_out_islands: timed_out,
        diverged_islands: diverged,
        unstable,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::protocol::{CacheStats, ContactArgs};
    use crate::physics::settle::{ContactModel, Motion};

    fn island(
        motion: &[(&str, f64)],
        sim_time: f64,
        at_rest: bool,
        timed_out: bool,
    ) -> SettleReply {
        SettleReply {
            poses: BTreeMap::new(),
            motion: motion
                .iter()
                .map(|(id, d)| {
                    let m = Motion {
                        displacement_m: *d,
                        rotation_rad: 0.0,
                        start_z: 0.0,
                        end_z: 0.0,
                        speed_bound: 0.0,
                        angular_speed_bound: 0.0,
                    };
                    (id.to_string(), m)
                })
                .collect(),
            sim_time,
            steps: (sim_time * 1000.0) as u64,
            at_rest,
            timed_out,
            max_penetration_m: 0.0,
            free_bodies: motion.len(),
            wall_s: 1.0,
            build_s: 0.0,
            ms_per_step: 1.0,
            max_speed: 0.0,
            max_angular_speed: 0.0,
            contact: ContactArgs {
                model: ContactModel::AsWritten,
                approximation: None,
            },
            time_step: 1e-3,
            sim_s: 1.0,
            cache: CacheStats { hits: 0, misses: 1 },
            diverged: false,
            bounded: false,
        }
    }

    #[test]
    fn an_island_stopped_by_the_wall_clock_is_unstable() {
        let opts = StabilityOptions::default();
        let results = [
            island(&[("mug", 0.001), ("plate", 0.0)], 1.2, false, true),
            island(&[("book", 0.002)], 5.0, false, false),
            island(&[("lamp", 0.0)], 0.8, true, false),
        ];
        let s = verdicts(&opts, 3, &results);
        assert_eq!(s.timed_out_islands, 1);
        let ids: Vec<&str> = s.unstable.iter().map(|u| u.id.as_str()).collect();
        assert_eq!(ids, ["mug", "plate"]);
        assert_eq!((s.free_objects, s.stable), (4, 2));
    }

    #[test]
    fn an_island_that_diverged_is_unstable() {
        let opts = StabilityOptions::default();
        let mut blown = island(&[("pencil", 0.0005), ("desk", 0.0)], 2.5, false, false);
        blown.diverged = true;
        let results = [blown, island(&[("lamp", 0.0)], 0.8, true, false)];
        let s = verdicts(&opts, 2, &results);
        assert_eq!((s.diverged_islands, s.timed_out_islands), (1, 0));
        let ids: Vec<&str> = s.unstable.iter().map(|u| u.id.as_str()).collect();
        assert_eq!(ids, ["desk", "pencil"]);
        assert_eq!((s.free_objects, s.stable), (3, 1));
    }

    #[test]
    fn early_stop_at_rest_adds_what_the_rest_of_the_time_could_move() {
        let opts = StabilityOptions::default();
        // 4.5 s left at 0.5 mm/s could add 2.25 mm: 8 mm becomes more than 1 cm.
        let s = verdicts(&opts, 1, &[island(&[("cup", 0.008)], 0.5, true, false)]);
        assert_eq!(s.stable, 0);
        let s = verdicts(&opts, 1, &[island(&[("cup", 0.007)], 0.5, true, false)]);
        assert_eq!(s.stable, 1);
    }

    #[test]
    fn a_bounded_stop_adds_each_objects_own_pace() {
        let opts = StabilityOptions::default();
        // Stopped at 1 s with 4 s to go: the cup creeping at 1 mm/s could reach 6 mm + 4 mm,
        // the plate at rest stays at 6 mm.
        let mut r = island(&[("cup", 0.006), ("plate", 0.006)], 1.0, false, false);
        r.bounded = true;
        if let Some(m) = r.motion.get_mut("cup") {
            m.speed_bound = 0.001;
        }
        let s = verdicts(&opts, 1, &[r]);
        let ids: Vec<&str> = s.unstable.iter().map(|u| u.id.as_str()).collect();
        assert_eq!(ids, ["cup"]);
        assert!(
            (s.md_mm - 6.0).abs() < 1e-9,
            "MD reports the simulated motion"
        );
    }
}
