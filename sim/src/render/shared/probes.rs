//! Architectures' probes as a shared pass leaves them: kept, copied and
//! fanned out to the next pass.

use umbra_core::probe::Probe;
use umbra_core::{DepthFormatKind, RasterConfig};

use super::super::costed::{SceneCounts, reading, report};
use crate::base::probes::{Fan, Tee};
use crate::cost::arch::Arch;
use crate::cost::arch::CacheParams;
use crate::cost::report::CostReport;
use crate::cost::timing::{ArchProbe, PassKind, Tally};
use crate::pass::algorithm::Units;
use crate::render::RenderConfig;

/// A probe kept as a pass left it, of either kind of architecture: one
/// that needs each fragment's address (a depth cache in front of off-chip
/// depth) or one that does not.
#[derive(Clone, Debug)]
pub(super) enum Kept {
    Plain(ArchProbe<false>),
    Detail(ArchProbe<true>),
}

impl Kept {
    /// A new probe of `arch` for a pass of `kind` over `raster` with
    /// `buffers` depth buffers of `format`, fed each fragment's address
    /// when `detail`.
    pub(super) fn new(
        arch: &Arch,
        (kind, raster): (PassKind, RasterConfig),
        (format, buffers): (DepthFormatKind, u32),
        detail: bool,
    ) -> Self {
        if detail {
            Self::Detail(ArchProbe::new(arch, kind, raster, format, buffers))
        } else {
            Self::Plain(ArchProbe::new(arch, kind, raster, format, buffers))
        }
    }

    /// The camera probe reading the map `cfg` and `units` draw.
    pub(super) fn reading(self, cfg: &RenderConfig, units: &Units) -> Self {
        match self {
            Self::Plain(p) => Self::Plain(reading(p, cfg, units, true)),
            Self::Detail(p) => Self::Detail(reading(p, cfg, units, true)),
        }
    }

    /// The probe as that of tiling `tiling` among those a shared shading's
    /// lookups are tested against.
    pub(super) fn in_tiling(mut self, tiling: usize) -> Self {
        match &mut self {
            Self::Plain(p) => p.tiling = tiling,
            Self::Detail(p) => p.tiling = tiling,
        }
        self
    }

    /// The report of the `lights` probes (one a light) and a `camera`
    /// probe, once the passes have run: `None` for probes of another kind
    /// than one another (one architecture's are all of one).
    pub(super) fn report(
        names: (&str, &SceneCounts),
        cfg: &RenderConfig,
        config: &str,
        lights: Vec<Self>,
        camera: Self,
    ) -> Option<CostReport> {
        let (mut plain, mut detail) = (Vec::new(), Vec::new());
        for l in lights {
            match l {
                Self::Plain(p) => plain.push(p),
                Self::Detail(p) => detail.push(p),
            }
        }
        Some(match (camera, plain.is_empty(), detail.is_empty()) {
            (_, false, false) => return None,
            (Self::Plain(c), _, true) => report(names, cfg, config, plain, c),
            (Self::Detail(c), _, true) => report(names, cfg, config, plain, c),
            (Self::Plain(c), true, false) => report(names, cfg, config, detail, c),
            (Self::Detail(c), true, false) => report(names, cfg, config, detail, c),
        })
    }
}

/// A pass that reports to a probe of any type: [`Probes::run`] gives it
/// the fan-out of the probes it holds.
pub(super) trait Reporting {
    /// What the pass gives.
    type Out;
    /// Run the pass, every event to `probe`.
    fn run<P: Probe>(self, probe: &mut P) -> Self::Out;
}

/// Probes of several architectures, split by kind so each kind is one
/// [`Fan`]: `(architecture index, probe)`.
#[derive(Debug, Default)]
pub(super) struct Probes {
    plain: Vec<(usize, ArchProbe<false>)>,
    detail: Vec<(usize, ArchProbe<true>)>,
}

impl Probes {
    pub(super) fn push(&mut self, arch: usize, p: Kept) {
        match p {
            Kept::Plain(p) => self.plain.push((arch, p)),
            Kept::Detail(p) => self.detail.push((arch, p)),
        }
    }

    /// Run `pass` with every probe fanned out (each kind in its order),
    /// then put them back. Without a probe that needs fragments, the pass
    /// reports none.
    pub(super) fn run<T: Reporting>(&mut self, pass: T) -> T::Out {
        let (a, plain): (Vec<usize>, Vec<_>) = std::mem::take(&mut self.plain).into_iter().unzip();
        let (b, detail): (Vec<usize>, Vec<_>) = std::mem::take(&mut self.detail).into_iter().unzip();
        let (out, plain, detail) = if detail.is_empty() {
            let mut fan = Fan(plain);
            (pass.run(&mut fan), fan.0, detail)
        } else {
            let mut fan = Tee(Fan(plain), Fan(detail));
            let out = pass.run(&mut fan);
            let Tee(Fan(plain), Fan(detail)) = fan;
            (out, plain, detail)
        };
        self.plain = a.into_iter().zip(plain).collect();
        self.detail = b.into_iter().zip(detail).collect();
        out
    }

    /// A tally for a shading of an image of `size` that these probes read:
    /// per tile of the finest of their tilings, for each of their tilings,
    /// through each of their map caches.
    pub(super) fn tally(&self, (width, height): (u32, u32)) -> Tally {
        let needs: Vec<_> = self
            .plain
            .iter()
            .map(|(_, p)| (p.tiling, p.tallied_as()))
            .chain(self.detail.iter().map(|(_, p)| (p.tiling, p.tallied_as())))
            .collect();
        let shift = needs.iter().map(|(_, (s, ..))| *s).min().unwrap_or(5);
        let tilings = needs.iter().map(|(t, _)| t + 1).max().unwrap_or(1);
        let caches: Vec<(usize, &CacheParams)> = needs.iter().map(|(t, (_, c, _))| (*t, *c)).collect();
        let addressing = needs.iter().find_map(|(_, (_, _, m))| m.cloned());
        Tally::new((width, height, shift), tilings, &caches, addressing)
    }

    /// Each probe's share of `tally`, added.
    pub(super) fn absorb(&mut self, tally: &Tally) {
        self.plain.iter_mut().for_each(|(_, p)| p.absorb(tally, p.tiling));
        self.detail.iter_mut().for_each(|(_, p)| p.absorb(tally, p.tiling));
    }

    /// The probes, by architecture.
    pub(super) fn into_kept(self) -> Vec<(usize, Kept)> {
        let mut all: Vec<(usize, Kept)> = self.plain.into_iter().map(|(i, p)| (i, Kept::Plain(p))).collect();
        all.extend(self.detail.into_iter().map(|(i, p)| (i, Kept::Detail(p))));
        all.sort_by_key(|(i, _)| *i);
        all
    }
}

/// Probe `i`'s kept copy among `list`.
pub(super) fn copy_of(list: &[(usize, Kept)], i: usize) -> Option<Kept> {
    list.iter().find(|(j, _)| *j == i).map(|(_, p)| p.clone())
}
