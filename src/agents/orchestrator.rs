//! The stage loop: an orchestrator drives a designer and a critic through control decisions;
//! every critique becomes a checkpoint; a regression rolls back; the stage keeps its best
//! checkpoint.

use std::ops::ControlFlow;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::json;

use super::backend::{
    AgentCx, AgentError, Critic, DesignRequest, Designer, LogEvent, PlacementStyle, RunLog,
};
use super::critique::{CategorySpec, Critique};
use super::tool::Toolbox;

/// Per-stage loop settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageConfig {
    /// Most critique rounds before the stage ends.
    pub max_rounds: usize,
    /// The stage ends early when every category scores at least this.
    pub early_finish_min_score: u8,
    /// Roll back when any category drops by this much or more.
    pub rollback_category_drop: u8,
    /// Roll back when the sum of scores drops by this much or more.
    pub rollback_sum_drop: u32,
    /// Hard cap on orchestrator decisions (guards a confused orchestrator).
    pub max_decisions: usize,
}

impl Default for StageConfig {
    fn default() -> Self {
        StageConfig {
            max_rounds: 3,
            early_finish_min_score: 8,
            rollback_category_drop: 2,
            rollback_sum_drop: 1,
            max_decisions: 24,
        }
    }
}

/// The orchestrator's control actions (its tools).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "tool", content = "args", rename_all = "snake_case")]
pub enum Decision {
    /// Ask the designer for the first design.
    RequestInitialDesign {},
    /// Ask the designer to change the current design.
    RequestDesignChange {
        /// What to change, concretely.
        instruction: String,
    },
    /// Ask the critic to score the current design (this records a checkpoint).
    RequestCritique {},
    /// Restore an earlier checkpoint.
    ResetSceneToCheckpoint {
        /// Why.
        reason: String,
        /// Checkpoint index; the previous one when omitted.
        #[serde(default)]
        checkpoint: Option<usize>,
    },
    /// Choose how precisely the designer aligns objects.
    SelectPlacementStyle {
        /// `natural` or `perfect`.
        style: PlacementStyle,
    },
    /// End the stage (the best checkpoint is kept).
    Finish {
        /// Why.
        reason: String,
    },
}

/// A saved state with its critique.
#[derive(Debug, Clone)]
pub struct Checkpoint<S> {
    /// The full stage state.
    pub state: S,
    /// Its critique.
    pub critique: Critique,
    /// The critique of the checkpoint it was derived from.
    pub previous: Option<Critique>,
    /// Rolled back from: a category or the sum dropped against `previous`. Never kept, even
    /// when its total is the highest (a gain in one category does not buy a loss in another).
    pub regressed: bool,
}

/// What the orchestrator sees when deciding.
#[derive(Debug, Clone, Serialize)]
pub struct LoopView {
    /// Stage name.
    pub stage: String,
    /// Whether a design exists.
    pub has_design: bool,
    /// Whether the design changed since the last critique.
    pub changed_since_critique: bool,
    /// Critique rounds so far.
    pub rounds: usize,
    /// The latest critique.
    pub last: Option<Critique>,
    /// The critique of the checkpoint the current state derives from.
    pub baseline: Option<Critique>,
    /// Set right after a rollback: why.
    pub rolled_back: Option<String>,
    /// Current placement style.
    pub style: PlacementStyle,
    /// Loop settings.
    pub config: StageConfig,
    /// Number of checkpoints.
    pub checkpoints: usize,
}

/// Decides the next control action.
pub trait Orchestrator {
    /// The next decision; an `Err` ends the stage with the best checkpoint so far.
    fn decide(&mut self, view: &LoopView) -> Result<Decision, AgentError>;
    /// Told when a decision could not be carried out, so an LLM can correct itself.
    fn rejected(&mut self, _decision: &Decision, _why: &str) {}
    /// Forgets everything (between stages).
    fn reset(&mut self) {}
}

