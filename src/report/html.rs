//! `index.html`: one self-contained page (inline CSS and SVG, no scripts,
//! no network) that links only to files written beside it.

use super::Runs;
use super::claims::{DRIFT_THRESHOLD, JITTER_THRESHOLD, SNAG_THRESHOLD, evaluate};
use super::matrix::Group;
use super::plots::{Figure, html_escape, scene_names};
use crate::lab::RunResult;
use crate::lab::scenes::BUILTIN;
use std::fmt::Write;

const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}\
table{border-collapse:collapse;margin:1em 0;font-size:13px}th,td{border:1px solid #ccc;padding:3px 6px;text-align:right}\
th{background:#f0f0f0}td.l,th.l{text-align:left}.yes{background:#e6f4e6}.no{background:#fbe3e3}\
figure{display:inline-block;margin:0.5em;vertical-align:top;max-width:660px}figcaption{font-size:12px;color:#555}\
code{background:#f4f4f4;padding:0 3px}.bad{color:#b00;font-weight:bold}";

fn sci(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.2e}") }
}

/// One row of the summary: the aggregate over the runs of one response in
/// one precision.
fn summary_row(out: &mut String, response: &str, precision: &str, rs: &[&RunResult]) {
    let max = |f: &dyn Fn(&RunResult) -> f64| rs.iter().map(|r| f(r)).fold(0.0, f64::max);
    let pen = rs.iter().map(|r| r.counted_penetration().1).fold(0.0, f64::max);
    let pen_frames: usize = rs.iter().map(|r| r.counted_penetration().0).sum();
    // Over the constant pushes whose jitter could be computed (a run with
    // NaN frames has none); "-" when there are none.
    let constant = || rs.iter().filter(|r| r.motion == "constant" && !r.jitter.is_nan());
    let jitter = constant().map(|r| r.jitter).reduce(f64::max);
    let wobble = constant().map(|r| r.wobble).reduce(f64::max);
    let sum = |f: &dyn Fn(&RunResult) -> usize| rs.iter().map(|r| f(r)).sum::<usize>();
    let snag = rs.iter().filter_map(|r| r.snag).fold(f64::INFINITY, f64::min);
    let drift = rs.iter().filter_map(|r| r.drift).reduce(f64::max);
    let mut times: Vec<f64> = rs.iter().map(|r| r.ns_per_move).collect();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    let all_pen = max(&|r| r.max_penetration);
    let _ = writeln!(
        out,
        "<tr><td class=l>{response}</td><td class=l>{precision}</td><td class={}>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class={}>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.0}</td></tr>",
        if pen > 0.0 { "no" } else { "yes" },
        sci(pen),
        pen_frames,
        sci(all_pen),
        jitter.map_or_else(|| "-".into(), sci),
        wobble.map_or_else(|| "-".into(), sci),
        rs.iter().map(|r| r.max_iterations).max().unwrap_or(0),
        if sum(&|r| r.nan_frames) > 0 { "no" } else { "yes" },
        sum(&|r| r.nan_frames),
        sum(&|r| r.decision_flips),
        sum(&|r| r.plane_flips),
        if snag.is_finite() { format!("{snag:.6}") } else { "-".into() },
        drift.map_or_else(|| "-".into(), sci),
        median
    );
}

fn figure(out: &mut String, f: &Figure) {
    let _ = writeln!(
        out,
        "<figure id=\"{0}\">{1}<figcaption><b>{2}</b> {3} <a href=\"plots/{0}.svg\">SVG</a></figcaption></figure>",
        f.name,
        f.svg.trim_start_matches(|c| c != '<').replacen("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", "", 1),
        html_escape(&f.title),
        html_escape(&f.caption)
    );
}

fn run_table(out: &mut String, rs: &[&RunResult]) {
    out.push_str("<table><tr><th class=l>response</th><th class=l>precision</th><th>seed</th><th>max penetration</th><th>penetrating frames</th><th>jitter</th><th>wobble</th><th>max checks</th><th>capped frames</th><th>NaN frames</th><th>decision flips</th><th>plane flips</th><th>snag</th><th>drift</th><th>ns/move</th></tr>\n");
    for r in rs {
        let _ = writeln!(
            out,
            "<tr><td class=l>{}</td><td class=l>{}</td><td>{}</td><td class={}>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.0}</td></tr>",
            r.response,
            r.precision,
            r.seed,
            if r.counted_penetration().0 > 0 { "no" } else { "yes" },
            sci(r.max_penetration),
            if r.back_face_frames > 0 {
                format!("{} ({} from behind)", r.penetrating_frames, r.back_face_frames)
            } else {
                r.penetrating_frames.to_string()
            },
            sci(r.jitter),
            sci(r.wobble),
            r.max_iterations,
            r.capped_frames,
            r.nan_frames,
            r.decision_flips,
            r.plane_flips,
            r.snag.map_or("-".into(), |s| format!("{s:.6}")),
            r.drift.map_or("-".into(), sci),
            r.ns_per_move
        );
    }
    out.push_str("</table>\n");
}

/// The whole page.
#[must_use]
pub fn page(runs: &Runs, figures: &[Figure], elapsed_s: Option<f64>) -> String {
    let main: Vec<&RunResult> =
        runs.records.iter().filter(|r| r.entry.group == Group::Main).filter_map(|r| r.outcome.as_ref().ok()).collect();
    let failed: Vec<String> = runs
        .records
        .iter()
        .filter_map(|r| r.outcome.as_ref().err().map(|e| format!("run {}: {}", r.entry.index, e)))
        .collect();
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>sweepslide error-analysis report</title><style>{STYLE}</style></head><body>\n"
    );
    let _ = writeln!(
        out,
        "<h1>sweepslide: error-analysis report</h1><p>{} matrix: {} runs ({} in the main table, {} on the precision dial){}. Data: <a href=\"results.json\">results.json</a>, <a href=\"results.csv\">results.csv</a>, <a href=\"runs.json\">runs.json</a>. Penetration is exact (MPFR, 512 bits or more, from the stored binary values, after every frame); decision flips compare every frame with the same frame replayed in <code>Mpfr&lt;256&gt;</code> (twice the run&#39;s precision beyond 128 bits) with the same tolerances (no rounding). See <code>docs/error-analysis.md</code> for the definitions.</p>",
        if runs.info.quick { "Quick" } else { "Full" },
        runs.info.runs,
        main.len(),
        runs.records.iter().filter(|r| r.entry.group == Group::Dial).count(),
        elapsed_s.map_or(String::new(), |s| format!(", made in {s:.0} s"))
    );
    if !failed.is_empty() {
        let _ = writeln!(out, "<p class=bad>{} runs failed: {}</p>", failed.len(), html_escape(&failed.join("; ")));
    }
    for note in super::degenerate_notes(runs) {
        let _ = writeln!(out, "<p class=bad>{}</p>", html_escape(&note));
    }
    out.push_str("<h2>Summary</h2><p>Aggregates over every scene of the main table, worst or total per response and precision. Penetration is in world units for a sphere and in radii for an ellipsoid (the <code>room</code> scene and some fuzz cases). For Fauerby's detection (kept by Linahan's response), which is one-sided by design, it leaves out the frames that end inside only triangles they entered from behind (the body's centre behind each one's plane at the start of the frame it entered it, moving along its front normal in one of that frame's passes, so that the detection culled it); the next column counts every frame. Jitter (the path's excess over the net displacement) and wobble (how much the step goes back and forth from frame to frame, which shows a sliding body's zigzag that jitter barely scores) count the constant-push scenes only (a steered path bends, which both also score). Drift is in radii off the ideal slide's line, from the first frame that slides as the ideal does (none where no frame does). Time is the median of the runs' mean time per move.</p>\n");
    out.push_str("<table><tr><th class=l>response</th><th class=l>precision</th><th>worst penetration</th><th>penetrating frames</th><th>incl. entered from behind</th><th>worst jitter</th><th>worst wobble</th><th>max checks/frame</th><th>NaN frames</th><th>decision flips</th><th>plane flips</th><th>worst snag ratio</th><th>worst drift</th><th>ns/move</th></tr>\n");
    for resp in ["fauerby", "linahan", "robust"] {
        for prec in super::matrix::PRECISIONS {
            let p = prec.to_string();
            let rs: Vec<&RunResult> = main.iter().copied().filter(|r| r.response == resp && r.precision == p).collect();
            if !rs.is_empty() {
                summary_row(&mut out, resp, &p, &rs);
            }
        }
    }
    out.push_str("</table>\n");
    let _ = writeln!(
        out,
        "<h2>Claims</h2><p>Jitter and wobble count above {JITTER_THRESHOLD:e} of the speed, snagging below a ratio of {SNAG_THRESHOLD}, drift from {DRIFT_THRESHOLD:e} radii on.</p><table><tr><th class=l>source</th><th class=l>claim</th><th class=l>verdict</th><th class=l>evidence</th></tr>"
    );
    for c in evaluate(runs) {
        let _ = writeln!(
            out,
            "<tr><td class=l>{}</td><td class=l>{}</td><td class=\"l {}\">{}</td><td class=l>{}</td></tr>",
            c.source,
            html_escape(c.text),
            if c.reproduced { "yes" } else { "no" },
            if c.reproduced { "reproduced" } else { "not reproduced" },
            html_escape(&c.evidence)
        );
    }
    out.push_str("</table>\n<h2>Figures</h2>\n");
    for f in figures.iter().filter(|f| f.scene.is_none()) {
        figure(&mut out, f);
    }
    out.push_str("<h2>Scenes</h2>\n");
    for scene in scene_names(runs) {
        let base = scene.split([':', '@']).next().unwrap_or(&scene);
        let description = match BUILTIN.iter().find(|b| b.0 == base) {
            Some(b) => b.2,
            None if base == "case" => "a fuzz case or finding (JSON)",
            None => "mesh from an OBJ file",
        };
        let _ = writeln!(out, "<h3 id=\"scene-{0}\">{0}</h3><p>{1}</p>", html_escape(&scene), html_escape(description));
        let rs: Vec<&RunResult> = main.iter().copied().filter(|r| r.scene == scene).collect();
        run_table(&mut out, &rs);
        for f in figures.iter().filter(|f| f.scene.as_deref() == Some(scene.as_str())) {
            figure(&mut out, f);
        }
    }
    out.push_str("</body></html>\n");
    out
}
