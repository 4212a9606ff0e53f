//! Detection cost.
//!
//! * `triangle/{fauerby,robust}/{f32,f64,mpfr53}/{hit,miss}`: one unit
//!   sphere swept against one triangle, ns per test. Each iteration runs
//!   the next of 256 precomputed inputs, so branch prediction does not
//!   learn a single case. "hit" inputs are those where the robust `f64`
//!   test finds a contact at `t > 0`; "miss" inputs are near misses: the
//!   triangle's box overlaps the box swept by the sphere (a broadphase
//!   would pass it on) but nothing is touched. Both variants run the same
//!   inputs.
//! * `terrain/{bvh,brute_force}/{f32,f64}`: one frame-sized sweep of a
//!   sphere (r = 0.5, 5 m/s at 60 Hz, i.e. 0.083 per frame, plus a small
//!   downward component) resting on a 224 x 224 heightfield (100,352
//!   triangles, 1 m cells), ns per sweep: through the BVH
//!   ([`sweep_world`], candidates, eSpace mapping and the robust test
//!   included) against the robust test over every triangle (already mapped
//!   into eSpace, so brute force is not charged for the mapping). 256
//!   start points are cycled. The setup checks that both give the same
//!   earliest hit for every start point.
//!
//! Smoke run: `cargo bench --bench detect -- --test` (each benchmark
//! once; the terrain is built once).

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::sync::Arc;
use sweepslide::detect::{Candidate, DetectOptions, Detection, earliest_hit, sweep_world};
use sweepslide::geom::{Ellipsoid, Triangle, Vec3};
use sweepslide::world::{TriangleMesh, World};
use sweepslide::{Mpfr, Real};

#[path = "common/triangle_cases.rs"]
mod triangle_cases;

use triangle_cases::{CASES, Case, Rng, cases, tri, v};

fn bench_triangle_for<T: Real>(c: &mut Criterion, hits: &[Case], misses: &[Case]) {
    let opts = DetectOptions::default();
    for (kind, cases) in [("hit", hits), ("miss", misses)] {
        let inputs: Vec<(Candidate<T>, Vec3<T>, Vec3<T>)> =
            cases.iter().map(|k| (Candidate::lone(0, tri(&k.tri)), v(&k.base), v(&k.vel))).collect();
        for d in [Detection::Fauerby, Detection::Robust] {
            let id = format!("triangle/{}/{}/{kind}", d.name(), T::name());
            let mut i = 0;
            c.bench_function(&id, |b| {
                b.iter(|| {
                    i = (i + 1) % CASES;
                    let (cand, base, vel) = &inputs[i];
                    black_box(d.sweep(black_box(cand), black_box(base), black_box(vel), &opts, None))
                })
            });
        }
    }
}

fn bench_triangle(c: &mut Criterion) {
    let (hits, misses) = cases();
    bench_triangle_for::<f32>(c, &hits, &misses);
    bench_triangle_for::<f64>(c, &hits, &misses);
    bench_triangle_for::<Mpfr<53>>(c, &hits, &misses);
}

// ------------------------------------------------------------- terrain --

const CELLS: usize = 224;
const RADIUS: f64 = 0.5;

/// Rolling hills, a few metres high.
fn height(x: f64, y: f64) -> f64 {
    1.5 * (0.11 * x).sin() * (0.13 * y).cos() + 0.6 * (0.37 * x + 0.23 * y).sin() + 0.2 * (0.91 * y - 0.5 * x).cos()
}

