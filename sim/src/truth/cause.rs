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

use std::collections::HashMap;
use std::sync::Mutex;

use glam::{DMat4, DVec3, DVec4};
use umbra_core::probe::{Event, Probe, Tap};
use umbra_core::shadow::{DepthTest, Filter, Shadow};
use umbra_core::{DepthFormat, DepthFormatKind};

use crate::truth::reference::{Reference, camera_ray};
use crate::world::scene::LightSource;

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
    /// Too light because what shadows the pixel lies where the map never
    /// saw it: outside the light's frustum (nearer than its near plane,
    /// past its far plane, beside it), or the pixel itself outside the map.
    Clipped,
}

impl Cause {
    /// Whether the class is an artifact (acne, detachment, leak, an
    /// occluder the map never saw) rather than the map's resolution or the filter at work.
    #[must_use]
    pub const fn is_artifact(self) -> bool {
        matches!(self, Self::Acne | Self::Detachment | Self::Leak | Self::Clipped)
    }
}

/// A wrong pixel's cause, and whether its receiver's plane fell back to a
/// flat one ([`Receiver::flat`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Judged {
    /// Why it is wrong.
    pub cause: Cause,
    /// Its receiver was judged without its plane.
    pub fallback: bool,
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
    /// A flat fallback ([`Receiver::flat`]), not its triangle's plane.
    flat: bool,
}

impl Receiver {
    /// The plane of `triangle` (world space) on a `width × height` map
    /// seen through `light` (world to light clip), in format `F`'s units:
    /// taken from the triangle's part beyond the light's near plane
    /// (clip-space `z ≥ 0`), where depth is defined — a triangle with a
    /// vertex behind the light keeps its plane. `None` when no part of it
    /// lies beyond the near plane or it is edge-on to the light.
    #[must_use]
    pub fn of<F: DepthFormat>(triangle: &[DVec3; 3], light: &DMat4, (width, height): (u32, u32)) -> Option<Self> {
        let unit = plane_unit::<F>();
        let clip = triangle.map(|p| *light * DVec4::new(p.x, p.y, p.z, 1.0));
        // Sutherland–Hodgman against the near plane: at most four corners.
        let mut part = [DVec3::ZERO; 4];
        let mut n = 0;
        for (i, &a) in clip.iter().enumerate() {
            let b = clip[(i + 1) % 3];
            let mut keep = |q: DVec4| {
                if q.w > 0.0 && n < part.len() {
                    let (x, y, z) = (q.x / q.w, q.y / q.w, q.z / q.w);
                    part[n] =
                        DVec3::new((x + 1.0) * f64::from(width) / 2.0, (1.0 - y) * f64::from(height) / 2.0, z * unit);
                    n += 1;
                }
            };
            if a.z >= 0.0 {
                keep(a);
            }
            if (a.z >= 0.0) != (b.z >= 0.0) {
                keep(a + (b - a) * (a.z / (a.z - b.z)));
            }
        }
        // Depth is affine on the plane's image: any three corners give the
        // plane; the fan triangle of the largest area gives it best.
        let det = |i: usize| {
            let (e1, e2) = (part[i] - part[0], part[i + 1] - part[0]);
            e1.x * e2.y - e1.y * e2.x
        };
        let k = (1..n.saturating_sub(1)).max_by(|&i, &j| det(i).abs().total_cmp(&det(j).abs()))?;
        let (a, e1, e2, det) = (part[0], part[k] - part[0], part[k + 1] - part[0], det(k));
        if det.abs() < 1e-12 || !det.is_finite() {
            return None;
        }
        let du = (e1.z * e2.y - e2.z * e1.y) / det;
        let dv = (e2.z * e1.x - e1.z * e2.x) / det;
        let z0 = a.z - du * a.x - dv * a.y;
        let step = step::<F>(a.z);
        [z0, du, dv].iter().all(|v| v.is_finite()).then_some(Self { z0, du, dv, step, flat: false })
    }

    /// A receiver known only by one depth (no plane could be set up: the
    /// triangle is edge-on to the light, or wholly nearer than its near
    /// plane): flat, its span one step of the format. Its taps are judged
    /// by that span alone ([`Receiver::fallback`]).
    #[must_use]
    pub fn flat<F: DepthFormat>(z: i64) -> Self {
        #[allow(clippy::cast_precision_loss, reason = "a depth in PlaneZ bits, below 2^57")]
        let z = z as f64;
        Self { z0: z, du: 0.0, dv: 0.0, step: step::<F>(z), flat: true }
    }

