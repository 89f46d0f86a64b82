//! The OBJ statement reader behind `scene::obj`: a stream of lines in, positions, texture
//! coordinates and normals kept, each face handed on as it is read (its corners in a
//! buffer reused from line to line). Index range checks against the whole file's counts
//! come after the last line (forward references are allowed, as in most loaders); when
//! one fails, a second pass with the counts known finds the first corner at fault, so the
//! error names its line without any line numbers being kept.

use super::files::{excerpt, MAX_FILE_BYTES};
use glam::DVec3;
use std::io::BufRead;
use std::path::{Path, PathBuf};

/// Why an OBJ file could not be loaded. `Display` gives the whole message.
#[derive(Debug, thiserror::Error)]
pub enum ObjError {
    /// The file could not be read (missing, not a regular file, too big); the message
    /// names the path.
    #[error("{message}")]
    Read { message: String },
    /// The file is not OBJ text (NUL bytes: a binary file, or UTF-16 text).
    #[error(
        "mesh file '{}' is not an OBJ text file (it holds NUL bytes: a binary or UTF-16 file?)",
        crate::display_path::shown(path)
    )]
    NotText { path: PathBuf },
    /// The file parsed but holds no face: there is nothing to render.
    #[error(
        "mesh file '{}' has no faces ('f' lines): there is nothing to render",
        crate::display_path::shown(path)
    )]
    NoFaces { path: PathBuf },
    #[error("{}:{line}: {message}", crate::display_path::shown(path))]
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
}

/// A face corner: 0-based position, texture and normal indices; [`NONE`] where absent.
pub type Corner = [u32; 3];

/// An absent texture or normal index.
pub const NONE: u32 = u32::MAX;

/// What the statements defined, and the largest index the faces used.
pub struct Parsed {
    pub positions: Vec<DVec3>,
    pub texcoords: Vec<[f64; 2]>,
    pub normals: Vec<[f64; 3]>,
    /// Largest 1-based position, texture and normal index of any corner.
    max_index: [u64; 3],
}

impl Parsed {
    /// Ok when every index is in range, else the file's counts (for the second pass).
    pub fn check(&self) -> Result<(), [usize; 3]> {
        let counts = [
            self.positions.len(),
            self.texcoords.len(),
            self.normals.len(),
        ];
        if (0..3).all(|k| self.max_index[k] <= counts[k] as u64) {
            Ok(())
        } else {
            Err(counts)
        }
    }
}

/// The three kinds of index: (name in messages, what the file has of it).
const KINDS: [(&str, &str); 3] = [
    ("face index", "vertices"),
    ("texture index", "texture coordinates"),
    ("normal index", "normals"),
];

/// Reads OBJ statements from `reader` (`path` for messages), calling `face` with each
/// face's corners. With `final_counts`, the pass that locates an index out of range: the
/// first corner past them is the error.
pub fn parse_stream(
    mut reader: impl BufRead,
    path: &Path,
    final_counts: Option<[usize; 3]>,
    face: &mut dyn FnMut(&[Corner]),
) -> Result<Parsed, ObjError> {
    let err = |line: usize, message: String| ObjError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut out = Parsed {
        positions: Vec::new(),
        texcoords: Vec::new(),
        normals: Vec::new(),
        max_index: [0; 3],
    };
    let mut faces = 0usize;
    let mut bytes_read = 0u64;
    let mut buffer = Vec::new();
    let mut corners: Vec<Corner> = Vec::new();
    let mut lineno = 0;
    loop {
        buffer.clear();
        let n = reader
            .read_until(b'\n', &mut buffer)
            .map_err(|e| read_error(path, &e.to_string()))?;
        if n == 0 {
            break;
        }
        bytes_read += n as u64;
        if bytes_read > MAX_FILE_BYTES {
            let grew = format!("it grew past the limit of {MAX_FILE_BYTES} bytes while being read");
            return Err(read_error(path, &grew));
        }
        lineno += 1;
        if buffer.contains(&0) {
            return Err(ObjError::NotText {
                path: path.to_path_buf(),
            });
        }
        let mut bytes = buffer.strip_suffix(b"\n").unwrap_or(&buffer);
        bytes = bytes.strip_suffix(b"\r").unwrap_or(bytes);
        if lineno == 1 {
            // A UTF-8 byte-order mark is not part of the first statement.
            bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        }
        // OBJ files in the wild are not always valid UTF-8 (comments in Latin-1); the
        // statements we read are ASCII, so a lossy conversion is harmless.
        let text = String::from_utf8_lossy(bytes);
        let line = text.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword {
            "v" | "vn" | "vt" => {
                vertex_statement(keyword, words, &mut out).map_err(|m| err(lineno, m))?
            }
            "f" => {
                face_statement(words, &out, final_counts, &mut corners)
                    .map_err(|m| err(lineno, m))?;
                for c in &corners {
                    for (max, &i) in out.max_index.iter_mut().zip(c) {
                        *max = (*max).max(u64::from(i.wrapping_add(1)));
                    }
                }
                faces += 1;
                face(&corners);
            }
            // Grouping, smoothing, materials, lines, points, free-form geometry: not ours.
            _ => {}
        }
    }
    if faces == 0 {
        return Err(ObjError::NoFaces {
            path: path.to_path_buf(),
        });
    }
    Ok(out)
}

