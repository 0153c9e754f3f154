//! Run the core's light pass over buffers owned here.

use glam::{Mat4, Vec3};
use umbra_core::bin::Bin;
use umbra_core::setup::Setup;
use umbra_core::{
    ConfigError, CullMode, D16, D24, DepthFormat, DepthFormatKind, DepthUnit, F32, LightBuffers, LightPass,
    LightPassConfig, Probe, SubmitError, TileState,
};

/// Bin capacity the simulator uses unless told otherwise: bins live in
/// memory, so they are deep (a bin of 2-byte entries is 512 bytes).
pub const DEFAULT_BIN_CAPACITY: usize = 256;
/// Setup-store size the simulator uses unless told otherwise: the most the
/// bins can address, so a scene of up to 64k triangles is captured whole
/// before any tile is rasterized.
pub const DEFAULT_SETUPS: usize = umbra_core::bin::MAX_SETUPS;

/// One draw call: a mesh, its transform to light clip space and its cull mode.
#[derive(Clone, Copy, Debug)]
pub struct Draw<'a> {
    /// Object-space positions.
    pub positions: &'a [Vec3],
    /// Vertex indices, three per triangle.
    pub triangles: &'a [[u32; 3]],
    /// Object space to light clip space.
    pub transform: Mat4,
    /// Which facing to discard.
    pub cull: CullMode,
}

/// The maps of one light pass.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LightMaps<T> {
    /// The configuration they were rendered with.
    pub config: LightPassConfig,
    /// Nearest depth, row-major.
    pub z1: Vec<T>,
    /// Second-nearest depth (empty unless the unit is dual).
    pub z2: Vec<T>,
    /// Per-tile summaries, row-major.
    pub tiles: Vec<TileState<T>>,
}