/// The 224 x 224 heightfield, 2 triangles per 1 m cell.
fn terrain() -> TriangleMesh {
    let n = CELLS + 1;
    let mut vertices = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64, j as f64);
            vertices.push([x, y, height(x, y)]);
        }
    }
    let mut triangles = Vec::with_capacity(2 * CELLS * CELLS);
    for j in 0..CELLS {
        for i in 0..CELLS {
            let a = (j * n + i) as u32;
            let (b, c, d) = (a + 1, a + n as u32, a + n as u32 + 1);
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    TriangleMesh::new(vertices, triangles).expect("a valid heightfield")
}

/// 256 frame sweeps: the sphere just above the ground (0.01 clear of the
/// height at its centre's foot, so it may touch a slope), moving 5 m/s at
/// 60 Hz in a random horizontal direction, falling slightly.
fn frames() -> Vec<([f64; 3], [f64; 3])> {
    let mut rng = Rng(0x0074_6572_7261_696e);
    (0..CASES)
        .map(|_| {
            let (x, y) = (rng.range(8.0, CELLS as f64 - 8.0), rng.range(8.0, CELLS as f64 - 8.0));
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let step = 5.0 / 60.0;
            let pos = [x, y, height(x, y) + RADIUS + 0.01];
            let vel = [step * angle.cos(), step * angle.sin(), -9.81 / 60.0 / 60.0];
            (pos, vel)
        })
        .collect()
}

fn bench_terrain_for<T: Real>(c: &mut Criterion, mesh: &Arc<TriangleMesh>, frames: &[([f64; 3], [f64; 3])]) {
    let world = World::<T>::new(mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::sphere(RADIUS).expect("valid radius");
    let opts = DetectOptions::default();
    // Brute force: every triangle, mapped into eSpace once.
    let all: Vec<Candidate<T>> = (0..mesh.len() as u32)
        .map(|t| {
            let w = world.triangle(t);
            let e = Triangle::new(body.to_espace(&w.a), body.to_espace(&w.b), body.to_espace(&w.c));
            Candidate::new(t, e, mesh.active(t))
        })
        .collect();
    let inputs: Vec<(Vec3<T>, Vec3<T>)> = frames.iter().map(|(p, q)| (v(p), v(q))).collect();
    let mut hits = 0;
    for (pos, vel) in &inputs {
        let fast = sweep_world(&world, &body, pos, vel, Detection::Robust, &opts).expect("finite input");
        let brute = earliest_hit(Detection::Robust, &all, &body.to_espace(pos), &body.to_espace(vel), &opts);
        let key = |t: Option<(T, u32)>| t.map(|(t, i)| (t.to_f64(), i));
        // The two map into eSpace from different origins, so times may
        // differ in the last bits, and where two triangles are touched at
        // the same time (a seam) either may win: the triangle must be the
        // same unless the brute force, alone on the BVH's triangle, finds
        // it touched at the same time.
        let (f, b) = (key(fast.map(|h| (h.t, h.triangle))), key(brute.map(|h| (h.t, h.triangle))));
        assert_eq!(f.is_some(), b.is_some(), "{}: BVH and brute force disagree at {pos:?}", T::name());
        if let (Some(f), Some(b)) = (f, b) {
            assert!((f.0 - b.0).abs() <= 1e-3, "{}: times {f:?} vs {b:?}", T::name());
            if f.1 != b.1 {
                let alone = earliest_hit(
                    Detection::Robust,
                    &all[f.1 as usize..=f.1 as usize],
                    &body.to_espace(pos),
                    &body.to_espace(vel),
                    &opts,
                );
                let tie = alone.is_some_and(|h| (h.t.to_f64() - b.0).abs() <= 1e-3);
                assert!(tie, "{}: BVH and brute force disagree at {pos:?}: {f:?} vs {b:?}", T::name());
            }
        }
        hits += usize::from(f.is_some());
    }
    eprintln!("terrain [{}]: {} triangles, {hits} of {} frame sweeps touch the ground", T::name(), mesh.len(), CASES);
    let mut i = 0;
    c.bench_function(&format!("terrain/bvh/{}", T::name()), |b| {
        b.iter(|| {
            i = (i + 1) % CASES;
            let (pos, vel) = &inputs[i];
            black_box(sweep_world(&world, &body, black_box(pos), black_box(vel), Detection::Robust, &opts))
        })
    });
    let mut i = 0;
    let espace: Vec<(Vec3<T>, Vec3<T>)> = inputs.iter().map(|(p, q)| (body.to_espace(p), body.to_espace(q))).collect();
    c.bench_function(&format!("terrain/brute_force/{}", T::name()), |b| {
        b.iter(|| {
            i = (i + 1) % CASES;
            let (base, vel) = &espace[i];
            black_box(earliest_hit(Detection::Robust, &all, black_box(base), black_box(vel), &opts))
        })
    });
}

fn bench_terrain(c: &mut Criterion) {
    let mesh = Arc::new(terrain());
    assert_eq!(mesh.len(), 100_352);
    let frames = frames();
    bench_terrain_for::<f32>(c, &mesh, &frames);
    bench_terrain_for::<f64>(c, &mesh, &frames);
}

criterion_group!(benches, bench_triangle, bench_terrain);
criterion_main!(benches);
