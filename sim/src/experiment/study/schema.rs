//! The rows' schema: every column of `results.csv` (and field of
//! `results.jsonl`) with its type, unit and meaning, written beside the
//! rows as `schema.csv` so that a script needs no documentation to read
//! them.

use std::fmt::Write as _;

use crate::cost::report::unit_of;

/// One column: name, type (`integer`, `number`, `text`, `boolean`), unit
/// (`-` for none) and meaning. An empty cell is a value that does not apply
/// to the row (or a skipped row's measurement).
pub type Column = (&'static str, &'static str, &'static str, &'static str);

/// Every fixed column, in the order the rows hold them; the architecture
/// axes' columns (`arch_<key>_<unit>`) follow `arch_params`.
pub const COLUMNS: &[Column] = &[
    ("config_index", "integer", "-", "the configuration's position in the sweep"),
    ("arch_index", "integer", "-", "the architecture point's position in the sweep"),
    ("scene", "text", "-", "the scene's name"),
    ("algorithm", "text", "-", "the algorithm as umbra render --algo spells it"),
    ("family", "text", "-", "its family: first depth, second depth, midpoint and dual, silhouette map, shadow volumes"),
    ("bias", "number", "depth", "the bias, a depth in [0, 1] (Reeves' Bias0 for a bias range)"),
    ("bias1", "number", "depth", "Reeves' Bias1, for a bias range (empty otherwise)"),
    ("offset", "number", "depth", "Weiskopf & Ertl's offset, for dual depth (empty otherwise)"),
    ("virtual_samples", "boolean", "-", "Wang & Molnar's virtual samples on (empty but for second depth)"),
    ("culling", "text", "-", "the light pass's culling per object class, as umbra render --cull takes it"),
    ("depth_format", "text", "-", "the map's depth format: d16, d24, f32"),
    ("map_side_texels", "integer", "texels", "the map's side"),
    ("filter_name", "text", "-", "the filter as umbra render --filter spells it"),
    ("arch", "text", "-", "the architecture point's name (- without architectures)"),
    ("base_arch", "text", "-", "the architecture it was made from (- without architectures)"),
    ("arch_params", "text", "-", "its axis assignments, key=value,… as the sweep file spells them"),
    ("image_width_px", "integer", "px", "the camera image's width"),
    ("image_height_px", "integer", "px", "the camera image's height"),
    ("reference_rays", "integer", "-", "reference rays a pixel side (n for n × n)"),
    ("command", "text", "-", "the umbra render command that renders the row again"),
    ("umbra_version", "text", "-", "the version that made the row"),
    ("sweep_hash", "text", "-", "the sweep file's hash"),
    ("status", "text", "-", "ok or skipped"),
    ("reason", "text", "-", "why the row was skipped (empty when ok)"),
    ("evaluated_px", "integer", "px", "pixels compared (facing the light)"),
    ("misclassified_percent", "number", "percent", "misclassified by the ½ verdict, of the evaluated pixels"),
    ("false_shadow_px", "integer", "px", "shadowed by the ½ verdict, lit in truth"),
    ("false_light_px", "integer", "px", "lit by the ½ verdict, shadowed in truth"),
    ("aliasing_px", "integer", "px", "wrong because the taps straddle a true edge or miss the occluder: aliasing"),
    ("penumbra_px", "integer", "px", "a filter's own partial shade across a true edge: penumbra"),
    ("acne_px", "integer", "px", "too dark from the receiver's own surface: acne"),
    ("terminator_acne_px", "integer", "px", "of the acne, near grazing beside a surface facing away: the terminator's"),
    ("detachment_px", "integer", "px", "too light because only the bias moved the test past an occluder: detachment"),
    ("leaks_px", "integer", "px", "too light because the depth compared lies behind the receiver: leaks"),
    ("aliasing_area_px", "number", "px", "the aliasing's summed shade difference"),
    ("penumbra_area_px", "number", "px", "the penumbra's summed shade difference"),
    ("acne_area_px", "number", "px", "the acne's summed excess shadow"),
    ("detachment_area_px", "number", "px", "the detachment's summed missing shadow"),
    ("leak_area_px", "number", "px", "the leaks' summed missing shadow"),
    (
        "artifact_percent",
        "number",
        "percent",
        "acne, detachment and leaks, of the evaluated pixels: what budgets bound",
    ),
    ("penumbra_width_p95_px", "number", "px", "95th percentile distance of penumbra pixels from the exact boundary"),
    ("mean_abs_error", "number", "shadow fraction", "mean |shadow fraction − true shadowed area|"),
    ("rms_error", "number", "shadow fraction", "root mean square of the same"),
    ("displacement_mean_px", "number", "px", "mean distance of the rendered boundary from the exact one"),
    ("displacement_p95_px", "number", "px", "its 95th percentile"),
    ("footprint_x_texels_per_px", "number", "texels/px", "median map texels a pixel along x (below 1: magnified)"),
    ("footprint_y_texels_per_px", "number", "texels/px", "the same along y"),
    ("virtual_sample_percent", "number", "percent", "lookups with virtual samples"),
    ("light_cycles", "integer", "cycles", "the light pass (silhouette pass included)"),
    (
        "light_bottleneck",
        "text",
        "-",
        "what bounds the light pass: setup, raster, depth, shadow, shade, dram-bandwidth, dram-latency",
    ),
    ("camera_cycles", "integer", "cycles", "the camera pass"),
    ("camera_shadow_cycles", "integer", "cycles", "the camera pass's shadow-unit cycles summed over tiles"),
    ("camera_bottleneck", "text", "-", "what bounds the camera pass"),
    ("total_cycles", "integer", "cycles", "the frame: light pass then camera pass"),
    ("clock_hertz", "number", "Hz", "the architecture's clock"),
    ("frame_seconds", "number", "s", "the frame at the clock"),
    ("frames_per_second", "number", "1/s", "frames a second at the clock"),
    ("energy_joules", "number", "J", "the frame's energy"),
    ("dram_achieved_bytes_per_second", "number", "B/s", "the frame's DRAM bytes over its time"),
    ("dram_peak_bytes_per_second", "number", "B/s", "the DRAM's bandwidth"),
    ("dram_latency_ceiling_bytes_per_second", "number", "B/s", "requests in flight × burst / latency (Little's law)"),
    ("dram_map_write_bytes", "integer", "B", "map texels written by the light pass"),
    ("dram_map_readback_bytes", "integer", "B", "depth read back by the light pass"),
    ("dram_bin_bytes", "integer", "B", "bins and setup records of both passes"),
    ("dram_camera_depth_bytes", "integer", "B", "camera visibility depth, when off chip"),
    ("dram_map_requested_bytes", "integer", "B", "map bytes the shadow unit requested"),
    ("dram_map_fetched_bytes", "integer", "B", "map bytes fetched through the map cache"),
    ("dram_silhouette_bytes", "integer", "B", "silhouette points written and read"),
    ("dram_volume_depth_bytes", "integer", "B", "scene depth read by shadow-volume fragments"),
    ("dram_stencil_bytes", "integer", "B", "stencil read and written by shadow-volume fragments"),
    ("total_dram_bytes", "integer", "B", "all DRAM traffic, map reads as fetched"),
    ("on_chip_bytes", "integer", "B", "on-chip depth storage of the light pass"),
    ("light_culled_percent", "number", "percent", "light-pass triangle-tile pairs and blocks max-z culled"),
    ("camera_culled_percent", "number", "percent", "the same of the camera's visibility"),
    ("lookups_culled_per_px", "number", "1/px", "shadow lookups decided by the tiles' bounds a covered pixel"),
    ("map_bytes_per_px", "number", "B/px", "camera-pass map bytes a covered pixel"),
];

