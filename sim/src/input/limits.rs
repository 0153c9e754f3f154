//! Resource limits of the simulator: how large a map, an image, a scene and
//! a file it accepts. Each is checked before anything of that size is
//! allocated, and each breach is a typed [`LimitError`] naming the quantity,
//! the value asked for and the limit.
//!
//! The core has its own, fixed bounds (a target side of at most 2¹⁴, see
//! `umbra_core::config`); these are the simulator's, below them, chosen so
//! that one render fits comfortably in a workstation's memory. They are
//! plain data: a caller that needs more builds its own [`Limits`].
//!
//! ```
//! use umbra_sim::Limits;
//! let limits = Limits::DEFAULT;
//! assert!(limits.check_map(limits.max_map_side).is_ok());
//! let err = limits.check_map(limits.max_map_side + 1).unwrap_err();
//! assert!(err.to_string().contains(&limits.max_map_side.to_string()), "{err}");
//! ```

use std::io::Read;
use std::path::Path;

/// What the simulator accepts. [`Limits::DEFAULT`] is used unless a caller
/// passes its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest light-map side, texels (a dual 24-bit map of this side is
    /// `2 · 4 · side²` bytes: 512 MiB at 8192).
    pub max_map_side: u32,
    /// Largest camera image side, pixels.
    pub max_image_side: u32,
    /// Most camera image pixels (the camera pass and the reference keep
    /// about 100 bytes per pixel).
    pub max_image_pixels: u64,
    /// Most triangles in a scene, all objects together (the reference keeps
    /// about 200 bytes per triangle).
    pub max_triangles: u64,
    /// Largest scene or mesh file, bytes.
    pub max_file_bytes: u64,
    /// Largest TOML file (a scene, a sweep, an architecture), bytes: its
    /// parse keeps about `Footprint::PER_TEXT_BYTE` bytes a byte.
    pub max_text_bytes: u64,
    /// Most objects in a scene file, counted before any mesh is built.
    pub max_objects: u64,
    /// Most memory a run may take, bytes: every render, study and scene
    /// file is bounded by its [`Footprint`] before the work starts.
    pub max_memory: u64,
}

impl Limits {
    /// The defaults: 8192² maps, 8192-pixel image sides and 2²⁵ pixels (8K
    /// UHD), 2²² triangles, 256 MiB files, 8 MiB TOML files of at most 2¹⁶
    /// objects, and 16 GiB of memory (a 24 GiB machine with room for the
    /// rest of it). The largest render these allow takes
    /// [`Footprint::render`] of 2²⁵ pixels, an 8192² map and 2²² triangles:
    /// at most 10.6 GiB.
    pub const DEFAULT: Self = Self {
        max_map_side: 8192,
        max_image_side: 8192,
        max_image_pixels: 1 << 25,
        max_triangles: 1 << 22,
        max_file_bytes: 256 << 20,
        max_text_bytes: 8 << 20,
        max_objects: 1 << 16,
        max_memory: 16 << 30,
    };

    /// The share of the machine's physical memory a run may take by
    /// default, `(numerator, denominator)`: three quarters, leaving the
    /// rest to the system and whatever else runs.
    pub const MACHINE_SHARE: (u64, u64) = (3, 4);

    /// [`Limits::DEFAULT`] with [`Limits::max_memory`] at
    /// [`Limits::MACHINE_SHARE`] of this machine's physical memory (18 GiB
    /// of 24), or the default 16 GiB where it cannot be read.
    #[must_use]
    pub fn for_machine() -> Self {
        let (n, d) = Self::MACHINE_SHARE;
        let max_memory = physical_memory().map_or(Self::DEFAULT.max_memory, |bytes| bytes / d * n);
        Self { max_memory, ..Self::DEFAULT }
    }

    /// Check the memory a run will take, `footprint` bytes, before it starts.
    ///
    /// # Errors
    /// [`LimitError::Memory`] above [`Limits::max_memory`], naming `what`.
    pub(crate) const fn check_memory(&self, what: &'static str, footprint: u64) -> Result<(), LimitError> {
        if footprint > self.max_memory {
            return Err(LimitError::Memory { what, bytes: footprint, max: self.max_memory });
        }
        Ok(())
    }

    /// Check an object count.
    ///
    /// # Errors
    /// [`LimitError::Objects`] above [`Limits::max_objects`].
    pub(crate) const fn check_objects(&self, objects: u64) -> Result<(), LimitError> {
        if objects > self.max_objects {
            return Err(LimitError::Objects { objects, max: self.max_objects });
        }
        Ok(())
    }

