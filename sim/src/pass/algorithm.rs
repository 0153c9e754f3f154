//! The shadow algorithms of the four papers, and the one place each is
//! mapped to the units it uses: the light pass's depth unit and culling,
//! the shadow unit's test and bias, and the map the camera pass reads.

use serde::{Deserialize, Serialize};
use umbra_core::shadow::{Bias, DepthTest};
use umbra_core::{CullMode, DepthFormat, DepthUnit};

/// A shadow algorithm of the four papers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Algorithm {
    /// Williams' first depth with a bias.
    First,
    /// First depth with Reeves et al.'s bias range: each sample's bias drawn
    /// uniformly from `[bias, hi]` (`Bias0`, `Bias1`; 1987 §3.2).
    BiasRange {
        /// `Bias1`, as a depth in `[0, 1]` (`Bias0` is the configuration's bias).
        hi: f64,
    },
    /// Wang & Molnar's second depth from the dual unit.
    Second,
    /// Second depth from front-face culling (solids culled, open surfaces not).
    SecondFrontCulled,
    /// Woo's midpoint of the dual unit.
    Midpoint,
    /// Weiskopf & Ertl's dual depth; solids back-face culled, open surfaces not.
    Dual {
        /// The largest distance above `z1`, as a depth in `[0, 1]`.
        offset: f64,
    },
    /// Sen, Cammarano & Hanrahan's silhouette map over a first-depth map
    /// (with the bias), decided by the skewed quadrants; no filter.
    Silhouette {
        /// Points packed to 4 bits per axis (one byte per texel) instead of
        /// 16 bits per axis.
        packed: bool,
    },
    /// Depth-fail stencil shadow volumes on the camera's raster: exact hard
    /// shadows, no light pass and no map.
    Volumes,
}

/// The one spelling of an algorithm: its [`Algorithm::name`].
impl std::fmt::Display for Algorithm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is no algorithm's.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{name}` is not an algorithm{} ({})",
    umbra_core::spelling::closest(.0, Algorithm::NAMES).map_or_else(String::new, |n| format!(": did you mean `{n}`?")),
    Algorithm::NAMES.join(", "),
    name = .0
)]
pub struct UnknownAlgorithm(pub String);

/// The paper an algorithm comes from, as the study groups them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Family {
    /// Williams' first depth, with a constant bias or Reeves' range.
    FirstDepth,
    /// Wang & Molnar's second depth.
    SecondDepth,
    /// Woo's midpoint and Weiskopf & Ertl's dual depth.
    MidpointDual,
    /// Sen, Cammarano & Hanrahan's silhouette map.
    Silhouette,
    /// Depth-fail stencil shadow volumes.
    Volumes,
}

umbra_core::spelled!(Family, "algorithm family", {
    FirstDepth => "first depth",
    SecondDepth => "second depth",
    MidpointDual => "midpoint and dual",
    Silhouette => "silhouette map",
    Volumes => "shadow volumes",
});

/// How the light pass culls one class of object.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cull {
    /// As the algorithm does it: solids as `Units::solids` says, open
    /// surfaces never (Weiskopf & Ertl §3.2).
    #[default]
    Algorithm,
    /// Nothing culled.
    None,
    /// Faces towards the light culled.
    Front,
    /// Faces away from the light culled.
    Back,
}

umbra_core::spelled!(Cull, "culling", { Algorithm => "algorithm", None => "none", Front => "front", Back => "back" });

/// The light pass's culling per object class: closed solids and open
/// surfaces (Weiskopf & Ertl §3.2 cull solids' back faces and nothing of an
/// open surface, which has no back; Wang & Molnar §3.4 cull solids' front
/// faces). Either class may be overridden, for the comparisons their
/// figures make.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Culling {
    /// Objects detected (or declared) closed.
    pub solids: Cull,
    /// Open surfaces.
    pub open: Cull,
}

impl Culling {
    /// Each class as the algorithm culls it.
    pub const ALGORITHM: Self = Self { solids: Cull::Algorithm, open: Cull::Algorithm };
    /// Nothing culled (Weiskopf & Ertl's Figure 5 (b)–(d) and 6).
    pub const OFF: Self = Self { solids: Cull::None, open: Cull::None };
}

/// The one spelling `umbra render --cull`, sweep files and rows use:
/// `algorithm` for the algorithm's own, else `solids=…,open=…`.
impl std::fmt::Display for Culling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if *self == Self::ALGORITHM {
            f.write_str("algorithm")
        } else {
            write!(f, "solids={},open={}", self.solids.name(), self.open.name())
        }
    }
}

