//! Running a sweep: each configuration rendered once against the reference and costed on every architecture.

mod work;

use indicatif::ProgressBar;
use rayon::prelude::*;

use std::sync::Mutex;

use super::{Config, Row, RowCost, RowMetrics, Shard, Spec, StudyError};
use crate::base::maps::with_format;
use crate::base::stop;
use crate::cost::arch::Arch;
use crate::cost::report::CostReport;
use crate::input::limits::Limits;
use crate::render::shared::{ImageShare, LightKey, LightShare, Scratch, render_shared};
use crate::render::{Algorithm, RenderConfig, RenderError, TruthSource, cost_others, render_costed, truth};
use crate::truth::reference::PixelTruth;
use crate::world::scene::Scene;
use umbra_core::probe::Totals;
use umbra_core::shadow::{Filter, ShadowConfig};
use umbra_core::{DepthFormat, DepthFormatKind};
use work::Progress;

/// The render configuration of `c`.
#[must_use]
#[allow(clippy::needless_update, reason = "a parameter no sweep axis sets takes its default")]
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
        cascades: v.cascades,
        ..RenderConfig::DEFAULT
    }
}

/// Render one configuration once and cost it on every architecture: one
/// row per architecture (one row when the sweep has none). A render or
/// costing that fails gives skipped rows that say why.
///
/// The render (light pass, camera pass, metrics against the scene's
/// reference `truth` of its scene and image) also costs the architectures that draw as it
/// does; the others are costed in one run of the passes per tiling
/// ([`render_costed`]), because a tile size changes the light pass's events
/// (`PixelFlow`'s 128² regions bin and flush differently from 32² chunks).
/// The exact reference, the expensive part, is not recomputed.
#[must_use]
pub(crate) fn run_config(spec: &Spec, c: &Config, truth: &Truth) -> Vec<Row> {
    let scene = &spec.scenes[c.scene];
    let cfg = render_config(spec, c);
    let done = match truth {
        Ok(t) => cfg
            .check(scene, &spec.limits)
            .and_then(|job| render_costed(&job, TruthSource::Given(t.clone()), &spec.archs))
            .map_err(|e| e.to_string()),
        Err(e) => Err(format!("reference: {e}")),
    };
    let done =
        done.map(|(r, costs)| (RowMetrics::new(&r.frame_metrics(), tangent_share(&r.camera_events.totals)), costs));
    rows_of(spec, c, &done)
}

/// What a configuration's render measured: its metrics and its cost on
/// each architecture.
type Measured = (RowMetrics, Vec<Result<CostReport, RenderError>>);

