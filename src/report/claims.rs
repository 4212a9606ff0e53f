//! The claims the report checks: the paper's, the independent
//! reimplementation's (ALGORITHMS.md section 8) and ours, each judged on the
//! runs with the evidence spelled out.

use super::Runs;
use super::matrix::Group;
use crate::lab::RunResult;

/// A claim and what the runs say about it.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// Who claims it.
    pub source: &'static str,
    /// The claim.
    pub text: &'static str,
    /// Whether the runs show it.
    pub reproduced: bool,
    /// The numbers behind the verdict.
    pub evidence: String,
}

pub use crate::lab::metrics::{DRIFT_THRESHOLD, JITTER_THRESHOLD};
/// A snag ratio below this counts as snagging.
pub const SNAG_THRESHOLD: f64 = 0.999;

fn results(runs: &Runs) -> Vec<&RunResult> {
    runs.records.iter().filter(|r| r.entry.group == Group::Main).filter_map(|r| r.outcome.as_ref().ok()).collect()
}

fn describe(r: &RunResult) -> String {
    let seed = if r.seed == 1 { String::new() } else { format!(" (seed {})", r.seed) };
    format!("{} / {}{seed}", r.scene, r.precision)
}

/// The worst run by `key` among `rs`, the first of equals (the table's
/// order: `f32` before the `mpfr24` that reproduces it), described with
/// the value (a NaN value, which sorts above every other, says it could
/// not be computed).
fn worst<'a>(rs: impl Iterator<Item = &'a RunResult>, key: impl Fn(&RunResult) -> f64, unit: &str) -> String {
    let first_of_equals = rs.reduce(|best, r| if key(r).total_cmp(&key(best)).is_gt() { r } else { best });
    first_of_equals.map_or("no runs".into(), |r| match key(r) {
        k if k.is_nan() => format!("not computable ({}: NaN frames)", describe(r)),
        k => format!("worst {k:.3e}{unit} ({})", describe(r)),
    })
}

/// The smallest snag ratio of `rs` and over how many runs (those with an
/// ideal slide), or that there are none.
fn smallest_snag<'a>(rs: impl Iterator<Item = &'a RunResult>, what: &str) -> String {
    let ratios: Vec<f64> = rs.filter_map(|r| r.snag).collect();
    match ratios.iter().copied().reduce(f64::min) {
        Some(least) => format!("smallest snag ratio {least:.6} over {} {what}", ratios.len()),
        None => format!("no {what}"),
    }
}

/// The precisions with `f32`'s significand (the hardware float and its
/// MPFR twin).
fn single(r: &RunResult) -> bool {
    r.precision == "f32" || r.precision == "mpfr24"
}

/// Whether a run came to rest or slid steadily: its jitter and its wobble
/// ([`crate::lab::metrics::wobble`], the measure that a sliding body's
/// zigzag shows in) at most [`JITTER_THRESHOLD`]; `false` where either is
/// NaN.
fn steady(r: &RunResult) -> bool {
    r.jitter <= JITTER_THRESHOLD && r.wobble <= JITTER_THRESHOLD
}

/// The runs of `rs` without NaN frames, and how many had some: after a
/// NaN position a run shows nothing (no penetration can be measured, no
/// jitter computed), so it cannot show an absence and is left out of the
/// claims that judge one, and said ([`left_out`]).
fn without_nan<'a>(rs: impl Iterator<Item = &'a RunResult>) -> (Vec<&'a RunResult>, usize) {
    let (clean, nan): (Vec<&RunResult>, Vec<&RunResult>) = rs.partition(|r| r.nan_frames == 0);
    (clean, nan.len())
}

/// The note on the runs [`without_nan`] left out (empty when none).
fn left_out(nan_runs: usize) -> String {
    if nan_runs == 0 {
        String::new()
    } else {
        format!(" (left out: {nan_runs} runs with NaN frames, which show nothing after the NaN)")
    }
}

/// One run's slide ratio and frames at the cap, then `more` (what else
/// the claim weighs), for the evidence of the freeze claims.
fn slide_evidence(r: &RunResult, more: &str) -> String {
    // A run that ends at NaN has no slide ratio.
    let snag = r.snag.map_or_else(|| "none (no finite end)".to_string(), |s| format!("{s:.3}"));
    format!(
        "{} {}: snag ratio {snag}, {} of {} frames at the cap, {more}",
        r.response,
        describe(r),
        r.capped_frames,
        r.frames
    )
}

fn is_base(r: &RunResult, base: &str) -> bool {
    r.scene.split(':').next() == Some(base) && !r.scene.contains('@')
}

