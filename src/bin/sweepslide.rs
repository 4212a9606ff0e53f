//! The `sweepslide` command line: run the lab, list scenes, make reports.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use sweepslide::Error;
use sweepslide::detect::Detection;
use sweepslide::lab::scenes::{self, BUILTIN, build};
use sweepslide::lab::{Motion, Precision, RunConfig, RunOutput, Scene, run};
use sweepslide::respond::{FauerbyOptions, Response};

#[derive(Parser)]
#[command(
    name = "sweepslide",
    version,
    about = "Collide-and-slide lab: Fauerby, Linahan and a robust response in any precision"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene with one response in one precision and print its metrics.
    Run(Box<RunArgs>),
    /// List the built-in scenes.
    Scenes,
    /// Run the experiment matrix (or one shard of it) and write the report.
    Report(ReportArgs),
    /// Search random scenes (angles, clearances, speeds, offsets; spheres and
    /// ellipsoids; with --meshes, bodies over real meshes too) for
    /// penetration, NaN, jitter, freezes, drift and wobble, and print how to
    /// reproduce each failure.
    Search {
        /// Seed of the search.
        #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
        seed: u64,
        /// Number of random scenes (at least 1); each runs 3 responses x {f32, f64}.
        #[arg(long, default_value_t = 200, allow_negative_numbers = true)]
        trials: usize,
        /// Worker threads (default: one per core).
        #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
        jobs: usize,
        /// Print the findings as JSON lines.
        #[arg(long)]
        json: bool,
        /// Directory of OBJ meshes: adds a family of trials that move bodies over them.
        #[arg(long)]
        meshes: Option<PathBuf>,
    },
    /// Combine shard directories into one report.
    Merge {
        /// Output directory of the merged report.
        out: PathBuf,
        /// Shard directories (each written by `report --shard K/N`).
        #[arg(required = true)]
        shards: Vec<PathBuf>,
    },
}

#[derive(clap::Args)]
struct ReportArgs {
    /// The quick matrix (fewer frames, seeds and dial steps; under 3 minutes on 2 cores).
    #[arg(long)]
    quick: bool,
    /// Output directory.
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    jobs: usize,
    /// Directory of OBJ meshes to add as scenes (default: ../shared/meshes when it exists).
    #[arg(long)]
    meshes: Option<PathBuf>,
    /// Directory of fuzz cases (.json) to add as scenes (default: scenes/fuzz when it exists).
    #[arg(long)]
    cases: Option<PathBuf>,
    /// Run only the K-th of N slices of the matrix (1-based), e.g. 2/8; merge the shards with `sweepslide merge`.
    #[arg(long, value_parser = parse_shard, allow_hyphen_values = true)]
    shard: Option<(usize, usize)>,
}

fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    sweepslide::report::matrix::parse_shard(s).map_err(|e| e.to_string())
}

#[derive(Clone, Copy, ValueEnum)]
enum ResponseArg {
    Fauerby,
    Linahan,
    Robust,
}

#[derive(Clone, Copy, ValueEnum)]
enum DetectionArg {
    Fauerby,
    Robust,
}

