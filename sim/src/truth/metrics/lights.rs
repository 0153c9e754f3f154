//! A frame's metrics over several shadow-casting lights: each pixel is
//! judged once per light it faces (what the shadow unit compared for that
//! light against that light's exact reference), so the frame's figures are
//! over (pixel, light) pairs.

use super::Metrics;

impl Metrics {
    /// The metrics of a frame of several lights, from each light's: the
    /// counts and areas summed over (pixel, light) pairs, the percentages
    /// and the mean and RMS errors over those pairs; a mean (of the
    /// boundary's displacement) weighted by each light's evaluated pixels;
    /// a median, 95th percentile or maximum, which do not add, the largest
    /// of the lights'. One light's metrics are its own.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "pixel counts far below 2^53")]
    pub fn of_lights(lights: &[Self]) -> Self {
        if let [one] = lights {
            return *one;
        }
        let mut m = Self::default();
        let largest = |a: &mut f64, b: f64| *a = a.max(b);
        let (mut abs_error, mut square_error, mut displacement, mut texels) = (0.0, 0.0, 0.0, 0.0);
        for l in lights {
            m.evaluated += l.evaluated;
            m.false_shadow += l.false_shadow;
            m.false_light += l.false_light;
            m.aliasing += l.aliasing;
            m.aliasing_area += l.aliasing_area;
            m.acne += l.acne;
            m.terminator_acne += l.terminator_acne;
            m.acne_area += l.acne_area;
            m.detachment += l.detachment;
            m.detachment_area += l.detachment_area;
            m.leaks += l.leaks;
            m.leak_area += l.leak_area;
            m.clipped += l.clipped;
            m.clipped_area += l.clipped_area;
            m.receiver_fallbacks += l.receiver_fallbacks;
            m.penumbra += l.penumbra;
            m.penumbra_area += l.penumbra_area;
            m.ties += l.ties;
            let n = l.evaluated as f64;
            abs_error += l.mean_abs_error * n;
            square_error += l.rms_error * l.rms_error * n;
            displacement += l.displacement[0] * n;
            texels += l.displacement_texels[0] * n;
            for k in 0..2 {
                largest(&mut m.penumbra_width[k], l.penumbra_width[k]);
                largest(&mut m.footprint_x[k], l.footprint_x[k]);
                largest(&mut m.footprint_y[k], l.footprint_y[k]);
                largest(&mut m.footprint_spread[k], l.footprint_spread[k]);
            }
            for k in 1..3 {
                largest(&mut m.displacement[k], l.displacement[k]);
                largest(&mut m.displacement_texels[k], l.displacement_texels[k]);
            }
        }
        m.rates(abs_error, square_error);
        if m.evaluated > 0 {
            let n = m.evaluated as f64;
            m.displacement[0] = displacement / n;
            m.displacement_texels[0] = texels / n;
        }
        m
    }
}
