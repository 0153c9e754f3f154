//! Run the core's light pass over buffers owned here.

use glam::{Mat4, Vec3};
use umbra_core::bin::Bin;
use umbra_core::front_end::{self, Output};
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

/// Setup-store size of a pass whose probe ignores events: four setups a
/// tile, between 4096 (640 KB, within a core's cache) and
/// [`DEFAULT_SETUPS`] (ten MB, written and read back through memory). Each
/// time the store fills, every tile with work is resolved, so the store
/// grows with the tiles.
fn unwatched_setups(raster: &umbra_core::RasterConfig) -> usize {
    raster.tile_count().saturating_mul(4).clamp(4096, DEFAULT_SETUPS)
}

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
    let mut maps = LightMaps::cleared(config);
    let LightMaps { z1, z2, tiles, .. } = &mut maps;
    let probe = run::<F, P, B>(config, z1, z2, tiles, setups, probe, |pass| {
        for (draw, d) in draws.iter().enumerate() {
            pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
                .map_err(|source| LightError::Submit { draw, source })?;
        }
        Ok(())
    })?;
    Ok((maps, probe))
}

impl<T: Copy> LightMaps<T> {
    /// Maps of the right sizes for `config`, before the pass clears them.
    fn cleared(config: LightPassConfig) -> Self
    where
        T: Default,
    {
        let texels = config.raster.texel_count();
        let z2 = if config.unit == DepthUnit::Dual { texels } else { 0 };
        let tiles = config.raster.tile_count();
        Self {
            config,
            z1: vec![T::default(); texels],
            z2: vec![T::default(); z2],
            tiles: vec![TileState::cleared(T::default(), 0); tiles],
        }
    }
}