#[derive(clap::Args)]
// Exactly one scene source; a missing one is named with all three.
#[command(group(clap::ArgGroup::new("source").required(true).args(["scene", "mesh", "case"])))]
struct RunArgs {
    /// Built-in scene, `name` or `name:parameter` (see `sweepslide scenes`).
    #[arg(long)]
    scene: Option<String>,
    /// A Wavefront OBJ file to use as the scene.
    #[arg(long)]
    mesh: Option<PathBuf>,
    /// A fuzz case or finding (.json, as the fuzz targets write them) to use as the scene.
    #[arg(long)]
    case: Option<PathBuf>,
    /// Collision response.
    #[arg(long, value_enum, default_value = "robust")]
    response: ResponseArg,
    /// Detection variant (default: the response's own).
    #[arg(long, value_enum)]
    detection: Option<DetectionArg>,
    /// f32, f64 or mpfr<BITS> (for example mpfr53).
    #[arg(long, default_value = "f64", value_parser = parse_precision)]
    precision: Precision,
    /// Number of frames (default: the scene's).
    #[arg(long, allow_negative_numbers = true)]
    frames: Option<usize>,
    /// Start position X,Y,Z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec3)]
    start: Option<[f64; 3]>,
    /// Pushing displacement per frame X,Y,Z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec3)]
    velocity: Option<[f64; 3]>,
    /// Gravity displacement per frame X,Y,Z (a second pass each frame).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec3)]
    gravity: Option<[f64; 3]>,
    /// Sphere radius.
    #[arg(long, conflicts_with = "radii", allow_hyphen_values = true, value_parser = parse_positive)]
    radius: Option<f64>,
    /// Ellipsoid radii X,Y,Z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec3)]
    radii: Option<[f64; 3]>,
    /// Move the whole scene (geometry and start) by X,Y,Z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec3)]
    offset: Option<[f64; 3]>,
    /// World units per metre (Fauerby's unitsPerMeter; default 1): the faithful responses' eps is
    /// 5e-5 times this, in eSpace units
    #[arg(long, allow_hyphen_values = true, value_parser = parse_positive)]
    units_per_meter: Option<f64>,
    /// Seed of seeded scenes and random-walk motion.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    seed: u64,
    /// Print one JSON object instead of a summary.
    #[arg(long)]
    json: bool,
    /// Write per-frame positions and metrics to this CSV file.
    #[arg(long)]
    trace: Option<PathBuf>,
}

fn parse_precision(s: &str) -> Result<Precision, String> {
    Precision::parse(s).map_err(|e| e.to_string())
}

fn parse_number(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| format!("`{s}` is not a number"))?;
    if v.is_finite() { Ok(v) } else { Err(format!("`{s}` is not finite")) }
}

fn parse_positive(s: &str) -> Result<f64, String> {
    let v = parse_number(s)?;
    if v > 0.0 { Ok(v) } else { Err(format!("`{s}` must be positive")) }
}

fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("`{s}` must be three numbers X,Y,Z"));
    }
    Ok([parse_number(parts[0])?, parse_number(parts[1])?, parse_number(parts[2])?])
}

/// Writes a line to standard output; a reader that went away (`| head`)
/// ends the output quietly instead of a panic.
fn emit(line: &str) -> Result<(), Failure> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(line.as_bytes()).and_then(|()| stdout.write_all(b"\n")) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure(Error::Io { path: "standard output".into(), message: e.to_string() }))
        }
        _ => Ok(()),
    }
}

/// `println!` through [`emit`], returning its error.
macro_rules! out {
    ($($arg:tt)*) => {
        emit(&format!($($arg)*))?
    };
}

/// A failure and the exit code it maps to: 2 for bad input, 1 otherwise.
struct Failure(Error);

impl Failure {
    fn code(&self) -> u8 {
        match self.0 {
            Error::Io { .. } => 1,
            _ => 2,
        }
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure(e)
    }
}

