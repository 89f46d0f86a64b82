//! Golden images: every CS488 sample scene (with its family's transform order) and every
//! scene in `scenes/`, rendered by the CPU tracer with default options, against the PNG
//! reviewed by eye and kept in `tests/golden/`.
//!
//! The comparison is exact: the 8-bit PNG bytes of the render must equal the golden's, byte
//! for byte. The CPU tracer is deterministic (the same image on every run and thread
//! count), so any difference is a change in what it computes, and no platform difference
//! has been shown that would need a tolerance. On a mismatch, actual, expected and a FLIP
//! heat map are written to `target/test-failures/` with the figures below.
//!
//! `GLINT_BLESS=1` (only `1`; any other value is an error) rewrites every golden that
//! differs and prints, per rewritten image, the changed-pixel count, the largest channel
//! difference and the FLIP mean against the old golden; the run then fails, listing them,
//! so a blessing never reports success for an image it changed. Review, commit, and run
//! again without `GLINT_BLESS`.

use crate::common;

use common::{
    bless_requested, corpus_scenes, failure_dir, load_packed, own_scenes, render_cpu, root,
    scene_name,
};
use glint::diff::diff_films;
use glint::film::Film;
use glint::image_io::{read_image, write_image};
use glint::scene::OptionOverrides;
use std::path::Path;

#[test]
fn every_scene_matches_its_golden_image() {
    let bless = bless_requested();
    let golden_dir = root().join("tests/golden");
    let mut differing = Vec::new();
    // scenes/scrabble.lua renders at 1280×720; its golden is a small one, in tests/images/scrabble.rs.
    // scenes/scrabble-orbit.lua is that scene from a moving camera (tests/cli/farm.rs).
    let scenes: Vec<_> = corpus_scenes()
        .into_iter()
        .chain(own_scenes())
        .filter(|p| !p.ends_with("scrabble.lua") && !p.ends_with("scrabble-orbit.lua"))
        .collect();
    for path in &scenes {
        let name = scene_name(path);
        let film = render_cpu(&load_packed(path, &OptionOverrides::default()));
        let golden = golden_dir.join(format!("{name}.png"));
        let expected = match read_image(&golden) {
            Ok(expected) => Some(expected),
            Err(e) if bless => {
                eprintln!("{name}: no golden yet ({e})");
                None
            }
            Err(e) => panic!("{e} (run with GLINT_BLESS=1 to create it)"),
        };
        let change = match &expected {
            Some(expected) => match golden_change(&name, &film, expected) {
                None => continue,
                Some(change) => change,
            },
            None => format!("{name}: new golden"),
        };
        if bless {
            write_image(&film, &golden).unwrap_or_else(|e| panic!("{e}"));
            println!("rewrote {}: {change}", golden.display());
            differing.push(change);
        } else if let Some(expected) = &expected {
            let written = write_failure_images(&name, &film, expected);
            differing.push(format!("{change}\n{written}"));
        }
    }
    println!(
        "{} scenes, {} identical to their golden",
        scenes.len(),
        scenes.len() - differing.len()
    );
    if bless {
        assert!(
            differing.is_empty(),
            "GLINT_BLESS=1 rewrote {} golden images (review them, commit, and run again \
             without GLINT_BLESS):\n{}",
            differing.len(),
            differing.join("\n")
        );
    }
    assert!(
        differing.is_empty(),
        "{} of {} scenes differ from their golden image (GLINT_BLESS=1 rewrites them):\n{}",
        differing.len(),
        scenes.len(),
        differing.join("\n\n")
    );
}

/// None when the 8-bit render equals `expected` byte for byte; otherwise a line saying how
/// it differs: changed pixels, largest channel difference (in 1/255), FLIP mean.
fn golden_change(name: &str, film: &Film, expected: &Film) -> Option<String> {
    if (film.width, film.height) != (expected.width, expected.height) {
        return Some(format!(
            "{name}: size {}x{} against the golden's {}x{}",
            film.width, film.height, expected.width, expected.height
        ));
    }
    let (actual, golden) = (film.to_rgb8(), expected.to_rgb8());
    if actual == golden {
        return None;
    }
    let mut changed_pixels = 0usize;
    let mut largest = 0u8;
    for (a, g) in actual.chunks_exact(3).zip(golden.chunks_exact(3)) {
        let pixel = a.iter().zip(g).map(|(x, y)| x.abs_diff(*y)).max().unwrap();
        changed_pixels += usize::from(pixel > 0);
        largest = largest.max(pixel);
    }
    let flip = diff_films(expected, &quantised(film))
        .map(|(report, _)| format!("{:.6}", report.flip_mean))
        .unwrap_or_else(|e| e.to_string());
    Some(format!(
        "{name}: {changed_pixels} of {} pixels changed, largest channel difference {largest}/255, \
         FLIP mean {flip}",
        actual.len() / 3
    ))
}

/// The film as a PNG holds it (quantised to 8 bits), for a like-for-like FLIP.
fn quantised(film: &Film) -> Film {
    Film {
        width: film.width,
        height: film.height,
        pixels: film
            .to_rgb8()
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]].map(|v| f32::from(v) / 255.0))
            .collect(),
    }
}

/// Writes `<name>-actual.png`, `-expected.png` and (same size) `-heatmap.png` to
/// `target/test-failures/`; returns the lines naming them.
fn write_failure_images(name: &str, film: &Film, expected: &Film) -> String {
    let dir = failure_dir();
    let mut images = vec![("actual", film.clone()), ("expected", expected.clone())];
    if let Ok((_, heat_map)) = diff_films(expected, &quantised(film)) {
        images.push(("heatmap", heat_map));
    }
    let mut lines = Vec::new();
    if let Err(e) = std::fs::create_dir_all(&dir) {
        lines.push(format!("could not create {}: {e}", dir.display()));
    }
    for (kind, image) in &images {
        let path = dir.join(format!("{name}-{kind}.png"));
        lines.push(match write_image(image, Path::new(&path)) {
            Ok(()) => format!("wrote {}", path.display()),
            Err(e) => format!("could not write: {e}"),
        });
    }
    lines.join("\n")
}
