//! Bounded fuzzing of the front end on stable Rust: structured random OBJ files and Lua
//! scenes from a seeded generator (splitmix64), a few thousand cases, fed in-process to
//! the OBJ reader and to the Lua front end (with flattening at each `gr.render`: every
//! `gr` call and method with random arguments, textures among them), and mutated PNG,
//! JPEG and EXR files to the texture loader and `glint diff`. Each case must return,
//! without a panic or an abort, either a result or an error whose message names the
//! file. A failure prints the case's seed and text, so it can be replayed.

use glint::scene::flatten::flatten;
use glint::scene::lua::{run_scene_source, ScriptConfig};
use glint::scene::obj::parse_obj;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::time::Duration;

/// splitmix64: small, seedable, and the same everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len() as u64) as usize]
    }
}

/// A number as OBJ files (and hostile ones) write them.
/// `noise` (0–3) sets how often a token is junk: 0 never, 3 about one in ten.
fn obj_number(r: &mut Rng, noise: u64) -> String {
    match r.below(30) {
        n if n < noise => r
            .pick(&[
                "nan", "inf", "-inf", "1e400", "", "x", "0x10", "--1", "1.2.3",
            ])
            .to_string(),
        1 => format!("{}", r.next() as i64),
        _ => format!("{:.3}", (r.below(2000) as f64 - 1000.0) / 10.0),
    }
}

/// An index as a face corner may hold it: valid (absolute or relative) unless `noise`
/// (0–3) makes it zero, out of range or junk, up to about one in thirteen.
fn obj_index(r: &mut Rng, count: i64, noise: u64) -> String {
    if r.below(40) >= noise {
        return if r.below(4) == 0 && count > 0 {
            format!("-{}", 1 + r.below(count as u64))
        } else {
            format!("{}", 1 + r.below(count.max(1) as u64))
        };
    }
    match r.below(4) {
        0 => "0".into(),
        1 => format!("-{}", count + 1 + r.below(3) as i64),
        2 => format!("{}", count + 10 + r.below(5) as i64),
        _ => r
            .pick(&["", "a", "1.5", "99999999999999999999"])
            .to_string(),
    }
}

fn obj_line(r: &mut Rng, verts: &mut i64, noise: u64) -> String {
    match r.below(12 + noise) {
        0..=4 => {
            *verts += 1;
            let n = if r.below(30) < noise {
                *r.pick(&[2, 4, 6])
            } else {
                3
            };
            let nums: Vec<String> = (0..n).map(|_| obj_number(r, noise)).collect();
            format!("v {}", nums.join(" "))
        }
        5 => format!("vt {} {}", obj_number(r, noise), obj_number(r, noise)),
        6 => format!(
            "vn {} {} {}",
            obj_number(r, noise),
            obj_number(r, noise),
            obj_number(r, noise)
        ),
        7..=10 => {
            let corners = if r.below(30) < noise {
                r.below(3)
            } else {
                3 + r.below(4)
            };
            let c: Vec<String> = (0..corners)
                .map(|_| {
                    let v = obj_index(r, *verts, noise);
                    if r.below(8) < noise {
                        // The file defines no texture coordinates: out of range.
                        format!("{v}/{}", obj_index(r, 3, noise))
                    } else {
                        v
                    }
                })
                .collect();
            format!("f {}", c.join(" "))
        }
        11 => r
            .pick(&[
                "# comment",
                "g group",
                "usemtl m",
                "s off",
                "o x",
                "l 1 2",
                "",
            ])
            .to_string(),
        12 => {
            // Raw bytes: control characters, invalid UTF-8 made lossy, long words.
            let len = r.below(40);
            (0..len)
                .map(|_| char::from((r.below(96) + 32) as u8))
                .collect()
        }
        _ => format!("f {}", "1 ".repeat(r.below(300) as usize)),
    }
}

