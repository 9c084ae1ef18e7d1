//! The prompt reader on the dev prompts: a table test of objects, counts, relations, rooms,
//! styles and negations against `tests/fixtures/reader_expectations.json` (what a careful
//! human lists), plus synthetic prompts for negation and density.
//!
//! `cargo test --test prompt_reader -- --nocapture` prints the accuracy table.

use scenesmith::prompt::{self, Count, Mention, Per, Reading, RelationKind, Scope, Target};
use serde_json::Value;

fn fixtures() -> (Vec<(String, String)>, Value) {
    let dev = std::fs::read_to_string("tests/fixtures/dev_prompts.jsonl").unwrap();
    let prompts = dev
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Value = serde_json::from_str(l).unwrap();
            (
                v["id"].as_str().unwrap().to_string(),
                v["prompt"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    let exp: Value = serde_json::from_str(
        &std::fs::read_to_string("tests/fixtures/reader_expectations.json").unwrap(),
    )
    .unwrap();
    (prompts, exp)
}

fn count_matches(want: &str, got: Count) -> bool {
    match (want, got) {
        ("several", Count::Several) => true,
        (w, Count::Exactly(n)) if w.starts_with('=') => w[1..].parse::<u32>().ok() == Some(n),
        (w, Count::AtLeast(n)) if w.starts_with(">=") => w[2..].parse::<u32>().ok() == Some(n),
        _ => false,
    }
}

fn kind_name(k: RelationKind) -> String {
    serde_json::to_value(k)
        .unwrap()
        .as_str()
        .unwrap()
        .to_string()
}

fn target_name(r: &Reading, t: Target) -> String {
    match t {
        Target::Mention(i) => r.mentions[i].category.clone(),
        other => serde_json::to_value(other).unwrap()["kind"]
            .as_str()
            .unwrap()
            .to_string(),
    }
}

/// Does mention `m` have the relation `spec` ("kind:target#i[part]", alternatives with |)?
fn has_relation(r: &Reading, m: &Mention, spec: &str) -> bool {
    spec.split('|').any(|alt| {
        let (kind, rest) = alt.split_once(':').unwrap();
        let (rest, part) = match rest.split_once('[') {
            Some((a, b)) => (a, Some(b.trim_end_matches(']'))),
            None => (rest, None),
        };
        let (target, inst) = match rest.split_once('#') {
            Some((a, b)) => (a, Some(b.parse::<u32>().unwrap())),
            None => (rest, None),
        };
        m.relations.iter().any(|rel| {
            kind_name(rel.kind) == kind
                && (target_name(r, rel.target) == target
                    || rel.second.is_some_and(|s| target_name(r, s) == target))
                && (inst.is_none() || rel.instance == inst)
                && (part.is_none() || rel.part.as_deref() == part)
        })
    })
}

fn per_matches(r: &Reading, m: &Mention, per: Option<&str>) -> bool {
    match (per, m.per) {
        (None, None) => true,
        // "several per several parents" is still several.
        (None, Some(_)) => {
            m.count == Count::Several
                && r.total(
                    r.mentions
                        .iter()
                        .position(|x| std::ptr::eq(x, m))
                        .unwrap_or(0),
                ) == Count::Several
        }
        (Some("setting"), Some(Per::Setting { .. })) => true,
        (Some(p), Some(Per::Each { parent })) => r.mentions[parent].category == p,
        _ => false,
    }
}

fn attrs_of(m: &Mention) -> Vec<String> {
    let a = &m.attributes;
    a.modifiers
        .iter()
        .chain(&a.adjectives)
        .chain(&a.colors)
        .chain(&a.styles)
        .map(|s| s.to_lowercase())
        .chain(a.size.iter().cloned())
        .collect()
}

#[derive(Default, Debug)]
struct Score {
    prompts: usize,
    objects: usize,
    found: usize,
    counts: usize,
    relations: usize,
    relations_right: usize,
    styles: usize,
    styles_right: usize,
    rooms_right: usize,
    spurious: usize,
    negations: usize,
    negations_right: usize,
    misses: Vec<String>,
}

fn check(id: &str, r: &Reading, e: &Value, s: &mut Score) {
    s.prompts += 1;
    let scope = if r.scope == Scope::House {
        "house"
    } else {
        "room"
    };
    let rooms: Vec<&str> = r.rooms.iter().map(|x| x.room_type.as_str()).collect();
    let want_rooms: Vec<&str> = e["rooms"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    let parents_ok = match e.get("parents") {
        Some(p) => p
            .as_array()
            .unwrap()
            .iter()
            .zip(&r.rooms)
            .all(|(w, got)| w.as_u64().map(|x| x as usize) == got.parent),
        None => true,
    };
    if scope == e["scope"].as_str().unwrap() && rooms == want_rooms && parents_ok {
        s.rooms_right += 1;
    } else {
        s.misses.push(format!(
            "{id}: rooms {scope} {rooms:?}, want {} {want_rooms:?}",
            e["scope"]
        ));
    }
    if let Some(styles) = e.get("styles").and_then(Value::as_array) {
        for st in styles {
            s.styles += 1;
            if r.rooms
                .iter()
                .any(|x| x.styles.iter().any(|y| y == st.as_str().unwrap()))
            {
                s.styles_right += 1;
            } else {
                s.misses.push(format!("{id}: room style {st} missing"));
            }
        }
    }
    for n in e["negated"].as_array().unwrap() {
        s.negations += 1;
        if r.mentions
            .iter()
            .any(|m| m.negated && m.category == n.as_str().unwrap())
        {
            s.negations_right += 1;
        } else {
            s.misses.push(format!("{id}: negation of {n} missing"));
        }
    }
    let mut used = vec![false; r.mentions.len()];
    for o in e["objects"].as_array().unwrap() {
        s.objects += 1;
        let noun = o["noun"].as_str().unwrap();
        let room = o.get("room").and_then(Value::as_u64).unwrap_or(0) as usize;
        let attrs: Vec<String> = o
            .get("attrs")
            .and_then(Value::as_array)
            .map_or(Vec::new(), |a| {
                a.iter()
                    .map(|x| x.as_str().unwrap().to_lowercase())
                    .collect()
            });
        let rels: Vec<&str> = o
            .get("rel")
            .and_then(Value::as_array)
            .map_or(Vec::new(), |a| {
                a.iter().map(|x| x.as_str().unwrap()).collect()
            });
        s.relations += rels.len();
        let candidates: Vec<usize> = (0..r.mentions.len())
            .filter(|&i| {
                !used[i]
                    && !r.mentions[i].negated
                    && r.mentions[i].room == room
                    && r.mentions[i].category == noun
            })
            .collect();
        let pick = candidates
            .iter()
            .copied()
            .find(|&i| {
                let have = attrs_of(&r.mentions[i]);
                attrs
                    .iter()
                    .all(|a| have.iter().any(|h| h.contains(a.as_str())))
            })
            .or_else(|| candidates.first().copied());
        let Some(i) = pick else {
            s.misses.push(format!("{id}: missing {noun} (room {room})"));
            continue;
        };
        used[i] = true;
        s.found += 1;
        let m = &r.mentions[i];
        let want_count = o["count"].as_str().unwrap();
        let per = o.get("per").and_then(Value::as_str);
        if count_matches(want_count, m.count) && per_matches(r, m, per) {
            s.counts += 1;
        } else {
            s.misses.push(format!(
                "{id}: {noun} count {:?} per {:?}, want {want_count} per {per:?}",
                m.count, m.per
            ));
        }
        for spec in rels {
            if has_relation(r, m, spec) {
                s.relations_right += 1;
            } else {
                let got: Vec<String> = m
                    .relations
                    .iter()
                    .map(|x| format!("{}:{}", kind_name(x.kind), target_name(r, x.target)))
                    .collect();
                s.misses.push(format!(
                    "{id}: {noun} relation {spec} missing (has {got:?})"
                ));
            }
        }
        if let Some(styles) = o.get("styles").and_then(Value::as_array) {
            for st in styles {
                s.styles += 1;
                if m.attributes
                    .styles
                    .iter()
                    .any(|y| y == st.as_str().unwrap())
                {
                    s.styles_right += 1;
                } else {
                    s.misses.push(format!(
                        "{id}: {noun} style {st} missing (has {:?})",
                        m.attributes.styles
                    ));
                }
            }
        }
        let have = attrs_of(m);
        for a in &attrs {
            if !have.iter().any(|h| h.contains(a.as_str())) {
                s.misses
                    .push(format!("{id}: {noun} attribute {a} missing (has {have:?})"));
            }
        }
    }
    for (i, m) in r.mentions.iter().enumerate() {
        if !used[i] && !m.negated {
            s.spurious += 1;
            s.misses.push(format!(
                "{id}: extra mention {} ({:?})",
                m.category, m.count
            ));
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

fn report(title: &str, s: &Score) {
    println!("{title} ({} prompts)", s.prompts);
    println!(
        "  objects found      {:4}/{:4}  {:5.1}%",
        s.found,
        s.objects,
        pct(s.found, s.objects)
    );
    println!(
        "  counts right       {:4}/{:4}  {:5.1}%  (of objects found)",
        s.counts,
        s.found,
        pct(s.counts, s.found)
    );
    println!(
        "  relations right    {:4}/{:4}  {:5.1}%",
        s.relations_right,
        s.relations,
        pct(s.relations_right, s.relations)
    );
    println!(
        "  styles right       {:4}/{:4}  {:5.1}%",
        s.styles_right,
        s.styles,
        pct(s.styles_right, s.styles)
    );
    println!(
        "  negations right    {:4}/{:4}  {:5.1}%",
        s.negations_right,
        s.negations,
        pct(s.negations_right, s.negations)
    );
    println!(
        "  rooms right        {:4}/{:4}  {:5.1}%  (scope, room types, en-suite parents)",
        s.rooms_right,
        s.prompts,
        pct(s.rooms_right, s.prompts)
    );
    println!(
        "  extra mentions     {:4}       (precision {:5.1}%)",
        s.spurious,
        pct(s.found, s.found + s.spurious)
    );
    for m in &s.misses {
        println!("  miss: {m}");
    }
}

#[test]
fn reader_table_on_dev_prompts() {
    let (prompts, exp) = fixtures();
    let mut s = Score::default();
    let entries = exp["prompts"].as_array().unwrap();
    assert!(
        entries.len() >= 40,
        "the table covers {} dev prompts",
        entries.len()
    );
    for e in entries {
        let id = e["id"].as_str().unwrap();
        let text = &prompts
            .iter()
            .find(|(i, _)| i == id)
            .unwrap_or_else(|| panic!("no dev prompt {id}"))
            .1;
        check(id, &prompt::read(text), e, &mut s);
    }
    report(
        "reader accuracy on the dev prompts (the rules were tuned on these)",
        &s,
    );
    // Floors at the measured level: a change that makes the reader worse fails here.
    assert!(
        pct(s.found, s.objects) >= 99.0,
        "objects {}/{}",
        s.found,
        s.objects
    );
    assert!(
        pct(s.counts, s.found) >= 98.0,
        "counts {}/{}",
        s.counts,
        s.found
    );
    assert!(
        pct(s.relations_right, s.relations) >= 95.0,
        "relations {}/{}",
        s.relations_right,
        s.relations
    );
    assert!(
        pct(s.styles_right, s.styles) >= 95.0,
        "styles {}/{}",
        s.styles_right,
        s.styles
    );
    assert_eq!(s.rooms_right, s.prompts, "room structure");
    assert!(s.spurious <= 3, "{} extra mentions", s.spurious);
}

#[test]
fn reader_table_on_synthetic_prompts() {
    let (_, exp) = fixtures();
    let mut s = Score::default();
    for e in exp["synthetic"].as_array().unwrap() {
        let id = e["id"].as_str().unwrap();
        let r = prompt::read(e["prompt"].as_str().unwrap());
        check(id, &r, e, &mut s);
        if let Some(d) = e.get("density").and_then(Value::as_str) {
            let got = r.density.map(|x| {
                serde_json::to_value(x)
                    .unwrap()
                    .as_str()
                    .unwrap()
                    .to_string()
            });
            assert_eq!(got.as_deref(), Some(d), "{id}");
        }
    }
    assert!(s.misses.is_empty(), "{:#?}", s.misses);
    assert!(s.negations >= 4);
}

#[test]
fn reader_table_on_held_out_prompts() {
    let exp: Value = serde_json::from_str(
        &std::fs::read_to_string("tests/fixtures/reader_heldout.json").unwrap(),
    )
    .unwrap();
    let mut s = Score::default();
    for e in exp["prompts"].as_array().unwrap() {
        let id = e["id"].as_str().unwrap();
        let r = prompt::read(e["prompt"].as_str().unwrap());
        check(id, &r, e, &mut s);
    }
    // Their first run (before any fix they prompted) scored objects 91.5%, counts 98.1%,
    // relations 80.8%, rooms 96%: that is the honest estimate; these floors guard the fixes.
    report("reader accuracy on held-out prompts", &s);
    assert!(
        pct(s.found, s.objects) >= 97.0,
        "objects {}/{}",
        s.found,
        s.objects
    );
    assert!(
        pct(s.counts, s.found) >= 97.0,
        "counts {}/{}",
        s.counts,
        s.found
    );
    assert!(
        pct(s.relations_right, s.relations) >= 95.0,
        "relations {}/{}",
        s.relations_right,
        s.relations
    );
    assert_eq!(s.rooms_right, s.prompts, "room structure");
}

#[test]
fn reader_table_on_second_held_out_set() {
    let exp: Value = serde_json::from_str(
        &std::fs::read_to_string("tests/fixtures/reader_heldout2.json").unwrap(),
    )
    .unwrap();
    let mut s = Score::default();
    for e in exp["prompts"].as_array().unwrap() {
        let id = e["id"].as_str().unwrap();
        let r = prompt::read(e["prompt"].as_str().unwrap());
        check(id, &r, e, &mut s);
    }
    // First run (before any fix it prompted): objects 85.7%, counts 96.7%, relations 75.6%,
    // rooms 86.7% — the honest estimate after the first held-out round.
    report("reader accuracy on the second held-out set", &s);
    assert!(
        pct(s.found, s.objects) >= 97.0,
        "objects {}/{}",
        s.found,
        s.objects
    );
    assert!(
        pct(s.counts, s.found) >= 95.0,
        "counts {}/{}",
        s.counts,
        s.found
    );
    assert!(
        pct(s.relations_right, s.relations) >= 88.0,
        "relations {}/{}",
        s.relations_right,
        s.relations
    );
    assert_eq!(s.rooms_right, s.prompts, "room structure");
}

/// Refusing prompts it cannot read must not refuse English ones: every dev prompt is
/// understood (a room word or an object noun grounded, English function words present).
#[test]
fn every_dev_prompt_is_understood() {
    let (prompts, _) = fixtures();
    for (id, text) in &prompts {
        let r = prompt::read(text);
        assert!(r.understood(), "{id}: {}", r.understanding());
    }
}
