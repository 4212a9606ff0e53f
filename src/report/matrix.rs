//! The experiment matrix: which runs a report makes, in a fixed order, and
//! how it splits into shards.

use crate::Error;
use crate::lab::scenes::{BUILTIN, build};
use crate::lab::{Precision, RunConfig, Scene};
use crate::respond::Response;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

/// The precisions of the main table: the hardware floats, their MPFR twins,
/// quadruple-like 113 bits and the 256-bit reference.
pub const PRECISIONS: [Precision; 6] = [
    Precision::F32,
    Precision::F64,
    Precision::Mpfr(24),
    Precision::Mpfr(53),
    Precision::Mpfr(113),
    Precision::Mpfr(256),
];

/// Scenes of the precision dial (jitter and penetration against bits).
pub const DIAL_SCENES: [&str; 3] = ["corner", "wedge", "crease"];

/// Scenes added to the built-ins at their defaults: the extreme wedge and
/// slot, a fold as deep as a valley (where both faithful responses freeze
/// in `f32`), and scenes away from the origin (on the tilted floor at
/// `(1e3, 2e3, -1e3)`, in `f32`, Fauerby's response freezes and Linahan's
/// gives NaN).
pub const EXTRA_SCENES: [(&str, [f64; 3]); 6] = [
    ("wedge:1", [0.0; 3]),
    ("slot:0.0001", [0.0; 3]),
    ("fold:5", [0.0; 3]),
    ("tilted-floor", [1e3, 2e3, -1e3]),
    ("corner", [1e4, 0.0, 1e4]),
    ("floor", [1e5, 0.0, 1e5]),
];

/// Which part of the report a run belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// The main matrix: scenes x responses x [`PRECISIONS`] x seeds.
    Main,
    /// The precision dial: [`DIAL_SCENES`] x responses x MPFR bits.
    Dial,
}

/// Where a run's scene comes from.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SceneSource {
    /// A built-in scene (`name` or `name:parameter`), moved by `offset`.
    Builtin {
        /// The scene spec.
        spec: String,
        /// Offset of the whole scene, as `f64` bit patterns (exact and
        /// hashable).
        offset: [u64; 3],
    },
    /// An OBJ file.
    Mesh {
        /// Its path.
        path: PathBuf,
    },
    /// A fuzz case file ([`Scene::from_case_file`]).
    Case {
        /// Its path.
        path: PathBuf,
    },
}

/// One run of the matrix.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Entry {
    /// Position in the whole matrix (shards keep it).
    pub index: usize,
    /// Main table or precision dial.
    pub group: Group,
    /// The scene.
    pub source: SceneSource,
    /// The response.
    pub response: Response,
    /// The precision, as `sweepslide run --precision` spells it.
    pub precision: String,
    /// The seed.
    pub seed: u64,
    /// Frames to run.
    pub frames: usize,
}

/// What identifies a matrix: shards of different matrices must not merge.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct MatrixInfo {
    /// Quick or full.
    pub quick: bool,
    /// The meshes included.
    pub meshes: Vec<PathBuf>,
    /// The fuzz cases included.
    #[serde(default)]
    pub cases: Vec<PathBuf>,
    /// Number of runs in the whole matrix.
    pub runs: usize,
    /// Each mesh's and case's file name and a digest of its contents
    /// (64-bit FNV-1a; 0 for a file that could not be read), in the order
    /// of `meshes` then `cases`: what identifies them wherever they lie,
    /// so shards made where the files sit at other paths merge, and a file
    /// changed under the same path does not. Empty in files written before
    /// the twenty-sixth session (their paths are compared instead).
    #[serde(default)]
    pub inputs: Vec<(String, u64)>,
}

impl MatrixInfo {
    /// How the matrix `other` differs from this one, in words (empty when
    /// it is the same matrix).
    #[must_use]
    pub fn differences(&self, other: &MatrixInfo) -> Vec<String> {
        let kind = |quick: bool| if quick { "quick" } else { "full" };
        let mut out = Vec::new();
        if self.quick != other.quick {
            out.push(format!("a {} matrix and a {} one", kind(self.quick), kind(other.quick)));
        }
        if self.runs != other.runs {
            out.push(format!("{} runs and {}", self.runs, other.runs));
        }
        let names = |i: &MatrixInfo| i.inputs.iter().map(|(n, d)| format!("{n} ({d:016x})")).collect::<Vec<_>>();
        let paths =
            |i: &MatrixInfo| i.meshes.iter().chain(&i.cases).map(|p| p.display().to_string()).collect::<Vec<_>>();
        let (a, b) = if self.inputs.is_empty() || other.inputs.is_empty() {
            (paths(self), paths(other))
        } else {
            (names(self), names(other))
        };
        if a != b {
            out.push(format!("meshes and cases [{}] and [{}]", a.join(", "), b.join(", ")));
        }
        out
    }
}

/// A file's name and the 64-bit FNV-1a digest of its contents (0 when it
/// cannot be read: the run that loads it reports why).
fn identify(path: &std::path::Path) -> (String, u64) {
    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let digest = std::fs::read(path).map_or(0, |bytes| {
        bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
    });
    (name, digest)
}

/// The seeds a scene runs with: several for seeded scenes (their geometry
/// or motion depends on the seed), one for the others.
fn seeds_for(seeded: bool, quick: bool) -> Vec<u64> {
    if seeded && !quick {
        vec![1, 2, 3]
    } else if seeded {
        vec![1, 2]
    } else {
        vec![1]
    }
}

