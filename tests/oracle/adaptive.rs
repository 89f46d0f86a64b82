//! Adaptive anti-aliasing in passes over a per-tile lattice (`tracer::sampling::adaptive`) against the
//! per-pixel reference walk (`tracer::sampling::render::adaptive_pixel`): the same decisions, samples
//! and summation order, so the images are identical bit for bit.

use crate::common;

use common::{corpus, packed_from_file, root};
use glint::constants::{AA_FINE_DETAIL_DEPTH, AA_ITEM_EDGE_DEPTH};
use glint::scene::{AaMode, OptionOverrides};
use glint::testing::adaptive_lattice_sample;
use glint::tracer::sampling::render::{adaptive_leaf_counts, render_pixel};
use glint::tracer::traversal::traverse::NoCounters;

fn check(file: &str, size: u32, depth: u32) {
    check_path(&corpus().join("a4-2021plus").join(file), size, depth, None);
}

/// Passes against per-pixel walk on `path` at size² and depth `depth` (and threshold
/// `threshold`, else the scene's); returns the leaf counts.
fn check_path(path: &std::path::Path, size: u32, depth: u32, threshold: Option<f32>) -> Vec<u32> {
    let file = path.display();
    let overrides = OptionOverrides {
        width: Some(size),
        height: Some(size),
        aa: Some(AaMode::Adaptive),
        aa_depth: Some(glint::scene::AaDepth::constant(depth)),
        aa_threshold: threshold,
        ..OptionOverrides::default()
    };
    let scene = packed_from_file(path, &overrides).remove(0);
    let film = glint::tracer::render(&scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(&scene);
    let mut split = 0;
    for y in 0..size {
        for x in 0..size {
            let reference = render_pixel(&scene, x, y, &mut NoCounters).to_array();
            let got = film.pixels[(y * size + x) as usize];
            assert_eq!(got, reference, "{file} d={depth} pixel ({x}, {y})");
            let l = leaves[(y * size + x) as usize];
            assert_eq!(l % 3, 1, "leaf count {l}");
            split += (l > 1) as u32;
        }
    }
    assert!(depth == 0 || split > 0, "{file} d={depth}: nothing split");
    leaves
}

#[test]
fn lattice_matches_per_pixel_walk() {
    check("nonhier.lua", 40, 0);
    check("nonhier.lua", 40, 1);
    check("nonhier.lua", 37, 3);
    check("nonhier.lua", 24, 6);
    check("macho-cows.lua", 32, 3);
}

/// Soft shadows: a lattice sample that saw a penumbra splits the squares it is a corner
/// or centre of down to AA_FINE_DETAIL_DEPTH, in the passes as in the per-pixel walk. With a
/// threshold no contrast exceeds, only penumbrae and edges between items split, each no
/// deeper than its depth.
#[test]
fn penumbrae_split_down_to_their_depth() {
    let path = root().join("scenes/soft-shadows.lua");
    check_path(&path, 40, 3, None);
    let leaves = check_path(&path, 40, 3, Some(f32::MAX));
    let deepest = 1 << (2 * AA_FINE_DETAIL_DEPTH);
    let full = leaves.iter().filter(|&&l| l == deepest).count();
    eprintln!(
        "{full} of {} pixels split to 4^{AA_FINE_DETAIL_DEPTH}",
        leaves.len()
    );
    assert!(full > 0, "no penumbra split");
    // Edges between items split deeper (AA_ITEM_EDGE_DEPTH), whatever their contrast.
    let item_edges = 1 << (2 * AA_FINE_DETAIL_DEPTH.max(AA_ITEM_EDGE_DEPTH));
    assert!(
        leaves.iter().all(|&l| l <= item_edges),
        "deeper than the hints' depths"
    );
}

/// Two walls meeting at x = 0 straight ahead of the camera (black to the left, white to
/// the right; ambient light only), so the edge between them lies exactly on the boundary
/// of pixel columns 7 and 8 of a 16 × 64 image.
fn pixel_aligned_edge(depth: u32) -> glint::pack::PackedScene {
    adaptive_scene(&common::two_walls_source(0.0, 1.0), 0.0, depth)
}

/// The first render of scene script `source` under adaptive AA at `threshold` and
/// `depth`.
fn adaptive_scene(source: &str, threshold: f32, depth: u32) -> glint::pack::PackedScene {
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(threshold),
        aa_depth: Some(glint::scene::AaDepth::constant(depth)),
        ..OptionOverrides::default()
    };
    common::packed_from_source(source, &overrides).remove(0)
}

