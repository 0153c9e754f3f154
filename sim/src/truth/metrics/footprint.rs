//! The map's footprint on screen: how far the light-space point moves
//! from one pixel to the next.

use glam::DVec2;
use umbra_core::shade::Shaded;

use super::evaluated;
use super::fields::neighbour;
use crate::truth::reference::PixelTruth;

/// Neighbouring pixels whose light-space points are farther apart than
/// this, in texels, are on different surfaces (or across a depth
/// discontinuity) and give no derivative.
const SAME_SURFACE_TEXELS: f64 = 8.0;

/// A pixel's light-space point's derivatives along x and y, texels per pixel.
pub(super) type Derivatives = (Option<DVec2>, Option<DVec2>);

/// Each evaluated pixel's light-space point of a `width`-wide render,
/// converted once, from which the map's footprint at any pixel follows.
pub(super) struct Points {
    points: Vec<Option<DVec2>>,
    width: usize,
    height: usize,
}

std::thread_local! {
    /// The last measure's points on this thread, for the next to fill
    /// without fresh pages.
    static SPARE_POINTS: core::cell::RefCell<Vec<Option<DVec2>>> = const { core::cell::RefCell::new(Vec::new()) };
}

impl Points {
    pub(super) fn new(render: &[Shaded], truth: &[Option<PixelTruth>], width: usize) -> Self {
        let mut points = SPARE_POINTS.with(|p| p.take());
        points.clear();
        points.extend(render.iter().zip(truth).map(|(s, t)| {
            let l = s.light?;
            evaluated(t)?;
            Some(DVec2::new(l.x.to_num(), l.y.to_num()))
        }));
        let height = render.len().checked_div(width).unwrap_or(0);
        Self { points, width, height }
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
        let derivative = |before: Option<usize>, after: Option<usize>| {
            let near =
                |n: Option<usize>| n.and_then(|n| self.at(n)).filter(|p| (*p - c).length() <= SAME_SURFACE_TEXELS);
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
