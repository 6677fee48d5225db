//! How deep a ray tree can be shown. Each level can double a tree (a glass surface sends a
//! reflected and a refracted ray on), so a tree of the scene format's deepest recursion could
//! hold 2⁶⁴ rays. A tree is shown to any depth up to `FREE_DEPTH`, and deeper only while it
//! holds at most `TREE_BUDGET` rays: a corridor of mirrors goes to its scene's depth, a glass
//! sphere's tree stops in time.

use glam::DVec3;

use super::Tracer;
use crate::geometry::Ray;
use crate::sampling::Rng;
use crate::scene::Scene;

/// Depths up to this are always traced.
pub const FREE_DEPTH: u32 = 16;

/// The most rays a tree deeper than `FREE_DEPTH` may hold.
pub const TREE_BUDGET: u64 = 100_000;

/// The deepest depth up to `asked` whose tree from `ray` holds at most `TREE_BUDGET` rays, or
/// `asked` itself up to `FREE_DEPTH`. A tree one level deeper holds at most a few times the
/// rays of the last (two rays on per surface, a shadow ray per light), so finding where the
/// budget is passed costs a few budgets' worth of rays, however deep the scene asks to go.
pub fn affordable_depth(scene: &Scene, ray: &Ray, asked: u32, rng: &dyn Fn() -> Rng) -> u32 {
    let mut depth = asked.min(FREE_DEPTH);
    while depth < asked {
        let mut tracer = Tracer::new(scene).with_depth(depth + 1).with_rng(rng());
        let _: DVec3 = tracer.radiance(ray);
        if tracer.stats.rays() > TREE_BUDGET {
            break;
        }
        depth += 1;
    }
    depth
}

/// Why a tree stops at `depth`, short of the depth asked.
pub fn budget_note(depth: u32) -> String {
    format!("a tree deeper than {depth} holds over {TREE_BUDGET} rays: the tree is shown to depth {depth}")
}
