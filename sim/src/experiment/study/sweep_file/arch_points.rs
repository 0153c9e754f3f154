//! A sweep's architecture points: each listed architecture crossed with
//! every point of the `[[arch_axes]]`, each value parsed in its key's unit
//! and named after its base and values.

use super::{AxisValue, FileText, SweepError, SweepFile};
use crate::cost::arch::Arch;
use crate::experiment::study::ArchPoint;
use crate::input::limits::Limits;

impl SweepFile {
    /// The architectures, each crossed with every point of the parameter
    /// axes (named `<arch>-<key>-<value>…`), with each point's assignments.
    pub(super) fn archs(&self, t: &FileText, limits: &Limits) -> Result<(Vec<Arch>, Vec<ArchPoint>), SweepError> {
        let mut base = Vec::new();
        for (i, a) in t.archs.iter().enumerate() {
            let bundled = crate::cost::arch::BUNDLED.iter().any(|(n, _)| n == a);
            base.push(
                Arch::open(&self.relative(a, bundled), limits)
                    .map_err(|e| self.err(format!("archs[{i}]"), e.to_string()))?,
            );
        }
        // The points are counted before any is built: nine axes of ten
        // values would be 10⁹ of them.
        let mut count = base.len().max(1);
        for (i, axis) in t.arch_axes.iter().enumerate() {
            if axis.values.is_empty() {
                return Err(self.err(format!("arch_axes[{i}].values"), "the axis is empty"));
            }
            count = count.saturating_mul(axis.values.len());
            if count > crate::experiment::study::MAX_ARCHITECTURES {
                return Err(self.err(
                    format!("arch_axes[{i}]"),
                    format!(
                        "the architectures and the axes up to this one make more than {} points",
                        crate::experiment::study::MAX_ARCHITECTURES
                    ),
                ));
            }
        }
        // One axis per key, each value once as the value it means
        // (`1GB/s` and `1 GB/s` are one): a point is one assignment per key.
        let values: Vec<Vec<String>> =
            t.arch_axes.iter().map(|a| a.values.iter().map(AxisValue::text).collect()).collect();
        for (i, (axis, written)) in t.arch_axes.iter().zip(&values).enumerate() {
            if let Some(j) = t.arch_axes[..i].iter().position(|a| a.key == axis.key) {
                return Err(self.err(
                    format!("arch_axes[{i}].key"),
                    format!("`{}` is also arch_axes[{j}].key: one axis per key, every value on it", axis.key),
                ));
            }
            let parsed = written
                .iter()
                .enumerate()
                .map(|(k, v)| {
                    Arch::value_of(&axis.key, v).map_err(|e| {
                        self.err(format!("arch_axes[{i}].values[{k}]"), format!("{} = `{v}`: {e}", axis.key))
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            self.once(&format!("arch_axes[{i}].values"), &parsed, written)?;
        }
        let mut points: Vec<Vec<(usize, &str)>> = vec![Vec::new()];
        for (i, axis) in values.iter().enumerate() {
            points = points
                .iter()
                .flat_map(|p| axis.iter().map(move |v| [p.clone(), vec![(i, v.as_str())]].concat()))
                .collect();
        }
        let (mut archs, mut params) = (Vec::new(), Vec::new());
        for a in &base {
            for p in &points {
                let mut arch = a.clone();
                let mut assignments = Vec::new();
                for &(i, value) in p {
                    let key = &t.arch_axes[i].key;
                    arch.assign(key, value).map_err(|e| {
                        self.err(format!("arch_axes[{i}]"), format!("{key} = `{value}` on {}: {e}", a.name))
                    })?;
                    arch.name = Arch::name_with(&arch.name, key, value);
                    assignments.push((key.clone(), value.to_owned()));
                }
                arch.check().map_err(|(k, e)| self.err(format!("arch_axes ({k})"), e.to_string()))?;
                archs.push(arch);
                params.push(ArchPoint { base: a.name.clone(), assignments });
            }
        }
        Ok((archs, params))
    }
}
