//! The metrics on synthetic images with known answers: a boundary moved by
//! k pixels is displaced by k; acne far from any edge is an artifact, the
//! same pattern along the edge is edge placement; a magnified map's
//! staircase within its texel's band is edge placement and beyond it
//! artifacts; stripes a filter dims below ½ are acne of their magnitude;
//! a footprint is read along each axis; a filtered image equal to the area
//! reference has no area error and no artifact; ties are counted.

use umbra::core::depth::PlaneZ;
use umbra::core::glam::Vec3;
use umbra::core::shade::{LightPoint, Shaded};
use umbra::core::shadow::{MapCoord, Shadow};
use umbra::sim::truth::metrics::compare;
use umbra::sim::truth::reference::PixelTruth;

const W: usize = 40;
const H: usize = 30;

fn px(shadow: f64) -> Shaded {
    Shaded { triangle: 0, light: None, normal: Vec3::Y, shadow: Shadow::from_num(shadow) }
}

/// Truth: shadowed left of column `edge`, lit from it on; every pixel
/// faces the light, its visibility its centre's verdict.
fn truth(edge: usize) -> Vec<Option<PixelTruth>> {
    (0..W * H)
        .map(|k| {
            let lit = k % W >= edge;
            Some(PixelTruth { faces_light: true, lit, visibility: f64::from(u8::from(lit)), light_cos: 1.0 })
        })
        .collect()
}

/// A render shadowed left of column `edge`.
fn render(edge: usize) -> Vec<Shaded> {
    (0..W * H).map(|k| px(if k % W >= edge { 0.0 } else { 1.0 })).collect()
}

#[test]
fn a_boundary_moved_by_k_pixels_is_displaced_by_k() {
    let t = truth(20);
    for k in 0..5usize {
        let m = compare(&render(20 + k), &t, W as u32);
        // The boundary's lit column moved from 20 to 20 + k.
        let expected = [k as f64; 3];
        assert_eq!(m.displacement, expected, "k = {k}");
        // The shadow reaches k columns into the lit side: false shadows.
        assert_eq!(m.false_shadow, (k * H) as u64);
        // The first of them touches the exact boundary: edge placement;
        // the rest are acne.
        assert_eq!(m.edge_placement, (k.min(1) * H) as u64, "k = {k}");
        assert_eq!(m.acne, (k.saturating_sub(1) * H) as u64, "k = {k}");
        // Moved the other way, the shadow detaches: leaks.
        if k >= 1 {
            let m = compare(&render(20 - k), &t, W as u32);
            assert_eq!((m.false_light, m.leaks), ((k * H) as u64, ((k - 1) * H) as u64), "k = {k}");
            assert_eq!(m.displacement, expected, "k = -{k}");
        }
    }
}

#[test]
fn acne_far_from_an_edge_is_an_artifact_and_along_it_edge_placement() {
    let t = truth(20);
    // A checker of false shadows in the lit half, 10 pixels from the edge.
    let mut far = render(20);
    let mut near = render(20);
    for y in (4..H - 4).step_by(2) {
        far[y * W + 30] = px(1.0);
        near[y * W + 20] = px(1.0);
    }
    let (f, n) = (compare(&far, &t, W as u32), compare(&near, &t, W as u32));
    assert_eq!((f.false_shadow, f.acne, f.edge_placement), (11, 11, 0));
    assert_eq!((n.false_shadow, n.acne, n.edge_placement), (11, 0, 11));
    assert!(f.artifact_percent > 0.0 && n.artifact_percent == 0.0);
}

#[test]
fn a_filtered_image_equal_to_the_area_reference_has_no_area_error() {
    // Visibility ramps across the image; the render's fraction matches it.
    let t: Vec<Option<PixelTruth>> = (0..W * H)
        .map(|k| {
            let v = (k % W) as f64 / (W - 1) as f64;
            Some(PixelTruth { faces_light: true, lit: v > 0.5, visibility: v, light_cos: 1.0 })
        })
        .collect();
    let exact: Vec<Shaded> = t.iter().map(|p| px(1.0 - p.expect("evaluated").visibility)).collect();
    let m = compare(&exact, &t, W as u32);
    // Fractions are stored at 16 bits: within 2^-16 a pixel.
    assert!(m.mean_abs_error < 2e-5 && m.rms_error < 2e-5, "{} {}", m.mean_abs_error, m.rms_error);
    // Off by 0.25 everywhere: both errors are 0.25.
    let off: Vec<Shaded> = t.iter().map(|p| px((1.0 - p.expect("evaluated").visibility - 0.25).max(0.0))).collect();
    let m = compare(&off, &t, W as u32);
    assert!(m.rms_error >= m.mean_abs_error && m.mean_abs_error > 0.2, "{} {}", m.mean_abs_error, m.rms_error);
}

#[test]
fn ties_at_one_half_count_as_lit_and_are_counted() {
    let t = truth(20);
    let mut r = render(20);
    for x in 0..5 {
        r[10 * W + x] = px(0.5);
    }
    let m = compare(&r, &t, W as u32);
    assert_eq!((m.ties, m.false_light), (5, 5));
}

