//! Silicon: the area of each unit a render needs on an architecture, at
//! the architecture's process ([`Technology`]), and the leakage it burns
//! while a frame runs.
//!
//! **Storage** is bits of SRAM: an array's area is its bit cells over the
//! array efficiency (the share the cells take of an array beside its
//! decoders, sense amplifiers and drivers). A cache stores, besides its
//! data, a tag, a valid bit and its LRU age (`log2 ways` bits) per line;
//! tags are of a 40-bit physical address.
//!
//! **Logic** is NAND2 gate equivalents ([`gates`]) times the node's gate
//! area. Each datapath is as many lanes as its unit's rate per clock, each
//! lane its blocks at their widths: a depth interpolator adds a plane's
//! step in the format's bits and [`PLANE_FRACTION_BITS`]; a depth test is
//! a comparator per buffer (Wang & Molnar's dual unit, 1994 §3.2, keeps
//! two); the shadow unit compares each sample against the buffers its test
//! reads, adds the bias (and a dual map's offset, Weiskopf & Ertl 2003 §3),
//! draws a random bias per sample for Reeves et al.'s bias range (1987
//! §3.2, a 16-bit LFSR), weighs a bilinear lookup's four verdicts (four
//! [`MAP_FRACTION_BITS`]-square multipliers and an adder tree), evaluates
//! tangent planes for the virtual samples (Wang & Molnar §4: two
//! forward-difference adders per lane, and the dividers, each an
//! iterative restoring divider: an adder and three registers), or decides
//! a silhouette map's skewed quadrant (Sen, Cammarano & Hanrahan 2003
//! §4.2: four line-side tests, two multipliers and an adder each). A
//! bit-serial machine (PixelFlow) has a one-bit adder and comparator per
//! pixel of its region instead of lanes.
//!
//! The units are the ones the render uses: a light pass's depth buffers
//! only when on chip, the map cache only for an algorithm that reads a
//! map, the stencil only for shadow volumes. Every unit's area, and so
//! its leakage, comes from this one description.
//!
//! ```
//! use umbra_sim::Arch;
//! use umbra_sim::cost::silicon::{Demand, Silicon};
//! let tbdr = Arch::bundled("mobile-tbdr")?;
//! let one = Silicon::of(&tbdr, &Demand { depth_buffers: 1, ..Demand::DEFAULT });
//! let two = Silicon::of(&tbdr, &Demand::DEFAULT);
//! // Wang & Molnar's second buffer: 32 × 32 more 24-bit texels, and a
//! // second comparator per lane.
//! assert!(two.square_metres() > one.square_metres());
//! # Ok::<(), umbra_sim::cost::arch::ArchError>(())
//! ```

pub mod gates;

use gates::{Block, gate_equivalents};
use serde::Serialize;
use umbra_core::budget::{MAP_FRACTION_BITS, PLANE_FRACTION_BITS};

use crate::cost::arch::{Arch, CacheParams, Technology};

/// Bits of a physical address a cache's tags hold.
const ADDRESS_BITS: u32 = 40;
/// Bits of one bin's head pointer (a DRAM address of its list).
const BIN_POINTER_BITS: u32 = 32;
/// Bits of a camera pixel's visibility depth (the camera pass is D24).
const CAMERA_DEPTH_BITS: u32 = 24;
/// Bits of a camera pixel's triangle id.
const ID_BITS: u32 = 32;
/// Bits of a stencil value.
const STENCIL_BITS: u32 = 8;
/// Bits of the random source a bias-range lane draws from (an LFSR).
const LFSR_BITS: u32 = 16;

