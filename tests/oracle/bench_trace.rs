//! `glint bench --trace`: prints its three result lines in the exact form, and traces
//! real rays: its hit counts and checksum equal those of brute force (every item tested
//! against every ray) over the same camera and shadow rays; `--dump-rays` writes the
//! documented format, and refuses, with a clear error and no file, kinds the Embree
//! harness cannot trace.

use crate::common;

use common::temp_dir;
use glint::bench::trace_rays::{
    camera_rays, count_work, load_first_render, shadow_rays, summarise, trace_primary, trace_shadow,
};
use glint::mailboxes::Mailboxes;
use glint::pack::pack;
use glint::scene::GridMode;
use std::path::Path;
use std::process::{Command, Output};

/// A small scene with triangles (a tilted quad and a stellated dodecahedron), spheres and
/// boxes, two lights: hits, misses, lit and shadowed points.
const SCENE: &str = r#"
local m = gr.material({0.7, 0.7, 0.7}, {0.2, 0.2, 0.2}, 10)
local root = gr.node('root')
local quad = gr.mesh('quad', {{-3, -1, -3}, {3, -1, -3}, {3, -1, 3}, {-3, -1.5, 3}}, {{0, 1, 2, 3}})
quad:set_material(m)
root:add_child(quad)
local dodec = gr.mesh('dodec', 'dodec.obj')
dodec:scale(0.01, 0.01, 0.01)
dodec:translate(1, 0, 0)
dodec:set_material(m)
root:add_child(dodec)
for i = 0, 4 do
  local s = gr.nh_sphere('s' .. i, {-2 + i, -0.5 + 0.1 * i, -1 - 0.3 * i}, 0.3 + 0.05 * i)
  s:set_material(m)
  root:add_child(s)
end
local b = gr.cube('b')
b:scale(0.6, 0.3, 0.5)
b:rotate('y', 30)
b:translate(-1.2, -0.9, 0.8)
b:set_material(m)
root:add_child(b)
gr.render(root, 'out.png', 48, 40, {0, 1, 6}, {0, -0.3, -1}, {0, 1, 0}, 50,
  {0.2, 0.2, 0.2},
  {gr.light({2, 5, 4}, {0.8, 0.8, 0.8}, {1, 0, 0}), gr.light({-4, 2, 1}, {0.3, 0.3, 0.3}, {1, 0, 0})})
"#;

fn scene_dir(tag: &str) -> glint::testing::scratch::TempDir {
    let dir = temp_dir(tag);
    std::fs::write(dir.join("scene.lua"), SCENE).unwrap();
    std::fs::copy(
        common::corpus().join("a4-2021plus/smstdodeca.obj"),
        dir.join("dodec.obj"),
    )
    .unwrap();
    dir
}

fn glint(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("glint runs")
}

fn stdout_of(out: &Output) -> String {
    assert!(
        out.status.success(),
        "glint failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

/// The number in `line` between `prefix` and `suffix`.
fn number_between(line: &str, prefix: &str, suffix: &str) -> f64 {
    let rest = line
        .strip_prefix(prefix)
        .unwrap_or_else(|| panic!("{line:?} does not start with {prefix:?}"));
    let number = rest
        .strip_suffix(suffix)
        .unwrap_or_else(|| panic!("{line:?} does not end with {suffix:?}"));
    assert!(
        !number.is_empty() && number.chars().all(|c| c.is_ascii_digit() || c == '.'),
        "{line:?}: {number:?} is not a plain decimal number"
    );
    number.parse().unwrap()
}

/// The line of `text` starting with `prefix`, without it.
fn line_after<'a>(text: &'a str, prefix: &str) -> &'a str {
    text.lines()
        .find_map(|l| l.strip_prefix(prefix))
        .unwrap_or_else(|| panic!("no line starting {prefix:?} in:\n{text}"))
}

/// (count, sub-count) from "N (K word) in T ms".
fn counts(text: &str, prefix: &str) -> (usize, usize) {
    let rest = line_after(text, prefix);
    let (n, rest) = rest.split_once(" (").unwrap();
    let k = rest.split_once(' ').unwrap().0;
    (n.parse().unwrap(), k.parse().unwrap())
}

