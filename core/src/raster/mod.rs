//! The raster block, in the order of Mesa llvmpipe's split (its setup, like
//! llvmpipe's `lp_setup`, is the front end's: [`crate::front::setup`]): bins
//! (a tile's list of set-up triangles over [`crate::grid`]), traversal (a
//! binned triangle over one tile: culling, classification, spans) and the
//! coverage-mask unit it uses for partial rectangles.

pub mod bin;
pub mod mask;
mod traverse;

pub use traverse::BLOCK;
pub(crate) use traverse::{TileView, rasterize};
