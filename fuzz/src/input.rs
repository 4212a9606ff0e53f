//! The fuzz inputs: small "shape" enums and integer parameters decoded with
//! `arbitrary`, turned into `f64` geometry here.
//!
//! No raw floats are decoded: every coordinate comes from a shape (regular,
//! right-angled, sliver or lattice triangle; floor, fold, slot, lab scene
//! piece), a scale (unit ~1, tiny ~1e-4, large ~10, huge ~1e4-1e5), an
//! offset (origin, near, far ~1e3-1e6), a feature of a triangle to aim at
//! (face point, edge point, vertex, a point 1e-k from a vertex) and a gap
//! to it (exactly touching, some `f32` or `f64` ulps, 10^-k, a fraction),
//! and angles that include exactly head-on, exactly grazing and 10^-k from
//! grazing. That puts most inputs where the numerics are hard: near
//! touching, near an edge, nearly parallel, nearly degenerate, nearly
//! coplanar, far from the origin.

use crate::oracle::{FrameInput, MoveCase};
use crate::{encode_enum, encode_struct};
use arbitrary::Arbitrary;
use std::f64::consts::PI;
use sweepslide::lab::scenes;

// ------------------------------------------------------------ vectors --

/// A plain `f64` 3-vector.
pub type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn mul(a: V, s: f64) -> V {
    a.map(|x| x * s)
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(a: V) -> V {
    let l = dot(a, a).sqrt();
    if l > 1e-300 && l.is_finite() { mul(a, 1.0 / l) } else { [0.0, 0.0, 1.0] }
}

/// Two unit vectors completing `n` to an orthonormal frame.
fn frame(n: V) -> (V, V) {
    let helper = if n[0].abs() < 0.6 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let u = unit(cross(n, helper));
    (u, cross(n, u))
}

/// `u` rotated by `angle` about the unit `n` (`u` perpendicular to `n`).
fn rotate(u: V, n: V, angle: f64) -> V {
    let (s, c) = angle.sin_cos();
    add(mul(u, c), mul(cross(n, u), s))
}

fn frac16(x: u16) -> f64 {
    f64::from(x) / 65535.0
}

fn frac8(x: u8) -> f64 {
    f64::from(x) / 255.0
}

/// `sign(k) * 10^-(1 + |k| % 15)`, zero for zero.
fn signed_pow(k: i8) -> f64 {
    if k == 0 {
        return 0.0;
    }
    let e = 1 + i32::from(k.unsigned_abs() % 15);
    10f64.powi(-e).copysign(f64::from(k))
}

// -------------------------------------------------------- parameters --

/// The backend a case runs in.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// `f32`.
    F32,
    /// `f64`.
    F64,
}
encode_enum!(Precision[2] { 0 => F32, 1 => F64 });

/// A non-negative magnitude.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mag {
    /// Exactly zero.
    Zero,
    /// `1e-9 ..= 1e-3`.
    Tiny(u16),
    /// `0.01 ..= 3`.
    Unit(u16),
    /// `3 ..= 1000`.
    Large(u16),
    /// `1e4 ..= 1e6`.
    Huge(u16),
}
encode_enum!(Mag[5] { 0 => Zero, 1 => Tiny(x), 2 => Unit(x), 3 => Large(x), 4 => Huge(x) });

impl Mag {
    /// The value.
    #[must_use]
    pub fn value(self) -> f64 {
        match self {
            Mag::Zero => 0.0,
            Mag::Tiny(x) => 10f64.powf(-9.0 + 6.0 * frac16(x)),
            Mag::Unit(x) => 10f64.powf(-2.0 + 2.477 * frac16(x)),
            Mag::Large(x) => 10f64.powf(0.477 + 2.523 * frac16(x)),
            Mag::Huge(x) => 10f64.powf(4.0 + 2.0 * frac16(x)),
        }
    }
}

/// A signed small distance added to the radius (1 in eSpace): where
/// exactly-touching and nearly-touching cases live.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Gap {
    /// Exactly touching.
    Zero,
    /// `k` units of `2^-24` (`f32` ulps at 1).
    Ulps32(i16),
    /// `k` units of `2^-53` (`f64` ulps at 1).
    Ulps64(i16),
    /// `+-10^-(1..15)`.
    Pow(i8),
    /// `k / 4096`, in `[-8, 8)`.
    Fraction(i16),
}
encode_enum!(Gap[5] { 0 => Zero, 1 => Ulps32(x), 2 => Ulps64(x), 3 => Pow(x), 4 => Fraction(x) });

impl Gap {
    /// The value.
    #[must_use]
    pub fn value(self) -> f64 {
        match self {
            Gap::Zero => 0.0,
            Gap::Ulps32(k) => f64::from(k) * 2f64.powi(-24),
            Gap::Ulps64(k) => f64::from(k) * 2f64.powi(-53),
            Gap::Pow(k) => signed_pow(k),
            Gap::Fraction(k) => f64::from(k) / 4096.0,
        }
    }
}

