//! Geometry shared by every stage: vector helpers, planes, triangles and the
//! ellipsoid's map into the unit-sphere space ("eSpace").
//!
//! Everything here is generic over [`Real`](crate::Real) and performs its
//! operations in a fixed, documented order, so `Mpfr<24>` and `f32` (and
//! `Mpfr<53>` and `f64`) produce the same bits.

mod ellipsoid;
mod plane;
mod triangle;
mod vec;

pub use ellipsoid::Ellipsoid;
pub use plane::Plane;
pub use triangle::{Feature, Triangle, closest_point_on_triangle};
pub(crate) use triangle::{closest_point_on_sides, unit_scale};
pub use vec::{
    Vec3, cross, cross_of_edges, dot, from_f64, is_finite, max_abs, norm, norm_squared, normalize, normalize_near_unit,
    to_f64, vec3,
};
