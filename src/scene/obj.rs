//! Wavefront OBJ loading for `gr.mesh(name, file)` and the `readobj` built-in.
//!
//! Our own small parser rather than a crate, so that every error can name the file and
//! line (`cow.obj:17: face index 912 out of range (file has 300 vertices)`), which is
//! what a student fixing a scene needs. Supported: `v`, `vt`, `vn` (vertex normals, for
//! smooth shading; normalised here, a zero `vn` leaves its corners without a normal),
//! `f` with `a`, `a/b`, `a/b/c`, `a//c` and negative (relative) indices, polygons of 3+
//! corners (fan-triangulated). Grouping, smoothing groups (`s`), material and line
//! statements are ignored, as are statements this renderer has no use for.

use super::files::{excerpt, read_regular, Opened, MAX_FILE_BYTES};
use super::Mesh;
use glam::DVec3;
use std::collections::HashMap;
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

/// One face corner: 0-based position index and optional 0-based texture and normal
/// indices.
type Corner = (u32, Option<u32>, Option<u32>);

/// A parsed, validated OBJ file: every index is checked and 0-based.
#[derive(Debug, Default)]
struct ParsedObj {
    positions: Vec<[f64; 3]>,
    texcoords: Vec<[f64; 2]>,
    normals: Vec<[f64; 3]>,
    faces: Vec<Vec<Corner>>,
}

/// Most bytes parsing takes per byte of OBJ text: the text and its copy (2), a corner
/// (`1 `, 2 bytes) as written (24 bytes) and checked (12) at once, 20 in all, and the
/// allocator's blocks; a vertex line (`v 1 1 1`, 8 bytes) is 24 bytes, doubled while its
/// vector grows.
pub const PARSE_BYTES_PER_BYTE: u64 = 24;

/// Reads and parses an OBJ file into a triangle mesh named `name`.
pub fn load_obj(path: &Path, name: &str) -> Result<Mesh, ObjError> {
    let bytes = read_regular(path, "mesh file", MAX_FILE_BYTES)
        .map_err(|message| ObjError::Read { message })?;
    parse_obj(&text(bytes, path)?, path, name)
}

/// [`load_obj`] for a file the scene's read rule opened ([`ReadPolicy::open`](super::files::ReadPolicy::open)).
pub fn load_opened_obj(file: Opened, name: &str) -> Result<Mesh, ObjError> {
    let path = file.path.clone();
    parse_obj(&opened_text(file)?, &path, name)
}

/// Parses OBJ text; `path` is only used in error messages.
pub fn parse_obj(text: &str, path: &Path, name: &str) -> Result<Mesh, ObjError> {
    let parsed = parse(text, path)?;
    Ok(to_mesh(parsed, name))
}

/// An OBJ file as plain tables: vertex positions and 0-based polygons.
pub type RawObj = (Vec<[f64; 3]>, Vec<Vec<u32>>);

/// Reads an OBJ file as plain tables, for the Lua `readobj` built-in: vertex positions and
/// polygons with 0-based position indices (texture and normal indices dropped), exactly
/// the shape of the inline `gr.mesh(name, verts, faces)` form.
pub fn read_obj_raw(file: Opened) -> Result<RawObj, ObjError> {
    let path = file.path.clone();
    let text = opened_text(file)?;
    let parsed = parse(&text, &path)?;
    let faces = parsed
        .faces
        .into_iter()
        .map(|f| f.into_iter().map(|(v, _, _)| v).collect())
        .collect();
    Ok((parsed.positions, faces))
}

/// Reads an opened mesh file: at most [`MAX_FILE_BYTES`], OBJ text.
fn opened_text(file: Opened) -> Result<String, ObjError> {
    let path = file.path.clone();
    let bytes = file
        .read("mesh file", MAX_FILE_BYTES)
        .map_err(|message| ObjError::Read { message })?;
    text(bytes, &path)
}

