//! Sweeps nearly along a long edge whose nearer end lies far along it,
//! found by a review of the twenty-third session's F35 fix with a directed
//! probe (R23a): the edge's entry quadratic took `m . a`, with
//! `m = e x vel` and `a` the nearer end. `m` is perpendicular to `e` in
//! exact arithmetic, but rounded it has a component of `u |e| |vel|` along
//! `e`, which `m . a` multiplied by `a`'s reach along the edge, hundreds of
//! radii: at a grazing angle the discriminant came out negative and the
//! edge was dropped. The quadratic is now formed from `a` across the edge.

use std::sync::Arc;
use sweepslide::detect::{Candidate, DetectOptions, sweep_robust};
use sweepslide::geom::{Ellipsoid, Feature, Triangle, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A unit sphere at the origin in `f32`, swept 282 radii nearly along
/// edge 0, whose nearer end lies about 600 radii along it: it starts
/// `2.2e-3` outside the edge's line, enters its cylinder at `t = 0.256`
/// and is `3.6e-3` inside at the end, within the edge. The discriminant
/// was `-2.2e7` where it is `+1.5e8`.
#[test]
fn grazing_sweep_along_a_long_edge_whose_end_is_far_enters_it() {
    let v = |x: [f64; 3]| vec3::<f32>(x[0], x[1], x[2]);
    let c = Candidate::lone(
        0,
        Triangle::new(
            v([108.9849, -522.2937, -370.31494]),
            v([-104.513596, 494.13428, 348.8664]),
            v([24.47615, -39.66458, -100.728264]),
        ),
    );
    let vel = v([-47.696926, 227.34096, 160.76678]);
    let hit = sweep_robust(&c, &Vec3::zeros(), &vel, &DetectOptions::default(), None).expect("the edge is entered");
    assert_eq!(hit.feature, Feature::Edge(0), "{hit:?}");
    assert!((hit.t - 0.256).abs() < 0.01, "{hit:?}");
}

/// The same miss in a robust move (`f32`, the probe's case 8008 of seed
/// 11): a unit sphere resting by a wall of three long triangles, pushed
/// 282 radii nearly along one of their edges in one frame, ended `2.8e-3`
/// inside.
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
