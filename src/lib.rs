//! # scenesmith
//!
//! Text prompt in, simulation-ready indoor scene out: rooms with volumetric walls, doors and
//! windows, furniture and small objects that are each separately manipulable, with convex
//! collision geometry, mass, inertia, friction and articulated doors and drawers. The native
//! output is SDFormat plus Drake model directives.
//!
//! Modules follow the pipeline (see `Where the code lives` in the README):
//! [`words`] says what words are (tokens, lexicon, WordNet), [`prompt`] reads the prompt,
//! [`plan`] says what each room should contain, [`layout`] builds rooms, [`stages`] place
//! objects, [`assets`] make them (room architecture included), [`state`] holds the scene with
//! its built assets, [`physics`] checks them (parry3d in-process, Drake through the bridge),
//! [`formats`] write the scene directory, [`render`] draws it, [`export`] writes MJCF, USD and
//! GLB, [`pipeline`] ties the run together (and the `asset` command's run).
//!
//! They form layers without import cycles (`tests/module_layers.rs`), bottom to top: scene,
//! geometry, util, words, knowledge, prompt, assets, state, agents, formats, physics, eval,
//! plan, render, layout, stages, export, pipeline, task.
//!
//! This crate does not render, simulate or plan by itself: Drake (through `drake_bridge/`)
//! does the simulation.

#![warn(missing_docs)]
// Index loops read better than iterator chains in small fixed-size matrix code.
#![allow(clippy::needless_range_loop)]

pub mod agents;
pub mod assets;
pub mod batch;
pub mod eval;
pub mod export;
pub mod formats;
pub mod geometry;
pub mod knowledge;
pub mod layout;
pub mod physics;
pub mod pipeline;
pub mod plan;
pub mod prompt;
pub mod render;
pub mod scene;
pub mod stages;
pub mod state;
pub mod task;
pub mod util;
pub mod view;
pub mod words;
