#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod arch;
pub mod cache;
pub mod camera;
pub mod counters;
pub mod light;
pub mod limits;
pub mod mesh;
pub mod metrics;
pub mod occluders;
pub mod output;
pub mod plan;
pub mod presets;
pub mod reference;
pub mod render;
pub mod scene;
pub mod scene_file;
pub mod storage;
pub mod study;

pub use glam;
pub use umbra_core as core;
