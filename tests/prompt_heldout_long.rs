//! The reader on long descriptive prompts it was never tuned on
//! (`tests/fixtures/heldout_long.jsonl`): requirements written independently of the reader, by
//! someone who did not read its code, scored against the reader's plan the way a label-based
//! check scores a scene (object labels with count operators, negatives, rooms with counts).
//!
//! `cargo test --test prompt_heldout_long -- --nocapture` prints the table. The file is held
//! out: rules are never fitted to it; the floors (`assert_floors`) sit under the measured score
//! so a change that makes reading worse fails.

use scenesmith::eval::requirements;
use scenesmith::prompt::{self, Count, Reading, Scope};
use serde_json::Value;

/// Does a reader noun (`category`, `noun` as written) meet an object label? The rule of
/// `scenesmith eval --requirements` (label matching on names).
fn names(label: &str, category: &str, noun: &str) -> bool {
    requirements::name_meets(label, category) || requirements::name_meets(label, noun)
}

fn room_names(label: &str, r: &prompt::RoomReading) -> bool {
    requirements::room_name_meets(label, &r.room_type, false)
        || requirements::room_name_meets(label, &r.words, true)
}

/// Smallest and largest number a count allows (None: unbounded).
fn range(c: Count) -> (u32, Option<u32>) {
    match c {
        Count::Exactly(n) => (n, Some(n)),
        Count::AtLeast(n) => (n, None),
        Count::Several => (2, None),
    }
}

fn met(op: &str, lo: u32, hi: Option<u32>, exact_several: bool) -> bool {
    let num = |s: &str| s.trim().parse::<u32>().ok();
    if op == "several" {
        return lo >= 2 || exact_several;
    }
    if let Some(n) = op.strip_prefix(">=").and_then(num) {
        return lo >= n;
    }
    if let Some(n) = op.strip_prefix("<=").and_then(num) {
        return hi.is_some_and(|h| h <= n) && lo >= 1;
    }
    if let Some(n) = op.strip_prefix('=').and_then(num) {
        return lo == n && hi == Some(n);
    }
    false
}

#[derive(Default)]
struct Score {
    objects: usize,
    objects_met: usize,
    absent: usize,
    absent_met: usize,
    rooms: usize,
    rooms_met: usize,
    refuse: usize,
    refuse_met: usize,
    extra: usize,
    misses: Vec<String>,
}

fn check(id: &str, kind: &str, r: &Reading, reqs: &[Value], s: &mut Score) {
    if kind == "refuse" {
        s.refuse += 1;
        if r.understood() {
            s.misses.push(format!("{id}: not refused"));
        } else {
            s.refuse_met += 1;
        }
        return;
    }
    let mut used = vec![false; r.mentions.len()];
    for q in reqs {
        // A room requirement names a room alone: `{"absent": "chair", "room": "cell"}` is an
        // absent requirement in a room.
        if let Some(label) = q.get("room").and_then(Value::as_str)
            && q.get("object").is_none()
            && q.get("absent").is_none()
        {
            s.rooms += 1;
            let op = q["count"].as_str().unwrap_or("=1");
            let n = r.rooms.iter().filter(|x| room_names(label, x)).count() as u32;
            let house_ok = kind != "house" || r.scope == Scope::House;
            if met(op, n, Some(n), false) && house_ok {
                s.rooms_met += 1;
            } else {
                let got: Vec<&str> = r.rooms.iter().map(|x| x.words.as_str()).collect();
                s.misses
                    .push(format!("{id}: room {label} {op}: {n} (rooms {got:?})"));
            }
        } else if let Some(label) = q.get("absent").and_then(Value::as_str) {
            s.absent += 1;
            let neg = r
                .mentions
                .iter()
                .any(|m| m.negated && names(label, &m.category, &m.noun));
            let pos = r
                .mentions
                .iter()
                .any(|m| !m.negated && names(label, &m.category, &m.noun));
            if neg && !pos {
                s.absent_met += 1;
            } else {
                s.misses.push(format!(
                    "{id}: absent {label}: negated {neg}, planned {pos}"
                ));
            }
        } else if let Some(label) = q.get("object").and_then(Value::as_str) {
            s.objects += 1;
            let op = q["count"].as_str().unwrap_or("=1");
            let room = q.get("room").and_then(Value::as_str);
            let (mut lo, mut hi, mut several) = (0u32, Some(0u32), false);
            for (i, m) in r.mentions.iter().enumerate() {
                let in_room =
                    room.is_none_or(|l| r.rooms.get(m.room).is_some_and(|x| room_names(l, x)));
                if m.negated || !in_room || !names(label, &m.category, &m.noun) {
                    continue;
                }
                used[i] = true;
                let t = r.total(i);
                several |= t == Count::Several;
                let (a, b) = range(t);
                lo += a;
                hi = match (hi, b) {
                    (Some(x), Some(y)) => Some(x + y),
                    _ => None,
                };
            }
            if met(op, lo, hi, several) {
                s.objects_met += 1;
            } else {
                s.misses.push(format!(
                    "{id}: object {label} {op}{}: planned {lo}..{hi:?}",
                    room.map(|x| format!(" in {x}")).unwrap_or_default()
                ));
            }
        }
    }
    for (i, m) in r.mentions.iter().enumerate() {
        if !used[i] && !m.negated {
            let label_of_any = reqs.iter().any(|q| {
                ["object", "absent"].iter().any(|k| {
                    q.get(*k)
                        .and_then(Value::as_str)
                        .is_some_and(|l| names(l, &m.category, &m.noun))
                })
            });
            if !label_of_any {
                s.extra += 1;
                s.misses
                    .push(format!("{id}: extra {} ({})", m.category, m.noun));
            }
        }
    }
}

