//! The `umbra` command.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use indicatif::ProgressBar;
use umbra_core::{CullMode, DepthFormatKind, DepthUnit, LightPassConfig, RasterConfig};
use umbra_sim::arch::ArchParams;
use umbra_sim::counters::Counters;
use umbra_sim::glam::{Mat4, Vec3};
use umbra_sim::light::{RawMaps, render_raw};
use umbra_sim::limits::Limits;
use umbra_sim::mesh::Mesh;
use umbra_sim::output::{
    RawMap, write_error_image, write_npy, write_preview, write_shadow_image, write_shadow_term, write_text,
};
use umbra_sim::render::{Algorithm, RenderConfig};
use umbra_sim::scene::{Light, Object, Perspective, Scene, parse_matrix};

/// Umbra: a bit-exact model of fixed-function shadow-mapping hardware.
///
/// With no subcommand, renders the light-view maps of the bundled default
/// scene into `out/depth/` and prints per-tile statistics.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    limits: LimitArgs,
}

/// What the simulator accepts, each checked before anything of that size is
/// allocated (`umbra_sim::limits`). Options, not scene-file keys: a file
/// cannot raise the limits it is read under.
#[derive(clap::Args, Debug, Clone, Copy)]
#[command(next_help_heading = "Limits")]
struct LimitArgs {
    /// Largest light-map side, texels (a dual 24-bit map of side s takes 8·s² bytes).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_map_side)]
    max_map_side: u32,
    /// Largest camera image side, pixels.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_image_side)]
    max_image_side: u32,
    /// Most camera image pixels (a render keeps about 100 bytes a pixel).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_image_pixels)]
    max_image_pixels: u64,
    /// Most triangles of a scene, every object together (the reference keeps about 200 bytes a triangle).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_triangles)]
    max_triangles: u64,
    /// Largest file read (a scene, an OBJ mesh, a `--matrix` file, study results to merge), bytes.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_file_bytes)]
    max_file_bytes: u64,
}

