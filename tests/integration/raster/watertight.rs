//! Watertightness: meshes of triangles sharing edges — fans, jittered grids
//! and random triangulations — cover every pixel centre inside their convex
//! outline exactly once, and none outside.
//!
//! Vertices are generated on the 1/256-pixel grid and converted to NDC
//! exactly (the target is 64 pixels, so NDC = grid / 2^13 − 1), so the mesh
//! the hardware sees is exactly the mesh generated.

use proptest::prelude::*;
use umbra::core::glam::Vec4;
use umbra::core::{CullMode, D16, DepthUnit};

use crate::common::{Recorder, config, run};
use crate::mock_map::MockMap;

const SIZE: u32 = 64;
const GRID: i64 = 256 * SIZE as i64;

type P = (i64, i64);

fn ndc(p: P, z: f32) -> Vec4 {
    let s = (GRID / 2) as f32;
    Vec4::new(p.0 as f32 / s - 1.0, 1.0 - p.1 as f32 / s, z, 1.0)
}

fn cross(a: P, b: P, c: P) -> i64 {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
}

/// Coverage counts of a mesh, per pixel.
fn coverage(points: &[P], tris: &[[usize; 3]], depths: &[f32]) -> Vec<u32> {
    let clip: Vec<[Vec4; 3]> = tris.iter().map(|t| t.map(|i| ndc(points[i], depths[i % depths.len()]))).collect();
    let (_, rec) =
        run::<D16, _, 16>(config(SIZE, 16, DepthUnit::Single, false), &clip, CullMode::None, 256, Recorder::default());
    let mut count = vec![0u32; (SIZE * SIZE) as usize];
    for f in rec.fragments {
        count[(f.y * SIZE + f.x) as usize] += 1;
    }
    count
}

/// Pixel centres inside a convex polygon under the top-left rule (y down).
fn inside_outline(outline: &[P]) -> Vec<bool> {
    let mut poly = outline.to_vec();
    let area: i64 = (0..poly.len()).map(|i| cross((0, 0), poly[i], poly[(i + 1) % poly.len()])).sum();
    if area < 0 {
        poly.reverse();
    }
    let n = poly.len();
    let mut inside = vec![false; (SIZE * SIZE) as usize];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let q = (i64::from(x) * 256 + 128, i64::from(y) * 256 + 128);
            inside[(y * SIZE + x) as usize] = (0..n).all(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                let e = cross(a, b, q);
                let (ex, ey) = (b.0 - a.0, b.1 - a.1);
                e > 0 || (e == 0 && (ey < 0 || (ey == 0 && ex > 0)))
            });
        }
    }
    inside
}

fn assert_exactly_once(points: &[P], tris: &[[usize; 3]], outline: &[P], depths: &[f32]) -> Result<(), TestCaseError> {
    let count = coverage(points, tris, depths);
    let inside = inside_outline(outline);
    for (i, (&c, &inn)) in count.iter().zip(&inside).enumerate() {
        prop_assert!(c <= 1, "pixel ({}, {}) covered {} times", i as u32 % SIZE, i as u32 / SIZE, c);
        prop_assert_eq!(
            c == 1,
            inn,
            "pixel ({}, {}) coverage {} but inside outline = {}",
            i as u32 % SIZE,
            i as u32 / SIZE,
            c,
            inn
        );
    }
    Ok(())
}

