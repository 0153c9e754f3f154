//! A glTF file's bytes and its buffers: the JSON (alone, or the first chunk
//! of a `.glb`, whose header and chunks are checked here) parsed and
//! validated — first what the `gltf` crate's validation would index
//! unchecked, then the crate's validation, then the specification's rules
//! it leaves out ([`super::spec`]) — and each buffer found (the `.glb`'s
//! binary chunk, a `data:` URI, or a file in the model's own folder) and
//! checked against the length it declares, all within the limits.
//!
//! A buffer's file is confined to the model's folder (or a folder the
//! user allowed, [`crate::base::reads::allow_folder`]): its URI is
//! percent-decoded and normalised, and an absolute path, a `..` that
//! climbs out, a scheme other than `data:`, a symbolic link that leads
//! out, or a system file (`/proc`, `/sys`) is refused by name before a
//! byte of it is read (a device, pipe or socket is refused by
//! [`Limits::read_file`] before it is opened).

use std::path::{Path, PathBuf};

use base64::Engine as _;

use super::{Fault, GltfProblem};
use crate::input::limits::{FileError, Footprint, LimitError, Limits};

/// A glTF file parsed and validated, its buffers not yet read.
pub(super) struct Parsed {
    pub(super) document: gltf::Document,
    /// The `.glb`'s binary chunk.
    pub(super) blob: Option<Vec<u8>>,
    /// The bytes of its JSON.
    pub(super) json_bytes: u64,
}

/// A file read within `limits`, its failure as a [`GltfProblem`].
fn read(path: &Path, limits: &Limits) -> Result<Vec<u8>, GltfProblem> {
    limits.read_file(path).map_err(|e| match e {
        FileError::Io(e) => GltfProblem::Read(e),
        FileError::NotAFile => GltfProblem::NotAFile,
        FileError::Limit(l) => GltfProblem::Limit(l),
    })
}

/// A chunk type as a message names it: its four letters where they are
/// printable, else its bytes in hex.
fn chunk_type(word: u32) -> String {
    let bytes = word.to_le_bytes();
    if bytes.iter().all(|b| b.is_ascii_graphic() || *b == 0) {
        format!("`{}`", String::from_utf8_lossy(&bytes).trim_end_matches('\0'))
    } else {
        format!("0x{word:08x}")
    }
}

/// The JSON chunk's type, `JSON`.
const JSON_CHUNK: u32 = 0x4E4F_534A;
/// The binary chunk's type, `BIN\0`.
const BIN_CHUNK: u32 = 0x004E_4942;

/// A glTF file's JSON and, of a `.glb`, its binary chunk: the header's
/// version and length and each chunk's length checked against the file,
/// chunks of other types skipped (as the specification asks).
fn split(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), Fault> {
    if !bytes.starts_with(b"glTF") {
        return Ok((bytes, None));
    }
    let word = |at: usize| bytes.get(at..at + 4).and_then(|w| w.try_into().ok()).map(u32::from_le_bytes);
    let fault = |at: &str, problem: String| (at.to_owned(), GltfProblem::Syntax(problem));
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(fault(
            "(glb header)",
            format!("a binary glTF of {} bytes is shorter than its 12-byte header", bytes.len()),
        ));
    };
    if version != 2 {
        return Err(fault("(glb header)", format!("binary glTF version {version}; Umbra reads version 2")));
    }
    let length = length as usize;
    if length > bytes.len() || length < 20 {
        return Err(fault(
            "(glb header)",
            format!(
                "the header gives a length of {length} bytes; the file has {} (and a JSON chunk needs 20)",
                bytes.len()
            ),
        ));
    }
    let bytes = &bytes[..length];
    let (Some(json_length), Some(kind)) = (word(12), word(16)) else {
        return Err(fault("(glb chunk 0)", "the file ends inside the JSON chunk's header".into()));
    };
    if kind != JSON_CHUNK {
        return Err(fault("(glb chunk 0)", format!("the first chunk is of type {}, not `JSON`", chunk_type(kind))));
    }
    let json = 20usize.checked_add(json_length as usize).and_then(|end| bytes.get(20..end)).ok_or_else(|| {
        fault(
            "(glb chunk 0)",
            format!("the JSON chunk declares {json_length} bytes; the file has {} after its headers", length - 20),
        )
    })?;
    // Further chunks: the first `BIN` one is the buffer; others are skipped.
    let mut at = 20 + json.len();
    let mut index = 1;
    while at < length {
        let (Some(chunk_length), Some(kind)) = (word(at), word(at + 4)) else {
            return Err(fault(&format!("(glb chunk {index})"), "the file ends inside the chunk's header".into()));
        };
        let start = at + 8;
        let data = start.checked_add(chunk_length as usize).and_then(|end| bytes.get(start..end)).ok_or_else(|| {
            fault(
                &format!("(glb chunk {index})"),
                format!(
                    "the chunk of type {} declares {chunk_length} bytes; the file has {} after its header",
                    chunk_type(kind),
                    length.saturating_sub(start)
                ),
            )
        })?;
        if kind == BIN_CHUNK {
            return Ok((json, Some(data)));
        }
        at = start + data.len();
        index += 1;
    }
    Ok((json, None))
}

