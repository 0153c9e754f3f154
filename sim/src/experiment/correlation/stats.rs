//! The statistics simulators are judged by (Accel-Sim's correlator): over
//! points of predicted against measured values, the mean absolute error,
//! Pearson's r, the normalised RMS error, and counts within 10 % and 25 %,
//! over and under.

use serde::Serialize;

/// The statistics of a set of `(predicted, measured)` points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Stats {
    /// Points.
    pub points: usize,
    /// Mean of |predicted / measured − 1|, percent.
    pub mean_absolute_error_percent: f64,
    /// Pearson's correlation of predicted with measured; `None` for fewer
    /// than two points, points of different units, or no spread.
    pub pearson_r: Option<f64>,
    /// RMS of predicted − measured over the mean measured value, percent;
    /// `None` for points of different units.
    pub nrmse_percent: Option<f64>,
    /// Points within 10 % of the measurement.
    pub within_10_percent: usize,
    /// Points within 25 %.
    pub within_25_percent: usize,
    /// Points predicted above the measurement.
    pub over: usize,
    /// Points predicted below it.
    pub under: usize,
}

impl Stats {
    /// The statistics of `points` (`(predicted, measured)`, measured
    /// positive); `one_unit` when every point is in the same unit, so that
    /// r and NRMSE mean something.
    #[must_use]
    #[allow(clippy::cast_precision_loss, reason = "a handful of points")]
    pub(crate) fn of(points: &[(f64, f64)], one_unit: bool) -> Self {
        let n = points.len();
        if n == 0 {
            return Self::default();
        }
        let errors: Vec<f64> = points.iter().map(|&(p, m)| p / m - 1.0).collect();
        let count = |f: &dyn Fn(f64) -> bool| errors.iter().filter(|&&e| f(e)).count();
        let k = n as f64;
        let mean_m = points.iter().map(|p| p.1).sum::<f64>() / k;
        let mean_p = points.iter().map(|p| p.0).sum::<f64>() / k;
        let (mut sxy, mut sxx, mut syy, mut sq) = (0.0, 0.0, 0.0, 0.0);
        for &(p, m) in points {
            sxy += (p - mean_p) * (m - mean_m);
            sxx += (p - mean_p).powi(2);
            syy += (m - mean_m).powi(2);
            sq += (p - m).powi(2);
        }
        let r = (one_unit && n >= 2 && sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt());
        Self {
            points: n,
            mean_absolute_error_percent: 100.0 * errors.iter().map(|e| e.abs()).sum::<f64>() / k,
            pearson_r: r,
            nrmse_percent: one_unit.then(|| 100.0 * (sq / k).sqrt() / mean_m),
            // A rounding margin, so that a point exactly on the edge counts.
            within_10_percent: count(&|e| e.abs() <= 0.10 + 1e-12),
            within_25_percent: count(&|e| e.abs() <= 0.25 + 1e-12),
            over: count(&|e| e > 0.0),
            under: count(&|e| e < 0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Stats;

    #[test]
    fn statistics_as_worked_by_hand() {
        // Errors +10 %, −20 %, +50 %.
        let s = Stats::of(&[(110.0, 100.0), (80.0, 100.0), (30.0, 20.0)], true);
        assert_eq!(s.points, 3);
        assert!((s.mean_absolute_error_percent - 80.0 / 3.0).abs() < 1e-9);
        // Means 73.33 both; Σdpdm = 3466.67, Σdp² = 3266.67, Σdm² = 4266.67.
        let (sxy, sxx, syy) = (10_400.0 / 3.0, 9_800.0 / 3.0, 12_800.0 / 3.0);
        assert!((s.pearson_r.expect("one unit") - sxy / f64::sqrt(sxx * syy)).abs() < 1e-9);
        assert!((s.pearson_r.expect("r") - 0.928_571_4).abs() < 1e-6);
        // √((10² + 20² + 10²)/3) / 73.33 = 19.28 %.
        assert!((s.nrmse_percent.expect("one unit") - 19.284_730).abs() < 1e-5);
        assert_eq!((s.within_10_percent, s.within_25_percent, s.over, s.under), (1, 2, 2, 1));
        // Points of different units: no r, no NRMSE.
        let mixed = Stats::of(&[(110.0, 100.0), (80.0, 100.0)], false);
        assert_eq!((mixed.pearson_r, mixed.nrmse_percent), (None, None));
        assert_eq!(Stats::of(&[], true).points, 0);
    }
}