    /// Check a light-map side.
    ///
    /// # Errors
    /// [`LimitError::MapSide`] above [`Limits::max_map_side`].
    pub const fn check_map(&self, side: u32) -> Result<(), LimitError> {
        if side > self.max_map_side {
            return Err(LimitError::MapSide { side, max: self.max_map_side });
        }
        Ok(())
    }

    /// Check a camera image size.
    ///
    /// # Errors
    /// [`LimitError::ImageSide`] or [`LimitError::ImagePixels`].
    pub(crate) const fn check_image(&self, width: u32, height: u32) -> Result<(), LimitError> {
        let side = if width > height { width } else { height };
        if side > self.max_image_side {
            return Err(LimitError::ImageSide { side, max: self.max_image_side });
        }
        let pixels = width as u64 * height as u64;
        if pixels > self.max_image_pixels {
            return Err(LimitError::ImagePixels { width, height, max: self.max_image_pixels });
        }
        Ok(())
    }

    /// Check a triangle count.
    ///
    /// # Errors
    /// [`LimitError::Triangles`] above [`Limits::max_triangles`].
    pub(crate) const fn check_triangles(&self, triangles: u64) -> Result<(), LimitError> {
        if triangles > self.max_triangles {
            return Err(LimitError::Triangles { triangles, max: self.max_triangles });
        }
        Ok(())
    }

    /// Read a whole regular file of at most [`Limits::max_file_bytes`],
    /// never reading past the limit (files that grow included). A
    /// directory, pipe, socket or device is refused before it is opened
    /// (opening a pipe blocks until a writer comes), and the open itself
    /// does not wait, should one replace the file in between.
    ///
    /// # Errors
    /// [`FileError::Io`] when it cannot be opened or read,
    /// [`FileError::NotAFile`] for a directory, device, socket or pipe,
    /// [`FileError::Limit`] when it is larger than the limit.
    pub fn read_file(&self, path: &Path) -> Result<Vec<u8>, FileError> {
        crate::base::reads::note(path);
        Self::read_within(path, self.max_file_bytes, |bytes, max| LimitError::FileBytes { bytes, max })
    }

    /// [`Limits::read_file`] of a file a run of Umbra wrote (a study's
    /// rows read back to merge or resume), which, unlike an input, a later
    /// run may replace: not noted as read ([`crate::base::reads`]).
    ///
    /// # Errors
    /// As [`Limits::read_file`].
    pub(crate) fn read_output(&self, path: &Path) -> Result<Vec<u8>, FileError> {
        Self::read_within(path, self.max_file_bytes, |bytes, max| LimitError::FileBytes { bytes, max })
    }

    /// [`Limits::read_file`] for a TOML file (a scene, a sweep, an
    /// architecture): at most [`Limits::max_text_bytes`], since its parse
    /// takes many times its size.
    ///
    /// # Errors
    /// As [`Limits::read_file`], with [`LimitError::TextBytes`], and
    /// [`LimitError::Memory`] when its parse would not fit
    /// [`Limits::max_memory`].
    pub fn read_text_file(&self, path: &Path) -> Result<Vec<u8>, FileError> {
        crate::base::reads::note(path);
        let bytes = Self::read_within(path, self.max_text_bytes, |bytes, max| LimitError::TextBytes { bytes, max })?;
        let parse = (bytes.len() as u64).saturating_mul(Footprint::PER_TEXT_BYTE).saturating_add(Footprint::BASE);
        self.check_memory("parsing the TOML file", parse).map_err(FileError::Limit)?;
        Ok(bytes)
    }

