//! A Wavefront OBJ reader for collision geometry, with line numbers in
//! every error.
//!
//! Reads `v` (positions; an optional fourth coordinate, the weight of
//! rational curves, must be a finite number and is not used: polygons have
//! no use for it) and `f` (faces, any `v`, `v/vt`, `v//vn`, `v/vt/vn`
//! form, negative indices counted from the end; the texture and normal
//! indices are checked like the vertex's, against the `vt` and `vn`
//! statements read so far, and not used). Polygons are
//! triangulated as a fan around their first vertex; a polygon whose fan
//! folds over itself (a concave polygon seen from a vertex that does not
//! see all of it) is rejected with its line number, since the fan would
//! cover area the polygon does not. A non-planar polygon's fan is a valid
//! surface and is kept. Statements that carry no collision geometry
//! (`vt`, `vn`, `o`, `g`, `s`, `usemtl`, `mtllib`, ...) are accepted and
//! counted in [`ObjData::ignored`], which the command line reports; `l`
//! and `p` (lines and points) are geometry a swept body cannot collide
//! with, and `curv`, `curv2` and `surf` free-form geometry this reader
//! does not evaluate: both are rejected with their line number rather
//! than dropped.
//!
//! Lines end with `\n`, `\r\n` or a lone `\r` (as classic Mac OS tools
//! wrote), and a line whose content (before any `#` comment) ends with a
//! backslash continues on the next, as the OBJ specification allows; an
//! error in a continued statement names its first line.

use crate::Error;
use std::borrow::Cow;
use std::path::Path;

/// The positions and triangles of an OBJ text.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjData {
    /// Vertex positions in file order.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles (0-based vertex indices), fans of the file's polygons.
    pub triangles: Vec<[u32; 3]>,
    /// For each triangle, the 1-based line of the face it came from.
    pub lines: Vec<usize>,
    /// The statements read and not used, by keyword, in order of first
    /// appearance.
    pub ignored: Vec<Ignored>,
    /// The 1-based number of the text's last line (1 for an empty text;
    /// a line end at the end of the text starts no new line).
    pub last_line: usize,
}

/// Statements of one keyword that an OBJ file gave and the reader did not
/// use (they carry no collision geometry).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ignored {
    /// The keyword (`vn`, `usemtl`, ...).
    pub keyword: String,
    /// How many statements had it.
    pub count: usize,
    /// The 1-based line of the first.
    pub first_line: usize,
}

/// Longest word an error message quotes whole, in characters: in a file
/// that is not OBJ (one long line of JSON, say) the offending word can be
/// megabytes long.
const QUOTED_CHARS: usize = 60;

/// A word of the file as an error message quotes it: in backticks, cut to
/// [`QUOTED_CHARS`] characters (saying how long it was), so that what is
/// wrong with it still shows, with control characters escaped (`\0`,
/// `\u{1b}`: a review found a NUL byte of an index written raw to the
/// terminal).
struct Quoted<'a>(&'a str);

impl std::fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (shown, cut) = match self.0.char_indices().nth(QUOTED_CHARS) {
            None => (self.0, false),
            Some((end, _)) => (&self.0[..end], true),
        };
        f.write_str("`")?;
        for c in shown.chars() {
            if c.is_control() { write!(f, "{}", c.escape_debug())? } else { write!(f, "{c}")? }
        }
        if cut { write!(f, "...` ({} characters)", self.0.chars().count()) } else { f.write_str("`") }
    }
}

/// Parses OBJ text; `path` only names the source in errors. A leading
/// byte-order mark (as some Windows tools write) is ignored.
///
/// # Errors
/// [`Error::Obj`] with the 1-based line number for a malformed number, a
/// vertex with fewer than three coordinates, a face with fewer than three
/// vertices or whose fan folds over itself, an index of zero or out of
/// range, a line/point element or free-form geometry.
pub fn parse_obj(text: &str, path: &Path) -> Result<ObjData, Error> {
    let mut reader = Reader::default();
    let err = |line: usize, message: String| Error::Obj { path: path.to_path_buf(), line, message };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // A statement continued from earlier lines: its first line and text.
    let mut continued: Option<(usize, String)> = None;
    for (n, raw) in physical_lines(text).enumerate() {
        reader.data.last_line = n + 1;
        let content = raw.split('#').next().unwrap_or("");
        let (content, continues) = match content.trim_end().strip_suffix('\\') {
            Some(head) => (head, true),
            None => (content, false),
        };
        let (line, statement) = match continued.take() {
            Some((first, mut joined)) => {
                joined.push(' ');
                joined.push_str(content);
                (first, Cow::Owned(joined))
            }
            None => (n + 1, Cow::Borrowed(content)),
        };
        if continues {
            continued = Some((line, statement.into_owned()));
        } else {
            reader.statement(line, &statement).map_err(|m| err(line, m))?;
        }
    }
    // A backslash on the last line continues onto nothing.
    if let Some((line, statement)) = continued {
        reader.statement(line, &statement).map_err(|m| err(line, m))?;
    }
    if text.ends_with(['\n', '\r']) {
        reader.data.last_line -= 1;
    }
    reader.data.last_line = reader.data.last_line.max(1);
    Ok(reader.data)
}

