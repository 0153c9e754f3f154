//! The metrics on synthetic images with known answers: a boundary moved by
//! k pixels is displaced by k; acne far from any edge is an artifact, the
//! same pattern along the edge is edge placement; a filtered image equal
//! to the area reference has no area error; ties are counted.

use umbra::core::glam::Vec3;
use umbra::core::shade::Shaded;
use umbra::core::shadow::Shadow;
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
            Some(PixelTruth { faces_light: true, lit, visibility: f64::from(u8::from(lit)) })
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
            Some(PixelTruth { faces_light: true, lit: v > 0.5, visibility: v })
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
