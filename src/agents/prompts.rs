//! System prompts of every role and stage, from `prompts/<stage>_<role>.md`, compiled in and
//! rendered with `{{placeholder}}` values at run time.

use super::tool::Role;

/// Stages that have prompts.
pub const STAGES: [&str; 5] = ["layout", "furniture", "wall", "ceiling", "manipuland"];

macro_rules! prompt_table {
    ($($stage:literal),*) => {
        &[$(
            ($stage, "designer", include_str!(concat!("../../prompts/", $stage, "_designer.md"))),
            ($stage, "critic", include_str!(concat!("../../prompts/", $stage, "_critic.md"))),
            ($stage, "orchestrator", include_str!(concat!("../../prompts/", $stage, "_orchestrator.md"))),
        )*]
    };
}

const TEMPLATES: &[(&str, &str, &str)] =
    prompt_table!("layout", "furniture", "wall", "ceiling", "manipuland");

/// The raw template of a stage and role (stages without their own prompt use `furniture`'s).
pub fn template(stage: &str, role: Role) -> &'static str {
    let find = |s: &str| {
        TEMPLATES
            .iter()
            .find(|(st, r, _)| *st == s && *r == role.as_str())
            .map(|(_, _, t)| *t)
    };
    find(stage).or_else(|| find("furniture")).unwrap_or("")
}

/// The template with every `{{key}}` replaced by its value.
pub fn render(stage: &str, role: Role, vars: &[(&str, &str)]) -> String {
    let mut out = template(stage, role).to_string();
    for (k, v) in vars {
        out = out.replace(&format!("{{{{{k}}}}}"), v);
    }
    out
}

/// Placeholders a template uses.
pub fn placeholders(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(start) = rest.find("{{") {
        let after = &rest[start + 2..];
        match after.find("}}") {
            Some(end) => {
                out.push(after[..end].to_string());
                rest = &after[end + 2..];
            }
            None => break,
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_stage_and_role_has_a_prompt_with_known_placeholders() {
        let known_agent = ["stage", "brief", "tools", "categories", "style"];
        let known_orch = ["stage", "brief", "max_rounds", "early_finish"];
        for stage in STAGES {
            for role in [Role::Designer, Role::Critic, Role::Orchestrator] {
                let t = TEMPLATES
                    .iter()
                    .find(|(s, r, _)| *s == stage && *r == role.as_str())
                    .map(|(_, _, t)| *t)
                    .unwrap();
                assert!(t.len() > 200, "{stage}/{}: prompt too short", role.as_str());
                let known: &[&str] = if role == Role::Orchestrator {
                    &known_orch
                } else {
                    &known_agent
                };
                for p in placeholders(t) {
                    assert!(
                        known.contains(&p.as_str()),
                        "{stage}/{}: unknown placeholder {p}",
                        role.as_str()
                    );
                }
            }
        }
        let r = render(
            "wall",
            Role::Designer,
            &[
                ("stage", "wall"),
                ("brief", "B"),
                ("tools", "T"),
                ("categories", "C"),
                ("style", "natural"),
            ],
        );
        assert!(!r.contains("{{"));
    }
}