#[test]
fn obj_reader_never_panics_and_names_the_file() {
    const CASES: u64 = 3000;
    let (mut accepted, mut refused) = (0, 0);
    for seed in 0..CASES {
        let mut r = Rng(seed);
        let mut verts = 0;
        let noise = r.below(4);
        let lines = r.below(30);
        let text: String = (0..lines)
            .map(|_| obj_line(&mut r, &mut verts, noise) + "\n")
            .collect();
        let result = catch_unwind(|| parse_obj(&text, Path::new("fuzz.obj"), "m"));
        let result = result.unwrap_or_else(|_| panic!("seed {seed}: panicked on:\n{text}"));
        match result {
            Ok(mesh) => {
                assert!(
                    !mesh.triangles.is_empty(),
                    "seed {seed}: empty mesh accepted"
                );
                let n = mesh.positions.len() as u32;
                assert!(
                    mesh.triangles.iter().flatten().all(|&i| i < n),
                    "seed {seed}: index out of range in:\n{text}"
                );
                assert!(mesh.positions.iter().all(|p| p.is_finite()), "seed {seed}");
                accepted += 1;
            }
            Err(e) => {
                let m = e.to_string();
                assert!(m.contains("fuzz.obj"), "seed {seed}: {m}");
                assert!(m.len() < 400, "seed {seed}: message too long: {m}");
                refused += 1;
            }
        }
    }
    // The generator reaches both outcomes often (else it tests little).
    assert!(
        accepted > CASES / 20 && refused > CASES / 20,
        "{accepted} accepted, {refused} refused"
    );
}

/// A Lua value of a random kind, as source text.
fn lua_value(r: &mut Rng, depth: u32) -> String {
    match r.below(if depth > 2 { 9 } else { 11 }) {
        0 => "nil".into(),
        1 => r
            .pick(&[
                "0/0",
                "1/0",
                "-1/0",
                "1e308",
                "-1e-320",
                "2^63",
                "math.maxinteger",
            ])
            .to_string(),
        2 => format!("{}", (r.below(2000) as f64 - 1000.0) / 7.0),
        3 => format!("{}", r.below(20)),
        4 => r
            .pick(&[
                "'x'",
                "''",
                "'post'",
                "'u'",
                "'none'",
                "string.rep('n', 300)",
                "'fuzz.png'",
                "'fuzz.jpg'",
                "'fuzz.exr'",
                "'tri.obj'",
                "'../x.png'",
                "'/tmp/x.png'",
                "'o\\255.png'",
            ])
            .to_string(),
        5 => r.pick(&["true", "print", "gr", "{}"]).to_string(),
        6 => r.pick(&["n1", "n2", "m1", "l1", "root"]).to_string(),
        7 | 8 => format!(
            "{{{}, {}, {}}}",
            (r.below(20) as f64 - 10.0) / 3.0,
            (r.below(20) as f64 - 10.0) / 3.0,
            (r.below(20) as f64 - 10.0) / 3.0
        ),
        _ => {
            let n = r.below(4);
            let items: Vec<String> = (0..n).map(|_| lua_value(r, depth + 1)).collect();
            format!("{{{}}}", items.join(", "))
        }
    }
}

fn lua_args(r: &mut Rng, n: u64) -> String {
    (0..r.below(n + 2))
        .map(|_| lua_value(r, 0))
        .collect::<Vec<_>>()
        .join(", ")
}

