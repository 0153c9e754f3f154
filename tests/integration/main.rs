//! Integration and property tests of Umbra, as one binary.
#![allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_possible_wrap,
    clippy::cast_precision_loss,
    reason = "test arithmetic on small, bounded values"
)]

mod common;
mod mock_map;
mod scratch;

mod firmware;

mod depth;
mod raster;
mod shade;
mod shadow;
mod silhouette;
mod stencil;

mod cost;
mod experiment;
mod io;
mod probe;
mod render;
mod truth;

mod world;

mod determinism;
mod layers;
mod python_build;
mod regressions;
mod surface;
