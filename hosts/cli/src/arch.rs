//! `umbra arch show | check | diff | upgrade`: an architecture file's
//! effective values and what they imply, its ineffective keys, two files
//! side by side, and a file brought to the current format.

use anyhow::{Result, bail};
use clap::Subcommand;
use umbra_sim::Arch;
use umbra_sim::cost::arch::PARAMS;
use umbra_sim::cost::arch::derived::diff;
use umbra_sim::cost::silicon::Silicon;
use umbra_sim::experiment::attribution::attribute;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::table::{Align, Table};
use umbra_sim::render::RenderConfig;
use umbra_sim::world::scene::Scene;

use crate::cost::OneArchArgs;
use crate::say::say;

#[derive(Subcommand, Debug)]
pub(super) enum ArchCommand {
    /// Every key with its value and unit, then the derived figures (peak
    /// rates, achievable DRAM bandwidth and its latency ceiling, cache
    /// geometry, on-chip bytes a tile needs), then each unit's silicon
    /// area at its technology for the default render.
    Show(OneArchArgs),
    /// Every key that has no effect, each named with why: the derived
    /// ceilings that cap another key, and the keys no unit of this machine
    /// reads (a warning when set to do something, a note otherwise); exits
    /// non-zero when the file is not a machine the model can run.
    Check(OneArchArgs),
    /// Rewrite an architecture file for the current format: the format
    /// stated, and every key added since with the value that keeps the
    /// earlier behaviour, its meaning and unit as a comment.
    Upgrade(crate::upgrade::UpgradeArgs),
    /// Two architectures key by key and derived figure by derived figure;
    /// with `--scene`, the difference in time, energy and DRAM bytes by
    /// purpose on that scene's render attributed to each key by its
    /// Shapley value (its effect averaged over every order of changing
    /// the keys), ranked by effect.
    Diff {
        /// The first: a bundled name or an architecture file.
        a: String,
        /// The second.
        b: String,
        /// A bundled scene or a scene file whose default render (the
        /// scene's image, 1024² map, second depth, bilinear) the difference
        /// is measured on.
        #[arg(long)]
        scene: Option<String>,
    },
}

/// `umbra arch …`.
pub(super) fn arch(command: &ArchCommand, limits: &Limits) -> Result<()> {
    match command {
        ArchCommand::Show(which) => {
            let a = which.one("talisman", limits)?;
            let columns = |first: &'static str, third: &'static str| {
                [(first, Align::Left), ("value", Align::Right), (third, Align::Left)]
            };
            let mut keys = Table::new(&columns("key", "meaning"));
            for p in PARAMS {
                keys.row([format!("`{}`", p.key), p.written(&a), p.doc.to_owned()]);
            }
            let mut derived = Table::new(&columns("derived", "how"));
            for f in a.derived() {
                derived.row([f.name.to_owned(), f.text(), f.how.to_owned()]);
            }
            let title = umbra_sim::output::markdown::escape(&format!("# `{}`: {}", a.name, a.description));
            let render = RenderConfig::DEFAULT;
            let silicon = Silicon::of(&a, &render.demand());
            say!(
                "{title}\n\n{}\n{}\n\nThe units of the default render ({}):\n{}",
                keys.markdown(),
                derived.markdown().trim_end(),
                render.describe(),
                silicon.markdown().trim_end()
            );
            Ok(())
        }
        ArchCommand::Check(which) => {
            let a = which.one("talisman", limits)?;
            let warnings = a.warnings();
            for (key, w) in &warnings {
                say!("warning: {}: {key}: {w}", a.name);
            }
            // Every key no unit reads, set to something or not.
            let unread = a.unread();
            for u in unread.iter().filter(|u| !u.meant) {
                say!("note: {}: {}: not read ({})", a.name, u.key, u.why);
            }
            say!(
                "{}: a machine the model can run; {} warning(s); {} key(s) no unit reads",
                a.name,
                warnings.len(),
                unread.len()
            );
            Ok(())
        }
        ArchCommand::Upgrade(args) => crate::upgrade::upgrade(crate::upgrade::Kind::Arch, args, limits),
        ArchCommand::Diff { a, b, scene } => {
            let (a, b) = (Arch::open(a, limits)?, Arch::open(b, limits)?);
            if a.name == b.name && a == b {
                bail!("`{}` and `{}` are the same architecture", a.name, b.name);
            }
            let (keys, figures) = diff(&a, &b);
            let columns = |first: &str| {
                [(first.to_owned(), Align::Left), (a.name.clone(), Align::Right), (b.name.clone(), Align::Right)]
            };
            let mut by_key = Table::new(&columns("key"));
            for (k, x, y) in keys {
                by_key.row([format!("`{k}`"), x, y]);
            }
            let mut by_figure = Table::new(&columns("derived"));
            for (k, x, y) in figures {
                by_figure.row([k.to_owned(), x, y]);
            }
            say!("{}\n{}", by_key.markdown(), by_figure.markdown().trim_end());
            if let Some(scene) = scene {
                let scene = Scene::open(scene, limits)?;
                let cfg = RenderConfig { width: scene.image[0], height: scene.image[1], ..RenderConfig::DEFAULT };
                let t = attribute(&cfg.check(&scene, limits)?, &a, &b)?;
                say!("\n{}", t.markdown().trim_end());
            }
            Ok(())
        }
    }
}
