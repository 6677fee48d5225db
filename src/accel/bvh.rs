//! Bounding volume hierarchy: a binary tree of boxes built with the surface area heuristic,
//! flattened into an array in depth-first order (the left child follows its parent).
//!
//! Seed 002: a ray that misses a node's box skips everything below it, turning the cost of a
//! ray from O(n) intersections into roughly O(log n).

use glam::DVec3;

use super::aabb::SlabRay;
use super::Aabb;

/// A node of the flattened tree, 32 bytes. Its box is kept in single precision, each bound
/// rounded outward: half the memory of a double-precision box, and a box that only grows never
/// loses a hit (it can only let a ray visit a subtree it would have skipped by less than the
/// rounding, where every item is then tested exactly as before).
#[derive(Clone, Copy, Debug)]
#[repr(align(32))]
pub struct Node {
    min: [f32; 3],
    max: [f32; 3],
    /// Leaf: first index into `items`. Interior: index of the right child.
    pub offset: u32,
    /// Leaf: number of items (> 0). Interior: 0.
    pub count: u16,
    /// Interior: the axis it was split on, to visit the nearer child first.
    pub axis: u8,
}

impl Node {
    fn new(bounds: Aabb, offset: u32, count: u16) -> Node {
        Node {
            min: bounds.min.to_array().map(round_down),
            max: bounds.max.to_array().map(round_up),
            offset,
            count,
            axis: 0,
        }
    }

    /// The box around everything below this node (exact in double precision).
    pub fn bounds(&self) -> Aabb {
        let wide = |v: [f32; 3]| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
        Aabb {
            min: wide(self.min),
            max: wide(self.max),
        }
    }
}

/// The largest f32 at or below x (−∞ below f32's range). Both candidates are worked out and
/// one chosen, which compiles to a select: which way x rounds is a coin toss a branch misses.
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    let below = f.next_down();
    if f as f64 > x {
        below
    } else {
        f
    }
}

/// The smallest f32 at or above x (+∞ above f32's range), chosen as in `round_down`.
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    let above = f.next_up();
    if (f as f64) < x {
        above
    } else {
        f
    }
}

/// A bounding volume hierarchy over a list of boxes, built by the surface area heuristic (SAH) and
/// flattened into an array; the items are indices into the boxes it was built from.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    items: Vec<u32>,
}

/// Work done by one traversal.
#[derive(Clone, Copy, Debug, Default)]
pub struct Visits {
    /// Nodes whose box the ray was tested against.
    pub nodes: u64,
    /// Items (primitives) of the leaves reached, each one intersection test.
    pub items: u64,
}

const BINS: usize = 12;
const MAX_LEAF: usize = 4;

impl Bvh {
    /// Builds over the given item boxes (all finite); item i is reported as `i`. The SAH
    /// counts a box test as half an item's test: the items are a scene's objects (spheres, CSG
    /// trees, whole meshes), each dearer than a box.
    pub fn build(boxes: &[Aabb]) -> Bvh {
        Bvh::build_with(boxes, 0.5, PARALLEL_ITEMS)
    }

    /// Builds over the boxes of a mesh's triangles. A triangle test costs about a box test, so
    /// the SAH counts them alike: leaves then hold two or three triangles instead of one, which
    /// halves the nodes (the tree of a million triangles would otherwise outweigh them) for the
    /// same time per ray.
    pub fn build_over_triangles(boxes: &[Aabb]) -> Bvh {
        Bvh::build_with(boxes, 1.0, PARALLEL_ITEMS)
    }

