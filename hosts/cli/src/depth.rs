//! `umbra depth`: one light pass over a mesh or a scene, its maps as arrays and previews, and its tiles.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use umbra_sim::output::table::{Align, Table};

use crate::say::{Style, say};
use anyhow::{Context, Result};
use clap::ValueEnum;
use umbra_core::{CullMode, DepthFormatKind, DepthUnit, LightPassConfig, RasterConfig};
use umbra_sim::base::counters::Counters;
use umbra_sim::glam::Mat4;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::{Claim, OutputFolder, RunKind};
use umbra_sim::output::formats::{RawMap, write_npy};
use umbra_sim::output::picture::write_preview;
use umbra_sim::pass::light::{EmptyMap, RawMaps};
use umbra_sim::render::files::map_title;
use umbra_sim::world::scene::{Scene, parse_matrix};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(super) enum Unit {
    Single,
    Dual,
}

#[derive(clap::Args, Debug)]
pub(super) struct DepthArgs {
    /// An OBJ mesh to render (instead of the default scene).
    #[arg(long)]
    pub(super) mesh: Option<PathBuf>,
    /// The view-projection matrix: a row-major 4×4 JSON array, inline or in a
    /// file. Clip = M · (x, y, z, 1)ᵀ; depth z/w in [0, 1] (near 0, far 1);
    /// NDC y up, map row 0 at NDC y = +1. Default: the scene's light, or for
    /// a mesh a spot light that frames it.
    #[arg(long)]
    pub(super) matrix: Option<String>,
    /// Map width and height in texels.
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(1..), alias = "size")]
    pub(super) map: u32,
    /// Depth format: d16, d24, f32.
    #[arg(long, default_value = "d24", alias = "format")]
    pub(super) depth: DepthFormatKind,
    /// Facing to discard: none, back, front.
    #[arg(long, default_value = "none")]
    pub(super) cull: CullMode,
    /// Depth unit: nearest only, or nearest and second nearest.
    #[arg(long, value_enum, default_value_t = Unit::Dual)]
    pub(super) unit: Unit,
    /// Tile side in texels (power of two, 8..=128).
    #[arg(long, default_value_t = RasterConfig::DEFAULT_TILE_SIZE)]
    pub(super) tile: u32,
    /// Subpixel bits of the vertex snap (1..=8).
    #[arg(long, default_value_t = RasterConfig::DEFAULT_SUBPIXEL_BITS)]
    pub(super) subpixel_bits: u32,
    /// Turn per-tile max-z culling off.
    #[arg(long)]
    pub(super) no_max_z_cull: bool,
    /// Output folder.
    #[arg(long, default_value = "out/depth")]
    pub(super) out: PathBuf,
    /// Replace another command's results in --out deliberately.
    #[arg(long, help = crate::REPLACE_HELP)]
    pub(super) replace: bool,
}

impl Default for DepthArgs {
    fn default() -> Self {
        Self {
            mesh: None,
            matrix: None,
            map: 512,
            depth: DepthFormatKind::D24,
            cull: CullMode::None,
            unit: Unit::Dual,
            tile: RasterConfig::DEFAULT_TILE_SIZE,
            subpixel_bits: RasterConfig::DEFAULT_SUBPIXEL_BITS,
            no_max_z_cull: false,
            out: PathBuf::from("out/depth"),
            replace: false,
        }
    }
}

/// Read the `--matrix` argument: a file holding the JSON (a regular file
/// within `limits`) when one exists at that path, else inline JSON.
fn read_matrix(arg: &str, limits: &Limits) -> Result<Mat4> {
    let path = Path::new(arg);
    if path.exists() {
        let bytes = limits.read_file(path).with_context(|| format!("--matrix: cannot read file `{arg}`"))?;
        let text = String::from_utf8(bytes).with_context(|| format!("--matrix: file `{arg}` is not UTF-8 text"))?;
        return parse_matrix(&text).with_context(|| format!("--matrix: file `{arg}`"));
    }
    parse_matrix(arg).with_context(|| format!("--matrix `{arg}`: no such file, and not a 4×4 JSON array"))
}

pub(super) fn depth(args: &DepthArgs, limits: &Limits, style: Style) -> Result<()> {
    limits.check_map(args.map).with_context(|| format!("--map {}", args.map))?;
    let scene = match &args.mesh {
        Some(path) => Scene::of_obj(path, limits)?,
        None => Scene::default_scene(),
    };
    let matrix = match &args.matrix {
        Some(m) => read_matrix(m, limits)?,
        None => scene.light().view_projection(),
    };
    let raster = RasterConfig::new(args.map, args.map, args.tile, args.subpixel_bits)?;
    let unit = match args.unit {
        Unit::Single => DepthUnit::Single,
        Unit::Dual => DepthUnit::Dual,
    };
    let (format, cull) = (args.depth, args.cull);
    let config = LightPassConfig { raster, unit, max_z_cull: !args.no_max_z_cull };
    let draws = scene.draws(matrix, cull);
    let (maps, counters) = RawMaps::render(config, format, &draws, Counters::new(&raster))?;
    let view = if args.matrix.is_some() { "--matrix" } else { "lights[0]" };
    EmptyMap::check(&counters.totals, view, None)?;
    let mut folder = OutputFolder::create(&args.out, Claim::new(RunKind::Depth).replacing(args.replace))?;

    write_maps(&mut folder, &maps, &scene)?;
    folder.write_text("tiles.md", &tile_report(&scene, &maps, &counters, args))?;
    folder.write_text("counters.json", &serde_json::to_string_pretty(&counters.totals)?)?;
    let (manifest, replaced) = folder.finish_replacing(None)?;
    if style == Style::Brief {
        crate::say::wrapped(&format!("light pass of `{}`: {}", scene.name, describe(&maps)))?;
    } else {
        say!("{}", summary(&maps, &counters, scene.ignored()));
    }
    crate::say::wrote_in(style, &args.out, &manifest, &replaced)
}