/// `r` with light-space points that move `sx` texels a pixel along x and
/// `sy` along y (a map magnified `1/sx` times along x).
fn with_light(mut r: Vec<Shaded>, sx: f64, sy: f64) -> Vec<Shaded> {
    for (k, p) in r.iter_mut().enumerate() {
        let (x, y) = ((k % W) as f64, (k / W) as f64);
        p.light = Some(LightPoint {
            x: MapCoord::from_num(10.0 + x * sx),
            y: MapCoord::from_num(10.0 + y * sy),
            z: PlaneZ::from_num(0.5),
        });
    }
    r
}

/// A map magnified 4× (a quarter texel a pixel both ways) has a band of 4
/// pixels: a staircase of false shadows reaching 1 to 3 pixels into the
/// lit side is all edge placement; the same steps 8 to 10 pixels from the
/// edge are all acne; at 1:1 (band 1) only the pixels next to the edge are
/// edge placement.
#[test]
fn a_magnified_staircase_within_the_band_is_edge_placement_and_beyond_it_acne() {
    let t = truth(20);
    // Steps: row y darkens `1 + y % 3` pixels past column `from`.
    let stairs = |from: usize| {
        let mut r = render(20);
        for y in 0..H {
            for x in from..from + 1 + y % 3 {
                r[y * W + x] = px(1.0);
            }
        }
        r
    };
    let steps = (0..H).map(|y| 1 + y % 3).sum::<usize>() as u64;
    let within = compare(&with_light(stairs(20), 0.25, 0.25), &t, W as u32);
    assert_eq!(within.band, [4.0, 4.0]);
    assert_eq!((within.edge_placement, within.acne, within.leaks), (steps, 0, 0));
    assert_eq!(within.half_acne, 0);
    let beyond = compare(&with_light(stairs(28), 0.25, 0.25), &t, W as u32);
    assert_eq!((beyond.edge_placement, beyond.acne, beyond.half_acne), (0, steps, steps));
    assert!((beyond.acne_area - steps as f64).abs() < 1e-3, "{}", beyond.acne_area);
    // Unmagnified, the same staircase at the edge is edge placement only
    // where it touches the exact boundary's pixels.
    let one = compare(&with_light(stairs(20), 1.0, 1.0), &t, W as u32);
    assert_eq!(one.band, [1.0, 1.0]);
    assert_eq!((one.edge_placement, one.acne), (H as u64, steps - H as u64));
}

/// Stripes of shadow fraction 0.3 on the lit side, far from any edge,
/// below the ½ verdict: each is acne of magnitude 0.3 (none of them a
/// false shadow by the ½ verdict); at 0.05, under the visible step, none.
#[test]
fn stripes_a_filter_dims_below_one_half_are_acne_of_their_magnitude() {
    let t = truth(10);
    let striped = |f: f64| {
        let mut r = render(10);
        for y in (2..H - 2).step_by(3) {
            for x in 20..36 {
                r[y * W + x] = px(f);
            }
        }
        r
    };
    let stripes = (2..H - 2).step_by(3).count() as u64 * 16;
    let m = compare(&striped(0.3), &t, W as u32);
    assert_eq!((m.acne, m.false_shadow, m.half_acne), (stripes, 0, 0));
    assert!((m.acne_area - 0.3 * stripes as f64).abs() < 1e-3, "{}", m.acne_area);
    assert_eq!(compare(&striped(0.05), &t, W as u32).acne, 0);
}

/// A floor seen so that one pixel steps 0.25 texels along x and 3 along
/// y: the footprint says magnified along x and minified along y.
#[test]
fn a_footprint_is_read_along_each_axis() {
    let m = compare(&with_light(render(20), 0.25, 3.0), &truth(20), W as u32);
    assert!((m.footprint_x[0] - 0.25).abs() < 1e-3 && (m.footprint_x[1] - 0.25).abs() < 1e-3, "{:?}", m.footprint_x);
    assert!((m.footprint_y[0] - 3.0).abs() < 1e-3, "{:?}", m.footprint_y);
    // The texel spans 4 pixels along x, a third of one along y: the band
    // is the longer, 4.
    assert_eq!(m.band, [4.0, 4.0]);
}

/// A filtered image equal to the area reference, soft shadow included,
/// counts no artifact and no edge placement.
#[test]
fn a_filtered_image_equal_to_the_reference_counts_no_artifact() {
    let t: Vec<Option<PixelTruth>> = (0..W * H)
        .map(|k| {
            let v = ((k % W) as f64 / 10.0 - 1.0).clamp(0.0, 1.0);
            Some(PixelTruth { faces_light: true, lit: v >= 0.5, visibility: v, light_cos: 1.0 })
        })
        .collect();
    let exact: Vec<Shaded> = t.iter().map(|p| px(1.0 - p.expect("evaluated").visibility)).collect();
    let m = compare(&with_light(exact, 0.5, 0.5), &t, W as u32);
    assert_eq!((m.acne, m.leaks, m.edge_placement), (0, 0, 0));
}
