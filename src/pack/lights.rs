//! Lights packed: point and area lights, their attenuation checked and their shadow
//! sample counts settled.

use super::layout::PackedLight;
use super::PackError;
use crate::constants::{LIGHT_AREA, LIGHT_POINT};
use crate::scene::flatten::FlatScene;

/// The scene's lights as the tracers read them; an attenuation that is zero or
/// negative at some distance is an error.
pub(super) fn pack_lights(scene: &FlatScene) -> Result<Vec<PackedLight>, PackError> {
    let shadow_samples = scene.options.shadow_samples;
    scene
        .lights
        .iter()
        .enumerate()
        .map(|(index, l)| {
            let [c0, c1, c2] = l.falloff;
            if c0 < 0.0 || c1 < 0.0 || c2 < 0.0 || c0 + c1 + c2 <= 0.0 {
                return Err(PackError::BadFalloff {
                    index,
                    falloff: l.falloff,
                });
            }
            let (kind, samples, edge_u, edge_v) = match &l.area {
                None => (LIGHT_POINT, 1, [0.0; 3], [0.0; 3]),
                Some(a) => (
                    LIGHT_AREA,
                    shadow_samples.unwrap_or(a.samples).get(),
                    a.u.as_vec3().to_array(),
                    a.v.as_vec3().to_array(),
                ),
            };
            Ok(PackedLight {
                position: l.position.as_vec3().to_array(),
                kind,
                colour: l.colour,
                samples,
                falloff: l.falloff,
                _pad0: 0,
                edge_u,
                _pad1: 0,
                edge_v,
                _pad2: 0,
            })
        })
        .collect::<Result<Vec<_>, _>>()
}
