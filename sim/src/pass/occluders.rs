//! The two passes over a scene's occluders ([`crate::world::occluders`]):
//! the silhouette map (Sen, Cammarano & Hanrahan 2003 §3.2) and the
//! depth-fail shadow volumes counted in a stencil (their §5 comparison).

use glam::{DVec3, Mat4, Vec3};
use umbra_core::front::clip::ClipVertex;
use umbra_core::probe::Probe;
use umbra_core::shade::SilhouetteUnit;
use umbra_core::shadow::{MapView, ShadowConfig};
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap, SilhouettePass};
use umbra_core::stencil::{StencilPass, Volume, VolumeLight};
use umbra_core::{ConfigError, DepthFormat, RasterConfig};

use crate::world::occluders::Occluders;
use crate::world::scene::{Light, Scene};

fn clip(m: &Mat4, p: Vec3) -> ClipVertex {
    (*m * p.extend(1.0)).to_array().map(f64::from)
}

/// The silhouette map of `occluders` on the depth map `map` (`light` is
/// its view-projection), its visibility tested with `cfg`'s test and bias.
///
/// # Errors
/// [`ConfigError`] when `map` is unusable.
fn silhouette_map<S: SilStore, F: DepthFormat, P: Probe>(
    occluders: &Occluders,
    light: &Mat4,
    map: &MapView<'_, F>,
    cfg: ShadowConfig,
    probe: &mut P,
) -> Result<Vec<S>, ConfigError> {
    let r = *map.raster();
    let mut texels = vec![S::default(); (r.width() as usize + 1) * (r.height() as usize + 1)];
    let mut pass = SilhouettePass::new(&mut texels, map, cfg)?;
    for [a, b] in occluders.silhouette_edges() {
        pass.draw_clip(&clip(light, a), &clip(light, b), probe);
    }
    Ok(texels)
}

/// A silhouette map's texels in the store its algorithm names: drawn once
/// for a configuration's light, read by its shading and by its judge.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum SilTexels {
    /// Packed texels (Sen et al.'s eight bits a point).
    Packed(Vec<Packed>),
    /// A point a texel, unpacked.
    Points(Vec<SilPoint>),
}

impl SilTexels {
    /// The silhouette map [`silhouette_map`] draws, packed when `packed`.
    ///
    /// # Errors
    /// [`ConfigError`] when `map` is unusable.
    pub(crate) fn draw<F: DepthFormat, P: Probe>(
        packed: bool,
        occluders: &Occluders,
        light: &Mat4,
        map: &MapView<'_, F>,
        cfg: ShadowConfig,
        probe: &mut P,
    ) -> Result<Self, ConfigError> {
        Ok(if packed {
            Self::Packed(silhouette_map::<Packed, F, P>(occluders, light, map, cfg, probe)?)
        } else {
            Self::Points(silhouette_map::<SilPoint, F, P>(occluders, light, map, cfg, probe)?)
        })
    }

    /// `reader` given the silhouette unit over these texels, for a depth
    /// map of `map`'s size.
    ///
    /// # Errors
    /// [`ConfigError`] when the texels do not fit the map's size.
    pub(crate) fn read<R: SilReader>(&self, map: &RasterConfig, reader: R) -> Result<R::Out, ConfigError> {
        let (w, h) = (map.width(), map.height());
        Ok(match self {
            Self::Packed(t) => reader.read(&SilhouetteUnit(&SilhouetteMap::view(w, h, t)?)),
            Self::Points(t) => reader.read(&SilhouetteUnit(&SilhouetteMap::view(w, h, t)?)),
        })
    }
}

