//! Golden images: every CS488 sample scene (with its family's transform order) and every
//! scene in `scenes/`, rendered by the CPU tracer with default options, against the PNG
//! reviewed by eye and kept in `tests/golden/`. `GLINT_BLESS=1` rewrites the goldens.
//!
//! Thresholds: FLIP mean < 0.005 and ≥ 99.9% of pixels within 2/255. The CPU tracer is
//! deterministic, so on the machine that blessed the goldens the difference is exactly
//! zero; the slack covers a platform libm whose sin/cos/exp2/log2 differ by an ulp and
//! move a few edge pixels. On failure, actual, expected and a FLIP heat map are written
//! to `target/test-failures/`.

mod common;

use common::{corpus_scenes, failure_dir, load_packed, own_scenes, render_cpu, root, scene_name};
use glint::diff::assert_images_match;
use glint::image_io::{read_image, write_image};
use glint::scene::OptionOverrides;

#[test]
fn every_scene_matches_its_golden_image() {
    let bless = std::env::var_os("GLINT_BLESS").is_some();
    let golden_dir = root().join("tests/golden");
    let mut failures = Vec::new();
    let mut worst = (String::new(), 0.0f64);
    // scenes/scrabble.lua renders at 1280×720; its golden is a small one, in tests/scrabble.rs.
    let scenes: Vec<_> = corpus_scenes()
        .into_iter()
        .chain(own_scenes())
        .filter(|p| !p.ends_with("scrabble.lua"))
        .collect();
    for path in &scenes {
        let name = scene_name(path);
        let film = render_cpu(&load_packed(path, &OptionOverrides::default()));
        let golden = golden_dir.join(format!("{name}.png"));
        if bless {
            write_image(&film, &golden).unwrap();
            continue;
        }
        let expected = read_image(&golden)
            .unwrap_or_else(|e| panic!("{e} (run with GLINT_BLESS=1 to create it)"));
        // Compare what a PNG holds: the 8-bit quantised render.
        let actual = read_back_8bit(&film);
        match assert_images_match(&name, &actual, &expected, 0.005, 0.999, &failure_dir()) {
            Ok(report) => {
                if report.flip_mean >= worst.1 {
                    worst = (name, report.flip_mean);
                }
            }
            Err(message) => failures.push(message),
        }
    }
    println!(
        "{} scenes; worst FLIP mean {:.5} ({})",
        scenes.len(),
        worst.1,
        worst.0
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The film as a PNG would store it (quantised to 8 bits), for a like-for-like diff.
fn read_back_8bit(film: &glint::film::Film) -> glint::film::Film {
    let bytes = film.to_rgb8();
    glint::film::Film {
        width: film.width,
        height: film.height,
        pixels: bytes
            .chunks(3)
            .map(|c| [c[0], c[1], c[2]].map(|v| v as f32 / 255.0))
            .collect(),
    }
}
