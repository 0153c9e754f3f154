#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod world;

pub mod pass;

pub mod cost;
pub mod truth;

pub mod experiment;

pub mod io;

pub use glam;
pub use umbra_core as core;
