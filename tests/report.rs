//! The report: shards merge into exactly the unsharded results, and the
//! quick report is a well-formed, self-contained page with one JSON record
//! per run.
#![cfg(feature = "cli")]

use std::collections::HashSet;
use std::path::Path;
use sweepslide::lab::RunResult;
use sweepslide::report::matrix::{matrix, shard};
use sweepslide::report::{Record, Runs, merge, run_entries};

fn timeless(records: Vec<Record>) -> Vec<Record> {
    records
        .into_iter()
        .map(|mut r| {
            r.outcome = r.outcome.map(|o| RunResult { ns_per_move: 0.0, ..o });
            r
        })
        .collect()
}

#[test]
fn two_shards_merged_give_the_unsharded_results() {
    let (info, entries) = matrix(true, &[], &[]);
    // A slice of the matrix that mixes scenes, responses, precisions and the
    // dial, kept small so the test is quick; indices are renumbered so it
    // is a matrix of its own.
    let mut picked: Vec<_> = entries.iter().step_by(23).cloned().collect();
    for (i, e) in picked.iter_mut().enumerate() {
        e.index = i;
    }
    let info = sweepslide::report::matrix::MatrixInfo { runs: picked.len(), ..info };
    let whole = Runs { info: info.clone(), records: run_entries(&picked, 2, &|| {}, &|_| {}).unwrap() };
    let shards: Vec<Runs> = (1..=2)
        .map(|k| {
            let part = shard(picked.clone(), k, 2).unwrap();
            Runs { info: info.clone(), records: run_entries(&part, 1, &|| {}, &|_| {}).unwrap() }
        })
        .collect();
    assert!(shards.iter().all(|s| !s.records.is_empty()));
    let merged = merge(shards.clone()).unwrap();
    // Compared as printed: a run that ends with a NaN position has a NaN
    // jitter, and NaN is never `==` to itself.
    let (merged, whole) = (timeless(merged.records), timeless(whole.records));
    assert_eq!(merged.len(), whole.len());
    for (m, w) in merged.iter().zip(&whole) {
        assert_eq!(format!("{m:?}"), format!("{w:?}"), "run {}", w.entry.index);
    }
    // A missing shard or a doubled one is refused.
    assert!(merge(vec![shards[0].clone()]).is_err());
    assert!(merge(vec![shards[0].clone(), shards[0].clone(), shards[1].clone()]).is_err());
}

#[test]
fn a_shard_whose_run_ends_with_a_nan_position_is_written_read_and_merged() {
    // Linahan's response ends this fuzz case with a NaN position; JSON has
    // no NaN, and `runs.json` once wrote `null` there and could not be read
    // back by `sweepslide merge`.
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz/linahan-nan-narrow-slot.json");
    let (info, entries) = matrix(true, &[], std::slice::from_ref(&case));
    let mut picked: Vec<_> = entries
        .into_iter()
        .filter(|e| e.response == sweepslide::respond::Response::Linahan && format!("{:?}", e.source).contains("nan"))
        .collect();
    for (i, e) in picked.iter_mut().enumerate() {
        e.index = i;
    }
    let info = sweepslide::report::matrix::MatrixInfo { runs: picked.len(), ..info };
    let runs = Runs { info, records: run_entries(&picked, 1, &|| {}, &|_| {}).unwrap() };
    let nan_ended = |runs: &Runs| {
        runs.records
            .iter()
            .filter(|r| r.outcome.as_ref().is_ok_and(|o| o.final_position.iter().any(|x| x.is_nan())))
            .count()
    };
    assert!(nan_ended(&runs) > 0, "the case no longer ends with NaN: {:?}", runs.records);
    let dir = std::env::temp_dir().join(format!("sweepslide-nan-shard-{}", std::process::id()));
    sweepslide::report::write_runs(&dir, &runs).unwrap();
    let back = sweepslide::report::read_runs(&dir).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(nan_ended(&back), nan_ended(&runs));
    // Bit for bit otherwise: the same text when written again.
    assert_eq!(serde_json::to_string(&back).unwrap(), serde_json::to_string(&runs).unwrap());
    assert_eq!(merge(vec![back]).unwrap().records.len(), picked.len());
}

