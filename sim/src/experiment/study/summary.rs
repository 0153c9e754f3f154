//! The study's outputs: the results table, the summary an architect reads,
//! and the plots.

use super::rank::{cheapest, keys, objectives, one_clock};
use super::{Manifest, Row, RowCost, StudyError, distinct, jsonl, loosest, plot, sort_rows};
use crate::experiment::study::budget::Budget;
use crate::experiment::study::objective::{CostLimits, Costs};
use crate::output::folder::OutputFolder;
use crate::output::markdown::escape;
use crate::output::table::{Align, Table};
use std::fmt::Write as _;

/// Write `results.jsonl`, `results.csv`, the Pareto plots per scene and
/// `summary.md` for a whole run's rows into `folder` (whose manifest,
/// written when it is finished, carries `manifest`).
///
/// # Errors
/// See [`StudyError`].
pub(crate) fn write_outputs(folder: &mut OutputFolder, rows: &[Row], manifest: &Manifest) -> Result<(), StudyError> {
    let mut rows = rows.to_vec();
    sort_rows(&mut rows);
    folder.write_text("results.jsonl", &jsonl(&rows))?;
    let (table, header) = table(&rows);
    folder.write_text("results.csv", &table)?;
    folder.write_text("schema.csv", &super::schema::schema_csv(&header))?;
    let scenes = scenes_of(&rows);
    let slugs: Vec<String> = scenes.iter().map(|s| slug(s)).collect();
    for (k, s) in slugs.iter().enumerate() {
        if let Some(j) = slugs[..k].iter().position(|t| t == s) {
            return Err(StudyError::Plot {
                path: folder.dir().join(format!("pareto-{s}-time.svg")),
                problem: format!("scenes `{}` and `{}` would share this file name", scenes[j], scenes[k]),
            });
        }
    }
    for (scene, name) in scenes.iter().zip(&slugs) {
        let mine: Vec<&Row> = rows.iter().filter(|r| &r.config.scene == scene).collect();
        plot::pareto(folder, name, &mine, manifest)?;
        plot::arch_axes(folder, name, &mine, manifest)?;
    }
    folder.write_text("summary.md", &summary(&rows, manifest))?;
    Ok(())
}

/// A row's leaves, `(field name, value)`, in order: blocks flattened, each
/// field name unique and carrying its unit; absent values empty.
fn leaves(v: &serde_json::Value, key: &str, out: &mut Vec<(String, String)>) {
    match v {
        serde_json::Value::Object(m) => m.iter().for_each(|(k, v)| leaves(v, k, out)),
        serde_json::Value::Null => out.push((key.to_owned(), String::new())),
        serde_json::Value::String(s) => out.push((key.to_owned(), s.clone())),
        other => out.push((key.to_owned(), other.to_string())),
    }
}

/// The rows flat as `results.csv` holds them, and the header: one column
/// per field of a row with every block (a skipped row's metric and cost
/// columns empty).
#[must_use]
pub fn table(rows: &[Row]) -> (String, Vec<String>) {
    let flat = |r: &Row| {
        let mut cells = Vec::new();
        // A Row holds only strings, numbers, booleans and options: it always serialises.
        leaves(&serde_json::to_value(r).unwrap_or_default(), "", &mut cells);
        cells
    };
    let Some(first) = rows.first() else { return (String::new(), Vec::new()) };
    let template = Row { metrics: Some(super::RowMetrics::default()), cost: Some(RowCost::default()), ..first.clone() };
    let header: Vec<String> = flat(&template).into_iter().map(|c| c.0).collect();
    let mut t = Table::new(&header.iter().map(|h| (h.as_str(), Align::Left)).collect::<Vec<_>>());
    for r in rows {
        let cells = flat(r);
        t.row(header.iter().map(|h| cells.iter().find(|c| &c.0 == h).map_or("", |c| c.1.as_str())));
    }
    (t.csv(), header)
}

/// A scene name as it may appear in a file name: letters, digits, `-` and
/// `_` kept, anything else (a `/`, a `.`) made `_`, so that no name writes
/// outside the output folder or changes a file's extension.
#[must_use]
pub(crate) fn slug(name: &str) -> String {
    let s: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
    if s.is_empty() { "scene".to_owned() } else { s }
}

/// Scene names in order of first appearance.
pub(super) fn scenes_of(rows: &[Row]) -> Vec<String> {
    distinct(rows.iter().map(|r| r.config.scene.clone()))
}

