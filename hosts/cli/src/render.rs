//! `umbra render`: one shadow algorithm against the exact reference, with its pictures and metrics.

use std::path::PathBuf;

use crate::say::say;
use anyhow::Result;
use indicatif::ProgressBar;
use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::OutputFolder;
use umbra_sim::output::formats::{RawMap, write_array, write_npy, write_preview};
use umbra_sim::render::arrays::PixelArrays;
use umbra_sim::render::pictures::{write_error_image, write_shadow_image, write_shadow_term};
use umbra_sim::render::{Algorithm, Culling, RenderConfig, TruthSource};
use umbra_sim::truth::metrics::SHADE_STEP;
use umbra_sim::world::scene::Scene;

#[derive(clap::Args, Debug)]
pub(super) struct RenderArgs {
    /// A bundled scene by name (table-and-sphere, wang-molnar-4,
    /// reeves-sphere, weiskopf-l, weiskopf-l-boxes, double-torus, thin,
    /// open-sheet, crowd, crowd-zoom, crowd-overhead, crowd-grazing, grazing,
    /// factory, quad) or a scene file.
    #[arg(default_value = "table-and-sphere")]
    pub(super) scene: String,
    /// Shadow algorithm: first (Williams, use --bias), bias-range (Reeves:
    /// per sample from [--bias, --bias1]), second (Wang & Molnar, dual
    /// unit), second-ffc (second depth by front-face culling), midpoint
    /// (Woo), dual (Weiskopf & Ertl, use --offset), silhouette and
    /// silhouette-packed (Sen et al.), volumes (depth-fail stencil).
    #[arg(long, default_value = "second", value_parser = clap::builder::PossibleValuesParser::new(Algorithm::NAMES))]
    pub(super) algo: String,
    /// Depth format of the map: d16, d24, f32.
    #[arg(long, default_value = "d24", alias = "format")]
    pub(super) depth: DepthFormatKind,
    /// Map side in texels.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..), alias = "size")]
    pub(super) map: u32,
    /// Percentage-closer filter: point, bilinear, box<N> (N from 1 to 16),
    /// or Reeves' jitter<NumSamples> with optional
    /// ,res-factor=<texels>,min-samples=<n>,min-size=<texels>
    /// (jitter16 is Reeves' Figure 4).
    #[arg(long, default_value = "bilinear")]
    pub(super) filter: Filter,
    /// Depth bias, as a depth in [0, 1] (`Bias0` of a bias range).
    #[arg(long, default_value_t = 0.0)]
    pub(super) bias: f64,
    /// `Bias1` of Reeves' bias range (--algo bias-range), as a depth in [0, 1].
    #[arg(long, default_value_t = Algorithm::DEFAULT_BIAS1)]
    pub(super) bias1: f64,
    /// The dual-depth offset, as a depth in [0, 1].
    #[arg(long, default_value_t = Algorithm::DEFAULT_OFFSET)]
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
    #[arg(
        long,
        default_value_t = RenderConfig::DEFAULT.reference_rays,
        value_parser = clap::value_parser!(u32).range(RenderConfig::reference_rays_flag()),
        alias = "reference-samples"
    )]
    pub(super) reference_rays: u32,
    /// Output folder (default: the command's own, out/render, out/cost or
    /// out/trace, so that one command's run never replaces another's).
    #[arg(long)]
    pub(super) out: Option<PathBuf>,
}

impl Default for RenderArgs {
    fn default() -> Self {
        Self {
            scene: "table-and-sphere".into(),
            algo: "second".into(),
            depth: DepthFormatKind::D24,
            map: 1024,
            filter: Filter::Bilinear,
            bias: 0.0,
            bias1: Algorithm::DEFAULT_BIAS1,
            offset: Algorithm::DEFAULT_OFFSET,
            no_virtual_samples: false,
            cull: Culling::ALGORITHM,
            width: None,
            height: None,
            reference_rays: 4,
            out: None,
        }
    }
}

/// The scene and render configuration the arguments ask for, checked.
pub(super) fn render_config(args: &RenderArgs, limits: &Limits) -> Result<(Scene, RenderConfig)> {
    let scene = Scene::open(&args.scene, limits)?;
    let [width, height] = scene.image;
    let cfg = RenderConfig {
        algorithm: Algorithm::named(&args.algo, args.bias1, args.offset)?,
        format: args.depth,
        map_size: args.map,
        filter: args.filter,
        bias: args.bias,
        virtual_samples: !args.no_virtual_samples,
        width: args.width.unwrap_or(width),
        height: args.height.unwrap_or(height),
        reference_rays: args.reference_rays,
        culling: args.cull,
    };
    // The flags name what the render checks: --bias, --bias1, --offset.
    let cfg = cfg.checked().map_err(|e| anyhow::anyhow!("--{e}"))?;
    // The limits, memory included, before any folder is made.
    cfg.within(&scene, limits)?;
    Ok((scene, cfg))
}

