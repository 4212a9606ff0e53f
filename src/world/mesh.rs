//! The validated mesh (`f64`) and its conversion into a backend.

use super::obj::{Ignored, parse_obj};
use super::{Aabb, ActiveFeatures, Adjacency, Ball, Bvh};
use crate::geom::{Triangle, Vec3, from_f64};
use crate::{Error, Real};
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A validated, indexed triangle mesh in `f64` with adjacency and a BVH.
///
/// Every triangle has finite coordinates and a non-zero area
/// ([`Triangle::validate`]). Invalid input triangles are either an error
/// ([`TriangleMesh::new`]) or skipped and listed in
/// [`TriangleMesh::skipped`] ([`TriangleMesh::new_skipping_invalid`] and the
/// OBJ loaders), never dropped silently; the kept ones are numbered afresh,
/// and [`TriangleMesh::input_index`] maps a kept triangle (a hit's
/// `triangle`, say) back to the input's numbering.
#[derive(Clone, Debug)]
pub struct TriangleMesh {
    vertices: Vec<Vector3<f64>>,
    triangles: Vec<[u32; 3]>,
    adjacency: Adjacency,
    active: Vec<ActiveFeatures>,
    bvh: Bvh,
    bounds: Aabb,
    skipped: Vec<Error>,
    ignored: Vec<Ignored>,
    /// Each triangle's index in the input it was built from
    /// ([`TriangleMesh::input_index`]).
    inputs: Vec<u32>,
    /// For a mesh read from OBJ text: the file, and the line of each input
    /// triangle (so that a later [`TriangleMesh::moved`] names the lines of
    /// the triangles it collapses).
    source: Option<Arc<Source>>,
    /// The cosine of the internal-edge angle its active features were
    /// classified with ([`TriangleMesh::with_internal_edge_angle`]).
    internal_cos: f64,
}

/// Where a mesh's triangles came from: an OBJ file and, per input
/// triangle, the line of its `f` statement.
#[derive(Debug)]
struct Source {
    path: PathBuf,
    lines: Vec<usize>,
}

/// Default largest angle between two triangles' normals for their shared
/// edge to count as internal (see `Adjacency::active_features`): 5 degrees.
pub const INTERNAL_EDGE_DEGREES: f64 = 5.0;

