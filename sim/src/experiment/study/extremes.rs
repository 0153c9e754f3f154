//! Numerical extremes: the cases where a depth format or the fixed-point
//! pipeline runs out of range, rendered through the same sweep as the study.
//!
//! * the light's near/far ratio from 10 to 10⁶ (a perspective map's depth
//!   `z = f/(f − n) · (1 − n/d)` crowds every surface towards 1 as `n`
//!   shrinks, so a format's steps run out: Reeves et al. §3's precision
//!   problem, and the reason Wang & Molnar §3.4 keep a second depth);
//! * a directional light grazing a floor within 0.1° and 0.02°;
//! * vertices beyond the guard band (±2¹⁶ pixels, the limit of the
//!   snapped fixed-point coordinates) and far past it;
//! * slivers and sub-pixel triangles;
//! * coincident surfaces.
//!
//! None may panic; each must give a finite metric.

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use glam::Vec3;
use indicatif::ProgressBar;
use umbra_core::DepthFormatKind;

use super::plot::{self, Series};
use super::{Row, Shard, Spec, StudyError, Variant};
use crate::input::limits::Limits;
use crate::output::folder::OutputFolder;
use crate::render::Algorithm;
use crate::world::mesh::Mesh;
use crate::world::scene::{Light, Object, Scene};

/// The light near/far ratios swept.
pub(crate) const RATIOS: [f64; 6] = [10.0, 1e2, 1e3, 1e4, 1e5, 1e6];

/// The grazing angles, degrees between the light and the floor.
pub(crate) const GRAZING_DEGREES: [f64; 2] = [0.1, 0.02];

/// Wang & Molnar's table (a spot light) with the light's near plane at
/// `far / ratio`, its far plane where the scene file has it. The scene is
/// named `near-far-<ratio>`.
///
/// # Panics
/// Never: the bundled table-and-sphere scene is valid.
#[must_use]
pub(crate) fn near_far_scene(ratio: f64) -> Scene {
    let mut s = Scene::default_scene();
    if let Some(Light::Spot(p)) = s.lights.first_mut() {
        #[allow(clippy::cast_possible_truncation, reason = "a plane distance well inside f32")]
        let near = (f64::from(p.far) / ratio) as f32;
        p.near = near;
    }
    s.name = near_far_name(ratio);
    s
}

/// The name of the near/far scene at `ratio`.
fn near_far_name(ratio: f64) -> String {
    format!("near-far-{ratio:e}")
}

/// The `grazing` scene with its directional light `degrees` above the floor.
///
/// # Panics
/// Never: the bundled grazing scene is valid.
#[must_use]
pub(crate) fn grazing_scene(degrees: f64) -> Scene {
    let mut s = Scene::bundled("grazing").expect("the bundled grazing scene is valid");
    if let Some(Light::Directional(o, _)) = s.lights.first_mut() {
        let d = o.position - o.target;
        let horizontal = Vec3::new(d.x, 0.0, d.z).length();
        #[allow(clippy::cast_possible_truncation, reason = "a height well inside f32")]
        let height = (f64::from(horizontal) * degrees.to_radians().tan()) as f32;
        o.position.y = o.target.y + height;
    }
    s.name = format!("grazing-{degrees}deg");
    s
}

/// An open, upward-facing rectangle `[x0, x1] × [z0, z1]` at height `y`.
fn floor_quad(name: &str, x: (f32, f32), z: (f32, f32), y: f32) -> Object {
    let mesh = Mesh::quad(Vec3::new(x.0, y, z.0), Vec3::new(0.0, 0.0, z.1 - z.0), Vec3::new(x.1 - x.0, 0.0, 0.0));
    Object { name: name.to_owned(), mesh, solid: false }
}

