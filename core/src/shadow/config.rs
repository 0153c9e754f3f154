//! What the shadow unit is asked to do: the depth test, the bias and the filter.

use core::fmt;

use super::MapCoord;
use crate::depth::PlaneZ;
use crate::spelling::closest;

/// Which reference depth a sample compares against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthTest {
    /// Nearest depth `z1`.
    First,
    /// Second-nearest depth `z2`: from the dual unit, or the single buffer
    /// of a front-face-culled pass ([`MapView::front_culled`](super::MapView::front_culled)).
    Second,
    /// Woo's midpoint `(z1 + z2) / 2`.
    Midpoint,
    /// Weiskopf & Ertl's dual depth `z1 + min((z2 − z1) / 2, offset)`.
    Dual {
        /// The largest distance above `z1`, in [`PlaneZ`] (format LSBs).
        offset: PlaneZ,
    },
}

impl DepthTest {
    /// Whether the test reads `z2`.
    #[must_use]
    pub const fn needs_z2(self) -> bool {
        !matches!(self, Self::First)
    }

    /// Whether the test reads `z1`.
    #[must_use]
    pub const fn needs_z1(self) -> bool {
        !matches!(self, Self::Second)
    }

    /// The reference depth from `z1` and `z2` ([`PlaneZ`] bits). Monotonic
    /// in both, so tile bounds bound it.
    #[inline]
    pub(super) fn reference(self, z1: i64, z2: i64) -> i64 {
        match self {
            Self::First => z1,
            Self::Second => z2,
            Self::Midpoint => (z1 >> 1) + (z2 >> 1) + (z1 & z2 & 1),
            Self::Dual { offset } => z1.saturating_add(((z2 - z1) >> 1).min(offset.to_bits().max(0))),
        }
    }
}

/// The depth bias, in [`PlaneZ`] (format LSBs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bias {
    /// The same for every sample.
    Constant(PlaneZ),
    /// Drawn uniformly per sample from `[lo, hi]` (Reeves' `Bias0`, `Bias1`).
    Range {
        /// `Bias0`.
        lo: PlaneZ,
        /// `Bias1`.
        hi: PlaneZ,
    },
}

impl Default for Bias {
    /// No bias: Wang & Molnar's default for second depth.
    fn default() -> Self {
        Self::ZERO
    }
}

impl Bias {
    /// No bias.
    pub const ZERO: Self = Self::Constant(PlaneZ::ZERO);

    /// The smallest and largest bias a sample can get.
    #[must_use]
    pub fn bounds(self) -> (i64, i64) {
        match self {
            Self::Constant(b) => (b.to_bits(), b.to_bits()),
            Self::Range { lo, hi } => (lo.to_bits(), hi.to_bits()),
        }
    }
}

/// Reeves' stochastic filter parameters (Figure 4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Jitter {
    /// `NumSamples`: samples per lookup (before the per-axis clamps).
    pub num_samples: u16,
    /// `ResFactor`: enlarges the footprint (softer shadows).
    pub res_factor: MapCoord,
    /// `MinSamples`: fewest samples along each axis.
    pub min_samples: u16,
    /// `MinSize`: smallest half-size of the sampled region, texels.
    pub min_size: MapCoord,
}

impl Jitter {
    /// The values Reeves et al. list in Figure 4.
    pub const REEVES: Self =
        Self { num_samples: 16, res_factor: MapCoord::lit("3"), min_samples: 1, min_size: MapCoord::ZERO };
}

/// How the binary comparisons of a lookup are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Filter {
    /// The texel under the point.
    Point,
    /// The four nearest texel centres, weighted by the fractional position.
    Bilinear,
    /// `size × size` texels centred on the point, equally weighted.
    Box {
        /// Side in texels, `1..=16`.
        size: u8,
    },
    /// Reeves' jittered stochastic sampling of the footprint.
    Jittered(Jitter),
}

impl Filter {
    /// The box sides the shadow unit takes.
    pub const BOX_SIDES: core::ops::RangeInclusive<u8> = 1..=16;
}

