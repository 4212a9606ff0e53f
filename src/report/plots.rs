//! The report's figures, drawn as SVG with `plotters` (no fonts or network
//! needed: text is SVG text).

use super::matrix::{DIAL_SCENES, Group, SceneSource};
use super::{Record, Runs};
use crate::lab::{FrameRecord, RunResult};
use plotters::prelude::*;

/// One figure.
#[derive(Clone, Debug)]
pub struct Figure {
    /// File stem (`plots/<name>.svg`).
    pub name: String,
    /// Title shown above it.
    pub title: String,
    /// What it shows, in a sentence.
    pub caption: String,
    /// Scene it belongs to, or `None` for the overview.
    pub scene: Option<String>,
    /// The SVG document.
    pub svg: String,
}

/// Values at or below this are drawn at this height on log axes (zero has
/// no logarithm); captions say so.
pub const LOG_FLOOR: f64 = 1e-18;

const RESPONSES: [&str; 3] = ["fauerby", "linahan", "robust"];

fn colour(response: &str) -> RGBColor {
    match response {
        "fauerby" => RGBColor(214, 39, 40),
        "linahan" => RGBColor(31, 119, 180),
        _ => RGBColor(44, 160, 44),
    }
}

/// A named polyline.
struct Series {
    label: String,
    colour: RGBColor,
    points: Vec<(f64, f64)>,
}

fn bounds(series: &[Series], log_y: bool) -> ((f64, f64), (f64, f64)) {
    let pts = series.iter().flat_map(|s| s.points.iter()).filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, if log_y { LOG_FLOOR } else { 0.0 }, 1.0);
    }
    // A constant coordinate is padded by a twentieth of the other axis's
    // span (else of its own size): padded by its own size, a slide 15
    // units long at `z = 1e4` was drawn in a window 1,000 units wide, a
    // dot (a review, session 39).
    let pad = |a: f64, b: f64, other: f64| {
        let d = if b > a {
            (b - a) * 0.05
        } else if other > 0.0 {
            other * 0.05
        } else {
            a.abs().max(1.0) * 0.05
        };
        (a - d, b + d)
    };
    let (dx, dy) = (x1 - x0, y1 - y0);
    let (x0, x1) = pad(x0, x1, if log_y { 0.0 } else { dy });
    let (y0, y1) = if log_y { (y0.max(LOG_FLOOR) / 3.0, y1.max(LOG_FLOOR * 10.0) * 3.0) } else { pad(y0, y1, dx) };
    ((x0, x1), (y0, y1))
}

/// A tick label: integers without a fraction, other values without
/// trailing zeros, and never `-0`.
fn tick(v: &f64) -> String {
    let v = *v + 0.0;
    if v == v.round() && v.abs() < 1e15 {
        return format!("{v:.0}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// Height of the plot itself, above the key.
const PLOT_HEIGHT: u32 = 420;

/// A line chart; with `equal` the axes share one scale (for trajectories:
/// a circle marks each path's start, a cross its end). The key lies below
/// the plot, where it hides no data.
fn line_chart(title: &str, x_label: &str, y_label: &str, series: &[Series], log_y: bool, equal: bool) -> String {
    let mut svg = String::new();
    let ((mut x0, mut x1), (mut y0, mut y1)) = bounds(series, log_y);
    if equal {
        let (cx, cy, half) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0, ((x1 - x0).max(y1 - y0)) / 2.0);
        (x0, x1, y0, y1) = (cx - half * 1.4, cx + half * 1.4, cy - half, cy + half);
    }
    // Ranges whose ends or widths overflow (positions near `f64::MAX` in a
    // hand-edited `runs.json`) would send the axis's tick search into an
    // endless loop.
    let drawable = [x0, x1, y0, y1, x1 - x0, y1 - y0].iter().all(|v| v.abs() < PLOT_LIMIT) && x1 > x0 && y1 > y0;
    if !drawable {
        return failed_svg(&format!("coordinates beyond {PLOT_LIMIT:e} cannot be plotted"));
    }
    {
        let key_height = if series.is_empty() { 0 } else { 10 + 18 * series.len() as u32 };
        let root = SVGBackend::with_string(&mut svg, (640, PLOT_HEIGHT + key_height)).into_drawing_area();
        let drawn: Result<(), Box<dyn std::error::Error>> = (|| {
            root.fill(&WHITE)?;
            let (plot, key) = root.split_vertically(PLOT_HEIGHT);
            let mut builder = ChartBuilder::on(&plot);
            builder.caption(title, ("sans-serif", 18)).margin(12).x_label_area_size(40).y_label_area_size(70);
            let grey = ("sans-serif", 12).into_font().color(&BLACK.mix(0.6));
            if log_y {
                let mut chart = builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())?;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .x_label_formatter(&tick)
                    .y_label_formatter(&|v| format!("{v:.0e}"))
                    .draw()?;
                draw_series(&mut chart, series, |y| y.max(LOG_FLOOR), equal)?;
                // Zero has no logarithm: say where it is drawn, and say so
                // where every value is zero (the axis then has no ticks).
                let values = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(|y| y.is_finite());
                let all_zero = values.clone().all(|y| y <= LOG_FLOOR) && values.count() > 0;
                let note = if all_zero {
                    format!("every value is 0 (or below {LOG_FLOOR:.0e}), drawn at {LOG_FLOOR:.0e}")
                } else {
                    format!("0 (and below {LOG_FLOOR:.0e}) is drawn at {LOG_FLOOR:.0e}")
                };
                chart.draw_series(std::iter::once(Text::new(note, (x0, LOG_FLOOR * 30.0), grey)))?;
            } else {
                let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1)?;
                chart
                    .configure_mesh()
                    .x_desc(x_label)
                    .y_desc(y_label)
                    .x_label_formatter(&tick)
                    .y_label_formatter(&tick)
                    .draw()?;
                draw_series(&mut chart, series, |y| y, equal)?;
            }
            for (k, s) in series.iter().enumerate() {
                let y = 6 + 18 * k as i32;
                key.draw(&PathElement::new(vec![(80, y + 7), (112, y + 7)], s.colour.stroke_width(3)))?;
                key.draw(&Text::new(s.label.clone(), (120, y), ("sans-serif", 13)))?;
            }
            root.present()?;
            Ok(())
        })();
        if let Err(e) = drawn {
            return failed_svg(&e.to_string());
        }
    }
    svg
}

