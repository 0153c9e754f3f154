//! A render's parameters, each declared once in [`PARAMS`]: its name (the
//! `umbra render` flag, Python's keyword), the values it takes, its unit,
//! its column in a study's rows, what it means, and how it reads and
//! writes a [`RenderRequest`] (`request.rs`). The command line's flags,
//! Python's keyword arguments, the rows' schema, the command that renders
//! a row again and the documentation's flag table (`umbra schema render`)
//! are all made from this table; [`RenderConfig::DEFAULT`] holds the
//! defaults.

use crate::output::table::{Align, Table};
use std::fmt::Write as _;

use umbra_core::DepthFormatKind;

use super::request::RenderRequest;
use super::{Algorithm, RenderConfig};

/// What values a render parameter takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// One of these names.
    Choice(&'static [&'static str]),
    /// Text in its type's one spelling (a filter, a culling).
    Spelled,
    /// A whole number from `min` to `max`.
    Whole {
        /// The least value.
        min: u32,
        /// The greatest value.
        max: u32,
    },
    /// A depth in `[0, 1]`.
    Depth,
    /// On or off; on the command line, `--no-<name>` turns it off.
    Flag,
}

impl Kind {
    /// The type its column holds in a study's rows.
    #[must_use]
    pub(crate) const fn column_type(self) -> &'static str {
        match self {
            Self::Choice(_) | Self::Spelled => "text",
            Self::Whole { .. } => "integer",
            Self::Depth => "number",
            Self::Flag => "boolean",
        }
    }
}

/// When [`RenderConfig::command`] writes a parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Written {
    /// Always.
    Always,
    /// Only for the algorithm of this name (Reeves' `Bias1`, the dual offset).
    For(&'static str),
    /// Only when it is not the default.
    Changed,
}

/// One parameter of a render.
pub struct RenderParam {
    /// Its name: the flag (`_` written `-`) and Python's keyword.
    pub name: &'static str,
    /// Other names the flag and the keyword take.
    pub aliases: &'static [&'static str],
    /// The values it takes.
    pub kind: Kind,
    /// Its unit (`-` for none).
    pub unit: &'static str,
    /// Its column in a study's rows.
    pub column: &'static str,
    /// What it means, in a line (the rows' schema).
    pub meaning: &'static str,
    /// The values in words, for the command line's help and the docs.
    pub values: &'static str,
    /// When the command that renders again writes it.
    pub written: Written,
    get: fn(&RenderRequest) -> Option<String>,
    set: fn(&mut RenderRequest, &str) -> Result<(), String>,
}

impl core::fmt::Debug for RenderParam {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("RenderParam").field("name", &self.name).field("kind", &self.kind).finish_non_exhaustive()
    }
}

/// A value a parameter cannot take, or a name no parameter has.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParamError {
    /// No parameter of that name.
    #[error("no render parameter is called `{0}` (the parameters: {names})", names = names())]
    Unknown(String),
    /// A value the parameter cannot take.
    #[error("{name} `{value}`: {problem}")]
    Value {
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: String,
        /// What is wrong with it.
        problem: String,
    },
}

fn names() -> String {
    PARAMS.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
}

fn whole(text: &str, min: u32, max: u32) -> Result<u32, String> {
    match text.trim().parse::<u32>() {
        Ok(n) if (min..=max).contains(&n) => Ok(n),
        _ if max == u32::MAX => Err(format!("expected a whole number from {min}")),
        _ => Err(format!("expected a whole number in {min}..={max}")),
    }
}

fn depth(text: &str) -> Result<f64, String> {
    let x = text.trim().parse::<f64>().map_err(|_| "expected a depth in [0, 1]".to_owned())?;
    RenderConfig::depth("the value", x).map(|_| x).map_err(|_| "expected a depth in [0, 1]".to_owned())
}

fn flag(text: &str) -> Result<bool, String> {
    match text.trim() {
        "true" | "on" | "yes" | "1" => Ok(true),
        "false" | "off" | "no" | "0" => Ok(false),
        _ => Err("expected true or false".to_owned()),
    }
}

fn spelled<T: std::str::FromStr>(text: &str) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    text.trim().parse().map_err(|e: T::Err| e.to_string())
}

/// A map's or an image's side takes any whole number from 1: the
/// machine's [`Limits`](crate::input::limits::Limits) bound it.
const SIDE: u32 = u32::MAX;