/// What a render asks of the hardware, in the terms silicon is counted
/// in (the render layer builds it from a configuration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Demand {
    /// The light pass's depth buffers per texel: 1, or 2 for a dual unit.
    pub depth_buffers: u32,
    /// Bits of a map texel (16, 24, 32).
    pub depth_bits: u32,
    /// The map's side, texels (width, height).
    pub map: [u32; 2],
    /// The camera image, pixels (width, height).
    pub image: [u32; 2],
    /// Buffers the shadow test compares each sample with: 1, or 2.
    pub buffers_read: u32,
    /// Depth samples one lookup takes.
    pub samples_per_lookup: u32,
    /// Whether a lookup weighs its samples bilinearly.
    pub bilinear: bool,
    /// Whether the test adds a dual map's offset.
    pub offset: bool,
    /// Whether each sample draws its bias from a range.
    pub bias_range: bool,
    /// Whether Wang & Molnar's virtual samples are evaluated.
    pub virtual_samples: bool,
    /// Bits a texel's silhouette point is stored in (0: no silhouette map).
    pub silhouette_bits: u32,
    /// Shadow volumes: no map, a stencil on the camera's raster.
    pub volumes: bool,
}

impl Demand {
    /// The default render's demand: second depth (a dual unit) in D24, a
    /// 1024² map, bilinear, a 640×480 image.
    pub const DEFAULT: Self = Self {
        depth_buffers: 2,
        depth_bits: 24,
        map: [1024, 1024],
        image: [640, 480],
        buffers_read: 1,
        samples_per_lookup: 4,
        bilinear: true,
        offset: false,
        bias_range: false,
        virtual_samples: false,
        silhouette_bits: 0,
        volumes: false,
    };
}

/// What a unit's area is made of.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// SRAM bits.
    Storage,
    /// Logic, NAND2 gate equivalents.
    Logic,
}

/// One unit's silicon.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnitArea {
    /// The unit (`light depth buffers`, `map cache`).
    pub unit: &'static str,
    /// Storage or logic.
    pub kind: Kind,
    /// Its size: SRAM bits, or NAND2 gate equivalents.
    pub size: f64,
    /// How the size is counted, in words.
    pub how: String,
    /// Its area, square metres.
    pub square_metres: f64,
}

/// The silicon of a render's units on an architecture.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Silicon {
    /// The process node.
    pub node: String,
    /// Every unit, storage first.
    pub units: Vec<UnitArea>,
    /// Leakage per area at the node, watts per square metre.
    pub leakage_per_square_metre: f64,
}

impl Silicon {
    /// The units `demand` needs on `arch`, each with its area at the
    /// architecture's technology.
    #[must_use]
    pub fn of(arch: &Arch, demand: &Demand) -> Self {
        let mut units = Units { tech: &arch.technology, list: Vec::new() };
        storage(arch, demand, &mut units);
        logic(arch, demand, &mut units);
        Self {
            node: arch.technology.node.clone(),
            units: units.list,
            leakage_per_square_metre: arch.technology.leakage,
        }
    }

    /// Every unit's area added, square metres.
    #[must_use]
    pub fn square_metres(&self) -> f64 {
        self.units.iter().map(|u| u.square_metres).sum()
    }

    /// Leakage power of the units, watts.
    #[must_use]
    pub fn leakage_watts(&self) -> f64 {
        self.leakage_per_square_metre * self.square_metres()
    }
}

/// The units counted so far, at a technology.
struct Units<'a> {
    tech: &'a Technology,
    list: Vec<UnitArea>,
}

impl Units<'_> {
    /// An SRAM array of `bits`.
    fn sram(&mut self, unit: &'static str, bits: f64, how: String) {
        if bits > 0.0 {
            let square_metres = bits * self.tech.sram_bit / self.tech.array_efficiency;
            self.list.push(UnitArea { unit, kind: Kind::Storage, size: bits, how, square_metres });
        }
    }

    /// Logic of `gates` NAND2 equivalents.
    fn logic(&mut self, unit: &'static str, gates: f64, how: String) {
        if gates > 0.0 {
            let square_metres = gates * self.tech.gate;
            self.list.push(UnitArea { unit, kind: Kind::Logic, size: gates, how, square_metres });
        }
    }
}

