//! Integration and property tests of Umbra, as one binary.
#![allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_possible_wrap,
    clippy::cast_precision_loss,
    reason = "test arithmetic on small, bounded values"
)]

mod common;

mod arch;
mod cache;
mod camera_pass;
mod claims;
mod culling;
mod determinism;
mod dual_depth;
mod fill_rule;
mod firmware;
mod hostile;
mod hostile_scenes;
mod maps_io;
mod plan;
mod quantize;
mod reference;
mod regressions;
mod scenes;
mod shadow_unit;
mod silhouette;
mod storage;
mod study;
mod tiling;
mod watertight;
