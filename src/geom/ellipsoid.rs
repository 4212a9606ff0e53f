//! The axis-aligned ellipsoid body and its map into eSpace.

use super::{Vec3, normalize};
use crate::{Error, Real};
use nalgebra::Vector3;

/// An axis-aligned ellipsoid with radii `(rx, ry, rz)`; a sphere when all
/// three are equal.
///
/// Dividing coordinates by the radii ("eSpace", Fauerby's term) turns the
/// ellipsoid into the unit sphere, so detection and response only ever
/// deal with a unit sphere. The map multiplies by the rounded inverse radii
/// (a product is several times cheaper than a quotient, and a frame maps
/// dozens of vertices): each coordinate carries a relative error of at most
/// `2u` (the inverse's rounding and the product's), exact when the radii are
/// powers of two, for radii whose inverse is a normal number of `T`
/// (below about `8.5e37` in `f32`, `4.5e307` in `f64`): a larger radius
/// has a subnormal inverse, rounded more coarsely (about `3u` for an `f64`
/// radius of `1.5e308`, a review found).
#[derive(Clone, Debug, PartialEq)]
pub struct Ellipsoid<T: Real> {
    radii: Vec3<T>,
    /// `1 / radii`, rounded.
    inverse: Vec3<T>,
}

impl<T: Real> Ellipsoid<T> {
    /// An ellipsoid with the given radii.
    ///
    /// # Errors
    /// [`Error::InvalidRadius`] when a radius is zero, negative, NaN or
    /// infinite, or does not survive the conversion to `T` as a positive
    /// finite value with a finite inverse (in `T` and in `f64`: a normal
    /// `f64`, from about `2.2e-308` to `1.8e308`).
    pub fn new(radii: [f64; 3]) -> Result<Self, Error> {
        let converted = Vector3::new(T::from_f64(radii[0]), T::from_f64(radii[1]), T::from_f64(radii[2]));
        for ((axis, r), rt) in ['x', 'y', 'z'].into_iter().zip(radii).zip(converted.iter()) {
            if !(r > 0.0 && r.is_finite() && usable(rt)) {
                return Err(Error::InvalidRadius { axis, value: r });
            }
        }
        Ok(Self::checked(converted))
    }

    /// An ellipsoid with radii already in backend `T`.
    ///
    /// # Errors
    /// [`Error::InvalidRadius`] when a radius is not positive and finite, or
    /// so small that its inverse overflows (in `T` or in `f64`: an MPFR
    /// radius must also lie within `f64`'s normal range, about `2.2e-308`
    /// to `1.8e308`, as [`Ellipsoid::new`]).
    pub fn from_radii(radii: Vec3<T>) -> Result<Self, Error> {
        for (axis, r) in ['x', 'y', 'z'].into_iter().zip(radii.iter()) {
            if !usable(r) {
                return Err(Error::InvalidRadius { axis, value: r.to_f64() });
            }
        }
        Ok(Self::checked(radii))
    }

    /// The ellipsoid of radii already found [`usable`].
    fn checked(radii: Vec3<T>) -> Self {
        let inverse = radii.map(|r| T::one() / &r);
        Ellipsoid { radii, inverse }
    }

    /// A sphere of radius `r`.
    ///
    /// # Errors
    /// As [`Ellipsoid::new`].
    pub fn sphere(r: f64) -> Result<Self, Error> {
        Self::new([r, r, r])
    }

    /// The three radii.
    #[must_use]
    pub fn radii(&self) -> &Vec3<T> {
        &self.radii
    }

    /// `true` when all radii are equal.
    #[must_use]
    pub fn is_sphere(&self) -> bool {
        self.radii.x == self.radii.y && self.radii.y == self.radii.z
    }

    /// World space to eSpace: multiplies each coordinate by its rounded
    /// inverse radius (the division by the radius up to `2u` relative).
    #[inline]
    #[must_use]
    pub fn to_espace(&self, p: &Vec3<T>) -> Vec3<T> {
        Vector3::new(p.x.clone() * &self.inverse.x, p.y.clone() * &self.inverse.y, p.z.clone() * &self.inverse.z)
    }

    /// eSpace to world space: multiplies each coordinate by its radius.
    #[inline]
    #[must_use]
    pub fn from_espace(&self, p: &Vec3<T>) -> Vec3<T> {
        Vector3::new(p.x.clone() * &self.radii.x, p.y.clone() * &self.radii.y, p.z.clone() * &self.radii.z)
    }

    /// A unit surface normal in eSpace (a contact's, as a move's
    /// [`crate::respond::Trace`] reports it) as the unit normal of the same
    /// surface in world space: each coordinate divided by its radius, then
    /// normalised (a normal maps by the inverse transpose of the point
    /// map). For a flat ellipsoid the two differ much: on a 20-degree ramp
    /// a `(0.4, 0.9, 0.4)` body's eSpace normal leans 9 degrees from the
    /// vertical, its world normal 20. `n` itself where the result would not
    /// be finite (a zero `n`).
    #[must_use]
    pub fn normal_from_espace(&self, n: &Vec3<T>) -> Vec3<T> {
        normalize(&Vec3::from_fn(|i, _| n[i].clone() / &self.radii[i])).unwrap_or_else(|| n.clone())
    }

    /// The smallest radius.
    #[must_use]
    pub fn min_radius(&self) -> T {
        self.radii.x.clone().min(self.radii.y.clone()).min(self.radii.z.clone())
    }

    /// The largest radius.
    #[must_use]
    pub fn max_radius(&self) -> T {
        self.radii.x.clone().max(self.radii.y.clone()).max(self.radii.z.clone())
    }
}

/// A radius the eSpace map can use: positive, finite, with a finite
/// inverse, in `T` and as an `f64` too, since the world's BVH measures the
/// eSpace reach in `f64` ([`crate::world::World::each_candidate`]): an MPFR
/// radius below about `5.6e-309` has an `f64` inverse of infinity, which
/// made every ball query empty and every wall missed (found by a review);
/// the radius must be a normal `f64` (at least about `2.2e-308`).
fn usable<T: Real>(r: &T) -> bool {
    let f = r.to_f64();
    *r > T::zero() && r.is_finite() && (T::one() / r).is_finite() && f.is_normal() && (1.0 / f).is_finite()
}
