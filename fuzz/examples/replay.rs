//! Triage: decodes fuzz inputs and runs them through their target's checks
//! without the fuzzing harness, printing the decoded input (Rust values),
//! the geometry it builds and the verdict, one file after another.
//!
//! `cargo run --manifest-path fuzz/Cargo.toml --example replay -- TARGET FILE...`
//! with TARGET one of `sweep_triangle`, `move_robust`, `compare_responses`,
//! `obj_parse`. Add `--brief` for one line per file.

use arbitrary::{Arbitrary, Unstructured};
use std::path::Path;
use std::sync::Arc;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::respond::Response;
use sweepslide::world::{TriangleMesh, World};
use sweepslide_fuzz::input::{MoveInput, Precision, SweepInput, obj_text};
use sweepslide_fuzz::oracle::{MoveCase, check_sweep, play, prepare};

fn moves<T: sweepslide::Real>(case: &MoveCase, all: bool) -> String {
    let prepared = match prepare::<T>(case) {
        Ok(p) => p,
        Err(skip) => return format!("skipped ({skip:?})"),
    };
    let responses: &[Response] = if all { &Response::ALL } else { &[Response::Robust] };
    responses
        .iter()
        .map(|&r| match play(case, &prepared, r) {
            None => format!("{}: ok", r.name()),
            Some(f) => format!("{}: FAILS {f:?}", r.name()),
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let brief = args.iter().any(|a| a == "--brief");
    let mut args = args.into_iter().filter(|a| a != "--brief");
    let target = args.next().expect("usage: replay TARGET FILE...");
    for file in args {
        let data = std::fs::read(&file).expect("read the input");
        let (decoded, verdict) = match target.as_str() {
            "sweep_triangle" => {
                let Ok(input) = SweepInput::arbitrary_take_rest(Unstructured::new(&data)) else { continue };
                let case = input.build();
                let v = match input.precision {
                    Precision::F32 => check_sweep::<f32>(case.base, case.vel, case.tri),
                    Precision::F64 => check_sweep::<f64>(case.base, case.vel, case.tri),
                };
                let v = match v {
                    Ok(Ok(s)) => format!("ok (hit {}, worst {:.3} u*s*k)", s.hit, s.worst),
                    Ok(Err(skip)) => format!("skipped ({skip:?})"),
                    Err(e) => format!("FAILS {e}"),
                };
                (format!("{input:?}\n{case:?}"), v)
            }
            "move_robust" | "compare_responses" => {
                let Ok(input) = MoveInput::arbitrary_take_rest(Unstructured::new(&data)) else { continue };
                let case = input.build();
                let all = target == "compare_responses";
                let v = match input.precision {
                    Precision::F32 => moves::<f32>(&case, all),
                    Precision::F64 => moves::<f64>(&case, all),
                };
                (format!("{input:?}\n{case:?}"), v)
            }
            "obj_parse" => {
                let text = obj_text(&data);
                let v = match TriangleMesh::from_obj_str(&text, Path::new("replay.obj")) {
                    Err(e) => format!("error: {e}"),
                    Ok(mesh) => {
                        let b = *mesh.bounds();
                        let n = mesh.len();
                        match World::<f32>::new(Arc::new(mesh)) {
                            Err(e) => format!("mesh of {n} triangles; in f32: {e}"),
                            Ok(world) => {
                                let (c, d) = (b.centre(), b.max - b.min);
                                let r = (d.norm() * 0.05).clamp(1e-3, 1e3);
                                let body = Ellipsoid::<f32>::sphere(r).expect("radius");
                                let pos = vec3::<f32>(c.x, b.max.y + 2.0 * r, c.z);
                                let vel = vec3::<f32>(d.x * 0.1, -(d.y + 4.0 * r), d.z * 0.1);
                                let hit = sweep_world(
                                    &world,
                                    &body,
                                    &pos,
                                    &vel,
                                    Detection::Robust,
                                    &DetectOptions::default(),
                                );
                                format!("mesh of {n} triangles; sweep of r = {r} from {pos:?} by {vel:?}: {hit:?}")
                            }
                        }
                    }
                };
                (format!("{text:?}"), v)
            }
            other => panic!("unknown target {other}"),
        };
        if brief {
            println!("{file}: {}", verdict.lines().next().unwrap_or(""));
        } else {
            println!("== {file}\n{decoded}\n-> {verdict}\n");
        }
    }
}
