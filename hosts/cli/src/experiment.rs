//! `umbra plan`, `umbra study` and `umbra merge`: the planner and the trade study.

use std::path::PathBuf;

use crate::cost::{ArchArgs, OneArchArgs};
use crate::say::say;
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use umbra_core::RasterConfig;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::OutputFolder;
use umbra_sim::render::RenderConfig;
use umbra_sim::world::scene::Scene;

#[derive(clap::Args, Debug)]
pub(super) struct PlanArgs {
    /// A bundled scene by name or a scene file.
    #[arg(default_value = "table-and-sphere")]
    pub(super) scene: String,
    /// Artifacts allowed (acne, detachment and leaks, judged by their
    /// cause), e.g. `0.1%` (percent of the pixels facing the light).
    #[arg(long, default_value = "0.1%")]
    pub(super) error_budget: String,
    /// The architecture whose cost is minimised (default: talisman).
    #[command(flatten)]
    pub(super) archs: OneArchArgs,
    /// Output folder for plan.md and plan.json.
    #[arg(long, default_value = "out/plan")]
    pub(super) out: PathBuf,
}

#[derive(clap::Args, Debug)]
pub(super) struct StudyArgs {
    /// Bundled scene names or scene files, in place of the sweep's.
    pub(super) scenes: Vec<String>,
    /// The sweep: a bundled one (`quick`, `full`) or a sweep file (TOML,
    /// see sweeps/). The flags below override single axes.
    #[arg(long, default_value = "full")]
    pub(super) sweep: String,
    /// The bundled quick sweep (`--sweep quick`): 3 scenes, a few
    /// parameters of each algorithm, 640×360.
    #[arg(long, conflicts_with = "sweep")]
    pub(super) quick: bool,
    /// Image sizes, in place of the sweep's (`--image 640x360`; repeat for
    /// several: an axis).
    #[arg(long = "image")]
    pub(super) images: Vec<String>,
    /// Reference rays per pixel side, in place of the sweep's.
    #[arg(long, value_parser = clap::value_parser!(u32).range(RenderConfig::reference_rays_flag()))]
    pub(super) reference_rays: Option<u32>,
    /// Error budgets, percent artifacts, in place of the sweep's
    /// (`--budgets 1,0.1`).
    #[arg(long, value_delimiter = ',')]
    pub(super) budgets: Vec<f64>,
    /// Run only shard i of n (every n-th block of configurations that share
    /// a scene, image, format and map side, so each block's passes are
    /// drawn once) and write a partial results.jsonl; `umbra merge` joins
    /// the shards.
    #[arg(long)]
    pub(super) shard: Option<String>,
    /// Also run the numerical extremes (near/far ratio, grazing light,
    /// guard band, slivers, coincident surfaces): extremes.md, precision plot.
    #[arg(long)]
    pub(super) extremes: bool,
    /// Map sides to sweep instead of the set's own (e.g. `--maps 2048` or
    /// `--maps 256,1024`).
    #[arg(long, value_delimiter = ',')]
    pub(super) maps: Vec<u32>,
    /// The architectures each configuration is costed on, in place of the
    /// sweep's (`--set` applies to the sweep's when `--arch` is not given).
    #[command(flatten)]
    pub(super) archs: ArchArgs,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    pub(super) out: PathBuf,
}

