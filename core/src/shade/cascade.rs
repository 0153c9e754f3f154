//! The cascade selector of a camera pass that reads cascaded maps (Zhang
//! et al. 2006, parallel-split shadow maps §3; Microsoft's "Cascaded
//! Shadow Maps"): the camera's depth range is split into slices, each
//! lit through a map of its own, and each pixel reads the map of the
//! slice its depth lies in.
//!
//! The unit compares the pixel's depth-buffer value (the visibility
//! unit's, in the camera's [`D24`](crate::D24) format) with one split
//! register a boundary, as hardware does: no division, no view-space
//! depth. A pixel within a boundary's blend band (from the band
//! register up to the split) reads both maps and mixes the two
//! fractions by where it lies in the band, in the depth buffer's own
//! units, with an 8-bit weight. [`shade_cascaded`] is the shading unit
//! with the selector in front: pixel by pixel, each against the map its
//! pick names, the probe told each time the map changes.

use glam::Mat4;

use super::{Normals, PixelResult, ShadeInputs, ShadeSetup, Shaded, ShadowUnit, TriangleSource, setup_of, shade_pixel};
use crate::config::ConfigError;
use crate::depth::DepthFormat;
use crate::grid::TileRect;
use crate::light_pass::NO_TRIANGLE;
use crate::probe::{Event, Probe};
use crate::shadow::{Built, Shadow};

/// The most cascades a selector holds.
pub const MAX_CASCADES: usize = 8;

/// What the selector decides for a pixel: the cascade whose map it
/// reads, and, in a blend band, the weight (of 256) of the next
/// cascade's fraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pick {
    /// The cascade, `0` nearest the camera.
    pub cascade: u8,
    /// Within the band before the next cascade: the next cascade's weight
    /// out of 256 (`1..=255`); `None` outside every band.
    pub next_weight: Option<u16>,
}

/// The selector's registers: where each cascade after the first begins,
/// and where the band blending into it begins, as depth-buffer values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CascadeSelect {
    count: u8,
    /// `splits[i]`: the least depth read through cascade `i + 1`.
    splits: [u32; MAX_CASCADES - 1],
    /// `bands[i]`: the least depth whose pixel blends cascade `i` into
    /// `i + 1` (equal to `splits[i]` for no band).
    bands: [u32; MAX_CASCADES - 1],
}

impl CascadeSelect {
    /// One cascade: every pixel reads map 0.
    pub const ONE: Self = Self { count: 1, splits: [u32::MAX; MAX_CASCADES - 1], bands: [u32::MAX; MAX_CASCADES - 1] };

    /// A selector of `splits.len() + 1` cascades: `splits` the depths at
    /// which each cascade after the first begins, `bands` where each
    /// boundary's blend band begins (`bands[i] <= splits[i]`; equal for
    /// none).
    ///
    /// Two equal splits leave the cascade between them empty.
    ///
    /// # Errors
    /// [`ConfigError::Cascades`] for more than [`MAX_CASCADES`] cascades,
    /// `bands` of another length, splits that decrease, or a band that
    /// starts after its split or before the previous split.
    pub fn new(splits: &[u32], bands: &[u32]) -> Result<Self, ConfigError> {
        let n = splits.len();
        if n >= MAX_CASCADES || bands.len() != n {
            return Err(ConfigError::Cascades { splits: n, bands: bands.len() });
        }
        let mut s = Self::ONE;
        let mut previous = 0;
        for (i, (&split, &band)) in splits.iter().zip(bands).enumerate() {
            if split < previous || band > split || band < previous {
                return Err(ConfigError::Cascades { splits: n, bands: bands.len() });
            }
            s.splits[i] = split;
            s.bands[i] = band;
            previous = split;
        }
        s.count = u8::try_from(n + 1).unwrap_or(1);
        Ok(s)
    }

    /// How many cascades it selects among.
    #[must_use]
    pub const fn count(&self) -> u8 {
        self.count
    }

    /// The cascade a pixel of depth-buffer value `z` reads, and its
    /// blend weight.
    #[must_use]
    #[inline]
    pub fn pick(&self, z: u32) -> Pick {
        let last = usize::from(self.count) - 1;
        let cascade = self.splits.iter().take(last).take_while(|&&s| z >= s).count();
        let next_weight = match (self.splits.get(cascade), self.bands.get(cascade)) {
            (Some(&split), Some(&band)) if cascade < last && z >= band && band < split => {
                // z < split: the weight is below 256.
                let w = (u64::from(z - band) << 8) / u64::from(split - band);
                u16::try_from(w.max(1)).ok()
            }
            _ => None,
        };
        Pick { cascade: u8::try_from(cascade).unwrap_or(0), next_weight }
    }
}

