//! `umbra render`: one shadow algorithm against the exact reference, with its pictures and metrics.

use std::path::PathBuf;
use umbra_sim::output::table::{Align, Table};

use crate::say::{Style, say};
use anyhow::Result;
use indicatif::ProgressBar;
use umbra_sim::input::limits::Limits;
use umbra_sim::output::folder::{Claim, OutputFolder, RunKind};
use umbra_sim::render::params::Kind;
use umbra_sim::render::params::PARAMS;
use umbra_sim::render::{Checked, RenderRequest, TruthSource};
use umbra_sim::truth::metrics::SHADE_STEP;
use umbra_sim::world::scene::Scene;
use umbra_sim::world::scene_file::BUNDLED;

/// The scene, the render's parameters and the output folder. The
/// parameters' flags are made from the library's table of them
/// ([`PARAMS`]): name, values, default and help.
#[derive(Debug, Clone)]
pub(super) struct RenderArgs {
    /// A bundled scene by name, a scene file or a glTF file.
    pub(super) scene: String,
    /// A glTF file's camera, by name or index.
    pub(super) camera: Option<String>,
    /// Where to move the scene's first light (`X,Y,Z`, read once by
    /// its flag's parser).
    pub(super) light_from: Option<umbra_core::glam::Vec3>,
    /// Each parameter given, by name, as written (a switch as `false`).
    pub(super) params: Vec<(&'static str, String)>,
    /// Output folder (default: the command's own).
    pub(super) out: Option<PathBuf>,
    /// Replace another command's results in the output folder.
    pub(super) replace: bool,
}

impl Default for RenderArgs {
    fn default() -> Self {
        Self {
            scene: DEFAULT_SCENE.to_owned(),
            camera: None,
            light_from: None,
            params: Vec::new(),
            out: None,
            replace: false,
        }
    }
}

const DEFAULT_SCENE: &str = "table-and-sphere";

impl clap::FromArgMatches for RenderArgs {
    fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
        let mut params = Vec::new();
        for p in PARAMS {
            if p.kind == Kind::Flag {
                if m.get_flag(p.name) {
                    params.push((p.name, "false".to_owned()));
                }
            } else if let Some(v) = m.get_one::<String>(p.name) {
                params.push((p.name, v.clone()));
            }
        }
        Ok(Self {
            scene: m.get_one::<String>("scene").cloned().unwrap_or_else(|| DEFAULT_SCENE.to_owned()),
            camera: m.get_one::<String>("camera").cloned(),
            light_from: m.get_one::<umbra_core::glam::Vec3>("light-from").copied(),
            params,
            out: m.get_one::<PathBuf>("out").cloned(),
            replace: m.get_flag("replace"),
        })
    }

    fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl clap::Args for RenderArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        use clap::{Arg, ArgAction};
        let scenes: Vec<&str> = BUNDLED.iter().map(|b| b.0).collect();
        let scenes = scenes.join(", ");
        let mut cmd = cmd.arg(
            Arg::new("scene")
                .default_value(DEFAULT_SCENE)
                .help(format!("A bundled scene by name ({scenes}), a scene file, or a glTF file (.gltf, .glb)")),
        );
        cmd = cmd.arg(
            Arg::new("camera")
                .long("camera")
                .value_name("NAME|INDEX")
                .help("A glTF file's camera, by name or by index in the order of its nodes [default: its first]"),
        );
        cmd = cmd.arg(
            Arg::new("light-from")
                .long("light-from")
                .value_name("X,Y,Z")
                .allow_hyphen_values(true)
                .value_parser(umbra_sim::world::relight::parse_point)
                .help("Move the scene's first light to X,Y,Z, aimed at the scene's centre [default: where its file puts it]"),
        );
        for p in PARAMS {
            let flag = p.flag();
            let default = match p.default_value() {
                Some(v) if p.kind == Kind::Flag => format!(" [default: {}]", if v == "true" { "on" } else { "off" }),
                Some(v) => format!(" [default: {v}]"),
                None => " [default: the scene's]".to_owned(),
            };
            let values = p.values.replace('`', "");
            let help = if p.kind == Kind::Flag { format!("Turn off {values}") } else { capitalised(&values) };
            let help = format!("{help}{default}");
            let mut arg = Arg::new(p.name)
                .long(flag.trim_start_matches("--").to_owned())
                .value_name(p.name.to_uppercase())
                .help(help)
                .aliases(p.aliases.iter().map(|a| a.replace('_', "-")));
            arg = match p.kind {
                Kind::Flag => arg.action(ArgAction::SetTrue),
                // A choice is read by the library, as every other value is:
                // case aside, and a slip answered with what it was nearly.
                _ => {
                    arg.value_parser(clap::builder::ValueParser::new(move |s: &str| p.check(s).map(|()| s.to_owned())))
                }
            };
            cmd = cmd.arg(arg);
        }
        cmd.arg(
            Arg::new("out")
                .long("out")
                .value_parser(clap::value_parser!(PathBuf))
                .help("Output folder (default: the command's own, out/render, out/cost or out/trace, so that one command's run never replaces another's)"),
        )
        .arg(Arg::new("replace").long("replace").action(ArgAction::SetTrue).help(crate::REPLACE_HELP))
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl RenderArgs {
    /// The scene the arguments name, with its camera and its light where
    /// `--light-from` puts it, its loader's notes printed.
    pub(super) fn scene(&self, limits: &Limits) -> Result<Scene> {
        let mut scene = Scene::open_with_camera(&self.scene, self.camera.as_deref(), limits)?;
        if let Some(point) = self.light_from {
            scene = scene.with_light_from(point)?;
        }
        for note in &scene.notes {
            say!("note: {note}");
        }
        Ok(scene)
    }
}

/// `text` with its first letter a capital.
fn capitalised(text: &str) -> String {
    let mut c = text.chars();
    c.next().map_or_else(String::new, |f| f.to_uppercase().chain(c).collect())
}

/// The render the arguments ask for, of `scene` (opened from
/// `args.scene`), checked once against it and the limits.
pub(super) fn job<'s>(args: &RenderArgs, scene: &'s Scene, limits: &Limits) -> Result<Checked<'s>> {
    let mut request = RenderRequest::DEFAULT;
    for (name, value) in &args.params {
        request.set(name, value)?;
    }
    Ok(request.config(scene.image)?.check(scene, limits)?)
}

