#![no_std]
#![forbid(unsafe_code)]
#![doc = include_str!("../README.md")]

pub mod checksum;
pub mod footprint;
pub mod scene;

use core::fmt;
use core::mem::size_of;

use umbra_core::depth::PlaneZ;
use umbra_core::glam::Vec3;
use umbra_core::raster::bin::Bin;
use umbra_core::raster::setup::{DepthPlane, Edge, Setup};
use umbra_core::shade::{Normals, ShadeConfig, Shaded, shade};
use umbra_core::shadow::{Bias, DepthTest, Filter, MapView, Shadow, ShadowConfig, ShadowConfigError};
use umbra_core::{
    ConfigError, CullMode, D16, D24, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, RasterConfig,
    SubmitError, TileState,
};

pub use checksum::Fnv1a;
pub use umbra_core::probe::Totals;

/// Map side, texels.
pub const MAP: u32 = 64;
/// Camera image side, pixels.
pub const IMAGE: u32 = 64;
/// Tile side of both passes, pixels.
pub const TILE: u32 = 16;
/// Bin capacity: small, so that full bins flush early.
pub const BIN_CAPACITY: usize = 16;
/// Setup-store entries: fewer than the scene's triangles, so the store
/// fills and every bin is drained once mid-pass.
pub const SETUPS: usize = 32;
/// Seed of the shading unit's per-pixel random numbers.
pub const SEED: u64 = 0x5eed;

const MAP_TEXELS: usize = (MAP * MAP) as usize;
const IMAGE_TEXELS: usize = (IMAGE * IMAGE) as usize;
const MAP_TILES: usize = (MAP / TILE * (MAP / TILE)) as usize;
const IMAGE_TILES: usize = (IMAGE / TILE * (IMAGE / TILE)) as usize;
const BINS: usize = if MAP_TILES > IMAGE_TILES { MAP_TILES } else { IMAGE_TILES };

/// A pixel result with every byte zero, so that a `static` [`Memory`] is
/// zero-initialised (no flash image).
const ZERO_PIXEL: Shaded = Shaded { triangle: 0, light: None, normal: Vec3::ZERO, shadow: Shadow::ZERO };

/// A setup-store entry with every byte zero (the store is written before
/// it is read).
const ZERO_SETUP: Setup = Setup {
    edges: [Edge { dx: 0, dy: 0, c: 0 }; 3],
    plane: DepthPlane { a: 0, b: 0, c: 0 },
    bbox: umbra_core::TileRect { x0: 0, y0: 0, x1: 0, y1: 0 },
    z_min: PlaneZ::ZERO,
    z_max: PlaneZ::ZERO,
    triangle: 0,
};

/// Every buffer of both passes. Bins and the setup store are shared: the
/// camera pass starts after the light pass has drained them.
pub struct Memory {
    z1: [u16; MAP_TEXELS],
    z2: [u16; MAP_TEXELS],
    map_tiles: [TileState<u16>; MAP_TILES],
    depth: [u32; IMAGE_TEXELS],
    ids: [u32; IMAGE_TEXELS],
    image_tiles: [TileState<u32>; IMAGE_TILES],
    bins: [Bin<BIN_CAPACITY>; BINS],
    setups: [Setup; SETUPS],
    pixels: [Shaded; IMAGE_TEXELS],
}

impl Default for Memory {
    fn default() -> Self {
        Self::new()
    }
}

impl Memory {
    /// All buffers zeroed (a `const`, so it can initialise a `static`).
    #[must_use]
    pub const fn new() -> Self {
        Self {
            z1: [0; MAP_TEXELS],
            z2: [0; MAP_TEXELS],
            map_tiles: [TileState::cleared(0, 0); MAP_TILES],
            depth: [0; IMAGE_TEXELS],
            ids: [0; IMAGE_TEXELS],
            image_tiles: [TileState::cleared(0, 0); IMAGE_TILES],
            bins: [const { Bin::new() }; BINS],
            setups: [ZERO_SETUP; SETUPS],
            pixels: [ZERO_PIXEL; IMAGE_TEXELS],
        }
    }

    /// The light pass's nearest and second-nearest depths, row-major.
    #[must_use]
    pub const fn maps(&self) -> (&[u16], &[u16]) {
        (&self.z1, &self.z2)
    }

    /// The camera pass's result per pixel, row-major.
    #[must_use]
    pub const fn pixels(&self) -> &[Shaded] {
        &self.pixels
    }
}

