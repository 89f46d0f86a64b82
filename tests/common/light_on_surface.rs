//! Scenes with a light lying exactly on a surface (issue 37: a point light in a ceiling's
//! lower face, on a box's edge, inside a box thinner than rounding; an area light in a
//! ceiling's plane), the same scenes with the light moved slightly off the surface, and
//! the speckle measure that compares the two.

use glint::film::Film;
use glint::scene::flatten::{flatten, FlatScene};
use glint::scene::lua::{run_scene_source, ScriptConfig};

/// Where the light lies.
#[derive(Clone, Copy, Debug)]
pub enum LightOnSurface {
    /// A point light in the lower face of the ceiling (a thin box from y = 50 to 50.1).
    Face,
    /// The same with a glass ball in the room (shadow rays through `shadow_transmittance`).
    FaceThroughGlass,
    /// A point light on the top-right edge of a shelf (x = 0, y = 40).
    Edge,
    /// A point light at the centre of a ceiling panel 10⁻⁴ thick (5·10⁻⁵ either side of
    /// y = 50: thinner than the bound shadow rays stop short of their light by, so it
    /// does not shadow the light).
    ThinBox,
    /// An area light in the plane of the ceiling's lower face.
    AreaInFace,
}

impl LightOnSurface {
    pub const ALL: [LightOnSurface; 5] = [
        LightOnSurface::Face,
        LightOnSurface::FaceThroughGlass,
        LightOnSurface::Edge,
        LightOnSurface::ThinBox,
        LightOnSurface::AreaInFace,
    ];
}

/// Lua for a 96×96 Cornell-style room (floor, three walls, ceiling: thin boxes; a ball on
/// the floor, a shelf on the left wall) lit as `case` says, the light moved off its
/// surface by `off` (0: exactly on it; off the face downwards, off the edge outwards). The
/// camera looks down into the room and sees no ceiling, whose own lighting changes when
/// the light moves below it: every difference it sees is the shadow rays'.
pub fn light_on_surface_source(case: LightOnSurface, off: f64) -> String {
    let ceiling = match case {
        LightOnSurface::ThinBox => {
            let h = 5e-5; // 13 f32 ulps of 50, under shadow_reach's 2⁻¹⁷ × 50 (100 ulps)
            format!(
                "ceiling:scale(100, {}, 100) ceiling:translate(-50, {}, -50)",
                2.0 * h,
                50.0 - h
            )
        }
        _ => "ceiling:scale(100, 0.1, 100) ceiling:translate(-50, 50, -50)".to_string(),
    };
    let light = match case {
        LightOnSurface::Edge => format!(
            "gr.light({{{}, {}, -15}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})",
            off,
            40.0 + off
        ),
        LightOnSurface::AreaInFace => format!(
            "gr.area_light({{5, {}, -5}}, {{20, 0, 0}}, {{0, 0, 20}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}}, 3)",
            50.0 - off
        ),
        _ => format!(
            "gr.light({{10, {}, -5}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})",
            50.0 - off
        ),
    };
    let glass = match case {
        LightOnSurface::FaceThroughGlass => {
            "glass = gr.material({0, 0, 0}, {0.5, 0.5, 0.5}, 100) glass:set_refraction(1.5)
            g = gr.sphere('g') g:scale(8, 8, 8) g:translate(20, 8, 10) g:set_material(glass)
            root:add_child(g)"
        }
        _ => "",
    };
    format!(
        "
        white = gr.material({{0.7, 0.7, 0.7}}, {{0.2, 0.2, 0.2}}, 20)
        red = gr.material({{0.7, 0.2, 0.2}}, {{0.2, 0.2, 0.2}}, 20)
        root = gr.node('root')
        function slab(name, m, sx, sy, sz, tx, ty, tz)
          local b = gr.cube(name) b:scale(sx, sy, sz) b:translate(tx, ty, tz)
          b:set_material(m) root:add_child(b) return b
        end
        slab('floor', white, 100, 0.1, 100, -50, -0.1, -50)
        slab('back', white, 100, 50, 0.1, -50, 0, -50.1)
        slab('left', red, 0.1, 50, 100, -50.1, 0, -50)
        slab('right', white, 0.1, 50, 100, 50, 0, -50)
        slab('shelf', red, 30, 10, 30, -30, 30, -30)
        ceiling = gr.cube('ceiling') ceiling:set_material(white) root:add_child(ceiling)
        {ceiling}
        ball = gr.sphere('ball') ball:scale(10, 10, 10) ball:translate(-15, 10, -10)
        ball:set_material(white) root:add_child(ball)
        {glass}
        l = {light}
        gr.render(root, 'room.png', 96, 96, {{0, 25, 110}}, {{0, -0.3, -1}}, {{0, 1, 0}}, 40,
                  {{0.1, 0.1, 0.1}}, {{l}}, {{aa = 'none'}})
        "
    )
}

/// The flattened scene of [`light_on_surface_source`].
pub fn light_on_surface_scene(case: LightOnSurface, off: f64) -> FlatScene {
    let source = light_on_surface_source(case, off);
    let mut out = None;
    run_scene_source(
        "room.lua",
        &source,
        std::path::Path::new("."),
        &ScriptConfig::default(),
        &mut |graph, request| {
            out = Some(flatten(graph, request)?);
            Ok(())
        },
    )
    .unwrap_or_else(|e| panic!("{e}\n{source}"));
    out.expect("the room renders once")
}

/// Speckle of `film` against `reference` (the light moved slightly off the surface):
/// (share of pixels more than 16/255 darker in luminance, share of pixels that are so and
/// isolated: no 4-neighbour of them also darker by that much).
pub fn speckle(film: &Film, reference: &Film) -> (f64, f64) {
    let luminance = |f: &Film, x: u32, y: u32| {
        let [r, g, b] = f.get(x, y);
        0.2126 * r.clamp(0.0, 1.0) + 0.7152 * g.clamp(0.0, 1.0) + 0.0722 * b.clamp(0.0, 1.0)
    };
    let dark = |x: i64, y: i64| {
        x >= 0
            && y >= 0
            && x < film.width as i64
            && y < film.height as i64
            && luminance(reference, x as u32, y as u32) - luminance(film, x as u32, y as u32)
                > 16.0 / 255.0
    };
    let (mut darker, mut isolated) = (0usize, 0usize);
    for y in 0..film.height as i64 {
        for x in 0..film.width as i64 {
            if dark(x, y) {
                darker += 1;
                let neighbours = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)];
                if !neighbours.iter().any(|&(a, b)| dark(a, b)) {
                    isolated += 1;
                }
            }
        }
    }
    let n = (film.width * film.height) as f64;
    (darker as f64 / n, isolated as f64 / n)
}
