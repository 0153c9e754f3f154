//! Running a sweep: each configuration rendered once against the reference and costed on every architecture.

use indicatif::ProgressBar;
use rayon::prelude::*;

use super::{Config, Row, RowCost, RowMetrics, Shard, Spec, StudyError};
use crate::cost::arch::Arch;
use crate::io::limits::Limits;
use crate::render::{RenderConfig, TruthSource, render_costed, truth};
use crate::truth::reference::PixelTruth;
use crate::world::scene::Scene;

/// The render configuration of `c`.
#[must_use]
pub fn render_config(spec: &Spec, c: &Config) -> RenderConfig {
    let v = &spec.variants[c.variant];
    RenderConfig {
        algorithm: v.algorithm,
        format: c.format,
        map_size: c.map_size,
        filter: spec.filters[c.filter],
        bias: v.bias,
        virtual_samples: v.virtual_samples,
        width: spec.images[c.image][0],
        height: spec.images[c.image][1],
        reference_rays: spec.reference_rays,
        culling: v.culling,
    }
}

/// Render one configuration once and cost it on every architecture: one
/// row per architecture (one row when the sweep has none). A render or
/// costing that fails gives skipped rows that say why.
///
/// The render (light pass, camera pass, metrics against the scene's
/// reference from [`truths`]) also costs the architectures that draw as it
/// does; the others are costed in one run of the passes per tiling
/// ([`render_costed`]), because a tile size changes the light pass's events
/// (`PixelFlow`'s 128² regions bin and flush differently from 32² chunks).
/// The exact reference, the expensive part, is not recomputed.
#[must_use]
pub fn run_config(spec: &Spec, c: &Config, truths: &[Truth]) -> Vec<Row> {
    let scene = &spec.scenes[c.scene];
    let cfg = render_config(spec, c);
    let done = match &truths[c.scene * spec.images.len() + c.image] {
        Ok(t) => render_costed(scene, &cfg, &spec.limits, TruthSource::Given(t.clone()), &spec.archs)
            .map_err(|e| e.to_string()),
        Err(e) => Err(format!("reference: {e}")),
    };
    let done = done.map(|(r, costs)| {
        let t = &r.camera_events.totals;
        (RowMetrics::new(&r.metrics, ratio(t.tangent_setups, t.tangent_setups + t.trivial_pixels())), costs)
    });
    let arch_rows: Vec<Option<(usize, &Arch)>> =
        if spec.archs.is_empty() { vec![None] } else { spec.archs.iter().enumerate().map(Some).collect() };
    arch_rows
        .into_iter()
        .map(|arch| {
            let mut row = Row::new(spec, c, arch);
            match &done {
                Ok((m, costs)) => {
                    row.metrics = Some(*m);
                    match arch.map(|(i, a)| (a, &costs[i])) {
                        Some((_, Ok(report))) => row.cost = Some(RowCost::new(report)),
                        Some((a, Err(e))) => row.skip(format!("cost on {}: {e}", a.name)),
                        None => {}
                    }
                }
                Err(e) => row.skip(format!("render: {e}")),
            }
            row
        })
        .collect()
}

/// A scene's exact reference at the study's image size, or why there is none.
pub type Truth = Result<Vec<Option<PixelTruth>>, String>;

/// The exact reference of every scene of `spec` at every image size
/// (scene-major), built once (in parallel): it depends only on the scene,
/// the image size and the rays per pixel, not on the configuration.
#[must_use]
pub fn truths(spec: &Spec) -> Vec<Truth> {
    let pairs: Vec<(&Scene, [u32; 2])> =
        spec.scenes.iter().flat_map(|s| spec.images.iter().map(move |&i| (s, i))).collect();
    pairs
        .par_iter()
        .map(|&(scene, [w, h])| {
            truth(scene, w, h, spec.reference_rays, &ProgressBar::hidden()).map_err(|e| e.to_string())
        })
        .collect()
}

/// Run the configurations of `shard` in parallel (on the current rayon pool),
/// ticking `progress` once per configuration. Rows come back sorted by
/// configuration and preset.
///
/// ```
/// use umbra_sim::{Limits, SweepFile};
/// let text = r#"
/// name = "mine"
/// scenes = ["weiskopf-l"]
/// images = [[96, 72]]
/// reference_rays = 1
/// formats = ["d16", "d24"]
/// maps = [128]
/// filters = ["point", "box5"]
/// archs = ["talisman"]
/// budgets = [1.0]
/// [[algorithms]]
/// algo = "first"
/// bias = [0.002]
/// "#;
/// let file = SweepFile { file: "mine.toml".into(), text: text.to_owned(), bundled: false };
/// let spec = file.spec(&Limits::DEFAULT)?;
/// let rows = umbra_sim::study(&spec, umbra_sim::experiment::study::Shard::ALL, &indicatif::ProgressBar::hidden());
/// assert_eq!(rows.len(), 4); // 2 formats × 2 filters × 1 architecture
/// assert!(rows.iter().all(|r| r.complete()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[must_use]
pub fn run(spec: &Spec, shard: Shard, progress: &ProgressBar) -> Vec<Row> {
    let truths = truths(spec);
    let configs: Vec<Config> = spec.configs().into_iter().filter(|c| shard.contains(c.index)).collect();
    progress.set_length(configs.len() as u64);
    let rows: Vec<Vec<Row>> = configs
        .par_iter()
        .map(|c| {
            let rows = run_config(spec, c, &truths);
            progress.inc(1);
            rows
        })
        .collect();
    let mut rows: Vec<Row> = rows.into_iter().flatten().collect();
    sort_rows(&mut rows);
    rows
}

#[allow(clippy::cast_precision_loss, reason = "a ratio of pixel counts")]
fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

pub(super) fn sort_rows(rows: &mut [Row]) {
    rows.sort_by_key(|r| (r.config_index, r.arch_index));
}

/// Load scenes by scene file or bundled name ([`Scene::open`]) within `limits`.
///
/// # Errors
/// [`StudyError::Scene`] naming the scene.
pub fn load_scenes<S: AsRef<str>>(names: &[S], limits: &Limits) -> Result<Vec<Scene>, StudyError> {
    names.iter().map(|n| Ok(Scene::open(n.as_ref(), limits)?)).collect()
}