/// A cache's bits: data, and per line a tag, a valid bit and its LRU age.
fn cache_bits(c: &CacheParams) -> (f64, String) {
    if c.size == 0 {
        return (0.0, String::new());
    }
    let lines = c.size / c.line;
    let sets = lines / c.ways;
    let tag = ADDRESS_BITS.saturating_sub(sets.ilog2() + c.line.ilog2());
    let per_line = u64::from(tag) + 1 + u64::from(c.ways.ilog2());
    #[allow(clippy::cast_precision_loss, reason = "bit counts far below 2^53")]
    let bits = (c.size * 8 + lines * per_line) as f64;
    (bits, format!("{lines} lines of {} B, each with a {tag}-bit tag, valid and {}-bit LRU", c.line, c.ways.ilog2()))
}

/// Tiles of side `tile` covering `side`.
fn tiles(side: [u32; 2], tile: u32) -> u64 {
    u64::from(side[0].div_ceil(tile)) * u64::from(side[1].div_ceil(tile))
}

/// The storage units.
#[allow(clippy::cast_precision_loss, reason = "bit counts far below 2^53")]
fn storage(arch: &Arch, d: &Demand, u: &mut Units<'_>) {
    let t = arch.raster.tile;
    let texels = u64::from(t) * u64::from(t);
    if !d.volumes {
        if arch.on_chip.light_depth {
            // A second light pass peels with one buffer.
            let layers = if arch.depth.second_depth_pass { 1 } else { d.depth_buffers };
            let bits = texels * u64::from(layers * d.depth_bits);
            u.sram("light depth buffers", bits as f64, format!("{layers} × {t}² texels × {} bits", d.depth_bits));
            if d.silhouette_bits > 0 {
                let bits = texels * u64::from(d.silhouette_bits);
                u.sram("silhouette points", bits as f64, format!("{t}² texels × {} bits", d.silhouette_bits));
            }
        }
        let (bits, how) = cache_bits(&arch.map_cache);
        u.sram("map cache", bits, how);
    }
    if arch.on_chip.camera_depth {
        let bits = texels * u64::from(CAMERA_DEPTH_BITS + ID_BITS);
        u.sram("camera depth and ids", bits as f64, format!("{t}² pixels × ({CAMERA_DEPTH_BITS} + {ID_BITS}) bits"));
    }
    if d.volumes && arch.on_chip.stencil {
        let bits = texels * u64::from(STENCIL_BITS);
        u.sram("stencil", bits as f64, format!("{t}² pixels × {STENCIL_BITS} bits"));
    }
    let off_chip =
        (!d.volumes && !arch.on_chip.light_depth) || !arch.on_chip.camera_depth || (d.volumes && !arch.on_chip.stencil);
    if off_chip {
        let (bits, how) = cache_bits(&arch.depth_cache);
        u.sram("depth cache", bits, how);
    }
    if !arch.immediate() {
        // One list head per tile of the larger of the passes' targets.
        let heads = if d.volumes { 0 } else { tiles(d.map, t) }.max(tiles(d.image, t));
        let bits = heads * u64::from(BIN_POINTER_BITS);
        u.sram("bin heads", bits as f64, format!("{heads} tiles × {BIN_POINTER_BITS}-bit pointers"));
    }
}

/// Lanes of a unit that does `rate` a clock.
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "rates checked below 65 536")]
fn lanes(rate: f64) -> u32 {
    rate.ceil().max(1.0) as u32
}