/// Checks that every element opened is closed in order (void elements
/// aside) and returns the `href` and `src` targets.
fn check_balanced(html: &str) -> Vec<String> {
    const VOID: [&str; 6] = ["meta", "br", "img", "link", "hr", "input"];
    let mut stack: Vec<String> = Vec::new();
    let mut links = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        let end = rest[start..].find('>').expect("every tag is closed") + start;
        let tag = &rest[start + 1..end];
        rest = &rest[end + 1..];
        if tag.starts_with('!') || tag.starts_with('?') {
            continue;
        }
        for attr in ["href=\"", "src=\""] {
            if let Some(i) = tag.find(attr) {
                let value = &tag[i + attr.len()..];
                links.push(value[..value.find('"').expect("quoted")].to_string());
            }
        }
        let name: String =
            tag.trim_start_matches('/').chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '-').collect();
        if tag.starts_with('/') {
            assert_eq!(stack.pop().as_deref(), Some(name.as_str()), "closing </{name}> out of order");
        } else if !(tag.ends_with('/') || VOID.contains(&name.as_str())) {
            stack.push(name);
        }
    }
    assert!(stack.is_empty(), "unclosed elements: {stack:?}");
    links
}

#[test]
fn quick_report_is_complete_and_self_contained() {
    let out = std::env::temp_dir().join(format!("sweepslide-report-{}", std::process::id()));
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_sweepslide"))
        .args([
            "report",
            "--quick",
            "--out",
            out.to_str().unwrap(),
            "--meshes",
            out.join("no-meshes").to_str().unwrap(),
        ])
        .status();
    // A missing --meshes directory is an error (exit 2); with none, the
    // matrix is the built-in one plus the fuzz cases of scenes/fuzz.
    assert_eq!(status.unwrap().code(), Some(2));
    let empty = out.join("empty-meshes");
    std::fs::create_dir_all(&empty).unwrap();
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_sweepslide"))
        .args(["report", "--quick", "--out", out.to_str().unwrap(), "--meshes", empty.to_str().unwrap()])
        .status()
        .unwrap();
    assert!(status.success());
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    for link in check_balanced(&html) {
        assert!(!link.contains("://"), "no network: {link}");
        let target = link.split('#').next().unwrap();
        if !target.is_empty() {
            assert!(Path::new(&out).join(target).is_file(), "{link} exists");
        }
    }
    assert!(html.contains("<svg"), "plots are inline");
    // The verdicts the quick matrix pins (docs/findings.md): Fauerby's
    // penetrations at 53 bits or more all enter from behind (the soup, the
    // fuzz cases), so "only in f32" holds; the robust response never
    // penetrates.
    let verdict = |claim: &str| {
        let row = &html[html.find(claim).unwrap_or_else(|| panic!("claim {claim:?} in the table"))..];
        let row = &row[..row.find("</tr>").unwrap()];
        row.contains(">reproduced<")
    };
    assert!(verdict("Fauerby's response lets the sphere penetrate"));
    assert!(verdict("Fauerby penetrates only in f32, never in f64."));
    assert!(verdict("The robust response never penetrates"));
    assert!(verdict("In f32 both faithful responses freeze in a V-shaped valley"));
    assert!(verdict("In f32, away from the origin, on a tilted floor Fauerby's response freezes"));
    assert!(verdict("The robust response does not snag"));
    assert!(verdict("The robust response keeps to the ideal slide's line"));
    let cases = sweepslide::lab::scenes::cases_in(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz"));
    assert!(!cases.is_empty());
    let (info, entries) = matrix(true, &[], &cases);
    let results: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(results.len(), info.runs, "one record per run");
    let indices: HashSet<u64> = results.iter().map(|r| r["index"].as_u64().unwrap()).collect();
    assert_eq!(indices.len(), entries.len());
    for r in &results {
        for field in [
            "scene",
            "response",
            "detection",
            "precision",
            "frames",
            "max_penetration",
            "penetrating_frames",
            "back_face_frames",
            "max_front_penetration",
            "jitter",
            "max_iterations",
            "max_pass_iterations",
            "mean_iterations",
            "nan_frames",
            "decision_flips",
            "final_position",
            "ns_per_move",
        ] {
            assert!(r.get(field).is_some(), "missing {field} in {r}");
        }
    }
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), info.runs + 1);
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn unreadable_runs_json_is_io_and_malformed_or_non_utf8_is_invalid_argument() {
    use sweepslide::Error;
    let dir = std::env::temp_dir().join(format!("sweepslide-bad-runs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    assert!(matches!(sweepslide::report::read_runs(&dir), Err(Error::Io { .. })));
    for bytes in [&b"{\"info\": \"\xff\xfe\"}"[..], b"{\"info\": 1,"] {
        std::fs::write(dir.join("runs.json"), bytes).unwrap();
        match sweepslide::report::read_runs(&dir) {
            Err(Error::InvalidArgument { what, message }) => {
                assert!(what.ends_with("runs.json"), "{what}");
                assert!(message.contains("line 1"), "{message}");
            }
            other => panic!("{:?}", other.map(|r| r.records.len())),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A review's finding (twenty-first session): with no runs, six claims
/// read "reproduced" ("no penetrating frame in 0 robust runs") and the
/// evidence printed a snag ratio of `inf`; and runs that reached NaN
/// counted as evidence of an absence. Without runs nothing is reproduced;
/// a NaN run is left out of the absence claims, and said.
#[test]
fn claims_need_runs_and_nan_runs_show_no_absence() {
    use sweepslide::report::claims::evaluate;
    let (info, _) = matrix(true, &[], &[]);
    let empty = Runs { info: sweepslide::report::matrix::MatrixInfo { runs: 0, ..info.clone() }, records: vec![] };
    for claim in evaluate(&empty) {
        assert!(!claim.reproduced, "reproduced without runs: {claim:?}");
        assert!(!claim.evidence.contains("inf"), "{claim:?}");
    }
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz/linahan-nan-narrow-slot.json");
    let (info, entries) = matrix(true, &[], std::slice::from_ref(&case));
    let mut picked: Vec<_> = entries
        .into_iter()
        .filter(|e| e.response == sweepslide::respond::Response::Linahan && format!("{:?}", e.source).contains("nan"))
        .filter(|e| e.group == sweepslide::report::matrix::Group::Main)
        .collect();
    for (i, e) in picked.iter_mut().enumerate() {
        e.index = i;
    }
    let info = sweepslide::report::matrix::MatrixInfo { runs: picked.len(), ..info };
    let runs = Runs { info, records: run_entries(&picked, 1, &|| {}, &|_| {}).unwrap() };
    let nan_runs = runs.records.iter().filter(|r| r.outcome.as_ref().is_ok_and(|o| o.nan_frames > 0)).count();
    assert!(nan_runs > 0, "the case no longer reaches NaN");
    let never = evaluate(&runs).into_iter().find(|c| c.text.starts_with("Linahan's response never lets")).unwrap();
    assert!(never.evidence.contains(&format!("left out: {nan_runs} runs with NaN frames")), "{never:?}");
    // Expected from the runs themselves, not from the claim's own words: no
    // run penetrates (counted as the one-sided detection counts) and some
    // run is free of NaN.
    let results: Vec<_> = runs.records.iter().filter_map(|r| r.outcome.as_ref().ok()).collect();
    let clean = results.iter().filter(|o| o.nan_frames == 0).count();
    let penetrating = results.iter().filter(|o| o.counted_penetration().0 > 0).count();
    assert_eq!(never.reproduced, clean > 0 && penetrating == 0, "{never:?}");
}

/// A mesh whose triangle collapses once rounded into `f32` (one `1e8` from
/// the origin with sides of 1): the page, `results.csv` and `runs.json`
/// say so for its `f32` runs and for no other (a review, twenty-first
/// session, found only `sweepslide run` saying it).
#[test]
fn a_report_says_which_scenes_have_triangles_degenerate_in_a_precision() {
    let dir = std::env::temp_dir().join(format!("sweepslide-degenerate-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("collapsing.obj");
    std::fs::write(
        &mesh,
        "v 100000000 0 0\nv 100000001 0 0\nv 100000000 0 1\nv -5 0 -5\nv 5 0 -5\nv -5 0 5\nf 1 3 2\nf 4 6 5\n",
    )
    .unwrap();
    let (info, entries) = matrix(true, std::slice::from_ref(&mesh), &[]);
    let mut picked: Vec<_> = entries
        .into_iter()
        .filter(|e| format!("{:?}", e.source).contains("collapsing") && ["f32", "f64"].contains(&e.precision.as_str()))
        .collect();
    assert!(picked.iter().any(|e| e.precision == "f32") && picked.iter().any(|e| e.precision == "f64"));
    for (i, e) in picked.iter_mut().enumerate() {
        e.index = i;
    }
    let info = sweepslide::report::matrix::MatrixInfo { runs: picked.len(), ..info };
    let runs = Runs { info, records: run_entries(&picked, 1, &|| {}, &|_| {}).unwrap() };
    for r in &runs.records {
        let o = r.outcome.as_ref().expect("the mesh runs");
        assert_eq!(o.degenerate_triangles, usize::from(o.precision == "f32"), "{}", o.precision);
    }
    let notes = sweepslide::report::degenerate_notes(&runs);
    assert_eq!(notes.len(), 1, "one line per scene and precision: {notes:?}");
    assert!(notes[0].contains("in f32: 1 triangle(s) degenerate"), "{}", notes[0]);
    let out = dir.join("report");
    sweepslide::report::write_runs(&out, &runs).unwrap();
    sweepslide::report::render(&out, &runs, None).unwrap();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("in f32: 1 triangle(s) degenerate"), "the page says it");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let column = lines.next().unwrap().split(',').position(|h| h == "degenerate_triangles").expect("a CSV column");
    // The last column: no quoted field with a comma sits before it here.
    let counts: Vec<&str> = lines.map(|l| l.split(',').nth(column).unwrap()).collect();
    assert!(counts.contains(&"1") && counts.contains(&"0"), "{counts:?}");
    // `sweepslide merge` reads it back and says it on standard error.
    let merged = dir.join("merged");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sweepslide"))
        .args(["merge", merged.to_str().unwrap(), out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(String::from_utf8_lossy(&output.stderr).contains("note: collapsing in f32: 1 triangle(s)"));
    // Into one of its own shards (by another spelling of the path) it
    // refuses, and leaves the shard as it was (a review, thirty-eighth
    // session: the merged runs replaced the shard's).
    let before = std::fs::read(out.join("runs.json")).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sweepslide"))
        .args(["merge", dir.join("merged/../report").to_str().unwrap(), out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(String::from_utf8_lossy(&output.stderr).contains("is one of the shards"));
    assert_eq!(std::fs::read(out.join("runs.json")).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Splits one CSV line into its fields, a quoted field's doubled quotes
/// read as one.
fn csv_fields(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted, mut chars) = (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// A mesh whose file name holds a quote and a comma keeps its row's
/// columns in `results.csv` (the scene field is quoted, its quotes
/// doubled; a review, twenty-first session, fixed it without a test), and
/// `runs.json` whose counts contradict each other is refused on reading.
#[test]
fn csv_quotes_odd_scene_names_and_inconsistent_runs_are_refused() {
    let dir = std::env::temp_dir().join(format!("sweepslide-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("we\"ird,name.obj");
    std::fs::write(&mesh, "v -5 0 -5\nv 5 0 -5\nv -5 0 5\nf 1 3 2\n").unwrap();
    let (info, entries) = matrix(true, std::slice::from_ref(&mesh), &[]);
    let mut picked: Vec<_> =
        entries.into_iter().filter(|e| format!("{:?}", e.source).contains("ird")).take(2).collect();
    assert!(!picked.is_empty());
    for (i, e) in picked.iter_mut().enumerate() {
        e.index = i;
    }
    let info = sweepslide::report::matrix::MatrixInfo { runs: picked.len(), ..info };
    let mut runs = Runs { info, records: run_entries(&picked, 1, &|| {}, &|_| {}).unwrap() };
    let out = dir.join("report");
    sweepslide::report::render(&out, &runs, None).unwrap();
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let header = csv_fields(lines.next().unwrap());
    let scene = header.iter().position(|h| h == "scene").unwrap();
    // The CSV holds the fields of `results.json`, the vectors one column
    // per coordinate (a review, session 39: `units_per_meter` was missing).
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let mut keys: Vec<String> = json[0]
        .as_object()
        .unwrap()
        .keys()
        .flat_map(|k| match k.as_str() {
            "final_position" => ["final_x", "final_y", "final_z"].map(String::from).to_vec(),
            "radii" => ["radius_x", "radius_y", "radius_z"].map(String::from).to_vec(),
            _ => vec![k.clone()],
        })
        .collect();
    let mut columns = header.clone();
    keys.sort();
    columns.sort();
    assert_eq!(columns, keys, "the CSV's columns and the JSON's fields");
    for line in lines {
        let fields = csv_fields(line);
        assert_eq!(fields.len(), header.len(), "{line}");
        assert_eq!(fields[scene], "we\"ird,name", "{line}");
    }
    // More frames entered from behind than penetrating frames: refused.
    let first = runs.records[0].outcome.as_mut().expect("the run succeeds");
    first.back_face_frames = first.penetrating_frames + 1;
    sweepslide::report::write_runs(&out, &runs).unwrap();
    let e = sweepslide::report::read_runs(&out).expect_err("inconsistent counts").to_string();
    assert!(e.contains("record 0") && e.contains("entered from behind"), "{e}");
    // A precision the lab does not know, or a result in another precision
    // than its entry's: refused (a review, session 36: merged and rendered).
    let first = runs.records[0].outcome.as_mut().expect("the run succeeds");
    first.back_face_frames = 0;
    let last = runs.records.len() - 1;
    runs.records[last].entry.precision = "f17".into();
    sweepslide::report::write_runs(&out, &runs).unwrap();
    let e = sweepslide::report::read_runs(&out).expect_err("unknown precision").to_string();
    assert!(e.contains(&format!("record {last}")) && e.contains("f17"), "{e}");
    let known = if runs.records[last].outcome.as_ref().unwrap().precision == "f32" { "f64" } else { "f32" };
    runs.records[last].entry.precision = known.into();
    sweepslide::report::write_runs(&out, &runs).unwrap();
    let e = sweepslide::report::read_runs(&out).expect_err("precisions differ").to_string();
    assert!(e.contains(&format!("record {last}")) && e.contains("its entry in"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Failed runs are said on standard error by `merge` (and `report`), with
/// their scene, response, precision and error, beside the page's list
/// (fixed in the twenty-first session without a test: a review).
#[test]
fn merge_warns_of_failed_runs_on_standard_error() {
    let (info, entries) = matrix(true, &[], &[]);
    let mut entry = entries[0].clone();
    entry.index = 0;
    let info = sweepslide::report::matrix::MatrixInfo { runs: 1, ..info };
    let runs = Runs { info, records: vec![Record { entry, outcome: Err("the run broke here".into()), frames: None }] };
    let dir = std::env::temp_dir().join(format!("sweepslide-failed-{}", std::process::id()));
    let shard = dir.join("shard");
    sweepslide::report::write_runs(&shard, &runs).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sweepslide"))
        .args(["merge", dir.join("merged").to_str().unwrap(), shard.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("warning: 1 of 1 runs failed") && stderr.contains("the run broke here"), "{stderr}");
    let html = std::fs::read_to_string(dir.join("merged/index.html")).unwrap();
    assert!(html.contains("1 runs failed") && html.contains("the run broke here"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A review's finding (twenty-sixth session): `merge` compared the mesh
/// paths, so shards made where the same meshes sit at other paths were
/// refused (with a debug dump of both matrices), and a mesh changed under
/// the same path would have merged. Meshes and cases are now identified by
/// file name and contents, and the refusal says what differs.
#[test]
fn shards_are_the_same_matrix_when_their_meshes_are_the_same_files_anywhere() {
    use sweepslide::report::matrix::matrix;
    let dir = std::env::temp_dir().join(format!("sweepslide-matrix-{}", std::process::id()));
    let (here, there) = (dir.join("here"), dir.join("there"));
    std::fs::create_dir_all(&here).unwrap();
    std::fs::create_dir_all(&there).unwrap();
    let obj = "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n";
    std::fs::write(here.join("tri.obj"), obj).unwrap();
    std::fs::write(there.join("tri.obj"), obj).unwrap();
    let info = |dir: &std::path::Path, quick: bool| matrix(quick, &[dir.join("tri.obj")], &[]).0;
    assert_eq!(info(&here, true).differences(&info(&there, true)), Vec::<String>::new());
    std::fs::write(there.join("tri.obj"), "v 0 0 0\nv 2 0 0\nv 0 0 1\nf 1 2 3\n").unwrap();
    let changed = info(&here, true).differences(&info(&there, true));
    assert!(changed.len() == 1 && changed[0].starts_with("meshes and cases [tri.obj ("), "{changed:?}");
    let kinds = info(&here, true).differences(&info(&here, false));
    assert!(kinds.iter().any(|d| d == "a quick matrix and a full one"), "{kinds:?}");
    // Files written before the digests existed are compared by path.
    let old = |dir: &std::path::Path| sweepslide::report::matrix::MatrixInfo { inputs: vec![], ..info(dir, true) };
    assert_eq!(old(&here).differences(&old(&here)), Vec::<String>::new());
    assert_eq!(old(&here).differences(&old(&there)).len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}
