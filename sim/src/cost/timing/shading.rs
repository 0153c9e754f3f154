//! The shading's events tallied per tile: integer counts, charged as
//! cycles once, when the pass is finished, rather than event by event.
//!
//! An architecture's probe counts the shading unit's events of each tile
//! ([`ShadeCounts`]) and turns them into cycles in [`ArchProbe::finish`]:
//! `pixels × (shade, lookup program)`, `samples ÷ samples a clock`, and so
//! on, one product a count. Event by event, the same charges were sums of
//! one term an event; the two differ only in the rounding of those sums
//! (see [`charges_event_by_event`]).

use super::ArchProbe;
use crate::cost::work::Stage;

/// The shading unit's events of one tile, counted: what its shade and
/// shadow cycles are charged from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct ShadeCounts {
    /// Pixels shaded (each one shading program and one lookup's).
    pub(crate) pixels: u64,
    /// Depth samples and silhouette points read.
    pub(crate) samples: u64,
    /// Lookups culled by the tiles' bounds (one compare each).
    pub(crate) culled: u64,
    /// Virtual samples (an add and a compare each).
    pub(crate) virtual_samples: u64,
    /// Tangent-plane setups (a division each).
    pub(crate) tangents: u64,
}

impl ShadeCounts {
    pub(super) fn add(&mut self, o: &Self) {
        self.pixels += o.pixels;
        self.samples += o.samples;
        self.culled += o.culled;
        self.virtual_samples += o.virtual_samples;
        self.tangents += o.tangents;
    }
}

#[cfg(test)]
thread_local! {
    /// Charge the shading's cycles event by event, as the tallies' reference.
    static EVENT_BY_EVENT: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
}

/// Run `f` with every architecture probe made on this thread charging the
/// shading's cycles event by event (the reference the tallies are held to).
#[cfg(test)]
pub(crate) fn charges_event_by_event<T>(f: impl FnOnce() -> T) -> T {
    EVENT_BY_EVENT.with(|e| e.set(true));
    let out = f();
    EVENT_BY_EVENT.with(|e| e.set(false));
    out
}

/// Whether probes made now charge event by event.
pub(super) fn event_by_event() -> bool {
    #[cfg(test)]
    return EVENT_BY_EVENT.with(core::cell::Cell::get);
    #[cfg(not(test))]
    false
}

impl<const D: bool> ArchProbe<D> {
    /// The shade and shadow cycles of `n`: the shading program and the
    /// lookup's own instructions per pixel (none on a machine shading per
    /// fragment, which charges them per fragment), each sample read at the
    /// shadow unit's rate (fetched in the program when shading per
    /// fragment), a compare per culled lookup and per virtual sample, and a
    /// divider's occupancy per tangent setup.
    #[allow(clippy::cast_precision_loss, reason = "counts far below 2^53")]
    fn shading_cycles(&self, n: &ShadeCounts) -> (f64, f64) {
        let a = &self.arch;
        let spc = a.shadow.samples_per_clock;
        let (shade, lookup) = if a.shade.per_fragment { (0.0, 0.0) } else { self.program() };
        let samples = if a.shade.per_fragment { 0.0 } else { Self::per(n.samples, spc) };
        let divide = a.shadow.divider_cycles / a.shadow.dividers.max(1) as f64;
        let shadow = n.pixels as f64 * lookup
            + samples
            + Self::per(n.culled, spc)
            + Self::per(n.virtual_samples, spc)
            + n.tangents as f64 * divide;
        (n.pixels as f64 * shade, shadow)
    }

    /// Count the shading's `n` in the current tile: tallied, or (for the
    /// tallies' reference) charged at once.
    pub(super) fn shaded(&mut self, n: &ShadeCounts) {
        if self.event_by_event {
            let (shade, shadow) = self.shading_cycles(n);
            let w = self.work();
            w.charge(Stage::Shade, shade);
            w.charge(Stage::Shadow, shadow);
            return;
        }
        let i = self.unit();
        if self.shading.len() < self.tiles.len() {
            self.shading.resize(self.tiles.len(), ShadeCounts::default());
        }
        self.shading[i].add(n);
    }

    /// Charge each tile's tallied shading as cycles (once, when the pass is finished).
    pub(super) fn charge_tallies(&mut self) {
        let tallies = core::mem::take(&mut self.shading);
        for (i, n) in tallies.iter().enumerate() {
            let (shade, shadow) = self.shading_cycles(n);
            if let Some(w) = self.tiles.get_mut(i) {
                w.charge(Stage::Shade, shade);
                w.charge(Stage::Shadow, shadow);
            }
        }
    }
}