/// A mesh file's bytes as OBJ text (`path` for messages).
fn text(bytes: Vec<u8>, path: &Path) -> Result<String, ObjError> {
    if bytes.contains(&0) {
        return Err(ObjError::NotText {
            path: path.to_path_buf(),
        });
    }
    // OBJ files in the wild are not always valid UTF-8 (comments in Latin-1); the
    // statements we read are ASCII, so a lossy conversion is harmless.
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// A face corner as written, before the end-of-file range check: positive indices are
/// kept 1-based (checked against the final counts, so forward references work, as in
/// most loaders); negative ones are resolved against the counts at that line.
struct RawFace {
    line: usize,
    corners: Vec<RawCorner>,
}

/// One face corner's position, texture and normal indices, 1-based, not yet range-checked.
type RawCorner = (i64, Option<i64>, Option<i64>);

fn parse(text: &str, path: &Path) -> Result<ParsedObj, ObjError> {
    let err = |line: usize, message: String| ObjError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut out = ParsedObj::default();
    let mut raw_faces = Vec::new();
    // A UTF-8 byte-order mark is not part of the first statement.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);

    for (i, line) in text.lines().enumerate() {
        let lineno = i + 1;
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword {
            "v" | "vn" | "vt" => {
                let mut nums = Vec::with_capacity(4);
                for w in words {
                    nums.push(number(w).map_err(|m| err(lineno, m))?);
                }
                // `v` may carry w or vertex colours after x y z; `vt` may carry w.
                let needed = if keyword == "vt" { 1 } else { 3 };
                if nums.len() < needed {
                    return Err(err(
                        lineno,
                        format!(
                            "'{keyword}' needs at least {needed} numbers, found {}",
                            nums.len()
                        ),
                    ));
                }
                match keyword {
                    "v" => out.positions.push([nums[0], nums[1], nums[2]]),
                    "vt" => out
                        .texcoords
                        .push([nums[0], nums.get(1).copied().unwrap_or(0.0)]),
                    _ => out.normals.push([nums[0], nums[1], nums[2]]),
                }
            }
            "f" => {
                let counts = (out.positions.len(), out.texcoords.len(), out.normals.len());
                let corners = face_corners(words, counts).map_err(|m| err(lineno, m))?;
                raw_faces.push(RawFace {
                    line: lineno,
                    corners,
                });
            }
            // Grouping, smoothing, materials, lines, points, free-form geometry: not ours.
            _ => {}
        }
    }

    let nv = out.positions.len();
    let nt = out.texcoords.len();
    let nn = out.normals.len();
    for face in raw_faces {
        let mut corners = Vec::with_capacity(face.corners.len());
        for (v, t, n) in face.corners {
            let v = check_index(v, nv, "face index", "vertices").map_err(|m| err(face.line, m))?;
            let t = t
                .map(|t| check_index(t, nt, "texture index", "texture coordinates"))
                .transpose()
                .map_err(|m| err(face.line, m))?;
            let n = n
                .map(|n| check_index(n, nn, "normal index", "normals"))
                .transpose()
                .map_err(|m| err(face.line, m))?;
            corners.push((v, t, n));
        }
        out.faces.push(corners);
    }
    if out.faces.is_empty() {
        return Err(ObjError::NoFaces {
            path: path.to_path_buf(),
        });
    }
    Ok(out)
}

/// The corners of an `f` line (at least 3), each index resolved against `counts`: the
/// positions, texture coordinates and normals defined so far (for relative indices).
fn face_corners<'a>(
    words: impl Iterator<Item = &'a str>,
    (nv, nt, nn): (usize, usize, usize),
) -> Result<Vec<RawCorner>, String> {
    let mut corners = Vec::new();
    for w in words {
        corners.push(corner(w, nv, nt, nn)?);
    }
    if corners.len() < 3 {
        return Err(format!(
            "face has {} corner{}; a face needs at least 3",
            corners.len(),
            if corners.len() == 1 { "" } else { "s" }
        ));
    }
    // Kept until the end of the file: no growth slack (see PARSE_BYTES_PER_BYTE).
    corners.shrink_to_fit();
    Ok(corners)
}

fn number(word: &str) -> Result<f64, String> {
    match word.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("bad number '{}'", excerpt(word))),
    }
}

/// Parses one `f` corner (`a`, `a/b`, `a/b/c`, `a//c`). Negative indices count back from
/// the last element defined so far and are resolved here (to 1-based).
fn corner(
    word: &str,
    nv: usize,
    nt: usize,
    nn: usize,
) -> Result<(i64, Option<i64>, Option<i64>), String> {
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
    let v = index(parts.next().unwrap_or(""), nv, "vertex")?;
    let t = match parts.next() {
        None | Some("") => None,
        Some(s) => Some(index(s, nt, "texture")?),
    };
    let n = match parts.next() {
        None | Some("") => None,
        Some(s) => Some(index(s, nn, "normal")?),
    };
    if parts.next().is_some() {
        return Err(format!("bad face corner '{}'", excerpt(word)));
    }
    Ok((v, t, n))
}

