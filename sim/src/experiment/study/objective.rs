//! What "least costly" means: the objective a plan or a study ranks
//! candidates (rows) by — cycles, energy, silicon area, the energy-delay product,
//! the energy-delay-area product, or a weighted sum of time, energy and
//! area — and the cost limits a pick must stay within (`--max-area`,
//! `--max-energy`), spelt alike on the command line and in Python.

use std::str::FromStr;

use serde::Serialize;

use crate::cost::arch::Unit;

/// A candidate's cost in the terms objectives and limits read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Costs {
    /// Frame cycles.
    pub cycles: f64,
    /// Frame time, seconds.
    pub seconds: f64,
    /// Frame energy, dynamic and static, joules.
    pub joules: f64,
    /// Silicon of the units it uses, square metres.
    pub square_metres: f64,
}

/// What a plan minimises and a study's summary ranks by.
///
/// ```
/// use umbra_sim::experiment::plan::Objective;
/// assert_eq!("edp".parse::<Objective>()?, Objective::EnergyDelay);
/// let w: Objective = "cycles=1,area=2".parse()?;
/// assert_eq!(w, Objective::Weighted { cycles: 1.0, energy: 0.0, area: 2.0 });
/// assert_eq!(w.to_string(), "cycles=1,energy=0,area=2");
/// assert!("speed".parse::<Objective>().is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Objective {
    /// Frame cycles on the architecture.
    #[default]
    Cycles,
    /// Frame energy, dynamic and static.
    Energy,
    /// Silicon area of the units the candidate uses.
    Area,
    /// Energy × time.
    EnergyDelay,
    /// Energy × time × area.
    EnergyDelayArea,
    /// A weighted sum of cycles, energy and area, each over the least of
    /// it among the candidates (so the weights are unitless).
    Weighted {
        /// The weight of cycles.
        cycles: f64,
        /// The weight of energy.
        energy: f64,
        /// The weight of area.
        area: f64,
    },
}

impl Objective {
    /// The objectives a study's summary names a best for.
    pub const NAMED: [Self; 5] = [Self::Cycles, Self::Energy, Self::Area, Self::EnergyDelay, Self::EnergyDelayArea];

    /// Its spelling in `--objective` (a weighted sum's as its weights).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Cycles => "cycles",
            Self::Energy => "energy",
            Self::Area => "area",
            Self::EnergyDelay => "edp",
            Self::EnergyDelayArea => "edap",
            Self::Weighted { .. } => "weighted",
        }
    }

    /// What it ranks by, in words.
    #[must_use]
    pub fn words(self) -> String {
        match self {
            Self::Cycles => "cycles".into(),
            Self::Energy => "energy".into(),
            Self::Area => "silicon area".into(),
            Self::EnergyDelay => "energy × time".into(),
            Self::EnergyDelayArea => "energy × time × area".into(),
            Self::Weighted { cycles, energy, area } => {
                format!("{cycles}·cycles + {energy}·energy + {area}·area, each over its least")
            }
        }
    }

    /// `c`'s score: lower is better. `least` is the least of each measure
    /// among the candidates, which a weighted sum divides by.
    #[must_use]
    pub fn score(self, c: &Costs, least: &Costs) -> f64 {
        let over = |x: f64, l: f64| if l > 0.0 { x / l } else { 0.0 };
        match self {
            Self::Cycles => c.cycles,
            Self::Energy => c.joules,
            Self::Area => c.square_metres,
            Self::EnergyDelay => c.joules * c.seconds,
            Self::EnergyDelayArea => c.joules * c.seconds * c.square_metres,
            Self::Weighted { cycles, energy, area } => {
                cycles * over(c.cycles, least.cycles)
                    + energy * over(c.joules, least.joules)
                    + area * over(c.square_metres, least.square_metres)
            }
        }
    }

    /// `c`'s score in its unit, for a report (`0.0123 mm²`, `4.1e-12 J·s`).
    #[must_use]
    pub fn text(self, c: &Costs, least: &Costs) -> String {
        let v = self.score(c, least);
        match self {
            Self::Cycles => format!("{v:.0} cycles"),
            Self::Energy => format!("{:.3} µJ", v * 1e6),
            Self::Area => format!("{:.4} mm²", v * 1e6),
            Self::EnergyDelay => format!("{v:.4e} J·s"),
            Self::EnergyDelayArea => format!("{:.4e} J·s·mm²", v * 1e6),
            Self::Weighted { .. } => format!("{v:.4}"),
        }
    }

    /// The least of each measure among `all`.
    #[must_use]
    pub fn least<'a>(all: impl IntoIterator<Item = &'a Costs>) -> Costs {
        all.into_iter().fold(
            Costs {
                cycles: f64::INFINITY,
                seconds: f64::INFINITY,
                joules: f64::INFINITY,
                square_metres: f64::INFINITY,
            },
            |l, c| Costs {
                cycles: l.cycles.min(c.cycles),
                seconds: l.seconds.min(c.seconds),
                joules: l.joules.min(c.joules),
                square_metres: l.square_metres.min(c.square_metres),
            },
        )
    }
}