/// The rows of `c` given what its render `done` measured (or why it
/// failed): one per architecture (one when the sweep has none).
fn rows_of(spec: &Spec, c: &Config, done: &Result<Measured, String>) -> Vec<Row> {
    let arch_rows: Vec<Option<(usize, &Arch)>> =
        if spec.archs.is_empty() { vec![None] } else { spec.archs.iter().enumerate().map(Some).collect() };
    arch_rows
        .into_iter()
        .map(|arch| {
            let mut row = Row::new(spec, c, arch);
            match done {
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

/// The rows of `c` rendered from what it shares with the configurations
/// of its scene, image and light pass ([`crate::render::shared`]): those
/// of [`run_config`], bit for bit, or `None` for it to render on its own.
fn run_shared<F: DepthFormat>(
    spec: &Spec,
    c: &Config,
    image: &ImageShare<'_>,
    lights: &[LightShare<F::Texel>],
    scratch: &mut Scratch,
) -> Option<Vec<Row>> {
    let cfg = render_config(spec, c);
    let (metrics, camera, mut costs) = render_shared::<F>(image, lights, &cfg, scratch)?;
    let job = cfg.check(&spec.scenes[c.scene], &spec.limits).ok()?;
    cost_others((&job, image.lit()), &spec.archs, &mut costs);
    let costs = costs.into_iter().map(|r| r.unwrap_or_else(|| Err(RenderError::Cost("not costed".into()))));
    Some(rows_of(spec, c, &Ok((RowMetrics::new(&metrics, tangent_share(&camera)), costs.collect()))))
}

/// A scene's exact reference at the study's image size, one per
/// shadow-casting light, or why there is none.
pub(crate) type Truth = Result<Vec<Vec<Option<PixelTruth>>>, String>;

/// The exact reference of scene `scene` at image size `image` of `spec`,
/// built in parallel: it depends only on the scene, the image size and the
/// rays per pixel, not on the configuration. An image beyond the limits is
/// refused before anything is built.
pub(crate) fn truth_of(spec: &Spec, scene: usize, image: usize) -> Truth {
    let [w, h] = spec.images[image];
    spec.limits.check_image(w, h).map_err(|e| e.to_string())?;
    truth(&spec.scenes[scene], w, h, spec.reference_rays, &ProgressBar::hidden()).map_err(|e| e.to_string())
}

/// Run the configurations of `shard` in parallel (on the current rayon pool).
/// Rows come back sorted by configuration and preset. `progress`'s length
/// is the run's estimated work, ticked as each reference and configuration
/// is done, and its message says how many configurations are done of how
/// many.
///
/// One scene and image size is run at a time: its reference is built once,
/// shared by its configurations and dropped before the next, and at most
/// `Spec::renders_at_once` of its configurations render at once, so the
/// study stays within [`Limits::max_memory`].
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
/// let rows = umbra_sim::study(&spec, umbra_sim::experiment::study::Shard::ALL, &indicatif::ProgressBar::hidden())?;
/// assert_eq!(rows.len(), 4); // 2 formats × 2 filters × 1 architecture
/// assert!(rows.iter().all(|r| r.complete()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`StudyError::Limit`] when even one render beside the scenes and a
/// reference would take more than [`Limits::max_memory`];
/// [`StudyError::Stopped`] when a stop is requested ([`crate::base::stop`]):
/// no configuration starts after it.
pub fn run(spec: &Spec, shard: Shard, progress: &ProgressBar) -> Result<Vec<Row>, StudyError> {
    run_with(spec, shard, progress, true)
}

#[cfg(test)]
/// [`run`] rendering every configuration, even those that render alike
/// (`alike`): the reference the shared path is held to.
///
/// # Errors
/// As [`run`].
pub(crate) fn run_unshared(spec: &Spec, shard: Shard, progress: &ProgressBar) -> Result<Vec<Row>, StudyError> {
    run_with(spec, shard, progress, false)
}

/// What configuration `c` renders as, for those whose algorithm reads only
/// some of the axes: shadow volumes draw no map, so neither the map's
/// format, its side nor the filter changes their render or its cost; a
/// silhouette map's test reads the four depth samples at its texel's
/// corners whatever the filter (Sen et al. §3.2), so the filter changes
/// neither. Only a configuration within every limit and valid on its own
/// is shared, so that one beyond a limit keeps its own skipped row.
fn alike(spec: &Spec, c: &Config) -> Option<RenderConfig> {
    let cfg = render_config(spec, c);
    let like = match cfg.algorithm {
        Algorithm::Volumes => RenderConfig { format: DepthFormatKind::D24, map_size: 1, filter: Filter::Point, ..cfg },
        // Its own filter must be one the shadow unit takes, or its row is
        // its own failure.
        Algorithm::Silhouette { .. } => {
            let units = cfg.algorithm.units::<umbra_core::D24>(cfg.bias);
            ShadowConfig::new(units.test, units.bias, cfg.filter, true).ok()?;
            RenderConfig { filter: Filter::Point, ..cfg }
        }
        _ => return None,
    };
    cfg.check(&spec.scenes[c.scene], &spec.limits).is_ok().then_some(like)
}

/// The rows of `c`, rendered alike to the configuration whose rows are
/// `like`: its own configuration, their numbers.
fn rows_like(spec: &Spec, c: &Config, like: &[Row]) -> Vec<Row> {
    like.iter()
        .map(|r| {
            let arch = spec.archs.get(r.arch_index).map(|a| (r.arch_index, a));
            let mut row = Row::new(spec, c, arch);
            row.status = r.status;
            row.reason.clone_from(&r.reason);
            row.metrics = r.metrics;
            row.cost.clone_from(&r.cost);
            row
        })
        .collect()
}

/// The configurations of one scene and image size of a shard, run together
/// on their reference.
pub(super) struct Group<'c> {
    /// The scene.
    pub(super) scene: usize,
    /// The image size.
    pub(super) image: usize,
    /// Its configurations, in the study's order.
    pub(super) configs: Vec<&'c Config>,
    /// For each, the position of the first that renders alike to it
    /// ([`alike`]; its own when none): only the first is rendered.
    pub(super) first: Vec<usize>,
    /// Whether its configurations share what they can
    /// ([`crate::render::shared`]).
    pub(super) shared: bool,
}

/// The groups of `configs`, scene by scene, each image size in turn;
/// configurations that render alike are noted when `share`.
pub(super) fn groups<'c>(spec: &Spec, configs: &'c [Config], share: bool) -> Vec<Group<'c>> {
    let mut groups = Vec::new();
    for scene in 0..spec.scenes.len() {
        for image in 0..spec.images.len() {
            let group: Vec<&Config> = configs.iter().filter(|c| c.scene == scene && c.image == image).collect();
            if group.is_empty() {
                continue;
            }
            let keys: Vec<Option<RenderConfig>> =
                group.iter().map(|c| if share { alike(spec, c) } else { None }).collect();
            let first = (0..group.len())
                .map(|i| keys[i].map_or(i, |k| keys.iter().position(|o| *o == Some(k)).unwrap_or(i)))
                .collect();
            groups.push(Group { scene, image, configs: group, first, shared: share });
        }
    }
    groups
}

fn run_with(spec: &Spec, shard: Shard, progress: &ProgressBar, share: bool) -> Result<Vec<Row>, StudyError> {
    let at_once = spec.renders_at_once(rayon::current_num_threads())?;
    let layout = super::Layout::of(spec);
    let configs: Vec<Config> = spec.configs().into_iter().filter(|c| shard.contains(&layout, c.index)).collect();
    let groups = groups(spec, &configs, share);
    let progress = Progress::new(progress, spec, &groups);
    let mut rows = Vec::new();
    let scratch = Mutex::new(Vec::<Scratch>::new());
    for g in &groups {
        stop::check()?;
        let (group, first) = (&g.configs, &g.first);
        let truth = truth_of(spec, g.scene, g.image);
        stop::check()?;
        progress.reference(spec, g);
        // Each configuration's first of its kind, rendered; the others
        // reported from it.
        let rendered: Vec<&Config> = (0..group.len()).filter(|&i| first[i] == i).map(|i| group[i]).collect();
        let [w, h] = spec.images[g.image];
        let shared = match &truth {
            Ok(t) if g.shared => ImageShare::new(&spec.scenes[g.scene], (w, h), t, &spec.archs, &spec.limits),
            _ => None,
        };
        // The configurations that render on their own (shadow volumes,
        // which draw no map; every one when nothing is shared), and
        // blocks of one format and map side of the others, in the order
        // their first comes: each block's light passes drawn at once,
        // in parallel, then every configuration of the block in
        // parallel.
        let (alone, blocks) = blocks(spec, &rendered, shared.is_some());
        let alone = || run_waves(&alone, at_once, &progress, |c| run_config(spec, c, &truth));
        let blocks = || {
            let mut done: Vec<Vec<Row>> = Vec::with_capacity(rendered.len());
            for ((format, _), members) in blocks {
                let Some(image) = &shared else { continue };
                let mut rows = with_format!(format, F => {
                    let lights = light_shares::<F>(spec, image, &members);
                    run_waves(&members, at_once, &progress, |c| {
                        let cfg = render_config(spec, c);
                        let light = LightKey::of(&cfg)
                            .and_then(|k| lights.iter().find(|l| l.0 == k))
                            .and_then(|l| l.1.as_ref());
                        let mut mine = scratch.lock().map(|mut s| s.pop()).ok().flatten().unwrap_or_default();
                        let rows = light
                            .and_then(|l| run_shared::<F>(spec, c, image, l, &mut mine))
                            .unwrap_or_else(|| run_config(spec, c, &truth));
                        if let Ok(mut s) = scratch.lock() {
                            s.push(mine);
                        }
                        rows
                    })
                });
                done.append(&mut rows);
            }
            done
        };
        // A configuration on its own takes as long as many shared ones
        // (a shadow volume's stencil pass): with room for a render a
        // thread, those run beside the blocks rather than after them,
        // so that no thread waits alone at the end.
        let (mut done, mut own) = if at_once >= rayon::current_num_threads() {
            let (own, done) = rayon::join(alone, blocks);
            (done, own)
        } else {
            (blocks(), alone())
        };
        // Configurations skipped for a stop left no rows.
        stop::check()?;
        done.append(&mut own);
        done.sort_by_key(|r| r.first().map(|r| r.config_index));
        for (i, c) in group.iter().enumerate() {
            if first[i] != i {
                let at = done
                    .iter()
                    .position(|r| r.first().map(|r| r.config_index) == Some(group[first[i]].index))
                    .unwrap_or(0);
                rows.extend(rows_like(spec, c, &done[at]));
                progress.config(c);
            }
        }
        rows.extend(done.into_iter().flatten());
    }
    sort_rows(&mut rows);
    Ok(rows)
}

/// The configurations of `rendered` (of one scene and image) that render on
/// their own (all of them unless `shared`), and the others in blocks of one
/// format and map side, in the order each block's first comes.
#[allow(clippy::type_complexity, reason = "a block's key and its configurations")]
fn blocks<'c>(
    spec: &Spec,
    rendered: &[&'c Config],
    shared: bool,
) -> (Vec<&'c Config>, Vec<((DepthFormatKind, u32), Vec<&'c Config>)>) {
    let mut alone = Vec::new();
    let mut blocks: Vec<((DepthFormatKind, u32), Vec<&Config>)> = Vec::new();
    for &c in rendered {
        let cfg = render_config(spec, c);
        if !shared || LightKey::of(&cfg).is_none() || cfg.cascaded(&spec.scenes[c.scene]) {
            alone.push(c);
            continue;
        }
        match blocks.iter_mut().find(|b| b.0 == (c.format, c.map_size)) {
            Some(b) => b.1.push(c),
            None => blocks.push(((c.format, c.map_size), vec![c])),
        }
    }
    // The filters that compare the most samples first, so that a block
    // does not end waiting on one of them alone (the rows are sorted
    // afterwards).
    for (_, members) in &mut blocks {
        members.sort_by_key(|c| core::cmp::Reverse(work::taps(spec, c)));
    }
    (alone, blocks)
}