/// The one spelling of a filter, which [`Filter`]'s `FromStr` reads back:
/// `point`, `bilinear`, `box<N>` (N in `1..=16`), and Reeves' jittered
/// filter as `jitter<NumSamples>` followed by each parameter that differs
/// from Figure 4's (`,res-factor=<texels>`, `,min-samples=<n>`,
/// `,min-size=<texels>`): `jitter16` is [`Jitter::REEVES`], `jitter4` the
/// same with 4 samples.
///
/// ```
/// use umbra_core::shadow::{Filter, Jitter, MapCoord};
/// assert_eq!(Filter::Box { size: 5 }.to_string(), "box5");
/// assert_eq!("box5".parse(), Ok(Filter::Box { size: 5 }));
/// let soft = Filter::Jittered(Jitter { num_samples: 8, res_factor: MapCoord::lit("1.5"), ..Jitter::REEVES });
/// assert_eq!(soft.to_string(), "jitter8,res-factor=1.5");
/// assert_eq!("jitter8,res-factor=1.5".parse(), Ok(soft));
/// ```
impl fmt::Display for Filter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Point => f.write_str("point"),
            Self::Bilinear => f.write_str("bilinear"),
            Self::Box { size } => write!(f, "box{size}"),
            Self::Jittered(j) => {
                let r = Jitter::REEVES;
                write!(f, "jitter{}", j.num_samples)?;
                if j.res_factor != r.res_factor {
                    write!(f, ",res-factor={}", j.res_factor)?;
                }
                if j.min_samples != r.min_samples {
                    write!(f, ",min-samples={}", j.min_samples)?;
                }
                if j.min_size != r.min_size {
                    write!(f, ",min-size={}", j.min_size)?;
                }
                Ok(())
            }
        }
    }
}

/// Text that names no filter, with what is wrong with it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterNameError {
    /// Not `point`, `bilinear`, `box<N>` or `jitter<N>…`; with the
    /// filter's name it nearly spells, if any.
    Unknown {
        /// The name the text nearly spells.
        near: Option<&'static str>,
    },
    /// A box side outside `1..=16`.
    BoxSide,
    /// A sample count that is not a whole number from 1 to 65535.
    Samples(&'static str),
    /// A jitter parameter that is not `res-factor`, `min-samples` or
    /// `min-size`; with the one it nearly spells, if any.
    Parameter {
        /// The parameter the text nearly spells.
        near: Option<&'static str>,
    },
    /// A size in texels that is not a non-negative number below 32768.
    Texels(&'static str),
}

impl fmt::Display for FilterNameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let near = |n: &Option<&'static str>| n.map(|n| (" (did you mean ", n, "?)")).unwrap_or_default();
        match self {
            Self::Unknown { near: n } => {
                let (a, b, c) = near(n);
                write!(
                    f,
                    "not a filter{a}{b}{c}: expected point, bilinear, box<N> (N from 1 to 16) or jitter<N> with \
                     optional ,res-factor=<texels>,min-samples=<n>,min-size=<texels>"
                )
            }
            Self::BoxSide => f.write_str("a box filter's side must be 1 to 16 texels"),
            Self::Samples(p) => write!(f, "{p} must be a whole number from 1 to 65535"),
            Self::Parameter { near: n } => {
                let (a, b, c) = near(n);
                write!(f, "not a jitter parameter{a}{b}{c}: they are res-factor, min-samples and min-size")
            }
            Self::Texels(p) => write!(f, "{p} must be a non-negative number of texels below 32768"),
        }
    }
}

impl core::error::Error for FilterNameError {}

impl core::str::FromStr for Filter {
    type Err = FilterNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let samples =
            |p: &'static str, t: &str| t.parse::<u16>().ok().filter(|&n| n >= 1).ok_or(FilterNameError::Samples(p));
        let texels = |p: &'static str, t: &str| {
            t.parse::<MapCoord>().ok().filter(|v| *v >= MapCoord::ZERO).ok_or(FilterNameError::Texels(p))
        };
        // Case aside: the help writes a name at a sentence's start.
        let prefix = |p: &str| s.get(..p.len()).filter(|h| h.eq_ignore_ascii_case(p)).map(|_| &s[p.len()..]);
        if s.eq_ignore_ascii_case("point") {
            return Ok(Self::Point);
        }
        if s.eq_ignore_ascii_case("bilinear") {
            return Ok(Self::Bilinear);
        }
        if let Some(side) = prefix("box") {
            let size = side.parse::<u8>().map_err(|_| FilterNameError::BoxSide)?;
            return if Self::BOX_SIDES.contains(&size) {
                Ok(Self::Box { size })
            } else {
                Err(FilterNameError::BoxSide)
            };
        }
        let rest = prefix("jitter").ok_or_else(|| {
            // The name's letters against the filters' (`bilinaer`, `jiter8`).
            let letters = s.find(|c: char| !c.is_ascii_alphabetic()).map_or(s, |k| &s[..k]);
            FilterNameError::Unknown { near: closest(letters, ["point", "bilinear", "box", "jitter"]) }
        })?;
        let mut parts = rest.split(',');
        let mut j = Jitter { num_samples: samples("num-samples", parts.next().unwrap_or_default())?, ..Jitter::REEVES };
        for part in parts {
            match part.split_once('=') {
                Some(("res-factor", v)) => j.res_factor = texels("res-factor", v)?,
                Some(("min-samples", v)) => j.min_samples = samples("min-samples", v)?,
                Some(("min-size", v)) => j.min_size = texels("min-size", v)?,
                _ => {
                    let name = part.split_once('=').map_or(part, |(k, _)| k);
                    let near = closest(name, ["res-factor", "min-samples", "min-size"]);
                    return Err(FilterNameError::Parameter { near });
                }
            }
        }
        Ok(Self::Jittered(j))
    }
}