/// A direction.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    /// `+-x`, `+-y`, `+-z` (`k % 6`).
    Axis(u8),
    /// Polar and azimuthal angles.
    Spherical([u16; 2]),
    /// An axis (`k % 6`) tilted by `+-10^-(1..15)` along the other two.
    NearAxis(u8, [i8; 2]),
    /// `(+-1, +-1, +-1)` normalised, signs from the low bits.
    Diagonal(u8),
}
encode_enum!(Dir[4] { 0 => Axis(x), 1 => Spherical(x), 2 => NearAxis(x, y), 3 => Diagonal(x) });

fn axis(k: u8) -> V {
    let mut v = [0.0; 3];
    v[usize::from(k % 3)] = if (k % 6) < 3 { 1.0 } else { -1.0 };
    v
}

impl Dir {
    /// The unit vector.
    #[must_use]
    pub fn unit(self) -> V {
        match self {
            Dir::Axis(k) => axis(k),
            Dir::Spherical([a, b]) => {
                let (theta, phi) = (PI * frac16(a), 2.0 * PI * frac16(b));
                [theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()]
            }
            Dir::NearAxis(k, [s, t]) => {
                let mut v = axis(k);
                let i = usize::from(k % 3);
                v[(i + 1) % 3] = signed_pow(s);
                v[(i + 2) % 3] = signed_pow(t);
                unit(v)
            }
            Dir::Diagonal(b) => unit([0, 1, 2].map(|i| if b >> i & 1 == 1 { -1.0 } else { 1.0 })),
        }
    }
}

/// An angle in `[0, pi/2]`: 0 is head-on (or along the normal), `pi/2`
/// grazing (or in the plane).
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Angle {
    /// Exactly 0.
    Zero,
    /// Exactly `pi/2` (as an `f64`).
    Right,
    /// `pi/2 - 10^-(1..15)`.
    NearRight(u8),
    /// Uniform in `[0, pi/2]`.
    Uniform(u16),
}
encode_enum!(Angle[4] { 0 => Zero, 1 => Right, 2 => NearRight(x), 3 => Uniform(x) });

impl Angle {
    /// The value in radians.
    #[must_use]
    pub fn radians(self) -> f64 {
        match self {
            Angle::Zero => 0.0,
            Angle::Right => PI / 2.0,
            Angle::NearRight(k) => PI / 2.0 - 10f64.powi(-(1 + i32::from(k % 15))),
            Angle::Uniform(x) => PI / 2.0 * frac16(x),
        }
    }

    /// `(cos, sin)`, exactly `(1, 0)` and `(0, 1)` at the ends.
    #[must_use]
    pub fn cos_sin(self) -> (f64, f64) {
        match self {
            Angle::Zero => (1.0, 0.0),
            Angle::Right => (0.0, 1.0),
            _ => {
                let (s, c) = self.radians().sin_cos();
                (c, s)
            }
        }
    }
}

/// A point of a triangle to aim at.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// The face, at barycentric-like parameters (folded into the
    /// triangle).
    Face([u16; 2]),
    /// Edge `k % 3` at a parameter along it.
    Edge(u8, u16),
    /// Vertex `k % 3`.
    Vertex(u8),
    /// Edge `k % 3`, `10^-(1..15)` (of its length) from its start
    /// (`j >= 0`) or its end.
    NearVertex(u8, i8),
}
encode_enum!(Feature[4] { 0 => Face(x), 1 => Edge(x, y), 2 => Vertex(x), 3 => NearVertex(x, y) });

/// Where a [`Feature`] lies: the point, and the unit in-plane direction
/// pointing away from the triangle there (for the face: a direction given
/// by `azimuth`).
fn feature_point(tri: &[V; 3], f: Feature, azimuth: u16) -> (V, V) {
    let n = unit(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])));
    let centroid = mul(add(add(tri[0], tri[1]), tri[2]), 1.0 / 3.0);
    let edge_out = |i: usize, s: f64| {
        let (a, b) = (tri[i], tri[(i + 1) % 3]);
        let p = add(a, mul(sub(b, a), s));
        let out = unit(cross(sub(b, a), n));
        // Outward: away from the opposite vertex.
        let out = if dot(out, sub(tri[(i + 2) % 3], a)) > 0.0 { mul(out, -1.0) } else { out };
        (p, out)
    };
    match f {
        Feature::Face([a, b]) => {
            let (mut s, mut t) = (frac16(a), frac16(b));
            if s + t > 1.0 {
                (s, t) = (1.0 - s, 1.0 - t);
            }
            let p = add(tri[0], add(mul(sub(tri[1], tri[0]), s), mul(sub(tri[2], tri[0]), t)));
            let (u, _) = frame(n);
            (p, rotate(u, n, 2.0 * PI * frac16(azimuth)))
        }
        Feature::Edge(i, s) => edge_out(usize::from(i % 3), frac16(s)),
        Feature::NearVertex(i, k) => {
            let d = 10f64.powi(-(1 + i32::from(k.unsigned_abs() % 15)));
            edge_out(usize::from(i % 3), if k >= 0 { d } else { 1.0 - d })
        }
        Feature::Vertex(i) => {
            let p = tri[usize::from(i % 3)];
            let out = sub(p, centroid);
            let out = sub(out, mul(n, dot(out, n)));
            (p, unit(out))
        }
    }
}

