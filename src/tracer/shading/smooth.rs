//! Smooth shading of meshes with vertex normals (Phong normal interpolation): the
//! shading normal of a hit on a smooth triangle ([`smooth_normal`]), and the terminator
//! rule that keeps it on the side the viewer sees ([`visible_normal`]). Only scenes with
//! the SMOOTH feature call them; the geometric normal (`Surface::normal`) still decides
//! the side a ray is on and where secondary rays start. A smooth dielectric refracts by
//! the interpolated normal ([`smooth_interface`]) unless that would send the ray back
//! across its facet.
//!
//! The terminator rule follows Keller et al., "The Iray light transport simulation and
//! rendering system" (2017), on local shading normals: an interpolated normal may lean so
//! far that the viewer sees the surface from behind it (N·V < 0: the facet would shade as
//! unlit, black) or that the view reflected about it points into the surface (a mirror
//! would show the mesh's inside). Where the reflected view leaves the visible side at less
//! than `SMOOTH_MIN_REFLECTION_COSINE` to the geometric normal, the reflection is lifted to
//! exactly that cosine in the plane it spans with the geometric normal, and the shading
//! normal becomes the half vector between the view and the lifted reflection (the normal
//! that reflects one into the other). Elsewhere the interpolated normal is left alone, so
//! the bend shows only in a thin band along silhouettes.

use super::dielectric::{
    dielectric_interface, refract_direction, schlick_reflectance, surface_sides, Interface,
    MediumStack,
};
use super::surface::Surface;
use crate::constants::{KIND_MESH, SMOOTH_MIN_REFLECTION_COSINE};
use crate::pack::{load_instance, load_triangle_normals, PackedScene};
use crate::tracer::traversal::hit::Hit;
use glam::Vec3;

/// The shading normal at `hit` on surface `s`: on a mesh triangle with vertex normals,
/// the corners' normals interpolated with the hit's barycentrics, mapped to world space
/// through the transpose of world→object, normalised and turned to the side of the
/// geometric normal `s.normal` (so a mesh whose normals disagree with its winding shades
/// the same); `s.normal` itself elsewhere, on flat triangles, and where the interpolated
/// normals cancel out (no direction).
// Mirror of src/tracer/shading/smooth.wgsl::smooth_normal — change both.
pub fn smooth_normal(scene: &PackedScene, hit: &Hit, s: &Surface) -> Vec3 {
    let inst = load_instance(scene, hit.item);
    if inst.kind != KIND_MESH {
        return s.normal;
    }
    let corners = load_triangle_normals(scene, hit.part);
    let n0 = Vec3::from(corners.n0);
    // Packing zeroes every corner of a flat triangle.
    if n0 == Vec3::ZERO {
        return s.normal;
    }
    let b0 = 1.0 - hit.b1 - hit.b2;
    let n_obj = n0 * b0 + Vec3::from(corners.n1) * hit.b1 + Vec3::from(corners.n2) * hit.b2;
    let w2o = &inst.world_to_object;
    let row = |r: &[f32; 4]| Vec3::new(r[0], r[1], r[2]);
    let n = row(&w2o[0]) * n_obj.x + row(&w2o[1]) * n_obj.y + row(&w2o[2]) * n_obj.z;
    let length = n.length();
    // The negated test also rejects NaN and ∞.
    if !(length > 0.0 && length < f32::MAX) {
        return s.normal;
    }
    let n = n / length;
    if n.dot(s.normal) < 0.0 {
        -n
    } else {
        n
    }
}

/// The terminator rule (module header): the shading normal `n`, already on the viewer's
/// side of the geometric normal `facing`, for a viewer in the unit direction `v`; bent
/// towards `facing` where the view reflected about `n` would leave the visible side at
/// less than `SMOOTH_MIN_REFLECTION_COSINE` (which includes every `n` facing away from
/// the viewer). `facing` itself where nothing finite comes out.
// Mirror of src/tracer/shading/smooth.wgsl::visible_normal — change both.
pub fn visible_normal(n: Vec3, facing: Vec3, v: Vec3) -> Vec3 {
    let r = n * (2.0 * n.dot(v)) - v;
    let above = r.dot(facing);
    if above >= SMOOTH_MIN_REFLECTION_COSINE {
        return n;
    }
    // The reflection's part along the surface, kept; its height set to the minimum.
    let along = r - facing * above;
    let along_length = along.length();
    let c = SMOOTH_MIN_REFLECTION_COSINE;
    let lifted = if along_length > 0.0 {
        facing * c + along * ((1.0 - c * c).sqrt() / along_length)
    } else {
        facing
    };
    let bent = (v + lifted).normalize();
    if bent.is_finite() {
        bent
    } else {
        facing
    }
}