/// The lattice is jittered (AA_LATTICE_JITTER): the points on a pixel boundary spread over
/// both sides of an edge that lies exactly on it, so its two pixel columns share the
/// boundary's error (at most half the boundary's weight, 1/32 of a pixel at depth 3, each
/// on average; less where a square whose boundary points all fell on its own side stays
/// unsplit and exact). A regular lattice puts them all on the edge, one side of it: one
/// column then errs by the boundary's whole weight (1/16) in every row, a visible line,
/// and the other not at all.
#[test]
fn lattice_points_on_a_pixel_aligned_edge_fall_on_both_sides() {
    let scene = pixel_aligned_edge(3);
    let film = glint::tracer::render(&scene, &|_, _| {});
    let column_error = |x: usize, exact: f32| {
        (0..64)
            .map(|y| (film.pixels[y * 16 + x][1] - exact).abs())
            .sum::<f32>()
            / 64.0
    };
    let (left, right) = (column_error(7, 0.0), column_error(8, 1.0));
    eprintln!("mean error: column 7 (black) {left}, column 8 (white) {right}");
    for (name, err) in [("7", left), ("8", right)] {
        assert!(
            (1.0 / 128.0..=3.0 / 64.0).contains(&err),
            "column {name}: mean error {err}: the boundary's error is not shared"
        );
    }
    assert!(
        left + right < 1.0 / 16.0,
        "more error in all than one regular column"
    );
    // Away from the edge the walls are exact.
    assert_eq!(column_error(3, 0.0), 0.0);
    assert_eq!(column_error(12, 1.0), 0.0);
}

/// White vertical bars on black (ambient light only) in a 16 × 16 image, each given by
/// the pixel column where it starts and its width in pixels, rendered under adaptive AA
/// at threshold 0.2 and depth 3 (contrast 1 splits levels 0–2: 1 > 0.2·2^k).
fn white_bars(bars: &[(f64, f64)]) -> glint::pack::PackedScene {
    // At distance 4 with vfov 50 over 16 pixels, a pixel is 8·tan 25°/16 = 0.23314
    // units, and pixel 8 starts at x = 0; the bars' fronts are at distance 4.
    let pixel = 8.0 * 25f64.to_radians().tan() / 16.0;
    let mut source = String::from(
        "black = gr.material({0, 0, 0}, {0, 0, 0}, 10)
        white = gr.material({1, 1, 1}, {0, 0, 0}, 10)
        root = gr.node('root')
        wall = gr.cube('wall') wall:scale(20, 20, 1) wall:translate(-10, -10, -7)
        wall:set_material(black) root:add_child(wall)\n",
    );
    for (k, (start, width)) in bars.iter().enumerate() {
        source += &format!(
            "bar{k} = gr.cube('bar{k}') bar{k}:scale({}, 20, 0.001) \
             bar{k}:translate({}, -10, -4.001) bar{k}:set_material(white) root:add_child(bar{k})\n",
            width * pixel,
            (start - 8.0) * pixel
        );
    }
    source +=
        "gr.render(root, 'bars.png', 16, 16, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 50, {1, 1, 1}, {})";
    adaptive_scene(&source, 0.2, 3)
}

/// A white bar a quarter of a pixel wide down the middle of pixel column 8 (8.375–8.625):
/// no corner of those pixels sees it (corners are jittered by at most 1/16 pixel at depth
/// 3), their centres always do.
fn bar_between_corners() -> glint::pack::PackedScene {
    white_bars(&[(8.375, 0.25)])
}