/// The size of a triangle or piece.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// `0.25 ..= 4`.
    Unit(u8),
    /// `1e-4 ..= 1e-3`.
    Tiny(u8),
    /// `4 ..= 100`.
    Large(u8),
    /// `1e4 ..= 1e5`.
    Huge(u8),
}
encode_enum!(Scale[4] { 0 => Unit(x), 1 => Tiny(x), 2 => Large(x), 3 => Huge(x) });

impl Scale {
    /// The value.
    #[must_use]
    pub fn value(self) -> f64 {
        match self {
            Scale::Unit(x) => 0.25 * 16f64.powf(frac8(x)),
            Scale::Tiny(x) => 1e-4 * 10f64.powf(frac8(x)),
            Scale::Large(x) => 4.0 * 25f64.powf(frac8(x)),
            Scale::Huge(x) => 1e4 * 10f64.powf(frac8(x)),
        }
    }
}

/// Where in the world a case sits.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Offset {
    /// At the origin.
    Origin,
    /// Within `+-16` (units of `1/8`).
    Near([i8; 3]),
    /// `10^(3 ..= 6)` times a direction with components `k / 127`.
    Far(u8, [i8; 3]),
}
encode_enum!(Offset[3] { 0 => Origin, 1 => Near(x), 2 => Far(x, y) });

impl Offset {
    /// The offset vector.
    #[must_use]
    pub fn value(self) -> V {
        match self {
            Offset::Origin => [0.0; 3],
            Offset::Near(v) => v.map(|x| f64::from(x) / 8.0),
            Offset::Far(e, v) => {
                let m = 10f64.powf(3.0 + 3.0 * frac8(e));
                v.map(|x| m * f64::from(x) / 127.0)
            }
        }
    }
}

// ---------------------------------------------------------- triangles --

/// A triangle shape, of size about 1 (scaled by a [`Scale`]).
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriShape {
    /// Vertices at distances `0.3 ..= 2.5` from the centre, 120 degrees
    /// apart plus up to `+-0.5` rad: angles above roughly 15 degrees.
    Regular {
        /// Plane normal.
        normal: Dir,
        /// Rotation about the normal.
        spin: u16,
        /// Distances of the vertices.
        radii: [u8; 3],
        /// Angular jitter.
        jitter: [i8; 3],
    },
    /// A right triangle, legs `0.5 ..= 4` (axis-aligned for an axis normal
    /// and zero spin, like the lab's floors and walls).
    Right {
        /// Plane normal.
        normal: Dir,
        /// Rotation about the normal.
        spin: u16,
        /// Leg lengths.
        legs: [u8; 2],
    },
    /// A base of length 2 and an apex at height `2 * 10^-(0..4)` over a
    /// point `[-0.5, 1.5]` along it: needles and near-degenerate slivers.
    Sliver {
        /// Plane normal.
        normal: Dir,
        /// Rotation about the normal.
        spin: u16,
        /// Where the apex projects along the base.
        apex: u16,
        /// Height exponent.
        thin: u8,
    },
    /// Lattice points `k / 32` (can be degenerate).
    Lattice([[i8; 3]; 3]),
}

impl crate::encode::Encode for TriShape {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            TriShape::Regular { normal, spin, radii, jitter } => {
                variant(out, 0, 4);
                (normal, spin, radii, jitter).encode(out);
            }
            TriShape::Right { normal, spin, legs } => {
                variant(out, 1, 4);
                (normal, spin, legs).encode(out);
            }
            TriShape::Sliver { normal, spin, apex, thin } => {
                variant(out, 2, 4);
                (normal, spin, apex, thin).encode(out);
            }
            TriShape::Lattice(v) => {
                variant(out, 3, 4);
                v.encode(out);
            }
        }
    }
}

impl TriShape {
    /// The triangle, centred near the origin, of size about `size`.
    #[must_use]
    pub fn build(self, size: f64) -> [V; 3] {
        let in_plane = |normal: Dir, spin: u16, pts: [[f64; 2]; 3]| {
            let n = normal.unit();
            let (u, _) = frame(n);
            let u2 = rotate(u, n, 2.0 * PI * frac16(spin));
            let w2 = cross(n, u2);
            pts.map(|[x, y]| add(mul(u2, x * size), mul(w2, y * size)))
        };
        match self {
            TriShape::Regular { normal, spin, radii, jitter } => {
                let pts = std::array::from_fn(|i| {
                    let r = 0.3 + 2.2 * frac8(radii[i]);
                    let ang = i as f64 * 2.0 * PI / 3.0 + 0.5 * f64::from(jitter[i]) / 128.0;
                    [r * ang.cos(), r * ang.sin()]
                });
                in_plane(normal, spin, pts)
            }
            TriShape::Right { normal, spin, legs } => {
                let [a, b] = legs.map(|l| 0.5 + 3.5 * frac8(l));
                in_plane(normal, spin, [[0.0, 0.0], [a, 0.0], [0.0, b]])
            }
            TriShape::Sliver { normal, spin, apex, thin } => {
                let h = 2.0 * 10f64.powf(-4.0 * frac8(thin));
                let x = -1.0 + 4.0 * frac16(apex);
                in_plane(normal, spin, [[-1.0, 0.0], [1.0, 0.0], [x, h]])
            }
            TriShape::Lattice(v) => v.map(|p| p.map(|x| f64::from(x) / 32.0 * size)),
        }
    }
}

