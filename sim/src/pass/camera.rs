//! The camera pass over owned buffers: the visibility unit with the camera's
//! matrix, then the shading unit against a light pass's maps.

use core::ops::Range;

use glam::Mat4;
use umbra_core::front::setup::Setup;
use umbra_core::raster::bin::Bin;
use umbra_core::shade::{
    Normals, PixelResult, SceneTriangle, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, ShadowUnit, shade_rect,
    shade_with,
};

use umbra_core::shadow::{MapView, Shadow, ShadowConfig};
use umbra_core::{
    CullMode, D24, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, NO_TRIANGLE, Probe, RasterConfig,
    TileRect, TileState,
};

use super::PassError;
use crate::base::maps::Tiling;
use crate::pass::light::{DEFAULT_BIN_CAPACITY, DEFAULT_SETUPS, LightMaps};
use crate::world::occluders::Lit;
use crate::world::scene::Scene;

/// What the camera pass produced.
#[derive(Clone, Debug)]
pub struct CameraImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// One result per pixel, row-major.
    pub pixels: Vec<Shaded>,
    /// The camera's view-projection the image was seen through.
    pub camera: Mat4,
}

/// How a camera pass runs: the one options type of [`render`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The shadow unit's test, bias and filter.
    pub shadow: ShadowConfig,
    /// Wang & Molnar's virtual samples (second depth only).
    pub virtual_samples: bool,
    /// The visibility unit's tiles and draw order.
    pub tiling: Tiling,
}

/// What the visibility unit decided besides its buffers: the camera's
/// matrix and target.
#[derive(Clone, Copy, Debug)]
pub struct Visibility {
    /// World to camera clip space.
    pub camera: Mat4,
    /// The camera target.
    pub raster: RasterConfig,
}

/// Entries of the shading unit's setup store: more than the triangles a
/// row of a 1920-pixel image of the bundled scenes crosses, so that each
/// visible triangle is set up about once a pass; a frame whose rows cross
/// more triangles gets more.
pub const SHADE_SETUPS: usize = 256;

/// Entries of the shading unit's setup store for a visibility pass's
/// `ids`, rows of `width`: twice the most triangles a row crosses (its
/// runs of one id), a power of two from [`SHADE_SETUPS`] to 8192, so that
/// each visible triangle is set up about once a band of rows however small
/// the triangles (a million-triangle city at 1920×1080 crosses thousands a
/// row), and a scene that needs no more keeps a store no longer to empty.
/// The results and events do not depend on it, only the work.
#[must_use]
pub(crate) fn shade_setups(ids: &[u32], width: u32) -> usize {
    let runs = |row: &[u32]| 1 + row.windows(2).filter(|w| w[0] != w[1]).count();
    let most = ids.chunks(width.max(1) as usize).map(runs).max().unwrap_or(1);
    (2 * most).next_power_of_two().clamp(SHADE_SETUPS, 8192)
}

/// The camera pass's memory, kept from frame to frame as hardware keeps its
/// framebuffer: the visibility unit's depth, ids, tile states, bins and
/// setup store, the shading unit's setup store, and the shaded pixels. A
/// pass into a frame it has drawn at the same size before allocates nothing
/// (the passes clear what they use).
#[derive(Clone, Debug, Default)]
pub struct CameraFrame {
    z: Vec<u32>,
    ids: Vec<u32>,
    tiles: Vec<TileState<u32>>,
    bins: Vec<Bin<DEFAULT_BIN_CAPACITY>>,
    store: Vec<Setup>,
    shade_setups: Vec<ShadeSetup>,
    size: (u32, u32),
    /// The camera's view-projection of the last visibility pass.
    camera: Mat4,
    /// The configuration the visibility buffers were last drawn with: a
    /// pass with the same one clears only the tiles that pass wrote.
    drawn: Option<LightPassConfig>,
    /// The shaded pixels of the last pass, row-major.
    pub pixels: Vec<Shaded>,
}

impl CameraFrame {
    /// The visible triangle per pixel of the last visibility pass, row-major,
    /// numbered as [`Scene::triangles`] lists them
    /// ([`umbra_core::NO_TRIANGLE`] for none).
    #[must_use]
    pub fn ids(&self) -> &[u32] {
        &self.ids
    }

