// surface.wgsl — surface reconstruction at a hit (surface_at: point, normal, material, UV
// and tangent frame) and the Phong colours there: what texturing, dielectrics and
// shading read about a hit point.

// What shading needs to know about a hit point.
// Mirror of src/tracer/shading/surface.rs::Surface — change both.
struct Surface {
    // World-space point, reprojected onto the surface.
    p: vec3<f32>,
    // Unit geometric normal in world space (outward for analytic primitives, by winding
    // for triangles; not yet turned towards the viewer).
    normal: vec3<f32>,
    // Largest coordinate magnitude that went into p (for offset_ray).
    magnitude: f32,
    material: u32,
    // Texture coordinates (conventions in src/tracer/geometry/uv.rs; zero on triangles of scenes
    // without textures or bump maps, which pack no triangle UVs).
    uv: vec2<f32>,
    // World-space ∂p/∂u and ∂p/∂v (the tangent frame of bump mapping; unnormalised).
    dpdu: vec3<f32>,
    dpdv: vec3<f32>,
    // Width, in uv, of the patch one pixel covers here (texture.wgsl::texture_footprint):
    // the texture filter's footprint. surface_at leaves it 0; tracing sets it in scenes
    // with textures or bump maps.
    footprint: f32,
// #if PROCEDURAL
    // The point in the primitive's own space (the mesh's for a triangle, the leaf's for
    // CSG), where procedural textures are evaluated.
    p_object: vec3<f32>,
    // The instance whose object space p_object is in.
    instance: u32,
    // Width, in world units, of the patch one pixel covers here (texture.wgsl::
    // pixel_footprint): 0 from surface_at; tracing sets it.
    world_footprint: f32,
// #endif
}

// The Phong colours at a shading point (the material's, or its textures' at the UV).
// Mirror of src/tracer/shading/surface.rs::Phong — change both.
struct Phong {
    kd: vec3<f32>,
    ks: vec3<f32>,
}

// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// Largest |entry| sum over the rows of an affine 3×4 matrix: bounds the magnitude of the
// world coordinates it produces from a point in the unit box.
// Mirror of src/tracer/shading/surface.rs::affine_magnitude — change both.
fn affine_magnitude(rows: array<vec4<f32>, 3>) -> f32 {
    var m = 0.0;
    for (var i = 0u; i < 3u; i++) {
        let r = abs(rows[i]);
        m = max(m, r.x + r.y + r.z + r.w);
    }
    return m;
}

