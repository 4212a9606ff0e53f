//! The sphere-vs-triangle inputs shared by `benches/detect.rs` and the
//! peers' `triangle_mixed` (`benches/peers/benches/peers.rs`), included by
//! both with `#[path]`: random hits and near misses, classified by the
//! robust `f64` test, so that both benches time the same inputs.

use sweepslide::Real;
use sweepslide::detect::{Candidate, DetectOptions, Detection};
use sweepslide::geom::{Triangle, Vec3, vec3};

/// Inputs of each kind.
pub const CASES: usize = 256;

/// Deterministic uniform numbers in `[0, 1)` (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    /// The next number.
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A number uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    /// A point uniform in the cube of half side `half`.
    pub fn point(&mut self, half: f64) -> [f64; 3] {
        std::array::from_fn(|_| self.range(-half, half))
    }
}

/// One sphere-vs-triangle input, in `f64`.
#[derive(Clone, Copy)]
pub struct Case {
    /// The triangle.
    pub tri: [[f64; 3]; 3],
    /// The sphere's centre at `t = 0`.
    pub base: [f64; 3],
    /// The displacement over `t` in `[0, 1]`.
    pub vel: [f64; 3],
}

/// A vector of backend `T`.
pub fn v<T: Real>(p: &[f64; 3]) -> Vec3<T> {
    vec3(p[0], p[1], p[2])
}

/// A triangle of backend `T`.
pub fn tri<T: Real>(t: &[[f64; 3]; 3]) -> Triangle<T> {
    Triangle::new(v(&t[0]), v(&t[1]), v(&t[2]))
}

/// `CASES` hits and `CASES` near misses, classified by the robust `f64`
/// test: random unit-scale triangles near a random path of length 0.5
/// to 3.
pub fn cases() -> (Vec<Case>, Vec<Case>) {
    let mut rng = Rng(0x6465_7465_6374);
    let (mut hits, mut misses) = (Vec::new(), Vec::new());
    let opts = DetectOptions::default();
    while hits.len() < CASES || misses.len() < CASES {
        let base = rng.point(0.5);
        let vel = rng.point(1.0).map(|x| x * rng.range(0.5, 3.0));
        let tau = rng.next();
        let centre: [f64; 3] = std::array::from_fn(|k| base[k] + tau * vel[k] + rng.range(-2.0, 2.0));
        let tri: [[f64; 3]; 3] = std::array::from_fn(|_| {
            let d = rng.point(1.5);
            std::array::from_fn(|k| centre[k] + d[k])
        });
        let case = Case { tri, base, vel };
        let c = Candidate::lone(0, self::tri::<f64>(&tri));
        if c.normal.is_none() {
            continue;
        }
        match Detection::Robust.sweep(&c, &v(&base), &v(&vel), &opts, None) {
            Some(h) if h.t > 0.0 => {
                if hits.len() < CASES {
                    hits.push(case);
                }
            }
            Some(_) => {}
            None => {
                // A near miss: the boxes overlap.
                let end: [f64; 3] = std::array::from_fn(|k| base[k] + vel[k]);
                let overlaps = (0..3).all(|k| {
                    let (lo, hi) = (base[k].min(end[k]) - 1.0, base[k].max(end[k]) + 1.0);
                    let (tlo, thi) = (
                        tri.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min),
                        tri.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max),
                    );
                    tlo <= hi && thi >= lo
                });
                if overlaps && misses.len() < CASES {
                    misses.push(case);
                }
            }
        }
    }
    (hits, misses)
}
