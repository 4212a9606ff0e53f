//! A bounding-volume hierarchy over triangle bounds, in `f64`.
//!
//! Built top-down by binned surface-area heuristic in `f64`, then stored for
//! queries as a flat array of inner nodes that each hold both children's
//! boxes, in `f32` rounded outward, and references (32 bytes a child, one
//! 64-byte cache line a node): a query reads one line per node it enters and
//! tests both children from it. A query returns every triangle whose box
//! overlaps the query box (closed intervals; the query box is rounded
//! outward too, so no overlap is lost), in a deterministic order.

use nalgebra::Vector3;

/// An axis-aligned box `[min, max]` (closed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vector3<f64>,
    /// Upper corner.
    pub max: Vector3<f64>,
}

impl Aabb {
    /// The empty box (grows from nothing).
    #[must_use]
    pub fn empty() -> Self {
        Aabb { min: Vector3::repeat(f64::INFINITY), max: Vector3::repeat(f64::NEG_INFINITY) }
    }

    /// Grows the box to contain `p`.
    pub fn grow(&mut self, p: &Vector3<f64>) {
        self.min = self.min.inf(p);
        self.max = self.max.sup(p);
    }

    /// Grows the box to contain `other`.
    pub fn merge(&mut self, other: &Aabb) {
        self.min = self.min.inf(&other.min);
        self.max = self.max.sup(&other.max);
    }

    /// `true` when the two closed boxes share a point.
    #[inline]
    #[must_use]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
            && self.min.z <= other.max.z
            && other.min.z <= self.max.z
    }

    /// Half the surface area (the SAH cost measure).
    #[must_use]
    pub fn half_area(&self) -> f64 {
        let d = self.max - self.min;
        if d.x < 0.0 { 0.0 } else { d.x * d.y + d.y * d.z + d.z * d.x }
    }

    /// The box centre.
    #[must_use]
    pub fn centre(&self) -> Vector3<f64> {
        (self.min + self.max) * 0.5
    }
}

/// A node of the tree while it is built.
#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: index of the first triangle in `order`; inner: the right child.
    index: u32,
    /// Leaf: number of triangles (> 0); inner: 0.
    count: u32,
}

/// A child as its parent stores it: its box in `f32`, rounded outward, and
/// either an inner node's index (`count == 0`) or a leaf's triangles
/// (`order[index..index + count]`).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Child {
    min: [f32; 3],
    max: [f32; 3],
    index: u32,
    count: u32,
}

impl Child {
    /// The box rounded outward to `f32` (infinities where it exceeds the
    /// `f32` range), with the given reference.
    #[inline]
    fn new(bounds: &Aabb, index: u32, count: u32) -> Self {
        let down = |x: f64| {
            let f = x as f32;
            if f64::from(f) > x { f.next_down() } else { f }
        };
        let up = |x: f64| {
            let f = x as f32;
            if f64::from(f) < x { f.next_up() } else { f }
        };
        Child { min: [0, 1, 2].map(|i| down(bounds.min[i])), max: [0, 1, 2].map(|i| up(bounds.max[i])), index, count }
    }

    /// `true` when the two closed boxes share a point.
    #[inline]
    fn overlaps(&self, other: &Child) -> bool {
        // Every comparison evaluated (no branch per axis).
        (0..3).fold(true, |all, i| all & (self.min[i] <= other.max[i]) & (other.min[i] <= self.max[i]))
    }
}

/// An ellipsoidal ball for [`Bvh::query`]: the points `q` with
/// `sum_i ((q_i - centre_i) scale_i)^2 <= radius^2` (in eSpace terms: the
/// centre, the inverse radii and the eSpace radius).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre.
    pub centre: Vector3<f64>,
    /// Per-axis scale (inverse radii).
    pub scale: Vector3<f64>,
    /// Radius, in scaled units.
    pub radius: f64,
}