/// A culling choice that does not parse, with the text and what was expected.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "culling `{text}`: {problem}; expected `algorithm` or `solids=X,open=Y` with X, Y one of algorithm, none, front, back"
)]
pub struct CullingError {
    /// The text given.
    pub text: String,
    /// What is wrong with it.
    pub problem: String,
}

impl std::str::FromStr for Culling {
    type Err = CullingError;

    /// `algorithm`, or `solids=X,open=Y` (either part may be left out, and
    /// is then the algorithm's).
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let err = |problem: String| CullingError { text: text.to_owned(), problem };
        let mut c = Self::ALGORITHM;
        if text == "algorithm" {
            return Ok(c);
        }
        for part in text.split(',') {
            let (class, choice) = part.split_once('=').ok_or_else(|| err(format!("`{part}` has no `=`")))?;
            let cull = Cull::ALL
                .into_iter()
                .find(|c| c.name() == choice)
                .ok_or_else(|| err(format!("`{choice}` is not a culling")))?;
            match class {
                "solids" => c.solids = cull,
                "open" => c.open = cull,
                _ => return Err(err(format!("`{class}` is not an object class (solids, open)"))),
            }
        }
        Ok(c)
    }
}

/// The map an algorithm's camera pass reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MapKind {
    /// A depth map (single, dual, or single front-face culled).
    Depth,
    /// Sen et al.'s silhouette map over a first-depth map.
    Silhouette {
        /// Points packed to one byte per texel.
        packed: bool,
    },
    /// None: shadow volumes on the camera's raster.
    Volumes,
}

/// What an algorithm asks of the hardware.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Units {
    /// The map the camera pass reads.
    pub map: MapKind,
    /// The light pass's depth unit.
    pub unit: DepthUnit,
    /// The light pass culls solids' front faces, so the single map holds
    /// the second depth (Wang & Molnar §3.4).
    pub front_culled: bool,
    /// How the light pass culls solids (open surfaces are never culled:
    /// Weiskopf & Ertl §3.2).
    pub solids: CullMode,
    /// The shadow unit's depth test.
    pub test: DepthTest,
    /// The shadow unit's bias.
    pub bias: Bias,
}

impl Units {
    /// Whether Wang & Molnar's virtual samples apply when asked for: only
    /// to the second-depth test.
    #[must_use]
    pub(crate) fn virtual_samples(&self, asked: bool) -> bool {
        asked && self.test == DepthTest::Second
    }

    /// How the light pass culls an object, solid or open, under `culling`.
    #[must_use]
    pub(crate) const fn cull(&self, solid: bool, culling: Culling) -> CullMode {
        match (if solid { culling.solids } else { culling.open }, solid) {
            (Cull::Algorithm, true) => self.solids,
            (Cull::Algorithm, false) | (Cull::None, _) => CullMode::None,
            (Cull::Front, _) => CullMode::Front,
            (Cull::Back, _) => CullMode::Back,
        }
    }
}

impl Algorithm {
    /// The units this algorithm uses in format `F`, with `bias` (a depth in
    /// `[0, 1]`; Reeves' `Bias0` for a bias range).
    #[must_use]
    pub(crate) fn units<F: DepthFormat>(self, bias: f64) -> Units {
        let constant = Bias::Constant(F::plane_z(bias));
        let units = |unit, test| Units {
            map: MapKind::Depth,
            unit,
            front_culled: false,
            solids: CullMode::None,
            test,
            bias: constant,
        };
        match self {
            Self::First => units(DepthUnit::Single, DepthTest::First),
            Self::BiasRange { hi } => Units {
                bias: Bias::Range { lo: F::plane_z(bias), hi: F::plane_z(hi) },
                ..units(DepthUnit::Single, DepthTest::First)
            },
            Self::Second => units(DepthUnit::Dual, DepthTest::Second),
            Self::SecondFrontCulled => {
                Units { front_culled: true, solids: CullMode::Front, ..units(DepthUnit::Single, DepthTest::Second) }
            }
            Self::Midpoint => units(DepthUnit::Dual, DepthTest::Midpoint),
            Self::Dual { offset } => Units {
                solids: CullMode::Back,
                ..units(DepthUnit::Dual, DepthTest::Dual { offset: F::plane_z(offset) })
            },
            Self::Silhouette { packed } => {
                Units { map: MapKind::Silhouette { packed }, ..units(DepthUnit::Single, DepthTest::First) }
            }
            Self::Volumes => Units { map: MapKind::Volumes, ..units(DepthUnit::Single, DepthTest::First) },
        }
    }