/// The built-in orchestrator: design, critique, improve the weakest points until the scores
/// are good enough or the rounds run out.
#[derive(Debug, Clone, Default)]
pub struct BuiltinOrchestrator {
    /// Style to select at the start, if any.
    pub style: Option<PlacementStyle>,
    style_sent: bool,
}

impl BuiltinOrchestrator {
    /// An orchestrator that selects `style` before the first design.
    pub fn with_style(style: PlacementStyle) -> Self {
        BuiltinOrchestrator {
            style: Some(style),
            style_sent: false,
        }
    }
}

impl Orchestrator for BuiltinOrchestrator {
    fn decide(&mut self, v: &LoopView) -> Result<Decision, AgentError> {
        if let Some(style) = self.style
            && !self.style_sent
        {
            self.style_sent = true;
            return Ok(Decision::SelectPlacementStyle { style });
        }
        if !v.has_design {
            return Ok(Decision::RequestInitialDesign {});
        }
        if v.changed_since_critique {
            return Ok(Decision::RequestCritique {});
        }
        let Some(last) = &v.last else {
            return Ok(Decision::RequestCritique {});
        };
        if last.min_score() >= v.config.early_finish_min_score {
            return Ok(Decision::Finish {
                reason: format!(
                    "every category scores at least {}",
                    v.config.early_finish_min_score
                ),
            });
        }
        if v.rounds >= v.config.max_rounds {
            return Ok(Decision::Finish {
                reason: format!("{} critique rounds done", v.rounds),
            });
        }
        // Ask for the weakest categories and the concrete issues, worst first.
        let basis = v.baseline.as_ref().unwrap_or(last);
        let mut weak: Vec<_> = basis.scores.iter().filter(|s| s.score < 10).collect();
        weak.sort_by_key(|s| s.score);
        let mut parts: Vec<String> = weak
            .iter()
            .take(3)
            .map(|s| format!("improve {} ({}/10: {})", s.category, s.score, s.reason))
            .collect();
        parts.extend(basis.issues.iter().take(6).map(|i| i.description.clone()));
        Ok(Decision::RequestDesignChange {
            instruction: parts.join("; "),
        })
    }

    fn reset(&mut self) {
        self.style_sent = false;
    }
}

/// What a stage produced.
#[derive(Debug, Clone)]
pub struct StageOutcome<S> {
    /// The kept state: the best checkpoint, or the current state if nothing was critiqued.
    pub state: S,
    /// Its critique.
    pub critique: Option<Critique>,
    /// All critiques in order.
    pub history: Vec<Critique>,
    /// Index of the kept checkpoint.
    pub kept: Option<usize>,
}

/// One stage: its name, categories, tools and the text brief the agents get.
pub struct StageSpec<'a, S> {
    /// Name (`layout`, `furniture`, ...).
    pub name: &'a str,
    /// Critic categories.
    pub categories: &'a [CategorySpec],
    /// Tools.
    pub toolbox: &'a Toolbox<S>,
    /// Task description for the agents.
    pub brief: &'a str,
}

/// Runs one stage to the end and returns its best checkpoint.
pub fn run_stage<S: Clone>(
    spec: &StageSpec<'_, S>,
    initial: S,
    designer: &mut dyn Designer<S>,
    critic: &mut dyn Critic<S>,
    orchestrator: &mut dyn Orchestrator,
    config: &StageConfig,
    log: &mut RunLog,
) -> Result<StageOutcome<S>, AgentError> {
    designer.reset();
    critic.reset();
    orchestrator.reset();
    let mut agents = Agents {
        designer,
        critic,
        orchestrator,
    };
    let mut run = StageLoop::new(spec.name, initial);
    for _ in 0..config.max_decisions {
        let decision = match agents.orchestrator.decide(&run.view(config)) {
            Ok(d) => d,
            Err(e) if !run.checkpoints.is_empty() => {
                tracing::warn!(
                    "orchestrator of {} failed ({e}); keeping the best checkpoint",
                    run.stage
                );
                break;
            }
            Err(e) => return Err(e),
        };
        log.events.push(LogEvent::Decision {
            stage: run.stage.clone(),
            decision: serde_json::to_value(&decision).unwrap_or(json!(null)),
        });
        let mut cx = AgentCx {
            stage: spec.name,
            toolbox: spec.toolbox,
            categories: spec.categories,
            brief: spec.brief,
            style: run.style,
            attempt: run.attempt,
            log,
        };
        if run
            .apply(decision, &mut agents, &mut cx, config)?
            .is_break()
        {
            break;
        }
    }
    Ok(run.finish(log))
}

