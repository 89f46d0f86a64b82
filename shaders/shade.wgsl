// shade.wgsl — surface reconstruction at a hit, A4 Phong shading with shadow rays, and the
// background.

// Set when an area light reaches a shaded point through some of its shadow samples but
// not all (a penumbra; the CPU's TraversalCounters::partial_light); render.wgsl's
// penumbra_sample clears it before a sample and reads it after.
var<private> fine_detail_seen: bool;

// What shading needs to know about a hit point.
// Mirror of src/cpu/surface.rs::Surface — change both.
struct Surface {
    // World-space point, reprojected onto the surface.
    p: vec3<f32>,
    // Unit geometric normal in world space (outward for analytic primitives, by winding
    // for triangles; not yet turned towards the viewer).
    normal: vec3<f32>,
    // Largest coordinate magnitude that went into p (for offset_ray).
    magnitude: f32,
    material: u32,
    // Texture coordinates (conventions in src/cpu/uv.rs; zero on triangles of scenes
    // without textures or bump maps, which pack no triangle UVs).
    uv: vec2<f32>,
    // World-space ∂p/∂u and ∂p/∂v (the tangent frame of bump mapping; unnormalised).
    dpdu: vec3<f32>,
    dpdv: vec3<f32>,
    // Width, in uv, of the patch one pixel covers here (texture.wgsl::texture_footprint):
    // the texture filter's footprint. surface_at leaves it 0; tracing sets it in scenes
    // with textures or bump maps.
    footprint: f32,
}

// The Phong colours at a shading point (the material's, or its textures' at the UV).
// Mirror of src/cpu/surface.rs::Phong — change both.
struct Phong {
    kd: vec3<f32>,
    ks: vec3<f32>,
}

// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// Largest |entry| sum over the rows of an affine 3×4 matrix: bounds the magnitude of the
// world coordinates it produces from a point in the unit box.
// Mirror of src/cpu/surface.rs::affine_magnitude — change both.
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
// Mirror of src/cpu/surface.rs::instance_surface — change both.
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
    return Surface(p, normal, magnitude, inst.material, s.uv, dpdu, dpdv, 0.0);
}
// #endif

// #if CSG
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// The surface of a CSG hit: that of the leaf it lies on (point, material), the normal
// negated on a subtracted operand's surface, which bounds the result from the other side.
// Mirror of src/cpu/surface.rs::csg_surface — change both.
fn csg_surface(ray: Ray, hit: Hit) -> Surface {
    var s = instance_surface(load_instance(hit.part & CSG_INDEX_MASK), ray, hit.t);
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
// Mirror of src/cpu/surface.rs::mapped_magnitude — change both.
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
// Mirror of src/cpu/surface.rs::mesh_surface — change both.
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
    return Surface(p, normal, mapped_magnitude(o2w, magnitude_obj), inst.material, uv, world_dpdu, world_dpdv, 0.0);
}
// #endif

// The surface at a hit: an analytic instance's, a CSG object's or a mesh triangle's.
// Mirror of src/cpu/surface.rs::surface_at — change both.
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
    return instance_surface(inst, ray, hit.t);
// #else
    return Surface();
// #endif
}

// base^exponent for base in [0, 1] without NaN or overflow for any exponent ≥ 0
// (shininess can be 5e7): zero unless base > 0.
// Mirror of src/cpu/shade.rs::phong_power — change both.
fn phong_power(base: f32, exponent: f32) -> f32 {
    if base > 0.0 {
        return exp2(exponent * log2(min(base, 1.0)));
    }
    return 0.0;
}

// A4 lighting at a surface point: kd·ambient plus, for each light a shadow ray reaches,
// (kd·max(0,N·L) + ks·max(0,R·V)^shininess)·I/(c0 + c1·d + c2·d²). n faces the viewer;
// v points to the viewer. An area light is n×n such point lights, one jittered point per
// stratum of its parallelogram (random numbers from seed), each with 1/n² of its colour.
// Mirror of src/cpu/shade.rs::shade_phong — change both.
fn shade_phong(s: Surface, n: vec3<f32>, v: vec3<f32>, seed: SampleSeed) -> vec3<f32> {
    let m = load_material(s.material);
    var phong = Phong(m.kd, m.ks);
// #if TEXTURE
    phong = surface_colours(m, s);
// #endif
    var colour = phong.kd * globals.ambient;
    let origin = offset_ray(s.p, n, s.magnitude);
    for (var i = 0u; i < globals.num_lights; i++) {
        let light = load_light(i);
// #if AREA_LIGHT
        if light.kind == LIGHT_AREA {
            colour += area_light(s, phong, n, v, origin, light, i, seed);
            continue;
        }
// #endif
        colour += point_light(s, phong, n, v, origin, light.position, light);
    }
    return colour;
}

