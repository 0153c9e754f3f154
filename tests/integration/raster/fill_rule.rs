//! The fill rule, facing and clipping on hand-worked cases.

use umbra::core::glam::Vec4;
use umbra::core::{CullMode, D16, D24, DepthFormat, DepthUnit};

use crate::common::{Recorder, assert_matches_reference, config, reference, run};
use crate::mock_map::MockMap;

const SIZE: u32 = 32;

/// NDC of the centre of pixel `p` on an axis of `SIZE` pixels (y flips).
fn centre(p: f32) -> f32 {
    (p + 0.5) / SIZE as f32 * 2.0 - 1.0
}

fn covered(tris: &[[Vec4; 3]], cull: CullMode) -> Vec<(u32, u32)> {
    let (_, rec) = run::<D16, _, 64>(config(SIZE, 8, DepthUnit::Single, false), tris, cull, 64, Recorder::default());
    let mut px: Vec<(u32, u32)> = rec.fragments.iter().map(|f| (f.x, f.y)).collect();
    px.sort_unstable();
    px
}

/// A rectangle whose corners are the centres of pixels (4, 6) and (12, 10),
/// drawn as two triangles: the top-left rule takes its top row and left
/// column (centres exactly on those edges) and leaves its bottom row and
/// right column, so it covers exactly `[4, 12) × [6, 10)`, each pixel once.
#[test]
fn top_left_rule_on_a_rectangle_through_pixel_centres() {
    let (x0, x1) = (centre(4.0), centre(12.0));
    let (y_top, y_bottom) = (-centre(6.0), -centre(10.0));
    let v = |x: f32, y: f32| Vec4::new(x, y, 0.5, 1.0);
    let tris = [[v(x0, y_bottom), v(x1, y_bottom), v(x1, y_top)], [v(x0, y_bottom), v(x1, y_top), v(x0, y_top)]];
    let got = covered(&tris, CullMode::None);
    let want: Vec<(u32, u32)> = (4..12).flat_map(|x| (6..10).map(move |y| (x, y))).collect();
    assert_eq!(got, want);
}

/// Counter-clockwise in NDC (y up) faces the light: back-face culling keeps
/// it, front-face culling drops it, and the reverse for clockwise.
#[test]
fn facing_follows_ndc_winding() {
    let v = |x: f32, y: f32| Vec4::new(x, y, 0.5, 1.0);
    let ccw = [v(-0.5, -0.5), v(0.5, -0.5), v(0.0, 0.5)];
    let cw = [ccw[0], ccw[2], ccw[1]];
    assert!(!covered(&[ccw], CullMode::Back).is_empty());
    assert!(covered(&[ccw], CullMode::Front).is_empty());
    assert!(covered(&[cw], CullMode::Back).is_empty());
    assert!(!covered(&[cw], CullMode::Front).is_empty());
    assert_eq!(covered(&[ccw], CullMode::None), covered(&[cw], CullMode::None));
}

/// A triangle through the near plane is clipped there. Its two crossing
/// edges meet `z = 0` at their midpoints (worked out by hand), so the
/// clipped polygon is the quad below, and the pass must produce exactly the
/// reference fragments of that quad as a fan — with no depth below 0.
#[test]
fn near_plane_clipping_matches_the_hand_clipped_quad() {
    let tri = [Vec4::new(-0.5, -0.5, -0.5, 1.0), Vec4::new(0.5, -0.5, 0.5, 1.0), Vec4::new(-0.5, 0.5, 0.5, 1.0)];
    let quad = [
        Vec4::new(0.0, -0.5, 0.0, 1.0),
        Vec4::new(0.5, -0.5, 0.5, 1.0),
        Vec4::new(-0.5, 0.5, 0.5, 1.0),
        Vec4::new(-0.5, 0.0, 0.0, 1.0),
    ];
    let (_, rec) =
        run::<D24, _, 64>(config(SIZE, 8, DepthUnit::Single, false), &[tri], CullMode::None, 64, Recorder::default());
    let fan = [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]];
    let mut want = reference::<D24>(SIZE, &fan, CullMode::None);
    for f in &mut want {
        f.triangle = 0;
    }
    assert_matches_reference(rec.fragments, want).expect("clipped triangle equals its hand-clipped fan");
}

/// A triangle reaching far outside the target is clipped by the guard band
/// and still covers every pixel exactly once, at its (constant) depth.
#[test]
fn huge_triangle_covers_the_target_once() {
    let big = 1.0e6;
    let tri = [Vec4::new(-big, -big, 0.25, 1.0), Vec4::new(big, -big, 0.25, 1.0), Vec4::new(0.0, big, 0.25, 1.0)];
    let (maps, rec) =
        run::<D24, _, 64>(config(SIZE, 8, DepthUnit::Single, false), &[tri], CullMode::None, 64, Recorder::default());
    assert_eq!(rec.fragments.len(), (SIZE * SIZE) as usize);
    assert!(maps.z1.iter().all(|&z| z == D24::quantize(0.25)));
}

/// What an 8×8 target's pass draws, as a mock map.
fn picture(tris: &[[Vec4; 3]]) -> MockMap {
    run::<D16, _, 64>(config(8, 8, DepthUnit::Single, false), tris, CullMode::None, 64, MockMap::new(8, 8)).1
}

/// Vertices at pixel *corners* (1, 1), (7, 1), (1, 7) of an 8×8 target: a
/// centre `(px + ½, py + ½)` is inside iff `px ≥ 1`, `py ≥ 1` and
/// `px + py ≤ 6`; centres with `px + py = 7` lie exactly on the hypotenuse,
/// a bottom-right edge, and stay out. Then the mirror image across the
/// hypotenuse, which takes exactly those centres: together they tile the
/// square with no gap and no overdraw.
#[test]
fn ascii_triangle_and_its_mirror() {
    let v = |x: f32, y: f32| Vec4::new(x / 4.0 - 1.0, 1.0 - y / 4.0, 0.5, 1.0);
    let upper = [v(1.0, 1.0), v(7.0, 1.0), v(1.0, 7.0)];
    let lower = [v(7.0, 1.0), v(7.0, 7.0), v(1.0, 7.0)];
    picture(&[upper]).assert_pattern(&[
        "........", ".#####..", ".####...", ".###....", ".##.....", ".#......", "........", "........",
    ]);
    picture(&[upper, lower]).assert_pattern(&[
        "........", ".######.", ".######.", ".######.", ".######.", ".######.", ".######.", "........",
    ]);
}