/// A validated shadow-unit configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShadowConfig {
    pub(super) test: DepthTest,
    pub(super) bias: Bias,
    pub(super) filter: Filter,
    pub(super) cull_lookups: bool,
}

/// A shadow configuration the unit cannot use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShadowConfigError {
    /// A box filter side outside `1..=16`.
    BoxSize {
        /// The side asked for.
        size: u8,
    },
    /// `NumSamples` outside `1..=256`, or `MinSamples` above it or zero.
    Samples {
        /// `NumSamples`.
        num_samples: u16,
        /// `MinSamples`.
        min_samples: u16,
    },
    /// A negative `ResFactor` or `MinSize`.
    Region,
    /// A bias range with `lo > hi`.
    BiasRange,
    /// A negative dual-depth offset.
    Offset,
}

impl fmt::Display for ShadowConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::BoxSize { size } => write!(f, "box filter size {size} is outside 1..=16"),
            Self::Samples { num_samples, min_samples } => {
                write!(f, "NumSamples {num_samples} must be in 1..=256 and MinSamples {min_samples} in 1..=NumSamples")
            }
            Self::Region => write!(f, "ResFactor and MinSize must not be negative"),
            Self::BiasRange => write!(f, "bias range has Bias0 > Bias1"),
            Self::Offset => write!(f, "dual-depth offset must not be negative"),
        }
    }
}

impl core::error::Error for ShadowConfigError {}

impl ShadowConfig {
    /// Validate a configuration. `cull_lookups` enables per-tile culling.
    ///
    /// # Errors
    /// See [`ShadowConfigError`].
    pub fn new(test: DepthTest, bias: Bias, filter: Filter, cull_lookups: bool) -> Result<Self, ShadowConfigError> {
        match filter {
            Filter::Box { size } if !Filter::BOX_SIDES.contains(&size) => {
                return Err(ShadowConfigError::BoxSize { size });
            }
            Filter::Jittered(j) => {
                if !(1..=256).contains(&j.num_samples) || j.min_samples == 0 || j.min_samples > j.num_samples {
                    return Err(ShadowConfigError::Samples { num_samples: j.num_samples, min_samples: j.min_samples });
                }
                if j.res_factor < 0 || j.min_size < 0 {
                    return Err(ShadowConfigError::Region);
                }
            }
            _ => {}
        }
        if let Bias::Range { lo, hi } = bias
            && lo > hi
        {
            return Err(ShadowConfigError::BiasRange);
        }
        if let DepthTest::Dual { offset } = test
            && offset < 0
        {
            return Err(ShadowConfigError::Offset);
        }
        Ok(Self { test, bias, filter, cull_lookups })
    }

    /// The depth test.
    #[must_use]
    pub const fn test(&self) -> DepthTest {
        self.test
    }

    /// The filter.
    #[must_use]
    pub const fn filter(&self) -> Filter {
        self.filter
    }

    /// The bias.
    #[must_use]
    pub const fn bias(&self) -> Bias {
        self.bias
    }

    /// Whether a lookup draws random numbers (the jittered filter's
    /// positions, or a bias range's per-sample bias): only then does its
    /// [`Lookup::seed`](super::Lookup::seed) matter.
    #[must_use]
    pub const fn draws_random(&self) -> bool {
        matches!(self.filter, Filter::Jittered(_)) || matches!(self.bias, Bias::Range { .. })
    }

    /// The same configuration with lookup culling on or off.
    #[must_use]
    pub const fn with_cull_lookups(self, cull_lookups: bool) -> Self {
        Self { cull_lookups, ..self }
    }
}