// Point, normal and magnitude of an instance hit, computed in object space (where the
// point is snapped onto the exact surface) and mapped to world space.
// Mirror of src/tracer/shading/surface.rs::instance_surface — change both.
fn instance_surface(inst: PackedInstance, ray: Ray, t: f32) -> Surface {
    let local = to_object_space(inst, ray.origin, ray.dir);
    let p_hit = local.origin + local.dir * t;
    // Every kind snaps the point onto its surface; an unknown kind (none) leaves it.
    var s = ObjectSurface(p_hit, vec3<f32>(0.0), vec2<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
// #if CYLINDER
    if inst.kind == KIND_CYLINDER {
        s = cylinder_surface(p_hit);
    }
// #endif
// #if CONE
    if inst.kind == KIND_CONE {
        s = cone_surface(p_hit, inst.params.x, inst.params.y);
    }
// #endif
// #if SPHERE
    if inst.kind == KIND_SPHERE {
        s = sphere_surface(p_hit);
    }
// #endif
// #if TORUS
    if inst.kind == KIND_TORUS {
        s = torus_surface(p_hit, inst.params.x, inst.params.y);
    }
// #endif
// #if CUBE
    if inst.kind == KIND_CUBE {
        s = cube_surface(p_hit);
    }
// #endif
    let p_obj = s.p;
    let n_obj = s.normal;
    let o2w = inst.object_to_world;
    let p = vec3<f32>(
        dot(o2w[0].xyz, p_obj) + o2w[0].w,
        dot(o2w[1].xyz, p_obj) + o2w[1].w,
        dot(o2w[2].xyz, p_obj) + o2w[2].w,
    );
    // Normals transform by the inverse transpose: Σ n_obj[i] · (row i of world→object).
    let w2o = inst.world_to_object;
    let normal = normalize(w2o[0].xyz * n_obj.x + w2o[1].xyz * n_obj.y + w2o[2].xyz * n_obj.z);
    // Object points may lie beyond the unit box (a torus reaches rin + rout).
    let magnitude = affine_magnitude(o2w) * max(max_element(abs(p_obj)), 1.0);
    // Tangents transform like directions: the linear part of object→world.
    let dpdu = vec3<f32>(dot(o2w[0].xyz, s.dpdu), dot(o2w[1].xyz, s.dpdu), dot(o2w[2].xyz, s.dpdu));
    let dpdv = vec3<f32>(dot(o2w[0].xyz, s.dpdv), dot(o2w[1].xyz, s.dpdv), dot(o2w[2].xyz, s.dpdv));
// #if PROCEDURAL
    return Surface(p, normal, magnitude, inst.material, s.uv, dpdu, dpdv, 0.0, p_obj, 0u, 0.0);
// #else
    return Surface(p, normal, magnitude, inst.material, s.uv, dpdu, dpdv, 0.0);
// #endif
}
// #endif

// #if CSG
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// The surface of a CSG hit: that of the leaf it lies on (point, material), the normal
// negated on a subtracted operand's surface, which bounds the result from the other side.
// Mirror of src/tracer/shading/surface.rs::csg_surface — change both.
fn csg_surface(ray: Ray, hit: Hit) -> Surface {
    var s = instance_surface(load_instance(hit.part & CSG_INDEX_MASK), ray, hit.t);
// #if PROCEDURAL
    s.instance = hit.part & CSG_INDEX_MASK;
// #endif
    if (hit.part & CSG_FLIP) != 0u {
        s.normal = -s.normal;
    }
    return s;
}
// #endif
// #endif

// #if MESH
// Largest world coordinate magnitude an affine map (rows) gives a point whose coordinates
// are at most `magnitude`: max over rows of Σ|linear|·magnitude + |w| (exactly
// `magnitude` under the identity).
// Mirror of src/tracer/shading/surface.rs::mapped_magnitude — change both.
fn mapped_magnitude(rows: array<vec4<f32>, 3>, magnitude: f32) -> f32 {
    var m = 0.0;
    for (var i = 0u; i < 3u; i++) {
        let r = abs(rows[i]);
        m = max(m, (r.x + r.y + r.z) * magnitude + r.w);
    }
    return m;
}

// The surface of a mesh hit: triangle hit.part of the instance's mesh at the hit's
// barycentrics, computed in the mesh's space and mapped to world space (point and
// tangents through object→world, the normal through the transpose of world→object).
// Mirror of src/tracer/shading/surface.rs::mesh_surface — change both.
fn mesh_surface(inst: PackedInstance, hit: Hit) -> Surface {
    let index = hit.part;
    let corners = triangle_vertices(index);
    let p0 = corners[0];
    let p1 = corners[1];
    let p2 = corners[2];
    // The barycentric point is exact to a few ulps of the vertices (unlike o + t·d).
    let b0 = 1.0 - hit.b1 - hit.b2;
    let p_obj = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
    let magnitude_obj = max_element(max(max(abs(p0), abs(p1)), abs(p2)));
    let n_obj = cross(p1 - p0, p2 - p0);
    var uv = vec2<f32>(0.0);
    var dpdu = vec3<f32>(0.0);
    var dpdv = vec3<f32>(0.0);
// #if TEXTURE|BUMP
    // Triangle UVs are packed only for scenes that use them.
    let t = load_triangle_uv(index);
    uv = t.uv0 * b0 + t.uv1 * hit.b1 + t.uv2 * hit.b2;
    let frame = triangle_frame(p0, p1, p2, t.uv0, t.uv1, t.uv2, normalize(n_obj));
    dpdu = frame[0];
    dpdv = frame[1];
// #endif
    let o2w = inst.object_to_world;
    let w2o = inst.world_to_object;
    let normal = normalize(w2o[0].xyz * n_obj.x + w2o[1].xyz * n_obj.y + w2o[2].xyz * n_obj.z);
    let p = vec3<f32>(dot(o2w[0].xyz, p_obj), dot(o2w[1].xyz, p_obj), dot(o2w[2].xyz, p_obj))
        + vec3<f32>(o2w[0].w, o2w[1].w, o2w[2].w);
    let world_dpdu = vec3<f32>(dot(o2w[0].xyz, dpdu), dot(o2w[1].xyz, dpdu), dot(o2w[2].xyz, dpdu));
    let world_dpdv = vec3<f32>(dot(o2w[0].xyz, dpdv), dot(o2w[1].xyz, dpdv), dot(o2w[2].xyz, dpdv));
// #if PROCEDURAL
    return Surface(p, normal, mapped_magnitude(o2w, magnitude_obj), inst.material, uv, world_dpdu, world_dpdv, 0.0, p_obj, hit.item, 0.0);
// #else
    return Surface(p, normal, mapped_magnitude(o2w, magnitude_obj), inst.material, uv, world_dpdu, world_dpdv, 0.0);
// #endif
}
// #endif

// The surface at a hit: an analytic instance's, a CSG object's or a mesh triangle's.
// Mirror of src/tracer/shading/surface.rs::surface_at — change both.
fn surface_at(ray: Ray, hit: Hit) -> Surface {
    let inst = load_instance(hit.item);
// #if MESH
    if inst.kind == KIND_MESH {
        return mesh_surface(inst, hit);
    }
// #endif
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// #if CSG
    if inst.kind == KIND_CSG {
        return csg_surface(ray, hit);
    }
// #endif
// #if PROCEDURAL
    var s = instance_surface(inst, ray, hit.t);
    s.instance = hit.item;
    return s;
// #else
    return instance_surface(inst, ray, hit.t);
// #endif
// #else
    return Surface();
// #endif
}