    /// The depth buffer of the last visibility pass, row-major, in
    /// [`D24`].
    #[must_use]
    pub fn depth(&self) -> &[u32] {
        &self.z
    }

    /// What a shading over the last visibility pass reads and keeps: its
    /// ids and depth, the shading unit's setup store, the camera's
    /// matrix and the image's size.
    #[allow(clippy::type_complexity, reason = "the frame's parts a shading borrows at once")]
    pub(crate) fn for_shading(&mut self) -> ((&[u32], &[u32]), &mut Vec<ShadeSetup>, Mat4, (u32, u32)) {
        ((&self.ids, &self.z), &mut self.shade_setups, self.camera, self.size)
    }

    /// The last pass's image, taken out of the frame.
    #[must_use]
    pub fn take_image(&mut self) -> CameraImage {
        let (width, height) = self.size;
        CameraImage { width, height, pixels: core::mem::take(&mut self.pixels), camera: self.camera }
    }
}

/// The scene's camera for a `width × height` image (the field of view is
/// vertical).
fn camera_matrix(scene: &Scene, width: u32, height: u32) -> Mat4 {
    #[allow(clippy::cast_precision_loss, reason = "an aspect ratio")]
    let aspect = width as f32 / height as f32;
    scene.camera.view_projection_aspect(aspect)
}

/// The shading unit's configuration for `options`, seen through `camera`,
/// against the map drawn through `light` (a light's view-projection):
/// flat tangent planes, the fixed seed.
pub(crate) fn shade_config(light: Mat4, camera: Mat4, options: &CameraOptions) -> ShadeConfig {
    ShadeConfig {
        camera,
        light,
        width: options.width,
        height: options.height,
        shadow: options.shadow,
        virtual_samples: options.virtual_samples,
        normals: Normals::Flat,
        seed: 0x5eed,
    }
}

/// The visibility unit over `scene` from its camera at `width × height`
/// walking the image as `tiling` says into `frame`'s depth and ids.
///
/// # Errors
/// [`PassError`] for an unusable size or a malformed mesh.
pub fn visibility<P: Probe>(
    frame: &mut CameraFrame,
    scene: &Scene,
    (width, height): (u32, u32),
    tiling: Tiling,
    probe: &mut P,
) -> Result<Visibility, PassError> {
    let raster = RasterConfig::new(width, height, tiling.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let config = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
    let camera = camera_matrix(scene, width, height);
    let (texels, tiles) = (raster.texel_count(), raster.tile_count());
    let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
    frame.size = (width, height);
    frame.camera = camera;
    let kept = frame.drawn.replace(config) == Some(config) && frame.z.len() == texels;
    let CameraFrame { z, ids, tiles: states, bins, store, .. } = frame;
    z.resize(texels, D24::FAR);
    ids.resize(texels, NO_TRIANGLE);
    states.resize(tiles, TileState::cleared(D24::FAR, 0));
    bins.resize(tiles, Bin::new());
    store.resize(triangles.clamp(1, DEFAULT_SETUPS), Setup::EMPTY);
    let buffers = LightBuffers { z1: z, z2: &mut [], ids, tiles: states, bins, setups: store };
    let mut pass = if kept {
        LightPass::<D24, &mut P, DEFAULT_BIN_CAPACITY>::new_kept(config, buffers, &mut *probe)?
    } else {
        LightPass::<D24, &mut P, DEFAULT_BIN_CAPACITY>::new(config, buffers, &mut *probe)?
    };
    for (draw, d) in scene.draws(camera, CullMode::None).iter().enumerate() {
        pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
            .map_err(|source| PassError::Submit { draw, source })?;
        if tiling.per_draw {
            pass.flush();
        }
    }
    pass.finish();
    Ok(Visibility { camera, raster })
}

/// The shadow unit's view of a light pass's maps: a dual map, or a single
/// front-face-culled one when `front_culled`.
///
/// # Errors
/// [`PassError`] when the maps do not fit their configuration.
pub fn map_view<F: DepthFormat>(maps: &LightMaps<F::Texel>, front_culled: bool) -> Result<MapView<'_, F>, PassError> {
    let map_raster = maps.config.raster;
    Ok(if front_culled {
        MapView::<F>::front_culled(map_raster, &maps.z1, &maps.tiles)?
    } else {
        MapView::<F>::new(map_raster, &maps.z1, &maps.z2, &maps.tiles)?
    })
}

