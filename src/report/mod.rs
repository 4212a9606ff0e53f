//! The error-analysis report: runs the experiment matrix (or a shard of
//! it), and renders `index.html`, `results.json`, `results.csv` and the
//! plots from the runs.
//!
//! Every output directory also gets `runs.json`: the matrix's identity and
//! each run's entry, metrics and (for the runs the plots need) frames. A
//! shard's directory holds only `runs.json`; [`merge`] reads several and
//! renders exactly what one unsharded run renders (timings aside).

pub mod claims;
pub mod html;
pub mod matrix;
pub mod plots;

use crate::Error;
use crate::lab::{FrameRecord, Precision, RunResult, run_all};
use matrix::{Entry, Group, MatrixInfo, configs};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One run of the matrix and what came of it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The run.
    pub entry: Entry,
    /// Its metrics, or why it failed.
    pub outcome: Result<RunResult, String>,
    /// Its frames, kept for the plots (main-table runs in `f32` and `f64`).
    pub frames: Option<Vec<FrameRecord>>,
}

/// The contents of `runs.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Runs {
    /// Which matrix these runs belong to.
    pub info: MatrixInfo,
    /// The runs, by increasing index.
    pub records: Vec<Record>,
}

fn io(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Io { path: path.to_path_buf(), message: e.to_string() }
}

/// Runs `entries` on `jobs` threads, calling `progress` after each run and
/// `note` with what loading each mesh file left out (see
/// [`matrix::configs`]).
///
/// # Errors
/// Building a scene or loading a mesh can fail; a failing *run* is kept as
/// a record with its error instead.
pub fn run_entries(
    entries: &[Entry],
    jobs: usize,
    progress: &(dyn Fn() + Sync),
    note: &dyn Fn(&str),
) -> Result<Vec<Record>, Error> {
    let configs = configs(entries, note)?;
    let outputs = run_all(&configs, jobs, &|_| progress())?;
    Ok(entries
        .iter()
        .zip(outputs)
        .map(|(entry, out)| {
            let keep_frames = entry.group == Group::Main && (entry.precision == "f32" || entry.precision == "f64");
            match out {
                Ok(o) => {
                    Record { entry: entry.clone(), outcome: Ok(o.result), frames: keep_frames.then_some(o.frames) }
                }
                Err(e) => Record { entry: entry.clone(), outcome: Err(e.to_string()), frames: None },
            }
        })
        .collect())
}

/// Writes `runs.json` into `dir` (created if needed).
///
/// # Errors
/// [`Error::Io`] when the directory or file cannot be written.
pub fn write_runs(dir: &Path, runs: &Runs) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let path = dir.join("runs.json");
    let text = serde_json::to_string(runs).map_err(|e| io(&path, e))?;
    std::fs::write(&path, text).map_err(|e| io(&path, e))
}

/// Reads `runs.json` from `dir`.
///
/// # Errors
/// [`Error::Io`] when it cannot be read, [`Error::InvalidArgument`] (with
/// the line and column) when it is malformed, not UTF-8 included, or when
/// a run counts more frames entered from behind than penetrating frames
/// (no run writes that; the counts that subtract them would wrap), names a
/// precision the lab does not know, or holds a result of another precision
/// than its entry's.
pub fn read_runs(dir: &Path) -> Result<Runs, Error> {
    let path = dir.join("runs.json");
    let bytes = std::fs::read(&path).map_err(|e| io(&path, e))?;
    let bad = |message: String| Error::InvalidArgument { what: path.display().to_string(), message };
    let runs: Runs = serde_json::from_slice(&bytes).map_err(|e| bad(e.to_string()))?;
    // A precision the lab does not know, or a result of another precision
    // than its entry's, was merged and rendered without a word (a review,
    // session 36).
    let inconsistent = runs.records.iter().enumerate().find_map(|(k, r)| {
        if let Err(e) = Precision::parse(&r.entry.precision) {
            return Some(format!("record {k}: {e}"));
        }
        let o = r.outcome.as_ref().ok()?;
        if o.precision != r.entry.precision {
            Some(format!("record {k}: its result is in `{}`, its entry in `{}`", o.precision, r.entry.precision))
        } else if o.back_face_frames > o.penetrating_frames {
            Some(format!("record {k}: more frames entered from behind than penetrating frames"))
        } else {
            None
        }
    });
    match inconsistent {
        Some(message) => Err(bad(message)),
        None => Ok(runs),
    }
}

