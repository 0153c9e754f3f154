//! Each wrong pixel judged by its cause: what the shadow unit compared.
//!
//! A pixel whose shade differs from the reference is replayed through the
//! core's own shadow unit with a probe that records every sample it
//! compared (a [`Tap`]: the texel, the receiver's depth and bias, the
//! depth compared against, the map's first layer there, the outcome and
//! the filter's weight). Each tap is then read against the exact
//! geometry: the receiver's own plane on the map (its depth at the tap's
//! texel and its slope across a texel) and, for a tap that came out lit,
//! whether the exact light ray through the texel's centre meets a surface
//! in front of the receiver. The classes, in the papers' terms:
//!
//! | class | rule | paper |
//! |---|---|---|
//! | [`Cause::Acne`] | too dark, and every tap that darkens it compared against a depth within the receiver's own span at that texel (`c ≥ r − σ`: its depth `r` there less its slope across the texel and one step of the format) — the receiver, or a surface touching it, shadowed itself | Williams 1978; Wang & Molnar 1994 §2, "self-shadowing" |
//! | [`Cause::Detachment`] | too light, and most of the lit taps' weight is on taps whose exact ray meets an occluder in front of the receiver and that only the bias (or the dual depth's offset) moved past it: without them the tap would shadow | Wang & Molnar 1994, Figure 4 |
//! | [`Cause::Leak`] | too light, and most of the lit taps' weight is on taps under an exact occluder that the map's first layer holds in front of the receiver, where the depth compared (second depth, midpoint, a dual depth held to its midpoint) lies behind the receiver | Wang & Molnar 1994 §3.4; Weiskopf & Ertl 2003 §3 |
//! | [`Cause::Penumbra`] | otherwise, a partial shade of one of Reeves' filters wider than a texel (a box of 2 or more, the jittered filter): its taps straddle a true edge, the filter's own soft edge | Reeves et al. 1987 §2 |
//! | [`Cause::Aliasing`] | otherwise: the taps straddle a true occluder's edge (a point or bilinear lookup), or the occluder falls between them (or no depth was compared: a shadow volume's edge) | — |
//!
//! Acne, detachment and leaks are the artifacts; aliasing and penumbra
//! are the map's resolution and the filter at work.

use glam::{DMat4, DVec3, DVec4};
use umbra_core::probe::{Event, Probe, Tap};
use umbra_core::shadow::{DepthTest, Filter, Shadow};
use umbra_core::{DepthFormat, DepthFormatKind};

use crate::truth::reference::{Reference, camera_ray};

/// Why a pixel's shade is wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cause {
    /// Too dark from the receiver's own surface (or one touching it).
    Acne,
    /// Too light because only the bias or offset moved the test past an
    /// occluder the map holds.
    Detachment,
    /// Too light because the depth compared lies behind the receiver
    /// under a first-layer occluder.
    Leak,
    /// The taps straddle a true edge, or miss the occluder: edge placement.
    Aliasing,
    /// A filter's own partial shade across a true edge.
    Penumbra,
}

impl Cause {
    /// Whether the class is an artifact (acne, detachment, leak) rather
    /// than the map's resolution or the filter at work.
    #[must_use]
    pub const fn is_artifact(self) -> bool {
        matches!(self, Self::Acne | Self::Detachment | Self::Leak)
    }
}

/// A probe that records the taps of the pixels a shading unit decides,
/// each pixel's apart (from the unit's `PixelShaded` event on). Wang &
/// Molnar's virtual samples decide a pixel in up to two lookups: when the
/// tangent plane is set up the taps of the lookup that decides start
/// afresh, and when it falls back the ordinary lookup's taps are put back.
#[derive(Clone, Debug, Default)]
pub struct Taps {
    taps: Vec<Tap>,
    /// Each shaded pixel's column and where its taps start.
    pixels: Vec<(u32, usize)>,
    ordinary: Vec<Tap>,
}

impl Taps {
    /// Forget every pixel's taps.
    pub(crate) fn clear(&mut self) {
        self.taps.clear();
        self.pixels.clear();
        self.ordinary.clear();
    }

    /// Every tap recorded since the last `Taps::clear` (a lookup made
    /// directly, outside a shading pass, is one pixel's).
    #[must_use]
    pub fn taps(&self) -> &[Tap] {
        &self.taps
    }

    /// The taps that decided the pixel of column `x` in the row shaded
    /// since the last [`Taps::clear`]; empty when it was not shaded.
    #[must_use]
    pub(crate) fn of_column(&self, x: u32) -> &[Tap] {
        // The pixels of a row are shaded left to right.
        let Ok(at) = self.pixels.binary_search_by_key(&x, |p| p.0) else { return &[] };
        let end = self.pixels.get(at + 1).map_or(self.taps.len(), |p| p.1);
        self.taps.get(self.pixels[at].1..end).unwrap_or_default()
    }