/// The fraction of a pixel in a blend band: `near`'s (its own cascade's)
/// and `far`'s (the next's) mixed as `(near·(256 − w) + far·w) / 256`,
/// rounded to nearest.
#[must_use]
#[inline]
pub fn blend(near: Shadow, far: Shadow, next_weight: u16) -> Shadow {
    let w = u64::from(next_weight.min(256));
    let mixed = (u64::from(near.to_bits()) * (256 - w) + u64::from(far.to_bits()) * w + 128) >> 8;
    Shadow::from_bits(u32::try_from(mixed).unwrap_or(u32::MAX))
}

/// A cascaded light as the shading unit reads it: each cascade's inputs
/// (its light's configuration, its map and its shadow unit, nearest
/// first), the map each is bound as ([`Probe::map_bound`]: a render's
/// maps numbered across its lights and cascades), and the selector.
pub struct Cascaded<'a, F: DepthFormat, S, U> {
    /// Each cascade's shading inputs.
    pub each: &'a [ShadeInputs<'a, F, S, U>],
    /// Each cascade's map as the probe is told it.
    pub bound: &'a [u16],
    /// The split and band registers.
    pub select: &'a CascadeSelect,
}

/// One pixel shaded against cascade `c`: its setup from the cascade's
/// store, the shading unit's event, its result; `None` for a triangle the
/// scene does not have.
#[allow(clippy::too_many_arguments, reason = "the unit's inputs, its store, the pixel and the probe")]
fn shade_one<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, P: Probe>(
    inputs: &ShadeInputs<'_, F, S, U>,
    store: &mut [ShadeSetup],
    light_inverse_transpose: &Mat4,
    probe: &mut P,
    (px, py): (u32, u32),
    id: u32,
) -> Option<Shaded> {
    let interp = setup_of(inputs.cfg, inputs.map, inputs.scene, store, id)?;
    probe.event(Event::PixelShaded { x: px, y: py });
    Some(shade_pixel(inputs.cfg, inputs.map, inputs.unit, probe, light_inverse_transpose, (px, py), interp))
}

