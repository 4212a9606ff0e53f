//! Writes the committed seed corpus, `fuzz/corpus/seeds/<target>/seed-*`:
//! inputs resembling the lab's built-in scenes (floor, corner, wedge,
//! crease, slot, dead-end, tessellated floor, staircase) at the origin and
//! far from it, in `f32` and `f64`, plus hand-picked sweeps and OBJ texts.
//!
//! Run from anywhere: `cargo run --manifest-path fuzz/Cargo.toml --example
//! make_corpus` (stable is enough). Every seed is decoded back with
//! `arbitrary` and must equal what was encoded, and is run through its
//! target's check (in range, and passing) before it is written.

use arbitrary::{Arbitrary, Unstructured};
use std::path::PathBuf;
use sweepslide_fuzz::encode::{Encode, to_bytes};
use sweepslide_fuzz::input::*;
use sweepslide_fuzz::oracle::{check_robust_moves, check_sweep};

fn roundtrip<'a, T: Arbitrary<'a> + Encode + PartialEq + std::fmt::Debug>(x: &T, bytes: &'a [u8]) {
    let back = T::arbitrary_take_rest(Unstructured::new(bytes)).expect("decodes");
    assert_eq!(&back, x, "the encoding does not decode back (has arbitrary's format changed?)");
}

fn write(target: &str, name: &str, bytes: &[u8]) {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/corpus/seeds")).join(target);
    std::fs::create_dir_all(&dir).expect("create the seed directory");
    std::fs::write(dir.join(format!("seed-{name}")), bytes).expect("write a seed");
}

fn sweep_seeds() -> Vec<(String, SweepInput)> {
    let up = Dir::Axis(1);
    let floor = TriShape::Right { normal: up, spin: 0, legs: [255, 255] };
    let regular =
        TriShape::Regular { normal: Dir::Spherical([9000, 20000]), spin: 1234, radii: [128; 3], jitter: [0; 3] };
    let sliver = TriShape::Sliver { normal: Dir::NearAxis(1, [3, -5]), spin: 7, apex: 30000, thin: 160 };
    let head_on = |at| SweepPath::Touch {
        at,
        side: true,
        theta: Angle::Zero,
        azimuth: 0,
        gap: Gap::Zero,
        phi: Angle::Zero,
        heading: 0,
        tau: 0,
        speed: Mag::Unit(30000),
    };
    let graze = |at, gap| SweepPath::Touch {
        at,
        side: true,
        theta: Angle::Uniform(20000),
        azimuth: 100,
        gap,
        phi: Angle::NearRight(6),
        heading: 15000,
        tau: 8000,
        speed: Mag::Unit(50000),
    };
    let mut v = Vec::new();
    let mut add = |name: &str, shape, size, offset, path| {
        for (p, precision) in [("f32", Precision::F32), ("f64", Precision::F64)] {
            v.push((format!("{name}-{p}"), SweepInput { precision, shape, size, offset, path, tail: 0 }));
        }
    };
    add("floor-face", floor, Scale::Large(128), Offset::Origin, head_on(Feature::Face([20000, 20000])));
    add("floor-edge-graze", floor, Scale::Unit(128), Offset::Origin, graze(Feature::Edge(1, 30000), Gap::Ulps32(3)));
    add("vertex", regular, Scale::Unit(100), Offset::Near([8, -3, 2]), head_on(Feature::Vertex(2)));
    add("near-vertex", regular, Scale::Unit(100), Offset::Origin, graze(Feature::NearVertex(0, 9), Gap::Ulps64(-5)));
    add(
        "far-1e5",
        floor,
        Scale::Unit(200),
        Offset::Far(170, [127, 64, -127]),
        graze(Feature::Face([9000, 100]), Gap::Zero),
    );
    add("huge-tri", regular, Scale::Huge(50), Offset::Origin, head_on(Feature::Face([30000, 30000])));
    add("tiny-tri", regular, Scale::Tiny(50), Offset::Origin, graze(Feature::Vertex(1), Gap::Pow(6)));
    add("sliver", sliver, Scale::Unit(128), Offset::Origin, graze(Feature::Edge(2, 40000), Gap::Pow(-9)));
    add(
        "parallel-edge",
        floor,
        Scale::Unit(128),
        Offset::Origin,
        SweepPath::Parallel {
            edge: 0,
            along: -4000,
            side: true,
            theta: Angle::Right,
            gap: Gap::Zero,
            speed: Mag::Unit(40000),
            backward: false,
        },
    );
    add(
        "start-overlap",
        regular,
        Scale::Unit(128),
        Offset::Origin,
        SweepPath::Touch {
            at: Feature::Face([10000, 10000]),
            side: false,
            theta: Angle::Zero,
            azimuth: 0,
            gap: Gap::Fraction(-200),
            phi: Angle::Uniform(10000),
            heading: 0,
            tau: -23405,
            speed: Mag::Tiny(30000),
        },
    );
    add(
        "free",
        regular,
        Scale::Unit(128),
        Offset::Origin,
        SweepPath::Free { base: [3000, 4000, -2000], dir: Dir::Diagonal(5), speed: Mag::Large(10000) },
    );
    v
}

