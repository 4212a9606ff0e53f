type F = f32;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::scenes::{Steering, build};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::World;
fn main() {
    let scene = build("terrain:224", 1).unwrap();
    let w64 = World::<F>::new(scene.mesh.clone());
    let b64 = Ellipsoid::<F>::new(scene.radii).unwrap();
    let g64 = vec3::<F>(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let mut steering = Steering::new(&scene, 7);
    let mut p = vec3::<F>(scene.start[0], scene.start[1], scene.start[2]);
    let o = MoveOptions::new(Response::Robust);
    let mut path = Vec::new();
    while path.len() < 256 {
        let v = steering.next(&scene);
        let s = p;
        let m = move_body(&w64, &b64, &p, &vec3(v[0], v[1], v[2]), Some(&g64), &o).unwrap();
        if !path.is_empty() || !m.trace.contacts.is_empty() {
            path.push((s, v));
        }
        p = m.position;
    }
    let world = World::<F>::new(scene.mesh.clone());
    let body = Ellipsoid::<F>::new(scene.radii).unwrap();
    let g: Vec3<F> = vec3(scene.gravity[0], scene.gravity[1], scene.gravity[2]);
    let inputs: Vec<(Vec3<F>, Vec3<F>)> = path.iter().map(|(p, v)| (*p, vec3(v[0], v[1], v[2]))).collect();
    let reps: usize = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(10);
    let t0 = std::time::Instant::now();
    let (iters, sum, contacts) = replay(reps, &inputs, &world, &body, &g, &o);
    let n = (reps * inputs.len()) as f64;
    eprintln!("checksum {sum:x}");
    eprintln!(
        "{:.0} ns/move, {:.2} checks/move, {:.2} contacts/move",
        t0.elapsed().as_nanos() as f64 / n,
        iters as f64 / n,
        contacts as f64 / n
    );
}
#[inline(never)]
fn replay(
    reps: usize,
    inputs: &[(Vec3<F>, Vec3<F>)],
    world: &World<F>,
    body: &Ellipsoid<F>,
    g: &Vec3<F>,
    o: &MoveOptions,
) -> (u64, u64, usize) {
    let mut iters = 0u64;
    let mut sum = 0u64;
    let mut contacts = 0usize;
    for _ in 0..reps {
        for (p, v) in inputs {
            let m = move_body(world, body, p, v, Some(g), o).unwrap();
            iters += m.trace.iterations as u64;
            sum = sum.wrapping_mul(31).wrapping_add(m.position.iter().map(|x| x.to_bits() as u64).sum::<u64>());
            contacts += m.trace.contacts.len();
            std::hint::black_box(m);
        }
    }
    (iters, sum, contacts)
}
