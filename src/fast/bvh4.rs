//! The objects' BVH with four children a node, for packets of rays: the binary tree
//! (`accel::bvh`) with every other level folded into the level above, so that a packet tests
//! four boxes with one set of vector instructions (see `Hull::classify_four`) and walks half
//! as many levels.
//!
//! It is made from the binary tree, not built anew: its leaves, their items and their boxes
//! are the binary tree's, and each node remembers the axes its two levels were split on, so a
//! walk can meet the leaves in the order the binary walk meets them (`Node4::order`). That is
//! what lets `bvh_packet` answer exactly as the core's `Bvh::closest` and `Bvh::any` do.

use glam::DVec3;

use crate::accel::bvh::Node as BinaryNode;
use crate::accel::{Aabb, Bvh};

/// A node: up to four children, each a subtree (another `Node4`) or a leaf of the binary tree.
/// Children 0 and 1 stand on the binary node's left side, 2 and 3 on its right; a side whose
/// binary child is a leaf holds it as child 0 (or 2) alone.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
pub struct Node4 {
    /// The children's boxes axis by axis, lane k for child k: the binary tree's own boxes
    /// (single precision, rounded outward). Unused lanes hold zeros.
    min: [[f32; 4]; 3],
    max: [[f32; 4]; 3],
    /// Child k: a subtree's index in the nodes, or a leaf's first index into the items.
    pub offset: [u32; 4],
    /// Child k: a leaf's number of items, or 0 for a subtree.
    pub count: [u16; 4],
    /// Bit k set when child k exists.
    pub used: u8,
    /// The axes the binary tree split on: this node's, then its left and its right child's.
    axes: [u8; 3],
}

impl Node4 {
    fn empty() -> Node4 {
        Node4 {
            min: [[0.0; 4]; 3],
            max: [[0.0; 4]; 3],
            offset: [0; 4],
            count: [0; 4],
            used: 0,
            axes: [0; 3],
        }
    }

    /// Child k's box (exact in double precision).
    pub fn bounds(&self, k: usize) -> Aabb {
        let corner = |v: &[[f32; 4]; 3]| {
            DVec3::new(f64::from(v[0][k]), f64::from(v[1][k]), f64::from(v[2][k]))
        };
        Aabb {
            min: corner(&self.min),
            max: corner(&self.max),
        }
    }

    /// The children's lower (`max` false) or upper bounds on one axis, lane k for child k.
    #[inline(always)]
    pub fn planes(&self, axis: usize, max: bool) -> [f64; 4] {
        let v = if max { &self.max } else { &self.min };
        v[axis].map(f64::from)
    }

    /// The order in which the binary tree's walk meets the children: nearer side first by
    /// the rays' direction signs (`negative`: the right side first on an axis where they point
    /// down it), or left to right without signs, as `Bvh::any` goes.
    #[inline(always)]
    pub fn order(&self, negative: Option<[bool; 3]>) -> [usize; 4] {
        match negative {
            None => [0, 1, 2, 3],
            Some(negative) => {
                let flip = |axis: u8| usize::from(negative[axis as usize]);
                let first = flip(self.axes[0]);
                let side = |s: usize| {
                    let near = flip(self.axes[1 + s]);
                    [2 * s + near, 2 * s + 1 - near]
                };
                let ([a, b], [c, d]) = (side(first), side(1 - first));
                [a, b, c, d]
            }
        }
    }
}

/// The four-wide tree over the same items as the binary tree it was made from.
#[derive(Clone, Debug, Default)]
pub struct Bvh4 {
    nodes: Vec<Node4>,
    items: Vec<u32>,
}

impl Bvh4 {
    /// Folds a binary tree: its root's children's children become the root's children, and so
    /// on down. A binary tree that is a single leaf becomes a root with that one child.
    pub fn new(bvh: &Bvh) -> Bvh4 {
        let mut tree = Bvh4 {
            nodes: Vec::with_capacity(bvh.node_count() / 2 + 1),
            items: bvh.items().to_vec(),
        };
        let binary = bvh.nodes();
        if let Some(root) = binary.first() {
            if root.count > 0 {
                let mut node = Node4::empty();
                set_child(&mut node, 0, root);
                tree.nodes.push(node);
            } else {
                tree.fold(binary, 0);
            }
        }
        tree
    }

    /// Appends the node for binary interior node `index` and its subtrees; returns its index.
    fn fold(&mut self, binary: &[BinaryNode], index: usize) -> u32 {
        let at = self.nodes.len();
        self.nodes.push(Node4::empty());
        let node = &binary[index];
        let mut folded = Node4::empty();
        folded.axes[0] = node.axis;
        let mut subtrees = vec![];
        for (side, child) in [index + 1, node.offset as usize].into_iter().enumerate() {
            let c = &binary[child];
            let grandchildren = if c.count > 0 {
                vec![child]
            } else {
                folded.axes[1 + side] = c.axis;
                vec![child + 1, c.offset as usize]
            };
            for (j, g) in grandchildren.into_iter().enumerate() {
                let k = 2 * side + j;
                set_child(&mut folded, k, &binary[g]);
                if binary[g].count == 0 {
                    subtrees.push((k, g));
                }
            }
        }
        for (k, g) in subtrees {
            folded.offset[k] = self.fold(binary, g);
        }
        self.nodes[at] = folded;
        at as u32
    }