/// The camera pass into `frame`: the visibility unit over `scene` from its
/// camera, then the shading unit against `view` with shadow unit `unit`
/// (the map's [`MapUnit`](tyalias@umbra_core::shade::MapUnit), or Sen et al.'s silhouette unit), reporting every
/// event of both units to `probe`. The shaded pixels are `frame.pixels`.
///
/// # Errors
/// [`PassError`] for an unusable size or a malformed mesh.
pub fn render<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    frame: &mut CameraFrame,
    scene: &Scene,
    view: &MapView<'_, F>,
    unit: &U,
    options: &CameraOptions,
    probe: &mut P,
) -> Result<(), PassError> {
    let mut pixels = std::mem::take(&mut frame.pixels);
    let done = render_into(frame, scene, view, unit, options, probe, &mut pixels);
    frame.pixels = pixels;
    done
}

/// [`render`] keeping only the part of each pixel's result `R` holds — the
/// shadow fraction alone ([`umbra_core::shadow::Shadow`]: 4 bytes a pixel
/// rather than 40) — in `out`, row-major; `frame.pixels` is left as it was.
///
/// # Errors
/// As [`render`].
pub fn render_into<F: DepthFormat, U: ShadowUnit<F>, R: PixelResult, P: Probe>(
    frame: &mut CameraFrame,
    scene: &Scene,
    view: &MapView<'_, F>,
    unit: &U,
    options: &CameraOptions,
    probe: &mut P,
    out: &mut Vec<R>,
) -> Result<(), PassError> {
    let Visibility { camera, .. } = visibility(frame, scene, (options.width, options.height), options.tiling, probe)?;
    let CameraFrame { ids, shade_setups, .. } = frame;
    let light = scene.light().view_projection();
    shade((light, &scene.triangles()), (ids, camera), view, unit, options, probe, out, shade_setups, None)
}

/// What reads a shading's pixels as the shading writes them: told, after
/// each band of `rows` rows of the image, the band's pixels (indices into
/// the image) and the image as far as it is written.
pub(crate) struct Bands<'b, R> {
    /// Rows a band.
    pub rows: u32,
    /// What reads each band.
    pub then: &'b mut dyn FnMut(Range<usize>, &[R]),
}

/// The shading unit alone over a visibility pass's `ids` seen through
/// `camera` (a [`visibility`] pass drawn before, for any number of
/// shadings: its ids do not depend on the tiling) of a scene whose
/// [`Scene::triangles`] are `triangles` (worked out once for every
/// shading of its frame), against `view`, drawn through `light` (the
/// light's view-projection), with
/// shadow unit `unit`, into `out` (row-major) with the setup store
/// `setups`, reporting every event to `probe`, and `bands` told of each
/// band of rows as it is written. Its events are those the shading of
/// [`render_into`] reports, in the same order, band or none.
///
/// # Errors
/// As [`render`].
#[allow(clippy::too_many_arguments, reason = "the unit's inputs, its store, its probe and its reader")]
pub(crate) fn shade<F: DepthFormat, U: ShadowUnit<F>, R: PixelResult, P: Probe>(
    (light, triangles): (Mat4, &[SceneTriangle]),
    (ids, camera): (&[u32], Mat4),
    view: &MapView<'_, F>,
    unit: &U,
    options: &CameraOptions,
    probe: &mut P,
    out: &mut Vec<R>,
    setups: &mut Vec<ShadeSetup>,
    bands: Option<Bands<'_, R>>,
) -> Result<(), PassError> {
    let cfg = shade_config(light, camera, options);
    let source = |id: u32| triangles.get(id as usize).copied();
    // Every pixel is written: the fill only sizes a new frame.
    out.resize(ids.len(), R::BACKGROUND);
    setups.resize(shade_setups(ids, cfg.width), ShadeSetup::EMPTY);
    let inputs = ShadeInputs { cfg: &cfg, map: view, scene: &source, unit };
    let Some(Bands { rows, then }) = bands else {
        shade_with(&inputs, ids, out, setups, probe)?;
        return Ok(());
    };
    // Each band a rectangle of whole rows: the same pixels, bit for bit,
    // and the same events in the same order as the whole image.
    let width = cfg.width as usize;
    let expected = width.saturating_mul(cfg.height as usize);
    if ids.len() != expected {
        return Err(umbra_core::ConfigError::BufferLength { buffer: "ids", expected, found: ids.len() }.into());
    }
    let mut y0 = 0;
    while y0 < cfg.height {
        let y1 = cfg.height.min(y0.saturating_add(rows.max(1)));
        let pixels = y0 as usize * width..y1 as usize * width;
        let rect = TileRect { x0: 0, y0, x1: cfg.width, y1 };
        let (ids, band) =
            (ids.get(pixels.clone()).unwrap_or_default(), out.get_mut(pixels.clone()).unwrap_or_default());
        shade_rect(&inputs, rect, ids, band, setups, probe)?;
        then(pixels, out);
        y0 = y1;
    }
    Ok(())
}

