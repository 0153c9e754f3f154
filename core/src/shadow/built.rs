//! What a shadow unit is built with: its filters, its bias kinds, and the
//! tangent planes its virtual samples can solve.
//!
//! Each filter is its own datapath; a unit built with all of them (the
//! default, [`AllFilters`]) takes any [`ShadowConfig`], one built with fewer
//! ([`BoxFilter`]: the box filter with a constant bias, tangent planes
//! from flat normals) carries less code — what a microcontroller's flash
//! asks — and refuses a configuration needing what it lacks
//! ([`crate::ConfigError::ShadowNotBuilt`]) before it shades. What it
//! computes is the same bits either way.

use super::{Bias, Filter, ShadowConfig};

/// The datapaths a shadow unit is built with (compile-time constants: one
/// not built is not in the program).
pub trait Built {
    /// [`Filter::Point`].
    const POINT: bool;
    /// [`Filter::Bilinear`].
    const BILINEAR: bool;
    /// [`Filter::Box`].
    const BOX: bool;
    /// [`Filter::Jittered`], Reeves' stochastic filter.
    const JITTERED: bool;
    /// [`Bias::Range`], a bias drawn per sample.
    const BIAS_RANGE: bool;
    /// Tangent planes from smooth (interpolated) normals, for virtual
    /// samples ([`crate::shade::Normals::Smooth`]).
    const SMOOTH_TANGENTS: bool;

    /// The first datapath `cfg` (and `smooth` normals) needs that this
    /// build lacks, named; `None` when it has them all.
    #[must_use]
    fn missing(cfg: &ShadowConfig, smooth: bool) -> Option<&'static str> {
        let filter = match cfg.filter {
            Filter::Point => (Self::POINT, "the point filter"),
            Filter::Bilinear => (Self::BILINEAR, "the bilinear filter"),
            Filter::Box { .. } => (Self::BOX, "the box filter"),
            Filter::Jittered(_) => (Self::JITTERED, "the jittered filter"),
        };
        let bias = match cfg.bias {
            Bias::Constant(_) => (true, ""),
            Bias::Range { .. } => (Self::BIAS_RANGE, "a bias range"),
        };
        let normals = (!smooth || Self::SMOOTH_TANGENTS, "tangent planes from smooth normals");
        [filter, bias, normals].into_iter().find_map(|(built, what)| (!built).then_some(what))
    }
}

/// Every filter, bias kind and tangent plane: a unit that takes any
/// configuration.
#[derive(Clone, Copy, Debug, Default)]
pub struct AllFilters;

impl Built for AllFilters {
    const POINT: bool = true;
    const BILINEAR: bool = true;
    const BOX: bool = true;
    const JITTERED: bool = true;
    const BIAS_RANGE: bool = true;
    const SMOOTH_TANGENTS: bool = true;
}

/// The box filter alone, with a constant bias and tangent planes from flat
/// normals: percentage-closer filtering's commonest unit.
#[derive(Clone, Copy, Debug, Default)]
pub struct BoxFilter;

impl Built for BoxFilter {
    const POINT: bool = false;
    const BILINEAR: bool = false;
    const BOX: bool = true;
    const JITTERED: bool = false;
    const BIAS_RANGE: bool = false;
    const SMOOTH_TANGENTS: bool = false;
}
