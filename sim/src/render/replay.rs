//! Each wrong pixel of a render replayed through the shadow unit that
//! shaded it, its taps recorded, and judged by their cause
//! ([`crate::truth::cause`]).

use glam::{DMat4, Mat4};
use umbra_core::shade::{
    MapUnit, SceneTriangle, ShadeConfig, ShadeInputs, ShadeSetup, Shaded, ShadowUnit, SilhouetteUnit, shade_rect,
};
use umbra_core::shadow::MapView;
use umbra_core::silhouette::SilStore;
use umbra_core::{DepthFormat, TileRect};

use crate::pass::PassError;
use crate::pass::algorithm::MapKind;
use crate::pass::camera::{CameraOptions, shade_config};
use crate::pass::occluders::{SilReader, SilTexels};
use crate::truth::cause::{Cause, Judge, Judged, OccluderMemo, Rays, Receiver, Sight, Taps};
use crate::truth::metrics::{Attribution, Fields, Footprints, Metrics, Verdict, compare_with};
use crate::truth::reference::{PixelTruth, Reference, surface_point};
use crate::world::scene::{Light, LightSource};

/// What a render's judge reads: the scene, the visibility it shaded (ids
/// and camera), the map and the camera options, and the exact reference.
pub(crate) struct PassInputs<'a, F: DepthFormat> {
    /// The light whose map the shading read (a cascade's, for a cascaded
    /// light).
    pub light: Light,
    /// The scene's [`Scene::triangles`](crate::world::scene::Scene::triangles).
    pub triangles: &'a [SceneTriangle],
    /// The visible triangle of each pixel, and the camera it was seen through.
    pub seen: (&'a [u32], Mat4),
    /// The map the camera pass read (`None` for shadow volumes, which
    /// read none).
    pub view: Option<&'a MapView<'a, F>>,
    /// The camera pass's options.
    pub options: &'a CameraOptions,
    /// What the shadow unit read.
    pub source: ShadowSource<'a>,
    /// The occluders the judge's rays found for earlier renders of the
    /// same image and light, to ask first (`None`: none kept).
    pub memo: Option<&'a OccluderMemo>,
}

/// What a camera pass's shadow unit read, for its judge to read the same.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ShadowSource<'a> {
    /// The depth map, through the map's own unit.
    Map,
    /// Shadow volumes in the stencil: no map.
    Volumes,
    /// A silhouette map over the depth map, the texels the shading read
    /// (drawn once for both).
    Silhouette(&'a SilTexels),
}

impl<'a> ShadowSource<'a> {
    /// What an algorithm drawing `kind` read, given the silhouette map
    /// its passes drew (which a silhouette algorithm always has).
    #[must_use]
    pub(crate) fn of(kind: MapKind, silhouette: Option<&'a SilTexels>) -> Self {
        match (kind, silhouette) {
            (MapKind::Volumes, _) => Self::Volumes,
            (MapKind::Silhouette { .. }, Some(texels)) => Self::Silhouette(texels),
            _ => Self::Map,
        }
    }
}

/// The render's metrics and verdicts, each wrong pixel judged by replaying
/// it through the shadow unit that shaded it ([`with_judge`]).
///
/// # Errors
/// [`PassError`] when the silhouette map cannot be drawn again.
pub(crate) fn judged<F: DepthFormat>(
    what: &PassInputs<'_, F>,
    pixels: &[Shaded],
    (truth, fields, reference): (&[Option<PixelTruth>], &Fields, &Reference),
    footprints: Option<&Footprints>,
) -> Result<(Metrics, Vec<Verdict>), PassError> {
    with_judge(what, (reference, fields), |judge| compare_with(pixels, truth, fields, judge, footprints))
}

/// The cause of wrong pixel `k` of a shadow volume render, too dark when
/// `dark`. Volumes compare no depth and take no taps: a pixel the exact
/// shadow boundary passes within one pixel of is the volume's rasterized
/// edge, aliasing. One with no true edge near is the volumes' own error,
/// never aliasing: too light, a leak (light through an occluder the
/// volumes missed — a light inside a closed occluder casts no silhouette);
/// too dark, acne (a surface inside a volume that should not hold it).
fn volume_cause(fields: &Fields, k: usize, dark: bool) -> Cause {
    match (fields.edge_near(k), dark) {
        (true, _) => Cause::Aliasing,
        (false, true) => Cause::Acne,
        (false, false) => Cause::Leak,
    }
}

