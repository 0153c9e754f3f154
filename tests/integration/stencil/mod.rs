//! The stencil unit (Sen et al.'s shadow volumes, counted on the camera's
//! raster) on hand-worked pictures.

use umbra::core::stencil::StencilPass;
use umbra::core::{D24, RasterConfig};

use crate::mock_map::MockMap;

/// Two front-facing volume triangles tiling a rectangle whose corners are
/// the centres of pixels (2, 1) and (9, 5), over a scene depth of 0 (every
/// fragment at or behind it): each pixel of `[2, 9) × [1, 5)` is decremented
/// exactly once (the shared diagonal's centres go to one triangle), and no
/// other pixel is touched. The picture counts each pixel's stencil steps,
/// so a pixel counted twice shows `2`.
#[test]
fn two_volume_triangles_count_each_pixel_once_as_a_picture() {
    const W: u32 = 12;
    const H: u32 = 8;
    let raster = RasterConfig::new(W, H, 8, 8).expect("valid");
    let (depth, mut stencil) = (vec![0u32; (W * H) as usize], vec![0u8; (W * H) as usize]);
    let mut pass = StencilPass::<D24>::new(raster, &depth, &mut stencil).expect("sized");
    let c = |p: f64, n: u32| (p + 0.5) / f64::from(n) * 2.0 - 1.0;
    let v = |x: f64, y: f64| [c(x, W), -c(y, H), 0.5, 1.0];
    let (x0, x1, y0, y1) = (2.0, 9.0, 1.0, 5.0);
    pass.draw(&[v(x0, y1), v(x1, y1), v(x1, y0)], &mut umbra::core::NoProbe);
    pass.draw(&[v(x0, y1), v(x1, y0), v(x0, y0)], &mut umbra::core::NoProbe);
    let mut map = MockMap::new(W, H);
    for (k, &s) in pass.stencil().iter().enumerate() {
        // A front face decrements: the steps are the stencil's distance from 0.
        let steps = (s as i8).unsigned_abs();
        (0..steps).for_each(|_| map.draw(k as u32 % W, k as u32 / W));
    }
    map.assert_pattern(&[
        "............",
        "..#######...",
        "..#######...",
        "..#######...",
        "..#######...",
        "............",
        "............",
        "............",
    ]);
}
