//! The plan as a person reads it: the pick, why, its figures beside the
//! runners-up, and the map's storage, in Markdown.

use std::fmt::Write as _;

use super::{Budget, Candidate, Measure, Plan, RunnerUp};
use crate::cost::storage::REEVES_TILE;
use crate::world::scene::Scene;

impl Plan {
    /// The plan as Markdown: the pick, why, its figures, the runners-up
    /// and the map's storage.
    #[must_use]
    pub fn markdown(&self, scene: &Scene) -> String {
        let mut s = String::new();
        let list = self.budgets.iter().map(|b| format!("{} ≤ {}%", b.measure.name(), b.percent)).collect::<Vec<_>>();
        let p = &self.pick;
        let _ = writeln!(
            s,
            "## Plan for `{}` ({}; costed on `{}`)\n\n{}\n\n`{}`\n",
            scene.name,
            list.join(", "),
            self.arch,
            p.label,
            p.command
        );
        for r in &self.reasons {
            let _ = writeln!(s, "- {r}");
        }
        let measures: Vec<Measure> = budget_columns(&self.budgets);
        let heads: String = measures.iter().map(|m| format!(" {} % |", m.name())).collect();
        let rules: String = measures.iter().map(|_| "---:|").collect();
        let _ = writeln!(
            s,
            "\n| candidate | cycles | time (ms) | DRAM bytes |{heads} why not |\n|---|---:|---:|---:|{rules}---|"
        );
        let row = |s: &mut String, c: &Candidate, why: &str| {
            let figures: String = measures.iter().map(|&m| format!(" {:.3} |", c.measure(m))).collect();
            let _ =
                writeln!(s, "| {} | {} | {:.3} | {} |{figures} {why} |", c.label, c.cycles, c.seconds * 1e3, c.bytes);
        };
        let pick = if self.meets { "the pick" } else { "the pick, nearest the budgets" };
        let cheaper: Vec<&RunnerUp> = self.runners_up.iter().filter(|r| r.cheaper).collect();
        for r in cheaper.iter().rev() {
            row(&mut s, &r.candidate, &r.lost);
        }
        let _ = write!(s, "| **{}** | **{}** | **{:.3}** | **{}** |", p.label, p.cycles, p.seconds * 1e3, p.bytes);
        for &m in &measures {
            let _ = write!(s, " **{:.3}** |", p.measure(m));
        }
        let _ = writeln!(s, " {pick} |");
        for r in self.runners_up.iter().filter(|r| !r.cheaper) {
            row(&mut s, &r.candidate, &r.lost);
        }
        let st = &self.storage;
        let _ = writeln!(
            s,
            "\nMap storage (Reeves et al. Table 2), {} buffer(s):\n\n| scheme | bytes | holds |\n|---|---:|---|",
            st.buffers
        );
        let _ = writeln!(s, "| raw | {} | every texel |", st.raw);
        let _ = writeln!(s, "| bounding box | {} | {} texels of finite depth |", st.bounding_box, st.box_texels);
        let _ = writeln!(
            s,
            "| {REEVES_TILE}×{REEVES_TILE} tiles | {} | {} of {} tiles that received geometry |",
            st.tiles, st.stored_tiles, st.grid_tiles
        );
        s
    }
}

/// The measures a plan's table shows: the budgeted ones, then artifacts
/// and misclassified pixels when not budgeted.
fn budget_columns(budgets: &[Budget]) -> Vec<Measure> {
    let mut out: Vec<Measure> = budgets.iter().map(|b| b.measure).collect();
    for m in [Measure::Artifacts, Measure::Misclassified] {
        if !out.contains(&m) {
            out.push(m);
        }
    }
    out
}
