//! Error metrics of a render against the exact reference, in the terms
//! the papers argue in.
//!
//! A pixel is **wrong** when the ½ verdict (shadowed when more than half
//! of it is) disagrees with the reference's at its centre, or when its
//! filtered shade differs from the reference's area-averaged shadow by
//! more than [`SHADE_STEP`]. Every wrong pixel gets exactly one class,
//! decided by its cause — what the shadow unit compared
//! ([`crate::truth::cause`]), never a distance to an edge:
//!
//! * **acne** (too dark from the receiver's own surface; Wang & Molnar
//!   §2), **detachment** (too light because only the bias moved the test
//!   past an occluder the map holds; their Figure 4) and **leaks** (too
//!   light because the depth compared lies behind the receiver under a
//!   first-layer occluder) and **clipped** occluders (too light because
//!   what shadows the pixel lies outside the light's frustum: the map
//!   never saw it) are the artifacts;
//! * **aliasing** (the taps straddle a true edge or miss the occluder:
//!   edge placement) and **penumbra** (a filter's own partial shade
//!   across a true edge; Reeves et al.) are the map's resolution and the
//!   filter at work.
//!
//! Acne on a surface lit within `GRAZING_COS` of grazing next to where
//! it turns from the light is the terminator's (the occluder's own shadow
//! line; Weiskopf & Ertl §3), the rest the receiver's. Area error and the
//! displacement of the rendered boundary from the exact one are reported
//! besides.

use serde::Serialize;
use umbra_core::shade::Shaded;
use umbra_core::shadow::Shadow;

use crate::truth::cause::{Cause, Judged};
use crate::truth::reference::PixelTruth;

mod fields;
mod footprint;
mod lights;
mod sums;

pub use self::fields::Fields;
pub(crate) use self::footprint::Footprints;
pub(crate) use self::sums::Sums;

/// The smallest difference between a pixel's filtered shadow fraction and
/// the reference's area-averaged shadow that counts as an artifact: 0.1.
///
/// A step of 0.1 in the shadow fraction changes the shaded pixel's direct
/// light by a tenth — five times the 2 % contrast a viewer detects on a
/// uniform surface (Weber's fraction for luminance; Wandell, *Foundations
/// of Vision*, ch. 7) — so every difference above it is visible on a lit
/// receiver, while the reference's own quantisation (steps of 1/16 at its
/// default 4 × 4 rays a pixel) stays below it.
pub const SHADE_STEP: f64 = 0.1;

/// Acne on a surface whose cosine to the light is below this (within about
/// 15.5° of grazing) and within [`TERMINATOR_REACH`] of a surface that
/// faces away from the light is the terminator's: the self-shadowing of
/// an occluder's own shadow line, where its surface turns from the light
/// (the sphere's in Wang & Molnar's Figure 4, the L's silhouettes in
/// Weiskopf & Ertl's Figure 5), rather than a receiver's (a floor lit at
/// grazing, far from any such line).
pub(crate) const GRAZING_COS: f64 = 0.25;

/// How near, in pixels, terminator acne lies to a surface facing away
/// from the light.
pub(crate) const TERMINATOR_REACH: u32 = 16;

