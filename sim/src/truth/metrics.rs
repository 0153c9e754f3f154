//! Error metrics of a render against the exact reference: misclassified
//! pixels, split into edge placement and artifacts by their distance to the
//! reference's shadow boundary; area error; and the displacement of the
//! rendered boundary from the exact one.

use serde::Serialize;
use umbra_core::shade::Shaded;
use umbra_core::shadow::Shadow;

use crate::truth::reference::PixelTruth;

/// A misclassified pixel this close to the reference's shadow boundary is
/// edge placement, farther an artifact. The distance is Chebyshev, in
/// pixels, to the nearest pixel with an 8-neighbour of the other exact
/// verdict: at 0, the exact boundary passes within a pixel of the pixel's
/// centre (1½ diagonally), so which side its centre falls on is a coin
/// toss at the image's resolution, not an error of the algorithm.
pub const EDGE_DISTANCE: u32 = 0;

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
    /// Misclassified pixels within [`EDGE_DISTANCE`] of the reference's
    /// shadow boundary.
    pub edge_placement: u64,
    /// False shadows farther from it: acne and self-shadowing.
    pub acne: u64,
    /// False light farther from it: leaks and detached shadows.
    pub leaks: u64,
    /// Artifacts (acne and leaks), in percent of the evaluated pixels.
    pub artifact_percent: f64,
    /// Pixels whose filtered shadow fraction is exactly ½: counted as lit.
    pub ties: u64,
    /// Mean |pipeline shadow fraction − true shadowed area fraction|.
    pub mean_abs_error: f64,
    /// Root mean square of the same difference.
    pub rms_error: f64,
    /// The rendered boundary's distance from the exact one, pixels: mean,
    /// 95th percentile and largest, over the lit pixels on the rendered
    /// boundary (an evaluated 8-neighbour rendered shadowed), each to the
    /// nearest lit pixel on the exact boundary.
    pub displacement: [f64; 3],
    /// The same in map texels, between the two pixels' light-space points
    /// (where both have one).
    pub displacement_texels: [f64; 3],
    /// The map's footprint on screen: the median distance, in map texels,
    /// between the light-space points of horizontally adjacent evaluated
    /// pixels on the same surface. Below 1 the map is magnified (a texel
    /// covers several pixels, the case Sen et al.'s §5 bandwidth argument
    /// assumes), above 1 minified.
    pub texels_per_pixel: f64,
}

/// Mean, 95th percentile and largest of `v` (zeros when empty).
#[allow(
    clippy::cast_precision_loss,
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    reason = "a count and an index"
)]
fn summary(v: &mut [f64]) -> [f64; 3] {
    v.sort_by(f64::total_cmp);
    let Some(&max) = v.last() else { return [0.0; 3] };
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let p95 = v[((v.len() - 1) as f64 * 0.95).round() as usize];
    [mean, p95, max]
}

/// Chebyshev distance, in pixels, from every pixel of a `width`-wide image
/// to the nearest pixel marked in `sites` (`u32::MAX` when there is none),
/// and which site that is: two chamfer passes, exact for this metric.
fn distance(sites: &[bool], width: usize) -> Vec<(u32, usize)> {
    let mut d: Vec<(u32, usize)> = sites.iter().enumerate().map(|(k, &s)| (if s { 0 } else { u32::MAX }, k)).collect();
    let height = d.len().checked_div(width).unwrap_or(0);
    // Take the nearer of a pixel's own site and its neighbours' (at `steps`) plus one.
    let mut relax = |x: usize, y: usize, steps: [(isize, isize); 4]| {
        let mut best = d[y * width + x];
        for (dx, dy) in steps {
            if let Some(k) = neighbour(x, y, dx, dy, width, height) {
                let (nd, site) = d[k];
                if nd.saturating_add(1) < best.0 {
                    best = (nd + 1, site);
                }
            }
        }
        d[y * width + x] = best;
    };
    for y in 0..height {
        for x in 0..width {
            relax(x, y, [(-1, -1), (0, -1), (1, -1), (-1, 0)]);
        }
    }
    for y in (0..height).rev() {
        for x in (0..width).rev() {
            relax(x, y, [(1, 1), (0, 1), (-1, 1), (1, 0)]);
        }
    }
    d
}

/// The index of the pixel `(dx, dy)` from `(x, y)`, if it is inside.
fn neighbour(x: usize, y: usize, dx: isize, dy: isize, width: usize, height: usize) -> Option<usize> {
    let (nx, ny) = (x.checked_add_signed(dx)?, y.checked_add_signed(dy)?);
    (nx < width && ny < height).then(|| ny * width + nx)
}

/// Pixels on a boundary of `dark` (`None`: not evaluated): evaluated, with
/// an evaluated 8-neighbour of the other verdict; only the lit ones when
/// `lit_side` (so that a boundary is one pixel thick and a shift by k
/// pixels moves it by k).
fn boundary(dark: &[Option<bool>], width: usize, lit_side: bool) -> Vec<bool> {
    let height = dark.len().checked_div(width).unwrap_or(0);
    (0..dark.len())
        .map(|k| {
            let Some(v) = dark[k].filter(|&v| !(lit_side && v)) else { return false };
            let (x, y) = (k % width, k / width);
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| neighbour(x, y, dx, dy, width, height).and_then(|n| dark[n]).is_some_and(|n| n != v))
            })
        })
        .collect()
}

/// One pixel's verdict against the truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Background, or a surface facing away from the light.
    Unevaluated,
    /// Shadowed or lit as in truth.
    Right,
    /// Misclassified within [`EDGE_DISTANCE`] of the exact boundary.
    EdgePlacement,
    /// Shadowed in error away from it.
    Acne,
    /// Lit in error away from it.
    Leak,
}

