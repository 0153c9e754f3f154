//! The light-pass driver: triangles in, depth maps out, over buffers the
//! caller owns.
//!
//! ```text
//! submit ─► front end (vertex, clip, snap, setup) ─► bin ──(bin full / setup store full / finish)──►
//!   rasterize tile: load (or clear) ─► each binned triangle ─► resolve ─► store
//! ```
//!
//! The map is row-major, `width × height` texels, row 0 at the top (see
//! [`crate::front::snap`](mod@crate::front::snap) for the orientation). [`LightPass::new`] clears it to the
//! far value ([`LightPass::new_kept`] only the tiles the last pass over the
//! same buffers wrote); [`LightPass::finish`] drains every bin. Results do not depend on
//! the bin capacity, the setup-store size or the tile size: only the events
//! reported on the way do.

use core::marker::PhantomData;

use glam::{Mat4, Vec3, Vec4};

use crate::config::{ConfigError, CullMode, DepthUnit, LightPassConfig};
use crate::depth::{DepthFormat, TileState};
use crate::front::setup::Setup;
use crate::front::vertex::{CACHE_ENTRIES, VertexCache};
use crate::front::{self, Output};
use crate::grid::{TileId, TileRect};
use crate::probe::{Event, FlushReason, NoProbe, Probe, RejectReason};
use crate::raster::bin::{Bin, MAX_SETUPS, SetupIndex, touches};
use crate::raster::{TileView, rasterize};
use resolve::resolve;

mod buffers;
mod resolve;

pub use crate::depth::datapaths::{Datapaths, DualOnly, Every, SingleOnly, VisibilityOnly};
pub use crate::front::SubmitError;
pub use buffers::{LightBuffers, NO_TRIANGLE};

/// A light pass in progress, built with the datapaths `D` ([`Every`]
/// unless the caller needs fewer).
pub struct LightPass<'a, F: DepthFormat, P: Probe = NoProbe, const B: usize = 64, D: Datapaths = Every> {
    cfg: LightPassConfig,
    buf: LightBuffers<'a, F, B>,
    setups_used: usize,
    triangles: u32,
    probe: P,
    datapaths: PhantomData<D>,
}

impl<'a, F: DepthFormat, P: Probe, const B: usize, D: Datapaths> LightPass<'a, F, P, B, D> {
    /// Start a light pass: check the buffers against the configuration and
    /// clear the map.
    ///
    /// Every buffer is the caller's (here on the stack: a 16² dual map in
    /// 8-texel tiles, 64-entry bins, 32 triangle setups):
    ///
    /// ```
    /// use umbra_core::front::setup::Setup;
    /// use umbra_core::glam::{Mat4, Vec3};
    /// use umbra_core::probe::Totals;
    /// use umbra_core::raster::bin::Bin;
    /// use umbra_core::{CullMode, D16, DepthFormat, DepthUnit, LightBuffers, LightPass, LightPassConfig, RasterConfig, TileState};
    ///
    /// let raster = RasterConfig::new(16, 16, 8, 4)?;
    /// let cfg = LightPassConfig { raster, unit: DepthUnit::Dual, max_z_cull: true };
    /// let (mut z1, mut z2) = ([0u16; 256], [0u16; 256]);
    /// let mut tiles = [TileState::cleared(D16::FAR, 0); 4];
    /// let mut bins = [const { Bin::<64>::new() }; 4];
    /// let mut setups = [Setup::EMPTY; 32];
    /// let buffers = LightBuffers { z1: &mut z1, z2: &mut z2, ids: &mut [], tiles: &mut tiles, bins: &mut bins, setups: &mut setups };
    /// let mut pass = LightPass::<D16, _, 64>::new(cfg, buffers, Totals::default())?;
    /// // Two triangles at depth ½ over the whole map (clip space: x, y in [-1, 1], z/w in [0, 1]).
    /// let quad = [Vec3::new(-1.0, -1.0, 0.5), Vec3::new(1.0, -1.0, 0.5), Vec3::new(1.0, 1.0, 0.5), Vec3::new(-1.0, 1.0, 0.5)];
    /// pass.draw_mesh(&quad, &[[0, 1, 2], [0, 2, 3]], &Mat4::IDENTITY, CullMode::None)?;
    /// let totals = pass.finish();
    /// assert_eq!(totals.fragments, 256); // every texel once: the fill rule shares the diagonal
    /// assert!(z1.iter().all(|&z| z == D16::quantize(0.5)));
    /// assert!(z2.iter().all(|&z| z == D16::FAR)); // nothing behind it
    /// # Ok::<(), Box<dyn core::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`ConfigError::BufferLength`] naming the first buffer whose length is
    /// wrong; [`ConfigError::NotBuilt`] if `D` lacks the datapath `cfg` needs.
    pub fn new(cfg: LightPassConfig, buf: LightBuffers<'a, F, B>, probe: P) -> Result<Self, ConfigError> {
        Self::start(cfg, buf, probe, false)
    }