#[test]
fn prints_the_three_lines_in_the_exact_form_first() {
    let dir = scene_dir("trace-form");
    let out = glint(
        &[
            "bench",
            "--trace",
            "scene.lua",
            "--threads",
            "2",
            "--repeat",
            "1",
        ],
        &dir,
    );
    let text = stdout_of(&out);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() >= 3, "{text}");
    let primary = number_between(lines[0], "primary: ", " Mrays/s");
    let shadow = number_between(lines[1], "shadow: ", " Mrays/s");
    let memory = number_between(lines[2], "memory: ", " bytes per triangle");
    assert!(primary > 0.0 && shadow > 0.0, "{text}");
    // At least the 48-byte triangle itself.
    assert!(memory >= 48.0, "{text}");
    assert!(line_after(&text, "image: ").contains("2 threads"), "{text}");
}

#[test]
fn hits_equal_brute_force_over_the_same_rays() {
    let dir = scene_dir("trace-brute");
    let out = glint(&["bench", "--trace", "scene.lua", "--repeat", "1"], &dir);
    let text = stdout_of(&out);

    // Brute force: the same scene with the grid off, every item against every ray.
    let mut scene =
        load_first_render(&dir.join("scene.lua"), None, None, &Default::default()).unwrap();
    scene.options.grid = GridMode::Off;
    let brute = pack(&scene).unwrap();
    assert_eq!(brute.globals.grid_enabled, 0);
    let rays = camera_rays(&brute);
    let hits = trace_primary(&brute, &rays);
    let shadow = shadow_rays(&brute, &rays, &hits);
    let occluded = trace_shadow(&brute, &shadow);
    let expected = summarise(&brute, &hits, &occluded);

    // The scene has hits and misses, lit and shadowed points, triangles and spheres hit.
    assert_eq!(expected.primary_rays, 48 * 40);
    assert!(expected.primary_hits > 0 && expected.primary_hits < expected.primary_rays);
    assert!(expected.shadow_occluded > 0 && expected.shadow_occluded < expected.shadow_rays);
    let is_mesh = |h: &&glint::tracer::traversal::traverse::Hit| {
        brute.instances[h.item as usize].kind == glint::constants::KIND_MESH
    };
    assert!(hits.iter().filter(|h| h.is_hit()).any(|h| !is_mesh(&h)));
    assert!(hits.iter().filter(|h| h.is_hit()).any(|h| is_mesh(&h)));

    assert_eq!(
        counts(&text, "primary rays: "),
        (expected.primary_rays, expected.primary_hits),
        "{text}"
    );
    assert_eq!(
        counts(&text, "shadow rays: "),
        (expected.shadow_rays, expected.shadow_occluded),
        "{text}"
    );
    assert_eq!(
        line_after(&text, "hit checksum: "),
        expected.hit_checksum.to_string(),
        "{text}"
    );

    // The work lines are the counts of the same traversal; brute force (the scene grid
    // off) tests more primitives than the grids do.
    let grid =
        pack(&load_first_render(&dir.join("scene.lua"), None, None, &Default::default()).unwrap())
            .unwrap();
    let grid_shadow = shadow_rays(&grid, &rays, &trace_primary(&grid, &rays));
    let [grid_primary_work, grid_shadow_work] = count_work(&grid, &rays, &grid_shadow);
    let [brute_primary_work, brute_shadow_work] = count_work(&brute, &rays, &shadow);
    assert!(brute_primary_work.items_tested > grid_primary_work.items_tested);
    assert!(brute_shadow_work.items_tested > grid_shadow_work.items_tested);
    let per_ray = |n: u64, rays: usize| n as f64 / rays as f64;
    for (name, work, rays) in [
        ("primary", grid_primary_work, rays.len()),
        ("shadow", grid_shadow_work, grid_shadow.len()),
    ] {
        assert_eq!(
            line_after(&text, &format!("{name} work: ")),
            format!(
                "{:.2} cells visited, {:.2} primitives tested per ray (untimed count)",
                per_ray(work.cells_visited, rays),
                per_ray(work.items_tested, rays)
            ),
            "{text}"
        );
    }
}

