//! Planes in Hessian normal form.

use super::{Triangle, Vec3, cross, dot, normalize};
use crate::Real;

/// The plane `{x : normal . x + constant = 0}` with a unit `normal`.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane<T: Real> {
    /// Unit normal (the side it points to is the positive side).
    pub normal: Vec3<T>,
    /// `-normal . origin` for any point `origin` of the plane.
    pub constant: T,
}

impl<T: Real> Plane<T> {
    /// The plane through `origin` with the given unit `normal` (not
    /// re-normalised: pass a unit vector).
    #[inline]
    #[must_use]
    pub fn from_point_normal(origin: &Vec3<T>, normal: Vec3<T>) -> Self {
        let constant = -dot(&normal, origin);
        Plane { normal, constant }
    }

    /// The plane of a triangle, normal `normalize((b - a) x (c - a))`
    /// (counter-clockwise front face), through vertex `a`, as Fauerby builds
    /// it. `None` when the triangle is degenerate in this precision.
    #[inline]
    #[must_use]
    pub fn from_triangle(tri: &Triangle<T>) -> Option<Self> {
        let n = normalize(&tri.unnormalized_normal())?;
        Some(Self::from_point_normal(&tri.a, n))
    }

    /// Signed distance `normal . p + constant` (positive on the normal's
    /// side). Rounding: the constant carries an error proportional to the
    /// magnitude of the origin it was built from; prefer relative
    /// coordinates for points far from the origin.
    #[inline]
    #[must_use]
    pub fn signed_distance(&self, p: &Vec3<T>) -> T {
        dot(&self.normal, p) + &self.constant
    }

    /// The cross product of two plane normals (the crease direction,
    /// unnormalised; its length is the sine of the angle between them).
    #[must_use]
    pub fn crease(&self, other: &Self) -> Vec3<T> {
        cross(&self.normal, &other.normal)
    }
}
