//! `umbra cost` and `umbra trace`: a render's cost on architectures, and its timeline.

use crate::render::{RenderArgs, job};
use crate::say::say;
use anyhow::{Result, bail};
use umbra_sim::cost::arch::Arch;
use umbra_sim::cost::arch::BUNDLED;
use umbra_sim::cost::report::files;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::{Claim, OutputFolder, RunKind};

/// Which architectures, and what to change in them.
#[derive(clap::Args, Debug, Clone, Default)]
#[command(next_help_heading = "Architecture")]
pub(super) struct ArchArgs {
    /// A bundled architecture (pixelflow, talisman, immediate, mobile-tbdr,
    /// desktop-imr, r300), an architecture file (TOML, see arch/), or `all`
    /// (every bundled one). Repeat for several.
    #[arg(long = "arch")]
    pub(super) arch: Vec<String>,
    /// Override a parameter of every chosen architecture: `key=value`, with
    /// units where the key has one (`dram.bandwidth=25.6GB/s`,
    /// `clock=800MHz`, `map_cache.size=16KiB`, `dram.latency=2ns`). Repeat
    /// for several.
    #[arg(long = "set")]
    pub(super) set: Vec<String>,
}

impl ArchArgs {
    /// The chosen architectures with the overrides applied; `default` names
    /// them when `--arch` is not given.
    pub(super) fn resolve(&self, default: &[&str], limits: &Limits) -> Result<Vec<Arch>> {
        let archs = umbra_sim::experiment::study::choose_archs(&self.arch, &self.set, default, limits)?;
        // A file that calls itself by a bundled machine's name, but is not
        // that machine, would have its outputs named after the original.
        for file in self.arch.iter().filter(|a| !umbra_sim::cost::arch::BUNDLED.iter().any(|b| b.0 == *a)) {
            if let Ok(arch) = Arch::open(file, limits)
                && let Some(keys) = arch.namesake_differences()
            {
                eprintln!(
                    "warning: {file} calls itself `{}`, as a bundled architecture does, but differs from it ({}): its outputs are named `{}`; give it a `name` of its own",
                    arch.name,
                    keys.join(", "),
                    arch.name
                );
            }
        }
        Ok(archs)
    }
}

/// The one architecture of a command that costs on one (`plan`,
/// `correlate`).
#[derive(clap::Args, Debug, Default)]
pub(super) struct OneArchArgs {
    /// A bundled architecture (pixelflow, talisman, immediate, mobile-tbdr,
    /// desktop-imr, r300) or an architecture file (TOML, see arch/).
    #[arg(long = "arch")]
    pub(super) arch: Option<String>,
    /// Override a parameter of the architecture: `key=value`, with units
    /// where the key has one (`dram.bandwidth=25.6GB/s`). Repeat for
    /// several.
    #[arg(long = "set")]
    pub(super) set: Vec<String>,
}

impl OneArchArgs {
    /// The architecture with the overrides applied; `default` when `--arch`
    /// is not given.
    pub(super) fn one(&self, default: &str, limits: &Limits) -> Result<Arch> {
        let name = self.arch.as_deref().unwrap_or(default);
        if name == "all" {
            bail!("--arch all: this command costs on one architecture; name one");
        }
        let mut archs = ArchArgs { arch: vec![name.to_owned()], set: self.set.clone() }.resolve(&[default], limits)?;
        Ok(archs.remove(0))
    }
}

#[derive(clap::Args, Debug)]
pub(super) struct CostArgs {
    #[command(flatten)]
    pub(super) archs: ArchArgs,
    #[command(flatten)]
    pub(super) render: RenderArgs,
}

/// The command line, as outputs record it.
pub(super) fn command_line() -> String {
    umbra_sim::output::provenance::command_line()
}

