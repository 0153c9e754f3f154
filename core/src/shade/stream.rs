//! The camera pass streamed by tile: visibility and shading one screen tile
//! at a time, each tile's results handed to the caller as soon as they are
//! made, so that no buffer the size of the frame exists — the way a
//! tile-based renderer with on-chip tile memory (PixelFlow's, Talisman's
//! chunks) keeps a frame it never holds whole.
//!
//! ```text
//! for each tile: geometry again ─► visibility on the tile (a window of the image) ─► shade the tile ─► sink
//! ```
//!
//! The visibility unit draws each tile as a window of the whole image
//! ([`crate::RasterConfig::window`]), which rasterizes exactly the
//! fragments the whole image has there, and the shading unit shades the
//! tile's pixels at their places in the image ([`super::shade_rect`]): the
//! results are the full-frame pass's, bit for bit. The price is the
//! geometry, sent through the front end once per tile.

use crate::config::{ConfigError, DepthUnit, LightPassConfig};
use crate::depth::{DepthFormat, TileState};
use crate::front::setup::Setup;
use crate::grid::TileRect;
use crate::light_pass::{Datapaths, LightBuffers, LightPass, SubmitError};
use crate::probe::Probe;
use crate::raster::bin::Bin;
use crate::shadow::MapView;

use super::{PixelResult, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, ShadowUnit, TriangleSource, shade_rect};

/// The caller-owned memory of a camera pass streamed by tile: one tile of
/// everything, besides the setup stores. For a tile of `T × T` pixels:
/// `depth`, `ids` and `pixels` of `T²` entries, one tile summary and one
/// bin.
pub struct TileBuffers<'a, V: DepthFormat, const B: usize, R: PixelResult = Shaded> {
    /// The visibility unit's depth for one tile.
    pub depth: &'a mut [V::Texel],
    /// The visible triangle's id per pixel of one tile.
    pub ids: &'a mut [u32],
    /// One tile summary.
    pub state: &'a mut [TileState<V::Texel>],
    /// One bin.
    pub bins: &'a mut [Bin<B>],
    /// The visibility unit's triangle-setup store (any length in `1..=65536`).
    pub setups: &'a mut [Setup],
    /// The shading unit's setup store (any length; empty: none).
    pub shade_setups: &'a mut [ShadeSetup],
    /// One tile of results (the whole [`Shaded`] or the part kept), handed
    /// to the sink.
    pub pixels: &'a mut [R],
}

/// Why the streamed pass stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum StreamError {
    /// A configuration or a buffer the core refuses.
    Config(ConfigError),
    /// The geometry the caller drew.
    Submit(SubmitError),
}

impl core::fmt::Display for StreamError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Config(e) => write!(f, "{e}"),
            Self::Submit(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for StreamError {}

impl From<ConfigError> for StreamError {
    fn from(e: ConfigError) -> Self {
        Self::Config(e)
    }
}

impl From<SubmitError> for StreamError {
    fn from(e: SubmitError) -> Self {
        Self::Submit(e)
    }
}

/// The camera pass, tile by tile in row-major tile order: for each tile of
/// `vis.raster` (the camera image; its tile side is the streaming unit),
/// `draw` sends the scene's geometry to a visibility pass on that tile,
/// the shading unit shades it against `map`, and `sink` receives the
/// tile's rectangle and its results, row-major. `vis` must be a single
/// depth unit (and `D`, the datapaths its visibility pass is built with,
/// must have it: [`crate::light_pass::VisibilityOnly`] is all it needs);
/// `cfg`'s image size must be the raster's. The probe sees the
/// events of every tile's passes and is handed back.
///
/// # Errors
/// [`StreamError::Config`] for a configuration or a buffer of the wrong
/// size (checked before any tile is drawn); [`StreamError::Submit`] for
/// geometry `draw` could not send.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, its memory, its probe, and its two callers' ends")]
pub fn camera_pass_by_tile<V, F, S, U, R, P, D, const B: usize>(
    vis: LightPassConfig,
    cfg: &ShadeConfig,
    map: &MapView<'_, F>,
    scene: &S,
    unit: &U,
    buf: TileBuffers<'_, V, B, R>,
    mut probe: P,
    mut draw: impl FnMut(&mut LightPass<'_, V, P, B, D>) -> Result<(), SubmitError>,
    mut sink: impl FnMut(TileRect, &[R]),
) -> Result<P, StreamError>
where
    V: DepthFormat,
    F: DepthFormat,
    S: TriangleSource,
    U: ShadowUnit<F>,
    R: PixelResult,
    P: Probe,
    D: Datapaths,
{
    let raster = vis.raster;
    if vis.unit != DepthUnit::Single || [raster.width(), raster.height()] != [cfg.width, cfg.height] {
        return Err(ConfigError::Window { x0: 0, y0: 0, width: cfg.width, height: cfg.height }.into());
    }
    let side = raster.tile_size() as usize;
    let texels = side * side;
    for (buffer, expected, found) in [
        ("depth", texels, buf.depth.len()),
        ("ids", texels, buf.ids.len()),
        ("pixels", texels, buf.pixels.len()),
        ("tiles", 1, buf.state.len()),
        ("bins", 1, buf.bins.len()),
    ] {
        if expected != found {
            return Err(ConfigError::BufferLength { buffer, expected, found }.into());
        }
    }
    for t in 0..raster.tile_count() {
        let rect = raster.tile_rect(raster.tile_id(t));
        let window = raster.window(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0)?;
        let n = rect.area() as usize;
        let buffers = LightBuffers::<V, B> {
            z1: &mut buf.depth[..n],
            z2: &mut [],
            ids: &mut buf.ids[..n],
            tiles: &mut *buf.state,
            bins: &mut *buf.bins,
            setups: &mut *buf.setups,
        };
        let mut pass = LightPass::new(LightPassConfig { raster: window, ..vis }, buffers, probe)?;
        draw(&mut pass)?;
        probe = pass.finish();
        let (ids, pixels) = (&buf.ids[..n], &mut buf.pixels[..n]);
        shade_rect(&ShadeInputs { cfg, map, scene, unit }, rect, ids, pixels, buf.shade_setups, &mut probe)?;
        sink(rect, pixels);
    }
    Ok(probe)
}
