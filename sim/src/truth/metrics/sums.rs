//! The metrics summed as the shading writes the pixels: each band of rows
//! judged and added while it is fresh ([`Sums::add`]), the figures over
//! the whole image worked out once the last band is in ([`Sums::finish`]).

use core::ops::Range;

use umbra_core::shade::Shaded;
use umbra_core::shadow::Shadow;

use super::fields::boundary;
use super::{
    Attribution, Fields, Footprints, GRAZING_COS, Metrics, TERMINATOR_REACH, Verdict, evaluated, excess_shadow,
    quantiles, shadowed, summary, wrong,
};
use crate::truth::cause::Cause;
use crate::truth::reference::PixelTruth;

/// A render's metrics as far as its pixels have been added: the counts
/// and areas of each class, the errors' sums, and each pixel's verdict and
/// ½ verdict for the figures over the whole image.
#[derive(Debug, Default)]
pub(crate) struct Sums {
    m: Metrics,
    abs_error: f64,
    square_error: f64,
    penumbra_width: Vec<f64>,
    /// Each evaluated pixel's ½ verdict (shadowed), `None` elsewhere.
    rendered: Vec<Option<bool>>,
    verdicts: Vec<Verdict>,
    /// The wrong pixels of the band being added, and which way.
    wrong: Vec<(usize, bool)>,
}

impl Sums {
    /// Nothing added yet, of a render of `pixels` pixels.
    #[must_use]
    pub(crate) fn new(pixels: usize) -> Self {
        Self { rendered: Vec::with_capacity(pixels), verdicts: Vec::with_capacity(pixels), ..Self::default() }
    }

    /// Add the pixels `band` of `render` (the next ones: every pixel
    /// before it is added), each judged against `truth`, the wrong ones by
    /// `causes`.
    pub(crate) fn add(
        &mut self,
        band: Range<usize>,
        render: &[Shaded],
        truth: &[Option<PixelTruth>],
        fields: &Fields,
        causes: &mut dyn Attribution,
    ) {
        debug_assert_eq!(band.start, self.verdicts.len(), "bands in order");
        let (pixels, truths) =
            (render.get(band.clone()).unwrap_or_default(), truth.get(band.clone()).unwrap_or_default());
        self.wrong.clear();
        for (k, (s, t)) in band.clone().zip(pixels.iter().zip(truths)) {
            let e = evaluated(t);
            self.rendered.push(e.map(|_| shadowed(s)));
            self.verdicts.push(match e {
                None => Verdict::Unevaluated,
                Some(t) => match wrong(s, &t) {
                    None => Verdict::Right,
                    Some(dark) => {
                        self.wrong.push((k, dark));
                        // Judged below.
                        Verdict::Wrong(Cause::Aliasing)
                    }
                },
            });
        }
        if !self.wrong.is_empty() {
            for (&(k, _), judged) in self.wrong.iter().zip(causes.causes(&self.wrong, render)) {
                self.verdicts[k] = Verdict::Wrong(judged.cause);
                self.m.receiver_fallbacks += u64::from(judged.fallback);
            }
        }
        for (k, (s, t)) in band.zip(pixels.iter().zip(truths)) {
            let (Some(t), Some(&v)) = (evaluated(t), self.verdicts.get(k)) else { continue };
            self.pixel(k, s, &t, v, fields);
        }
    }

    /// Count evaluated pixel `k`, shaded `s`, of verdict `v`.
    fn pixel(&mut self, k: usize, s: &Shaded, t: &PixelTruth, v: Verdict, fields: &Fields) {
        let m = &mut self.m;
        m.evaluated += 1;
        m.ties += u64::from(s.shadow == Shadow::from_bits(1 << 15));
        m.false_shadow += u64::from(shadowed(s) && t.lit);
        m.false_light += u64::from(!shadowed(s) && !t.lit);
        let e = excess_shadow(s, t);
        match v {
            Verdict::Wrong(Cause::Aliasing) => {
                m.aliasing += 1;
                m.aliasing_area += e.abs();
            }
            Verdict::Wrong(Cause::Penumbra) => {
                m.penumbra += 1;
                m.penumbra_area += e.abs();
                self.penumbra_width.push(f64::from(fields.to_edge.get(k).copied().unwrap_or(u32::MAX)));
            }
            Verdict::Wrong(Cause::Acne) => {
                m.acne += 1;
                m.acne_area += e.abs();
                let turning = fields.to_away.get(k).is_some_and(|&d| d <= TERMINATOR_REACH);
                m.terminator_acne += u64::from(t.light_cos < GRAZING_COS && turning);
            }
            Verdict::Wrong(Cause::Detachment) => {
                m.detachment += 1;
                m.detachment_area += e.abs();
            }
            Verdict::Wrong(Cause::Leak) => {
                m.leaks += 1;
                m.leak_area += e.abs();
            }
            Verdict::Wrong(Cause::Clipped) => {
                m.clipped += 1;
                m.clipped_area += e.abs();
            }
            Verdict::Right | Verdict::Unevaluated => {}
        }
        self.abs_error += e.abs();
        self.square_error += e * e;
    }

    /// The metrics of `render`, every pixel added, and each pixel's
    /// verdict, with the map's footprint over it when that is known
    /// already (one that [`Footprints::fits`] the render, against the same
    /// reference; it is worked out otherwise).
    #[must_use]
    pub(crate) fn finish(
        self,
        render: &[Shaded],
        truth: &[Option<PixelTruth>],
        fields: &Fields,
        footprints: Option<&Footprints>,
    ) -> (Metrics, Vec<Verdict>) {
        debug_assert_eq!(self.verdicts.len(), render.len(), "every pixel added");
        let Self { mut m, abs_error, square_error, penumbra_width, rendered, verdicts, .. } = self;
        // The rendered boundary's distance from the exact one, lit side to
        // lit side; in map texels between the two pixels' light-space points.
        let texel = |k: usize| render.get(k).and_then(|s| s.light).map(|l| (l.x.to_num::<f64>(), l.y.to_num::<f64>()));
        let (mut pixels, mut texels) = (Vec::new(), Vec::new());
        for (k, on) in boundary(&rendered, fields.width, true).iter().enumerate() {
            let Some(&(d, site)) = fields.to_lit_edge.get(k).filter(|(d, _)| *on && *d != u32::MAX) else { continue };
            pixels.push(f64::from(d));
            if let (Some(a), Some(b)) = (texel(k), texel(site)) {
                texels.push((a.0 - b.0).hypot(a.1 - b.1));
            }
        }
        let worked;
        debug_assert!(footprints.is_none_or(|f| f.fits(render)), "a footprint of other points");
        let footprints = match footprints {
            Some(f) => f,
            None => {
                worked = Footprints::of(render, truth, fields.width);
                &worked
            }
        };
        (m.footprint_x, m.footprint_y, m.footprint_spread) = (footprints.x, footprints.y, footprints.spread);
        m.penumbra_width = quantiles(penumbra_width);
        m.displacement = summary(&mut pixels);
        m.displacement_texels = summary(&mut texels);
        m.rates(abs_error, square_error);
        (m, verdicts)
    }
}