// --------------------------------------------------------------- sweep --

/// How the unit sphere moves past the triangle.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum SweepPath {
    /// At time `tau` the centre is at `1 + gap` from a feature point, in
    /// direction `side * n cos(theta) + out sin(theta)`; it moves at
    /// `phi` from head-on (`pi/2`: grazing), turned by `heading` about the
    /// contact direction.
    Touch {
        /// The feature aimed at.
        at: Feature,
        /// Front or back side.
        side: bool,
        /// Contact direction: 0 along the normal, `pi/2` in the plane.
        theta: Angle,
        /// In-plane direction for a face point.
        azimuth: u16,
        /// Distance beyond 1 at time `tau`.
        gap: Gap,
        /// Angle of the motion from head-on.
        phi: Angle,
        /// Turn of the motion about the contact direction.
        heading: u16,
        /// Time of the (near) touch, `[-0.2, 1.2]`.
        tau: i16,
        /// Speed (eSpace units per frame).
        speed: Mag,
    },
    /// Moving exactly parallel to an edge, at `1 + gap` from its line.
    Parallel {
        /// The edge (`k % 3`).
        edge: u8,
        /// Start along the edge line, `k / 8192` of its length.
        along: i16,
        /// Front or back side.
        side: bool,
        /// Direction around the edge line.
        theta: Angle,
        /// Distance beyond 1 from the line.
        gap: Gap,
        /// Speed.
        speed: Mag,
        /// Against the edge's direction.
        backward: bool,
    },
    /// Anywhere near: the start at `k / 4096` of the triangle's size.
    Free {
        /// The start.
        base: [i16; 3],
        /// The direction of motion.
        dir: Dir,
        /// Speed.
        speed: Mag,
    },
}

impl crate::encode::Encode for SweepPath {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            SweepPath::Touch { at, side, theta, azimuth, gap, phi, heading, tau, speed } => {
                variant(out, 0, 3);
                (at, side, theta, azimuth).encode(out);
                (gap, phi, heading, tau).encode(out);
                speed.encode(out);
            }
            SweepPath::Parallel { edge, along, side, theta, gap, speed, backward } => {
                variant(out, 1, 3);
                (edge, along, side, theta).encode(out);
                (gap, speed, backward).encode(out);
            }
            SweepPath::Free { base, dir, speed } => {
                variant(out, 2, 3);
                (base, dir, speed).encode(out);
            }
        }
    }
}

/// The `sweep_triangle` target's input.
#[derive(Arbitrary, Debug, Clone, PartialEq, Eq)]
pub struct SweepInput {
    /// `f32` or `f64`.
    pub precision: Precision,
    /// The triangle's shape.
    pub shape: TriShape,
    /// Its size.
    pub size: Scale,
    /// Where the whole case sits.
    pub offset: Offset,
    /// The motion.
    pub path: SweepPath,
    /// Unused (keeps the last field a plain byte; see `encode`).
    pub tail: u8,
}
encode_struct!(SweepInput { precision, shape, size, offset, path, tail });

/// A sweep in `f64`: the unit sphere's centre, its motion and the triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepCase {
    /// The centre at `t = 0`.
    pub base: V,
    /// The motion over the frame.
    pub vel: V,
    /// The triangle.
    pub tri: [V; 3],
}

/// The sphere centre at `1 + gap` from feature `at` of `tri`, in direction
/// `side * n cos(theta) + out sin(theta)`: the centre and that direction.
fn near_feature(tri: &[V; 3], at: Feature, side: bool, theta: Angle, azimuth: u16, gap: Gap) -> (V, V) {
    let n = unit(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])));
    let n = if side { n } else { mul(n, -1.0) };
    let (p, out) = feature_point(tri, at, azimuth);
    let (c, s) = theta.cos_sin();
    let dir = unit(add(mul(n, c), mul(out, s)));
    (add(p, mul(dir, 1.0 + gap.value())), dir)
}

