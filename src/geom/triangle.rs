//! Triangles, their features, and the closest point on a triangle.

use super::{Vec3, cross, dot, norm_squared};
use crate::{Error, Real};

/// A triangle given by its vertices `a`, `b`, `c`. Its front face is the
/// side `(b - a) x (c - a)` points to (counter-clockwise winding). Edge `i`
/// runs from vertex `i` to vertex `(i + 1) % 3`.
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle<T: Real> {
    /// Vertex 0.
    pub a: Vec3<T>,
    /// Vertex 1.
    pub b: Vec3<T>,
    /// Vertex 2.
    pub c: Vec3<T>,
}

/// The part of a triangle a contact lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "lab", derive(serde::Serialize, serde::Deserialize))]
pub enum Feature {
    /// The interior of the face.
    Face,
    /// Edge `i`, from vertex `i` to vertex `(i + 1) % 3`.
    Edge(u8),
    /// Vertex `i`.
    Vertex(u8),
}

impl Feature {
    /// The indices of the vertices it spans: an edge's two (the second
    /// taken modulo 3 by [`Triangle::vertex`]), a vertex's one, none for
    /// the face.
    #[must_use]
    pub fn corners(self) -> std::ops::Range<usize> {
        match self {
            Feature::Face => 0..0,
            Feature::Edge(i) => usize::from(i)..usize::from(i) + 2,
            Feature::Vertex(i) => usize::from(i)..usize::from(i) + 1,
        }
    }
}

impl<T: Real> Triangle<T> {
    /// Whether `feature` (an edge or a vertex; `false` for the face) lies
    /// on or behind the plane through `q` with unit normal `n`: every
    /// vertex `v` of it has `n . (v - q) <= slack + ulps max(|v - q|, 1)`
    /// (`max` of the coordinates' magnitudes), `slack` the plane's own
    /// distance tolerance and `ulps` the rounding of `n` and of the
    /// difference over the lever `v - q`.
    #[must_use]
    pub fn feature_on_or_behind(&self, feature: Feature, n: &Vec3<T>, q: &Vec3<T>, slack: &T, ulps: &T) -> bool {
        feature != Feature::Face
            && feature.corners().all(|k| {
                let rel = self.vertex(k) - q;
                dot(n, &rel) <= slack.clone() + ulps.clone() * super::max_abs(&rel, T::one())
            })
    }

    /// A triangle from its three vertices.
    #[must_use]
    pub fn new(a: Vec3<T>, b: Vec3<T>, c: Vec3<T>) -> Self {
        Triangle { a, b, c }
    }

    /// Vertex `i` (0, 1 or 2; taken modulo 3).
    #[must_use]
    pub fn vertex(&self, i: usize) -> &Vec3<T> {
        match i % 3 {
            0 => &self.a,
            1 => &self.b,
            _ => &self.c,
        }
    }

    /// `(b - a) x (c - a)`: normal times twice the area.
    #[inline]
    #[must_use]
    pub fn unnormalized_normal(&self) -> Vec3<T> {
        cross(&(&self.b - &self.a), &(&self.c - &self.a))
    }

    /// Its box: the lower and upper corners (exact: comparisons only).
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> (Vec3<T>, Vec3<T>) {
        let (a, b, c) = (&self.a, &self.b, &self.c);
        let lo = Vec3::from_fn(|i, _| a[i].clone().min(b[i].clone()).min(c[i].clone()));
        let hi = Vec3::from_fn(|i, _| a[i].clone().max(b[i].clone()).max(c[i].clone()));
        (lo, hi)
    }

    /// The triangle with `origin` subtracted from every vertex (so that
    /// `origin` becomes the new origin of coordinates).
    #[inline]
    #[must_use]
    pub fn relative_to(&self, origin: &Vec3<T>) -> Self {
        Triangle { a: &self.a - origin, b: &self.b - origin, c: &self.c - origin }
    }
}

