//! Shared harness: a light pass over clip-space triangles, a probe that
//! records every fragment, a plain whole-target reference rasterizer, and
//! proptest strategies.

use proptest::prelude::*;
use umbra::core::depth::Texel;
use umbra::core::front::setup::Setup;
use umbra::core::glam::Vec4;
use umbra::core::probe::{Event, FlushReason, Fragment, Probe};
use umbra::core::raster::bin::Bin;
use umbra::core::{
    ConfigError, CullMode, Datapaths, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, RasterConfig,
    TileState,
};

/// Records every fragment and counts the events tests look at.
#[derive(Default, Debug, Clone)]
pub struct Recorder {
    pub fragments: Vec<Fragment>,
    pub bin_full_flushes: u32,
    pub setup_full_flushes: u32,
    pub culled: u32,
    pub fragment_events: u64,
    pub rejected: u32,
}

impl Probe for Recorder {
    const FRAGMENTS: bool = true;

    fn event(&mut self, e: Event) {
        match e {
            Event::BinFlush { reason: FlushReason::BinFull, .. } => self.bin_full_flushes += 1,
            Event::BinFlush { reason: FlushReason::SetupFull, .. } => self.setup_full_flushes += 1,
            Event::Culled { .. } => self.culled += 1,
            Event::Fragments { count, .. } => self.fragment_events += u64::from(count),
            Event::TriangleRejected { .. } => self.rejected += 1,
            _ => {}
        }
    }

    fn fragment(&mut self, f: Fragment) {
        self.fragments.push(f);
    }
}

impl Recorder {
    /// The fragments as a sorted multiset.
    pub fn sorted(mut self) -> Vec<Fragment> {
        self.fragments.sort_unstable();
        self.fragments
    }
}

/// The buffers a pass left behind.
pub struct Maps<T> {
    pub z1: Vec<T>,
    pub z2: Vec<T>,
    pub tiles: Vec<TileState<T>>,
}

pub fn config(size: u32, tile: u32, unit: DepthUnit, max_z_cull: bool) -> LightPassConfig {
    LightPassConfig {
        raster: RasterConfig::new(size, size, tile, 8).expect("valid test configuration"),
        unit,
        max_z_cull,
    }
}

/// Owned buffers for a pass, sized from its configuration.
pub struct Buffers<F: DepthFormat, const B: usize> {
    pub z1: Vec<F::Texel>,
    pub z2: Vec<F::Texel>,
    pub ids: Vec<u32>,
    pub tiles: Vec<TileState<F::Texel>>,
    bins: Vec<Bin<B>>,
    setups: Vec<Setup>,
}

impl<F: DepthFormat, const B: usize> Buffers<F, B> {
    /// Buffers for `cfg` with a setup store of `setups`; `ids` adds the
    /// visibility unit's id buffer.
    pub fn new(cfg: &LightPassConfig, setups: usize, ids: bool) -> Self {
        let r = cfg.raster;
        let n = r.texel_count();
        Self {
            z1: vec![F::Texel::default(); n],
            z2: vec![F::Texel::default(); if cfg.unit == DepthUnit::Dual { n } else { 0 }],
            ids: vec![0; if ids { n } else { 0 }],
            tiles: vec![TileState::cleared(F::FAR, 0); r.tile_count()],
            bins: vec![Bin::<B>::new(); r.tile_count()],
            setups: vec![Setup::EMPTY; setups],
        }
    }

    /// Start a pass over these buffers.
    pub fn pass<P: Probe>(&mut self, cfg: LightPassConfig, probe: P) -> LightPass<'_, F, P, B> {
        self.pass_built(cfg, probe).expect("buffers sized from the configuration")
    }

    /// Start a pass built with the datapaths `D` over these buffers.
    pub fn pass_built<P: Probe, D: Datapaths>(
        &mut self,
        cfg: LightPassConfig,
        probe: P,
    ) -> Result<LightPass<'_, F, P, B, D>, ConfigError> {
        let buffers = LightBuffers {
            z1: &mut self.z1,
            z2: &mut self.z2,
            ids: &mut self.ids,
            tiles: &mut self.tiles,
            bins: &mut self.bins,
            setups: &mut self.setups,
        };
        LightPass::new(cfg, buffers, probe)
    }

    fn maps(self) -> Maps<F::Texel> {
        Maps { z1: self.z1, z2: self.z2, tiles: self.tiles }
    }
}