/// The demo's light pass as [`footprint::light_pass`] describes it, on
/// the target this is compiled for.
#[must_use]
pub const fn light_footprint_config() -> footprint::FootprintConfig {
    footprint::FootprintConfig {
        width: MAP,
        height: MAP,
        tile: TILE,
        format: umbra_core::DepthFormatKind::D16,
        unit: DepthUnit::Dual,
        bin_capacity: BIN_CAPACITY,
        setups: SETUPS,
        pointer_bytes: footprint::POINTER_BYTES,
    }
}

/// Bytes of the buffers the demo's light pass uses, from `size_of` of their
/// types on the target this is compiled for: what
/// [`light_footprint_config`] must predict.
pub const LIGHT_BUFFER_BYTES: usize = 2 * size_of::<[u16; MAP_TEXELS]>()
    + size_of::<[TileState<u16>; MAP_TILES]>()
    + size_of::<[Bin<BIN_CAPACITY>; MAP_TILES]>()
    + size_of::<[Setup; SETUPS]>();

/// What [`render`] reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Summary {
    /// FNV-1a 64 of the light pass's maps: every `z1` texel, then every
    /// `z2` texel, row-major, each as 2 little-endian bytes.
    pub map_checksum: u64,
    /// FNV-1a 64 of the camera pass, per pixel row-major: the triangle id
    /// (`u32`); then `0u8` when there is no light point, or `1u8` and the
    /// point's `x`, `y` (`i32` bits of 16.16 texels) and `z` (`i64` bits of
    /// 32.32 LSBs); then the shadow fraction (`u32` bits of 16.16).
    /// Integers are little-endian.
    pub camera_checksum: u64,
    /// Pixels the camera sees the scene in.
    pub covered: u32,
    /// Covered pixels wholly in shadow.
    pub shadowed: u32,
    /// Event totals of the light pass.
    pub light: Totals,
    /// Event totals of the camera pass (visibility and shading).
    pub camera: Totals,
}

/// Why the demo could not render (none of these happens with the bundled
/// scene; they are the core's errors, passed on).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DemoError {
    /// A configuration or buffer the core rejected.
    Config(ConfigError),
    /// A malformed mesh.
    Submit(SubmitError),
    /// A shadow configuration the core rejected.
    Shadow(ShadowConfigError),
}

impl fmt::Display for DemoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Config(e) => write!(f, "demo configuration: {e}"),
            Self::Submit(e) => write!(f, "demo scene: {e}"),
            Self::Shadow(e) => write!(f, "demo shadow unit: {e}"),
        }
    }
}

impl core::error::Error for DemoError {}

impl From<ConfigError> for DemoError {
    fn from(e: ConfigError) -> Self {
        Self::Config(e)
    }
}

impl From<SubmitError> for DemoError {
    fn from(e: SubmitError) -> Self {
        Self::Submit(e)
    }
}

impl From<ShadowConfigError> for DemoError {
    fn from(e: ShadowConfigError) -> Self {
        Self::Shadow(e)
    }
}

/// The light pass's configuration: 64² map, 16-pixel tiles, dual depth
/// unit, max-z culling.
///
/// # Errors
/// None for the constants here; the core's check is kept.
pub fn light_config() -> Result<LightPassConfig, ConfigError> {
    let raster = RasterConfig::new(MAP, MAP, TILE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    Ok(LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true })
}

/// The shadow unit's configuration: second depth (Wang & Molnar 1994 §3.1),
/// no bias, 2×2 box filter, lookups culled by the tiles' bounds.
///
/// # Errors
/// None for the constants here; the core's check is kept.
pub fn shadow_config() -> Result<ShadowConfig, ShadowConfigError> {
    ShadowConfig::new(DepthTest::Second, Bias::ZERO, Filter::Box { size: 2 }, true)
}

