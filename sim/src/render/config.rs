//! What a render is asked for ([`RenderConfig`]), checked against the
//! limits and turned into the passes' targets before anything is
//! allocated.

use serde::Serialize;
use umbra_core::shadow::Filter;
use umbra_core::{DepthFormatKind, RasterConfig};

use super::{Algorithm, Culling, RenderError};
use crate::input::limits::{Footprint, Limits};
use crate::world::cascade::Cascades;
use crate::world::scene::{Light, Scene};

/// What to render and how.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RenderConfig {
    /// The shadow algorithm (written as `--algo` spells it; a dual offset
    /// or a bias range's end is in the render command).
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub algorithm: Algorithm,
    /// The map's depth format.
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub format: DepthFormatKind,
    /// The map's side in texels.
    pub map_size: u32,
    /// The filter.
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub filter: Filter,
    /// The bias, as a depth in `[0, 1]`.
    pub bias: f64,
    /// Wang & Molnar's virtual samples (second-depth algorithms).
    pub virtual_samples: bool,
    /// Camera image width.
    pub width: u32,
    /// Camera image height.
    pub height: u32,
    /// Reference rays per pixel side for the area-averaged visibility.
    pub reference_rays: u32,
    /// The light pass's culling per object class.
    #[serde(serialize_with = "crate::base::text::serialize")]
    pub culling: Culling,
    /// Every directional light's cascades (`None`: each light's own, as
    /// its scene gives them; one map for a light that gives none).
    pub cascades: Option<Cascades>,
}

/// A render configuration no render takes, naming the quantity and the value.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RenderConfigError {
    /// A bias, `Bias1` or dual offset outside `[0, 1]` (or not a number).
    #[error("{quantity} {value} is not a depth in [0, 1]")]
    Depth {
        /// `bias`, `bias1` or `offset`.
        quantity: &'static str,
        /// The value given.
        value: f64,
    },
    /// Reference rays per pixel side outside `RenderConfig::REFERENCE_RAYS`.
    #[error("reference_rays {0} is outside {range:?}", range = RenderConfig::REFERENCE_RAYS)]
    ReferenceRays(u32),
    /// A map side or image side of zero.
    #[error("{quantity} is 0: it must be at least 1")]
    Zero {
        /// `map_size`, `width` or `height`.
        quantity: &'static str,
    },
    /// A cascade split given outside the camera's depth range, or not
    /// beyond the one before.
    #[error(
        "cascades: the split at view distance {split} does not lie beyond the one before and between the camera's near plane {near} and far plane {far}"
    )]
    Split {
        /// The split given.
        split: f32,
        /// The camera's near plane.
        near: f32,
        /// Its far plane.
        far: f32,
    },
}

/// A render configuration checked once, against its scene and the
/// limits ([`RenderConfig::check`]): what every render and costing takes,
/// so none checks it again.
#[derive(Clone, Copy, Debug)]
pub struct Checked<'s> {
    scene: &'s Scene,
    config: RenderConfig,
}

/// The passes' targets, the map and the camera image, in one tile size.
#[derive(Clone, Copy, Debug)]
pub struct Targets {
    /// The light pass's target (the map).
    pub(super) map: RasterConfig,
    /// The camera pass's target (the image).
    pub(super) image: RasterConfig,
}

impl<'s> Checked<'s> {
    /// The scene it was checked against.
    #[must_use]
    pub const fn scene(&self) -> &'s Scene {
        self.scene
    }

    /// The configuration.
    #[must_use]
    pub const fn config(&self) -> &RenderConfig {
        &self.config
    }

    /// The targets the passes draw, in `tile`-pixel tiles.
    pub(crate) fn targets(&self, tile: u32) -> Result<Targets, RenderError> {
        let bits = RasterConfig::DEFAULT_SUBPIXEL_BITS;
        let c = &self.config;
        let image = RasterConfig::new(c.width, c.height, tile, bits).map_err(RenderError::ImageSize)?;
        // Shadow volumes draw no map: one texel stands for it.
        let side = if c.algorithm == Algorithm::Volumes { 1 } else { c.map_size };
        let map = RasterConfig::new(side, side, tile, bits).map_err(RenderError::MapSize)?;
        Ok(Targets { map, image })
    }
}

impl RenderConfig {
    /// The default render (`umbra render`'s): Wang & Molnar's second depth
    /// with virtual samples, a 24-bit 1024² map, bilinear filtering, no
    /// bias, the algorithm's culling, 960×540 against 4² reference rays a
    /// pixel. Change fields with struct update syntax, then `checked`.
    pub const DEFAULT: Self = Self {
        algorithm: Algorithm::Second,
        format: DepthFormatKind::D24,
        map_size: 1024,
        filter: Filter::Bilinear,
        bias: 0.0,
        virtual_samples: true,
        width: 960,
        height: 540,
        reference_rays: 4,
        culling: Culling::ALGORITHM,
        cascades: None,
    };

    /// Reference rays per pixel side a render takes: the one statement of
    /// the bound, which the command line, Python and sweep files read.
    pub(crate) const REFERENCE_RAYS: std::ops::RangeInclusive<u32> = 1..=16;

    /// `RenderConfig::REFERENCE_RAYS` as a command-line parser's range.
    #[must_use]
    pub fn reference_rays_flag() -> std::ops::RangeInclusive<i64> {
        i64::from(*Self::REFERENCE_RAYS.start())..=i64::from(*Self::REFERENCE_RAYS.end())
    }

    /// `value` if it is a depth in `[0, 1]`, for the quantity named.
    ///
    /// # Errors
    /// [`RenderConfigError::Depth`].
    pub(crate) fn depth(quantity: &'static str, value: f64) -> Result<f64, RenderConfigError> {
        if value.is_finite() && (0.0..=1.0).contains(&value) {
            Ok(value)
        } else {
            Err(RenderConfigError::Depth { quantity, value })
        }
    }