fn lua_statement(r: &mut Rng) -> String {
    let calls = [
        "gr.node",
        "gr.joint",
        "gr.sphere",
        "gr.cube",
        "gr.cylinder",
        "gr.cone",
        "gr.nh_sphere",
        "gr.nh_box",
        "gr.torus",
        "gr.mesh",
        "gr.csg",
        "gr.material",
        "gr.light",
        "gr.area_light",
        "gr.transform_order",
        "gr.render",
        "readobj",
        "require",
        "unpack",
        "load",
        "pcall",
    ];
    let methods = [
        "add_child",
        "set_material",
        "scale",
        "translate",
        "rotate",
        "set_diffuse",
        "set_specular",
        "set_shininess",
        "set_reflection",
        "set_refraction",
        "set_bump",
    ];
    let targets = ["n1", "n2", "m1", "l1", "root"];
    let stmt = match r.below(10) {
        0..=3 => format!(
            "{} = {}({})",
            r.pick(&targets),
            r.pick(&calls),
            lua_args(r, 5)
        ),
        4..=6 => format!(
            "{}:{}({})",
            r.pick(&targets),
            r.pick(&methods),
            lua_args(r, 4)
        ),
        7 if r.below(2) == 0 => format!(
            "gr.render({}, 'fuzz.png', {}, {}, {{0,0,5}}, {}, {}, {}, {{0.1,0.1,0.1}}, {{}}, {})",
            r.pick(&targets),
            r.below(6),
            r.below(6),
            lua_value(r, 0),
            lua_value(r, 0),
            lua_value(r, 0),
            lua_value(r, 0)
        ),
        7 => format!(
            "gr.render(root, 'fuzz.png', {}, {}, {{0,0,5}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0.1,0.1,0.1}}, {{l1}})",
            1 + r.below(4),
            1 + r.below(4)
        ),
        8 => "root:add_child(n1) n1:add_child(n2)".into(),
        _ => format!(
            "gr.mesh('m', {{{{0,0,0}}, {{1,0,0}}, {{0,1,0}}}}, {})",
            lua_value(r, 0)
        ),
    };
    // Half the statements may fail without ending the script.
    if r.below(2) == 0 {
        format!("pcall(function() {stmt} end)")
    } else {
        stmt
    }
}