/// The camera pass streamed by tile ([`umbra_core::shade::stream`]): the
/// core's pass a microcontroller runs, one tile of visibility and results
/// at a time, the scene's geometry sent again for every tile; the tiles
/// put back together into the image here. Bit for bit [`render`]'s image.
///
/// # Errors
/// [`PassError`] for an unusable size or buffer.
pub fn streamed<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    scene: &Scene,
    view: &MapView<'_, F>,
    unit: &U,
    options: &CameraOptions,
    probe: &mut P,
) -> Result<CameraImage, PassError> {
    use umbra_core::shade::stream::{TileBuffers, camera_pass_by_tile};
    let CameraOptions { width, height, tiling, .. } = *options;
    let raster = RasterConfig::new(width, height, tiling.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let vis = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
    let camera = camera_matrix(scene, width, height);
    let cfg = shade_config(scene.light().view_projection(), camera, options);
    let triangles = scene.triangles();
    let source = |id: u32| triangles.get(id as usize).copied();
    let tile = (tiling.tile * tiling.tile) as usize;
    let (mut depth, mut ids, mut pixels) =
        (vec![D24::FAR; tile], vec![NO_TRIANGLE; tile], vec![Shaded::BACKGROUND; tile]);
    let mut state = [TileState::cleared(D24::FAR, 0)];
    let mut bins = [Bin::<DEFAULT_BIN_CAPACITY>::new()];
    let mut store = vec![Setup::EMPTY; triangles.len().clamp(1, DEFAULT_SETUPS)];
    let mut shade_setups = vec![ShadeSetup::EMPTY; SHADE_SETUPS];
    let buffers = TileBuffers::<D24, DEFAULT_BIN_CAPACITY> {
        depth: &mut depth,
        ids: &mut ids,
        state: &mut state,
        bins: &mut bins,
        setups: &mut store,
        shade_setups: &mut shade_setups,
        pixels: &mut pixels,
    };
    let draws = scene.draws(camera, CullMode::None);
    let mut image = vec![Shaded::BACKGROUND; raster.texel_count()];
    // The draw that failed, for the error.
    let failed = core::cell::Cell::new(0);
    let draw = |pass: &mut LightPass<'_, D24, &mut P, DEFAULT_BIN_CAPACITY>| {
        draws.iter().enumerate().try_for_each(|(k, d)| {
            failed.set(k);
            pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
        })
    };
    let sink = |rect: umbra_core::TileRect, tile: &[Shaded]| {
        let w = (rect.x1 - rect.x0) as usize;
        for (row, y) in tile.chunks_exact(w).zip(rect.y0..) {
            let at = y as usize * width as usize + rect.x0 as usize;
            image[at..at + w].copy_from_slice(row);
        }
    };
    camera_pass_by_tile(vis, &cfg, view, &source, unit, buffers, &mut *probe, draw, sink).map_err(|e| match e {
        umbra_core::shade::stream::StreamError::Submit(source) => PassError::Submit { draw: failed.get(), source },
        umbra_core::shade::stream::StreamError::Config(e) => PassError::from(e),
        _ => PassError::from(umbra_core::ConfigError::Window { x0: 0, y0: 0, width, height }),
    })?;
    Ok(CameraImage { width, height, pixels: image, camera })
}