/// Each pixel's centre is sampled with its corners and takes part in its split decision
/// (`square_contrast_of`): detail that lies between the corners splits the pixel, and its
/// colour approaches the bar's coverage (1/4) where corners alone saw black and never
/// split. Pixels away from the bar stay unsplit and exact.
#[test]
fn detail_between_a_pixels_corners_splits_it() {
    let scene = bar_between_corners();
    let film = glint::tracer::render(&scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(&scene);
    for y in 0..16 {
        let at = |x: usize| y * 16 + x;
        assert!(leaves[at(8)] > 1, "row {y}: the bar's pixel did not split");
        let green = film.pixels[at(8)][1];
        assert!(
            (0.15..=0.35).contains(&green),
            "row {y}: the bar's pixel is {green}, its coverage 0.25"
        );
        for x in [3, 12] {
            assert_eq!(leaves[at(x)], 1, "row {y}, column {x} split");
            assert_eq!(film.pixels[at(x)][1], 0.0, "row {y}, column {x}");
        }
    }
}

/// Pixel column 8: a white bar 0.16 of a pixel wide around the centre of its left half
/// (8.17–8.33), which no pixel corner, pixel centre or pixel midpoint sees (all jittered
/// by at most 1/16 pixel at depth 3), only the centres of the left half's squares; and a
/// white wall from 8.9 onwards, which the pixel's right corners see, so every pixel of the
/// column splits.
fn bar_inside_a_half() -> glint::pack::PackedScene {
    white_bars(&[(8.17, 0.16), (8.9, 1.1)])
}

/// Every square above aa_depth has a centre sample that takes part in its split decision
/// and its colour, not only the pixel: a split pixel's left half, whose corners all see
/// black, still splits where its squares' centres see a bar between those corners, and
/// the pixel's colour counts the bar (coverage 0.16 + 0.1 = 0.26; without the squares'
/// centres only the wall's 0.1 or so shows).
#[test]
fn detail_between_a_squares_corners_splits_it_at_every_level() {
    let scene = bar_inside_a_half();
    let film = glint::tracer::render(&scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(&scene);
    for y in 0..16 {
        let at = |x: usize| y * 16 + x;
        // The right quarters split where the wall is (10 leaves each); the left ones
        // split for the bar, down to level 3 (16 leaves each), where left whole they
        // would be one leaf each: 22 leaves in all.
        assert!(leaves[at(8)] > 30, "row {y}: {} leaves", leaves[at(8)]);
        let green = film.pixels[at(8)][1];
        assert!(
            (0.2..=0.32).contains(&green),
            "row {y}: the pixel is {green}, its coverage 0.26"
        );
    }
}

/// An edge between two items of the same colour splits the squares around it down to
/// AA_ITEM_EDGE_DEPTH, whatever the threshold (here one no contrast exceeds), in the passes
/// as in the per-pixel walk; nothing else splits. The edge lies on the boundary of
/// columns 7 and 8, whose lattice points are jittered to either side of it; column 7's
/// centres are always left of it and column 8's right, so in every row one of the two
/// pixels (or both) sees both walls.
#[test]
fn item_edges_split_whatever_the_contrast() {
    let scene = adaptive_scene(&common::two_walls_source(1.0, 1.0), f32::MAX, 3);
    let (film, leaves) = assert_splits_only_at_the_middle_edge(&scene);
    let deepest = 1 << (2 * AA_ITEM_EDGE_DEPTH);
    for (k, pixel) in film.pixels.iter().enumerate() {
        assert_eq!(*pixel, [1.0, 1.0, 1.0], "pixel {k}");
        assert!(leaves[k] <= deepest, "pixel {k}: {}", leaves[k]);
    }
    // Level AA_ITEM_EDGE_DEPTH − 1 splits too (the halves of a pixel that straddle the
    // edge), and no deeper level.
    let above = 1 << (2 * (AA_ITEM_EDGE_DEPTH - 1));
    assert!(
        leaves.iter().any(|&l| l > above),
        "no square below a pixel split"
    );
}

/// Renders a 16×64 scene whose only edge lies between pixel columns 7 and 8 and checks
/// that in every row a pixel beside it splits, no other pixel does, and the passes give
/// the per-pixel walk's colours. Returns the film and the leaves per pixel.
fn assert_splits_only_at_the_middle_edge(
    scene: &glint::pack::PackedScene,
) -> (glint::film::Film, Vec<u32>) {
    let film = glint::tracer::render(scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(scene);
    for y in 0..64 {
        let at = |x: usize| y * 16 + x;
        assert!(
            leaves[at(7)] > 1 || leaves[at(8)] > 1,
            "row {y}: neither pixel at the edge split ({}, {})",
            leaves[at(7)],
            leaves[at(8)]
        );
        for x in 0..16 {
            let reference = render_pixel(scene, x as u32, y as u32, &mut NoCounters).to_array();
            assert_eq!(film.pixels[at(x)], reference, "pixel ({x}, {y})");
            if !(7..=8).contains(&x) {
                assert_eq!(
                    leaves[at(x)],
                    1,
                    "pixel ({x}, {y}) away from the edge split"
                );
            }
        }
    }
    (film, leaves)
}

/// An edge seen in a mirror splits as an edge seen directly: two white walls meeting on a
/// pixel boundary, seen only in a mirror, with a threshold no contrast exceeds. Every
/// sample hits the mirror first; the item its reflected ray hits keys it too
/// (`sample_item_key`), so in every row a pixel at the reflected edge splits and no other
/// pixel does (keyed by the mirror alone, nothing would split).
#[test]
fn edges_seen_in_a_mirror_split_whatever_the_contrast() {
    let scene = adaptive_scene(&common::mirrored_walls_source(), f32::MAX, 3);
    assert_splits_only_at_the_middle_edge(&scene);
}

/// Texture detail at the pixel's scale splits down to AA_FINE_DETAIL_DEPTH: a quad with
/// thin dark lines (`striped_quad`) at threshold 0.15, so a pixel splits by contrast only
/// where two of its five samples differ by more than 0.15, and a square of level 1 only
/// over 0.3, which no two samples reach. The samples near a line see its texture lose
/// about 0.1 between the pixel's footprint and twice it (more than
/// AA_TEXTURE_DETAIL_SHARE × 0.15): the pixels they belong to split all the same, also
/// where the contrast does not reach the threshold (without the hint those stay whole),
/// and no deeper than the hint's depth; pixels with neither stay whole.
#[test]
fn texture_detail_splits_down_to_the_fine_detail_depth() {
    let dir = common::temp_dir("adaptive-texture-detail");
    let threshold = 0.15;
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(threshold),
        aa_depth: Some(glint::scene::AaDepth::constant(3)),
        ..OptionOverrides::default()
    };
    let scene = common::striped_quad(&dir, &overrides);
    let film = glint::tracer::render(&scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(&scene);
    let deepest = 1 << (2 * AA_FINE_DETAIL_DEPTH);
    assert!(leaves.iter().all(|&l| l <= deepest), "{leaves:?}");
    let mut split_by_the_hint_alone = 0;
    for y in 0..32 {
        for x in 0..32 {
            let (fx, fy) = (x as f32, y as f32);
            let samples = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)]
                .map(|(dx, dy)| adaptive_lattice_sample(&scene, fx + dx, fy + dy));
            let green = samples.map(|(c, _)| c.y);
            let contrast = green.iter().fold(f32::MIN, |a, &g| a.max(g))
                - green.iter().fold(f32::MAX, |a, &g| a.min(g));
            let detail = samples.iter().any(|&(_, d)| d);
            let leaves = leaves[(y * 32 + x) as usize];
            if contrast <= threshold {
                assert_eq!(leaves > 1, detail, "pixel ({x}, {y}): {leaves} leaves");
                split_by_the_hint_alone += detail as u32;
            }
        }
    }
    eprintln!("{split_by_the_hint_alone} pixels split by texture detail alone");
    assert!(split_by_the_hint_alone > 0, "{leaves:?}");
    for y in 0..32 {
        for x in 0..32 {
            let reference = render_pixel(&scene, x, y, &mut NoCounters).to_array();
            assert_eq!(
                film.pixels[(y * 32 + x) as usize],
                reference,
                "pixel ({x}, {y})"
            );
        }
    }
}
