//! Counters of the work a render did, and of the work it skipped.

use serde::Serialize;

/// Counters of the work a trace or render did and skipped, summed over threads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Rays from the eye through the pixels.
    pub primary_rays: u64,
    /// Shadow rays cast towards lights.
    pub shadow_rays: u64,
    /// Reflection rays traced.
    pub reflection_rays: u64,
    /// Refraction rays traced.
    pub refraction_rays: u64,
    /// Shadow rays not cast because the light is behind the surface (n·l ≤ 0).
    pub shadow_skipped_backfacing: u64,
    /// Shadow rays not cast because the light has zero intensity.
    pub shadow_skipped_dark: u64,
    /// Shadow rays not cast because they start inside a convex solid the light is outside
    /// of: the solid itself blocks them.
    pub shadow_skipped_inside: u64,
    /// Secondary rays not cast because the path reached the maximum depth.
    pub max_depth_cutoffs: u64,
    /// Secondary rays not cast because their weight fell below the adaptive threshold.
    pub adaptive_cutoffs: u64,
    /// Refraction rays replaced by a mirror ray past the critical angle.
    pub total_internal_reflections: u64,
    /// CSG subtrees skipped (bounding box missed, or empty operand of ∩ / −).
    pub csg_pruned: u64,
    /// Objects not tested because the ray misses their bounding box (or meets it only beyond
    /// the nearest hit so far). Plain spheres and planes are tested directly, without a box.
    pub bounds_skipped: u64,
    /// BVH nodes whose box was tested.
    pub bvh_nodes_visited: u64,
    /// Object (or primitive) intersection routines run.
    pub primitives_tested: u64,
    /// Reflection and refraction rays drawn from glossy and frosted lobes.
    pub glossy_rays: u64,
    /// Squares of pixels split by adaptive antialiasing.
    pub aa_splits: u64,
}

impl Stats {
    /// All rays traced: primary, shadow, reflection and refraction.
    pub fn rays(&self) -> u64 {
        self.primary_rays + self.shadow_rays + self.reflection_rays + self.refraction_rays
    }

    /// Adds another run's counters to these.
    pub fn add(&mut self, o: &Stats) {
        self.primary_rays += o.primary_rays;
        self.shadow_rays += o.shadow_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.shadow_skipped_backfacing += o.shadow_skipped_backfacing;
        self.shadow_skipped_dark += o.shadow_skipped_dark;
        self.shadow_skipped_inside += o.shadow_skipped_inside;
        self.max_depth_cutoffs += o.max_depth_cutoffs;
        self.adaptive_cutoffs += o.adaptive_cutoffs;
        self.total_internal_reflections += o.total_internal_reflections;
        self.csg_pruned += o.csg_pruned;
        self.bounds_skipped += o.bounds_skipped;
        self.bvh_nodes_visited += o.bvh_nodes_visited;
        self.primitives_tested += o.primitives_tested;
        self.glossy_rays += o.glossy_rays;
        self.aa_splits += o.aa_splits;
    }

    /// A human-readable report, one counter per line.
    pub fn report(&self) -> String {
        table(&self.rows())
    }

    /// The report's rows: a label and its value, each counter and the per-ray averages.
    pub fn rows(&self) -> Vec<(&'static str, String)> {
        let rays = self.rays().max(1) as f64;
        let count = |label, n: u64| (label, n.to_string());
        vec![
            count("rays traced", self.rays()),
            count("  primary", self.primary_rays),
            count("  shadow", self.shadow_rays),
            count("  reflection", self.reflection_rays),
            count("  refraction", self.refraction_rays),
            count("  of which glossy/frosted samples", self.glossy_rays),
            count(
                "skipped: shadow rays, light behind (n·l ≤ 0)",
                self.shadow_skipped_backfacing,
            ),
            count("skipped: shadow rays, dark light", self.shadow_skipped_dark),
            count(
                "skipped: shadow rays inside convex solids",
                self.shadow_skipped_inside,
            ),
            count(
                "skipped: secondary rays at max depth",
                self.max_depth_cutoffs,
            ),
            count(
                "skipped: secondary rays, adaptive depth",
                self.adaptive_cutoffs,
            ),
            count(
                "total internal reflections",
                self.total_internal_reflections,
            ),
            count("skipped: CSG subtrees pruned", self.csg_pruned),
            count("BVH nodes visited", self.bvh_nodes_visited),
            count("skipped: objects, bounding box missed", self.bounds_skipped),
            count("objects/primitives tested", self.primitives_tested),
            count("adaptive antialiasing: squares split", self.aa_splits),
            (
                "BVH nodes per ray",
                format!("{:.2}", self.bvh_nodes_visited as f64 / rays),
            ),
            (
                "primitives tested per ray",
                format!("{:.2}", self.primitives_tested as f64 / rays),
            ),
        ]
    }
}

/// Rows of a label and a value as lines ending in the same column: the labels padded to the
/// longest, the values right-aligned. Widths are counted in characters, not bytes (`n·l ≤ 0`
/// is 7 characters of 11 bytes); every label is of characters one column wide.
pub fn table(rows: &[(&str, String)]) -> String {
    let chars = |s: &str| s.chars().count();
    let label = rows.iter().map(|r| chars(r.0)).max().unwrap_or(0);
    let value = rows.iter().map(|r| chars(&r.1)).max().unwrap_or(0).max(14);
    rows.iter()
        .map(|(k, v)| format!("{k:<label$} {v:>value$}\n"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every line of the report ends in the same column, the longest label and the largest
    /// count included.
    #[test]
    fn every_row_of_the_report_ends_in_the_same_column() {
        let stats = Stats {
            primary_rays: u64::MAX / 4,
            shadow_skipped_backfacing: 7,
            ..Stats::default()
        };
        let report = stats.report();
        let ends: Vec<usize> = report.lines().map(|l| l.chars().count()).collect();
        assert_eq!(ends.len(), stats.rows().len());
        assert!(ends.iter().all(|&e| e == ends[0]), "{report}");
    }
}