    fn read_within(path: &Path, max: u64, over: fn(u64, u64) -> LimitError) -> Result<Vec<u8>, FileError> {
        if !std::fs::metadata(path)?.is_file() {
            return Err(FileError::NotAFile);
        }
        let mut options = std::fs::OpenOptions::new();
        options.read(true);
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
        let file = options.open(path)?;
        let meta = file.metadata()?;
        if !meta.is_file() {
            return Err(FileError::NotAFile);
        }
        if meta.len() > max {
            return Err(FileError::Limit(over(meta.len(), max)));
        }
        let mut bytes = Vec::new();
        file.take(max.saturating_add(1)).read_to_end(&mut bytes)?;
        let read = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
        if read > max {
            return Err(FileError::Limit(over(read, max)));
        }
        Ok(bytes)
    }
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A request beyond a [`Limits`] value. Its message names the field of
/// [`Limits`] to raise (the `umbra` command's option of the same name:
/// `max_map_side` is `--max-map-side`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// A light map wider or taller than allowed.
    #[error("map side {side} is above the limit of {max} (`max_map_side`)")]
    MapSide {
        /// The side asked for.
        side: u32,
        /// The limit.
        max: u32,
    },
    /// A camera image wider or taller than allowed.
    #[error("image side {side} is above the limit of {max} (`max_image_side`)")]
    ImageSide {
        /// The larger side asked for.
        side: u32,
        /// The limit.
        max: u32,
    },
    /// A camera image of too many pixels.
    #[error("image {width}x{height} has more pixels than the limit of {max} (`max_image_pixels`)")]
    ImagePixels {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// The limit.
        max: u64,
    },
    /// A scene of too many triangles.
    #[error("{triangles} triangles is above the limit of {max} (`max_triangles`)")]
    Triangles {
        /// Triangles asked for (so far, when counted object by object).
        triangles: u64,
        /// The limit.
        max: u64,
    },
    /// An OBJ file of too many primitives: its triangles, and the polyline
    /// segments and points it holds besides (ignored, but read).
    #[error(
        "{primitives} primitives, {triangles} of them triangles and the rest polyline segments and points, is above the limit of {max} (`max_triangles`)"
    )]
    Primitives {
        /// Triangles, segments and points.
        primitives: u64,
        /// The triangles among them.
        triangles: u64,
        /// The limit.
        max: u64,
    },
    /// A file larger than allowed.
    #[error("file of {bytes} bytes is above the limit of {max} (`max_file_bytes`)")]
    FileBytes {
        /// Its size (at least; reading stops past the limit).
        bytes: u64,
        /// The limit.
        max: u64,
    },
    /// A TOML file larger than allowed.
    #[error("TOML file of {bytes} bytes is above the limit of {max} (`max_text_bytes`)")]
    TextBytes {
        /// Its size (at least; reading stops past the limit).
        bytes: u64,
        /// The limit.
        max: u64,
    },
    /// A scene file of too many objects.
    #[error("{objects} objects is above the limit of {max} (`max_objects`)")]
    Objects {
        /// Objects in the file.
        objects: u64,
        /// The limit.
        max: u64,
    },
    /// A run that would take more memory than allowed.
    #[error(
        "{what} would take up to {} MiB, above the limit of {} MiB (`max_memory`)",
        bytes.div_ceil(1 << 20),
        max / (1 << 20)
    )]
    Memory {
        /// What would take it (`the render`, `the study`).
        what: &'static str,
        /// Its [`Footprint`], bytes.
        bytes: u64,
        /// The limit.
        max: u64,
    },
}

/// This machine's physical memory, bytes, where the system says
/// (`MemTotal` of Linux's `/proc/meminfo`); `None` elsewhere.
#[must_use]
pub fn physical_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let total = text.lines().find_map(|l| l.strip_prefix("MemTotal:"))?;
    let kib: u64 = total.trim().strip_suffix("kB")?.trim().parse().ok()?;
    kib.checked_mul(1024)
}

/// The memory model a run is bounded by: upper bounds, in bytes, of what
/// the simulator keeps for each pixel, texel, triangle and byte of TOML,
/// measured as peak resident memory (and held by the tests that run the
/// `umbra` command under a `--max-memory` equal to its footprint).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Footprint;

impl Footprint {
    /// The process, its code, thread stacks and small tables.
    pub(crate) const BASE: u64 = 96 << 20;
    /// A camera pixel: the camera pass's image and bins, its reference,
    /// the metrics' per-pixel verdicts and the pictures written from them
    /// (about 70 measured).
    pub(crate) const PER_PIXEL: u64 = 160;
    /// A light-map texel: two 32-bit z-buffers, the bins (8 bytes a texel
    /// with 8-texel tiles) and the map's picture (about 14 measured with
    /// 32-texel tiles).
    pub(crate) const PER_TEXEL: u64 = 24;
    /// A scene triangle: the mesh, the passes' transformed copies and the
    /// reference's bounding-volume hierarchy (about 600 measured).
    pub(crate) const PER_TRIANGLE: u64 = 1024;
    /// A byte of a TOML file while it is parsed.
    pub(crate) const PER_TEXT_BYTE: u64 = 96;

