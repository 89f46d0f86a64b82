//! Wavefront OBJ loading for `gr.mesh(name, file)` and the `readobj` built-in.
//!
//! Our own small parser rather than a crate, so that every error can name the file and
//! line (`cow.obj:17: face index 912 out of range (file has 300 vertices)`), which is
//! what a student fixing a scene needs. Supported: `v`, `vt`, `vn` (vertex normals, for
//! smooth shading; normalised here, a zero `vn` leaves its corners without a normal),
//! `f` with `a`, `a/b`, `a/b/c`, `a//c` and negative (relative) indices, polygons of 3+
//! corners (fan-triangulated). Grouping, smoothing groups (`s`), material and line
//! statements are ignored, as are statements this renderer has no use for.
//!
//! The file is read as a stream (`obj_stream`), a line at a time, straight into the
//! mesh's final arrays: a big file's text is never held whole, and nothing made for a line
//! outlives it. A file whose faces use texture coordinates or normals is resolved to one
//! vertex per distinct corner at the end ([`MeshBuilder::finish`]).

use super::files::{open_regular_within, Opened, MAX_FILE_BYTES};
pub use super::obj_stream::ObjError;
use super::obj_stream::{parse_stream, Corner, Parsed, NONE};
use super::Mesh;
use glam::DVec3;
use std::collections::HashMap;
use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek};
use std::path::Path;

/// Most bytes loading an OBJ file takes per byte of its text, its peak over the file's
/// size: the least text per triangle is an `f` line of single-digit indices (`f 1 2 3`,
/// 8 bytes: 12 bytes of triangle, 12 more while `vt`/`vn` corners are resolved) and per
/// vertex a `v 1 1 1` line (8 bytes: 24 bytes of position, doubled while its vector grows,
/// and its resolved copy). The Lua `readobj` tables are charged by the Lua heap itself.
pub const PARSE_BYTES_PER_BYTE: u64 = 8;

/// Reads and parses an OBJ file into a triangle mesh named `name`.
pub fn load_obj(path: &Path, name: &str) -> Result<Mesh, ObjError> {
    let (file, _) = open_regular_within(path, "mesh file", MAX_FILE_BYTES, &|len| {
        format!("it is {len} bytes, over the limit of {MAX_FILE_BYTES} bytes")
    })
    .map_err(|message| ObjError::Read { message })?;
    mesh_from_file(file, path, name)
}

/// [`load_obj`] for a file the scene's read rule opened ([`ReadPolicy::open`](super::files::ReadPolicy::open)).
pub fn load_opened_obj(file: Opened, name: &str) -> Result<Mesh, ObjError> {
    check_size(&file)?;
    mesh_from_file(file.file, &file.path, name)
}

fn mesh_from_file(file: File, path: &Path, name: &str) -> Result<Mesh, ObjError> {
    let mut builder = MeshBuilder::default();
    let parsed = parse_file(file, path, &mut |corners: &[Corner]| builder.face(corners))?;
    Ok(builder.finish(parsed, name))
}

/// Parses OBJ text; `path` is only used in error messages.
pub fn parse_obj(text: &str, path: &Path, name: &str) -> Result<Mesh, ObjError> {
    let mut builder = MeshBuilder::default();
    let parsed = parse_stream(text.as_bytes(), path, None, &mut |c: &[Corner]| {
        builder.face(c)
    })?;
    if let Err(counts) = parsed.check() {
        return Err(locate_out_of_range(text.as_bytes(), path, counts));
    }
    Ok(builder.finish(parsed, name))
}

/// An OBJ file as plain tables: vertex positions and 0-based polygons.
pub type RawObj = (Vec<[f64; 3]>, Vec<Vec<u32>>);

/// Reads an OBJ file as plain tables, for the Lua `readobj` built-in: vertex positions and
/// polygons with 0-based position indices (texture and normal indices dropped), exactly
/// the shape of the inline `gr.mesh(name, verts, faces)` form.
pub fn read_obj_raw(file: Opened) -> Result<RawObj, ObjError> {
    check_size(&file)?;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let positions = parse_file(file.file, &file.path, &mut |corners: &[Corner]| {
        faces.push(corners.iter().map(|c| c[0]).collect())
    })?
    .positions;
    Ok((positions.iter().map(DVec3::to_array).collect(), faces))
}

/// An opened mesh file is refused over [`MAX_FILE_BYTES`].
fn check_size(file: &Opened) -> Result<(), ObjError> {
    if file.len > MAX_FILE_BYTES {
        return Err(ObjError::Read {
            message: format!(
                "cannot read mesh file '{}': it is {} bytes, over the limit of {MAX_FILE_BYTES} bytes",
                crate::display_path::shown(&file.path),
                file.len
            ),
        });
    }
    Ok(())
}

/// Streams a mesh file through the parser, each face to `face`; an index past the end of
/// the file is located by reading it again.
fn parse_file(
    mut file: File,
    path: &Path,
    face: &mut dyn FnMut(&[Corner]),
) -> Result<Parsed, ObjError> {
    let reader = BufReader::with_capacity(1 << 16, (&mut file).take(MAX_FILE_BYTES + 1));
    let parsed = parse_stream(reader, path, None, face)?;
    if let Err(counts) = parsed.check() {
        file.rewind().map_err(|e| ObjError::Read {
            message: format!(
                "cannot read mesh file '{}': {e}",
                crate::display_path::shown(path)
            ),
        })?;
        let reader = BufReader::with_capacity(1 << 16, file.take(MAX_FILE_BYTES + 1));
        return Err(locate_out_of_range(reader, path, counts));
    }
    Ok(parsed)
}

