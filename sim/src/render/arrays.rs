//! A render's results pixel by pixel, as arrays: what `umbra render`
//! writes as `.npy` files beside its pictures, and what a script reads.

use super::{PartRef, Render};
use crate::truth::cause::Cause;
use crate::truth::metrics::Verdict;

/// A render's per-pixel arrays, each `height × width` in row-major order
/// (the camera image's first row first).
#[derive(Clone, Debug, PartialEq)]
pub struct PixelArrays {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The pipeline's shadow fraction, 0 (lit) to 1 (in shadow), exactly
    /// the shadow unit's 16.16 fixed-point result; NaN where no triangle
    /// covers the pixel.
    pub shadow: Vec<f32>,
    /// The exact reference's shadowed fraction of the pixel's area
    /// (1 − the fraction its reference rays see the light); NaN for the
    /// background.
    pub reference: Vec<f32>,
    /// Each pixel's verdict as a code (`Verdict::code`): 0 unevaluated,
    /// 1 right, 2 aliasing, 3 acne, 4 leak, 5 detachment, 6 penumbra,
    /// 7 clipped (an occluder the map never saw).
    pub verdict: Vec<u8>,
}

impl Verdict {
    /// The verdict's code in [`PixelArrays::verdict`]: 0 unevaluated,
    /// 1 right, then the causes (the codes of earlier releases kept: 2 was
    /// edge placement, now aliasing).
    #[must_use]
    pub(crate) const fn code(self) -> u8 {
        match self {
            Self::Unevaluated => 0,
            Self::Right => 1,
            Self::Wrong(Cause::Aliasing) => 2,
            Self::Wrong(Cause::Acne) => 3,
            Self::Wrong(Cause::Leak) => 4,
            Self::Wrong(Cause::Detachment) => 5,
            Self::Wrong(Cause::Penumbra) => 6,
            Self::Wrong(Cause::Clipped) => 7,
        }
    }
}

impl PixelArrays {
    /// The arrays of `render`.
    ///
    /// ```
    /// use umbra_sim::{Limits, RenderConfig, Scene, TruthSource};
    /// use umbra_sim::render::arrays::PixelArrays;
    /// let scene = Scene::open("weiskopf-l", &Limits::DEFAULT)?;
    /// let cfg = RenderConfig { width: 96, height: 72, map_size: 256, reference_rays: 1, ..RenderConfig::DEFAULT };
    /// let r = umbra_sim::render(&cfg.check(&scene, &Limits::DEFAULT)?, TruthSource::Quiet)?;
    /// let a = PixelArrays::of(&r);
    /// assert_eq!(a.shadow.len(), 96 * 72);
    /// // Each verdict counted by the metrics is a code in the array.
    /// assert_eq!(a.verdict.iter().filter(|&&v| v == 3).count() as u64, r.metrics.acne);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn of(render: &Render) -> Self {
        Self::of_part(render.parts().next().unwrap_or_else(|| unreachable!("a render has a first light")))
    }

    /// The arrays of one light's part of a render.
    #[must_use]
    #[allow(clippy::cast_possible_truncation, reason = "a fraction in [0, 1], kept as f32")]
    pub fn of_part(part: PartRef<'_>) -> Self {
        let image = part.image;
        let shadow = image
            .pixels
            .iter()
            .map(|p| if p.triangle == umbra_core::NO_TRIANGLE { f32::NAN } else { p.shadow.to_num::<f32>() })
            .collect();
        let reference = part.truth.iter().map(|t| t.map_or(f32::NAN, |t| (1.0 - t.visibility) as f32)).collect();
        let verdict = part.verdicts.iter().copied().map(Verdict::code).collect();
        Self { width: image.width, height: image.height, shadow, reference, verdict }
    }
}
