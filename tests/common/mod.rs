//! Helpers shared by the integration tests: paths, scratch folders, rendering a scene.
#![allow(dead_code)]

pub mod light_on_surface;
pub mod probes;
pub mod tilings;
pub mod tree_scenes;

use glint::film::Film;
use glint::pack::PackedScene;
use glint::pipeline::pack_scene;
use glint::scene::flatten::{flatten, FlatScene};
use glint::scene::lua::{run_scene_file, ScriptConfig};
use glint::scene::{OptionOverrides, TransformOrder};
use std::path::{Path, PathBuf};

/// The CS488 sample corpus beside the repository.
pub fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cs488")
}

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Where failing image tests write actual/expected/heat-map images.
pub fn failure_dir() -> PathBuf {
    root().join("target/test-failures")
}

/// Scratch folders that remove themselves (shared with the unit tests).
#[allow(unused_imports)]
pub use glint::testing::scratch::temp_dir;

/// The transform order a corpus folder's scenes were written for.
pub fn family_order(path: &Path) -> Option<TransformOrder> {
    path.to_string_lossy()
        .contains("a4-pre2015")
        .then_some(TransformOrder::Post)
}

/// Every corpus scene that calls gr.render (icosa.lua is broken as shipped).
pub fn corpus_scenes() -> Vec<PathBuf> {
    let mut scenes = Vec::new();
    for family in ["a4-pre2015", "a4-2015", "a4-2016to2020", "a4-2021plus"] {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(corpus().join(family))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "lua"))
            .filter(|p| std::fs::read_to_string(p).unwrap().contains("gr.render"))
            .collect();
        entries.sort();
        scenes.extend(entries);
    }
    scenes
}

/// glint's own scenes in `scenes/`.
pub fn own_scenes() -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lua"))
        .collect();
    scenes.sort();
    scenes
}

/// A short name for a scene path: `family-stem`.
pub fn scene_name(path: &Path) -> String {
    let family = path
        .parent()
        .unwrap()
        .file_name()
        .unwrap()
        .to_string_lossy();
    let stem = path.file_stem().unwrap().to_string_lossy();
    format!("{family}-{stem}")
}