impl TriangleMesh {
    /// A mesh from vertex positions and triangles (indices into
    /// `vertices`), rejecting the first invalid triangle. Only the vertices
    /// of triangles are checked: one that no triangle uses is kept as given
    /// (in [`TriangleMesh::vertices`], NaN included) and never read by a
    /// query.
    ///
    /// # Errors
    /// [`Error::VertexIndexOutOfRange`], [`Error::NonFinite`],
    /// [`Error::DegenerateTriangle`] naming the first bad triangle, or
    /// [`Error::EmptyMesh`].
    pub fn new(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Self, Error> {
        let (mesh, mut skipped) = Self::build(vertices, triangles, None, None, Self::default_internal_cos());
        match (mesh, skipped.is_empty()) {
            (Some(mesh), true) => Ok(mesh),
            (None, true) => Err(Error::EmptyMesh),
            (_, false) => Err(skipped.swap_remove(0)),
        }
    }

    /// A mesh from vertex positions and triangles that leaves out invalid
    /// triangles and lists why in [`TriangleMesh::skipped`]. Vertices that
    /// no triangle uses are kept unchecked, as [`TriangleMesh::new`] keeps
    /// them.
    ///
    /// # Errors
    /// [`Error::EmptyMesh`] when no triangle is given,
    /// [`Error::NoValidTriangle`] when none is valid.
    pub fn new_skipping_invalid(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Self, Error> {
        let (mesh, skipped) = Self::build(vertices, triangles, None, None, Self::default_internal_cos());
        Self::with_skipped(mesh, skipped)
    }

    fn default_internal_cos() -> f64 {
        INTERNAL_EDGE_DEGREES.to_radians().cos()
    }

    /// The same triangles over the vertices `at` maps each vertex to (a
    /// scene moved far from the origin, say), validated again: a triangle
    /// the new coordinates collapse (their rounding can merge a small
    /// triangle's corners) is skipped and listed in
    /// [`TriangleMesh::skipped`], by its OBJ line for a mesh read from OBJ
    /// text, else by its index in the original input
    /// ([`TriangleMesh::input_index`], which the new mesh keeps too). The
    /// new mesh lists only what the move collapsed: neither this mesh's
    /// skipped triangles nor its ignored OBJ statements. Its internal edges
    /// follow this mesh's angle threshold.
    ///
    /// # Errors
    /// [`Error::NoValidTriangle`] when every triangle collapses.
    pub fn moved(&self, at: impl Fn(&Vector3<f64>) -> [f64; 3]) -> Result<Self, Error> {
        let vertices = self.vertices.iter().map(at).collect();
        let inputs = Some(self.inputs.clone());
        let (mesh, skipped) =
            Self::build(vertices, self.triangles.clone(), inputs, self.source.clone(), self.internal_cos);
        Self::with_skipped(mesh, skipped)
    }

    /// The mesh `build` gave, with its skipped triangles, or the error that
    /// says why there is none.
    fn with_skipped(mesh: Option<Self>, mut skipped: Vec<Error>) -> Result<Self, Error> {
        match mesh {
            Some(mut mesh) => {
                mesh.skipped = skipped;
                Ok(mesh)
            }
            None if skipped.is_empty() => Err(Error::EmptyMesh),
            None => Err(Error::NoValidTriangle { count: skipped.len(), first: Box::new(skipped.swap_remove(0)) }),
        }
    }

    /// Loads a Wavefront OBJ file; degenerate faces are skipped and listed
    /// in [`TriangleMesh::skipped`] with their line numbers.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be read, [`Error::Obj`] (with the
    /// line number) if it is malformed, not UTF-8 text or holds no face,
    /// [`Error::NoValidTriangle`] if no face is valid.
    pub fn from_obj_file(path: &Path) -> Result<Self, Error> {
        let bytes = std::fs::read(path).map_err(|e| Error::Io { path: path.to_path_buf(), message: e.to_string() })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let at = e.utf8_error().valid_up_to();
            let bytes = e.as_bytes();
            Error::Obj {
                path: path.to_path_buf(),
                line: super::obj::line_at_end(&bytes[..at]),
                message: format!("not UTF-8 text (byte {:#04x} at offset {at})", bytes[at]),
            }
        })?;
        Self::from_obj_str(&text, path)
    }

    /// Parses OBJ text (`path` only names it in errors); see
    /// [`TriangleMesh::from_obj_file`].
    ///
    /// # Errors
    /// As [`TriangleMesh::from_obj_file`].
    pub fn from_obj_str(text: &str, path: &Path) -> Result<Self, Error> {
        let obj = parse_obj(text, path)?;
        if obj.triangles.is_empty() {
            return Err(Error::Obj {
                path: path.to_path_buf(),
                line: obj.last_line,
                message: "end of file: no face (`f` statement), nothing to collide with".into(),
            });
        }
        let source = Arc::new(Source { path: path.to_path_buf(), lines: obj.lines });
        let (mesh, skipped) =
            Self::build(obj.vertices, obj.triangles, None, Some(source), Self::default_internal_cos());
        let mut mesh = Self::with_skipped(mesh, skipped)?;
        mesh.ignored = obj.ignored;
        Ok(mesh)
    }

