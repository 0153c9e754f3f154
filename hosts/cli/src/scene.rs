//! `umbra scene …`: a scene file upgraded for the current format, or a
//! glTF city generated.

use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::{Claim, OutputFolder, RunKind};
use umbra_sim::world::gltf::City;

use crate::say::say;
use crate::upgrade::{self, UpgradeArgs};

/// `umbra scene …`.
#[derive(Subcommand, Debug)]
pub(super) enum SceneCommand {
    /// Rewrite the file for the current file format: the format stated,
    /// every comment and value as it was.
    Upgrade(UpgradeArgs),
    /// Generate a glTF city: one building mesh placed by a node per
    /// building (stored once, instanced) on a ground plane, a camera over a
    /// corner, a low sun and a spot light; `city.glb` in the output folder.
    City(CityArgs),
}

/// The city's size and where it goes.
#[derive(clap::Args, Debug)]
pub(super) struct CityArgs {
    /// Buildings along each side (at least 1; at most what the limits allow
    /// a render to read back: --max-triangles, --max-text-bytes, --max-memory).
    #[arg(long, default_value_t = City::SMALL.side)]
    side: u32,
    /// Window columns along each wall (a power of two).
    #[arg(long, default_value_t = City::SMALL.columns)]
    columns: u32,
    /// Storeys up each wall (a power of two).
    #[arg(long, default_value_t = City::SMALL.storeys)]
    storeys: u32,
    /// Output folder.
    #[arg(long, default_value = "out/scene-city")]
    out: PathBuf,
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    replace: bool,
}

/// Run `umbra scene …`.
pub(super) fn scene(command: &SceneCommand, limits: &Limits) -> Result<()> {
    match command {
        SceneCommand::Upgrade(args) => upgrade::upgrade(upgrade::Kind::Scene, args, limits),
        SceneCommand::City(args) => {
            let city = City { side: args.side, columns: args.columns, storeys: args.storeys };
            let bytes = city.glb_within(limits)?;
            let mut folder = OutputFolder::create(&args.out, Claim::new(RunKind::Scene).replacing(args.replace))?;
            let path = folder.write("city.glb", &bytes)?;
            let (_, replaced) = folder.finish_replacing(None)?;
            say!(
                "a city of {0} × {0} buildings, {1} triangles: wrote {2}",
                city.side,
                city.triangles(),
                path.display()
            );
            crate::say::replacements(&args.out, &replaced)
        }
    }
}
