//! Cascaded shadow maps for a directional light: the camera's depth range
//! split into slices, each lit through a map of its own fitted to what
//! the slice can show (Zhang, Sun, Xu & Lau 2006, "Parallel-split shadow
//! maps for large-scale virtual environments", §3; Microsoft's technical
//! article "Cascaded Shadow Maps"; Lauritzen, Salvi & Lefohn 2011,
//! "Sample distribution shadow maps", for fitting to the visible samples).
//!
//! This module is what a scene or a user asks for: how many cascades,
//! where the slices split ([`Cascades::distances`]), each map's side, how
//! each is fitted and the blend band, in one spelling. The passes above
//! fit each cascade's light to its slice: an ordinary orthographic
//! light, whose map is drawn and tested as any other.

use core::fmt;
use core::str::FromStr;

/// The most cascades a light takes (the core's selector's registers).
pub const MAX_CASCADES: usize = umbra_core::shade::cascade::MAX_CASCADES;

/// The default weight of the logarithmic split in the practical scheme:
/// halfway between logarithmic and uniform (Zhang et al. §3.2).
pub const DEFAULT_LAMBDA: f32 = 0.5;

/// Where the camera's depth range is split.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Split {
    /// Zhang et al.'s practical scheme: each split the mix `λ·log + (1 − λ)·uniform`
    /// of the logarithmic and the uniform split's (λ in `[0, 1]`).
    Practical(f32),
    /// Given view distances from the camera, one per boundary, increasing,
    /// between the camera's near and far planes.
    Given([f32; MAX_CASCADES - 1]),
}

/// How each cascade's light is fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fit {
    /// To the whole slice of the camera's view between its two splits.
    Slice,
    /// To the visible samples of the slice, the camera's depth range first
    /// narrowed to the visible samples' (sample distribution shadow maps).
    Samples,
}

/// A directional light's cascades: how many, where they split, each map's
/// side, how each is fitted, and the blend band at each boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascades {
    count: u8,
    /// Where the depth range splits.
    pub split: Split,
    /// Each cascade's map side (`0`: the render's map side).
    sides: [u32; MAX_CASCADES],
    /// How each cascade's light is fitted.
    pub fit: Fit,
    /// The blend band at the far end of each cascade but the last, as a
    /// fraction of the cascade's depth range (`0`: none): its pixels read
    /// both maps.
    pub blend: f32,
}

/// A cascade spelling no light takes.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "cascades `{text}`: {problem} (spelled `N[,lambda=L][,splits=D1/D2/…][,sides=S|S1/S2/…][,fit=slice|samples][,blend=B]`, N from 1 to 8)"
)]
pub struct CascadesError {
    /// The text given.
    pub text: String,
    /// What is wrong with it.
    pub problem: String,
}

impl Cascades {
    /// One map: the light as it is.
    pub const ONE: Self = Self {
        count: 1,
        split: Split::Practical(DEFAULT_LAMBDA),
        sides: [0; MAX_CASCADES],
        fit: Fit::Slice,
        blend: 0.0,
    };

    /// `count` cascades split by the practical scheme at the default λ,
    /// each the render's map side, fitted to its slice, without blending.
    ///
    /// # Errors
    /// [`CascadesError`] for a count outside `1..=8`.
    pub fn practical(count: usize) -> Result<Self, CascadesError> {
        format!("{count}").parse()
    }

    /// How many cascades.
    #[must_use]
    pub const fn count(&self) -> usize {
        self.count as usize
    }

    /// Whether there is more than one.
    #[must_use]
    pub const fn cascaded(&self) -> bool {
        self.count > 1
    }

    /// Cascade `c`'s map side, for a render whose map side is `map_size`.
    #[must_use]
    pub fn side(&self, c: usize, map_size: u32) -> u32 {
        match self.sides.get(c) {
            Some(&s) if s > 0 => s,
            _ => map_size,
        }
    }