impl SweepInput {
    /// The geometry.
    #[must_use]
    pub fn build(&self) -> SweepCase {
        let size = self.size.value();
        let tri = self.shape.build(size);
        let o = self.offset.value();
        let (base, vel) = match self.path {
            SweepPath::Touch { at, side, theta, azimuth, gap, phi, heading, tau, speed } => {
                let (centre, c) = near_feature(&tri, at, side, theta, azimuth, gap);
                let (u, _) = frame(c);
                let w = rotate(u, c, 2.0 * PI * frac16(heading));
                let (cp, sp) = phi.cos_sin();
                let vel = mul(add(mul(c, -cp), mul(w, sp)), speed.value());
                let tau = 0.5 + 0.7 * f64::from(tau) / 32768.0;
                (sub(centre, mul(vel, tau)), vel)
            }
            SweepPath::Parallel { edge, along, side, theta, gap, speed, backward } => {
                let i = usize::from(edge % 3);
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                let e = sub(b, a);
                let s = f64::from(along) / 8192.0;
                let on_line = add(a, mul(e, s));
                let n = unit(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])));
                let n = if side { n } else { mul(n, -1.0) };
                let out = unit(cross(e, n));
                let out = if dot(out, sub(tri[(i + 2) % 3], a)) > 0.0 { mul(out, -1.0) } else { out };
                let (c, sn) = theta.cos_sin();
                let dir = unit(add(mul(n, c), mul(out, sn)));
                let base = add(on_line, mul(dir, 1.0 + gap.value()));
                let v = mul(unit(e), if backward { -speed.value() } else { speed.value() });
                (base, v)
            }
            SweepPath::Free { base, dir, speed } => {
                (base.map(|x| f64::from(x) / 4096.0 * size.max(1.0)), mul(dir.unit(), speed.value()))
            }
        };
        SweepCase { base: add(base, o), vel, tri: tri.map(|p| add(p, o)) }
    }
}

// --------------------------------------------------------------- moves --

/// The body.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body {
    /// A sphere of radius `10^((k - 128) / 32)` (`1e-4` to about `8e3`).
    Sphere(u8),
    /// An ellipsoid: the first radius as a sphere's, the others that times
    /// `2^((k - 128) / 32)` (ratios `1/16` to about 16).
    Ellipsoid([u8; 3]),
}
encode_enum!(Body[2] { 0 => Sphere(x), 1 => Ellipsoid(x) });

fn radius(k: u8) -> f64 {
    10f64.powf((f64::from(k) - 128.0) / 32.0)
}

impl Body {
    /// The radii.
    #[must_use]
    pub fn radii(self) -> V {
        match self {
            Body::Sphere(k) => [radius(k); 3],
            Body::Ellipsoid([a, b, c]) => {
                let r = radius(a);
                [r, r * 2f64.powf((f64::from(b) - 128.0) / 32.0), r * 2f64.powf((f64::from(c) - 128.0) / 32.0)]
            }
        }
    }
}

/// The lab scenes a piece can copy (their parameter from a byte).
pub const SCENES: [&str; 8] =
    ["floor", "corner", "wedge", "crease", "slot", "dead-end", "tessellated-floor", "staircase"];

/// A piece of the soup, in units of the body's largest radius `R`.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece {
    /// A built-in lab scene (`SCENES[k % 8]`, at most 8 triangles), scaled
    /// so that its body's radius becomes `R`.
    Scene(u8, u8),
    /// One triangle of a shape and size, at `k / 8` R.
    Triangle(TriShape, Scale, [i8; 3]),
    /// Two triangles meeting along a hinge: a fold of dihedral angle
    /// `angle` (wedges, corners, creases, nearly flat seams).
    Fold(Fold),
    /// Two parallel quads `2 (1 + gap)` R apart (in the body's extent
    /// along their normal): a slot.
    Slot(Dir, u16, Gap, [i8; 3]),
}

impl crate::encode::Encode for Piece {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            Piece::Scene(a, b) => {
                variant(out, 0, 4);
                (a, b).encode(out);
            }
            Piece::Triangle(s, z, at) => {
                variant(out, 1, 4);
                (s, z, at).encode(out);
            }
            Piece::Fold(f) => {
                variant(out, 2, 4);
                f.encode(out);
            }
            Piece::Slot(d, spin, g, at) => {
                variant(out, 3, 4);
                (d, spin, g, at).encode(out);
            }
        }
    }
}

/// The dihedral angle of a [`Fold`].
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoldAngle {
    /// Uniform in `(0, 2 pi)`.
    Uniform(u16),
    /// `pi +- 10^-(1..15)`: nearly coplanar.
    NearFlat(i8),
    /// `10^-(1..15)`: a razor-thin wedge.
    NearZero(u8),
    /// Exactly `pi` (coplanar, as computed).
    Flat,
}
encode_enum!(FoldAngle[4] { 0 => Uniform(x), 1 => NearFlat(x), 2 => NearZero(x), 3 => Flat });

impl FoldAngle {
    fn radians(self) -> f64 {
        match self {
            FoldAngle::Uniform(x) => 2.0 * PI * (f64::from(x) + 0.5) / 65536.0,
            FoldAngle::NearFlat(k) => PI + signed_pow(k),
            FoldAngle::NearZero(k) => 10f64.powi(-(1 + i32::from(k % 15))),
            FoldAngle::Flat => PI,
        }
    }
}