/// The light passes of `configs` (of one format `F` and map side), one
/// share per [`LightKey`] and shadow-casting light, drawn in parallel:
/// `None` for a key one of whose passes cannot run (its configurations
/// render on their own).
#[allow(clippy::type_complexity, reason = "a key and its lights' shares")]
fn light_shares<F: DepthFormat>(
    spec: &Spec,
    image: &ImageShare<'_>,
    configs: &[&Config],
) -> Vec<(LightKey, Option<Vec<LightShare<F::Texel>>>)> {
    let mut keys: Vec<(LightKey, RenderConfig)> = Vec::new();
    for c in configs {
        let cfg = render_config(spec, c);
        if let Some(k) = LightKey::of(&cfg).filter(|k| !keys.iter().any(|(o, _)| o == k)) {
            keys.push((k, cfg));
        }
    }
    let lights = image.lights();
    let passes: Vec<(usize, usize)> = (0..keys.len()).flat_map(|k| (0..lights).map(move |l| (k, l))).collect();
    let drawn: Vec<Option<LightShare<F::Texel>>> =
        passes.into_par_iter().map(|(k, l)| LightShare::new::<F>(image, &keys[k].1, l)).collect();
    let mut drawn = drawn.into_iter();
    keys.into_iter()
        .map(|(k, _)| {
            let mine: Vec<_> = drawn.by_ref().take(lights).collect();
            (k, mine.into_iter().collect())
        })
        .collect()
}