fn scene_of(args: &RunArgs) -> Result<Scene, Error> {
    let (mut scene, built_in) = match (&args.scene, &args.mesh, &args.case) {
        (Some(name), _, _) => (build(name, args.seed)?, true),
        (None, Some(path), _) | (None, None, Some(path)) => {
            let s = if args.mesh.is_some() { Scene::from_obj(path)? } else { Scene::from_case_file(path)? };
            warn_skipped(&s, &path.display().to_string());
            if args.case.is_some() {
                note_finding(path, args);
            }
            (s, false)
        }
        (None, None, None) => unreachable!("clap requires --scene, --mesh or --case"),
    };
    if let Some(f) = args.frames {
        scene.frames = f;
    }
    // A built-in scene's inputs are `f32` numbers, so that every precision
    // runs the same ones (`sweepslide::lab::scenes`): values given for it
    // are rounded likewise. (Given as they were, `--start=0,5.1,0` started
    // the `f64` run at 5.1 and the `f32` run at 5.099999904632568.)
    // A steered (random-walk) scene, such as a mesh's, rounds every frame's
    // velocity to `f32` too ([`sweepslide::lab::scenes::Steering`]): a
    // velocity given for one is checked likewise (a review: `1e-50`
    // became a body at rest, `1e39` an "infinite" velocity, silently).
    let why = built_in.then_some("a built-in scene's inputs are rounded (so that every precision runs the same ones)");
    let steered = matches!(scene.motion, Motion::RandomWalk { .. })
        .then_some("a steered scene's velocity is rounded every frame (so that every precision runs the same one)");
    let input = |flag: &str, v: Option<[f64; 3]>, why: Option<&str>| -> Result<Option<[f64; 3]>, Error> {
        let (Some(v), Some(why)) = (v, why) else { return Ok(v) };
        let rounded = v.map(|x| x as f32 as f64);
        match v.iter().zip(&rounded).find(|(x, r)| !r.is_finite() || (**r == 0.0) != (**x == 0.0)) {
            Some((x, r)) => Err(Error::InvalidArgument {
                what: flag.into(),
                message: format!(
                    "{x:e} rounds to {} in f32, to which {why}",
                    if r.is_finite() { "zero" } else { "infinity" }
                ),
            }),
            None => Ok(Some(if built_in { rounded } else { v })),
        }
    };
    let (start, gravity) = (input("--start", args.start, why)?, input("--gravity", args.gravity, why)?);
    let velocity = input("--velocity", args.velocity, why.or(steered))?;
    let radii = input("--radius/--radii", args.radius.map(|r| [r; 3]).or(args.radii), why)?;
    if let Some(v) = start {
        scene.start = v;
    }
    if let Some(v) = gravity {
        scene.gravity = v;
        // The scene's ideal slide is that of its push alone.
        if v != [0.0; 3] {
            scene.ideal = None;
        }
    }
    if let Some(v) = velocity {
        // A case's recorded velocities give way to the one asked for.
        if matches!(scene.motion, Motion::Scripted { .. }) {
            scene.motion = Motion::Constant;
        }
        scene = scene.with_velocity(v);
    }
    if let Some(r) = radii {
        scene = scene.with_radii(r);
    }
    if let Some(u) = args.units_per_meter {
        // Given for the robust response it would change nothing, silently
        // (a review, session 36).
        if matches!(args.response, ResponseArg::Robust) {
            return Err(Error::InvalidArgument {
                what: "--units-per-meter".into(),
                message: "it sets the faithful responses' eps (Fauerby's veryCloseDistance); the robust response has \
                          no such constant: pass --response fauerby or linahan, or leave it out"
                    .into(),
            });
        }
        scene.units_per_meter = u;
    }
    if let Some(o) = args.offset {
        // The offset itself is not rounded (the shifted coordinates are),
        // but one beyond `f32`'s range leaves no finite vertex: refused
        // here, by name, rather than as a mesh without valid triangles.
        if let Some(x) = o.iter().find(|x| built_in && (**x as f32).is_infinite()) {
            return Err(Error::InvalidArgument {
                what: "--offset".into(),
                message: format!(
                    "{x:e} rounds to infinity in f32, to which a built-in scene's coordinates are rounded (so that \
                     every precision runs the same ones)"
                ),
            });
        }
        scene = scene.offset(o, built_in)?;
        warn_skipped(&scene, &format!("the scene at offset {},{},{}", o[0], o[1], o[2]));
    }
    Ok(scene)
}