/// Combines shards into the whole matrix.
///
/// # Errors
/// [`Error::InvalidArgument`] when the shards belong to different matrices,
/// overlap, or leave runs out.
pub fn merge(shards: Vec<Runs>) -> Result<Runs, Error> {
    let bad = |message: String| Error::InvalidArgument { what: "merge".into(), message };
    let info = shards.first().map(|s| s.info.clone()).ok_or_else(|| bad("no shard given".into()))?;
    if let Some((k, differences)) =
        shards.iter().map(|s| info.differences(&s.info)).enumerate().find(|(_, d)| !d.is_empty())
    {
        return Err(bad(format!("shards 1 and {} come from different matrices: {}", k + 1, differences.join("; "))));
    }
    let mut records: Vec<Record> = shards.into_iter().flat_map(|s| s.records).collect();
    records.sort_by_key(|r| r.entry.index);
    for (i, r) in records.iter().enumerate() {
        if r.entry.index != i {
            let what = if r.entry.index < i { "appears twice" } else { "is missing" };
            return Err(bad(format!("run {} {what}", r.entry.index.min(i))));
        }
    }
    if records.len() != info.runs {
        return Err(bad(format!("{} of {} runs present", records.len(), info.runs)));
    }
    Ok(Runs { info, records })
}

/// One line per scene and precision whose runs met triangles degenerate
/// once rounded into that precision ([`RunResult::degenerate_triangles`]),
/// in the order of the runs: those triangles collided as the segments or
/// points they became, which the report and the command line both say.
#[must_use]
pub fn degenerate_notes(runs: &Runs) -> Vec<String> {
    let mut notes: Vec<String> = Vec::new();
    for r in runs.records.iter().filter_map(|r| r.outcome.as_ref().ok()).filter(|r| r.degenerate_triangles > 0) {
        let note = format!(
            "{} in {}: {} triangle(s) degenerate once rounded into this precision (zero area), which collided as the \
             segments or points they became",
            r.scene, r.precision, r.degenerate_triangles
        );
        if !notes.contains(&note) {
            notes.push(note);
        }
    }
    notes
}

/// One line of `results.json`: the run's metrics (the `sweepslide run
/// --json` fields) plus where it sits in the matrix.
#[derive(Serialize)]
struct ResultLine<'a> {
    index: usize,
    group: Group,
    #[serde(flatten)]
    result: &'a RunResult,
}

/// Renders the whole report into `dir`: `results.json`, `results.csv`,
/// `plots/*.svg` and `index.html`.
///
/// # Errors
/// [`Error::Io`] when a file cannot be written.
pub fn render(dir: &Path, runs: &Runs, elapsed_s: Option<f64>) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir.join("plots")).map_err(|e| io(dir, e))?;
    let ok: Vec<(&Record, &RunResult)> =
        runs.records.iter().filter_map(|r| r.outcome.as_ref().ok().map(|o| (r, o))).collect();
    let lines: Vec<ResultLine<'_>> =
        ok.iter().map(|(r, o)| ResultLine { index: r.entry.index, group: r.entry.group, result: o }).collect();
    let json_path = dir.join("results.json");
    std::fs::write(&json_path, serde_json::to_string_pretty(&lines).map_err(|e| io(&json_path, e))?)
        .map_err(|e| io(&json_path, e))?;
    let csv_path = dir.join("results.csv");
    std::fs::write(&csv_path, csv(&lines)).map_err(|e| io(&csv_path, e))?;
    let claims_path = dir.join("claims.json");
    std::fs::write(&claims_path, claims_json(runs)).map_err(|e| io(&claims_path, e))?;
    let figures = plots::figures(runs);
    let mut written = vec![json_path, csv_path, claims_path];
    for f in &figures {
        let path = dir.join("plots").join(format!("{}.svg", f.name));
        std::fs::write(&path, &f.svg).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    let html_path = dir.join("index.html");
    std::fs::write(&html_path, html::page(runs, &figures, elapsed_s)).map_err(|e| io(&html_path, e))?;
    written.push(html_path);
    Ok(written)
}