/// Run one light pass over the given maps (the pass clears them), with bins
/// and a setup store of its own: `feed` draws, then the pass is finished.
#[allow(clippy::too_many_arguments, reason = "the buffers of one pass")]
fn run<F: DepthFormat, P: Probe, const B: usize>(
    config: LightPassConfig,
    z1: &mut [F::Texel],
    z2: &mut [F::Texel],
    tiles: &mut [TileState<F::Texel>],
    setups: usize,
    probe: P,
    feed: impl FnOnce(&mut LightPass<'_, F, P, B>) -> Result<(), LightError>,
) -> Result<P, LightError> {
    let mut bins = vec![Bin::<B>::new(); config.raster.tile_count()];
    let mut store = vec![Setup::EMPTY; setups];
    let buffers = LightBuffers { z1, z2, ids: &mut [], tiles, bins: &mut bins, setups: &mut store };
    let mut pass = LightPass::<F, P, B>::new(config, buffers, probe)?;
    feed(&mut pass)?;
    Ok(pass.finish())
}

/// The setup store of one band: small enough to stay in cache (a band's
/// bins drain whenever it fills; the maps do not depend on its size).
const BAND_SETUPS: usize = 8192;

/// Triangles the front end sets up in one parallel job.
const FRONT_END_RUN: usize = 2048;

/// The light pass on every core of the current rayon pool, as parallel
/// hardware would run it: the front end ([`umbra_core::front_end`]) sets up
/// runs of triangles in parallel, in submission order, and sorts each setup
/// into the bands of tile rows it reaches; then the bands are rasterized in
/// parallel, each a window of the target
/// ([`umbra_core::RasterConfig::window`]) with its own bins, setup store and
/// tiles, storing its setups moved into its window
/// ([`LightPass::draw_setup_from`]). The maps are exactly those of [`render`], on
/// any number of threads.
///
/// # Errors
/// See [`LightError`].
pub fn render_bands<F: DepthFormat>(
    config: LightPassConfig,
    draws: &[Draw<'_>],
) -> Result<LightMaps<F::Texel>, LightError> {
    use rayon::prelude::*;
    let r = config.raster;
    let mut jobs = Vec::new();
    let mut first_id = 0u32;
    for (draw, d) in draws.iter().enumerate() {
        front_end::check_indices(d.positions.len(), d.triangles)
            .map_err(|source| LightError::Submit { draw, source })?;
        for (k, run) in d.triangles.chunks(FRONT_END_RUN).enumerate() {
            #[allow(clippy::cast_possible_truncation, reason = "ids wrap, as the light pass numbers them")]
            jobs.push((d, run, first_id.wrapping_add((k * FRONT_END_RUN) as u32)));
        }
        #[allow(clippy::cast_possible_truncation, reason = "ids wrap, as the light pass numbers them")]
        let n = d.triangles.len() as u32;
        first_id = first_id.wrapping_add(n);
    }
    // Narrow bands (up to 32 a thread, one tile row at least), so that a
    // thread done with light bands takes over heavy ones: a band costs only
    // its bins, and reads only the setups that reach it.
    let (across, down) = r.tiles();
    let threads = u32::try_from(rayon::current_num_threads()).unwrap_or(1);
    let bands = threads.saturating_mul(32).clamp(1, down);
    let t = r.tile_size();
    let rows: Vec<(u32, u32)> = (0..bands)
        .map(|b| (b * down / bands * t, ((b + 1) * down / bands * t).min(r.height())))
        .filter(|(y0, y1)| y1 > y0)
        .collect();
    let windows = rows.iter().map(|&(y0, y1)| r.window(0, y0, r.width(), y1 - y0)).collect::<Result<Vec<_>, _>>()?;
    // The band of each tile row (bands are whole tile rows).
    let band_of_row: Vec<usize> = (0..down).map(|ty| rows.partition_point(|&(_, y1)| y1 <= ty * t)).collect();
    let band_of = |y: u32| band_of_row.get((y >> r.tile_shift()) as usize).copied().unwrap_or(rows.len());
    // The front end, in parallel: each job's setups, in order, and for each
    // band the indices of those that reach it (each band moves its own into
    // its window when it draws them).
    let pieces: Vec<(Vec<Setup>, Vec<Vec<u32>>)> = jobs
        .par_iter()
        .map(|&(d, run, id)| {
            let mut setups = Vec::with_capacity(run.len());
            let mut by_band = vec![Vec::new(); rows.len()];
            front_end::mesh::<F>(&r, d.positions, run, &d.transform, d.cull, id, &mut |o| {
                if let Output::Setup(s) = o {
                    // A job holds at most FRONT_END_RUN setups.
                    let k = u32::try_from(setups.len()).unwrap_or(u32::MAX);
                    for bucket in by_band.iter_mut().take(band_of(s.bbox.y1 - 1) + 1).skip(band_of(s.bbox.y0)) {
                        bucket.push(k);
                    }
                    setups.push(*s);
                }
            });
            (setups, by_band)
        })
        .collect();
    // Each band draws into its own rows of the maps and its own tiles.
    let mut maps = LightMaps::cleared(config);
    let mut jobs = Vec::with_capacity(rows.len());
    let (mut z1, mut z2, mut tiles) = (&mut maps.z1[..], &mut maps.z2[..], &mut maps.tiles[..]);
    let (width, dual) = (r.width() as usize, !z2.is_empty());
    for (band, &(y0, y1)) in rows.iter().enumerate() {
        let texels = (y1 - y0) as usize * width;
        let (a, rest) = core::mem::take(&mut z1).split_at_mut(texels);
        z1 = rest;
        let (b, rest) = core::mem::take(&mut z2).split_at_mut(if dual { texels } else { 0 });
        z2 = rest;
        let (c, rest) = core::mem::take(&mut tiles)
            .split_at_mut(((y1 - y0) / t + u32::from((y1 - y0) % t > 0)) as usize * across as usize);
        tiles = rest;
        jobs.push((band, a, b, c));
    }
    jobs.into_par_iter()
        .map(|(band, z1, z2, tiles)| {
            let own = || {
                pieces.iter().flat_map(move |(setups, by_band)| {
                    by_band.get(band).into_iter().flatten().filter_map(|&k| setups.get(k as usize))
                })
            };
            let store = own().count().clamp(1, BAND_SETUPS);
            let (window, y0) = (windows[band], rows[band].0);
            let band = LightPassConfig { raster: window, ..config };
            run::<F, _, DEFAULT_BIN_CAPACITY>(band, z1, z2, tiles, store, umbra_core::NoProbe, |pass| {
                own().for_each(|s| pass.draw_setup_from(s, [0, y0]));
                Ok(())
            })
            .map(|_| ())
        })
        .collect::<Result<(), LightError>>()?;
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
    // A setup store as large as the scene (at most the bins' reach); a pass
    // whose events no one counts keeps its store in cache instead.
    let triangles: usize = draws.iter().map(|d| d.triangles.len()).sum();
    let most = if P::EVENTS { DEFAULT_SETUPS } else { unwatched_setups(&config.raster) };
    render_with::<F, P, DEFAULT_BIN_CAPACITY>(config, draws, triangles.clamp(1, most), probe)
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