    /// Validates and indexes; invalid triangles go to the returned list,
    /// by their input index (`inputs[k]` for `triangles[k]`, or `k`
    /// itself without `inputs`), or, given `source` (an OBJ file and each
    /// input triangle's line), as [`Error::Obj`] with their line. No mesh
    /// when no triangle is valid.
    fn build(
        vertices: Vec<[f64; 3]>,
        triangles: Vec<[u32; 3]>,
        inputs: Option<Vec<u32>>,
        source: Option<Arc<Source>>,
        internal_cos: f64,
    ) -> (Option<Self>, Vec<Error>) {
        let report = |index: usize, e: Error| match &source {
            Some(s) => Error::Obj { path: s.path.clone(), line: s.lines[index], message: e.to_string() },
            None => e,
        };
        let vertices: Vec<Vector3<f64>> = vertices.into_iter().map(Vector3::from).collect();
        let mut kept = Vec::with_capacity(triangles.len());
        let mut kept_inputs = Vec::with_capacity(triangles.len());
        let mut skipped = Vec::new();
        for (k, tri) in triangles.into_iter().enumerate() {
            let index = inputs.as_ref().map_or(k, |i| i[k] as usize);
            let checked = tri
                .iter()
                .find(|&&v| v as usize >= vertices.len())
                .map(|&v| Error::VertexIndexOutOfRange {
                    triangle: index,
                    vertex: v as usize,
                    vertex_count: vertices.len(),
                })
                .map_or_else(|| corners(&vertices, &tri).validate(index), Err);
            match checked {
                Ok(()) => {
                    kept.push(tri);
                    // Input counts fit `u32`, like the vertex indices.
                    kept_inputs.push(index as u32);
                }
                Err(e) => skipped.push(report(index, e)),
            }
        }
        if kept.is_empty() {
            return (None, skipped);
        }
        let boxes: Vec<Aabb> = kept
            .iter()
            .map(|t| {
                let mut b = Aabb::empty();
                t.iter().for_each(|&v| b.grow(&vertices[v as usize]));
                b
            })
            .collect();
        let mut bounds = Aabb::empty();
        boxes.iter().for_each(|b| bounds.merge(b));
        let adjacency = Adjacency::build(&vertices, &kept);
        let active = adjacency.active_features(&vertices, &kept, internal_cos);
        let mesh = TriangleMesh {
            adjacency,
            active,
            bvh: Bvh::build(&boxes),
            vertices,
            triangles: kept,
            bounds,
            skipped: Vec::new(),
            ignored: Vec::new(),
            inputs: kept_inputs,
            source,
            internal_cos,
        };
        (Some(mesh), skipped)
    }