/// Says on standard error where a finding file (a case under `"case"`, as
/// the `compare_responses` fuzz target writes them) records another
/// response or precision than this run uses: the run does not reproduce
/// the finding unless they are passed with `--response` and
/// `--precision`.
fn note_finding(path: &std::path::Path, args: &RunArgs) {
    let Some(finding) = std::fs::read_to_string(path)
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .filter(|v| v.get("case").is_some())
    else {
        return;
    };
    let response = args.response.to_possible_value().map(|v| v.get_name().to_string()).unwrap_or_default();
    let precision = args.precision.to_string();
    let known = |key: &str, value: &str| match key {
        "response" => ResponseArg::from_str(value, true).is_ok(),
        _ => Precision::parse(value).is_ok(),
    };
    for (key, used) in [("response", response), ("precision", precision)] {
        // A value that is no string (`"response": 5`) is an unknown one,
        // said like any other (a review: it was passed over in silence).
        let recorded = finding.get(key).map(|v| v.as_str().map_or_else(|| v.to_string(), str::to_string));
        if let Some(recorded) = recorded.as_deref().filter(|r| !r.eq_ignore_ascii_case(&used)) {
            if known(key, recorded) {
                eprintln!(
                    "note: {} records {key} `{recorded}`; this run uses `{used}` (pass --{key} {recorded} to reproduce \
                     it)",
                    path.display()
                );
            } else {
                eprintln!("note: {} records an unknown {key} `{recorded}`; this run uses `{used}`", path.display());
            }
        }
    }
}

/// Says on standard error what loading `scene` left out (a file's invalid
/// faces, those an offset's rounding collapsed, the OBJ statements that
/// carry no collision geometry).
fn warn_skipped(scene: &Scene, what: &str) {
    for line in scene.mesh.load_notes(what) {
        eprintln!("{line}");
    }
}

fn write_trace(path: &std::path::Path, out: &RunOutput) -> Result<(), Error> {
    let mut csv = String::from("frame,x,y,z,penetration,from_behind,iterations,stop,flip,embedded\n");
    for f in &out.frames {
        let pen = f.penetration.map_or(String::new(), |p| format!("{p:e}"));
        let stop = format!("{:?}", f.stop);
        csv += &format!(
            "{},{:e},{:e},{:e},{},{},{},{},{},{}\n",
            f.frame,
            f.position[0],
            f.position[1],
            f.position[2],
            pen,
            f.from_behind,
            f.iterations,
            stop,
            f.flip,
            f.embedded
        );
    }
    std::fs::write(path, csv).map_err(|e| Error::Io { path: path.to_path_buf(), message: e.to_string() })
}

/// Checks, before the run, that the trace file `path` can be written, so
/// that an unwritable one is reported before the run rather than after it,
/// without changing a file that is there (it is opened to append, and
/// written only once the run succeeds); returns whether this created it.
///
/// # Errors
/// [`Error::InvalidArgument`] if `path` is one of the run's `inputs` (the
/// trace would overwrite the mesh or case it was made from), [`Error::Io`]
/// if it cannot be opened for writing.
fn open_trace<'a>(path: &std::path::Path, inputs: impl Iterator<Item = &'a PathBuf>) -> Result<bool, Error> {
    let same = |input: &PathBuf| matches!((path.canonicalize(), input.canonicalize()), (Ok(a), Ok(b)) if a == b);
    if let Some(input) = inputs.into_iter().find(|input| same(input)) {
        return Err(Error::InvalidArgument {
            what: "--trace".into(),
            message: format!("{} is the run's input; the trace would overwrite it", input.display()),
        });
    }
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|e| Error::Io { path: path.to_path_buf(), message: e.to_string() })?;
    Ok(!existed)
}