/// Weiskopf & Ertl's L over receivers at the limits of the snapped
/// coordinates: with the 512² map of [`spec`] (8 world units across, 64
/// texels per unit) the guard band's ±2¹⁶ pixels lie at x ≈ −1028 and
/// x ≈ +1020; one floor ends just inside them, one just outside, and one
/// reaches ±10⁵ units.
///
/// # Panics
/// Never: the bundled scene is valid.
#[must_use]
pub(crate) fn guard_band_scene() -> Scene {
    let mut s = Scene::bundled("weiskopf-l").expect("the bundled weiskopf-l scene is valid");
    s.objects.retain(|o| o.name != "plane");
    s.objects.push(floor_quad("inside the guard band", (-1027.9, 1019.9), (-3.0, 3.0), 0.0));
    s.objects.push(floor_quad("outside the guard band", (-1028.1, 1020.1), (-1028.1, -3.0), 0.0));
    s.objects.push(floor_quad("far outside", (-1e5, 1e5), (3.0, 1e5), 0.0));
    s.name = "guard-band".to_owned();
    s
}

/// The table with 200 slivers (3 units long, 10⁻⁴ wide) and a 40 × 40 grid
/// of sub-pixel triangles (2·10⁻³ units, a fraction of a texel) floating
/// above it.
#[must_use]
pub(crate) fn sliver_scene() -> Scene {
    let mut s = Scene::default_scene();
    let mut slivers = Mesh::default();
    for k in 0..200u16 {
        let z = -1.0 + f32::from(k) * 0.01;
        let y = 1.6;
        let base = u32::try_from(slivers.positions.len()).unwrap_or(u32::MAX);
        slivers.positions.extend([Vec3::new(-1.0, y, z), Vec3::new(2.0, y, z + 1e-4), Vec3::new(2.0, y, z)]);
        slivers.triangles.push([base, base + 1, base + 2]);
    }
    let mut dust = Mesh::default();
    for i in 0..40u16 {
        for j in 0..40u16 {
            let p = Vec3::new(-0.5 + f32::from(i) * 0.05, 1.3, -0.5 + f32::from(j) * 0.05);
            let base = u32::try_from(dust.positions.len()).unwrap_or(u32::MAX);
            dust.positions.extend([p, p + Vec3::new(0.0, 0.0, 2e-3), p + Vec3::new(2e-3, 0.0, 0.0)]);
            dust.triangles.push([base, base + 1, base + 2]);
        }
    }
    s.objects.push(Object { name: "slivers".to_owned(), mesh: slivers, solid: false });
    s.objects.push(Object { name: "sub-pixel triangles".to_owned(), mesh: dust, solid: false });
    s.name = "slivers".to_owned();
    s
}

/// Weiskopf & Ertl's L with its base duplicated in place (two coincident
/// solids) and an open sheet lying exactly on the plane's top.
///
/// # Panics
/// Never: the bundled scene is valid.
#[must_use]
pub(crate) fn coincident_scene() -> Scene {
    let mut s = Scene::bundled("weiskopf-l").expect("the bundled weiskopf-l scene is valid");
    let base = s.objects.iter().find(|o| o.name == "L base").cloned();
    s.objects.extend(base.map(|mut o| {
        o.name = "L base again".to_owned();
        o
    }));
    s.objects.push(floor_quad("sheet on the plane", (-4.0, 4.0), (-4.0, 4.0), 0.0));
    s.name = "coincident".to_owned();
    s
}

/// The algorithms the extremes run: first depth at a bias that suits the
/// bundled scenes, second depth, midpoint and dual.
#[must_use]
pub(crate) fn variants() -> Vec<Variant> {
    vec![
        Variant::new(Algorithm::First, 0.002),
        Variant::new(Algorithm::Second, 0.0),
        Variant::new(Algorithm::Midpoint, 0.0),
        Variant::new(Algorithm::Dual { offset: 0.005 }, 0.0),
    ]
}

