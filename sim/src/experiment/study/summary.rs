//! The study's outputs: the results table, the summary by error budget, and the plots.

use std::fmt::Write as _;
use std::path::Path;

use super::{Row, StudyError, jsonl, plot, sort_rows};
use crate::io::output::write_text;

/// The error budgets of the summary, percent misclassified.
pub const BUDGETS: [f64; 3] = [1.0, 0.1, 0.01];

/// Write `results.jsonl`, `results.csv`, the Pareto plots per scene and
/// `summary.md` for a whole run's rows.
///
/// # Errors
/// See [`StudyError`].
pub fn write_outputs(dir: &Path, rows: &[Row]) -> Result<(), StudyError> {
    let mut rows = rows.to_vec();
    sort_rows(&mut rows);
    write_text(&dir.join("results.jsonl"), &jsonl(&rows))?;
    let mut csv = csv::Writer::from_writer(Vec::new());
    for r in &rows {
        csv.serialize(r)?;
    }
    let bytes = csv.into_inner().map_err(|e| StudyError::Csv(e.into_error().into()))?;
    write_text(&dir.join("results.csv"), &String::from_utf8_lossy(&bytes))?;
    for scene in scenes_of(&rows) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
        plot::pareto(dir, &scene, &mine)?;
    }
    write_text(&dir.join("summary.md"), &summary(&rows))?;
    Ok(())
}

/// Scene names in order of first appearance.
fn scenes_of(rows: &[Row]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for r in rows {
        if !names.contains(&r.scene) {
            names.push(r.scene.clone());
        }
    }
    names
}

/// The cheapest complete row by `key` whose artifacts (acne and leaks, not
/// edge placement) are within `budget` percent (ties: the earlier row).
fn cheapest<'a>(rows: &[&'a Row], budget: f64, key: impl Fn(&Row) -> Option<u64>) -> Option<&'a Row> {
    rows.iter()
        .copied()
        .filter(|r| r.complete() && r.artifact_percent.is_some_and(|m| m <= budget))
        .min_by_key(|r| (key(r).unwrap_or(u64::MAX), r.index, r.arch_index))
}

/// `summary.md`: per scene, the cheapest configuration in cycles and in DRAM
/// bytes under each error budget, and every skipped row's reason.
#[must_use]
pub fn summary(rows: &[Row]) -> String {
    let mut s = String::new();
    let configs = rows.iter().map(|r| r.index).collect::<std::collections::BTreeSet<_>>().len();
    let skipped: Vec<&Row> = rows.iter().filter(|r| r.status != "ok").collect();
    let _ = writeln!(s, "# Umbra study: the cheapest configuration per error budget\n");
    let _ = writeln!(
        s,
        "{} rows ({configs} render configurations × architectures), {} skipped. Budgets: \
         artifacts (acne and leaks: pixels misclassified against the exact reference away from its shadow \
         boundaries), percent of the pixels facing the light; misclassified: every misclassified pixel, edge \
         placement included. Cycles: the frame (light \
         pass, then camera pass) in the architecture's per-tile timing model. Bytes: all DRAM traffic, map reads \
         as fetched through the architecture's map cache.\n",
        rows.len(),
        skipped.len()
    );
    for scene in scenes_of(rows) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
        let _ = writeln!(s, "## {scene}\n");
        let _ = writeln!(
            s,
            "| artifact budget | cheapest in cycles | cycles | artifacts % | misclassified % | cheapest in bytes | bytes | artifacts % | misclassified % |"
        );
        let _ = writeln!(s, "|---:|---|---:|---:|---:|---|---:|---:|---:|");
        for budget in BUDGETS {
            let by = |key: fn(&Row) -> Option<u64>| match cheapest(&mine, budget, key) {
                Some(r) => format!(
                    "{} | {} | {:.4} | {:.4}",
                    r.label(),
                    key(r).unwrap_or(0),
                    r.artifact_percent.unwrap_or(f64::NAN),
                    r.misclassified_percent.unwrap_or(f64::NAN)
                ),
                None => "none meets it | – | – | –".to_owned(),
            };
            let _ = writeln!(s, "| {budget} % | {} | {} |", by(|r| r.total_cycles), by(|r| r.total_bytes));
        }
        let best = mine.iter().filter(|r| r.misclassified_percent.is_some()).min_by(|a, b| {
            a.misclassified_percent.partial_cmp(&b.misclassified_percent).unwrap_or(std::cmp::Ordering::Equal)
        });
        if let Some(b) = best {
            let _ = writeln!(
                s,
                "\nLowest error: {} at {:.4} %.",
                b.render_label(),
                b.misclassified_percent.unwrap_or(f64::NAN)
            );
        }
        if let Some(n) = mine.iter().find_map(|r| r.evaluated).filter(|&n| n > 0) {
            #[allow(clippy::cast_precision_loss, reason = "a pixel count")]
            let one = 100.0 / n as f64;
            let _ = writeln!(s, "{n} pixels evaluated: one pixel is {one:.4} %.");
        }
        let _ = writeln!(s);
    }
    if !skipped.is_empty() {
        let _ = writeln!(s, "## Skipped\n");
        let _ = writeln!(s, "| row | configuration | reason |");
        let _ = writeln!(s, "|---:|---|---|");
        for r in skipped {
            let _ = writeln!(s, "| {} | {} {} | {} |", r.index, r.scene, r.label(), r.reason.replace('|', "\\|"));
        }
    }
    s
}
