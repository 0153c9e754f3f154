//! Which keys a machine's units read. Most keys are read by every machine;
//! the ones below are read only when other keys make the unit that reads
//! them exist — an evaluator rasterizer, a bit-serial depth unit, a second
//! light pass, a resolve of on-chip depth, a cache of some size, a buffer
//! off chip for the depth cache to hold. This table is the one place that
//! knows it: `arch check` reports from it, and a test changes every key it
//! calls unread on every bundled machine and finds the cost unchanged.

use super::keys::{PARAMS, Value};
use super::machine::Arch;

/// A key of `arch` that no unit of it reads, and why, if it is not read.
type Rule = fn(&Arch) -> Option<&'static str>;

/// Whether any buffer the depth cache holds is off chip.
const fn depth_cache_used(a: &Arch) -> bool {
    !(a.on_chip.light_depth && a.on_chip.camera_depth && a.on_chip.stencil)
}

const ALL_ON_CHIP: &str = "every buffer the depth cache would hold (light depth, camera depth, stencil) is on chip";
const NO_DEPTH_CACHE: &str = "depth_cache.size is 0: there is no depth cache";
const NO_SECOND_PASS: &str = "depth.second_depth_pass is false: there is no second light pass";

fn depth_cache_geometry(a: &Arch) -> Option<&'static str> {
    if !depth_cache_used(a) {
        Some(ALL_ON_CHIP)
    } else if a.depth_cache.size == 0 {
        Some(NO_DEPTH_CACHE)
    } else {
        None
    }
}

fn map_cache_geometry(a: &Arch) -> Option<&'static str> {
    (a.map_cache.size == 0).then_some("map_cache.size is 0: there is no map cache")
}

/// The keys read only on some machines, each with its rule.
const READ_WHEN: &[(&str, Rule)] = &[
    ("raster.cycles_per_tile", |a| {
        (a.raster.fragments_per_clock > 0.0)
            .then_some("raster.fragments_per_clock is set, so the rasterizer is not an evaluator")
    }),
    ("depth.cycles_per_bit", |a| {
        (a.depth.fragments_per_clock > 0.0)
            .then_some("depth.fragments_per_clock is set, so the depth unit is not bit-serial")
    }),
    ("depth.peel_cycles", |a| (!a.depth.second_depth_pass).then_some(NO_SECOND_PASS)),
    ("depth.combine_cycles", |a| {
        (!a.depth.second_depth_pass).then_some("depth.second_depth_pass is false: no pass combines two maps")
    }),
    ("on_chip.resolve_test_value_only", |a| {
        (!a.on_chip.light_depth)
            .then_some("on_chip.light_depth is false: the light pass writes depth to DRAM, no tile is resolved")
    }),
    ("map_cache.line", map_cache_geometry),
    ("map_cache.ways", map_cache_geometry),
    ("map_cache.misses_in_flight", map_cache_geometry),
    ("depth_cache.size", |a| (!depth_cache_used(a)).then_some(ALL_ON_CHIP)),
    ("depth_cache.line", depth_cache_geometry),
    ("depth_cache.ways", depth_cache_geometry),
    ("depth_cache.misses_in_flight", depth_cache_geometry),
    ("energy.cache_access", |a| {
        (a.map_cache.size == 0 && depth_cache_geometry(a).is_some())
            .then_some("the machine has no cache that is ever accessed")
    }),
];

/// A key no unit of a machine reads: its value has no effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unread {
    /// The key.
    pub key: &'static str,
    /// Which other key makes it so.
    pub why: &'static str,
    /// Its value looks meant to do something: a number other than 0, or a
    /// flag set, on a key where 0 or unset means "nothing". `arch check`
    /// warns of these; the rest it lists.
    pub meant: bool,
}

impl Arch {
    /// Every key no unit of this machine reads, in file order.
    ///
    /// ```
    /// use umbra_sim::Arch;
    /// let mut a = Arch::bundled("talisman")?;
    /// a.set("depth.peel_cycles=50")?;
    /// let peel = a.unread().into_iter().find(|u| u.key == "depth.peel_cycles").expect("unread");
    /// assert!(peel.meant && peel.why.contains("second_depth_pass"));
    /// # Ok::<(), umbra_sim::cost::arch::ArchError>(())
    /// ```
    #[must_use]
    pub fn unread(&self) -> Vec<Unread> {
        PARAMS
            .iter()
            .filter_map(|p| {
                let (_, rule) = READ_WHEN.iter().find(|(k, _)| *k == p.key)?;
                let why = rule(self)?;
                let zero_means_none = p.range.is_none_or(|(min, _)| min <= 0.0);
                let meant = zero_means_none
                    && match (p.get)(self) {
                        Value::Number(x) => x != 0.0,
                        Value::Flag(f) => f,
                        Value::Text(_) => false,
                    };
                Some(Unread { key: p.key, why, meant })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    /// Every key the table names is a key.
    #[test]
    fn every_rule_names_a_key() {
        for (key, _) in super::READ_WHEN {
            assert!(super::PARAMS.iter().any(|p| p.key == *key), "{key}");
        }
    }
}
