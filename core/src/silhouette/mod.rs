//! The silhouette unit: Sen, Cammarano & Hanrahan 2003, *Shadow Silhouette
//! Maps* — a map of one point per texel on the light-view silhouette, used
//! by the camera pass to reconstruct a piecewise-linear shadow boundary
//! where a depth map alone gives a staircase.
//!
//! # Grids
//! The silhouette map is the depth map's dual grid, **offset by half a
//! texel** (§2): silhouette texel `(i, j)` spans map coordinates
//! `[i − ½, i + ½) × [j − ½, j + ½)`, so its four corners are the centres of
//! depth texels `(i − 1, j − 1)`, `(i, j − 1)`, `(i − 1, j)` and `(i, j)`.
//! A `W × H` depth map has a `(W + 1) × (H + 1)` silhouette map. A point is
//! stored as its offset from its texel's top-left corner, 16 fraction bits
//! per axis ([`SilPoint`]), or packed to 4 bits per axis in one byte as Sen
//! suggests ([`Packed`]); an empty texel means its centre.
//!
//! # The silhouette pass (§3.1)
//! Each silhouette edge is clipped to the light's near and far planes,
//! projected (f64, as the vertex unit) and rasterized conservatively: every
//! texel within [`CORNER_SLACK`] of the segment gets a fragment, so the
//! fragments are 4-connected and a segment through a corner reaches all four
//! texels around it. Each fragment picks its point in integers: an endpoint
//! inside the texel; otherwise the segment's intersections with the texel's
//! two diagonals, accepted within the enlarged square — one: that point, two:
//! their midpoint, none: the fragment is killed. The point is clamped into
//! the texel. A fragment behind all four corner depths (a hidden silhouette)
//! is killed too. Last write wins.
//!
//! # The camera pass (§3.2)
//! The four corner depth tests (the shadow unit's test and bias); if they
//! agree, that is the verdict. Otherwise the texel's point and its four
//! neighbours' points split the texel into four skewed quadrants; eight
//! pie-shaped regions (rays from the texel's point to the neighbours and to
//! the corners) place the receiver in one, and it takes the verdict of that
//! quadrant's corner.

mod lookup;
mod map;
mod pass;

use lookup::corners;
pub use lookup::{DEPTH_SAMPLES, quadrant, shadow};
pub use map::{CORNER_SLACK, Packed, SilPoint, SilStore, SilhouetteMap};
use map::{dual, index};
pub use pass::{Segment, SilhouettePass, project, select_point};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::MAP_ONE;
    use crate::depth::PlaneZ;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Segment {
        let f = |v: f64| crate::round::round_ties_even(v * crate::budget::MAP_SCALE);
        Segment { a: [f(a[0]), f(a[1])], b: [f(b[0]), f(b[1])], za: PlaneZ::ZERO, zb: PlaneZ::ZERO }
    }

    #[test]
    fn endpoint_inside_is_stored() {
        let (p, t) = select_point(&seg([2.25, 3.75], [9.0, 9.0]), 2, 3).unwrap();
        assert_eq!((p.x, p.y, t), (0x4000, 0xC000, 0));
    }

    #[test]
    fn one_diagonal_hit_is_stored() {
        // A horizontal segment at y = 0.25 across texel (0, 0) meets y = x at
        // (0.25, 0.25) and x + y = 1 at (0.75, 0.25): two hits, midpoint (0.5, 0.25).
        let (p, _) = select_point(&seg([-3.0, 0.25], [5.0, 0.25]), 0, 0).unwrap();
        assert_eq!((p.x, p.y), (0x8000, 0x4000));
        // A segment cutting the top-left corner, parallel to x + y = 1:
        // one hit, on y = x at (0.05, 0.05). The endpoints round to
        // (−32768, 39322) and (39322, −32768) in 2⁻¹⁶ texels, so the hit is
        // halfway, at −32768 + 72090/2 = 3277.
        let (p, _) = select_point(&seg([-0.5, 0.6], [0.6, -0.5]), 0, 0).unwrap();
        assert_eq!((p.x, p.y), (3277, 3277));
    }

    #[test]
    fn a_miss_is_killed() {
        assert!(select_point(&seg([-3.0, 1.5], [5.0, 1.5]), 0, 0).is_none());
    }

    #[test]
    fn packing_keeps_the_centre_and_rounds_to_sixteenths() {
        assert_eq!(Packed::encode(SilPoint::CENTRE).decode(), SilPoint::CENTRE);
        let p = Packed::encode(SilPoint { x: 0x4100, y: 0xFFFF }).decode();
        assert_eq!((p.x, p.y), (0x4000, 0xF000));
    }

    #[test]
    fn quadrants_of_a_centred_fan() {
        let c = [MAP_ONE / 2, MAP_ONE / 2];
        let n = [
            [MAP_ONE / 2, -MAP_ONE / 2],
            [3 * MAP_ONE / 2, MAP_ONE / 2],
            [MAP_ONE / 2, 3 * MAP_ONE / 2],
            [-MAP_ONE / 2, MAP_ONE / 2],
        ];
        assert_eq!(quadrant(c, n, [MAP_ONE / 4, MAP_ONE / 4]), 0);
        assert_eq!(quadrant(c, n, [3 * MAP_ONE / 4, MAP_ONE / 4]), 1);
        assert_eq!(quadrant(c, n, [MAP_ONE / 4, 3 * MAP_ONE / 4]), 2);
        assert_eq!(quadrant(c, n, [3 * MAP_ONE / 4, 3 * MAP_ONE / 4]), 3);
    }
}
