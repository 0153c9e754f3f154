//! The rasterizer: one binned triangle in one tile.
//!
//! Rules of the hot path: setup has computed everything, so the loops here
//! only add; no allocation, no `dyn`, no panicking index (buffers are
//! reached through `get_mut`); variants (single/dual, masked/full, culling
//! on/off) are const generics.
//!
//! Traversal, after Mesa llvmpipe:
//! 1. the triangle's bounding box is clipped to the tile;
//! 2. **max-z culling** (the per-tile max z of Reeves et al. 1987 §3.3): if
//!    the nearest depth of the triangle over the rectangle (the larger of its
//!    nearest vertex and the plane's minimum at the rectangle's corners) is
//!    at or beyond the tile's max stored depth (`z2` for dual), no fragment
//!    can change the tile, and the triangle is skipped;
//! 3. the rectangle is classified **empty / partial / full** by corner tests
//!    of the edge functions ([`Setup::classify`]), unless it is no bigger
//!    than a block: then per-row coverage masks find its pixels directly;
//! 4. a full rectangle runs whole rows without edge tests; a partial one no
//!    bigger than a block (or, when no block could be culled, no wider than
//!    [`SMALL`]) runs per-row coverage masks, and the depth unit takes each
//!    row's covered pixels — one run, as a triangle meets a row in an
//!    interval — as a span without edge tests, or pixel by pixel when the
//!    run is short; any other partial one is split into
//!    [`BLOCK`]×[`BLOCK`] blocks, each classified and culled the same way,
//!    and neighbouring blocks of a kind are merged into runs of full rows
//!    (no edge tests) or masked rows.
//!
//! Fragments come out per tile, per triangle in bin order, in row-major
//! order within each row of blocks, rows of blocks top to bottom — which is
//! row-major order over the rectangle, whichever way it was walked.

use crate::budget::{ROUND_HALF, TILE_SIZES};
use crate::depth::DepthFormat;
use crate::depth::datapaths::Datapaths;
use crate::depth::{SpanEdges, SpanOut, TileState, count_of, min_max, span, tile_rows};
use crate::front::setup::{Coverage, Setup};
use crate::grid::{TileId, TileRect};
use crate::probe::{Buffer, CullLevel, Event, Fragment, Probe};
use crate::raster::mask::{LANE_GROUP, LANES, Lanes, RowMask, Serial, WIDEST};

/// Bytes of one visible-triangle id.
const ID_BYTES: u32 = 4;

/// Side of the fragment blocks a partial tile is split into.
pub const BLOCK: u32 = 8;

const _: () = assert!(BLOCK <= *TILE_SIZES.start(), "blocks must fit in the smallest tile");

/// Width of the widest partial rectangle drawn by row masks ([`small`])
/// rather than split into blocks, when no block could be culled.
const SMALL: u32 = WIDEST;

/// One tile of the map, as the rasterizer sees it.
pub(crate) struct TileView<'m, T> {
    pub z1: &'m mut [T],
    pub z2: &'m mut [T],
    pub ids: &'m mut [u32],
    pub width: usize,
    pub state: &'m mut TileState<T>,
    pub tile: TileId,
    pub rect: TileRect,
}

impl<T: Copy> TileView<'_, T> {
    /// The slices of row `y`, columns `x0..x1`, of the buffers the unit
    /// keeps (`z2` with `DUAL`, `ids` with `IDS`; empty otherwise).
    #[inline(always)]
    fn rows<const DUAL: bool, const IDS: bool>(
        &mut self,
        y: u32,
        x0: u32,
        x1: u32,
    ) -> Option<(&mut [T], &mut [T], &mut [u32])> {
        let base = y as usize * self.width;
        let range = base + x0 as usize..base + x1 as usize;
        let z1 = self.z1.get_mut(range.clone())?;
        let z2 = if DUAL { self.z2.get_mut(range.clone())? } else { &mut [][..] };
        let ids = if IDS { self.ids.get_mut(range)? } else { &mut [][..] };
        Some((z1, z2, ids))
    }
}

/// The nearest depth of `s` over the pixel centres of `r`, as a texel.
#[inline]
fn nearest<F: DepthFormat>(s: &Setup, r: &TileRect) -> F::Texel {
    F::texel(s.z_min.max(s.plane.min_over(r)))
}

