//! The memory the light-pass driver works in, owned by the caller, and what it refuses.

use crate::depth::{DepthFormat, TileState};
use crate::front::setup::Setup;
use crate::raster::bin::Bin;

/// The caller-owned memory of a light pass.
pub struct LightBuffers<'a, F: DepthFormat, const B: usize> {
    /// Nearest depth, `width × height` texels.
    pub z1: &'a mut [F::Texel],
    /// Second-nearest depth: `width × height` texels for [`DepthUnit::Dual`](crate::DepthUnit::Dual), empty for single.
    pub z2: &'a mut [F::Texel],
    /// Visible-triangle ids, `width × height`, for a single unit that
    /// records visibility (the camera pass); empty otherwise. A pixel no
    /// triangle covers holds [`NO_TRIANGLE`].
    pub ids: &'a mut [u32],
    /// One summary per tile, row-major.
    pub tiles: &'a mut [TileState<F::Texel>],
    /// One bin per tile, row-major.
    pub bins: &'a mut [Bin<B>],
    /// The triangle-setup store: any length in `1..=65536`.
    pub setups: &'a mut [Setup],
}

/// The id of a pixel that no triangle covers.
pub const NO_TRIANGLE: u32 = u32::MAX;
