//! Runs the layout stage through the agent loop (built-in or LLM backend); installing its rooms
//! in a scene is [`crate::state::install_rooms`].

use super::builtin::{BuiltinLayoutCritic, BuiltinLayoutDesigner};
use super::state::LayoutState;
use super::tools;
use super::validate::Validation;
use crate::agents::llm::{LlmCritic, LlmDesigner, LlmOrchestrator};
use crate::agents::{
    AgentError, Backend, BuiltinOrchestrator, Critic, Designer, Orchestrator, RunLog, StageConfig,
    StageSpec, StageSummary, run_stage,
};
use crate::scene::Room;

/// What the layout stage produced.
#[derive(Debug, Clone)]
pub struct LayoutOutcome {
    /// The kept state.
    pub state: LayoutState,
    /// The rooms with walls, openings, materials and per-room prompts.
    pub rooms: Vec<Room>,
    /// Validation of the kept layout.
    pub validation: Validation,
    /// The stage's scores.
    pub summary: StageSummary,
}

type Agents = (
    Box<dyn Designer<LayoutState>>,
    Box<dyn Critic<LayoutState>>,
    Box<dyn Orchestrator>,
);

fn brief(state: &LayoutState) -> String {
    let rooms: Vec<String> = state.brief.rooms.iter().map(|r| r.label.clone()).collect();
    format!(
        "Prompt: \"{}\". Rooms the prompt names: {}. An initial layout was generated from the \
         prompt; inspect it (observe_scene, render_ascii, validate) and improve it, or call \
         generate_room_specs to start over.",
        state.prompt,
        if rooms.is_empty() {
            "none recognised".to_string()
        } else {
            rooms.join(", ")
        }
    )
}

/// Runs the layout stage for `prompt` and returns the kept layout.
pub fn run_layout(
    prompt: &str,
    seed: u64,
    backend: &Backend,
    log: &mut RunLog,
) -> Result<LayoutOutcome, AgentError> {
    let t0 = std::time::Instant::now();
    let initial = LayoutState::from_prompt(prompt, seed);
    let text = brief(&initial);
    let toolbox = tools::toolbox();
    let categories = tools::categories();
    let (mut designer, mut critic, mut orchestrator): Agents = match backend {
        Backend::Builtin => (
            Box::new(BuiltinLayoutDesigner),
            Box::new(BuiltinLayoutCritic),
            Box::new(BuiltinOrchestrator::default()),
        ),
        Backend::Llm { transport, config } => {
            let mut orch = LlmOrchestrator::new(transport.clone(), config.clone());
            orch.set_stage("layout", &text);
            (
                Box::new(LlmDesigner::new(transport.clone(), config.clone())),
                Box::new(LlmCritic::new(transport.clone(), config.clone())),
                Box::new(orch),
            )
        }
    };
    let spec = StageSpec {
        name: "layout",
        categories: &categories,
        toolbox: &toolbox,
        brief: &text,
    };
    let config = StageConfig {
        max_rounds: 3,
        early_finish_min_score: 8,
        ..StageConfig::default()
    };
    let outcome = run_stage(
        &spec,
        initial,
        designer.as_mut(),
        critic.as_mut(),
        orchestrator.as_mut(),
        &config,
        log,
    )?;
    let mut state = outcome.state;
    if state.spec.is_none() {
        // A designer that threw the layout away without making a new one: start from the
        // prompt again rather than build an empty house.
        tracing::warn!("the layout designer left no rooms; using the layout read from the prompt");
        state = LayoutState::from_prompt(prompt, seed);
    }
    let (rooms, _) = state.rooms();
    let validation = state.validation();
    if !validation.ok {
        tracing::warn!("layout problems: {}", validation.errors.join("; "));
    }
    Ok(LayoutOutcome {
        rooms,
        validation,
        summary: StageSummary {
            stage: "layout".into(),
            room: "house".into(),
            entity: None,
            critique: outcome.critique,
            rounds: outcome.history.len(),
            seconds: t0.elapsed().as_secs_f64(),
        },
        state,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_stage_lays_out_a_valid_house() {
        let mut log = RunLog::default();
        let out = run_layout(
            "A small office suite with a reception, a private office, and a bathroom.",
            4,
            &Backend::Builtin,
            &mut log,
        )
        .unwrap();
        assert!(out.validation.ok, "{:?}", out.validation);
        assert_eq!(out.rooms.len(), 3);
        let c = out.summary.critique.unwrap();
        assert_eq!(c.scores.len(), 5);
        assert!(c.min_score() >= 7, "{}", c.summary());
        assert!(log.calls("layout", crate::agents::Role::Critic).count() >= 2);
    }
}