/// Checks a resolved 1-based index against the file's count, giving a 0-based index.
fn check_index(i: i64, count: usize, what: &str, plural: &str) -> Result<u32, String> {
    if i >= 1 && (i as usize) <= count {
        Ok((i - 1) as u32)
    } else {
        Err(format!(
            "{what} {i} out of range (file has {count} {plural})"
        ))
    }
}

/// Fan-triangulates the polygons. Without texture coordinates or normals the vertices
/// are kept as they are; with either, each distinct (position, texcoord, normal) corner
/// becomes one vertex, since the mesh stores one UV and one normal per vertex.
fn to_mesh(parsed: ParsedObj, name: &str) -> Mesh {
    let has_uv = parsed.faces.iter().flatten().any(|c| c.1.is_some());
    let has_normals = parsed.faces.iter().flatten().any(|c| c.2.is_some());
    let split = has_uv || has_normals;
    let mut positions: Vec<DVec3> = Vec::new();
    let mut uvs: Vec<[f32; 2]> = Vec::new();
    let mut normals: Vec<DVec3> = Vec::new();
    let mut remap: HashMap<Corner, u32> = HashMap::new();
    if !split {
        positions = parsed
            .positions
            .iter()
            .map(|p| DVec3::from_array(*p))
            .collect();
    }
    let mut triangles = Vec::new();
    for face in &parsed.faces {
        let ids: Vec<u32> = face
            .iter()
            .map(|&(v, t, n)| {
                if !split {
                    return v;
                }
                *remap.entry((v, t, n)).or_insert_with(|| {
                    positions.push(DVec3::from_array(parsed.positions[v as usize]));
                    uvs.push(t.map_or([0.0, 0.0], |t| {
                        let [u, v] = parsed.texcoords[t as usize];
                        [u as f32, v as f32]
                    }));
                    normals.push(n.map_or(DVec3::ZERO, |n| {
                        unit_or_zero(DVec3::from_array(parsed.normals[n as usize]))
                    }));
                    (positions.len() - 1) as u32
                })
            })
            .collect();
        for k in 1..ids.len() - 1 {
            triangles.push([ids[0], ids[k], ids[k + 1]]);
        }
    }
    Mesh {
        name: name.to_string(),
        positions,
        triangles,
        uvs: has_uv.then_some(uvs),
        normals: has_normals.then_some(normals),
    }
}