/// [`dielectric_interface`] with the shading normal `shading` (from [`smooth_normal`], on
/// the side of the geometric normal `normal`): the sides and media from the geometric
/// normal, the Fresnel share and the refracted direction from the shading one, which
/// bends them smoothly across a smooth glass mesh. Where that direction would not cross
/// the facet (it leans back out, near the terminator), the facet's own refraction.
// Mirror of src/tracer/shading/smooth.wgsl::smooth_interface — change both.
pub fn smooth_interface(
    dir: Vec3,
    normal: Vec3,
    shading: Vec3,
    ior: f32,
    media: &MediumStack,
) -> Interface {
    let sides = surface_sides(dir, normal, ior, media);
    let n = if shading.dot(sides.n) < 0.0 {
        -shading
    } else {
        shading
    };
    let cos_incident = (-n.dot(dir)).clamp(0.0, 1.0);
    let reflectance = schlick_reflectance(cos_incident, sides.n1, sides.n2);
    match refract_direction(dir, n, sides.n1 / sides.n2) {
        // refract_direction and schlick_reflectance decide TIR from the same sin²θt.
        None => Interface {
            reflectance: 1.0,
            dir,
            media: sides.beyond,
        },
        Some(t) if t.dot(sides.n) < 0.0 => Interface {
            reflectance,
            dir: t,
            media: sides.beyond,
        },
        Some(_) => dielectric_interface(dir, normal, ior, media),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit vector from two numbers in [0, 1) (uniform on the sphere).
    fn unit(a: f32, b: f32) -> Vec3 {
        let z = 2.0 * a - 1.0;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = std::f32::consts::TAU * b;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// The rule over random normals and views, grazing ones included (views down to
    /// cos 10⁻⁶ from the surface): the result is a unit normal the viewer sees (n·v > 0,
    /// on the visible side of the facet), the view reflected about it leaves the surface
    /// at the minimum cosine or more (less f32 rounding: where the view and the lifted
    /// reflection are nearly opposite, their half vector is the normalised difference of
    /// near-opposite vectors, a few 10⁻⁵ off), and a normal that already did so is kept
    /// bit for bit.
    #[test]
    fn visible_normals_reflect_the_view_out_of_the_surface() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut random = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let facing = Vec3::Z;
        let (mut bent, mut kept) = (0, 0);
        for i in 0..100_000 {
            let mut n = unit(random(), random());
            n.z = n.z.abs();
            let mut v = unit(random(), random());
            v.z = v.z.abs();
            if i % 4 == 0 {
                // Grazing views: cosines from 10⁻⁶ to 10⁻².
                v.z = 10f32.powf(-6.0 + 4.0 * random());
                v = v.normalize();
            }
            let out = visible_normal(n, facing, v);
            assert!((out.length() - 1.0).abs() < 1e-5, "{n} {v}: {out}");
            assert!(out.dot(v) > 0.0, "{n} {v}: {out} faces away");
            assert!(out.dot(facing) > 0.0, "{n} {v}: {out} below the facet");
            let r = out * (2.0 * out.dot(v)) - v;
            assert!(
                r.dot(facing) >= SMOOTH_MIN_REFLECTION_COSINE - 1e-4,
                "{n} {v}: reflection {r} into the surface"
            );
            if out == n {
                kept += 1;
            } else {
                bent += 1;
                let before = n * (2.0 * n.dot(v)) - v;
                assert!(before.dot(facing) < SMOOTH_MIN_REFLECTION_COSINE, "{n} {v}");
            }
        }
        assert!(bent > 10_000 && kept > 10_000, "bent {bent}, kept {kept}");
    }
}
