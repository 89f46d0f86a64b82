//! Tilings of an image for the farm's bit-for-bit tests: the farm's own N-tile splits,
//! 1×N strips, N×M blocks and 1-pixel tiles at the edges and corners, each an exact cover.

use glint::farm::split::tile_rect;
use glint::film::Film;
use glint::tiling::PixelRect;

fn rect(x0: u32, x1: u32, y0: u32, y1: u32) -> PixelRect {
    PixelRect { x0, x1, y0, y1 }
}

/// Named tilings of a `w × h` image (w, h ≥ 3).
pub fn tilings(w: u32, h: u32, splits: &[u32]) -> Vec<(String, Vec<PixelRect>)> {
    let mut out: Vec<(String, Vec<PixelRect>)> = splits
        .iter()
        .map(|&n| {
            let tiles = (0..n).map(|i| tile_rect(w, h, i, n).unwrap()).collect();
            (format!("--tile of {n}"), tiles)
        })
        .collect();
    // Strips of one row each, then of columns 3 wide (the last narrower).
    out.push((
        "1-row strips".into(),
        (0..h).map(|y| rect(0, w, y, y + 1)).collect(),
    ));
    let cols = (0..w.div_ceil(3)).map(|k| rect(3 * k, (3 * k + 3).min(w), 0, h));
    out.push(("3-column strips".into(), cols.collect()));
    // Blocks of 2×5 pixels (odd remainders at the right and bottom).
    let mut blocks = Vec::new();
    for y in (0..h).step_by(5) {
        for x in (0..w).step_by(2) {
            blocks.push(rect(x, (x + 2).min(w), y, (y + 5).min(h)));
        }
    }
    out.push(("2×5 blocks".into(), blocks));
    // A 1-pixel frame around the image, corners alone, and the inside.
    out.push((
        "1-pixel edges".into(),
        vec![
            rect(0, 1, 0, 1),
            rect(1, w - 1, 0, 1),
            rect(w - 1, w, 0, 1),
            rect(0, 1, 1, h - 1),
            rect(1, w - 1, 1, h - 1),
            rect(w - 1, w, 1, h - 1),
            rect(0, 1, h - 1, h),
            rect(1, w - 1, h - 1, h),
            rect(w - 1, w, h - 1, h),
        ],
    ));
    out
}

/// The tiles' films put back into a `w × h` film; panics unless they cover it once.
pub fn join(w: u32, h: u32, tiles: &[(PixelRect, Film)]) -> Film {
    let mut film = Film::new(w, h);
    let mut hits = vec![0u32; (w * h) as usize];
    for (r, tile) in tiles {
        assert_eq!((tile.width, tile.height), (r.width(), r.height()), "{r:?}");
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                hits[(y * w + x) as usize] += 1;
                film.set(x, y, tile.get(x - r.x0, y - r.y0));
            }
        }
    }
    assert!(
        hits.iter().all(|&n| n == 1),
        "the tiling is not an exact cover"
    );
    film
}

/// The first pixel where `a` and `b` differ in any bit, if any.
pub fn first_difference(a: &Film, b: &Film) -> Option<(u32, u32, [f32; 3], [f32; 3])> {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let bits = |p: [f32; 3]| p.map(f32::to_bits);
    (0..a.height)
        .flat_map(|y| (0..a.width).map(move |x| (x, y)))
        .find(|&(x, y)| bits(a.get(x, y)) != bits(b.get(x, y)))
        .map(|(x, y)| (x, y, a.get(x, y), b.get(x, y)))
}
