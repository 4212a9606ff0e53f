//! Frame moves on the 100,352-triangle terrain (each response, f32 / f64 /
//! Mpfr<53>) and on the real meshes of `../shared/meshes/`, the BVH, the batch API from 1 to 2 threads, and the lab's
//! throughput per precision.
//!
//! Smoke mode: `cargo bench --bench moves -- --test`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::PathBuf;
use std::sync::Arc;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::scenes::{Scene, Steering, build, meshes_in};
use sweepslide::lab::{Precision, RunConfig, run};

use sweepslide::respond::{BodyMove, MoveOptions, Response, move_bodies, move_body};
use sweepslide::world::{Aabb, Bvh, World};
use sweepslide::{Mpfr, Real};

/// A ball of radius 0.5 at 5 m/s, 60 Hz, steered over the terrain with
/// gravity (or the lab's OBJ scene's sphere over a mesh): the starts and
/// velocities of 256 consecutive robust frames played in `T`, from the first
/// one that touches the geometry, so they are moves on the ground, not the
/// free fall from the scene's start. The velocities do not depend on the
/// backend; the starts are each backend's own: a trajectory recorded in
/// `f64` and rounded to `f32` would start most `f32` frames embedded by the
/// rounding (its resting gap is `1e-14`, the rounding `1e-7`), which no `f32`
/// user sees. The first steering seed from 7 on whose body touches within
/// 2,000 frames is used (on the cow, the lab's default walk leaves the
/// model and falls).
fn trajectory<T: Real>(scene: &Scene) -> Vec<([f64; 3], [f64; 3])> {
    let world = World::<T>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::new(scene.radii).unwrap();
    let gravity = vec3::<T>(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let options = MoveOptions::new(Response::Robust);
    for seed in 7..40 {
        let mut steering = Steering::new(scene, seed);
        let mut p = vec3::<T>(scene.start[0], scene.start[1], scene.start[2]);
        let mut path = Vec::with_capacity(256);
        for _ in 0..256 + 2_000 {
            let v = steering.next(scene);
            let start = [0, 1, 2].map(|i| p[i].to_f64());
            let m = move_body(&world, &body, &p, &vec3(v[0], v[1], v[2]), Some(&gravity), &options).unwrap();
            if !path.is_empty() || !m.trace.contacts.is_empty() {
                path.push((start, v));
                if path.len() == 256 {
                    return path;
                }
            }
            p = m.position;
        }
    }
    panic!("the body never touched the geometry of {}", scene.name);
}

fn moves_in<T: Real>(
    c: &mut Criterion,
    scene: &Scene,
    path: &[([f64; 3], [f64; 3])],
    group: &str,
    responses: &[Response],
) {
    let world = World::<T>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::new(scene.radii).unwrap();
    let gravity: Vec3<T> = vec3(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let inputs: Vec<(Vec3<T>, Vec3<T>)> =
        path.iter().map(|(p, v)| (vec3(p[0], p[1], p[2]), vec3(v[0], v[1], v[2]))).collect();
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(inputs.len() as u64));
    for &response in responses {
        let options = MoveOptions::new(response);
        g.bench_function(BenchmarkId::new(response.name(), T::name()), |b| {
            b.iter(|| {
                for (p, v) in &inputs {
                    black_box(move_body(&world, &body, p, v, Some(&gravity), &options).unwrap());
                }
            })
        });
    }
    g.finish();
}

fn frame_moves(c: &mut Criterion) {
    let scene = build("terrain:224", 1).unwrap();
    moves_in::<f32>(c, &scene, &trajectory::<f32>(&scene), "move_terrain100k", &Response::ALL);
    let path = trajectory::<f64>(&scene);
    moves_in::<f64>(c, &scene, &path, "move_terrain100k", &Response::ALL);
    // `Mpfr<53>` replays the `f64` starts, which it holds exactly.
    moves_in::<Mpfr<53>>(c, &scene, &path[..32], "move_terrain100k_mpfr", &[Response::Robust]);
    moves_in::<f64>(c, &scene, &path[..32], "move_terrain100k_mpfr", &[Response::Robust]);
}

/// The same 256-frame replay on each real mesh of `../shared/meshes/` (or
/// `$SWEEPSLIDE_MESHES`): the lab's default OBJ scene, a sphere of 2% of the
/// mesh's diagonal steered by a random walk with gravity. Skipped, with a
/// note, when the directory holds no mesh.
fn mesh_moves(c: &mut Criterion) {
    let dir = std::env::var_os("SWEEPSLIDE_MESHES").map_or_else(|| "../shared/meshes".into(), PathBuf::from);
    let meshes = meshes_in(&dir);
    if meshes.is_empty() {
        eprintln!("move_mesh: no .obj file in {}, skipped", dir.display());
    }
    for path in meshes {
        let scene = Scene::from_obj(&path).unwrap();
        let group = format!("move_mesh_{}", scene.name);
        moves_in::<f32>(c, &scene, &trajectory::<f32>(&scene), &group, &Response::ALL);
        moves_in::<f64>(c, &scene, &trajectory::<f64>(&scene), &group, &Response::ALL);
    }
}

fn bvh(c: &mut Criterion) {
    let scene = build("terrain:224", 1).unwrap();
    let mesh = &scene.mesh;
    let boxes: Vec<Aabb> = (0..mesh.len() as u32)
        .map(|t| {
            let tri = mesh.triangle(t);
            let mut b = Aabb::empty();
            [tri.a, tri.b, tri.c].iter().for_each(|v| b.grow(v));
            b
        })
        .collect();
    let mut g = c.benchmark_group("bvh_terrain100k");
    g.sample_size(10);
    g.bench_function("build", |b| b.iter(|| black_box(Bvh::build(&boxes))));
    let world = World::<f32>::new(mesh.clone()).expect("the mesh fits the backend");
    let path = trajectory::<f32>(&scene);
    let mut out = Vec::new();
    g.bench_function("query_frame_box", |b| {
        b.iter(|| {
            for (p, _) in &path {
                let (lo, hi) =
                    (vec3::<f32>(p[0] - 0.6, p[1] - 0.6, p[2] - 0.6), vec3::<f32>(p[0] + 0.6, p[1] + 0.6, p[2] + 0.6));
                world.candidates(&lo, &hi, &mut out);
                black_box(out.len());
            }
        })
    });
    g.finish();
}

fn batch(c: &mut Criterion) {
    let scene = build("terrain:224", 1).unwrap();
    let world = World::<f32>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let path = trajectory::<f32>(&scene);
    let body = Ellipsoid::<f32>::new(scene.radii).unwrap();
    let gravity = Some(vec3::<f32>(0.0, scene.gravity[1], 0.0));
    // Bodies standing on the ground all over the middle of the terrain
    // (dropped onto it from above, 0.001 above the contact), each with a
    // velocity of the steered path: 10,000 characters in one frame.
    let world64 = World::<f64>::new(scene.mesh.clone()).expect("the mesh fits the backend");
    let body64 = Ellipsoid::<f64>::new(scene.radii).unwrap();
    let mut seed = 0x6261_7463_6800_0001_u64;
    let mut coordinate = || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 50.0 - 25.0
    };
    let bodies: Vec<BodyMove<f32>> = (0..10_000)
        .map(|i| {
            let (x, z) = (coordinate(), coordinate());
            let drop = vec3(0.0, -100.0, 0.0);
            let hit =
                sweep_world(&world64, &body64, &vec3(x, 50.0, z), &drop, Detection::Robust, &DetectOptions::default())
                    .unwrap()
                    .expect("the terrain is below");
            let v = path[i % path.len()].1;
            BodyMove {
                body: body.clone(),
                position: vec3(x, 50.0 - 100.0 * hit.t + 0.001, z),
                velocity: vec3(v[0], v[1], v[2]),
                gravity,
            }
        })
        .collect();
    let options = MoveOptions::new(Response::Robust);
    let mut g = c.benchmark_group("batch_10000_bodies");
    g.sample_size(10);
    g.throughput(Throughput::Elements(bodies.len() as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        g.bench_function(BenchmarkId::new("threads", threads), |b| {
            b.iter(|| pool.install(|| black_box(move_bodies(&world, &bodies, &options))))
        });
    }
    g.finish();
}

fn lab_throughput(c: &mut Criterion) {
    let scene = Arc::new({
        let mut s = build("corner", 1).unwrap();
        s.frames = 50;
        s
    });
    let mut g = c.benchmark_group("lab_frames_corner");
    g.sample_size(10);
    g.throughput(Throughput::Elements(scene.frames as u64));
    for precision in [Precision::F32, Precision::F64, Precision::Mpfr(24), Precision::Mpfr(53), Precision::Mpfr(113)] {
        let cfg = RunConfig { scene: scene.clone(), response: Response::Robust, detection: None, precision, seed: 1 };
        g.bench_function(BenchmarkId::new("robust", precision.to_string()), |b| {
            b.iter(|| black_box(run(&cfg).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, frame_moves, mesh_moves, bvh, batch, lab_throughput);
criterion_main!(benches);