/// Run a light pass over clip-space triangles with bin capacity `B`.
pub fn run<F: DepthFormat, P: Probe, const B: usize>(
    cfg: LightPassConfig,
    tris: &[[Vec4; 3]],
    cull: CullMode,
    setups: usize,
    probe: P,
) -> (Maps<F::Texel>, P) {
    let mut b = Buffers::<F, B>::new(&cfg, setups, false);
    let mut pass = b.pass(cfg, probe);
    for t in tris {
        pass.draw_clip(*t, cull);
    }
    let probe = pass.finish();
    (b.maps(), probe)
}

/// Run the visibility unit (single depth with triangle ids) over clip-space
/// triangles; returns the ids, the depths and the recorded fragments.
pub fn run_visibility<F: DepthFormat>(
    size: u32,
    tile: u32,
    tris: &[[Vec4; 3]],
    cull: bool,
) -> (Vec<u32>, Vec<F::Texel>, Recorder) {
    let cfg = config(size, tile, DepthUnit::Single, cull);
    let mut b = Buffers::<F, 8>::new(&cfg, 16, true);
    let mut pass = b.pass(cfg, Recorder::default());
    for t in tris {
        pass.draw_clip(*t, CullMode::None);
    }
    let rec = pass.finish();
    (b.ids, b.z1, rec)
}

/// Snap like the hardware's documented viewport transform (f64,
/// `x·(1/w)`, ties to even): `((x/w + 1)·W/2, (1 − y/w)·H/2)` in 1/256 pixel.
pub fn snap(v: Vec4, size: u32) -> (i128, i128) {
    let (inv, half) = (1.0 / f64::from(v.w), f64::from(size) * 0.5 * 256.0);
    let x = ((f64::from(v.x) * inv + 1.0) * half).round_ties_even();
    let y = ((1.0 - f64::from(v.y) * inv) * half).round_ties_even();
    (x as i128, y as i128)
}

/// A fragment of the reference rasterizer, with how close its exact depth
/// came to a rounding tie (so a 1-LSB difference there is not a failure).
#[derive(Clone, Copy, Debug)]
pub struct RefFragment {
    pub x: u32,
    pub y: u32,
    pub depth: u32,
    pub near_tie: bool,
    pub triangle: u32,
}

/// The plain reference: every pixel centre of the target against every
/// triangle, edge functions and depth evaluated directly (no tiles, no
/// stepping) in i128, depth as the exact rational, rounded half up to the
/// format's LSB. For triangles that need no clipping (`0 ≤ z ≤ w`, `w > 0`).
/// Fill rule: a centre on an edge belongs to the triangle iff the edge is a
/// top edge (horizontal, interior below, y down) or a left edge.
pub fn reference<F: DepthFormat>(size: u32, tris: &[[Vec4; 3]], cull: CullMode) -> Vec<RefFragment> {
    let mut out = Vec::new();
    for (id, t) in tris.iter().enumerate() {
        let p: Vec<(i128, i128)> = t.iter().map(|v| snap(*v, size)).collect();
        let z: Vec<i128> =
            t.iter().map(|v| i128::from(F::plane_z(f64::from(v.z) / f64::from(v.w)).to_bits())).collect();
        let (a, mut b, mut c) = (0usize, 1usize, 2usize);
        let cross =
            |a: (i128, i128), b: (i128, i128), q: (i128, i128)| (b.0 - a.0) * (q.1 - a.1) - (b.1 - a.1) * (q.0 - a.0);
        let area = cross(p[0], p[1], p[2]);
        if area == 0 {
            continue;
        }
        // Negative area in y-down raster = counter-clockwise in NDC = facing the light.
        let facing = area < 0;
        if (cull == CullMode::Back && !facing) || (cull == CullMode::Front && facing) {
            continue;
        }
        if area < 0 {
            std::mem::swap(&mut b, &mut c);
        }
        let area = area.abs();
        let top_left = |from: (i128, i128), to: (i128, i128)| {
            let (ex, ey) = (to.0 - from.0, to.1 - from.1);
            ey < 0 || (ey == 0 && ex > 0)
        };
        let inside = |e: i128, from, to| e > 0 || (e == 0 && top_left(from, to));
        let unit = i128::from(1u32 << 31) * 2;
        let scale = i128::from(F::SCALE);
        for py in 0..size {
            for px in 0..size {
                let q = (i128::from(px) * 256 + 128, i128::from(py) * 256 + 128);
                let (wa, wb, wc) = (cross(p[b], p[c], q), cross(p[c], p[a], q), cross(p[a], p[b], q));
                if !(inside(wa, p[b], p[c]) && inside(wb, p[c], p[a]) && inside(wc, p[a], p[b])) {
                    continue;
                }
                let num = wa * z[a] + wb * z[b] + wc * z[c];
                let den = area * unit;
                let q = ((2 * num + den).div_euclid(2 * den)).clamp(0, scale);
                let rem = num.rem_euclid(den);
                let near_tie = (2 * rem - den).abs() < den >> 10;
                out.push(RefFragment { x: px, y: py, depth: q as u32, near_tie, triangle: id as u32 });
            }
        }
    }
    out
}