/// Whether the pipeline shadows a pixel: more than half of it is ([`Shadow`]
/// above ½; a tie at exactly ½ counts as lit).
fn shadowed(s: &Shaded) -> bool {
    s.shadow > Shadow::from_bits(1 << 15)
}

/// The pixels whose surface faces the light (the others are dark by
/// shading whatever the shadow test says).
fn evaluated(t: &Option<PixelTruth>) -> Option<PixelTruth> {
    t.filter(|t| t.faces_light)
}

/// Each pixel's verdict, for a `width`-wide render: the counts
/// [`compare`] reports, pixel by pixel (the error map draws them).
#[must_use]
pub fn verdicts(render: &[Shaded], truth: &[Option<PixelTruth>], width: u32) -> Vec<Verdict> {
    let exact: Vec<Option<bool>> = truth.iter().map(|t| evaluated(t).map(|t| !t.lit)).collect();
    let to_edge = distance(&boundary(&exact, width as usize, false), width as usize);
    render
        .iter()
        .zip(truth)
        .enumerate()
        .map(|(k, (s, t))| {
            let Some(t) = evaluated(t) else { return Verdict::Unevaluated };
            let (false_shadow, false_light) = (shadowed(s) && t.lit, !shadowed(s) && !t.lit);
            #[allow(
                clippy::absurd_extreme_comparisons,
                reason = "the stated distance is a parameter that may be raised"
            )]
            let near = to_edge.get(k).is_some_and(|&(d, _)| d <= EDGE_DISTANCE);
            match (false_shadow, false_light, near) {
                (false, false, _) => Verdict::Right,
                (_, _, true) => Verdict::EdgePlacement,
                (true, _, false) => Verdict::Acne,
                (false, true, false) => Verdict::Leak,
            }
        })
        .collect()
}

/// Compare a `width`-wide render with the truth. A pixel counts as shadowed
/// by the pipeline when more than half of it is ([`Shadow`] above ½; a tie
/// at exactly ½ counts as lit, and is counted in [`Metrics::ties`]).
#[must_use]
#[allow(
    clippy::cast_precision_loss,
    clippy::cast_possible_wrap,
    clippy::cast_sign_loss,
    reason = "pixel counts and coordinates"
)]
pub fn compare(render: &[Shaded], truth: &[Option<PixelTruth>], width: u32) -> Metrics {
    let verdicts = verdicts(render, truth, width);
    let width = width as usize;
    let exact: Vec<Option<bool>> = truth.iter().map(|t| evaluated(t).map(|t| !t.lit)).collect();
    let rendered: Vec<Option<bool>> =
        render.iter().zip(truth).map(|(s, t)| evaluated(t).map(|_| shadowed(s))).collect();
    let to_lit_edge = distance(&boundary(&exact, width, true), width);
    let mut m = Metrics::default();
    let (mut abs_error, mut square_error) = (0.0, 0.0);
    for ((s, t), v) in render.iter().zip(truth).zip(&verdicts) {
        let Some(t) = evaluated(t) else { continue };
        m.evaluated += 1;
        m.ties += u64::from(s.shadow == Shadow::from_bits(1 << 15));
        m.false_shadow += u64::from(shadowed(s) && t.lit);
        m.false_light += u64::from(!shadowed(s) && !t.lit);
        m.edge_placement += u64::from(*v == Verdict::EdgePlacement);
        m.acne += u64::from(*v == Verdict::Acne);
        m.leaks += u64::from(*v == Verdict::Leak);
        let e = s.shadow.to_num::<f64>() - (1.0 - t.visibility);
        abs_error += e.abs();
        square_error += e * e;
    }
    // The rendered boundary's distance from the exact one, lit side to lit
    // side.
    // In map texels: between the two pixels' light-space points.
    let texel = |k: usize| render.get(k).and_then(|s| s.light).map(|l| (l.x.to_num::<f64>(), l.y.to_num::<f64>()));
    let (mut pixels, mut texels) = (Vec::new(), Vec::new());
    for (k, on) in boundary(&rendered, width, true).iter().enumerate() {
        let Some(&(d, site)) = to_lit_edge.get(k).filter(|(d, _)| *on && *d != u32::MAX) else { continue };
        pixels.push(f64::from(d));
        if let (Some(a), Some(b)) = (texel(k), texel(site)) {
            texels.push((a.0 - b.0).hypot(a.1 - b.1));
        }
    }
    // The footprint: horizontal neighbours, both evaluated, on one surface
    // (a jump of more than 8 texels is taken as another surface).
    let mut steps: Vec<f64> = (1..render.len())
        .filter(|&k| k % width != 0 && rendered[k].is_some() && rendered[k - 1].is_some())
        .filter_map(|k| Some((texel(k)?, texel(k - 1)?)))
        .map(|(a, b)| (a.0 - b.0).hypot(a.1 - b.1))
        .filter(|d| *d <= 8.0)
        .collect();
    steps.sort_by(f64::total_cmp);
    m.texels_per_pixel = steps.get(steps.len() / 2).copied().unwrap_or(0.0);
    m.displacement = summary(&mut pixels);
    m.displacement_texels = summary(&mut texels);
    if m.evaluated > 0 {
        let n = m.evaluated as f64;
        let (fs, fl) = (m.false_shadow as f64, m.false_light as f64);
        m.false_shadow_rate = fs / n;
        m.false_light_rate = fl / n;
        m.misclassified_percent = 100.0 * (fs + fl) / n;
        m.artifact_percent = 100.0 * (m.acne + m.leaks) as f64 / n;
        m.mean_abs_error = abs_error / n;
        m.rms_error = (square_error / n).sqrt();
    }
    m
}