impl LimitArgs {
    const fn limits(self) -> Limits {
        Limits {
            max_map_side: self.max_map_side,
            max_image_side: self.max_image_side,
            max_image_pixels: self.max_image_pixels,
            max_triangles: self.max_triangles,
            max_file_bytes: self.max_file_bytes,
        }
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render the light-view depth maps (z1, z2) of a mesh or scene.
    Depth(DepthArgs),
    /// Render a scene with a shadow algorithm, compare it with the exact
    /// reference, and write the pictures and the metrics.
    Render(RenderArgs),
    /// The cost of a render on the architecture presets: cycles per stage,
    /// DRAM bytes, culling rates, Sen's bandwidth model (table and JSON).
    Cost(CostArgs),
    /// A per-tile timeline of the light pass in Chrome trace-event JSON
    /// (open it in Perfetto).
    Trace(CostArgs),
    /// The speed/accuracy trade study: scene × algorithm × depth format ×
    /// map size × filter × architecture; results.jsonl/.csv, Pareto plots
    /// and summary.md.
    Study(StudyArgs),
    /// Merge the results.jsonl of `study --shard` runs into the whole run's
    /// files.
    Merge(MergeArgs),
    /// The least costly configuration a scene needs for an error budget:
    /// buffers, depth precision, map size and filter, with the reasons, the
    /// predicted and measured error and cost, and the map's storage.
    Plan(PlanArgs),
}

#[derive(clap::Args, Debug)]
struct PlanArgs {
    /// A bundled scene by name or a scene file.
    #[arg(default_value = "table")]
    scene: String,
    /// Misclassified pixels allowed, e.g. `0.1%` (percent of the pixels
    /// facing the light).
    #[arg(long, default_value = "0.1%")]
    error_budget: String,
    /// Architecture preset whose cost is minimised.
    #[arg(long, value_enum, default_value_t = ArchArg::Talisman)]
    arch: ArchArg,
    /// Output folder for plan.md and plan.json.
    #[arg(long, default_value = "out/plan")]
    out: PathBuf,
}

#[derive(clap::Args, Debug)]
struct StudyArgs {
    /// Bundled scene names or scene files (default: every bundled scene, or
    /// the quick set with --quick).
    scenes: Vec<String>,
    /// The small sweep: 3 scenes, fewer biases, formats, map sizes and
    /// filters, 160×90 images.
    #[arg(long)]
    quick: bool,
    /// Run only shard i of n (configurations whose index is i mod n) and
    /// write a partial results.jsonl; `umbra merge` joins the shards.
    #[arg(long)]
    shard: Option<String>,
    /// Also run the numerical extremes (near/far ratio, grazing light,
    /// guard band, slivers, coincident surfaces): extremes.md, precision plot.
    #[arg(long)]
    extremes: bool,
    /// Map sides to sweep instead of the set's own (e.g. `--maps 2048` or
    /// `--maps 256,1024`).
    #[arg(long, value_delimiter = ',')]
    maps: Vec<u32>,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    out: PathBuf,
}

#[derive(clap::Args, Debug)]
struct MergeArgs {
    /// Shard output folders or results.jsonl files.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    out: PathBuf,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ArchArg {
    Pixelflow,
    Talisman,
    Immediate,
    All,
}

#[derive(clap::Args, Debug)]
struct CostArgs {
    /// Architecture preset.
    #[arg(long, value_enum, default_value_t = ArchArg::All)]
    arch: ArchArg,
    #[command(flatten)]
    render: RenderArgs,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Algo {
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
enum FilterArg {
    Point,
    Bilinear,
    Box3,
    Jitter4,
    Jitter16,
}

#[derive(clap::Args, Debug)]
struct RenderArgs {
    /// A bundled scene by name (table, reeves-sphere, weiskopf-l,
    /// double-torus, thin, open-sheet, crowd, grazing) or a scene file.
    #[arg(default_value = "table")]
    scene: String,
    /// Shadow algorithm.
    #[arg(long, value_enum, default_value_t = Algo::Second)]
    algo: Algo,
    /// Depth format of the map.
    #[arg(long, value_enum, default_value_t = Format::D24)]
    depth: Format,
    /// Map side in texels.
    #[arg(long, default_value_t = 1024)]
    map: u32,
    /// Percentage-closer filter.
    #[arg(long, value_enum, default_value_t = FilterArg::Bilinear)]
    filter: FilterArg,
    /// Depth bias, as a depth in [0, 1] (`Bias0` of a bias range).
    #[arg(long, default_value_t = 0.0)]
    bias: f64,
    /// `Bias1` of Reeves' bias range (--algo bias-range), as a depth in [0, 1].
    #[arg(long, default_value_t = 0.005)]
    bias1: f64,
    /// The dual-depth offset, as a depth in [0, 1].
    #[arg(long, default_value_t = 0.01)]
    offset: f64,
    /// Turn Wang & Molnar's virtual samples off.
    #[arg(long)]
    no_virtual_samples: bool,
    /// Image width (default: the scene's).
    #[arg(long)]
    width: Option<u32>,
    /// Image height (default: the scene's).
    #[arg(long)]
    height: Option<u32>,
    /// Reference rays per pixel side for the area-averaged visibility.
    #[arg(long, default_value_t = 4)]
    reference_samples: u32,
    /// Output folder.
    #[arg(long, default_value = "out/render")]
    out: PathBuf,
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
            no_virtual_samples: false,
            width: None,
            height: None,
            reference_samples: 4,
            out: PathBuf::from("out/render"),
        }
    }
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Format {
    D16,
    D24,
    F32,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Cull {
    None,
    Back,
    Front,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Unit {
    Single,
    Dual,
}

#[derive(clap::Args, Debug)]
struct DepthArgs {
    /// An OBJ mesh to render (instead of the default scene).
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// The view-projection matrix: a row-major 4×4 JSON array, inline or in a
    /// file. Clip = M · (x, y, z, 1)ᵀ; depth z/w in [0, 1] (near 0, far 1);
    /// NDC y up, map row 0 at NDC y = +1. Default: the scene's light, or for
    /// a mesh a spot light that frames it.
    #[arg(long)]
    matrix: Option<String>,
    /// Map width and height in texels.
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Depth format.
    #[arg(long, value_enum, default_value_t = Format::D24)]
    format: Format,
    /// Facing to discard.
    #[arg(long, value_enum, default_value_t = Cull::None)]
    cull: Cull,
    /// Depth unit: nearest only, or nearest and second nearest.
    #[arg(long, value_enum, default_value_t = Unit::Dual)]
    unit: Unit,
    /// Tile side in texels (power of two, 8..=128).
    #[arg(long, default_value_t = RasterConfig::DEFAULT_TILE_SIZE)]
    tile: u32,
    /// Subpixel bits of the vertex snap (1..=8).
    #[arg(long, default_value_t = RasterConfig::DEFAULT_SUBPIXEL_BITS)]
    subpixel_bits: u32,
    /// Turn per-tile max-z culling off.
    #[arg(long)]
    no_max_z_cull: bool,
    /// Output folder.
    #[arg(long, default_value = "out/depth")]
    out: PathBuf,
}

impl Default for DepthArgs {
    fn default() -> Self {
        Self {
            mesh: None,
            matrix: None,
            size: 512,
            format: Format::D24,
            cull: Cull::None,
            unit: Unit::Dual,
            tile: RasterConfig::DEFAULT_TILE_SIZE,
            subpixel_bits: RasterConfig::DEFAULT_SUBPIXEL_BITS,
            no_max_z_cull: false,
            out: PathBuf::from("out/depth"),
        }
    }
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    let limits = &cli.limits.limits();
    match cli.command {
        Some(Command::Depth(args)) => depth(&args, limits),
        Some(Command::Render(args)) => render(&args, limits),
        Some(Command::Cost(args)) => cost(&args, false, limits),
        Some(Command::Trace(args)) => cost(&args, true, limits),
        Some(Command::Study(args)) => study(&args, limits),
        Some(Command::Plan(args)) => plan(&args, limits),
        Some(Command::Merge(args)) => {
            let n = umbra_sim::study::merge(&args.inputs, &args.out, limits)?;
            println!("merged {n} rows into {}", args.out.display());
            Ok(())
        }
        None => {
            depth(&DepthArgs::default(), limits)?;
            render(&RenderArgs::default(), limits)?;
            study(
                &StudyArgs {
                    scenes: Vec::new(),
                    quick: true,
                    shard: None,
                    extremes: false,
                    maps: Vec::new(),
                    out: PathBuf::from("out/study"),
                },
                limits,
            )
        }
    }
}

/// `umbra plan`.
fn plan(args: &PlanArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::plan::{PlanSpec, plan};
    let text = args.error_budget.trim().trim_end_matches('%');
    let budget: f64 =
        text.trim().parse().with_context(|| format!("--error-budget `{}` is not a percentage", args.error_budget))?;
    if !budget.is_finite() || !(0.0..=100.0).contains(&budget) {
        bail!("--error-budget {budget}% is outside 0…100%");
    }
    let scene = Scene::open(&args.scene, limits)?;
    let mut spec = PlanSpec::new(&scene, budget);
    spec.limits = *limits;
    spec.arch = match args.arch {
        ArchArg::Pixelflow => ArchParams::PIXELFLOW,
        ArchArg::Immediate => ArchParams::IMMEDIATE,
        ArchArg::Talisman | ArchArg::All => ArchParams::TALISMAN,
    };
    let p = plan(&scene, &spec)?;
    let md = p.markdown(&scene.name, budget);
    print!("{md}");
    if !p.meets(budget) {
        println!("\nThe measured error exceeds the budget: no candidate meets it at this image size.");
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    write_text(&args.out.join("plan.md"), &md)?;
    write_text(&args.out.join("plan.json"), &serde_json::to_string_pretty(&p)?)?;
    Ok(())
}

/// `umbra study`.
fn study(args: &StudyArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::study::{self, QUICK_SCENES, Shard, Spec};
    let names: Vec<String> = if !args.scenes.is_empty() {
        args.scenes.clone()
    } else if args.quick {
        QUICK_SCENES.iter().map(|s| (*s).to_owned()).collect()
    } else {
        umbra_sim::scene_file::BUNDLED.iter().map(|(n, _)| (*n).to_owned()).collect()
    };
    let scenes = study::load_scenes(&names, limits)?;
    let mut spec = if args.quick { Spec::quick(scenes) } else { Spec::full(scenes) };
    spec.limits = *limits;
    if !args.maps.is_empty() {
        for &side in &args.maps {
            limits.check_map(side).with_context(|| format!("--maps {side}"))?;
            RasterConfig::new(side, side, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
                .with_context(|| format!("--maps {side}"))?;
        }
        spec.map_sizes.clone_from(&args.maps);
    }
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?.unwrap_or(Shard::ALL);
    let style =
        indicatif::ProgressStyle::with_template("{prefix} [{elapsed_precise}] {wide_bar} {pos}/{len} ETA {eta}")
            .context("progress bar template")?;
    let progress = ProgressBar::new(0).with_style(style).with_prefix("study");
    let start = std::time::Instant::now();
    let rows = study::run(&spec, shard, &progress);
    progress.finish_and_clear();
    let configs = rows.iter().map(|r| r.index).collect::<std::collections::BTreeSet<_>>().len();
    let skipped = rows.iter().filter(|r| r.status != "ok").count();
    if shard == Shard::ALL {
        study::write_outputs(&args.out, &rows)?;
        println!("{}", study::summary(&rows));
    } else {
        study::write_partial(&args.out, &rows)?;
    }
    println!(
        "study: {configs} configurations, {} rows ({skipped} skipped) in {:.1} s; wrote {}",
        rows.len(),
        start.elapsed().as_secs_f64(),
        args.out.display()
    );
    if args.extremes {
        let report = study::extremes::run_all(&args.out, limits)?;
        println!("{report}");
        println!("wrote {}", args.out.join("extremes.md").display());
    }
    Ok(())
}

/// `umbra cost` and `umbra trace`.
fn cost(args: &CostArgs, trace: bool, limits: &Limits) -> Result<()> {
    let (scene, cfg, _) = render_config(&args.render, limits)?;
    let presets: Vec<ArchParams> = match args.arch {
        ArchArg::Pixelflow => vec![ArchParams::PIXELFLOW],
        ArchArg::Talisman => vec![ArchParams::TALISMAN],
        ArchArg::Immediate => vec![ArchParams::IMMEDIATE],
        ArchArg::All => ArchParams::PRESETS.to_vec(),
    };
    let out = &args.render.out;
    let mut reports = Vec::new();
    for arch in presets {
        let (report, light) = umbra_sim::render::cost_within(&scene, &cfg, arch, limits)?;
        if trace {
            let path = out.join(format!("trace-{}.json", arch.name));
            write_text(&path, &serde_json::to_string(&umbra_sim::arch::CostReport::trace(&light))?)?;
            println!("wrote {} ({} slices)", path.display(), light.tile_cycles.len());
        } else {
            println!("{}", report.markdown());
        }
        reports.push(report);
    }
    if !trace {
        let path = out.join("cost.json");
        write_text(&path, &serde_json::to_string_pretty(&reports)?)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The scene and render configuration the arguments ask for.
fn render_config(args: &RenderArgs, limits: &Limits) -> Result<(Scene, RenderConfig, &'static str)> {
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
    let filter = match args.filter {
        FilterArg::Point => 0,
        FilterArg::Bilinear => 1,
        FilterArg::Box3 => 2,
        FilterArg::Jitter4 => 3,
        FilterArg::Jitter16 => 4,
    };
    let (filter_name, filter) = umbra_sim::presets::FILTERS[filter];
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
    };
    Ok((scene, cfg, filter_name))
}

/// `umbra render`: the pictures, the metrics and the events of one render.
fn render(args: &RenderArgs, limits: &Limits) -> Result<()> {
    let (scene, cfg, filter_name) = render_config(args, limits)?;
    let progress = ProgressBar::new(u64::from(cfg.height)).with_message("reference rays");
    let r = umbra_sim::render::render_within(&scene, &cfg, limits, &progress)?;
    progress.finish_and_clear();
    let out = &args.out;
    let (w, h) = (r.maps.maps.config.raster.width(), r.maps.maps.config.raster.height());
    write_shadow_image(&out.join("shaded.png"), &r.image, scene.light().direction())?;
    write_shadow_term(&out.join("shadow.png"), &r.image)?;
    write_error_image(&out.join("error.png"), &r.image, &r.truth)?;
    for (name, data) in [("z1", &r.maps.maps.z1), ("z2", &r.maps.maps.z2)] {
        if !data.is_empty() {
            write_preview(
                &out.join(format!("{name}.png")),
                &RawMap { format: r.maps.format, width: w, height: h, raw: data },
            )?;
        }
    }
    write_text(&out.join("metrics.json"), &serde_json::to_string_pretty(&r.metrics)?)?;
    let m = &r.metrics;
    let t = &r.camera_events.totals;
    println!(
        "render `{}`: {:?}, {} map {}², {filter_name} filter, bias {}, {}×{}",
        scene.name,
        cfg.algorithm,
        cfg.format.name(),
        cfg.map_size,
        cfg.bias,
        cfg.width,
        cfg.height
    );
    println!("| pixels evaluated | false shadow | false light | misclassified | mean abs error |");
    println!("|---:|---:|---:|---:|---:|");
    println!(
        "| {} | {:.3} % | {:.3} % | {:.3} % | {:.4} |",
        m.evaluated,
        100.0 * m.false_shadow_rate,
        100.0 * m.false_light_rate,
        m.misclassified_percent,
        m.mean_abs_error
    );
    println!(
        "virtual samples for {} pixels, {} trivially decided, {} tangent fallbacks, {} lookups culled, {} map bytes read",
        t.tangent_setups, t.trivial_pixels, t.tangent_fallbacks, t.lookups_culled, t.map_read_bytes
    );
    for f in ["shaded.png", "shadow.png", "error.png", "z1.png", "metrics.json"] {
        println!("wrote {}", out.join(f).display());
    }
    Ok(())
}

fn format_kind(f: Format) -> DepthFormatKind {
    match f {
        Format::D16 => DepthFormatKind::D16,
        Format::D24 => DepthFormatKind::D24,
        Format::F32 => DepthFormatKind::F32,
    }
}

/// Read the `--matrix` argument: inline JSON or a file holding it (a
/// regular file within `limits`).
fn read_matrix(arg: &str, limits: &Limits) -> Result<Mat4> {
    let text = if arg.trim_start().starts_with('[') {
        arg.to_owned()
    } else {
        let bytes = limits.read_file(Path::new(arg)).with_context(|| format!("--matrix: cannot read file `{arg}`"))?;
        String::from_utf8(bytes).with_context(|| format!("--matrix: file `{arg}` is not UTF-8 text"))?
    };
    parse_matrix(&text).with_context(|| format!("--matrix `{arg}`"))
}

/// A spot light that frames a mesh, looking down from above and to the side.
fn framing_light(mesh: &Mesh) -> Result<Perspective> {
    let (lo, hi) = mesh.bounds().context("the mesh has no vertices")?;
    let center = (lo + hi) / 2.0;
    let radius = ((hi - lo).length() / 2.0).max(f32::MIN_POSITIVE);
    let distance = 3.0 * radius;
    Ok(Perspective {
        position: center + Vec3::new(1.0, 2.0, 1.5).normalize() * distance,
        target: center,
        fov_degrees: 2.0 * (radius / distance).asin().to_degrees() * 1.1,
        near: distance - 1.2 * radius,
        far: distance + 1.2 * radius,
    })
}

fn depth(args: &DepthArgs, limits: &Limits) -> Result<()> {
    limits.check_map(args.size).with_context(|| format!("--size {}", args.size))?;
    let scene = match &args.mesh {
        Some(path) => {
            let mesh = Mesh::load_obj_within(path, limits)?;
            let light = framing_light(&mesh)?;
            let name = path.file_stem().map_or_else(|| "mesh".into(), |s| s.to_string_lossy().into_owned());
            let lights = vec![Light::Spot(light)];
            Scene {
                name: name.clone(),
                objects: vec![Object { name, mesh, solid: false }],
                lights,
                camera: light,
                image: [512, 512],
            }
        }
        None => Scene::default_scene(),
    };
    let matrix = match &args.matrix {
        Some(m) => read_matrix(m, limits)?,
        None => scene.light().view_projection(),
    };
    let raster = RasterConfig::new(args.size, args.size, args.tile, args.subpixel_bits)?;
    let unit = match args.unit {
        Unit::Single => DepthUnit::Single,
        Unit::Dual => DepthUnit::Dual,
    };
    let format = format_kind(args.format);
    let cull = match args.cull {
        Cull::None => CullMode::None,
        Cull::Back => CullMode::Back,
        Cull::Front => CullMode::Front,
    };
    let config = LightPassConfig { raster, unit, max_z_cull: !args.no_max_z_cull };
    let draws = scene.draws(matrix, cull);
    let (maps, counters) = render_raw(config, format, &draws, Counters::new(&raster))?;

    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let written = write_maps(&args.out, &maps)?;
    let report = tile_report(&scene, &maps, &counters, args);
    write_text(&args.out.join("tiles.md"), &report)?;
    write_text(&args.out.join("counters.json"), &serde_json::to_string_pretty(&counters.totals)?)?;
    println!("{}", summary(&maps, &counters));
    for f in written.iter().chain([&args.out.join("tiles.md"), &args.out.join("counters.json")]) {
        println!("wrote {}", f.display());
    }
    Ok(())
}

fn write_maps(dir: &Path, maps: &RawMaps) -> Result<Vec<PathBuf>> {
    let (w, h) = (maps.maps.config.raster.width(), maps.maps.config.raster.height());
    let mut files = Vec::new();
    for (name, data) in [("z1", &maps.maps.z1), ("z2", &maps.maps.z2)] {
        if data.is_empty() {
            continue;
        }
        let npy = dir.join(format!("{name}.npy"));
        let png = dir.join(format!("{name}.png"));
        let map = RawMap { format: maps.format, width: w, height: h, raw: data };
        write_npy(&npy, &map)?;
        write_preview(&png, &map)?;
        files.extend([npy, png]);
    }
    Ok(files)
}

/// The configuration of a pass in one line.
fn describe(maps: &RawMaps) -> String {
    let cfg = maps.maps.config;
    let r = cfg.raster;
    let (across, down) = r.tiles();
    format!(
        "{}×{} texels, {} depth, {:?} unit, {}×{} tiles of {} px, {} subpixel bits, max-z culling {}",
        r.width(),
        r.height(),
        maps.format.name(),
        cfg.unit,
        across,
        down,
        r.tile_size(),
        r.subpixel_bits(),
        if cfg.max_z_cull { "on" } else { "off" }
    )
}

/// Totals and a grid of fragments per tile, for the terminal.
fn summary(maps: &RawMaps, c: &Counters) -> String {
    let t = &c.totals;
    let raster = maps.maps.config.raster;
    let across = raster.tiles().0;
    let mut s = String::new();
    let _ = writeln!(s, "light pass {}", describe(maps));
    let _ = writeln!(
        s,
        "triangles {} submitted, {} set up, {} rejected (facing {}, clipped {}, degenerate {}, no coverage {}, non-finite {})",
        t.submitted,
        t.setups,
        t.rejected_facing + t.rejected_clipped + t.rejected_degenerate + t.rejected_no_coverage + t.rejected_non_finite,
        t.rejected_facing,
        t.rejected_clipped,
        t.rejected_degenerate,
        t.rejected_no_coverage,
        t.rejected_non_finite
    );
    let _ = writeln!(
        s,
        "fragments {}, max-z culled {} triangles + {} blocks ({} texels), bin flushes {} full / {} setup / {} end",
        t.fragments,
        t.culled_triangles,
        t.culled_blocks,
        t.culled_texels,
        t.flushes_bin_full,
        t.flushes_setup_full,
        t.flushes_finish
    );
    let touched = c.tiles.iter().filter(|k| k.fragments > 0).count();
    let _ = writeln!(s, "tiles with fragments {touched} of {}; fragments per tile (hundreds):", c.tiles.len());
    for row in c.tiles.chunks(across as usize) {
        let line: Vec<String> = row.iter().map(|k| format!("{:>4}", k.fragments.div_ceil(100))).collect();
        let _ = writeln!(s, "{}", line.join(""));
    }
    s
}

/// One Markdown row per tile: fragments, culls, flushes and depth bounds.
fn tile_report(scene: &Scene, maps: &RawMaps, c: &Counters, args: &DepthArgs) -> String {
    let raster = maps.maps.config.raster;
    let mut s = String::new();
    let _ = writeln!(s, "# Light-pass tiles: {}\n", scene.name);
    let _ = writeln!(s, "{}, cull {:?}.\n", describe(maps), args.cull);
    let _ = writeln!(s, "| tile | triangles | fragments | culled | flushes | z1 min | z1 max | z2 min | z2 max |");
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (i, (k, st)) in c.tiles.iter().zip(&maps.maps.tiles).enumerate() {
        let id = raster.tile_id(i);
        let _ = writeln!(
            s,
            "| ({}, {}) | {} | {} | {} | {} | {} | {} | {} | {} |",
            id.x, id.y, k.triangles, k.fragments, k.culled, k.flushes, st.z1_min, st.z1_max, st.z2_min, st.z2_max
        );
    }
    s
}