/// The unit an architecture axis's column ends in, as the stats file
/// names it ([`unit_of`]); `-` for a key without one.
pub(crate) fn axis_unit(column: &str) -> &'static str {
    match unit_of(column) {
        "count" => "-",
        unit => unit,
    }
}

/// The schema of rows whose columns are `header`, as `schema.csv`
/// (`column,type,unit,meaning`): each fixed column from [`COLUMNS`], each
/// architecture axis's (a name starting `arch_` not in the table) as a
/// number in the SI unit its name ends in. A column that is neither has
/// an empty meaning.
#[must_use]
pub fn schema_csv(header: &[String]) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut row = |cells: [&str; 4]| {
        // Writing to memory cannot fail.
        let _ = w.write_record(cells);
    };
    row(["column", "type", "unit", "meaning"]);
    for h in header {
        match COLUMNS.iter().find(|c| c.0 == h) {
            Some(c) => row([c.0, c.1, c.2, c.3]),
            None if h.starts_with("arch_") => {
                let meaning = format!("the architecture axis {}, in SI base units (a flag or text as it is)", &h[5..]);
                row([h, "number", axis_unit(h), &meaning]);
            }
            None => row([h, "text", "-", ""]),
        }
    }
    String::from_utf8_lossy(&w.into_inner().unwrap_or_default()).into_owned()
}

/// The fixed columns as a Markdown table.
#[must_use]
pub fn markdown() -> String {
    let mut s = String::from("| column | type | unit | meaning |\n|---|---|---|---|\n");
    for (name, kind, unit, meaning) in COLUMNS {
        let _ = writeln!(s, "| `{name}` | {kind} | {unit} | {meaning} |");
    }
    s
}
