// smooth.wgsl — smooth shading of meshes with vertex normals: the interpolated shading
// normal of a hit (smooth_normal) and the terminator rule that keeps it on the side the
// viewer sees (visible_normal); see src/tracer/shading/smooth.rs for the why. Compiled only into
// scenes with the SMOOTH feature.

// #if SMOOTH
// The shading normal at hit on surface s: on a mesh triangle with vertex normals, the
// corners' normals interpolated with the hit's barycentrics, mapped to world space through
// the transpose of world→object, normalised and turned to the side of the geometric normal
// s.normal; s.normal itself elsewhere, on flat triangles, and where the interpolated
// normals cancel out.
// Mirror of src/tracer/shading/smooth.rs::smooth_normal — change both.
fn smooth_normal(hit: Hit, s: Surface) -> vec3<f32> {
    let inst = load_instance(hit.item);
    if inst.kind != KIND_MESH {
        return s.normal;
    }
    let corners = load_triangle_normals(hit.part);
    let n0 = vec3<f32>(corners.n0[0], corners.n0[1], corners.n0[2]);
    // Packing zeroes every corner of a flat triangle.
    if all(n0 == vec3<f32>(0.0)) {
        return s.normal;
    }
    let n1 = vec3<f32>(corners.n1[0], corners.n1[1], corners.n1[2]);
    let n2 = vec3<f32>(corners.n2[0], corners.n2[1], corners.n2[2]);
    let b0 = 1.0 - hit.b1 - hit.b2;
    let n_obj = n0 * b0 + n1 * hit.b1 + n2 * hit.b2;
    let w2o = inst.world_to_object;
    let n = w2o[0].xyz * n_obj.x + w2o[1].xyz * n_obj.y + w2o[2].xyz * n_obj.z;
    let len = length(n);
    // The negated test also rejects NaN and ∞, as the CPU's does.
    if !(len > 0.0 && len < F32_MAX) {
        return s.normal;
    }
    let unit = n / len;
    if dot(unit, s.normal) < 0.0 {
        return -unit;
    }
    return unit;
}

// The terminator rule: the shading normal n, already on the viewer's side of the
// geometric normal facing, for a viewer in the unit direction v; bent towards facing
// where the view reflected about n would leave the visible side at less than
// SMOOTH_MIN_REFLECTION_COSINE. facing itself where nothing finite comes out.
// Mirror of src/tracer/shading/smooth.rs::visible_normal — change both.
fn visible_normal(n: vec3<f32>, facing: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let r = n * (2.0 * dot(n, v)) - v;
    let above = dot(r, facing);
    if above >= SMOOTH_MIN_REFLECTION_COSINE {
        return n;
    }
    // The reflection's part along the surface, kept; its height set to the minimum.
    let along = r - facing * above;
    let along_length = length(along);
    let c = SMOOTH_MIN_REFLECTION_COSINE;
    var lifted = facing;
    if along_length > 0.0 {
        lifted = facing * c + along * (sqrt(1.0 - c * c) / along_length);
    }
    let bent = normalize(v + lifted);
    // The comparison is false for NaN and ∞, like Rust's is_finite.
    if all(abs(bent) <= vec3<f32>(F32_MAX)) {
        return bent;
    }
    return facing;
}

// #if REFRACTION
// dielectric_interface with the shading normal (from smooth_normal, on the side of the
// geometric normal): the sides and media from the geometric normal, the Fresnel share and
// the refracted direction from the shading one; where that direction would not cross the
// facet, the facet's own refraction.
// Mirror of src/tracer/shading/smooth.rs::smooth_interface — change both.
fn smooth_interface(dir: vec3<f32>, normal: vec3<f32>, shading: vec3<f32>, ior: f32, media: MediumStack) -> Interface {
    let sides = surface_sides(dir, normal, ior, media);
    var n = shading;
    if dot(shading, sides.n) < 0.0 {
        n = -shading;
    }
    let cos_incident = clamp(-dot(n, dir), 0.0, 1.0);
    let reflectance = schlick_reflectance(cos_incident, sides.n1, sides.n2);
    let transmitted = refract_direction(dir, n, sides.n1 / sides.n2);
    // refract_direction and schlick_reflectance decide TIR from the same sin²θt.
    if !transmitted.valid {
        return Interface(1.0, dir, sides.beyond);
    }
    if dot(transmitted.dir, sides.n) < 0.0 {
        return Interface(reflectance, transmitted.dir, sides.beyond);
    }
    return dielectric_interface(dir, normal, ior, media);
}
// #endif
// #endif
