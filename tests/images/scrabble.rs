//! The showcase scene `scenes/scrabble.lua` on the CPU tracer: the game on its board is a
//! legal position (every run of two or more letters a word, one connected group over the
//! centre star, no letter more often than the 100-tile set has it), the scene uses every
//! feature it is meant to show, a small render matches its golden exactly, and the scene
//! scaled by 10⁻³ and 10³ renders like scale 1 (FLIP mean ≤ 0.001).

use crate::common;

use common::{bless_requested, failure_dir, load_scenes, render_cpu, root, scaled_scene};
use glint::film::Film;
use glint::image_io::{read_image, write_image};
use glint::pack::{pack, SceneFeatures};
use glint::scene::OptionOverrides;
use std::collections::HashMap;

fn scene_path() -> std::path::PathBuf {
    root().join("scenes/scrabble.lua")
}

/// The 15 rows of the board and the two racks, read from the scene's source.
fn game() -> (Vec<Vec<char>>, Vec<String>) {
    let source = std::fs::read_to_string(scene_path()).unwrap();
    let rows: Vec<Vec<char>> = source
        .lines()
        .map(str::trim)
        .filter(|l| l.len() == 18 && l.starts_with('\'') && l.ends_with("',"))
        .map(|l| l[1..16].chars().collect())
        .collect();
    let racks = ["near_rack", "far_rack"]
        .iter()
        .map(|name| {
            let line = source
                .lines()
                .find(|l| l.starts_with(&format!("local {name} = '")))
                .unwrap_or_else(|| panic!("no {name} in the scene"));
            line.split('\'').nth(1).unwrap().to_string()
        })
        .collect();
    (rows, racks)
}

/// The words the game claims, each checked by hand against the Scrabble dictionaries
/// (TWL and Collins both list them).
const WORDS: &[&str] = &[
    "ANGLE", "FLASH", "GAME", "LENS", "LIGHT", "MIRROR", "PRIZE", "RAY", "SHADOW", "TORUS", "WAVE",
    "WORDS",
];

/// How many tiles of each letter the English 100-tile set has (blanks aside).
fn tile_set() -> HashMap<char, usize> {
    let counts = [
        9, 2, 2, 4, 12, 2, 3, 2, 9, 1, 1, 4, 2, 6, 8, 2, 1, 6, 4, 6, 4, 2, 2, 1, 2, 1,
    ];
    ('A'..='Z').zip(counts).collect()
}