    /// The vertex positions.
    #[must_use]
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The triangles as vertex indices.
    #[must_use]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Triangle `t` with its vertex positions.
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`] (an index
    /// that the mesh, its BVH or a hit gave is always in range).
    #[must_use]
    pub fn triangle(&self, t: u32) -> Triangle<f64> {
        corners(&self.vertices, &self.triangles[t as usize])
    }

    /// Number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// `true` if there are no triangles (never, for a constructed mesh).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Edge and vertex adjacency.
    #[must_use]
    pub fn adjacency(&self) -> &Adjacency {
        &self.adjacency
    }

    /// The active edges and vertices of triangle `t`.
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`] (an index
    /// that the mesh, its BVH or a hit gave is always in range).
    #[must_use]
    pub fn active(&self, t: u32) -> ActiveFeatures {
        self.active[t as usize]
    }

    /// The mesh with its internal edges recomputed for another angle
    /// threshold (degrees, in `[0, 180]`; the default is
    /// [`INTERNAL_EDGE_DEGREES`]). Zero makes internal only the edges whose
    /// two normals, as rounded, agree exactly: coplanar triangles whose
    /// normals round differently (a review found 130 of 1,000 shared edges
    /// of exactly coplanar integer quads) stay active; give a small angle to
    /// merge coplanar triangles.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an angle outside `[0, 180]` or NaN.
    pub fn with_internal_edge_angle(mut self, degrees: f64) -> Result<Self, Error> {
        if !(0.0..=180.0).contains(&degrees) {
            return Err(Error::InvalidArgument {
                what: "internal edge angle".into(),
                message: format!("must lie in [0, 180] degrees, got {}", crate::error::Num(degrees)),
            });
        }
        self.internal_cos = degrees.to_radians().cos();
        self.active = self.adjacency.active_features(&self.vertices, &self.triangles, self.internal_cos);
        Ok(self)
    }

    /// The bounding-volume hierarchy.
    #[must_use]
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The box around all triangles.
    #[must_use]
    pub fn bounds(&self) -> &Aabb {
        &self.bounds
    }

    /// The index of triangle `t` in the input the mesh was built from: the
    /// `triangles` given to [`TriangleMesh::new`] or
    /// [`TriangleMesh::new_skipping_invalid`], or an OBJ file's faces in
    /// order (a polygon counting one per triangle of its fan), the numbering
    /// [`TriangleMesh::skipped`] uses. The mesh numbers only the triangles it
    /// kept, so hits, [`TriangleMesh::triangle`] and
    /// [`TriangleMesh::active`] differ from the input's numbering from the
    /// first skipped triangle on; this maps them back (a moved mesh,
    /// [`TriangleMesh::moved`], keeps the original input's numbering).
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`].
    #[must_use]
    pub fn input_index(&self, t: u32) -> usize {
        self.inputs[t as usize] as usize
    }

    /// Triangle `t` as a user gave it: `FILE:LINE` of its `f` statement
    /// for a mesh read from OBJ text, `triangle N` (its input index, from
    /// 0) otherwise.
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`].
    #[must_use]
    pub fn input_name(&self, t: u32) -> String {
        let input = self.input_index(t);
        match &self.source {
            Some(s) => format!("{}:{}", s.path.display(), s.lines[input]),
            None => format!("triangle {input}"),
        }
    }

    /// The input triangles that were left out, each with the reason, by
    /// their index in the input ([`TriangleMesh::input_index`]).
    #[must_use]
    pub fn skipped(&self) -> &[Error] {
        &self.skipped
    }

    /// The statements of the OBJ file this mesh was read from that carry
    /// no collision geometry and were not used (empty for other meshes).
    #[must_use]
    pub fn ignored(&self) -> &[Ignored] {
        &self.ignored
    }

    /// What loading left out, as lines for a user: the skipped triangles
    /// (the first five, then a count) and the ignored OBJ statements, per
    /// keyword; `what` names the mesh. Empty when nothing was left out.
    #[must_use]
    pub fn load_notes(&self, what: &str) -> Vec<String> {
        let mut notes = Vec::new();
        if !self.skipped.is_empty() {
            notes.push(format!("warning: {} triangle(s) of {what} skipped:", self.skipped.len()));
            notes.extend(self.skipped.iter().take(5).map(|e| format!("  {e}")));
            if self.skipped.len() > 5 {
                notes.push(format!("  ... and {} more", self.skipped.len() - 5));
            }
        }
        if !self.ignored.is_empty() {
            let each: Vec<String> = self
                .ignored
                .iter()
                .map(|i| format!("{} `{}` (first on line {})", i.count, i.keyword, i.first_line))
                .collect();
            notes.push(format!("note: {what}: ignored, carrying no collision geometry: {}", each.join(", ")));
        }
        notes
    }
}

fn corners(vertices: &[Vector3<f64>], t: &[u32; 3]) -> Triangle<f64> {
    Triangle::new(vertices[t[0] as usize], vertices[t[1] as usize], vertices[t[2] as usize])
}

/// A mesh converted into backend `T`: the vertices rounded to nearest in `T`
/// and a shared handle to the `f64` mesh, its adjacency and BVH.
#[derive(Clone, Debug)]
pub struct World<T: Real> {
    mesh: Arc<TriangleMesh>,
    vertices: Vec<Vec3<T>>,
    /// The largest distance, per coordinate, between an `f64` vertex and
    /// its `T` rounding (rounded up): BVH queries widen by it.
    slack: f64,
}

impl<T: Real> World<T> {
    /// Converts `mesh` into backend `T` (each coordinate rounded to
    /// nearest).
    ///
    /// # Errors
    /// A vertex of a triangle with a coordinate beyond `T`'s range (above
    /// about `3.4e38` in `f32`): rounded to infinity, it would make every
    /// query meaningless. The first such triangle's is named: for a mesh
    /// read from OBJ text as [`Error::Obj`] with the file and its face's
    /// line, otherwise as [`Error::InvalidArgument`] with the vertex and
    /// the triangle's index in the input. Vertices that no triangle uses
    /// are not checked.
    pub fn new(mesh: Arc<TriangleMesh>) -> Result<Self, Error> {
        let vertices = mesh.vertices.iter().map(from_f64).collect();
        Self::with_vertices(mesh, vertices)
    }

