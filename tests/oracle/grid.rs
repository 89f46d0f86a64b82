//! The grid changes speed, never the picture: every test scene rendered through the grid
//! and by brute force gives the same 8-bit image; and the render does not depend on the
//! number of threads.

use crate::common;

use common::{corpus_scenes, load_packed, own_scenes, render_cpu, scene_name};
use glint::scene::{AaMode, GridMode, OptionOverrides};

/// Small renders: brute force over macho-cows' 17 548 items is slow.
fn overrides(grid: GridMode) -> OptionOverrides {
    OptionOverrides {
        grid: Some(grid),
        aa: Some(AaMode::None),
        width: Some(48),
        height: Some(48),
        ..OptionOverrides::default()
    }
}

#[test]
fn grid_and_brute_force_give_the_same_image() {
    let mut report = Vec::new();
    for path in corpus_scenes().into_iter().chain(own_scenes()) {
        let with_grid = load_packed(&path, &overrides(GridMode::Auto));
        let brute = load_packed(&path, &overrides(GridMode::Off));
        assert_eq!(with_grid.globals.grid_enabled, 1);
        assert_eq!(brute.globals.grid_enabled, 0);
        let a = render_cpu(&with_grid).to_rgb8();
        let b = render_cpu(&brute).to_rgb8();
        let differing = a.chunks(3).zip(b.chunks(3)).filter(|(x, y)| x != y).count();
        report.push(format!("{}: {differing} pixels differ", scene_name(&path)));
        assert_eq!(
            differing,
            0,
            "{}: grid and brute force differ",
            path.display()
        );
    }
    println!("{}", report.join("\n"));
}

#[test]
fn grid_densities_give_the_same_image() {
    let path = common::corpus().join("a4-2021plus/macho-cows.lua");
    let reference = render_cpu(&load_packed(&path, &overrides(GridMode::Auto))).to_rgb8();
    for density in [0.1, 1.0, 7.0, 50.0] {
        let film = render_cpu(&load_packed(&path, &overrides(GridMode::Density(density))));
        assert!(
            film.to_rgb8() == reference,
            "density {density} changes the image"
        );
    }
}

#[test]
fn image_is_independent_of_thread_count() {
    let path = common::root().join("scenes/demo.lua");
    let packed = load_packed(
        &path,
        &OptionOverrides {
            width: Some(80),
            height: Some(50),
            ..OptionOverrides::default()
        },
    );
    let render_on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_cpu(&packed))
    };
    let one = render_on(1);
    for threads in [2, 3, 7] {
        assert!(
            render_on(threads).pixels == one.pixels,
            "{threads} threads differ from 1"
        );
    }
    assert!(
        render_cpu(&packed).pixels == one.pixels,
        "a second run differs"
    );
}

/// A scene of `count` unit spheres in a row, written to a fresh folder: the folder's
/// guard (the folder goes with it) and the scene's path.
fn spheres_scene(count: usize) -> (glint::testing::scratch::TempDir, std::path::PathBuf) {
    let dir = common::temp_dir(&format!("grid-{count}-spheres"));
    let mut lua = String::from(
        "local root = gr.node('root')\n\
         local m = gr.material({0.7, 0.5, 0.3}, {0.4, 0.4, 0.4}, 20)\n",
    );
    for k in 0..count {
        lua += &format!(
            "local s{k} = gr.sphere('s{k}')\ns{k}:set_material(m)\n\
             s{k}:translate({}, 0, 0)\nroot:add_child(s{k})\n",
            3 * k
        );
    }
    lua += "gr.render(root, 'spheres.png', 40, 30, {0, 1, 9}, {0, 0, -1}, {0, 1, 0}, 50,\n\
            {0.2, 0.2, 0.2}, {gr.light({4, 6, 8}, {0.9, 0.9, 0.9}, {1, 0, 0})})\n";
    let path = dir.join("spheres.lua");
    std::fs::write(&path, lua).unwrap();
    (dir, path)
}

#[test]
fn a_single_item_gets_no_scene_grid_unless_asked() {
    // One item: the grid's bounds would be the item's, so it could cull nothing.
    let (_dir, one) = spheres_scene(1);
    let auto = load_packed(&one, &overrides(GridMode::Auto));
    assert_eq!(
        auto.globals.grid_enabled, 0,
        "auto built a grid over one item"
    );
    let asked = load_packed(&one, &overrides(GridMode::Density(8.0)));
    assert_eq!(
        asked.globals.grid_enabled, 1,
        "an explicit density is obeyed"
    );
    let image = render_cpu(&auto).to_rgb8();
    let background = &image[0..3];
    assert!(
        image.chunks(3).filter(|p| *p != background).count() > 100,
        "the sphere is not in view"
    );
    assert!(
        image == render_cpu(&asked).to_rgb8(),
        "one item: brute force and the grid differ"
    );
    // Two items: a grid can cull one of them, and auto builds it.
    let (_dir2, two) = spheres_scene(2);
    let two = load_packed(&two, &overrides(GridMode::Auto));
    assert_eq!(
        two.globals.grid_enabled, 1,
        "auto built no grid over two items"
    );
}
