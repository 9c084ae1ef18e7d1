//! Splitting prompt text into tokens that remember where they came from.
//!
//! Words keep their original spelling (capitals mark proper names such as "Frozen" the film),
//! their byte span in the prompt, and punctuation survives as its own token because it scopes
//! counts ("four chairs, plates and mugs": the four belongs to the chairs only). This module
//! does not know any vocabulary; the lexicon does.

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TokenKind {
    /// Letters, digits, inner hyphens ("x-ray", "45-pound", "3d").
    Word,
    /// A run of digits ("10"); its value.
    Number(u32),
    /// One punctuation character (`,` `.` `;` `:` `!` `?` `(` `)` `+` `&` `/`).
    Punct(char),
}

/// One token of a prompt.
#[derive(Debug, Clone, PartialEq)]
pub struct Token {
    /// Lower-case text.
    pub text: String,
    /// The text as written.
    pub raw: String,
    /// Byte offset of the first character in the prompt.
    pub start: usize,
    /// Byte offset one past the last character.
    pub end: usize,
    /// Word, number or punctuation.
    pub kind: TokenKind,
    /// True when written with a possessive "'s" ("a moment's notice"), which the text drops.
    pub possessive: bool,
}

impl Token {
    /// True when written with a leading capital letter.
    pub fn capitalized(&self) -> bool {
        self.raw.chars().next().is_some_and(char::is_uppercase)
    }

    /// True for a word or number (not punctuation).
    pub fn is_word(&self) -> bool {
        !matches!(self.kind, TokenKind::Punct(_))
    }

    /// True for the punctuation character `c`.
    pub fn is_punct(&self, c: char) -> bool {
        self.kind == TokenKind::Punct(c)
    }

    /// True when the token ends a sentence.
    pub fn ends_sentence(&self) -> bool {
        matches!(self.kind, TokenKind::Punct('.' | '!' | '?' | ';'))
    }
}

fn is_word_char(c: char) -> bool {
    c.is_alphanumeric() || c == '-' || c == '\''
}

/// Splits `text` into word, number and punctuation tokens. Underscores separate words
/// ("common_room" reads as "common room"); a possessive "'s" is dropped ("teacher's desk"
/// reads as "teacher desk"); quotes and other symbols are skipped.
pub fn lex(text: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut chars = text.char_indices().peekable();
    while let Some(&(i, c)) = chars.peek() {
        if is_word_char(c) && c != '\'' && c != '-' {
            let mut end = i;
            while let Some(&(j, d)) = chars.peek() {
                if is_word_char(d) {
                    end = j + d.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            push_word(&mut out, text, i, end);
            continue;
        }
        chars.next();
        // An en or em dash sets off a phrase ("Stuffed animals — at least a dozen — tumble
        // out"); both read as an em dash.
        let c = if c == '\u{2013}' { '\u{2014}' } else { c };
        if matches!(
            c,
            ',' | '.' | ';' | ':' | '!' | '?' | '(' | ')' | '+' | '&' | '/' | '\u{2014}'
        ) {
            // A decimal point inside a number ("2.5 m") is not a sentence end.
            let in_number = c == '.'
                && out
                    .last()
                    .is_some_and(|t: &Token| matches!(t.kind, TokenKind::Number(_)) && t.end == i)
                && chars.peek().is_some_and(|&(_, d)| d.is_ascii_digit());
            if in_number {
                continue;
            }
            out.push(Token {
                text: c.to_string(),
                raw: c.to_string(),
                start: i,
                end: i + c.len_utf8(),
                kind: TokenKind::Punct(c),
                possessive: false,
            });
        }
    }
    out
}

fn push_word(out: &mut Vec<Token>, text: &str, start: usize, end: usize) {
    let raw = &text[start..end];
    // Possessives and stray apostrophes/hyphens at the edges.
    let mut trimmed = raw;
    let mut possessive = false;
    for suffix in ["'s", "'S", "\u{2019}s"] {
        if let Some(t) = trimmed.strip_suffix(suffix) {
            trimmed = t;
            possessive = true;
        }
    }
    let lead = trimmed.len() - trimmed.trim_start_matches(['-', '\'']).len();
    let trimmed = trimmed.trim_matches(|c| c == '-' || c == '\'');
    if trimmed.is_empty() {
        return;
    }
    let start = start + lead;
    let end = start + trimmed.len();
    let lower = trimmed.to_lowercase().replace('\'', "");
    let kind = if lower.chars().all(|c| c.is_ascii_digit()) {
        match lower.parse::<u32>() {
            Ok(n) => TokenKind::Number(n),
            Err(_) => TokenKind::Word,
        }
    } else {
        TokenKind::Word
    };
    out.push(Token {
        text: lower,
        raw: trimmed.to_string(),
        start,
        end,
        kind,
        possessive,
    });
}

/// Lower-case word tokens only (punctuation dropped), the form older callers use.
pub fn tokenize(text: &str) -> Vec<String> {
    lex(text)
        .into_iter()
        .filter(Token::is_word)
        .map(|t| t.text)
        .collect()
}

/// Splits a token list into sentences (the closing punctuation stays with its sentence).
pub fn sentences(tokens: &[Token]) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, t) in tokens.iter().enumerate() {
        if t.ends_sentence() {
            if i + 1 > start {
                out.push(start..i + 1);
            }
            start = i + 1;
        }
    }
    if start < tokens.len() {
        out.push(start..tokens.len());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_numbers_and_punctuation() {
        let t = lex("A teacher's desk, 45-pound plates; an X-ray room.");
        let texts: Vec<&str> = t.iter().map(|t| t.text.as_str()).collect();
        assert_eq!(
            texts,
            [
                "a", "teacher", "desk", ",", "45-pound", "plates", ";", "an", "x-ray", "room", "."
            ]
        );
        assert!(t[8].capitalized());
        assert_eq!(&"A teacher's desk"[t[1].start..t[1].end], "teacher");
    }

    #[test]
    fn underscores_split_and_numbers_parse() {
        let t = lex("a common_room with 10+ books");
        let texts: Vec<&str> = t.iter().map(|t| t.text.as_str()).collect();
        assert_eq!(texts, ["a", "common", "room", "with", "10", "+", "books"]);
        assert_eq!(t[4].kind, TokenKind::Number(10));
        assert_eq!(tokenize("Hello, World"), ["hello", "world"]);
    }

    #[test]
    fn sentence_ranges() {
        let t = lex("A kitchen. The table has a mug. ");
        let s = sentences(&t);
        assert_eq!(s.len(), 2);
        assert_eq!(t[s[1].start].text, "the");
    }
}
