//! What words are: prompt text split into tokens with their spans ([`tokens`]), the
//! vocabulary of object nouns and word classes ([`lexicon`](mod@lexicon)), Princeton WordNet 3.0
//! ([`wordnet`]) and grounding nouns in it ([`ground`]).
//!
//! The prompt reader (`prompt`), the room registry (`knowledge`) and the asset router
//! (`assets`) all ask these questions, so they sit below all three. This module answers "what
//! is this word (or run of words)?"; it does not read phrases or decide what a prompt means.

pub mod ground;
pub mod lexicon;
pub mod tokens;
pub mod wordnet;

pub use lexicon::{Lexicon, NounEntry, Support, lexicon};
pub use tokens::tokenize;