/// The shading unit over `frame`'s last [`visibility`] pass against
/// `view`, drawn through `light` (a scene's [`Scene::triangles`] beside
/// it), with shadow unit `unit`, its pixels as an image (the frame's own
/// pixels left as they were): a camera pass that tests several lights
/// shades once per light over one visibility pass.
///
/// # Errors
/// As [`render`].
pub(crate) fn shade_visible<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    frame: &mut CameraFrame,
    light: (Mat4, &[SceneTriangle]),
    view: &MapView<'_, F>,
    unit: &U,
    options: &CameraOptions,
    probe: &mut P,
) -> Result<CameraImage, PassError> {
    let mut pixels = Vec::new();
    let CameraFrame { ids, shade_setups, camera, size, .. } = frame;
    shade(light, (ids, *camera), view, unit, options, probe, &mut pixels, shade_setups, None)?;
    Ok(CameraImage { width: size.0, height: size.1, pixels, camera: *camera })
}

/// The lit pass of a frame whose shadows the shading unit does not test
/// — shadow volumes, whose stencil decides them, or none at all: every
/// pixel of `ids` (a `width`-wide image) that a triangle covers shaded
/// once and its colour written, as the shading unit reports it
/// ([`Event::PixelShaded`](umbra_core::probe::Event::PixelShaded)), with
/// no lookup.
pub(crate) fn lit_pass<P: Probe>(ids: &[u32], width: u32, probe: &mut P) {
    let across = width.max(1) as usize;
    for (k, &id) in ids.iter().enumerate() {
        if id != NO_TRIANGLE {
            #[allow(clippy::cast_possible_truncation, reason = "pixel coordinates of a checked image")]
            let (x, y) = ((k % across) as u32, (k / across) as u32);
            probe.event(umbra_core::probe::Event::PixelShaded { x, y });
        }
    }
}

/// The camera pass of depth-fail shadow volumes into `frame` of a scene
/// with its [`Scene::triangles`]: the
/// visibility unit (walking the image as `tiling` says), then, for each
/// of `lit` (the scene lit by each of its lights in turn), the stencil
/// unit over every occluder's volume and the lit pass over every covered
/// pixel ([`lit_pass`]), as a map's camera pass shades each; a pixel is
/// in shadow where its stencil is non-zero. One image per light.
///
/// # Errors
/// [`PassError`] for an unusable size or a malformed mesh.
pub(crate) fn volumes<P: Probe>(
    frame: &mut CameraFrame,
    (scene, triangles, lit): (&Scene, &[SceneTriangle], &[Lit<'_>]),
    size: (u32, u32),
    tiling: Tiling,
    probe: &mut P,
) -> Result<Vec<CameraImage>, PassError> {
    let vis = visibility(frame, scene, size, tiling, probe)?;
    let mut images = Vec::with_capacity(lit.len());
    for one in lit {
        let (occluders, one) = (one.occluders(), &one.scene);
        let stencil =
            crate::pass::occluders::stencil::<D24, _>(one, occluders, &vis.camera, vis.raster, &frame.z, probe)?;
        lit_pass(&frame.ids, size.0, probe);
        let pixels = frame
            .ids
            .iter()
            .zip(&stencil)
            .map(|(&id, &s)| match triangles.get(id as usize) {
                Some(t) => Shaded {
                    triangle: id,
                    light: None,
                    normal: t.normals[0],
                    shadow: if s == 0 { Shadow::ZERO } else { Shadow::ONE },
                },
                None => Shaded::BACKGROUND,
            })
            .collect();
        images.push(CameraImage { width: size.0, height: size.1, pixels, camera: vis.camera });
    }
    Ok(images)
}