/// The nearest and farthest depth of `s` over the pixel centres of `r`.
#[inline]
fn depth_range<F: DepthFormat>(s: &Setup, r: &TileRect) -> (F::Texel, F::Texel) {
    let (lo, hi) = s.plane.range_over(r);
    (F::texel(s.z_min.max(lo)), F::texel(s.z_max.min(hi)))
}

/// A horizontal run of blocks in one block row: full (no edge tests) or masked.
#[derive(Clone, Copy, Debug)]
struct Run {
    x0: u32,
    x1: u32,
    masked: bool,
}

/// The longest run of a row mask that the depth unit takes pixel by pixel
/// rather than as a span (whose loop costs more to start).
const SPAN: u32 = 8;

/// Most blocks in one row of the largest tile.
const MAX_RUNS: usize = (*TILE_SIZES.end() / BLOCK) as usize;

/// Rasterize one set-up triangle into one tile, with the traversal
/// copies `D` has ([`Datapaths::STALE_MAX_COPY`]).
pub(crate) fn rasterize<
    F: DepthFormat,
    P: Probe,
    D: Datapaths,
    const DUAL: bool,
    const IDS: bool,
    const MAX_Z_CULL: bool,
>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    probe: &mut P,
) {
    let Some(rect) = view.rect.intersect(&s.bbox) else { return };
    if MAX_Z_CULL {
        let (bound, farthest) = depth_range::<F>(s, &rect);
        let st = &*view.state;
        // The max is stale once every texel that held it was lowered. Making
        // it exact is worth a reduction only if this triangle lies wholly
        // behind the tile's min: otherwise the exact max (≥ the min) cannot
        // cull it — so drawing back to front never pays for it.
        let culled_min = if DUAL { st.z2_min } else { st.z1_min };
        if st.cull_count == 0 && bound > culled_min {
            refresh_max::<F, P, DUAL>(view, probe);
        }
        if bound >= view.state.cull_max {
            probe.event(Event::Culled { tile: view.tile, level: CullLevel::Triangle, texels: rect.area() });
            return;
        }
        let coverage = coverage(s, &rect);
        if coverage == Coverage::Empty {
            return;
        }
        // Blocks can be culled only if part of the triangle reaches the max.
        let cull_blocks = farthest >= view.state.cull_max;
        // Counting where the max is stale lowers a zero count by
        // nothing: the same summary, one comparison a fragment dearer.
        if view.state.cull_count > 0 || !D::STALE_MAX_COPY {
            return traverse::<F, P, DUAL, IDS, true>(s, view, &rect, coverage, cull_blocks, probe);
        }
        return traverse::<F, P, DUAL, IDS, false>(s, view, &rect, coverage, cull_blocks, probe);
    }
    let coverage = coverage(s, &rect);
    if coverage != Coverage::Empty {
        traverse::<F, P, DUAL, IDS, false>(s, view, &rect, coverage, false, probe);
    }
}

/// How the triangle meets `rect`, as far as traversal needs to know: a
/// rectangle no bigger than a block is taken as partial unclassified, since
/// its coverage masks find the covered pixels (none, some or all) for less
/// than the corner tests cost.
#[inline(always)]
fn coverage(s: &Setup, rect: &TileRect) -> Coverage {
    if within(rect, BLOCK) { Coverage::Partial } else { s.classify(rect) }
}

/// Whether `rect` is no wider and no taller than `side`.
#[inline(always)]
const fn within(rect: &TileRect, side: u32) -> bool {
    rect.width() <= side && rect.height() <= side
}

