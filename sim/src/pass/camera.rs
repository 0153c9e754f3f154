//! The camera pass over owned buffers: the visibility unit with the camera's
//! matrix, then the shading unit against a light pass's maps.

use glam::Mat4;
use umbra_core::raster::bin::Bin;
use umbra_core::raster::setup::Setup;
use umbra_core::shade::{CameraConfig, MapUnit, Normals, ShadeSetup, Shaded, ShadowUnit, shade_with};
use umbra_core::shadow::{MapView, Shadow, ShadowConfig};
use umbra_core::{
    CullMode, D24, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, NO_TRIANGLE, Probe, RasterConfig,
    TileState,
};

use crate::pass::light::{DEFAULT_BIN_CAPACITY, DEFAULT_SETUPS, LightError, LightMaps};
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
}

/// The visibility unit over `scene` from its camera at `width × height`:
/// the camera's matrix (world to clip) and the visible triangle per pixel,
/// numbered as [`Scene::triangles`] lists them.
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
pub fn visibility<P: Probe>(
    scene: &Scene,
    width: u32,
    height: u32,
    probe: &mut P,
) -> Result<(Mat4, Vec<u32>), LightError> {
    visibility_depth(scene, width, height, probe).map(|v| (v.camera, v.ids))
}

/// What the visibility unit leaves: the camera's matrix, the visible
/// triangle and its (24-bit) depth per pixel.
#[derive(Clone, Debug)]
pub struct Visibility {
    /// World to camera clip space.
    pub camera: Mat4,
    /// The camera target.
    pub raster: RasterConfig,
    /// Visible triangle per pixel, row-major ([`umbra_core::NO_TRIANGLE`] for none).
    pub ids: Vec<u32>,
    /// Its depth, 24-bit.
    pub depth: Vec<u32>,
}

/// [`visibility`] keeping the depth buffer too (the stencil unit tests
/// shadow volumes against it).
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
pub fn visibility_depth<P: Probe>(
    scene: &Scene,
    width: u32,
    height: u32,
    probe: &mut P,
) -> Result<Visibility, LightError> {
    let mut frame = CameraFrame::default();
    let (camera, raster) = visibility_in(scene, width, height, probe, &mut frame)?;
    Ok(Visibility { camera, raster, ids: frame.ids, depth: frame.z })
}

/// Entries of the shading unit's setup store: more than the triangles a
/// row of a 1920-pixel image of the bundled scenes crosses, so that each
/// visible triangle is set up about once a pass.
pub const SHADE_SETUPS: usize = 256;

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
    /// The shaded pixels of the last pass, row-major.
    pub pixels: Vec<Shaded>,
}

/// The visibility unit into `frame`'s depth and ids: the camera's matrix
/// and target.
fn visibility_in<P: Probe>(
    scene: &Scene,
    width: u32,
    height: u32,
    probe: &mut P,
    frame: &mut CameraFrame,
) -> Result<(Mat4, RasterConfig), LightError> {
    let raster =
        RasterConfig::new(width, height, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let config = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
    #[allow(clippy::cast_precision_loss, reason = "an aspect ratio")]
    let camera = scene.camera.view_projection_aspect(width as f32 / height as f32);
    let (texels, tiles) = (raster.texel_count(), raster.tile_count());
    let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
    let CameraFrame { z, ids, tiles: states, bins, store, .. } = frame;
    z.resize(texels, D24::FAR);
    ids.resize(texels, NO_TRIANGLE);
    states.resize(tiles, TileState::cleared(D24::FAR, 0));
    bins.resize(tiles, Bin::new());
    store.resize(triangles.clamp(1, DEFAULT_SETUPS), Setup::EMPTY);
    let buffers = LightBuffers { z1: z, z2: &mut [], ids, tiles: states, bins, setups: store };
    let mut pass = LightPass::<D24, &mut P, DEFAULT_BIN_CAPACITY>::new(config, buffers, &mut *probe)?;
    for (draw, d) in scene.draws(camera, CullMode::None).iter().enumerate() {
        pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
            .map_err(|source| LightError::Submit { draw, source })?;
    }
    pass.finish();
    Ok((camera, raster))
}

/// Render `scene` from its camera at `width × height` and shade it against
/// `maps` (a dual map, or a single front-face-culled one when
/// `front_culled`), reporting every event of both units to `probe`.
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, each a separate choice")]
pub fn render_camera<F: DepthFormat, P: Probe>(
    scene: &Scene,
    maps: &LightMaps<F::Texel>,
    front_culled: bool,
    shadow: ShadowConfig,
    virtual_samples: bool,
    width: u32,
    height: u32,
    probe: &mut P,
) -> Result<CameraImage, LightError> {
    let mut frame = CameraFrame::default();
    render_camera_in::<F, _>(scene, maps, front_culled, shadow, virtual_samples, (width, height), probe, &mut frame)?;
    Ok(CameraImage { width, height, pixels: frame.pixels })
}

/// [`render_camera`] into `frame` (its pixels are the image): frames of
/// one size drawn over and over reuse their memory.
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, each a separate choice")]
pub fn render_camera_in<F: DepthFormat, P: Probe>(
    scene: &Scene,
    maps: &LightMaps<F::Texel>,
    front_culled: bool,
    shadow: ShadowConfig,
    virtual_samples: bool,
    (width, height): (u32, u32),
    probe: &mut P,
    frame: &mut CameraFrame,
) -> Result<(), LightError> {
    let view = map_view::<F>(maps, front_culled)?;
    shade_frame(scene, &view, shadow, virtual_samples, (width, height), &MapUnit, probe, frame)
}

/// The shadow unit's view of a light pass's maps.
///
/// # Errors
/// [`LightError`] when the maps do not fit their configuration.
pub fn map_view<F: DepthFormat>(maps: &LightMaps<F::Texel>, front_culled: bool) -> Result<MapView<'_, F>, LightError> {
    let map_raster = maps.config.raster;
    Ok(if front_culled {
        MapView::<F>::front_culled(map_raster, &maps.z1, &maps.tiles)?
    } else {
        MapView::<F>::new(map_raster, &maps.z1, &maps.z2, &maps.tiles)?
    })
}

