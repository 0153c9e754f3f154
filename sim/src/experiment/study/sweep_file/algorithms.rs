//! A sweep file's algorithm entry and the variants it makes: every
//! combination of its lists (bias, offset, virtual samples, culling,
//! cascades), each value checked as `umbra render` reads it.

use serde::Deserialize;

use super::{SweepError, SweepFile};
use crate::experiment::study::Variant;
use crate::render::{Algorithm, Culling, RenderConfig};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AlgorithmText {
    pub(super) algo: String,
    #[serde(default)]
    pub(super) bias: Option<Vec<f64>>,
    #[serde(default)]
    pub(super) bias1: Option<f64>,
    #[serde(default)]
    pub(super) offset: Option<Vec<f64>>,
    #[serde(default)]
    pub(super) virtual_samples: Option<Vec<bool>>,
    #[serde(default)]
    pub(super) cull: Option<Vec<String>>,
    #[serde(default)]
    pub(super) cascades: Option<Vec<String>>,
}

impl SweepFile {
    /// The variants of one algorithm entry: every combination of its lists.
    pub(super) fn variants(&self, key: &str, a: &AlgorithmText) -> Result<Vec<Variant>, SweepError> {
        let one = |v: &Option<Vec<f64>>, default: f64| v.clone().unwrap_or_else(|| vec![default]);
        let biases = one(&a.bias, 0.0);
        for (k, &b) in biases.iter().chain(a.bias1.iter()).enumerate() {
            RenderConfig::depth("bias", b).map_err(|e| self.err(format!("{key}.bias"), format!("value {k}: {e}")))?;
        }
        // A list of spelled values, each read as its one spelling; the
        // default's value when the entry gives none.
        let spelled = |what: &str, list: &Option<Vec<String>>, default: &str| -> Vec<(String, String)> {
            let texts = list.as_deref().map_or_else(|| vec![default.to_owned()], <[String]>::to_vec);
            texts.into_iter().map(|t| (t, format!("{key}.{what}"))).collect()
        };
        let culls = spelled("cull", &a.cull, "algorithm")
            .into_iter()
            .map(|(t, k)| t.parse::<Culling>().map_err(|e| self.err(k, e.to_string())))
            .collect::<Result<Vec<_>, _>>()?;
        let cascades = spelled("cascades", &a.cascades, crate::world::cascade::SCENE)
            .into_iter()
            .map(|(t, k)| crate::world::cascade::read_choice(&t).map_err(|e| self.err(k, e.to_string())))
            .collect::<Result<Vec<_>, _>>()?;
        let needs = |what: &str| self.err(format!("{key}.{what}"), format!("`{}` needs `{what}`", a.algo));
        if a.algo == "bias-range" && a.bias1.is_none() {
            return Err(needs("bias1"));
        }
        let named = |offset| {
            Algorithm::named(&a.algo, a.bias1.unwrap_or_default(), offset)
                .map_err(|e| self.err(format!("{key}.algo"), e.to_string()))
        };
        // Only dual depth has an offset axis: any other is one algorithm.
        let algorithms = if a.algo == "dual" {
            let offsets = a.offset.as_deref().ok_or_else(|| needs("offset"))?;
            offsets
                .iter()
                .map(|&o| {
                    RenderConfig::depth("offset", o).map_err(|e| self.err(format!("{key}.offset"), e.to_string()))?;
                    named(o)
                })
                .collect::<Result<Vec<_>, _>>()?
        } else {
            vec![named(0.0)?]
        };
        let mut out = Vec::new();
        for &algorithm in &algorithms {
            for &bias in &biases {
                for &vs in a.virtual_samples.as_deref().unwrap_or(&[true]) {
                    for &culling in &culls {
                        for &cascades in &cascades {
                            out.push(Variant { algorithm, bias, virtual_samples: vs, culling, cascades });
                        }
                    }
                }
            }
        }
        Ok(out)
    }
}