/// Walk the triangle's rectangle in the tile: whole rows when it is full,
/// block rows of runs otherwise. `COUNT_MAX` tracks how many texels still hold
/// the tile's max. Not inlined: one copy per variant, shared by callers.
#[inline(never)]
fn traverse<F: DepthFormat, P: Probe, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    rect: &TileRect,
    coverage: Coverage,
    cull_blocks: bool,
    probe: &mut P,
) {
    let mut out = SpanOut::new(F::FAR);
    if coverage == Coverage::Full {
        // Whole rows without edge tests.
        let run = Run { x0: rect.x0, x1: rect.x1, masked: false };
        rows::<F, P, DUAL, IDS, COUNT_MAX>(s, view, rect.y0, rect.y1, &[run], &mut out, probe);
    } else if within(rect, BLOCK) || (rect.width() <= SMALL && !cull_blocks) {
        // A partial rectangle no bigger than a block, or (when no block can
        // be culled, so that the blocks would only split the work) no wider
        // than [`SMALL`].
        small::<F, P, DUAL, IDS, COUNT_MAX>(s, view, rect, &mut out, probe);
    } else {
        let mut by = rect.y0 & !(BLOCK - 1);
        while by < rect.y1 {
            let (y0, y1) = (by.max(rect.y0), (by + BLOCK).min(rect.y1));
            let runs = block_row::<F, P>(s, view, rect, y0, y1, cull_blocks, probe);
            rows::<F, P, DUAL, IDS, COUNT_MAX>(s, view, y0, y1, &runs, &mut out, probe);
            by += BLOCK;
        }
    }
    finish_triangle::<F, P, DUAL, IDS, COUNT_MAX>(view, &out, probe);
}

/// A partial rectangle no wider than [`SMALL`] by coverage masks
/// ([`crate::raster::mask`]), in as few groups of lanes as its width needs: per
/// row, the covered pixels as bits of the three edge functions, then the
/// depth unit on the set bits only. The same fragments in the same order as
/// masked rows, without stepping the depth unit over the pixels the
/// triangle misses.
fn small<F: DepthFormat, P: Probe, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    rect: &TileRect,
    out: &mut SpanOut<F::Texel>,
    probe: &mut P,
) {
    let width = rect.width();
    let drawn = if !LANES {
        None
    } else if width <= LANE_GROUP {
        Lanes::<1>::new(s, rect).map(|m| masked::<F, P, _, DUAL, IDS, COUNT_MAX>(s, view, rect, m, out, probe))
    } else if width <= 2 * LANE_GROUP {
        Lanes::<2>::new(s, rect).map(|m| masked::<F, P, _, DUAL, IDS, COUNT_MAX>(s, view, rect, m, out, probe))
    } else if width <= 4 * LANE_GROUP {
        Lanes::<4>::new(s, rect).map(|m| masked::<F, P, _, DUAL, IDS, COUNT_MAX>(s, view, rect, m, out, probe))
    } else {
        Lanes::<8>::new(s, rect).map(|m| masked::<F, P, _, DUAL, IDS, COUNT_MAX>(s, view, rect, m, out, probe))
    };
    if drawn.is_none() {
        masked::<F, P, _, DUAL, IDS, COUNT_MAX>(s, view, rect, Serial::new(s, rect), out, probe);
    }
}

/// The depth unit on the pixels of `rect` that `masks` set, row by row.
///
/// A triangle meets a row of pixel centres in one interval, so a row's mask
/// is one run of set bits: a run longer than [`SPAN`] goes to the depth unit
/// as a span without edge tests, as a scanline rasterizer draws between its
/// edges. A shorter run, or a mask with a gap (only an edge function out of
/// the setup's budget can wrap into one), takes the set bits one at a time.
#[inline(always)]
fn masked<F: DepthFormat, P: Probe, M: RowMask, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    rect: &TileRect,
    mut masks: M,
    total: &mut SpanOut<F::Texel>,
    probe: &mut P,
) {
    // Counted here and added once, so that the counts stay in registers.
    let mut out = SpanOut::new(F::FAR);
    let (dzx, dzy) = (s.plane.step_x().to_bits(), s.plane.step_y().to_bits());
    let cull_max = view.state.cull_max;
    let mut z_row = s.plane.at(i64::from(rect.x0), i64::from(rect.y0)).to_bits().wrapping_add(ROUND_HALF);
    for y in rect.y0..rect.y1 {
        let mask = masks.next_row();
        if mask != 0 {
            let (k0, k1) = (mask.trailing_zeros(), u64::BITS - mask.leading_zeros());
            let run = mask >> k0;
            if M::WIDTH > SPAN && k1 - k0 > SPAN && run & run.wrapping_add(1) == 0 {
                let Some((z1, z2, ids)) = view.rows::<DUAL, IDS>(y, rect.x0 + k0, rect.x0 + k1) else { break };
                let z = z_row.wrapping_add(dzx.wrapping_mul(i64::from(k0)));
                let edges = SpanEdges { e: [0; 3], de: [0; 3] };
                out.add(&span::<F, DUAL, IDS, false, COUNT_MAX>(z1, z2, ids, s.triangle, z, dzx, edges, cull_max));
            } else {
                let Some((z1, z2, ids)) = view.rows::<DUAL, IDS>(y, rect.x0, rect.x1) else { break };
                bits::<F, DUAL, IDS, COUNT_MAX>(mask, z1, z2, ids, s.triangle, z_row, dzx, &mut out, cull_max);
            }
            if P::FRAGMENTS {
                let mut mask = mask;
                while mask != 0 {
                    let k = mask.trailing_zeros();
                    mask &= mask - 1;
                    let q = F::texel_inside(z_row.wrapping_add(dzx.wrapping_mul(i64::from(k))));
                    let depth = crate::depth::Texel::to_raw(q);
                    probe.fragment(Fragment { x: rect.x0 + k, y, depth, triangle: s.triangle });
                }
            }
        }
        z_row = z_row.wrapping_add(dzy);
    }
    total.add(&out);
}

