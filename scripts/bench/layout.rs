//! Layout benchmark (`scripts/bench_layout`): placement search time for houses of 1, 5, 10
//! and 15 rooms and for every house prompt of the dev set, with compactness and the number of
//! rooms reached only through another room that is not a corridor (or the entrance).

use std::time::Instant;

use scenesmith::agents::Backend;
use scenesmith::agents::RunLog;
use scenesmith::layout::search::{SearchConfig, place};
use scenesmith::layout::stage::run_layout;
use scenesmith::layout::state::LayoutState;
use scenesmith::layout::{brief, spec};

const SIZED: [(&str, &str); 4] = [
    ("1 room", "A kitchen with a table and four chairs."),
    (
        "5 rooms",
        "A small restaurant with a dining area, a kitchen, a bar, a storage room, and a bathroom.",
    ),
    (
        "10 rooms",
        "A family home with a hallway, a living room, a kitchen, a dining room, a master bedroom, \
         two kids bedrooms, a study, and two bathrooms.",
    ),
    (
        "15 rooms",
        "A boutique hotel with a reception, a corridor, four guest bedrooms with en-suite \
         bathrooms, a restaurant, a kitchen, a bar, a lounge, and a gym.",
    ),
];

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn row(label: &str, prompt: &str) {
    let b = brief::read(prompt);
    let hs = spec::house_spec(&b);
    let cfg = SearchConfig::default();
    let mut times = Vec::new();
    let mut stats = None;
    for _ in 0..3 {
        let t0 = Instant::now();
        let (_, s) = place(&hs, None, &cfg);
        times.push(t0.elapsed().as_secs_f64());
        stats = Some(s);
    }
    let Some(stats) = stats else { return };
    let t0 = Instant::now();
    let out = run_layout(prompt, 0, &Backend::Builtin, &mut RunLog::default());
    let stage_s = t0.elapsed().as_secs_f64();
    let (valid, via, flow) = match &out {
        Ok(o) => (
            o.validation.ok,
            o.validation.only_through_room.len(),
            o.summary
                .critique
                .as_ref()
                .and_then(|c| c.score("spatial_flow"))
                .unwrap_or(0),
        ),
        Err(_) => (false, 0, 0),
    };
    let state = LayoutState::from_prompt(prompt, 0);
    println!(
        "| {label} | {} | {:.1} | {:.1} | {} | {} | {:.2} | {} | {} | {} | {} |",
        hs.rooms.len(),
        1e3 * median(times),
        1e3 * stage_s,
        stats.nodes,
        stats.leaves,
        state.placement.compactness(),
        via,
        flow,
        if stats.relaxed { "yes" } else { "no" },
        if valid { "yes" } else { "NO" },
    );
}

fn main() {
    println!(
        "| house | rooms | search ms (median of 3) | stage ms | nodes | layouts scored | compactness | rooms only through another room | flow score | relaxed | valid |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (label, prompt) in SIZED {
        row(label, prompt);
    }
    let dev = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/dev_prompts.jsonl"
    ))
    .unwrap_or_default();
    for line in dev.lines() {
        let Ok(v) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        if v["category"] == "house" {
            row(
                v["id"].as_str().unwrap_or_default(),
                v["prompt"].as_str().unwrap_or_default(),
            );
        }
    }
}