fn pct(a: usize, b: usize) -> f64 {
    if b == 0 {
        100.0
    } else {
        100.0 * a as f64 / b as f64
    }
}

/// `read_env` names the variable that lists ids whose whole reading is printed (the dev set
/// only: the held-out prompts are never looked at, and their misses are not printed).
fn score_file(path: &str, title: &str, misses_env: &str, read_env: Option<&str>) -> Score {
    let text = std::fs::read_to_string(path).unwrap();
    let mut s = Score::default();
    let mut n = 0;
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Value = serde_json::from_str(line).unwrap();
        let id = v["id"].as_str().unwrap();
        let kind = v["kind"].as_str().unwrap();
        let reqs = v["requirements"].as_array().cloned().unwrap_or_default();
        let r = prompt::read(v["prompt"].as_str().unwrap());
        if read_env
            .and_then(|e| std::env::var(e).ok())
            .is_some_and(|want| want.split(',').any(|w| w == id))
        {
            println!("READING {id} {}", serde_json::to_string(&r).unwrap());
        }
        check(id, kind, &r, &reqs, &mut s);
        n += 1;
    }
    println!("{title} ({n} prompts)");
    println!(
        "  objects met   {:4}/{:4} {:5.1}%",
        s.objects_met,
        s.objects,
        pct(s.objects_met, s.objects)
    );
    println!(
        "  absent met    {:4}/{:4} {:5.1}%",
        s.absent_met,
        s.absent,
        pct(s.absent_met, s.absent)
    );
    println!(
        "  rooms met     {:4}/{:4} {:5.1}%",
        s.rooms_met,
        s.rooms,
        pct(s.rooms_met, s.rooms)
    );
    println!("  refused       {:4}/{:4}", s.refuse_met, s.refuse);
    println!(
        "  extra objects {:4} (planned, named by no requirement)",
        s.extra
    );
    if read_env.is_some() && std::env::var_os(misses_env).is_some() {
        for m in &s.misses {
            println!("  miss: {m}");
        }
    }
    assert!(n >= 30, "{n} prompts");
    s
}

/// Fails when a score falls under its floor: the floors sit a few points under the score
/// measured when they were set (held-out, session of 2026-11-27: objects 84.7 %, absents
/// 91.3 %, rooms 93.6 %, refused 4/4; dev long, 102 prompts: 94.2 %, 97.4 %, 99.2 %, 4/4).
fn assert_floors(s: &Score, objects: f64, absent: f64, rooms: f64) {
    let o = pct(s.objects_met, s.objects);
    let a = pct(s.absent_met, s.absent);
    let r = pct(s.rooms_met, s.rooms);
    assert!(o >= objects, "objects met {o:.1}% < floor {objects}%");
    assert!(a >= absent, "absents met {a:.1}% < floor {absent}%");
    assert!(r >= rooms, "rooms met {r:.1}% < floor {rooms}%");
    assert_eq!(s.refuse_met, s.refuse, "every unreadable prompt is refused");
}

