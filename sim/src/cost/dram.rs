//! DRAM traffic by purpose: the byte side of a pass's ledger. Every byte a
//! pass moves is charged to one [`Purpose`] as it is moved, and every
//! total is the sum of the purposes ([`Dram::total`]), never kept beside
//! them.

use serde::Serialize;
use serde::ser::SerializeMap;

/// What a DRAM byte was moved for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(usize)]
pub enum Purpose {
    /// Map texels written by the light pass's resolve.
    MapWrites,
    /// A tile's depth loaded back on chip by a later flush of its bins
    /// (the map's in the light pass, the visibility's in the camera pass).
    TileReloads,
    /// Two maps read and one written by the pass combining them (a second
    /// depth by a second light pass).
    MapCombine,
    /// Depth kept off chip, read and written per fragment: cache lines
    /// fetched and written back, or every access when uncached.
    OffChipDepth,
    /// Map texels the shadow unit read, without a map cache.
    MapReads,
    /// Silhouette points the shadow unit read, without a map cache.
    SilhouetteReads,
    /// Lines the map cache fetched (map texels and silhouette points).
    MapCacheFills,
    /// Shaded pixels' colour written to the frame buffer.
    Colour,
    /// Bins and setup records, written at binning and read at a flush.
    Bins,
    /// Silhouette points written by the silhouette pass.
    SilhouetteWrites,
    /// Scene depth read by shadow-volume fragments (stencil off chip).
    VolumeDepthReads,
    /// Stencil read and written by shadow-volume fragments (off chip).
    Stencil,
}

impl Purpose {
    /// Every purpose, in the order reports list them.
    pub const ALL: [Self; 12] = [
        Self::MapWrites,
        Self::TileReloads,
        Self::MapCombine,
        Self::OffChipDepth,
        Self::MapReads,
        Self::SilhouetteReads,
        Self::MapCacheFills,
        Self::Colour,
        Self::Bins,
        Self::SilhouetteWrites,
        Self::VolumeDepthReads,
        Self::Stencil,
    ];

    /// Its name in files (`cost.json`, the stats file, the rows).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::MapWrites => "map_writes",
            Self::TileReloads => "tile_reloads",
            Self::MapCombine => "map_combine",
            Self::OffChipDepth => "off_chip_depth",
            Self::MapReads => "map_reads",
            Self::SilhouetteReads => "silhouette_reads",
            Self::MapCacheFills => "map_cache_fills",
            Self::Colour => "colour",
            Self::Bins => "bins",
            Self::SilhouetteWrites => "silhouette_writes",
            Self::VolumeDepthReads => "volume_depth_reads",
            Self::Stencil => "stencil",
        }
    }

    /// Its name in words, as a report's sentence gives it.
    #[must_use]
    pub const fn words(self) -> &'static str {
        match self {
            Self::MapWrites => "map writes",
            Self::TileReloads => "tile reloads",
            Self::MapCombine => "combining maps",
            Self::OffChipDepth => "off-chip depth",
            Self::MapReads => "map reads",
            Self::SilhouetteReads => "silhouette reads",
            Self::MapCacheFills => "map-cache fills",
            Self::Colour => "colour",
            Self::Bins => "bins",
            Self::SilhouetteWrites => "silhouette writes",
            Self::VolumeDepthReads => "volume depth reads",
            Self::Stencil => "stencil",
        }
    }

    /// What it counts, as the stats file explains it.
    #[must_use]
    pub const fn meaning(self) -> &'static str {
        match self {
            Self::MapWrites => "map texels written by the light pass's resolve",
            Self::TileReloads => "tile depth loaded back on chip by a later flush of its bins",
            Self::MapCombine => "two maps read and one written by the pass combining them",
            Self::OffChipDepth => "depth kept off chip, read and written per fragment",
            Self::MapReads => "map texels the shadow unit read without a map cache",
            Self::SilhouetteReads => "silhouette points the shadow unit read without a map cache",
            Self::MapCacheFills => "lines the map cache fetched",
            Self::Colour => "shaded pixels' colour written to the frame buffer",
            Self::Bins => "bins and setup records written and read",
            Self::SilhouetteWrites => "silhouette points written by the silhouette pass",
            Self::VolumeDepthReads => "scene depth read by shadow-volume fragments",
            Self::Stencil => "stencil read and written by shadow-volume fragments",
        }
    }
}

/// DRAM traffic by purpose, bytes: one entry per [`Purpose`]. Written as
/// a map from each purpose's name to its bytes (its total beside it, where
/// it is written, is [`Dram::total`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dram([u64; 12]);

impl Dram {
    /// The bytes moved for `purpose`.
    #[must_use]
    pub const fn get(&self, purpose: Purpose) -> u64 {
        self.0[purpose as usize]
    }

    /// Charge `bytes` to `purpose`.
    pub(crate) const fn add(&mut self, purpose: Purpose, bytes: u64) {
        self.0[purpose as usize] += bytes;
    }

    /// Every byte, the sum of the purposes.
    #[must_use]
    pub fn total(&self) -> u64 {
        self.0.iter().sum()
    }

    /// Both added, purpose by purpose.
    #[must_use]
    pub(crate) fn plus(&self, o: &Self) -> Self {
        let mut d = *self;
        d.0.iter_mut().zip(o.0).for_each(|(a, b)| *a += b);
        d
    }

    /// Every purpose `k` times.
    #[must_use]
    pub(crate) fn times(&self, k: u64) -> Self {
        Self(self.0.map(|b| b * k))
    }

    /// Every purpose's bytes with its name, in [`Purpose::ALL`] order.
    pub fn fields(&self) -> impl Iterator<Item = (Purpose, u64)> + '_ {
        Purpose::ALL.into_iter().map(|p| (p, self.get(p)))
    }

    /// The purposes that moved bytes, in words, as a report's sentence
    /// lists them (`map writes 2777088, bins 1084056`); "none" for none.
    #[must_use]
    pub(crate) fn words(&self) -> String {
        let parts: Vec<String> =
            self.fields().filter(|&(_, b)| b > 0).map(|(p, b)| format!("{} {b}", p.words())).collect();
        if parts.is_empty() { "none".to_owned() } else { parts.join(", ") }
    }
}

impl Serialize for Dram {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(Purpose::ALL.len()))?;
        for (p, b) in self.fields() {
            m.serialize_entry(p.name(), &b)?;
        }
        m.end()
    }
}

/// What the shadow unit asked of memory before any cache, bytes: not
/// traffic when a map cache stands between (its fills are), but what
/// Sen et al.'s bandwidth model counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Requested {
    /// Map texels.
    pub map: u64,
    /// Silhouette points.
    pub silhouette: u64,
}

impl Requested {
    /// Both added.
    #[must_use]
    pub(crate) const fn plus(&self, o: &Self) -> Self {
        Self { map: self.map + o.map, silhouette: self.silhouette + o.silhouette }
    }
}
