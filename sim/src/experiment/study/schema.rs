//! The rows' schema: every column of `results.csv` (and field of
//! `results.jsonl`) with its type, unit and meaning, written beside the
//! rows as `schema.csv` so that a script needs no documentation to read
//! them.

use std::fmt::Write as _;

use crate::cost::report::unit_of;
use crate::render::RenderParam;

/// One column: name, type (`integer`, `number`, `text`, `boolean`), unit
/// (`-` for none) and meaning. An empty cell is a value that does not apply
/// to the row (or a skipped row's measurement).
pub type Column = (&'static str, &'static str, &'static str, &'static str);

/// Where a column is declared: here, or (a configuration's) as a render
/// parameter ([`PARAMS`](crate::render::PARAMS), by name), whose column, type, unit and meaning
/// it takes.
enum Declared {
    Own(&'static str, &'static str, &'static str, &'static str),
    Param(&'static str),
}

/// Every fixed column, in the order the rows hold them; the architecture
/// axes' columns (`arch_<key>_<unit>`) follow `arch_params`.
const DECLARED: &[Declared] = &[
    Declared::Own("config_index", "integer", "-", "the configuration's position in the sweep"),
    Declared::Own("arch_index", "integer", "-", "the architecture point's position in the sweep"),
    Declared::Own("scene", "text", "-", "the scene's name"),
    Declared::Param("algo"),
    Declared::Own(
        "family",
        "text",
        "-",
        "its family: first depth, second depth, midpoint and dual, silhouette map, shadow volumes",
    ),
    Declared::Param("bias"),
    Declared::Param("bias1"),
    Declared::Param("offset"),
    Declared::Param("virtual_samples"),
    Declared::Param("cull"),
    Declared::Param("depth"),
    Declared::Param("map"),
    Declared::Param("filter"),
    Declared::Own("arch", "text", "-", "the architecture point's name (- without architectures)"),
    Declared::Own("base_arch", "text", "-", "the architecture it was made from (- without architectures)"),
    Declared::Own("arch_params", "text", "-", "its axis assignments, key=value,… as the sweep file spells them"),
    Declared::Param("width"),
    Declared::Param("height"),
    Declared::Param("reference_rays"),
    Declared::Own("command", "text", "-", "the umbra render command that renders the row again"),
    Declared::Own("umbra_version", "text", "-", "the version that made the row"),
    Declared::Own("sweep_hash", "text", "-", "the sweep file's hash"),
    Declared::Own("status", "text", "-", "ok or skipped"),
    Declared::Own("reason", "text", "-", "why the row was skipped (empty when ok)"),
    Declared::Own("evaluated_px", "integer", "px", "pixels compared (facing the light)"),
    Declared::Own(
        "misclassified_percent",
        "number",
        "percent",
        "misclassified by the ½ verdict, of the evaluated pixels",
    ),
    Declared::Own("false_shadow_px", "integer", "px", "shadowed by the ½ verdict, lit in truth"),
    Declared::Own("false_light_px", "integer", "px", "lit by the ½ verdict, shadowed in truth"),
    Declared::Own(
        "aliasing_px",
        "integer",
        "px",
        "wrong because the taps straddle a true edge or miss the occluder: aliasing",
    ),
    Declared::Own("penumbra_px", "integer", "px", "a filter's own partial shade across a true edge: penumbra"),
    Declared::Own("acne_px", "integer", "px", "too dark from the receiver's own surface: acne"),
    Declared::Own(
        "terminator_acne_px",
        "integer",
        "px",
        "of the acne, near grazing beside a surface facing away: the terminator's",
    ),
    Declared::Own(
        "detachment_px",
        "integer",
        "px",
        "too light because only the bias moved the test past an occluder: detachment",
    ),
    Declared::Own("leaks_px", "integer", "px", "too light because the depth compared lies behind the receiver: leaks"),
    Declared::Own("aliasing_area_px", "number", "px", "the aliasing's summed shade difference"),
    Declared::Own("penumbra_area_px", "number", "px", "the penumbra's summed shade difference"),
    Declared::Own("acne_area_px", "number", "px", "the acne's summed excess shadow"),
    Declared::Own("detachment_area_px", "number", "px", "the detachment's summed missing shadow"),
    Declared::Own("leak_area_px", "number", "px", "the leaks' summed missing shadow"),
    Declared::Own(
        "artifact_percent",
        "number",
        "percent",
        "acne, detachment and leaks, of the evaluated pixels: what budgets bound",
    ),
    Declared::Own(
        "penumbra_width_p95_px",
        "number",
        "px",
        "95th percentile distance of penumbra pixels from the exact boundary",
    ),
    Declared::Own("mean_abs_error", "number", "shadow fraction", "mean |shadow fraction − true shadowed area|"),
    Declared::Own("rms_error", "number", "shadow fraction", "root mean square of the same"),
    Declared::Own("displacement_mean_px", "number", "px", "mean distance of the rendered boundary from the exact one"),
    Declared::Own("displacement_p95_px", "number", "px", "its 95th percentile"),
    Declared::Own(
        "footprint_x_texels_per_px",
        "number",
        "texels/px",
        "median map texels a pixel along x (below 1: magnified)",
    ),
    Declared::Own("footprint_y_texels_per_px", "number", "texels/px", "the same along y"),
    Declared::Own("virtual_sample_percent", "number", "percent", "lookups with virtual samples"),
    Declared::Own("light_cycles", "integer", "cycles", "the light pass (silhouette pass included)"),
    Declared::Own(
        "light_bottleneck",
        "text",
        "-",
        "what bounds the light pass: setup, raster, depth, shadow, shade, dram-bandwidth, dram-latency",
    ),
    Declared::Own("camera_cycles", "integer", "cycles", "the camera pass"),
    Declared::Own(
        "camera_shadow_cycles",
        "integer",
        "cycles",
        "the camera pass's shadow-unit cycles summed over tiles",
    ),
    Declared::Own("camera_bottleneck", "text", "-", "what bounds the camera pass"),
    Declared::Own("total_cycles", "integer", "cycles", "the frame: light pass then camera pass"),
    Declared::Own("clock_hertz", "number", "Hz", "the architecture's clock"),
    Declared::Own("frame_seconds", "number", "s", "the frame at the clock"),
    Declared::Own("frames_per_second", "number", "1/s", "frames a second at the clock"),
    Declared::Own("energy_joules", "number", "J", "the frame's energy"),
    Declared::Own("dram_achieved_bytes_per_second", "number", "B/s", "the frame's DRAM bytes over its time"),
    Declared::Own("dram_peak_bytes_per_second", "number", "B/s", "the DRAM's bandwidth"),
    Declared::Own(
        "dram_latency_ceiling_bytes_per_second",
        "number",
        "B/s",
        "requests in flight × burst / latency (Little's law)",
    ),
    Declared::Own("dram_map_write_bytes", "integer", "B", "map texels written by the light pass"),
    Declared::Own("dram_map_readback_bytes", "integer", "B", "depth read back by the light pass"),
    Declared::Own("dram_bin_bytes", "integer", "B", "bins and setup records of both passes"),
    Declared::Own("dram_camera_depth_bytes", "integer", "B", "camera visibility depth, when off chip"),
    Declared::Own("dram_map_requested_bytes", "integer", "B", "map bytes the shadow unit requested"),
    Declared::Own("dram_map_fetched_bytes", "integer", "B", "map bytes fetched through the map cache"),
    Declared::Own("dram_silhouette_bytes", "integer", "B", "silhouette points written and read"),
    Declared::Own("dram_volume_depth_bytes", "integer", "B", "scene depth read by shadow-volume fragments"),
    Declared::Own("dram_stencil_bytes", "integer", "B", "stencil read and written by shadow-volume fragments"),
    Declared::Own("total_dram_bytes", "integer", "B", "all DRAM traffic, map reads as fetched"),
    Declared::Own("on_chip_bytes", "integer", "B", "on-chip depth storage of the light pass"),
    Declared::Own(
        "light_culled_percent",
        "number",
        "percent",
        "light-pass triangle-tile pairs and blocks max-z culled",
    ),
    Declared::Own("camera_culled_percent", "number", "percent", "the same of the camera's visibility"),
    Declared::Own(
        "lookups_culled_per_px",
        "number",
        "1/px",
        "shadow lookups decided by the tiles' bounds a covered pixel",
    ),
    Declared::Own("map_bytes_per_px", "number", "B/px", "camera-pass map bytes a covered pixel"),
];

/// Every fixed column, in the order the rows hold them, each from its
/// one declaration.
#[must_use]
pub fn columns() -> Vec<Column> {
    DECLARED
        .iter()
        .filter_map(|d| match d {
            &Declared::Own(name, kind, unit, meaning) => Some((name, kind, unit, meaning)),
            Declared::Param(name) => {
                RenderParam::named(name).ok().map(|p| (p.column, p.kind.column_type(), p.unit, p.meaning))
            }
        })
        .collect()
}

/// The unit an architecture axis's column ends in, as the stats file
/// names it ([`unit_of`]); `-` for a key without one.
pub(crate) fn axis_unit(column: &str) -> &'static str {
    match unit_of(column) {
        "count" => "-",
        unit => unit,
    }
}

/// The schema of rows whose columns are `header`, as `schema.csv`
/// (`column,type,unit,meaning`): each fixed column from [`columns`], each
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
    let columns = columns();
    for h in header {
        match columns.iter().find(|c| c.0 == h) {
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
    for (name, kind, unit, meaning) in columns() {
        let _ = writeln!(s, "| `{name}` | {kind} | {unit} | {meaning} |");
    }
    s
}