    /// A glTF vertex as an accessor is decoded: its position read (12
    /// bytes) and its new number once the unused are dropped (4).
    pub(crate) const PER_VERTEX_DECODED: u64 = 16;
    /// A glTF index as an accessor is decoded.
    pub(crate) const PER_INDEX_DECODED: u64 = 4;
    /// A vertex a mesh keeps: its position.
    pub(crate) const PER_VERTEX: u64 = 12;
    /// A triangle a mesh keeps: its three indices.
    pub(crate) const PER_MESH_TRIANGLE: u64 = 12;
    /// A glTF node as the walk of its tree keeps it (its world transform
    /// and its place on the stack).
    pub(crate) const PER_GLTF_NODE: u64 = 512;

    /// A further light's share of a scene triangle: the scene lit by it
    /// alone (its meshes copied) and the shading unit's triangle list.
    pub(crate) const PER_LIGHT_TRIANGLE: u64 = 128;

    /// One render (or costing) of `pixels` camera pixels, a map of side
    /// `map_side` and `triangles`, its reference included.
    #[must_use]
    pub const fn render(pixels: u64, map_side: u32, triangles: u64) -> u64 {
        Self::render_lit(pixels, map_side, triangles, 1)
    }

    /// [`Footprint::render`] of a scene of `lights` lights: each a map, a
    /// shading and a reference of its own, and a copy of the scene.
    #[must_use]
    pub const fn render_lit(pixels: u64, map_side: u32, triangles: u64, lights: u64) -> u64 {
        let texels = map_side as u64 * map_side as u64;
        let lights = if lights == 0 { 1 } else { lights };
        Self::BASE
            .saturating_add(pixels.saturating_mul(Self::PER_PIXEL).saturating_mul(lights))
            .saturating_add(texels.saturating_mul(Self::PER_TEXEL).saturating_mul(lights))
            .saturating_add(triangles.saturating_mul(Self::PER_TRIANGLE))
            .saturating_add(triangles.saturating_mul(Self::PER_LIGHT_TRIANGLE).saturating_mul(lights - 1))
    }
}

/// Why [`Limits::read_file`] failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// The file cannot be opened or read.
    #[error("cannot read: {0}")]
    Io(#[from] std::io::Error),
    /// Not a regular file.
    #[error("not a regular file")]
    NotAFile,
    /// Larger than the limit.
    #[error(transparent)]
    Limit(LimitError),
}

#[cfg(test)]
mod tests {
    use super::Footprint;

    /// `docs/reliability.md` states the allowances the memory bounds use:
    /// each as the constant it names, so the page cannot go stale.
    #[test]
    fn the_reliability_page_states_the_allowances() {
        let page = include_str!("../../../docs/reliability.md").split_whitespace().collect::<Vec<_>>().join(" ");
        for stated in [
            format!("{} MiB, plus {} bytes a camera pixel", Footprint::BASE >> 20, Footprint::PER_PIXEL),
            format!("{} a map texel and {} a triangle", Footprint::PER_TEXEL, Footprint::PER_TRIANGLE),
            format!(
                "the {} MiB base, the JSON held ({} bytes a byte)",
                Footprint::BASE >> 20,
                Footprint::PER_TEXT_BYTE
            ),
            format!(
                "{} bytes a node, {} bytes a declared vertex and {} an index",
                Footprint::PER_GLTF_NODE,
                Footprint::PER_VERTEX_DECODED,
                Footprint::PER_INDEX_DECODED
            ),
            format!(
                "{} bytes a vertex it keeps and {} a triangle",
                Footprint::PER_VERTEX,
                Footprint::PER_MESH_TRIANGLE
            ),
        ] {
            assert!(page.contains(&stated), "docs/reliability.md does not say `{stated}`");
        }
    }

    /// The default memory bound is three quarters of the memory the system
    /// reports, read here independently (`getconf`'s pages × page size,
    /// which counts a little more than `MemTotal`: the kernel's own
    /// reservation).
    #[cfg(target_os = "linux")]
    #[test]
    fn the_default_memory_bound_follows_the_machine() {
        let conf = |name: &str| -> Option<u64> {
            let o = std::process::Command::new("getconf").arg(name).output().ok()?;
            String::from_utf8_lossy(&o.stdout).trim().parse().ok()
        };
        let physical = conf("_PHYS_PAGES").zip(conf("PAGE_SIZE")).map(|(p, s)| p * s).expect("getconf reports memory");
        let bound = super::Limits::for_machine().max_memory;
        assert!(bound <= physical / 4 * 3, "{bound} of {physical}");
        assert!(bound >= physical / 100 * 70, "{bound} of {physical}: MemTotal is within 7 % of the pages");
    }
}