/// `umbra cost` and `umbra trace`.
pub(super) fn cost(args: &CostArgs, trace: bool, limits: &Limits) -> Result<()> {
    let scene = args.render.scene(limits)?;
    let job = job(&args.render, &scene, limits)?;
    let archs = args.archs.resolve(&BUNDLED.map(|b| b.0), limits)?;
    let own = if trace { "out/trace" } else { "out/cost" };
    let out = args.render.out.clone().unwrap_or_else(|| std::path::PathBuf::from(own));
    let kind = if trace { RunKind::Trace } else { RunKind::Cost };
    let mut folder = OutputFolder::create(&out, Claim::new(kind).replacing(args.render.replace))?;
    let reports = archs.iter().map(|arch| umbra_sim::render::cost(&job, arch)).collect::<Result<Vec<_>, _>>()?;
    if trace {
        let slices = files::write_trace(&mut folder, &reports)?;
        for (r, n) in reports.iter().zip(slices) {
            let unit = if r.arch.immediate() { "draw" } else { "tile" };
            say!("trace.json: {} ({:.3} ms): {n} {unit} slices", r.arch.name, r.seconds() * 1e3);
        }
    } else {
        let comparison = files::write_costs(&mut folder, &reports)?;
        for r in &reports {
            say!("{}", r.markdown());
        }
        if let Some(c) = comparison {
            say!("{}", c.markdown());
        }
    }
    let (manifest, replaced) = folder.finish_replacing(None)?;
    crate::say::wrote(&out, &manifest, &replaced)
}

#[derive(clap::Args, Debug)]
pub(super) struct CorrelateArgs {
    /// A bundled dataset (weiskopf-ertl-2003, peak-rates, arm-render-passes,
    /// sen-cammarano-hanrahan-2003) or a dataset file (TOML, see
    /// data/correlation/). Repeat for several; default: every bundled one.
    #[arg(long = "dataset")]
    pub(super) datasets: Vec<String>,
    /// An architecture file standing in for the bundled architecture of
    /// its name wherever a dataset names it. Repeat for several.
    #[arg(long = "arch")]
    pub(super) archs: Vec<String>,
    /// Override a parameter of every point's architecture: `key=value`,
    /// with units where the key has one. Repeat for several.
    #[arg(long = "set")]
    pub(super) set: Vec<String>,
    /// Output folder.
    #[arg(long, default_value = "out/correlate")]
    pub(super) out: std::path::PathBuf,
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    pub(super) replace: bool,
}

/// `umbra correlate`: every dataset's points simulated against their
/// measurements, the statistics, the tables and the plots.
pub(super) fn correlate(args: &CorrelateArgs, limits: &Limits) -> Result<()> {
    use umbra_sim::experiment::correlation::{self, BUNDLED as DATASETS, Dataset};
    let names: Vec<&str> = if args.datasets.is_empty() {
        DATASETS.iter().map(|d| d.0).collect()
    } else {
        args.datasets.iter().map(String::as_str).collect()
    };
    crate::no_repeats("--dataset", names.iter().copied())?;
    let datasets = names.iter().map(|n| Dataset::open(n, limits)).collect::<Result<Vec<_>, _>>()?;
    let files =
        args.archs.iter().map(|f| Arch::load(std::path::Path::new(f), limits)).collect::<Result<Vec<_>, _>>()?;
    crate::no_repeats("--arch", files.iter().map(|a| a.name.as_str()))?;
    crate::no_repeats("--set", args.set.iter().map(|s| s.split_once('=').map_or(s.as_str(), |(k, _)| k.trim())))?;
    let resolve = |name: &str, set: &[String]| -> std::result::Result<Arch, String> {
        let mut arch = match files.iter().find(|a| a.name == name) {
            Some(a) => a.clone(),
            None => Arch::open(name, limits).map_err(|e| e.to_string())?,
        };
        for s in set.iter().chain(&args.set) {
            arch.set(s).map_err(|e| e.to_string())?;
        }
        Ok(arch)
    };
    let mut folder = OutputFolder::create(&args.out, Claim::new(RunKind::Correlation).replacing(args.replace))?;
    let c = correlation::run(&datasets, &resolve, limits).map_err(anyhow::Error::msg)?;
    let md = c.markdown();
    say!("{}", md.trim_end());
    folder.write_text("correlation.md", &md)?;
    let json = serde_json::json!({
        "version": umbra_sim::output::provenance::version(),
        "command": command_line(),
        "correlation": c,
    });
    folder.write_text("correlation.json", &serde_json::to_string_pretty(&json)?)?;
    correlation::plot(&mut folder, &c.datasets)?;
    let mut used: Vec<String> =
        datasets.iter().flat_map(|d| d.points.iter().filter_map(|p| p.arch.clone()).chain(d.arch.clone())).collect();
    used.sort();
    used.dedup();
    for name in used {
        let arch = resolve(&name, &[]).map_err(anyhow::Error::msg)?;
        folder.write_text(&format!("arch-{name}.toml"), &arch.to_toml())?;
    }
    let (manifest, replaced) = folder.finish_replacing(None)?;
    crate::say::wrote(&args.out, &manifest, &replaced)
}
