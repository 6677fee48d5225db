//! Monte Carlo means: a node that is the mean of n sampled rays (a glossy or frosted cone) is an
//! estimate, and an answer to it is graded within k standard errors of that estimate
//! (`tolerance: { standard_errors: k }`).

use glam::DVec3;

use super::Worked;
use crate::lessons::Exercise;
use crate::lessons::Tolerance;
use crate::trace::RayNode;

/// The standard error of a cone's mean, s/√n with s² = Σ(xᵢ − x̄)²/(n − 1) over its n sampled
/// rays' intensities, taken on the colour channel where it is largest. None for a node that is
/// not the mean of two or more sampled rays.
pub fn standard_error(n: &RayNode) -> Option<f64> {
    let count = n.samples?;
    let values: Vec<DVec3> = n.secondary().map(|c| c.color).collect();
    if count < 2 || values.len() != count as usize {
        return None;
    }
    let k = values.len() as f64;
    let mean = values.iter().sum::<DVec3>() / k;
    let var = values
        .iter()
        .map(|x| (*x - mean) * (*x - mean))
        .sum::<DVec3>()
        / (k - 1.0);
    Some((var / k).max_element().sqrt())
}

/// The exercise's tolerance, with a standard-error rule filled in from the node it asks about.
pub(super) fn tolerance(ex: &Exercise, node: &RayNode) -> Result<Tolerance, String> {
    if ex.tolerance.standard_errors == 0.0 {
        return Ok(ex.tolerance);
    }
    let se = standard_error(node).ok_or_else(|| {
        format!(
            "exercise `{}`: a tolerance in standard errors needs a node that is the mean of sampled rays (glossy or frosted)",
            ex.id
        )
    })?;
    Ok(ex.tolerance.with_standard_error(se))
}

/// The lines that say how the tolerance came from the samples.
pub(super) fn explain(w: &Worked, n: &RayNode) -> Vec<String> {
    match standard_error(n) {
        Some(se) if w.tolerance.standard_errors > 0.0 => vec![format!(
            "the {} rays' values spread with a standard error of the mean s/√n = {} (on the channel where it is largest): an answer within {} standard errors (±{}) of raytree's mean is right, and so is the exact value the mean estimates",
            n.samples.unwrap_or(0),
            crate::trace::text::num(se),
            crate::trace::text::num(w.tolerance.standard_errors),
            crate::trace::text::num(w.tolerance.absolute)
        )],
        _ => Vec::new(),
    }
}