/// The `gltf` crate's validation error as the JSON path it names and the
/// problem.
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
        other => ("(file)".to_owned(), GltfProblem::Syntax(other.to_string())),
    }
}

/// What the `gltf` crate's validation indexes without checking: each
/// primitive's `POSITION` accessor (its check of `min` and `max`).
fn unchecked_indices(root: &gltf::json::Root) -> Result<(), Fault> {
    use gltf::json::validation::Checked;
    let accessors = root.accessors.len();
    for (i, mesh) in root.meshes.iter().enumerate() {
        for (j, p) in mesh.primitives.iter().enumerate() {
            let position = p.attributes.get(&Checked::Valid(gltf::json::mesh::Semantic::Positions));
            if let Some(a) = position.filter(|a| a.value() >= accessors) {
                let problem = format!("names accessors[{}]; the file has {accessors} accessors", a.value());
                return Err((
                    format!("meshes[{i}].primitives[{j}].attributes.POSITION"),
                    GltfProblem::Invalid(problem),
                ));
            }
        }
    }
    Ok(())
}

/// Read and validate the glTF file at `path` within `limits`: the file at
/// most [`Limits::max_file_bytes`], its JSON at most
/// [`Limits::max_text_bytes`] and its parse within [`Limits::max_memory`].
/// Its buffers are not read ([`load`] reads them).
pub(super) fn parse(path: &Path, limits: &Limits) -> Result<Parsed, Fault> {
    let bytes = read(path, limits).map_err(|p| ("(file)".to_owned(), p))?;
    let (json, blob) = split(&bytes)?;
    let over = |l: LimitError| ("(json)".to_owned(), GltfProblem::Limit(l));
    let json_bytes = json.len() as u64;
    if json_bytes > limits.max_text_bytes {
        return Err(over(LimitError::TextBytes { bytes: json_bytes, max: limits.max_text_bytes }));
    }
    limits.check_memory("parsing the glTF file's JSON", parse_footprint(json_bytes)).map_err(over)?;
    if json.starts_with(b"\xEF\xBB\xBF") {
        let problem = "the JSON begins with a UTF-8 byte-order mark, which glTF forbids: save it as UTF-8 without one";
        return Err(("(json)".to_owned(), GltfProblem::Syntax(problem.into())));
    }
    let root: gltf::json::Root = gltf::json::deserialize::from_slice(json)
        .map_err(|e| ("(json)".to_owned(), GltfProblem::Syntax(e.to_string())))?;
    unchecked_indices(&root)?;
    let document = gltf::Document::from_json(root).map_err(crate_fault)?;
    super::spec::check(&document)?;
    Ok(Parsed { document, blob: blob.map(<[u8]>::to_vec), json_bytes })
}

/// The memory a JSON of `bytes` takes while parsed and held.
pub(super) const fn parse_footprint(bytes: u64) -> u64 {
    bytes.saturating_mul(Footprint::PER_TEXT_BYTE).saturating_add(Footprint::BASE)
}

