//! `umbra plan`, `umbra study` and `umbra merge`: the planner and the trade study.

use std::path::PathBuf;

use crate::cost::{ArchArgs, OneArchArgs};
use crate::say::{Style, say};
use anyhow::{Context, Result};
use indicatif::ProgressBar;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::{Claim, OutputFolder, RunKind};
use umbra_sim::render::RenderConfig;
use umbra_sim::world::scene::Scene;

#[derive(clap::Args, Debug)]
pub(super) struct PlanArgs {
    /// A bundled scene by name or a scene file.
    #[arg(default_value = "table-and-sphere")]
    pub(super) scene: String,
    /// An error budget the pick must meet, `MEASURE=PERCENT` (repeat it
    /// for several, all met at once): a measure of `artifacts`,
    /// `misclassified`, `acne`, `detachment`, `leaks`, `clipped`,
    /// `aliasing`, `penumbra`, `false-shadow`, `false-light`, percent of
    /// the pixels facing the light (`--budget acne=0.01% --budget
    /// misclassified=0.1%`); a bare percentage bounds artifacts. Default:
    /// `artifacts=0.1%` and `misclassified=2%`, so a render with few
    /// artifacts but most pixels wrong is never the pick.
    #[arg(long = "budget", value_parser = budget)]
    pub(super) budgets: Vec<umbra_sim::experiment::plan::Budget>,
    /// The same as `--budget artifacts=PERCENT`.
    #[arg(long, value_parser = budget, conflicts_with = "budgets")]
    pub(super) error_budget: Option<umbra_sim::experiment::plan::Budget>,
    /// Take the candidates' algorithms, depth formats, map sides and
    /// filters from a sweep (`quick`, `full`, or a sweep file) instead of
    /// the quick sweep's algorithms and formats over map sides 128…2048
    /// and the point, bilinear and 3×3 box filters.
    #[arg(long)]
    pub(super) sweep: Option<String>,
    /// Map sides to try instead (`--maps 256,512`).
    #[arg(long, value_delimiter = ',')]
    pub(super) maps: Vec<u32>,
    /// The image the candidates are measured at (`--image 640x360`);
    /// default: the scene's.
    #[arg(long)]
    pub(super) image: Option<String>,
    /// What the pick minimises: `cycles` (the default), `energy` (dynamic
    /// and static), `area` (silicon of the units it uses), `edp` (energy
    /// × time), `edap` (energy × time × area), or a weighted sum such as
    /// `cycles=1,energy=1,area=0.5` (each measure over its least among the
    /// candidates).
    #[arg(long, value_parser = objective, default_value = "cycles")]
    pub(super) objective: umbra_sim::experiment::plan::Objective,
    /// The most silicon the pick's units may take (`2mm2`, `500um2`).
    #[arg(long)]
    pub(super) max_area: Option<String>,
    /// The most energy a frame of the pick may take (`150uJ`, `1mJ`).
    #[arg(long)]
    pub(super) max_energy: Option<String>,
    /// The architecture the candidates are costed on (default: talisman).
    #[command(flatten)]
    pub(super) archs: OneArchArgs,
    /// Output folder for plan.md and plan.json.
    #[arg(long, default_value = "out/plan")]
    pub(super) out: PathBuf,
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    pub(super) replace: bool,
}

/// An `--objective` value, read as the library (and Python) reads it.
fn objective(text: &str) -> Result<umbra_sim::experiment::plan::Objective, String> {
    text.parse()
}

/// A `--budget` value, read as the library (and Python) reads it.
fn budget(text: &str) -> Result<umbra_sim::experiment::plan::Budget, String> {
    text.parse()
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
    /// Error budgets in place of the sweep's, each a percentage of
    /// artifacts or `MEASURE=PERCENT` as `plan --budget` spells it
    /// (`--budgets 1,0.1,acne=0.01%`). The bundled sweeps' bound
    /// artifacts (1, 0.1 and 0.01 %) and misclassified pixels (2 %).
    #[arg(long, value_delimiter = ',', value_parser = budget)]
    pub(super) budgets: Vec<umbra_sim::experiment::plan::Budget>,
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
    /// The most silicon the summary's best per objective may take
    /// (`2mm2`).
    #[arg(long)]
    pub(super) max_area: Option<String>,
    /// The most energy a frame of the summary's best per objective may
    /// take (`150uJ`).
    #[arg(long)]
    pub(super) max_energy: Option<String>,
    /// The architectures each configuration is costed on, in place of the
    /// sweep's (`--set` applies to the sweep's when `--arch` is not given).
    #[command(flatten)]
    pub(super) archs: ArchArgs,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    pub(super) out: PathBuf,
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    pub(super) replace: bool,
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
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    pub(super) replace: bool,
}