    /// These cascades with every map `side` texels on a side.
    #[must_use]
    pub const fn with_side(mut self, side: u32) -> Self {
        self.sides = [side; MAX_CASCADES];
        self
    }

    /// The view distances that bound the slices, from `near` to `far`:
    /// `count + 1` of them, `near` first and `far` last. The practical
    /// scheme's split `i` of `N` is `λ·n·(f/n)^(i/N) + (1 − λ)·(n + (f − n)·i/N)`.
    #[must_use]
    pub fn distances(&self, near: f32, far: f32) -> Vec<f32> {
        let n = self.count();
        let (near64, far64) = (f64::from(near), f64::from(far));
        let mut d = Vec::with_capacity(n + 1);
        d.push(near);
        for i in 1..n {
            #[allow(clippy::cast_precision_loss, reason = "at most 8 cascades")]
            let t = i as f64 / n as f64;
            #[allow(clippy::cast_possible_truncation, reason = "a distance between two f32 planes")]
            d.push(match self.split {
                Split::Practical(lambda) => {
                    let lambda = f64::from(lambda);
                    let log = near64 * (far64 / near64).powf(t);
                    let uniform = near64 + (far64 - near64) * t;
                    (lambda * log + (1.0 - lambda) * uniform) as f32
                }
                Split::Given(at) => at[i - 1],
            });
        }
        d.push(far);
        d
    }

    /// Given splits that do not lie strictly between `near` and `far` in
    /// increasing order: the first such, for the error.
    #[must_use]
    pub fn misplaced_split(&self, near: f32, far: f32) -> Option<f32> {
        let Split::Given(at) = self.split else { return None };
        let mut previous = near;
        for &d in at.iter().take(self.count() - 1) {
            if d <= previous || d >= far {
                return Some(d);
            }
            previous = d;
        }
        None
    }
}

/// How a render parameter or a sweep spells "each light's own
/// cascades", as the scene gives them.
pub const SCENE: &str = "scene";

/// A choice of cascades as the render parameter spells it: [`SCENE`] for
/// each light's own (`None`), or the cascades' spelling.
#[must_use]
pub fn choice_text(choice: Option<Cascades>) -> String {
    choice.map_or_else(|| SCENE.to_owned(), |c| c.to_string())
}

/// A choice of cascades read back from [`choice_text`]'s spelling.
///
/// # Errors
/// [`CascadesError`] for text that is neither [`SCENE`] nor cascades.
pub fn read_choice(text: &str) -> Result<Option<Cascades>, CascadesError> {
    if text.trim() == SCENE { Ok(None) } else { text.parse().map(Some) }
}

impl Default for Cascades {
    fn default() -> Self {
        Self::ONE
    }
}

/// A list written `a/b/c`.
fn list<T: fmt::Display>(items: &[T]) -> String {
    items.iter().map(ToString::to_string).collect::<Vec<_>>().join("/")
}

impl fmt::Display for Cascades {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.count();
        write!(f, "{n}")?;
        match self.split {
            Split::Practical(l) if l.to_bits() == DEFAULT_LAMBDA.to_bits() => {}
            Split::Practical(l) => write!(f, ",lambda={l}")?,
            Split::Given(at) => write!(f, ",splits={}", list(&at[..n - 1]))?,
        }
        let sides = &self.sides[..n];
        if sides.iter().any(|&s| s != 0) {
            if sides.iter().all(|&s| s == sides[0]) {
                write!(f, ",sides={}", sides[0])?;
            } else {
                write!(f, ",sides={}", list(sides))?;
            }
        }
        if self.fit == Fit::Samples {
            write!(f, ",fit=samples")?;
        }
        if self.blend > 0.0 {
            write!(f, ",blend={}", self.blend)?;
        }
        Ok(())
    }
}