/// The extremes' sweep over `scenes`: [`variants`] in d16, d24 and f32, a
/// 512² map, bilinear filter, metrics only (no presets), `width × height`
/// images against one reference ray per pixel.
#[must_use]
pub(crate) fn spec(scenes: Vec<Scene>, width: u32, height: u32) -> Spec {
    Spec {
        scenes,
        variants: variants(),
        formats: vec![DepthFormatKind::D16, DepthFormatKind::D24, DepthFormatKind::F32],
        map_sizes: vec![512],
        filters: vec![umbra_core::shadow::Filter::Bilinear],
        archs: Vec::new(),
        arch_points: Vec::new(),
        images: vec![[width, height]],
        reference_rays: 1,
        budgets: Vec::new(),
        cost_limits: super::objective::CostLimits::default(),
        name: "extremes".to_owned(),
        hash: String::new(),
        limits: Limits::DEFAULT,
    }
}

/// Every extreme scene: the near/far sweep, then the other cases.
#[must_use]
pub(crate) fn scenes() -> Vec<Scene> {
    let mut s: Vec<Scene> = RATIOS.iter().map(|&r| near_far_scene(r)).collect();
    s.extend(GRAZING_DEGREES.iter().map(|&d| grazing_scene(d)));
    s.extend([guard_band_scene(), sliver_scene(), coincident_scene()]);
    s
}

/// Misclassified % of `rows` for one algorithm and format, in scene order.
fn curve<'a>(rows: &'a [Row], algorithm: &'a str, format: DepthFormatKind) -> impl Iterator<Item = &'a Row> + 'a {
    rows.iter().filter(move |r| r.config.algorithm == algorithm && r.config.depth_format == format)
}

/// A misclassified percentage beyond which the near/far sweep counts a
/// format as broken down: 1 point above what it scores at ratio 10.
pub(crate) const BREAKDOWN_POINTS: f64 = 1.0;

/// The smallest swept ratio at which `algorithm` in `format` misclassifies
/// `BREAKDOWN_POINTS` more than at ratio 10; `None` if it never does.
#[must_use]
pub(crate) fn breakdown(rows: &[Row], algorithm: &str, format: DepthFormatKind) -> Option<f64> {
    let errs: Vec<(f64, f64)> =
        curve(rows, algorithm, format).filter_map(|r| Some((ratio_of(&r.config.scene)?, misclassified(r)?))).collect();
    let base = errs.first()?.1;
    errs.iter().find(|(_, e)| *e > base + BREAKDOWN_POINTS).map(|(r, _)| *r)
}

/// The ratio of the near/far scene named `scene`, if it is one.
fn ratio_of(scene: &str) -> Option<f64> {
    RATIOS.iter().copied().find(|&r| near_far_name(r) == scene)
}