/// Whether a built-in scene depends on its seed.
fn is_seeded(spec: &str) -> bool {
    let name = spec.split(':').next().unwrap_or(spec);
    matches!(name, "tessellated-floor" | "tilted-floor" | "messy-floor" | "terrain" | "soup" | "room")
}

/// The whole matrix, in its fixed order.
#[must_use]
pub fn matrix(quick: bool, meshes: &[PathBuf], cases: &[PathBuf]) -> (MatrixInfo, Vec<Entry>) {
    let frames = |default: usize| if quick { default.min(150) } else { default };
    let mut sources: Vec<(SceneSource, bool, usize)> = BUILTIN
        .iter()
        .map(|b| (SceneSource::Builtin { spec: b.0.to_string(), offset: [0; 3] }, is_seeded(b.0), default_frames(b.0)))
        .collect();
    for (spec, offset) in EXTRA_SCENES {
        sources.push((
            SceneSource::Builtin { spec: spec.to_string(), offset: offset.map(f64::to_bits) },
            false,
            default_frames(spec),
        ));
    }
    for path in meshes {
        sources.push((SceneSource::Mesh { path: path.clone() }, true, 300));
    }
    for path in cases {
        let recorded = Scene::from_case_file(path).map_or(1, |s| s.frames);
        sources.push((SceneSource::Case { path: path.clone() }, false, recorded));
    }
    let mut entries = Vec::new();
    for (source, seeded, default) in &sources {
        for seed in seeds_for(*seeded, quick) {
            for response in Response::ALL {
                for precision in PRECISIONS {
                    entries.push(Entry {
                        index: entries.len(),
                        group: Group::Main,
                        source: source.clone(),
                        response,
                        precision: precision.to_string(),
                        seed,
                        frames: frames(*default),
                    });
                }
            }
        }
    }
    let step = if quick { 8 } else { 2 };
    for spec in DIAL_SCENES {
        for response in Response::ALL {
            for bits in (8..=64).step_by(step) {
                entries.push(Entry {
                    index: entries.len(),
                    group: Group::Dial,
                    source: SceneSource::Builtin { spec: spec.to_string(), offset: [0; 3] },
                    response,
                    precision: Precision::Mpfr(bits).to_string(),
                    seed: 1,
                    frames: frames(default_frames(spec)).min(if quick { 100 } else { 200 }),
                });
            }
        }
    }
    let inputs = meshes.iter().chain(cases).map(|p| identify(p)).collect();
    (MatrixInfo { quick, meshes: meshes.to_vec(), cases: cases.to_vec(), runs: entries.len(), inputs }, entries)
}

fn default_frames(spec: &str) -> usize {
    build(spec, 1).map_or(200, |s| s.frames)
}

/// The `k`-th (1-based) of `n` deterministic slices: every `n`-th entry
/// starting at `k - 1`, so each shard gets a similar mix of cheap and
/// expensive runs.
///
/// # Errors
/// [`Error::InvalidArgument`] unless `1 <= k <= n`.
pub fn shard(entries: Vec<Entry>, k: usize, n: usize) -> Result<Vec<Entry>, Error> {
    if !(1..=n).contains(&k) {
        return Err(Error::InvalidArgument {
            what: format!("shard {k}/{n}"),
            message: "expected K/N with 1 <= K <= N".into(),
        });
    }
    Ok(entries.into_iter().filter(|e| e.index % n == k - 1).collect())
}

/// Parses `K/N`.
///
/// # Errors
/// [`Error::InvalidArgument`] for anything else.
pub fn parse_shard(s: &str) -> Result<(usize, usize), Error> {
    let bad =
        || Error::InvalidArgument { what: format!("shard `{s}`"), message: "expected K/N with 1 <= K <= N".into() };
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
    if (1..=n).contains(&k) { Ok((k, n)) } else { Err(bad()) }
}

/// Builds each distinct scene of `entries` once and pairs every entry with
/// its run configuration; `note` gets each mesh file's load notes
/// ([`crate::world::TriangleMesh::load_notes`]: skipped faces, ignored
/// statements) once, when it is read.
///
/// # Errors
/// Whatever building a scene or loading a mesh reports.
pub fn configs(entries: &[Entry], note: &dyn Fn(&str)) -> Result<Vec<RunConfig>, Error> {
    let mut cache: HashMap<(SceneSource, u64, usize), Arc<Scene>> = HashMap::new();
    let mut meshes: HashMap<PathBuf, Scene> = HashMap::new();
    entries
        .iter()
        .map(|e| {
            let key = (e.source.clone(), e.seed, e.frames);
            let scene = match cache.get(&key) {
                Some(s) => s.clone(),
                None => {
                    let mut scene = match &e.source {
                        SceneSource::Builtin { spec, offset } => {
                            build(spec, e.seed)?.offset(offset.map(f64::from_bits), true)?
                        }
                        SceneSource::Case { path } => Scene::from_case_file(path)?,
                        SceneSource::Mesh { path } => match meshes.get(path) {
                            Some(s) => s.clone(),
                            None => {
                                let s = Scene::from_obj(path)?;
                                s.mesh.load_notes(&path.display().to_string()).iter().for_each(|l| note(l));
                                meshes.insert(path.clone(), s.clone());
                                s
                            }
                        },
                    };
                    scene.frames = e.frames;
                    let scene = Arc::new(scene);
                    cache.insert(key, scene.clone());
                    scene
                }
            };
            Ok(RunConfig {
                scene,
                response: e.response,
                detection: None,
                precision: Precision::parse(&e.precision)?,
                seed: e.seed,
            })
        })
        .collect()
}
