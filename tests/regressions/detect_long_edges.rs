//! Sweeps nearly along a long edge whose nearer end lies far along it,
//! found by a review of the twenty-third session's F35 fix with a directed
//! probe (R23a): the edge's entry quadratic took `m . a`, with
//! `m = e x vel` and `a` the nearer end. `m` is perpendicular to `e` in
//! exact arithmetic, but rounded it has a component of `u |e| |vel|` along
//! `e`, which `m . a` multiplied by `a`'s reach along the edge, hundreds of
//! radii: at a grazing angle the discriminant came out negative and the
//! edge was dropped. The quadratic is now formed from `a` across the edge.
//! And, found by the session's second review, an overlapped inactive edge
//! of a long flat cap, sunk into while sliding along it (R23b).

use std::sync::Arc;
use sweepslide::detect::{Candidate, DetectOptions, sweep_robust};
use sweepslide::geom::{Ellipsoid, Feature, Triangle, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

fn v32(x: [f64; 3]) -> Vec3<f32> {
    vec3(x[0], x[1], x[2])
}

/// A unit sphere at the origin in `f32`, swept 282 radii nearly along
/// edge 0, whose nearer end lies about 600 radii along it: it starts
/// `2.2e-3` outside the edge's line, enters its cylinder at `t = 0.256`
/// and is `3.6e-3` inside at the end, within the edge. The discriminant
/// was `-2.2e7` where it is `+1.5e8`.
#[test]
fn grazing_sweep_along_a_long_edge_whose_end_is_far_enters_it() {
    let c = Candidate::lone(
        0,
        Triangle::new(
            v32([108.9849, -522.2937, -370.31494]),
            v32([-104.513596, 494.13428, 348.8664]),
            v32([24.47615, -39.66458, -100.728264]),
        ),
    );
    let vel = v32([-47.696926, 227.34096, 160.76678]);
    let hit = sweep_robust(&c, &Vec3::zeros(), &vel, &DetectOptions::default(), None).expect("the edge is entered");
    assert_eq!(hit.feature, Feature::Edge(0), "{hit:?}");
    assert!((hit.t - 0.256).abs() < 0.01, "{hit:?}");
}

/// The same miss in a robust move (`f32`, the probe's case 8008 of seed
/// 11): a unit sphere resting by a wall of three long triangles, pushed
/// 282 radii nearly along one of their edges in one frame, ended `2.8e-3`
/// inside. (The code before F35's fix took another path here and passed;
/// with F35's fix and without R23a's, this fails.)
#[test]
fn robust_push_along_a_long_edge_whose_end_is_far_stays_out() {
    let soup = [
        [
            [61.28607749658316, -294.9647247812257, -209.53175524398262],
            [-152.21241071722167, 721.4632835676455, 509.64957304716927],
            [-23.222675358347757, 187.66439148167603, 60.05492220037827],
        ],
        [
            [-130.006845244407, 792.5373826140953, 503.62076954201893],
            [100.39169268920497, -304.3487311828022, -272.4893000594969],
            [42.230730297066, -366.9965721637967, -201.21417002562117],
        ],
        [
            [-130.006845244407, 792.5373826140953, 503.62076954201893],
            [42.230730297066, -366.9965721637967, -201.21417002562117],
            [-188.16780763654597, 729.8895416331009, 574.8958995758946],
        ],
    ];
    let settle = ([0.0; 3], [0.029772491558371292, 0.027180996405738445, -0.029576885921238305]);
    let drift = [9.261615554104328e-5, 8.45545420993353e-5, -9.200766625562707e-5];
    let mut frames = vec![settle; 6];
    frames.push(([-47.70341363813809, 227.3276005587677, 160.7837344691945], drift));
    frames.push(([-47.6904019029886, 227.33947654878898, 160.7708108670507], drift));
    let vertices: Vec<[f64; 3]> = soup.iter().flatten().copied().collect();
    let indices = (0..soup.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let world = World::<f32>::new(Arc::new(TriangleMesh::new(vertices, indices).unwrap())).unwrap();
    let body = Ellipsoid::<f32>::sphere(1.0).unwrap();
    let v = |x: [f64; 3]| vec3::<f32>(x[0], x[1], x[2]);
    let mut p = Vec3::<f32>::zeros();
    let options = MoveOptions::new(Response::Robust);
    for (k, (vel, gravity)) in frames.iter().enumerate() {
        let before = p;
        p = move_body(&world, &body, &p, &v(*vel), Some(&v(*gravity)), &options).unwrap().position;
        let depth = penetration(&world, body.radii(), &p).unwrap_or(f64::NEG_INFINITY);
        assert!(depth <= 0.0, "frame {k}: {depth:e} inside at {p:?} (from {before:?})");
    }
    assert!(p.y > 400.0, "the pushes slide the body along the wall: {p:?}");
}

/// R23b: a unit sphere overlapping (0.91 from) the inactive edge 0 of a
/// flat cap 80 radii long in `f32`, centred over the face, moving 10 radii
/// along the edge and sinking into the face by `2.5e-5`. An inactive edge
/// over the face is judged with the face normal, which, computed from the
/// two shorter edges, is off along the long edge by `u` times its tilt
/// (`-5e-6` here): F35's first fix judged the approach of an overlapping
/// edge from `-sep . vel` alone, read the motion along the edge as
/// receding and reported nothing (a coplanar neighbour caught it in a
/// world). Only the motion across the edge's line counts again.
#[test]
fn overlapped_inactive_edge_of_a_flat_cap_sunk_into_while_sliding_along_it_is_met() {
    let (a, b, c) =
        ([1.9420174, 0.29264745, -0.5410054], [57.699562, 53.34715, -64.38704], [29.73931, 26.840164, -32.518337]);
    // Its neighbour across edge 0 (`a`-`b`), coplanar: the edge is internal.
    let mirror = [a[0] + b[0] - c[0], a[1] + b[1] - c[1], a[2] + b[2] - c[2]];
    let mesh = TriangleMesh::new(vec![a, b, c, mirror], vec![[0, 1, 2], [1, 0, 3]]).unwrap();
    let active = mesh.active(0);
    assert!(!active.edge(0), "edge 0 must be internal");
    let cap = Candidate::new(0, Triangle::new(v32(a), v32(b), v32(c)), active);
    let base = v32([29.759365, 27.5404, -31.918947]);
    let vel = v32([-5.5757504, -5.305471, 6.3845897]);
    let hit = sweep_robust(&cap, &base, &vel, &DetectOptions::default(), None).expect("met at the start");
    assert!(hit.t == 0.0 && hit.started_overlapping, "{hit:?}");
}
