//! `index.html`: one self-contained page (inline CSS and SVG, no scripts,
//! no network) that links only to files written beside it.

use super::Runs;
use super::claims::{DRIFT_THRESHOLD, JITTER_THRESHOLD, SNAG_THRESHOLD, evaluate};
use super::matrix::Group;
use super::plots::{Figure, html_escape, scene_names};
use crate::lab::RunResult;
use crate::lab::scenes::BUILTIN;
use std::fmt::Write;

const STYLE: &str = "body{font-family:sans-serif;max-width:1300px;margin:2em auto;padding:0 1em;color:#222}\
table{border-collapse:collapse;margin:1em 0;font-size:13px}th,td{border:1px solid #ccc;padding:3px 6px;text-align:right}\
th{background:#f0f0f0}td.l,th.l{text-align:left}.yes{background:#e6f4e6}.no{background:#fbe3e3}\
figure{display:inline-block;margin:0.5em;vertical-align:top;max-width:660px}figcaption{font-size:12px;color:#555}\
code{background:#f4f4f4;padding:0 3px}.bad{color:#b00;font-weight:bold}small{color:#666}.wide{overflow-x:auto}";

fn sci(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.2e}") }
}

/// The scene (and seed, other than 1) a worst value came from, set small
/// under it.
fn from_run(r: &RunResult) -> String {
    let seed = if r.seed == 1 { String::new() } else { format!(" seed {}", r.seed) };
    format!("<br><small>{}{seed}</small>", html_escape(&r.scene))
}

/// The cell of the run of `rs` with the largest `key` (the first of
/// equals): the value, then the run it came from; `-` where `rs` is empty.
fn worst_cell<'a>(
    rs: impl Iterator<Item = &'a RunResult>,
    key: impl Fn(&RunResult) -> f64,
    show: fn(f64) -> String,
) -> String {
    rs.reduce(|w, r| if key(r) > key(w) { r } else { w })
        .map_or_else(|| "-".into(), |r| format!("{}{}", show(key(r)), from_run(r)))
}

/// Whether the scene's ideal motion is rest or a straight slide (a scene
/// with an ideal slide, where the run has a snag ratio, or the corner and
/// the dead end, pushed to rest), so that jitter and wobble measure the
/// response: elsewhere the path bends by design (a staircase's climb, a
/// steered walk), which both also score.
fn straight_ideal(r: &RunResult) -> bool {
    let base = r.scene.split([':', '@']).next().unwrap_or(&r.scene);
    r.motion == "constant" && (r.snag.is_some() || base == "corner" || base == "dead-end")
}

/// The class and text of a penetration cell: red where it penetrates,
/// green where it does not, and uncoloured, marked with a dagger, where a
/// run reached NaN (its penetration covers only the frames before).
fn penetration_cell(depth: f64, reached_nan: bool) -> (&'static str, String) {
    match (depth > 0.0, reached_nan) {
        (true, _) => ("no", sci(depth)),
        (false, true) => ("l", format!("{}&dagger;", sci(depth))),
        (false, false) => ("yes", sci(depth)),
    }
}