impl Triangle<f64> {
    /// Checks that every coordinate is finite and the triangle has a
    /// non-zero area: `|(b-a) x (c-a)| > 16 eps |b-a| |c-a|` with `eps` the
    /// f64 machine epsilon, i.e. the sine of the angle at `a` is above the
    /// rounding noise of the cross product.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::DegenerateTriangle`], naming `index`;
    /// [`Error::InvalidArgument`] when a side overflows `f64` (finite
    /// vertices more than about `1.8e308` apart).
    pub fn validate(&self, index: usize) -> Result<(), Error> {
        for (i, v) in [&self.a, &self.b, &self.c].into_iter().enumerate() {
            if let Some(bad) = v.iter().find(|x| !x.is_finite()) {
                return Err(Error::NonFinite { what: format!("triangle {index} vertex {i}"), value: *bad });
            }
        }
        // Scaled by a power of two (exact) to a largest coordinate in
        // [1, 2): the fourth powers below then neither overflow (sides of
        // 1e160) nor underflow (sides of 1e-170), which would have called
        // a good triangle collinear.
        let (ab, ac) = (self.b - self.a, self.c - self.a);
        if !(ab.iter().chain(ac.iter()).chain((self.c - self.b).iter()).all(|x| x.is_finite())) {
            return Err(Error::InvalidArgument {
                what: format!("triangle {index}"),
                message: "its sides overflow f64 (vertices more than about 1.8e308 apart along an axis): \
                          scale the mesh down"
                    .into(),
            });
        }
        let scale = unit_scale(ab.amax().max(ac.amax()));
        let (ab, ac) = (ab * scale, ac * scale);
        let area2 = norm_squared(&cross(&ab, &ac));
        let bound = 16.0 * f64::EPSILON;
        let limit = bound * bound * norm_squared(&ab) * norm_squared(&ac);
        if !(area2 > limit) {
            let reason = if ab == Vec3::zeros() || ac == Vec3::zeros() || self.b == self.c {
                "two vertices coincide".to_string()
            } else {
                "the vertices are collinear".to_string()
            };
            return Err(Error::DegenerateTriangle { index, reason });
        }
        Ok(())
    }
}

/// The power of two that scales `largest` (a positive finite magnitude)
/// into `[1, 2)`, exactly (a subnormal one, below `2^-1022`, only as far
/// as `2^1022` takes it); 1 for zero or NaN, `2^-1022` for infinity.
/// Products of vectors
/// scaled by it (cross products, squared lengths) neither overflow nor
/// underflow for any finite `f64` input.
#[must_use]
pub(crate) fn unit_scale(largest: f64) -> f64 {
    let exponent = if largest > 0.0 { (largest.log2().floor() as i32).clamp(-1022, 1022) } else { 0 };
    f64::from_bits(((1023 - exponent) as u64) << 52)
}

/// The point of `tri` closest to `p`, and the feature it lies on.
///
/// Voronoi-region classification by dot products (Ericson, *Real-Time
/// Collision Detection*, 5.1.5). Rounding: each region test is a dot product
/// or a difference of products of edge vectors with `p - vertex`; for points
/// near a region boundary the feature may flip between neighbours, but the
/// returned point is then close to both. The face coordinates are
/// quotients of differences of products of dot products, each product up
/// to `(|e| far)^2` (`|e|` the longest edge, `far` the distance from `p` to
/// the vertices) against an area term of `|e|^4 / k^2` (`k` the shape
/// factor, `|e|^2 / (2 area)`): the point's error is of the order of
/// `u k^2 far^2 / |e|`, that is `u k far` times the lever `k far / |e|`,
/// plus `u |a|` for the final `a + ab v`. The lever is about 1 for a
/// well-shaped triangle near `p` and large for a sliver or a small
/// triangle (0.59 for a point 0.9 above a 40 x 0.05 strip in `f32`, 218
/// times `u k far`: a review); [`crate::detect::closest_point`] takes the
/// foot on the plane instead where it can. Pass coordinates relative to a
/// nearby origin to keep `|a|` small.
///
/// A triangle that is degenerate in this precision (two vertices equal,
/// or all three collinear: a tiny triangle far from the origin in `f32`)
/// gets a finite answer, never NaN: the vertex for a side of zero length,
/// the nearest point of the three sides for collinear vertices.
///
/// Always inlined: returned through the stack, the point stalled every
/// caller on a store-forwarding failure.
#[must_use]
#[inline(always)]
pub fn closest_point_on_triangle<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> (Vec3<T>, Feature) {
    let zero = T::zero();
    let ab = &tri.b - &tri.a;
    let ac = &tri.c - &tri.a;
    let ap = p - &tri.a;
    let d1 = dot(&ab, &ap);
    let d2 = dot(&ac, &ap);
    if d1 <= zero && d2 <= zero {
        return (tri.a.clone(), Feature::Vertex(0));
    }
    let bp = p - &tri.b;
    let d3 = dot(&ab, &bp);
    let d4 = dot(&ac, &bp);
    if d3 >= zero && d4 <= d3 {
        return (tri.b.clone(), Feature::Vertex(1));
    }
    let vc = d1.clone() * &d4 - d3.clone() * &d2;
    if vc <= zero && d1 >= zero && d3 <= zero {
        let span = d1.clone() - &d3;
        if !(span > zero) {
            // `ab . ab = 0`: `b` is `a` (degenerate in this precision).
            return (tri.a.clone(), Feature::Vertex(0));
        }
        let v = d1 / span;
        return (&tri.a + ab * v, Feature::Edge(0));
    }
    let cp = p - &tri.c;
    let d5 = dot(&ab, &cp);
    let d6 = dot(&ac, &cp);
    if d6 >= zero && d5 <= d6 {
        return (tri.c.clone(), Feature::Vertex(2));
    }
    let vb = d5.clone() * &d2 - d1 * &d6;
    if vb <= zero && d2 >= zero && d6 <= zero {
        let span = d2.clone() - &d6;
        if !(span > zero) {
            // `ac . ac = 0`: `c` is `a`.
            return (tri.a.clone(), Feature::Vertex(0));
        }
        let w = d2 / span;
        return (&tri.a + ac * w, Feature::Edge(2));
    }
    let va = d3.clone() * &d6 - d5.clone() * &d4;
    let d43 = d4 - &d3;
    let d56 = d5 - &d6;
    if va <= zero && d43 >= zero && d56 >= zero {
        let span = d43.clone() + &d56;
        if !(span > zero) {
            // `bc . bc = 0`: `c` is `b`.
            return (tri.b.clone(), Feature::Vertex(1));
        }
        let w = d43 / span;
        return (&tri.b + (&tri.c - &tri.b) * w, Feature::Edge(1));
    }
    let area = va.clone() + &vb + &vc;
    if !(area > zero) {
        // Collinear vertices (degenerate in this precision): the nearest
        // point of the three sides.
        return closest_point_on_sides(p, tri);
    }
    // One quotient, two products (Ericson's form).
    let inverse = T::one() / area;
    let v = vb * &inverse;
    let w = vc * &inverse;
    (&tri.a + ab * v + ac * w, Feature::Face)
}

