//! The rasterizer: one binned triangle in one tile.
//!
//! Rules of the hot path: setup has computed everything, so the loops here
//! only add; no allocation, no `dyn`, no panicking index (buffers are
//! reached through `get_mut`); variants (single/dual, masked/full, culling
//! on/off) are const generics.
//!
//! Traversal, after Mesa llvmpipe:
//! 1. the triangle's bounding box is clipped to the tile;
//! 2. the rectangle is classified **empty / partial / full** by corner tests
//!    of the edge functions ([`Setup::classify`]);
//! 3. **max-z culling**: if the nearest depth of the triangle over the
//!    rectangle (the smaller of its nearest vertex and the plane's minimum
//!    at the rectangle's corners) is at or beyond the tile's max stored depth,
//!    no fragment can change the tile, and the triangle is skipped;
//! 4. a full rectangle runs whole rows without edge tests; a partial one is
//!    split into [`BLOCK`]×[`BLOCK`] blocks, each classified and culled the
//!    same way, and run as full rows or as masked rows.
//!
//! Fragments come out per tile, per triangle in bin order, in row-major
//! order within each block, blocks in row-major order.

use crate::depth::{DepthFormat, PlaneZ};
use crate::probe::{Buffer, CullLevel, Event, Fragment, Probe};
use crate::setup::{Coverage, Setup};
use crate::tile::{TileId, TileRect};
use crate::zbuffer::{SpanEdges, SpanOut, TileState, max_and_count, span, tile_rows};

/// Side of the fragment blocks a partial tile is split into.
pub const BLOCK: u32 = 8;

const _: () = assert!(BLOCK <= *crate::config::TILE_SIZES.start(), "blocks must fit in the smallest tile");

/// One tile of the map, as the rasterizer sees it.
pub(crate) struct TileView<'m, T> {
    pub z1: &'m mut [T],
    pub z2: &'m mut [T],
    pub width: usize,
    pub state: &'m mut TileState<T>,
    pub tile: TileId,
    pub rect: TileRect,
}

impl<T: Copy> TileView<'_, T> {
    /// The slices of row `y`, columns `x0..x1`, of both buffers (`z2` empty for single).
    #[inline(always)]
    fn rows(&mut self, y: u32, x0: u32, x1: u32) -> Option<(&mut [T], &mut [T])> {
        let base = y as usize * self.width;
        let range = base + x0 as usize..base + x1 as usize;
        let z1 = self.z1.get_mut(range.clone())?;
        let z2 = if self.z2.is_empty() { &mut [][..] } else { self.z2.get_mut(range)? };
        Some((z1, z2))
    }
}

/// The nearest depth of `s` over the pixel centres of `r`, as a texel.
#[inline]
fn nearest<F: DepthFormat>(s: &Setup, r: &TileRect) -> F::Texel {
    F::texel(s.z_min.max(s.plane.min_over(r)))
}

/// Rasterize one set-up triangle into one tile.
pub(crate) fn rasterize<F: DepthFormat, P: Probe, const DUAL: bool, const CULL: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    probe: &mut P,
) {
    let Some(rect) = view.rect.intersect(&s.bbox) else { return };
    let coverage = s.classify(&rect);
    if coverage == Coverage::Empty {
        return;
    }
    if CULL && nearest::<F>(s, &rect) >= view.state.cull_max {
        probe.event(Event::Culled { tile: view.tile, level: CullLevel::Triangle, texels: rect.area() });
        return;
    }
    let mut out = SpanOut::new(F::FAR);
    if coverage == Coverage::Full {
        rows::<F, P, DUAL, false, CULL>(s, view, &rect, &mut out, probe);
    } else {
        let mask = !(BLOCK - 1);
        let mut by = rect.y0 & mask;
        while by < rect.y1 {
            let mut bx = rect.x0 & mask;
            while bx < rect.x1 {
                let block = TileRect { x0: bx, y0: by, x1: bx + BLOCK, y1: by + BLOCK };
                if let Some(b) = block.intersect(&rect) {
                    block_step::<F, P, DUAL, CULL>(s, view, &b, &mut out, probe);
                }
                bx += BLOCK;
            }
            by += BLOCK;
        }
    }
    finish_triangle::<F, P, DUAL, CULL>(view, &out, probe);
}