/// The largest magnitude of an axis's ends and width that a plot accepts.
const PLOT_LIMIT: f64 = 1e300;

/// A one-line SVG saying why a plot could not be drawn.
fn failed_svg(why: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"40\"><text x=\"10\" y=\"25\">plot failed: {}</text></svg>",
        html_escape(why)
    )
}

/// Draws `series`; with `paths` (trajectories), a circle at each start and
/// a cross at each end.
fn draw_series<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, DB, CT>,
    series: &[Series],
    map_y: impl Fn(f64) -> f64,
    paths: bool,
) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    // Earlier series are drawn a little wider and lighter, so a later one
    // lying on top of them (responses that agree) leaves them visible at
    // its sides: 2 px more per later series, at most 6 px in all (a review
    // found lines 17 px wide hiding the detail of unrelated runs).
    let n = series.len();
    for (k, s) in series.iter().enumerate() {
        let pts: Vec<(f64, f64)> =
            s.points.iter().map(|&(x, y)| (x, map_y(y))).filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
        let c = s.colour;
        let width = 2 + 2 * (n - 1 - k).min(2) as u32;
        let style = c.mix(if k + 1 == n { 1.0 } else { 0.6 }).stroke_width(width);
        chart.draw_series(LineSeries::new(pts.clone(), style))?;
        if let (true, Some(&first)) = (paths, pts.first()) {
            chart.draw_series(std::iter::once(Circle::new(first, 6, c.stroke_width(2))))?;
        }
        if let Some(&last) = pts.last() {
            chart.draw_series(std::iter::once(Cross::new(last, 6, c.stroke_width(2))))?;
        }
        if pts.len() <= 40 {
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
        }
    }
    Ok(())
}

/// Escapes text for HTML and SVG.
#[must_use]
pub fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn slug(s: &str) -> String {
    s.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '-' }).collect()
}

fn main_runs<'a>(
    runs: &'a Runs,
    precision: &'a str,
) -> impl Iterator<Item = (&'a Record, &'a RunResult, &'a [FrameRecord])> + 'a {
    runs.records.iter().filter_map(move |r| {
        let o = r.outcome.as_ref().ok()?;
        let frames = r.frames.as_deref()?;
        (r.entry.group == Group::Main && r.entry.precision == precision && r.entry.seed == 1).then_some((r, o, frames))
    })
}

/// The scene names of the main table, in matrix order.
#[must_use]
pub fn scene_names(runs: &Runs) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for r in &runs.records {
        if let (Group::Main, Ok(o)) = (r.entry.group, &r.outcome)
            && !names.contains(&o.scene)
        {
            names.push(o.scene.clone());
        }
    }
    names
}

