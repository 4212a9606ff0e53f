//! Any text as an OBJ file: `TriangleMesh::from_obj_str` returns an error
//! or a valid mesh (every triangle validates, indices in range, nothing
//! dropped silently, adjacency and BVH usable), never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use std::sync::Arc;
use sweepslide::Error;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::world::{TriangleMesh, World, parse_obj};
use sweepslide_fuzz::input::obj_text;

fuzz_target!(|data: &[u8]| {
    let text = obj_text(data);
    let path = Path::new("fuzz.obj");
    let parsed = parse_obj(&text, path);
    match TriangleMesh::from_obj_str(&text, path) {
        // A file that parses without a face names itself at its last line.
        Err(Error::Obj { line, message, .. }) if parsed.as_ref().is_ok_and(|d| d.triangles.is_empty()) => {
            assert_eq!(line, line_count(&text), "a face-less file's error at line {line}");
            assert!(message.contains("no face"), "{message}");
            let data = parsed.expect("checked above");
            assert!(
                TriangleMesh::new_skipping_invalid(data.vertices, data.triangles).is_err(),
                "no face for from_obj_str but a mesh from new_skipping_invalid"
            );
        }
        Err(Error::NoValidTriangle { count, first }) => {
            let data = parsed.expect("NoValidTriangle only after a successful parse");
            assert_eq!(count, data.triangles.len(), "NoValidTriangle miscounts");
            assert!(matches!(*first, Error::Obj { line, .. } if line >= 1), "first error without its line: {first:?}");
        }
        Err(Error::Obj { line, .. }) => {
            assert!(parsed.is_err() && line >= 1 && line <= line_count(&text), "bad error line {line}");
        }
        Err(e) => panic!("unexpected error kind {e:?}"),
        Ok(mesh) => {
            let data = parsed.expect("a mesh implies a successful parse");
            assert!(!mesh.is_empty());
            assert_eq!(mesh.len() + mesh.skipped().len(), data.triangles.len(), "a triangle was dropped silently");
            assert_eq!(
                TriangleMesh::new(data.vertices.clone(), data.triangles.clone()).is_ok(),
                mesh.skipped().is_empty()
            );
            let nv = mesh.vertices().len();
            for t in 0..mesh.len() as u32 {
                assert!(mesh.triangles()[t as usize].iter().all(|&i| (i as usize) < nv));
                mesh.triangle(t).validate(t as usize).expect("a kept triangle validates");
                for e in 0..3 {
                    if let Some(n) = mesh.adjacency().neighbour(t, e) {
                        assert!((n as usize) < mesh.len());
                    }
                }
                let _ = mesh.active(t);
            }
            let b = *mesh.bounds();
            // A coordinate beyond `f32`'s range is refused, not rounded to
            // infinity (named by its file and face's line, as `Error::Obj`);
            // nothing else is.
            let huge = b.min.iter().chain(b.max.iter()).any(|x| x.abs() > f64::from(f32::MAX));
            let world = match World::<f32>::new(Arc::new(mesh)) {
                Ok(world) => world,
                Err(e) => {
                    assert!(huge && matches!(e, Error::Obj { .. }), "{e:?}");
                    return;
                }
            };
            let centre = b.centre();
            let d = b.max - b.min;
            let r = (d.norm() * 0.05).clamp(1e-3, 1e3);
            if let Ok(body) = Ellipsoid::<f32>::sphere(r) {
                let pos = vec3::<f32>(centre.x, b.max.y + 2.0 * r, centre.z);
                let vel = vec3::<f32>(d.x * 0.1, -(d.y + 4.0 * r), d.z * 0.1);
                if pos.iter().chain(vel.iter()).all(|x| x.is_finite()) {
                    match sweep_world(&world, &body, &pos, &vel, Detection::Robust, &DetectOptions::default()) {
                        Ok(Some(h)) => assert!((0.0..=1.0).contains(&h.t), "t = {}", h.t),
                        Ok(None) => {}
                        // Refused only where, in radii, a triangle's sides
                        // or the motion overflow `f32` when squared (beyond
                        // about 1.8e19 radii).
                        Err(Error::InvalidArgument { what, .. }) => {
                            assert!(what.starts_with("triangle ") || what == "move", "{what}");
                            assert!(d.amax() / r > 1e17, "refused at {:e} radii", d.amax() / r);
                        }
                        Err(e) => panic!("{e:?}"),
                    }
                }
            }
        }
    }
});

/// The number of lines of `text` (at least 1), each ended by `\n`, `\r\n`
/// or a lone `\r`, or by the end of a text that does not end with one;
/// counted here apart from the reader.
fn line_count(text: &str) -> usize {
    let bytes = text.as_bytes();
    let ends =
        (0..bytes.len()).filter(|&k| bytes[k] == b'\n' || (bytes[k] == b'\r' && bytes.get(k + 1) != Some(&b'\n')));
    let unended = !text.is_empty() && !text.ends_with(['\n', '\r']);
    (ends.count() + usize::from(unended)).max(1)
}