/// The depth unit on the pixels of a row whose bits `mask` sets (bit `k`
/// for the `k`-th texel of the slices), one at a time.
#[inline(always)]
#[allow(clippy::too_many_arguments, reason = "the hot path's state, passed flat")]
fn bits<F: DepthFormat, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
    mut mask: u64,
    z1: &mut [F::Texel],
    z2: &mut [F::Texel],
    ids: &mut [u32],
    id: u32,
    z: i64,
    dzx: i64,
    out: &mut SpanOut<F::Texel>,
    cull_max: F::Texel,
) {
    while mask != 0 {
        out.fragments += 1;
        let k = mask.trailing_zeros();
        mask &= mask - 1;
        let q = F::texel_inside(z.wrapping_add(dzx.wrapping_mul(i64::from(k))));
        let i = k as usize;
        if DUAL {
            if let (Some(a), Some(b)) = (z1.get_mut(i), z2.get_mut(i)) {
                out.dual::<COUNT_MAX>(a, b, q, cull_max);
            }
        } else if IDS {
            if let (Some(a), Some(t)) = (z1.get_mut(i), ids.get_mut(i)) {
                out.visible::<COUNT_MAX>(a, t, id, q, cull_max);
            }
        } else if let Some(a) = z1.get_mut(i) {
            out.single::<COUNT_MAX>(a, q, cull_max);
        }
    }
}

/// Make the tile's max exact again: a reduction over the culled buffer.
fn refresh_max<F: DepthFormat, P: Probe, const DUAL: bool>(view: &mut TileView<'_, F::Texel>, probe: &mut P) {
    let (r, width) = (view.rect, view.width);
    let buf: &[F::Texel] = if DUAL { view.z2 } else { view.z1 };
    let (_, max) = min_max(tile_rows(buf, r, width), F::FAR);
    view.state.cull_max = max;
    view.state.cull_count = count_of(tile_rows(buf, r, width), max);
    let texels = r.area();
    let buffer = if DUAL { Buffer::Z2 } else { Buffer::Z1 };
    probe.event(Event::TileMaxUpdate { tile: view.tile });
    probe.event(Event::DepthRead { buffer, texels, bytes: texels * F::KIND.bytes() });
}

/// Classify (and cull) the blocks of one block row, merging neighbours of
/// the same kind into runs.
#[inline(always)]
fn block_row<F: DepthFormat, P: Probe>(
    s: &Setup,
    view: &TileView<'_, F::Texel>,
    rect: &TileRect,
    y0: u32,
    y1: u32,
    cull_blocks: bool,
    probe: &mut P,
) -> heapless::Vec<Run, MAX_RUNS> {
    let mut runs: heapless::Vec<Run, MAX_RUNS> = heapless::Vec::new();
    let mut bx = rect.x0 & !(BLOCK - 1);
    while bx < rect.x1 {
        let b = TileRect { x0: bx.max(rect.x0), y0, x1: (bx + BLOCK).min(rect.x1), y1 };
        bx += BLOCK;
        let masked = match s.classify(&b) {
            Coverage::Empty => continue,
            Coverage::Full => false,
            Coverage::Partial => true,
        };
        if cull_blocks && nearest::<F>(s, &b) >= view.state.cull_max {
            probe.event(Event::Culled { tile: view.tile, level: CullLevel::Block, texels: b.area() });
            continue;
        }
        match runs.last_mut() {
            Some(last) if last.x1 == b.x0 && last.masked == masked => last.x1 = b.x1,
            // One run per block at most, so the vector cannot overflow.
            _ => {
                let _ = runs.push(Run { x0: b.x0, x1: b.x1, masked });
            }
        }
    }
    runs
}

