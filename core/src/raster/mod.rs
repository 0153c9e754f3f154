//! The raster block, in the order of Mesa llvmpipe's split: setup (edge
//! functions with the fill rule's bias, the depth plane it solves for the
//! plane interpolator), bins (a tile's list of set-up triangles), tiles
//! (the target's grid), traversal (a binned triangle over one tile:
//! culling, classification, spans) and the coverage-mask unit it uses for
//! partial rectangles.

pub mod bin;
pub mod mask;
mod plane;
pub mod setup;
pub mod tile;
mod traverse;

pub use traverse::BLOCK;
pub(crate) use traverse::{TileView, rasterize};