/// `then` with the judge of a render's wrong pixels, which replays each
/// through the shadow unit that shaded it (a silhouette map's, over the
/// texels the shading read). Shadow volumes compare no depth: their wrong
/// pixels are judged by the exact boundary alone ([`volume_cause`]).
///
/// # Errors
/// [`PassError`] when the silhouette map does not fit the depth map.
pub(crate) fn with_judge<F: DepthFormat, T>(
    what: &PassInputs<'_, F>,
    (reference, fields): (&Reference, &Fields),
    then: impl FnOnce(&mut dyn Attribution) -> T,
) -> Result<T, PassError> {
    Ok(match (what.source, what.view) {
        (ShadowSource::Volumes, _) | (_, None) => {
            then(&mut |k: usize, _: &Shaded, dark: bool| volume_cause(fields, k, dark))
        }
        (ShadowSource::Silhouette(texels), Some(view)) => {
            texels.read(view.raster(), Judging { what, view, reference, then })?
        }
        (ShadowSource::Map, Some(view)) => then(&mut Replay::new(what, view, &MapUnit, reference)),
    })
}

/// `then` with the judge of a silhouette map's render, as [`SilReader`].
struct Judging<'a, 'v, F: DepthFormat, Then> {
    what: &'a PassInputs<'a, F>,
    view: &'a MapView<'v, F>,
    reference: &'a Reference,
    then: Then,
}

impl<F: DepthFormat, T, Then: FnOnce(&mut dyn Attribution) -> T> SilReader for Judging<'_, '_, F, Then> {
    type Out = T;

    fn read<S: SilStore>(self, unit: &SilhouetteUnit<'_, '_, S>) -> T {
        (self.then)(&mut Replay::new(self.what, self.view, unit, self.reference))
    }
}

/// The wrong pixels' judge: shades each run of them along a row again
/// through `unit` with a probe recording their taps, then reads each
/// pixel's taps against its receiver's plane and the exact rays.
struct Replay<'a, F: DepthFormat, U> {
    cfg: ShadeConfig,
    ids: &'a [u32],
    view: &'a MapView<'a, F>,
    unit: &'a U,
    triangles: &'a [SceneTriangle],
    reference: &'a Reference,
    light: DMat4,
    light_source: LightSource,
    camera_inverse: DMat4,
    rays: Rays<'a>,
    taps: Taps,
    setups: Vec<ShadeSetup>,
    out: Vec<Shaded>,
}

impl<'a, F: DepthFormat, U: ShadowUnit<F>> Replay<'a, F, U> {
    fn new(what: &PassInputs<'a, F>, view: &'a MapView<'a, F>, unit: &'a U, reference: &'a Reference) -> Self {
        let cfg = shade_config(what.light.view_projection(), what.seen.1, what.options);
        let light = cfg.light.as_dmat4();
        let raster = view.raster();
        let size = (raster.width(), raster.height());
        Self {
            cfg,
            ids: what.seen.0,
            view,
            unit,
            triangles: what.triangles,
            reference,
            light,
            light_source: what.light.source(),
            camera_inverse: cfg.camera.as_dmat4().inverse(),
            rays: Rays::new(reference, &light, size, what.memo),
            taps: Taps::default(),
            setups: vec![ShadeSetup::EMPTY; 16],
            out: Vec::new(),
        }
    }

    /// Shade the pixels `k0..k1` of one row again, their taps recorded.
    fn replay(&mut self, k0: usize, k1: usize) {
        let width = self.cfg.width as usize;
        #[allow(clippy::cast_possible_truncation, reason = "pixels of the image")]
        let rect = TileRect {
            x0: (k0 % width) as u32,
            y0: (k0 / width) as u32,
            x1: (k1 - k0 + k0 % width) as u32,
            y1: (k0 / width) as u32 + 1,
        };
        let triangles = self.triangles;
        let source = |i: u32| triangles.get(i as usize).copied();
        self.taps.clear();
        self.out.clear();
        self.out.resize(k1 - k0, Shaded::BACKGROUND);
        let ids = self.ids.get(k0..k1).unwrap_or_default();
        let inputs = ShadeInputs { cfg: &self.cfg, map: self.view, scene: &source, unit: self.unit };
        let replayed = shade_rect(&inputs, rect, ids, &mut self.out, &mut self.setups, &mut self.taps);
        debug_assert!(replayed.is_ok(), "the replay of pixels {k0}..{k1} runs as the pass did");
    }

