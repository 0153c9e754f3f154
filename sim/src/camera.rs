//! The camera pass over owned buffers: the visibility unit with the camera's
//! matrix, then the shading unit against a light pass's maps.

use glam::Mat4;
use umbra_core::bin::Bin;
use umbra_core::camera::{CameraConfig, Normals, Shaded, shade};
use umbra_core::setup::Setup;
use umbra_core::shadow::{MapView, ShadowConfig};
use umbra_core::{
    CullMode, D24, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, Probe, RasterConfig, TileState,
};

use crate::light::{DEFAULT_BIN_CAPACITY, DEFAULT_SETUPS, LightError, LightMaps};
use crate::scene::Scene;

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
    let raster =
        RasterConfig::new(width, height, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let config = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
    #[allow(clippy::cast_precision_loss, reason = "an aspect ratio")]
    let camera = scene.camera.view_projection_aspect(width as f32 / height as f32);
    let texels = raster.texel_count();
    let (mut z, mut ids) = (vec![D24::FAR; texels], vec![0u32; texels]);
    let mut tiles = vec![TileState::cleared(D24::FAR, 0); raster.tile_count()];
    let mut bins = vec![Bin::<DEFAULT_BIN_CAPACITY>::new(); raster.tile_count()];
    let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
    let mut store = vec![Setup::EMPTY; triangles.clamp(1, DEFAULT_SETUPS)];
    let buffers =
        LightBuffers { z1: &mut z, z2: &mut [], ids: &mut ids, tiles: &mut tiles, bins: &mut bins, setups: &mut store };
    let mut pass = LightPass::<D24, &mut P, DEFAULT_BIN_CAPACITY>::new(config, buffers, &mut *probe)?;
    for (draw, d) in scene.draws(camera, CullMode::None).iter().enumerate() {
        pass.draw_mesh(d.positions, d.triangles, &d.transform, d.cull)
            .map_err(|source| LightError::Submit { draw, source })?;
    }
    pass.finish();
    Ok((camera, ids))
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
    let (camera, ids) = visibility(scene, width, height, probe)?;
    let map_raster = maps.config.raster;
    let view = if front_culled {
        MapView::<F>::front_culled(map_raster, &maps.z1, &maps.tiles)?
    } else {
        MapView::<F>::new(map_raster, &maps.z1, &maps.z2, &maps.tiles)?
    };
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
    let mut pixels = vec![Shaded::BACKGROUND; ids.len()];
    shade(&cfg, &ids, &view, &source, &mut pixels, probe)?;
    Ok(CameraImage { width, height, pixels })
}
