//! `umbra cost` and `umbra trace`: a render's cost on an architecture, and its timeline.

use crate::render::{RenderArgs, render_config};
use anyhow::Result;
use clap::ValueEnum;
use umbra_sim::cost::arch::ArchParams;
use umbra_sim::io::limits::Limits;
use umbra_sim::io::output::write_text;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(super) enum ArchArg {
    Pixelflow,
    Talisman,
    Immediate,
    All,
}

#[derive(clap::Args, Debug)]
pub(super) struct CostArgs {
    /// Architecture preset.
    #[arg(long, value_enum, default_value_t = ArchArg::All)]
    pub(super) arch: ArchArg,
    #[command(flatten)]
    pub(super) render: RenderArgs,
}

/// `umbra cost` and `umbra trace`.
pub(super) fn cost(args: &CostArgs, trace: bool, limits: &Limits) -> Result<()> {
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
        let (report, light) = umbra_sim::pass::render::cost(&scene, &cfg, arch, limits)?;
        if trace {
            let path = out.join(format!("trace-{}.json", arch.name));
            write_text(&path, &serde_json::to_string(&umbra_sim::cost::arch::CostReport::trace(&light))?)?;
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
