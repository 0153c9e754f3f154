//! Events: what each unit did, reported to a [`Probe`].
//!
//! The core never counts cycles or bytes of traffic itself: every unit tells
//! the probe what it did, in batches per span or per tile, and a probe (an
//! architecture model in the simulator, a counter in a test) decides what
//! that costs. The default [`NoProbe`] does nothing, and because the driver
//! is generic over the probe, its calls compile away.
//!
//! Per-fragment detail (position, depth, triangle) is reported only to
//! probes that set [`Probe::FRAGMENTS`]; for all others that code is not
//! compiled in.

mod event;
mod totals;

pub use event::{Buffer, CullLevel, Event, FlushReason, Fragment, RejectReason, Tap, TexelRead, TexelRect};
pub use totals::{Counted, Totals};

/// Receives unit events. Every method has an empty default.
pub trait Probe {
    /// Whether [`Probe::fragment`] is called. When `false` (the default) the
    /// per-fragment reporting is not compiled in.
    const FRAGMENTS: bool = false;

    /// Whether [`Probe::texel_read`] is called (off by default, compiled out).
    const TEXELS: bool = false;

    /// Whether [`Probe::tap`] is called (off by default, compiled out). A
    /// probe that watches taps sees every sample of every lookup: the
    /// shadow unit's shortcuts (the tile-bounds cull, the uniform box)
    /// are skipped for it, which gives the same result.
    const TAPS: bool = false;

    /// Whether the probe looks at [`Probe::event`] (on by default). A driver
    /// may size the stores and bins of a pass no one watches for its own
    /// speed: the maps do not depend on them, only the events do.
    const EVENTS: bool = true;

    /// A unit event.
    #[inline(always)]
    fn event(&mut self, event: Event) {
        let _ = event;
    }

    /// A generated fragment (only when [`Probe::FRAGMENTS`] is set).
    #[inline(always)]
    fn fragment(&mut self, fragment: Fragment) {
        let _ = fragment;
    }

    /// A texel the shadow unit read (only when [`Probe::TEXELS`] is set).
    #[inline(always)]
    fn texel_read(&mut self, read: TexelRead) {
        let _ = read;
    }

    /// A rectangle of texels the shadow unit read (only when
    /// [`Probe::TEXELS`] is set): by default each of its reads
    /// ([`TexelRect::reads`]) in turn, as [`Probe::texel_read`]. A probe
    /// that models memory may take the rectangle at once.
    #[inline(always)]
    fn texels_read(&mut self, rect: TexelRect) {
        for read in rect.reads() {
            self.texel_read(read);
        }
    }

    /// A sample the shadow unit compared (only when [`Probe::TAPS`] is set).
    #[inline(always)]
    fn tap(&mut self, tap: Tap) {
        let _ = tap;
    }

    /// The shadow unit is pointed at light `light`'s map (its base
    /// address): the texels read from here on are that map's, until the
    /// next. A camera pass that tests several lights binds each in turn;
    /// one that tests one never calls this (light 0's map is bound).
    #[inline(always)]
    fn map_bound(&mut self, light: u16) {
        let _ = light;
    }

    /// An event of only some of the tilings a shadow unit tests its
    /// lookups against ([`MapView::with_tilings`](crate::shadow::MapView::with_tilings)):
    /// a lookup that one tiling's stored bounds cull and another's do not.
    /// A probe that models one tiling keeps the events of its own; the
    /// default is tiling 0's, the map's own.
    #[inline(always)]
    fn event_for(&mut self, tilings: Tilings, event: Event) {
        if tilings.has(0) {
            self.event(event);
        }
    }

    /// A texel read for only some tilings, as [`Probe::event_for`].
    #[inline(always)]
    fn texel_read_for(&mut self, tilings: Tilings, read: TexelRead) {
        if tilings.has(0) {
            self.texel_read(read);
        }
    }