/// `umbra render`: the pictures, the metrics and the events of one render.
pub(super) fn render(args: &RenderArgs, limits: &Limits) -> Result<()> {
    let (scene, cfg) = render_config(args, limits)?;
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out/render"));
    let mut folder = OutputFolder::create(&out)?;
    let progress = ProgressBar::new(u64::from(cfg.height)).with_message("reference rays");
    let r = umbra_sim::render::render(&scene, &cfg, limits, TruthSource::Build(&progress))?;
    progress.finish_and_clear();
    let (w, h) = (r.maps.maps.config.raster.width(), r.maps.maps.config.raster.height());
    let f = &mut folder;
    write_shadow_image(f, "shaded.png", &r.image, &r.truth)?;
    write_shadow_term(f, "shadow.png", &r.image)?;
    write_error_image(f, "error.png", &r.image, &r.verdicts, &r.truth)?;
    for (name, data) in r.maps.stored() {
        let map = RawMap { format: r.maps.format, width: w, height: h, raw: data };
        write_npy(f, &format!("{name}.npy"), &map)?;
        write_preview(f, &format!("{name}.png"), &map)?;
    }
    // Pixel by pixel, for scripts: the shadow term, the reference and the verdicts.
    let arrays = PixelArrays::of(&r);
    let size = (arrays.width, arrays.height);
    write_array(f, "shadow.npy", size, &arrays.shadow)?;
    write_array(f, "reference.npy", size, &arrays.reference)?;
    write_array(f, "verdict.npy", size, &arrays.verdict)?;
    // The metrics, with what made them.
    let mut record = serde_json::to_value(r.metrics)?;
    if let Some(fields) = record.as_object_mut() {
        for (k, v) in [
            ("umbra_version", umbra_sim::output::provenance::version()),
            ("command", umbra_sim::output::provenance::command_line()),
            ("scene", scene.source.clone()),
            ("configuration_text", cfg.describe()),
            ("render_again", r.command.clone()),
        ] {
            fields.insert(k.to_owned(), serde_json::Value::String(v));
        }
        fields.insert("configuration".to_owned(), serde_json::to_value(cfg)?);
    }
    folder.write_text("metrics.json", &serde_json::to_string_pretty(&record)?)?;
    let manifest = folder.finish(None)?;
    let m = &r.metrics;
    let t = &r.camera_events.totals;
    say!("render `{}`: {}", scene.name, cfg.describe());
    if !scene.ignored().is_empty() {
        say!("the scene's OBJ files: {}", scene.ignored());
    }
    say!("| pixels evaluated | false shadow | false light | misclassified | mean abs error |");
    say!("|---:|---:|---:|---:|---:|");
    say!(
        "| {} | {:.3} % | {:.3} % | {:.3} % | {:.4} |",
        m.evaluated,
        m.false_shadow_percent,
        m.false_light_percent,
        m.misclassified_percent,
        m.mean_abs_error
    );
    say!(
        "artifacts (wrong by their cause, shade off the reference by more than {} or on the wrong side of ½): {} acne ({} on terminators; {:.1} px of excess shadow), {} detachment ({:.1} px of missing shadow), {} leaks ({:.1} px of missing shadow): {:.3} % artifacts",
        SHADE_STEP,
        m.acne,
        m.terminator_acne,
        m.acne_area,
        m.detachment,
        m.detachment_area,
        m.leaks,
        m.leak_area,
        m.artifact_percent,
    );
    say!(
        "not artifacts: {} aliasing ({:.1} px), {} penumbra ({:.1} px; within {} / {} px of the exact edge, median / 95th percentile); {} ties at ½; RMS area error {:.4}; boundary displacement {:.2} / {:.2} / {:.2} pixels, {:.2} / {:.2} / {:.2} texels (mean / 95th percentile / max)",
        m.aliasing,
        m.aliasing_area,
        m.penumbra,
        m.penumbra_area,
        m.penumbra_width[0],
        m.penumbra_width[1],
        m.ties,
        m.rms_error,
        m.displacement[0],
        m.displacement[1],
        m.displacement[2],
        m.displacement_texels[0],
        m.displacement_texels[1],
        m.displacement_texels[2]
    );
    let way = |f: [f64; 2]| if f[0] < 1.0 { "magnified" } else { "minified" };
    say!(
        "map footprint, texels per pixel (median / 95th percentile): {:.3} / {:.3} along x ({}), {:.3} / {:.3} along y ({})",
        m.footprint_x[0],
        m.footprint_x[1],
        way(m.footprint_x),
        m.footprint_y[0],
        m.footprint_y[1],
        way(m.footprint_y)
    );
    say!(
        "virtual samples for {} pixels, {} trivially decided, {} tangent fallbacks, {} lookups culled, {} map bytes read",
        t.tangent_setups,
        t.trivial_pixels(),
        t.tangent_fallbacks,
        t.lookups_culled,
        t.map_read_bytes
    );
    crate::say::wrote(&out, &manifest)
}