impl Ball {
    /// Whether a node's box comes within the ball. Conservative: the scaled
    /// distance is computed in `f64` (relative error a few `u`) and compared
    /// with the radius grown by a relative `1e-9`; callers widen `radius`
    /// for any rounding of their own inputs.
    #[inline]
    fn meets(&self, c: &Child) -> bool {
        let distance_sq = (0..3).fold(0.0, |sum, i| {
            let excess = (f64::from(c.min[i]) - self.centre[i]).max(self.centre[i] - f64::from(c.max[i])).max(0.0);
            let x = excess * self.scale[i];
            sum + x * x
        });
        let r = self.radius * (1.0 + 1e-9);
        distance_sq <= r * r
    }
}

/// An inner node: both children, one cache line.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Inner {
    children: [Child; 2],
}

/// The hierarchy: the root, the inner nodes, and the triangle order its
/// leaves index into.
#[derive(Clone, Debug)]
pub struct Bvh {
    root: Child,
    inner: Vec<Inner>,
    order: Vec<u32>,
}

const LEAF_SIZE: usize = 4;
const BINS: usize = 12;
/// Below this depth splits follow the SAH; from it on, the object median,
/// which halves the count, so no path is longer than `SAH_DEPTH + 32`.
const SAH_DEPTH: usize = 60;
const MAX_DEPTH: usize = SAH_DEPTH + 34;

impl Bvh {
    /// Builds the hierarchy over the given triangle boxes (index = triangle
    /// index).
    #[must_use]
    pub fn build(boxes: &[Aabb]) -> Self {
        let mut tree = Tree {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1),
            order: (0..boxes.len() as u32).collect(),
        };
        if boxes.is_empty() {
            return Bvh { root: Child::new(&Aabb::empty(), 0, 0), inner: Vec::new(), order: tree.order };
        }
        let centres: Vec<Vector3<f64>> = boxes.iter().map(Aabb::centre).collect();
        tree.build_node(boxes, &centres, 0, boxes.len(), 0);
        let mut inner = Vec::with_capacity(tree.nodes.len() / 2);
        let root = tree.compile(0, &mut inner);
        Bvh { root, inner, order: tree.order }
    }

    /// Calls `visit` with every triangle whose box overlaps `query`, or,
    /// given a `ball`, only those in a leaf whose box also meets the ball
    /// (tested at the leaves only: on the inner nodes the box test alone
    /// is cheaper than what the ball would prune).
    pub fn query(&self, query: &Aabb, ball: Option<&Ball>, mut visit: impl FnMut(u32)) {
        let query = Child::new(query, 0, 0);
        if !self.root.overlaps(&query) {
            return;
        }
        let mut leaf = |child: &Child| {
            if ball.is_none_or(|b| b.meets(child)) {
                let first = child.index as usize;
                self.order[first..first + child.count as usize].iter().for_each(|&t| visit(t));
            }
        };
        if self.root.count > 0 {
            leaf(&self.root);
            return;
        }
        // Depth first, left to right (leaves come out in the order of
        // `order`, which keeps nearby triangles' indices mostly sorted);
        // only children that overlap go on the stack, as `2 node + side`
        // (at most one pending sibling per level, plus the two just pushed).
        let mut stack = [0u32; MAX_DEPTH + 2];
        let mut top = 0;
        let push_children = |node: u32, stack: &mut [u32], top: &mut usize| {
            for side in [1, 0] {
                if self.inner[node as usize].children[side as usize].overlaps(&query) {
                    stack[*top] = 2 * node + side;
                    *top += 1;
                }
            }
        };
        push_children(self.root.index, &mut stack, &mut top);
        while top > 0 {
            top -= 1;
            let id = stack[top];
            let child = &self.inner[(id / 2) as usize].children[(id % 2) as usize];
            if child.count > 0 {
                leaf(child);
            } else {
                push_children(child.index, &mut stack, &mut top);
            }
        }
    }

    /// Number of nodes, leaves included (for statistics).
    #[must_use]
    pub fn node_count(&self) -> usize {
        2 * self.inner.len() + 1
    }
}