/// `summary.md`: per scene, the cheapest configuration under each budget,
/// overall (in cycles, bytes and energy) and per algorithm family; budgets
/// below one pixel flagged; ties and how they were broken; where the
/// winner changes with image size and map size; and which architecture
/// parameter moves the bottleneck. Then every skipped row's reason.
#[must_use]
pub fn summary(rows: &[Row], manifest: &Manifest) -> String {
    let mut s = String::new();
    let configs = rows.iter().map(|r| r.config_index).collect::<std::collections::BTreeSet<_>>().len();
    let skipped: Vec<&Row> = rows.iter().filter(|r| r.metrics.is_none()).collect();
    let _ = writeln!(s, "# Umbra study `{}`: what wins where, and why\n", manifest.sweep);
    let _ = writeln!(
        s,
        "{}; sweep {} ({}). {} rows ({configs} configurations × architectures), {} skipped. A budget bounds \
         artifacts — acne, detachment, leaks and clipped occluders: wrong pixels (shade off the area-averaged \
         reference by more than 0.1, or on the wrong side of ½) judged by what the shadow unit compared — or the \
         measure it names, in percent of the pixels facing the light; aliasing and a filter's penumbra are not \
         artifacts. Time: \
         the frame, light pass then camera pass, in each architecture's per-tile timing model at its clock; {}; \
         bytes: all DRAM traffic, map reads as fetched through the map cache; energy: DRAM, buffers, caches and \
         units. Each cell names the architecture point that won.\n",
        manifest.umbra_version,
        manifest.sweep,
        manifest.sweep_hash,
        rows.len(),
        skipped.len(),
        match one_clock(&rows.iter().collect::<Vec<_>>()) {
            Some(clock) => format!("every architecture runs at {} MHz, so cycles rank as time does", clock / 1e6),
            None => "the architectures' clocks differ, so time ranks, not cycles".to_owned(),
        }
    );
    for scene in scenes_of(rows) {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.config.scene == scene).collect();
        let _ = writeln!(s, "## {}\n", escape(&scene));
        scene_summary(&mut s, &mine, manifest);
    }
    if !skipped.is_empty() {
        let mut t = Table::new(&[("row", Align::Right), ("configuration", Align::Left), ("reason", Align::Left)]);
        for r in skipped {
            t.row([r.config_index.to_string(), format!("{} {}", r.config.scene, r.label()), r.reason.clone()]);
        }
        let _ = write!(s, "## Skipped\n\n{}", t.markdown());
    }
    s
}

fn scene_summary(s: &mut String, rows: &[&Row], manifest: &Manifest) {
    let budgets = &manifest.budgets[..];
    // The smallest image of the sweep sets the budget a pixel is.
    let pixel = rows.iter().filter_map(|r| r.metrics.map(|m| m.evaluated_px)).filter(|&n| n > 0).min().map(|n| {
        #[allow(clippy::cast_precision_loss, reason = "a pixel count")]
        let p = 100.0 / n as f64;
        p
    });
    let keys = keys(rows);
    let (l, r) = (Align::Left, Align::Right);
    let mut t = Table::new(&[
        ("budget", r),
        ("cost", l),
        ("cheapest", l),
        ("cost", r),
        ("artifacts %", r),
        ("misclassified %", r),
    ]);
    for budget in budgets {
        let flag = if pixel.is_some_and(|p| budget.percent < p) { " (below one pixel)" } else { "" };
        for key in keys {
            let cells = match cheapest(rows, budget, key) {
                Some((r, ties)) => {
                    let m = r.metrics.unwrap_or_default();
                    let tie = if ties > 1 { format!(" ({ties} tie; the first in sweep order)") } else { String::new() };
                    [
                        format!("{}{tie}", r.label()),
                        r.cost.as_ref().map_or_else(String::new, |c| (key.show)((key.value)(c))),
                        format!("{:.4}", m.artifact_percent),
                        format!("{:.4}", m.misclassified_percent),
                    ]
                }
                None => ["none meets it", "–", "–", "–"].map(str::to_owned),
            };
            t.row([format!("{}{flag}", budget.short()), key.name.to_owned()].into_iter().chain(cells));
        }
    }
    s.push_str(&t.markdown());
    if let Some(p) = pixel {
        let _ = writeln!(
            s,
            "\nOne pixel is {p:.4} % of those evaluated at the sweep's smallest image: a budget below it is met only \
             by a configuration with no artifact at all.\n"
        );
    }
    best_per_objective(s, rows, budgets, &manifest.cost_limits);
    let families = distinct(rows.iter().map(|r| r.config.family));
    for key in keys {
        let mut columns = vec![("family".to_owned(), Align::Left)];
        columns.extend(budgets.iter().map(|b| (b.short(), Align::Left)));
        let mut t = Table::new(&columns);
        for f in &families {
            let fam: Vec<&Row> = rows.iter().copied().filter(|r| r.config.family == *f).collect();
            let cells = budgets.iter().map(|b| {
                cheapest(&fam, b, key).map_or_else(
                    || "–".to_owned(),
                    |(r, _)| {
                        let cost = r.cost.as_ref().map_or_else(String::new, |c| (key.show)((key.value)(c)));
                        format!("{} ({cost})", r.label())
                    },
                )
            });
            t.row([f.to_string()].into_iter().chain(cells));
        }
        let _ = writeln!(s, "Cheapest per algorithm family in {}:\n\n{}", key.name, t.markdown());
    }
    crossovers(s, rows, budgets);
    bottlenecks(s, rows, budgets);
}