/// `n` normalised, or zero when it has no direction (a zero `vn`, or one whose length
/// overflows): a corner without a normal.
pub(crate) fn unit_or_zero(n: DVec3) -> DVec3 {
    let unit = n.normalize_or_zero();
    if unit.is_finite() {
        unit
    } else {
        DVec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<Mesh, ObjError> {
        parse_obj(text, Path::new("test.obj"), "m")
    }

    #[test]
    fn triangles_and_quads_are_fan_triangulated() {
        let m = parse_str("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n").unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 2]]);
        assert!(m.uvs.is_none());
    }

    #[test]
    fn corner_forms_and_negative_indices() {
        let text = "o x\ng y\ns 1\nusemtl m\nmtllib a.mtl\n# comment\n\
                    v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n\
                    f 1//1 2//1 3//1\nf -3 -2 -1\nl 1 2\n";
        let m = parse_str(text).unwrap();
        // The first face's corners have a normal, the second's not: six vertices.
        assert_eq!(m.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(&m.positions[..3], &m.positions[3..]);
        let normals = m.normals.unwrap();
        assert_eq!(normals[..3], [DVec3::Z; 3]);
        assert_eq!(normals[3..], [DVec3::ZERO; 3]);
    }

    #[test]
    fn texcoords_give_per_vertex_uvs_duplicating_where_needed() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n\
                    f 1/1 2/2 3/3\nf 2/2 4/4 3/4\n";
        let m = parse_str(text).unwrap();
        // (3,3) and (3,4) differ, so vertex 3 is duplicated: 5 vertices.
        assert_eq!(m.positions.len(), 5);
        let uvs = m.uvs.unwrap();
        assert_eq!(uvs.len(), 5);
        assert_eq!(m.triangles[0], [0, 1, 2]);
        assert_eq!(m.triangles[1][0], 1);
        assert_eq!(uvs[m.triangles[1][2] as usize], [0.5, 0.5]);
    }

    #[test]
    fn normals_give_per_vertex_unit_normals_splitting_where_needed() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 2\nvn 0 3 4\nvn 0 0 0\n\
                    f 1//1 2//1 3//2\nf 2//1 4//3 3//1\n";
        let m = parse_str(text).unwrap();
        // Vertex 3 (index 2) has two normals: (3,2) and (3,1) are two vertices.
        assert_eq!(m.positions.len(), 5);
        assert!(m.uvs.is_none());
        let normals = m.normals.unwrap();
        let t = &m.triangles;
        assert_eq!(normals[t[0][0] as usize], DVec3::Z, "normalised");
        assert!((normals[t[0][2] as usize] - DVec3::new(0.0, 0.6, 0.8)).length() < 1e-15);
        // A zero `vn` leaves its corner without a normal.
        assert_eq!(normals[t[1][1] as usize], DVec3::ZERO);
        assert_eq!(normals[t[1][2] as usize], DVec3::Z);
        // Faces without normals in a file that has some: corners without one.
        let m =
            parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\nf 1//1 2//1 3//1\n").unwrap();
        let normals = m.normals.unwrap();
        assert_eq!(normals[m.triangles[0][0] as usize], DVec3::ZERO);
        assert_eq!(normals[m.triangles[1][0] as usize], DVec3::Z);
        assert!(parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
            .unwrap()
            .normals
            .is_none());
    }

    #[test]
    fn normal_index_out_of_range_names_file_line_and_count() {
        let e = parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "test.obj:5: normal index 2 out of range (file has 1 normals)"
        );
    }

    #[test]
    fn out_of_range_index_names_file_line_and_count() {
        let e = parse_str("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 912\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "test.obj:5: face index 912 out of range (file has 3 vertices)"
        );
    }

    #[test]
    fn bad_number_and_short_faces() {
        let e = parse_str("v 0 x1 0\n").unwrap_err();
        assert_eq!(e.to_string(), "test.obj:1: bad number 'x1'");
        let e = parse_str("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
        assert!(
            e.to_string().starts_with("test.obj:3: face has 2 corners"),
            "{e}"
        );
        let e = parse_str("v 0 0 0\nf 0 1 1\n").unwrap_err();
        assert!(e.to_string().contains("index 0"), "{e}");
        let e = parse_str("v 0 0 0\nf -2 1 1\n").unwrap_err();
        assert!(e.to_string().contains("relative vertex index -2"), "{e}");
        let e = parse_str("v 0 0\n").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("test.obj:1: 'v' needs at least 3"),
            "{e}"
        );
    }

    #[test]
    fn missing_file_names_the_path_tried() {
        let e = load_obj(Path::new("no/such/dir/cow.obj"), "cow").unwrap_err();
        let s = e.to_string();
        assert!(
            s.starts_with("cannot read mesh file 'no/such/dir/cow.obj': "),
            "{s}"
        );
    }

    #[test]
    fn raw_form_keeps_polygons() {
        let dir = std::env::temp_dir().join(format!("glint-obj-raw-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("q.obj");
        std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 3/3/3 4/4/4\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n").ok();
        // Forward references (elements defined after the face) are accepted.
        let policy = crate::scene::files::ReadPolicy::new(&dir, &[]);
        let (v, f) = read_obj_raw(policy.open(&p, "mesh file").unwrap()).unwrap();
        assert_eq!((v.len(), f.len()), (4, 1));
        std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        let (v, f) = read_obj_raw(policy.open(&p, "mesh file").unwrap()).unwrap();
        assert_eq!(v.len(), 4);
        assert_eq!(f, vec![vec![0, 1, 2, 3]]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn corpus_meshes_parse() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cs488/a4-2021plus");
        let Ok(entries) = std::fs::read_dir(&dir) else {
            return; // corpus not beside this checkout
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "obj") {
                let m = load_obj(&p, "m").unwrap_or_else(|e| panic!("{e}"));
                assert!(!m.triangles.is_empty(), "{}", p.display());
            }
        }
    }
}
