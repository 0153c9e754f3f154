//! The filters: compare each sample, then weigh the results.

use super::{
    AllFilters, Bias, Built, DepthTest, Filter, HALF, Lookup, MapCoord, MapView, Shadow, ShadowConfig, Slope, Texels,
    TileBounds, floor, jitter_grid, reference_bounds,
};
use crate::budget::MAP_FRACTION_BITS;
use crate::depth::{DepthFormat, PlaneZ};
use crate::grid::TileRect;
use crate::probe::{Event, NoProbe, Probe, TexelRect};
#[cfg(feature = "tilings")]
use crate::probe::{For, Tilings};

/// Shadow a lookup: the fraction of its samples in shadow.
pub fn shadow<F: DepthFormat, P: Probe>(map: &MapView<'_, F>, cfg: &ShadowConfig, l: &Lookup, probe: &mut P) -> Shadow {
    lookup::<F, P, AllFilters>(map, cfg, l, l.slope, probe)
}

/// [`shadow`] with the receiver's slope given apart from the lookup (a
/// pixel's ordinary and virtual-sample lookups share the rest). The front
/// of the unit (footprint, clip, the tile-bounds cull) decides most lookups
/// on its own; the filter runs for the rest. Only the datapaths `K` has
/// are in the program; a configuration needing another is lit (the units
/// refuse such configurations before they shade: [`Built::missing`]).
#[inline(always)]
pub(crate) fn lookup<F: DepthFormat, P: Probe, K: Built>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    slope: Option<Slope>,
    probe: &mut P,
) -> Shadow {
    if l.z < 0 {
        return Shadow::ZERO;
    }
    let grid = match cfg.filter {
        Filter::Jittered(j) if K::JITTERED => Some(jitter_grid(&j, l.footprint)),
        _ => None,
    };
    let Some(footprint) = Texels::under(cfg.filter, l, grid) else { return Shadow::ZERO };
    let (inside_map, whole) = footprint.clip(map.raster.width(), map.raster.height());
    let Some(inside_map) = inside_map else {
        // Entirely outside the map: lit, and nothing to read.
        probe.event(Event::LookupCulled { texels: footprint.count() });
        return Shadow::ZERO;
    };
    // A probe that watches taps sees every sample: the cull's result is theirs.
    if cfg.cull_lookups && !P::TAPS {
        let (bias_lo, bias_hi) = cfg.bias.bounds();
        // The receiver's depth range over the footprint: a plane takes its
        // extremes at the corners (a receiver without a slope is one depth).
        let (z_lo, z_hi) = if slope.is_some() {
            let corners = [
                (footprint.x0, footprint.y0),
                (footprint.x1, footprint.y0),
                (footprint.x0, footprint.y1),
                (footprint.x1, footprint.y1),
            ]
            .map(|(x, y)| l.depth_on(slope, x, y));
            (corners.iter().copied().min().unwrap_or(0), corners.iter().copied().max().unwrap_or(0))
        } else {
            (l.z.to_bits(), l.z.to_bits())
        };
        let lit_from = at_format::<F>(z_hi.saturating_sub(bias_lo));
        let shadowed_above = at_format::<F>(z_lo.saturating_sub(bias_hi));
        let cull = |tiles: &TileBounds<'_, F::Texel>| {
            let (r_lo, r_hi) = reference_bounds(map, tiles, cfg.test, &inside_map);
            if lit_from <= r_lo { Some(Shadow::ZERO) } else { (whole && shadowed_above > r_hi).then_some(Shadow::ONE) }
        };
        let own = cull(&map.bounds);
        let culled = Event::LookupCulled { texels: footprint.count() };
        #[cfg(feature = "tilings")]
        if !map.others.is_empty() {
            // Each tiling's bounds tested; the texels are read once for
            // the tilings that do not cull, and reported to them alone.
            let (mut by, mut result) = (Tilings(u8::from(own.is_some())), own);
            for (k, tiles) in map.others.iter().enumerate() {
                if let Some(shadow) = cull(tiles) {
                    by.0 |= 1 << (k + 1);
                    result = Some(shadow);
                }
            }
            let all = Tilings(u8::MAX >> (Tilings::MAX - 1 - map.others.len()));
            match result {
                Some(shadow) if by == all => {
                    probe.event(culled);
                    return shadow;
                }
                Some(_) => {
                    probe.event_for(by, culled);
                    let mut rest = For { probe: &mut *probe, tilings: Tilings(all.0 & !by.0) };
                    return read::<F, _, K>(map, cfg, l, slope, (footprint, inside_map, whole), grid, &mut rest);
                }
                None => return read::<F, P, K>(map, cfg, l, slope, (footprint, inside_map, whole), grid, probe),
            }
        }
        if let Some(shadow) = own {
            probe.event(culled);
            return shadow;
        }
    }
    read::<F, P, K>(map, cfg, l, slope, (footprint, inside_map, whole), grid, probe)
}

