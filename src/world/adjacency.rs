//! Edge and vertex adjacency, for telling internal edges from real ones.
//!
//! Vertices are welded by exact position first, so a soup that repeats a
//! vertex instead of sharing its index still gets its adjacency.

use nalgebra::Vector3;
use std::collections::HashMap;

/// Which features of a triangle are *active*, i.e. real edges and corners
/// of the surface, as opposed to internal edges and vertices of a flat or
/// gently convex tessellation (Jolt's "active edges"). A contact on an
/// inactive feature takes the face normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ActiveFeatures(u8);

impl ActiveFeatures {
    /// Every edge and vertex active (a lone triangle).
    pub const ALL: ActiveFeatures = ActiveFeatures(0b11_1111);

    /// Whether edge `i` (from vertex `i` to `i + 1`) is active.
    #[must_use]
    pub fn edge(self, i: u8) -> bool {
        self.0 & (1 << (i % 3)) != 0
    }

    /// Whether vertex `i` is active.
    #[must_use]
    pub fn vertex(self, i: u8) -> bool {
        self.0 & (8 << (i % 3)) != 0
    }
}

/// Which triangles meet at each edge and vertex.
#[derive(Clone, Debug, Default)]
pub struct Adjacency {
    /// `neighbours[t][i]`: the one other triangle sharing edge `i` of
    /// triangle `t`, or `None` on a boundary or non-manifold edge.
    neighbours: Vec<[Option<u32>; 3]>,
    /// Triangles around each welded vertex, as offsets into `around`.
    offsets: Vec<u32>,
    around: Vec<u32>,
    /// Welded vertex id of each input vertex.
    weld: Vec<u32>,
}

impl Adjacency {
    /// Computes the adjacency of the given triangles over `vertices`
    /// (crate-internal: the indices must be valid, as [`super::TriangleMesh`]
    /// makes sure).
    #[must_use]
    pub(crate) fn build(vertices: &[Vector3<f64>], triangles: &[[u32; 3]]) -> Self {
        let mut ids: HashMap<[u64; 3], u32> = HashMap::with_capacity(vertices.len());
        let weld: Vec<u32> = vertices
            .iter()
            .map(|v| {
                // +0.0 and -0.0 are the same point.
                let key = [v.x + 0.0, v.y + 0.0, v.z + 0.0].map(f64::to_bits);
                let next = ids.len() as u32;
                *ids.entry(key).or_insert(next)
            })
            .collect();
        let welded = |t: &[u32; 3]| t.map(|i| weld[i as usize]);
        let mut edges: HashMap<(u32, u32), Vec<(u32, u8)>> = HashMap::with_capacity(triangles.len() * 2);
        for (t, tri) in triangles.iter().enumerate() {
            let w = welded(tri);
            for i in 0..3 {
                let (p, q) = (w[i], w[(i + 1) % 3]);
                edges.entry((p.min(q), p.max(q))).or_default().push((t as u32, i as u8));
            }
        }
        let mut neighbours = vec![[None; 3]; triangles.len()];
        for sharing in edges.values() {
            if let [(t0, e0), (t1, e1)] = sharing[..] {
                neighbours[t0 as usize][e0 as usize] = Some(t1);
                neighbours[t1 as usize][e1 as usize] = Some(t0);
            }
        }
        let mut counts = vec![0u32; ids.len() + 1];
        for tri in triangles {
            for v in welded(tri) {
                counts[v as usize + 1] += 1;
            }
        }
        for i in 1..counts.len() {
            counts[i] += counts[i - 1];
        }
        let offsets = counts.clone();
        let mut around = vec![0u32; *counts.last().unwrap_or(&0) as usize];
        for (t, tri) in triangles.iter().enumerate() {
            for v in welded(tri) {
                around[counts[v as usize] as usize] = t as u32;
                counts[v as usize] += 1;
            }
        }
        Adjacency { neighbours, offsets, around, weld }
    }

    /// The triangle on the other side of edge `edge` of `triangle`, if the
    /// edge is shared by exactly two triangles.
    ///
    /// # Panics
    /// If `triangle` is not a triangle of the mesh. `edge` is taken modulo
    /// 3, as [`ActiveFeatures::edge`] takes it.
    #[must_use]
    pub fn neighbour(&self, triangle: u32, edge: u8) -> Option<u32> {
        self.neighbours[triangle as usize][edge as usize % 3]
    }