/// Two quads (four triangles) hinged on a common edge.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fold {
    /// The hinge direction.
    pub hinge: Dir,
    /// Rotation of the first wing about the hinge.
    pub spin: u16,
    /// The dihedral angle between the wings.
    pub angle: FoldAngle,
    /// Wing size.
    pub size: Scale,
    /// Position of the hinge's middle, `k / 8` R.
    pub at: [i8; 3],
    /// Which diagonal splits the quads.
    pub diagonal: bool,
}
encode_struct!(Fold { hinge, spin, angle, size, at, diagonal });

/// Where the body starts.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// The first scene piece's start (else the offset itself).
    SceneDefault,
    /// At `1 + gap` (eSpace) from a feature of triangle `k % count`.
    Near {
        /// The triangle.
        tri: u8,
        /// The feature.
        at: Feature,
        /// Front or back.
        side: bool,
        /// Contact direction from the normal.
        theta: Angle,
        /// The gap.
        gap: Gap,
    },
    /// At `k / 16` R from the offset.
    Free([i8; 3]),
}

impl crate::encode::Encode for Start {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            Start::SceneDefault => variant(out, 0, 3),
            Start::Near { tri, at, side, theta, gap } => {
                variant(out, 1, 3);
                (tri, at, side, theta).encode(out);
                gap.encode(out);
            }
            Start::Free(v) => {
                variant(out, 2, 3);
                v.encode(out);
            }
        }
    }
}

/// A displacement per frame.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Push {
    /// The first scene piece's velocity (else `-0.1 R` along y).
    SceneDefault,
    /// A direction and a speed (R per frame).
    Dir(Dir, Mag),
    /// Into triangle `k % count`'s plane (from the start's side) at
    /// `phi` from head-on, turned by `heading`.
    Into(u8, Angle, u16, Mag),
    /// No motion.
    Zero,
}

impl crate::encode::Encode for Push {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            Push::SceneDefault => variant(out, 0, 4),
            Push::Dir(d, m) => {
                variant(out, 1, 4);
                (d, m).encode(out);
            }
            Push::Into(k, phi, h, m) => {
                variant(out, 2, 4);
                (k, phi, h, m).encode(out);
            }
            Push::Zero => variant(out, 3, 4),
        }
    }
}

/// One step of the sequence: a push repeated `1 + k % 4` frames.
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Step {
    /// The displacement.
    pub push: Push,
    /// Repetitions.
    pub repeat: u8,
}
encode_struct!(Step { push, repeat });

/// Gravity (the second pass of every frame).
#[derive(Arbitrary, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Gravity {
    /// No gravity pass.
    None,
    /// The first scene piece's gravity (else none).
    SceneDefault,
    /// Straight down, this many R per frame.
    Down(Mag),
    /// Any direction.
    Dir(Dir, Mag),
}

impl crate::encode::Encode for Gravity {
    fn encode(&self, out: &mut Vec<u8>) {
        use crate::encode::variant;
        match self {
            Gravity::None => variant(out, 0, 4),
            Gravity::SceneDefault => variant(out, 1, 4),
            Gravity::Down(m) => {
                variant(out, 2, 4);
                m.encode(out);
            }
            Gravity::Dir(d, m) => {
                variant(out, 3, 4);
                (d, m).encode(out);
            }
        }
    }
}

/// The input of the `move_robust` and `compare_responses` targets.
#[derive(Arbitrary, Debug, Clone, PartialEq, Eq)]
pub struct MoveInput {
    /// `f32` or `f64`.
    pub precision: Precision,
    /// The body.
    pub body: Body,
    /// Where the whole case sits.
    pub offset: Offset,
    /// The soup (at most [`MAX_TRIANGLES`] triangles are kept; none: the
    /// lab's floor).
    pub pieces: Vec<Piece>,
    /// The start.
    pub start: Start,
    /// The frames (at most [`MAX_FRAMES`] are played).
    pub steps: Vec<Step>,
    /// Gravity.
    pub gravity: Gravity,
    /// Unused (keeps the last field a plain byte; see `encode`).
    pub tail: u8,
}
encode_struct!(MoveInput { precision, body, offset, pieces, start, steps, gravity, tail });

/// Most triangles in a soup.
pub const MAX_TRIANGLES: usize = 16;
/// Most frames played.
pub const MAX_FRAMES: usize = 24;

/// A built-in scene's triangles, start, velocity and gravity, scaled by
/// `k` (its body radius becomes `k` times its own).
struct SceneBits {
    triangles: Vec<[V; 3]>,
    start: V,
    velocity: V,
    gravity: V,
}

fn scene_piece(which: u8, param: u8, k_over_r: f64) -> Option<SceneBits> {
    let name = SCENES[usize::from(which % 8)];
    let f = frac8(param);
    let spec = match name {
        "corner" => format!("corner:{}", 1.0 + 88.0 * f),
        "wedge" => format!("wedge:{}", 0.5 + 88.5 * f),
        "crease" => format!("crease:{}", 1.0 + 79.0 * f),
        "slot" => format!("slot:{}", if param == 0 { 0.0 } else { 10f64.powf(-7.0 + 8.0 * f) }),
        "tessellated-floor" => format!("tessellated-floor:{}", 1 + param % 2),
        "staircase" => "staircase:1".to_string(),
        other => other.to_string(),
    };
    let s = scenes::build(&spec, u64::from(param)).ok()?;
    let k = k_over_r / s.radii[0];
    let m = &s.mesh;
    let triangles = (0..m.len() as u32)
        .map(|t| {
            let tri = m.triangle(t);
            [tri.a, tri.b, tri.c].map(|v| mul([v.x, v.y, v.z], k))
        })
        .collect();
    Some(SceneBits { triangles, start: mul(s.start, k), velocity: mul(s.velocity, k), gravity: mul(s.gravity, k) })
}