/// The three agents of a stage.
struct Agents<'a, S> {
    designer: &'a mut dyn Designer<S>,
    critic: &'a mut dyn Critic<S>,
    orchestrator: &'a mut dyn Orchestrator,
}

/// The stage loop between decisions: the working state and the checkpoints taken so far.
struct StageLoop<S> {
    stage: String,
    current: S,
    checkpoints: Vec<Checkpoint<S>>,
    /// The checkpoint `current` derives from: critiques are judged against it.
    baseline: Option<usize>,
    has_design: bool,
    changed: bool,
    /// Set by a rollback until the next design change, which is told why.
    rolled_back: Option<String>,
    style: PlacementStyle,
    attempt: u32,
}

impl<S: Clone> StageLoop<S> {
    fn new(stage: &str, initial: S) -> Self {
        StageLoop {
            stage: stage.to_string(),
            current: initial,
            checkpoints: Vec::new(),
            baseline: None,
            has_design: false,
            changed: false,
            rolled_back: None,
            style: PlacementStyle::default(),
            attempt: 0,
        }
    }

    fn view(&self, config: &StageConfig) -> LoopView {
        LoopView {
            stage: self.stage.clone(),
            has_design: self.has_design,
            changed_since_critique: self.changed,
            rounds: self.checkpoints.len(),
            last: self.checkpoints.last().map(|c| c.critique.clone()),
            baseline: self.baseline.map(|i| self.checkpoints[i].critique.clone()),
            rolled_back: self.rolled_back.clone(),
            style: self.style,
            config: config.clone(),
            checkpoints: self.checkpoints.len(),
        }
    }

    /// Carries out one decision, or tells the orchestrator why it cannot; breaks on `Finish`.
    fn apply(
        &mut self,
        decision: Decision,
        agents: &mut Agents<'_, S>,
        cx: &mut AgentCx<'_, S>,
        config: &StageConfig,
    ) -> Result<ControlFlow<()>, AgentError> {
        match decision {
            Decision::RequestInitialDesign {} if self.has_design => {
                agents.orchestrator.rejected(
                    &decision,
                    "a design exists; request a design change instead",
                );
            }
            Decision::RequestInitialDesign {} => {
                self.design(agents.designer, &DesignRequest::Initial, cx)?;
            }
            Decision::RequestDesignChange { .. } if !self.has_design => {
                agents.orchestrator.rejected(
                    &decision,
                    "there is no design yet; request the initial design",
                );
            }
            Decision::RequestDesignChange { instruction } => {
                let request = match self.rolled_back.take() {
                    Some(reason) => DesignRequest::AfterRollback {
                        reason,
                        instruction,
                    },
                    None => DesignRequest::Change { instruction },
                };
                self.design(agents.designer, &request, cx)?;
            }
            Decision::RequestCritique {} if !self.has_design => {
                agents
                    .orchestrator
                    .rejected(&decision, "there is no design to critique yet");
            }
            Decision::RequestCritique {} => self.critique(agents.critic, cx, config)?,
            Decision::ResetSceneToCheckpoint { reason, checkpoint } => {
                self.reset_to(reason, checkpoint, agents.orchestrator, cx.log);
            }
            Decision::SelectPlacementStyle { style } => self.style = style,
            Decision::Finish { .. } => return Ok(ControlFlow::Break(())),
        }
        Ok(ControlFlow::Continue(()))
    }

    fn design(
        &mut self,
        designer: &mut dyn Designer<S>,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, S>,
    ) -> Result<(), AgentError> {
        designer.design(&mut self.current, request, cx)?;
        self.has_design = true;
        self.changed = true;
        self.attempt += 1;
        Ok(())
    }

