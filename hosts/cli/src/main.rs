//! The `umbra` command.

use std::path::PathBuf;

use anyhow::Result;
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use cost::{CorrelateArgs, CostArgs, correlate, cost};
use depth::{DepthArgs, depth};
use experiment::{MergeArgs, PlanArgs, StatusArgs, StudyArgs, plan, study};
use limits::LimitArgs;
use render::{RenderArgs, render};

mod arch;
mod cost;
mod depth;
mod experiment;
mod limits;
mod render;
mod say;
mod scene;
mod stop;
mod upgrade;

use say::{Style, say};

/// Umbra: a bit-exact model of fixed-function shadow-mapping hardware.
///
/// With no subcommand, does what `cargo umbra` shows a newcomer: the
/// default scene's light-view maps into `out/depth/`, its render against
/// the exact reference into `out/render/`, and the quick trade study into
/// `out/study/`.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Worker threads of the commands that run in parallel (a study, a
    /// correlation), from 1 to 256; default: one a core (or
    /// `RAYON_NUM_THREADS`). The results do not depend on it. On Slurm,
    /// `--threads $SLURM_CPUS_PER_TASK`.
    #[arg(long, global = true, value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: Option<u16>,
    /// A folder a glTF model may read its buffers from besides its own
    /// (by default a model reads only files in its own folder and below).
    /// Repeat for several.
    #[arg(long = "allow-read", global = true, value_name = "FOLDER")]
    allow_read: Vec<PathBuf>,
    // Last: the options after it would join its help section.
    #[command(flatten)]
    limits: LimitArgs,
}

/// The help of every command's `--replace`.
const REPLACE_HELP: &str = "Replace what --out holds when it is another command's results or files no run of umbra wrote there (a new, empty or same-command folder needs no flag); files this run reads are kept, and none umbra did not write is deleted";

#[derive(Subcommand, Debug)]
enum Command {
    /// Render the light-view depth maps (z1, z2) of a mesh or scene.
    Depth(DepthArgs),
    /// Render a scene with a shadow algorithm, compare it with the exact
    /// reference, and write the pictures and the metrics.
    Render(RenderArgs),
    /// The cost of a render on architectures (bundled or files): per-tile
    /// timing, cycles per stage, DRAM bytes, energy, Sen's bandwidth figures
    /// (a table, cost.json, gem5-style stats and the effective architecture).
    Cost(CostArgs),
    /// The frame's timeline from the timing model in Chrome trace-event
    /// JSON (open it in Perfetto): a process per architecture, a slice per
    /// pass enclosing its tiles, a track per stage, DRAM bandwidth.
    Trace(CostArgs),
    /// The timing model against published hardware: each dataset's
    /// measurements (Weiskopf & Ertl's Radeon 9700 frame rates, published
    /// peak rates, Arm's attachment bandwidths) beside the model's, the
    /// statistics, and predicted-against-measured plots.
    Correlate(CorrelateArgs),
    /// The speed/accuracy trade study: scene × algorithm × depth format ×
    /// map size × filter × architecture; results.jsonl/.csv, Pareto plots
    /// and summary.md.
    Study(StudyArgs),
    /// Merge the results.jsonl of `study --shard` runs into the whole run's
    /// files.
    Merge(MergeArgs),
    /// The state of a sharded study's folders: which shards are complete,
    /// missing, running or abandoned (a pending manifest), or corrupt
    /// (files differing from their manifest). Fails unless every shard is
    /// complete.
    Status(StatusArgs),
    /// The columns of a study's rows (results.csv, results.jsonl): name,
    /// type, unit and meaning, as each study writes them to schema.csv
    /// (architecture axes add one column each, `arch_<key>_<unit>`); or,
    /// `umbra schema render`, a render's parameters: flag, Python keyword,
    /// values, default, unit and column.
    Schema {
        /// `rows` or `render`.
        #[arg(default_value = "rows", value_parser = ["rows", "render"])]
        what: String,
    },
    /// Show an architecture with its derived figures, check it for keys
    /// that have no effect, compare two, or upgrade a file written for an
    /// earlier format.
    #[command(subcommand)]
    Arch(arch::ArchCommand),
    /// Upgrade a scene file written for an earlier format, or generate a
    /// glTF city.
    #[command(subcommand)]
    Scene(scene::SceneCommand),
    /// Upgrade a sweep file written for an earlier format.
    #[command(subcommand)]
    Sweep(upgrade::FileCommand),
    /// The least costly configuration a scene needs for an error budget:
    /// buffers, depth precision, map size and filter, with the reasons, the
    /// predicted and measured error and cost, and the map's storage.
    Plan(PlanArgs),
}

/// Refuse a list flag that names one thing twice (it would run it twice).
fn no_repeats<'a>(flag: &str, items: impl IntoIterator<Item = &'a str>) -> Result<()> {
    Ok(umbra_sim::experiment::study::no_repeats(flag, items)?)
}

