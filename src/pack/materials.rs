//! Materials packed, and the features the materials in use need (reflection,
//! refraction, textures, bump maps).

use super::features::SceneFeatures;
use super::layout::PackedMaterial;
use crate::constants::{
    AIR_IOR, MATERIAL_REFLECTIVE, MATERIAL_REFRACTIVE, NO_TEXTURE, PROCEDURAL_TEXTURE,
};
use crate::scene::flatten::{CsgStep, FlatScene};
use crate::scene::DebugView;

/// The scene's materials as the tracers read them.
/// Procedural textures' blocks follow the permutation table at word `procedural_base`
/// of `texels` (`pack::procedural`).
pub(super) fn pack_materials(scene: &FlatScene, procedural_base: u32) -> Vec<PackedMaterial> {
    let slots = super::procedural::slot_indices(&scene.materials, procedural_base, NO_TEXTURE);
    scene
        .materials
        .iter()
        .zip(slots)
        .map(|(m, [diffuse_texture, specular_texture, bump_texture])| {
            let reflective = m.reflection.iter().any(|&c| c > 0.0);
            let refractive = if m.ior.is_some() {
                MATERIAL_REFRACTIVE
            } else {
                0
            };
            PackedMaterial {
                kd: m.kd,
                shininess: m.shininess,
                ks: m.ks,
                flags: if reflective { MATERIAL_REFLECTIVE } else { 0 } | refractive,
                reflection: m.reflection,
                ior: m.ior.unwrap_or(AIR_IOR),
                diffuse_texture,
                specular_texture,
                bump_texture,
                bump_strength: m.bump_strength,
            }
        })
        .collect()
}

/// Which materials some geometry uses (marked in one pass: a scan per material would
/// cost materials × triangles).
fn materials_in_use(scene: &FlatScene, count: usize) -> Vec<bool> {
    let mut in_use = vec![false; count];
    let leaves = scene
        .csg
        .iter()
        .flat_map(|c| &c.program)
        .filter_map(|step| match step {
            CsgStep::Leaf(o) => Some(o.material),
            CsgStep::Op(_) => None,
        });
    for m in scene
        .objects
        .iter()
        .map(|o| o.material)
        .chain(scene.triangles.iter().map(|t| t.material))
        .chain(scene.mesh_instances.iter().map(|m| m.material))
        .chain(leaves)
    {
        if let Some(slot) = in_use.get_mut(m) {
            *slot = true;
        }
    }
    in_use
}

/// The features the materials need; only materials some geometry uses count.
pub(super) fn material_features(scene: &FlatScene, materials: &[PackedMaterial]) -> SceneFeatures {
    let mut features = SceneFeatures::empty();
    let in_use = materials_in_use(scene, materials.len());
    let used = |m: usize| in_use[m];
    if (0..materials.len()).any(|m| materials[m].flags & MATERIAL_REFLECTIVE != 0 && used(m)) {
        features.insert(SceneFeatures::REFLECTION);
    }
    if (0..materials.len()).any(|m| materials[m].flags & MATERIAL_REFRACTIVE != 0 && used(m)) {
        features.insert(SceneFeatures::REFRACTION);
    }
    let textured =
        |m: &PackedMaterial| m.diffuse_texture != NO_TEXTURE || m.specular_texture != NO_TEXTURE;
    // The UV debug view needs the UV code that textures bring.
    if scene.options.debug == DebugView::Uv
        || (0..materials.len()).any(|m| textured(&materials[m]) && used(m))
    {
        features.insert(SceneFeatures::TEXTURE);
    }
    if (0..materials.len()).any(|m| materials[m].bump_texture != NO_TEXTURE && used(m)) {
        features.insert(SceneFeatures::BUMP);
    }
    let procedural = |t: u32| t != NO_TEXTURE && t & PROCEDURAL_TEXTURE != 0;
    if (0..materials.len()).any(|m| {
        let p = &materials[m];
        used(m)
            && [p.diffuse_texture, p.specular_texture, p.bump_texture]
                .into_iter()
                .any(procedural)
    }) {
        features.insert(SceneFeatures::PROCEDURAL);
    }
    features
}