    /// Where the current pixel's taps start.
    fn start(&self) -> usize {
        self.pixels.last().map_or(0, |p| p.1)
    }
}

impl Probe for Taps {
    const TAPS: bool = true;

    fn event(&mut self, event: Event) {
        match event {
            Event::PixelShaded { x, .. } => self.pixels.push((x, self.taps.len())),
            Event::TangentSetup => {
                let start = self.start();
                self.ordinary.clear();
                self.ordinary.extend(self.taps.drain(start..));
            }
            Event::TangentFallback => {
                self.taps.truncate(self.start());
                self.taps.append(&mut self.ordinary);
            }
            _ => {}
        }
    }

    fn tap(&mut self, tap: Tap) {
        self.taps.push(tap);
    }
}

/// A receiver triangle's depth on the map: `z(u, v) = z0 + du·u + dv·v`
/// in [`PlaneZ`](umbra_core::depth::PlaneZ) bits, `u`, `v` in texels —
/// exact, since light-space depth `z/w` is affine on a plane's image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    z0: f64,
    du: f64,
    dv: f64,
    /// One step of the map's format at the receiver's depth, `PlaneZ` bits.
    step: f64,
}

impl Receiver {
    /// The plane of `triangle` (world space) on a `width × height` map
    /// seen through `light` (world to light clip), in format `F`'s units;
    /// `None` when a vertex lies behind the light or the triangle is
    /// edge-on to it.
    #[must_use]
    pub fn of<F: DepthFormat>(triangle: &[DVec3; 3], light: &DMat4, (width, height): (u32, u32)) -> Option<Self> {
        let unit = plane_unit::<F>();
        let [a, b, c] = triangle.map(|p| {
            let q = *light * DVec4::new(p.x, p.y, p.z, 1.0);
            (q.w > 0.0).then(|| {
                let (x, y, z) = (q.x / q.w, q.y / q.w, q.z / q.w);
                DVec3::new((x + 1.0) * f64::from(width) / 2.0, (1.0 - y) * f64::from(height) / 2.0, z * unit)
            })
        });
        let (a, b, c) = (a?, b?, c?);
        let (e1, e2) = (b - a, c - a);
        let det = e1.x * e2.y - e1.y * e2.x;
        if det.abs() < 1e-12 || !det.is_finite() {
            return None;
        }
        let du = (e1.z * e2.y - e2.z * e1.y) / det;
        let dv = (e2.z * e1.x - e1.z * e2.x) / det;
        let z0 = a.z - du * a.x - dv * a.y;
        let step = step::<F>(a.z);
        [z0, du, dv].iter().all(|v| v.is_finite()).then_some(Self { z0, du, dv, step })
    }

    /// A receiver known only by one depth (no plane could be set up):
    /// flat, its span one step of the format.
    #[must_use]
    pub fn flat<F: DepthFormat>(z: i64) -> Self {
        #[allow(clippy::cast_precision_loss, reason = "a depth in PlaneZ bits, below 2^57")]
        let z = z as f64;
        Self { z0: z, du: 0.0, dv: 0.0, step: step::<F>(z) }
    }

    /// The receiver's depth at the centre of texel `(x, y)`.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "texel coordinates")]
    pub fn at(&self, x: i64, y: i64) -> f64 {
        self.z0 + self.du * (x as f64 + 0.5) + self.dv * (y as f64 + 0.5)
    }

    /// The receiver's own depth span at a texel: its slope across one
    /// texel along both axes, plus one step of the format.
    #[must_use]
    pub fn span(&self) -> f64 {
        self.du.abs() + self.dv.abs() + self.step
    }
}

/// `PlaneZ` bits per unit of light-space depth in format `F`.
#[allow(clippy::cast_precision_loss, reason = "2^24 or less, times 2^32: exact")]
fn plane_unit<F: DepthFormat>() -> f64 {
    F::SCALE as f64 * umbra_core::budget::PLANE_ONE
}

/// One step of format `F` at depth `z` (`PlaneZ` bits): a texel's LSB for
/// the integer formats, the float's spacing for f32.
fn step<F: DepthFormat>(z: f64) -> f64 {
    match F::KIND {
        DepthFormatKind::F32 => (z.abs() * f64::from(f32::EPSILON)).max(1.0),
        _ => umbra_core::budget::PLANE_ONE,
    }
}

/// The exact light rays through the texel centres of a map: which surface,
/// if any, lies in front of a receiver along each.
pub(crate) struct Rays<'r> {
    reference: &'r Reference,
    inverse: DMat4,
    size: (u32, u32),
}

impl<'r> Rays<'r> {
    /// The rays of a `size` map seen through `light` (world to light clip).
    #[must_use]
    pub(crate) fn new(reference: &'r Reference, light: &DMat4, size: (u32, u32)) -> Self {
        Self { reference, inverse: light.inverse(), size }
    }