    /// Whether the receiver is a flat fallback ([`Receiver::flat`]), not
    /// its triangle's plane.
    #[must_use]
    pub const fn fallback(&self) -> bool {
        self.flat
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
    memo: Option<&'r OccluderMemo>,
}

/// The occluders [`Rays::occluder`] found for one image and light, kept
/// for the renders that ask again: a study's configurations with maps of
/// one side judge the same texels' rays against the same receivers. Keyed
/// by the map's side, the texel and the receiver's triangle; at most
/// [`OccluderMemo::MAX`] entries, the first found.
#[derive(Debug, Default)]
pub(crate) struct OccluderMemo(Mutex<HashMap<MemoKey, Option<u32>>>);

/// An [`OccluderMemo`]'s key: the map's size, the texel, the receiver's
/// triangle.
type MemoKey = ((u32, u32), i64, i64, u32);

impl OccluderMemo {
    /// The most entries a memo keeps.
    pub(crate) const MAX: usize = 1 << 19;
    /// Bytes a memo holds at most: each entry's key and value, and the
    /// table's room around them.
    pub(crate) const BYTES: u64 = 2 * 48 * Self::MAX as u64;

    /// The entry of `key`, or `find`'s answer, kept while there is room.
    fn get_or(&self, key: MemoKey, find: impl FnOnce() -> Option<u32>) -> Option<u32> {
        if let Some(found) = self.0.lock().ok().and_then(|m| m.get(&key).copied()) {
            return found;
        }
        let found = find();
        if let Ok(mut m) = self.0.lock()
            && m.len() < Self::MAX
        {
            m.insert(key, found);
        }
        found
    }
}

impl<'r> Rays<'r> {
    /// The rays of a `size` map seen through `light` (world to light
    /// clip), their occluders kept in `memo` when one is given (it must be
    /// of this light and reference).
    #[must_use]
    pub(crate) fn new(
        reference: &'r Reference,
        light: &DMat4,
        size: (u32, u32),
        memo: Option<&'r OccluderMemo>,
    ) -> Self {
        Self { reference, inverse: light.inverse(), size, memo }
    }

    /// The object whose surface the exact light ray through the centre of
    /// texel `(x, y)` meets inside the light's frustum (past its near
    /// plane, short of its far plane) before it reaches the plane of
    /// `receiver` (world space; triangle `id` of the reference): the true
    /// occluder of that tap the map could hold, if there is one. `None`
    /// too for a texel outside the map.
    #[must_use]
    pub(crate) fn occluder(&self, x: i64, y: i64, (id, receiver): (u32, &[DVec3; 3])) -> Option<u32> {
        let find = || {
            let inside = (0..i64::from(self.size.0)).contains(&x) && (0..i64::from(self.size.1)).contains(&y);
            let (near, dir, t, normal) = self.to_plane(x, y, receiver).filter(|_| inside)?;
            self.reference.first_in_front((near, near + dir * t.min(1.0)), (near + dir * t, normal))
        };
        match self.memo {
            Some(memo) => memo.get_or((self.size, x, y, id), find),
            None => find(),
        }
    }

    /// Whether the exact ray from the light through the centre of texel
    /// `(x, y)` meets a surface before the plane of `receiver` anywhere
    /// (nearer than the near plane, past the far plane or beside the
    /// frustum included): with no [`Rays::occluder`], a surface the map
    /// never saw.
    #[must_use]
    pub(crate) fn unseen(&self, x: i64, y: i64, receiver: &[DVec3; 3], light: &LightSource) -> bool {
        self.to_plane(x, y, receiver).is_some_and(|(near, dir, t, normal)| {
            let on = near + dir * t;
            self.reference.first_in_front((self.reference.light_from(on, light), on), (on, normal)).is_some()
        })
    }