// Light from a point at `position` with light's colour and falloff: the A4 term, or zero
// when the point is behind the surface or a shadow ray from origin is blocked (dimmed
// instead by the glass it crosses, in scenes with refraction) before shadow_reach, just
// short of the light.
// Mirror of src/cpu/shade.rs::point_light — change both.
fn point_light(s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, origin: vec3<f32>, position: vec3<f32>, light: PackedLight) -> vec3<f32> {
    let m = load_material(s.material);
    let to_light = position - s.p;
    let distance = length(to_light);
    let l = to_light / distance;
    let n_dot_l = dot(n, l);
    // Lights behind the surface (as seen from the viewer's side) add nothing; the negated
    // test also rejects NaN, like Rust's is_nan check.
    if !(n_dot_l > 0.0) {
        return vec3<f32>(0.0);
    }
    // With dielectrics, light passes through glass, dimmed (see dielectric.wgsl).
// #if REFRACTION
    let transmittance = shadow_transmittance(origin, position, s.magnitude);
// #else
    var transmittance = 1.0;
    if shadow_blocked(origin, position, s.magnitude) {
        transmittance = 0.0;
    }
// #endif
    if transmittance <= 0.0 {
        return vec3<f32>(0.0);
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(dot(r, v), m.shininess);
    let c0 = light.falloff.x;
    let c1 = light.falloff.y;
    let c2 = light.falloff.z;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    return (phong.kd * n_dot_l + phong.ks * specular) * light.colour * attenuation * transmittance;
}

// Whether anything blocks the shadow ray from origin to a light at position before
// shadow_reach (magnitude: the shaded surface's), just short of the light, so that a
// surface through the light does not speckle.
// Mirror of src/cpu/shade.rs::shadow_blocked — change both.
fn shadow_blocked(origin: vec3<f32>, position: vec3<f32>, magnitude: f32) -> bool {
    let shadow_dir = position - origin;
    let shadow_distance = length(shadow_dir);
    let shadow_ray = Ray(origin, shadow_dir / shadow_distance);
    let reach = shadow_reach(origin, position, shadow_distance, magnitude);
    return any_hit(shadow_ray, reach);
}

// #if AREA_LIGHT
// Light from area light number `index`: the mean of point_light over one jittered point
// in each of the n×n strata of its parallelogram, stratum k = (k mod n, k div n); sets
// fine_detail_seen when some of those points light it and others do not, at the first hit of
// a camera ray only (seed.depth 0; see the twin for why).
// Mirror of src/cpu/shade.rs::area_light — change both.
fn area_light(s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, origin: vec3<f32>, light: PackedLight, index: u32, seed: SampleSeed) -> vec3<f32> {
    let k = light.samples;
    let scale = 1.0 / f32(k);
    var sum = vec3<f32>(0.0);
    var lit = 0u;
    let stream = shadow_stream(seed, index);
    for (var stratum = 0u; stratum < k * k; stratum++) {
        let a = (f32(stratum % k) + shadow_random(stream, stratum, 0u)) * scale - 0.5;
        let b = (f32(stratum / k) + shadow_random(stream, stratum, 1u)) * scale - 0.5;
        let position = light.position + light.edge_u * a + light.edge_v * b;
        let c = point_light(s, phong, n, v, origin, position, light);
        lit += select(0u, 1u, any(c != vec3<f32>(0.0)));
        sum += c;
    }
    if seed.depth == 0u && lit > 0u && lit < k * k {
        fine_detail_seen = true;
    }
    return sum * (scale * scale);
}
// #endif

// Colour of a ray that hits nothing: the vertical gradient by direction (solid when
// top = bottom), "up" being the camera's up.
// Mirror of src/cpu/shade.rs::background — change both.
fn background(dir: vec3<f32>) -> vec3<f32> {
    let t = 0.5 * (dot(dir, globals.up) + 1.0);
    return globals.background_bottom * (1.0 - t) + globals.background_top * t;
}