    /// The cause of pixel `k`, shaded `s`, too dark when `dark`, from its
    /// taps of the last replay, and whether its receiver's plane fell back
    /// to a flat one.
    fn judge(&self, k: usize, s: &Shaded, dark: bool, receiver: &mut Option<(u32, Receiver)>) -> Judged {
        let shadow = self.cfg.shadow;
        let judge = Judge { test: shadow.test(), shade: s.shadow, dark, soft: Judge::softens(shadow.filter()) };
        let width = self.cfg.width as usize;
        #[allow(clippy::cast_possible_truncation, reason = "a pixel of the image")]
        let (x, y) = ((k % width) as u32, (k / width) as u32);
        let (Some(&id), Some(light)) = (self.ids.get(k), s.light) else {
            // No lookup: the pixel lies behind the light.
            let cause = judge.cause(&[], &Receiver::flat::<F>(0), |_| Sight::Clear);
            return Judged { cause, fallback: false };
        };
        let triangle = self.reference.triangle(id).copied();
        // The receiver's plane, kept while the pixels stay on its triangle.
        let plane = match *receiver {
            Some((of, plane)) if of == id => plane,
            _ => {
                let raster = self.view.raster();
                let plane = triangle
                    .and_then(|t| Receiver::of::<F>(&t, &self.light, (raster.width(), raster.height())))
                    .unwrap_or_else(|| Receiver::flat::<F>(light.z.to_bits()));
                *receiver = Some((id, plane));
                plane
            }
        };
        // The object that hides the pixel's own centre from the light,
        // found when a lit tap asks: a tap's occluder must be it (a tap
        // across a crease onto another surface touching the receiver is
        // not), unless the centre is lit.
        let mut own: Option<Option<u32>> = None;
        let size = (f64::from(self.cfg.width), f64::from(self.cfg.height));
        let cause = judge.cause(self.taps.of_column(x), &plane, |t| {
            let Some(tri) = triangle else { return Sight::Clear };
            match self.rays.occluder(t.x, t.y, (id, &tri)) {
                Some(_) if dark => Sight::Occluded,
                Some(occluder) => {
                    let own = *own.get_or_insert_with(|| {
                        let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                        let (p, _) = surface_point(&self.camera_inverse, centre, size, &tri)?;
                        self.reference.occluder_of(p, &self.light_source)
                    });
                    if own.is_none_or(|o| o == occluder) { Sight::Occluded } else { Sight::Elsewhere }
                }
                None if !dark && self.rays.unseen(t.x, t.y, &tri, &self.light_source) => Sight::Unseen,
                None => Sight::Clear,
            }
        });
        Judged { cause, fallback: plane.fallback() }
    }
}

impl<F: DepthFormat, U: ShadowUnit<F>> Attribution for Replay<'_, F, U> {
    fn causes(&mut self, wrong: &[(usize, bool)], render: &[Shaded]) -> Vec<Judged> {
        let width = (self.cfg.width as usize).max(1);
        let mut causes = Vec::with_capacity(wrong.len());
        let mut receiver = None;
        // Runs of wrong pixels next to each other along a row, each shaded
        // again at once.
        let mut at = 0;
        while at < wrong.len() {
            let k0 = wrong[at].0;
            let mut end = at + 1;
            while end < wrong.len() && wrong[end].0 == wrong[end - 1].0 + 1 && !wrong[end].0.is_multiple_of(width) {
                end += 1;
            }
            self.replay(k0, wrong[end - 1].0 + 1);
            for &(k, dark) in &wrong[at..end] {
                let s = render.get(k).copied().unwrap_or(Shaded::BACKGROUND);
                debug_assert_eq!(self.out.get(k - k0).map(|o| o.shadow), Some(s.shadow), "pixel {k} replayed");
                causes.push(self.judge(k, &s, dark, &mut receiver));
            }
            at = end;
        }
        causes
    }
}