impl FromStr for Objective {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let t = text.trim();
        if let Some(o) = Self::NAMED.into_iter().find(|o| o.name() == t) {
            return Ok(o);
        }
        if !t.contains('=') {
            return Err(format!(
                "objective `{text}`: one of cycles, energy, area, edp, edap, or weights such as `cycles=1,energy=1,area=0.5`"
            ));
        }
        let (mut cycles, mut energy, mut area) = (0.0, 0.0, 0.0);
        for part in t.split(',') {
            let (k, v) =
                part.split_once('=').ok_or_else(|| format!("objective `{text}`: `{part}` is not name=weight"))?;
            let w: f64 = v.trim().parse().map_err(|_| format!("objective `{text}`: `{v}` is not a weight"))?;
            if !(w.is_finite() && w >= 0.0) {
                return Err(format!("objective `{text}`: the weight {w} is not a non-negative number"));
            }
            match k.trim() {
                "cycles" => cycles = w,
                "energy" => energy = w,
                "area" => area = w,
                k => return Err(format!("objective `{text}`: `{k}` is not cycles, energy or area")),
            }
        }
        if cycles + energy + area <= 0.0 {
            return Err(format!("objective `{text}`: every weight is 0"));
        }
        Ok(Self::Weighted { cycles, energy, area })
    }
}

impl std::fmt::Display for Objective {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Weighted { cycles, energy, area } => write!(f, "cycles={cycles},energy={energy},area={area}"),
            o => f.write_str(o.name()),
        }
    }
}

/// The most a pick may cost: limits on its area and energy (none: no
/// limit).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct CostLimits {
    /// The most silicon, square metres.
    pub max_square_metres: Option<f64>,
    /// The most energy a frame, joules.
    pub max_joules: Option<f64>,
}

impl CostLimits {
    /// `--max-area` and `--max-energy` as written (`2mm2`, `150uJ`).
    ///
    /// ```
    /// use umbra_sim::experiment::study::objective::CostLimits;
    /// let l = CostLimits::parse(Some("2mm2"), Some("150uJ"))?;
    /// assert_eq!(l.max_square_metres, Some(2e-6));
    /// assert!(CostLimits::parse(Some("2 acres"), None).is_err());
    /// # Ok::<(), String>(())
    /// ```
    ///
    /// # Errors
    /// The flag and what it expects, for text that is not an area or an
    /// energy.
    pub fn parse(area: Option<&str>, energy: Option<&str>) -> Result<Self, String> {
        let read = |flag: &str, unit: Unit, t: Option<&str>| {
            t.map(|t| unit.parse(t).map_err(|e| format!("{flag} {t}: {e}"))).transpose()
        };
        Ok(Self {
            max_square_metres: read("--max-area", Unit::Area, area)?,
            max_joules: read("--max-energy", Unit::Joules, energy)?,
        })
    }

    /// Whether it limits anything.
    #[must_use]
    pub const fn any(&self) -> bool {
        self.max_square_metres.is_some() || self.max_joules.is_some()
    }

    /// The limits as a summary heads them (`area ≤ 2 mm², energy ≤ 150 µJ`).
    #[must_use]
    pub fn words(&self) -> String {
        let mut out = Vec::new();
        if let Some(m) = self.max_square_metres {
            out.push(format!("area ≤ {} mm²", m * 1e6));
        }
        if let Some(m) = self.max_joules {
            out.push(format!("energy ≤ {} µJ", m * 1e6));
        }
        out.join(", ")
    }

    /// The limits `c` exceeds, each as `area 2.1 mm² > 2 mm²`.
    #[must_use]
    pub fn exceeded(&self, c: &Costs) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(m) = self.max_square_metres.filter(|&m| c.square_metres > m) {
            out.push(format!("area {:.4} mm² > {} mm²", c.square_metres * 1e6, m * 1e6));
        }
        if let Some(m) = self.max_joules.filter(|&m| c.joules > m) {
            out.push(format!("energy {:.3} µJ > {} µJ", c.joules * 1e6, m * 1e6));
        }
        out
    }

    /// The worst ratio of a limited cost to its limit (at most 1 is within
    /// every limit).
    #[must_use]
    pub fn worst(&self, c: &Costs) -> f64 {
        let ratio = |x: f64, m: Option<f64>| m.map_or(0.0, |m| if m > 0.0 { x / m } else { f64::INFINITY });
        ratio(c.square_metres, self.max_square_metres).max(ratio(c.joules, self.max_joules))
    }
}