/// The lines of `text`, each ended by `\n`, `\r\n` or a lone `\r` (the
/// last one by the end of the text).
fn physical_lines(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let text = rest?;
        let Some(end) = text.find(['\n', '\r']) else {
            rest = None;
            return Some(text);
        };
        let next = if text[end..].starts_with("\r\n") { end + 2 } else { end + 1 };
        rest = Some(&text[next..]);
        Some(&text[..end])
    })
}

/// The 1-based line, as [`parse_obj`] counts them, on which the byte at
/// `bytes.len()` stands, for text that is not UTF-8 from there on.
#[must_use]
pub(crate) fn line_at_end(bytes: &[u8]) -> usize {
    let ends =
        bytes.iter().enumerate().filter(|&(k, &b)| b == b'\n' || (b == b'\r' && bytes.get(k + 1) != Some(&b'\n')));
    1 + ends.count()
}

/// The state of [`parse_obj`]: what was read so far.
#[derive(Default)]
struct Reader {
    data: ObjData,
    /// `vt` statements read so far, for the faces' texture indices.
    textures: usize,
    /// `vn` statements read so far, for the faces' normal indices.
    normals: usize,
}

impl Reader {
    /// Reads one statement (without its comment) that starts on `line`;
    /// the error message if it is malformed.
    fn statement(&mut self, line: usize, content: &str) -> Result<(), String> {
        let data = &mut self.data;
        let mut words = content.split_whitespace();
        let Some(keyword) = words.next() else {
            return Ok(());
        };
        match keyword {
            "v" => {
                let coords: Vec<&str> = words.collect();
                if !(3..=4).contains(&coords.len()) {
                    return Err(format!("vertex needs 3 coordinates (optionally a weight), found {}", coords.len()));
                }
                let mut v = [0.0; 4];
                for (slot, word) in v.iter_mut().zip(&coords) {
                    *slot = word.parse::<f64>().map_err(|_| format!("{} is not a number", Quoted(word)))?;
                    if !slot.is_finite() {
                        return Err(format!("vertex coordinate {} is not finite", Quoted(word)));
                    }
                }
                data.vertices.push([v[0], v[1], v[2]]);
            }
            "f" => {
                let mut corners = Vec::with_capacity(4);
                for word in words {
                    corners.push(resolve_corner(word, [data.vertices.len(), self.textures, self.normals])?);
                }
                if corners.len() < 3 {
                    return Err(format!("face needs at least 3 vertices, found {}", corners.len()));
                }
                if let Some(k) = folded_fan(&data.vertices, &corners) {
                    return Err(format!(
                        "this {}-sided polygon is concave as seen from its first vertex: its fan's triangle {k} \
                         faces against the polygon and would cover area outside it; split the polygon into \
                         triangles or convex polygons",
                        corners.len()
                    ));
                }
                for k in 1..corners.len() - 1 {
                    data.triangles.push([corners[0], corners[k], corners[k + 1]]);
                    data.lines.push(line);
                }
            }
            "l" | "p" => {
                return Err(format!("`{keyword}` elements (lines, points) are not collision geometry"));
            }
            "curv" | "curv2" | "surf" => {
                return Err(format!(
                    "`{keyword}`: free-form curves and surfaces are not supported; export them as polygons"
                ));
            }
            "vt" | "vn" | "vp" | "o" | "g" | "s" | "usemtl" | "mtllib" | "cstype" | "deg" | "parm" | "end" | "lod"
            | "bevel" | "c_interp" | "d_interp" | "shadow_obj" | "trace_obj" | "maplib" | "usemap" | "mg" => {
                self.textures += usize::from(keyword == "vt");
                self.normals += usize::from(keyword == "vn");
                match data.ignored.iter_mut().find(|i| i.keyword == keyword) {
                    Some(i) => i.count += 1,
                    None => data.ignored.push(Ignored { keyword: keyword.to_string(), count: 1, first_line: line }),
                }
            }
            other => return Err(format!("unknown statement {}", Quoted(other))),
        }
        Ok(())
    }
}

