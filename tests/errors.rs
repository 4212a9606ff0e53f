//! Every kind of bad input is reported with its specific `Error` variant
//! (and the index, axis or line it concerns), never repaired silently.

use std::path::Path;
use sweepslide::Error;
use sweepslide::detect::check_finite;
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::world::TriangleMesh;

/// A unit square in the z = 0 plane as two triangles.
fn square() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    (vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2], [0, 2, 3]])
}

// ---------------------------------------------------------------------------
// TriangleMesh::new
// ---------------------------------------------------------------------------

#[test]
fn valid_mesh_is_accepted() {
    let (v, t) = square();
    let mesh = TriangleMesh::new(v, t).unwrap();
    assert_eq!(mesh.len(), 2);
    assert!(mesh.skipped().is_empty());
}

fn non_finite_vertex(bad: f64) {
    let (mut v, t) = square();
    v[2][1] = bad;
    match TriangleMesh::new(v, t) {
        Err(Error::NonFinite { what, value }) => {
            assert!(value.to_bits() == bad.to_bits() || (value.is_nan() && bad.is_nan()), "value {value}");
            assert!(what.contains("triangle 0"), "the first triangle using vertex 2 is named: {what}");
        }
        other => panic!("expected NonFinite for {bad}, got {other:?}"),
    }
}

#[test]
fn nan_vertex_coordinate_is_non_finite() {
    non_finite_vertex(f64::NAN);
}

#[test]
fn positive_infinite_vertex_coordinate_is_non_finite() {
    non_finite_vertex(f64::INFINITY);
}

#[test]
fn negative_infinite_vertex_coordinate_is_non_finite() {
    non_finite_vertex(f64::NEG_INFINITY);
}

#[test]
fn non_finite_vertex_only_in_second_triangle_names_it() {
    let (mut v, t) = square();
    v[3][0] = f64::NAN; // only triangle 1 uses vertex 3
    match TriangleMesh::new(v, t) {
        Err(Error::NonFinite { what, value }) => {
            assert!(value.is_nan());
            assert!(what.contains("triangle 1"), "{what}");
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
}

#[test]
fn coincident_vertices_are_a_degenerate_triangle() {
    let (mut v, mut t) = square();
    v.push([0.5, 0.5, 0.0]);
    t.push([4, 4, 1]); // index 2: two corners are the same vertex
    match TriangleMesh::new(v.clone(), t) {
        Err(Error::DegenerateTriangle { index, reason }) => {
            assert_eq!(index, 2);
            assert!(reason.contains("coincide"), "{reason}");
        }
        other => panic!("expected DegenerateTriangle, got {other:?}"),
    }
    // Two distinct vertices at the same position.
    v.push([0.5, 0.5, 0.0]);
    let t = vec![[0, 1, 2], [4, 5, 0], [0, 2, 3]];
    match TriangleMesh::new(v, t) {
        Err(Error::DegenerateTriangle { index, reason }) => {
            assert_eq!(index, 1);
            assert!(reason.contains("coincide"), "{reason}");
        }
        other => panic!("expected DegenerateTriangle, got {other:?}"),
    }
}

#[test]
fn collinear_vertices_are_a_degenerate_triangle() {
    let (mut v, mut t) = square();
    v.extend([[0.0, 0.0, 5.0], [1.0, 2.0, 8.0], [3.0, 6.0, 14.0]]);
    t.push([4, 5, 6]); // index 2
    match TriangleMesh::new(v, t) {
        Err(Error::DegenerateTriangle { index, reason }) => {
            assert_eq!(index, 2);
            assert!(reason.contains("collinear"), "{reason}");
        }
        other => panic!("expected DegenerateTriangle, got {other:?}"),
    }
}

#[test]
fn nearly_collinear_sliver_within_rounding_is_degenerate() {
    // The third vertex is off the line by far less than the rounding noise.
    let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 1e-300, 0.0], [0.0, 1.0, 0.0]];
    match TriangleMesh::new(v, vec![[0, 3, 1], [0, 1, 2]]) {
        Err(Error::DegenerateTriangle { index: 1, .. }) => {}
        other => panic!("expected DegenerateTriangle for triangle 1, got {other:?}"),
    }
}

