//! Error metrics of a render against the exact reference.

use serde::Serialize;
use umbra_core::shade::Shaded;
use umbra_core::shadow::Shadow;

use crate::truth::reference::PixelTruth;

/// How a render's shadows compare with the truth, over the pixels whose
/// surface faces the light (the others are dark by shading whatever the
/// shadow test says).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// Pixels compared.
    pub evaluated: u64,
    /// Shadowed by the pipeline, lit in truth (acne, self-shadowing).
    pub false_shadow: u64,
    /// Lit by the pipeline, shadowed in truth (leaks, detached shadows).
    pub false_light: u64,
    /// `false_shadow / evaluated`.
    pub false_shadow_rate: f64,
    /// `false_light / evaluated`.
    pub false_light_rate: f64,
    /// Both, in percent of the evaluated pixels.
    pub misclassified_percent: f64,
    /// Mean |pipeline shadow fraction − true shadowed area fraction|.
    pub mean_abs_error: f64,
}

/// Compare a render with the truth. A pixel counts as shadowed by the
/// pipeline when more than half of it is ([`Shadow`] above ½).
#[must_use]
pub fn compare(render: &[Shaded], truth: &[Option<PixelTruth>]) -> Metrics {
    let half = Shadow::from_bits(1 << 15);
    let mut m = Metrics::default();
    let mut abs_error = 0.0;
    for (s, t) in render.iter().zip(truth) {
        let Some(t) = t.filter(|t| t.faces_light) else { continue };
        m.evaluated += 1;
        let shadowed = s.shadow > half;
        m.false_shadow += u64::from(shadowed && t.lit);
        m.false_light += u64::from(!shadowed && !t.lit);
        abs_error += (s.shadow.to_num::<f64>() - (1.0 - t.visibility)).abs();
    }
    if m.evaluated > 0 {
        #[allow(clippy::cast_precision_loss, reason = "pixel counts")]
        let n = m.evaluated as f64;
        #[allow(clippy::cast_precision_loss, reason = "pixel counts")]
        let (fs, fl) = (m.false_shadow as f64, m.false_light as f64);
        m.false_shadow_rate = fs / n;
        m.false_light_rate = fl / n;
        m.misclassified_percent = 100.0 * (fs + fl) / n;
        m.mean_abs_error = abs_error / n;
    }
    m
}
