//! A study's headline: the few lines a person reads first — for each
//! scene, the fastest design within the loosest budget — where the
//! summary (`summary.md`) holds every table.

use super::budget::Budget;
use super::rank::{TIME, cheapest};
use super::summary::scenes_of;
use super::{Row, loosest};

/// For each scene of `rows`, its fastest complete row within the loosest
/// of `budgets` (on artifacts, else the first): the scene, the budget,
/// the row's label, its frame time and its errors; or that none meets it.
///
/// ```
/// use umbra_sim::experiment::study::{budget::Budget, headline};
/// assert!(headline(&[], &[Budget::artifacts(1.0)]).is_empty()); // no rows, no scene
/// ```
#[must_use]
pub fn headline(rows: &[Row], budgets: &[Budget]) -> Vec<String> {
    let Some(budget) = loosest(budgets) else { return Vec::new() };
    scenes_of(rows)
        .into_iter()
        .map(|scene| {
            let mine: Vec<&Row> = rows.iter().filter(|r| r.config.scene == scene).collect();
            match cheapest(&mine, &budget, TIME) {
                Some((r, _)) => {
                    let m = r.metrics.unwrap_or_default();
                    let us = r.cost.as_ref().map_or(0.0, |c| c.frame_seconds * 1e6);
                    format!(
                        "{scene}: the fastest with {} ≤ {} %: {} — {us:.1}\u{a0}µs, {:.3} % artifacts, {:.3} % \
                         misclassified",
                        budget.measure.name(),
                        budget.percent,
                        r.label(),
                        m.artifact_percent,
                        m.misclassified_percent
                    )
                }
                None => format!("{scene}: no design with {} ≤ {} %", budget.measure.name(), budget.percent),
            }
        })
        .collect()
}
