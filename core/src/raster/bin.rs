//! Binning: each tile has a bin of fixed capacity holding the set-up
//! triangles that touch it, in submission order.
//!
//! A bin is a [`heapless::Vec`] with its capacity `B` as a const generic. When
//! a bin is full its tile is rasterized early (a *bin flush*, reported to the
//! probe) and binning retries, as binning hardware does; the tile's depth
//! goes back to the map and is loaded again when its next bin is drained.
//! Bins hold indices into the shared triangle-setup store; when that store
//! is full, every bin is drained.

use crate::front::setup::Setup;

/// Index of a set-up triangle in the setup store.
pub type SetupIndex = u16;

/// Largest setup store the bin entries can address.
pub const MAX_SETUPS: usize = SetupIndex::MAX as usize + 1;

/// One tile's bin.
pub type Bin<const B: usize> = heapless::Vec<SetupIndex, B>;

/// Whether `s` may cover a pixel centre of the tile `r`: a conservative
/// corner test, so a bin may hold a triangle that then covers nothing there.
#[inline]
#[must_use]
pub fn touches(s: &Setup, r: &crate::grid::TileRect) -> bool {
    r.intersect(&s.bbox).is_some_and(|r| s.classify(&r) != crate::front::setup::Coverage::Empty)
}