fn run_command(args: &RunArgs) -> Result<(), Failure> {
    let scene = scene_of(args)?;
    let created_trace = match &args.trace {
        Some(path) => open_trace(path, [&args.mesh, &args.case].into_iter().flatten())?,
        None => false,
    };
    let cfg = RunConfig {
        scene: Arc::new(scene),
        response: match args.response {
            ResponseArg::Fauerby => Response::Fauerby,
            ResponseArg::Linahan => Response::Linahan,
            ResponseArg::Robust => Response::Robust,
        },
        detection: args.detection.map(|d| match d {
            DetectionArg::Fauerby => Detection::Fauerby,
            DetectionArg::Robust => Detection::Robust,
        }),
        precision: args.precision,
        seed: args.seed,
    };
    let out = run(&cfg).inspect_err(|_| {
        // A trace file created above would be left empty; one that was
        // there is left as it was.
        if let Some(path) = args.trace.as_ref().filter(|_| created_trace) {
            let _ = std::fs::remove_file(path);
        }
    })?;
    if let Some(path) = &args.trace {
        write_trace(path, &out)?;
    }
    if !out.degenerate.is_empty() {
        eprintln!(
            "note: {} triangle(s) of the scene are degenerate in {} (zero area once rounded): they collided as the \
             segments or points they became:",
            out.degenerate.len(),
            args.precision
        );
        for &t in out.degenerate.iter().take(5) {
            eprintln!("  {}", cfg.scene.mesh.input_name(t));
        }
        if out.degenerate.len() > 5 {
            eprintln!("  ... and {} more", out.degenerate.len() - 5);
        }
    }
    let r = &out.result;
    if args.json {
        out!("{}", serde_json::to_string(r).expect("metrics serialise"));
    } else {
        out!(
            "scene {} | response {} on {} detection | {} | {} frames (seed {})",
            r.scene,
            r.response,
            r.detection,
            r.precision,
            r.frames,
            r.seed
        );
        if r.response != Response::Robust.name() {
            out!(
                "  eps           {:.3e} eSpace units (--units-per-meter {})",
                FauerbyOptions { units_per_meter: r.units_per_meter, ..FauerbyOptions::default() }
                    .very_close_distance(),
                if (1e-3..1e6).contains(&r.units_per_meter) {
                    r.units_per_meter.to_string()
                } else {
                    format!("{:e}", r.units_per_meter)
                }
            );
        }
        out!(
            "  penetration   max {:.3e}, {} frame(s) inside{}",
            r.max_penetration,
            r.penetrating_frames,
            r.first_penetrating_frame.map_or(String::new(), |f| format!(", first at frame {f}"))
        );
        if r.back_face_frames > 0 {
            out!(
                "                {} of them entered from behind (every triangle it ends inside, from its back{}); max of the others {:.3e}",
                r.back_face_frames,
                if r.one_sided() { ": this one-sided detection passes them by design" } else { "" },
                r.max_front_penetration
            );
        }
        out!("  jitter        {:.3e}", r.jitter);
        out!(
            "  iterations    max {} per frame ({} per pass), mean {:.2}, {} frame(s) at the cap",
            r.max_iterations,
            r.max_pass_iterations,
            r.mean_iterations,
            r.capped_frames
        );
        out!("  NaN frames    {}", r.nan_frames);
        if r.embedded_frames > 0 {
            out!(
                "  embedded      {} frame(s) began inside geometry the body could not be pushed out of (moved on from the best position measured)",
                r.embedded_frames
            );
        }
        out!(
            "  decision flips vs mpfr{}: {}; frames with another sliding plane: {}",
            sweepslide::lab::runner::reference_bits(args.precision),
            r.decision_flips,
            r.plane_flips
        );
        if let Some(s) = r.snag {
            out!("  snag ratio    {s:.6} (1 = ideal slide)");
        }
        if let Some(d) = r.drift {
            out!("  drift         {d:.3e} radii off the ideal slide's line");
        }
        out!("  final position {:?}", r.final_position);
        out!("  time per move  {:.0} ns (the moves again, back to back, after the run)", r.ns_per_move);
    }
    Ok(())
}