/// Assert that recorded fragments equal the reference's: the same pixels of
/// the same triangles, and the same depths except within 2⁻¹⁰ LSB of a tie,
/// where they may differ by one.
pub fn assert_matches_reference(mut got: Vec<Fragment>, mut want: Vec<RefFragment>) -> Result<(), TestCaseError> {
    got.sort_unstable_by_key(|f| (f.triangle, f.y, f.x));
    want.sort_unstable_by_key(|f| (f.triangle, f.y, f.x));
    prop_assert_eq!(got.len(), want.len(), "fragment counts differ");
    for (g, w) in got.iter().zip(&want) {
        prop_assert_eq!((g.triangle, g.x, g.y), (w.triangle, w.x, w.y), "different pixels");
        let ok = g.depth == w.depth || (w.near_tie && g.depth.abs_diff(w.depth) == 1);
        prop_assert!(ok, "depth at ({}, {}) of triangle {}: got {}, want {}", g.x, g.y, g.triangle, g.depth, w.depth);
    }
    Ok(())
}

/// Per texel, all fragment depths that landed there.
pub fn depths_per_texel(frags: &[Fragment], size: u32) -> Vec<Vec<u32>> {
    let mut per = vec![Vec::new(); (size * size) as usize];
    for f in frags {
        per[(f.y * size + f.x) as usize].push(f.depth);
    }
    per
}

/// Per texel, the two smallest depths of `frags` (the far value where fewer
/// landed): what a dual unit must hold after drawing them, in any order.
pub fn two_smallest(frags: &[Fragment], size: u32, far: u32) -> (Vec<u32>, Vec<u32>) {
    depths_per_texel(frags, size)
        .into_iter()
        .map(|mut ds| {
            ds.sort_unstable();
            (ds.first().copied().unwrap_or(far), ds.get(1).copied().unwrap_or(far))
        })
        .unzip()
}

/// A vertex in clip space with `w` in `[0.5, 2]`, NDC `x, y` in `[-1.3, 1.3]`
/// and depth in `[0, 1]`: inside near, far and the guard band.
pub fn clip_vertex() -> impl Strategy<Value = Vec4> {
    (-1.3f32..1.3, -1.3f32..1.3, 0.0f32..=1.0, 0.5f32..2.0).prop_map(|(x, y, z, w)| Vec4::new(x * w, y * w, z * w, w))
}

pub fn triangle() -> impl Strategy<Value = [Vec4; 3]> {
    [clip_vertex(), clip_vertex(), clip_vertex()]
}

/// A list of triangles, each either random or small (a few pixels across).
pub fn triangles(max: usize) -> impl Strategy<Value = Vec<[Vec4; 3]>> {
    let small = (clip_vertex(), [(-0.1f32..0.1, -0.1f32..0.1), (-0.1f32..0.1, -0.1f32..0.1)], 0.0f32..1.0).prop_map(
        |(v, d, z)| {
            let at = |(dx, dy): (f32, f32)| Vec4::new(v.x / v.w + dx, v.y / v.w + dy, z, 1.0);
            [Vec4::new(v.x / v.w, v.y / v.w, v.z / v.w, 1.0), at(d[0]), at(d[1])]
        },
    );
    prop::collection::vec(prop_oneof![triangle(), small], 1..max)
}