/// A lookup's samples read, once no tiling's bounds decided it: the
/// footprint, its part on the map, and whether that is all of it.
#[inline(always)]
fn read<F: DepthFormat, P: Probe, K: Built>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    slope: Option<Slope>,
    (footprint, inside_map, whole): (Texels, TileRect, bool),
    grid: Option<([MapCoord; 2], [u32; 2])>,
    probe: &mut P,
) -> Shadow {
    if let (Filter::Box { .. }, true, None, Bias::Constant(b), true, false) =
        (cfg.filter, whole, slope, cfg.bias, K::BOX, P::TAPS)
    {
        return uniform_box(
            map,
            cfg.test,
            &inside_map,
            at_format::<F>(l.z.to_bits().saturating_sub(b.to_bits())),
            probe,
        );
    }
    filter::<F, P, K>(map, cfg, &Lookup { slope, ..*l }, footprint, grid, probe)
}

/// The commonest filter, inline: a box all on the map against one receiver
/// depth, already biased and rounded, so that each texel is a compare; its
/// texels reported as one rectangle ([`Probe::texels_read`]).
#[inline]
fn uniform_box<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    test: DepthTest,
    r: &TileRect,
    receiver: i64,
    probe: &mut P,
) -> Shadow {
    if P::TEXELS {
        let mut buffers = map.buffers_read(test);
        let buffers = [buffers.next(), buffers.next()];
        probe.texels_read(TexelRect { x0: r.x0, y0: r.y0, x1: r.x1, y1: r.y1, buffers });
    }
    let mut count = 0u64;
    for y in r.y0..r.y1 {
        for x in r.x0..r.x1 {
            count += u64::from(map.compare(test, x, y, receiver, &mut NoProbe));
        }
    }
    let reads = r.area();
    report_reads(map, test, reads, false, probe);
    fraction(count, u64::from(reads))
}

/// Report a lookup's `reads` texels read from each buffer its test reads,
/// and whether they were virtual samples.
#[inline]
fn report_reads<F: DepthFormat, P: Probe>(
    map: &MapView<'_, F>,
    test: DepthTest,
    reads: u32,
    virtual_samples: bool,
    probe: &mut P,
) {
    if reads == 0 {
        return;
    }
    if virtual_samples {
        probe.event(Event::VirtualSamples { count: reads });
    }
    for buffer in map.buffers_read(test) {
        probe.event(Event::MapRead { buffer, texels: reads, bytes: reads * F::KIND.bytes() });
    }
}