/// Shade every pixel of `rect` (as [`shade_rect`](super::shade_rect)
/// does) against the cascade the selector picks for its depth-buffer
/// value in `depth`: the probe told of each change of map as the pixels
/// come, a pixel in a blend band shaded by both cascades (two lookups,
/// two events) and its fractions mixed ([`blend`]). `out` receives each
/// result, and `own`, where given, each pixel as its own cascade shaded
/// it, unmixed. `setups` is shared out among the cascades, an equal part
/// each (at least one entry).
///
/// # Errors
/// [`ConfigError::Cascades`] when the inputs, the bound maps and the
/// selector count different cascades; as [`shade_rect`](super::shade_rect)
/// for the window and the buffers.
#[allow(clippy::too_many_lines, reason = "one loop over the pixels, its checks before it")]
pub fn shade_cascaded<F: DepthFormat, S: TriangleSource, U: ShadowUnit<F>, R: PixelResult, P: Probe>(
    cascaded: &Cascaded<'_, F, S, U>,
    rect: TileRect,
    (ids, depth): (&[u32], &[u32]),
    (out, mut own): (&mut [R], Option<&mut [Shaded]>),
    setups: &mut [ShadeSetup],
    probe: &mut P,
) -> Result<(), ConfigError> {
    let &Cascaded { each, bound, select } = cascaded;
    let n = each.len();
    if n == 0 || n != usize::from(select.count()) || bound.len() != n {
        return Err(ConfigError::Cascades { splits: n.saturating_sub(1), bands: bound.len().saturating_sub(1) });
    }
    let Some(first) = each.first() else { return Ok(()) };
    for inputs in each {
        if let Some(missing) = U::Built::missing(&inputs.cfg.shadow, inputs.cfg.normals == Normals::Smooth) {
            return Err(ConfigError::ShadowNotBuilt { missing });
        }
    }
    let TileRect { x0, y0, x1, y1 } = rect;
    let (width, height) = (first.cfg.width, first.cfg.height);
    if x0 > x1 || y0 > y1 || x1 > width || y1 > height {
        return Err(ConfigError::Window { x0, y0, width: x1.wrapping_sub(x0), height: y1.wrapping_sub(y0) });
    }
    let texels = ((x1 - x0) as usize).saturating_mul((y1 - y0) as usize);
    let own_len = own.as_ref().map_or(texels, |o| o.len());
    for (buffer, found) in [("ids", ids.len()), ("depth", depth.len()), ("out", out.len()), ("own", own_len)] {
        if found != texels {
            return Err(ConfigError::BufferLength { buffer, expected: texels, found });
        }
    }
    let across = (x1 - x0) as usize;
    if across == 0 {
        return Ok(());
    }
    let mut spare = [ShadeSetup::EMPTY; MAX_CASCADES];
    let setups = if setups.len() < n { &mut spare[..n] } else { setups };
    setups.fill(ShadeSetup::EMPTY);
    let per = setups.len() / n;
    let mut lit = [Mat4::IDENTITY; MAX_CASCADES];
    for (l, inputs) in lit.iter_mut().zip(each) {
        *l = inputs.cfg.light.inverse().transpose();
    }
    // The map the unit reads, told to the probe when it changes.
    let mut reading: Option<usize> = None;
    for (k, ((&id, &z), o)) in ids.iter().zip(depth).zip(out.iter_mut()).enumerate() {
        #[allow(clippy::cast_possible_truncation, reason = "within the rectangle's sides")]
        let (px, py) = (x0 + (k % across) as u32, y0 + (k / across) as u32);
        let pick = select.pick(z);
        let mut shade = |c: usize, probe: &mut P| {
            let (inputs, store, light) = (each.get(c)?, setups.get_mut(c * per..(c + 1) * per)?, lit.get(c)?);
            if reading != Some(c) {
                probe.map_bound(bound.get(c).copied().unwrap_or(u16::MAX));
                reading = Some(c);
            }
            shade_one(inputs, store, light, probe, (px, py), id)
        };
        let c = usize::from(pick.cascade);
        let mine = if id == NO_TRIANGLE { None } else { shade(c, probe) };
        let mixed = match (mine, pick.next_weight) {
            (Some(near), Some(w)) => {
                let far = shade(c + 1, probe).map_or(near.shadow, |f| f.shadow);
                Some(Shaded { shadow: blend(near.shadow, far, w), ..near })
            }
            (shaded, _) => shaded,
        };
        *o = mixed.map_or(R::BACKGROUND, R::keep);
        if let Some(slot) = own.as_deref_mut().and_then(|o| o.get_mut(k)) {
            *slot = mine.unwrap_or(Shaded::BACKGROUND);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Worked by hand: splits at 100 and 200, a band from 150 to 200.
    #[test]
    fn picks_by_the_split_registers() {
        let s = CascadeSelect::new(&[100, 200], &[100, 150]).expect("valid");
        assert_eq!(s.pick(0), Pick { cascade: 0, next_weight: None });
        assert_eq!(s.pick(99), Pick { cascade: 0, next_weight: None });
        assert_eq!(s.pick(100), Pick { cascade: 1, next_weight: None });
        assert_eq!(s.pick(149), Pick { cascade: 1, next_weight: None });
        // (175 − 150)·256 / 50 = 128.
        assert_eq!(s.pick(175), Pick { cascade: 1, next_weight: Some(128) });
        assert_eq!(s.pick(150), Pick { cascade: 1, next_weight: Some(1) });
        assert_eq!(s.pick(199), Pick { cascade: 1, next_weight: Some(250) });
        assert_eq!(s.pick(200), Pick { cascade: 2, next_weight: None });
        assert_eq!(s.pick(u32::MAX), Pick { cascade: 2, next_weight: None });
        assert_eq!(CascadeSelect::ONE.pick(u32::MAX), Pick { cascade: 0, next_weight: None });
    }

    #[test]
    fn refuses_registers_out_of_order() {
        assert!(CascadeSelect::new(&[200, 100], &[200, 100]).is_err());
        assert!(CascadeSelect::new(&[100], &[101]).is_err());
        assert!(CascadeSelect::new(&[100, 200], &[100, 99]).is_err());
        // Equal splits: the cascade between is empty.
        let s = CascadeSelect::new(&[100, 100], &[100, 100]).expect("valid");
        assert_eq!(s.pick(100).cascade, 2);
        assert!(CascadeSelect::new(&[1, 2, 3, 4, 5, 6, 7, 8], &[1, 2, 3, 4, 5, 6, 7, 8]).is_err());
        assert!(CascadeSelect::new(&[1, 2, 3, 4, 5, 6, 7], &[1, 2, 3, 4, 5, 6, 7]).is_ok());
    }

    #[test]
    fn blends_to_the_nearest_step() {
        let (a, b) = (Shadow::ZERO, Shadow::ONE);
        assert_eq!(blend(a, b, 128), Shadow::from_num(0.5));
        assert_eq!(blend(b, a, 64), Shadow::from_num(0.75));
        assert_eq!(blend(b, b, 200), Shadow::ONE);
    }
}
