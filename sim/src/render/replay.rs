//! Each wrong pixel of a render replayed through the shadow unit that
//! shaded it, its taps recorded, and judged by their cause
//! ([`crate::truth::cause`]).

use glam::{DMat4, DVec3, Mat4};
use umbra_core::shade::{
    MapUnit, SceneTriangle, ShadeConfig, ShadeSetup, Shaded, ShadowUnit, SilhouetteUnit, shade_rect,
};
use umbra_core::shadow::MapView;
use umbra_core::silhouette::{Packed, SilPoint, SilStore, SilhouetteMap};
use umbra_core::{DepthFormat, TileRect};

use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
use crate::pass::camera::{CameraOptions, shade_config};
use crate::pass::occluders::silhouette_map;
use crate::truth::cause::{Cause, Judge, Rays, Receiver, Taps};
use crate::truth::metrics::{Attribution, Fields, Metrics, Verdict, compare};
use crate::truth::reference::{PixelTruth, Reference, surface_point};
use crate::world::occluders::Occluders;
use crate::world::scene::{LightSource, Scene};

/// What a render's judge reads: the scene, the visibility it shaded (ids
/// and camera), the map and the camera options, and the exact reference.
pub struct PassInputs<'a, F: DepthFormat> {
    /// The scene.
    pub scene: &'a Scene,
    /// The visible triangle of each pixel, and the camera it was seen through.
    pub seen: (&'a [u32], Mat4),
    /// The map the camera pass read (`None` for shadow volumes, which
    /// read none).
    pub view: Option<&'a MapView<'a, F>>,
    /// The camera pass's options.
    pub options: &'a CameraOptions,
    /// The map the shadow unit reads (a depth map, or a silhouette map over it).
    pub kind: MapKind,
}

/// The render's metrics and verdicts, each wrong pixel judged by replaying
/// it through the shadow unit that shaded it (a silhouette map is drawn
/// again for it, bit for bit the camera pass's). Shadow volumes compare
/// no depth: each of their wrong pixels is the volume's rasterized edge,
/// aliasing.
///
/// # Errors
/// [`PassError`] when the silhouette map cannot be drawn again.
pub fn judged<F: DepthFormat>(
    what: &PassInputs<'_, F>,
    pixels: &[Shaded],
    (truth, fields, reference): (&[Option<PixelTruth>], &Fields, &Reference),
) -> Result<(Metrics, Vec<Verdict>), PassError> {
    Ok(match (what.kind, what.view) {
        (MapKind::Volumes, _) | (_, None) => compare(pixels, truth, fields, &mut |_, _: &_, _| Cause::Aliasing),
        (MapKind::Silhouette { packed: true }, Some(view)) => {
            silhouettes::<Packed, F>(what, view, pixels, (truth, fields, reference))?
        }
        (MapKind::Silhouette { packed: false }, Some(view)) => {
            silhouettes::<SilPoint, F>(what, view, pixels, (truth, fields, reference))?
        }
        (MapKind::Depth, Some(view)) => {
            compare(pixels, truth, fields, &mut Replay::new(what, view, &MapUnit, reference))
        }
    })
}

/// [`judged`] with a silhouette unit over the map drawn again.
fn silhouettes<S: SilStore, F: DepthFormat>(
    what: &PassInputs<'_, F>,
    view: &MapView<'_, F>,
    pixels: &[Shaded],
    (truth, fields, reference): (&[Option<PixelTruth>], &Fields, &Reference),
) -> Result<(Metrics, Vec<Verdict>), PassError> {
    let light = what.scene.light().view_projection();
    let occluders = Occluders::new(what.scene);
    let texels = silhouette_map::<S, F, _>(&occluders, &light, view, what.options.shadow, &mut umbra_core::NoProbe)?;
    let raster = view.raster();
    let sil = SilhouetteMap::view(raster.width(), raster.height(), &texels)?;
    Ok(compare(pixels, truth, fields, &mut Replay::new(what, view, &SilhouetteUnit(&sil), reference)))
}

