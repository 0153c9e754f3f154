//! The camera's visibility, drawn once per tiling for every configuration
//! of a scene and image, and what each of its lights' shadings reads
//! beside the map: the scene as that light lights it, its exact
//! reference and the reference's fields.

use std::sync::{Arc, Mutex};

use glam::Mat4;
use rayon::prelude::*;
use umbra_core::probe::{Probe, Totals};
use umbra_core::shade::{SceneTriangle, Shaded};
use umbra_core::{DepthFormatKind, RasterConfig};

use super::assign;
use super::probes::{Kept, Probes, Reporting};
use crate::base::maps::Tiling;
use crate::base::probes::Tee;
use crate::cost::arch::Arch;
use crate::cost::timing::PassKind;
use crate::input::limits::Limits;
use crate::pass::PassError;
use crate::pass::camera::{CameraFrame, Visibility, visibility};
use crate::render::costed::{SceneCounts, shape};
use crate::truth::cause::OccluderMemo;
use crate::truth::metrics::{Fields, Footprints};
use crate::truth::reference::{PixelTruth, Reference};
use crate::world::occluders::Lit;
use crate::world::scene::Scene;

/// One visibility pass, in one tiling, and what it left.
#[derive(Debug)]
pub(super) struct Seen {
    /// The first pass (this one or an earlier) with the same visible ids:
    /// passes with the same ids shade alike.
    pub(super) class: usize,
    pub(super) frame: CameraFrame,
    pub(super) camera: Mat4,
    /// The pass's events, totalled.
    pub(super) totals: Totals,
    /// The camera probes of the architectures drawn in this tiling, as the
    /// pass left them (they read no map yet).
    pub(super) probes: Vec<(usize, Kept)>,
}

/// What the renders of one scene at one image size share: a visibility
/// pass per tiling, the scene's counts, the exact reference's rays and
/// what each shadow-casting light's shading reads ([`Lighting`]).
#[derive(Debug)]
pub(crate) struct ImageShare<'s> {
    pub(super) scene: &'s Scene,
    pub(super) size: (u32, u32),
    /// The exact reference's rays, for judging wrong pixels by cause.
    pub(super) reference: Reference,
    pub(super) archs: &'s [Arch],
    pub(super) limits: Limits,
    /// The default tiling's first, then each architecture's.
    pub(super) seen: Vec<Seen>,
    /// For each architecture that [`shares`](super::shares), its entry in `seen`.
    pub(super) seen_by: Vec<Option<usize>>,
    pub(super) counts: SceneCounts,
    /// The scene's triangles ([`Scene::triangles`]), for every shading.
    pub(super) triangles: Vec<SceneTriangle>,
    /// The scene as each shadow-casting light lights it, in the scene's
    /// order.
    pub(super) lit: Vec<Lit<'s>>,
    /// What each light's shadings read beside its map, in the same order.
    pub(super) lights: Vec<Lighting<'s>>,
}

/// What the shadings against one light read beside its map and the scene
/// as it lights it: the light's exact reference with its [`Fields`], the
/// occluders its judge found, and the map's footprints kept over renders.
#[derive(Debug)]
pub(super) struct Lighting<'s> {
    pub(super) truth: &'s [Option<PixelTruth>],
    pub(super) fields: Fields,
    /// The occluders the judge's rays found, for every configuration.
    pub(super) occluders: OccluderMemo,
    /// The map's footprints over renders of this image, kept for the
    /// configurations whose visible points on the map are the same (at
    /// most [`KEPT_FOOTPRINTS`]: one a map side).
    footprints: Mutex<Vec<Arc<Footprints>>>,
}

/// The most footprints an [`ImageShare`] keeps.
pub(crate) const KEPT_FOOTPRINTS: usize = 4;

/// The visibility unit over a scene into a frame, as [`Reporting`].
struct Draw<'a> {
    frame: &'a mut CameraFrame,
    scene: &'a Scene,
    size: (u32, u32),
    tiling: Tiling,
    totals: &'a mut Totals,
}

impl Reporting for Draw<'_> {
    type Out = Result<Visibility, PassError>;

    fn run<P: Probe>(self, probe: &mut P) -> Self::Out {
        visibility(self.frame, self.scene, self.size, self.tiling, &mut Tee(self.totals, probe))
    }
}