    /// The world of `mesh` whose vertices, rounded into `T` by any route,
    /// are `vertices`: checks them as [`World::new`] does and measures the
    /// conversion slack against the mesh's own `f64` vertices.
    fn with_vertices(mesh: Arc<TriangleMesh>, vertices: Vec<Vec3<T>>) -> Result<Self, Error> {
        // Only the vertices of triangles matter (a file may list others).
        let overflows = |i: &u32| !vertices[*i as usize].iter().all(Real::is_finite);
        let first =
            mesh.triangles.iter().enumerate().find_map(|(t, tri)| tri.iter().find(|i| overflows(i)).map(|&i| (t, i)));
        if let Some((t, i)) = first {
            let v = mesh.vertices[i as usize];
            let message = format!("({:e}, {:e}, {:e}) overflows this precision", v.x, v.y, v.z);
            let input = mesh.input_index(t as u32);
            return Err(match &mesh.source {
                Some(s) => Error::Obj {
                    path: s.path.clone(),
                    line: s.lines[input],
                    message: format!("this face's vertex {} (its `v` statement, counted from 1) {message}", i + 1),
                },
                None => {
                    Error::InvalidArgument { what: format!("vertex {i} (counted from 0) of triangle {input}"), message }
                }
            });
        }
        let mut used = vec![false; vertices.len()];
        mesh.triangles.iter().flatten().for_each(|&i| used[i as usize] = true);
        let used = || (0..vertices.len()).filter(|&i| used[i]);
        let (given, rounded) = (&mesh.vertices, &vertices);
        let slack =
            used().flat_map(|i| (0..3).map(move |k| (rounded[i][k].to_f64() - given[i][k]).abs())).fold(0.0, f64::max);
        let slack = if slack > 0.0 { (slack * (1.0 + 4.0 * f64::EPSILON)).next_up() } else { 0.0 };
        Ok(World { mesh, vertices, slack })
    }

    /// The triangles (mesh indices, ascending) that are degenerate once
    /// their vertices are rounded into `T` (zero area or collinear, as
    /// [`TriangleMesh::new`] judges them, from the rounded values): they
    /// still collide, as the segments or points they became, but no longer
    /// as the triangles the mesh gave. [`TriangleMesh::input_name`] names
    /// each for a user.
    #[must_use]
    pub fn degenerate_in_backend(&self) -> Vec<u32> {
        // Without conversion slack every vertex is the mesh's own, and the
        // mesh keeps only valid triangles (every `f64` and wider run).
        if self.slack == 0.0 {
            return Vec::new();
        }
        let rounded = |i: u32| self.vertices[i as usize].map(|x| x.to_f64());
        let triangles = self.mesh.triangles.iter().enumerate();
        triangles
            .filter(|(k, t)| Triangle::new(rounded(t[0]), rounded(t[1]), rounded(t[2])).validate(*k).is_err())
            .map(|(k, _)| k as u32)
            .collect()
    }

    /// The same world in another backend `U`, converted from this world's
    /// stored values (through MPFR, exactly when `U` has at least as many
    /// bits), so `U` sees the very numbers `T` computed with. The
    /// conversion slack is measured again: a narrower `U` rounds the
    /// vertices further from the `f64` ones the BVH's boxes hold (keeping
    /// `T`'s slack, a review found box queries in `Mpfr<11>` missing
    /// triangles).
    ///
    /// # Errors
    /// As [`World::new`], when a vertex overflows `U`.
    #[cfg(feature = "mpfr")]
    pub fn converted<U: Real>(&self) -> Result<World<U>, Error> {
        let vertices = self.vertices.iter().map(|v| v.map(|x| U::from_rug(&x.to_rug()))).collect();
        World::with_vertices(self.mesh.clone(), vertices)
    }

    /// The `f64` mesh this world was made from.
    #[must_use]
    pub fn mesh(&self) -> &TriangleMesh {
        &self.mesh
    }