/// The best row per objective under each budget and within the cost
/// limits, with why: its time, energy and area against the fastest
/// row's.
fn best_per_objective(s: &mut String, rows: &[&Row], budgets: &[Budget], limits: &CostLimits) {
    let within = |c: &RowCost| {
        let costs = Costs {
            cycles: 0.0,
            seconds: c.frame_seconds,
            joules: c.energy_joules,
            square_metres: c.area_square_metres,
        };
        limits.exceeded(&costs).is_empty()
    };
    let rows: Vec<&Row> = rows.iter().copied().filter(|r| r.cost.as_ref().is_none_or(within)).collect();
    let rows = &rows[..];
    let objectives = objectives(rows);
    let (l, r) = (Align::Left, Align::Right);
    let mut t = Table::new(&[
        ("budget", r),
        ("objective", l),
        ("best", l),
        ("time (µs)", r),
        ("energy (µJ)", r),
        ("area (mm²)", r),
        ("why", l),
    ]);
    let ratio = |a: f64, b: f64| if b > 0.0 { format!("{:.2}×", a / b) } else { "–".to_owned() };
    for budget in budgets {
        let fastest = cheapest(rows, budget, objectives[0]).and_then(|(r, _)| Some((r, r.cost.as_ref()?)));
        for key in objectives {
            let Some((best, c)) = cheapest(rows, budget, key).and_then(|(r, _)| Some((r, r.cost.as_ref()?))) else {
                t.row([budget.short(), key.name.to_owned(), "none meets it".to_owned()]);
                continue;
            };
            let why = match fastest {
                Some((f, _)) if f.config_index == best.config_index && f.arch_index == best.arch_index => {
                    "the fastest too".to_owned()
                }
                Some((f, fc)) => format!(
                    "least {}: {} of the fastest's ({}), at {} its time, {} its energy, {} its area",
                    key.name,
                    ratio((key.value)(c), (key.value)(fc)),
                    f.label(),
                    ratio(c.frame_seconds, fc.frame_seconds),
                    ratio(c.energy_joules, fc.energy_joules),
                    ratio(c.area_square_metres, fc.area_square_metres)
                ),
                None => String::new(),
            };
            t.row([
                budget.short(),
                key.name.to_owned(),
                best.label(),
                format!("{:.3}", c.frame_seconds * 1e6),
                format!("{:.3}", c.energy_joules * 1e6),
                format!("{:.4}", c.area_square_metres * 1e6),
                why,
            ]);
        }
    }
    let _ = writeln!(
        s,
        "Best per objective (energy: dynamic and static; area: the silicon of the units each configuration \
         uses at its architecture's technology){}, each against the fastest:\n\n{}",
        if limits.any() { format!(" within {}", limits.words()) } else { String::new() },
        t.markdown()
    );
}

