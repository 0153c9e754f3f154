//! Error budgets: the measures a budget can bound (a class of the
//! metrics' wrong pixels, percent of the evaluated pixels, each judged by
//! its cause) and their one spelling, which the planner, the study, sweep
//! files, the command line and Python read alike.

use std::str::FromStr;

use serde::Serialize;

use super::RowMetrics;

/// What a budget bounds: a class of the metrics' wrong pixels
/// ([`crate::truth::metrics`]), percent of the evaluated pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    /// Acne, detachment, leaks and clipped occluders together.
    Artifacts,
    /// Every pixel the ½ verdict gets wrong, aliasing included.
    Misclassified,
    /// Too dark from the receiver's own surface.
    Acne,
    /// Too light because only the bias moved the test past an occluder.
    Detachment,
    /// Too light because the depth compared lies behind the receiver.
    Leaks,
    /// Too light because what shadows it lies outside the light's frustum.
    Clipped,
    /// Wrong because the taps straddle a true edge or miss the occluder.
    Aliasing,
    /// A filter's own partial shade across a true edge.
    Penumbra,
    /// Shadowed by the ½ verdict, lit in truth.
    FalseShadow,
    /// Lit by the ½ verdict, shadowed in truth.
    FalseLight,
}

impl Measure {
    /// How many measures there are.
    pub const COUNT: usize = 10;

    /// Every measure, in the order reports list them.
    pub const ALL: [Self; Self::COUNT] = [
        Self::Artifacts,
        Self::Misclassified,
        Self::Acne,
        Self::Detachment,
        Self::Leaks,
        Self::Clipped,
        Self::Aliasing,
        Self::Penumbra,
        Self::FalseShadow,
        Self::FalseLight,
    ];

    /// Its one spelling, in `--budget` and in Python.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Artifacts => "artifacts",
            Self::Misclassified => "misclassified",
            Self::Acne => "acne",
            Self::Detachment => "detachment",
            Self::Leaks => "leaks",
            Self::Clipped => "clipped",
            Self::Aliasing => "aliasing",
            Self::Penumbra => "penumbra",
            Self::FalseShadow => "false-shadow",
            Self::FalseLight => "false-light",
        }
    }

    /// Its value in a row's metrics: percent of the evaluated pixels.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "pixel counts far below 2^53")]
    pub fn percent(self, m: &RowMetrics) -> f64 {
        let of = |px: u64| if m.evaluated_px == 0 { 0.0 } else { 100.0 * px as f64 / m.evaluated_px as f64 };
        match self {
            Self::Artifacts => m.artifact_percent,
            Self::Misclassified => m.misclassified_percent,
            Self::Acne => of(m.acne_px),
            Self::Detachment => of(m.detachment_px),
            Self::Leaks => of(m.leaks_px),
            Self::Clipped => of(m.clipped_px),
            Self::Aliasing => of(m.aliasing_px),
            Self::Penumbra => of(m.penumbra_px),
            Self::FalseShadow => of(m.false_shadow_px),
            Self::FalseLight => of(m.false_light_px),
        }
    }
}

/// An error budget: a measure and the most of it allowed, percent of the
/// evaluated pixels. Spelt `acne=0.01%` (the `%` optional), or a bare
/// percentage for artifacts (`0.1%`), alike in `umbra plan --budget` and
/// Python's `umbra.plan`.
///
/// ```
/// use umbra_sim::experiment::study::budget::{Budget, Measure};
/// let b: Budget = "misclassified=0.1%".parse()?;
/// assert_eq!((b.measure, b.percent), (Measure::Misclassified, 0.1));
/// assert_eq!("0.01".parse::<Budget>()?.measure, Measure::Artifacts);
/// assert!("glare=1%".parse::<Budget>().is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Budget {
    /// What it bounds.
    pub measure: Measure,
    /// The most allowed, percent.
    pub percent: f64,
}

impl FromStr for Budget {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let (measure, value) = match text.split_once('=') {
            Some((m, v)) => {
                let m = m.trim();
                let measure = Measure::ALL.into_iter().find(|x| x.name() == m).ok_or_else(|| {
                    let names: Vec<&str> = Measure::ALL.iter().map(|x| x.name()).collect();
                    format!("budget `{text}`: `{m}` is not a measure (one of {})", names.join(", "))
                })?;
                (measure, v)
            }
            None => (Measure::Artifacts, text),
        };
        let v = value.trim();
        let v = v.strip_suffix('%').unwrap_or(v).trim();
        let percent: f64 = v.parse().map_err(|_| format!("budget `{text}`: `{value}` is not a percentage"))?;
        if !(0.0..=100.0).contains(&percent) {
            return Err(format!("budget `{text}`: `{value}` is not a percentage in 0…100"));
        }
        Ok(Self { measure, percent })
    }
}

impl Budget {
    /// Artifacts within `percent`: what a bare number means.
    #[must_use]
    pub const fn artifacts(percent: f64) -> Self {
        Self { measure: Measure::Artifacts, percent }
    }

    /// As a table heads it: `1 %` for artifacts, `acne 0.01 %` for another
    /// measure.
    #[must_use]
    pub fn short(&self) -> String {
        match self.measure {
            Measure::Artifacts => format!("{} %", self.percent),
            m => format!("{} {} %", m.name(), self.percent),
        }
    }

    /// Whether `m`'s measure is within it.
    #[must_use]
    pub fn met_by(&self, m: &RowMetrics) -> bool {
        self.measure.percent(m) <= self.percent
    }
}

/// Budgets as a study's manifest and sweep files write them: a number for
/// artifacts (as every earlier file wrote them), `MEASURE=PERCENT` text for
/// another measure; each read back either way.
pub(crate) mod written {
    use super::Budget;
    use serde::{Deserialize, Deserializer, Serializer};

    /// One budget as written: a number or text.
    #[derive(Deserialize)]
    #[serde(untagged)]
    pub(crate) enum Written {
        /// Artifacts, percent.
        Number(f64),
        /// `MEASURE=PERCENT`.
        Text(String),
    }

    impl Written {
        /// The budget it spells.
        pub(crate) fn budget(&self) -> Result<Budget, String> {
            match self {
                Self::Number(p) => Ok(Budget::artifacts(*p)),
                Self::Text(t) => t.parse(),
            }
        }
    }

    pub(crate) fn serialize<S: Serializer>(budgets: &[Budget], s: S) -> Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        #[serde(untagged)]
        enum Out {
            Number(f64),
            Text(String),
        }
        s.collect_seq(budgets.iter().map(|b| match b.measure {
            super::Measure::Artifacts => Out::Number(b.percent),
            _ => Out::Text(b.to_string()),
        }))
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Budget>, D::Error> {
        let written = Vec::<Written>::deserialize(d)?;
        written.iter().map(|w| w.budget().map_err(serde::de::Error::custom)).collect()
    }
}

impl std::fmt::Display for Budget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}={}%", self.measure.name(), self.percent)
    }
}