#[test]
fn lua_front_end_never_panics_and_names_the_file() {
    const CASES: u64 = 3000;
    let (mut finished, mut failed, mut rendered) = (0, 0, 0);
    let dir = std::env::temp_dir().join(format!("glint-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    for ((ext, bytes), name) in seed_images()
        .into_iter()
        .zip(["fuzz", "fuzz16", "fuzz", "fuzz"])
    {
        std::fs::write(dir.join(format!("{name}.{ext}")), bytes).unwrap();
    }
    let config = ScriptConfig {
        instruction_limit: 1_000_000,
        memory_limit: 64 << 20,
        time_limit: Duration::from_secs(5),
        ..ScriptConfig::default()
    };
    let prelude = "root = gr.node('root') n1 = gr.sphere('s') n2 = gr.mesh('t', 'tri.obj') m1 = gr.material({1,0,0}, {0,0,0}, 10) l1 = gr.light({1,1,1}, {1,1,1}, {1,0,0})\n";
    for seed in 0..CASES {
        let mut r = Rng(seed ^ 0xF022);
        let lines = 1 + r.below(12);
        let body: String = (0..lines).map(|_| lua_statement(&mut r) + "\n").collect();
        let source = format!("{prelude}{body}");
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            run_scene_source("fuzz.lua", &source, &dir, &config, &mut |graph, request| {
                flatten(graph, request)?;
                rendered += 1;
                Ok(())
            })
        }))
        .unwrap_or_else(|_| panic!("seed {seed}: panicked on:\n{source}"));
        match outcome {
            Ok(_) => finished += 1,
            Err(e) => {
                let m = e.to_string();
                assert!(m.contains("fuzz.lua"), "seed {seed}: {m}\n{source}");
                failed += 1;
            }
        }
    }
    assert!(
        finished > CASES / 20 && failed > CASES / 20 && rendered > CASES / 100,
        "{finished} finished, {failed} failed, {rendered} flattened renders"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Small images of each format glint reads, encoded in memory: 8-bit RGB and 16-bit
/// RGBA PNG, JPEG, float EXR.
fn seed_images() -> Vec<(&'static str, Vec<u8>)> {
    let encode = |image: image::DynamicImage, format| {
        let mut bytes = Vec::new();
        image
            .write_to(&mut std::io::Cursor::new(&mut bytes), format)
            .unwrap();
        bytes
    };
    let rgb = image::RgbImage::from_fn(6, 5, |x, y| image::Rgb([x as u8 * 40, y as u8 * 50, 7]));
    let rgba16: image::ImageBuffer<image::Rgba<u16>, Vec<u16>> =
        image::ImageBuffer::from_pixel(5, 4, image::Rgba([9000, 2, 65535, 100]));
    let float = image::Rgb32FImage::from_pixel(4, 3, image::Rgb([0.25, 2.0, -1.0]));
    vec![
        ("png", encode(rgb.clone().into(), image::ImageFormat::Png)),
        ("png", encode(rgba16.into(), image::ImageFormat::Png)),
        ("jpg", encode(rgb.into(), image::ImageFormat::Jpeg)),
        ("exr", encode(float.into(), image::ImageFormat::OpenExr)),
    ]
}

/// `bytes` mutated by the seeded generator: flipped bytes, 32-bit fields overwritten
/// with extreme values (sizes, lengths, windows), truncation, inserted runs.
fn mutate(r: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for _ in 0..1 + r.below(4) {
        let at = r.below(out.len() as u64) as usize;
        match r.below(5) {
            0 => out[at] ^= 1 << r.below(8),
            1 => out[at] = r.next() as u8,
            2 if at + 4 <= out.len() => {
                let random = r.next() as u32;
                let v = *r.pick(&[u32::MAX, 0x7FFF_FFFF, 1 << 30, 0, 65_536, random]);
                let v = if r.below(2) == 0 {
                    v.to_le_bytes()
                } else {
                    v.to_be_bytes()
                };
                out[at..at + 4].copy_from_slice(&v);
            }
            3 => out.truncate(at.max(1)),
            _ => {
                let run = vec![r.next() as u8; 1 + r.below(64) as usize];
                out.splice(at..at, run);
            }
        }
    }
    out
}

/// Mutated PNG, JPEG and EXR files through the texture loader (under a 64 MiB budget,
/// named by every extension: content decides) and through `glint diff`'s reader and
/// comparison (`glint::diff::diff_files`): no panic, no abort (an allocation the header
/// check missed would end this process), and every refusal names the file.
#[test]
fn mutated_images_never_panic_or_abort() {
    use glint::image_io::{read_image_within, MAX_READ_PIXELS};
    use glint::scene::texture::load_texture;
    const CASES: u64 = 600;
    let dir = std::env::temp_dir().join(format!("glint-fuzz-images-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let seeds = seed_images();
    let reference = dir.join("reference.png");
    std::fs::write(&reference, &seeds[0].1).unwrap();
    let (mut decoded, mut refused) = (0, 0);
    for seed in 0..CASES {
        let mut r = Rng(seed ^ 0x1A6E);
        let (ext, base) = r.pick(&seeds);
        let bytes = mutate(&mut r, base);
        // Named by its own extension or another: the content decides.
        let ext = if r.below(3) == 0 {
            *r.pick(&["png", "jpg", "exr"])
        } else {
            ext
        };
        let path = dir.join(format!("m{seed}.{ext}"));
        std::fs::write(&path, &bytes).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let outcome = catch_unwind(|| {
            let texture = load_texture(&path, 64 << 20);
            let film = read_image_within(&path, MAX_READ_PIXELS, |_, _| Ok(()));
            let diff = glint::diff::diff_files(&reference, &path);
            (texture, film.map(|_| ()), diff.map(|_| ()))
        })
        .unwrap_or_else(|_| panic!("seed {seed}: panicked on {name}"));
        match outcome.0 {
            Ok(_) => decoded += 1,
            Err(e) => {
                assert!(e.contains(&name), "seed {seed}: {e}");
                refused += 1;
            }
        }
        if let Err(e) = outcome.1 {
            assert!(e.to_string().contains(&name), "seed {seed}: {e}");
        }
        if let Err(e) = outcome.2 {
            assert!(e.to_string().contains(&name), "seed {seed}: {e}");
        }
        let _ = std::fs::remove_file(&path);
    }
    assert!(
        decoded > CASES / 20 && refused > CASES / 20,
        "{decoded} decoded, {refused} refused"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