/// The CPU's switch for the traversal's mailboxes (the twin of the GPU kernel's
/// variants): with one item slot and with none, every answer is the same and more
/// primitives are tested (each mesh triangle, and with none each scene item, in every
/// cell that lists it), the fewer slots the more.
#[test]
fn mailboxes_change_the_work_not_the_answers() {
    let dir = scene_dir("mailboxes");
    let mut scene =
        pack(&load_first_render(&dir.join("scene.lua"), None, None, &Default::default()).unwrap())
            .unwrap();
    let rays = camera_rays(&scene);
    assert_eq!(
        scene.mailboxes,
        Mailboxes::Full,
        "the CPU tracer keeps its mailboxes by default"
    );
    let hits = trace_primary(&scene, &rays);
    let shadow = shadow_rays(&scene, &rays, &hits);
    let occluded = trace_shadow(&scene, &shadow);
    let mut work = vec![count_work(&scene, &rays, &shadow)];
    for fewer in [Mailboxes::LastItem, Mailboxes::Off] {
        scene.mailboxes = fewer;
        assert_eq!(
            format!("{:?}", trace_primary(&scene, &rays)),
            format!("{hits:?}"),
            "{fewer}"
        );
        assert_eq!(trace_shadow(&scene, &shadow), occluded, "{fewer}");
        work.push(count_work(&scene, &rays, &shadow));
    }
    for pair in work.windows(2) {
        let (with, fewer) = (&pair[0], &pair[1]);
        for (kind, (a, b)) in ["primary", "shadow"].iter().zip(with.iter().zip(fewer)) {
            // A mesh instance met again in a later scene cell is walked again, cells and
            // all; without the triangle slots a triangle in several cells is retested.
            assert!(b.cells_visited >= a.cells_visited, "{kind}");
            assert!(
                b.items_tested > a.items_tested,
                "{kind}: {} primitives tested with fewer mailboxes, {} with more",
                b.items_tested,
                a.items_tested
            );
        }
    }
}

#[test]
fn dump_rays_writes_geometry_rays_and_answers() {
    let dir = scene_dir("trace-dump");
    let out = glint(
        &[
            "bench",
            "--trace",
            "scene.lua",
            "--repeat",
            "1",
            "--dump-rays",
            "rays.bin",
        ],
        &dir,
    );
    let text = stdout_of(&out);
    let bytes = std::fs::read(dir.join("rays.bin")).unwrap();
    assert_eq!(&bytes[..8], b"GLINTRAY");
    let word = |i: usize| u32::from_le_bytes(bytes[8 + 4 * i..12 + 4 * i].try_into().unwrap());
    let (version, triangles, instances, primary, shadow) =
        (word(0), word(1), word(2), word(3), word(4));
    assert_eq!(version, 1);
    assert_eq!(instances, 6, "five spheres and a box");
    assert_eq!(
        (primary as usize, shadow as usize),
        (
            counts(&text, "primary rays: ").0,
            counts(&text, "shadow rays: ").0
        )
    );
    let expected_len =
        28 + 36 * triangles as usize + 100 * instances as usize + 32 * (primary + shadow) as usize;
    assert_eq!(bytes.len(), expected_len);
    // glint's answers ride with the rays: the primary hits counted from the dump match.
    let rays_start = 28 + 36 * triangles as usize + 100 * instances as usize;
    let answer = |ray: usize| {
        let at = rays_start + 32 * ray + 28;
        u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
    };
    let hits = (0..primary as usize)
        .filter(|&r| answer(r) != u32::MAX)
        .count();
    assert_eq!(hits, counts(&text, "primary rays: ").1);
    let occluded = (primary as usize..(primary + shadow) as usize)
        .filter(|&r| answer(r) == 1)
        .count();
    assert_eq!(occluded, counts(&text, "shadow rays: ").1);
}

#[test]
fn dump_rays_refuses_kinds_the_harness_cannot_trace() {
    let dir = temp_dir("trace-dump-refuses");
    std::fs::write(
        dir.join("scene.lua"),
        "local root = gr.node('root')\nroot:add_child(gr.torus('t', 1, 0.3))\n\
         gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n",
    )
    .unwrap();
    let out = glint(
        &["bench", "--trace", "scene.lua", "--dump-rays", "rays.bin"],
        &dir,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("spheres, boxes and triangles only"), "{err}");
    assert!(err.contains("torus 4"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!dir.join("rays.bin").exists());
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "only the scene is left");
}