/// The seeds of the move targets: each lab scene with its own defaults.
fn move_seeds() -> Vec<(String, MoveInput)> {
    let scenes: [(&str, u8, u8); 8] = [
        ("floor", 0, 0),
        ("corner-45", 1, 128),
        ("wedge-10", 2, 27),
        ("crease-30", 3, 94),
        ("slot-0.01", 4, 159),
        ("dead-end", 5, 0),
        ("tessellated-floor", 6, 1),
        ("staircase", 7, 0),
    ];
    let default_steps =
        vec![Step { push: Push::SceneDefault, repeat: 3 }, Step { push: Push::SceneDefault, repeat: 3 }];
    let mut v = Vec::new();
    for (name, which, param) in scenes {
        for (p, precision) in [("f32", Precision::F32), ("f64", Precision::F64)] {
            for (o, offset) in [("origin", Offset::Origin), ("far", Offset::Far(85, [127, 0, -127]))] {
                v.push((
                    format!("{name}-{p}-{o}"),
                    MoveInput {
                        precision,
                        body: Body::Sphere(128),
                        offset,
                        pieces: vec![Piece::Scene(which, param)],
                        start: Start::SceneDefault,
                        steps: default_steps.clone(),
                        gravity: Gravity::SceneDefault,
                        tail: 0,
                    },
                ));
            }
        }
    }
    // An ellipsoid in the dead end, a fold and a slot built from pieces.
    v.push((
        "ellipsoid-dead-end-f32".into(),
        MoveInput {
            precision: Precision::F32,
            body: Body::Ellipsoid([128, 160, 100]),
            offset: Offset::Origin,
            pieces: vec![Piece::Scene(5, 0)],
            start: Start::SceneDefault,
            steps: default_steps.clone(),
            gravity: Gravity::Down(Mag::Unit(10000)),
            tail: 0,
        },
    ));
    v.push((
        "fold-near-flat-f32".into(),
        MoveInput {
            precision: Precision::F32,
            body: Body::Sphere(128),
            offset: Offset::Far(40, [127, 127, 127]),
            pieces: vec![Piece::Fold(Fold {
                hinge: Dir::Axis(2),
                spin: 0,
                angle: FoldAngle::NearFlat(4),
                size: Scale::Large(40),
                at: [0; 3],
                diagonal: true,
            })],
            start: Start::Near {
                tri: 0,
                at: Feature::Face([20000, 20000]),
                side: true,
                theta: Angle::Zero,
                gap: Gap::Ulps32(40),
            },
            steps: vec![Step { push: Push::Into(0, Angle::Uniform(50000), 16000, Mag::Unit(30000)), repeat: 3 }],
            gravity: Gravity::None,
            tail: 0,
        },
    ));
    v.push((
        "slot-wedge-f64".into(),
        MoveInput {
            precision: Precision::F64,
            body: Body::Sphere(100),
            offset: Offset::Origin,
            pieces: vec![
                Piece::Slot(Dir::Axis(0), 0, Gap::Ulps64(100), [0; 3]),
                Piece::Fold(Fold {
                    hinge: Dir::Axis(1),
                    spin: 3000,
                    angle: FoldAngle::NearZero(1),
                    size: Scale::Unit(200),
                    at: [0, 0, 24],
                    diagonal: false,
                }),
            ],
            start: Start::Free([0, 0, -8]),
            steps: vec![
                Step { push: Push::Dir(Dir::NearAxis(2, [2, 0]), Mag::Unit(40000)), repeat: 3 },
                Step { push: Push::Into(1, Angle::Zero, 0, Mag::Unit(40000)), repeat: 2 },
            ],
            gravity: Gravity::Dir(Dir::Axis(4), Mag::Tiny(60000)),
            tail: 0,
        },
    ));
    v
}

