//! What the metrics need of the reference alone: which pixels lie on the
//! exact shadow boundary, and the distance fields from them.

use super::evaluated;
use crate::truth::reference::PixelTruth;

/// What the metrics need of the reference alone, worked out once for
/// every render measured against it (a study measures many): which side
/// of the exact boundary each pixel is on, and three distance fields —
/// to the exact boundary (the edge band's test), to its lit side (the
/// displacement's, with the site found) and to the surfaces facing away
/// from the light (the terminator's reach).
#[derive(Clone, Debug)]
pub struct Fields {
    pub(crate) width: usize,
    pub(super) to_edge: Vec<u32>,
    pub(super) to_lit_edge: Vec<(u32, usize)>,
    pub(super) to_away: Vec<u32>,
}

impl Fields {
    /// Whether the exact shadow boundary passes within one pixel
    /// (Chebyshev) of pixel `k`: a true edge there.
    #[must_use]
    pub(crate) fn edge_near(&self, k: usize) -> bool {
        self.to_edge.get(k).is_some_and(|&d| d <= 1)
    }

    /// The fields of a `width`-wide reference.
    #[must_use]
    pub fn new(truth: &[Option<PixelTruth>], width: u32) -> Self {
        let width = width as usize;
        let exact: Vec<Option<bool>> = truth.iter().map(|t| evaluated(t).map(|t| !t.lit)).collect();
        // The exact boundary passes through a pixel whose neighbours' centres
        // fall on both sides, or whose own area is partly shadowed (a shadow
        // narrower than a pixel crosses no centre).
        let mut sites = boundary(&exact, width, false);
        for (site, t) in sites.iter_mut().zip(truth) {
            *site |= evaluated(t).is_some_and(|t| t.visibility > 0.0 && t.visibility < 1.0);
        }
        let distances = |d: Vec<(u32, usize)>| d.into_iter().map(|(d, _)| d).collect();
        let away: Vec<bool> = truth.iter().map(|t| t.is_some_and(|t| !t.faces_light)).collect();
        Self {
            width,
            to_edge: distances(distance(&sites, width)),
            to_lit_edge: distance(&boundary(&exact, width, true), width),
            to_away: distances(distance(&away, width)),
        }
    }
}

/// Chebyshev distance, in pixels, from every pixel of a `width`-wide image
/// to the nearest pixel marked in `sites` (`u32::MAX` when there is none),
/// and which site that is: two chamfer passes, exact for this metric.
fn distance(sites: &[bool], width: usize) -> Vec<(u32, usize)> {
    let mut d: Vec<(u32, usize)> = sites.iter().enumerate().map(|(k, &s)| (if s { 0 } else { u32::MAX }, k)).collect();
    let height = d.len().checked_div(width).unwrap_or(0);
    // Take the nearer of a pixel's own site and a neighbour's plus one, the
    // neighbours in a fixed order (the first nearer one wins a tie).
    let relax = |d: &mut [(u32, usize)], k: usize, n: usize| {
        let (nd, site) = d[n];
        if nd.saturating_add(1) < d[k].0 {
            d[k] = (nd + 1, site);
        }
    };
    // Forward: the row above (left, middle, right), then the left.
    for y in 0..height {
        for x in 0..width {
            let k = y * width + x;
            if y > 0 {
                let up = k - width;
                if x > 0 {
                    relax(&mut d, k, up - 1);
                }
                relax(&mut d, k, up);
                if x + 1 < width {
                    relax(&mut d, k, up + 1);
                }
            }
            if x > 0 {
                relax(&mut d, k, k - 1);
            }
        }
    }
    // Backward: the row below (right, middle, left), then the right.
    for y in (0..height).rev() {
        for x in (0..width).rev() {
            let k = y * width + x;
            if y + 1 < height {
                let down = k + width;
                if x + 1 < width {
                    relax(&mut d, k, down + 1);
                }
                relax(&mut d, k, down);
                if x > 0 {
                    relax(&mut d, k, down - 1);
                }
            }
            if x + 1 < width {
                relax(&mut d, k, k + 1);
            }
        }
    }
    d
}

