//! A candidate as the planner measured it: its configuration, its cost
//! (cycles, bytes, energy, silicon) and every error measure, and what it
//! misses of the budgets and cost limits.

use serde::Serialize;
use umbra_core::DepthFormatKind;
use umbra_core::shadow::Filter;

use super::{Budget, CostLimits, Costs, Measure};

/// One candidate as the planner measured it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Candidate {
    /// The configuration in words (`dual offset 0.005, d16, 256², point`).
    pub label: String,
    /// Its algorithm, as `--algo` spells it.
    pub algorithm: String,
    /// Depth format.
    #[serde(with = "crate::base::text")]
    pub format: DepthFormatKind,
    /// Map side, texels.
    pub map_size: u32,
    /// Filter.
    #[serde(with = "crate::base::text")]
    pub filter: Filter,
    /// Frame cycles on the architecture.
    pub cycles: u64,
    /// Frame time on the architecture, seconds.
    pub seconds: f64,
    /// DRAM bytes of the frame.
    pub bytes: u64,
    /// Energy of the frame, dynamic and static, joules.
    pub joules: f64,
    /// Silicon of the units it uses, square metres.
    pub square_metres: f64,
    /// Every measure, percent of the evaluated pixels, in [`Measure::ALL`]
    /// order.
    #[serde(serialize_with = "by_measure")]
    pub percent: [f64; Measure::COUNT],
    /// RMS area error.
    pub rms_error: f64,
    /// The `umbra render` command that renders it.
    pub command: String,
}

/// Per-measure figures as a map from the measure's name.
fn by_measure<S: serde::Serializer>(v: &[f64; Measure::COUNT], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(Measure::ALL.iter().map(|m| m.name()).zip(v))
}

impl Candidate {
    /// One measure of it, percent.
    #[must_use]
    pub fn measure(&self, m: Measure) -> f64 {
        self.percent[m as usize]
    }

    /// What it measured: cycles, bytes and every measure, exactly (two
    /// candidates that render alike measure alike).
    pub(super) fn outcome(&self) -> (u64, u64, [u64; Measure::COUNT]) {
        (self.cycles, self.bytes, self.percent.map(f64::to_bits))
    }

    /// Its cost as objectives read it.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "cycle counts far below 2^53")]
    pub const fn costs(&self) -> Costs {
        Costs {
            cycles: self.cycles as f64,
            seconds: self.seconds,
            joules: self.joules,
            square_metres: self.square_metres,
        }
    }

    /// The budgets it misses, each as `acne 0.031% > 0.01%`, and the cost
    /// limits it exceeds.
    pub(super) fn misses(&self, budgets: &[Budget], limits: &CostLimits) -> Vec<String> {
        let mut out: Vec<String> = budgets
            .iter()
            .filter(|b| self.measure(b.measure) > b.percent)
            .map(|b| format!("{} {:.3}% > {}%", b.measure.name(), self.measure(b.measure), b.percent))
            .collect();
        out.extend(limits.exceeded(&self.costs()));
        out
    }

    /// The worst ratio of a budgeted measure to its budget, or of a
    /// limited cost to its limit: at most 1 meets every budget and limit.
    pub(super) fn worst(&self, budgets: &[Budget], limits: &CostLimits) -> f64 {
        let measures = budgets
            .iter()
            .map(|b| {
                let v = self.measure(b.measure);
                if v <= b.percent {
                    0.0
                } else if b.percent > 0.0 {
                    v / b.percent
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max);
        measures.max(limits.worst(&self.costs()))
    }
}

/// A candidate the pick beat, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunnerUp {
    /// The candidate.
    pub candidate: Candidate,
    /// Whether it ranks before the pick by the objective (else after it,
    /// or level with more DRAM bytes).
    pub cheaper: bool,
    /// Why it lost: the budgets it missed, or how much dearer it is.
    pub lost: String,
}