/// `umbra render`: the pictures, the metrics and the events of one render,
/// printed in `style`.
pub(super) fn render(args: &RenderArgs, limits: &Limits, style: Style) -> Result<()> {
    let scene = args.scene(limits)?;
    let job = job(args, &scene, limits)?;
    let cfg = *job.config();
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out/render"));
    let mut folder = OutputFolder::create(&out, Claim::new(RunKind::Render).replacing(args.replace))?;
    let progress =
        ProgressBar::new(u64::from(cfg.height) * scene.lights.len().max(1) as u64).with_message("reference rays");
    let r = umbra_sim::render::render(&job, TruthSource::Build(&progress))?;
    progress.finish_and_clear();
    umbra_sim::render::files::write_render(&mut folder, &job, &r)?;
    let (manifest, replaced) = folder.finish_replacing(None)?;
    let m = r.frame_metrics();
    let t = &r.camera_events.totals;
    if style == Style::Brief {
        crate::say::wrapped(&format!("render `{}`: {}", scene.name, cfg.describe()))?;
        crate::say::wrapped(&format!(
            "misclassified {:.3} % of {} pixels facing the light; artifacts {:.3} % ({} acne, {} detachment, {} \
             leaks, {} clipped); {} aliasing",
            m.misclassified_percent,
            m.evaluated,
            m.artifact_percent,
            m.acne,
            m.detachment,
            m.leaks,
            m.clipped,
            m.aliasing
        ))?;
        return crate::say::wrote_in(style, &out, &manifest, &replaced);
    }
    say!("render `{}`: {}", scene.name, cfg.describe());
    if !scene.ignored().is_empty() {
        say!("the scene's mesh files: {}", scene.ignored());
    }
    let several = !r.more.is_empty();
    let mut heads = vec![("pixels evaluated", Align::Right)];
    if several {
        heads.insert(0, ("light", Align::Left));
    }
    heads.extend(["false shadow", "false light", "misclassified", "mean abs error"].map(|h| (h, Align::Right)));
    if several {
        heads.push(("artifacts", Align::Right));
    }
    let mut table = Table::new(&heads);
    let row = |light: Option<String>, m: &umbra_sim::truth::metrics::Metrics| {
        light
            .into_iter()
            .chain([
                m.evaluated.to_string(),
                format!("{:.3} %", m.false_shadow_percent),
                format!("{:.3} %", m.false_light_percent),
                format!("{:.3} %", m.misclassified_percent),
                format!("{:.4}", m.mean_abs_error),
            ])
            .chain(several.then(|| format!("{:.3} %", m.artifact_percent)))
            .collect::<Vec<_>>()
    };
    if several {
        for (k, part) in r.parts().enumerate() {
            table.row(row(Some(Scene::light_key(k)), part.metrics));
        }
        table.row(row(Some("the frame (pixel, light pairs)".to_owned()), &m));
    } else {
        table.row(row(None, &m));
    }
    say!("{}", table.markdown().trim_end());
    cascades(&r, several)?;
    say!(
        "artifacts (wrong by their cause, shade off the reference by more than {} or on the wrong side of ½): {} acne ({} on terminators; {:.1} px of excess shadow), {} detachment ({:.1} px of missing shadow), {} leaks ({:.1} px of missing shadow), {} clipped ({:.1} px of missing shadow, occluders outside the light's frustum): {:.3} % artifacts",
        SHADE_STEP,
        m.acne,
        m.terminator_acne,
        m.acne_area,
        m.detachment,
        m.detachment_area,
        m.leaks,
        m.leak_area,
        m.clipped,
        m.clipped_area,
        m.artifact_percent,
    );
    if m.receiver_fallbacks > 0 {
        say!(
            "{} wrong pixels judged against a flat receiver: their triangle's plane could not be set up (edge-on to the light, or nearer than its near plane)",
            m.receiver_fallbacks
        );
    }
    say!(
        "not artifacts: {} aliasing ({:.1} px), {} penumbra ({:.1} px; within {} / {} px of the exact edge, median / 95th percentile); {} ties at ½; RMS area error {:.4}; boundary displacement {:.2} / {:.2} / {:.2} pixels, {:.2} / {:.2} / {:.2} texels (mean / 95th percentile / max)",
        m.aliasing,
        m.aliasing_area,
        m.penumbra,
        m.penumbra_area,
        m.penumbra_width[0],
        m.penumbra_width[1],
        m.ties,
        m.rms_error,
        m.displacement[0],
        m.displacement[1],
        m.displacement[2],
        m.displacement_texels[0],
        m.displacement_texels[1],
        m.displacement_texels[2]
    );
    // Shadow volumes read no map: no footprint, lookups or map bytes.
    if cfg.algorithm != umbra_sim::Algorithm::Volumes {
        let way = |f: [f64; 2]| if f[0] < 1.0 { "magnified" } else { "minified" };
        say!(
            "map footprint, texels per pixel (median / 95th percentile): {:.3} / {:.3} along x ({}), {:.3} / {:.3} along y ({})",
            m.footprint_x[0],
            m.footprint_x[1],
            way(m.footprint_x),
            m.footprint_y[0],
            m.footprint_y[1],
            way(m.footprint_y)
        );
        say!(
            "virtual samples for {} pixels, {} trivially decided, {} tangent fallbacks, {} lookups culled, {} map bytes read",
            t.tangent_setups,
            t.trivial_pixels(),
            t.tangent_fallbacks,
            t.lookups_culled,
            t.map_read_bytes
        );
    }
    crate::say::wrote(&out, &manifest, &replaced)
}

/// Each cascaded light's cascades, a row each: the slice of the view it
/// holds, its map, its pixels' errors and the map's footprint on them.
fn cascades(r: &umbra_sim::Render, several: bool) -> Result<()> {
    for (k, part) in r.parts().enumerate().filter(|(_, p)| !p.cascades.is_empty()) {
        // The slice in view distance; the map's footprint along x, its
        // median and its 95th percentile over its 5th (`footprint_spread`).
        let heads = [
            ("cascade", Align::Left),
            ("slice", Align::Left),
            ("map", Align::Right),
            ("evaluated", Align::Right),
            ("misclassified", Align::Right),
            ("aliasing", Align::Right),
            ("artifacts", Align::Right),
            ("texels/px x", Align::Right),
            ("spread x", Align::Right),
        ];
        let mut table = Table::new(&heads);
        for (c, cascade) in part.cascades.iter().enumerate() {
            let m = &cascade.metrics;
            let name = if several { format!("{}.cascades[{c}]", Scene::light_key(k)) } else { c.to_string() };
            table.row(vec![
                name,
                format!("{:.2} – {:.2}", cascade.slice[0], cascade.slice[1]),
                format!("{}²", cascade.side),
                m.evaluated.to_string(),
                format!("{:.3} %", m.misclassified_percent),
                m.aliasing.to_string(),
                format!("{:.3} %", m.artifact_percent),
                format!("{:.3}", m.footprint_x[0]),
                format!("{:.1}", m.footprint_spread[0]),
            ]);
        }
        say!("{}", table.markdown().trim_end());
    }
    Ok(())
}
