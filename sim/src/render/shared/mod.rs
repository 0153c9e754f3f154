//! Renders that share what does not change between them: a study's
//! configurations of one scene and image size.
//!
//! What each part of a render reads decides who shares it:
//!
//! * the camera's **visibility** reads the scene, the image and the
//!   architecture's tiling — never the algorithm or the map — so it is drawn
//!   once per tiling ([`ImageShare`]), and each architecture's camera probe is
//!   kept as the visibility left it, for every configuration to continue;
//! * each light's **light pass** reads the scene as that light lights it,
//!   the depth unit and the culling, the depth format, the map side and
//!   the tiling — never the filter, the shadow test or its bias — so it is
//!   drawn once per tiling and light for every configuration with the same
//!   [`LightKey`] ([`LightShare`]), each architecture's light probe kept as
//!   it left it;
//! * the **shading** reads the visible ids, one light's map's texels and
//!   its tiles' bounds (lookup culling): it runs once per configuration and
//!   light for each distinct pair of them, feeding every architecture that
//!   drew that pair at once (pixel coordinates, not the tiling, place its
//!   events); the lights are shaded in the scene's order after the one
//!   visibility, each architecture's camera probe told which light's map it
//!   reads, as a render on its own shades them;
//! * each light's **reference** and its boundaries and distance fields
//!   (`Fields`) are worked out once per scene and image.
//!
//! A probe continued from a kept copy receives exactly the events, in
//! exactly the order, that a probe of its own passes would: every report is
//! the unshared render's bit for bit (`study::run_unshared` is the
//! reference the tests hold it to). An architecture that shades per
//! fragment charges its filter during visibility, so it keeps passes of its
//! own ([`shares`]).

mod lit;
mod probes;
mod seen;
mod shading;

use umbra_core::{CullMode, DepthUnit};

pub(crate) use self::lit::LightShare;
pub(crate) use self::seen::ImageShare;
pub(crate) use self::shading::Scratch;
pub(crate) use self::shading::render_shared;
use super::RenderConfig;
use super::costed::shape;
use crate::base::maps::Tiling;
use crate::cost::arch::Arch;
use crate::pass::algorithm::MapKind;

/// Whether `arch`'s passes can be shared: one that shades per fragment
/// charges the filter's instructions on the visibility pass's depth writes,
/// so its visibility is not the same for every configuration.
#[must_use]
pub(crate) fn shares(arch: &Arch) -> bool {
    !arch.shade.per_fragment
}

/// The distinct `key`s of the `archs` that [`shares`], `first` first, and
/// for each architecture the index of its key (`None` for one that does
/// not share): the passes a share draws, and who reads each.
fn assign<K: PartialEq + Copy>(archs: &[Arch], first: K, key: impl Fn(&Arch) -> K) -> (Vec<K>, Vec<Option<usize>>) {
    let mut keys = vec![first];
    let by = archs
        .iter()
        .map(|a| {
            shares(a).then(|| {
                let k = key(a);
                keys.iter().position(|&o| o == k).unwrap_or_else(|| {
                    keys.push(k);
                    keys.len() - 1
                })
            })
        })
        .collect();
    (keys, by)
}

/// What a light pass reads of a configuration: configurations with the
/// same key draw the same maps with the same events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LightKey {
    format: umbra_core::DepthFormatKind,
    map_size: u32,
    unit: DepthUnit,
    solids: CullMode,
    open: CullMode,
}

impl LightKey {
    /// The key of `cfg`: `None` for shadow volumes, which draw no map.
    #[must_use]
    pub(crate) fn of(cfg: &RenderConfig) -> Option<Self> {
        // The unit and its culling do not depend on the format.
        let units = cfg.algorithm.units::<umbra_core::D24>(cfg.bias);
        (units.map != MapKind::Volumes).then(|| Self {
            format: cfg.format,
            map_size: cfg.map_size,
            unit: units.unit,
            solids: units.cull(true, cfg.culling),
            open: units.cull(false, cfg.culling),
        })
    }
}

/// Bytes an [`ImageShare`] holds beside its references and its scenes,
/// at most, for an image of `pixels` drawn in `tilings` tilings of a scene
/// of `triangles` triangles, shaded against `lights` lights: each
/// tiling's depth and ids, the triangles as the shading reads them, and
/// for each light its reference's fields, the footprints it keeps (a
/// map position of 12 bytes a pixel each) and its judge's occluders.
#[must_use]
pub(crate) const fn image_bytes(pixels: u64, tilings: u64, (triangles, lights): (u64, u64)) -> u64 {
    let triangle = core::mem::size_of::<umbra_core::shade::SceneTriangle>() as u64;
    let light = pixels * (32 + 12 * seen::KEPT_FOOTPRINTS as u64) + crate::truth::cause::OccluderMemo::BYTES;
    pixels * 8 * tilings + lights * light + triangles * triangle
}

/// Bytes a key's [`LightShare`]s hold, at most, for maps of `texels`
/// texels drawn in `tilings` tilings for each of `lights` lights: two
/// buffers of 4-byte texels each.
#[must_use]
pub(crate) const fn light_bytes(texels: u64, tilings: u64, lights: u64) -> u64 {
    texels * 8 * tilings * lights
}

/// The passes a share draws for `archs`, at most: the visibility's
/// tilings or the light pass's shapes, whichever are more (for the memory
/// a share takes).
#[must_use]
pub(crate) fn tilings(archs: &[Arch]) -> usize {
    let light = |a: &Arch| {
        let s = shape(a);
        (s.tiling, s.light_addresses)
    };
    assign(archs, Tiling::DEFAULT, Arch::tiling).0.len().max(assign(archs, (Tiling::DEFAULT, false), light).0.len())
}