#[test]
fn well_shaped_triangles_validate_at_any_scale() {
    // Their squared areas overflow (1e160) or underflow (1e-170) `f64`:
    // they were once reported as collinear.
    for scale in [1e160, 1e-170, 1e300, 1e-300, 1.0] {
        let v = [[0.0, 0.0, 0.0], [scale, 0.0, 0.0], [0.0, scale, 0.0], [scale, scale, 0.0]];
        let mesh = TriangleMesh::new(v.to_vec(), vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(mesh.map(|m| m.len()), Ok(2), "scale {scale}");
    }
}

#[test]
fn vertex_index_out_of_range() {
    let (v, mut t) = square();
    t.push([0, 2, 4]); // index 2; only 4 vertices
    assert_eq!(
        TriangleMesh::new(v, t).unwrap_err(),
        Error::VertexIndexOutOfRange { triangle: 2, vertex: 4, vertex_count: 4 }
    );
    let (v, _) = square();
    assert_eq!(
        TriangleMesh::new(v, vec![[u32::MAX, 0, 1]]).unwrap_err(),
        Error::VertexIndexOutOfRange { triangle: 0, vertex: u32::MAX as usize, vertex_count: 4 }
    );
}

#[test]
fn first_bad_triangle_is_reported() {
    let (mut v, _) = square();
    v.push([f64::NAN, 0.0, 0.0]);
    let t = vec![[0, 1, 2], [0, 0, 1], [0, 1, 9], [0, 1, 4]];
    match TriangleMesh::new(v, t) {
        Err(Error::DegenerateTriangle { index: 1, .. }) => {}
        other => panic!("expected DegenerateTriangle for triangle 1, got {other:?}"),
    }
}

#[test]
fn empty_mesh() {
    assert_eq!(TriangleMesh::new(vec![], vec![]).unwrap_err(), Error::EmptyMesh);
    let (v, _) = square();
    assert_eq!(TriangleMesh::new(v.clone(), vec![]).unwrap_err(), Error::EmptyMesh);
    assert_eq!(TriangleMesh::new_skipping_invalid(v, vec![]).unwrap_err(), Error::EmptyMesh);
}

#[test]
fn new_skipping_invalid_keeps_valid_triangles_and_lists_skipped_ones() {
    let (mut v, _) = square();
    v.push([f64::INFINITY, 0.0, 0.0]); // vertex 4
    v.push([2.0, 0.0, 0.0]); // vertex 5, collinear with 0 and 1
    let t = vec![
        [0, 1, 2], // 0 ok
        [0, 0, 2], // 1 coincident
        [0, 2, 3], // 2 ok
        [0, 1, 7], // 3 out of range
        [0, 1, 4], // 4 non-finite
        [0, 1, 5], // 5 collinear
    ];
    let mesh = TriangleMesh::new_skipping_invalid(v, t).unwrap();
    assert_eq!(mesh.triangles(), &[[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.len(), 2);
    let skipped = mesh.skipped();
    assert_eq!(skipped.len(), 4, "{skipped:?}");
    assert!(matches!(&skipped[0], Error::DegenerateTriangle { index: 1, .. }), "{:?}", skipped[0]);
    assert_eq!(skipped[1], Error::VertexIndexOutOfRange { triangle: 3, vertex: 7, vertex_count: 6 });
    assert!(
        matches!(&skipped[2], Error::NonFinite { what, value } if what.contains("triangle 4") && *value == f64::INFINITY),
        "{:?}",
        skipped[2]
    );
    assert!(matches!(&skipped[3], Error::DegenerateTriangle { index: 5, .. }), "{:?}", skipped[3]);
}

/// A lenient constructor left with no valid triangle says how many there
/// were and why the first was rejected (it once said only "no valid
/// triangle").
#[test]
fn new_skipping_invalid_with_no_valid_triangle_says_why() {
    let (v, _) = square();
    let result = TriangleMesh::new_skipping_invalid(v, vec![[0, 0, 1], [1, 2, 9]]);
    match result.unwrap_err() {
        Error::NoValidTriangle { count: 2, first } => {
            assert!(matches!(*first, Error::DegenerateTriangle { index: 0, .. }), "{first:?}")
        }
        e => panic!("{e:?}"),
    }
    let text = format!("{V4}f 1 1 2\nf 1 2 2\n");
    match TriangleMesh::from_obj_str(&text, Path::new("flat.obj")).unwrap_err() {
        e @ Error::NoValidTriangle { count: 2, .. } => {
            let message = e.to_string();
            assert!(message.contains("flat.obj:5:"), "{message}");
        }
        e => panic!("{e:?}"),
    }
}

// ---------------------------------------------------------------------------
// Ellipsoid radii
// ---------------------------------------------------------------------------

fn invalid_radius<T: sweepslide::Real>() {
    let cases = [
        ([0.0, 1.0, 1.0], 'x', 0.0),
        ([1.0, -0.0, 1.0], 'y', -0.0),
        ([1.0, 1.0, -2.0], 'z', -2.0),
        ([f64::NAN, 1.0, 1.0], 'x', f64::NAN),
        ([1.0, f64::INFINITY, 1.0], 'y', f64::INFINITY),
        ([1.0, 1.0, f64::NEG_INFINITY], 'z', f64::NEG_INFINITY),
        // The first bad axis is named.
        ([1.0, 0.0, -1.0], 'y', 0.0),
    ];
    for (radii, axis, value) in cases {
        match Ellipsoid::<T>::new(radii) {
            Err(Error::InvalidRadius { axis: a, value: v }) => {
                assert_eq!(a, axis, "{radii:?}");
                assert!(v.to_bits() == value.to_bits() || (v.is_nan() && value.is_nan()), "{radii:?}: {v}");
            }
            other => panic!("{}: expected InvalidRadius for {radii:?}, got {other:?}", T::name()),
        }
    }
    for (r, expected) in [(0.0, 0.0), (-1.0, -1.0), (f64::INFINITY, f64::INFINITY)] {
        assert_eq!(Ellipsoid::<T>::sphere(r).unwrap_err(), Error::InvalidRadius { axis: 'x', value: expected });
    }
    assert!(matches!(
        Ellipsoid::<T>::sphere(f64::NAN),
        Err(Error::InvalidRadius { axis: 'x', value }) if value.is_nan()
    ));
    assert!(Ellipsoid::<T>::new([0.5, 1.0, 2.0]).is_ok());
    assert!(Ellipsoid::<T>::sphere(1e-3).is_ok());
}

#[test]
fn invalid_radius_f32() {
    invalid_radius::<f32>();
    // Radii that are fine in f64 but not in f32: underflow to 0, overflow to inf.
    assert_eq!(Ellipsoid::<f32>::sphere(1e-50).unwrap_err(), Error::InvalidRadius { axis: 'x', value: 1e-50 });
    assert_eq!(Ellipsoid::<f32>::new([1.0, 1.0, 1e40]).unwrap_err(), Error::InvalidRadius { axis: 'z', value: 1e40 });
    assert!(Ellipsoid::<f64>::sphere(1e-50).is_ok());
}

#[test]
fn invalid_radius_f64() {
    invalid_radius::<f64>();
}

#[cfg(feature = "mpfr")]
#[test]
fn invalid_radius_mpfr() {
    use sweepslide::Mpfr;
    invalid_radius::<Mpfr<24>>();
    invalid_radius::<Mpfr<113>>();
    // MPFR's exponent range holds a radius of 1e-309 and its inverse, but
    // the world's BVH measures the reach in `f64`, where that inverse is
    // infinite: every ball query came back empty and every wall was missed
    // (a review); such radii are refused, by both constructors.
    assert_eq!(Ellipsoid::<Mpfr<53>>::sphere(1e-309).unwrap_err(), Error::InvalidRadius { axis: 'x', value: 1e-309 });
    let tiny = Mpfr::<113>::from_rug(&(rug::Float::with_val(113, 1) >> 2000u32));
    let radii = sweepslide::geom::vec3::<Mpfr<113>>(1.0, 1.0, 1.0).map(|r| r * &tiny);
    assert_eq!(Ellipsoid::from_radii(radii).unwrap_err(), Error::InvalidRadius { axis: 'x', value: 0.0 });
    assert!(Ellipsoid::<Mpfr<53>>::sphere(1e-300).is_ok());
}

// ---------------------------------------------------------------------------
// Precision
// ---------------------------------------------------------------------------

#[cfg(feature = "mpfr")]
#[test]
fn precision_out_of_range() {
    use sweepslide::real::{MAX_BITS, MIN_BITS, with_precision};
    for bits in [0, 1] {
        let mut ran = false;
        let result = with_precision(bits, || ran = true);
        assert_eq!(result.unwrap_err(), Error::PrecisionOutOfRange { bits, min: MIN_BITS, max: MAX_BITS });
        assert!(!ran, "the closure must not run for {bits} bits");
    }
    assert_eq!(MIN_BITS, 2);
    if let Some(too_many) = MAX_BITS.checked_add(1) {
        assert!(
            matches!(with_precision(too_many, || ()), Err(Error::PrecisionOutOfRange { bits, .. }) if bits == too_many)
        );
    }
    assert!(with_precision(MIN_BITS, || ()).is_ok());
}

/// `Real::with_bits`, the hand-over of a thread's precision, checks it as
/// `with_precision` does: 0 bits panicked inside MPFR, and 1 ran below
/// `MIN_BITS` (a review, session 29). The fixed backends ignore it.
#[cfg(feature = "mpfr")]
#[test]
fn with_bits_out_of_range() {
    use sweepslide::real::{MAX_BITS, MIN_BITS};
    use sweepslide::{MpfrDyn, Real};
    for bits in [0, 1, MAX_BITS + 1] {
        let mut ran = false;
        let result = <MpfrDyn as Real>::with_bits(bits, || ran = true);
        assert_eq!(result.unwrap_err(), Error::PrecisionOutOfRange { bits, min: MIN_BITS, max: MAX_BITS });
        assert!(!ran, "the closure must not run for {bits} bits");
    }
    assert_eq!(<MpfrDyn as Real>::with_bits(77, || MpfrDyn::from_f64(1.5).own_bits()), Ok(Some(77)));
    assert_eq!(<f32 as Real>::with_bits(0, || 2), Ok(2));
}

// ---------------------------------------------------------------------------
// detect::check_finite
// ---------------------------------------------------------------------------

fn check_finite_for<T: sweepslide::Real>() {
    assert_eq!(check_finite("velocity", &vec3::<T>(1.0, -2.0, 3.0)), Ok(()));
    assert_eq!(check_finite("velocity", &vec3::<T>(0.0, -0.0, 1e-30)), Ok(()));
    match check_finite("velocity", &vec3::<T>(1.0, f64::NAN, 0.0)) {
        Err(Error::NonFinite { what, value }) => {
            assert_eq!(what, "velocity");
            assert!(value.is_nan());
        }
        other => panic!("{}: expected NonFinite, got {other:?}", T::name()),
    }
    assert_eq!(
        check_finite("position", &vec3::<T>(1.0, 2.0, f64::INFINITY)),
        Err(Error::NonFinite { what: "position".into(), value: f64::INFINITY })
    );
    assert_eq!(
        check_finite("gravity", &vec3::<T>(f64::NEG_INFINITY, 2.0, 0.0)),
        Err(Error::NonFinite { what: "gravity".into(), value: f64::NEG_INFINITY })
    );
}

#[test]
fn check_finite_reports_non_finite() {
    check_finite_for::<f32>();
    check_finite_for::<f64>();
    #[cfg(feature = "mpfr")]
    check_finite_for::<sweepslide::Mpfr<53>>();
    // A value that overflows f32 only.
    assert!(check_finite("p", &vec3::<f64>(1e300, 0.0, 0.0)).is_ok());
    assert_eq!(
        check_finite("p", &vec3::<f32>(1e300, 0.0, 0.0)),
        Err(Error::NonFinite { what: "p".into(), value: f64::INFINITY })
    );
}

// ---------------------------------------------------------------------------
// OBJ
// ---------------------------------------------------------------------------

const V4: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

/// Parses `text` and asserts an `Error::Obj` on `line` whose message
/// contains `needle`.
#[track_caller]
fn obj_error(text: &str, line: usize, needle: &str) {
    match TriangleMesh::from_obj_str(text, Path::new("x.obj")) {
        Err(Error::Obj { path, line: l, message }) => {
            assert_eq!(path, Path::new("x.obj"));
            assert_eq!(l, line, "wrong line for {text:?}: {message}");
            assert!(message.contains(needle), "message {message:?} lacks {needle:?}");
        }
        other => panic!("expected Error::Obj at line {line} for {text:?}, got {other:?}"),
    }
}

#[test]
fn obj_bad_number() {
    obj_error(&format!("{V4}v 1 x 2\nf 1 2 3\n"), 5, "`x` is not a number");
    obj_error("# header\n\nv 1.0 2.0 3.0.0\n", 3, "not a number");
}

/// A control character in a quoted word is escaped, not written to the
/// terminal (a review, thirty-eighth session: a NUL byte of an index).
#[test]
fn obj_error_escapes_control_characters() {
    obj_error(&format!("{V4}f 1 2 3\u{0}\n"), 5, "`3\\0`");
    obj_error(&format!("{V4}v 1 \u{1b}[31m 2\n"), 5, "`\\u{1b}[31m` is not a number");
}

/// A review's finding (twenty-sixth session): the message quoted the
/// offending word whole, so a 2 MB line gave a 2 MB error. The quoted word
/// is cut now, saying how long it was, and the message still says what is
/// wrong with it.
#[test]
fn obj_error_on_a_huge_word_is_short() {
    let word = "x".repeat(2_000_000);
    obj_error(&format!("{V4}v 1 {word} 2\n"), 5, "...` (2000000 characters) is not a number");
    obj_error(&format!("{V4}{word} 1 2\n"), 5, "unknown statement `xxx");
    for text in [format!("{V4}v 1 {word} 2\n"), format!("{V4}f 1 2 {word}\n"), format!("{V4}f 1 2 3/{word}\n")] {
        match TriangleMesh::from_obj_str(&text, Path::new("x.obj")) {
            Err(Error::Obj { message, .. }) => {
                assert!(message.len() < 300, "{} bytes: {}", message.len(), &message[..300])
            }
            other => panic!("{other:?}"),
        }
    }
}

/// The optional fourth value of `v` (the weight) is a number too.
#[test]
fn obj_bad_vertex_weight_is_a_bad_number() {
    obj_error(&format!("{V4}v 1 2 3 w\nf 1 2 3\n"), 5, "not a number");
}

#[test]
fn obj_too_few_vertex_coordinates() {
    obj_error(&format!("{V4}f 1 2 3\nv 1 2\n"), 6, "found 2");
    obj_error("v\n", 1, "found 0");
    obj_error("v 1 2 3 4 5\n", 1, "found 5");
}

#[test]
fn obj_face_with_fewer_than_three_vertices() {
    obj_error(&format!("{V4}f 1 2\n"), 5, "at least 3");
    obj_error(&format!("{V4}\n\nf\n"), 7, "found 0");
}

#[test]
fn obj_index_zero() {
    obj_error(&format!("{V4}f 1 2 3\nf 0 1 2\n"), 6, "index 0");
    obj_error(&format!("{V4}vt 0 0\nf 1/1 0/1 2/1\n"), 6, "index 0");
}

#[test]
fn obj_index_out_of_range_positive() {
    obj_error(&format!("{V4}f 1 2 5\n"), 5, "out of range");
    // Forward references are out of range too (only vertices read so far).
    obj_error(&format!("v 0 0 0\nv 1 0 0\nf 1 2 3\n{V4}"), 3, "out of range");
}

#[test]
fn obj_index_out_of_range_negative() {
    obj_error(&format!("{V4}f -1 -2 -5\n"), 5, "out of range");
    obj_error(&format!("{V4}f -1 -2 -3\nf -5//1 -1//1 -2//1\n"), 6, "out of range");
}

#[test]
fn obj_non_numeric_index() {
    obj_error(&format!("{V4}f 1 two 3\n"), 5, "not a vertex index");
    obj_error(&format!("{V4}f 1 2 /3\n"), 5, "not a vertex index");
    obj_error(&format!("{V4}f 1 2 3.0\n"), 5, "not a vertex index");
}

/// A face corner's texture and normal indices are checked like its
/// vertex's, against the `vt` and `vn` statements read so far.
#[test]
fn obj_texture_and_normal_indices_are_checked() {
    let vt_vn = "vt 0 0\nvt 1 0\nvn 0 0 1\n";
    obj_error(&format!("{V4}{vt_vn}f 1/2/1 2/x/1 3//1\n"), 8, "`x` is not a texture coordinate index");
    obj_error(&format!("{V4}{vt_vn}f 1/3 2/1 3/1\n"), 8, "texture coordinate index 3 is out of range");
    obj_error(&format!("{V4}{vt_vn}f 1//2 2//1 3//1\n"), 8, "normal index 2 is out of range");
    obj_error(&format!("{V4}{vt_vn}f 1/0/1 2/1/1 3/1/1\n"), 8, "texture coordinate index 0");
    obj_error(&format!("{V4}{vt_vn}f 1/1/1/1 2 3\n"), 8, "not a face corner");
    // Valid references, negative ones included, are read (and not used).
    let mesh = TriangleMesh::from_obj_str(&format!("{V4}{vt_vn}f 1/1/1 2/-1/-1 3//1 4/2\n"), Path::new("x.obj"));
    assert_eq!(mesh.map(|m| m.len()), Ok(2));
}

#[test]
fn obj_line_and_point_elements() {
    obj_error(&format!("{V4}f 1 2 3\nl 1 2\n"), 6, "`l`");
    obj_error(&format!("{V4}p 1\nf 1 2 3\n"), 5, "`p`");
}

#[test]
fn obj_unknown_statement() {
    obj_error(&format!("{V4}f 1 2 3\nbogus 1 2 3\n"), 6, "unknown statement `bogus`");
    obj_error("V 0 0 0\n", 1, "unknown statement `V`");
}

#[test]
fn obj_non_finite_coordinate() {
    obj_error(&format!("{V4}v 1 inf 2\n"), 5, "not finite");
    obj_error(&format!("{V4}v 1 2 NaN\n"), 5, "not finite");
    obj_error("v -infinity 0 0\n", 1, "not finite");
    // Overflowing decimal literals parse to infinity and are rejected too.
    obj_error("v 1e400 0 0\n", 1, "not finite");
}

#[test]
fn obj_error_line_numbers_count_blank_and_comment_lines() {
    let text = "# a comment\n\n   \nv 0 0 0 # trailing comment\nv 1 0 0\r\nv 0 1 0\n\nf 1 2 3\nf 1 2 4\n";
    obj_error(text, 9, "out of range");
}

/// Lone `\r` line ends (classic Mac OS) count as line ends: the file
/// reads like its `\n` twin, and errors name the same line. (They were
/// one line, whose first `v` statement then had every coordinate of the
/// file.)
#[test]
fn obj_lone_carriage_returns_end_lines() {
    let unix = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n";
    let mac = unix.replace('\n', "\r");
    let mixed = "v 0 0 0\r\nv 1 0 0\rv 0 1 0\nv 0 0 1\r\rf 1 2 3\nf 1 2 4";
    let read = |text: &str| TriangleMesh::from_obj_str(text, Path::new("x.obj")).unwrap();
    let expected = read(unix);
    assert_eq!(expected.len(), 2);
    for text in [mac.as_str(), mixed] {
        let mesh = read(text);
        assert_eq!(mesh.len(), 2, "{text:?}");
        assert_eq!(mesh.vertices(), expected.vertices(), "{text:?}");
    }
    obj_error("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 5\r", 4, "out of range");
    // The blank line between `\r\r` counts; `\r\n` is one line end.
    obj_error("v 0 0 0\r\nv 1 0 0\r\rv 0 1 0\nf 1 2 5", 5, "out of range");
    obj_error("v 0 0 0\rv 1 0 0\r", 2, "no face");
}

/// A backslash at the end of a line's content continues the statement on
/// the next line (the OBJ specification's line continuation); its errors
/// name the statement's first line. A backslash inside a comment does not
/// continue anything, and one on the last line ends the statement there.
#[test]
fn obj_backslash_continues_a_statement() {
    let text = "v 0 0 \\\n 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 \\  \r\n2 \\\n3 4 # a quad over three lines\n";
    let mesh = TriangleMesh::from_obj_str(text, Path::new("x.obj")).unwrap();
    assert_eq!(mesh.len(), 2);
    assert_eq!(mesh.vertices()[0], nalgebra::Vector3::new(0.0, 0.0, 0.0));
    obj_error("v 0 0 0\nv 1 \\\n0 x\nv 0 1 0\nf 1 2 3\n", 2, "`x` is not a number");
    obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n# comment \\\nf 1 2 4\n", 5, "out of range");
    obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\", 4, "at least 3 vertices");
}

#[test]
fn obj_missing_file_is_io_error() {
    let path = Path::new("/nonexistent-sweepslide-dir/missing.obj");
    match TriangleMesh::from_obj_file(path) {
        Err(Error::Io { path: p, message }) => {
            assert_eq!(p, path);
            assert!(!message.is_empty());
        }
        other => panic!("expected Error::Io, got {other:?}"),
    }
}

/// A file without faces names itself (with several meshes in a report,
/// `Error::EmptyMesh` alone did not say which: a review).
#[test]
fn obj_file_without_faces_names_its_path() {
    obj_error("", 1, "no face");
    obj_error(&format!("# only vertices\n{V4}vn 0 0 1\n"), 6, "no face");
}

/// A concave polygon whose fan from its first corner folds over itself is
/// refused with its line: the fan covered the notch twice and area outside
/// the polygon (an arrowhead of area 1 became triangles of area 3, found by
/// a review). A polygon star-shaped around its first corner, a non-planar
/// one, and one with a corner on a side (whose collinear fan triangle is
/// rounding noise, skipped as degenerate) are kept.
#[test]
fn obj_concave_polygon_whose_fan_folds_is_refused() {
    let arrow = "v 0 0 0\nv 2 0 -1\nv 1 0 0\nv 2 0 1\n";
    obj_error(&format!("{arrow}f 2 3 4 1\n"), 5, "concave");
    // The same arrowhead around its reflex corner: a valid fan.
    let mesh = TriangleMesh::from_obj_str(&format!("{arrow}f 3 4 1 2\n"), Path::new("x.obj")).unwrap();
    assert_eq!(mesh.triangles(), &[[2, 3, 0], [2, 0, 1]]);
    // Refused at every scale the mesh accepts (the fan's products were
    // once unscaled, and the test blind beyond 1e77 and below 1e-81).
    for scale in [1e-170, 1e-82, 1e77, 1e160] {
        let arrow: String = [[0.0, 0.0, 0.0], [2.0, 0.0, -1.0], [1.0, 0.0, 0.0], [2.0, 0.0, 1.0]]
            .iter()
            .map(|p| format!("v {:e} {:e} {:e}\n", p[0] * scale, p[1] * scale, p[2] * scale))
            .collect();
        obj_error(&format!("{arrow}f 2 3 4 1\n"), 5, "concave");
    }
    // A bowtie whose two halves cancel exactly (a review: no polygon
    // normal was left to judge them by, and it was kept), and a lopsided
    // one.
    for top in ["1", "1.5"] {
        obj_error(&format!("v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 {top} 0\nf 1 2 3 4\n"), 5, "concave");
    }
    // A warped quad.
    let warped = "v 0 0 0\nv 1 0 0.2\nv 1 1 0\nv 0 1 0.2\nf 1 2 3 4\n";
    assert_eq!(TriangleMesh::from_obj_str(warped, Path::new("x.obj")).unwrap().len(), 2);
    // A square with a corner on its first side, seen from the far side's
    // corner 0.1 / 3 off the grid (rounding in every cross product).
    let side = "v 0.1 0.3 0\nv 0.1 0.2 0\nv 0.1 0.1 0\nv 0.9 0.1 0\nv 0.9 0.3 0\nf 1 2 3 4 5\n";
    let mesh = TriangleMesh::from_obj_str(side, Path::new("x.obj")).unwrap();
    assert_eq!((mesh.len(), mesh.skipped().len()), (2, 1));
}

/// Free-form geometry is refused like lines and points, not dropped; the
/// statements that carry no collision geometry are counted by keyword with
/// their first line, and reported in the load notes.
#[test]
fn obj_free_form_is_refused_and_ignored_statements_are_counted() {
    obj_error(&format!("{V4}f 1 2 3\ncstype bspline\ndeg 3 3\nsurf 0 1 0 1 1 2 3 4\n"), 8, "`surf`: free-form");
    obj_error(&format!("{V4}curv 0 1 1 2\n"), 5, "`curv`");
    let text = format!("o thing\n{V4}vn 0 0 1\nvn 0 0 1\ns off\nf 1//1 2//2 3//1\n");
    let mesh = TriangleMesh::from_obj_str(&text, Path::new("x.obj")).unwrap();
    let ignored: Vec<_> = mesh.ignored().iter().map(|i| (i.keyword.as_str(), i.count, i.first_line)).collect();
    assert_eq!(ignored, [("o", 1, 1), ("vn", 2, 6), ("s", 1, 8)]);
    let notes = mesh.load_notes("x.obj");
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].contains("2 `vn` (first on line 6)"), "{notes:?}");
    assert!(
        TriangleMesh::from_obj_str(&format!("{V4}f 1 2 3\n"), Path::new("x.obj")).unwrap().load_notes("x").is_empty()
    );
}

/// A triangle whose sides overflow `f64` says so, instead of calling its
/// vertices collinear (a review).
#[test]
fn a_triangle_whose_sides_overflow_says_so() {
    let v = vec![[-1e308, 0.0, 0.0], [1e308, 0.0, 0.0], [0.0, 1e308, 0.0]];
    match TriangleMesh::new(v, vec![[0, 1, 2]]) {
        Err(Error::InvalidArgument { what, message }) => {
            assert_eq!(what, "triangle 0");
            assert!(message.contains("overflow"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn obj_valid_file_parses_to_expected_triangles() {
    let text = "\
# a quad, a pentagon, and every face-corner form
mtllib scene.mtl
o thing
g group
s off
usemtl stone
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0   # weightless
v 0.5 2 0 1.0
vt 0 0
vt 1 0
vt 1 1
vn 0 0 1
f 1 2 3 4
f 1/1 2/2 3/3
f 1/1/1 2/2/1 3/3/1
f 1//1 2//1 3//1
f -5 -4 -3 -1 -2
f -5/1/1 -4/2/1 -3/3/1
";
    let mesh = TriangleMesh::from_obj_str(text, Path::new("x.obj")).unwrap();
    assert!(mesh.skipped().is_empty(), "{:?}", mesh.skipped());
    assert_eq!(mesh.vertices().len(), 5);
    let v4: [f64; 3] = mesh.vertices()[4].into();
    assert_eq!(v4, [0.5, 2.0, 0.0]);
    assert_eq!(
        mesh.triangles(),
        &[
            // quad, fan around its first corner
            [0, 1, 2],
            [0, 2, 3],
            // v/vt, v/vt/vn, v//vn
            [0, 1, 2],
            [0, 1, 2],
            [0, 1, 2],
            // pentagon with negative indices: 1 2 3 5 4
            [0, 1, 2],
            [0, 2, 4],
            [0, 4, 3],
            // negative with slashes
            [0, 1, 2],
        ]
    );
}

#[test]
fn obj_degenerate_face_is_skipped_with_its_line() {
    let text = format!("{V4}f 1 2 3\nf 1 1 2\nf 1 3 4\n");
    let mesh = TriangleMesh::from_obj_str(&text, Path::new("x.obj")).unwrap();
    assert_eq!(mesh.triangles(), &[[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.skipped().len(), 1);
    match &mesh.skipped()[0] {
        Error::Obj { path, line, message } => {
            assert_eq!(path, Path::new("x.obj"));
            assert_eq!(*line, 6);
            assert!(message.contains("degenerate"), "{message}");
        }
        other => panic!("expected Error::Obj, got {other:?}"),
    }
}

/// A mesh moved far from the origin (`sweepslide run --offset`) names the
/// OBJ lines of the triangles the move collapses, and keeps naming the
/// right ones after earlier faces were skipped (left alone in the
/// twenty-first session: they were named by their index among the kept
/// triangles, which no file shows).
#[test]
fn a_moved_obj_mesh_names_the_lines_of_the_triangles_it_collapses() {
    // Line 1 a comment, a degenerate face on line 7 (skipped on loading),
    // a large triangle on line 8, one thin along x (1e-3) on line 9 and one
    // thin along y on line 10.
    let text =
        "# big and thin\nv 0 0 0\nv 100 0 0\nv 0 0 100\nv 0.001 0 0\nv 0 0.001 0\nf 1 1 2\nf 1 3 2\nf 1 3 4\nf 1 2 5\n";
    let mesh = TriangleMesh::from_obj_str(text, Path::new("x.obj")).unwrap();
    assert_eq!(mesh.len(), 3);
    let line_of = |m: &TriangleMesh| match m.skipped() {
        [Error::Obj { path, line, message }] => {
            assert_eq!(path, Path::new("x.obj"));
            assert!(message.contains("degenerate"), "{message}");
            *line
        }
        other => panic!("expected one Error::Obj, got {other:?}"),
    };
    // At 1e14 a coordinate is rounded to 1/64: moved along x, the triangle
    // thin along x collapses, the others keep their shape.
    let moved = mesh.moved(|v| [v.x + 1e14, v.y, v.z]).unwrap();
    assert_eq!(moved.len(), 2);
    assert_eq!(line_of(&moved), 9, "only what the move collapsed, by its line");
    // Moved again along y, the line still follows the triangle (index 1
    // among the two kept, 2 among the file's valid faces).
    let twice = moved.moved(|v| [v.x, v.y + 1e14, v.z]).unwrap();
    assert_eq!((twice.len(), line_of(&twice)), (1, 10));
    // Each kept triangle maps back to the file's faces (0 degenerate, then
    // the big one, the one thin along x, the one thin along y).
    assert_eq!((0..3).map(|t| mesh.input_index(t)).collect::<Vec<_>>(), [1, 2, 3]);
    assert_eq!((twice.input_index(0), moved.input_index(1)), (1, 3));
    // A mesh not read from OBJ names the triangle by its index.
    let plain = TriangleMesh::new(mesh.vertices().iter().map(|v| [v.x, v.y, v.z]).collect(), mesh.triangles().to_vec())
        .unwrap();
    let moved = plain.moved(|v| [v.x + 1e14, v.y, v.z]).unwrap();
    assert!(matches!(&moved.skipped()[0], Error::DegenerateTriangle { index: 1, .. }), "{:?}", moved.skipped());
}

/// A review (twenty-second session): skipping a triangle renumbered the
/// kept ones with no way back to the input's numbering (per-triangle user
/// data went to the wrong triangle), and a moved mesh lost its
/// internal-edge angle.
#[test]
fn kept_triangles_map_back_to_the_input_and_a_move_keeps_the_edge_angle() {
    // Input 0 collinear (skipped), 1 a floor, 2 a ceiling.
    let vertices = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]];
    let mesh = TriangleMesh::new_skipping_invalid(vertices, vec![[0, 1, 2], [0, 1, 4], [0, 3, 1]]).unwrap();
    assert!(matches!(mesh.skipped(), [Error::DegenerateTriangle { index: 0, .. }]), "{:?}", mesh.skipped());
    assert_eq!((mesh.len(), mesh.input_index(0), mesh.input_index(1)), (2, 1, 2));
    // A fold of 20 degrees: internal under a 30 degree threshold, moved or not.
    let (s, c) = 20f64.to_radians().sin_cos();
    let fold = TriangleMesh::new(
        vec![[0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [c, 0.0, -s]],
        vec![[0, 1, 2], [1, 0, 3]],
    )
    .unwrap();
    assert!(fold.active(0).edge(0), "a 20 degree fold is a real edge by default");
    let wide = fold.with_internal_edge_angle(30.0).unwrap();
    assert!(!wide.active(0).edge(0));
    assert!(!wide.moved(|v| [v.x + 10.0, v.y, v.z]).unwrap().active(0).edge(0), "the move keeps the threshold");
}

// ---------------------------------------------------------------------------
// Scene::from_case_file (fuzz cases as lab scenes)
// ---------------------------------------------------------------------------

/// The same folds at any scale the mesh accepts: the normals are taken
/// from edges scaled by a power of two (unscaled, the cross product's
/// square overflowed beyond sides of about 1e77 and underflowed below
/// 1e-81, making flat edges active and, near the underflow, convex folds
/// of 6 to 30 degrees internal: a review).
#[test]
fn internal_edges_are_found_at_any_scale() {
    let (s, c) = 30f64.to_radians().sin_cos();
    for scale in [1.77e-81, 1e-200, 1.0, 1e80, 1e300] {
        let ridge = |fold: f64| {
            let v = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [c, fold * s, 0.0]];
            let v = v.iter().map(|p| p.map(|x| x * scale)).collect();
            TriangleMesh::new(v, vec![[0, 1, 2], [1, 0, 3]]).unwrap()
        };
        let flat = |fold: f64| !ridge(fold).with_internal_edge_angle(31.0).unwrap().active(0).edge(0);
        let active = |fold: f64| ridge(fold).active(0).edge(0);
        assert!(flat(1.0) && flat(-1.0), "scale {scale:e}: a 30 degree fold within a 31 degree threshold");
        assert!(active(1.0) && active(-1.0), "scale {scale:e}: a 30 degree fold is a real edge, convex or concave");
    }
    // A convex right-angled ridge between a sliver and a wall, turned
    // every way: the sliver's normal is tilted by `eps / sin` of its angle,
    // which lifted the shared edge's own ends and called the ridge concave
    // (internal) in half the orientations for a sliver `1e-6` thin.
    for k in 0..200 {
        let (a, b) = (0.3 + 0.005 * f64::from(k), 0.7 + 0.01 * f64::from(k));
        let turn = |p: [f64; 3]| {
            let (x, y, z) = (p[0] * a.cos() - p[1] * a.sin(), p[0] * a.sin() + p[1] * a.cos(), p[2]);
            [x, y * b.cos() - z * b.sin(), y * b.sin() + z * b.cos()]
        };
        let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1e-6, 0.0], [0.5, 0.0, -1.0]].map(turn);
        let ridge = TriangleMesh::new(v.to_vec(), vec![[0, 1, 2], [1, 0, 3]]).unwrap();
        assert!(ridge.active(0).edge(0) && ridge.active(1).edge(0), "turn {k}: a convex ridge is a real edge");
    }
}

#[cfg(feature = "lab")]
#[test]
fn malformed_case_files_are_invalid_arguments_with_the_reason() {
    use sweepslide::lab::Scene;
    let dir = std::env::temp_dir().join(format!("sweepslide-cases-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tri = "[[0,0,0],[1,0,0],[0,0,1]]";
    let cases = [
        ("syntax", "{\n  \"triangles\": [\n  oops\n}", "line 3"),
        (
            "no-frames",
            &format!(r#"{{"triangles": [{tri}], "radii": [1,1,1], "start": [0,2,0], "frames": []}}"#),
            "no frame",
        ),
        (
            "gravity",
            &format!(
                r#"{{"triangles": [{tri}], "radii": [1,1,1], "start": [0,2,0], "frames": [
                {{"velocity": [0,-1,0], "gravity": [0,-1,0]}}, {{"velocity": [0,-1,0], "gravity": null}}]}}"#
            ),
            "gravity changes",
        ),
        ("missing", r#"{"radii": [1,1,1], "start": [0,2,0], "frames": []}"#, "triangles"),
        // A wrong type names its line and column, in a plain case and in a
        // finding file's (they once had none: the case was read from a
        // parsed value).
        (
            "wrong-type",
            &format!("{{\"triangles\": [{tri}],\n \"radii\": [1,1,\"x\"], \"start\": [0,2,0], \"frames\": []}}"),
            "line 2 column",
        ),
        (
            "wrong-type-finding",
            &format!(
                "{{\"response\": \"linahan\", \"case\": {{\"triangles\": [{tri}],\n\n \"radii\": 3, \"start\": [0,2,0], \"frames\": []}}}}"
            ),
            "line 3 column",
        ),
        (
            "misspelt",
            &format!(
                r#"{{"triangles": [{tri}], "radii": [1,1,1], "start": [0,2,0],
                "frames": [{{"velocity": [0,-1,0], "gravty": [0,-1,0]}}]}}"#
            ),
            "unknown field `gravty`",
        ),
        (
            "finding-key",
            &format!(
                r#"{{"respnse": "linahan", "case": {{"triangles": [{tri}], "radii": [1,1,1], "start": [0,2,0],
                "frames": [{{"velocity": [0,-1,0], "gravity": null}}]}}}}"#
            ),
            "unknown key `respnse`",
        ),
        (
            "only-degenerate",
            r#"{"triangles": [[[0,0,0],[1,0,0],[2,0,0]]], "radii": [1,1,1], "start": [0,2,0],
                "frames": [{"velocity": [0,-1,0]}]}"#,
            "degenerate",
        ),
        (
            "no-triangle",
            r#"{"triangles": [], "radii": [1,1,1], "start": [0,2,0], "frames": [{"velocity": [0,-1,0]}]}"#,
            "no triangle",
        ),
    ];
    for (name, text, reason) in cases {
        let path = dir.join(format!("{name}.json"));
        std::fs::write(&path, text).unwrap();
        match Scene::from_case_file(&path) {
            Err(Error::InvalidArgument { what, message }) => {
                assert!(what.contains(name), "{what}");
                assert!(message.contains(reason), "{name}: {message}");
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    assert!(matches!(Scene::from_case_file(&dir.join("absent.json")), Err(Error::Io { .. })));
    // A well-formed case with a zero-area triangle keeps the others and lists it.
    let path = dir.join("degenerate.json");
    let text = format!(
        r#"{{"case": {{"triangles": [{tri}, [[0,0,0],[1,0,0],[2,0,0]]], "radii": [1,1,1], "start": [0,2,0],
        "frames": [{{"velocity": [0,-1,0], "gravity": null}}]}}}}"#
    );
    std::fs::write(&path, text).unwrap();
    let scene = Scene::from_case_file(&path).unwrap();
    assert_eq!((scene.mesh.len(), scene.mesh.skipped().len()), (1, 1));
}