/// The tree while it is built: nodes in depth-first order (the left child
/// follows its parent; the right child's index is stored).
struct Tree {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Tree {
    /// Stores node `id` and its subtree for queries: inner nodes appended
    /// to `inner`, the node itself returned as its parent's child.
    fn compile(&self, id: usize, inner: &mut Vec<Inner>) -> Child {
        let node = &self.nodes[id];
        if node.count > 0 {
            return Child::new(&node.bounds, node.index, node.count);
        }
        let slot = inner.len();
        let placeholder = Child::new(&Aabb::empty(), 0, 0);
        inner.push(Inner { children: [placeholder; 2] });
        let left = self.compile(id + 1, inner);
        let right = self.compile(node.index as usize, inner);
        inner[slot].children = [left, right];
        Child::new(&node.bounds, slot as u32, 0)
    }

    fn build_node(
        &mut self,
        boxes: &[Aabb],
        centres: &[Vector3<f64>],
        start: usize,
        end: usize,
        depth: usize,
    ) -> usize {
        let mut bounds = Aabb::empty();
        let mut cbounds = Aabb::empty();
        for &t in &self.order[start..end] {
            bounds.merge(&boxes[t as usize]);
            cbounds.grow(&centres[t as usize]);
        }
        let id = self.nodes.len();
        self.nodes.push(Node { bounds, index: start as u32, count: (end - start) as u32 });
        if end - start <= LEAF_SIZE {
            return id;
        }
        let mid = if depth < SAH_DEPTH { self.split(boxes, centres, &cbounds, start, end) } else { None };
        let mid = mid.unwrap_or_else(|| {
            let axis = (cbounds.max - cbounds.min).imax();
            let half = (end - start) / 2;
            self.order[start..end].select_nth_unstable_by(half, |&p, &q| {
                centres[p as usize][axis].total_cmp(&centres[q as usize][axis]).then(p.cmp(&q))
            });
            start + half
        });
        self.build_node(boxes, centres, start, mid, depth + 1);
        let right = self.build_node(boxes, centres, mid, end, depth + 1);
        self.nodes[id].index = right as u32;
        self.nodes[id].count = 0;
        id
    }

    /// Chooses a binned-SAH split and partitions `order[start..end]`;
    /// `None` when the centres do not spread along any axis or no bin
    /// boundary separates them (the caller splits at the median).
    fn split(
        &mut self,
        boxes: &[Aabb],
        centres: &[Vector3<f64>],
        cb: &Aabb,
        start: usize,
        end: usize,
    ) -> Option<usize> {
        let extent = cb.max - cb.min;
        let axis = extent.imax();
        let (lo, width) = (cb.min[axis], extent[axis]);
        if !(width > 0.0) {
            return None;
        }
        let bin_of = |t: u32| (((centres[t as usize][axis] - lo) / width * BINS as f64) as usize).min(BINS - 1);
        let mut bins = [(Aabb::empty(), 0usize); BINS];
        for &t in &self.order[start..end] {
            let b = &mut bins[bin_of(t)];
            b.0.merge(&boxes[t as usize]);
            b.1 += 1;
        }
        let mut best = (f64::INFINITY, 0);
        for split in 1..BINS {
            let (mut l, mut r) = (Aabb::empty(), Aabb::empty());
            let (mut nl, mut nr) = (0, 0);
            for (b, n) in &bins[..split] {
                l.merge(b);
                nl += n;
            }
            for (b, n) in &bins[split..] {
                r.merge(b);
                nr += n;
            }
            if nl == 0 || nr == 0 {
                continue;
            }
            let cost = l.half_area() * nl as f64 + r.half_area() * nr as f64;
            if cost < best.0 {
                best = (cost, split);
            }
        }
        if best.1 == 0 {
            return None;
        }
        let slice = &mut self.order[start..end];
        let mut i = 0;
        for j in 0..slice.len() {
            if bin_of(slice[j]) < best.1 {
                slice.swap(i, j);
                i += 1;
            }
        }
        Some(start + i)
    }
}
