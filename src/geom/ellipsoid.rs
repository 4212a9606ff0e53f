//! The axis-aligned ellipsoid body and its map into eSpace.

use super::Vec3;
use crate::{Error, Real};
use nalgebra::Vector3;

/// An axis-aligned ellipsoid with radii `(rx, ry, rz)`; a sphere when all
/// three are equal.
///
/// Dividing coordinates by the radii ("eSpace", Fauerby's term) turns the
/// ellipsoid into the unit sphere, so detection and response only ever
/// deal with a unit sphere. The map rounds once per coordinate (exact when
/// the radii are powers of two).
#[derive(Clone, Debug, PartialEq)]
pub struct Ellipsoid<T: Real> {
    radii: Vec3<T>,
}

impl<T: Real> Ellipsoid<T> {
    /// An ellipsoid with the given radii.
    ///
    /// # Errors
    /// [`Error::InvalidRadius`] when a radius is zero, negative, NaN or
    /// infinite, or does not survive the conversion to `T` as a positive
    /// finite value.
    pub fn new(radii: [f64; 3]) -> Result<Self, Error> {
        for (axis, r) in ['x', 'y', 'z'].into_iter().zip(radii) {
            let rt = T::from_f64(r);
            if !(r > 0.0 && r.is_finite() && rt > T::zero() && rt.is_finite()) {
                return Err(Error::InvalidRadius { axis, value: r });
            }
        }
        Ok(Ellipsoid { radii: Vector3::new(T::from_f64(radii[0]), T::from_f64(radii[1]), T::from_f64(radii[2])) })
    }

    /// An ellipsoid with radii already in backend `T`.
    ///
    /// # Errors
    /// [`Error::InvalidRadius`] when a radius is not positive and finite.
    pub fn from_radii(radii: Vec3<T>) -> Result<Self, Error> {
        for (axis, r) in ['x', 'y', 'z'].into_iter().zip(radii.iter()) {
            if !(*r > T::zero() && r.is_finite()) {
                return Err(Error::InvalidRadius { axis, value: r.to_f64() });
            }
        }
        Ok(Ellipsoid { radii })
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

    /// World space to eSpace: divides each coordinate by its radius.
    #[inline]
    #[must_use]
    pub fn to_espace(&self, p: &Vec3<T>) -> Vec3<T> {
        Vector3::new(p.x.clone() / &self.radii.x, p.y.clone() / &self.radii.y, p.z.clone() / &self.radii.z)
    }

    /// eSpace to world space: multiplies each coordinate by its radius.
    #[inline]
    #[must_use]
    pub fn from_espace(&self, p: &Vec3<T>) -> Vec3<T> {
        Vector3::new(p.x.clone() * &self.radii.x, p.y.clone() * &self.radii.y, p.z.clone() * &self.radii.z)
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