    /// `box_cost`: the SAH's cost of one box test relative to one item's test. Subtrees over
    /// `parallel_items` items or more, near the root, build their halves on two threads.
    fn build_with(boxes: &[Aabb], box_cost: f64, parallel_items: usize) -> Bvh {
        let mut items: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * boxes.len());
        if !boxes.is_empty() {
            let centers: Vec<DVec3> = boxes.iter().map(Aabb::center).collect();
            let builder = Builder {
                boxes,
                centers: &centers,
                box_cost,
                parallel_items,
            };
            builder.node(&mut items, 0, 0, &mut nodes);
        }
        // The tree has fewer than the 2N nodes reserved for it (leaves hold up to MAX_LEAF).
        nodes.shrink_to_fit();
        Bvh { nodes, items }
    }

    /// The bytes the tree holds on the heap: its nodes and its item indices.
    pub fn heap_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>()
            + self.items.capacity() * std::mem::size_of::<u32>()
    }

    /// How many nodes, leaves and interior, the flattened tree has (0 when built from no boxes).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nodes in depth-first order: the root first, a left child right after its parent.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The items of the leaves, each leaf's a run of `count` from `offset`.
    pub fn items(&self) -> &[u32] {
        &self.items
    }

    /// The root's box, around every item; empty when there are none.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::empty(), Node::bounds)
    }

    /// Visits items in near-to-far order of their subtrees. `visit(item, t_max)` returns a
    /// closer hit distance, which then shrinks the search.
    pub fn closest(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        visit: impl FnMut(u32, f64) -> Option<f64>,
    ) -> Visits {
        self.closest_watched(origin, dir, t_min, t_max, visit, |_, _| {})
    }

    /// `closest`, telling `watch(node, entered)` of every node whose box it tests, in order:
    /// what the explorer draws to show the boxes a ray visits. The renderer's searches pass a
    /// watcher that does nothing, which the compiler removes.
    pub fn closest_watched(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        mut t_max: f64,
        mut visit: impl FnMut(u32, f64) -> Option<f64>,
        mut watch: impl FnMut(u32, bool),
    ) -> Visits {
        let mut work = Visits::default();
        if self.nodes.is_empty() {
            return work;
        }
        let slabs = SlabRay::new(origin, dir.recip());
        let negative = slabs.negative;
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            work.nodes += 1;
            let entered = node.bounds().hit_slabs(&slabs, t_min, t_max);
            watch(stack[top], entered);
            if !entered {
                continue;
            }
            if node.count > 0 {
                let first = node.offset as usize;
                for &item in &self.items[first..first + node.count as usize] {
                    work.items += 1;
                    if let Some(t) = visit(item, t_max) {
                        t_max = t_max.min(t);
                    }
                }
            } else {
                let left = stack[top] + 1;
                let (near, far) = if negative[node.axis as usize] {
                    (node.offset, left)
                } else {
                    (left, node.offset)
                };
                stack[top] = far;
                stack[top + 1] = near;
                top += 2;
            }
        }
        work
    }

    /// Stops at the first item for which `visit` returns true (shadow rays need any blocker).
    pub fn any(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        visit: impl FnMut(u32) -> bool,
    ) -> (bool, Visits) {
        self.any_watched(origin, dir, t_min, t_max, visit, |_, _| {})
    }

    /// `any`, telling `watch(node, entered)` of every node whose box it tests, in order.
    pub fn any_watched(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        mut visit: impl FnMut(u32) -> bool,
        mut watch: impl FnMut(u32, bool),
    ) -> (bool, Visits) {
        let mut work = Visits::default();
        if self.nodes.is_empty() {
            return (false, work);
        }
        let slabs = SlabRay::new(origin, dir.recip());
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let index = stack[top];
            let node = &self.nodes[index as usize];
            work.nodes += 1;
            let entered = node.bounds().hit_slabs(&slabs, t_min, t_max);
            watch(index, entered);
            if !entered {
                continue;
            }
            if node.count > 0 {
                let first = node.offset as usize;
                for &item in &self.items[first..first + node.count as usize] {
                    work.items += 1;
                    if visit(item) {
                        return (true, work);
                    }
                }
            } else {
                stack[top] = node.offset;
                stack[top + 1] = index + 1;
                top += 2;
            }
        }
        (false, work)
    }
}

/// What every step of a build reads: the items' boxes and centres, the SAH's cost of a box
/// test relative to an item's, and from how many items on a subtree is built on two threads.
struct Builder<'a> {
    boxes: &'a [Aabb],
    centers: &'a [DVec3],
    box_cost: f64,
    parallel_items: usize,
}

/// A subtree over at least this many items, in the tree's top `PARALLEL_DEPTH` levels, builds
/// its right half on another thread when there is one. Below that size a thread saves less than
/// it costs to start; deeper down the threads are all busy already, and every level built apart
/// moves its halves' nodes once more (for a million triangles, more time than it saves).
const PARALLEL_ITEMS: usize = 1 << 12;
/// The levels from the root whose subtrees may build their halves on two threads: up to eight
/// builds at once, enough to keep the threads busy while one half finishes before the other.
const PARALLEL_DEPTH: usize = 3;

