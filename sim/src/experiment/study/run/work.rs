//! The work of a study, estimated from what drives its cost, and the
//! progress bar that counts it: configurations differ in cost by orders
//! of magnitude (a 1920×1080 image against a 320×180 one, a 16-sample
//! filter against one tap, a scene's reference of 4×4 rays a pixel), so a
//! bar counting configurations would tell a rate, and a time left, that
//! the next ones do not keep.
//!
//! The figures are nanoseconds of one core, measured on the bundled scenes
//! and `scenes/large/torus-100k.toml` (each the slope of a study's time
//! against the axis it varies): an estimate whose ratios matter, not a
//! promise of time.

use std::sync::atomic::{AtomicUsize, Ordering};

use indicatif::ProgressBar;
use umbra_core::shadow::{Filter, MapCoord, jitter_grid};

use super::super::{Config, Spec};
use super::{Group, render_config};
use crate::render::shared::LightKey;
use crate::world::scene::Scene;

/// A reference pixel: the camera's visibility, the boundaries and
/// distance fields, the centre's ray.
const REFERENCE_PIXEL: u64 = 600;
/// Each of a reference pixel's `n × n` area rays.
const REFERENCE_RAY: u64 = 200;
/// A camera pixel shaded and judged, beside its filter's taps.
const SHADED_PIXEL: u64 = 150;
/// A map sample a filter compares at a pixel.
const TAP: u64 = 65;
/// A light-map texel cleared and drawn.
const TEXEL: u64 = 5;
/// A triangle set up and drawn by one pass.
const TRIANGLE: u64 = 2500;

/// The map samples `c`'s filter compares at a pixel, as they cost. A
/// jittered filter's grid follows the pixel's footprint on the map
/// ([`jitter_grid`]), taken as the map's side over the image's (its
/// pixels' square root); it measures as one tap and half a tap a sample.
#[must_use]
pub(crate) fn taps(spec: &Spec, c: &Config) -> u64 {
    match spec.filters[c.filter] {
        Filter::Point => 1,
        Filter::Bilinear => 4,
        Filter::Box { size } => u64::from(size) * u64::from(size),
        Filter::Jittered(j) => {
            #[allow(clippy::cast_precision_loss, reason = "a side over another, an estimate")]
            let footprint = f64::from(c.map_size) / (pixels(spec, c.image) as f64).sqrt().max(1.0);
            let (_, [s, t]) = jitter_grid(&j, [MapCoord::saturating_from_num(footprint); 2]);
            1 + u64::from(s) * u64::from(t) / 2
        }
    }
}

/// The passes a scene draws for each: one a shadow-casting light.
fn lights(scene: &Scene) -> u64 {
    scene.lights.len().max(1) as u64
}

fn triangles(scene: &Scene) -> u64 {
    scene.objects.iter().map(|o| o.mesh.triangles.len() as u64).sum()
}

fn pixels(spec: &Spec, image: usize) -> u64 {
    let [w, h] = spec.images[image];
    u64::from(w) * u64::from(h)
}

/// The work of the reference a scene and image size's configurations
/// share: the camera's visibility and the exact rays, for each light.
#[must_use]
pub(crate) fn reference(spec: &Spec, scene: usize, image: usize) -> u64 {
    let s = &spec.scenes[scene];
    let n = u64::from(spec.reference_rays);
    let rays = lights(s).saturating_mul(pixels(spec, image)).saturating_mul(REFERENCE_PIXEL + REFERENCE_RAY * n * n);
    rays.saturating_add(triangles(s).saturating_mul(TRIANGLE))
}

/// The work of `c`'s own passes beside the shading: each light's map
/// drawn (or, for shadow volumes, the stencil pass's triangles).
#[must_use]
pub(crate) fn passes(spec: &Spec, c: &Config) -> u64 {
    let s = &spec.scenes[c.scene];
    let texels = LightKey::of(&render_config(spec, c)).map_or(0, |_| u64::from(c.map_size) * u64::from(c.map_size));
    lights(s).saturating_mul(texels.saturating_mul(TEXEL).saturating_add(triangles(s).saturating_mul(TRIANGLE)))
}

/// The work of shading `c`: every pixel with its filter's taps, for each
/// light.
#[must_use]
pub(crate) fn shading(spec: &Spec, c: &Config) -> u64 {
    let per_pixel = SHADED_PIXEL.saturating_add(TAP.saturating_mul(taps(spec, c)));
    lights(&spec.scenes[c.scene]).saturating_mul(pixels(spec, c.image)).saturating_mul(per_pixel)
}

/// Each configuration's work as the run spends it: a configuration that
/// renders alike to an earlier one copies its rows and takes none; one
/// that shares a light pass with earlier ones of its group
/// ([`LightKey`]) shades only; any other draws its passes and shades.
/// Indexed by [`Config::index`].
#[must_use]
pub(crate) fn configs(spec: &Spec, groups: &[Group<'_>]) -> Vec<u64> {
    let mut work = vec![0; groups.iter().flat_map(|g| &g.configs).map(|c| c.index + 1).max().unwrap_or(0)];
    for g in groups {
        let mut drawn: Vec<LightKey> = Vec::new();
        for (i, &c) in g.configs.iter().enumerate() {
            if g.first[i] != i {
                continue;
            }
            let key = LightKey::of(&render_config(spec, c)).filter(|_| g.shared);
            let passes = match key {
                Some(k) if drawn.contains(&k) => 0,
                Some(k) => {
                    drawn.push(k);
                    passes(spec, c)
                }
                None => passes(spec, c),
            };
            work[c.index] = shading(spec, c).saturating_add(passes);
        }
    }
    work
}

/// A study's progress on a bar: its length the work of the groups'
/// references and of the configurations, ticked as each is done; its
/// message how many configurations are done of how many.
pub(crate) struct Progress<'p> {
    bar: &'p ProgressBar,
    /// Each configuration's work, by index.
    work: Vec<u64>,
    /// The configurations run.
    configs: usize,
    /// Those done.
    done: AtomicUsize,
}