/// [`render_camera`] with any shadow unit (the map's, or Sen et al.'s
/// silhouette unit) over a map view.
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, each a separate choice")]
pub fn render_camera_with<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    scene: &Scene,
    view: &MapView<'_, F>,
    shadow: ShadowConfig,
    virtual_samples: bool,
    width: u32,
    height: u32,
    unit: &U,
    probe: &mut P,
) -> Result<CameraImage, LightError> {
    let mut frame = CameraFrame::default();
    shade_frame(scene, view, shadow, virtual_samples, (width, height), unit, probe, &mut frame)?;
    Ok(CameraImage { width, height, pixels: frame.pixels })
}

/// Both units of the camera pass into `frame`.
#[allow(clippy::too_many_arguments, reason = "the pass's inputs, each a separate choice")]
fn shade_frame<F: DepthFormat, U: ShadowUnit<F>, P: Probe>(
    scene: &Scene,
    view: &MapView<'_, F>,
    shadow: ShadowConfig,
    virtual_samples: bool,
    (width, height): (u32, u32),
    unit: &U,
    probe: &mut P,
    frame: &mut CameraFrame,
) -> Result<(), LightError> {
    let (camera, _) = visibility_in(scene, width, height, probe, frame)?;
    let cfg = CameraConfig {
        camera,
        light: scene.light().view_projection(),
        width,
        height,
        shadow,
        virtual_samples,
        normals: Normals::Flat,
        seed: 0x5eed,
    };
    let triangles = scene.triangles();
    let source = |id: u32| triangles.get(id as usize).copied();
    // Every pixel is written: the fill only sizes a new frame.
    frame.pixels.resize(frame.ids.len(), Shaded::BACKGROUND);
    frame.shade_setups.resize(SHADE_SETUPS, ShadeSetup::EMPTY);
    shade_with(&cfg, &frame.ids, view, &source, &mut frame.pixels, unit, &mut frame.shade_setups, probe)?;
    Ok(())
}

/// The camera image of depth-fail shadow volumes: the visibility unit,
/// then the stencil unit over every occluder's volume; a pixel is in
/// shadow where its stencil is non-zero.
///
/// # Errors
/// [`LightError`] for an unusable size or a malformed mesh.
pub fn render_volumes<P: Probe>(
    scene: &Scene,
    width: u32,
    height: u32,
    probe: &mut P,
) -> Result<CameraImage, LightError> {
    let vis = visibility_depth(scene, width, height, probe)?;
    let occluders = crate::world::occluders::Occluders::new(scene);
    let stencil =
        crate::world::occluders::stencil::<D24, _>(scene, &occluders, &vis.camera, vis.raster, &vis.depth, probe)?;
    let triangles = scene.triangles();
    let pixels = vis
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
    Ok(CameraImage { width, height, pixels })
}