impl<'s> ImageShare<'s> {
    /// The visibility of `scene` at `size` in the default tiling and in
    /// each tiling of `archs`, and each light's reference of `truths` (one
    /// a shadow-casting light) with its fields: `None` when a reference
    /// has no pixel to measure or a pass cannot run, for each
    /// configuration to render (and fail) on its own.
    #[must_use]
    pub(crate) fn new(
        scene: &'s Scene,
        size: (u32, u32),
        truths: &'s [Vec<Option<PixelTruth>>],
        archs: &'s [Arch],
        limits: &Limits,
    ) -> Option<Self> {
        let pixels = u64::from(size.0) * u64::from(size.1);
        let lit = Lit::each(scene);
        let measured = |t: &[Option<PixelTruth>]| t.len() as u64 == pixels && t.iter().flatten().any(|t| t.faces_light);
        if truths.len() != lit.len() || !truths.iter().all(|t| measured(t)) {
            return None;
        }
        let (tilings, seen_by) = assign(archs, Tiling::DEFAULT, Arch::tiling);
        // Each tiling's pass, in parallel.
        let drawn: Vec<Option<Seen>> = tilings
            .par_iter()
            .enumerate()
            .map(|(k, &tiling)| {
                let raster =
                    RasterConfig::new(size.0, size.1, tiling.tile, RasterConfig::DEFAULT_SUBPIXEL_BITS).ok()?;
                let mut probes = Probes::default();
                for (i, a) in archs.iter().enumerate().filter(|&(i, _)| seen_by[i] == Some(k)) {
                    let detail = shape(a).camera_addresses;
                    probes.push(i, Kept::new(a, (PassKind::Camera, raster), (DepthFormatKind::D24, 1), detail));
                }
                let (mut frame, mut totals) = (CameraFrame::default(), Totals::default());
                let draw = Draw { frame: &mut frame, scene, size, tiling, totals: &mut totals };
                let camera = probes.run(draw).ok()?.camera;
                Some(Seen { class: k, frame, camera, totals, probes: probes.into_kept() })
            })
            .collect();
        let mut seen: Vec<Seen> = Vec::with_capacity(tilings.len());
        for pass in drawn {
            let mut pass = pass?;
            pass.class = seen.iter().position(|s| s.frame.ids() == pass.frame.ids()).unwrap_or(pass.class);
            seen.push(pass);
        }
        let lights = truths
            .iter()
            .map(|truth| Lighting {
                truth,
                fields: Fields::new(truth, size.0),
                occluders: OccluderMemo::default(),
                footprints: Mutex::new(Vec::new()),
            })
            .collect();
        let triangles = scene.triangles();
        Some(Self {
            scene,
            size,
            reference: Reference::with_objects(&triangles, &scene.triangle_objects()).ok()?,
            archs,
            limits: *limits,
            seen,
            seen_by,
            counts: SceneCounts::of(scene, &lit, &[]),
            triangles,
            lit,
            lights,
        })
    }
}

impl<'s> ImageShare<'s> {
    /// The scene's shadow-casting lights (one for a scene of none).
    #[must_use]
    pub(crate) fn lights(&self) -> usize {
        self.lights.len()
    }

    /// The scene as each of its shadow-casting lights lights it.
    #[must_use]
    pub(crate) fn lit(&self) -> &[Lit<'s>] {
        &self.lit
    }
}

impl Lighting<'_> {
    /// The footprints kept from earlier configurations of this image.
    pub(super) fn kept_footprints(&self) -> Vec<Arc<Footprints>> {
        self.footprints.lock().map(|k| k.clone()).unwrap_or_default()
    }

    /// The map's footprint over `render`, a render of this image (`width`
    /// pixels wide) against this light: `fits`, one kept that fits it (the
    /// same points on the map), or worked out, and kept while there is
    /// room.
    pub(super) fn footprints(&self, render: &[Shaded], width: u32, fits: Option<&Arc<Footprints>>) -> Arc<Footprints> {
        if let Some(f) = fits {
            return Arc::clone(f);
        }
        let f = Arc::new(Footprints::of(render, self.truth, width as usize));
        if let Ok(mut k) = self.footprints.lock()
            && k.len() < KEPT_FOOTPRINTS
        {
            k.push(Arc::clone(&f));
        }
        f
    }
}
