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
    pub fn of(points: &[(f64, f64)], one_unit: bool) -> Self {
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
