#![forbid(unsafe_code)]
#![warn(unnameable_types)]
#![doc = include_str!("../README.md")]
//!
//! # The API in one sitting
//!
//! Load a scene (a bundled name, a scene file or an OBJ mesh), choose an
//! architecture (a bundled preset or a file), then render, cost, sweep or
//! plan. The names below are the whole API a library user needs; the
//! modules hold the units behind them.
//!
//! ```
//! use umbra_sim::{Algorithm, Arch, Limits, RenderConfig, Scene, TruthSource};
//!
//! let limits = Limits::DEFAULT;
//! let scene = Scene::open("table-and-sphere", &limits)?;
//! let arch = Arch::open("mobile-tbdr", &limits)?;
//! // First depth at bias 0.002, on a small image and map to keep this quick.
//! let config = RenderConfig {
//!     algorithm: Algorithm::First,
//!     bias: 0.002,
//!     width: 160,
//!     height: 90,
//!     map_size: 256,
//!     ..RenderConfig::DEFAULT
//! };
//! // Checked once, against the scene and the limits: what a render takes.
//! let job = config.check(&scene, &limits)?;
//! let render = umbra_sim::render(&job, TruthSource::Quiet)?;
//! assert!(render.metrics.evaluated > 0);
//! let cost = umbra_sim::cost(&job, &arch)?;
//! assert!(cost.cycles() > 0.0 && cost.bytes() > 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod base;

pub mod input;
pub mod output;

pub mod world;

pub mod pass;

pub mod cost;
pub mod truth;

pub mod render;

pub mod experiment;

pub use glam;
pub use umbra_core as core;

pub use cost::arch::Arch;
pub use cost::report::CostReport;
pub use experiment::plan::{Plan, PlanSpec, plan};
pub use experiment::study::{Row, Spec as StudySpec, SweepFile, run as study};
pub use input::limits::Limits;
pub use pass::algorithm::{Algorithm, Culling};
pub use render::{Checked, Render, RenderConfig, RenderRequest, TruthSource, cost, render};
pub use world::mesh::Mesh;
pub use world::scene::Scene;