/// The most worker threads a run starts. `RAYON_NUM_THREADS` above it is
/// lowered to it, with a notice: each thread costs a stack and a start, and
/// a hundred thousand of them stop a one-second render. The results do not
/// depend on the thread count.
const MAX_THREADS: usize = 256;

/// Clamp the worker threads `RAYON_NUM_THREADS` asks for to [`MAX_THREADS`].
fn clamp_threads() {
    let asked = std::env::var("RAYON_NUM_THREADS").ok().and_then(|v| v.trim().parse::<usize>().ok());
    if let Some(n) = asked.filter(|&n| n > MAX_THREADS) {
        eprintln!("RAYON_NUM_THREADS={n} is more than {MAX_THREADS} threads: using {MAX_THREADS}");
        // Only fails if a pool was built already, and none is before this.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(MAX_THREADS).build_global();
    }
}

/// Run the command; an error is one line on stderr and exit status 1 (a
/// user's mistake is not a crash: no stack trace, whatever
/// `RUST_BACKTRACE` says). A run stopped by Ctrl-C or SIGTERM has said so
/// already and exits with [`stop::STATUS`].
fn main() -> std::process::ExitCode {
    match stop::on_signals().and_then(|()| run()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(_) if umbra_sim::base::stop::requested() => std::process::ExitCode::from(stop::STATUS),
        Err(e) => {
            eprintln!("Error: {}", one_line(&e));
            std::process::ExitCode::FAILURE
        }
    }
}

/// The command line, read by `umbra`'s command with the limits listed
/// once ([`limits::listed_once`]); help, the version and mistakes are
/// printed and exit here, as clap does.
fn parse() -> Cli {
    let mut umbra = limits::listed_once(Cli::command());
    let mut matches = umbra.get_matches_mut();
    Cli::from_arg_matches_mut(&mut matches).unwrap_or_else(|e| e.format(&mut umbra).exit())
}

/// An error and its causes in one line, each cause said once: a cause
/// whose text its error already holds (`/proc/x: No such file or
/// directory`, whose source is the OS error it quotes) is not said again.
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if !line.contains(&text) {
            if !line.is_empty() {
                line.push_str(": ");
            }
            line.push_str(&text);
        }
    }
    line
}

fn run() -> Result<()> {
    let cli = parse();
    if let Some(n) = cli.threads {
        // Only fails if a pool was built already, and none is before this.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(usize::from(n)).build_global();
    }
    clamp_threads();
    for dir in &cli.allow_read {
        umbra_sim::base::reads::allow_folder(dir)
            .map_err(|e| anyhow::anyhow!("--allow-read {}: {e}", dir.display()))?;
    }
    let limits = &cli.limits.limits();
    match cli.command {
        Some(Command::Depth(args)) => depth(&args, limits, Style::Full),
        Some(Command::Render(args)) => render(&args, limits, Style::Full),
        Some(Command::Cost(args)) => cost(&args, false, limits),
        Some(Command::Trace(args)) => cost(&args, true, limits),
        Some(Command::Correlate(args)) => correlate(&args, limits),
        Some(Command::Study(args)) => study(&args, limits, Style::Full),
        Some(Command::Plan(args)) => plan(&args, limits),
        Some(Command::Arch(command)) => arch::arch(&command, limits),
        Some(Command::Scene(command)) => scene::scene(&command, limits),
        Some(Command::Sweep(upgrade::FileCommand::Upgrade(args))) => {
            upgrade::upgrade(upgrade::Kind::Sweep, &args, limits)
        }
        Some(Command::Schema { what }) => {
            let table = if what == "render" {
                umbra_sim::render::params::markdown()
            } else {
                umbra_sim::experiment::study::schema::markdown()
            };
            say!("{}", table.trim_end());
            Ok(())
        }
        Some(Command::Status(args)) => {
            let s = umbra_sim::experiment::study::status(&args.inputs, limits);
            say!("{}", s.markdown().trim_end());
            if !s.ready() {
                anyhow::bail!("not ready to merge: {} problem(s), listed above", s.problems.len());
            }
            Ok(())
        }
        Some(Command::Merge(args)) => {
            let n = umbra_sim::experiment::study::merge_replacing(&args.inputs, (&args.out, args.replace), limits)?;
            say!("merged {n} rows into {}", args.out.display());
            Ok(())
        }
        None => {
            // The headline of each, the full figures in the files.
            depth(&DepthArgs::default(), limits, Style::Brief)?;
            render(&RenderArgs::default(), limits, Style::Brief)?;
            study(
                &StudyArgs {
                    scenes: Vec::new(),
                    sweep: "quick".to_owned(),
                    quick: true,
                    images: Vec::new(),
                    reference_rays: None,
                    budgets: Vec::new(),
                    shard: None,
                    extremes: false,
                    maps: Vec::new(),
                    max_area: None,
                    max_energy: None,
                    archs: cost::ArchArgs::default(),
                    out: PathBuf::from("out/study"),
                    replace: false,
                },
                limits,
                Style::Brief,
            )?;
            say!("every figure: out/depth/tiles.md, out/render/metrics.json and out/study/summary.md");
            Ok(())
        }
    }
}