impl<'p> Progress<'p> {
    /// The progress of running `groups` of `spec`, shown on `bar`.
    pub(crate) fn new(bar: &'p ProgressBar, spec: &Spec, groups: &[Group<'_>]) -> Self {
        let work = configs(spec, groups);
        let references = groups.iter().map(|g| reference(spec, g.scene, g.image));
        bar.set_length(references.chain(work.iter().copied()).fold(0, u64::saturating_add));
        let configs = groups.iter().map(|g| g.configs.len()).sum();
        let progress = Self { bar, work, configs, done: AtomicUsize::new(0) };
        progress.say(0);
        progress
    }

    fn say(&self, done: usize) {
        self.bar.set_message(format!("{done}/{} configurations", self.configs));
    }

    /// The reference of `g` is built.
    pub(crate) fn reference(&self, spec: &Spec, g: &Group<'_>) {
        self.bar.inc(reference(spec, g.scene, g.image));
    }

    /// Configuration `c` is done.
    pub(crate) fn config(&self, c: &Config) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        self.say(done);
        self.bar.inc(self.work.get(c.index).copied().unwrap_or(0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Algorithm;
    use crate::experiment::study::{self, Shard, Variant};
    use crate::input::limits::Limits;

    /// One scene, one configuration a point of each axis given.
    fn spec(images: Vec<[u32; 2]>, maps: Vec<u32>, filters: Vec<Filter>, rays: u32) -> Spec {
        let scenes = study::load_scenes(&["weiskopf-l"], &Limits::DEFAULT).expect("bundled");
        let mut spec = Spec::quick(scenes);
        spec.variants = vec![Variant::new(Algorithm::First, 0.002)];
        spec.formats.truncate(1);
        spec.images = images;
        spec.map_sizes = maps;
        spec.filters = filters;
        spec.reference_rays = rays;
        spec
    }

    fn first(spec: &Spec) -> Config {
        spec.configs()[0]
    }

    #[test]
    fn a_larger_image_map_filter_or_reference_is_more_work() {
        let small = spec(vec![[320, 180]], vec![256], vec![Filter::Point], 1);
        let at = |images, maps, filters, rays| spec(images, maps, filters, rays);
        let large = at(vec![[1920, 1080]], vec![256], vec![Filter::Point], 1);
        assert!(shading(&large, &first(&large)) > 30 * shading(&small, &first(&small)));
        let map = at(vec![[320, 180]], vec![4096], vec![Filter::Point], 1);
        assert!(passes(&map, &first(&map)) > passes(&small, &first(&small)));
        let box5 = at(vec![[320, 180]], vec![256], vec![Filter::Box { size: 5 }], 1);
        assert!(shading(&box5, &first(&box5)) > 5 * shading(&small, &first(&small)));
        // A jittered filter takes more samples where a pixel covers more
        // texels: a larger map behind the same image.
        let jitter = |map| at(vec![[1920, 1080]], vec![map], vec!["jitter16".parse().expect("a filter")], 1);
        let (coarse, fine) = (jitter(256), jitter(2048));
        assert!(taps(&fine, &first(&fine)) > 2 * taps(&coarse, &first(&coarse)));
        let rays = at(vec![[320, 180]], vec![256], vec![Filter::Point], 4);
        assert!(reference(&rays, 0, 0) > 4 * reference(&small, 0, 0));
        // A 1080p reference of 4×4 rays outweighs many a configuration at that size.
        let full = at(vec![[1920, 1080]], vec![256], vec![Filter::Point], 4);
        assert!(reference(&full, 0, 0) > 10 * shading(&full, &first(&full)));
    }

    #[test]
    fn the_bar_is_the_work_and_ends_full_counting_every_configuration() {
        let mut spec = spec(vec![[64, 36], [96, 54]], vec![64, 128], vec![Filter::Point, Filter::Bilinear], 1);
        // Shadow volumes render alike at every map and filter: copies.
        spec.variants.push(Variant::new(Algorithm::Volumes, 0.0));
        let bar = ProgressBar::hidden();
        let rows = study::run(&spec, Shard::ALL, &bar).expect("within the limits");
        let n = spec.configs().len();
        assert_eq!(rows.len(), n * spec.archs.len().max(1));
        let configs: Vec<Config> = spec.configs();
        let groups = super::super::groups(&spec, &configs, true);
        let work = super::configs(&spec, &groups);
        let references: u64 = groups.iter().map(|g| reference(&spec, g.scene, g.image)).sum();
        assert_eq!(bar.length(), Some(references + work.iter().sum::<u64>()));
        assert_eq!(bar.position(), bar.length().unwrap_or(0), "every unit ticked once");
        assert_eq!(bar.message(), format!("{n}/{n} configurations"));
        // A volume's copies take no work; the first of them its passes.
        let volumes: Vec<&Config> = configs.iter().filter(|c| c.variant == 1).collect();
        assert!(work[volumes[0].index] > 0);
        assert!(volumes[1..].iter().filter(|c| c.image == volumes[0].image).all(|c| work[c.index] == 0));
        // A light pass shared by the filters is charged once.
        let firsts: Vec<&Config> =
            configs.iter().filter(|c| c.variant == 0 && c.image == 0 && c.map_size == 128).collect();
        assert_eq!(work[firsts[0].index], shading(&spec, firsts[0]) + passes(&spec, firsts[0]));
        assert_eq!(work[firsts[1].index], shading(&spec, firsts[1]));
    }
}