/// Every maximal run of two or more letters along rows and columns.
fn runs(rows: &[Vec<char>]) -> Vec<String> {
    let columns: Vec<Vec<char>> = (0..15)
        .map(|c| rows.iter().map(|r| r[c]).collect())
        .collect();
    rows.iter()
        .chain(&columns)
        .flat_map(|line| {
            line.iter()
                .collect::<String>()
                .split('.')
                .filter(|w| w.len() >= 2)
                .map(str::to_string)
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn the_game_is_a_legal_position() {
    let (rows, racks) = game();
    assert_eq!(rows.len(), 15, "the board has 15 rows");
    assert!(rows.iter().all(|r| r.len() == 15));
    let tiles: Vec<(usize, usize)> = (0..15)
        .flat_map(|r| (0..15).map(move |c| (r, c)))
        .filter(|&(r, c)| rows[r][c] != '.')
        .collect();
    assert!(tiles.len() >= 40, "{} tiles on the board", tiles.len());
    assert_ne!(rows[7][7], '.', "the centre star is covered");
    // Every run is a word, and every claimed word is played.
    let played = runs(&rows);
    for run in &played {
        assert!(
            WORDS.contains(&run.as_str()),
            "'{run}' is not a word of the game"
        );
    }
    for word in WORDS {
        assert!(
            played.iter().any(|p| p == word),
            "{word} is not on the board"
        );
    }
    // One connected group.
    let mut seen = vec![tiles[0]];
    let mut stack = vec![tiles[0]];
    while let Some((r, c)) = stack.pop() {
        for (dr, dc) in [(0i32, 1i32), (0, -1), (1, 0), (-1, 0)] {
            let next = ((r as i32 + dr) as usize, (c as i32 + dc) as usize);
            if tiles.contains(&next) && !seen.contains(&next) {
                seen.push(next);
                stack.push(next);
            }
        }
    }
    assert_eq!(seen.len(), tiles.len(), "the tiles form one group");
    // The board and the racks draw from one set.
    assert!(racks.iter().all(|r| r.len() == 7), "full racks: {racks:?}");
    let mut used: HashMap<char, usize> = HashMap::new();
    for letter in tiles
        .iter()
        .map(|&(r, c)| rows[r][c])
        .chain(racks.concat().chars())
    {
        *used.entry(letter).or_default() += 1;
    }
    let set = tile_set();
    for (letter, n) in &used {
        assert!(
            n <= &set[letter],
            "{n} tiles of {letter}, the set has {}",
            set[letter]
        );
    }
}

#[test]
fn the_scene_uses_every_feature_it_shows() {
    let scene = &load_scenes(&scene_path(), &small(64, 36))[0];
    let features = pack(scene).unwrap().features;
    for (flag, name) in [
        (SceneFeatures::TEXTURE, "texture"),
        (SceneFeatures::BUMP, "bump"),
        (SceneFeatures::REFRACTION, "refraction"),
        (SceneFeatures::REFLECTION, "reflection"),
        (SceneFeatures::CSG, "csg"),
        (SceneFeatures::CYLINDER, "cylinder"),
        (SceneFeatures::TORUS, "torus"),
        (SceneFeatures::AREA_LIGHT, "area-light"),
    ] {
        assert!(features.contains(flag), "no {name} in [{features}]");
        // `--stats` prints this list.
        assert!(features.to_string().split(' ').any(|n| n == name));
    }
}

/// The scene's own render options at another size.
fn small(width: u32, height: u32) -> OptionOverrides {
    OptionOverrides {
        width: Some(width),
        height: Some(height),
        ..OptionOverrides::default()
    }
}

/// 160×90 with the scene's own options, against `tests/golden/scenes-scrabble-160x90.png`
/// pixel for pixel (the CPU tracer is deterministic). `GLINT_BLESS=1` rewrites it when it
/// differs, and the run then fails saying so (a blessing is not a pass).
#[test]
fn small_render_matches_its_golden_exactly() {
    let golden = root().join("tests/golden/scenes-scrabble-160x90.png");
    let scene = &load_scenes(&scene_path(), &small(160, 90))[0];
    let film = render_cpu(&pack(scene).unwrap());
    let bless = bless_requested();
    let expected = match read_image(&golden) {
        Ok(expected) => expected,
        Err(e) if bless => {
            write_image(&film, &golden).unwrap();
            panic!(
                "GLINT_BLESS=1 wrote the missing golden {} ({e}): review it",
                golden.display()
            );
        }
        Err(e) => panic!("{e} (run with GLINT_BLESS=1 to create it)"),
    };
    let (actual_bytes, expected_bytes) = (film.to_rgb8(), expected.to_rgb8());
    let differing = actual_bytes
        .chunks(3)
        .zip(expected_bytes.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    let resized = (film.width, film.height) != (expected.width, expected.height);
    if bless && (differing > 0 || resized) {
        write_image(&film, &golden).unwrap();
        panic!(
            "GLINT_BLESS=1 rewrote {}: {differing} pixels changed (review it, commit, and run \
             again without GLINT_BLESS)",
            golden.display()
        );
    }
    if differing > 0 || resized {
        let actual_path = failure_dir().join("scenes-scrabble-160x90-actual.png");
        write_image(&film, &actual_path).unwrap();
        panic!(
            "{differing} pixels differ from {} (actual: {})",
            golden.display(),
            actual_path.display()
        );
    }
}

/// The whole scene (camera, lights, falloff) scaled by 10⁻³ and 10³ about the origin
/// renders like scale 1: FLIP mean ≤ 0.001, ≥ 99.9% of pixels within 2/255, no NaN.
#[test]
fn scaled_scene_renders_like_scale_one() {
    let scene = &load_scenes(&scene_path(), &small(192, 108))[0];
    let reference = render_cpu(&pack(scene).unwrap());
    for s in [1e-3, 1e3] {
        let film: Film = render_cpu(&pack(&scaled_scene(scene, s)).unwrap());
        assert!(
            film.pixels.iter().flatten().all(|v| v.is_finite()),
            "NaN at scale {s}"
        );
        let name = format!("scrabble-scale-{s}");
        let report = glint::diff::assert_images_match(
            &name,
            &film,
            &reference,
            0.001,
            0.999,
            &failure_dir(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{name}: FLIP mean {:.5}, {:.3}% within 2/255, RMSE {:.5}",
            report.flip_mean,
            100.0 * report.share_within(2.0 / 255.0),
            report.rmse
        );
    }
}