/// The four corners of a quad `p, p + a, p + a + b, p + b` as two
/// triangles, split along one diagonal or the other.
fn quad(p: V, a: V, b: V, diagonal: bool) -> [[V; 3]; 2] {
    let (q, r, s) = (add(p, a), add(add(p, a), b), add(p, b));
    if diagonal { [[p, q, r], [p, r, s]] } else { [[p, q, s], [q, r, s]] }
}

impl MoveInput {
    /// The geometry and frames, in `f64`.
    #[must_use]
    pub fn build(&self) -> MoveCase {
        let radii = self.body.radii();
        let r = radii.iter().copied().fold(0.0, f64::max);
        let o = self.offset.value();
        let at = |v: [i8; 3]| add(o, v.map(|x| f64::from(x) / 8.0 * r));
        let mut triangles: Vec<[V; 3]> = Vec::new();
        let mut scene: Option<SceneBits> = None;
        // No pieces: the lab's floor, so that every input has geometry.
        let floor = [Piece::Scene(0, 0)];
        let pieces = if self.pieces.is_empty() { &floor[..] } else { &self.pieces[..] };
        for piece in pieces {
            if triangles.len() >= MAX_TRIANGLES {
                break;
            }
            match *piece {
                Piece::Scene(which, param) => {
                    if let Some(s) = scene_piece(which, param, r) {
                        triangles.extend(s.triangles.iter().map(|t| t.map(|v| add(v, o))));
                        scene.get_or_insert(s);
                    }
                }
                Piece::Triangle(shape, size, p) => {
                    let c = at(p);
                    triangles.push(shape.build(size.value() * r).map(|v| add(v, c)));
                }
                Piece::Fold(f) => {
                    let e = f.hinge.unit();
                    let (u0, _) = frame(e);
                    let u = rotate(u0, e, 2.0 * PI * frac16(f.spin));
                    let w = rotate(u, e, f.angle.radians());
                    let size = f.size.value() * r;
                    let c = at(f.at);
                    let p = sub(c, mul(e, size));
                    let e2 = mul(e, 2.0 * size);
                    triangles.extend(quad(p, e2, mul(u, size), f.diagonal));
                    triangles.extend(quad(p, e2, mul(w, size), !f.diagonal));
                }
                Piece::Slot(d, spin, gap, p) => {
                    let n = d.unit();
                    let (u0, _) = frame(n);
                    let u = rotate(u0, n, 2.0 * PI * frac16(spin));
                    let w = cross(n, u);
                    // The body's extent along n.
                    let extent = (0..3).map(|i| (radii[i] * n[i]).powi(2)).sum::<f64>().sqrt();
                    let half = extent * (1.0 + gap.value());
                    let c = at(p);
                    let size = 8.0 * r;
                    for s in [-1.0, 1.0] {
                        let corner = add(add(c, mul(n, s * half)), add(mul(u, -size), mul(w, -size)));
                        triangles.extend(quad(corner, mul(u, 2.0 * size), mul(w, 2.0 * size), s > 0.0));
                    }
                }
            }
        }
        triangles.truncate(MAX_TRIANGLES);
        let count = triangles.len().max(1);
        let start = match self.start {
            Start::SceneDefault => scene.as_ref().map_or(o, |s| add(s.start, o)),
            Start::Near { tri, at, side, theta, gap } => match triangles.get(usize::from(tri) % count) {
                // In eSpace, so the gap is measured for the ellipsoid.
                Some(t) => {
                    let te = t.map(|v| [0, 1, 2].map(|i| v[i] / radii[i]));
                    let (ce, _) = near_feature(&te, at, side, theta, 0, gap);
                    [0, 1, 2].map(|i| ce[i] * radii[i])
                }
                None => o,
            },
            Start::Free(v) => add(o, v.map(|x| f64::from(x) / 16.0 * r)),
        };
        let gravity = match self.gravity {
            Gravity::None => None,
            Gravity::SceneDefault => scene.as_ref().map(|s| s.gravity).filter(|g| *g != [0.0; 3]),
            Gravity::Down(m) => Some([0.0, -m.value() * r, 0.0]),
            Gravity::Dir(d, m) => Some(mul(d.unit(), m.value() * r)),
        };
        let push = |p: Push| match p {
            Push::SceneDefault => scene.as_ref().map_or([0.0, -0.1 * r, 0.0], |s| s.velocity),
            Push::Dir(d, m) => mul(d.unit(), m.value() * r),
            Push::Into(k, phi, heading, m) => match triangles.get(usize::from(k) % count) {
                Some(t) => {
                    let n = unit(cross(sub(t[1], t[0]), sub(t[2], t[0])));
                    let n = if dot(n, sub(start, t[0])) < 0.0 { mul(n, -1.0) } else { n };
                    let (u, _) = frame(n);
                    let w = rotate(u, n, 2.0 * PI * frac16(heading));
                    let (c, s) = phi.cos_sin();
                    mul(add(mul(n, -c), mul(w, s)), m.value() * r)
                }
                None => [0.0; 3],
            },
            Push::Zero => [0.0; 3],
        };
        let steps =
            if self.steps.is_empty() { vec![Step { push: Push::SceneDefault, repeat: 0 }] } else { self.steps.clone() };
        let mut frames = Vec::new();
        for step in &steps {
            let velocity = push(step.push);
            for _ in 0..=(step.repeat % 4) {
                frames.push(FrameInput { velocity, gravity });
            }
        }
        frames.truncate(MAX_FRAMES);
        MoveCase { triangles, radii, start, frames }
    }
}