fn grid_point() -> impl Strategy<Value = P> {
    (0..GRID, 0..GRID)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A fan around an interior point of a convex polygon.
    #[test]
    fn fans_are_watertight(n in 3usize..24, r in 2000i64..8000, c in (6000i64..10000, 6000i64..10000), phase in 0.0f64..1.0, z in prop::collection::vec(0.0f32..1.0, 1..8)) {
        let ring: Vec<P> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * (i as f64 + phase) / n as f64;
                (c.0 + (r as f64 * a.cos()).round() as i64, c.1 + (r as f64 * a.sin()).round() as i64)
            })
            .collect();
        // Rounding keeps a ring of ≥ 2000 subpixels strictly convex for n < 24.
        prop_assume!((0..n).all(|i| cross(ring[i], ring[(i + 1) % n], ring[(i + 2) % n]) > 0));
        let mut points = ring.clone();
        points.push(c);
        let tris: Vec<[usize; 3]> = (0..n).map(|i| [n, i, (i + 1) % n]).collect();
        assert_exactly_once(&points, &tris, &ring, &z)?;
    }

    /// A grid of jittered interior vertices, each cell split along a random diagonal.
    #[test]
    fn jittered_grids_are_watertight(
        (cols, rows, jitter, diagonals) in (1usize..8, 1usize..8).prop_flat_map(|(c, r)| (
            Just(c), Just(r),
            prop::collection::vec((-400i64..400, -400i64..400), (c + 1) * (r + 1)),
            prop::collection::vec(any::<bool>(), c * r),
        )),
        origin in (0i64..2000, 0i64..2000),
        z in prop::collection::vec(0.0f32..1.0, 1..8),
    ) {
        let cell = (GRID - 4000) / 8;
        let idx = |i: usize, j: usize| j * (cols + 1) + i;
        let mut points = Vec::new();
        for j in 0..=rows {
            for i in 0..=cols {
                let interior = i > 0 && i < cols && j > 0 && j < rows;
                let d = if interior { jitter[idx(i, j)] } else { (0, 0) };
                points.push((origin.0 + i as i64 * cell + d.0, origin.1 + j as i64 * cell + d.1));
            }
        }
        let mut tris = Vec::new();
        for j in 0..rows {
            for i in 0..cols {
                let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
                if diagonals[j * cols + i] {
                    tris.extend([[a, b, c], [a, c, d]]);
                } else {
                    tris.extend([[a, b, d], [b, c, d]]);
                }
            }
        }
        let outline = [points[idx(0, 0)], points[idx(cols, 0)], points[idx(cols, rows)], points[idx(0, rows)]];
        assert_exactly_once(&points, &tris, &outline, &z)?;
    }

    /// Random points inserted one by one into a square, each splitting the
    /// triangle that strictly contains it into three.
    #[test]
    fn random_triangulations_are_watertight(
        inserts in prop::collection::vec(grid_point(), 0..40),
        corner in (0i64..3000, 0i64..3000),
        side in 4000i64..13000,
        z in prop::collection::vec(0.0f32..1.0, 1..8),
    ) {
        let outline = vec![corner, (corner.0 + side, corner.1), (corner.0 + side, corner.1 + side), (corner.0, corner.1 + side)];
        let mut points = outline.clone();
        let mut tris = vec![[0, 1, 2], [0, 2, 3]];
        for p in inserts {
            let Some(k) = tris.iter().position(|t| {
                let s = [cross(points[t[0]], points[t[1]], p), cross(points[t[1]], points[t[2]], p), cross(points[t[2]], points[t[0]], p)];
                s.iter().all(|&v| v > 0) || s.iter().all(|&v| v < 0)
            }) else { continue };
            let [a, b, c] = tris.swap_remove(k);
            let n = points.len();
            points.push(p);
            tris.extend([[a, b, n], [b, c, n], [c, a, n]]);
        }
        assert_exactly_once(&points, &tris, &outline, &z)?;
    }
}

/// A watertight fan as a picture: a square with its corners at the centres
/// of pixels (3, 3) and (11, 11), cut into four triangles meeting at the
/// centre of pixel (7, 7). The centres on the four inner edges go to one
/// triangle each (no `2`), and the outline keeps its top row and left
/// column as the fill rule says: exactly `[3, 11) × [3, 11)`.
#[test]
fn a_fan_of_four_triangles_as_a_picture() {
    let c = |p: f32| (p + 0.5) / 16.0 * 2.0 - 1.0;
    let v = |x: f32, y: f32| Vec4::new(c(x), -c(y), 0.5, 1.0);
    let (centre, corners) = (v(7.0, 7.0), [v(3.0, 3.0), v(11.0, 3.0), v(11.0, 11.0), v(3.0, 11.0)]);
    let fan: Vec<[Vec4; 3]> = (0..4).map(|k| [centre, corners[k], corners[(k + 1) % 4]]).collect();
    let (_, map) =
        run::<D16, _, 8>(config(16, 8, DepthUnit::Single, false), &fan, CullMode::None, 8, MockMap::new(16, 16));
    let (outside, inside) = ("................", "...########.....");
    let rows: Vec<&str> = (0..16).map(|y| if (3..11).contains(&y) { inside } else { outside }).collect();
    map.assert_pattern(&rows);
}