impl Builder<'_> {
    /// Appends the subtree over `items` to `nodes` in depth-first order and returns its root's
    /// index; `first` is the index of `items[0]` in the whole list. Interior nodes' offsets count
    /// from the start of `nodes`.
    fn node(&self, items: &mut [u32], first: usize, depth: usize, nodes: &mut Vec<Node>) -> usize {
        let index = nodes.len();
        // The box around the items, and the box around their centres (which the split needs).
        let (mut bounds, mut centroid_bounds) = (Aabb::empty(), Aabb::empty());
        for &i in items.iter() {
            bounds = bounds.union(&self.boxes[i as usize]);
            centroid_bounds = centroid_bounds.grow(self.centers[i as usize]);
        }
        nodes.push(Node::new(bounds, first as u32, items.len() as u16));
        let n = items.len();
        if n <= 1 {
            return index;
        }
        let extent = centroid_bounds.max - centroid_bounds.min;
        let axis = extent.max_position();
        if extent[axis] <= 0.0 {
            // All centres coincide: no split separates them.
            if n <= u16::MAX as usize {
                return index;
            }
        }
        // Deep down, halve at the median so the traversal stack (64 entries) can never overflow.
        let split = if depth < 40 {
            self.sah_split(items, axis, &centroid_bounds, &bounds)
        } else {
            None
        };
        let mid = match split {
            Some(mid) => mid,
            None if n <= MAX_LEAF
                || (depth >= 40 && n <= u16::MAX as usize && extent[axis] <= 0.0) =>
            {
                return index
            }
            // The SAH prefers a leaf but it is too big: split at the median.
            None => {
                items.sort_by(|&a, &b| {
                    self.centers[a as usize][axis].total_cmp(&self.centers[b as usize][axis])
                });
                n / 2
            }
        };
        nodes[index].count = 0;
        nodes[index].axis = axis as u8;
        let (left, right) = items.split_at_mut(mid);
        let parallel = n >= self.parallel_items && depth < PARALLEL_DEPTH;
        let right_index = if parallel && rayon::current_num_threads() > 1 {
            // The same tree as one thread builds: the right subtree on its own, then moved in
            // behind the left one with its offsets shifted.
            let ((), subtree) = rayon::join(
                || {
                    self.node(left, first, depth + 1, nodes);
                },
                || {
                    let mut own = vec![];
                    self.node(right, first + mid, depth + 1, &mut own);
                    own
                },
            );
            let base = nodes.len();
            nodes.extend(subtree.into_iter().map(|mut node| {
                if node.count == 0 {
                    node.offset += base as u32;
                }
                node
            }));
            base
        } else {
            self.node(left, first, depth + 1, nodes);
            self.node(right, first + mid, depth + 1, nodes)
        };
        nodes[index].offset = right_index as u32;
        index
    }

    /// Binned SAH: partitions the items and returns the split point, or None when a leaf is
    /// cheaper than any split.
    fn sah_split(&self, items: &mut [u32], axis: usize, cb: &Aabb, bounds: &Aabb) -> Option<usize> {
        let (lo, width) = (cb.min[axis], cb.max[axis] - cb.min[axis]);
        if width <= 0.0 {
            return None;
        }
        // The bin of a centre c: ⌊(c − lo)/width · BINS⌋, the last bin taking c = hi. Each bin
        // also keeps its largest c, where the partition below cuts.
        let bin_of = |c: f64| ((c - lo) / width * BINS as f64).min((BINS - 1) as f64) as usize;
        let mut bins = [(Aabb::empty(), 0usize, f64::NEG_INFINITY); BINS];
        for &i in items.iter() {
            let c = self.centers[i as usize][axis];
            let b = &mut bins[bin_of(c)];
            b.0 = b.0.union(&self.boxes[i as usize]);
            b.1 += 1;
            b.2 = b.2.max(c);
        }
        // Sweep from the right to get the cost of every "left of bin k | right" split.
        let mut right_area = [0.0; BINS];
        let mut right_count = [0usize; BINS];
        let (mut acc, mut cnt) = (Aabb::empty(), 0);
        for k in (1..BINS).rev() {
            acc = acc.union(&bins[k].0);
            cnt += bins[k].1;
            right_area[k] = acc.surface_area();
            right_count[k] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::empty(), 0);
        let mut best = (f64::INFINITY, 0);
        for k in 1..BINS {
            acc = acc.union(&bins[k - 1].0);
            cnt += bins[k - 1].1;
            if cnt == 0 || right_count[k] == 0 {
                continue;
            }
            let cost = acc.surface_area() * cnt as f64 + right_area[k] * right_count[k] as f64;
            if cost < best.0 {
                best = (cost, k);
            }
        }
        let n = items.len();
        let leaf_cost = n as f64;
        let split_cost = self.box_cost + best.0 / bounds.surface_area().max(f64::MIN_POSITIVE);
        if best.0.is_infinite() || (n <= MAX_LEAF && split_cost >= leaf_cost) {
            return None;
        }
        // A bin only grows with c, so the items left of bin k are exactly those whose c is at
        // most the largest c in bins 0..k: one comparison each, no second division.
        let cut = bins[..best.1]
            .iter()
            .fold(f64::NEG_INFINITY, |m, b| m.max(b.2));
        // Each item found left swaps places with the first one not (the exchange written with
        // selects: which way an item goes is a coin toss the processor cannot predict).
        let mut left = 0;
        for i in 0..n {
            let (this, first) = (items[i], items[left]);
            let goes_left = self.centers[this as usize][axis] <= cut;
            items[i] = if goes_left { first } else { this };
            items[left] = if goes_left { this } else { first };
            left += goes_left as usize;
        }
        Some(left)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Boxes on a line; the BVH must report exactly the boxes a brute-force test finds.
    #[test]
    fn finds_the_same_items_as_brute_force() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| {
                let x = (i as f64 * 7.31).sin() * 50.0;
                let y = (i as f64 * 3.17).cos() * 50.0;
                let c = DVec3::new(x, y, (i % 17) as f64);
                Aabb::new(c - 0.5, c + 0.5)
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        for k in 0..50 {
            let origin = DVec3::new(-60.0, (k as f64) * 2.0 - 50.0, 8.0);
            let dir = DVec3::new(1.0, 0.01, 0.0).normalize();
            let inv = dir.recip();
            let mut found = vec![];
            bvh.closest(origin, dir, 0.0, f64::INFINITY, |i, _| {
                if boxes[i as usize].hit(origin, inv, 0.0, f64::INFINITY) {
                    found.push(i);
                }
                None
            });
            found.sort();
            let brute: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| boxes[i as usize].hit(origin, inv, 0.0, f64::INFINITY))
                .collect();
            assert_eq!(found, brute);
        }
    }

    /// Every split the SAH chose is the binned SAH's by its definition: the node's items
    /// binned by ⌊(c − lo)/width · BINS⌋ along the axis of the centres' largest extent, each
    /// cut between bins k − 1 and k costed as area × count on both sides, the cheapest (the
    /// first of equals) taken, and the left child holding exactly the items of bins below it.
    /// Centres on a coarse grid put many items in one bin and many at one value.
    #[test]
    fn each_split_is_the_binned_sah_split() {
        let boxes: Vec<Aabb> = (0..3000)
            .map(|i| {
                let t = i as f64;
                let c = DVec3::new(
                    ((t * 7.31).sin() * 40.0).round() / 2.0,
                    ((t * 3.17).cos() * 9.0).round(),
                    (i % 7) as f64,
                );
                Aabb::new(c - 0.2 - 0.1 * (t * 1.3).sin().abs(), c + 0.3)
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        // The items under node `at`: its leaves' ranges, in order.
        fn under(bvh: &Bvh, at: usize, out: &mut Vec<u32>) {
            let node = &bvh.nodes[at];
            if node.count > 0 {
                let first = node.offset as usize;
                out.extend_from_slice(&bvh.items[first..first + node.count as usize]);
            } else {
                under(bvh, at + 1, out);
                under(bvh, node.offset as usize, out);
            }
        }
        let mut checked = 0;
        for at in 0..bvh.nodes.len() {
            if bvh.nodes[at].count > 0 {
                continue;
            }
            let (mut all, mut left) = (vec![], vec![]);
            under(&bvh, at, &mut all);
            under(&bvh, at + 1, &mut left);
            let centre = |i: u32| boxes[i as usize].center();
            let (lo, hi) = all
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), &i| {
                    (a.min(centre(i)), b.max(centre(i)))
                });
            let axis = (hi - lo).max_position();
            let width = hi[axis] - lo[axis];
            let bin = |i: u32| {
                let x = (centre(i)[axis] - lo[axis]) / width * BINS as f64;
                (x.floor() as usize).min(BINS - 1)
            };
            let side = |k: usize, below: bool| {
                let items: Vec<u32> = all
                    .iter()
                    .copied()
                    .filter(|&i| (bin(i) < k) == below)
                    .collect();
                let b = items
                    .iter()
                    .fold(Aabb::empty(), |b, &i| b.union(&boxes[i as usize]));
                (items.len(), b.surface_area() * items.len() as f64)
            };
            let mut best: Option<(f64, usize)> = None;
            for k in 1..BINS {
                let ((nl, cl), (nr, cr)) = (side(k, true), side(k, false));
                if nl > 0 && nr > 0 && best.is_none_or(|(c, _)| cl + cr < c) {
                    best = Some((cl + cr, k));
                }
            }
            let Some((_, k)) = best else { continue };
            let mut expected: Vec<u32> = all.iter().copied().filter(|&i| bin(i) < k).collect();
            expected.sort();
            left.sort();
            assert_eq!(left, expected, "node {at}: the left child is bins 0..{k}");
            checked += 1;
        }
        assert!(checked > 1000, "{checked} splits checked");
    }

    /// A node's single-precision box holds the double-precision box it was built from, and
    /// is at most one f32 step larger on each side; beyond f32's range it is unbounded.
    #[test]
    fn a_node_box_is_rounded_outward_by_at_most_one_step() {
        let values: [f64; 11] = [
            0.1,
            -0.1,
            1.0,
            1.0 / 3.0,
            -7.25,
            1e-30,
            -1e-300,
            123_456_789.123,
            3.0e38,
            -1e39,
            1e300,
        ];
        for &a in &values {
            for &b in &values {
                let (lo, hi) = (a.min(b), a.max(b));
                let exact = Aabb::new(DVec3::splat(lo), DVec3::new(hi, hi, lo.max(0.5)));
                let node = Node::new(exact, 0, 1).bounds();
                for k in 0..3 {
                    let (min, max) = (node.min[k], node.max[k]);
                    assert!(
                        min <= exact.min[k] && max >= exact.max[k],
                        "{exact:?} {node:?}"
                    );
                    let step = |x: f64| (x as f32).next_up() as f64 - x as f32 as f64;
                    for (rounded, x) in [(min, exact.min[k]), (max, exact.max[k])] {
                        if x.abs() > f32::MAX as f64 {
                            assert!(rounded.is_infinite() || rounded.abs() == f32::MAX as f64);
                        } else {
                            assert!(
                                (rounded - x).abs() <= step(x).max(step(rounded)),
                                "{x} → {rounded}"
                            );
                        }
                    }
                }
            }
        }
        assert_eq!(
            Node::new(Aabb::new(DVec3::splat(0.5), DVec3::ONE), 0, 1)
                .bounds()
                .min
                .x,
            0.5
        );
        assert_eq!(std::mem::size_of::<Node>(), 32);
    }

    /// The tree holds no more nodes than it has: the 2N reserved while building are given back.
    #[test]
    fn the_tree_keeps_only_its_nodes() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| Aabb::new(DVec3::splat(i as f64), DVec3::splat(i as f64 + 0.5)))
            .collect();
        let bvh = Bvh::build(&boxes);
        assert!(bvh.node_count() < 2 * boxes.len());
        assert_eq!(
            bvh.heap_bytes(),
            bvh.node_count() * 32 + boxes.len() * 4,
            "32 bytes a node and an item index per box"
        );
    }

    /// Built on two threads, the tree is the one a single thread builds: the same nodes in the
    /// same order and the same items, for objects (SAH box cost ½) and triangles (1).
    #[test]
    fn a_parallel_build_is_the_sequential_build() {
        let boxes: Vec<Aabb> = (0..5000)
            .map(|i| {
                let t = i as f64;
                let c = DVec3::new((t * 7.31).sin() * 50.0, (t * 3.17).cos() * 20.0, t % 13.0);
                Aabb::new(c - 0.3 - 0.2 * (t * 1.7).sin().abs(), c + 0.4)
            })
            .collect();
        for box_cost in [0.5, 1.0] {
            let one = Bvh::build_with(&boxes, box_cost, usize::MAX);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap();
            let two = pool.install(|| Bvh::build_with(&boxes, box_cost, 64));
            assert_eq!(one.items, two.items);
            let key = |n: &Node| (n.min, n.max, n.offset, n.count, n.axis);
            let keys = |b: &Bvh| b.nodes.iter().map(key).collect::<Vec<_>>();
            assert_eq!(keys(&one), keys(&two));
            assert!(one.node_count() > 1000);
        }
    }
}