/// The filter: the samples of a lookup the front did not decide, over its
/// footprint (inclusive; samples off the map are lit).
#[inline(never)]
fn filter<F: DepthFormat, P: Probe, K: Built>(
    map: &MapView<'_, F>,
    cfg: &ShadowConfig,
    l: &Lookup,
    footprint: Texels,
    grid: Option<([MapCoord; 2], [u32; 2])>,
    probe: &mut P,
) -> Shadow {
    let mut rng = oorandom::Rand32::new(l.seed);
    let mut reads = 0u32;
    let mut sample = |x: i32, y: i32, z: i64, weight: u64, rng: &mut oorandom::Rand32| -> bool {
        let bias = match cfg.bias {
            Bias::Constant(b) => b.to_bits(),
            Bias::Range { lo, hi } if K::BIAS_RANGE => lerp_bits(lo.to_bits(), hi.to_bits(), rng.rand_u32()),
            Bias::Range { .. } => 0,
        };
        let shadowed = map.sample(cfg.test, (x.into(), y.into()), z, bias, weight, probe);
        reads += u32::from(shadowed.is_some());
        shadowed.unwrap_or(false)
    };
    let result = match (cfg.filter, grid) {
        (Filter::Point, _) if K::POINT => {
            let (x, y) = (footprint.x0, footprint.y0);
            Shadow::from_num(u8::from(sample(x, y, l.depth_at(x, y), 1, &mut rng)))
        }
        (Filter::Bilinear, _) if K::BILINEAR => {
            // Weights from the fractional position, 16 bits each: they sum to 2³² exactly.
            let fx = u64::from(l.x.saturating_sub(HALF).frac().to_bits().unsigned_abs());
            let fy = u64::from(l.y.saturating_sub(HALF).frac().to_bits().unsigned_abs());
            let one = 1u64 << MAP_FRACTION_BITS;
            let weights = [(one - fx) * (one - fy), fx * (one - fy), (one - fx) * fy, fx * fy];
            // The receiver at the four centres by forward differences.
            let z00 = l.depth_at(footprint.x0, footprint.y0);
            let (du, dv) = l.slope.map_or((0, 0), |s| (s.du, s.dv));
            let z = [z00, z00.saturating_add(du), z00.saturating_add(dv), z00.saturating_add(du).saturating_add(dv)];
            let corners = [(0, 0), (1, 0), (0, 1), (1, 1)];
            let shadowed: u64 = corners
                .iter()
                .zip(weights)
                .zip(z)
                .map(
                    |((&(dx, dy), wgt), z)| {
                        if sample(footprint.x0 + dx, footprint.y0 + dy, z, wgt, &mut rng) { wgt } else { 0 }
                    },
                )
                .sum();
            fraction(shadowed, 1 << (2 * MAP_FRACTION_BITS))
        }
        (Filter::Box { .. }, _) if K::BOX => {
            let mut count = 0u64;
            // One evaluation per row, then forward differences along it
            // (the box all on the map against one depth is `uniform_box`).
            let du = l.slope.map_or(0, |s| s.du);
            for y in footprint.y0..=footprint.y1 {
                let mut z = l.depth_at(footprint.x0, y);
                for x in footprint.x0..=footprint.x1 {
                    count += u64::from(sample(x, y, z, 1, &mut rng));
                    z = z.saturating_add(du);
                }
            }
            fraction(count, u64::from(footprint.count()))
        }
        (Filter::Jittered(_), Some((half, [ns, nt]))) if K::JITTERED => {
            // Subregions of 2·half/n texels; each sample jittered within its own.
            let step = |h: MapCoord, n: u32| {
                MapCoord::from_bits(h.to_bits().saturating_mul(2) / i32::try_from(n.max(1)).unwrap_or(i32::MAX))
            };
            let (ds, dt) = (step(half[0], ns), step(half[1], nt));
            let s0 = l.x.saturating_sub(half[0]).saturating_add(ds / 2);
            let t0 = l.y.saturating_sub(half[1]).saturating_add(dt / 2);
            let mut count = 0u64;
            for i in 0..ns {
                for j in 0..nt {
                    let s = s0.saturating_add(ds.saturating_mul_int(i32::try_from(i).unwrap_or(i32::MAX)));
                    let t = t0.saturating_add(dt.saturating_mul_int(i32::try_from(j).unwrap_or(i32::MAX)));
                    let ju = jitter(ds / 2, rng.rand_u32());
                    let jv = jitter(dt / 2, rng.rand_u32());
                    // Jittered texels are irregular: the plane is evaluated directly.
                    let (u, v) = (floor(s.saturating_add(ju)), floor(t.saturating_add(jv)));
                    count += u64::from(sample(u, v, l.depth_at(u, v), 1, &mut rng));
                }
            }
            fraction(count, u64::from(ns * nt))
        }
        // A jittered filter without its grid, or a filter not built.
        _ => Shadow::ZERO,
    };
    report_reads(map, cfg.test, reads, l.slope.is_some(), probe);
    result
}

/// A receiver depth rounded to the map's format (as the light pass rounds
/// fragments), widened back: comparisons are at the stored precision, so a
/// receiver exactly on a stored surface compares equal.
#[inline]
pub(super) fn at_format<F: DepthFormat>(z: i64) -> i64 {
    F::widen(F::texel(PlaneZ::from_bits(z)))
}

/// `k / n` as a [`Shadow`], rounded to nearest.
fn fraction(k: u64, n: u64) -> Shadow {
    let n = n.max(1);
    let bits = ((k << MAP_FRACTION_BITS) + n / 2) / n;
    Shadow::from_bits(u32::try_from(bits.min(1 << MAP_FRACTION_BITS)).unwrap_or(1 << MAP_FRACTION_BITS))
}

/// A uniform offset in `[−half, half)` from 32 random bits.
fn jitter(half: MapCoord, r: u32) -> MapCoord {
    let signed = i64::from(r) - (1 << 31); // [−2³¹, 2³¹)
    let v = (i64::from(half.to_bits()) * signed) >> 31;
    MapCoord::from_bits(i32::try_from(v).unwrap_or(0))
}

/// `lo + (hi − lo)·r/2³²` in [`PlaneZ`] bits.
fn lerp_bits(lo: i64, hi: i64, r: u32) -> i64 {
    let span = i128::from(hi) - i128::from(lo);
    let v = i128::from(lo) + ((span * i128::from(r)) >> 32);
    i64::try_from(v).unwrap_or(lo)
}
