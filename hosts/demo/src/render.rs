//! The demo's two passes over a [`Memory`], with the event counters or
//! without them (a firmware whose flash cannot spare the counters' code
//! renders the same bits uncounted).

use umbra_core::probe::{NoProbe, Probe, Totals};
use umbra_core::shade::stream::{TileBuffers, camera_pass_by_tile};
use umbra_core::shade::{MapUnitWith, Shaded};
use umbra_core::shadow::{BoxFilter, MapView};
use umbra_core::{CullMode, D16, D24, DualOnly, LightBuffers, LightPass, TileRect, VisibilityOnly};

use crate::{
    BIN_CAPACITY, CameraChecksum, DemoError, Memory, Summary, light_config, map_checksum, scene, shade_config,
    visibility_config,
};

/// Render the bundled scene ([`scene`]) into `mem`: the light pass (a
/// `MAP_SIDE`² map, D16, dual), then the camera pass streamed by tile
/// ([`umbra_core::shade::stream`]: visibility of each 8×8 tile in D24, then
/// shading with second depth, virtual samples and a 2×2 box filter), each
/// tile's results folded into the checksum as it is made. The passes'
/// events are counted into `mem`'s totals ([`Memory::totals`]).
///
/// # Errors
/// [`DemoError`] if the core rejects a configuration (it does not).
pub fn render<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize>(
    mem: &mut Memory<MAP_TEXELS, MAP_TILES, SETUPS>,
) -> Result<Summary, DemoError> {
    render_with(mem, || ())
}

/// [`render`], calling `between` after the light pass and before the
/// camera pass (a firmware reads its timer there).
///
/// # Errors
/// [`DemoError`] if the core rejects a configuration (it does not).
pub fn render_with<'m, const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize>(
    mem: &'m mut Memory<MAP_TEXELS, MAP_TILES, SETUPS>,
    between: impl FnOnce(),
) -> Result<Summary, DemoError> {
    // The probes are borrowed, not moved: the totals are large for a
    // microcontroller's stack.
    let count = |light: &'m mut Totals, camera: &'m mut Totals| {
        (*light, *camera) = (Totals::ZERO, Totals::ZERO);
        (light, camera)
    };
    passes(mem, count, between)
}

/// [`render_with`] without the event counters: the same summary, and the
/// totals left as they were.
///
/// # Errors
/// [`DemoError`] if the core rejects a configuration (it does not).
pub fn render_uncounted_with<const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize>(
    mem: &mut Memory<MAP_TEXELS, MAP_TILES, SETUPS>,
    between: impl FnOnce(),
) -> Result<Summary, DemoError> {
    passes(mem, |_, _| (NoProbe, NoProbe), between)
}

/// Both passes, reporting to the probes `probes` makes of the memory's
/// two totals.
fn passes<'m, const MAP_TEXELS: usize, const MAP_TILES: usize, const SETUPS: usize, L: Probe, C: Probe>(
    mem: &'m mut Memory<MAP_TEXELS, MAP_TILES, SETUPS>,
    probes: impl FnOnce(&'m mut Totals, &'m mut Totals) -> (L, C),
    between: impl FnOnce(),
) -> Result<Summary, DemoError> {
    let Memory {
        z1,
        z2,
        map_tiles,
        bins,
        setups,
        cache,
        depth,
        ids,
        camera_tile,
        camera_bin,
        shade_setups,
        pixels,
        light,
        camera: camera_totals,
    } = mem;
    let (light_probe, camera_probe) = probes(light, camera_totals);
    let light_cfg = light_config(Memory::<MAP_TEXELS, MAP_TILES, SETUPS>::MAP_SIDE)?;
    let buffers = LightBuffers::<D16, BIN_CAPACITY> { z1, z2, ids: &mut [], tiles: map_tiles, bins, setups };
    // Each pass is built with the one datapath it uses (a microcontroller's
    // flash holds no other).
    let mut pass = LightPass::<D16, L, BIN_CAPACITY, DualOnly<true>>::new(light_cfg, buffers, light_probe)?;
    pass.draw_mesh_cached(&scene::POSITIONS, &scene::INDICES, &scene::light_matrix(), CullMode::None, cache)?;
    pass.finish();
    between();

    let view = MapView::<D16>::new(light_cfg.raster, z1, z2, map_tiles)?;
    let cfg = shade_config()?;
    let tile = TileBuffers::<D24, BIN_CAPACITY> {
        depth,
        ids,
        state: camera_tile,
        bins: camera_bin,
        setups,
        shade_setups,
        pixels,
    };
    let camera = scene::camera_matrix();
    let draw = |p: &mut LightPass<'_, D24, C, BIN_CAPACITY, VisibilityOnly<true>>| {
        p.draw_mesh_cached(&scene::POSITIONS, &scene::INDICES, &camera, CullMode::None, cache)
    };
    let mut image = CameraChecksum::new();
    let sink = |rect: TileRect, tile: &[Shaded]| image.tile(rect, tile);
    let vis = visibility_config()?;
    camera_pass_by_tile(
        vis,
        &cfg,
        &view,
        &scene::triangle,
        &MapUnitWith::<BoxFilter>::new(),
        tile,
        camera_probe,
        draw,
        sink,
    )?;
    Ok(Summary {
        map_checksum: map_checksum::<D16>(z1, z2),
        camera_checksum: image.finish(),
        covered: image.covered,
        shadowed: image.shadowed,
    })
}
