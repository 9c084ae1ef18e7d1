//! What each subcommand does with its parsed options: one `run_*` per subcommand, returning
//! its exit code or an error (a [`super::args::UsageError`] for exit code 2).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use serde_json::json;

use super::args::{ContactArg, StageArg, usage};
use scenesmith::export::ExportSet;
use scenesmith::physics::protocol::{NoArgs, Versions};
use scenesmith::physics::{self, Bridge};
use scenesmith::pipeline::{self, GenerateOptions, PipelineError};

/// `r`'s value, or its error: a usage error (exit code 2) when `is_usage` says so.
fn or_usage<T, E>(r: Result<T, E>, is_usage: impl Fn(&E) -> bool) -> anyhow::Result<T>
where
    E: std::error::Error + Send + Sync + 'static,
{
    r.map_err(|e| if is_usage(&e) { usage(e) } else { e.into() })
}

pub(crate) fn print_json(v: &serde_json::Value) -> anyhow::Result<()> {
    println!("{}", serde_json::to_string_pretty(v)?);
    Ok(())
}

pub(crate) fn run_generate(cli_json: bool, opts: GenerateOptions) -> anyhow::Result<ExitCode> {
    eprintln!(
        "scenesmith: generating {:?} -> {}",
        opts.prompt,
        opts.out.display()
    );
    let summary = match pipeline::generate(&opts) {
        Ok(s) => s,
        Err(
            e @ (PipelineError::EmptyPrompt
            | PipelineError::UnusablePrompt(_)
            | PipelineError::NotUnderstood(_)),
        ) => {
            return Err(usage(e));
        }
        Err(e) => {
            return Err(e).context("generate failed; the output directory was left as it was");
        }
    };
    if cli_json {
        print_json(&serde_json::to_value(&summary)?)?;
    } else {
        eprintln!("wrote {}", summary.out.display());
        if let Some(kept) = &summary.kept_previous {
            eprintln!(
                "  the directory it replaced held files scenesmith did not write: kept as {}",
                kept.display()
            );
        }
        for (id, ty) in &summary.rooms {
            eprintln!("  room {id} ({ty})");
        }
        let cats: Vec<String> = summary
            .objects_per_category
            .iter()
            .map(|(c, n)| format!("{n} {c}"))
            .collect();
        eprintln!("  objects: {}", cats.join(", "));
        for (noun, planned, present) in &summary.plan_coverage {
            if present < planned {
                eprintln!("  note: the plan has {planned} {noun}, placed {present}");
            }
        }
        for noun in &summary.unknown_nouns {
            eprintln!(
                "  note: no asset generator knows {noun:?}; a generic stand-in shape carries its name"
            );
        }
        for line in scenesmith::prompt::report::summary_lines(&summary.nouns) {
            eprintln!("  {line}");
        }
        for n in &summary.notes {
            eprintln!("  note: {n}");
        }
        for st in &summary.stages {
            if let Some(c) = &st.critique {
                let scores: Vec<String> = c
                    .scores
                    .iter()
                    .map(|s| format!("{} {}", s.category, s.score))
                    .collect();
                eprintln!(
                    "  {} {}{}: {}",
                    st.stage,
                    st.room,
                    st.entity
                        .as_ref()
                        .map(|e| format!("/{e}"))
                        .unwrap_or_default(),
                    scores.join(", ")
                );
            }
        }
        let pp = &summary.post_process;
        let removed: Vec<&String> = pp
            .furniture
            .removed
            .iter()
            .chain(&pp.manipuland.removed)
            .chain(&pp.removed_penetrating)
            .collect();
        if !removed.is_empty() {
            eprintln!(
                "  post-processing removed {} objects (reasons in scene.json)",
                removed.len()
            );
        }
        eprint!("{}", scenesmith::eval::table(&summary.metrics));
        if let Some(c) = &summary.check {
            eprintln!(
                "  drake {}: {} model instances, {} free bodies, COL {:.2}% (max depth {:.2} mm)",
                c.drake,
                c.model_instances,
                c.free_bodies,
                c.col_percent,
                c.max_depth_m * 1e3
            );
        }
        let t: Vec<String> = summary
            .timings
            .iter()
            .map(|(k, v)| format!("{k} {v:.2}s"))
            .collect();
        eprintln!("  time: {}", t.join(", "));
    }
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn run_check(
    cli_json: bool,
    dir: PathBuf,
    threshold: f64,
    max_col: f64,
) -> anyhow::Result<ExitCode> {
    let mut bridge = Bridge::from_env()?;
    let t0 = std::time::Instant::now();
    let summary = physics::check_dir(&mut bridge, &dir, threshold)
        .with_context(|| format!("checking {}", dir.display()))?;
    let passed = summary.passed(max_col);
    if cli_json {
        let mut v = serde_json::to_value(&summary)?;
        v["passed"] = json!(passed);
        v["seconds"] = json!(t0.elapsed().as_secs_f64());
        print_json(&v)?;
    } else {
        eprintln!("check {} with drake {}", dir.display(), summary.drake);
        eprintln!(
            "  model instances {} (scene objects {}), bodies {}, free bodies {}",
            summary.model_instances, summary.scene_objects, summary.bodies, summary.free_bodies
        );
        eprintln!(
            "  COL {:.2}% of {} objects (> {:.1} mm), mean depth {:.2} mm, max {:.2} mm",
            summary.col_percent,
            summary.col_objects,
            summary.threshold_m * 1e3,
            summary.mean_depth_m * 1e3,
            summary.max_depth_m * 1e3
        );
        for (a, b, d) in &summary.pairs {
            eprintln!("  penetrating: {a} / {b}: {:.2} mm", d * 1e3);
        }
        for p in &summary.problems {
            eprintln!("  problem: {p}");
        }
        eprintln!(
            "  {} in {:.2}s",
            if passed { "PASS" } else { "FAIL" },
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

pub(crate) fn run_render(
    cli_json: bool,
    dir: PathBuf,
    out: Option<PathBuf>,
) -> anyhow::Result<ExitCode> {
    let t0 = std::time::Instant::now();
    let out = out.unwrap_or_else(|| dir.join("renders"));
    let files = scenesmith::render::render_scene_dir(&dir, Some(&out))
        .with_context(|| format!("rendering {} into {}", dir.display(), out.display()))?;
    if cli_json {
        print_json(&json!({ "files": files, "seconds": t0.elapsed().as_secs_f64() }))?;
    } else {
        for f in &files {
            eprintln!("wrote {}", f.display());
        }
        eprintln!(
            "  {} images in {:.2}s",
            files.len(),
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn run_eval(
    cli_json: bool,
    dir: PathBuf,
    robot_radius: f64,
    no_stb: bool,
    contact: ContactArg,
    full_stb: bool,
) -> anyhow::Result<ExitCode> {
    use scenesmith::eval::{self, EvalOptions, StabilityOptions};
    use scenesmith::physics::settle::ContactModel;
    let stb_contacts = match contact {
        ContactArg::AsWritten => vec![ContactModel::AsWritten],
        ContactArg::Point => vec![ContactModel::Point],
        ContactArg::Both => vec![ContactModel::AsWritten, ContactModel::Point],
    };
    let opts = EvalOptions {
        robot_radius_m: robot_radius,
        stability: (!no_stb).then(|| StabilityOptions {
            stop_at_rest: !full_stb,
            ..StabilityOptions::default()
        }),
        stb_contacts,
        ..EvalOptions::default()
    };
    let pool = (!no_stb).then(scenesmith::physics::BridgePool::from_env);
    let metrics = eval::evaluate_dir(&dir, pool.as_ref(), &opts)
        .with_context(|| format!("evaluating {}", dir.display()))?;
    eval::write_metrics(&dir, &metrics)?;
    if cli_json {
        print_json(&serde_json::to_value(&metrics)?)?;
    } else {
        eprintln!("metrics of {} (written to metrics.json)", dir.display());
        eprint!("{}", eval::table(&metrics));
    }
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn run_requirements(
    cli_json: bool,
    dir: PathBuf,
    file: PathBuf,
) -> anyhow::Result<ExitCode> {
    use scenesmith::eval::requirements::{
        REQUIREMENTS_REPORT_JSON, parse_requirements, score, table, write_report,
    };
    let reqs = match std::fs::read_to_string(&file)
        .map_err(|e| e.to_string())
        .and_then(|text| parse_requirements(&text).map_err(|e| e.to_string()))
    {
        Ok(r) => r,
        Err(e) => {
            return Err(usage(format!("requirements file {}: {e}", file.display())));
        }
    };
    let scene = scenesmith::formats::scene_dir::read_scene(&dir)
        .with_context(|| format!("reading the scene in {}", dir.display()))?;
    let report = score(&scene, &reqs);
    write_report(&dir, &report)
        .with_context(|| format!("writing {REQUIREMENTS_REPORT_JSON} in {}", dir.display()))?;
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        eprintln!(
            "requirements of {} from {} (written to {REQUIREMENTS_REPORT_JSON})",
            dir.display(),
            file.display()
        );
        eprint!("{}", table(&report));
    }
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn run_export(
    cli_json: bool,
    dir: PathBuf,
    set: ExportSet,
    check: bool,
    no_write: bool,
    seconds: f64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::export::{self, conformance};
    let state = scenesmith::formats::scene_dir::load_state(&dir)
        .with_context(|| format!("reading the scene in {}", dir.display()))?;
    let mut out = json!({ "dir": dir });
    if !no_write {
        let written = export::write_exports(&dir, &state, &set)
            .with_context(|| format!("exporting {}", dir.display()))?;
        for w in &written {
            if !cli_json {
                eprintln!(
                    "wrote {} ({} files, {:.1} kB)",
                    dir.join(&w.main_file).display(),
                    w.files,
                    w.bytes as f64 / 1e3
                );
            }
        }
        out["written"] = serde_json::to_value(&written)?;
    }
    let mut passed = true;
    if check {
        let mut bridge = Bridge::from_env()?;
        let opts = conformance::GateOptions {
            seconds,
            formats: set,
        };
        let report = conformance::run_gate(&mut bridge, &dir, &state, &opts)
            .with_context(|| format!("checking the exports of {}", dir.display()))?;
        passed = report.passed;
        if cli_json {
            out["check"] = serde_json::to_value(&report)?;
        } else {
            eprint!("{}", conformance::table(&report));
            if let Some(s) = &report.mujoco_stability {
                for (id, d, a) in &s.moved {
                    eprintln!("  moved in MuJoCo: {id}: {:.1} mm, {:.3} rad", d * 1e3, a);
                }
            }
            eprintln!("  {}", if passed { "PASS" } else { "FAIL" });
        }
    }
    if cli_json {
        out["passed"] = json!(passed);
        print_json(&out)?;
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

pub(crate) fn run_layout(
    cli_json: bool,
    prompt: &str,
    seed: u64,
    png: Option<PathBuf>,
) -> anyhow::Result<ExitCode> {
    use scenesmith::layout;
    if let Err(e) = pipeline::validate_prompt(prompt) {
        return Err(usage(e));
    }
    let mut log = scenesmith::agents::RunLog::default();
    let out = layout::stage::run_layout(
        prompt,
        seed,
        &scenesmith::agents::Backend::Builtin,
        &mut log,
    )?;
    if let Some(path) = &png {
        let bytes = scenesmith::render::plan_png(prompt, seed, &out.rooms)?;
        scenesmith::util::fsx::write_atomic(path, &bytes)?;
        eprintln!("wrote {}", path.display());
    }
    if cli_json {
        let obs = layout::tools::observe(&out.state).map_err(|e| anyhow::anyhow!(e.message))?;
        let mut v = serde_json::to_value(&obs)?;
        v["validation"] = serde_json::to_value(&out.validation)?;
        v["critique"] = serde_json::to_value(&out.summary.critique)?;
        print_json(&v)?;
    } else {
        print!("{}", layout::ascii::render(&out.rooms));
        for e in &out.validation.errors {
            eprintln!("  error: {e}");
        }
        for w in &out.validation.warnings {
            eprintln!("  warning: {w}");
        }
        let s = &out.state.stats;
        eprintln!(
            "  {} rooms, compactness {:.2}, search {} nodes in {:.2}s{}{}",
            out.rooms.len(),
            s.compactness,
            s.nodes,
            s.seconds,
            if s.relaxed { ", relaxed" } else { "" },
            if s.timed_out { ", timed out" } else { "" }
        );
    }
    Ok(if out.validation.ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

pub(crate) fn run_doctor(cli_json: bool) -> anyhow::Result<ExitCode> {
    let config = scenesmith::physics::BridgeConfig::from_env();
    let (home, python) = (config.home.clone(), config.python.clone());
    let versions = Bridge::start(config).and_then(|mut b| b.call::<Versions>(&NoArgs {}));
    let ok = versions.is_ok();
    if cli_json {
        let mut report = json!({
            "scenesmith": env!("CARGO_PKG_VERSION"),
            "home": home,
            "python": python,
        });
        match &versions {
            Ok(v) => report["bridge"] = serde_json::to_value(v)?,
            Err(e) => report["bridge_error"] = json!(e.to_string()),
        }
        print_json(&report)?;
    } else {
        eprintln!("scenesmith {}", env!("CARGO_PKG_VERSION"));
        eprintln!("  home:    {}", home.display());
        eprintln!("  python:  {}", python.display());
        match &versions {
            Ok(b) => {
                let missing = |v: &Option<String>| v.clone().unwrap_or_else(|| "missing".into());
                eprintln!("  Python {}", b.python);
                eprintln!("  drake {}", b.drake);
                eprintln!(
                    "  SNOPT available {} enabled {}; IPOPT available {}",
                    b.snopt.available, b.snopt.enabled, b.ipopt.available
                );
                eprintln!("  numpy {}", missing(&b.numpy));
                eprintln!("  mujoco {}", missing(&b.mujoco));
                eprintln!("  usd-core {}", missing(&b.usd_core));
            }
            Err(e) => eprintln!("  bridge: {e}"),
        }
    }
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

pub(crate) fn run_asset(
    cli_json: bool,
    description: String,
    out: PathBuf,
    stage: Option<StageArg>,
    size: Option<[f64; 3]>,
    seed: u64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::assets::router;
    use scenesmith::pipeline::asset as command;
    let opts = command::AssetOptions {
        description,
        out,
        stage: stage.map(Into::into),
        size,
        seed,
    };
    let ctx = router::RouterContext::from_env();
    let preview = |asset: &scenesmith::assets::Asset| {
        scenesmith::render::asset_preview(asset, 480, 360)
            .and_then(|image| image.encode_png())
            .ok()
    };
    let report = or_usage(command::make_asset(&opts, &ctx, Some(&preview)), |e| {
        matches!(e, command::AssetCommandError::Route(_))
    })?;
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        for a in &report.assets {
            eprintln!(
                "wrote {} ({} x{}, {:?}, {:.2} x {:.2} x {:.2} m, {:.2} kg, {} hulls{})",
                a.dir.display(),
                a.category,
                a.count,
                a.strategy,
                a.size_m[0],
                a.size_m[1],
                a.size_m[2],
                a.mass_kg,
                a.collision_pieces,
                if a.joints.is_empty() {
                    String::new()
                } else {
                    format!(", joints {}", a.joints.join(" "))
                }
            );
        }
        for n in &report.notes {
            eprintln!("  note: {n}");
        }
    }
    Ok(ExitCode::SUCCESS)
}

pub(crate) fn run_gallery(
    cli_json: bool,
    out: PathBuf,
    only: Option<String>,
    columns: usize,
    seed: u64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::render::gallery::{GalleryError, GalleryOptions, write_gallery};
    let mut opts = GalleryOptions::new(out);
    opts.filter = only;
    opts.columns = columns.max(1);
    opts.seed = seed;
    let report = or_usage(write_gallery(&opts), |e| {
        matches!(e, GalleryError::NothingMatches(_))
    })?;
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        for sheet in &report.sheets {
            eprintln!("wrote {}", sheet.display());
        }
        eprintln!("{} categories", report.entries.len());
        for (category, reason) in &report.failed {
            eprintln!("  failed: {category}: {reason}");
        }
    }
    Ok(if report.failed.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