/// Every claim, judged.
#[must_use]
pub fn evaluate(runs: &Runs) -> Vec<Claim> {
    let all = results(runs);
    let of = |resp: &'static str| all.iter().copied().filter(move |r| r.response == resp);
    let hw = |r: &&RunResult| r.precision == "f32" || r.precision == "f64";
    let mut claims = Vec::new();

    // Frames that end inside only triangles they entered from behind are
    // the one-sided detection's semantics, not failures: left out, and said.
    let behind = |resp: &'static str| {
        let rs: Vec<&RunResult> = of(resp).filter(|r| r.one_sided() && r.back_face_frames > 0).collect();
        let mut scenes: Vec<&str> = rs.iter().map(|r| r.scene.as_str()).collect();
        scenes.sort_unstable();
        scenes.dedup();
        if rs.is_empty() {
            String::new()
        } else {
            format!(
                " (left out: {} frames of {} runs that end inside only triangles they entered from behind, which a \
                 one-sided detection passes by design, in {})",
                rs.iter().map(|r| r.back_face_frames).sum::<usize>(),
                rs.len(),
                scenes.join(", ")
            )
        }
    };
    let counted = |r: &RunResult| r.counted_penetration().1;
    let pen: Vec<&RunResult> = of("fauerby").filter(|r| r.counted_penetration().0 > 0).collect();
    claims.push(Claim {
        source: "Linahan 2012, abstract",
        text: "Fauerby's response lets the sphere penetrate the triangles.",
        reproduced: !pen.is_empty(),
        evidence: format!(
            "{} of {} Fauerby runs end a frame inside the geometry: {}; {}{}",
            pen.len(),
            of("fauerby").count(),
            pen.iter().map(|r| describe(r)).collect::<Vec<_>>().join(", "),
            worst(pen.iter().copied(), counted, ""),
            behind("fauerby")
        ),
    });
    let wide_pen: Vec<&RunResult> = pen.iter().copied().filter(|r| !single(r)).collect();
    let (wide, wide_nan) = without_nan(of("fauerby").filter(|r| !single(r)));
    claims.push(Claim {
        source: "ALGORITHMS.md section 8",
        text: "Fauerby penetrates only in f32, never in f64.",
        reproduced: !pen.is_empty() && wide_pen.is_empty() && !wide.is_empty(),
        evidence: if wide_pen.is_empty() {
            format!(
                "all {} penetrating Fauerby runs are f32 or its twin mpfr24; none of {} at 53 bits or more{}{}",
                pen.len(),
                wide.len(),
                left_out(wide_nan),
                behind("fauerby")
            )
        } else {
            format!(
                "{} Fauerby runs at 53 bits or more penetrate; {}{}",
                wide_pen.len(),
                worst(wide_pen.iter().copied(), counted, ""),
                behind("fauerby")
            )
        },
    });
    let corner = |resp: &'static str| of(resp).filter(|r| is_base(r, "corner")).filter(hw).collect::<Vec<_>>();
    let (fj, fj_nan) = without_nan(corner("fauerby").into_iter());
    claims.push(Claim {
        source: "Linahan 2012, III.B, Fig. 2-3",
        text: "Fauerby's response jitters in an obtuse corner instead of coming to rest.",
        reproduced: !fj.is_empty() && fj.iter().all(|r| !steady(r)),
        evidence: fj
            .iter()
            .map(|r| format!("jitter {:.3}, wobble {:.3} in {}", r.jitter, r.wobble, describe(r)))
            .collect::<Vec<_>>()
            .join("; ")
            + &left_out(fj_nan),
    });
    let wedge: Vec<&RunResult> = of("fauerby").filter(|r| is_base(r, "wedge")).filter(hw).collect();
    claims.push(Claim {
        source: "Linahan 2012, III.C, Fig. 4",
        text: "In an acute wedge Fauerby's response ping-pongs until its recursion cap.",
        reproduced: !wedge.is_empty() && wedge.iter().all(|r| r.capped_frames > 0),
        evidence: wedge
            .iter()
            .map(|r| format!("{} of {} frames at the cap in {}", r.capped_frames, r.frames, describe(r)))
            .collect::<Vec<_>>()
            .join("; "),
    });
    let lpen: Vec<&RunResult> = of("linahan").filter(|r| r.counted_penetration().0 > 0).collect();
    let (lclean, lnan) = without_nan(of("linahan"));
    claims.push(Claim {
        source: "Linahan 2012, IV",
        text: "Linahan's response never lets the sphere penetrate the mesh.",
        reproduced: lpen.is_empty() && !lclean.is_empty(),
        evidence: if lpen.is_empty() {
            format!("no penetrating frame in {} Linahan runs{}{}", lclean.len(), left_out(lnan), behind("linahan"))
        } else {
            format!(
                "{} of {} Linahan runs penetrate: {}; {}{}",
                lpen.len(),
                of("linahan").count(),
                lpen.iter().map(|r| describe(r)).collect::<Vec<_>>().join(", "),
                worst(lpen.iter().copied(), counted, ""),
                behind("linahan")
            )
        },
    });
    let (lj, lj_nan) = without_nan(corner("linahan").into_iter());
    claims.push(Claim {
        source: "Linahan 2012, III.G",
        text: "Linahan's response comes to rest in corners: no jitter.",
        reproduced: !lj.is_empty() && lj.iter().all(|r| steady(r)),
        evidence: lj
            .iter()
            .map(|r| format!("jitter {:.3e}, wobble {:.3e} in {}", r.jitter, r.wobble, describe(r)))
            .collect::<Vec<_>>()
            .join("; ")
            + &left_out(lj_nan),
    });
    let over: Vec<&RunResult> = of("linahan").filter(|r| r.max_pass_iterations > 3).collect();
    claims.push(Claim {
        source: "Linahan 2012, III.G",
        text: "Linahan's response needs at most three collision checks per pass.",
        reproduced: over.is_empty() && of("linahan").next().is_some(),
        evidence: match (
            of("linahan").map(|r| r.max_pass_iterations).max(),
            of("linahan").map(|r| r.max_iterations).max(),
        ) {
            (Some(pass), Some(frame)) => format!(
                "largest count per pass {pass} (per frame {frame}: two passes when the scene has gravity){}",
                if over.is_empty() {
                    String::new()
                } else {
                    format!("; more in {}", over.iter().map(|r| describe(r)).collect::<Vec<_>>().join(", "))
                }
            ),
            _ => "no Linahan runs".into(),
        },
    });
    // The folds' freezes are stops at a third plane, not snags on edges:
    // their own claim below.
    let sliding = |resp: &'static str| of(resp).filter(|r| !is_base(r, "fold"));
    let snags: Vec<&RunResult> = sliding("linahan").filter(|r| r.snag.is_some_and(|s| s < SNAG_THRESHOLD)).collect();
    claims.push(Claim {
        source: "Linahan 2012, IV (open problem)",
        text: "Linahan's response snags on triangle edges.",
        reproduced: !snags.is_empty(),
        evidence: smallest_snag(sliding("linahan"), "runs with an ideal slide, the folds left out (next claims)"),
    });
    let folds = |resp: &'static str| of(resp).filter(|r| is_base(r, "fold")).filter(hw).collect::<Vec<_>>();
    let frozen = |r: &&RunResult| r.snag.is_some_and(|s| s < SNAG_THRESHOLD) && r.capped_frames > 0;
    let slides = |r: &&RunResult| r.snag.is_some_and(|s| s >= SNAG_THRESHOLD);
    let faithful: Vec<&RunResult> = folds("fauerby").into_iter().chain(folds("linahan")).collect();
    let frozen_f32 = |resp: &str| faithful.iter().any(|r| r.response == resp && r.precision == "f32" && frozen(r));
    claims.push(Claim {
        source: "sweepslide (lab)",
        text: "In f32 both faithful responses freeze in a V-shaped valley whose fold is not axis-aligned, where they slide in \
               f64.",
        reproduced: frozen_f32("fauerby")
            && frozen_f32("linahan")
            && faithful.iter().filter(|r| r.precision == "f64").all(&slides),
        evidence: faithful
            .iter()
            .map(|r| slide_evidence(r, &format!("{} inside", r.penetrating_frames)))
            .collect::<Vec<_>>()
            .join("; "),
    });
    // A tilted plane away from the origin: no coordinate is zero, and in
    // f32 the faithful responses' slides along it, rounded, approach it
    // again.
    let tilted: Vec<&RunResult> = all
        .iter()
        .copied()
        .filter(|r| r.response != "robust" && r.scene.starts_with("tilted-floor:") && r.scene.contains('@'))
        .filter(hw)
        .collect();
    let fails = |r: &RunResult| if r.response == "fauerby" { frozen(&r) } else { r.nan_frames > 0 };
    let in_f32_only = |resp: &str| {
        let rs: Vec<&&RunResult> = tilted.iter().filter(|r| r.response == resp).collect();
        rs.iter().any(|r| r.precision == "f32" && fails(r))
            && rs.iter().any(|r| r.precision == "f64")
            && rs.iter().filter(|r| r.precision == "f64").all(|r| slides(r))
    };
    claims.push(Claim {
        source: "sweepslide (lab)",
        text: "In f32, away from the origin, on a tilted floor Fauerby's response freezes and Linahan's gives NaN, where \
               both slide in f64.",
        reproduced: in_f32_only("fauerby") && in_f32_only("linahan"),
        evidence: if tilted.is_empty() {
            "no runs on a tilted floor away from the origin".into()
        } else {
            tilted
                .iter()
                .map(|r| slide_evidence(r, &format!("{} NaN frames", r.nan_frames)))
                .collect::<Vec<_>>()
                .join("; ")
        },
    });
    let nans: Vec<&RunResult> = all.iter().copied().filter(|r| r.response != "robust" && r.nan_frames > 0).collect();
    claims.push(Claim {
        source: "ALGORITHMS.md section 8",
        text: "Both faithful responses can produce NaN positions.",
        reproduced: nans.iter().any(|r| r.response == "fauerby") && nans.iter().any(|r| r.response == "linahan"),
        evidence: if nans.is_empty() {
            "no NaN in the built-in matrix (the fuzz campaigns and regression scenes look further)".into()
        } else {
            nans.iter()
                .map(|r| format!("{} {}: {} NaN frames", r.response, describe(r), r.nan_frames))
                .collect::<Vec<_>>()
                .join("; ")
        },
    });
    let rpen: Vec<&RunResult> = of("robust").filter(|r| r.counted_penetration().0 > 0).collect();
    let (rclean, rnan_runs) = without_nan(of("robust"));
    claims.push(Claim {
        source: "sweepslide",
        text: "The robust response never penetrates, in any precision of the table.",
        reproduced: rpen.is_empty() && !rclean.is_empty() && rnan_runs == 0,
        evidence: if rpen.is_empty() {
            format!(
                "no frame of {} robust runs ended inside the geometry (judged exactly after every frame, at 512 bits or more; within a frame a body is not judged){}",
                rclean.len(),
                left_out(rnan_runs)
            )
        } else {
            format!("{} robust runs penetrate; {}", rpen.len(), worst(rpen.iter().copied(), counted, ""))
        },
    });
    let rnan = of("robust").filter(|r| r.nan_frames > 0).count();
    claims.push(Claim {
        source: "sweepslide",
        text: "The robust response never produces NaN.",
        reproduced: rnan == 0 && of("robust").next().is_some(),
        evidence: format!("{rnan} of {} robust runs with NaN frames", of("robust").count()),
    });
    let rest: Vec<&RunResult> = of("robust")
        .filter(|r| ["corner", "dead-end", "wedge", "crease", "fold"].iter().any(|b| is_base(r, b)))
        .collect();
    claims.push(Claim {
        source: "sweepslide",
        text: "The robust response does not jitter in corners, wedges, creases, folds and dead ends.",
        reproduced: !rest.is_empty() && rest.iter().all(|r| steady(r)),
        evidence: format!(
            "{}; {}",
            worst(rest.iter().copied(), |r| r.jitter, " jitter"),
            worst(rest.iter().copied(), |r| r.wobble, " wobble")
        ),
    });
    let rs: Vec<&RunResult> = of("robust").filter(|r| r.snag.is_some()).collect();
    claims.push(Claim {
        source: "sweepslide",
        text: "The robust response does not snag: it slides at least 99.9% of the ideal distance.",
        reproduced: !rs.is_empty() && rs.iter().all(|r| r.snag.is_some_and(|s| s >= SNAG_THRESHOLD)),
        evidence: smallest_snag(rs.iter().copied(), "runs"),
    });
    let measured: Vec<&RunResult> = rs.iter().copied().filter(|r| r.drift.is_some()).collect();
    let unsettled = rs.len() - measured.len();
    claims.push(Claim {
        source: "sweepslide",
        text: "The robust response keeps to the ideal slide's line: once it slides as the ideal does, it drifts off that \
               line by less than its largest padding, a hundredth of a radius.",
        reproduced: !measured.is_empty() && measured.iter().all(|r| r.drift.is_some_and(|d| d < DRIFT_THRESHOLD)),
        evidence: format!(
            "{} over {} runs{}",
            worst(measured.iter().copied(), |r| r.drift.unwrap_or(f64::NAN), " radii"),
            measured.len(),
            if unsettled == 0 {
                String::new()
            } else {
                format!(
                    " (left out: {unsettled} runs with an ideal slide that no frame moved as: still approaching \
                     its surfaces when the run ended, or never steady, which jitter and wobble show)"
                )
            }
        ),
    });
    claims
}
