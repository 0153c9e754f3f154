//! `umbra plan`, `umbra study` and `umbra merge`: the planner and the trade study.

use std::path::PathBuf;

use crate::cost::ArchArgs;
use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use umbra_core::RasterConfig;
use umbra_sim::io::limits::Limits;
use umbra_sim::io::output::write_text;
use umbra_sim::world::scene::Scene;

#[derive(clap::Args, Debug)]
pub(super) struct PlanArgs {
    /// A bundled scene by name or a scene file.
    #[arg(default_value = "table")]
    pub(super) scene: String,
    /// Artifacts allowed (acne and leaks away from the exact shadow
    /// boundary), e.g. `0.1%` (percent of the pixels facing the light).
    #[arg(long, default_value = "0.1%")]
    pub(super) error_budget: String,
    /// The architecture whose cost is minimised (default: talisman).
    #[command(flatten)]
    pub(super) archs: ArchArgs,
    /// Output folder for plan.md and plan.json.
    #[arg(long, default_value = "out/plan")]
    pub(super) out: PathBuf,
}

#[derive(clap::Args, Debug)]
pub(super) struct StudyArgs {
    /// Bundled scene names or scene files (default: every bundled scene, or
    /// the quick set with --quick).
    pub(super) scenes: Vec<String>,
    /// The small sweep: 3 scenes, fewer biases, formats, map sizes and
    /// filters, 160×90 images.
    #[arg(long)]
    pub(super) quick: bool,
    /// Run only shard i of n (configurations whose index is i mod n) and
    /// write a partial results.jsonl; `umbra merge` joins the shards.
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
    /// The architectures each configuration is costed on (default:
    /// pixelflow, talisman, immediate).
    #[command(flatten)]
    pub(super) archs: ArchArgs,
    /// Output folder.
    #[arg(long, default_value = "out/study")]
    pub(super) out: PathBuf,
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
    let text = args.error_budget.trim().trim_end_matches('%');
    let budget: f64 =
        text.trim().parse().with_context(|| format!("--error-budget `{}` is not a percentage", args.error_budget))?;
    if !budget.is_finite() || !(0.0..=100.0).contains(&budget) {
        bail!("--error-budget {budget}% is outside 0…100%");
    }
    let scene = Scene::open(&args.scene, limits)?;
    let mut spec = PlanSpec::new(&scene, budget);
    spec.limits = *limits;
    spec.arch = args.archs.one("talisman")?;
    let p = plan(&scene, &spec)?;
    let md = p.markdown(&scene.name, budget);
    print!("{md}");
    if !p.meets(budget) {
        println!("\nThe measured artifacts exceed the budget: no candidate meets it at this image size.");
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    write_text(&args.out.join("plan.md"), &md)?;
    write_text(&args.out.join("plan.json"), &serde_json::to_string_pretty(&p)?)?;
    write_text(&args.out.join(format!("arch-{}.toml", spec.arch.name)), &spec.arch.to_toml())?;
    Ok(())
}

/// `umbra study`.
pub(super) fn study(args: &StudyArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::experiment::study::{self, QUICK_SCENES, Shard, Spec};
    let names: Vec<String> = if !args.scenes.is_empty() {
        args.scenes.clone()
    } else if args.quick {
        QUICK_SCENES.iter().map(|s| (*s).to_owned()).collect()
    } else {
        // The papers' scenes; `factory` is the timing correlation's.
        umbra_sim::world::scene_file::BUNDLED
            .iter()
            .filter(|(n, _)| *n != "factory")
            .map(|(n, _)| (*n).to_owned())
            .collect()
    };
    let scenes = study::load_scenes(&names, limits)?;
    let mut spec = if args.quick { Spec::quick(scenes) } else { Spec::full(scenes) };
    spec.limits = *limits;
    spec.archs = args.archs.resolve(&["pixelflow", "talisman", "immediate"])?;
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
    // The effective architectures, beside the rows that name them.
    for arch in &spec.archs {
        write_text(&args.out.join(format!("arch-{}.toml", arch.name)), &arch.to_toml())?;
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
