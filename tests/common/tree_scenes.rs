//! Scenes whose rays branch at their limits, shared by the CPU's wavefront-tree tests
//! (tests/images/wavefront.rs) and the GPU's (tests/gpu/gpu_wavefront_tree.rs): a full
//! ray stack, floors under glass slabs, a camera under water.

/// The camera inside a closed sphere of half-mirror glass: index 1 (the air's: no
/// interface, F = 0, so the transmitted ray leaves with the whole weight and misses) plus
/// a 0.9 mirror. Each hit pushes its transmitted ray then its reflected ray, which hits
/// the sphere again: the stack grows by one a bounce (every transmitted ray waits under
/// the reflected chain) until it is full at RAY_STACK_SIZE and the reflected ray is
/// dropped, long before max_depth.
pub const FULL_STACK_SCENE: &str = r#"
half = gr.material({0.3, 0.2, 0.1}, {0.2, 0.2, 0.2}, 20)
half:set_reflection(0.9, 0.9, 0.9)
half:set_refraction(1.0)
root = gr.node('root')
shell = gr.nh_sphere('shell', {0, 0, 0}, 5)
shell:set_material(half)
root:add_child(shell)
gr.render(root, 'full.png', 8, 6, {1, 0.5, 2}, {0.3, -0.2, -1}, {0, 1, 0}, 60,
          {0.3, 0.3, 0.3}, {gr.light({0, 20, 3}, {0.8, 0.8, 0.8}, {1, 0, 0})},
          {background = {top = {0.5, 0.7, 0.9}, bottom = {0.9, 0.8, 0.6}}})
"#;

/// A floor lit through `slabs` thin glass slabs (two surfaces each) over its left half,
/// seen through them from above.
pub fn slab_scene(slabs: u32) -> String {
    let mut source = String::from(
        r#"
gr.transform_order('pre')
white = gr.material({0.8, 0.8, 0.8}, {0.3, 0.3, 0.3}, 30)
glass = gr.material({0, 0, 0}, {0.5, 0.5, 0.5}, 100)
glass:set_refraction(1.5)
root = gr.node('root')
floor = gr.cube('floor')
floor:set_material(white)
floor:scale(20, 1, 20)
floor:translate(-10, -1, -10)
root:add_child(floor)
"#,
    );
    for k in 0..slabs {
        source += &format!(
            "slab{k} = gr.cube('slab{k}')\nslab{k}:set_material(glass)\n\
             slab{k}:scale(6, 0.2, 12)\nslab{k}:translate(-6, {}, -6)\nroot:add_child(slab{k})\n",
            2 + k
        );
    }
    source += r#"
gr.render(root, 'slabs.png', 12, 8, {0, 14, 10}, {0, -14, -10}, {0, 1, 0}, 50,
          {0.2, 0.2, 0.2}, {gr.light({0, 12, 0}, {0.9, 0.9, 0.9}, {1, 0, 0})})
"#;
    source
}

/// The camera under water (a sphere of index 1.33 around the whole scene), looking at a
/// glass ball over a floor, lit from outside the water: camera rays start in the media
/// packing found around the camera, and every shadow ray leaves the water.
pub const UNDERWATER_SCENE: &str = r#"
white = gr.material({0.8, 0.8, 0.8}, {0.3, 0.3, 0.3}, 30)
glass = gr.material({0, 0, 0}, {0.5, 0.5, 0.5}, 100)
glass:set_refraction(1.5)
water = gr.material({0, 0, 0}, {0.3, 0.3, 0.3}, 100)
water:set_refraction(1.33)
root = gr.node('root')
sea = gr.nh_sphere('sea', {0, 0, 0}, 30)
sea:set_material(water)
root:add_child(sea)
floor = gr.nh_box('floor', {-10, -11, -10}, 20)
floor:set_material(white)
root:add_child(floor)
ball = gr.nh_sphere('ball', {0, 1.5, 0}, 1.5)
ball:set_material(glass)
root:add_child(ball)
gr.render(root, 'underwater.png', 12, 8, {0, 3, 8}, {0, -0.3, -1}, {0, 1, 0}, 50,
          {0.2, 0.2, 0.2}, {gr.light({10, 40, 10}, {0.9, 0.9, 0.9}, {1, 0, 0})})
"#;