/// Why a light pass could not run.
#[derive(Debug, thiserror::Error)]
pub enum LightError {
    /// The configuration or a buffer is unusable.
    #[error("light pass configuration: {0}")]
    Config(#[from] ConfigError),
    /// A draw call is malformed.
    #[error("draw call {draw}: {source}")]
    Submit {
        /// Which draw call.
        draw: usize,
        /// What is wrong with it.
        source: SubmitError,
    },
}

/// Render the light pass of `draws` in format `F` with bin capacity `B` and a
/// setup store of `setups` entries.
///
/// # Errors
/// See [`LightError`].
pub fn render_with<F: DepthFormat, P: Probe, const B: usize>(
    config: LightPassConfig,
    draws: &[Draw<'_>],
    setups: usize,
    probe: P,
) -> Result<(LightMaps<F::Texel>, P), LightError> {
    let r = config.raster;
    let texels = r.texel_count();
    let mut z1 = vec![F::FAR; texels];
    let mut z2 = vec![F::FAR; if config.unit == DepthUnit::Dual { texels } else { 0 }];
    let mut tiles = vec![TileState::cleared(F::FAR, 0); r.tile_count()];
    let mut bins = vec![Bin::<B>::new(); r.tile_count()];
    let mut store = vec![Setup::EMPTY; setups];
    let buffers =
        LightBuffers { z1: &mut z1, z2: &mut z2, ids: &mut [], tiles: &mut tiles, bins: &mut bins, setups: &mut store };
    let mut pass = LightPass::<F, P, B>::new(config, buffers, probe)?;
    for (draw, d) in draws.iter().enumerate() {
        pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
            .map_err(|source| LightError::Submit { draw, source })?;
    }
    let probe = pass.finish();
    Ok((LightMaps { config, z1, z2, tiles }, probe))
}

/// The light pass on bands of tile rows in parallel (rayon; one band per
/// thread of the current pool, at most one per tile row): each band is a
/// window of the target ([`umbra_core::RasterConfig::window`]) with its own
/// bins, setup store and tiles, so the maps are exactly those of
/// [`render`], on any number of threads.
///
/// # Errors
/// See [`LightError`].
pub fn render_bands<F: DepthFormat>(
    config: LightPassConfig,
    draws: &[Draw<'_>],
) -> Result<LightMaps<F::Texel>, LightError> {
    use rayon::prelude::*;
    let r = config.raster;
    let (across, down) = r.tiles();
    let bands = u32::try_from(rayon::current_num_threads()).unwrap_or(1).clamp(1, down);
    let t = r.tile_size();
    let rows: Vec<(u32, u32)> = (0..bands)
        .map(|b| (b * down / bands * t, ((b + 1) * down / bands * t).min(r.height())))
        .filter(|(y0, y1)| y1 > y0)
        .collect();
    let parts = rows
        .par_iter()
        .map(|&(y0, y1)| {
            let raster = r.window(0, y0, r.width(), y1 - y0)?;
            render::<F, _>(LightPassConfig { raster, ..config }, draws, umbra_core::NoProbe).map(|(m, _)| m)
        })
        .collect::<Result<Vec<_>, LightError>>()?;
    let mut maps = LightMaps { config, z1: Vec::new(), z2: Vec::new(), tiles: Vec::new() };
    for part in parts {
        maps.z1.extend(part.z1);
        maps.z2.extend(part.z2);
        maps.tiles.extend(part.tiles);
    }
    debug_assert_eq!(maps.tiles.len(), across as usize * down as usize);
    Ok(maps)
}

/// Render with the default bin capacity and setup store.
///
/// # Errors
/// See [`LightError`].
pub fn render<F: DepthFormat, P: Probe>(
    config: LightPassConfig,
    draws: &[Draw<'_>],
    probe: P,
) -> Result<(LightMaps<F::Texel>, P), LightError> {
    // A setup store as large as the scene (at most the bins' reach).
    let triangles: usize = draws.iter().map(|d| d.triangles.len()).sum();
    render_with::<F, P, DEFAULT_BIN_CAPACITY>(config, draws, triangles.clamp(1, DEFAULT_SETUPS), probe)
}

/// Maps of a format chosen at run time, texels widened to their raw `u32` bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawMaps {
    /// The depth format.
    pub format: DepthFormatKind,
    /// The maps.
    pub maps: LightMaps<u32>,
}

/// The same maps with every texel widened to its raw `u32` bits.
pub(crate) fn widen<T: umbra_core::depth::Texel>(m: LightMaps<T>) -> LightMaps<u32> {
    let raw = |v: Vec<T>| v.into_iter().map(T::to_raw).collect();
    LightMaps {
        config: m.config,
        z1: raw(m.z1),
        z2: raw(m.z2),
        tiles: m.tiles.into_iter().map(|t| t.map(T::to_raw)).collect(),
    }
}

/// Render in a format chosen at run time.
///
/// # Errors
/// See [`LightError`].
pub fn render_raw<P: Probe>(
    config: LightPassConfig,
    format: DepthFormatKind,
    draws: &[Draw<'_>],
    probe: P,
) -> Result<(RawMaps, P), LightError> {
    let (maps, probe) = match format {
        DepthFormatKind::D16 => render::<D16, P>(config, draws, probe).map(|(m, p)| (widen(m), p))?,
        DepthFormatKind::D24 => render::<D24, P>(config, draws, probe).map(|(m, p)| (widen(m), p))?,
        DepthFormatKind::F32 => render::<F32, P>(config, draws, probe).map(|(m, p)| (widen(m), p))?,
    };
    Ok((RawMaps { format, maps }, probe))
}

/// The depth a raw texel of `format` stands for, in `[0, 1]`.
#[must_use]
pub fn raw_depth(format: DepthFormatKind, raw: u32) -> f64 {
    match format {
        DepthFormatKind::D16 => D16::unquantize(u16::try_from(raw).unwrap_or(u16::MAX)),
        DepthFormatKind::D24 => D24::unquantize(raw),
        DepthFormatKind::F32 => F32::unquantize(raw),
    }
}

/// The clear (far) value of `format`, as raw bits.
#[must_use]
pub fn raw_far(format: DepthFormatKind) -> u32 {
    match format {
        DepthFormatKind::D16 => u32::from(D16::FAR),
        DepthFormatKind::D24 => D24::FAR,
        DepthFormatKind::F32 => F32::FAR,
    }
}