    /// The object whose surface the exact light ray through the centre of
    /// texel `(x, y)` meets before it reaches the plane of `receiver`
    /// (world space): the true occluder of that tap, if there is one.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "texel coordinates")]
    pub(crate) fn occluder(&self, x: i64, y: i64, receiver: &[DVec3; 3]) -> Option<u32> {
        let size = (f64::from(self.size.0), f64::from(self.size.1));
        let (near, far) = camera_ray(&self.inverse, (x as f64 + 0.5, y as f64 + 0.5), size);
        let normal = (receiver[1] - receiver[0]).cross(receiver[2] - receiver[0]);
        let dir = far - near;
        let t = normal.dot(receiver[0] - near) / normal.dot(dir);
        if !(t.is_finite() && t > 0.0) {
            return None;
        }
        self.reference.first_on(near, near + dir * t)
    }
}

/// What a wrong pixel's taps are judged with.
#[derive(Clone, Copy, Debug)]
pub struct Judge {
    /// The test the unit ran.
    pub test: DepthTest,
    /// The pixel's shade.
    pub shade: Shadow,
    /// Too dark (`true`) or too light than the reference.
    pub dark: bool,
    /// The filter softens edges on purpose (Reeves' box or jittered
    /// filters, wider than a texel): its partial shades are penumbra. A
    /// point or bilinear lookup reconstructs the map, and its partial
    /// shades across an edge are aliasing.
    pub soft: bool,
}

impl Judge {
    /// Whether `filter` is one of Reeves' filters that soften edges on
    /// purpose ([`Judge::soft`]).
    #[must_use]
    pub const fn softens(filter: Filter) -> bool {
        matches!(filter, Filter::Box { size: 2.. } | Filter::Jittered(_))
    }
}

impl Judge {
    /// The cause of the pixel's error from `taps`, the `receiver`'s plane
    /// on the map and `occluded` (whether the exact ray through a tap's
    /// texel meets a surface in front of the receiver; asked only of lit
    /// taps of a too-light pixel).
    #[must_use]
    pub fn cause(&self, taps: &[Tap], receiver: &Receiver, mut occluded: impl FnMut(&Tap) -> bool) -> Cause {
        let counted = || taps.iter().filter(|t| t.weight > 0);
        let partial = self.soft && self.shade > Shadow::ZERO && self.shade < Shadow::ONE && counted().count() > 1;
        let edge = if partial { Cause::Penumbra } else { Cause::Aliasing };
        if self.dark {
            #[allow(clippy::cast_precision_loss, reason = "depths in PlaneZ bits, below 2^57")]
            let own = |t: &Tap| t.reference.is_some_and(|c| c as f64 >= receiver.at(t.x, t.y) - receiver.span());
            let mut darkening = counted().filter(|t| t.shadowed).peekable();
            let any = darkening.peek().is_some();
            return if any && darkening.all(own) { Cause::Acne } else { edge };
        }
        // Too light: weigh the lit taps by what let the light through.
        let (mut detached, mut leaked, mut missed) = (0u128, 0u128, 0u128);
        for t in counted().filter(|t| !t.shadowed) {
            let w = u128::from(t.weight);
            match self.lit_tap(t, &mut occluded) {
                Some(Cause::Detachment) => detached += w,
                Some(Cause::Leak) => leaked += w,
                _ => missed += w,
            }
        }
        if detached > 0 && detached >= leaked && detached >= missed {
            Cause::Detachment
        } else if leaked > 0 && leaked >= missed {
            Cause::Leak
        } else {
            edge
        }
    }

    /// Why a lit tap of a too-light pixel is lit: [`Cause::Detachment`],
    /// [`Cause::Leak`], or `None` when it missed the occluder (no surface
    /// in front of the receiver on its exact ray, or a first layer that
    /// does not hold it).
    fn lit_tap(&self, t: &Tap, occluded: &mut impl FnMut(&Tap) -> bool) -> Option<Cause> {
        let c = t.reference?;
        if !occluded(t) {
            return None;
        }
        // Without the bias the tap would shadow: the bias moved it past.
        if t.receiver > c {
            return Some(Cause::Detachment);
        }
        let holds = t.first.is_none_or(|f| t.receiver > f);
        match self.test {
            DepthTest::First => None,
            // The dual depth's offset, where it binds, moved it past (its
            // half-thickness binding is the midpoint's leak).
            DepthTest::Dual { offset } => {
                let first = t.first?;
                holds.then_some(if c - first == offset.to_bits().max(0) { Cause::Detachment } else { Cause::Leak })
            }
            DepthTest::Second | DepthTest::Midpoint => holds.then_some(Cause::Leak),
        }
    }
}
