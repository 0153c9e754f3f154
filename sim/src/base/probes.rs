//! Probes that pass the core's events on: to two probes ([`Tee`]) or to
//! each of several ([`Fan`]).

use umbra_core::probe::{Event, Fragment, Probe, Tap, TexelRead, TexelRect, Tilings};

/// Forwards every event, fragment and texel read to two probes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Tee<A, B>(pub A, pub B);

impl<A: Probe, B: Probe> Probe for Tee<A, B> {
    const FRAGMENTS: bool = A::FRAGMENTS || B::FRAGMENTS;
    const TEXELS: bool = A::TEXELS || B::TEXELS;
    const TAPS: bool = A::TAPS || B::TAPS;
    const EVENTS: bool = A::EVENTS || B::EVENTS;

    #[inline]
    fn event(&mut self, e: Event) {
        self.0.event(e);
        self.1.event(e);
    }

    #[inline]
    fn fragment(&mut self, f: Fragment) {
        self.0.fragment(f);
        self.1.fragment(f);
    }

    #[inline]
    fn texel_read(&mut self, r: TexelRead) {
        self.0.texel_read(r);
        self.1.texel_read(r);
    }

    #[inline]
    fn tap(&mut self, t: Tap) {
        self.0.tap(t);
        self.1.tap(t);
    }

    #[inline]
    fn map_bound(&mut self, light: u16) {
        self.0.map_bound(light);
        self.1.map_bound(light);
    }

    #[inline]
    fn event_for(&mut self, tilings: Tilings, e: Event) {
        self.0.event_for(tilings, e);
        self.1.event_for(tilings, e);
    }

    #[inline]
    fn texel_read_for(&mut self, tilings: Tilings, r: TexelRead) {
        self.0.texel_read_for(tilings, r);
        self.1.texel_read_for(tilings, r);
    }

    #[inline]
    fn texels_read(&mut self, r: TexelRect) {
        self.0.texels_read(r);
        self.1.texels_read(r);
    }

    #[inline]
    fn texels_read_for(&mut self, tilings: Tilings, r: TexelRect) {
        self.0.texels_read_for(tilings, r);
        self.1.texels_read_for(tilings, r);
    }
}

/// Every event to each of several probes, in order.
#[derive(Debug)]
pub(crate) struct Fan<P>(pub Vec<P>);

impl<P: Probe> Probe for Fan<P> {
    const FRAGMENTS: bool = P::FRAGMENTS;
    const TEXELS: bool = P::TEXELS;
    const TAPS: bool = P::TAPS;
    const EVENTS: bool = P::EVENTS;

    #[inline]
    fn event(&mut self, e: Event) {
        self.0.iter_mut().for_each(|p| p.event(e));
    }

    #[inline]
    fn fragment(&mut self, f: Fragment) {
        self.0.iter_mut().for_each(|p| p.fragment(f));
    }

    #[inline]
    fn map_bound(&mut self, light: u16) {
        self.0.iter_mut().for_each(|p| p.map_bound(light));
    }

    #[inline]
    fn texel_read(&mut self, r: TexelRead) {
        self.0.iter_mut().for_each(|p| p.texel_read(r));
    }

    #[inline]
    fn tap(&mut self, t: Tap) {
        self.0.iter_mut().for_each(|p| p.tap(t));
    }

    #[inline]
    fn event_for(&mut self, tilings: Tilings, e: Event) {
        self.0.iter_mut().for_each(|p| p.event_for(tilings, e));
    }

    #[inline]
    fn texel_read_for(&mut self, tilings: Tilings, r: TexelRead) {
        self.0.iter_mut().for_each(|p| p.texel_read_for(tilings, r));
    }

    #[inline]
    fn texels_read(&mut self, r: TexelRect) {
        self.0.iter_mut().for_each(|p| p.texels_read(r));
    }

    #[inline]
    fn texels_read_for(&mut self, tilings: Tilings, r: TexelRect) {
        self.0.iter_mut().for_each(|p| p.texels_read_for(tilings, r));
    }
}
