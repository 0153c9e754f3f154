//! The plan as a person reads it: the pick, why, its figures beside the
//! runners-up, and the map's storage, in Markdown.

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use super::{Budget, Candidate, Measure, Plan, RunnerUp};
use crate::cost::storage::REEVES_TILE;
use crate::world::scene::Scene;

impl Plan {
    /// The plan as Markdown: the pick, why, its figures, the runners-up
    /// and the map's storage (none for shadow volumes, which store none).
    #[must_use]
    pub fn markdown(&self, scene: &Scene) -> String {
        let mut s = String::new();
        let mut list =
            self.budgets.iter().map(|b| format!("{} ≤ {}%", b.measure.name(), b.percent)).collect::<Vec<_>>();
        if self.cost_limits.any() {
            list.push(self.cost_limits.words());
        }
        let p = &self.pick;
        let _ = writeln!(
            s,
            "## Plan for `{}` ({}; least {} on `{}`)\n\n{}\n\n`{}`\n",
            scene.name,
            list.join(", "),
            self.objective.words(),
            self.arch,
            p.label,
            p.command
        );
        for r in &self.reasons {
            let _ = writeln!(s, "- {r}");
        }
        let measures: Vec<Measure> = budget_columns(&self.budgets);
        let mut columns: Vec<(String, Align)> =
            ["candidate", "cycles", "time (ms)", "DRAM bytes", "energy (µJ)", "area (mm²)"]
                .iter()
                .enumerate()
                .map(|(i, h)| ((*h).to_owned(), if i == 0 { Align::Left } else { Align::Right }))
                .collect();
        columns.extend(measures.iter().map(|m| (format!("{} %", m.name()), Align::Right)));
        columns.push(("why not".to_owned(), Align::Left));
        let mut t = Table::new(&columns);
        let cells = |c: &Candidate, bold: bool| {
            let b = |x: String| if bold { format!("**{x}**") } else { x };
            let mut cells = vec![
                b(c.label.clone()),
                b(c.cycles.to_string()),
                b(format!("{:.3}", c.seconds * 1e3)),
                b(c.bytes.to_string()),
                b(format!("{:.3}", c.joules * 1e6)),
                b(format!("{:.4}", c.square_metres * 1e6)),
            ];
            cells.extend(measures.iter().map(|&m| b(format!("{:.3}", c.measure(m)))));
            cells
        };
        let pick = if self.meets { "the pick" } else { "the pick, nearest the budgets" };
        let cheaper: Vec<&RunnerUp> = self.runners_up.iter().filter(|r| r.cheaper).collect();
        for r in cheaper.iter().rev() {
            t.row(cells(&r.candidate, false).into_iter().chain([r.lost.clone()]));
        }
        t.row(cells(p, true).into_iter().chain([pick.to_owned()]));
        for r in self.runners_up.iter().filter(|r| !r.cheaper) {
            t.row(cells(&r.candidate, false).into_iter().chain([r.lost.clone()]));
        }
        let _ = write!(s, "\n{}", t.markdown());
        let Some(st) = &self.storage else { return s };
        let mut t = Table::new(&[("scheme", Align::Left), ("bytes", Align::Right), ("holds", Align::Left)]);
        t.row(["raw".to_owned(), st.raw.to_string(), "every texel".to_owned()]);
        t.row([
            "bounding box".to_owned(),
            st.bounding_box.to_string(),
            format!("{} texels of finite depth", st.box_texels),
        ]);
        t.row([
            format!("{REEVES_TILE}×{REEVES_TILE} tiles"),
            st.tiles.to_string(),
            format!("{} of {} tiles that received geometry", st.stored_tiles, st.grid_tiles),
        ]);
        let _ = write!(s, "\nMap storage (Reeves et al. Table 2), {} buffer(s):\n\n{}", st.buffers, t.markdown());
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
