//! `gr.checker`, `gr.noise`, `gr.marble` and `gr.wood`: procedural textures, values a
//! material's `set_diffuse`, `set_specular` and `set_bump` take in place of an image
//! file (`maps`). What they compute: `tracer::shading::procedural`.

use super::args::Args;
use super::handle_types::ProceduralHandle;
use super::unknown::unknown_method;
use crate::constants::PROCEDURAL_MAX_OCTAVES;
use crate::scene::{Procedural, ProceduralKind};
use mlua::{MetaMethod, UserData, UserDataMethods};

/// `gr.marble`'s turbulence and octaves when not given.
pub const MARBLE_DEFAULTS: (f64, u32) = (4.0, 4);
/// `gr.wood`'s turbulence and octaves when not given.
pub const WOOD_DEFAULTS: (f64, u32) = (0.3, 2);

/// `gr.checker(c1, c2, size)`: cubes of side `size` in the primitive's own space, `c1`
/// where ⌊x/size⌋ + ⌊y/size⌋ + ⌊z/size⌋ is even.
pub(super) fn checker(a: &Args) -> mlua::Result<ProceduralHandle> {
    let (c1, c2) = (a.colour(1, "c1")?, a.colour(2, "c2")?);
    let size = a.positive(3, "size")? as f32;
    Ok(ProceduralHandle(Procedural {
        kind: ProceduralKind::Checker,
        c1,
        c2,
        scale: size,
        octaves: 1,
        turbulence: 0.0,
    }))
}

/// `gr.noise(c1, c2, scale[, octaves])`: fBm of Perlin's improved noise at the point ×
/// `scale` (octaves default 1), mapped to [0, 1], blending `c1` → `c2`.
pub(super) fn noise(a: &Args) -> mlua::Result<ProceduralHandle> {
    let (c1, c2) = (a.colour(1, "c1")?, a.colour(2, "c2")?);
    let scale = a.positive(3, "scale")? as f32;
    let octaves = octaves(a, 4, 1)?;
    Ok(ProceduralHandle(Procedural {
        kind: ProceduralKind::Noise,
        c1,
        c2,
        scale,
        octaves,
        turbulence: 0.0,
    }))
}

/// `gr.marble(c1, c2, scale[, turbulence[, octaves]])`: veins across object x.
pub(super) fn marble(a: &Args) -> mlua::Result<ProceduralHandle> {
    turbulent(a, ProceduralKind::Marble, MARBLE_DEFAULTS)
}

/// `gr.wood(c1, c2, scale[, turbulence[, octaves]])`: rings around object z.
pub(super) fn wood(a: &Args) -> mlua::Result<ProceduralHandle> {
    turbulent(a, ProceduralKind::Wood, WOOD_DEFAULTS)
}

/// Marble and wood: colours, scale, then turbulence and octaves (defaults `defaults`).
fn turbulent(
    a: &Args,
    kind: ProceduralKind,
    defaults: (f64, u32),
) -> mlua::Result<ProceduralHandle> {
    let (c1, c2) = (a.colour(1, "c1")?, a.colour(2, "c2")?);
    let scale = a.positive(3, "scale")? as f32;
    let turbulence = if a.is_nil(4) {
        defaults.0
    } else {
        a.non_negative(4, "turbulence")?
    };
    let octaves = octaves(a, 5, defaults.1)?;
    Ok(ProceduralHandle(Procedural {
        kind,
        c1,
        c2,
        scale,
        octaves,
        turbulence: turbulence as f32,
    }))
}

/// Argument `n`, octaves: an integer from 1 to `PROCEDURAL_MAX_OCTAVES`, `default` if nil.
fn octaves(a: &Args, n: usize, default: u32) -> mlua::Result<u32> {
    if a.is_nil(n) {
        return Ok(default);
    }
    a.positive_int(n, "octaves", PROCEDURAL_MAX_OCTAVES)
}

impl UserData for ProceduralHandle {
    fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
        methods.add_meta_method(MetaMethod::ToString, |_, this, ()| Ok(this.describe()));
        // Without it Lua would report `attempt to index a ProceduralHandle value`.
        methods.add_meta_function(
            MetaMethod::Index,
            |lua, (_this, key): (mlua::AnyUserData, mlua::Value)| -> mlua::Result<()> {
                Err(unknown_method(lua, "a procedural texture", &key, &[]))
            },
        );
    }
}
