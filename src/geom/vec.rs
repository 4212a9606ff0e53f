//! Vector helpers on `nalgebra::Vector3<T>` for every [`Real`] backend.
//!
//! nalgebra's own `norm`/`normalize` need simba's `ComplexField`, which MPFR
//! values do not implement; these helpers are built on [`dot`] and
//! [`Real::sqrt`] instead, with one fixed evaluation order:
//! `dot(a, b) = (a.x*b.x + a.y*b.y) + a.z*b.z`, each operation rounded once.

use crate::Real;
use nalgebra::Vector3;

/// A 3-vector of any backend.
pub type Vec3<T> = Vector3<T>;

/// A vector built from `f64` components (rounded to nearest in `T`).
#[must_use]
pub fn vec3<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vector3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

/// Converts an `f64` vector into backend `T` (rounding each component to
/// nearest; exact where representable).
#[must_use]
pub fn from_f64<T: Real>(v: &Vector3<f64>) -> Vec3<T> {
    vec3(v.x, v.y, v.z)
}

/// Converts a vector of backend `T` to `f64` (rounding to nearest).
#[must_use]
pub fn to_f64<T: Real>(v: &Vec3<T>) -> Vector3<f64> {
    Vector3::new(v.x.to_f64(), v.y.to_f64(), v.z.to_f64())
}

/// Dot product, evaluated as `(a.x*b.x + a.y*b.y) + a.z*b.z`. Its rounding
/// error is at most `3u * sum |a_i b_i|` (`u` the unit roundoff).
#[inline]
#[must_use]
pub fn dot<T: Real>(a: &Vec3<T>, b: &Vec3<T>) -> T {
    a.x.clone() * &b.x + a.y.clone() * &b.y + a.z.clone() * &b.z
}

/// Cross product `a x b`, each component `a_i*b_j - a_j*b_i` with three
/// roundings (error at most `2u * (|a_i b_j| + |a_j b_i|)` per component).
#[inline]
#[must_use]
pub fn cross<T: Real>(a: &Vec3<T>, b: &Vec3<T>) -> Vec3<T> {
    Vector3::new(
        a.y.clone() * &b.z - a.z.clone() * &b.y,
        a.z.clone() * &b.x - a.x.clone() * &b.z,
        a.x.clone() * &b.y - a.y.clone() * &b.x,
    )
}

/// `a + b` and its rounding error: `s + e == a + b` exactly (Knuth's
/// TwoSum, valid in any binary precision rounding to nearest, barring
/// overflow).
fn two_sum<T: Real>(a: &T, b: &T) -> (T, T) {
    let s = a.clone() + b;
    let b_part = s.clone() - a;
    let a_part = s.clone() - &b_part;
    let e = (a.clone() - a_part) + (b.clone() - b_part);
    (s, e)
}

/// `a * b` and its rounding error: `p + e == a b` exactly (by a fused
/// multiply-add, barring overflow and underflow).
fn two_prod<T: Real>(a: &T, b: &T) -> (T, T) {
    let p = a.clone() * b;
    let e = a.mul_add(b, &-p.clone());
    (p, e)
}