impl SilTexels {
    /// `reader` given the silhouette units over each of `all` (a cascaded
    /// light's maps, all of one store), each for a depth map of the size
    /// `maps` gives in turn.
    ///
    /// # Errors
    /// [`ConfigError`] when texels do not fit their map's size, or `all`
    /// mixes packed and unpacked texels.
    pub(crate) fn read_all<R: SilReaderAll>(
        all: &[&Self],
        maps: &[RasterConfig],
        reader: R,
    ) -> Result<R::Out, ConfigError> {
        fn views<'t, S: SilStore>(
            all: impl Iterator<Item = Option<&'t [S]>>,
            maps: &[RasterConfig],
        ) -> Result<Vec<SilhouetteMap<'t, S>>, ConfigError> {
            all.zip(maps)
                .map(|(t, m)| {
                    let t = t.ok_or(ConfigError::Cascades { splits: maps.len(), bands: 0 })?;
                    SilhouetteMap::view(m.width(), m.height(), t)
                })
                .collect()
        }
        Ok(match all.first() {
            Some(Self::Packed(_)) => {
                let maps = views(all.iter().map(|t| if let Self::Packed(p) = t { Some(&p[..]) } else { None }), maps)?;
                reader.read_all(&maps.iter().map(SilhouetteUnit).collect::<Vec<_>>())
            }
            _ => {
                let maps = views(all.iter().map(|t| if let Self::Points(p) = t { Some(&p[..]) } else { None }), maps)?;
                reader.read_all(&maps.iter().map(SilhouetteUnit).collect::<Vec<_>>())
            }
        })
    }
}

/// What reads several silhouette maps of one store through their shadow
/// units ([`SilTexels::read_all`]).
pub(crate) trait SilReaderAll {
    /// What the reading gives.
    type Out;
    /// Read through `units`.
    fn read_all<S: SilStore>(self, units: &[SilhouetteUnit<'_, '_, S>]) -> Self::Out;
}

/// What reads a silhouette map through its shadow unit, whatever the
/// map's store ([`SilTexels::read`]).
pub(crate) trait SilReader {
    /// What the reading gives.
    type Out;
    /// Read through `unit`.
    fn read<S: SilStore>(self, unit: &SilhouetteUnit<'_, '_, S>) -> Self::Out;
}

/// The light as the volumes need it under `camera`, with an extrusion
/// that carries every volume past every point of the scene: a point
/// light's to twice the scene's farthest distance from it, a directional
/// light's by twice the scene's diagonal.
#[must_use]
pub(crate) fn volume_light(scene: &Scene, camera: &Mat4) -> VolumeLight {
    let points = scene.objects.iter().flat_map(|o| o.mesh.positions.iter().map(|p| p.as_dvec3()));
    let light = scene.light();
    let clip4 = |v: glam::Vec4| (*camera * v).to_array().map(f64::from);
    match light {
        Light::Spot(s) | Light::Cone(s) => {
            let l = s.position.as_dvec3();
            let (near, far) = points.fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
                let d = (p - l).length();
                (lo.min(d), hi.max(d))
            });
            let t = if near > 0.0 && near.is_finite() { (2.0 * far / near).min(1e6) } else { 1e6 };
            VolumeLight { clip: clip4(s.position.extend(1.0)), point: true, t }
        }
        Light::Directional(..) => {
            let (lo, hi) = points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
            let diagonal = (hi - lo).length();
            let towards = (-light.direction()).normalize_or_zero();
            let t = if diagonal.is_finite() { 2.0 * diagonal } else { 0.0 };
            VolumeLight { clip: clip4(towards.extend(0.0)), point: false, t }
        }
    }
}

/// Count the shadow volumes of `occluders` into a stencil over the camera
/// target `raster`, against the scene depth `depth` the visibility unit
/// stored under `camera`. Non-zero stencil: in shadow.
///
/// # Errors
/// [`ConfigError`] when a buffer does not fit `raster`.
pub(crate) fn stencil<F: DepthFormat, P: Probe>(
    scene: &Scene,
    occluders: &Occluders,
    camera: &Mat4,
    raster: RasterConfig,
    depth: &[F::Texel],
    probe: &mut P,
) -> Result<Vec<u8>, ConfigError> {
    let light = volume_light(scene, camera);
    let mut stencil = vec![0u8; raster.texel_count()];
    let mut pass = StencilPass::<F>::new(raster, depth, &mut stencil)?;
    for t in &occluders.triangles {
        let volume = Volume { tri: t.positions.map(|p| clip(camera, p)), sides: t.sides };
        for tri in volume.triangles(&light) {
            pass.draw(&tri, probe);
        }
    }
    Ok(stencil)
}