    /// The nodes, the root first.
    pub fn nodes(&self) -> &[Node4] {
        &self.nodes
    }

    /// The items the leaves name, as in the binary tree.
    pub fn items(&self) -> &[u32] {
        &self.items
    }
}

/// Makes binary node `b` child k of `node`: its box, and for a leaf its items (a subtree's
/// index is set once it is folded).
fn set_child(node: &mut Node4, k: usize, b: &BinaryNode) {
    let bounds = b.bounds();
    for axis in 0..3 {
        // Exact: the binary node's bounds are single-precision numbers.
        node.min[axis][k] = bounds.min[axis] as f32;
        node.max[axis][k] = bounds.max[axis] as f32;
    }
    node.used |= 1 << k;
    if b.count > 0 {
        (node.offset[k], node.count[k]) = (b.offset, b.count);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The leaves of the binary tree below node `i` in the order a walk meets them, every
    /// child entered: near side first by `negative`, left first without.
    fn binary_leaves(bvh: &Bvh, i: usize, negative: Option<[bool; 3]>, out: &mut Vec<(u32, u16)>) {
        let n = &bvh.nodes()[i];
        if n.count > 0 {
            out.push((n.offset, n.count));
            return;
        }
        let (left, right) = (i + 1, n.offset as usize);
        let right_first = negative.is_some_and(|neg| neg[n.axis as usize]);
        let sides = if right_first {
            [right, left]
        } else {
            [left, right]
        };
        for side in sides {
            binary_leaves(bvh, side, negative, out);
        }
    }

    /// The leaves of the folded tree below node `i`, children taken in `Node4::order`.
    fn folded_leaves(
        tree: &Bvh4,
        i: usize,
        negative: Option<[bool; 3]>,
        out: &mut Vec<(u32, u16)>,
    ) {
        let n = &tree.nodes()[i];
        for k in n.order(negative) {
            if n.used & (1 << k) == 0 {
                continue;
            }
            if n.count[k] > 0 {
                out.push((n.offset[k], n.count[k]));
            } else {
                folded_leaves(tree, n.offset[k] as usize, negative, out);
            }
        }
    }

    fn leaves_in_order(
        walk: impl Fn(usize, Option<[bool; 3]>, &mut Vec<(u32, u16)>),
        negative: Option<[bool; 3]>,
    ) -> Vec<(u32, u16)> {
        let mut out = vec![];
        walk(0, negative, &mut out);
        out
    }

    fn random_boxes(n: usize, seed: u64) -> Vec<Aabb> {
        let mut rng = crate::sampling::Rng::for_pixel(seed, 0, 0);
        (0..n)
            .map(|_| {
                let c = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 20.0;
                let h = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 0.7 + 0.01;
                Aabb::new(c - h, c + h)
            })
            .collect()
    }

    /// Every leaf of the binary tree is a child of exactly one folded node, with its own box,
    /// and a walk of the folded tree meets the leaves in the binary walk's order for every
    /// combination of direction signs, and without signs.
    #[test]
    fn the_folded_tree_meets_the_binary_leaves_in_their_order() {
        for (n, seed) in [(1, 1), (3, 2), (5, 3), (40, 4), (1000, 5)] {
            let boxes = random_boxes(n, seed);
            let bvh = Bvh::build(&boxes);
            let tree = Bvh4::new(&bvh);
            let mut signs: Vec<Option<[bool; 3]>> = vec![None];
            for bits in 0..8 {
                signs.push(Some([bits & 1 != 0, bits & 2 != 0, bits & 4 != 0]));
            }
            for negative in signs {
                let expected =
                    leaves_in_order(|i, s, out| binary_leaves(&bvh, i, s, out), negative);
                let folded = leaves_in_order(|i, s, out| folded_leaves(&tree, i, s, out), negative);
                assert_eq!(folded, expected, "{n} boxes, signs {negative:?}");
            }
            let leaves = bvh.nodes().iter().filter(|b| b.count > 0).count();
            assert_eq!(
                leaves_in_order(|i, s, out| binary_leaves(&bvh, i, s, out), None).len(),
                leaves
            );
            assert_eq!(tree.items(), bvh.items());
        }
    }

    /// A folded node's child boxes are the binary nodes' boxes, to the bit.
    #[test]
    fn children_keep_the_binary_boxes() {
        let bvh = Bvh::build(&random_boxes(300, 9));
        let tree = Bvh4::new(&bvh);
        let leaf_boxes: Vec<(u32, Aabb)> = bvh
            .nodes()
            .iter()
            .filter(|b| b.count > 0)
            .map(|b| (b.offset, b.bounds()))
            .collect();
        let mut seen = 0;
        for node in tree.nodes() {
            for k in 0..4 {
                if node.used & (1 << k) != 0 && node.count[k] > 0 {
                    let (_, b) = leaf_boxes
                        .iter()
                        .find(|(offset, _)| *offset == node.offset[k])
                        .unwrap();
                    assert_eq!(node.bounds(k), *b);
                    seen += 1;
                }
            }
        }
        assert_eq!(seen, leaf_boxes.len());
        // About half as many nodes as the binary tree has interior nodes.
        let interior = bvh.nodes().iter().filter(|b| b.count == 0).count();
        assert!(
            tree.nodes().len() <= interior,
            "{} {interior}",
            tree.nodes().len()
        );
    }
}