/// How a render's shadows compare with the truth, over the pixels whose
/// surface faces the light (the others are dark by shading whatever the
/// shadow test says).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// Pixels compared.
    #[serde(rename = "evaluated_px")]
    pub evaluated: u64,
    /// Shadowed by the pipeline (½ verdict), lit in truth.
    #[serde(rename = "false_shadow_px")]
    pub false_shadow: u64,
    /// Lit by the pipeline (½ verdict), shadowed in truth.
    #[serde(rename = "false_light_px")]
    pub false_light: u64,
    /// `false_shadow / evaluated`, percent.
    pub false_shadow_percent: f64,
    /// `false_light / evaluated`, percent.
    pub false_light_percent: f64,
    /// Both, in percent of the evaluated pixels.
    pub misclassified_percent: f64,
    /// Wrong pixels whose taps straddle a true edge or miss the occluder:
    /// aliasing (edge placement), not an artifact.
    #[serde(rename = "aliasing_px")]
    pub aliasing: u64,
    /// Their summed shade difference from the reference, pixels.
    #[serde(rename = "aliasing_area_px")]
    pub aliasing_area: f64,
    /// Too dark from the receiver's own surface: acne.
    #[serde(rename = "acne_px")]
    pub acne: u64,
    /// Of [`Metrics::acne`], on surfaces within `GRAZING_COS` of grazing
    /// and `TERMINATOR_REACH` of a surface facing away: the terminator's.
    #[serde(rename = "terminator_acne_px")]
    pub terminator_acne: u64,
    /// The acne's summed excess shadow, pixels (a stripe of fraction 0.3
    /// adds 0.3 a pixel).
    #[serde(rename = "acne_area_px")]
    pub acne_area: f64,
    /// Too light because only the bias or offset moved the test past an
    /// occluder the map holds: detached shadows.
    #[serde(rename = "detachment_px")]
    pub detachment: u64,
    /// The detachment's summed missing shadow, pixels.
    #[serde(rename = "detachment_area_px")]
    pub detachment_area: f64,
    /// Too light because the depth compared lies behind the receiver under
    /// a first-layer occluder: leaks.
    #[serde(rename = "leaks_px")]
    pub leaks: u64,
    /// The leaks' summed missing shadow, pixels.
    #[serde(rename = "leak_area_px")]
    pub leak_area: f64,
    /// Too light because what shadows it lies where the map never saw
    /// it (outside the light's frustum, or the pixel outside the map): a
    /// set-up error, an artifact.
    #[serde(rename = "clipped_px")]
    pub clipped: u64,
    /// Their summed missing shadow, pixels.
    #[serde(rename = "clipped_area_px")]
    pub clipped_area: f64,
    /// Wrong pixels whose receiver's plane could not be set up (its
    /// triangle edge-on to the light, or wholly nearer than its near
    /// plane), judged against a flat receiver one step thick.
    #[serde(rename = "receiver_fallback_px")]
    pub receiver_fallbacks: u64,
    /// A filter's own partial shade across a true edge: penumbra, not an
    /// artifact.
    #[serde(rename = "penumbra_px")]
    pub penumbra: u64,
    /// Their summed shade difference from the reference, pixels.
    #[serde(rename = "penumbra_area_px")]
    pub penumbra_area: f64,
    /// How far the penumbra pixels lie from the exact boundary (Chebyshev
    /// pixels, 0 on it): median and 95th percentile — the filter's soft
    /// edge's width on each side.
    #[serde(rename = "penumbra_width_px", serialize_with = "median_p95")]
    pub penumbra_width: [f64; 2],
    /// Artifacts (acne, detachment, leaks and occluders the map never
    /// saw), in percent of the evaluated pixels: the measure error budgets
    /// apply to.
    pub artifact_percent: f64,
    /// Pixels whose filtered shadow fraction is exactly ½: counted as lit.
    #[serde(rename = "ties_px")]
    pub ties: u64,
    /// Mean |pipeline shadow fraction − true shadowed area fraction|.
    pub mean_abs_error: f64,
    /// Root mean square of the same difference.
    pub rms_error: f64,
    /// The rendered boundary's distance from the exact one, pixels: mean,
    /// 95th percentile and largest, over the lit pixels on the rendered
    /// boundary (an evaluated 8-neighbour rendered shadowed), each to the
    /// nearest lit pixel on the exact boundary.
    #[serde(rename = "displacement_px", serialize_with = "mean_p95_max")]
    pub displacement: [f64; 3],
    /// The same in map texels, between the two pixels' light-space points
    /// (where both have one).
    #[serde(serialize_with = "mean_p95_max")]
    pub displacement_texels: [f64; 3],
    /// The map's footprint along the screen's x axis: how far, in texels,
    /// the light-space point moves from one pixel to the next, median and
    /// 95th percentile over the evaluated pixels. Below 1 the map is
    /// magnified that way (a texel covers several pixels, the case Sen et
    /// al.'s §5 assumes), above 1 minified.
    #[serde(rename = "footprint_x_texels_per_px", serialize_with = "median_p95")]
    pub footprint_x: [f64; 2],
    /// The same along y.
    #[serde(rename = "footprint_y_texels_per_px", serialize_with = "median_p95")]
    pub footprint_y: [f64; 2],
    /// How unevenly the map's texels spread over the view: the 95th
    /// percentile of the footprint over its 5th, along x and along y (1:
    /// every pixel the same share of texels; `0` when the 5th is `0`).
    /// Zhang et al. (2006, §3) split cascades to keep it small.
    #[serde(serialize_with = "along_x_y")]
    pub footprint_spread: [f64; 2],
}

/// Along x and along y, named.
fn along_x_y<S: serde::Serializer>(v: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map([("x", v[0]), ("y", v[1])])
}

/// Mean, 95th percentile and largest, named.
fn mean_p95_max<S: serde::Serializer>(v: &[f64; 3], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map([("mean", v[0]), ("p95", v[1]), ("max", v[2])])
}

/// Median and 95th percentile, named.
fn median_p95<S: serde::Serializer>(v: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map([("median", v[0]), ("p95", v[1])])
}

/// Mean, 95th percentile and largest of `v` (zeros when empty).
#[allow(
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    reason = "a count and an index"
)]
fn summary(v: &mut [f64]) -> [f64; 3] {
    // Selected, not sorted: linear in the pixels. The mean is summed in
    // the order the values came.
    if v.is_empty() {
        return [0.0; 3];
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let max = v.iter().copied().fold(f64::NEG_INFINITY, |a, b| if b.total_cmp(&a).is_gt() { b } else { a });
    let at = ((v.len() - 1) as f64 * 0.95).round() as usize;
    let p95 = *v.select_nth_unstable_by(at, f64::total_cmp).1;
    [mean, p95, max]
}

/// One pixel's verdict against the truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Background, or a surface facing away from the light.
    Unevaluated,
    /// Within [`SHADE_STEP`] of the reference, and on the right side of ½.
    Right,
    /// Wrong, for one [`Cause`].
    Wrong(Cause),
}

