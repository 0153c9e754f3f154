//! The files a render writes into its folder, the same from every door:
//! the pictures (`shaded.png`, `shadow.png`, `error.png`), the maps (`.npy`
//! of the stored integers and `.png` previews), the per-pixel arrays
//! (`shadow.npy`, `reference.npy`, `verdict.npy`) and `metrics.json` with
//! what made it (version, command line, scene, configuration, the command
//! that renders it again).

use serde_json::Value;

use super::arrays::PixelArrays;
use super::pictures::{write_error_image, write_shadow_image, write_shadow_term};
use super::{Checked, Render};
use crate::output::OutputError;
use crate::output::folder::OutputFolder;
use crate::output::formats::{RawMap, write_array, write_npy};
use crate::output::picture::write_preview;
use crate::output::provenance::{command_line, version};
use crate::world::scene::{Light, Scene};

/// Write render `r` of the checked `job` into `folder` (its manifest is
/// the caller's to finish). A scene of several shadow-casting lights
/// writes the frame's `shaded.png` and `metrics.json` (the frame's
/// metrics, and each light's under `lights`), and every other file once
/// per light, suffixed with its index from 0 (`lights[k]`):
/// `shadow-light0.png`, `shadow-light1.png`, `z1-light0.npy`.
///
/// # Errors
/// `OutputError` for a file that could not be written.
pub fn write_render(folder: &mut OutputFolder, job: &Checked<'_>, r: &Render) -> Result<(), OutputError> {
    let (scene, cfg) = (job.scene(), job.config());
    let detail = format!("{}: {}", scene.name, cfg.describe());
    let lights: Vec<_> = r.parts().map(|p| (p.image, p.truth)).collect();
    write_shadow_image(folder, "shaded.png", (&r.image, &lights, &r.shadowless), &detail)?;
    let several = !r.more.is_empty();
    for (k, part) in r.parts().enumerate() {
        let (named, detail) = if several {
            let light = Scene::light_key(k);
            (format!("-light{k}"), format!("{}: {light}: {}", scene.name, cfg.describe()))
        } else {
            (String::new(), detail.clone())
        };
        let file = |stem: &str, ext: &str| format!("{stem}{named}.{ext}");
        write_shadow_term(folder, &file("shadow", "png"), (part.image, part.truth), &detail)?;
        let truth = (part.truth, part.cascade_of, detail.as_str());
        write_error_image(folder, &file("error", "png"), part.image, part.verdicts, truth)?;
        // A cascaded light's first cascade's maps as its own, the
        // others' suffixed `-cascade<c>`.
        for (c, maps) in core::iter::once(part.maps).chain(part.cascade_maps).enumerate() {
            let (w, h) = (maps.maps.config.raster.width(), maps.maps.config.raster.height());
            let cascade = if c > 0 { format!("-cascade{c}") } else { String::new() };
            for (name, data) in maps.stored() {
                let map = RawMap { format: maps.format, width: w, height: h, raw: data };
                let stem = format!("{name}{cascade}");
                let title = if part.cascades.is_empty() {
                    map_title(name)
                } else {
                    format!("cascade {c}: {}", map_title(name))
                };
                write_npy(folder, &file(&stem, "npy"), &map)?;
                write_preview(folder, &file(&stem, "png"), &map, (&title, &detail))?;
            }
        }
        // Pixel by pixel, for scripts: the shadow term, the reference and the verdicts.
        let arrays = PixelArrays::of_part(part);
        let size = (arrays.width, arrays.height);
        write_array(folder, &file("shadow", "npy"), size, &arrays.shadow)?;
        write_array(folder, &file("reference", "npy"), size, &arrays.reference)?;
        write_array(folder, &file("verdict", "npy"), size, &arrays.verdict)?;
    }
    // The metrics, with what made them. Numbers and strings only: these
    // serialise without fail.
    let mut record = serde_json::to_value(r.frame_metrics()).unwrap_or(Value::Null);
    if let Some(fields) = record.as_object_mut() {
        for (k, v) in [
            ("umbra_version", version()),
            ("command", command_line()),
            ("scene", scene.source.clone()),
            ("configuration_text", cfg.describe()),
            ("render_again", r.command.clone()),
        ] {
            fields.insert(k.to_owned(), Value::String(v));
        }
        fields.insert("configuration".to_owned(), serde_json::to_value(cfg).unwrap_or(Value::Null));
        // The lights as rendered, and what the scene's loader supplied.
        fields.insert("light_views".to_owned(), scene.lights.iter().map(light_view).collect());
        fields.insert("scene_notes".to_owned(), scene.notes.iter().map(|n| Value::String(n.clone())).collect());
        if several {
            let each = r.parts().map(|p| serde_json::to_value(p.metrics).unwrap_or(Value::Null)).collect();
            fields.insert("lights".to_owned(), Value::Array(each));
        }
        if let Some(cascades) = cascades_json(r) {
            fields.insert("cascades".to_owned(), cascades);
        }
    }
    folder.write_text("metrics.json", &serde_json::to_string_pretty(&record).unwrap_or_default())?;
    Ok(())
}

/// Each light's cascades as `metrics.json` records them (an empty list
/// for a light of one map), when any light has them: each one's slice,
/// map side, light and metrics; `None` when no light has cascades.
#[must_use]
pub fn cascades_json(r: &Render) -> Option<Value> {
    r.parts()
        .any(|p| !p.cascades.is_empty())
        .then(|| r.parts().map(|p| p.cascades.iter().map(cascade_record).collect::<Value>()).collect())
}

/// An f32 as its shortest decimal (0.55, not 0.550000011920929).
fn shortest(v: f32) -> f64 {
    v.to_string().parse::<f64>().unwrap_or(f64::from(v))
}

/// A cascade as `metrics.json` records it: the view distances its slice
/// lies between, its map's side, its light and its metrics.
fn cascade_record(c: &super::CascadePart) -> Value {
    serde_json::json!({
        "slice": c.slice.map(shortest),
        "map_side_texels": c.side,
        "light_view": light_view(&c.light),
        "metrics": serde_json::to_value(c.metrics).unwrap_or(Value::Null),
    })
}

/// A light's view as `metrics.json` records it: its kind, where it is,
/// where it looks, and its frustum.
fn light_view(light: &Light) -> Value {
    let n = shortest;
    let xyz = |v: glam::Vec3| serde_json::json!([n(v.x), n(v.y), n(v.z)]);
    match light {
        Light::Spot(p) | Light::Cone(p) => serde_json::json!({
            "kind": if matches!(light, Light::Spot(_)) { "spot" } else { "cone" },
            "position": xyz(p.position),
            "target": xyz(p.target),
            "fov_degrees": n(p.fov_degrees),
            "near": n(p.near),
            "far": n(p.far),
        }),
        Light::Directional(o, cascades) => serde_json::json!({
            "kind": "directional",
            "position": xyz(o.position),
            "target": xyz(o.target),
            "extent": n(o.extent),
            "near": n(o.near),
            "far": n(o.far),
            "cascades": cascades.to_string(),
        }),
    }
}

/// What a stored map's preview shows, by its name (`z1`, `z2`, …).
#[must_use]
pub fn map_title(name: &str) -> String {
    let what = match name {
        "z1" => "the nearest depth the light sees",
        "z2" => "the second nearest depth",
        _ => "a stored map",
    };
    format!("{name}: {what}, near dark, far light")
}