/// `claims.json`: what the page's claims table says, with the thresholds
/// it judged by, the units and the matrix, for a reader of the data
/// without the page.
fn claims_json(runs: &Runs) -> String {
    let claims: Vec<serde_json::Value> = claims::evaluate(runs)
        .into_iter()
        .map(|c| {
            serde_json::json!({
                "source": c.source, "claim": c.text, "reproduced": c.reproduced, "evidence": c.evidence,
            })
        })
        .collect();
    let doc = serde_json::json!({
        "sweepslide": env!("CARGO_PKG_VERSION"),
        "matrix": if runs.info.quick { "quick" } else { "full" },
        "runs": runs.info.runs,
        "thresholds": {
            "jitter": claims::JITTER_THRESHOLD, "wobble": claims::JITTER_THRESHOLD,
            "snag_ratio": claims::SNAG_THRESHOLD, "drift_radii": claims::DRIFT_THRESHOLD,
        },
        "units": "penetration and final positions in world units for a sphere; penetration in radii (eSpace) for an \
                  ellipsoid (each run's radii in results.json); jitter and wobble relative to the speed; drift in radii; \
                  non-finite values written as the strings \"NaN\", \"inf\", \"-inf\" (docs/error-analysis.md)",
        "claims": claims,
    });
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

fn csv(lines: &[ResultLine<'_>]) -> String {
    let mut out = String::from(
        "index,group,scene,response,detection,precision,seed,frames,motion,max_penetration,penetrating_frames,first_penetrating_frame,back_face_frames,max_front_penetration,jitter,wobble,max_iterations,max_pass_iterations,mean_iterations,capped_frames,nan_frames,embedded_frames,decision_flips,plane_flips,snag,drift,final_x,final_y,final_z,ns_per_move,degenerate_triangles,units_per_meter,radius_x,radius_y,radius_z\n",
    );
    for l in lines {
        let r = l.result;
        let group = match l.group {
            Group::Main => "main",
            Group::Dial => "dial",
        };
        let snag = r.snag.map_or(String::new(), |s| format!("{s:e}"));
        let drift = r.drift.map_or(String::new(), |d| format!("{d:e}"));
        let first = r.first_penetrating_frame.map_or(String::new(), |f| f.to_string());
        let [x, y, z] = r.final_position;
        let radii = r.radii.map_or(",,".into(), |[a, b, c]| format!("{a:e},{b:e},{c:e}"));
        out += &format!(
            "{},{group},\"{}\",{},{},{},{},{},{},{:e},{},{first},{},{:e},{:e},{:e},{},{},{},{},{},{},{},{},{snag},{drift},{x:e},{y:e},{z:e},{:.1},{},{:e},{radii}\n",
            l.index,
            // A quoted CSV field doubles its quotes (a mesh's file name may
            // hold one).
            r.scene.replace('"', "\"\""),
            r.response,
            r.detection,
            r.precision,
            r.seed,
            r.frames,
            r.motion,
            r.max_penetration,
            r.penetrating_frames,
            r.back_face_frames,
            r.max_front_penetration,
            r.jitter,
            r.wobble,
            r.max_iterations,
            r.max_pass_iterations,
            r.mean_iterations,
            r.capped_frames,
            r.nan_frames,
            r.embedded_frames,
            r.decision_flips,
            r.plane_flips,
            r.ns_per_move,
            r.degenerate_triangles,
            r.units_per_meter
        );
    }
    out
}