/// The index of the pixel `(dx, dy)` from `(x, y)`, if it is inside.
pub(super) fn neighbour(x: usize, y: usize, dx: isize, dy: isize, width: usize, height: usize) -> Option<usize> {
    let (nx, ny) = (x.checked_add_signed(dx)?, y.checked_add_signed(dy)?);
    (nx < width && ny < height).then(|| ny * width + nx)
}

/// Pixels on a boundary of `dark` (`None`: not evaluated): evaluated, with
/// an evaluated 8-neighbour of the other verdict; only the lit ones when
/// `lit_side` (so that a boundary is one pixel thick and a shift by k
/// pixels moves it by k).
pub(super) fn boundary(dark: &[Option<bool>], width: usize, lit_side: bool) -> Vec<bool> {
    let height = dark.len().checked_div(width).unwrap_or(0);
    // Each row's shadowed and lit pixels as bits, 64 a word; a pixel is on
    // the boundary when the other kind lies in its 3 × 3 neighbourhood:
    // its row and the rows above and below (within the image), each
    // spread one column either way.
    let words = width.div_ceil(64);
    let rows = dark.len().div_ceil(width.max(1));
    let (mut shadowed, mut lit) = (vec![0u64; rows * words], vec![0u64; rows * words]);
    for (y, row) in dark.chunks(width.max(1)).enumerate() {
        for (x, d) in row.iter().enumerate() {
            let (at, bit) = (y * words + x / 64, 1u64 << (x % 64));
            match d {
                Some(true) => shadowed[at] |= bit,
                Some(false) => lit[at] |= bit,
                None => {}
            }
        }
    }
    let near = |bits: &[u64], y: usize, w: usize| {
        let mut n = 0u64;
        for ny in y.saturating_sub(1)..(y + 2).min(height) {
            let row = &bits[ny * words..(ny + 1) * words];
            let before = if w > 0 { row[w - 1] >> 63 } else { 0 };
            let after = row.get(w + 1).map_or(0, |a| a << 63);
            n |= row[w] | row[w] << 1 | before | row[w] >> 1 | after;
        }
        n
    };
    let mut on = vec![false; dark.len()];
    for y in 0..rows {
        for w in 0..words {
            let mut word = lit[y * words + w] & near(&shadowed, y, w);
            if !lit_side {
                word |= shadowed[y * words + w] & near(&lit, y, w);
            }
            while word != 0 {
                let x = w * 64 + word.trailing_zeros() as usize;
                word &= word - 1;
                on[y * width + x] = true;
            }
        }
    }
    on
}

#[cfg(test)]
mod tests {
    use super::{boundary, neighbour};

    /// The boundary as its definition reads, pixel by pixel through
    /// [`neighbour`]: the reference the row-by-row scan is held to.
    fn by_definition(dark: &[Option<bool>], width: usize, lit_side: bool) -> Vec<bool> {
        let height = dark.len() / width;
        (0..dark.len())
            .map(|k| {
                let Some(v) = dark[k].filter(|&v| !(lit_side && v)) else { return false };
                let (x, y) = (k % width, k / width);
                (-1..=1).any(|dy| {
                    (-1..=1)
                        .any(|dx| neighbour(x, y, dx, dy, width, height).and_then(|n| dark[n]).is_some_and(|n| n != v))
                })
            })
            .collect()
    }

    #[test]
    fn the_boundary_is_its_definition() {
        // Random verdicts (a third unevaluated) on images from one pixel to
        // a few rows, thin and wide (across words of 64 columns), some with
        // a partial last row.
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut boundaries = 0;
        for (width, len) in
            [(1, 1), (1, 9), (9, 1), (7, 21), (16, 48), (5, 23), (33, 99), (64, 192), (70, 350), (130, 400)]
        {
            for _ in 0..20 {
                let dark: Vec<Option<bool>> =
                    (0..len).map(|_| [None, Some(false), Some(true)][(next() % 3) as usize]).collect();
                for lit_side in [false, true] {
                    let found = boundary(&dark, width, lit_side);
                    assert_eq!(found, by_definition(&dark, width, lit_side), "{width} wide, {dark:?}");
                    boundaries += found.iter().filter(|&&b| b).count();
                }
            }
        }
        assert!(boundaries > 1000, "the cases have boundaries: {boundaries}");
    }
}