    /// The configuration, if a render takes it: every bias and offset a
    /// depth in `[0, 1]`, 1 to 16 reference rays a side, no side of zero.
    /// (Sizes against a machine's [`Limits`] are checked by
    /// [`check`](Self::check), the filter against the shadow unit when the
    /// render starts.) Sweep files call it to report a mistake before
    /// anything runs.
    ///
    /// # Errors
    /// [`RenderConfigError`] naming the first quantity out of range.
    pub(crate) fn checked(self) -> Result<Self, RenderConfigError> {
        Self::depth("bias", self.bias)?;
        if let Some(hi) = self.algorithm.bias_hi() {
            Self::depth("bias1", hi)?;
        }
        if let Some(offset) = self.algorithm.offset() {
            Self::depth("offset", offset)?;
        }
        if !Self::REFERENCE_RAYS.contains(&self.reference_rays) {
            return Err(RenderConfigError::ReferenceRays(self.reference_rays));
        }
        for (quantity, side) in [("map_size", self.map_size), ("width", self.width), ("height", self.height)] {
            if side == 0 {
                return Err(RenderConfigError::Zero { quantity });
            }
        }
        Ok(self)
    }

    /// The cascades light `k` of `scene` is drawn through: a directional
    /// light's, as this configuration or the scene gives them; one map
    /// for any other light, and for shadow volumes, which draw none.
    #[must_use]
    pub fn cascades_of(&self, scene: &Scene, k: usize) -> Cascades {
        match scene.lights.get(k) {
            Some(Light::Directional(_, own)) if self.algorithm != Algorithm::Volumes => self.cascades.unwrap_or(*own),
            _ => Cascades::ONE,
        }
    }

    /// Whether any light of `scene` is drawn through cascades: a study
    /// renders such a configuration on its own.
    #[must_use]
    pub fn cascaded(&self, scene: &Scene) -> bool {
        (0..scene.lights.len()).any(|k| self.cascades_of(scene, k).cascaded())
    }

    /// The configuration in words, every field (for the records outputs carry).
    #[must_use]
    pub fn describe(&self) -> String {
        // Shadow volumes use no map: no format, side, filter or bias of one.
        if self.algorithm == Algorithm::Volumes {
            return format!("volumes, image {}x{}, {}² reference rays", self.width, self.height, self.reference_rays);
        }
        let cascades = self.cascades.map_or_else(String::new, |c| format!(", cascades {c}"));
        format!(
            "{}, {}, map {}², filter {}, bias {}, virtual samples {}, culling {}{cascades}, image {}x{}, {}² reference rays",
            self.algorithm.flags().trim_start_matches("--algo "),
            self.format.name(),
            self.map_size,
            self.filter,
            self.bias,
            self.virtual_samples,
            self.culling,
            self.width,
            self.height,
            self.reference_rays
        )
    }

    /// The `umbra render` command line that renders this configuration of
    /// `scene` (a bundled name or a file, and its camera) again, bit for bit.
    #[must_use]
    pub fn command(&self, scene: &Scene) -> String {
        format!("umbra render {} {}", scene.arguments(), super::params::flags(self))
    }

    /// This configuration checked for a render of `scene` within `limits`:
    /// its values (`checked`), then the map side, the
    /// image size, the scene's triangles and the memory, all together
    /// ([`Footprint::render`]), before anything is allocated. Every render
    /// and costing takes the result, so a caller checks once, before it
    /// writes anything.
    ///
    /// ```
    /// use umbra_sim::{Limits, RenderConfig, Scene};
    /// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
    /// let huge = RenderConfig { map_size: 1 << 16, ..RenderConfig::DEFAULT };
    /// assert!(huge.check(&scene, &Limits::DEFAULT).is_err());
    /// assert!(RenderConfig::DEFAULT.check(&scene, &Limits::DEFAULT).is_ok());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`RenderError`] naming the first quantity out of range or beyond its limit.
    pub fn check<'s>(self, scene: &'s Scene, limits: &Limits) -> Result<Checked<'s>, RenderError> {
        self.checked()?;
        limits.check_map(self.map_size)?;
        limits.check_image(self.width, self.height)?;
        let triangles: usize = scene.objects.iter().map(|o| o.mesh.triangles.len()).sum();
        let triangles = u64::try_from(triangles).unwrap_or(u64::MAX);
        limits.check_triangles(triangles)?;
        let pixels = u64::from(self.width) * u64::from(self.height);
        let lights = (scene.lights.len() + scene.shadowless.len()) as u64;
        // Each cascade a map of its own, and an image its shading writes.
        let (near, far) = scene.camera.planes();
        let mut extra = 0u64;
        for k in 0..scene.lights.len() {
            let cascades = self.cascades_of(scene, k);
            if !cascades.cascaded() {
                continue;
            }
            if let Some(split) = cascades.misplaced_split(near, far) {
                return Err(RenderConfigError::Split { split, near, far }.into());
            }
            for c in 0..cascades.count() {
                let side = cascades.side(c, self.map_size);
                limits.check_map(side)?;
                let texels = u64::from(side) * u64::from(side);
                extra = extra.saturating_add(texels.saturating_mul(Footprint::PER_TEXEL));
            }
            extra = extra.saturating_add(pixels.saturating_mul(Footprint::PER_PIXEL));
        }
        let footprint = Footprint::render_lit(pixels, self.map_size, triangles, lights).saturating_add(extra);
        limits.check_memory("the render", footprint)?;
        let checked = Checked { scene, config: self };
        checked.targets(RasterConfig::DEFAULT_TILE_SIZE)?;
        Ok(checked)
    }
}