fn read_error(path: &Path, why: &str) -> ObjError {
    ObjError::Read {
        message: format!(
            "cannot read mesh file '{}': {why}",
            crate::display_path::shown(path)
        ),
    }
}

/// An `f` statement's corners into `corners` (0-based, [`NONE`] where absent), resolved
/// against what `out` holds so far; with `final_counts`, an index past them is the error.
fn face_statement<'a>(
    words: impl Iterator<Item = &'a str>,
    out: &Parsed,
    final_counts: Option<[usize; 3]>,
    corners: &mut Vec<Corner>,
) -> Result<(), String> {
    corners.clear();
    let counts = [out.positions.len(), out.texcoords.len(), out.normals.len()];
    for w in words {
        let corner = corner(w, counts)?;
        if let Some(finals) = final_counts {
            in_range(&corner, finals)?;
        }
        // 1-based to 0-based; an index past u32's range is out of range all the same.
        corners.push(corner.map(|i| {
            if i == 0 {
                NONE
            } else {
                (i - 1).min(i64::from(NONE) - 1) as u32
            }
        }));
    }
    if corners.len() < 3 {
        return Err(format!(
            "face has {} corner{}; a face needs at least 3",
            corners.len(),
            if corners.len() == 1 { "" } else { "s" }
        ));
    }
    Ok(())
}

/// A `v`, `vt` or `vn` statement's numbers, kept in `out`.
fn vertex_statement<'a>(
    keyword: &str,
    words: impl Iterator<Item = &'a str>,
    out: &mut Parsed,
) -> Result<(), String> {
    let mut nums = [0.0; 3];
    let mut count = 0;
    for w in words {
        let x = number(w)?;
        if count < 3 {
            nums[count] = x;
        }
        count += 1;
    }
    // `v` may carry w or vertex colours after x y z; `vt` may carry w.
    let needed = if keyword == "vt" { 1 } else { 3 };
    if count < needed {
        return Err(format!(
            "'{keyword}' needs at least {needed} numbers, found {count}"
        ));
    }
    match keyword {
        "v" => out.positions.push(DVec3::from_array(nums)),
        "vt" => out.texcoords.push([nums[0], nums[1]]),
        _ => out.normals.push(nums),
    }
    Ok(())
}

fn number(word: &str) -> Result<f64, String> {
    match word.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("bad number '{}'", excerpt(word))),
    }
}

/// Whether a corner's 1-based indices (0: absent) are within the file's `counts`.
fn in_range(corner: &[i64; 3], counts: [usize; 3]) -> Result<(), String> {
    for k in 0..3 {
        let i = corner[k];
        if i != 0 && i as u64 > counts[k] as u64 {
            let (what, plural) = KINDS[k];
            return Err(format!(
                "{what} {i} out of range (file has {} {plural})",
                counts[k]
            ));
        }
    }
    Ok(())
}

/// Parses one `f` corner (`a`, `a/b`, `a/b/c`, `a//c`): its 1-based position, texture and
/// normal indices (0 where absent). Negative indices count back from the last element
/// defined so far (`counts`) and are resolved here.
fn corner(word: &str, counts: [usize; 3]) -> Result<[i64; 3], String> {
    let mut parts = word.split('/');
    let index = |s: &str, count: usize, what: &str| -> Result<i64, String> {
        let i: i64 = s.parse().map_err(|_| {
            format!(
                "bad {what} index '{}' in face corner '{}'",
                excerpt(s),
                excerpt(word)
            )
        })?;
        match i {
            0 => Err(format!(
                "{what} index 0 in face corner '{}' (OBJ indices start at 1)",
                excerpt(word)
            )),
            i if i < 0 => {
                let resolved = count as i64 + i + 1;
                if resolved < 1 {
                    Err(format!(
                        "relative {what} index {i} reaches before the first one ({count} defined so far)"
                    ))
                } else {
                    Ok(resolved)
                }
            }
            i => Ok(i),
        }
    };
    let v = index(parts.next().unwrap_or(""), counts[0], "vertex")?;
    let t = match parts.next() {
        None | Some("") => 0,
        Some(s) => index(s, counts[1], "texture")?,
    };
    let n = match parts.next() {
        None | Some("") => 0,
        Some(s) => index(s, counts[2], "normal")?,
    };
    if parts.next().is_some() {
        return Err(format!("bad face corner '{}'", excerpt(word)));
    }
    Ok([v, t, n])
}