/// `(y - x) x (z - y)` (in exact arithmetic the cross product of two edges
/// of the triangle `x, y, z`, its doubled area vector) from the edges held
/// exactly as unevaluated sums (`two_sum`) and the products by fused
/// multiply-adds (`two_prod`). Each component is off by at most `u` of
/// itself plus `28 u^2 |y - x| |z - y|` (counting every rounding; a
/// review measured at most 1.4 in place of 28), so the direction is off by about
/// `3u + 50 u^2 g` (`g = |y - x| |z - y| / |(y - x) x (z - y)|`), where
/// [`cross`] of the rounded edges is off by a few `u g`: for a flat cap
/// (`g` up to `1e6` in `f32`) the difference between a tilt of a few `u`
/// and one of 0.1 radian. That holds while no product's rounding error
/// falls below the smallest normal value (gradual underflow: in `f32` for
/// edges' products below about `2^-100`; the candidates keep the rounded
/// edges' product there). About 90 operations against [`cross`]'s nine,
/// so taken only for triangles that need it.
#[must_use]
#[inline(never)]
pub fn cross_of_edges<T: Real>(x: &Vec3<T>, y: &Vec3<T>, z: &Vec3<T>) -> Vec3<T> {
    let e = [0, 1, 2].map(|i| two_sum(&y[i], &-x[i].clone()));
    let f = [0, 1, 2].map(|i| two_sum(&z[i], &-y[i].clone()));
    let component = |j: usize, k: usize| {
        // e_j f_k - e_k f_j, each edge `hi + lo`; `lo lo` terms (below
        // `u^2` of the products) left out.
        let ((ej, ejl), (ek, ekl), (fj, fjl), (fk, fkl)) = (&e[j], &e[k], &f[j], &f[k]);
        let (p, p_err) = two_prod(ej, fk);
        let (q, q_err) = two_prod(ek, fj);
        let (s, s_err) = two_sum(&p, &-q);
        let mixed = (ej.clone() * fkl + ejl.clone() * fk) - (ek.clone() * fjl + ekl.clone() * fj);
        let low = (s_err + (p_err - q_err)) + mixed;
        s + low
    };
    Vector3::new(component(1, 2), component(2, 0), component(0, 1))
}

/// Squared Euclidean length, `dot(a, a)`.
#[inline]
#[must_use]
pub fn norm_squared<T: Real>(a: &Vec3<T>) -> T {
    dot(a, a)
}

/// Euclidean length, `sqrt(dot(a, a))`.
#[inline]
#[must_use]
pub fn norm<T: Real>(a: &Vec3<T>) -> T {
    norm_squared(a).sqrt()
}

/// `a / |a|`, or `None` when `|a|` is zero or not finite (never NaN).
#[inline]
#[must_use]
pub fn normalize<T: Real>(a: &Vec3<T>) -> Option<Vec3<T>> {
    let n = norm(a);
    // A norm is never negative: positive is finite and not zero (a test
    // without a zero to compare with, which a heap-allocated backend
    // would build on every call).
    if n.is_finite() && !n.is_zero() {
        Some(Vector3::new(a.x.clone() / &n, a.y.clone() / &n, a.z.clone() / &n))
    } else {
        None
    }
}

/// `a / |a|` for a vector whose length is close to 1 (a contact normal,
/// from the contact point to the centre of a unit sphere touching it), by
/// one Newton step for `1 / sqrt(|a|^2)` from 1: `a (3 - |a|^2) / 2`, no
/// square root or quotient. For `|a|^2 = 1 + e` the step's own error is
/// `3 e^2 / 8` relative, at most `3u / 8` while `|e| <= sqrt(u)`; the
/// roundings of `|a|^2` (`3u`, half of it carried into the factor), of
/// `3 - |a|^2` and of the products add about `3.5u`, against about `3u`
/// for [`normalize`]'s root and quotient. Farther from 1, or not finite,
/// it is [`normalize`].
#[inline]
#[must_use]
pub fn normalize_near_unit<T: Real>(a: &Vec3<T>) -> Option<Vec3<T>> {
    let s = norm_squared(a);
    if (s.clone() - T::one()).abs() <= T::c(T::unit_roundoff().sqrt()) {
        let factor = (T::c(3.0) - s) * T::c(0.5);
        Some(a * factor)
    } else {
        normalize(a)
    }
}

/// `true` when all three components are finite.
#[inline]
#[must_use]
pub fn is_finite<T: Real>(a: &Vec3<T>) -> bool {
    a.x.is_finite() && a.y.is_finite() && a.z.is_finite()
}

/// The largest absolute component, `max(floor, |a.x|, |a.y|, |a.z|)`
/// (exact: no rounding).
#[inline]
#[must_use]
pub fn max_abs<T: Real>(a: &Vec3<T>, floor: T) -> T {
    floor.max_abs_of(&a.x).max_abs_of(&a.y).max_abs_of(&a.z)
}
