//! The depth block: the map's formats (how a depth becomes a texel and
//! how texels compare), the depth unit updated per fragment (single, dual,
//! and with ids for visibility), and the per-tile state it keeps.

pub mod datapaths;
pub mod format;
mod tile;
mod unit;

pub use format::{D16, D24, DepthFormat, DepthFormatKind, F32, PlaneZ, Texel};
pub use tile::TileState;
pub(crate) use tile::{count_of, min_max, tile_rows};
pub(crate) use unit::{SpanEdges, SpanOut, span};