// ----------------------------------------------------------------- OBJ --

/// A line of a structured OBJ text.
#[derive(Arbitrary, Debug, Clone, PartialEq, Eq)]
pub enum ObjLine {
    /// `v x y z` with coordinates `k / 16`, optionally a weight.
    Vertex([i16; 3], Option<u8>),
    /// `v` with an odd number of coordinates or odd spellings.
    OddVertex(u8, [i16; 2]),
    /// `f` with corners (index, form: `v`, `v/vt`, `v//vn`, `v/vt/vn`),
    /// negative indices counted from the end.
    Face(Vec<(i16, u8)>),
    /// A statement that carries no geometry (`vt`, `vn`, `o`, `g`, ...).
    Ignored(u8),
    /// `l` or `p`.
    LineOrPoint(bool),
    /// A comment.
    Comment,
    /// An empty line.
    Blank,
    /// Raw text.
    Raw(String),
}

impl ObjLine {
    /// The line's text (without the line break).
    #[must_use]
    pub fn render(&self) -> String {
        match self {
            ObjLine::Vertex(v, w) => {
                let mut s = format!("v {} {} {}", v[0] as f64 / 16.0, v[1] as f64 / 16.0, v[2] as f64 / 16.0);
                if let Some(w) = w {
                    s += &format!(" {w}");
                }
                s
            }
            ObjLine::OddVertex(k, [a, b]) => match k % 8 {
                0 => format!("v {a}"),
                1 => format!("v {a} {b}"),
                2 => format!("v {a} {b} {a} {b} {a}"),
                3 => format!("v {a}e308 {b}e308 1e309"),
                4 => format!("v nan {a} {b}"),
                5 => format!("v inf -inf {a}"),
                6 => format!("v 0x{a} {b} {a}"),
                _ => format!("v {a}.{b}e-320 {b} -0"),
            },
            ObjLine::Face(corners) => {
                let mut s = "f".to_string();
                for (i, form) in corners.iter().take(12) {
                    s += &match form % 5 {
                        0 => format!(" {i}"),
                        1 => format!(" {i}/1"),
                        2 => format!(" {i}//1"),
                        3 => format!(" {i}/1/1"),
                        _ => format!(" {i}/"),
                    };
                }
                s
            }
            ObjLine::Ignored(k) => {
                ["vt 0 0", "vn 0 1 0", "o thing", "g group", "s off", "usemtl stone", "mtllib a.mtl", "vp 0.5"]
                    [usize::from(k % 8)]
                .to_string()
            }
            ObjLine::LineOrPoint(l) => if *l { "l 1 2" } else { "p 1" }.to_string(),
            ObjLine::Comment => "# comment".to_string(),
            ObjLine::Blank => String::new(),
            ObjLine::Raw(s) => s.clone(),
        }
    }
}

/// The `obj_parse` target's input: the first byte chooses raw text (even:
/// the rest of the bytes, decoded lossily as UTF-8) or structured lines
/// (odd: [`ObjLines`] decoded with `arbitrary` from the rest).
#[must_use]
pub fn obj_text(data: &[u8]) -> String {
    match data.split_first() {
        None => String::new(),
        Some((first, rest)) if first % 2 == 0 => String::from_utf8_lossy(rest).into_owned(),
        Some((_, rest)) => {
            ObjLines::arbitrary_take_rest(arbitrary::Unstructured::new(rest)).map(|l| l.text()).unwrap_or_default()
        }
    }
}

/// Structured OBJ lines.
#[derive(Arbitrary, Debug, Clone, PartialEq, Eq)]
pub struct ObjLines {
    /// `\r\n` line breaks instead of `\n`.
    pub crlf: bool,
    /// The lines.
    pub lines: Vec<ObjLine>,
}

impl ObjLines {
    /// The OBJ text.
    #[must_use]
    pub fn text(&self) -> String {
        let sep = if self.crlf { "\r\n" } else { "\n" };
        self.lines.iter().map(ObjLine::render).collect::<Vec<_>>().join(sep)
    }
}