    /// The algorithm's one name, everywhere: `umbra render --algo`, sweep
    /// files and the study's rows.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::First => "first",
            Self::BiasRange { .. } => "bias-range",
            Self::Second => "second",
            Self::SecondFrontCulled => "second-ffc",
            Self::Midpoint => "midpoint",
            Self::Dual { .. } => "dual",
            Self::Silhouette { packed: false } => "silhouette",
            Self::Silhouette { packed: true } => "silhouette-packed",
            Self::Volumes => "volumes",
        }
    }

    /// The paper the algorithm comes from, as the study groups them.
    #[must_use]
    pub(crate) const fn family(self) -> Family {
        match self {
            Self::First | Self::BiasRange { .. } => Family::FirstDepth,
            Self::Second | Self::SecondFrontCulled => Family::SecondDepth,
            Self::Midpoint | Self::Dual { .. } => Family::MidpointDual,
            Self::Silhouette { .. } => Family::Silhouette,
            Self::Volumes => Family::Volumes,
        }
    }

    /// Every algorithm's name, in the order of the papers.
    pub(crate) const NAMES: [&'static str; 9] = {
        let every = Self::every(0.0, 0.0);
        let mut names = [""; 9];
        let mut k = 0;
        while k < names.len() {
            names[k] = every[k].name();
            k += 1;
        }
        names
    };

    /// Every algorithm, in the order of the papers, those with a parameter
    /// given `bias1` and `offset`.
    pub(crate) const fn every(bias1: f64, offset: f64) -> [Self; 9] {
        [
            Self::First,
            Self::BiasRange { hi: bias1 },
            Self::Second,
            Self::SecondFrontCulled,
            Self::Midpoint,
            Self::Dual { offset },
            Self::Silhouette { packed: false },
            Self::Silhouette { packed: true },
            Self::Volumes,
        ]
    }

    /// Reeves' `Bias1` when none is given (`umbra render --bias1`).
    pub(crate) const DEFAULT_BIAS1: f64 = 0.005;

    /// The dual-depth offset when none is given (`umbra render --offset`).
    pub(crate) const DEFAULT_OFFSET: f64 = 0.01;

    /// The algorithm named `name` ([`Algorithm::name`], case aside: the
    /// help writes a name at a sentence's start), with Reeves' `Bias1` for
    /// a bias range and the offset for dual depth (the others take
    /// neither). An unknown name's error suggests the name it was a slip of.
    ///
    /// ```
    /// use umbra_sim::pass::algorithm::Algorithm;
    /// assert_eq!(Algorithm::named("dual", 0.005, 0.01), Ok(Algorithm::Dual { offset: 0.01 }));
    /// assert_eq!(Algorithm::named("Second", 0.0, 0.0), Ok(Algorithm::Second));
    /// assert!(Algorithm::named("secnod", 0.0, 0.0).unwrap_err().to_string().contains("did you mean `second`?"));
    /// assert!(Algorithm::named("third", 0.0, 0.0).is_err());
    /// ```
    ///
    /// # Errors
    /// [`UnknownAlgorithm`] for any other name.
    pub fn named(name: &str, bias1: f64, offset: f64) -> Result<Self, UnknownAlgorithm> {
        Self::every(bias1, offset)
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(name))
            .ok_or_else(|| UnknownAlgorithm(name.to_owned()))
    }

    /// The algorithm as `umbra render` takes it: `--algo` and its own
    /// parameter.
    #[must_use]
    pub(crate) fn flags(self) -> String {
        match self {
            Self::BiasRange { hi } => format!("--algo bias-range --bias1 {hi}"),
            Self::Dual { offset } => format!("--algo dual --offset {offset}"),
            _ => format!("--algo {}", self.name()),
        }
    }

    /// Reeves' `Bias1`, if the algorithm draws its bias from a range.
    #[must_use]
    pub(crate) const fn bias_hi(self) -> Option<f64> {
        match self {
            Self::BiasRange { hi } => Some(hi),
            _ => None,
        }
    }

    /// The dual offset, if the algorithm has one.
    #[must_use]
    pub(crate) const fn offset(self) -> Option<f64> {
        match self {
            Self::Dual { offset } => Some(offset),
            _ => None,
        }
    }
}