/// `each` over `configs` in parallel, at most `at_once` at a time (all at
/// once on as many threads as the pool has when memory allows that many),
/// ticking `progress` as each is done: their rows, in order. Once a stop
/// is requested no configuration starts, and those not started give no
/// rows.
fn run_waves(
    configs: &[&Config],
    at_once: usize,
    progress: &Progress<'_>,
    each: impl Fn(&Config) -> Vec<Row> + Sync,
) -> Vec<Vec<Row>> {
    let mut done = Vec::with_capacity(configs.len());
    // A pool runs one configuration a thread: with room for one a thread,
    // one wave takes them all, and no thread waits for a wave's slowest.
    let wave = if at_once >= rayon::current_num_threads() { configs.len().max(1) } else { at_once };
    for wave in configs.chunks(wave) {
        done.par_extend(wave.par_iter().filter(|_| !stop::requested()).map(|c| {
            let rows = each(c);
            progress.config(c);
            rows
        }));
    }
    done
}

/// The share of a camera pass's decided pixels that needed a tangent
/// plane (Wang & Molnar's virtual samples), from its event totals.
#[allow(clippy::cast_precision_loss, reason = "a ratio of pixel counts")]
fn tangent_share(t: &Totals) -> f64 {
    let (a, b) = (t.tangent_setups, t.tangent_setups + t.trivial_pixels());
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
    let scenes = names.iter().map(|n| Scene::open(n.as_ref(), limits)).collect::<Result<Vec<_>, _>>()?;
    match super::same_names(&scenes) {
        Some((_, _, problem)) => {
            Err(StudyError::Sweep(super::SweepError { file: "--scene".into(), key: "(names)".into(), problem }))
        }
        None => Ok(scenes),
    }
}