    /// The ray through the centre of texel `(x, y)`: its point on the near
    /// plane, its direction to the far plane's point, where (in those
    /// units) it meets the plane of `receiver`, and the plane's normal;
    /// `None` along the plane or when the plane lies behind the near plane.
    #[allow(clippy::cast_precision_loss, reason = "texel coordinates")]
    fn to_plane(&self, x: i64, y: i64, receiver: &[DVec3; 3]) -> Option<(DVec3, DVec3, f64, DVec3)> {
        let size = (f64::from(self.size.0), f64::from(self.size.1));
        let (near, far) = camera_ray(&self.inverse, (x as f64 + 0.5, y as f64 + 0.5), size);
        let normal = (receiver[1] - receiver[0]).cross(receiver[2] - receiver[0]);
        let dir = far - near;
        let t = normal.dot(receiver[0] - near) / normal.dot(dir);
        (t.is_finite() && t > 0.0).then_some((near, dir, t, normal))
    }
}

/// What the exact light ray through a tap's texel centre meets before it
/// reaches the receiver's plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sight {
    /// Nothing: the receiver's plane is the first surface on it.
    Clear,
    /// A surface inside the light's frustum, which the map could hold (for
    /// a lit tap of a too-light pixel: the object that hides the pixel's
    /// own centre, or any when its centre is lit).
    Occluded,
    /// Another object than the one hiding the pixel's own centre: an edge
    /// lies between the pixel and the tap.
    Elsewhere,
    /// Only surfaces outside the light's frustum (nearer than its near
    /// plane, past its far plane, beside it): none the map could hold.
    Unseen,
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
    /// on the map and `sight` (what the exact ray through a tap's texel
    /// meets before the receiver's plane; asked of the darkening taps of a
    /// too-dark pixel and the lit taps of a too-light one).
    #[must_use]
    pub fn cause(&self, taps: &[Tap], receiver: &Receiver, mut sight: impl FnMut(&Tap) -> Sight) -> Cause {
        let counted = || taps.iter().filter(|t| t.weight > 0);
        let partial = self.soft && self.shade > Shadow::ZERO && self.shade < Shadow::ONE && counted().count() > 1;
        let edge = if partial { Cause::Penumbra } else { Cause::Aliasing };
        if self.dark {
            // The receiver's own darkening: the depth compared lies within
            // the receiver's span there, and (when its plane is known) no
            // surface truly lies in front of it on the tap's exact ray —
            // the stored depth is in front only through sampling and
            // precision. A surface in front, touching or not, is a true
            // occluder: its edge's placement.
            #[allow(clippy::cast_precision_loss, reason = "depths in PlaneZ bits, below 2^57")]
            let within = |t: &Tap| t.reference.is_some_and(|c| c as f64 >= receiver.at(t.x, t.y) - receiver.span());
            let mut darkening = counted().filter(|t| t.shadowed).peekable();
            let any = darkening.peek().is_some();
            let own = darkening
                .all(|t| within(t) && (receiver.fallback() || !matches!(sight(t), Sight::Occluded | Sight::Elsewhere)));
            return if any && own { Cause::Acne } else { edge };
        }
        // Too light: weigh the lit taps by what let the light through.
        let (mut detached, mut leaked, mut unseen, mut missed) = (0u128, 0u128, 0u128, 0u128);
        for t in counted().filter(|t| !t.shadowed) {
            let w = u128::from(t.weight);
            match self.lit_tap(t, &mut sight) {
                Some(Cause::Detachment) => detached += w,
                Some(Cause::Leak) => leaked += w,
                Some(Cause::Clipped) => unseen += w,
                _ => missed += w,
            }
        }
        if detached > 0 && detached >= leaked.max(unseen).max(missed) {
            Cause::Detachment
        } else if leaked > 0 && leaked >= unseen.max(missed) {
            Cause::Leak
        } else if missed > 0 && missed > unseen {
            edge
        } else {
            // No lit tap (the lookup read nothing: the pixel lies outside
            // the map), or the light came through where the map never saw
            // the occluder: no true edge among the taps.
            Cause::Clipped
        }
    }

    /// Why a lit tap of a too-light pixel is lit: [`Cause::Detachment`],
    /// [`Cause::Leak`], [`Cause::Clipped`] (its exact ray meets surfaces
    /// only where the map never saw), or `None` when it missed the
    /// occluder (no surface in front of the receiver on its exact ray,
    /// another occluder than the pixel's own, or a first layer that does
    /// not hold it).
    fn lit_tap(&self, t: &Tap, sight: &mut impl FnMut(&Tap) -> Sight) -> Option<Cause> {
        match sight(t) {
            Sight::Unseen => return Some(Cause::Clipped),
            Sight::Occluded => {}
            Sight::Clear | Sight::Elsewhere => return None,
        }
        let c = t.reference?;
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
