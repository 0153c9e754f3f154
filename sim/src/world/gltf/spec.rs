//! The glTF 2.0 specification's rules that the `gltf` crate's validation
//! leaves out, checked on the validated document before anything reads
//! it: `asset.version` 2.x; cameras whose planes and magnifications make
//! a view (§5.12–5.14: `aspectRatio` > 0, `yfov` > 0, `znear` > 0, `zfar` >
//! `znear`, `xmag`/`ymag` finite and non-zero, all finite); node transforms
//! (§3.5.2: a `matrix` or translation–rotation–scale, not both; a matrix
//! whose last row is (0, 0, 0, 1); a unit rotation quaternion); buffer
//! views' strides (§5.11: 4 to 252, a multiple of 4) and accessors'
//! offsets (§3.6.2.4: a multiple of the component size). Each refusal
//! names the JSON path of what breaks the rule.

use super::{Fault, GltfProblem};

/// How far a rotation's length may be from 1 (exporters write f32
/// quaternions normalised to about 10⁻⁷; the glTF validator allows 10⁻⁵
/// of the squared length: this is looser, for files written by hand).
const UNIT_TOLERANCE: f64 = 1e-3;

/// A problem at `path`.
fn fault(path: String, problem: String) -> Fault {
    (path, GltfProblem::Spec(problem))
}

/// Every rule above, on a validated document.
pub(super) fn check(document: &gltf::Document) -> Result<(), Fault> {
    let json = document.as_json();
    let version = json.asset.version.as_str();
    if version.split('.').next() != Some("2") {
        return Err(fault("asset.version".into(), format!("is \"{version}\"; Umbra reads glTF 2.x")));
    }
    for (i, c) in json.cameras.iter().enumerate() {
        camera(i, c)?;
    }
    for (i, n) in json.nodes.iter().enumerate() {
        node(i, n)?;
    }
    for (i, v) in json.buffer_views.iter().enumerate() {
        if let Some(stride) = v.byte_stride.map(|s| s.0)
            && (!(4..=252).contains(&stride) || stride % 4 != 0)
        {
            let problem = format!("is {stride}; a stride is 4 to 252 bytes, a multiple of 4");
            return Err(fault(format!("bufferViews[{i}].byteStride"), problem));
        }
    }
    for a in document.accessors() {
        let size = a.data_type().size();
        let view = a.view().map_or(0, |v| v.offset());
        if a.offset() % size != 0 || view % size != 0 {
            let problem = format!(
                "starts at byte {} of its buffer (byteOffset {}), not a multiple of its component's {size} bytes",
                view + a.offset(),
                a.offset()
            );
            return Err(fault(format!("accessors[{}].byteOffset", a.index()), problem));
        }
    }
    Ok(())
}

/// A camera's projection (§5.12–5.14).
fn camera(i: usize, c: &gltf::json::Camera) -> Result<(), Fault> {
    let at = |what: &str| format!("cameras[{i}].{what}");
    let positive = |path: String, name: &str, v: f32| {
        if v.is_finite() && v.is_normal() && v > 0.0 {
            Ok(())
        } else {
            Err(fault(path, format!("{name} {v} must be a positive, finite, normal number")))
        }
    };
    if let Some(p) = &c.perspective {
        if let Some(aspect) = p.aspect_ratio {
            positive(at("perspective.aspectRatio"), "aspectRatio", aspect)?;
        }
        positive(at("perspective.yfov"), "yfov", p.yfov)?;
        positive(at("perspective.znear"), "znear", p.znear)?;
        if let Some(far) = p.zfar
            && !(far.is_finite() && far > p.znear)
        {
            return Err(fault(
                at("perspective.zfar"),
                format!("zfar {far} must be finite and beyond znear {}", p.znear),
            ));
        }
    }
    if let Some(o) = &c.orthographic {
        for (name, v) in [("xmag", o.xmag), ("ymag", o.ymag)] {
            if !(v.is_finite() && v != 0.0) {
                return Err(fault(
                    at(&format!("orthographic.{name}")),
                    format!("{name} {v} must be finite and not zero"),
                ));
            }
        }
        if !(o.znear.is_finite() && o.znear >= 0.0) {
            return Err(fault(at("orthographic.znear"), format!("znear {} must be finite and not negative", o.znear)));
        }
        if !(o.zfar.is_finite() && o.zfar > o.znear) {
            return Err(fault(
                at("orthographic.zfar"),
                format!("zfar {} must be finite and beyond znear {}", o.zfar, o.znear),
            ));
        }
    }
    Ok(())
}

/// A node's transform (§3.5.2).
fn node(i: usize, n: &gltf::json::Node) -> Result<(), Fault> {
    let at = |what: &str| format!("nodes[{i}]{what}");
    if let Some(m) = &n.matrix {
        if n.translation.is_some() || n.rotation.is_some() || n.scale.is_some() {
            let problem = "has both a matrix and translation, rotation or scale; a node has one or the other";
            return Err(fault(at(""), problem.into()));
        }
        // Column-major: the last row is elements 3, 7, 11 and 15.
        let row = [m[3], m[7], m[11], m[15]];
        if row != [0.0, 0.0, 0.0, 1.0] {
            let problem = format!("its last row is {row:?}, not [0, 0, 0, 1]: a node's matrix is affine");
            return Err(fault(at(".matrix"), problem));
        }
    }
    if let Some(r) = &n.rotation {
        let length = r.0.iter().map(|&x| f64::from(x) * f64::from(x)).sum::<f64>().sqrt();
        let unit = (length - 1.0).abs() <= UNIT_TOLERANCE;
        if !unit {
            let problem = format!("has length {length:.6}; a rotation is a unit quaternion (within {UNIT_TOLERANCE})");
            return Err(fault(at(".rotation"), problem));
        }
    }
    Ok(())
}