/// Run the rows `y0..y1` of each run through the depth unit. The plane and
/// edge values are stepped from row to row by adds.
#[inline(always)]
#[allow(clippy::too_many_arguments, reason = "the hot path's state, passed flat")]
fn rows<F: DepthFormat, P: Probe, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
    s: &Setup,
    view: &mut TileView<'_, F::Texel>,
    y0: u32,
    y1: u32,
    runs: &[Run],
    out: &mut SpanOut<F::Texel>,
    probe: &mut P,
) {
    let (dzx, dzy) = (s.plane.step_x().to_bits(), s.plane.step_y().to_bits());
    let de = [s.edges[0].dx, s.edges[1].dx, s.edges[2].dx];
    let cull_max = view.state.cull_max;
    let mut z_row = s.plane.at(0, i64::from(y0)).to_bits().wrapping_add(ROUND_HALF);
    let mut e_row = [s.edges[0].at(0, i64::from(y0)), s.edges[1].at(0, i64::from(y0)), s.edges[2].at(0, i64::from(y0))];
    for y in y0..y1 {
        for run in runs {
            let x = i64::from(run.x0);
            let z = z_row.wrapping_add(dzx.wrapping_mul(x));
            let at = |k: usize| e_row[k].wrapping_add(de[k].wrapping_mul(x));
            let edges = SpanEdges { e: [at(0), at(1), at(2)], de };
            let Some((z1, z2, ids)) = view.rows::<DUAL, IDS>(y, run.x0, run.x1) else { return };
            let o = if run.masked {
                span::<F, DUAL, IDS, true, COUNT_MAX>(z1, z2, ids, s.triangle, z, dzx, edges, cull_max)
            } else {
                span::<F, DUAL, IDS, false, COUNT_MAX>(z1, z2, ids, s.triangle, z, dzx, edges, cull_max)
            };
            out.add(&o);
            if P::FRAGMENTS {
                report_fragments::<F, P>(s, run.x0, run.x1, y, z, edges, probe);
            }
        }
        z_row = z_row.wrapping_add(dzy);
        for (e, edge) in e_row.iter_mut().zip(&s.edges) {
            *e = e.wrapping_add(edge.dy);
        }
    }
}

/// Per-fragment detail for probes that ask for it.
fn report_fragments<F: DepthFormat, P: Probe>(
    s: &Setup,
    x0: u32,
    x1: u32,
    y: u32,
    z: i64,
    edges: SpanEdges,
    probe: &mut P,
) {
    let mut z = z;
    let mut e = edges.e;
    for x in x0..x1 {
        if e.iter().all(|&v| v >= 0) {
            let depth = crate::depth::Texel::to_raw(F::texel_inside(z));
            probe.fragment(Fragment { x, y, depth, triangle: s.triangle });
        }
        z = z.wrapping_add(s.plane.step_x().to_bits());
        for (v, d) in e.iter_mut().zip(edges.de) {
            *v = v.wrapping_add(d);
        }
    }
}

/// Report a triangle's work in a tile and bring the tile's summary up to date.
fn finish_triangle<F: DepthFormat, P: Probe, const DUAL: bool, const IDS: bool, const COUNT_MAX: bool>(
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
        if IDS && out.written1 > 0 {
            let texels = out.written1;
            probe.event(Event::DepthWrite { buffer: Buffer::Id, texels, bytes: texels * ID_BYTES });
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
    if COUNT_MAX {
        st.cull_count = st.cull_count.saturating_sub(out.lost_max);
    }
}