    /// Critiques the current state into a new checkpoint; rolls back to the baseline when the
    /// critique regressed from it, else makes it the baseline.
    fn critique(
        &mut self,
        critic: &mut dyn Critic<S>,
        cx: &mut AgentCx<'_, S>,
        config: &StageConfig,
    ) -> Result<(), AgentError> {
        let critique = critic.critique(&mut self.current, cx)?;
        let previous = self.baseline.map(|i| self.checkpoints[i].critique.clone());
        let index = self.checkpoints.len();
        cx.log.events.push(LogEvent::Checkpoint {
            stage: self.stage.clone(),
            index,
            total: critique.total(),
            critique: critique.clone(),
        });
        let regression = previous.as_ref().and_then(|p| {
            critique.regression_from(p, config.rollback_category_drop, config.rollback_sum_drop)
        });
        self.checkpoints.push(Checkpoint {
            state: self.current.clone(),
            critique: critique.clone(),
            previous: previous.clone(),
            regressed: regression.is_some() && self.baseline.is_some(),
        });
        self.changed = false;
        match (regression, self.baseline) {
            (Some(reason), Some(back)) => {
                self.current = self.checkpoints[back].state.clone();
                cx.log.events.push(LogEvent::Rollback {
                    stage: self.stage.clone(),
                    to: back,
                    reason: reason.clone(),
                });
                self.rolled_back = Some(reason);
            }
            _ => self.baseline = Some(index),
        }
        Ok(())
    }

    /// Restores `checkpoint` (the baseline when `None`) as the orchestrator asked.
    fn reset_to(
        &mut self,
        reason: String,
        checkpoint: Option<usize>,
        orchestrator: &mut dyn Orchestrator,
        log: &mut RunLog,
    ) {
        let target = checkpoint
            .or(self.baseline)
            .filter(|i| *i < self.checkpoints.len());
        match target {
            Some(i) => {
                self.current = self.checkpoints[i].state.clone();
                self.baseline = Some(i);
                self.changed = false;
                log.events.push(LogEvent::Rollback {
                    stage: self.stage.clone(),
                    to: i,
                    reason: reason.clone(),
                });
                self.rolled_back = Some(reason);
            }
            None => orchestrator.rejected(
                &Decision::ResetSceneToCheckpoint { reason, checkpoint },
                &format!("no such checkpoint; there are {}", self.checkpoints.len()),
            ),
        }
    }