/// The flattened scene of each gr.render call of a script, with `overrides` applied.
pub fn load_scenes(path: &Path, overrides: &OptionOverrides) -> Vec<FlatScene> {
    let config = ScriptConfig {
        transform_order: family_order(path),
        ..ScriptConfig::default()
    };
    let mut scenes = Vec::new();
    run_scene_file(path, &config, &mut |graph, request| {
        let mut request = request.clone();
        overrides.apply(&mut request.options);
        request.width = overrides.width.unwrap_or(request.width);
        request.height = overrides.height.unwrap_or(request.height);
        scenes.push(flatten(graph, &request)?);
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    scenes
}

/// The first render of a script, packed.
pub fn load_packed(path: &Path, overrides: &OptionOverrides) -> PackedScene {
    let scenes = load_scenes(path, overrides);
    pack_scene(&scenes[0]).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Renders on the CPU with the current rayon pool.
pub fn render_cpu(scene: &PackedScene) -> Film {
    glint::tracer::render(scene, &|_, _| {})
}

/// Whether `GLINT_BLESS=1` asks the golden tests to rewrite their references. Only `1`
/// blesses; any other value is an error (a typo must not silently compare instead).
pub fn bless_requested() -> bool {
    match std::env::var("GLINT_BLESS") {
        Err(std::env::VarError::NotPresent) => false,
        Ok(v) if v == "1" => true,
        Ok(v) => panic!("GLINT_BLESS must be 1 (rewrite the golden images) or unset, got '{v}'"),
        Err(e) => panic!("GLINT_BLESS must be 1 (rewrite the golden images) or unset: {e}"),
    }
}

/// How to get the software Vulkan GPU the GPU tests run on (Debian/Ubuntu).
pub const GPU_INSTALL_HINT: &str = "apt-get install mesa-vulkan-drivers libvulkan1";

/// A device on the default (Vulkan) adapter. A missing adapter fails the calling test with
/// the install hint: a GPU test that returned early would report `ok` without comparing
/// the tracers. Only `GLINT_SKIP_GPU=1` turns it into a skip (None), announced with one
/// line on stderr naming the test and the reason; any other value of it is an error.
///
/// Built with `GLINT_SKIP_GPU=1` (`cfg(glint_skip_gpu)`, see build.rs), every GPU test
/// is marked `#[cfg_attr(glint_skip_gpu, ignore = …)]` and never gets here: one that does
/// lacks the mark, and fails saying so, so that the skipped tests all report as ignored.
pub fn gpu_context() -> Option<glint::gpu::GpuContext> {
    if cfg!(glint_skip_gpu) {
        let test = std::thread::current().name().unwrap_or("?").to_string();
        panic!(
            "{test} asks for a GPU but is not marked as a GPU test: add \
             #[cfg_attr(glint_skip_gpu, ignore = \"needs a GPU adapter (GLINT_SKIP_GPU=1)\")] \
             under its #[test], so that GLINT_SKIP_GPU=1 reports it as ignored"
        );
    }
    let skip = match std::env::var("GLINT_SKIP_GPU") {
        Err(std::env::VarError::NotPresent) => false,
        Ok(v) if v == "1" => true,
        Ok(v) => panic!("GLINT_SKIP_GPU must be 1 (skip GPU tests) or unset, got '{v}'"),
        Err(e) => panic!("GLINT_SKIP_GPU must be 1 (skip GPU tests) or unset: {e}"),
    };
    match glint::gpu::GpuContext::new(None) {
        Ok(ctx) => Some(ctx),
        Err(e) if skip => {
            // Written past the test harness's capture, so the skip shows in a passing run.
            use std::io::Write;
            let test = std::thread::current().name().unwrap_or("?").to_string();
            let _ = writeln!(
                std::io::stderr(),
                "skipped GPU test {test}: no usable GPU adapter ({e}); GLINT_SKIP_GPU=1 is set"
            );
            None
        }
        Err(e) => panic!(
            "no usable GPU adapter: {e}\nThe GPU tests need a Vulkan driver; Mesa's software \
             one is enough: `{GPU_INSTALL_HINT}`. Set GLINT_SKIP_GPU=1 to skip the GPU tests \
             instead (each then says it was skipped)."
        ),
    }
}

/// Packed scenes of every gr.render in a Lua source (run from the 2021+ corpus folder, so
/// it can load that folder's meshes), with `overrides` applied.
pub fn packed_from_source(source: &str, overrides: &OptionOverrides) -> Vec<PackedScene> {
    let mut out = Vec::new();
    glint::scene::lua::run_scene_source(
        "test.lua",
        source,
        &corpus().join("a4-2021plus"),
        &ScriptConfig::default(),
        &mut |graph, request| {
            let mut request = request.clone();
            overrides.apply(&mut request.options);
            request.width = overrides.width.unwrap_or(request.width);
            request.height = overrides.height.unwrap_or(request.height);
            out.push(pack_scene(&flatten(graph, &request)?)?);
            Ok(())
        },
    )
    .unwrap_or_else(|e| panic!("{e}\n{source}"));
    out
}

/// A floor lit by a large area light (6 × 6, 3 units above) with nothing to cast a
/// shadow, 64×64: every pixel's colour moves only with where its shadow samples fall on
/// the light. The floor's material: diffuse `kd`, specular `ks`, `shininess` (grey).
pub fn area_lit_floor_source(kd: f32, ks: f32, shininess: f32) -> String {
    format!(
        "
        floor_mat = gr.material({{{kd}, {kd}, {kd}}}, {{{ks}, {ks}, {ks}}}, {shininess})
        root = gr.node('root')
        floor = gr.cube('floor') floor:scale(10, 0.5, 10) floor:translate(-5, -1.5, -9)
        floor:set_material(floor_mat) root:add_child(floor)
        a = gr.area_light({{0, 3, -4}}, {{6, 0, 0}}, {{0, 0, 6}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})
        gr.render(root, 'floor.png', 64, 64, {{0, 2, 3}}, {{0, -0.5, -1}}, {{0, 1, 0}}, 50,
                  {{0.1, 0.1, 0.1}}, {{a}})
        "
    )
}

/// Two walls meeting at x = 0 straight ahead of the camera, on the boundary of pixel
/// columns 7 and 8 of a 16 × 64 image, the left one grey level `left`, the right one
/// `right` (ambient light only, so every sample of a wall is exactly its level). They
/// fill the view.
pub fn two_walls_source(left: f32, right: f32) -> String {
    format!(
        "
        left_mat = gr.material({{{left}, {left}, {left}}}, {{0, 0, 0}}, 10)
        right_mat = gr.material({{{right}, {right}, {right}}}, {{0, 0, 0}}, 10)
        root = gr.node('root')
        l = gr.cube('l') l:scale(10, 20, 1) l:translate(-10, -10, -5) l:set_material(left_mat)
        r = gr.cube('r') r:scale(10, 20, 1) r:translate(0, -10, -5) r:set_material(right_mat)
        root:add_child(l) root:add_child(r)
        gr.render(root, 'walls.png', 16, 64, {{0, 0, 0}}, {{0, 0, -1}}, {{0, 1, 0}}, 50,
                  {{1, 1, 1}}, {{}})
        "
    )
}

/// Lua for a mirror (black, reflection 1) filling a 16×64 view along −z, and behind the
/// camera, facing it, two white walls meeting at x = 0: the image shows only the walls'
/// reflection, white everywhere, their edge on the boundary between pixel columns 7 and 8.
/// No contrast anywhere; only what the mirror shows differs.
pub fn mirrored_walls_source() -> String {
    "white = gr.material({1, 1, 1}, {0, 0, 0}, 10)
    mirror = gr.material({0, 0, 0}, {0, 0, 0}, 10) mirror:set_reflection(1)
    root = gr.node('root')
    l = gr.cube('l') l:scale(10, 20, 1) l:translate(-10, -10, 10) l:set_material(white)
    r = gr.cube('r') r:scale(10, 20, 1) r:translate(0, -10, 10) r:set_material(white)
    m = gr.cube('m') m:scale(40, 40, 1) m:translate(-20, -20, -6) m:set_material(mirror)
    root:add_child(l) root:add_child(r) root:add_child(m)
    gr.render(root, 'mirror.png', 16, 64, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 50, {1, 1, 1}, {})
    "
    .to_string()
}

/// A quad overfilling a 32×32 view (a narrow field of view, so the footprint hardly
/// changes across it), lit by ambient 1 alone, with a 64×64 diffuse texture of grey 0.7
/// crossed by vertical lines of grey 0.3, one texel wide, every 8 texels (written to
/// `dir`): 1.8 texels a pixel, mip level 0.87, which keeps a bit over half of the lines'
/// 0.4 of contrast (no two samples differ by 0.3), and twice the footprint about half of
/// that. Packed with `overrides`.
pub fn striped_quad(dir: &Path, overrides: &OptionOverrides) -> PackedScene {
    striped_quad_with(dir, overrides, "")
}

/// [`striped_quad`] with `material` (Lua calls on the quad's material `m`, e.g.
/// `m:set_reflection(0.3, 0.3, 0.3)`) after its texture.
pub fn striped_quad_with(dir: &Path, overrides: &OptionOverrides, material: &str) -> PackedScene {
    let texture = image::RgbImage::from_fn(64, 64, |x, _| {
        let grey = if x % 8 == 0 { 77 } else { 179 };
        image::Rgb([grey, grey, grey])
    });
    texture.save(dir.join("stripes.png")).unwrap();
    let source = format!(
        "m = gr.material('m') m:set_diffuse('stripes.png') {material} \
        q = gr.mesh('q', {{{{0,0,0}},{{1,0,0}},{{1,1,0}},{{0,1,0}}}}, {{{{0,1,2,3}}}}, \
                         {{{{0,0}},{{1,0}},{{1,1}},{{0,1}}}}) \
        q:set_material(m) \
        gr.render(q, 'o.png', 32, 32, {{0.5,0.5,2.6}}, {{0,0,-1}}, {{0,1,0}}, 20, {{1,1,1}}, {{}})"
    );
    let path = dir.join("stripes.lua");
    std::fs::write(&path, source).unwrap();
    packed_from_file(&path, overrides).remove(0)
}

/// Lua for six instances of one mesh, a flat square frame (outer half-width 1, a square
/// hole of half-width 0.5), scaled by 2, 1.75, … 0.75 and stacked along −z (frame k at
/// z = −2k), with a sphere behind them all: a ray along −z at distance r from the axis
/// passes through the holes of the frames wider than 2r and is stopped by the first
/// frame whose ring it meets, or by the sphere.
pub fn stacked_frames_source() -> String {
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0, 0, 0}, 10)
        frame = gr.mesh('frame', {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
            {-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}},
            {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}})
        frame:set_material(m)
        root = gr.node('root')
        ",
    );
    for k in 0..6 {
        let s = 2.0 - 0.25 * k as f64;
        lua += &format!(
            "n{k} = gr.node('frame{k}') n{k}:scale({s}, {s}, {s}) n{k}:translate(0, 0, {}) n{k}:add_child(frame) root:add_child(n{k})\n",
            -2.0 * k as f64
        );
    }
    lua + "ball = gr.sphere('ball') ball:scale(3, 3, 3) ball:translate(0, 0, -20) ball:set_material(m) root:add_child(ball)
        gr.render(root, 'frames.png', 32, 32, {0, 0, 20}, {0, 0, -1}, {0, 1, 0}, 30, {0.1, 0.1, 0.1}, {})\n"
}

