//! A cascaded light judged: each cascade's pixels against the light's
//! exact reference through the shadow unit that read that cascade's map
//! (its metrics: the cascade's own), then the light's whole image with
//! each wrong pixel's cause as its cascade's judge found it (the light's
//! metrics), the map's footprint between neighbours on the same cascade.

use umbra_core::DepthFormat;
use umbra_core::shade::Shaded;

use super::replay::{PassInputs, with_judge};
use crate::pass::PassError;
use crate::truth::cause::Judged;
use crate::truth::metrics::{Attribution, Fields, Footprints, Metrics, Verdict, compare_with};
use crate::truth::reference::{PixelTruth, Reference};
use crate::world::scene::Light;

/// One cascade of a cascaded light as a render produced it: the light
/// its map was drawn through, the slice of the view it holds, its map's
/// side, its metrics and its light pass's event totals.
#[derive(Clone, Copy, Debug)]
pub struct CascadePart {
    /// Its light: the scene's, fitted to its slice.
    pub light: Light,
    /// The view distances its slice lies between.
    pub slice: [f32; 2],
    /// Its map's side in texels.
    pub side: u32,
    /// Its pixels against the light's exact reference.
    pub metrics: Metrics,
    /// Its light pass's events.
    pub events: umbra_core::probe::Totals,
}

/// The causes each cascade's judge found, kept for the light's: the judge
/// reads each pixel as its own cascade shaded it (`own`: in a blend band,
/// before the next cascade's fraction is mixed in).
struct Recording<'a> {
    judge: &'a mut dyn Attribution,
    own: &'a [Shaded],
    kept: &'a mut [Option<Judged>],
}

impl Attribution for Recording<'_> {
    fn causes(&mut self, wrong: &[(usize, bool)], _: &[Shaded]) -> Vec<Judged> {
        let judged = self.judge.causes(wrong, self.own);
        for (&(k, _), j) in wrong.iter().zip(&judged) {
            if let Some(slot) = self.kept.get_mut(k) {
                *slot = Some(*j);
            }
        }
        judged
    }
}

/// The causes kept, read back.
struct Recorded<'a>(&'a [Option<Judged>]);

impl Attribution for Recorded<'_> {
    fn causes(&mut self, wrong: &[(usize, bool)], _: &[Shaded]) -> Vec<Judged> {
        wrong
            .iter()
            .map(|&(k, _)| {
                // Every pixel wrong in the light's image is wrong in its
                // cascade's: the same pixel against the same reference.
                self.0
                    .get(k)
                    .copied()
                    .flatten()
                    .unwrap_or(Judged { cause: crate::truth::cause::Cause::Aliasing, fallback: false })
            })
            .collect()
    }
}

/// A cascaded light's image `pixels`, whose pixel `k` read cascade
/// `cascade_of[k]` (shaded as `each[c]` says, the judge's inputs of
/// cascade `c`; `own` each pixel as that cascade shaded it, before a
/// blend band mixed it), judged against the light's reference: the
/// light's metrics and verdicts, and each cascade's metrics. A pixel is
/// wrong or right by its mixed fraction, and wrong for the cause its own
/// cascade's taps give.
///
/// # Errors
/// [`PassError`] when a silhouette map cannot be read again.
pub(super) fn judged<F: DepthFormat>(
    each: &[PassInputs<'_, F>],
    (pixels, own, cascade_of): (&[Shaded], &[Shaded], &[u8]),
    (truth, fields, reference): (&[Option<PixelTruth>], &Fields, &Reference),
) -> Result<(Metrics, Vec<Verdict>, Vec<Metrics>), PassError> {
    let mut kept = vec![None; pixels.len()];
    let mut cascades = Vec::with_capacity(each.len());
    for (c, what) in each.iter().enumerate() {
        let mine: Vec<Option<PixelTruth>> =
            truth.iter().zip(cascade_of).map(|(t, &k)| if usize::from(k) == c { *t } else { None }).collect();
        let (metrics, _) = with_judge(what, (reference, fields), |judge| {
            compare_with(pixels, &mine, fields, &mut Recording { judge, own, kept: &mut kept }, None)
        })?;
        cascades.push(metrics);
    }
    let footprints = Footprints::of_parts(pixels, truth, fields.width, cascade_of);
    let (metrics, verdicts) = compare_with(pixels, truth, fields, &mut Recorded(&kept), Some(&footprints));
    Ok((metrics, verdicts, cascades))
}
