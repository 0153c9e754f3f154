//! Which depth-unit datapaths a light pass is built with.
//!
//! The traversal is specialised per datapath — single, single with ids
//! (visibility), dual, each with or without max-z culling — so that the
//! per-fragment loop carries no runtime choice. Each specialisation is its
//! own copy of the traversal: about 3 KB of Thumb-2 code, which a host
//! does not notice and a microcontroller's flash does. A pass built with
//! [`Every`] (the default) takes any [`LightPassConfig`], with the fastest
//! copies; a pass built with one datapath ([`SingleOnly`],
//! [`VisibilityOnly`], [`DualOnly`]) carries one copy of the traversal and
//! refuses any other configuration ([`ConfigError::NotBuilt`]) when it
//! starts. The maps, the tile summaries and the events are the same
//! either way.

use crate::config::{ConfigError, DepthUnit, LightPassConfig};

/// The datapaths a light pass is built with (compile-time constants: a
/// datapath not built is not in the program).
pub trait Datapaths {
    /// Single depth, no ids.
    const SINGLE: bool;
    /// Single depth with the id of the visible triangle.
    const VISIBILITY: bool;
    /// Dual depth.
    const DUAL: bool;
    /// With max-z culling.
    const CULLED: bool;
    /// Without max-z culling.
    const UNCULLED: bool;
    /// With max-z culling, a second copy of the traversal for tiles whose
    /// max is stale, which skips the comparison a fragment that counts the
    /// texels holding the max (nothing to count there). Without it the
    /// counting copy serves those tiles too, with the same results.
    const STALE_MAX_COPY: bool;

    /// Whether this build has the datapath `cfg` needs (`ids`: the pass
    /// keeps triangle ids).
    #[must_use]
    fn builds(cfg: &LightPassConfig, ids: bool) -> bool {
        let unit = match (cfg.unit, ids) {
            (DepthUnit::Single, false) => Self::SINGLE,
            (DepthUnit::Single, true) => Self::VISIBILITY,
            (DepthUnit::Dual, _) => Self::DUAL,
        };
        unit && if cfg.max_z_cull { Self::CULLED } else { Self::UNCULLED }
    }

    /// [`builds`](Self::builds) as a result.
    ///
    /// # Errors
    /// [`ConfigError::NotBuilt`] naming the datapath missing.
    fn check(cfg: &LightPassConfig, ids: bool) -> Result<(), ConfigError> {
        if Self::builds(cfg, ids) {
            Ok(())
        } else {
            Err(ConfigError::NotBuilt { unit: cfg.unit, ids, max_z_cull: cfg.max_z_cull })
        }
    }
}

/// Every datapath: a pass that takes any configuration.
#[derive(Clone, Copy, Debug, Default)]
pub struct Every;

impl Datapaths for Every {
    const SINGLE: bool = true;
    const VISIBILITY: bool = true;
    const DUAL: bool = true;
    const CULLED: bool = true;
    const UNCULLED: bool = true;
    const STALE_MAX_COPY: bool = true;
}

/// The single depth unit alone, with max-z culling or without.
#[derive(Clone, Copy, Debug, Default)]
pub struct SingleOnly<const MAX_Z_CULL: bool>;

impl<const MAX_Z_CULL: bool> Datapaths for SingleOnly<MAX_Z_CULL> {
    const SINGLE: bool = true;
    const VISIBILITY: bool = false;
    const DUAL: bool = false;
    const CULLED: bool = MAX_Z_CULL;
    const UNCULLED: bool = !MAX_Z_CULL;
    const STALE_MAX_COPY: bool = false;
}

/// The visibility unit alone (single depth and triangle ids), with max-z
/// culling or without.
#[derive(Clone, Copy, Debug, Default)]
pub struct VisibilityOnly<const MAX_Z_CULL: bool>;

impl<const MAX_Z_CULL: bool> Datapaths for VisibilityOnly<MAX_Z_CULL> {
    const SINGLE: bool = false;
    const VISIBILITY: bool = true;
    const DUAL: bool = false;
    const CULLED: bool = MAX_Z_CULL;
    const UNCULLED: bool = !MAX_Z_CULL;
    const STALE_MAX_COPY: bool = false;
}

/// The dual depth unit alone, with max-z culling or without.
#[derive(Clone, Copy, Debug, Default)]
pub struct DualOnly<const MAX_Z_CULL: bool>;

impl<const MAX_Z_CULL: bool> Datapaths for DualOnly<MAX_Z_CULL> {
    const SINGLE: bool = false;
    const VISIBILITY: bool = false;
    const DUAL: bool = true;
    const CULLED: bool = MAX_Z_CULL;
    const UNCULLED: bool = !MAX_Z_CULL;
    const STALE_MAX_COPY: bool = false;
}