/// Where the winner (the fastest under the loosest budget) changes
/// with image size and map size, as measured; and, from the winner's and
/// the cheapest shadow-volume configuration's split of cycles into a light
/// pass (fixed) and a camera pass (per pixel), the image size at which
/// they cross.
fn crossovers(s: &mut String, rows: &[&Row], budgets: &[Budget]) {
    let Some(loose) = loosest(budgets) else { return };
    let fastest = keys(rows)[0];
    let by = |axis: &str, value: &dyn Fn(&Row) -> String| {
        let values = distinct(rows.iter().map(|r| value(r)));
        if values.len() < 2 {
            return String::new();
        }
        let mut out = format!("Winner within {} by {axis}:", loose.short());
        for v in &values {
            let sub: Vec<&Row> = rows.iter().copied().filter(|r| value(r) == *v).collect();
            let w =
                cheapest(&sub, &loose, fastest).map_or_else(|| "none".to_owned(), |(r, _)| r.config.family.to_string());
            let _ = write!(out, " {v}: {w};");
        }
        out.pop();
        out + ".\n\n"
    };
    s.push_str(&by("image size", &|r| format!("{}×{}", r.config.image_width_px, r.config.image_height_px)));
    s.push_str(&by("map side", &|r| format!("{}²", r.config.map_side_texels)));
    let volumes: Vec<&Row> = rows.iter().copied().filter(|r| r.config.algorithm == "volumes").collect();
    let maps: Vec<&Row> = rows.iter().copied().filter(|r| r.config.algorithm != "volumes").collect();
    if let (Some((v, _)), Some((m, _))) = (cheapest(&volumes, &loose, fastest), cheapest(&maps, &loose, fastest)) {
        let (Some(vc), Some(mc)) = (&v.cost, &m.cost) else { return };
        // Cycles where one clock runs every row, else nanoseconds.
        let one = one_clock(rows).is_some();
        #[allow(clippy::cast_precision_loss, reason = "cycle counts far below 2^53")]
        let time = |c: &RowCost, cycles: u64| if one { cycles as f64 } else { cycles as f64 / c.clock_hertz * 1e9 };
        let unit = if one { "cycles" } else { "ns" };
        let px = f64::from(v.config.image_width_px) * f64::from(v.config.image_height_px);
        let (pixels, v_px, m_px, m_fixed) =
            (px, time(vc, vc.total_cycles) / px, time(mc, mc.camera_cycles) / px, time(mc, mc.light_cycles));
        let _ = write!(
            s,
            "Shadow volumes against maps within {}: the cheapest volumes take {:.2} {unit} a pixel \
             (overdraw × stencil work), the cheapest map configuration ({}) {:.2} a pixel plus {:.0} for its light \
             pass. ",
            loose.short(),
            v_px,
            m.label(),
            m_px,
            m_fixed
        );
        if v_px > m_px {
            let cross = m_fixed / (v_px - m_px);
            let side = (cross / pixels).sqrt();
            let _ = writeln!(
                s,
                "They cross at about {:.0} pixels ({:.0}×{:.0} at this aspect): volumes are the cheaper below it, \
                 maps above.\n",
                cross,
                side * f64::from(v.config.image_width_px),
                side * f64::from(v.config.image_height_px)
            );
        } else {
            let _ = writeln!(s, "Volumes cost no more a pixel, so they stay the cheaper at every image size.\n");
        }
    }
}

/// For each configuration that wins (the fastest within the
/// loosest budget) at some architecture parameter point, its bottlenecks
/// at every point: where a parameter moves one, this shows it.
fn bottlenecks(s: &mut String, rows: &[&Row], budgets: &[Budget]) {
    let Some(loose) = loosest(budgets) else { return };
    let fastest = keys(rows)[0];
    let points = distinct(rows.iter().map(|r| r.config.arch_point()));
    if points.iter().all(|a| a.1.is_empty()) {
        return;
    }
    let at = |r: &Row, p: (&str, &str)| r.config.arch_point() == p;
    let mut winners: Vec<usize> = Vec::new();
    for &p in &points {
        let sub: Vec<&Row> = rows.iter().copied().filter(|r| at(r, p)).collect();
        if let Some((w, _)) = cheapest(&sub, &loose, fastest)
            && !winners.contains(&w.config_index)
        {
            winners.push(w.config_index);
        }
    }
    let _ = writeln!(
        s,
        "Bottlenecks (light pass / camera pass) of each configuration that wins within {} at some \
         architecture point, at every point:\n",
        loose.short()
    );
    let (l, r) = (Align::Left, Align::Right);
    let mut t = Table::new(&[
        ("configuration", l),
        ("architecture", l),
        ("parameters", l),
        ("cycles", r),
        ("time (µs)", r),
        ("DRAM achieved (GB/s)", r),
        ("DRAM latency ceiling (GB/s)", r),
        ("light pass", l),
        ("camera pass", l),
    ]);
    for w in winners {
        let mine: Vec<&Row> = rows.iter().copied().filter(|r| r.config_index == w).collect();
        let mut seen = Vec::new();
        for &p in &points {
            if let Some(c) = mine.iter().find(|r| at(r, p)).and_then(|r| Some((r, r.cost.as_ref()?))) {
                let (r, c) = c;
                t.row([
                    r.render_label(),
                    p.0.to_string(),
                    p.1.to_string(),
                    c.total_cycles.to_string(),
                    format!("{:.3}", c.frame_seconds * 1e6),
                    format!("{:.1}", c.dram_achieved_bytes_per_second / 1e9),
                    format!("{:.1}", c.dram_latency_ceiling_bytes_per_second / 1e9),
                    c.light_bottleneck.to_string(),
                    c.camera_bottleneck.to_string(),
                ]);
                seen.push((c.light_bottleneck, c.camera_bottleneck));
            }
        }
        seen.dedup();
        if seen.len() > 1
            && let Some(r) = mine.first()
        {
            t.row([format!("{}: the parameters move its bottleneck", r.render_label())]);
        }
    }
    s.push_str(&t.markdown());
    let _ = writeln!(s);
}
