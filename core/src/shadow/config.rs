//! What the shadow unit is asked to do: the depth test, the bias and the filter.

use core::fmt;

use super::MapCoord;
use crate::depth::PlaneZ;

/// Which reference depth a sample compares against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthTest {
    /// Nearest depth `z1`.
    First,
    /// Second-nearest depth `z2`: from the dual unit, or the single buffer
    /// of a front-face-culled pass ([`MapView::front_culled`](super::MapView::front_culled)).
    Second,
    /// Woo's midpoint `(z1 + z2) / 2`.
    Midpoint,
    /// Weiskopf & Ertl's dual depth `z1 + min((z2 − z1) / 2, offset)`.
    Dual {
        /// The largest distance above `z1`, in [`PlaneZ`] (format LSBs).
        offset: PlaneZ,
    },
}

impl DepthTest {
    /// Whether the test reads `z2`.
    #[must_use]
    pub const fn needs_z2(self) -> bool {
        !matches!(self, Self::First)
    }

    /// Whether the test reads `z1`.
    #[must_use]
    pub const fn needs_z1(self) -> bool {
        !matches!(self, Self::Second)
    }

    /// The reference depth from `z1` and `z2` ([`PlaneZ`] bits). Monotonic
    /// in both, so tile bounds bound it.
    #[inline]
    pub(super) fn reference(self, z1: i64, z2: i64) -> i64 {
        match self {
            Self::First => z1,
            Self::Second => z2,
            Self::Midpoint => (z1 >> 1) + (z2 >> 1) + (z1 & z2 & 1),
            Self::Dual { offset } => z1.saturating_add(((z2 - z1) >> 1).min(offset.to_bits().max(0))),
        }
    }
}

/// The depth bias, in [`PlaneZ`] (format LSBs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bias {
    /// The same for every sample.
    Constant(PlaneZ),
    /// Drawn uniformly per sample from `[lo, hi]` (Reeves' `Bias0`, `Bias1`).
    Range {
        /// `Bias0`.
        lo: PlaneZ,
        /// `Bias1`.
        hi: PlaneZ,
    },
}

impl Default for Bias {
    /// No bias: Wang & Molnar's default for second depth.
    fn default() -> Self {
        Self::ZERO
    }
}

impl Bias {
    /// No bias.
    pub const ZERO: Self = Self::Constant(PlaneZ::ZERO);

    /// The smallest and largest bias a sample can get.
    #[must_use]
    pub fn bounds(self) -> (i64, i64) {
        match self {
            Self::Constant(b) => (b.to_bits(), b.to_bits()),
            Self::Range { lo, hi } => (lo.to_bits(), hi.to_bits()),
        }
    }
}

/// Reeves' stochastic filter parameters (Figure 4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Jitter {
    /// `NumSamples`: samples per lookup (before the per-axis clamps).
    pub num_samples: u16,
    /// `ResFactor`: enlarges the footprint (softer shadows).
    pub res_factor: MapCoord,
    /// `MinSamples`: fewest samples along each axis.
    pub min_samples: u16,
    /// `MinSize`: smallest half-size of the sampled region, texels.
    pub min_size: MapCoord,
}

impl Jitter {
    /// The values Reeves et al. list in Figure 4.
    pub const REEVES: Self =
        Self { num_samples: 16, res_factor: MapCoord::lit("3"), min_samples: 1, min_size: MapCoord::ZERO };
}

/// How the binary comparisons of a lookup are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel under the point.
    Point,
    /// The four nearest texel centres, weighted by the fractional position.
    Bilinear,
    /// `size × size` texels centred on the point, equally weighted.
    Box {
        /// Side in texels, `1..=16`.
        size: u8,
    },
    /// Reeves' jittered stochastic sampling of the footprint.
    Jittered(Jitter),
}

/// A validated shadow-unit configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShadowConfig {
    pub(super) test: DepthTest,
    pub(super) bias: Bias,
    pub(super) filter: Filter,
    pub(super) cull_lookups: bool,
}

/// A shadow configuration the unit cannot use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShadowConfigError {
    /// A box filter side outside `1..=16`.
    BoxSize {
        /// The side asked for.
        size: u8,
    },
    /// `NumSamples` outside `1..=256`, or `MinSamples` above it or zero.
    Samples {
        /// `NumSamples`.
        num_samples: u16,
        /// `MinSamples`.
        min_samples: u16,
    },
    /// A negative `ResFactor` or `MinSize`.
    Region,
    /// A bias range with `lo > hi`.
    BiasRange,
    /// A negative dual-depth offset.
    Offset,
}

impl fmt::Display for ShadowConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BoxSize { size } => write!(f, "box filter size {size} is outside 1..=16"),
            Self::Samples { num_samples, min_samples } => {
                write!(f, "NumSamples {num_samples} must be in 1..=256 and MinSamples {min_samples} in 1..=NumSamples")
            }
            Self::Region => write!(f, "ResFactor and MinSize must not be negative"),
            Self::BiasRange => write!(f, "bias range has Bias0 > Bias1"),
            Self::Offset => write!(f, "dual-depth offset must not be negative"),
        }
    }
}

impl core::error::Error for ShadowConfigError {}

impl ShadowConfig {
    /// Validate a configuration. `cull_lookups` enables per-tile culling.
    ///
    /// # Errors
    /// See [`ShadowConfigError`].
    pub fn new(test: DepthTest, bias: Bias, filter: Filter, cull_lookups: bool) -> Result<Self, ShadowConfigError> {
        match filter {
            Filter::Box { size } if !(1..=16).contains(&size) => return Err(ShadowConfigError::BoxSize { size }),
            Filter::Jittered(j) => {
                if !(1..=256).contains(&j.num_samples) || j.min_samples == 0 || j.min_samples > j.num_samples {
                    return Err(ShadowConfigError::Samples { num_samples: j.num_samples, min_samples: j.min_samples });
                }
                if j.res_factor < 0 || j.min_size < 0 {
                    return Err(ShadowConfigError::Region);
                }
            }
            _ => {}
        }
        if let Bias::Range { lo, hi } = bias
            && lo > hi
        {
            return Err(ShadowConfigError::BiasRange);
        }
        if let DepthTest::Dual { offset } = test
            && offset < 0
        {
            return Err(ShadowConfigError::Offset);
        }
        Ok(Self { test, bias, filter, cull_lookups })
    }

    /// The depth test.
    #[must_use]
    pub const fn test(&self) -> DepthTest {
        self.test
    }

    /// The filter.
    #[must_use]
    pub const fn filter(&self) -> Filter {
        self.filter
    }

    /// The bias.
    #[must_use]
    pub const fn bias(&self) -> Bias {
        self.bias
    }

    /// Whether a lookup draws random numbers (the jittered filter's
    /// positions, or a bias range's per-sample bias): only then does its
    /// [`Lookup::seed`](super::Lookup::seed) matter.
    #[must_use]
    pub const fn draws_random(&self) -> bool {
        matches!(self.filter, Filter::Jittered(_)) || matches!(self.bias, Bias::Range { .. })
    }

    /// The same configuration with lookup culling on or off.
    #[must_use]
    pub const fn with_cull_lookups(self, cull_lookups: bool) -> Self {
        Self { cull_lookups, ..self }
    }
}