#[inline(always)]
fn block_step<F: DepthFormat, P: Probe, const DUAL: bool, const CULL: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    b: &TileRect,
    out: &mut SpanOut<F::Texel>,
    probe: &mut P,
) {
    match s.classify(b) {
        Coverage::Empty => {}
        coverage => {
            if CULL && nearest::<F>(s, b) >= view.state.cull_max {
                probe.event(Event::Culled { tile: view.tile, level: CullLevel::Block, texels: b.area() });
            } else if coverage == Coverage::Full {
                rows::<F, P, DUAL, false, CULL>(s, view, b, out, probe);
            } else {
                rows::<F, P, DUAL, true, CULL>(s, view, b, out, probe);
            }
        }
    }
}

#[inline(always)]
fn rows<F: DepthFormat, P: Probe, const DUAL: bool, const MASKED: bool, const CULL: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    r: &TileRect,
    out: &mut SpanOut<F::Texel>,
    probe: &mut P,
) {
    let dz = s.plane.step_x();
    let de = [s.edges[0].dx, s.edges[1].dx, s.edges[2].dx];
    let cull_max = view.state.cull_max;
    for y in r.y0..r.y1 {
        let (px, py) = (i64::from(r.x0), i64::from(y));
        let z = s.plane.at(px, py);
        let edges = SpanEdges { e: [s.edges[0].at(px, py), s.edges[1].at(px, py), s.edges[2].at(px, py)], de };
        let Some((z1, z2)) = view.rows(y, r.x0, r.x1) else { return };
        let o = span::<F, DUAL, MASKED, CULL>(z1, z2, z, dz, edges, cull_max);
        out.add(&o);
        if P::FRAGMENTS {
            report_fragments::<F, P, MASKED>(s, r.x0, r.x1, y, z, edges, probe);
        }
    }
}

/// Per-fragment detail for probes that ask for it.
fn report_fragments<F: DepthFormat, P: Probe, const MASKED: bool>(
    s: &Setup,
    x0: u32,
    x1: u32,
    y: u32,
    z: PlaneZ,
    edges: SpanEdges,
    probe: &mut P,
) {
    let mut z = z;
    let mut e = edges.e;
    for x in x0..x1 {
        if !MASKED || e.iter().all(|&v| v >= 0) {
            probe.fragment(Fragment { x, y, depth: crate::depth::Texel::to_raw(F::texel(z)), triangle: s.triangle });
        }
        z = z.wrapping_add(s.plane.step_x());
        for (v, d) in e.iter_mut().zip(edges.de) {
            *v += d;
        }
    }
}

/// Report a triangle's work in a tile and bring the tile's summary up to date.
fn finish_triangle<F: DepthFormat, P: Probe, const DUAL: bool, const CULL: bool>(
    view: &mut TileView<'_, F::Texel>,
    out: &SpanOut<F::Texel>,
    probe: &mut P,
) {
    let tile = view.tile;
    if out.fragments > 0 {
        let bytes = |texels: u32| texels * F::KIND.bytes();
        probe.event(Event::Fragments { tile, count: out.fragments });
        probe.event(Event::DepthRead { buffer: Buffer::Z1, texels: out.fragments, bytes: bytes(out.fragments) });
        if out.written1 > 0 {
            probe.event(Event::DepthWrite { buffer: Buffer::Z1, texels: out.written1, bytes: bytes(out.written1) });
        }
        if DUAL {
            probe.event(Event::DepthRead { buffer: Buffer::Z2, texels: out.fragments, bytes: bytes(out.fragments) });
            if out.written2 > 0 {
                probe.event(Event::DepthWrite { buffer: Buffer::Z2, texels: out.written2, bytes: bytes(out.written2) });
            }
        }
    }
    let st = &mut *view.state;
    st.z1_min = st.z1_min.min(out.min1);
    st.z2_min = st.z2_min.min(out.min2);
    if CULL && out.lost_max > 0 {
        st.cull_count = st.cull_count.saturating_sub(out.lost_max);
        if st.cull_count == 0 {
            let r = view.rect;
            let width = view.width;
            let buf: &[F::Texel] = if DUAL { view.z2 } else { view.z1 };
            let rows = tile_rows(buf, r, width);
            let (max, count) = max_and_count(rows);
            view.state.cull_max = max;
            view.state.cull_count = count;
            let texels = r.area();
            let buffer = if DUAL { Buffer::Z2 } else { Buffer::Z1 };
            probe.event(Event::TileMaxUpdate { tile });
            probe.event(Event::DepthRead { buffer, texels, bytes: texels * F::KIND.bytes() });
        }
    }
}