/// `umbra plan`.
pub(super) fn plan(args: &PlanArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::experiment::plan::{PlanSpec, plan};
    use umbra_sim::experiment::study::{SweepFile, image_size};
    let scene = Scene::open(&args.scene, limits)?;
    let budgets = match (&args.budgets[..], args.error_budget) {
        ([], Some(b)) => vec![b],
        ([], None) => umbra_sim::experiment::plan::DEFAULT_BUDGETS.to_vec(),
        (b, _) => b.to_vec(),
    };
    let mut spec = match &args.sweep {
        Some(sweep) => PlanSpec::from_sweep(&scene, budgets, &SweepFile::open(sweep, limits)?.spec(limits)?),
        None => PlanSpec::new(&scene, budgets),
    };
    spec.limits = *limits;
    spec.arch = args.archs.one("talisman", limits)?;
    spec.objective = args.objective;
    spec.cost_limits =
        umbra_sim::experiment::plan::CostLimits::parse(args.max_area.as_deref(), args.max_energy.as_deref())
            .map_err(anyhow::Error::msg)?;
    if !args.maps.is_empty() {
        umbra_sim::experiment::study::map_sides("--maps", &args.maps, limits)?;
        spec.map_sizes.clone_from(&args.maps);
    }
    if let Some(image) = &args.image {
        spec.image = image_size(image, limits)?;
    }
    let mut folder = OutputFolder::create(&args.out, Claim::new(RunKind::Plan).replacing(args.replace))?;
    let bar = configurations_bar("plan")?;
    let p = plan(&scene, &spec, &bar)?;
    bar.finish_and_clear();
    let md = p.markdown(&scene);
    say!("{}", md.trim_end());
    folder.write_text("plan.md", &md)?;
    folder.write_text("plan.json", &serde_json::to_string_pretty(&p)?)?;
    folder.write_text(&format!("arch-{}.toml", spec.arch.name), &spec.arch.to_toml())?;
    let (manifest, replaced) = folder.finish_replacing(None)?;
    crate::say::wrote(&args.out, &manifest, &replaced)
}

/// A bar of a study's work, on stderr (hidden when it is not a terminal):
/// the run sets its length to the configurations' estimated work, so that
/// the time left follows the work done, and its message to how many
/// configurations are done of how many.
fn configurations_bar(prefix: &'static str) -> Result<ProgressBar> {
    let style = indicatif::ProgressStyle::with_template("{prefix} [{elapsed_precise}] {wide_bar} {msg}, {eta} left")
        .context("progress bar template")?;
    Ok(ProgressBar::new(0).with_style(style).with_prefix(prefix))
}

/// `umbra study`: the library prepares (checks and hashes) and runs it;
/// this prints what it did.
pub(super) fn study(args: &StudyArgs, limits: &Limits, style: Style) -> Result<()> {
    use umbra_sim::experiment::study::{Outcome, Overrides, Request};
    let request = Request {
        sweep: if args.quick { "quick".to_owned() } else { args.sweep.clone() },
        overrides: Overrides {
            scenes: args.scenes.clone(),
            archs: args.archs.arch.clone(),
            sets: args.archs.set.clone(),
            images: args.images.clone(),
            reference_rays: args.reference_rays,
            budgets: args.budgets.clone(),
            maps: args.maps.clone(),
            cost_limits: umbra_sim::experiment::plan::CostLimits::parse(
                args.max_area.as_deref(),
                args.max_energy.as_deref(),
            )
            .map_err(anyhow::Error::msg)?,
        },
        shard: args.shard.clone(),
        extremes: args.extremes,
        out: args.out.clone(),
        replace: args.replace,
    };
    let prepared = request.prepare(limits, rayon::current_num_threads())?;
    let prepared_budgets = prepared.spec.budgets.clone();
    // A bound past half the limit is said: the run is near the machine's edge.
    let (renders, bound) = prepared.spec.memory(rayon::current_num_threads())?;
    if bound > limits.max_memory / 2 {
        say!(
            "study: {renders} render(s) at once, bounded by {} MiB of the {} MiB --max-memory allows (an upper bound: measured peaks are 30–60 % of it)",
            bound >> 20,
            limits.max_memory >> 20
        );
    }
    let progress = configurations_bar("study")?;
    let start = std::time::Instant::now();
    let outcome = prepared.run(&progress)?;
    progress.finish_and_clear();
    match outcome {
        Outcome::AlreadyComplete(m) => {
            say!("study: shard {} in {} is already complete and verified: not recomputed", m.shard, args.out.display());
        }
        Outcome::Ran { rows, summary, extremes, replaced, .. } => {
            match (style, summary) {
                (Style::Full, Some(summary)) => say!("{summary}"),
                (Style::Brief, Some(_)) => {
                    for line in umbra_sim::experiment::study::headline(&rows, &prepared_budgets) {
                        crate::say::wrapped(&line)?;
                    }
                }
                (_, None) => {}
            }
            if let Some(report) = extremes {
                say!("{report}");
            }
            let configs = rows.iter().map(|r| r.config_index).collect::<std::collections::BTreeSet<_>>().len();
            let skipped = rows.iter().filter(|r| r.metrics.is_none()).count();
            crate::say::wrapped(&format!(
                "study: {configs} configurations, {} rows ({skipped} skipped); wrote {} (its files in {})",
                rows.len(),
                args.out.display(),
                args.out.join(umbra_sim::output::folder::MANIFEST).display()
            ))?;
            crate::say::replacements(&args.out, &replaced)?;
            // The wall time varies with the machine: not part of the results.
            eprintln!("study took {:.1} s", start.elapsed().as_secs_f64());
        }
    }
    Ok(())
}