/// The extremes table in Markdown: the near/far sweep (misclassified % per
/// ratio, with each curve's breakdown) and the other cases.
#[must_use]
pub(crate) fn markdown(rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Umbra study: numerical extremes\n");
    let _ = writeln!(
        s,
        "Misclassified pixels, % of those facing the light, against the exact reference; 512² map, bilinear \
         filter, {}×{} images. A format breaks down where it misclassifies {BREAKDOWN_POINTS} points more than \
         at ratio 10.\n",
        rows.first().map_or(0, |r| r.config.image_width_px),
        rows.first().map_or(0, |r| r.config.image_height_px)
    );
    let _ = writeln!(s, "## Light near/far ratio (table-and-sphere scene, spot light)\n");
    let mut columns = vec![("algorithm".to_owned(), Align::Left), ("format".to_owned(), Align::Left)];
    columns.extend(RATIOS.iter().map(|r| (format!("{r:.0e}"), Align::Right)));
    columns.push(("breaks down at".to_owned(), Align::Left));
    let mut t = Table::new(&columns);
    for v in variants() {
        for f in DepthFormatKind::ALL {
            let name = v.algorithm.name();
            let mut cells = vec![name.to_owned(), f.to_string()];
            cells.extend(curve(rows, name, f).filter(|r| ratio_of(&r.config.scene).is_some()).map(cell));
            cells.resize(2 + RATIOS.len(), String::new());
            let measured = curve(rows, name, f).any(|r| r.metrics.is_some());
            cells.push(match breakdown(rows, name, f) {
                Some(r) => format!("{r:.0e}"),
                None if measured => "never (≤ 10⁶)".to_owned(),
                None => "not measured".to_owned(),
            });
            t.row(cells);
        }
    }
    s.push_str(&t.markdown());
    let _ = writeln!(s, "\n## Other extremes\n");
    let mut columns = vec![("case".to_owned(), Align::Left), ("algorithm".to_owned(), Align::Left)];
    columns.extend(DepthFormatKind::ALL.map(|f| (f.name().to_owned(), Align::Right)));
    let mut t = Table::new(&columns);
    let cases =
        super::distinct(rows.iter().filter(|r| ratio_of(&r.config.scene).is_none()).map(|r| r.config.scene.as_str()));
    for case in cases {
        for v in variants() {
            let name = v.algorithm.name();
            let mut cells = vec![case.to_owned(), name.to_owned()];
            for f in DepthFormatKind::ALL {
                let c = rows
                    .iter()
                    .find(|r| r.config.scene == case && r.config.algorithm == name && r.config.depth_format == f);
                cells.push(c.map_or_else(|| "–".to_owned(), cell));
            }
            t.row(cells);
        }
    }
    s.push_str(&t.markdown());
    s
}

/// A row's misclassified percentage, when measured.
fn misclassified(r: &Row) -> Option<f64> {
    r.metrics.map(|m| m.misclassified_percent)
}

fn cell(r: &Row) -> String {
    match misclassified(r) {
        Some(m) => format!("{m:.3}"),
        None => format!("skipped: {}", r.reason),
    }
}

/// The near/far curves as plot series: misclassified % against the ratio
/// for every algorithm of [`variants`] in d16 and d24 (f32 stores standard
/// `z/w`, whose steps near 1 are 2⁻²⁴ as well: its curves lie on d24's),
/// each named with its breakdown ratio.
#[must_use]
pub(crate) fn precision_series(rows: &[Row]) -> Vec<Series> {
    let mut out = Vec::new();
    for a in variants().iter().map(|v| v.algorithm.name()) {
        for f in [DepthFormatKind::D16, DepthFormatKind::D24] {
            let pts: Vec<(f64, f64)> =
                curve(rows, a, f).filter_map(|r| Some((ratio_of(&r.config.scene)?, misclassified(r)?))).collect();
            let at = breakdown(rows, a, f)
                .map_or_else(|| "never breaks down".to_owned(), |r| format!("breaks down at {r:.0e}"));
            out.push((format!("{a} {f}: {at}"), pts));
        }
    }
    out
}

/// Run every extreme at 160×90 on the current rayon pool, within
/// `limits` (a configuration beyond them is a skipped row that names the
/// limit), and write `extremes.jsonl`, `extremes.md` and
/// `precision.{svg,png}` into `folder`. Returns the Markdown.
///
/// # Errors
/// See [`StudyError`].
pub(crate) fn run_all(folder: &mut OutputFolder, limits: &Limits) -> Result<String, StudyError> {
    let spec = Spec { limits: *limits, ..spec(scenes(), 160, 90) };
    let rows = super::run(&spec, Shard::ALL, &ProgressBar::hidden())?;
    folder.write_text("extremes.jsonl", &super::jsonl(&rows))?;
    let md = markdown(&rows);
    folder.write_text("extremes.md", &md)?;
    plot::lines(
        folder,
        "precision",
        "Depth precision against the light's far/near (table-and-sphere)",
        "light far / near (f32 lies on d24)",
        "misclassified %",
        &precision_series(&rows),
    )?;
    Ok(md)
}
