//! The map's footprint on screen: how far the light-space point moves
//! from one pixel to the next. It depends on the visible surfaces' points
//! on the map, not on how the map is filtered or tested, so renders of
//! one visibility and one map side share it ([`Footprints`]).

use glam::DVec2;
use umbra_core::shade::Shaded;

use super::fields::neighbour;
use super::{evaluated, quantiles};
use crate::truth::reference::PixelTruth;

/// Neighbouring pixels whose light-space points are farther apart than
/// this, in texels, are on different surfaces (or across a depth
/// discontinuity) and give no derivative.
const SAME_SURFACE_TEXELS: f64 = 8.0;

/// A pixel's light-space point's derivatives along x and y, texels per pixel.
pub(super) type Derivatives = (Option<DVec2>, Option<DVec2>);

/// Each evaluated pixel's light-space point of a `width`-wide render,
/// converted once, from which the map's footprint at any pixel follows.
pub(super) struct Points<'p> {
    points: Vec<Option<DVec2>>,
    width: usize,
    height: usize,
    /// Each pixel's map (a cascade), where the render read several: a
    /// neighbour on another map gives no derivative.
    parts: &'p [u8],
}

std::thread_local! {
    /// The last measure's points on this thread, for the next to fill
    /// without fresh pages.
    static SPARE_POINTS: core::cell::RefCell<Vec<Option<DVec2>>> = const { core::cell::RefCell::new(Vec::new()) };
}

impl<'p> Points<'p> {
    pub(super) fn new(render: &[Shaded], truth: &[Option<PixelTruth>], width: usize, parts: &'p [u8]) -> Self {
        let mut points = SPARE_POINTS.with(|p| p.take());
        points.clear();
        points.extend(render.iter().zip(truth).map(|(s, t)| {
            let l = s.light?;
            evaluated(t)?;
            Some(DVec2::new(l.x.to_num(), l.y.to_num()))
        }));
        let height = render.len().checked_div(width).unwrap_or(0);
        Self { points, width, height, parts }
    }

    /// Give the buffer back for the next measure on this thread.
    pub(super) fn recycle(self) {
        SPARE_POINTS.with(|p| p.replace(self.points));
    }

    fn at(&self, k: usize) -> Option<DVec2> {
        self.points.get(k).copied().flatten()
    }

    /// The map's footprint at pixel `k`: the derivatives of the light-space
    /// point along x and along y, texels per pixel (central differences,
    /// one-sided at a surface's edge; `None` where the pixel has no
    /// neighbour on its surface that way).
    pub(super) fn footprint(&self, k: usize) -> Derivatives {
        let Some(c) = self.at(k) else { return (None, None) };
        let part = self.parts.get(k);
        let derivative = |before: Option<usize>, after: Option<usize>| {
            let near = |n: Option<usize>| {
                n.filter(|&n| self.parts.get(n) == part)
                    .and_then(|n| self.at(n))
                    .filter(|p| (*p - c).length() <= SAME_SURFACE_TEXELS)
            };
            match (near(before), near(after)) {
                (Some(a), Some(b)) => Some((b - a) / 2.0),
                (Some(a), None) => Some(c - a),
                (None, Some(b)) => Some(b - c),
                (None, None) => None,
            }
        };
        let (x, y) = (k % self.width, k / self.width);
        let n = |dx, dy| neighbour(x, y, dx, dy, self.width, self.height);
        (derivative(n(-1, 0), n(1, 0)), derivative(n(0, -1), n(0, 1)))
    }
}

/// The map's footprint over a render: the median and 95th percentile of
/// its derivatives' lengths along x and along y, texels per pixel, and
/// every pixel's light-space point (exactly, in map coordinates' bits)
/// they come from, so that a render of the same image, against the same
/// reference, with the same points takes them as they are.
#[derive(Debug)]
pub(crate) struct Footprints {
    points: Vec<Option<[i32; 2]>>,
    pub(super) x: [f64; 2],
    pub(super) y: [f64; 2],
    /// The 95th percentile over the 5th, along x and along y.
    pub(super) spread: [f64; 2],
}

/// The 95th percentile of `v` over its 5th (`0` when the 5th is `0`, or
/// `v` empty).
#[allow(clippy::cast_precision_loss, clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "an index")]
fn spread(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let last = (v.len() - 1) as f64;
    let at = |q: f64| (last * q).round() as usize;
    let p5 = *v.select_nth_unstable_by(at(0.05), f64::total_cmp).1;
    let p95 = *v.select_nth_unstable_by(at(0.95), f64::total_cmp).1;
    if p5 > 0.0 { p95 / p5 } else { 0.0 }
}

/// A pixel's light-space point in map coordinates' bits.
fn exact(s: &Shaded) -> Option<[i32; 2]> {
    s.light.map(|l| [l.x.to_bits(), l.y.to_bits()])
}

impl Footprints {
    /// The footprint of a `width`-wide render.
    #[must_use]
    pub(crate) fn of(render: &[Shaded], truth: &[Option<PixelTruth>], width: usize) -> Self {
        Self::of_parts(render, truth, width, &[])
    }

    /// The footprint of a `width`-wide render whose pixels read the maps
    /// `parts` names (a cascade each; empty for one map): each derivative
    /// between neighbours on the same map.
    #[must_use]
    pub(crate) fn of_parts(render: &[Shaded], truth: &[Option<PixelTruth>], width: usize, parts: &[u8]) -> Self {
        let points = Points::new(render, truth, width, parts);
        let (mut along_x, mut along_y) = (Vec::new(), Vec::new());
        for k in 0..render.len() {
            let (x, y) = points.footprint(k);
            along_x.extend(x.map(DVec2::length));
            along_y.extend(y.map(DVec2::length));
        }
        points.recycle();
        let spread = [spread(&mut along_x), spread(&mut along_y)];
        Self { points: render.iter().map(exact).collect(), x: quantiles(along_x), y: quantiles(along_y), spread }
    }

    /// Whether `render`'s pixels lie at exactly these points on the map (so
    /// that, against the same reference, its footprint is this one).
    #[must_use]
    pub(crate) fn fits(&self, render: &[Shaded]) -> bool {
        render.len() == self.points.len() && self.fits_in(0..render.len(), render)
    }

    /// Whether the pixels `band` of `render` lie at exactly these points.
    #[must_use]
    pub(crate) fn fits_in(&self, band: core::ops::Range<usize>, render: &[Shaded]) -> bool {
        match (render.get(band.clone()), self.points.get(band)) {
            (Some(r), Some(p)) => r.iter().zip(p).all(|(s, p)| exact(s) == *p),
            _ => false,
        }
    }
}