    /// A rectangle of texels read for only some tilings: by default each
    /// of its reads in turn, as [`Probe::texel_read_for`].
    #[inline(always)]
    fn texels_read_for(&mut self, tilings: Tilings, rect: TexelRect) {
        for read in rect.reads() {
            self.texel_read_for(tilings, read);
        }
    }
}

/// A set of the tilings a shadow unit tests a lookup against (at most
/// [`Tilings::MAX`]): tiling 0 is the map's own, the others are those of
/// [`MapView::with_tilings`](crate::shadow::MapView::with_tilings), in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Tilings(pub u8);

impl Tilings {
    /// The most tilings a lookup is tested against.
    pub const MAX: usize = 8;

    /// Whether tiling `k` is in the set.
    #[must_use]
    #[inline(always)]
    pub const fn has(self, k: usize) -> bool {
        k < Self::MAX && self.0 & (1 << k) != 0
    }
}

/// The probe that does nothing and costs nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {
    const EVENTS: bool = false;
}

impl<P: Probe + ?Sized> Probe for &mut P {
    const FRAGMENTS: bool = P::FRAGMENTS;
    const TEXELS: bool = P::TEXELS;
    const TAPS: bool = P::TAPS;
    const EVENTS: bool = P::EVENTS;

    #[inline(always)]
    fn event(&mut self, event: Event) {
        (**self).event(event);
    }

    #[inline(always)]
    fn fragment(&mut self, fragment: Fragment) {
        (**self).fragment(fragment);
    }

    #[inline(always)]
    fn map_bound(&mut self, light: u16) {
        (**self).map_bound(light);
    }

    #[inline(always)]
    fn texel_read(&mut self, read: TexelRead) {
        (**self).texel_read(read);
    }

    #[inline(always)]
    fn tap(&mut self, tap: Tap) {
        (**self).tap(tap);
    }

    #[inline(always)]
    fn event_for(&mut self, tilings: Tilings, event: Event) {
        (**self).event_for(tilings, event);
    }

    #[inline(always)]
    fn texel_read_for(&mut self, tilings: Tilings, read: TexelRead) {
        (**self).texel_read_for(tilings, read);
    }

    #[inline(always)]
    fn texels_read(&mut self, rect: TexelRect) {
        (**self).texels_read(rect);
    }

    #[inline(always)]
    fn texels_read_for(&mut self, tilings: Tilings, rect: TexelRect) {
        (**self).texels_read_for(tilings, rect);
    }
}

/// A probe that sees a shadow unit's events as those of `tilings` only:
/// the reads of a lookup that the other tilings' bounds culled.
#[cfg(feature = "tilings")]
pub(crate) struct For<P> {
    pub(crate) probe: P,
    pub(crate) tilings: Tilings,
}

#[cfg(feature = "tilings")]
impl<P: Probe> Probe for For<P> {
    const FRAGMENTS: bool = P::FRAGMENTS;
    const TEXELS: bool = P::TEXELS;
    const TAPS: bool = P::TAPS;
    const EVENTS: bool = P::EVENTS;

    #[inline(always)]
    fn event(&mut self, event: Event) {
        self.probe.event_for(self.tilings, event);
    }

    #[inline(always)]
    fn texel_read(&mut self, read: TexelRead) {
        self.probe.texel_read_for(self.tilings, read);
    }

    #[inline(always)]
    fn event_for(&mut self, tilings: Tilings, event: Event) {
        self.probe.event_for(Tilings(tilings.0 & self.tilings.0), event);
    }

    #[inline(always)]
    fn texel_read_for(&mut self, tilings: Tilings, read: TexelRead) {
        self.probe.texel_read_for(Tilings(tilings.0 & self.tilings.0), read);
    }

    #[inline(always)]
    fn texels_read(&mut self, rect: TexelRect) {
        self.probe.texels_read_for(self.tilings, rect);
    }

    #[inline(always)]
    fn texels_read_for(&mut self, tilings: Tilings, rect: TexelRect) {
        self.probe.texels_read_for(Tilings(tilings.0 & self.tilings.0), rect);
    }
}