#[test]
fn obj_file_that_is_not_utf8_names_its_line_and_a_byte_order_mark_is_ignored() {
    let dir = std::env::temp_dir().join(format!("sweepslide-utf8-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("latin1.obj");
    std::fs::write(&path, b"v 0 0 0\nv 1 0 0\nv 0 1 0\n# caf\xe9\nf 1 2 3\n").unwrap();
    match TriangleMesh::from_obj_file(&path).unwrap_err() {
        Error::Obj { line, message, .. } => assert!(line == 4 && message.contains("UTF-8"), "{line}: {message}"),
        e => panic!("{e:?}"),
    }
    let mesh = TriangleMesh::from_obj_str("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Path::new("bom.obj"));
    assert_eq!(mesh.unwrap().len(), 1);
}

// ---------------------------------------------------------------------------
// move_body: options and magnitudes out of range
// ---------------------------------------------------------------------------

/// A floor and a sphere above it, in `T`.
fn floor_world<T: sweepslide::Real>() -> sweepslide::world::World<T> {
    let (v, t) = square();
    let v = v.into_iter().map(|[x, y, _]| [10.0 * x - 5.0, 0.0, 10.0 * y - 5.0]).collect();
    sweepslide::world::World::new(std::sync::Arc::new(TriangleMesh::new(v, t).unwrap())).unwrap()
}

#[test]
fn move_options_out_of_range_name_the_field() {
    use sweepslide::respond::{MAX_ROUNDS, MoveOptions, Response, move_body};
    let world = floor_world::<f64>();
    let body = Ellipsoid::<f64>::sphere(0.5).unwrap();
    let (p, v) = (vec3::<f64>(0.0, 1.0, 0.0), vec3::<f64>(0.1, -0.2, 0.0));
    type Edit = fn(&mut MoveOptions);
    let cases: [(&str, Edit); 10] = [
        ("robust.max_padding", |o| o.robust.max_padding = -0.5),
        ("robust.padding_ulps", |o| o.robust.padding_ulps = -1e12),
        ("detect.touch_ulps", |o| o.detect.touch_ulps = f64::NAN),
        ("robust.feasible_ulps", |o| o.robust.feasible_ulps = f64::INFINITY),
        ("linahan.very_close_distance", |o| o.linahan.very_close_distance = f64::NAN),
        ("robust.free_tilt", |o| o.robust.free_tilt = 0.0),
        ("robust.rounding_ulps", |o| o.robust.rounding_ulps = -1.0),
        ("robust.depenetration_rounds", |o| o.robust.depenetration_rounds = u32::MAX),
        ("robust.max_iterations", |o| o.robust.max_iterations = 0),
        ("fauerby.max_depth", |o| o.fauerby.max_depth = MAX_ROUNDS + 1),
    ];
    for (field, edit) in cases {
        for response in Response::ALL {
            let mut o = MoveOptions::new(response);
            assert_eq!(o.validate(), Ok(()));
            edit(&mut o);
            match move_body(&world, &body, &p, &v, None, &o) {
                Err(Error::InvalidArgument { what, .. }) => assert_eq!(what, field),
                other => panic!("{field}: {other:?}"),
            }
        }
    }
}

/// A tolerance counted in units of `u` beyond `1 / (2u)` of the backend is
/// refused: `robust.rounding_ulps` (`1e7` in `f32` carried a body through a
/// slot's wall, `1e300` gave an infinite position, both `Ok`: a review,
/// session 29), `robust.feasible_ulps` (`1e16` in `f64` made every
/// displacement negligible and froze a body in empty space: a review,
/// thirty-eighth session); up to it, and in
/// `f64` where `1e7` is a small share, the move runs.
#[test]
fn a_tolerance_beyond_any_rounding_is_refused() {
    use sweepslide::respond::{MoveOptions, Response, move_body};
    let (p, v) = ([0.0, 1.0, 0.0], [0.1, -0.2, 0.0]);
    let move_in = |o: &MoveOptions, f64_world: bool| {
        let (pos, vel) = (vec3(p[0], p[1], p[2]), vec3(v[0], v[1], v[2]));
        if f64_world {
            move_body(&floor_world::<f64>(), &Ellipsoid::sphere(0.5).unwrap(), &pos, &vel, None, o).map(|m| m.position)
        } else {
            let (pos, vel) = (pos.map(|x| x as f32), vel.map(|x| x as f32));
            move_body(&floor_world::<f32>(), &Ellipsoid::sphere(0.5).unwrap(), &pos, &vel, None, o)
                .map(|m| m.position.map(f64::from))
        }
    };
    type Set = fn(&mut MoveOptions, f64);
    let fields: [(&str, Set); 2] = [
        ("robust.rounding_ulps", |o, x| o.robust.rounding_ulps = x),
        ("robust.feasible_ulps", |o, x| o.robust.feasible_ulps = x),
    ];
    for (name, set) in fields {
        let mut o = MoveOptions::new(Response::Robust);
        for ulps in [1e7, 1e300] {
            set(&mut o, ulps);
            assert_eq!(o.validate(), Ok(()), "{name}: the range depends on the backend");
            match move_in(&o, false) {
                Err(Error::InvalidArgument { what, .. }) => assert_eq!(what, name),
                other => panic!("{name} {ulps:e}: {other:?}"),
            }
        }
        set(&mut o, 0.5 / f64::from(f32::EPSILON / 2.0));
        assert!(move_in(&o, false).is_ok(), "{name}");
        set(&mut o, 1e7);
        let f64_move = move_in(&o, true);
        assert!(f64_move.is_ok(), "{name}: {f64_move:?}");
        set(&mut o, 1e16);
        assert!(matches!(move_in(&o, true), Err(Error::InvalidArgument { .. })), "{name}");
    }
}

/// A displacement whose length in radii squared overflows `T` is an error,
/// not a body that silently stays put (the robust response used to stop
/// with `Blocked`) or a NaN (the faithful ones).
fn overflowing_move<T: sweepslide::Real>(speed: f64, tiny_radius: f64) {
    use sweepslide::respond::{MoveOptions, Response, move_body};
    let world = floor_world::<T>();
    let body = Ellipsoid::<T>::sphere(0.5).unwrap();
    let p = vec3::<T>(0.0, 1.0, 0.0);
    for response in Response::ALL {
        let o = MoveOptions::new(response);
        let r = move_body(&world, &body, &p, &vec3(speed, 0.0, 0.0), None, &o);
        assert!(matches!(r, Err(Error::InvalidArgument { ref what, .. }) if what == "move"), "{r:?}");
        // The same speed in radii through a tiny body.
        let tiny = Ellipsoid::<T>::sphere(tiny_radius).unwrap();
        let at = vec3::<T>(0.0, 2.0 * tiny_radius, 0.0);
        let r = move_body(&world, &tiny, &at, &vec3(speed * tiny_radius, 0.0, 0.0), None, &o);
        assert!(matches!(r, Err(Error::InvalidArgument { ref what, .. }) if what == "move"), "{r:?}");
        // Within range, the move works.
        assert!(move_body(&world, &body, &p, &vec3(1e3, 0.0, 0.0), None, &o).is_ok());
    }
}

#[test]
fn overflowing_move_f32() {
    overflowing_move::<f32>(1e20, 1e-30);
}

#[test]
fn overflowing_move_f64() {
    overflowing_move::<f64>(1e160, 1e-150);
}

/// A pass longer than the robust response can slide in
/// `robust::MAX_PARTS` parts is refused, naming the velocity or the
/// gravity (a probe, twenty-eighth session: unsplit, `2e7` radii in `f32`
/// went through a wall and ended `2.5e6` radii away); just within, it
/// runs, and the faithful responses, which claim nothing there, run too.
fn too_long_for_parts<T: sweepslide::Real>() {
    use sweepslide::respond::{MoveOptions, Response, RobustOptions, move_body, robust};
    let opts = RobustOptions::default();
    let limit = robust::MAX_PARTS as f64 * opts.max_padding / (2.0 * opts.padding_ulps * T::unit_roundoff());
    let world = floor_world::<T>();
    let body = Ellipsoid::<T>::sphere(0.5).unwrap();
    let p = vec3::<T>(0.0, 1.0, 0.0);
    let robust = MoveOptions::new(Response::Robust);
    let beyond = vec3::<T>(0.0, 0.0, 0.5 * 1.01 * limit);
    let within = vec3::<T>(0.0, 0.0, 0.5 * 0.99 * limit);
    let refused = |v: Option<&_>, g: Option<&_>, name: &str| {
        let r = move_body(&world, &body, &p, v.unwrap_or(&vec3(0.0, 0.0, 0.0)), g, &robust);
        assert!(
            matches!(r, Err(Error::InvalidArgument { ref what, ref message })
                if what == name && message.contains("split the motion")),
            "{}: {r:?}",
            T::name()
        );
    };
    refused(Some(&beyond), None, "velocity");
    refused(None, Some(&beyond), "gravity");
    let moved = move_body(&world, &body, &p, &within, None, &robust).unwrap();
    assert!(moved.position[2].to_f64() > 0.9 * 0.5 * limit, "{}: {moved:?}", T::name());
    for response in [Response::Fauerby, Response::Linahan] {
        assert!(move_body(&world, &body, &p, &beyond, None, &MoveOptions::new(response)).is_ok());
    }
}

#[test]
fn a_push_too_long_for_its_parts_is_refused_f32() {
    too_long_for_parts::<f32>();
}

#[test]
fn a_push_too_long_for_its_parts_is_refused_f64() {
    too_long_for_parts::<f64>();
}

// ---------------------------------------------------------------------------
// The lab's scenes and runs
// ---------------------------------------------------------------------------

#[cfg(feature = "lab")]
#[test]
fn scene_parameters_are_never_dropped_or_truncated() {
    use sweepslide::lab::scenes::build;
    for (spec, reason) in [
        ("floor:5", "takes no parameter"),
        ("room:1", "takes no parameter"),
        ("dead-end:2", "takes no parameter"),
        ("staircase:20.7", "whole number"),
        ("terrain:2.9", "whole number"),
        ("soup:1.5", "whole number"),
        ("tessellated-floor:3.5", "whole number"),
    ] {
        match build(spec, 1) {
            Err(Error::InvalidArgument { message, .. }) => assert!(message.contains(reason), "{spec}: {message}"),
            other => panic!("{spec}: {:?}", other.map(|s| s.name)),
        }
    }
    assert_eq!(build("staircase:20", 1).unwrap().name, "staircase:20");
}

#[cfg(feature = "lab")]
#[test]
fn run_frames_out_of_range_and_a_case_starting_at_rest() {
    use std::sync::Arc;
    use sweepslide::lab::scenes::build;
    use sweepslide::lab::{Motion, Precision, RunConfig, run};
    use sweepslide::respond::Response;
    let config = |scene| RunConfig {
        scene: Arc::new(scene),
        response: Response::Robust,
        detection: None,
        precision: Precision::F64,
        seed: 1,
    };
    for frames in [0, sweepslide::lab::runner::MAX_FRAMES + 1, usize::MAX] {
        let scene = sweepslide::lab::Scene { frames, ..build("floor", 1).unwrap() };
        match run(&config(scene)) {
            Err(Error::InvalidArgument { what, .. }) => assert_eq!(what, "frames"),
            other => panic!("{frames}: {:?}", other.map(|o| o.result)),
        }
    }
    // A scripted motion that starts at rest and moves later is a motion.
    let mut scene = build("floor", 1).unwrap();
    scene.gravity = [0.0; 3];
    scene.velocity = [0.0; 3];
    scene.motion = Motion::Scripted { velocities: vec![[0.0; 3], [0.1, 0.0, 0.0]] };
    scene.frames = 2;
    let out = run(&config(scene.clone())).unwrap();
    assert!(out.result.final_position[0] > scene.start[0]);
    scene.motion = Motion::Scripted { velocities: vec![[0.0; 3]; 2] };
    assert_eq!(run(&config(scene)).unwrap_err(), Error::ZeroVelocity);
}

#[test]
fn world_refuses_a_used_vertex_beyond_the_backends_range_and_ignores_an_unused_one() {
    use sweepslide::world::World;
    let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1e39, 0.0, 0.0]];
    let unused = std::sync::Arc::new(TriangleMesh::new(v.clone(), vec![[0, 1, 2]]).unwrap());
    assert!(World::<f32>::new(unused).is_ok());
    let used = std::sync::Arc::new(TriangleMesh::new(v, vec![[0, 1, 2], [1, 3, 2]]).unwrap());
    match World::<f32>::new(used.clone()) {
        Err(Error::InvalidArgument { what, message }) => {
            assert_eq!(what, "vertex 3 (counted from 0) of triangle 1");
            assert!(message.contains("overflows"), "{message}");
        }
        other => panic!("{:?}", other.map(|w| w.mesh().len())),
    }
    assert!(World::<f64>::new(used).is_ok());
    // Read from OBJ text, the error names the file and the first face
    // that uses the vertex (a review, session 36: it named neither).
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# far\nv 0 0 1e39\nf 1 2 3\n\nf 1 2 4\n";
    let obj = std::sync::Arc::new(TriangleMesh::from_obj_str(text, std::path::Path::new("far.obj")).unwrap());
    match World::<f32>::new(obj) {
        Err(Error::Obj { path, line, message }) => {
            assert_eq!((path.to_str(), line), (Some("far.obj"), 8), "{message}");
            assert!(message.contains("vertex 4 (its `v` statement, counted from 1)"), "{message}");
            assert!(message.contains("overflows this precision"), "{message}");
        }
        other => panic!("{:?}", other.map(|w| w.mesh().len())),
    }
}

// ---------------------------------------------------------------------------
// Triangles too large for the precision, and sweep_world's options
// ---------------------------------------------------------------------------

/// A floor `[-h, h]^2` in the plane y = 0, as two triangles.
fn floor(h: f64) -> std::sync::Arc<TriangleMesh> {
    let v = vec![[-h, 0.0, -h], [-h, 0.0, h], [h, 0.0, h], [h, 0.0, -h]];
    std::sync::Arc::new(TriangleMesh::new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap())
}

/// One frame of a unit sphere 2 above the floor moving down by 2.5: it
/// lands (returns its height) or the move is refused.
fn fall_onto_floor<T: sweepslide::Real>(h: f64, response: sweepslide::respond::Response) -> Result<f64, Error> {
    use sweepslide::respond::{MoveOptions, move_body};
    use sweepslide::world::World;
    let world = World::<T>::new(floor(h))?;
    let body = Ellipsoid::<T>::sphere(1.0)?;
    let m = move_body(&world, &body, &vec3(5.0, 2.0, -5.0), &vec3(0.0, -2.5, 0.0), None, &MoveOptions::new(response))?;
    Ok(m.position[1].to_f64())
}

#[test]
fn a_triangle_whose_squared_sides_overflow_is_refused_not_passed_through() {
    use sweepslide::respond::Response;
    // Its sides' squares overflow `f32` (2e19 radii): every test would miss
    // it, and the body fell through (0.5 deep) before this was an error.
    for response in [Response::Robust, Response::Fauerby, Response::Linahan] {
        match fall_onto_floor::<f32>(1e19, response) {
            Err(Error::InvalidArgument { what, message }) => {
                assert!(what == "triangle 0" || what == "triangle 1", "{what}");
                assert!(message.contains("too long for this precision"), "{message}");
            }
            other => panic!("{response:?}: expected InvalidArgument, got {other:?}"),
        }
    }
    assert!(matches!(fall_onto_floor::<f64>(1e160, Response::Robust), Err(Error::InvalidArgument { .. })));
    // Below the limit the move runs and the body stays out of the floor,
    // in `f32` and in `f64`. (So large a triangle is not resolved to the
    // padding: its vertices relative to the body are rounded by more than
    // a radius, and the body need not come down onto it; see
    // docs/algorithms.md.)
    for (y, precision) in [
        (fall_onto_floor::<f32>(1e18, Response::Robust), "f32"),
        (fall_onto_floor::<f64>(1e19, Response::Robust), "f64"),
    ] {
        let y = y.unwrap();
        assert!(y >= 1.0, "{precision}: {y}");
    }
    // Sizes the precision resolves: the body lands within twice the largest
    // padding.
    for (y, precision) in
        [(fall_onto_floor::<f32>(1e3, Response::Robust), "f32"), (fall_onto_floor::<f64>(1e8, Response::Robust), "f64")]
    {
        let y = y.unwrap();
        assert!((1.0..=1.02).contains(&y), "{precision}: {y}");
    }
}

#[test]
fn sweep_world_checks_its_options_and_the_triangles_size() {
    use sweepslide::detect::{DetectOptions, Detection, sweep_world};
    use sweepslide::world::World;
    let world = World::<f64>::new(floor(50.0)).unwrap();
    let body = Ellipsoid::<f64>::sphere(1.0).unwrap();
    let (p, v) = (vec3(0.0, 3.0, 0.0), vec3(0.0, -3.0, 0.0));
    let hit = sweep_world(&world, &body, &p, &v, Detection::Robust, &DetectOptions::default()).unwrap();
    assert!(hit.is_some_and(|h| (h.t - 2.0 / 3.0).abs() < 1e-12));
    for (touch, approach, field) in [
        (-1e300, 0.0, "detect.touch_ulps"),
        (f64::NAN, 0.0, "detect.touch_ulps"),
        (16.0, f64::NAN, "detect.approach_ulps"),
        (16.0, f64::INFINITY, "detect.approach_ulps"),
    ] {
        let opts = DetectOptions { touch_ulps: touch, approach_ulps: approach, ..DetectOptions::default() };
        match sweep_world(&world, &body, &p, &v, Detection::Robust, &opts) {
            Err(Error::InvalidArgument { what, .. }) => assert_eq!(what, field),
            other => panic!("{touch} {approach}: expected InvalidArgument, got {other:?}"),
        }
    }
    let world = World::<f32>::new(floor(1e19)).unwrap();
    let body = Ellipsoid::<f32>::sphere(1.0).unwrap();
    let (p, v) = (vec3(0.0, 3.0, 0.0), vec3(0.0, -3.0, 0.0));
    assert!(matches!(
        sweep_world(&world, &body, &p, &v, Detection::Robust, &DetectOptions::default()),
        Err(Error::InvalidArgument { what, .. }) if what.starts_with("triangle ")
    ));
}

#[test]
fn tiny_and_huge_values_in_messages_are_in_scientific_notation() {
    let e = Ellipsoid::<f64>::sphere(-1e-320).unwrap_err().to_string();
    assert!(e.ends_with("got -1e-320"), "{e}");
    let e = Ellipsoid::<f64>::sphere(-2.5).unwrap_err().to_string();
    assert!(e.ends_with("got -2.5"), "{e}");
    let opts = sweepslide::detect::DetectOptions { touch_ulps: -1e300, ..Default::default() };
    let e = opts.validate().unwrap_err().to_string();
    assert!(e.ends_with("got -1e300"), "{e}");
}

#[test]
fn internal_edge_angle_is_checked_and_used() {
    // Two triangles folded by 10 degrees along their shared edge (0 -> 1,
    // the z axis), one way and the other.
    let (s, c) = 10f64.to_radians().sin_cos();
    let ridge = |fold: f64| {
        let v = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [c, fold * s, 0.0]];
        TriangleMesh::new(v, vec![[0, 1, 2], [1, 0, 3]]).unwrap()
    };
    // The shared edge is edge 0 of triangle 0. Convex or concave, a
    // threshold above its 10 degrees makes it internal and one below leaves
    // it active (a concave fold was internal at any threshold, which made
    // the same edge, a ridge seen from behind, stop bodies: a review).
    let active = |fold: f64, degrees: f64| ridge(fold).with_internal_edge_angle(degrees).unwrap().active(0).edge(0);
    for fold in [1.0, -1.0] {
        assert!(active(fold, 5.0) && active(fold, 0.0), "fold {fold}");
        assert!(!active(fold, 15.0) && !active(fold, 180.0), "fold {fold}");
    }
    for bad in [f64::NAN, -1.0, 180.5, f64::INFINITY] {
        match ridge(1.0).with_internal_edge_angle(bad) {
            Err(Error::InvalidArgument { what, .. }) => assert_eq!(what, "internal edge angle"),
            other => panic!("{bad}: expected InvalidArgument, got {:?}", other.map(|m| m.len())),
        }
    }
}