    /// Start a light pass over buffers that a light pass of the same
    /// configuration drew last (its tile summaries describe them), clearing
    /// only the tiles it wrote: a tile whose summary says it holds only the
    /// clear value (its `z1_min` and `z1_max` are the far value) is
    /// left as it is — the fast clear of hardware that keeps a cleared bit
    /// per tile — and the others are cleared when they are first loaded
    /// (just before their first triangles, while the tile is in cache) or,
    /// if no triangle reaches them, at [`LightPass::finish`]. The clear
    /// costs the tiles the last pass touched, not the map's area, and the
    /// maps are the bits [`LightPass::new`] gives. Until a kept tile is
    /// first stored, its summary's `z1_max` marks a pending clear.
    ///
    /// Buffers with any other history (another configuration, an id
    /// buffer the last pass did not have, texels written since) must start
    /// with [`LightPass::new`]: a summary that does not describe its tile is
    /// trusted here.
    ///
    /// # Errors
    /// As [`LightPass::new`].
    pub fn new_kept(cfg: LightPassConfig, buf: LightBuffers<'a, F, B>, probe: P) -> Result<Self, ConfigError> {
        Self::start(cfg, buf, probe, true)
    }

    /// Out of line, as [`LightPass::finish`]: once a pass, and a
    /// microcontroller's streamed camera pass keeps their frames off its own.
    #[inline(never)]
    fn start(cfg: LightPassConfig, buf: LightBuffers<'a, F, B>, probe: P, kept: bool) -> Result<Self, ConfigError> {
        const { assert!(B > 0, "a bin must hold at least one triangle") };
        let r = &cfg.raster;
        let texels = r.texel_count();
        let z2_len = if cfg.unit == DepthUnit::Dual { texels } else { 0 };
        let check = |buffer: &'static str, expected: usize, found: usize| {
            if expected == found { Ok(()) } else { Err(ConfigError::BufferLength { buffer, expected, found }) }
        };
        check("z1", texels, buf.z1.len())?;
        check("z2", z2_len, buf.z2.len())?;
        if !buf.ids.is_empty() {
            check("ids", if cfg.unit == DepthUnit::Single { texels } else { 0 }, buf.ids.len())?;
        }
        check("tiles", r.tile_count(), buf.tiles.len())?;
        check("bins", r.tile_count(), buf.bins.len())?;
        if buf.setups.is_empty() || buf.setups.len() > MAX_SETUPS {
            return Err(ConfigError::BufferLength { buffer: "setups", expected: MAX_SETUPS, found: buf.setups.len() });
        }
        D::check(&cfg, !buf.ids.is_empty())?;
        if !kept {
            buf.z1.fill(F::FAR);
            buf.z2.fill(F::FAR);
            buf.ids.fill(NO_TRIANGLE);
        }
        for (i, t) in buf.tiles.iter_mut().enumerate() {
            // A kept tile the last pass wrote — or whose clear a pass
            // dropped before its finish left pending — is cleared when it
            // is first loaded, or at the finish if no triangle reaches it.
            let pending = kept && (t.z1_min != F::FAR || t.z1_max != F::FAR);
            *t = TileState::cleared(F::FAR, r.tile_rect(r.tile_id(i)).area());
            if pending {
                t.z1_max = pending_clear::<F>();
            }
        }
        buf.bins.iter_mut().for_each(Bin::clear);
        Ok(Self { cfg, buf, setups_used: 0, triangles: 0, probe, datapaths: PhantomData })
    }

    /// The configuration.
    pub const fn config(&self) -> &LightPassConfig {
        &self.cfg
    }

    /// The probe.
    pub const fn probe(&mut self) -> &mut P {
        &mut self.probe
    }

    /// Draw an indexed mesh: positions in object space and `transform` to
    /// light clip space (`clip = transform · (p, 1)`, glam's column-vector
    /// convention). The transform is f32 (the vertex unit); a triangle with
    /// a vertex outside a clip plane is clipped in f64; everything after the
    /// snap is fixed point ([`crate::front`]).
    ///
    /// # Errors
    /// [`SubmitError::IndexOutOfRange`] before anything is drawn.
    pub fn draw_mesh(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        transform: &Mat4,
        cull: CullMode,
    ) -> Result<(), SubmitError> {
        let mut cache = VertexCache::<CACHE_ENTRIES>::new();
        self.draw_mesh_cached(positions, triangles, transform, cull, &mut cache)
    }

    /// [`draw_mesh`](Self::draw_mesh) with the caller's post-transform
    /// cache, of any size (a microcontroller's few entries, or none): the
    /// results are the same, only the vertex unit's work differs.
    ///
    /// # Errors
    /// [`SubmitError::IndexOutOfRange`] before anything is drawn.
    pub fn draw_mesh_cached<const N: usize>(
        &mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        transform: &Mat4,
        cull: CullMode,
        cache: &mut VertexCache<N>,
    ) -> Result<(), SubmitError> {
        front::check_indices(positions.len(), triangles)?;
        let raster = self.cfg.raster;
        let first = self.triangles;
        front::mesh::<F, N>(&raster, positions, triangles, transform, cull, first, cache, &mut |o| self.take(o));
        Ok(())
    }

    /// Draw one triangle given in light clip space. Any input is accepted:
    /// non-finite vertices are rejected and reported, never rasterized.
    pub fn draw_clip(&mut self, tri: [Vec4; 3], cull: CullMode) {
        let id = self.triangles;
        self.take(Output::Submitted);
        if !tri.iter().all(|v| v.is_finite()) {
            self.take(Output::Rejected(RejectReason::NonFinite));
            return;
        }
        let raster = self.cfg.raster;
        front::clip::<F>(&raster, &tri.map(|v| v.to_array().map(f64::from)), cull, id, &mut |o| self.take(o));
    }

    /// Take what the front end made of a triangle: count and report it,
    /// bin its pieces.
    fn take(&mut self, o: Output<'_>) {
        match o {
            Output::Submitted => {
                self.triangles = self.triangles.wrapping_add(1);
                self.probe.event(Event::TriangleSubmitted);
            }
            Output::Setup(s) => self.draw_setup(s),
            Output::Rejected(reason) => self.probe.event(Event::TriangleRejected { reason }),
        }
    }

    /// Bin a triangle the front end has set up for this target: the way in
    /// for a front end run elsewhere, on another core say.
    #[inline(never)]
    pub fn draw_setup(&mut self, setup: &Setup) {
        self.bin_setup(setup, [0, 0]);
    }

    /// Bin a triangle set up for a larger target of which this pass's target
    /// is the window at `by` ([`crate::RasterConfig::window`]): it is stored
    /// moved into the window, exactly as [`Setup::in_window`] moves it. A
    /// triangle outside the window bins to no tile.
    #[inline]
    pub fn draw_setup_from(&mut self, setup: &Setup, by: [u32; 2]) {
        self.bin_setup(setup, by);
    }

    /// The binning unit, for both ways in (inlined into each: a target's
    /// own setups move by nothing, and pay nothing for it).
    #[inline(always)]
    fn bin_setup(&mut self, setup: &Setup, by: [u32; 2]) {
        let raster = self.cfg.raster;
        self.probe.event(Event::TriangleSetup);
        // A setup from the front end lies inside its target; a hand-made one
        // is clamped to the window, so that binning stays bounded.
        let Some(seen) = setup.bbox.intersect(&raster.target_rect().moved(by)) else {
            self.probe.event(Event::TriangleBinned { tiles: 0 });
            return;
        };
        if self.setups_used == self.buf.setups.len() {
            self.flush_all(FlushReason::SetupFull);
        }
        let index = self.setups_used;
        let Some(slot) = self.buf.setups.get_mut(index) else { return };
        *slot = *setup;
        if by != [0, 0] {
            slot.move_by(by, seen);
        }
        self.setups_used += 1;
        #[allow(clippy::cast_possible_truncation, reason = "the store holds at most 2^16 setups")]
        let entry = index as SetupIndex;
        let shift = raster.tile_shift();
        let [dx, dy] = by;
        let (tx0, tx1) = ((seen.x0 - dx) >> shift, (seen.x1 - 1 - dx) >> shift);
        let (ty0, ty1) = ((seen.y0 - dy) >> shift, (seen.y1 - 1 - dy) >> shift);
        // A triangle whose bounding box lies in one tile goes to that bin
        // without a corner test.
        let single = tx0 == tx1 && ty0 == ty1;
        let mut binned = 0;
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                #[allow(clippy::cast_possible_truncation, reason = "at most 2^11 tiles per side")]
                let tile = TileId { x: tx as u16, y: ty as u16 };
                // The unmoved setup over the tile moved back: the same test.
                if !single && !touches(setup, &raster.tile_rect(tile).moved(by)) {
                    continue;
                }
                binned += 1;
                let t = raster.tile_index(tile);
                let full = self.buf.bins.get(t).is_some_and(Bin::is_full);
                if full {
                    self.flush_tile(t, FlushReason::BinFull);
                }
                if let Some(bin) = self.buf.bins.get_mut(t) {
                    // The bin is not full here: it was just drained, B > 0.
                    let _ = bin.push(entry);
                }
            }
        }
        self.probe.event(Event::TriangleBinned { tiles: binned });
    }

    fn flush_all(&mut self, reason: FlushReason) {
        for t in 0..self.buf.bins.len() {
            if !self.buf.bins[t].is_empty() {
                self.flush_tile(t, reason);
            }
        }
        self.setups_used = 0;
    }

    /// Rasterize a tile's bin: load (or clear), every triangle, resolve,
    /// store. Out of line: once a tile, and its frame stays off the
    /// callers' (a microcontroller's stack).
    #[inline(never)]
    fn flush_tile(&mut self, t: usize, reason: FlushReason) {
        let raster = self.cfg.raster;
        let tile = raster.tile_id(t);
        let rect = raster.tile_rect(tile);
        let LightBuffers { z1, z2, ids, tiles, bins, setups } = &mut self.buf;
        let (Some(bin), Some(state)) = (bins.get_mut(t), tiles.get_mut(t)) else { return };
        let tile_bytes = rect.area() * F::KIND.bytes() * self.cfg.unit.buffers();
        #[allow(clippy::cast_possible_truncation, reason = "a bin holds at most B ≤ 2^16 entries")]
        let triangles = bin.len() as u32;
        self.probe.event(Event::BinFlush { tile, triangles, reason });
        if state.stores > 0 {
            self.probe.event(Event::TileLoad { tile, bytes: tile_bytes });
        } else if state.z1_max == pending_clear::<F>() {
            state.z1_max = F::FAR;
            clear_tile::<F>(rect, raster.width() as usize, z1, z2, ids);
        }
        let width = raster.width() as usize;
        let with_ids = !ids.is_empty();
        let mut view = TileView { z1, z2, ids, width, state, tile, rect };
        let dual = self.cfg.unit == DepthUnit::Dual;
        for &i in bin.iter() {
            let Some(s) = setups.get(usize::from(i)) else { continue };
            let probe = &mut self.probe;
            // Only the datapaths built are in the program ([`Datapaths`]);
            // `new` refused a configuration needing another.
            match (dual, with_ids, self.cfg.max_z_cull) {
                (false, false, false) if D::SINGLE && D::UNCULLED => {
                    rasterize::<F, P, D, false, false, false>(s, &mut view, probe)
                }
                (false, false, true) if D::SINGLE && D::CULLED => {
                    rasterize::<F, P, D, false, false, true>(s, &mut view, probe)
                }
                (false, true, false) if D::VISIBILITY && D::UNCULLED => {
                    rasterize::<F, P, D, false, true, false>(s, &mut view, probe)
                }
                (false, true, true) if D::VISIBILITY && D::CULLED => {
                    rasterize::<F, P, D, false, true, true>(s, &mut view, probe)
                }
                (true, _, false) if D::DUAL && D::UNCULLED => {
                    rasterize::<F, P, D, true, false, false>(s, &mut view, probe)
                }
                (true, _, true) if D::DUAL && D::CULLED => rasterize::<F, P, D, true, false, true>(s, &mut view, probe),
                _ => {}
            }
        }
        bin.clear();
        resolve::<F>(&mut view, dual);
        view.state.stores += 1;
        self.probe.event(Event::TileStore { tile, bytes: tile_bytes, cleared: false });
    }

    /// Drain every bin now, as an immediate-mode machine finishes a draw
    /// before the next: each tile's triangles keep their order, so the maps
    /// are the same bits; only the events' order and the tiles' loads and
    /// stores change.
    pub fn flush(&mut self) {
        self.flush_all(FlushReason::Draw);
    }

    /// Drain every bin, store every tile, and hand back the probe. Out of
    /// line (once a pass; inlined into a streamed camera pass, its frame
    /// grew the Cortex-M0's peak stack by 1.1 KB).
    #[inline(never)]
    pub fn finish(mut self) -> P {
        for t in 0..self.buf.bins.len() {
            if !self.buf.bins[t].is_empty() {
                self.flush_tile(t, FlushReason::Finish);
            } else if self.buf.tiles[t].stores == 0 {
                let tile = self.cfg.raster.tile_id(t);
                let rect = self.cfg.raster.tile_rect(tile);
                let bytes = rect.area() * F::KIND.bytes() * self.cfg.unit.buffers();
                let LightBuffers { z1, z2, ids, tiles, .. } = &mut self.buf;
                if tiles[t].z1_max == pending_clear::<F>() {
                    tiles[t].z1_max = F::FAR;
                    clear_tile::<F>(rect, self.cfg.raster.width() as usize, z1, z2, ids);
                }
                self.buf.tiles[t].stores = 1;
                self.probe.event(Event::TileStore { tile, bytes, cleared: true });
            }
        }
        self.setups_used = 0;
        self.probe
    }
}

/// The mark of a kept tile whose clear is pending, in its `z1_max` until
/// it is first loaded: not the far value, which a summary of a cleared
/// tile holds (the nearest value, which no max of an unstored tile holds).
fn pending_clear<F: DepthFormat>() -> F::Texel {
    F::Texel::default()
}

/// Clear one tile's rows of `z1`, `z2` and `ids` (a row-major map `width`
/// texels wide; empty buffers are left). Out of line: it runs once a tile.
#[inline(never)]
fn clear_tile<F: DepthFormat>(rect: TileRect, width: usize, z1: &mut [F::Texel], z2: &mut [F::Texel], ids: &mut [u32]) {
    for y in rect.y0..rect.y1 {
        let row = y as usize * width;
        let (x0, x1) = (row + rect.x0 as usize, row + rect.x1 as usize);
        z1.get_mut(x0..x1).into_iter().for_each(|t| t.fill(F::FAR));
        z2.get_mut(x0..x1).into_iter().for_each(|t| t.fill(F::FAR));
        ids.get_mut(x0..x1).into_iter().for_each(|t| t.fill(NO_TRIANGLE));
    }
}