fn trajectory(scene: &str, runs: &Runs, axes: (usize, usize)) -> Vec<Series> {
    main_runs(runs, "f32")
        .filter(|(_, o, _)| o.scene == scene)
        .map(|(_, o, frames)| Series {
            label: o.response.clone(),
            colour: colour(&o.response),
            points: frames.iter().map(|f| (f.position[axes.0], f.position[axes.1])).collect(),
        })
        .collect()
}

/// Every figure of the report.
#[must_use]
pub fn figures(runs: &Runs) -> Vec<Figure> {
    let mut out = Vec::new();
    let names = scene_names(runs);
    // Trajectories in the paper's scenes, side views (each scene's top view
    // is in its own section).
    for base in DIAL_SCENES {
        let Some(scene) = names.iter().find(|n| n.split(':').next() == Some(base) && !n.contains('@')) else {
            continue;
        };
        out.push(Figure {
            name: format!("trajectory-{}-side", slug(scene)),
            title: format!("{scene}: trajectories, side view (f32)"),
            caption: "Centre of the body every frame, x against y, for each response in f32 (a circle marks the start, a cross the end; the top view is in the scene's section)."
                .into(),
            scene: None,
            svg: line_chart(&format!("{scene}, side view (f32)"), "x", "y", &trajectory(scene, runs, (0, 1)), false, true),
        });
    }
    // Jitter made visible: the corner's x coordinate frame by frame.
    if let Some(scene) = names.iter().find(|n| n.split(':').next() == Some("corner") && !n.contains('@')) {
        let series: Vec<Series> = main_runs(runs, "f32")
            .filter(|(_, o, _)| o.scene == *scene)
            .map(|(_, o, frames)| Series {
                label: o.response.clone(),
                colour: colour(&o.response),
                points: frames.iter().map(|f| (f.frame as f64, f.position[0])).collect(),
            })
            .collect();
        out.push(Figure {
            name: format!("position-{}-x", slug(scene)),
            title: format!("{scene}: x coordinate over frames (f32)"),
            caption: "The body's x every frame while it is pushed into the obtuse corner: a response that comes to rest draws a flat line at the end, a jittering one a saw-tooth.".into(),
            scene: None,
            svg: line_chart(&format!("{scene}: x over frames (f32)"), "frame", "x", &series, false, false),
        });
    }
    // Penetration over frames: the worst runs.
    let mut worst: Vec<(&Record, &RunResult, &[FrameRecord])> = main_runs(runs, "f32")
        .chain(main_runs(runs, "f64"))
        .filter(|(_, o, _)| o.counted_penetration().0 > 0)
        .collect();
    worst.sort_by(|a, b| {
        let depth = |o: &RunResult| o.counted_penetration().1;
        depth(b.1).total_cmp(&depth(a.1)).then(a.0.entry.index.cmp(&b.0.entry.index))
    });
    let palette = [
        RGBColor(214, 39, 40),
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(23, 190, 207),
    ];
    let series: Vec<Series> = worst
        .iter()
        .take(6)
        .zip(palette)
        .map(|((_, o, frames), colour)| Series {
            label: format!("{} {} {}", o.scene, o.response, o.precision),
            colour,
            points: frames
                .iter()
                .map(|f| {
                    let counted = !(f.from_behind && o.one_sided());
                    (f.frame as f64, if counted { f.penetration.unwrap_or(0.0).max(0.0) } else { 0.0 })
                })
                .collect(),
        })
        .collect();
    out.push(Figure {
        name: "penetration-over-frames".into(),
        title: "Penetration depth over frames (worst runs)".into(),
        caption: if series.is_empty() {
            "No run in f32 or f64 penetrated the geometry.".into()
        } else {
            format!("Exact penetration (MPFR, 512 bits) after each frame for the {} most penetrating runs in f32/f64 (world units for a sphere, radii for an ellipsoid); frames that do not penetrate, and for Fauerby's one-sided detection frames that end inside only triangles entered from behind, are drawn at {LOG_FLOOR:.0e}.", series.len())
        },
        scene: None,
        svg: line_chart("Penetration over frames", "frame", "penetration", &series, true, false),
    });
    // The precision dial.
    for base in DIAL_SCENES {
        let frames_in = |group: Group| {
            runs.records
                .iter()
                .find(|r| {
                    r.entry.group == group
                        && matches!(&r.entry.source, SceneSource::Builtin { spec, offset } if spec == base && *offset == [0; 3])
                })
                .map_or(0, |r| r.entry.frames)
        };
        let (frames, main_frames) = (frames_in(Group::Dial), frames_in(Group::Main));
        for (metric, pick) in [("jitter", 0usize), ("penetration", 1usize)] {
            let series: Vec<Series> = RESPONSES
                .iter()
                .map(|resp| {
                    let mut points: Vec<(f64, f64)> = runs
                        .records
                        .iter()
                        .filter(|r| r.entry.group == Group::Dial && r.entry.response.name() == *resp)
                        .filter(|r| matches!(&r.entry.source, SceneSource::Builtin { spec, .. } if spec == base))
                        .filter_map(|r| {
                            // A run that reached NaN has neither metric (its
                            // jitter and penetration stop at the NaN frame).
                            let o = r.outcome.as_ref().ok().filter(|o| o.nan_frames == 0)?;
                            // A run held at its cap most of the time is
                            // stuck: its jitter, zero, would read as the
                            // best (a review, session 39).
                            if pick == 0 && 2 * o.capped_frames > o.frames {
                                return None;
                            }
                            let bits: f64 = o.precision.trim_start_matches("mpfr").parse().ok()?;
                            Some((bits, if pick == 0 { o.jitter } else { o.counted_penetration().1 }))
                        })
                        .collect();
                    points.sort_by(|a, b| a.0.total_cmp(&b.0));
                    Series { label: resp.to_string(), colour: colour(resp), points }
                })
                .collect();
            out.push(Figure {
                name: format!("dial-{base}-{metric}"),
                title: format!("Precision dial: {metric} in {base} against MPFR bits"),
                caption: format!(
                    "{metric} of each response in the {base} scene run in Mpfr<BITS> ({frames} frames; the main table runs {main_frames}, so its jitter, over the last quarter, can differ); values below {LOG_FLOOR:.0e} (zero included) are drawn at it, and a precision whose run reached NaN has no point (the summary table counts its NaN frames){}.",
                    if pick == 0 { ", nor one that spent more than half its frames at its cap (stuck, which jitter does not show)" } else { "" }
                ),
                scene: None,
                svg: line_chart(
                    &format!("{base}: {metric} vs precision"),
                    "significand bits",
                    metric,
                    &series,
                    true,
                    false,
                ),
            });
        }
    }
    // Iterations histogram.
    let series: Vec<Series> = RESPONSES
        .iter()
        .map(|resp| {
            let mut counts = [0usize; 17];
            for (_, o, frames) in main_runs(runs, "f32").filter(|(_, o, _)| o.response == *resp) {
                let _ = o;
                for f in frames {
                    counts[(f.iterations as usize).min(16)] += 1;
                }
            }
            let total = counts.iter().sum::<usize>().max(1) as f64;
            Series {
                label: resp.to_string(),
                colour: colour(resp),
                points: counts.iter().enumerate().map(|(i, &c)| (i as f64, c as f64 / total)).collect(),
            }
        })
        .collect();
    out.push(Figure {
        name: "iterations-histogram".into(),
        title: "Collision checks per frame".into(),
        caption: "Share of frames (all main scenes, f32, seed 1) by the number of collision checks the frame needed; both passes (velocity and gravity) count, and the last point, at 16, counts 16 or more.".into(),
        scene: None,
        svg: line_chart("Collision checks per frame (f32)", "checks per frame", "share of frames", &series, false, false),
    });
    // One top view per scene.
    for scene in &names {
        out.push(Figure {
            name: format!("scene-{}-top", slug(scene)),
            title: format!("{scene}: top view (f32)"),
            caption: "Centre of the body every frame, seen from above (x against z), each response in f32, seed 1 (a circle marks the start, a cross the end)."
                .into(),
            scene: Some(scene.clone()),
            svg: line_chart(
                &format!("{scene}, top view (f32)"),
                "x",
                "z",
                &trajectory(scene, runs, (0, 2)),
                false,
                true,
            ),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{Series, line_chart};
    use plotters::style::RGBColor;

    fn chart(points: Vec<(f64, f64)>, equal: bool) -> String {
        let series = [Series { label: "robust f32".into(), colour: RGBColor(0, 0, 0), points }];
        line_chart("t", "x", "y", &series, false, equal)
    }

    #[test]
    fn coordinates_near_the_largest_float_give_a_message_not_an_endless_loop() {
        // Before the range check, the equal-axes trajectory plot of these
        // points never returned (plotters' tick search on an infinite range).
        for points in [vec![(1e308, 0.0), (1e308, 1e308)], vec![(-1.7e308, 0.0), (1.7e308, 1.0)]] {
            for equal in [true, false] {
                let svg = chart(points.clone(), equal);
                assert!(svg.contains("plot failed: coordinates beyond 1e300"), "{svg}");
            }
        }
        let svg = chart(vec![(0.0, 0.0), (1.0, 2.0), (2.0, 1.0)], true);
        assert!(!svg.contains("plot failed") && svg.contains("<polyline"), "{}", &svg[..svg.len().min(400)]);
    }
}
