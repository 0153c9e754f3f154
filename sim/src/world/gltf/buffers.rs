//! A glTF file's bytes and its buffers: the JSON (alone, or the first chunk
//! of a `.glb`) parsed and validated by the `gltf` crate, each buffer found
//! (the `.glb`'s binary chunk, a `data:` URI, or a file beside the glTF)
//! and checked against the length it declares, all within the limits.

use std::path::Path;

use base64::Engine as _;

use super::{Fault, GltfProblem};
use crate::input::limits::{FileError, Footprint, LimitError, Limits};

/// The JSON document and every buffer's bytes, each cut to its declared length.
pub(super) struct Loaded {
    pub(super) document: gltf::Document,
    pub(super) buffers: Vec<Vec<u8>>,
}

/// A file read within `limits`, its failure as a [`GltfProblem`].
fn read(path: &Path, limits: &Limits) -> Result<Vec<u8>, GltfProblem> {
    limits.read_file(path).map_err(|e| match e {
        FileError::Io(e) => GltfProblem::Read(e),
        FileError::NotAFile => GltfProblem::NotAFile,
        FileError::Limit(l) => GltfProblem::Limit(l),
    })
}

/// The length of the JSON a glTF file holds: the whole file, or the first
/// chunk of a `.glb`, whose header is checked here (the `gltf` crate
/// subtracts its header's size from a length it has not checked).
fn json_length(bytes: &[u8]) -> Result<usize, Fault> {
    if !bytes.starts_with(b"glTF") {
        return Ok(bytes.len());
    }
    let word = |at: usize| bytes.get(at..at + 4).and_then(|w| w.try_into().ok()).map(u32::from_le_bytes);
    let fault = |problem: String| ("(glb header)".to_owned(), GltfProblem::Syntax(problem));
    let (Some(version), Some(length), Some(json)) = (word(4), word(8), word(12)) else {
        return Err(fault(format!("a binary glTF of {} bytes is shorter than its 20-byte header", bytes.len())));
    };
    if version != 2 {
        return Err(fault(format!("binary glTF version {version}; Umbra reads version 2")));
    }
    if (length as usize) < 20 || length as usize > bytes.len() {
        return Err(fault(format!("the header gives a length of {length} bytes; the file has {}", bytes.len())));
    }
    Ok(json as usize)
}

/// The `gltf` crate's error as the JSON path it names and the problem.
fn crate_fault(e: gltf::Error) -> Fault {
    use gltf::json::validation::Error as V;
    match e {
        gltf::Error::Validation(errors) => {
            // A required extension the crate does not read is named as such.
            if let Some((path, _)) =
                errors.iter().find(|(p, e)| *e == V::Unsupported && p.as_str().contains("extensionsRequired"))
            {
                let (at, name) = path.as_str().split_once(" = ").unwrap_or((path.as_str(), ""));
                return (at.to_owned(), GltfProblem::Unsupported(name.trim_matches('"').to_owned()));
            }
            let more = errors.len().saturating_sub(1);
            let (path, problem) = errors
                .into_iter()
                .next()
                .map_or_else(|| ("(file)".to_owned(), "invalid".to_owned()), |(p, e)| (p.to_string(), e.to_string()));
            let also = if more > 0 { format!(" (and {more} more problems)") } else { String::new() };
            (path, GltfProblem::Invalid(format!("{problem}{also}")))
        }
        gltf::Error::Deserialize(e) => ("(json)".to_owned(), GltfProblem::Syntax(e.to_string())),
        gltf::Error::Binary(e) => ("(glb)".to_owned(), GltfProblem::Syntax(format!("{e:?}"))),
        other => ("(file)".to_owned(), GltfProblem::Syntax(other.to_string())),
    }
}

/// Read the glTF file at `path` and its buffers within `limits`: the file
/// and every buffer file at most [`Limits::max_file_bytes`] (all buffers
/// together too), its JSON at most [`Limits::max_text_bytes`] and its parse
/// within [`Limits::max_memory`].
pub(super) fn load(path: &Path, limits: &Limits) -> Result<Loaded, Fault> {
    let bytes = read(path, limits).map_err(|p| ("(file)".to_owned(), p))?;
    let json = json_length(&bytes)?;
    let over = |l: LimitError| ("(json)".to_owned(), GltfProblem::Limit(l));
    if json as u64 > limits.max_text_bytes {
        return Err(over(LimitError::TextBytes { bytes: json as u64, max: limits.max_text_bytes }));
    }
    let parse = (json as u64).saturating_mul(Footprint::PER_TEXT_BYTE).saturating_add(Footprint::BASE);
    limits.check_memory("parsing the glTF file's JSON", parse).map_err(over)?;
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(&bytes).map_err(crate_fault)?;
    drop(bytes);
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let mut buffers = Vec::new();
    let mut total = 0u64;
    for buffer in document.buffers() {
        let i = buffer.index();
        let key = format!("buffers[{i}]");
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.clone().ok_or_else(|| {
                (key.clone(), GltfProblem::Buffer("names the binary chunk, but the file has none".into()))
            })?,
            gltf::buffer::Source::Uri(uri) => uri_bytes(uri, dir, limits).map_err(|p| (format!("{key}.uri"), p))?,
        };
        total = total.saturating_add(data.len() as u64);
        if total > limits.max_file_bytes {
            let l = LimitError::FileBytes { bytes: total, max: limits.max_file_bytes };
            return Err((key, GltfProblem::Limit(l)));
        }
        if data.len() < buffer.length() {
            let problem = format!("declares {} bytes (byteLength), its data holds {}", buffer.length(), data.len());
            return Err((key, GltfProblem::Buffer(problem)));
        }
        data.truncate(buffer.length());
        buffers.push(data);
    }
    Ok(Loaded { document, buffers })
}

/// A buffer's bytes from its URI: a base64 `data:` URI, or a file
/// relative to the glTF's folder (percent-escapes decoded).
fn uri_bytes(uri: &str, dir: &Path, limits: &Limits) -> Result<Vec<u8>, GltfProblem> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (kind, payload) = rest.split_once(',').unwrap_or((rest, ""));
        if !kind.ends_with(";base64") {
            return Err(GltfProblem::Buffer(format!("a data URI of `{kind}`, not base64")));
        }
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| GltfProblem::Buffer(format!("its base64 does not decode: {e}")));
    }
    if uri.contains("://") {
        return Err(GltfProblem::Buffer(format!("`{uri}` is not a file beside the glTF; Umbra reads no network")));
    }
    read(&dir.join(percent_decoded(uri)?), limits)
}

/// `%XX` escapes decoded, as a URI's path holds them.
fn percent_decoded(uri: &str) -> Result<String, GltfProblem> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k] == b'%' {
            let hex = bytes.get(k + 1..k + 3).and_then(|h| std::str::from_utf8(h).ok());
            let byte = hex.and_then(|h| u8::from_str_radix(h, 16).ok());
            out.push(byte.ok_or_else(|| GltfProblem::Buffer(format!("`{uri}` has a broken %-escape at byte {k}")))?);
            k += 3;
        } else {
            out.push(bytes[k]);
            k += 1;
        }
    }
    String::from_utf8(out).map_err(|_| GltfProblem::Buffer(format!("`{uri}` decodes to bytes that are not UTF-8")))
}