/// For a polygon of more than three corners, the first triangle `k`
/// (counted from one) of its fan around corner 0 whose area vector points against the
/// polygon's (the sum of the fan's, Newell's normal; where that sum is
/// rounding noise, the fan's largest triangle's): the fan then covers
/// some area twice and area outside the polygon. `None` for a fan whose
/// triangles all face the same side (a convex polygon, or one star-shaped
/// around its first corner, planar or not).
///
/// A fan triangle whose corners are collinear (a corner on the polygon's
/// side, as T-junction repairs leave) has an area vector of rounding noise
/// only, `16 eps` times its two sides' lengths at most, pointing anywhere:
/// it counts as folded only beyond that (it is skipped as degenerate
/// later).
fn folded_fan(vertices: &[[f64; 3]], corners: &[u32]) -> Option<usize> {
    if corners.len() <= 3 {
        return None;
    }
    let at = |i: u32| nalgebra::Vector3::from(vertices[i as usize]);
    let origin = at(corners[0]);
    // Scaled exactly by a power of two, so that the products (fourth powers
    // of the polygon's size) neither overflow nor underflow: unscaled, a
    // review found the test blind beyond 1e77 and below 1e-81.
    let scale = crate::geom::unit_scale(corners[1..].iter().map(|&i| (at(i) - origin).amax()).fold(0.0, f64::max));
    let fan: Vec<_> = corners[1..]
        .windows(2)
        .map(|w| {
            let (e1, e2) = ((at(w[0]) - origin) * scale, (at(w[1]) - origin) * scale);
            (e1.cross(&e2), 16.0 * f64::EPSILON * e1.norm() * e2.norm())
        })
        .collect();
    let total: nalgebra::Vector3<f64> = fan.iter().map(|(a, _)| a).sum();
    // Triangles that cancel (a bowtie's two halves) leave no polygon
    // normal: the largest triangle's direction judges the others then (a
    // review found an exactly symmetric bowtie accepted).
    let noise: f64 = fan.iter().map(|(_, n)| n).sum();
    let reference = if total.norm() > noise {
        total
    } else {
        fan.iter().map(|(a, _)| *a).max_by(|a, b| a.norm().total_cmp(&b.norm())).unwrap_or(total)
    };
    let length = reference.norm();
    fan.iter().position(|(a, noise)| a.dot(&reference) < -noise * length).map(|k| k + 1)
}

/// Resolves one face corner (`v`, `v/vt`, `v//vn`, `v/vt/vn`) to a 0-based
/// vertex index, given how many vertices, texture coordinates and normals
/// (`counts`) were read so far; the texture and normal indices, where
/// given, must be valid too.
fn resolve_corner(word: &str, counts: [usize; 3]) -> Result<u32, String> {
    let parts: Vec<&str> = word.split('/').collect();
    if parts.len() > 3 {
        return Err(format!("{} is not a face corner (v, v/vt, v//vn or v/vt/vn)", Quoted(word)));
    }
    let vertex = resolve_index(parts[0], counts[0], "vertex", word)?;
    for (k, (part, what)) in parts.iter().zip(["vertex", "texture coordinate", "normal"]).enumerate().skip(1) {
        if !part.is_empty() {
            resolve_index(part, counts[k], what, word)?;
        }
    }
    u32::try_from(vertex).map_err(|_| format!("vertex index of {} is too large", Quoted(word)))
}

/// A 1-based (or, negative, from-the-end) OBJ index as 0-based, among the
/// `count` elements of its kind (`what`) read so far; `word` is the corner
/// it belongs to, for the message.
fn resolve_index(text: &str, count: usize, what: &str, word: &str) -> Result<usize, String> {
    let i: i64 = text.parse().map_err(|_| format!("{}: {} is not a {what} index", Quoted(word), Quoted(text)))?;
    let resolved = match i {
        0 => return Err(format!("{what} index 0 is invalid (OBJ indices start at 1)")),
        i if i > 0 => i - 1,
        i => count as i64 + i,
    };
    if resolved < 0 || resolved >= count as i64 {
        return Err(format!("{what} index {i} is out of range ({count} defined so far)"));
    }
    usize::try_from(resolved).map_err(|_| format!("{what} index {i} is too large"))
}