    /// The shared handle to the mesh.
    #[must_use]
    pub fn mesh_arc(&self) -> &Arc<TriangleMesh> {
        &self.mesh
    }

    /// Triangle `t` in backend `T`.
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`] (an index
    /// that the mesh, its BVH or a hit gave is always in range).
    #[must_use]
    pub fn triangle(&self, t: u32) -> Triangle<T> {
        let [a, b, c] = self.corners(t).map(Clone::clone);
        Triangle::new(a, b, c)
    }

    /// The corners of triangle `t` in backend `T`, borrowed.
    ///
    /// # Panics
    /// If `t` is not below the mesh's [`TriangleMesh::len`] (an index
    /// that the mesh, its BVH or a hit gave is always in range).
    #[must_use]
    pub fn corners(&self, t: u32) -> [&Vec3<T>; 3] {
        self.mesh.triangles[t as usize].map(|i| &self.vertices[i as usize])
    }

    /// Replaces `out` with every triangle whose bounds overlap the box
    /// `[min, max]` (in `T`), in a deterministic order. Never misses a
    /// triangle of this world that meets the box: the box is rounded
    /// outward into `f64` and widened by the conversion slack.
    pub fn candidates(&self, min: &Vec3<T>, max: &Vec3<T>, out: &mut Vec<u32>) {
        out.clear();
        self.each_candidate(min, max, None, |t| out.push(t));
    }

    /// [`World::candidates`] for a box given in `f64` (rounded outward from
    /// the caller's own values, which a box computed in `T` cannot be:
    /// `T`'s subtraction rounds to nearest), widened by the conversion
    /// slack.
    pub fn candidates_f64(&self, min: &Vector3<f64>, max: &Vector3<f64>, out: &mut Vec<u32>) {
        out.clear();
        self.mesh.bvh.query(&self.widened(min, max), None, |t| out.push(t));
    }

    /// The box `[min, max]` widened by the conversion slack and rounded
    /// outward.
    fn widened(&self, min: &Vector3<f64>, max: &Vector3<f64>) -> Aabb {
        Aabb { min: min.map(|x| (x - self.slack).next_down()), max: max.map(|x| (x + self.slack).next_up()) }
    }

    /// Calls `visit` with each triangle [`World::candidates`] would return,
    /// in the same order, without collecting them; given a `ball` (centre,
    /// per-axis radii, and a radius in units of those radii: an eSpace ball),
    /// only those of the BVH's leaves that also come within it. Never misses
    /// a triangle that meets both: the ball is widened by the conversion
    /// slack and the rounding of its centre to `f64`, both per coordinate,
    /// so by their sum times the length of the scale vector (`sqrt(3)`
    /// times the largest scale for a sphere; the largest scale alone let a
    /// vertex within reach escape in `Mpfr<8>`, whose slack no `f32` leaf
    /// box hides: a review).
    pub fn each_candidate(
        &self,
        min: &Vec3<T>,
        max: &Vec3<T>,
        ball: Option<(&Vec3<T>, &Vec3<T>, &T)>,
        visit: impl FnMut(u32),
    ) {
        let to_f64 = |v: &Vec3<T>| Vector3::from_fn(|i, _| v[i].to_f64());
        let bounds = self.widened(&to_f64(min), &to_f64(max));
        let ball = ball.map(|(centre, radii, radius)| {
            let centre = Vector3::from_fn(|i, _| centre[i].to_f64());
            let scale = Vector3::from_fn(|i, _| 1.0 / radii[i].to_f64());
            let off = self.slack + centre.amax() * f64::EPSILON;
            // `sqrt(3)` times the largest scale bounds the scale vector's
            // length without squaring it: a radius below about `1e-154`
            // overflowed the norm, and `0 * inf` made the ball NaN and
            // empty (a review). Zero `off` adds nothing.
            let widen = if off > 0.0 { off * (scale.amax() * 3f64.sqrt()) } else { 0.0 };
            Ball { centre, scale, radius: radius.to_f64() + widen }
        });
        self.mesh.bvh.query(&bounds, ball.as_ref(), visit);
    }
}
