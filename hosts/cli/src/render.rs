//! `umbra render`: one shadow algorithm against the exact reference, with its pictures and metrics.

use std::path::PathBuf;

use crate::depth::{Format, format_kind};
use crate::say::say;
use anyhow::{Context, Result, bail};
use clap::ValueEnum;
use indicatif::ProgressBar;
use umbra_core::shadow::{Filter, Jitter, MapCoord};
use umbra_sim::io::folder::OutputFolder;
use umbra_sim::io::limits::Limits;
use umbra_sim::io::output::{RawMap, write_error_image, write_preview, write_shadow_image, write_shadow_term};
use umbra_sim::pass::render::{Algorithm, Culling, RenderConfig, TruthSource};
use umbra_sim::world::scene::Scene;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(super) enum Algo {
    /// Williams' first depth (use --bias).
    First,
    /// First depth with Reeves' bias range: per sample from [--bias, --bias1].
    BiasRange,
    /// Wang & Molnar's second depth from the dual unit.
    Second,
    /// Second depth by front-face culling.
    SecondFfc,
    /// Woo's midpoint.
    Midpoint,
    /// Weiskopf & Ertl's dual depth (use --offset).
    Dual,
    /// Sen et al.'s silhouette map, 16-bit points (use --bias).
    Silhouette,
    /// Sen et al.'s silhouette map, points packed to one byte per texel.
    SilhouettePacked,
    /// Depth-fail stencil shadow volumes (exact hard shadows).
    Volumes,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(super) enum FilterArg {
    Point,
    Bilinear,
    Box3,
    Jitter4,
    Jitter16,
    /// Reeves' jittered filter with --num-samples, --res-factor,
    /// --min-samples and --min-size.
    Jitter,
}

#[derive(clap::Args, Debug)]
pub(super) struct RenderArgs {
    /// A bundled scene by name (table, reeves-sphere, weiskopf-l,
    /// double-torus, thin, open-sheet, crowd, crowd-zoom, grazing, factory) or a
    /// scene file.
    #[arg(default_value = "table")]
    pub(super) scene: String,
    /// Shadow algorithm.
    #[arg(long, value_enum, default_value_t = Algo::Second)]
    pub(super) algo: Algo,
    /// Depth format of the map.
    #[arg(long, value_enum, default_value_t = Format::D24)]
    pub(super) depth: Format,
    /// Map side in texels.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..))]
    pub(super) map: u32,
    /// Percentage-closer filter.
    #[arg(long, value_enum, default_value_t = FilterArg::Bilinear)]
    pub(super) filter: FilterArg,
    /// Depth bias, as a depth in [0, 1] (`Bias0` of a bias range).
    #[arg(long, default_value_t = 0.0)]
    pub(super) bias: f64,
    /// `Bias1` of Reeves' bias range (--algo bias-range), as a depth in [0, 1].
    #[arg(long, default_value_t = 0.005)]
    pub(super) bias1: f64,
    /// Reeves' `NumSamples` (--filter jitter): samples per lookup.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u16).range(1..))]
    pub(super) num_samples: u16,
    /// Reeves' `ResFactor` (--filter jitter): enlarges the sampled region.
    #[arg(long, default_value_t = 3.0)]
    pub(super) res_factor: f64,
    /// Reeves' `MinSamples` (--filter jitter): fewest samples per axis.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    pub(super) min_samples: u16,
    /// Reeves' `MinSize` (--filter jitter): smallest half-size of the
    /// sampled region, texels.
    #[arg(long, default_value_t = 0.0)]
    pub(super) min_size: f64,
    /// The dual-depth offset, as a depth in [0, 1].
    #[arg(long, default_value_t = 0.01)]
    pub(super) offset: f64,
    /// The light pass's culling per object class: `algorithm` (solids as
    /// the algorithm culls them, open surfaces never), or
    /// `solids=X,open=Y` with X, Y one of algorithm, none, front, back.
    #[arg(long, default_value = "algorithm")]
    pub(super) cull: Culling,
    /// Turn Wang & Molnar's virtual samples off.
    #[arg(long)]
    pub(super) no_virtual_samples: bool,
    /// Image width (default: the scene's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub(super) width: Option<u32>,
    /// Image height (default: the scene's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub(super) height: Option<u32>,
    /// Reference rays per pixel side for the area-averaged visibility.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub(super) reference_samples: u32,
    /// Output folder.
    #[arg(long, default_value = "out/render")]
    pub(super) out: PathBuf,
}

impl Default for RenderArgs {
    fn default() -> Self {
        Self {
            scene: "table".into(),
            algo: Algo::Second,
            depth: Format::D24,
            map: 1024,
            filter: FilterArg::Bilinear,
            bias: 0.0,
            bias1: 0.005,
            offset: 0.01,
            num_samples: 16,
            res_factor: 3.0,
            min_samples: 1,
            min_size: 0.0,
            no_virtual_samples: false,
            cull: Culling::ALGORITHM,
            width: None,
            height: None,
            reference_samples: 4,
            out: PathBuf::from("out/render"),
        }
    }
}

/// The scene and render configuration the arguments ask for.
pub(super) fn render_config(args: &RenderArgs, limits: &Limits) -> Result<(Scene, RenderConfig, &'static str)> {
    let scene = Scene::open(&args.scene, limits)?;
    let [width, height] = scene.image;
    let (width, height) = (args.width.unwrap_or(width), args.height.unwrap_or(height));
    for (name, v) in [("--bias", args.bias), ("--bias1", args.bias1), ("--offset", args.offset)] {
        if !v.is_finite() || !(0.0..=1.0).contains(&v) {
            bail!("{name} {v} is not a depth in [0, 1]");
        }
    }
    if args.reference_samples == 0 || args.reference_samples > 16 {
        bail!("--reference-samples {} is outside 1..=16", args.reference_samples);
    }
    let preset = |k: usize| umbra_sim::experiment::presets::FILTERS[k];
    let (filter_name, filter) = match args.filter {
        FilterArg::Point => preset(0),
        FilterArg::Bilinear => preset(1),
        FilterArg::Box3 => preset(2),
        FilterArg::Jitter4 => preset(3),
        FilterArg::Jitter16 => preset(4),
        FilterArg::Jitter => ("jitter", Filter::Jittered(jitter(args)?)),
    };
    let algorithm = match args.algo {
        Algo::First => Algorithm::First,
        Algo::BiasRange => Algorithm::BiasRange { hi: args.bias1 },
        Algo::Second => Algorithm::Second,
        Algo::SecondFfc => Algorithm::SecondFrontCulled,
        Algo::Midpoint => Algorithm::Midpoint,
        Algo::Dual => Algorithm::Dual { offset: args.offset },
        Algo::Silhouette => Algorithm::Silhouette { packed: false },
        Algo::SilhouettePacked => Algorithm::Silhouette { packed: true },
        Algo::Volumes => Algorithm::Volumes,
    };
    let cfg = RenderConfig {
        algorithm,
        format: format_kind(args.depth),
        map_size: args.map,
        filter,
        bias: args.bias,
        virtual_samples: !args.no_virtual_samples,
        width,
        height,
        reference_samples: args.reference_samples,
        culling: args.cull,
    };
    Ok((scene, cfg, filter_name))
}

/// Reeves' jittered filter from the command line's values (checked again,
/// with the rest of the shadow configuration, when the render starts).
fn jitter(args: &RenderArgs) -> Result<Jitter> {
    let coord = |name: &str, v: f64| {
        MapCoord::checked_from_num(v)
            .filter(|_| v.is_finite() && v >= 0.0)
            .with_context(|| format!("{name} {v} is not a non-negative number of texels below 32768"))
    };
    if args.num_samples == 0 || args.min_samples == 0 {
        bail!("--num-samples and --min-samples must be at least 1");
    }
    Ok(Jitter {
        num_samples: args.num_samples,
        res_factor: coord("--res-factor", args.res_factor)?,
        min_samples: args.min_samples,
        min_size: coord("--min-size", args.min_size)?,
    })
}

/// `umbra render`: the pictures, the metrics and the events of one render.
pub(super) fn render(args: &RenderArgs, limits: &Limits) -> Result<()> {
    let (scene, cfg, filter_name) = render_config(args, limits)?;
    let mut folder = OutputFolder::create(&args.out)?;
    let progress = ProgressBar::new(u64::from(cfg.height)).with_message("reference rays");
    let r = umbra_sim::pass::render::render(&scene, &cfg, limits, TruthSource::Build(&progress))?;
    progress.finish_and_clear();
    let (w, h) = (r.maps.maps.config.raster.width(), r.maps.maps.config.raster.height());
    let f = &mut folder;
    write_shadow_image(f, "shaded.png", &r.image, scene.light().direction())?;
    write_shadow_term(f, "shadow.png", &r.image)?;
    write_error_image(f, "error.png", &r.image, &r.truth, scene.light().direction())?;
    for (name, data) in [("z1", &r.maps.maps.z1), ("z2", &r.maps.maps.z2)] {
        if !data.is_empty() {
            write_preview(
                f,
                &format!("{name}.png"),
                &RawMap { format: r.maps.format, width: w, height: h, raw: data },
            )?;
        }
    }
    // The metrics, with what made them.
    let mut record = serde_json::to_value(r.metrics)?;
    if let Some(fields) = record.as_object_mut() {
        for (k, v) in [
            ("umbra_version", umbra_sim::io::provenance::version()),
            ("command", umbra_sim::io::provenance::command_line()),
            ("scene", scene.source.clone()),
            ("configuration", cfg.describe()),
            ("render_again", cfg.command(&scene.source)),
        ] {
            fields.insert(k.to_owned(), serde_json::Value::String(v));
        }
    }
    folder.write_text("metrics.json", &serde_json::to_string_pretty(&record)?)?;
    let manifest = folder.finish(None)?;
    let m = &r.metrics;
    let t = &r.camera_events.totals;
    say!(
        "render `{}`: {}, {} map {}², {filter_name} filter, bias {}, culling {}, {}×{}",
        scene.name,
        cfg.algorithm.flags().trim_start_matches("--algo "),
        cfg.format.name(),
        cfg.map_size,
        cfg.bias,
        cfg.culling.label(),
        cfg.width,
        cfg.height
    );
    if !scene.ignored().is_empty() {
        say!("the scene's OBJ files: {}", scene.ignored());
    }
    say!("| pixels evaluated | false shadow | false light | misclassified | mean abs error |");
    say!("|---:|---:|---:|---:|---:|");
    say!(
        "| {} | {:.3} % | {:.3} % | {:.3} % | {:.4} |",
        m.evaluated,
        100.0 * m.false_shadow_rate,
        100.0 * m.false_light_rate,
        m.misclassified_percent,
        m.mean_abs_error
    );
    say!(
        "misclassified: {} edge placement, {} acne, {} leaks ({:.3} % artifacts); {} ties at ½; RMS area error {:.4}; boundary displacement {:.2} / {:.2} / {:.2} pixels, {:.2} / {:.2} / {:.2} texels (mean / 95th percentile / max)",
        m.edge_placement,
        m.acne,
        m.leaks,
        m.artifact_percent,
        m.ties,
        m.rms_error,
        m.displacement[0],
        m.displacement[1],
        m.displacement[2],
        m.displacement_texels[0],
        m.displacement_texels[1],
        m.displacement_texels[2]
    );
    say!(
        "map footprint: {:.3} texels per pixel (the map is {} on screen)",
        m.texels_per_pixel,
        if m.texels_per_pixel < 1.0 { "magnified" } else { "minified" }
    );
    say!(
        "virtual samples for {} pixels, {} trivially decided, {} tangent fallbacks, {} lookups culled, {} map bytes read",
        t.tangent_setups,
        t.trivial_pixels(),
        t.tangent_fallbacks,
        t.lookups_culled,
        t.map_read_bytes
    );
    crate::say::wrote(&args.out, &manifest)
}
