//! A bounding-volume hierarchy over triangle bounds, in `f64`.
//!
//! Built top-down by binned surface-area heuristic, stored as a flat array
//! (left child follows its parent; the right child's index is stored). A
//! query returns every triangle whose box overlaps the query box (closed
//! intervals), in a deterministic order.

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

#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: index of the first triangle in `order`; inner: the right child.
    index: u32,
    /// Leaf: number of triangles (> 0); inner: 0.
    count: u32,
}

/// The hierarchy: nodes plus the triangle order its leaves index into.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
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
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1),
            order: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            let centres: Vec<Vector3<f64>> = boxes.iter().map(Aabb::centre).collect();
            bvh.build_node(boxes, &centres, 0, boxes.len(), 0);
        }
        bvh
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

    /// Calls `visit` with every triangle whose box overlaps `query`.
    pub fn query(&self, query: &Aabb, mut visit: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        if !self.nodes[0].bounds.overlaps(query) {
            return;
        }
        // Only nodes that overlap the query are pushed: each child is tested
        // before it goes on the stack.
        let mut stack = [0u32; MAX_DEPTH + 2];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let id = stack[top];
            let node = &self.nodes[id as usize];
            if node.count > 0 {
                let first = node.index as usize;
                self.order[first..first + node.count as usize].iter().for_each(|&t| visit(t));
            } else {
                // Left child directly follows its parent; the right one is
                // pushed first so the left is visited first, as before.
                for child in [node.index, id + 1] {
                    if self.nodes[child as usize].bounds.overlaps(query) {
                        stack[top] = child;
                        top += 1;
                    }
                }
            }
        }
    }

    /// Number of nodes (for statistics).
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}
