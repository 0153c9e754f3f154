#![no_std]
#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod budget;
pub mod config;
pub mod depth;
pub mod front;
pub mod grid;
pub mod light_pass;
pub mod probe;
pub mod raster;
pub mod round;
pub mod shade;
pub mod shadow;
pub mod silhouette;
pub mod spelling;
pub mod stencil;

pub use config::{ConfigError, CullMode, DepthUnit, LightPassConfig, RasterConfig};
pub use depth::TileState;
pub use depth::{D16, D24, DepthFormat, DepthFormatKind, F32};
pub use grid::{TileId, TileRect};
pub use light_pass::{
    Datapaths, DualOnly, Every, LightBuffers, LightPass, NO_TRIANGLE, SingleOnly, SubmitError, VisibilityOnly,
};
pub use probe::{Event, Fragment, NoProbe, Probe};

pub use glam;