/// Says why wrong pixels are wrong: [`crate::truth::cause`] replays them
/// through the shadow unit and reads their taps.
pub trait Attribution {
    /// The cause of each wrong pixel `(k, dark)` of `render` (in
    /// increasing `k`; too dark than the reference when `dark`, else too
    /// light), one each, in the same order.
    fn causes(&mut self, wrong: &[(usize, bool)], render: &[Shaded]) -> Vec<Judged>;
}

impl<F: FnMut(usize, &Shaded, bool) -> Cause> Attribution for F {
    fn causes(&mut self, wrong: &[(usize, bool)], render: &[Shaded]) -> Vec<Judged> {
        wrong.iter().map(|&(k, dark)| Judged { cause: self(k, &render[k], dark), fallback: false }).collect()
    }
}

/// Whether the pipeline shadows a pixel: more than half of it is ([`Shadow`]
/// above ½; a tie at exactly ½ counts as lit).
fn shadowed(s: &Shaded) -> bool {
    s.shadow > Shadow::from_bits(1 << 15)
}

/// The pixels whose surface faces the light (the others are dark by
/// shading whatever the shadow test says).
pub(super) fn evaluated(t: &Option<PixelTruth>) -> Option<PixelTruth> {
    t.filter(|t| t.faces_light)
}

/// Whether evaluated pixel `s` is wrong against `t`, and which way:
/// `Some(true)` too dark, `Some(false)` too light, `None` right. A shade
/// off by more than [`SHADE_STEP`] goes its own way; a pixel wrong only
/// by the ½ verdict goes the way of its verdict.
fn wrong(s: &Shaded, t: &PixelTruth) -> Option<bool> {
    let excess = excess_shadow(s, t);
    if excess.abs() > SHADE_STEP { Some(excess > 0.0) } else { (shadowed(s) == t.lit).then_some(t.lit) }
}

/// How much darker the pipeline shades a pixel than the reference: its
/// shadow fraction less the reference's shadowed area fraction.
fn excess_shadow(s: &Shaded, t: &PixelTruth) -> f64 {
    s.shadow.to_num::<f64>() - (1.0 - t.visibility)
}

/// The median and 95th percentile of `v` (zeros when empty).
fn quantiles(mut v: Vec<f64>) -> [f64; 2] {
    let [_, p95, _] = summary(&mut v);
    let half = v.len() / 2;
    let median = if v.is_empty() { 0.0 } else { *v.select_nth_unstable_by(half, f64::total_cmp).1 };
    [median, p95]
}

/// Compare a render with the truth, each wrong pixel judged by `causes`:
/// the metrics and each pixel's verdict.
#[must_use]
pub fn compare(
    render: &[Shaded],
    truth: &[Option<PixelTruth>],
    fields: &Fields,
    causes: &mut impl Attribution,
) -> (Metrics, Vec<Verdict>) {
    compare_with(render, truth, fields, causes, None)
}

/// [`compare`], with the map's footprint over the render when it is known
/// already (one that [`Footprints::fits`] the render, against the same
/// reference; it is worked out otherwise).
pub(crate) fn compare_with(
    render: &[Shaded],
    truth: &[Option<PixelTruth>],
    fields: &Fields,
    causes: &mut dyn Attribution,
    footprints: Option<&Footprints>,
) -> (Metrics, Vec<Verdict>) {
    let mut sums = Sums::new(render.len());
    sums.add(0..render.len(), render, truth, fields, causes);
    sums.finish(render, truth, fields, footprints)
}

impl Metrics {
    /// The percentages of the evaluated pixels, and the mean and RMS
    /// errors from the summed `abs_error` and `square_error` (nothing for
    /// no pixel evaluated).
    #[allow(clippy::cast_precision_loss, reason = "pixel counts far below 2^53")]
    fn rates(&mut self, abs_error: f64, square_error: f64) {
        if self.evaluated == 0 {
            return;
        }
        let n = self.evaluated as f64;
        let (fs, fl) = (self.false_shadow as f64, self.false_light as f64);
        self.false_shadow_percent = 100.0 * fs / n;
        self.false_light_percent = 100.0 * fl / n;
        self.misclassified_percent = 100.0 * (fs + fl) / n;
        self.artifact_percent = 100.0 * (self.acne + self.detachment + self.leaks + self.clipped) as f64 / n;
        self.mean_abs_error = abs_error / n;
        self.rms_error = (square_error / n).sqrt();
    }
}
