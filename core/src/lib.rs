#![no_std]
#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod bin;
pub mod camera;
pub mod clip;
pub mod config;
pub mod depth;
pub mod front_end;
pub mod light_pass;
pub mod mask;
pub mod probe;
pub mod raster;
pub mod round;
pub mod setup;
pub mod shadow;
pub mod silhouette;
pub mod snap;
pub mod stencil;
pub mod tile;
pub mod vertex;
pub mod zbuffer;

pub use config::{ConfigError, CullMode, DepthUnit, LightPassConfig, RasterConfig};
pub use depth::{D16, D24, DepthFormat, DepthFormatKind, F32};
pub use light_pass::{LightBuffers, LightPass, NO_TRIANGLE, SubmitError};
pub use probe::{Event, Fragment, NoProbe, Probe};
pub use tile::{TileId, TileRect};
pub use zbuffer::TileState;

pub use glam;
