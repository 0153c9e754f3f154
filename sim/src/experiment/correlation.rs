//! Correlation with published hardware, as simulators are judged: the frame
//! rates Weiskopf & Ertl (2003, §6, Table 1) measured on an ATI Radeon 9700
//! for a 13 284-triangle factory scene at a 1100² viewport, against what
//! the timing model predicts for the bundled `r300` architecture and the
//! bundled `factory` scene.
//!
//! Frame rates depend on the host, the driver and the shading programs,
//! which the model does not describe, so the comparison is of ratios: each
//! cell's frame rate over the frame rate without shadows, as published and
//! as predicted.

use std::fmt::Write as _;

use serde::Serialize;
use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

use crate::cost::arch::Arch;
use crate::io::limits::Limits;
use crate::render::{Algorithm, Culling, RenderConfig, RenderError, cost, cost_unshadowed};
use crate::world::scene::Scene;

/// Their frame rate without shadows (Table 1, first row).
pub const NO_SHADOW_FPS: f64 = 167.5;

/// The map sides of Table 1's columns.
pub const MAPS: [u32; 2] = [256, 2048];

/// Table 1's rows: the filter and the published frame rates for constant
/// bias at 256² and 2048², then midpoint / dual at 256² and 2048².
pub const TABLE_1: [(&str, Filter, [f64; 4]); 3] = [
    ("no filtering", Filter::Point, [106.2, 69.1, 85.3, 30.6]),
    ("bilinear", Filter::Bilinear, [44.8, 36.6, 40.6, 21.9]),
    // Their 4×4 jitter matrix: sixteen samples a pixel, as a 4×4 box takes.
    ("4×4", Filter::Box { size: 4 }, [27.2, 23.9, 25.5, 16.6]),
];

/// One cell of Table 1.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// The filter row.
    pub filter: &'static str,
    /// `constant bias` or `midpoint / dual`.
    pub method: &'static str,
    /// Map side.
    pub map: u32,
    /// Their frame rate.
    pub published_fps: f64,
    /// Their frame rate over their no-shadow frame rate.
    pub published_ratio: f64,
    /// The model's frame rate.
    pub predicted_fps: f64,
    /// The model's frame rate over its no-shadow frame rate.
    pub predicted_ratio: f64,
}

impl Cell {
    /// The predicted ratio's relative error against the published one.
    #[must_use]
    pub fn error(&self) -> f64 {
        self.predicted_ratio / self.published_ratio - 1.0
    }
}

/// The whole comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Correlation {
    /// The architecture's name.
    pub arch: String,
    /// The model's frame rate without shadows.
    pub no_shadow_fps: f64,
    /// Every cell, row by row, columns as in Table 1.
    pub cells: Vec<Cell>,
}

/// The methods of Table 1's columns: constant bias is Williams' first
/// depth; midpoint and dual depth cost the same (their §6), both needing
/// the second depth.
fn method(dual: bool) -> (&'static str, Algorithm) {
    if dual { ("midpoint / dual", Algorithm::Dual { offset: 0.01 }) } else { ("constant bias", Algorithm::First) }
}

/// Predict every cell of Table 1 for `scene` on `arch` at the scene's image.
///
/// # Errors
/// See [`RenderError`].
pub fn run(scene: &Scene, arch: &Arch, limits: &Limits) -> Result<Correlation, RenderError> {
    let [width, height] = scene.image;
    let base = cost_unshadowed(scene, (width, height), arch, limits)?.fps;
    let mut cells = Vec::new();
    for (filter_name, filter, published) in TABLE_1 {
        for (column, &fps) in published.iter().enumerate() {
            let (name, algorithm) = method(column >= 2);
            let map = MAPS[column % 2];
            let cfg = RenderConfig {
                algorithm,
                // A one-channel floating-point texture, as they used.
                format: DepthFormatKind::F32,
                map_size: map,
                filter,
                bias: if column >= 2 { 0.0 } else { 0.002 },
                virtual_samples: false,
                width,
                height,
                reference_rays: 1,
                culling: Culling::ALGORITHM,
            };
            let predicted = cost(scene, &cfg, arch, limits)?.fps;
            cells.push(Cell {
                filter: filter_name,
                method: name,
                map,
                published_fps: fps,
                published_ratio: fps / NO_SHADOW_FPS,
                predicted_fps: predicted,
                predicted_ratio: predicted / base,
            });
        }
    }
    Ok(Correlation { arch: arch.name.clone(), no_shadow_fps: base, cells })
}

impl Correlation {
    /// The comparison as a Markdown table: published and predicted ratios
    /// per cell, and the error.
    #[must_use]
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Frame rate over the no-shadow frame rate, Weiskopf & Ertl 2003 Table 1 (Radeon 9700, published {NO_SHADOW_FPS} fps without shadows) against `{}` (predicted {:.1} fps without shadows):\n",
            self.arch, self.no_shadow_fps
        );
        let _ = writeln!(s, "| filter | method | map | published | predicted | error |");
        let _ = writeln!(s, "|---|---|---:|---:|---:|---:|");
        for c in &self.cells {
            let _ = writeln!(
                s,
                "| {} | {} | {}² | {:.3} | {:.3} | {:+.0} % |",
                c.filter,
                c.method,
                c.map,
                c.published_ratio,
                c.predicted_ratio,
                100.0 * c.error()
            );
        }
        let within = self.cells.iter().filter(|c| c.error().abs() <= 0.25).count();
        let _ = writeln!(s, "\n{within} of {} cells within 25 %.", self.cells.len());
        s
    }
}