impl FromStr for Cascades {
    type Err = CascadesError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let fail = |problem: String| CascadesError { text: text.to_owned(), problem };
        let mut parts = text.trim().split(',');
        let count = parts.next().unwrap_or_default().trim();
        let n: usize = match count.parse() {
            Ok(n) if (1..=MAX_CASCADES).contains(&n) => n,
            _ => return Err(fail(format!("`{count}` is not a number of cascades from 1 to {MAX_CASCADES}"))),
        };
        let mut c = Self { count: u8::try_from(n).unwrap_or(1), ..Self::ONE };
        let number = |key: &str, v: &str, lo: f32, hi: f32| match v.trim().parse::<f32>() {
            Ok(x) if x.is_finite() && (lo..=hi).contains(&x) => Ok(x),
            _ => Err(fail(format!("{key} `{v}` is not a number in [{lo}, {hi}]"))),
        };
        for part in parts {
            let (key, value) = part.split_once('=').ok_or_else(|| fail(format!("`{part}` is not key=value")))?;
            match key.trim() {
                "lambda" => c.split = Split::Practical(number("lambda", value, 0.0, 1.0)?),
                "splits" => {
                    let at: Vec<f32> = value
                        .split('/')
                        .map(|v| number("a split", v, f32::MIN_POSITIVE, 1e9))
                        .collect::<Result<_, _>>()?;
                    if at.len() != n - 1 {
                        return Err(fail(format!("{} splits given for {n} cascades, which need {}", at.len(), n - 1)));
                    }
                    let mut given = [0.0; MAX_CASCADES - 1];
                    given[..at.len()].copy_from_slice(&at);
                    if at.windows(2).any(|w| w[1] <= w[0]) {
                        return Err(fail("the splits do not increase".to_owned()));
                    }
                    c.split = Split::Given(given);
                }
                "sides" => {
                    let sides: Vec<u32> = value
                        .split('/')
                        .map(|v| match v.trim().parse::<u32>() {
                            Ok(s) if s >= 1 => Ok(s),
                            _ => Err(fail(format!("a side `{v}` is not a whole number from 1"))),
                        })
                        .collect::<Result<_, _>>()?;
                    match sides.as_slice() {
                        [one] => c.sides = [*one; MAX_CASCADES],
                        all if all.len() == n => c.sides[..n].copy_from_slice(all),
                        all => {
                            return Err(fail(format!("{} sides given for {n} cascades: give one, or {n}", all.len())));
                        }
                    }
                }
                "fit" => {
                    c.fit = match value.trim() {
                        "slice" => Fit::Slice,
                        "samples" => Fit::Samples,
                        v => return Err(fail(format!("fit `{v}` is neither `slice` nor `samples`"))),
                    }
                }
                "blend" => c.blend = number("blend", value, 0.0, 0.5)?,
                k => return Err(fail(format!("no key `{k}` (lambda, splits, sides, fit, blend)"))),
            }
        }
        Ok(c)
    }
}

impl serde::Serialize for Cascades {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spells_and_reads_back() {
        for text in ["1", "4", "4,lambda=1", "3,splits=5/20", "4,sides=1024", "2,sides=2048/512,fit=samples,blend=0.1"]
        {
            let c: Cascades = text.parse().expect(text);
            assert_eq!(c.to_string(), text);
        }
        for bad in ["0", "9", "4,splits=5/20", "3,splits=20/5", "2,sides=1/2/3", "2,fit=box", "2,blend=0.7", "2,x=1"] {
            assert!(bad.parse::<Cascades>().is_err(), "{bad}");
        }
    }

    /// Zhang et al.'s two limits, worked by hand for n = 1, f = 100, N = 2:
    /// logarithmic 10, uniform 50.5, the practical mix at λ = ½ 30.25.
    #[test]
    fn splits_by_the_practical_scheme() {
        let at = |l: &str| Cascades::from_str(&format!("2,lambda={l}")).expect("valid").distances(1.0, 100.0);
        assert_eq!(at("1"), [1.0, 10.0, 100.0]);
        assert_eq!(at("0"), [1.0, 50.5, 100.0]);
        assert_eq!(at("0.5"), [1.0, 30.25, 100.0]);
    }
}