#[derive(clap::Args, Debug)]
pub(super) struct StatusArgs {
    /// Shard output folders (`shards/*/`).
    #[arg(required = true)]
    pub(super) inputs: Vec<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub(super) struct MergeArgs {
    /// Shard output folders or results.jsonl files.
    #[arg(required = true)]
    pub(super) inputs: Vec<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    pub(super) out: PathBuf,
}

/// `umbra plan`.
pub(super) fn plan(args: &PlanArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::experiment::plan::{PlanSpec, plan};
    let text = args.error_budget.trim();
    let text = text.strip_suffix('%').unwrap_or(text);
    let budget: f64 =
        text.trim().parse().with_context(|| format!("--error-budget `{}` is not a percentage", args.error_budget))?;
    if !budget.is_finite() || !(0.0..=100.0).contains(&budget) {
        bail!("--error-budget {budget}% is outside 0…100%");
    }
    let scene = Scene::open(&args.scene, limits)?;
    let mut spec = PlanSpec::new(&scene, budget);
    spec.limits = *limits;
    spec.arch = args.archs.one("talisman", limits)?;
    let mut folder = OutputFolder::create(&args.out)?;
    let p = plan(&scene, &spec)?;
    let md = p.markdown(&scene, budget);
    say!("{}", md.trim_end());
    if !p.meets(budget) {
        say!("\nNo candidate meets the budget at this image size: all {} were measured.", p.candidates);
    }
    folder.write_text("plan.md", &md)?;
    folder.write_text("plan.json", &serde_json::to_string_pretty(&p)?)?;
    folder.write_text(&format!("arch-{}.toml", spec.arch.name), &spec.arch.to_toml())?;
    let manifest = folder.finish(None)?;
    crate::say::wrote(&args.out, &manifest)
}

/// `umbra study`.
pub(super) fn study(args: &StudyArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::experiment::study::{self, Manifest, Shard, SweepFile};
    crate::no_repeats("scene", args.scenes.iter().map(String::as_str))?;
    crate::no_repeats("--image", args.images.iter().map(String::as_str))?;
    let maps: Vec<String> = args.maps.iter().map(u32::to_string).collect();
    crate::no_repeats("--maps", maps.iter().map(String::as_str))?;
    let file = SweepFile::open(if args.quick { "quick" } else { &args.sweep }, limits)?;
    let mut spec = file.spec(limits)?;
    if !args.scenes.is_empty() {
        spec.scenes = study::load_scenes(&args.scenes, limits)?;
    }
    if !args.archs.arch.is_empty() {
        spec.archs = args.archs.resolve(&[], limits)?;
        spec.arch_points.clear();
    } else {
        for arch in &mut spec.archs {
            for s in &args.archs.set {
                arch.set(s)?;
            }
        }
    }
    if !args.images.is_empty() {
        spec.images = args.images.iter().map(|i| image_size(i, limits)).collect::<Result<_>>()?;
    }
    // Within its bound already: the flag's parser reads it.
    if let Some(n) = args.reference_rays {
        spec.reference_rays = n;
    }
    if !args.budgets.is_empty() {
        if let Some((_, problem)) = study::budgets_problem(&args.budgets) {
            bail!("--budgets: {problem}");
        }
        spec.budgets.clone_from(&args.budgets);
    }
    // Flags change the sweep: its hash covers them, so shards run with
    // different flags do not merge. Without flags it is the file's own.
    let flagged = !(args.scenes.is_empty()
        && args.archs.arch.is_empty()
        && args.archs.set.is_empty()
        && args.images.is_empty()
        && args.reference_rays.is_none()
        && args.budgets.is_empty()
        && args.maps.is_empty());
    if flagged {
        let overrides = format!(
            "{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
            args.scenes, args.archs.arch, args.archs.set, args.images, args.reference_rays, args.budgets, args.maps
        );
        spec.hash = umbra_sim::output::provenance::hash(format!("{}{overrides}", file.text).as_bytes());
    }
    spec.limits = *limits;
    if !args.maps.is_empty() {
        for &side in &args.maps {
            limits.check_map(side).with_context(|| format!("--maps {side}"))?;
            RasterConfig::new(side, side, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
                .with_context(|| format!("--maps {side}"))?;
        }
        spec.map_sizes.clone_from(&args.maps);
    }
    if let Some(problem) = spec.size_problem() {
        bail!("the sweep with these flags: {problem}");
    }
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?.unwrap_or(Shard::ALL);
    // The memory bound, before any folder is made.
    spec.renders_at_once(rayon::current_num_threads())?;
    // A shard already complete and verified, of this sweep and version,
    // would be written again byte for byte: a rerun task skips it.
    let expected = Manifest::new(&spec, shard, 0);
    if shard != Shard::ALL && study::already_complete(&args.out, &expected, limits) {
        say!(
            "study: shard {} in {} is already complete and verified: not recomputed",
            expected.shard,
            args.out.display()
        );
        return Ok(());
    }
    let mut folder = OutputFolder::create(&args.out)?;
    let style = indicatif::ProgressStyle::with_template(
        "{prefix} [{elapsed_precise}] {wide_bar} {pos}/{len} configurations, {per_sec}, {eta} left",
    )
    .context("progress bar template")?;
    let progress = ProgressBar::new(0).with_style(style).with_prefix("study");
    let start = std::time::Instant::now();
    let rows = study::run(&spec, shard, &progress)?;
    progress.finish_and_clear();
    let configs = rows.iter().map(|r| r.config_index).collect::<std::collections::BTreeSet<_>>().len();
    let skipped = rows.iter().filter(|r| r.metrics.is_none()).count();
    let manifest = Manifest::new(&spec, shard, rows.len());
    if shard == Shard::ALL {
        study::write_outputs(&mut folder, &rows, &manifest)?;
    } else {
        study::write_partial(&mut folder, &rows)?;
    }
    folder.write_text("sweep.toml", &file.text)?;
    // The effective architectures, beside the rows that name them.
    for arch in &spec.archs {
        folder.write_text(&format!("arch-{}.toml", arch.name), &arch.to_toml())?;
    }
    let extremes = if args.extremes { Some(study::extremes::run_all(&mut folder, limits)?) } else { None };
    study::finish(folder, &manifest)?;
    if shard == Shard::ALL {
        say!("{}", study::summary(&rows, &manifest));
    }
    if let Some(report) = extremes {
        say!("{report}");
    }
    say!(
        "study: {configs} configurations, {} rows ({skipped} skipped); wrote {} (its files in {})",
        rows.len(),
        args.out.display(),
        args.out.join(umbra_sim::output::folder::MANIFEST).display()
    );
    // The wall time varies with the machine: not part of the results.
    eprintln!("study took {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// A `--image` size, `WIDTHxHEIGHT`, within the limits.
fn image_size(text: &str, limits: &Limits) -> Result<[u32; 2]> {
    let (w, h) = text
        .split_once(['x', '×'])
        .and_then(|(w, h)| Some((w.trim().parse::<u32>().ok()?, h.trim().parse::<u32>().ok()?)))
        .with_context(|| format!("--image `{text}`: expected WIDTHxHEIGHT, e.g. 640x360"))?;
    limits.check_image(w, h).with_context(|| format!("--image {text}"))?;
    RasterConfig::new(w, h, RasterConfig::DEFAULT_TILE_SIZE, RasterConfig::DEFAULT_SUBPIXEL_BITS)
        .with_context(|| format!("--image {text}"))?;
    Ok([w, h])
}