/// A wrong pixel's judge: shades the one pixel again through `unit` with
/// a probe recording its taps, then reads them against the receiver's
/// plane and the exact rays.
struct Replay<'a, F: DepthFormat, U> {
    cfg: ShadeConfig,
    ids: &'a [u32],
    view: &'a MapView<'a, F>,
    unit: &'a U,
    triangles: Vec<[DVec3; 3]>,
    light: DMat4,
    light_source: LightSource,
    camera_inverse: DMat4,
    rays: Rays<'a>,
    taps: Taps,
    setups: [ShadeSetup; 1],
}

impl<'a, F: DepthFormat, U: ShadowUnit<F>> Replay<'a, F, U> {
    fn new(what: &PassInputs<'a, F>, view: &'a MapView<'a, F>, unit: &'a U, reference: &'a Reference) -> Self {
        let cfg = shade_config(what.scene, what.seen.1, what.options);
        let light = cfg.light.as_dmat4();
        let raster = view.raster();
        let size = (raster.width(), raster.height());
        Self {
            cfg,
            ids: what.seen.0,
            view,
            unit,
            triangles: what.scene.triangles().iter().map(|t| t.positions.map(|p| p.as_dvec3())).collect(),
            light,
            light_source: what.scene.light().source(),
            camera_inverse: cfg.camera.as_dmat4().inverse(),
            rays: Rays::new(reference, &light, size),
            taps: Taps::default(),
            setups: [ShadeSetup::EMPTY],
        }
    }
}

impl<F: DepthFormat, U: ShadowUnit<F>> Attribution for Replay<'_, F, U> {
    fn cause(&mut self, k: usize, s: &Shaded, dark: bool) -> Cause {
        let shadow = self.cfg.shadow;
        let judge = Judge { test: shadow.test(), shade: s.shadow, dark, soft: Judge::softens(shadow.filter()) };
        let width = self.cfg.width as usize;
        let (Some(id), Some(light)) = (self.ids.get(k), s.light) else {
            return judge.cause(&[], &Receiver::flat::<F>(0), |_| false);
        };
        #[allow(clippy::cast_possible_truncation, reason = "a pixel of the image")]
        let (x, y) = ((k % width) as u32, (k / width) as u32);
        let source = |i: u32| -> Option<SceneTriangle> {
            let p = *self.triangles.get(i as usize)?;
            let f = p.map(|v| v.as_vec3());
            let n = (f[1] - f[0]).cross(f[2] - f[0]).normalize_or_zero();
            Some(SceneTriangle { positions: f, normals: [n; 3] })
        };
        self.taps.clear();
        let mut out = [Shaded::BACKGROUND];
        let rect = TileRect { x0: x, y0: y, x1: x + 1, y1: y + 1 };
        let replayed = shade_rect(
            &self.cfg,
            rect,
            core::slice::from_ref(id),
            self.view,
            &source,
            &mut out,
            self.unit,
            &mut self.setups,
            &mut self.taps,
        );
        debug_assert!(replayed.is_ok() && out[0].shadow == s.shadow, "the replay shades pixel {k} as the pass did");
        let raster = self.view.raster();
        let triangle = self.triangles.get(*id as usize).copied();
        let receiver = triangle
            .and_then(|t| Receiver::of::<F>(&t, &self.light, (raster.width(), raster.height())))
            .unwrap_or_else(|| Receiver::flat::<F>(light.z.to_bits()));
        // The object that hides the pixel's own centre from the light: a
        // tap's occluder must be it (a tap across a crease onto another
        // surface touching the receiver is not), unless the centre is lit.
        let own = triangle.and_then(|tri| {
            let size = (f64::from(self.cfg.width), f64::from(self.cfg.height));
            let (p, _) = surface_point(&self.camera_inverse, (f64::from(x) + 0.5, f64::from(y) + 0.5), size, &tri)?;
            self.rays.reference().occluder_of(p, &self.light_source)
        });
        let rays = &self.rays;
        judge.cause(self.taps.taps(), &receiver, |t| {
            let Some(tri) = triangle else { return false };
            rays.occluder(t.x, t.y, &tri).is_some_and(|o| own.is_none_or(|p| p == o))
        })
    }
}