/// Origins of rays along −z past the stacked frames of [`stacked_frames_source`]: from
/// the axis out past the widest frame (x = 0 … 2.2), off the diagonal (y = 0.37 x).
pub fn stacked_frames_origins() -> Vec<[f32; 3]> {
    (0..=220)
        .map(|i| {
            let x = i as f32 * 0.01;
            [x, 0.37 * x, 20.0]
        })
        .collect()
}

/// Packed scenes of every gr.render in a scene file, with `overrides` applied.
pub fn packed_from_file(path: &Path, overrides: &OptionOverrides) -> Vec<PackedScene> {
    load_scenes(path, overrides)
        .iter()
        .map(|s| pack_scene(s).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        .collect()
}

/// xorshift64*: small, seeded, reproducible.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545F4914F6CDD1D)
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// A flattened scene scaled by `s` about the origin, camera, lights and CSG leaves
/// included; the falloff is rescaled so lighting is the same function of the scaled
/// distances.
pub fn scaled_scene(scene: &FlatScene, s: f64) -> FlatScene {
    use glint::scene::flatten::CsgStep;
    let mut out = scene.clone();
    let m = glam::DMat4::from_scale(glam::DVec3::splat(s));
    for o in &mut out.objects {
        o.object_to_world = m * o.object_to_world;
    }
    for c in &mut out.csg {
        for step in &mut c.program {
            if let CsgStep::Leaf(o) = step {
                o.object_to_world = m * o.object_to_world;
            }
        }
    }
    for t in &mut out.triangles {
        t.positions = t.positions.map(|p| p * s);
    }
    for instance in &mut out.mesh_instances {
        instance.object_to_world = m * instance.object_to_world;
    }
    for l in &mut out.lights {
        l.position *= s;
        if let Some(area) = &mut l.area {
            area.u *= s;
            area.v *= s;
        }
        l.falloff = [
            l.falloff[0],
            l.falloff[1] / s as f32,
            l.falloff[2] / (s * s) as f32,
        ];
    }
    out.camera.eye *= s;
    out
}

/// Rays from the camera of `scenes/csg.lua` into the glass's bowl, aimed at its rim plane
/// inside the hollow (radius 0.54 of the bowl's 0.6, their top caps coplanar), and the
/// test of a speckle: a ray that stops on the bowl's own top cap there.
pub struct GlassProbe {
    /// Packed instance index of the bowl's leaf.
    pub bowl: u32,
    pub bowl_to_object: glam::DMat4,
    pub rays: Vec<glint::testing::probe::ProbeRay>,
}

impl GlassProbe {
    pub fn new(scene: &FlatScene, n: usize) -> GlassProbe {
        use glint::scene::flatten::CsgStep;
        let mut index = scene.objects.len() + scene.csg.len();
        let mut bowl = None;
        for c in &scene.csg {
            for step in &c.program {
                if let CsgStep::Leaf(o) = step {
                    if o.name.ends_with("/bowl") {
                        bowl = Some((index, o.object_to_world));
                    }
                    index += 1;
                }
            }
        }
        let (bowl, to_world) = bowl.expect("scenes/csg.lua has a glass with a bowl");
        let mut rng = Rng(0x61A55);
        let eye = scene.camera.eye;
        let rays = (0..n)
            .map(|_| {
                let phi = rng.range(0.0, std::f64::consts::TAU);
                let r = 0.9 * 0.98 * rng.range(0.0, 1.0).sqrt();
                let target =
                    to_world.transform_point3(glam::DVec3::new(r * phi.cos(), r * phi.sin(), 1.0));
                glint::testing::probe::ProbeRay {
                    origin: eye.as_vec3().to_array(),
                    t_max: glint::constants::T_MISS,
                    dir: (target - eye).normalize().as_vec3().to_array(),
                    mode: glint::testing::probe::CLOSEST_HIT,
                }
            })
            .collect();
        GlassProbe {
            bowl: bowl as u32,
            bowl_to_object: to_world.inverse(),
            rays,
        }
    }

    /// Whether a probe's result is a speckle (a hit on the bowl's top cap in the hollow).
    pub fn speckles(&self, results: &[glint::testing::probe::ProbeResult]) -> usize {
        self.rays
            .iter()
            .zip(results)
            .filter(|(ray, r)| {
                if r.hit == 0
                    || r.part & glint::constants::CSG_INDEX_MASK != self.bowl
                    || r.part & glint::constants::CSG_FLIP != 0
                {
                    return false;
                }
                let p = glam::Vec3::from(ray.origin).as_dvec3()
                    + glam::Vec3::from(ray.dir).as_dvec3() * r.t as f64;
                let q = self.bowl_to_object.transform_point3(p);
                (q.z - 1.0).abs() < 1e-3 && q.x.hypot(q.y) < 0.9 * 0.99
            })
            .count()
    }
}

/// Tier 4: renders `scene` on the GPU of `ctx` and on the CPU and asserts the images match
/// (FLIP mean ≤ `max_flip`, ≥ 99.9% of pixels within 2/255), printing the figures; failing
/// images go to `target/tmp/<dir>/`. Returns what the GPU render reported.
pub fn assert_gpu_matches_cpu(
    ctx: &glint::gpu::GpuContext,
    dir: &str,
    name: &str,
    scene: &PackedScene,
    max_flip: f64,
) -> glint::gpu::GpuRenderInfo {
    let glint::gpu::GpuRender {
        film: gpu, info, ..
    } = glint::gpu::render_gpu(ctx, scene, &Default::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let cpu = glint::tracer::render(scene, &|_, _| {});
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(dir);
    let report = glint::diff::assert_images_match(name, &gpu, &cpu, max_flip, 0.999, &out)
        .unwrap_or_else(|message| panic!("{message}"));
    eprintln!(
        "{name}: features [{}], FLIP mean {:.5}, {:.3}% within 2/255, max difference {:.4}, {} CPU-fallback pixels",
        info.features,
        report.flip_mean,
        report.share_within(2.0 / 255.0) * 100.0,
        report.max_abs,
        info.cpu_fallback_pixels
    );
    info
}

/// Lua for a coarse UV sphere mesh named `name` (`around` × `down` quads) of radius
/// `radius` at `centre`, with its unit positions as inline vertex normals (smooth
/// shading) and material `m`, added to `root`.
pub fn smooth_sphere_lua(
    name: &str,
    around: usize,
    down: usize,
    radius: f64,
    centre: glam::DVec3,
) -> String {
    let (mut verts, mut normals, mut faces) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..=down {
        let lat = std::f64::consts::PI * (j as f64 / down as f64 - 0.5);
        for i in 0..=around {
            let lon = std::f64::consts::TAU * i as f64 / around as f64;
            let n = glam::DVec3::new(lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin());
            let p = centre + n * radius;
            verts.push(format!("{{{:e}, {:e}, {:e}}}", p.x, p.y, p.z));
            normals.push(format!("{{{:e}, {:e}, {:e}}}", n.x, n.y, n.z));
        }
    }
    for j in 0..down {
        for i in 0..around {
            let a = j * (around + 1) + i;
            let b = a + around + 1;
            faces.push(format!("{{{a}, {}, {}, {b}}}", a + 1, b + 1));
        }
    }
    format!(
        "{name} = gr.mesh('{name}', {{{}}}, {{{}}}, nil, {{{}}})\n{name}:set_material(m)\nroot:add_child({name})\n",
        verts.join(", "),
        faces.join(", "),
        normals.join(", ")
    )
}

/// A scene of every primitive kind (sphere, cube, cylinder, cone, torus, a mesh quad)
/// wearing material `m` (Phong, with `set`, Lua that changes `m`, run first), in front
/// of a mirror that reflects them, 96×96, lit by one light: for the texture and
/// procedural-texture parity tests.
pub fn every_primitive_lua(set: &str) -> String {
    format!(
        "m = gr.material({{0.7, 0.5, 0.3}}, {{0.5, 0.5, 0.5}}, 30) {set}
         mirror = gr.material({{0.1, 0.1, 0.1}}, {{0, 0, 0}}, 1)
         mirror:set_reflection(0.5, 0.5, 0.5)
         root = gr.node('root')
         local function add(n, x, y) n:set_material(m) n:translate(x, y, 0) root:add_child(n) end
         add(gr.sphere('s'), -2.5, 1.2)
         add(gr.cube('c'), -0.5, 0.7)
         add(gr.cylinder('y'), 1.5, 0.7)
         add(gr.cone('k', 0.2, 1.2), -2.5, -1.5)
         add(gr.torus('t', 0.6, 0.25), 0, -1.2)
         add(gr.mesh('q', {{{{0,0,0}},{{1,0,0}},{{1,1,0}},{{0,1,0}}}}, {{{{0,1,2,3}}}}), 1.5, -1.5)
         back = gr.cube('back') back:set_material(mirror) back:scale(9, 9, 0.2)
         back:translate(-4.5, -4.5, -2) root:add_child(back)
         l = gr.light({{3, 4, 6}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})
         gr.render(root, 'o.png', 96, 96, {{0, 0, 8}}, {{0, 0, -1}}, {{0, 1, 0}}, 50,
                   {{0.2, 0.2, 0.2}}, {{l}})"
    )
}

/// The error message of running the scene script `source`, written as `dir/bad.lua`.
pub fn scene_error_in(dir: &Path, source: &str) -> String {
    let path = dir.join("bad.lua");
    std::fs::write(&path, source).unwrap();
    run_scene_file(&path, &ScriptConfig::default(), &mut |_, _| Ok(()))
        .expect_err("the scene must fail")
        .to_string()
}