/// Every buffer's bytes, each cut to its declared length: the binary
/// chunk, a `data:` URI's, or a file in the folder of the glTF file at
/// `path`; every buffer file at most [`Limits::max_file_bytes`], all
/// buffers together too.
pub(super) fn load(
    document: &gltf::Document,
    blob: &mut Option<Vec<u8>>,
    path: &Path,
    limits: &Limits,
) -> Result<Vec<Vec<u8>>, Fault> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."));
    let mut buffers = Vec::new();
    let mut sizes: Vec<String> = Vec::new();
    let mut total = 0u64;
    for buffer in document.buffers() {
        let i = buffer.index();
        let key = format!("buffers[{i}]");
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                (
                    key.clone(),
                    GltfProblem::Buffer(
                        "names the binary chunk, but the file has none (or another buffer took it)".into(),
                    ),
                )
            })?,
            gltf::buffer::Source::Uri(uri) => uri_bytes(uri, dir, limits).map_err(|p| (format!("{key}.uri"), p))?,
        };
        total = total.saturating_add(data.len() as u64);
        sizes.push(format!("{key} {} bytes", data.len()));
        if total > limits.max_file_bytes {
            let problem = format!(
                "the buffers together are {total} bytes ({}), above the limit of {} (`max_file_bytes`)",
                sizes.join(", "),
                limits.max_file_bytes
            );
            return Err((key, GltfProblem::Buffer(problem)));
        }
        if data.len() < buffer.length() {
            let problem = format!("declares {} bytes (byteLength), its data holds {}", buffer.length(), data.len());
            return Err((key, GltfProblem::Buffer(problem)));
        }
        data.truncate(buffer.length());
        buffers.push(data);
    }
    Ok(buffers)
}

/// A buffer's bytes from its URI: a base64 `data:` URI, or a file in the
/// glTF's folder `dir` ([`confined`]).
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
    read(&confined(uri, dir)?, limits)
}

/// The file a relative URI names inside `dir`, the model's folder: a path
/// that stays inside it once percent-decoded and normalised, and still
/// does once every symbolic link on the way is followed (or lies in a
/// folder the user allowed); not a device or system file. Nothing is read.
pub(super) fn confined(uri: &str, dir: &Path) -> Result<PathBuf, GltfProblem> {
    let refuse = |why: &str| {
        GltfProblem::Outside(format!(
            "`{uri}` {why}; a buffer is a data: URI or a file in the model's folder (allow another folder with --allow-read, in Python umbra.allow_read)"
        ))
    };
    let scheme = uri.split_once(':').map(|(s, _)| s).filter(|s| {
        s.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && s.chars().all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    if let Some(scheme) = scheme {
        return Err(refuse(&format!("is a `{scheme}:` URI (Umbra reads no network and no other scheme)")));
    }
    let decoded = percent_decoded(uri)?;
    if decoded.contains('\0') {
        return Err(refuse("holds a NUL byte"));
    }
    if decoded.starts_with(['/', '\\']) || Path::new(&decoded).is_absolute() {
        return Err(refuse("is an absolute path"));
    }
    let mut parts: Vec<&str> = Vec::new();
    for part in decoded.split(['/', '\\']) {
        match part {
            "" | "." => {}
            ".." => {
                if parts.pop().is_none() {
                    return Err(refuse("climbs out of the model's folder with `..`"));
                }
            }
            p => parts.push(p),
        }
    }
    if parts.is_empty() {
        return Err(refuse("names the model's folder itself, not a file"));
    }
    let joined: PathBuf = parts.iter().fold(dir.to_owned(), |p, part| p.join(part));
    let real = std::fs::canonicalize(&joined).map_err(GltfProblem::Read)?;
    let root = std::fs::canonicalize(dir).map_err(GltfProblem::Read)?;
    if ["/proc", "/sys"].iter().any(|s| real.starts_with(s)) {
        return Err(refuse(&format!("leads to {}, a system file", real.display())));
    }
    if !real.starts_with(&root) && !crate::base::reads::allowed(&real) {
        return Err(refuse("leads out of the model's folder through a symbolic link"));
    }
    Ok(real)
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