/// The point of `tri`'s boundary closest to `p`: the nearest of the closest
/// points of its three sides (a side of zero length gives its vertex), the
/// first on a tie, but never a vertex one of whose two sides has `p`'s
/// foot inside it: that side's point is then nearer in exact arithmetic,
/// while the rounded distances can tie (a centre beside an edge `1e-11`
/// from its end, the vertex's distance larger by `1e-22`), and a vertex
/// taken for the edge has a direction off along the edge, which a sweep
/// along the edge reads as receding (fuzz finding F36). The closest point
/// of the triangle where `p`'s foot on the plane lies outside it, or of a
/// triangle whose vertices are collinear in this precision. Rounded: each
/// side's parameter is a quotient of two dot products, off by a few `u`
/// times `|p - a| / |e|`, so the point by a few `u |p - a|`, whatever the
/// triangle's shape.
pub(crate) fn closest_point_on_sides<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> (Vec3<T>, Feature) {
    let ends = [(&tri.a, &tri.b), (&tri.b, &tri.c), (&tri.c, &tri.a)];
    let side = |i: usize| {
        let (a, b) = ends[i];
        let e = b - a;
        let e2 = dot(&e, &e);
        let f = dot(&(p - a), &e);
        let (point, feature) = if !(f > T::zero()) || !(e2 > T::zero()) {
            (a.clone(), Feature::Vertex(i as u8))
        } else if f >= e2 {
            (b.clone(), Feature::Vertex(((i + 1) % 3) as u8))
        } else {
            (a + e * (f / e2), Feature::Edge(i as u8))
        };
        (norm_squared(&(p - &point)), point, feature)
    };
    let sides = [side(0), side(1), side(2)];
    // Vertex `v` starts side `v` and ends side `v + 2` (mod 3).
    let inside = sides.each_ref().map(|s| matches!(s.2, Feature::Edge(_)));
    let allowed = |i: usize| match sides[i].2 {
        Feature::Vertex(v) => !(inside[usize::from(v)] || inside[(usize::from(v) + 2) % 3]),
        _ => true,
    };
    // The nearest allowed side, the first on a tie (an edge is always
    // allowed, and without one no vertex is ruled out).
    let best = (0..3).filter(|&i| allowed(i)).reduce(|k, i| if sides[i].0 < sides[k].0 { i } else { k }).unwrap_or(0);
    let (_, point, feature) = &sides[best];
    (point.clone(), *feature)
}