/// One row of the summary: the aggregate over the runs of one response in
/// one precision.
fn summary_row(out: &mut String, response: &str, precision: &str, rs: &[&RunResult]) {
    let sum = |f: &dyn Fn(&RunResult) -> usize| rs.iter().map(|r| f(r)).sum::<usize>();
    let counted = |r: &RunResult| r.counted_penetration().1;
    let worst_counted = rs.iter().map(|r| counted(r)).fold(0.0, f64::max);
    let (pen_class, pen) = penetration_cell(worst_counted, rs.iter().any(|r| r.nan_frames > 0));
    let pen_frames = sum(&|r| r.counted_penetration().0);
    let behind = sum(&|r| r.penetrating_frames) - pen_frames;
    // Over the runs whose ideal is rest or a straight slide and whose
    // jitter could be computed (a run with NaN frames has none).
    let straight = || rs.iter().copied().filter(|r| straight_ideal(r) && !r.jitter.is_nan());
    let snag = rs.iter().copied().filter(|r| r.snag.is_some()).reduce(|w, r| if r.snag < w.snag { r } else { w });
    let mut times: Vec<f64> = rs.iter().map(|r| r.ns_per_move).collect();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    let nan = sum(&|r| r.nan_frames);
    let _ = writeln!(
        out,
        "<tr><td class=l>{response}</td><td class=l>{precision}</td><td class={pen_class}>{pen}{}</td><td>{pen_frames}</td><td>{behind}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class={}>{nan}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{median:.0}</td></tr>",
        if worst_counted > 0.0 { worst_cell(rs.iter().copied(), counted, |_| String::new()) } else { String::new() },
        worst_cell(rs.iter().copied().filter(|r| r.max_penetration > 0.0), |r| r.max_penetration, sci),
        worst_cell(straight(), |r| r.jitter, sci),
        worst_cell(straight(), |r| r.wobble, sci),
        rs.iter().map(|r| r.max_iterations).max().unwrap_or(0),
        sum(&|r| r.capped_frames),
        if nan > 0 { "no" } else { "yes" },
        sum(&|r| r.decision_flips),
        sum(&|r| r.plane_flips),
        snag.map_or_else(|| "-".into(), |r| format!("{:.6}{}", r.snag.unwrap_or(f64::NAN), from_run(r))),
        worst_cell(rs.iter().copied().filter(|r| r.drift.is_some()), |r| r.drift.unwrap_or(0.0), sci),
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
        let (frames, depth) = r.counted_penetration();
        let (pen_class, pen) = penetration_cell(depth, r.nan_frames > 0);
        let behind = r.penetrating_frames - frames;
        let _ = writeln!(
            out,
            "<tr><td class=l>{}</td><td class=l>{}</td><td>{}</td><td class={pen_class}>{pen}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.0}</td></tr>",
            r.response,
            r.precision,
            r.seed,
            if behind > 0 {
                format!("{frames} (and {behind} entered from behind, to {})", sci(r.max_penetration))
            } else {
                frames.to_string()
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
        "<h1>sweepslide: error-analysis report</h1><p>{} matrix: {} runs ({} in the main table, {} on the precision dial){}. Data: <a href=\"results.json\">results.json</a>, <a href=\"results.csv\">results.csv</a>, <a href=\"runs.json\">runs.json</a>, <a href=\"claims.json\">claims.json</a> (the claims and the thresholds they are judged by). Penetration is exact (MPFR, 512 bits or more, from the stored binary values, after every frame); decision flips compare every frame with the same frame replayed in <code>Mpfr&lt;256&gt;</code> (twice the run&#39;s precision beyond 128 bits) with the same tolerances (no rounding). See <code>docs/error-analysis.md</code> for the definitions.</p>",
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
    let scenes = scene_names(runs);
    let _ = writeln!(
        out,
        "<nav><p>Contents: <a href=\"#summary\">Summary</a> &middot; <a href=\"#claims\">Claims</a> &middot; <a href=\"#figures\">Figures</a> &middot; <a href=\"#scenes\">Scenes</a>: {}</p></nav>",
        scenes.iter().map(|s| format!("<a href=\"#scene-{0}\">{0}</a>", html_escape(s))).collect::<Vec<_>>().join(", ")
    );
    out.push_str("<h2 id=summary>Summary</h2><p>Aggregates over every scene of the main table, worst or total per response and precision; under each worst value, the scene it came from. Penetration is in world units for a sphere and in radii for an ellipsoid (the <code>room</code> scene and some fuzz cases; each run's radii are in <code>results.json</code>), measured after every frame (a body that passed through a wall within one frame is not caught). For Fauerby's detection (kept by Linahan's response), which is one-sided by design, the first two penetration columns leave out the frames that end inside only triangles they entered from behind (the body's centre behind each one's plane at the start of the frame it entered it, moving along its front normal in one of that frame's passes, so that the detection culled it); the next two give those frames' count and the worst depth of every frame. &dagger;: some runs reached a NaN position, and their penetration covers only the frames before it. Jitter (the path's excess over the net displacement) and wobble (how much the step goes back and forth from frame to frame, which shows a sliding body's zigzag that jitter barely scores) are over the scenes whose ideal is rest or a straight slide, pushed constantly (the staircase's climb and a steered walk bend by design, which both also score). Capped frames stopped at the response's cap (Fauerby's depth, Linahan's third plane, the robust budget): a body held there can show no jitter, but it is stuck. Drift is in radii off the ideal slide's line, from the first frame that slides as the ideal does (none where no frame does). Time is the median over the runs of each run's time per move, the least of three passes over its moves. NaN positions at 113 and 256 bits only (Fauerby's, on the staircase, the room and the messy floor) come from exact ties that coarser precisions round away (<code>docs/findings.md</code>).</p>\n");
    out.push_str("<div class=wide><table><tr><th class=l>response</th><th class=l>precision</th><th>worst penetration</th><th>penetrating frames</th><th>frames entered from behind</th><th>worst incl. entered from behind</th><th>worst jitter</th><th>worst wobble</th><th>max checks/frame</th><th>capped frames</th><th>NaN frames</th><th>decision flips</th><th>plane flips</th><th>worst snag ratio</th><th>worst drift (radii)</th><th>ns/move</th></tr>\n");
    for resp in ["fauerby", "linahan", "robust"] {
        for prec in super::matrix::PRECISIONS {
            let p = prec.to_string();
            let rs: Vec<&RunResult> = main.iter().copied().filter(|r| r.response == resp && r.precision == p).collect();
            if !rs.is_empty() {
                summary_row(&mut out, resp, &p, &rs);
            }
        }
    }
    out.push_str("</table></div>\n");
    let _ = writeln!(
        out,
        "<h2 id=claims>Claims</h2><p>Jitter and wobble count above {JITTER_THRESHOLD:e} of the speed, snagging below a ratio of {SNAG_THRESHOLD}, drift from {DRIFT_THRESHOLD:e} radii on.</p><table><tr><th class=l>source</th><th class=l>claim</th><th class=l>verdict</th><th class=l>evidence</th></tr>"
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
    out.push_str("</table>\n<h2 id=figures>Figures</h2>\n");
    for f in figures.iter().filter(|f| f.scene.is_none()) {
        figure(&mut out, f);
    }
    out.push_str("<h2 id=scenes>Scenes</h2>\n");
    for scene in scenes {
        let base = scene.split([':', '@']).next().unwrap_or(&scene);
        let description = match BUILTIN.iter().find(|b| b.0 == base) {
            Some(b) => b.2,
            None if base == "case" => "a fuzz case or finding (JSON)",
            None => "mesh from an OBJ file",
        };
        let rs: Vec<&RunResult> = main.iter().copied().filter(|r| r.scene == scene).collect();
        let body = rs.iter().find_map(|r| r.radii).map_or(String::new(), |[a, b, c]| {
            if a == b && b == c {
                format!(" Body: a sphere of radius {a}.")
            } else {
                format!(" Body: an ellipsoid of radii ({a}, {b}, {c}).")
            }
        });
        let _ = writeln!(
            out,
            "<h3 id=\"scene-{0}\">{0}</h3><p>{1}{body}</p>",
            html_escape(&scene),
            html_escape(description)
        );
        run_table(&mut out, &rs);
        for f in figures.iter().filter(|f| f.scene.as_deref() == Some(scene.as_str())) {
            figure(&mut out, f);
        }
    }
    out.push_str("</body></html>\n");
    out
}