/// Raw bits of a depth buffer.
pub fn raw<T: Texel>(v: &[T]) -> Vec<u32> {
    v.iter().map(|t| t.to_raw()).collect()
}

pub use crate::scratch::Scratch;

/// A new scratch directory of this test process, named for `name` and
/// apart from every other (each call its own, though two tests give one
/// name).
pub fn scratch(name: &str) -> Scratch {
    static MADE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = MADE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("umbra-test-{}-{n}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    Scratch(dir)
}

/// The point of the plane `y = 0` seen at the centre of pixel `i` of a
/// `w`-wide, `h`-high image, given the inverse of the camera's matrix.
pub fn ground_point(inverse: &umbra::core::glam::DMat4, w: u32, h: u32, i: usize) -> umbra::core::glam::DVec3 {
    let (px, py) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
    let unproject = |z: f64| {
        let v = *inverse
            * umbra::core::glam::DVec4::new(2.0 * px / f64::from(w) - 1.0, 1.0 - 2.0 * py / f64::from(h), z, 1.0);
        v.truncate() / v.w
    };
    let (a, b) = (unproject(0.0), unproject(1.0));
    a + (b - a) * (-a.y / (b.y - a.y))
}

/// The camera pass of `scene` at `w × h` against a dual `maps` with the
/// map's shadow unit, into `frame`; its image.
pub fn camera_image<F: DepthFormat, P: Probe>(
    frame: &mut umbra::sim::pass::camera::CameraFrame,
    scene: &umbra::sim::world::scene::Scene,
    maps: &umbra::sim::pass::light::LightMaps<F::Texel>,
    (shadow, virtual_samples): (umbra::core::shadow::ShadowConfig, bool),
    (width, height): (u32, u32),
    probe: &mut P,
) -> umbra::sim::pass::camera::CameraImage {
    use umbra::sim::base::maps::Tiling;
    use umbra::sim::pass::camera::{CameraOptions, map_view, render};
    let view = map_view::<F>(maps, false).expect("maps fit their configuration");
    let options = CameraOptions { width, height, shadow, virtual_samples, tiling: Tiling::DEFAULT };
    render(frame, scene, &view, &umbra::core::shade::MapUnit, &options, probe).expect("renders");
    frame.take_image()
}

/// The silhouette pass over an 8 × 6 map that is all far (nothing hides an
/// edge) drawing one horizontal edge at `y = 3.25`, `x` from 1.25 to 5.75,
/// in silhouette-grid texels; the 9 × 7 grid of points it leaves (untouched
/// texels hold the centre).
pub fn horizontal_silhouette_edge<P: Probe>(probe: &mut P) -> Vec<umbra::core::silhouette::SilPoint> {
    use umbra::core::budget::MAP_SCALE;
    use umbra::core::shadow::{Bias, DepthTest, Filter, MapView, ShadowConfig};
    use umbra::core::silhouette::{Segment, SilPoint, SilhouettePass};
    use umbra::core::{D24, RasterConfig};

    let raster = RasterConfig::new(8, 6, 8, 8).expect("valid");
    let (z, tiles) = (vec![D24::FAR; 48], vec![TileState::cleared(D24::FAR, 48)]);
    let view = MapView::<D24>::front_culled(raster, &z, &tiles).expect("sized");
    let cfg = ShadowConfig::new(DepthTest::First, Bias::ZERO, Filter::Point, false).expect("valid");
    let mut texels = vec![SilPoint::CENTRE; 9 * 7];
    let mut pass = SilhouettePass::<SilPoint, D24>::new(&mut texels, &view, cfg).expect("sized");
    let q = |v: f64| (v * MAP_SCALE) as i64;
    let depth = D24::plane_z(0.5);
    pass.draw(&Segment { a: [q(1.25), q(3.25)], b: [q(5.75), q(3.25)], za: depth, zb: depth }, probe);
    texels
}
