//! The camera pass's silhouette test (Sen et al. 2003 §3.2): corners, then quadrants.

use super::{SilStore, SilhouetteMap};
use crate::budget::{MAP_FRACTION_BITS, MAP_HALF, MAP_ONE};
use crate::depth::{DepthFormat, PlaneZ};
use crate::probe::{Buffer, Event, Probe, TexelRead};
use crate::shadow::{MapCoord, MapView, Shadow, ShadowConfig};

/// The depth samples a silhouette test reads, whatever the filter: one at
/// each corner of its silhouette texel (Sen et al. 2003 §3.2, "the four
/// closest shadow depth samples").
pub const DEPTH_SAMPLES: usize = 4;

/// The depth texels at the corners of silhouette texel `(i, j)`: top-left,
/// top-right, bottom-left, bottom-right.
pub(super) const fn corners(i: i64, j: i64) -> [(i64, i64); DEPTH_SAMPLES] {
    [(i - 1, j - 1), (i, j - 1), (i - 1, j), (i, j)]
}

/// The camera pass's silhouette test for a lookup at map position
/// `(x, y)` with receiver depth `z`: Sen et al. 2003 §3.2. Outside the map
/// and behind the light is lit.
pub fn shadow<S: SilStore, F: DepthFormat, P: Probe>(
    sil: &SilhouetteMap<'_, S>,
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    x: MapCoord,
    y: MapCoord,
    z: PlaneZ,
    probe: &mut P,
) -> Shadow {
    if z < 0 {
        return Shadow::ZERO;
    }
    let (sx, sy) = (i64::from(x.to_bits()) + MAP_HALF, i64::from(y.to_bits()) + MAP_HALF);
    let (i, j) = (sx >> MAP_FRACTION_BITS, sy >> MAP_FRACTION_BITS);
    if i < 0 || j < 0 || i >= i64::from(sil.width) || j >= i64::from(sil.height) {
        return Shadow::ZERO;
    }
    let bias = cfg.bias().bounds().0;
    let mut reads = 0u32;
    let verdicts = corners(i, j).map(|c| match map.sample(cfg.test(), c, z.to_bits(), bias, 1, probe) {
        Some(s) => {
            reads += 1;
            s
        }
        None => false,
    });
    if reads > 0 {
        for buffer in map.buffers_read(cfg.test()) {
            probe.event(Event::MapRead { buffer, texels: reads, bytes: reads * F::KIND.bytes() });
        }
    }
    let lit = |s: bool| if s { Shadow::ONE } else { Shadow::ZERO };
    if verdicts.iter().all(|&v| v == verdicts[0]) {
        probe.event(Event::TrivialPixel { lit: !verdicts[0] });
        return lit(verdicts[0]);
    }
    probe.event(Event::SilhouetteRead { points: 5, bytes: 5 * S::BYTES });
    if P::TEXELS {
        for (di, dj) in [(0, 0), (0, -1), (1, 0), (0, 1), (-1, 0)] {
            if let (Ok(x), Ok(y)) = (u32::try_from(i + di), u32::try_from(j + dj))
                && x < sil.width
                && y < sil.height
            {
                probe.texel_read(TexelRead { buffer: Buffer::Silhouette, x, y });
            }
        }
    }
    let at = |di: i64, dj: i64| {
        let p = sil.point(i + di, j + dj);
        [i64::from(p.x) + di * MAP_ONE, i64::from(p.y) + dj * MAP_ONE]
    };
    let p = [sx & (MAP_ONE - 1), sy & (MAP_ONE - 1)];
    lit(verdicts[quadrant(at(0, 0), [at(0, -1), at(1, 0), at(0, 1), at(-1, 0)], p)])
}

/// The skewed quadrant of the texel that holds `p` (0 top-left, 1
/// top-right, 2 bottom-left, 3 bottom-right), given the texel's point `c`
/// and its neighbours' points `[up, right, down, left]`, all relative to
/// the texel's corner (y down). Eight pie-shaped regions: the rays from `c`
/// to the neighbours and to the corners, in clockwise order. If `p` lies in
/// none (a degenerate fan), the quadrant of `p` relative to `c`.
#[must_use]
pub fn quadrant(c: [i64; 2], n: [[i64; 2]; 4], p: [i64; 2]) -> usize {
    let corner = [[MAP_ONE, 0], [MAP_ONE, MAP_ONE], [0, MAP_ONE], [0, 0]];
    // Clockwise (y down): up, top-right, right, bottom-right, down, bottom-left, left, top-left.
    let rays = [n[0], corner[0], n[1], corner[1], n[2], corner[2], n[3], corner[3]];
    let region = [1, 1, 3, 3, 2, 2, 0, 0];
    let rel = |q: [i64; 2]| [i128::from(q[0] - c[0]), i128::from(q[1] - c[1])];
    let cross = |u: [i128; 2], v: [i128; 2]| u[0] * v[1] - u[1] * v[0];
    let pr = rel(p);
    for k in 0..8 {
        let (r1, r2) = (rel(rays[k]), rel(rays[(k + 1) % 8]));
        if cross(r1, r2) > 0 && cross(r1, pr) >= 0 && cross(pr, r2) > 0 {
            return region[k];
        }
    }
    usize::from(pr[0] >= 0) + 2 * usize::from(pr[1] >= 0)
}
