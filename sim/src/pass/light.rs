//! Run the core's light pass over buffers owned here.

use umbra_core::depth::Texel;
use umbra_core::front::setup::Setup;
use umbra_core::front::vertex::{CACHE_ENTRIES, VertexCache};
use umbra_core::front::{self, Output};
use umbra_core::raster::bin::Bin;
use umbra_core::{DepthFormat, DepthFormatKind, DepthUnit, LightBuffers, LightPass, LightPassConfig, Probe, TileState};

use super::PassError;
use crate::base::maps::with_format;
pub use crate::world::scene::Draw;

/// Bin capacity the simulator uses unless told otherwise: bins live in
/// memory, so they are deep (a bin of 2-byte entries is 512 bytes).
pub const DEFAULT_BIN_CAPACITY: usize = 256;
/// Setup-store size the simulator uses unless told otherwise: the most the
/// bins can address, so a scene of up to 64k triangles is captured whole
/// before any tile is rasterized.
pub(crate) const DEFAULT_SETUPS: usize = umbra_core::raster::bin::MAX_SETUPS;

/// Setup-store size of a pass whose probe ignores events: four setups a
/// tile, between 4096 (640 KB, within a core's cache) and
/// [`DEFAULT_SETUPS`] (ten MB, written and read back through memory). Each
/// time the store fills, every tile with work is resolved, so the store
/// grows with the tiles.
fn unwatched_setups(raster: &umbra_core::RasterConfig) -> usize {
    raster.tile_count().saturating_mul(4).clamp(4096, DEFAULT_SETUPS)
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

/// How a light pass runs: the one options type of [`render`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightOptions {
    /// Entries of the setup store. `None`: as large as the scene, at most
    /// the bins' reach (`DEFAULT_SETUPS`); for a pass whose probe ignores
    /// events, a store that stays in cache instead (the maps do not depend
    /// on its size, only the events do).
    pub setups: Option<usize>,
    /// Run on every core of the current rayon pool, in bands of tile rows
    /// (see [`render`]). A banded pass reports no events, so it takes only
    /// a probe that ignores them, and its own setup stores.
    pub bands: bool,
    /// Finish each draw before the next, as an immediate-mode machine does
    /// (the maps are the same bits; the events come draw by draw).
    pub per_draw: bool,
}

impl LightOptions {
    /// The pass in bands on every core.
    pub const BANDS: Self = Self { setups: None, bands: true, per_draw: false };

    /// A serial pass with a setup store of `setups` entries.
    #[must_use]
    pub const fn with_setups(setups: usize) -> Self {
        Self { setups: Some(setups), bands: false, per_draw: false }
    }
}

/// The light pass of `draws` into `frame` (its maps, bins and setup stores,
/// kept from one pass to the next: see [`LightFrame`]), run as `options`
/// says, reporting to `probe`. The maps are the frame's until its next pass.
///
/// A banded pass runs the front end ([`umbra_core::front`]) on runs of
/// triangles in parallel, in submission order, and sorts each setup into
/// the bands of tile rows it reaches; then the bands are rasterized in
/// parallel, each a window of the target
/// ([`umbra_core::RasterConfig::window`]) with its own bins, setup store
/// and tiles, storing its setups moved into its window
/// ([`LightPass::draw_setup_from`]). Its maps are exactly those of a serial
/// pass, on any number of threads: the same texels and tile bounds (each
/// tile's count of stores follows its band's own flushes).
///
/// # Errors
/// See [`PassError`]; [`PassError::BandsWatched`] for a banded pass whose
/// probe counts events.
pub fn render<'f, F: DepthFormat, P: Probe, const B: usize>(
    frame: &'f mut LightFrame<F::Texel, B>,
    config: LightPassConfig,
    draws: &[Draw<'_>],
    options: LightOptions,
    probe: P,
) -> Result<(&'f LightMaps<F::Texel>, P), PassError> {
    let LightFrame { maps, pass, jobs, bands } = frame;
    let maps = maps.get_or_insert_with(|| LightMaps::empty(config));
    let probe = draw_into::<F, P, B>(maps, pass, jobs, bands, config, draws, options, probe)?;
    Ok((maps, probe))
}