#[test]
fn reader_on_held_out_long_prompts() {
    let s = score_file(
        "tests/fixtures/heldout_long.jsonl",
        "reader on held-out long prompts",
        "HELDOUT_MISSES",
        None,
    );
    assert_floors(&s, 82.0, 88.0, 91.0);
}

/// A second held-out file (`tests/fixtures/heldout_long2.jsonl`, 44 prompts), written on
/// 2026-11-29 by a helper who read neither the reader nor the lexicon: scored, never read or
/// tuned on. Measured when added: objects 93.9 %, absents 94.1 %, rooms 96.0 %, refused 4/4
/// (its generated scenes scored 83.4 % of objects at the session's start).
#[test]
fn reader_on_second_held_out_long_prompts() {
    let s = score_file(
        "tests/fixtures/heldout_long2.jsonl",
        "reader on the second held-out long prompts",
        "HELDOUT2_NEVER_PRINTED",
        None,
    );
    assert_floors(&s, 90.0, 88.0, 93.0);
}

/// A third held-out file (`tests/fixtures/heldout_long3.jsonl`, 30 prompts), written on
/// 2026-11-29 by a helper who read neither the reader nor the lexicon: scored, never read or
/// tuned on. First run (commit a0f59cb): objects 86.2 %, absents 88.9 %, rooms 91.7 %,
/// refused 2/2; after the session's reader changes 87.4 %, 88.9 %, 93.1 %.
#[test]
fn reader_on_third_held_out_long_prompts() {
    let s = score_file(
        "tests/fixtures/heldout_long3.jsonl",
        "reader on the third held-out long prompts",
        "HELDOUT3_NEVER_PRINTED",
        None,
    );
    assert_floors(&s, 84.0, 85.0, 90.0);
}

/// The second development file (`tests/fixtures/devlong2.jsonl`, 40 prompts), written with
/// the third held-out file by the same helper; the reader may be tuned on it. First run
/// (commit a0f59cb): objects 87.7 %, absents 100 %, rooms 94.9 %; 91.0 %, 100 %, 98.0 % at
/// dcd8e72; 92.1 %, 100 %, 98.0 % after the reader changes of 2026-11-30.
#[test]
fn reader_on_second_dev_long_prompts() {
    let s = score_file(
        "tests/fixtures/devlong2.jsonl",
        "reader on the second dev long prompts",
        "DEVLONG2_MISSES",
        Some("DEVLONG2_READ"),
    );
    assert_floors(&s, 89.0, 95.0, 96.0);
}

/// The third development file (`tests/fixtures/devlong3.jsonl`, 40 prompts), written on
/// 2026-11-30 by a helper who read neither the reader, the lexicon nor the other prompt
/// files; the reader may be tuned on it. First run (commit 2420b17): objects 85.9 %, absents 85.7 %, rooms 91.3 %;
/// after the session's changes 85.9 %, 98.0 %, 91.3 %.
#[test]
fn reader_on_third_dev_long_prompts() {
    let s = score_file(
        "tests/fixtures/devlong3.jsonl",
        "reader on the third dev long prompts",
        "DEVLONG3_MISSES",
        Some("DEVLONG3_READ"),
    );
    assert_floors(&s, 83.0, 94.0, 89.0);
}

/// The development set of the same kind: the one the reader may be tuned on.
#[test]
fn reader_on_dev_long_prompts() {
    // A prompt of your own to look at while working on the reader (`READ_TEXT="..." cargo
    // test --test prompt_heldout_long dev -- --nocapture`).
    if let Ok(text) = std::env::var("READ_TEXT") {
        let r = prompt::read(&text);
        println!("READING text {}", serde_json::to_string(&r).unwrap());
    }
    let s = score_file(
        "tests/fixtures/devlong.jsonl",
        "reader on dev long prompts",
        "DEVLONG_MISSES",
        Some("DEVLONG_READ"),
    );
    assert_floors(&s, 92.0, 94.0, 97.0);
}