/// The logic units.
#[allow(clippy::cast_precision_loss, reason = "gate counts far below 2^53")]
fn logic(arch: &Arch, d: &Demand, u: &mut Units<'_>) {
    let ge = gate_equivalents;
    let t = arch.raster.tile;
    if !d.volumes {
        let layers = if arch.depth.second_depth_pass { 1 } else { d.depth_buffers };
        let wide = d.depth_bits + PLANE_FRACTION_BITS;
        if arch.depth.fragments_per_clock > 0.0 {
            let n = lanes(arch.depth.fragments_per_clock);
            let per = ge(Block::Add, wide, 1) + f64::from(layers) * ge(Block::Compare, d.depth_bits, 1);
            let how = format!("{n} lanes × ({wide}-bit interpolator + {layers} × {}-bit comparator)", d.depth_bits);
            u.logic("light depth test", f64::from(n) * per, how);
        } else {
            // Bit-serial: a one-bit adder and comparator per pixel, a tree
            // of adders evaluating the plane along the region's sides.
            let pixels = f64::from(t * t);
            let per = f64::from(layers) * (ge(Block::Add, 1, 1) + ge(Block::Compare, 1, 1));
            let tree = f64::from(2 * t) * ge(Block::Add, wide, 1);
            let how = format!("{t}² pixels × {layers} × 1-bit adder and comparator, 2·{t} {wide}-bit tree adders");
            u.logic("light depth test", pixels * per + tree, how);
        }
        shadow_unit(arch, d, u);
    } else {
        let n = lanes(arch.depth.fragments_per_clock.max(1.0));
        let how = format!("{n} lanes × {STENCIL_BITS}-bit increment and decrement");
        u.logic("stencil unit", f64::from(n) * ge(Block::Add, STENCIL_BITS, 1), how);
    }
}

/// The shadow unit's datapaths.
#[allow(clippy::cast_precision_loss, reason = "gate counts far below 2^53")]
fn shadow_unit(arch: &Arch, d: &Demand, u: &mut Units<'_>) {
    let ge = gate_equivalents;
    let bits = d.depth_bits;
    let samples = lanes(arch.shadow.samples_per_clock);
    let compare = f64::from(d.buffers_read) * ge(Block::Compare, bits, 1);
    let adders = 1 + u32::from(d.offset);
    let mut per = compare + f64::from(adders) * ge(Block::Add, bits, 1);
    let mut how =
        format!("{samples} sample lanes × ({} × {bits}-bit comparator + {adders} × {bits}-bit adder", d.buffers_read);
    if d.bias_range {
        per += ge(Block::Register, LFSR_BITS, 1) + 2.0 * ge(Block::Add, 1, 1);
        how += &format!(" + {LFSR_BITS}-bit LFSR");
    }
    how.push(')');
    u.logic("shadow compare", f64::from(samples) * per, how);
    let lookups = (samples / d.samples_per_lookup.max(1)).max(1);
    let f = MAP_FRACTION_BITS;
    if d.bilinear {
        let per = 4.0 * ge(Block::Multiply, f, f) + 3.0 * ge(Block::Add, 2 * f, 1);
        let how = format!("{lookups} lookup lanes × (4 × {f}×{f}-bit multiplier + 3 × {}-bit adder)", 2 * f);
        u.logic("filter weights", f64::from(lookups) * per, how);
    } else if d.samples_per_lookup > 1 {
        let w = d.samples_per_lookup.ilog2() + 1;
        let how = format!("{lookups} lookup lanes × {w}-bit counter");
        u.logic("filter accumulator", f64::from(lookups) * ge(Block::Add, w, 1), how);
    }
    if d.virtual_samples {
        let wide = bits + PLANE_FRACTION_BITS;
        let per = 2.0 * ge(Block::Add, wide, 1);
        let how = format!("{lookups} lookup lanes × 2 × {wide}-bit forward-difference adder");
        u.logic("tangent-plane differencers", f64::from(lookups) * per, how);
        let n = arch.shadow.dividers;
        let per = ge(Block::Add, wide, 1) + 3.0 * ge(Block::Register, wide, 1);
        let how = format!("{n} × ({wide}-bit adder + 3 × {wide}-bit register)");
        u.logic("dividers", n as f64 * per, how);
    }
    if d.silhouette_bits > 0 {
        let c = f + 1;
        let per = 4.0 * (2.0 * ge(Block::Multiply, c, c) + ge(Block::Add, 2 * c, 1));
        let how = format!("{lookups} lookup lanes × 4 × (2 × {c}×{c}-bit multiplier + {}-bit adder)", 2 * c);
        u.logic("silhouette evaluator", f64::from(lookups) * per, how);
    }
}
