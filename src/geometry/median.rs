//! A binary BVH built by median splits, for small sets of costly primitives (CSG objects, the
//! triangles of a CSG mesh operand), where a box test costs far less than a primitive test.

use glam::Vec3;

use super::Aabb;

/// A node: bounds, and two children (`count == 0`, left at `index`, right at `index + 1`) or a leaf
/// of the `count` items from `index` (in the order `MedianBvh::build` left them).
#[derive(Clone, Copy, Debug)]
pub struct Node {
    pub bounds: Aabb,
    pub index: u32,
    pub count: u32,
}

/// The nodes of the tree, root first (none for no items).
#[derive(Clone, Debug, Default)]
pub struct MedianBvh {
    pub nodes: Vec<Node>,
}

impl MedianBvh {
    /// The tree over `items`, reordered in place into leaf order: leaves of at most `leaf` items,
    /// each inner node split at the median of the items' `centre`s along the axis where they spread
    /// most. `bounds` gives the box of a run of items.
    pub fn build<T>(
        items: &mut [T],
        leaf: usize,
        bounds: impl Fn(&[T]) -> Aabb,
        centre: impl Fn(&T) -> Vec3,
    ) -> Self {
        let mut nodes = Vec::new();
        if !items.is_empty() {
            nodes.push(BLANK);
            let build = Build {
                leaf: leaf.max(1),
                bounds: &bounds,
                centre: &centre,
            };
            build.node(items, 0, 0, &mut nodes);
        }
        Self { nodes }
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

const BLANK: Node = Node {
    bounds: Aabb::EMPTY,
    index: 0,
    count: 0,
};

struct Build<'a, B, C> {
    leaf: usize,
    bounds: &'a B,
    centre: &'a C,
}

impl<B, C> Build<'_, B, C> {
    /// Builds node `at` over `items`, whose first item has index `base`.
    fn node<T>(&self, items: &mut [T], base: u32, at: usize, nodes: &mut Vec<Node>)
    where
        B: Fn(&[T]) -> Aabb,
        C: Fn(&T) -> Vec3,
    {
        let bounds = (self.bounds)(items);
        if items.len() <= self.leaf {
            nodes[at] = Node {
                bounds,
                index: base,
                count: items.len() as u32,
            };
            return;
        }
        let centre = self.centre;
        let axis = Aabb::from_points(items.iter().map(centre))
            .extent()
            .max_position();
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |a, b| centre(a)[axis].total_cmp(&centre(b)[axis]));
        let l = nodes.len();
        nodes.push(BLANK);
        nodes.push(BLANK);
        nodes[at] = Node {
            bounds,
            index: l as u32,
            count: 0,
        };
        let (left, right) = items.split_at_mut(mid);
        self.node(left, base, l, nodes);
        self.node(right, base + mid as u32, l + 1, nodes);
    }
}