/// The error of the first face corner whose index is past the file's `counts` (positions,
/// texture coordinates, normals): a second pass over the text, checking every corner.
fn locate_out_of_range(reader: impl BufRead, path: &Path, counts: [usize; 3]) -> ObjError {
    match parse_stream(reader, path, Some(counts), &mut |_: &[Corner]| {}) {
        Err(e) => e,
        // The file changed between the passes: say what the first pass found.
        Ok(_) => ObjError::Parse {
            path: path.to_path_buf(),
            line: 0,
            message: "a face index is out of range (the file changed while being read)".to_string(),
        },
    }
}

/// The triangles of an OBJ file's faces as they are parsed (fan-triangulated), with the
/// texture and normal index of each corner kept only once some corner has one.
#[derive(Default)]
struct MeshBuilder {
    triangles: Vec<[u32; 3]>,
    /// Per triangle corner: the texture index (or [`NONE`]); empty while no corner has one.
    corner_uvs: Vec<u32>,
    /// Per triangle corner: the normal index (or [`NONE`]); empty while no corner has one.
    corner_normals: Vec<u32>,
}

impl MeshBuilder {
    fn face(&mut self, corners: &[Corner]) {
        for k in 1..corners.len() - 1 {
            let triangle = [corners[0], corners[k], corners[k + 1]];
            let before = 3 * self.triangles.len();
            self.triangles.push(triangle.map(|c| c[0]));
            for (attribute, list) in [(1, &mut self.corner_uvs), (2, &mut self.corner_normals)] {
                if list.is_empty() && triangle.iter().all(|c| c[attribute] == NONE) {
                    continue;
                }
                list.resize(before, NONE);
                list.extend(triangle.map(|c| c[attribute]));
            }
        }
    }

    /// The mesh. Without texture coordinates or normals the vertices are kept as they are;
    /// with either, each distinct (position, texcoord, normal) corner becomes one vertex,
    /// in order of first use, since the mesh stores one UV and one normal per vertex.
    fn finish(mut self, parsed: Parsed, name: &str) -> Mesh {
        let has_uv = !self.corner_uvs.is_empty();
        let has_normals = !self.corner_normals.is_empty();
        if !has_uv && !has_normals {
            return Mesh {
                name: name.to_string(),
                positions: parsed.positions,
                triangles: self.triangles,
                uvs: None,
                normals: None,
            };
        }
        let corners = 3 * self.triangles.len();
        self.corner_uvs.resize(corners, NONE);
        self.corner_normals.resize(corners, NONE);
        let mut positions: Vec<DVec3> = Vec::new();
        let mut uvs: Vec<[f32; 2]> = Vec::new();
        let mut normals: Vec<DVec3> = Vec::new();
        let mut remap: HashMap<Corner, u32> = HashMap::new();
        for (i, v) in self.triangles.iter_mut().flatten().enumerate() {
            let (t, n) = (self.corner_uvs[i], self.corner_normals[i]);
            *v = *remap.entry([*v, t, n]).or_insert_with(|| {
                positions.push(parsed.positions[*v as usize]);
                uvs.push(if t == NONE {
                    [0.0, 0.0]
                } else {
                    let [u, v] = parsed.texcoords[t as usize];
                    [u as f32, v as f32]
                });
                normals.push(if n == NONE {
                    DVec3::ZERO
                } else {
                    unit_or_zero(DVec3::from_array(parsed.normals[n as usize]))
                });
                (positions.len() - 1) as u32
            });
        }
        Mesh {
            name: name.to_string(),
            positions,
            triangles: self.triangles,
            uvs: has_uv.then_some(uvs),
            normals: has_normals.then_some(normals),
        }
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
    fn a_file_out_of_range_index_is_located_by_a_second_pass() {
        let dir = std::env::temp_dir().join(format!("glint-obj-pass-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("fwd.obj");
        // Line 1 refers forward to vertex 4 (defined on line 6: fine); line 2 to vertex 9,
        // which never comes; line 3's texture index 2 is also past the end, but later.
        let text = "f 1 2 4\nf 1 2 9\nf 1/2 2/1 3/1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\n";
        std::fs::write(&p, text).unwrap();
        let e = load_obj(&p, "m").unwrap_err().to_string();
        assert!(
            e.ends_with("fwd.obj:2: face index 9 out of range (file has 4 vertices)"),
            "{e}"
        );
        assert_eq!(
            parse_str(text).unwrap_err().to_string(),
            "test.obj:2: face index 9 out of range (file has 4 vertices)"
        );
        // Without line 2, the texture index of line 3.
        let text = text.replace("f 1 2 9\n", "");
        assert_eq!(
            parse_str(&text).unwrap_err().to_string(),
            "test.obj:2: texture index 2 out of range (file has 1 texture coordinates)"
        );
        // A NUL byte anywhere: not an OBJ text file.
        std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\0\n").unwrap();
        assert!(matches!(load_obj(&p, "m"), Err(ObjError::NotText { .. })));
        std::fs::remove_dir_all(&dir).ok();
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
