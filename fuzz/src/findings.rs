//! The findings log of `compare_responses`: failures of the faithful
//! responses (Fauerby, Linahan) are recorded, never asserted.
//!
//! Per class (response, precision, kind of failure) the first failure and
//! every later one that beats the class's record (a deeper penetration)
//! print one line on stderr, `finding: ...`. With `SWEEPSLIDE_FINDINGS=1`
//! in the environment the same failures are also written to
//! `fuzz/findings/<target>/` (or `$SWEEPSLIDE_FINDINGS_DIR/<target>/`) as
//! `<class>-<hash>.json` (the decoded case and the failure) and
//! `<class>-<hash>.bin` (the raw input, replayable with
//! `cargo fuzz run <target> <file>`). Without it nothing is written, so CI
//! smoke runs leave no files behind.

use crate::input::Precision;
use crate::oracle::{FrameFailure, MoveCase};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Mutex;

static RECORDS: Mutex<Option<HashMap<String, f64>>> = Mutex::new(None);

/// FNV-1a of the input bytes, for file names.
fn hash(data: &[u8]) -> u64 {
    data.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// The directory findings of `target` go to.
#[must_use]
pub fn dir(target: &str) -> PathBuf {
    let root = std::env::var_os("SWEEPSLIDE_FINDINGS_DIR")
        .map_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/findings")), PathBuf::from);
    root.join(target)
}

/// Whether findings are written to files.
#[must_use]
pub fn enabled() -> bool {
    std::env::var("SWEEPSLIDE_FINDINGS").is_ok_and(|v| v == "1")
}

fn severity(f: &FrameFailure) -> f64 {
    match f.failure {
        crate::oracle::Failure::Penetration(p) => p,
        _ => f64::INFINITY,
    }
}

/// Records a failure of `response` on `case` (decoded from `data`).
/// Returns `true` when it was a new class or record (and so was printed,
/// and written if enabled).
pub fn record(
    target: &str,
    response: &str,
    precision: Precision,
    case: &MoveCase,
    data: &[u8],
    f: &FrameFailure,
) -> bool {
    let prec = match precision {
        Precision::F32 => "f32",
        Precision::F64 => "f64",
    };
    let class = format!("{response}-{prec}-{}", f.failure.kind());
    let depth = severity(f);
    {
        let mut guard = RECORDS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let records = guard.get_or_insert_with(HashMap::new);
        match records.get(&class) {
            Some(&best) if depth.partial_cmp(&best) != Some(std::cmp::Ordering::Greater) => return false,
            _ => {
                records.insert(class.clone(), depth);
            }
        }
    }
    eprintln!(
        "finding: {class} {:?} at frame {} of {} ({} triangles, radii {:?}, |start| {:.3e})",
        f.failure,
        f.frame,
        case.frames.len(),
        case.triangles.len(),
        case.radii,
        case.start.iter().fold(0.0f64, |m, x| m.max(x.abs())),
    );
    if enabled() {
        let dir = dir(target);
        let name = format!("{class}-{:016x}", hash(data));
        let frames: Vec<serde_json::Value> = case
            .frames
            .iter()
            .map(|fr| serde_json::json!({ "velocity": fr.velocity, "gravity": fr.gravity }))
            .collect();
        let doc = serde_json::json!({
            "target": target,
            "response": response,
            "precision": prec,
            "kind": f.failure.kind(),
            "failure": format!("{:?}", f.failure),
            "frame": f.frame,
            "from": f.from,
            "to": f.to,
            "case": {
                "triangles": case.triangles,
                "radii": case.radii,
                "start": case.start,
                "frames": frames,
            },
        });
        let written = std::fs::create_dir_all(&dir).and_then(|()| {
            std::fs::write(dir.join(format!("{name}.json")), serde_json::to_string_pretty(&doc).unwrap_or_default())?;
            std::fs::write(dir.join(format!("{name}.bin")), data)
        });
        if let Err(e) = written {
            eprintln!("finding: could not write {}: {e}", dir.display());
        }
    }
    true
}
