//! Why a pick beat the fastest candidate, when the objective is not
//! cycles: the two side by side, and the units whose silicon differs.

use super::{Candidate, Costs, Objective, PlanSpec};
use crate::cost::silicon::Silicon;
use crate::experiment::study::{Spec, render_config};

/// A reason line setting the pick beside the candidate with the fewest
/// cycles among those meeting every budget and limit, and the units
/// whose area differs between them; none when the objective is cycles or
/// the fastest is the pick.
pub(super) fn against_fastest(
    study: &Spec,
    spec: &PlanSpec,
    (all, least): (&[(Candidate, usize)], &Costs),
    (pick, index): (&Candidate, usize),
) -> Option<String> {
    if spec.objective == Objective::Cycles {
        return None;
    }
    let (fastest, at) = all
        .iter()
        .filter(|(c, _)| c.misses(&spec.budgets, &spec.cost_limits).is_empty())
        .min_by(|(a, i), (b, j)| a.cycles.cmp(&b.cycles).then(a.bytes.cmp(&b.bytes)).then(i.cmp(j)))?;
    if *at == index {
        return Some(format!("{}: also the fastest candidate meeting every budget", pick.label));
    }
    let configs = study.configs();
    let silicon = |i: usize| Silicon::of(&spec.arch, &render_config(study, &configs[i]).demand());
    let (mine, theirs) = (silicon(index), silicon(*at));
    let area = |s: &Silicon, unit: &str| s.units.iter().find(|u| u.unit == unit).map_or(0.0, |u| u.square_metres);
    let mut units: Vec<&str> = mine.units.iter().chain(&theirs.units).map(|u| u.unit).collect();
    units.dedup();
    units.sort_unstable();
    units.dedup();
    let differ: Vec<String> = units
        .into_iter()
        .filter(|u| area(&mine, u) != area(&theirs, u))
        .map(|u| format!("{u} {:.0} against {:.0} µm²", area(&mine, u) * 1e12, area(&theirs, u) * 1e12))
        .collect();
    let why = if differ.is_empty() { "the same units".to_owned() } else { differ.join("; ") };
    Some(format!(
        "against the fastest candidate meeting every budget, {} ({} cycles, {:.3} µJ, {:.4} mm²): {} {} against {}; silicon: {why}",
        fastest.label,
        fastest.cycles,
        fastest.joules * 1e6,
        fastest.square_metres * 1e6,
        spec.objective.words(),
        spec.objective.text(&pick.costs(), least),
        spec.objective.text(&fastest.costs(), least),
    ))
}