#[cfg(feature = "lab")]
#[test]
fn a_mesh_too_large_or_too_small_for_the_labs_f32_scene_values_says_so() {
    use sweepslide::lab::Scene;
    let dir = std::env::temp_dir().join(format!("sweepslide-scale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A default radius subnormal in `f32` (a mesh `1e-40` across) was let
    // through and refused as a radius the user had not given (a review,
    // session 36).
    for (name, h) in [("huge", 1e170), ("tiny", 1e-300), ("subnormal", 1e-40)] {
        let path = dir.join(format!("{name}.obj"));
        std::fs::write(&path, format!("v 0 0 0\nv {h} 0 0\nv 0 0 {h}\nf 1 2 3\n")).unwrap();
        match Scene::from_obj(&path) {
            Err(Error::InvalidArgument { what, message }) => {
                assert!(what.ends_with(&format!("{name}.obj")), "{what}");
                assert!(message.contains("beyond the normal `f32` numbers"), "{message}");
            }
            other => panic!("{name}: expected InvalidArgument, got {:?}", other.map(|s| s.name)),
        }
    }
    let path = dir.join("plain.obj");
    std::fs::write(&path, "v 0 0 0\nv 2 0 0\nv 0 0 2\nf 1 2 3\n").unwrap();
    let scene = Scene::from_obj(&path).unwrap();
    assert!((scene.radii[0] - 0.02 * 8f64.sqrt()).abs() < 1e-12);
}
