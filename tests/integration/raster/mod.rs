//! The raster block against a brute-force rasterizer: the fill rule, watertight meshes, every tiling, max-z culling.

mod culling;
mod datapaths;
mod fast_clear;
mod fill_rule;
mod tiling;
mod watertight;