/// Render the bundled scene ([`scene`]) into `mem`: the light pass (64²,
/// D16, dual), then the camera pass (visibility at 64² in D24, shading
/// with second depth, virtual samples and a 2×2 box filter).
///
/// # Errors
/// [`DemoError`] if the core rejects a configuration (it does not).
pub fn render(mem: &mut Memory) -> Result<Summary, DemoError> {
    let light = scene::light_matrix();
    let camera = scene::camera_matrix();

    // Light pass.
    let light_cfg = light_config()?;
    let buffers = LightBuffers::<D16, BIN_CAPACITY> {
        z1: &mut mem.z1,
        z2: &mut mem.z2,
        ids: &mut [],
        tiles: &mut mem.map_tiles,
        bins: &mut mem.bins[..MAP_TILES],
        setups: &mut mem.setups,
    };
    let mut pass = LightPass::<D16, Totals, BIN_CAPACITY>::new(light_cfg, buffers, Totals::default())?;
    pass.draw_mesh(&scene::POSITIONS, &scene::INDICES, &light, CullMode::None)?;
    let light_totals = pass.finish();

    // Camera pass: visibility, then shading against the maps.
    let raster = RasterConfig::new(IMAGE, IMAGE, TILE, RasterConfig::DEFAULT_SUBPIXEL_BITS)?;
    let vis_cfg = LightPassConfig { raster, unit: DepthUnit::Single, max_z_cull: true };
    let buffers = LightBuffers::<D24, BIN_CAPACITY> {
        z1: &mut mem.depth,
        z2: &mut [],
        ids: &mut mem.ids,
        tiles: &mut mem.image_tiles,
        bins: &mut mem.bins[..IMAGE_TILES],
        setups: &mut mem.setups,
    };
    let mut pass = LightPass::<D24, Totals, BIN_CAPACITY>::new(vis_cfg, buffers, Totals::default())?;
    pass.draw_mesh(&scene::POSITIONS, &scene::INDICES, &camera, CullMode::None)?;
    let mut camera_totals = pass.finish();

    let view = MapView::<D16>::new(light_cfg.raster, &mem.z1, &mem.z2, &mem.map_tiles)?;
    let cfg = ShadeConfig {
        camera,
        light,
        width: IMAGE,
        height: IMAGE,
        shadow: shadow_config()?,
        virtual_samples: true,
        normals: Normals::Flat,
        seed: SEED,
    };
    shade(&cfg, &mem.ids, &view, &scene::triangle, &mut mem.pixels, &mut camera_totals)?;

    let seen = mem.pixels.iter().filter(|p| p.triangle != umbra_core::NO_TRIANGLE);
    let (covered, shadowed) = seen.fold((0, 0), |(c, s), p| (c + 1, s + u32::from(p.shadow == Shadow::ONE)));
    Ok(Summary {
        map_checksum: map_checksum::<D16>(&mem.z1, &mem.z2),
        camera_checksum: camera_checksum(&mem.pixels),
        covered,
        shadowed,
        light: light_totals,
        camera: camera_totals,
    })
}

/// [`Summary::map_checksum`] of maps of any format with 16-bit texels.
#[must_use]
pub fn map_checksum<F: DepthFormat<Texel = u16>>(z1: &[u16], z2: &[u16]) -> u64 {
    let mut h = Fnv1a::new();
    z1.iter().chain(z2).for_each(|&t| h.u16(t));
    h.finish()
}

/// [`Summary::camera_checksum`] of per-pixel results.
#[must_use]
pub fn camera_checksum(pixels: &[Shaded]) -> u64 {
    let mut h = Fnv1a::new();
    for p in pixels {
        h.u32(p.triangle);
        match p.light {
            None => h.bytes(&[0]),
            Some(l) => {
                h.bytes(&[1]);
                h.i32(l.x.to_bits());
                h.i32(l.y.to_bits());
                h.i64(l.z.to_bits());
            }
        }
        h.u32(p.shadow.to_bits());
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::boxed::Box;

    use super::*;

    /// The scene is one a shadow test can fail on: the camera sees most of
    /// the image, part of it in shadow and most of it lit; both passes do
    /// the work the configuration asks for.
    #[test]
    fn the_scene_exercises_the_passes() {
        let mut mem = Box::new(Memory::new());
        let s = render(&mut mem).unwrap();
        assert!(s.covered > IMAGE * IMAGE / 2, "{s:?}");
        assert!(s.shadowed > 100 && s.shadowed < s.covered / 2, "{s:?}");
        assert_eq!(s.light.submitted, scene::TRIANGLES as u64);
        assert_eq!(s.camera.submitted, scene::TRIANGLES as u64);
        // Every flush stores its tile; the small setup store makes some
        // tiles flush twice, so they are loaded back.
        assert_eq!(s.light.flushes(), s.light.tile_stores);
        assert!(s.light.tile_loads > 0);
        // The dual unit reads z1 and z2 for every fragment.
        assert_eq!(s.light.depth_reads(), 2 * s.light.fragments);
        assert!(s.camera.virtual_samples > 0 && s.camera.lookups_culled > 0);
    }

    #[test]
    fn the_footprint_predicts_the_demo_buffers() {
        let f = footprint::light_pass(&light_footprint_config()).unwrap();
        assert_eq!(f.total(), LIGHT_BUFFER_BYTES);
    }
}