    /// The active features of every triangle. Edge `i` of `t` is inactive
    /// when exactly one other triangle shares it and the two are nearly
    /// coplanar (the cosine between their consistently oriented normals is at
    /// least `cos_min`); a sharper fold is active, whichever side it is
    /// concave from (the triangles are solid on both sides, and a concave
    /// edge is a ridge from behind). A vertex is inactive when every triangle
    /// around it is nearly coplanar with `t` (`|cos| >= cos_min`) and every
    /// edge at it, of every triangle around it, is inactive: a vertex that
    /// ends a border of the surface, or a fold, is a real corner even where
    /// the triangles around it are (anti)parallel (a sphere beside a floor's
    /// corner, in its plane, touches it there).
    ///
    /// Cost: each corner of each triangle compares its normal with those of
    /// every triangle around that vertex (one dot product each), so a
    /// vertex shared by `d` triangles costs `d^2` dot products: a mesh's
    /// load time grows with the square of its largest vertex degree
    /// (a disc of 40,000 triangles around one vertex: about 2 s of CPU).
    /// Whether a vertex ends an active edge is found once per vertex, so
    /// a polygon triangulated as a fan, whose centre ends the border, loads
    /// in linear time. Tessellated surfaces have degrees of 6 to 8.
    /// (Crate-internal: `vertices` and `triangles` must be those the
    /// adjacency was built from; [`super::TriangleMesh::with_internal_edge_angle`]
    /// is the public way to choose `cos_min`.)
    #[must_use]
    pub(crate) fn active_features(
        &self,
        vertices: &[Vector3<f64>],
        triangles: &[[u32; 3]],
        cos_min: f64,
    ) -> Vec<ActiveFeatures> {
        let normals: Vec<Vector3<f64>> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| vertices[i as usize]);
                // Scaled exactly by a power of two first: the cross
                // product's square overflowed beyond sides of about 1e77
                // and underflowed below 1e-81, which turned internal edges
                // active and, near the underflow, convex folds inactive (a
                // review).
                let (ab, ac) = (b - a, c - a);
                let scale = crate::geom::unit_scale(ab.amax().max(ac.amax()));
                (ab * scale).cross(&(ac * scale)).normalize()
            })
            .collect();
        let normal = |t: usize| normals[t];
        let welded = |t: usize| triangles[t].map(|i| self.weld[i as usize]);
        let edge_bits: Vec<u8> = (0..triangles.len())
            .map(|t| {
                let n = normal(t);
                let w = welded(t);
                let mut bits = 0u8;
                for e in 0..3 {
                    let Some(nb) = self.neighbours[t][e] else {
                        bits |= 1 << e;
                        continue;
                    };
                    let wn = welded(nb as usize);
                    // Consistent winding runs the shared edge the other way.
                    let (p, q) = (w[e], w[(e + 1) % 3]);
                    let same_way = (0..3).any(|k| wn[k] == p && wn[(k + 1) % 3] == q);
                    let m = if same_way { -normal(nb as usize) } else { normal(nb as usize) };
                    // A fold beyond the angle is a real edge, convex or
                    // concave: seen from the front a sphere meets a concave
                    // edge only through a face, but the triangles are solid
                    // on both sides, and from the back the same edge is a
                    // ridge (kept internal there, it gave the face normal
                    // and stopped bodies on the ridge: a review).
                    if !(n.dot(&m) >= cos_min) {
                        bits |= 1 << e;
                    }
                }
                bits
            })
            .collect();
        // An active edge (a border, a crease, a fold) at a vertex makes it a
        // real corner.
        let ends_active_edge = |corner: u32, around: &[u32]| {
            let w = self.weld[corner as usize];
            around.iter().any(|&o| {
                let wo = welded(o as usize);
                (0..3).any(|e| (wo[e] == w || wo[(e + 1) % 3] == w) && edge_bits[o as usize] & (1 << e) != 0)
            })
        };
        // Whether a vertex ends an active edge, per welded vertex, found once.
        let mut ends_active: Vec<Option<bool>> = vec![None; vertices.len()];
        (0..triangles.len())
            .map(|t| {
                let n = normal(t);
                let mut bits = edge_bits[t];
                for (v, &corner) in triangles[t].iter().enumerate() {
                    let around = self.triangles_around(corner);
                    let corner_of_edge = *ends_active[self.weld[corner as usize] as usize]
                        .get_or_insert_with(|| ends_active_edge(corner, around));
                    if corner_of_edge || !around.iter().all(|&o| n.dot(&normal(o as usize)).abs() >= cos_min) {
                        bits |= 8 << v;
                    }
                }
                ActiveFeatures(bits)
            })
            .collect()
    }

    /// Every triangle that has the (welded) vertex `vertex` as a corner, in
    /// increasing order.
    ///
    /// # Panics
    /// If `vertex` is not a vertex of the mesh.
    #[must_use]
    pub fn triangles_around(&self, vertex: u32) -> &[u32] {
        let w = self.weld[vertex as usize] as usize;
        &self.around[self.offsets[w] as usize..self.offsets[w + 1] as usize]
    }
}
