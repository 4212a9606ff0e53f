//! The static world: a validated triangle mesh with edge adjacency and a
//! bounding-volume hierarchy, and its conversion into a backend.
//!
//! The mesh is stored once in `f64` ([`TriangleMesh`]); a [`World<T>`]
//! holds the same vertices rounded into backend `T` plus a shared handle to
//! the mesh, its adjacency and its BVH. The BVH works in `f64`; queries
//! widen their box by the largest rounding distance between the `f64` and
//! the `T` vertices, so no backend ever misses a candidate.

mod adjacency;
mod bvh;
mod mesh;
mod obj;

pub use adjacency::{ActiveFeatures, Adjacency};
pub use bvh::{Aabb, Ball, Bvh};
pub use mesh::{INTERNAL_EDGE_DEGREES, TriangleMesh, World};
pub use obj::{Ignored, parse_obj};