/// Every parameter of a render, in the order the command that renders
/// again writes them.
pub const PARAMS: &[RenderParam] = &[
    RenderParam {
        name: "algo",
        aliases: &[],
        kind: Kind::Choice(&Algorithm::NAMES),
        unit: "-",
        column: "algorithm",
        meaning: "the algorithm as umbra render --algo spells it",
        values: "`first` (Williams' first depth), `bias-range` (Reeves' per-sample bias from `--bias` to `--bias1`), `second` (Wang & Molnar's second depth from the dual unit), `second-ffc` (second depth by front-face culling), `midpoint` (Woo's midpoint), `dual` (Weiskopf & Ertl's dual depth, with `--offset`), `silhouette` and `silhouette-packed` (Sen et al.'s silhouette map, 16-bit or packed points), `volumes` (depth-fail stencil shadow volumes)",
        written: Written::Always,
        get: |r| Some(r.algo.to_owned()),
        set: |r, v| {
            // Its one spelling, as every reader of algorithm names reads it.
            r.algo = Algorithm::named(v.trim(), 0.0, 0.0).map_err(|e| e.to_string())?.name();
            Ok(())
        },
    },
    RenderParam {
        name: "bias1",
        aliases: &[],
        kind: Kind::Depth,
        unit: "depth",
        column: "bias1",
        meaning: "Reeves' Bias1, for a bias range (empty otherwise)",
        values: "`Bias1` of Reeves' bias range (`--algo bias-range`), a depth in `[0, 1]`",
        written: Written::For("bias-range"),
        get: |r| Some(r.bias1.to_string()),
        set: |r, v| {
            r.bias1 = depth(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "offset",
        aliases: &[],
        kind: Kind::Depth,
        unit: "depth",
        column: "offset",
        meaning: "Weiskopf & Ertl's offset, for dual depth (empty otherwise)",
        values: "the dual-depth offset (`--algo dual`), a depth in `[0, 1]`",
        written: Written::For("dual"),
        get: |r| Some(r.offset.to_string()),
        set: |r, v| {
            r.offset = depth(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "depth",
        aliases: &["format"],
        kind: Kind::Choice(DepthFormatKind::NAMES),
        unit: "-",
        column: "depth_format",
        meaning: "the map's depth format: d16, d24, f32",
        values: "the map's depth format: `d16`, `d24`, `f32`",
        written: Written::Always,
        get: |r| Some(r.config.format.name().to_owned()),
        set: |r, v| {
            r.config.format = spelled(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "map",
        aliases: &["size"],
        kind: Kind::Whole { min: 1, max: SIDE },
        unit: "texels",
        column: "map_side_texels",
        meaning: "the map's side",
        values: "the map's side in texels",
        written: Written::Always,
        get: |r| Some(r.config.map_size.to_string()),
        set: |r, v| {
            r.config.map_size = whole(v, 1, SIDE)?;
            Ok(())
        },
    },
    RenderParam {
        name: "filter",
        aliases: &[],
        kind: Kind::Spelled,
        unit: "-",
        column: "filter_name",
        meaning: "the filter as umbra render --filter spells it",
        values: "`point`, `bilinear`, `box<N>` (N from 1 to 16: `box3`, `box5`), `jitter<N>` (Reeves' jittered filter with N samples; `jitter16` is their Figure 4), optionally followed by `,res-factor=<texels>`, `,min-samples=<n>`, `,min-size=<texels>` (`jitter8,res-factor=1.5`)",
        written: Written::Always,
        get: |r| Some(r.config.filter.to_string()),
        set: |r, v| {
            r.config.filter = spelled(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "bias",
        aliases: &[],
        kind: Kind::Depth,
        unit: "depth",
        column: "bias",
        meaning: "the bias, a depth in [0, 1] (Reeves' Bias0 for a bias range)",
        values: "the depth bias, a depth in `[0, 1]` (`Bias0` of a bias range)",
        written: Written::Always,
        get: |r| Some(r.config.bias.to_string()),
        set: |r, v| {
            r.config.bias = depth(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "width",
        aliases: &[],
        kind: Kind::Whole { min: 1, max: SIDE },
        unit: "px",
        column: "image_width_px",
        meaning: "the camera image's width",
        values: "the camera image's width in pixels",
        written: Written::Always,
        get: |r| r.width.map(|w| w.to_string()),
        set: |r, v| {
            r.width = Some(whole(v, 1, SIDE)?);
            Ok(())
        },
    },
    RenderParam {
        name: "height",
        aliases: &[],
        kind: Kind::Whole { min: 1, max: SIDE },
        unit: "px",
        column: "image_height_px",
        meaning: "the camera image's height",
        values: "the camera image's height in pixels",
        written: Written::Always,
        get: |r| r.height.map(|h| h.to_string()),
        set: |r, v| {
            r.height = Some(whole(v, 1, SIDE)?);
            Ok(())
        },
    },
    RenderParam {
        name: "reference_rays",
        aliases: &["reference_samples", "rays"],
        kind: Kind::Whole { min: *RenderConfig::REFERENCE_RAYS.start(), max: *RenderConfig::REFERENCE_RAYS.end() },
        unit: "-",
        column: "reference_rays",
        meaning: "reference rays a pixel side (n for n × n)",
        values: "rays per pixel side of the area-averaged reference",
        written: Written::Always,
        get: |r| Some(r.config.reference_rays.to_string()),
        set: |r, v| {
            let (min, max) = (*RenderConfig::REFERENCE_RAYS.start(), *RenderConfig::REFERENCE_RAYS.end());
            r.config.reference_rays = whole(v, min, max)?;
            Ok(())
        },
    },
    RenderParam {
        name: "virtual_samples",
        aliases: &[],
        kind: Kind::Flag,
        unit: "-",
        column: "virtual_samples",
        meaning: "Wang & Molnar's virtual samples on (empty but for second depth)",
        values: "Wang & Molnar's virtual samples (second-depth algorithms)",
        written: Written::Changed,
        get: |r| Some(r.config.virtual_samples.to_string()),
        set: |r, v| {
            r.config.virtual_samples = flag(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "cull",
        aliases: &["culling"],
        kind: Kind::Spelled,
        unit: "-",
        column: "culling",
        meaning: "the light pass's culling per object class, as umbra render --cull takes it",
        values: "the light pass's culling per object class: `algorithm` (solids as the algorithm culls them, open surfaces never) or `solids=X,open=Y`, with X and Y each `algorithm`, `none`, `front` or `back`",
        written: Written::Changed,
        get: |r| Some(r.config.culling.to_string()),
        set: |r, v| {
            r.config.culling = spelled(v)?;
            Ok(())
        },
    },
    RenderParam {
        name: "cascades",
        aliases: &[],
        kind: Kind::Spelled,
        unit: "-",
        column: "cascades",
        meaning: "every directional light's cascades as umbra render --cascades spells them (scene: each light's own)",
        values: "`scene` (each directional light's own, one map unless its scene file says `cascades`), or `N` cascades (1 to 8) split by Zhang et al.'s practical scheme, optionally followed by `,lambda=<0..1>` (1 logarithmic, 0 uniform; 0.5 unless given), `,splits=D1/D2/…` (view distances instead), `,sides=S` or `,sides=S1/S2/…` (each cascade's map side; the map's unless given), `,fit=samples` (each cascade fitted to the visible samples of its slice) and `,blend=B` (the last fraction B of each cascade's depth range blends into the next): `4`, `4,lambda=0.7,sides=2048/1024/1024/512`",
        written: Written::Changed,
        get: |r| Some(crate::world::cascade::choice_text(r.config.cascades)),
        set: |r, v| {
            r.config.cascades = crate::world::cascade::read_choice(v).map_err(|e| e.to_string())?;
            Ok(())
        },
    },
];

impl RenderParam {
    /// The parameter called `name`: its name, an alias or its flag
    /// (`-` and `_` alike, `--no-virtual-samples` for the switch).
    ///
    /// # Errors
    /// [`ParamError::Unknown`].
    pub fn named(name: &str) -> Result<&'static Self, ParamError> {
        let name = name.trim();
        let bare = name.trim_start_matches("--").replace('-', "_");
        PARAMS
            .iter()
            .find(|p| p.name == bare || p.aliases.contains(&bare.as_str()) || p.flag() == name)
            .ok_or(ParamError::Unknown(bare))
    }

    /// Its command-line flag (`--reference-rays`; `--no-virtual-samples`
    /// for a flag on by default).
    #[must_use]
    pub fn flag(&self) -> String {
        let name = self.name.replace('_', "-");
        if self.kind == Kind::Flag { format!("--no-{name}") } else { format!("--{name}") }
    }

    /// Its value in `request` as the command line writes it; none when
    /// the request leaves it to the scene.
    #[must_use]
    pub(crate) fn value(&self, request: &RenderRequest) -> Option<String> {
        (self.get)(request)
    }

    /// Its default as written (none: the scene's).
    #[must_use]
    pub fn default_value(&self) -> Option<String> {
        (self.get)(&RenderRequest::DEFAULT)
    }

    /// Whether `text` is a value it takes.
    ///
    /// # Errors
    /// [`ParamError::Value`] saying what it takes.
    pub fn check(&self, text: &str) -> Result<(), ParamError> {
        self.apply(&mut RenderRequest::DEFAULT.clone(), text)
    }

    /// Set this parameter of `request` to the value `text` writes.
    ///
    /// # Errors
    /// [`ParamError::Value`] saying what it takes.
    pub(super) fn apply(&self, request: &mut RenderRequest, text: &str) -> Result<(), ParamError> {
        (self.set)(request, text).map_err(|problem| ParamError::Value {
            name: self.name,
            value: text.to_owned(),
            problem,
        })
    }
}

impl RenderRequest {
    /// Set the parameter called `name` (as [`RenderParam::named`] finds
    /// it) to the value `text` writes.
    ///
    /// ```
    /// use umbra_sim::render::RenderRequest;
    /// let mut r = RenderRequest::DEFAULT;
    /// r.set("map", "512")?;
    /// r.set("reference-rays", "2")?;
    /// assert!(r.set("bias", "1.5").is_err());
    /// let cfg = r.config([320, 180]).expect("an algorithm");
    /// assert_eq!((cfg.map_size, cfg.reference_rays, cfg.width), (512, 2, 320));
    /// # Ok::<(), umbra_sim::render::params::ParamError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParamError`] naming the parameter or the value.
    pub fn set(&mut self, name: &str, text: &str) -> Result<(), ParamError> {
        RenderParam::named(name)?.apply(self, text)
    }
}

/// The parameters of a map, which a shadow-volume render has none of.
const MAP_PARAMS: [&str; 4] = ["depth", "map", "filter", "bias"];

/// The flags of `cfg` as the command that renders it again writes them
/// (`--algo dual --offset 0.01 --depth d24 …`; a shadow-volume render's
/// without the map's).
pub(super) fn flags(cfg: &RenderConfig) -> String {
    let (request, default) = (RenderRequest::of(cfg), RenderRequest::DEFAULT);
    let mut out = String::new();
    // Shadow volumes draw no map: no format, side, filter or bias of one.
    let volumes = cfg.algorithm == Algorithm::Volumes;
    for p in PARAMS {
        if volumes && MAP_PARAMS.contains(&p.name) {
            continue;
        }
        let Some(value) = p.value(&request) else { continue };
        let write = match p.written {
            Written::Always => true,
            Written::For(algo) => request.algo == algo,
            Written::Changed => p.value(&default).as_deref() != Some(value.as_str()),
        };
        if write {
            let sep = if out.is_empty() { "" } else { " " };
            if p.kind == Kind::Flag {
                let _ = write!(out, "{sep}{}", p.flag());
            } else {
                let _ = write!(out, "{sep}{} {value}", p.flag());
            }
        }
    }
    out
}

/// The parameters as a Markdown table: flag, Python keyword, values,
/// default, unit and the rows' column (`umbra schema render`).
#[must_use]
pub fn markdown() -> String {
    let mut t = Table::new(&["flag", "Python", "values", "default", "unit", "column"].map(|h| (h, Align::Left)));
    for p in PARAMS {
        let default = match (p.kind, p.default_value()) {
            (Kind::Flag, Some(v)) if v == "true" => "on".to_owned(),
            (Kind::Flag, Some(_)) => "off".to_owned(),
            (_, Some(v)) => format!("`{v}`"),
            (_, None) => "the scene's".to_owned(),
        };
        let range = match p.kind {
            Kind::Whole { min, max } if max < SIDE => format!(", {min} to {max}"),
            _ => String::new(),
        };
        t.row([
            format!("`{}`", p.flag()),
            format!("`{}=`", p.name),
            format!("{}{range}", p.values),
            default,
            p.unit.to_string(),
            format!("`{}`", p.column),
        ]);
    }
    t.markdown()
}