impl<T: Texel> LightMaps<T> {
    /// The maps of one light pass ([`render`]) into new buffers.
    ///
    /// # Errors
    /// See [`render`].
    pub fn draw<F: DepthFormat<Texel = T>, P: Probe>(
        config: LightPassConfig,
        draws: &[Draw<'_>],
        options: LightOptions,
        probe: P,
    ) -> Result<(Self, P), PassError> {
        let mut maps = Self::empty(config);
        let (mut pass, mut jobs, mut bands) = (PassScratch::<DEFAULT_BIN_CAPACITY>::new(), Vec::new(), Vec::new());
        let probe = draw_into::<F, P, DEFAULT_BIN_CAPACITY>(
            &mut maps, &mut pass, &mut jobs, &mut bands, config, draws, options, probe,
        )?;
        Ok((maps, probe))
    }
}

/// The pass of [`render`] into given maps and scratch.
#[allow(clippy::too_many_arguments, reason = "the buffers of one pass")]
fn draw_into<F: DepthFormat, P: Probe, const B: usize>(
    maps: &mut LightMaps<F::Texel>,
    pass: &mut PassScratch<B>,
    jobs: &mut Vec<JobScratch>,
    bands: &mut Vec<PassScratch<B>>,
    config: LightPassConfig,
    draws: &[Draw<'_>],
    options: LightOptions,
    probe: P,
) -> Result<P, PassError> {
    if options.bands {
        if P::EVENTS {
            return Err(PassError::BandsWatched);
        }
        bands_into::<F, B>(maps, jobs, bands, config, draws)?;
        return Ok(probe);
    }
    let setups = options.setups.unwrap_or_else(|| store_size::<P>(&config, draws));
    let kept = maps.resize(config);
    let LightMaps { z1, z2, tiles, .. } = maps;
    run::<F, P, B>(config, kept, z1, z2, tiles, pass, setups, probe, |pass| {
        for (draw, d) in draws.iter().enumerate() {
            pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
                .map_err(|source| PassError::Submit { draw, source })?;
            if options.per_draw {
                pass.flush();
            }
        }
        Ok(())
    })
}

impl<T: Copy> LightMaps<T> {
    /// Maps of no size, for [`LightMaps::resize`] to fit.
    const fn empty(config: LightPassConfig) -> Self {
        Self { config, z1: Vec::new(), z2: Vec::new(), tiles: Vec::new() }
    }

    /// Fit the maps to `config` (the pass clears them): nothing to do at
    /// the sizes they have, new zeroed pages (not written twice) otherwise.
    /// Whether they are kept: the last pass drew them with this
    /// configuration, so their tile summaries describe them and the pass
    /// need clear only the tiles it wrote ([`LightPass::new_kept`]).
    fn resize(&mut self, config: LightPassConfig) -> bool
    where
        T: Default,
    {
        fn fit<V: Clone>(v: &mut Vec<V>, len: usize, value: V) -> bool {
            let kept = v.len() == len;
            if !kept {
                *v = vec![value; len];
            }
            kept
        }
        let texels = config.raster.texel_count();
        let same = self.config == config;
        self.config = config;
        let z1 = fit(&mut self.z1, texels, T::default());
        let z2 = fit(&mut self.z2, if config.unit == DepthUnit::Dual { texels } else { 0 }, T::default());
        let tiles = fit(&mut self.tiles, config.raster.tile_count(), TileState::cleared(T::default(), 0));
        same && z1 && z2 && tiles
    }
}

/// The bins and setup store of one pass (or one band).
#[derive(Debug, Default)]
struct PassScratch<const B: usize> {
    bins: Vec<Bin<B>>,
    store: Vec<Setup>,
}

impl<const B: usize> PassScratch<B> {
    const fn new() -> Self {
        Self { bins: Vec::new(), store: Vec::new() }
    }
}

/// One front-end job of the banded pass: its setups, in order, and for
/// each band the indices of those that reach it.
#[derive(Debug, Default)]
struct JobScratch {
    setups: Vec<Setup>,
    by_band: Vec<Vec<u32>>,
}

/// What the light pass keeps from one pass to the next, as hardware keeps
/// its memory: the maps, the bins and the setup store, and for a banded
/// pass ([`LightOptions::bands`]) each front-end job's setups and each band's bins and
/// store. A pass at sizes the frame has drawn before allocates nothing, so
/// it touches no fresh pages.
#[derive(Debug)]
pub struct LightFrame<T, const B: usize = DEFAULT_BIN_CAPACITY> {
    maps: Option<LightMaps<T>>,
    pass: PassScratch<B>,
    jobs: Vec<JobScratch>,
    bands: Vec<PassScratch<B>>,
}

impl<T, const B: usize> LightFrame<T, B> {
    /// An empty frame: its first pass allocates.
    #[must_use]
    pub const fn new() -> Self {
        Self { maps: None, pass: PassScratch::new(), jobs: Vec::new(), bands: Vec::new() }
    }

    /// The maps of the last pass: none before the first, and whatever it
    /// left after a pass that failed.
    #[must_use]
    pub const fn maps(&self) -> Option<&LightMaps<T>> {
        self.maps.as_ref()
    }
}

impl<T, const B: usize> Default for LightFrame<T, B> {
    fn default() -> Self {
        Self::new()
    }
}

/// Run one light pass over the given maps (the pass clears them: the
/// tiles the last pass wrote, when they are `kept`), with the bins and a
/// setup store of `setups` entries from `scratch`: `feed` draws, then the
/// pass is finished.
#[allow(clippy::too_many_arguments, reason = "the buffers of one pass")]
fn run<F: DepthFormat, P: Probe, const B: usize>(
    config: LightPassConfig,
    kept: bool,
    z1: &mut [F::Texel],
    z2: &mut [F::Texel],
    tiles: &mut [TileState<F::Texel>],
    scratch: &mut PassScratch<B>,
    setups: usize,
    probe: P,
    feed: impl FnOnce(&mut LightPass<'_, F, P, B>) -> Result<(), PassError>,
) -> Result<P, PassError> {
    // The pass clears both.
    scratch.bins.resize(config.raster.tile_count(), Bin::new());
    scratch.store.resize(setups, Setup::EMPTY);
    let PassScratch { bins, store } = scratch;
    let buffers = LightBuffers { z1, z2, ids: &mut [], tiles, bins, setups: store };
    let mut pass = if kept {
        LightPass::<F, P, B>::new_kept(config, buffers, probe)?
    } else {
        LightPass::<F, P, B>::new(config, buffers, probe)?
    };
    feed(&mut pass)?;
    Ok(pass.finish())
}

/// The setup store of one band: small enough to stay in cache (a band's
/// bins drain whenever it fills; the maps do not depend on its size).
const BAND_SETUPS: usize = 8192;

/// Triangles the front end sets up in one parallel job.
const FRONT_END_RUN: usize = 2048;

/// The banded pass into given maps and scratch.
fn bands_into<F: DepthFormat, const B: usize>(
    maps: &mut LightMaps<F::Texel>,
    job_scratch: &mut Vec<JobScratch>,
    band_scratch: &mut Vec<PassScratch<B>>,
    config: LightPassConfig,
    draws: &[Draw<'_>],
) -> Result<(), PassError> {
    use rayon::prelude::*;
    let r = config.raster;
    let mut jobs = Vec::new();
    let mut first_id = 0u32;
    for (draw, d) in draws.iter().enumerate() {
        front::check_indices(d.positions.len(), d.triangles).map_err(|source| PassError::Submit { draw, source })?;
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
    job_scratch.resize_with(jobs.len(), JobScratch::default);
    job_scratch.par_iter_mut().zip(&jobs).for_each(|(JobScratch { setups, by_band }, &(d, run, id))| {
        setups.clear();
        by_band.resize_with(rows.len(), Vec::new);
        by_band.iter_mut().for_each(Vec::clear);
        let cache = &mut VertexCache::<CACHE_ENTRIES>::new();
        front::mesh::<F, CACHE_ENTRIES>(&r, d.positions, run, &d.transform, d.cull, id, cache, &mut |o| {
            if let Output::Setup(s) = o {
                // A job holds at most FRONT_END_RUN setups.
                let k = u32::try_from(setups.len()).unwrap_or(u32::MAX);
                for bucket in by_band.iter_mut().take(band_of(s.bbox.y1 - 1) + 1).skip(band_of(s.bbox.y0)) {
                    bucket.push(k);
                }
                setups.push(*s);
            }
        });
    });
    let pieces = &job_scratch[..];
    // Each band draws into its own rows of the maps and its own tiles (a
    // band of whole tile rows: its tiles' summaries are the map's).
    let kept = maps.resize(config);
    band_scratch.resize_with(rows.len(), PassScratch::new);
    let mut jobs = Vec::with_capacity(rows.len());
    let (mut z1, mut z2, mut tiles) = (&mut maps.z1[..], &mut maps.z2[..], &mut maps.tiles[..]);
    let (width, dual) = (r.width() as usize, !z2.is_empty());
    for ((band, &(y0, y1)), scratch) in rows.iter().enumerate().zip(band_scratch.iter_mut()) {
        let texels = (y1 - y0) as usize * width;
        let (a, rest) = core::mem::take(&mut z1).split_at_mut(texels);
        z1 = rest;
        let (b, rest) = core::mem::take(&mut z2).split_at_mut(if dual { texels } else { 0 });
        z2 = rest;
        let (c, rest) = core::mem::take(&mut tiles)
            .split_at_mut(((y1 - y0) / t + u32::from((y1 - y0) % t > 0)) as usize * across as usize);
        tiles = rest;
        jobs.push((band, a, b, c, scratch));
    }
    jobs.into_par_iter()
        .map(|(band, z1, z2, tiles, scratch)| {
            let own = || {
                pieces.iter().flat_map(move |JobScratch { setups, by_band }| {
                    by_band.get(band).into_iter().flatten().filter_map(|&k| setups.get(k as usize))
                })
            };
            let store = own().count().clamp(1, BAND_SETUPS);
            let (window, y0) = (windows[band], rows[band].0);
            let band = LightPassConfig { raster: window, ..config };
            run::<F, _, B>(band, kept, z1, z2, tiles, scratch, store, umbra_core::NoProbe, |pass| {
                own().for_each(|s| pass.draw_setup_from(s, [0, y0]));
                Ok(())
            })
            .map(|_| ())
        })
        .collect::<Result<(), PassError>>()?;
    debug_assert_eq!(maps.tiles.len(), across as usize * down as usize);
    Ok(())
}

/// The setup store of [`render`]: as large as the scene (at most the bins'
/// reach); a pass whose events no one counts keeps its store in cache
/// instead.
fn store_size<P: Probe>(config: &LightPassConfig, draws: &[Draw<'_>]) -> usize {
    let triangles: usize = draws.iter().map(|d| d.triangles.len()).sum();
    let most = if P::EVENTS { DEFAULT_SETUPS } else { unwatched_setups(&config.raster) };
    triangles.clamp(1, most)
}

/// A light map no fragment reached: the view it was drawn from sees no
/// triangle between near and far (or sees them only smaller than a
/// texel's centre). Every path that draws a map — a render, a study row,
/// `umbra depth` — refuses such a map with this one message, naming the
/// view (`lights[0]`, `--matrix`) and, where the view has them, its near
/// and far planes.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}: the map receives no fragment: no triangle lies in the view between {}", .view, between(*.planes))]
pub struct EmptyMap {
    /// The view, as the user gave it.
    pub view: String,
    /// Its near and far planes, where it has them (a light; not a matrix).
    pub planes: Option<(f32, f32)>,
}

/// The planes a message names.
fn between(planes: Option<(f32, f32)>) -> String {
    planes.map_or_else(|| "near and far".to_owned(), |(near, far)| format!("near {near:e} and far {far}"))
}

impl EmptyMap {
    /// `Err` when the light pass whose events `totals` counted drew no
    /// fragment.
    ///
    /// # Errors
    /// [`EmptyMap`] naming `view` and its `planes`.
    pub fn check(totals: &umbra_core::probe::Totals, view: &str, planes: Option<(f32, f32)>) -> Result<(), Self> {
        if totals.fragments == 0 { Err(Self { view: view.to_owned(), planes }) } else { Ok(()) }
    }
}

/// Maps of a format chosen at run time, texels widened to their raw `u32` bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawMaps {
    /// The depth format.
    pub format: DepthFormatKind,
    /// The maps.
    pub maps: LightMaps<u32>,
}

impl RawMaps {
    /// The buffers the pass kept: `z1`, and `z2` when the unit is dual.
    #[must_use]
    pub fn buffers(&self) -> Vec<&[u32]> {
        [&self.maps.z1[..], &self.maps.z2[..]].into_iter().filter(|b| !b.is_empty()).collect()
    }

    /// The maps stored, by name: `z1`, and `z2` when the unit is dual, each
    /// of the raster's `width × height` texels; none when the pass stored
    /// no tile: shadow volumes draw no map (their one far texel stands for
    /// it), and a light pass that drew anything stores the tiles it drew.
    #[must_use]
    pub fn stored(&self) -> Vec<(&'static str, &[u32])> {
        let r = self.maps.config.raster;
        let texels = u64::from(r.width()) * u64::from(r.height());
        let drawn = self.maps.tiles.iter().any(|t| t.stores > 0);
        [("z1", &self.maps.z1[..]), ("z2", &self.maps.z2[..])]
            .into_iter()
            .filter(|(_, b)| drawn && !b.is_empty() && b.len() as u64 == texels)
            .collect()
    }
}

/// The same maps with every texel widened to its raw `u32` bits.
pub(crate) fn widen<T: Texel>(m: &LightMaps<T>) -> LightMaps<u32> {
    let raw = |v: &[T]| v.iter().map(|&t| T::to_raw(t)).collect();
    LightMaps {
        config: m.config,
        z1: raw(&m.z1),
        z2: raw(&m.z2),
        tiles: m.tiles.iter().map(|t| t.map(T::to_raw)).collect(),
    }
}

impl RawMaps {
    /// A light pass ([`render`], serial, into new buffers) in a format
    /// chosen at run time.
    ///
    /// # Errors
    /// See [`PassError`].
    pub fn render<P: Probe>(
        config: LightPassConfig,
        format: DepthFormatKind,
        draws: &[Draw<'_>],
        probe: P,
    ) -> Result<(Self, P), PassError> {
        fn pass<F: DepthFormat, P: Probe>(
            config: LightPassConfig,
            draws: &[Draw<'_>],
            probe: P,
        ) -> Result<(LightMaps<u32>, P), PassError> {
            let (maps, probe) = LightMaps::draw::<F, P>(config, draws, LightOptions::default(), probe)?;
            Ok((widen(&maps), probe))
        }
        let (maps, probe) = with_format!(format, F => pass::<F, P>(config, draws, probe)?);
        Ok((Self { format, maps }, probe))
    }
}