fn write_maps(folder: &mut OutputFolder, maps: &RawMaps, scene: &Scene) -> Result<()> {
    let (w, h) = (maps.maps.config.raster.width(), maps.maps.config.raster.height());
    let detail = format!("{}: {}", scene.name, describe(maps));
    for (name, data) in [("z1", &maps.maps.z1), ("z2", &maps.maps.z2)] {
        if data.is_empty() {
            continue;
        }
        let map = RawMap { format: maps.format, width: w, height: h, raw: data };
        write_npy(folder, &format!("{name}.npy"), &map)?;
        write_preview(folder, &format!("{name}.png"), &map, (&map_title(name), &detail))?;
    }
    Ok(())
}

/// The configuration of a pass in one line.
fn describe(maps: &RawMaps) -> String {
    let cfg = maps.maps.config;
    let r = cfg.raster;
    let (across, down) = r.tiles();
    format!(
        "{}×{} texels, {} depth, {:?} unit, {}×{} tiles of {} px, {} subpixel bits, max-z culling {}",
        r.width(),
        r.height(),
        maps.format.name(),
        cfg.unit,
        across,
        down,
        r.tile_size(),
        r.subpixel_bits(),
        if cfg.max_z_cull { "on" } else { "off" }
    )
}

/// Totals and a grid of fragments per tile, for the terminal.
fn summary(maps: &RawMaps, c: &Counters, ignored: umbra_sim::world::mesh::Ignored) -> String {
    let t = &c.totals;
    let raster = maps.maps.config.raster;
    let across = raster.tiles().0;
    let mut s = String::new();
    let _ = writeln!(s, "light pass {}", describe(maps));
    if !ignored.is_empty() {
        let _ = writeln!(s, "{ignored}");
    }
    let rejected =
        t.rejected_facing + t.rejected_clipped + t.rejected_degenerate + t.rejected_no_coverage + t.rejected_non_finite;
    // The clipper cuts a triangle crossing the frustum into pieces, each
    // set up or rejected on its own: the pieces beyond one a triangle are
    // what set up and rejected count past the triangles submitted.
    let pieces = (t.setups + rejected).saturating_sub(t.submitted);
    let split = if pieces > 0 { format!(" (and {pieces} more pieces the clipper cut)") } else { String::new() };
    let _ = writeln!(
        s,
        "triangles {} submitted{split}, {} set up, {} rejected (facing {}, clipped {}, degenerate {}, no coverage {}, non-finite {})",
        t.submitted,
        t.setups,
        rejected,
        t.rejected_facing,
        t.rejected_clipped,
        t.rejected_degenerate,
        t.rejected_no_coverage,
        t.rejected_non_finite
    );
    let _ = writeln!(
        s,
        "fragments {}, max-z culled {} triangles + {} blocks ({} texels), bin flushes {} full / {} setup / {} end",
        t.fragments,
        t.culled_triangles,
        t.culled_blocks,
        t.culled_texels,
        t.flushes_bin_full,
        t.flushes_setup_full,
        t.flushes_finish
    );
    let touched = c.tiles.iter().filter(|k| k.fragments > 0).count();
    let _ = writeln!(s, "tiles with fragments {touched} of {}; fragments per tile (hundreds):", c.tiles.len());
    for row in c.tiles.chunks(across as usize) {
        let line: Vec<String> = row.iter().map(|k| format!("{:>4}", k.fragments.div_ceil(100))).collect();
        let _ = writeln!(s, "{}", line.join(""));
    }
    s
}

/// One Markdown row per tile: fragments, culls, flushes and depth bounds.
fn tile_report(scene: &Scene, maps: &RawMaps, c: &Counters, args: &DepthArgs) -> String {
    let raster = maps.maps.config.raster;
    let mut s = String::new();
    let _ = writeln!(s, "# Light-pass tiles: {}\n", umbra_sim::output::markdown::escape(&scene.name));
    let _ = writeln!(s, "{}, cull {:?}; {}.\n", describe(maps), args.cull, scene.ignored());
    let mut columns = vec![("tile", Align::Left)];
    columns.extend(
        ["triangles", "fragments", "culled", "flushes", "z1 min", "z1 max", "z2 min", "z2 max"]
            .map(|h| (h, Align::Right)),
    );
    let mut t = Table::new(&columns);
    for (i, (k, st)) in c.tiles.iter().zip(&maps.maps.tiles).enumerate() {
        let id = raster.tile_id(i);
        t.row([
            format!("({}, {})", id.x, id.y),
            k.triangles.to_string(),
            k.fragments.to_string(),
            k.culled.to_string(),
            k.flushes.to_string(),
            st.z1_min.to_string(),
            st.z1_max.to_string(),
            st.z2_min.to_string(),
            st.z2_max.to_string(),
        ]);
    }
    s.push_str(&t.markdown());
    s
}
