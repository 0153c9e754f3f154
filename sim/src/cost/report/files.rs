//! The files a costing writes into its folder, the same from every door:
//! each architecture's gem5-style `stats-<name>.txt` and effective
//! `arch-<name>.toml`, the comparison of several (`comparison.md`) and
//! `cost.json` with what made it and each report's statistics as its
//! stats file lists them; or, for a timeline, `trace.json`.

use super::{Comparison, CostReport, trace};
use crate::output::OutputError;
use crate::output::folder::OutputFolder;
use crate::output::provenance::{command_line, version};

/// Write `reports` (one per architecture, in order) into `folder`: each
/// one's stats file and effective architecture, then the comparison of
/// several and `cost.json`. The comparison, if there is one (its
/// manifest is the caller's to finish).
///
/// # Errors
/// `OutputError` for a file that could not be written.
pub fn write_costs(folder: &mut OutputFolder, reports: &[CostReport]) -> Result<Option<Comparison>, OutputError> {
    let command = command_line();
    for r in reports {
        let name = &r.arch.name;
        folder.write_text(&format!("stats-{name}.txt"), &r.stats(&command))?;
        folder.write_text(&format!("arch-{name}.toml"), &r.arch.to_toml())?;
    }
    let comparison = Comparison::new(reports);
    if let Some(c) = &comparison {
        folder.write_text("comparison.md", &c.markdown())?;
    }
    // Each report's statistics by name, as its stats file lists them.
    let statistics: Vec<serde_json::Map<String, serde_json::Value>> = reports
        .iter()
        .map(|r| r.statistics().into_iter().map(|s| (s.name.clone(), serde_json::json!(s))).collect())
        .collect();
    let json = serde_json::json!({
        "version": version(), "command": command, "reports": reports, "comparison": comparison,
        "statistics": statistics,
    });
    // Numbers and strings only: it serialises without fail.
    folder.write_text("cost.json", &serde_json::to_string_pretty(&json).unwrap_or_default())?;
    Ok(comparison)
}

/// Write the timeline of `reports` into `folder`: each architecture's
/// effective file, then `trace.json` (a process per architecture). The
/// slices each architecture's process holds.
///
/// # Errors
/// `OutputError` for a file that could not be written.
pub fn write_trace(folder: &mut OutputFolder, reports: &[CostReport]) -> Result<Vec<usize>, OutputError> {
    for r in reports {
        folder.write_text(&format!("arch-{}.toml", r.arch.name), &r.arch.to_toml())?;
    }
    let (json, slices) = trace(reports);
    folder.write_text("trace.json", &serde_json::to_string(&json).unwrap_or_default())?;
    Ok(slices)
}