    /// The kept result: the best critiqued checkpoint that was not rolled back from (latest on
    /// ties); a state that was never critiqued only when there is no checkpoint at all. The
    /// first checkpoint never regresses, so there is always a candidate.
    fn finish(mut self, log: &mut RunLog) -> StageOutcome<S> {
        let kept = self
            .checkpoints
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.regressed)
            .max_by_key(|(i, c)| (c.critique.total(), *i))
            .map(|(i, _)| i);
        log.events.push(LogEvent::StageEnd {
            stage: self.stage.clone(),
            kept,
            total: kept.map(|i| self.checkpoints[i].critique.total()),
            rounds: self.checkpoints.len(),
        });
        let history = self
            .checkpoints
            .iter()
            .map(|c| c.critique.clone())
            .collect();
        match kept {
            Some(i) => {
                let c = self.checkpoints.swap_remove(i);
                StageOutcome {
                    state: c.state,
                    critique: Some(c.critique),
                    history,
                    kept,
                }
            }
            None => StageOutcome {
                state: self.current,
                critique: None,
                history,
                kept: None,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::critique::Score;
    use crate::agents::tool::{Access, Role, ToolError};
    use schemars::JsonSchema;
    use serde::Deserialize;

    /// A toy stage: a number the designer moves, the critic likes 7.
    #[derive(Deserialize, JsonSchema)]
    struct SetArgs {
        value: i32,
    }
    #[derive(Deserialize, JsonSchema)]
    struct NoArgs {}
    #[derive(Serialize, JsonSchema)]
    struct Val {
        value: i32,
    }

    fn toolbox() -> Toolbox<i32> {
        let mut t = Toolbox::new();
        t.add(
            "set",
            "Set the value.",
            Access::Modify,
            |s: &mut i32, a: SetArgs| {
                *s = a.value;
                Ok(Val { value: *s })
            },
        );
        t.add(
            "get",
            "Read the value.",
            Access::Observe,
            |s: &mut i32, _: NoArgs| Ok::<_, ToolError>(Val { value: *s }),
        );
        t
    }

    /// Designs the values of a script, one per turn.
    struct Scripted(Vec<i32>, Vec<DesignRequest>);
    impl Designer<i32> for Scripted {
        fn design(
            &mut self,
            s: &mut i32,
            r: &DesignRequest,
            cx: &mut AgentCx<'_, i32>,
        ) -> Result<String, AgentError> {
            self.1.push(r.clone());
            let v = if self.0.is_empty() {
                *s
            } else {
                self.0.remove(0)
            };
            let _ = cx.call(s, Role::Designer, "set", json!({"value": v}));
            Ok(format!("set {v}"))
        }
    }
    struct Likes7;
    impl Critic<i32> for Likes7 {
        fn critique(
            &mut self,
            s: &mut i32,
            cx: &mut AgentCx<'_, i32>,
        ) -> Result<Critique, AgentError> {
            let v = cx.call(s, Role::Critic, "get", json!({})).unwrap()["value"]
                .as_i64()
                .unwrap() as i32;
            let score = (10 - (v - 7).abs()).clamp(0, 10) as u8;
            Ok(Critique {
                scores: vec![Score {
                    category: "closeness".into(),
                    score,
                    reason: format!("value {v}"),
                }],
                issues: vec![],
            })
        }
    }

    #[test]
    fn regression_rolls_back_and_best_checkpoint_is_kept() {
        let cats = [CategorySpec::new("closeness", "close to 7")];
        let tb = toolbox();
        let spec = StageSpec {
            name: "toy",
            categories: &cats,
            toolbox: &tb,
            brief: "",
        };
        // 3 (score 6) -> 5 (score 8: early finish at 9 not reached) -> 1 (score 4: rollback to 5)
        // -> 6 (score 9, finish).
        let mut designer = Scripted(vec![3, 5, 1, 6], vec![]);
        let config = StageConfig {
            max_rounds: 6,
            early_finish_min_score: 9,
            ..StageConfig::default()
        };
        let mut log = RunLog::default();
        let out = run_stage(
            &spec,
            0,
            &mut designer,
            &mut Likes7,
            &mut BuiltinOrchestrator::default(),
            &config,
            &mut log,
        )
        .unwrap();
        assert_eq!(out.state, 6);
        assert_eq!(out.critique.unwrap().total(), 9);
        let rollbacks: Vec<_> = log
            .events
            .iter()
            .filter(|e| matches!(e, LogEvent::Rollback { .. }))
            .collect();
        assert_eq!(rollbacks.len(), 1);
        // The designer was told about the rollback on its next turn.
        assert!(
            designer
                .1
                .iter()
                .any(|r| matches!(r, DesignRequest::AfterRollback { .. }))
        );
        // Every designer call went through the toolbox and is in the log.
        assert_eq!(log.calls("toy", Role::Designer).count(), 4);
    }

    #[test]
    fn never_keeps_a_degraded_state() {
        let cats = [CategorySpec::new("closeness", "close to 7")];
        let tb = toolbox();
        let spec = StageSpec {
            name: "toy",
            categories: &cats,
            toolbox: &tb,
            brief: "",
        };
        // 7 is perfect but the loop goes on (early finish disabled) and only gets worse.
        let mut designer = Scripted(vec![7, 8, 9, 10], vec![]);
        let config = StageConfig {
            max_rounds: 4,
            early_finish_min_score: 11,
            ..StageConfig::default()
        };
        let mut log = RunLog::default();
        let out = run_stage(
            &spec,
            0,
            &mut designer,
            &mut Likes7,
            &mut BuiltinOrchestrator::default(),
            &config,
            &mut log,
        )
        .unwrap();
        assert_eq!(out.state, 7);
        assert_eq!(out.kept, Some(0));
    }

    /// Two categories: "closeness" to 7 and "evenness" (10 for even values, 7 for odd ones).
    struct TwoCategories;
    impl Critic<i32> for TwoCategories {
        fn critique(
            &mut self,
            s: &mut i32,
            cx: &mut AgentCx<'_, i32>,
        ) -> Result<Critique, AgentError> {
            let v = cx.call(s, Role::Critic, "get", json!({})).unwrap()["value"]
                .as_i64()
                .unwrap() as i32;
            let score = |category: &str, score: i32| Score {
                category: category.into(),
                score: score.clamp(0, 10) as u8,
                reason: format!("value {v}"),
            };
            Ok(Critique {
                scores: vec![
                    score("closeness", 10 - (v - 7).abs()),
                    score("evenness", if v % 2 == 0 { 10 } else { 7 }),
                ],
                issues: vec![],
            })
        }
    }

    #[test]
    fn a_higher_total_does_not_keep_a_category_drop() {
        let cats = [
            CategorySpec::new("closeness", "close to 7"),
            CategorySpec::new("evenness", "even"),
        ];
        let tb = toolbox();
        let spec = StageSpec {
            name: "toy",
            categories: &cats,
            toolbox: &tb,
            brief: "",
        };
        // 5: 8 + 7 = 15. Then 8: 9 + 10 = 19, no drop: kept as the new baseline. Then 7:
        // 10 + 7 = 17 (evenness -3: rollback). Then 9: 8 + 7 = 15 (rollback again).
        // Then 4: 7 + 10 = 17: sum dropped by 2 against 8: rollback.
        let mut designer = Scripted(vec![5, 8, 7, 9, 4], vec![]);
        let config = StageConfig {
            max_rounds: 5,
            early_finish_min_score: 11,
            ..StageConfig::default()
        };
        let mut log = RunLog::default();
        let out = run_stage(
            &spec,
            0,
            &mut designer,
            &mut TwoCategories,
            &mut BuiltinOrchestrator::default(),
            &config,
            &mut log,
        )
        .unwrap();
        assert_eq!(out.state, 8);
        assert_eq!(out.kept, Some(1));

        // A regressed checkpoint is not kept even when its total is the highest.
        struct Tradeoff;
        impl Critic<i32> for Tradeoff {
            fn critique(
                &mut self,
                s: &mut i32,
                _cx: &mut AgentCx<'_, i32>,
            ) -> Result<Critique, AgentError> {
                // value 1: (5, 5); value 2: (9, 3): the total rises by 2, "b" drops by 2.
                let (a, b) = if *s == 1 { (5, 5) } else { (9, 3) };
                let score = |category: &str, score: u8| Score {
                    category: category.into(),
                    score,
                    reason: String::new(),
                };
                Ok(Critique {
                    scores: vec![score("a", a), score("b", b)],
                    issues: vec![],
                })
            }
        }
        let cats = [CategorySpec::new("a", "a"), CategorySpec::new("b", "b")];
        let spec = StageSpec {
            name: "tradeoff",
            categories: &cats,
            toolbox: &tb,
            brief: "",
        };
        let mut designer = Scripted(vec![1, 2], vec![]);
        let config = StageConfig {
            max_rounds: 2,
            early_finish_min_score: 11,
            ..StageConfig::default()
        };
        let out = run_stage(
            &spec,
            0,
            &mut designer,
            &mut Tradeoff,
            &mut BuiltinOrchestrator::default(),
            &config,
            &mut log,
        )
        .unwrap();
        assert_eq!(out.history.len(), 2);
        assert_eq!(
            out.history[1].total(),
            12,
            "the regressed checkpoint scores higher"
        );
        assert_eq!(out.state, 1);
        assert_eq!(out.kept, Some(0));
    }
}