fn report_command(args: &ReportArgs) -> Result<(), Failure> {
    use std::io::IsTerminal;
    use sweepslide::report::{Runs, matrix, render, run_entries, write_runs};
    let files_in = |given: &Option<PathBuf>, flag: &str, default: &str, list: fn(&std::path::Path) -> Vec<PathBuf>| {
        match given {
            Some(dir) if !dir.is_dir() => Err(Failure(Error::InvalidArgument {
                what: flag.into(),
                message: format!("{} is not a directory", dir.display()),
            })),
            Some(dir) => {
                // An empty directory is how a report leaves the default's
                // files out; said, not silent (a review: the report ran
                // without, saying only "(0 meshes)").
                let found = list(dir);
                if found.is_empty() {
                    eprintln!("note: nothing in {}: the report runs without {}", dir.display(), &flag[2..]);
                }
                Ok(found)
            }
            None => {
                let found = list(std::path::Path::new(default));
                // The default is relative to the working directory: say when
                // it found nothing, rather than leave the report quietly
                // without.
                if found.is_empty() {
                    eprintln!(
                        "note: nothing in {default} (relative to the working directory); pass {flag} DIR to add some"
                    );
                }
                Ok(found)
            }
        }
    };
    let meshes = files_in(&args.meshes, "--meshes", "../shared/meshes", scenes::meshes_in)?;
    let cases = files_in(&args.cases, "--cases", "scenes/fuzz", scenes::cases_in)?;
    // An unwritable output directory is reported before the runs (and
    // after the arguments, so a bad one leaves no directory behind).
    std::fs::create_dir_all(&args.out)
        .map_err(|e| Failure(Error::Io { path: args.out.clone(), message: e.to_string() }))?;
    let (info, entries) = matrix::matrix(args.quick, &meshes, &cases);
    let entries = match args.shard {
        Some((k, n)) => matrix::shard(entries, k, n)?,
        None => entries,
    };
    let total = entries.len();
    eprintln!(
        "sweepslide report: {} runs{} ({} meshes), output in {}",
        total,
        args.shard.map_or(String::new(), |(k, n)| format!(" of shard {k}/{n}")),
        meshes.len(),
        args.out.display()
    );
    let clock = std::time::Instant::now();
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(total as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs, eta {eta}")
                .expect("static template")
                .progress_chars("=> "),
        );
        bar
    });
    let done = std::sync::atomic::AtomicUsize::new(0);
    let progress = || {
        let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        match &bar {
            Some(b) => b.inc(1),
            None if n.is_multiple_of(50) || n == total => {
                eprintln!("  {n}/{total} runs done ({:.0} s)", clock.elapsed().as_secs_f64())
            }
            None => {}
        }
    };
    let note = |line: &str| match &bar {
        Some(b) => b.println(line),
        None => eprintln!("{line}"),
    };
    let records = run_entries(&entries, args.jobs, &progress, &note)?;
    if let Some(b) = bar {
        b.finish();
    }
    let runs = Runs { info, records };
    write_runs(&args.out, &runs)?;
    if args.shard.is_some() {
        eprintln!(
            "shard written to {}/runs.json; combine the shards with `sweepslide merge OUT DIR...`",
            args.out.display()
        );
        return Ok(());
    }
    let elapsed = clock.elapsed().as_secs_f64();
    render(&args.out, &runs, Some(elapsed))?;
    warn_failed(&runs);
    eprintln!("report written to {}/index.html in {elapsed:.0} s", args.out.display());
    Ok(())
}

