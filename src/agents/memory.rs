//! Conversation memory of one agent within one stage: the current and previous turn in full,
//! older turns replaced by their summaries, images kept only for the last few observations.

use serde_json::{Value, json};

/// Messages of one turn, with a one-line summary used once the turn is old.
#[derive(Debug, Clone, Default)]
struct Turn {
    messages: Vec<Value>,
    summary: String,
}

/// Chat memory (OpenAI message format).
#[derive(Debug, Clone)]
pub struct Memory {
    turns: Vec<Turn>,
    /// How many recent turns stay in full.
    pub full_turns: usize,
    /// How many recent images stay attached.
    pub image_window: usize,
}

impl Default for Memory {
    fn default() -> Self {
        Memory {
            turns: Vec::new(),
            full_turns: 2,
            image_window: 2,
        }
    }
}

/// True for a message part that carries an image.
fn is_image_part(part: &Value) -> bool {
    part["type"] == "image_url"
}

impl Memory {
    /// Starts a new turn.
    pub fn begin_turn(&mut self) {
        self.turns.push(Turn::default());
    }

    /// Adds a message to the current turn (starting one if needed).
    pub fn push(&mut self, message: Value) {
        if self.turns.is_empty() {
            self.begin_turn();
        }
        if let Some(t) = self.turns.last_mut() {
            t.messages.push(message);
        }
    }

    /// Ends the current turn with a summary for when it becomes old.
    pub fn end_turn(&mut self, summary: &str) {
        if let Some(t) = self.turns.last_mut() {
            t.summary = summary.to_string();
        }
    }

    /// Forgets everything (between stages).
    pub fn reset(&mut self) {
        self.turns.clear();
    }

    /// The messages to send: a summary of old turns, then the recent turns in full, with all
    /// but the last `image_window` images replaced by a note.
    pub fn messages(&self) -> Vec<Value> {
        let split = self.turns.len().saturating_sub(self.full_turns);
        let mut out = Vec::new();
        let old: Vec<String> = self.turns[..split]
            .iter()
            .enumerate()
            .map(|(i, t)| format!("Turn {}: {}", i + 1, t.summary))
            .collect();
        if !old.is_empty() {
            out.push(json!({
                "role": "user",
                "content": format!("Summary of earlier turns in this stage:\n{}", old.join("\n")),
            }));
        }
        for t in &self.turns[split..] {
            out.extend(t.messages.iter().cloned());
        }
        // Keep only the newest images.
        let mut seen = 0;
        for m in out.iter_mut().rev() {
            if let Some(parts) = m["content"].as_array_mut() {
                for p in parts.iter_mut().rev() {
                    if is_image_part(p) {
                        seen += 1;
                        if seen > self.image_window {
                            *p = json!({"type": "text", "text": "[earlier image omitted]"});
                        }
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(n: usize) -> Value {
        json!({"role": "user", "content": [
            {"type": "text", "text": format!("view {n}")},
            {"type": "image_url", "image_url": {"url": format!("data:image/png;base64,{n}")}}
        ]})
    }

    #[test]
    fn keeps_two_turns_and_two_images() {
        let mut m = Memory::default();
        for i in 0..4 {
            m.begin_turn();
            m.push(json!({"role": "user", "content": format!("instruction {i}")}));
            m.push(image(2 * i));
            m.push(image(2 * i + 1));
            m.end_turn(&format!("did {i}"));
        }
        let msgs = m.messages();
        let text = serde_json::to_string(&msgs).unwrap();
        assert!(text.contains("Turn 1: did 0") && text.contains("Turn 2: did 1"));
        assert!(!text.contains("instruction 0") && text.contains("instruction 2"));
        let images = text.matches("data:image/png").count();
        assert_eq!(images, 2);
        assert!(text.contains("base64,7") && text.contains("base64,6"));
        m.reset();
        assert!(m.messages().is_empty());
    }
}
