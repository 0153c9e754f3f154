//! The shadow algorithms of the four papers, and the one place each is
//! mapped to the units it uses: the light pass's depth unit and culling,
//! the shadow unit's test and bias, and the map the camera pass reads.

use serde::Serialize;
use umbra_core::shadow::{Bias, DepthTest};
use umbra_core::{CullMode, DepthFormat, DepthUnit};

/// A shadow algorithm of the four papers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Algorithm {
    /// Williams' first depth with a bias.
    First,
    /// First depth with Reeves et al.'s bias range: each sample's bias drawn
    /// uniformly from `[bias, hi]` (`Bias0`, `Bias1`; 1987 §3.2).
    BiasRange {
        /// `Bias1`, as a depth in `[0, 1]` (`Bias0` is the configuration's bias).
        hi: f64,
    },
    /// Wang & Molnar's second depth from the dual unit.
    Second,
    /// Second depth from front-face culling (solids culled, open surfaces not).
    SecondFrontCulled,
    /// Woo's midpoint of the dual unit.
    Midpoint,
    /// Weiskopf & Ertl's dual depth; solids back-face culled, open surfaces not.
    Dual {
        /// The largest distance above `z1`, as a depth in `[0, 1]`.
        offset: f64,
    },
    /// Sen, Cammarano & Hanrahan's silhouette map over a first-depth map
    /// (with the bias), decided by the skewed quadrants; no filter.
    Silhouette {
        /// Points packed to 4 bits per axis (one byte per texel) instead of
        /// 16 bits per axis.
        packed: bool,
    },
    /// Depth-fail stencil shadow volumes on the camera's raster: exact hard
    /// shadows, no light pass and no map.
    Volumes,
}

/// The map an algorithm's camera pass reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// A depth map (single, dual, or single front-face culled).
    Depth,
    /// Sen et al.'s silhouette map over a first-depth map.
    Silhouette {
        /// Points packed to one byte per texel.
        packed: bool,
    },
    /// None: shadow volumes on the camera's raster.
    Volumes,
}

/// What an algorithm asks of the hardware.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// The map the camera pass reads.
    pub map: MapKind,
    /// The light pass's depth unit.
    pub unit: DepthUnit,
    /// The light pass culls solids' front faces, so the single map holds
    /// the second depth (Wang & Molnar §3.4).
    pub front_culled: bool,
    /// How the light pass culls solids (open surfaces are never culled:
    /// Weiskopf & Ertl §3.2).
    pub solids: CullMode,
    /// The shadow unit's depth test.
    pub test: DepthTest,
    /// The shadow unit's bias.
    pub bias: Bias,
}

impl Units {
    /// Whether Wang & Molnar's virtual samples apply when asked for: only
    /// to the second-depth test.
    #[must_use]
    pub fn virtual_samples(&self, asked: bool) -> bool {
        asked && self.test == DepthTest::Second
    }

    /// How the light pass culls an object, solid or open.
    #[must_use]
    pub const fn cull(&self, solid: bool) -> CullMode {
        if solid { self.solids } else { CullMode::None }
    }
}

impl Algorithm {
    /// The units this algorithm uses in format `F`, with `bias` (a depth in
    /// `[0, 1]`; Reeves' `Bias0` for a bias range).
    #[must_use]
    pub fn units<F: DepthFormat>(self, bias: f64) -> Units {
        let constant = Bias::Constant(F::plane_z(bias));
        let units = |unit, test| Units {
            map: MapKind::Depth,
            unit,
            front_culled: false,
            solids: CullMode::None,
            test,
            bias: constant,
        };
        match self {
            Self::First => units(DepthUnit::Single, DepthTest::First),
            Self::BiasRange { hi } => Units {
                bias: Bias::Range { lo: F::plane_z(bias), hi: F::plane_z(hi) },
                ..units(DepthUnit::Single, DepthTest::First)
            },
            Self::Second => units(DepthUnit::Dual, DepthTest::Second),
            Self::SecondFrontCulled => {
                Units { front_culled: true, solids: CullMode::Front, ..units(DepthUnit::Single, DepthTest::Second) }
            }
            Self::Midpoint => units(DepthUnit::Dual, DepthTest::Midpoint),
            Self::Dual { offset } => Units {
                solids: CullMode::Back,
                ..units(DepthUnit::Dual, DepthTest::Dual { offset: F::plane_z(offset) })
            },
            Self::Silhouette { packed } => {
                Units { map: MapKind::Silhouette { packed }, ..units(DepthUnit::Single, DepthTest::First) }
            }
            Self::Volumes => Units { map: MapKind::Volumes, ..units(DepthUnit::Single, DepthTest::First) },
        }
    }

    /// Reeves' `Bias1`, if the algorithm draws its bias from a range.
    #[must_use]
    pub const fn bias_hi(self) -> Option<f64> {
        match self {
            Self::BiasRange { hi } => Some(hi),
            _ => None,
        }
    }

    /// The dual offset, if the algorithm has one.
    #[must_use]
    pub const fn offset(self) -> Option<f64> {
        match self {
            Self::Dual { offset } => Some(offset),
            _ => None,
        }
    }
}