/// Says on standard error which scenes met triangles degenerate in a run's
/// precision, and how many runs of a report failed and why (the first
/// five, with their scene, response and precision); the report lists them
/// too.
fn warn_failed(runs: &sweepslide::report::Runs) {
    use sweepslide::report::matrix::SceneSource;
    let failed: Vec<_> = runs.records.iter().filter_map(|r| r.outcome.as_ref().err().map(|e| (&r.entry, e))).collect();
    for note in sweepslide::report::degenerate_notes(runs) {
        eprintln!("note: {note}");
    }
    if failed.is_empty() {
        return;
    }
    eprintln!("warning: {} of {} runs failed (listed in the report):", failed.len(), runs.records.len());
    for (entry, error) in failed.iter().take(5) {
        let scene = match &entry.source {
            SceneSource::Builtin { spec, .. } => spec.clone(),
            SceneSource::Mesh { path } | SceneSource::Case { path } => path.display().to_string(),
        };
        eprintln!("  run {} ({scene}, {}, {}): {error}", entry.index, entry.response.name(), entry.precision);
    }
    if failed.len() > 5 {
        eprintln!("  ... and {} more", failed.len() - 5);
    }
}

fn merge_command(out: &std::path::Path, shards: &[PathBuf]) -> Result<(), Failure> {
    use sweepslide::report::{merge, read_runs, render, write_runs};
    // Writing into a shard's own directory would overwrite it (a review:
    // `merge x1 x1 x2` replaced shard 1's runs with the merged ones).
    let same = |a: &std::path::Path, b: &std::path::Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if let Some(shard) = shards.iter().find(|d| same(out, d)) {
        return Err(Failure(Error::InvalidArgument {
            what: "merge OUT".into(),
            message: format!("{} is one of the shards: write the merged report elsewhere", shard.display()),
        }));
    }
    let parts = shards.iter().map(|d| read_runs(d)).collect::<Result<Vec<_>, _>>()?;
    let runs = merge(parts)?;
    write_runs(out, &runs)?;
    render(out, &runs, None)?;
    warn_failed(&runs);
    eprintln!("merged {} shards ({} runs) into {}/index.html", shards.len(), runs.records.len(), out.display());
    Ok(())
}

fn search_command(
    seed: u64,
    trials: usize,
    jobs: usize,
    json: bool,
    meshes: Option<&std::path::Path>,
) -> Result<(), Failure> {
    if !(1..=sweepslide::lab::search::MAX_TRIALS).contains(&trials) {
        return Err(Failure(Error::InvalidArgument {
            what: "--trials".into(),
            message: format!("a search runs 1 to {} trials, got {trials}", sweepslide::lab::search::MAX_TRIALS),
        }));
    }
    let meshes = match meshes {
        None => Vec::new(),
        Some(dir) => {
            let found = scenes::meshes_in(dir);
            if found.is_empty() {
                return Err(Failure(Error::InvalidArgument {
                    what: "--meshes".into(),
                    message: format!("{} is not a directory with .obj files", dir.display()),
                }));
            }
            found
        }
    };
    let outcome = sweepslide::lab::search::search(seed, trials, jobs, &meshes, &|line| eprintln!("{line}"))?;
    for f in &outcome.findings {
        if json {
            out!("{}", serde_json::to_string(f).expect("findings serialise"));
        } else {
            out!("{:?} {:.3e}  {}", f.kind, f.value, f.command);
        }
    }
    let families: Vec<String> = outcome.trials.iter().map(|(family, n)| format!("{family} {n}")).collect();
    eprintln!(
        "{} finding(s) in {trials} trials (seed {seed}); trials per family: {}; {} of the trials with ellipsoids",
        outcome.findings.len(),
        families.join(", "),
        outcome.ellipsoids
    );
    Ok(())
}

fn scenes_command() -> Result<(), Failure> {
    for (name, param, description) in BUILTIN {
        let param = if param.is_empty() { String::new() } else { format!(" [:{param}]") };
        out!("{name}{param}\n    {description}");
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Run(args) => run_command(args),
        Command::Scenes => scenes_command(),
        Command::Report(args) => report_command(args),
        Command::Merge { out, shards } => merge_command(out, shards),
        Command::Search { seed, trials, jobs, json, meshes } => {
            search_command(*seed, *trials, *jobs, *json, meshes.as_deref())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("error: {}", f.0);
            ExitCode::from(f.code())
        }
    }
}