fn obj_seeds() -> Vec<(String, Vec<u8>)> {
    let texts = [
        ("quad", "# a quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvn 0 1 0\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\n"),
        (
            "cube",
            "o cube\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
             f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 5 1 4 8\n",
        ),
        ("negative", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4//1 -2//1 -1//1\n"),
        ("degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 4\n"),
        ("errors", "v 0 0\nv 1 0 0 1\nf 0 1 2\nl 1 2\n"),
        ("crlf-weights", "v 0 0 0 1\r\nv 1e5 0 0\r\nv 0 1e-5 1e5\r\ns off\r\ng a\r\nusemtl m\r\nf 1 2 3 # c\r\n"),
    ];
    texts
        .iter()
        .map(|(name, t)| {
            let mut bytes = vec![0];
            bytes.extend_from_slice(t.as_bytes());
            assert_eq!(obj_text(&bytes), *t);
            ((*name).to_string(), bytes)
        })
        .collect()
}

fn main() {
    let mut total = 0;
    for (name, input) in sweep_seeds() {
        let bytes = to_bytes(&input);
        roundtrip(&input, &bytes);
        let case = input.build();
        let checked = match input.precision {
            Precision::F32 => check_sweep::<f32>(case.base, case.vel, case.tri),
            Precision::F64 => check_sweep::<f64>(case.base, case.vel, case.tri),
        };
        match checked {
            Ok(Ok(s)) => println!("sweep_triangle/{name}: hit {} worst {:.2} u*s*k", s.hit, s.worst),
            Ok(Err(skip)) => println!("sweep_triangle/{name}: out of range ({skip:?})"),
            Err(e) => panic!("seed {name} fails its check: {e}"),
        }
        write("sweep_triangle", &name, &bytes);
        total += bytes.len();
    }
    for (name, input) in move_seeds() {
        let bytes = to_bytes(&input);
        roundtrip(&input, &bytes);
        let case = input.build();
        let checked = match input.precision {
            Precision::F32 => check_robust_moves::<f32>(&case),
            Precision::F64 => check_robust_moves::<f64>(&case),
        };
        match checked {
            Ok(Ok(())) => println!("move/{name}: {} triangles, {} frames, ok", case.triangles.len(), case.frames.len()),
            Ok(Err(skip)) => println!("move/{name}: out of range ({skip:?})"),
            Err(e) => println!("move/{name}: FAILS: {e}"),
        }
        for target in ["move_robust", "compare_responses"] {
            write(target, &name, &bytes);
            total += bytes.len();
        }
    }
    for (name, bytes) in obj_seeds() {
        write("obj_parse", &name, &bytes);
        total += bytes.len();
    }
    println!("{total} bytes of seeds written");
}
