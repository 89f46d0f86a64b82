//! The committed textures are what `tools/examples/make_textures.rs` makes: every PNG in
//! `textures/` is regenerated in memory and compared byte for byte (the encoder and its
//! settings are pinned by Cargo.lock and the generator). `GLINT_BLESS=1` (only `1`) rewrites
//! the ones that differ, and the run then fails naming them: a blessing is not a pass.
//! Also: the board's premium squares against the standard board, square by square.

use crate::common;
use crate::texture_gen;

use common::bless_requested;

use texture_gen::board::{premium, Premium};

#[test]
fn committed_textures_are_reproduced_byte_for_byte() {
    let dir = texture_gen::textures_dir();
    let bless = bless_requested();
    let mut differing = Vec::new();
    let assets = texture_gen::all_assets();
    for asset in &assets {
        let path = dir.join(asset.name);
        let committed = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        if committed != asset.png {
            differing.push(format!(
                "{}: committed {} bytes, generated {} bytes",
                asset.name,
                committed.len(),
                asset.png.len()
            ));
        }
    }
    if bless && !differing.is_empty() {
        texture_gen::write_all(&dir).unwrap();
        panic!(
            "GLINT_BLESS=1 rewrote textures/ (review the images, commit, and run again without \
             GLINT_BLESS):\n{}",
            differing.join("\n")
        );
    }
    assert!(
        differing.is_empty(),
        "textures/ differs from tools/examples/make_textures.rs (run `cargo run --example \
         make_textures` and review the images):\n{}",
        differing.join("\n")
    );
    // Every PNG in textures/ is one the generator makes (none drawn by hand).
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".png"))
        .collect();
    on_disk.sort();
    let mut generated: Vec<String> = assets.iter().map(|a| a.name.to_string()).collect();
    generated.sort();
    assert_eq!(on_disk, generated);
}

/// The standard board (rows and columns 0–14), written out square by square rather than
/// by symmetry, so a slip in the generator's folding shows.
#[test]
fn premium_squares_are_in_their_standard_places() {
    let triple_word = [
        (0, 0),
        (0, 7),
        (0, 14),
        (7, 0),
        (7, 14),
        (14, 0),
        (14, 7),
        (14, 14),
    ];
    let double_word = [
        (1, 1),
        (2, 2),
        (3, 3),
        (4, 4),
        (1, 13),
        (2, 12),
        (3, 11),
        (4, 10),
        (13, 1),
        (12, 2),
        (11, 3),
        (10, 4),
        (13, 13),
        (12, 12),
        (11, 11),
        (10, 10),
    ];
    let triple_letter = [
        (1, 5),
        (1, 9),
        (5, 1),
        (5, 5),
        (5, 9),
        (5, 13),
        (9, 1),
        (9, 5),
        (9, 9),
        (9, 13),
        (13, 5),
        (13, 9),
    ];
    let double_letter = [
        (0, 3),
        (0, 11),
        (2, 6),
        (2, 8),
        (3, 0),
        (3, 7),
        (3, 14),
        (6, 2),
        (6, 6),
        (6, 8),
        (6, 12),
        (7, 3),
        (7, 11),
        (8, 2),
        (8, 6),
        (8, 8),
        (8, 12),
        (11, 0),
        (11, 7),
        (11, 14),
        (12, 6),
        (12, 8),
        (14, 3),
        (14, 11),
    ];
    let mut counts = [0usize; 6];
    for row in 0..15 {
        for column in 0..15 {
            let square = (row, column);
            let expected = if square == (7, 7) {
                Premium::Centre
            } else if triple_word.contains(&square) {
                Premium::TripleWord
            } else if double_word.contains(&square) {
                Premium::DoubleWord
            } else if triple_letter.contains(&square) {
                Premium::TripleLetter
            } else if double_letter.contains(&square) {
                Premium::DoubleLetter
            } else {
                Premium::Plain
            };
            assert_eq!(premium(row, column), expected, "square {square:?}");
            counts[expected as usize] += 1;
        }
    }
    // 164 plain, 24 DL, 12 TL, 16 DW, 8 TW, the star.
    assert_eq!(counts, [164, 24, 12, 16, 8, 1]);
}
