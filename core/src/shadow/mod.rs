//! The shadow unit: compare a surface point's light-space depth with the
//! map and filter the binary results — percentage-closer filtering
//! (Reeves, Salesin & Cook 1987 §2): compare first, then filter.
//!
//! # Depth tests
//! A sample is **shadowed** iff `z − bias > r`, where `z` is the point's
//! depth and `r` the texel's reference depth:
//!
//! | test | `r` | paper |
//! |---|---|---|
//! | [`DepthTest::First`] | `z1` | Williams 1978 |
//! | [`DepthTest::Second`] | `z2` (so `z ≤ z2` is lit: planar two-sided surfaces work) | Wang & Molnar 1994 §3.1 |
//! | [`DepthTest::Midpoint`] | `(z1 + z2) / 2` | Woo 1992, via Weiskopf & Ertl 2003 §3 |
//! | [`DepthTest::Dual`] | `z1 + min((z2 − z1) / 2, offset)` | Weiskopf & Ertl 2003 §4 |
//!
//! The receiver's depth (less the bias) is rounded to the map's format as
//! the light pass rounds fragments, so a receiver exactly on a stored
//! surface compares equal; references are formed from the widened texels in
//! [`PlaneZ`](crate::depth::PlaneZ) bits (so the midpoint keeps its half LSB). The bias is
//! constant or, as Reeves' `[Bias0, Bias1]`, drawn per sample.
//!
//! # Virtual samples
//! With a [`Slope`], each sample compares the receiver's tangent plane at
//! that texel's centre instead of one depth (Wang & Molnar 1994 §3.2),
//! evaluated once per footprint row and stepped by forward differences.
//! [`shadow_with_virtual_samples`] is their second pass for one pixel.
//!
//! # Filters
//! Map coordinates are texels with 16 fraction bits ([`MapCoord`]); texel
//! `(i, j)` covers `[i, i + 1) × [j, j + 1)`. [`Filter::Point`] reads the
//! texel under the point; [`Filter::Bilinear`] the four nearest texel
//! centres, weighted by the fractional position; [`Filter::Box`] the `n × n`
//! texels centred on the point; [`Filter::Jittered`] Reeves' stochastic
//! filter (Figure 4): the footprint, enlarged by `ResFactor` and at least
//! `MinSize`, is split into `ns × nt` subregions (`NumSamples`,
//! `MinSamples`) sampled with jitter from a seeded PCG generator, each
//! sample with its own bias. Samples outside the map are lit, and a point
//! nearer than the near plane (`z < 0`, which includes behind the light)
//! is lit.
//!
//! # Culling lookups
//! Before any texel is read, the tiles under the footprint are consulted:
//! when their stored min/max prove that every sample agrees (all lit, or —
//! with the whole footprint inside the map — all shadowed), no texel is
//! read and the skip is reported (Reeves et al. 1987 §3.3's per-tile max z).
//! The result is exactly the one the samples would give.

mod built;
mod config;
mod cull;
mod filter;
mod footprint;
mod map;
mod tangent;

pub use built::{AllFilters, BoxFilter, Built};
pub use config::{Bias, DepthTest, Filter, FilterNameError, Jitter, ShadowConfig, ShadowConfigError};
use cull::reference_bounds;
pub(crate) use cull::settle_region;
use filter::at_format;
pub(crate) use filter::lookup;
pub use filter::shadow;
pub(crate) use footprint::mul_shift;
pub use footprint::{Lookup, Slope, jitter_grid};
use footprint::{Texels, floor};
pub use map::{MapView, TileBounds};
pub(crate) use tangent::virtual_samples;
pub use tangent::{TangentPlane, shadow_with_virtual_samples};

use fixed::types::{I16F16, U16F16};

use crate::budget::MAP_HALF;

/// A position on the map in texels, 16 fraction bits.
pub type MapCoord = I16F16;

/// The fraction of a lookup in shadow: 0 lit, 1 fully shadowed.
pub type Shadow = U16F16;

/// Half a texel.
#[allow(clippy::cast_possible_truncation, reason = "half a texel fits a map coordinate")]
const HALF: MapCoord = MapCoord::from_bits(MAP_HALF as i32);
