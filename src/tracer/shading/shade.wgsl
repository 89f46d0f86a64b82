// shade.wgsl — A4 Phong shading with shadow rays, and the background or the environment
// map (the surfaces it shades come from surface.wgsl).

// Set when an area light reaches a shaded point through some of its shadow samples but
// not all (a penumbra; the CPU's TraversalCounters::partial_light); pixel_sample.wgsl's
// hinted_sample clears it before a sample and reads it after.
var<private> fine_detail_seen: bool;

// base^exponent for base in [0, 1] without NaN or overflow for any exponent ≥ 0
// (shininess can be 5e7): zero unless base > 0.
// Mirror of src/tracer/shading/shade.rs::phong_power — change both.
fn phong_power(base: f32, exponent: f32) -> f32 {
    if base > 0.0 {
        return exp2(exponent * log2(min(base, 1.0)));
    }
    return 0.0;
}

// A shaded point as its lights see it: the surface, its Phong colours, the normal facing
// the viewer and the direction to the viewer (what each light point's term reads).
// Mirror of src/tracer/shading/shade.rs::LitPoint — change both.
struct LitPoint {
    s: Surface,
    phong: Phong,
    n: vec3<f32>,
    v: vec3<f32>,
}

// A4 lighting at a surface point: kd·ambient plus, for each light a shadow ray reaches,
// (kd·max(0,N·L) + ks·max(0,R·V)^shininess)·I/(c0 + c1·d + c2·d²). n faces the viewer;
// v points to the viewer. An area light is n×n such point lights, one jittered point per
// stratum of its parallelogram (random numbers from seed), each with 1/n² of its colour.
// Mirror of src/tracer/shading/shade.rs::shade_phong — change both.
fn shade_phong(s: Surface, n: vec3<f32>, v: vec3<f32>, seed: SampleSeed) -> vec3<f32> {
    let m = load_material(s.material);
    var phong = Phong(m.kd, m.ks);
// #if TEXTURE
    phong = surface_colours(m, s);
// #endif
    let lit = LitPoint(s, phong, n, v);
    var colour = phong.kd * globals.ambient;
    let origin = offset_ray(s.p, n, s.magnitude);
    for (var i = 0u; i < globals.num_lights; i++) {
        let light = load_light(i);
// #if AREA_LIGHT
        if light.kind == LIGHT_AREA {
            colour += area_light(lit, origin, light, i, seed);
            continue;
        }
// #endif
        colour += point_light(lit, origin, light.position, light);
    }
    return colour;
}

// Light from a point at `position` with light's colour and falloff: the A4 term, or zero
// when the point is behind the surface or a shadow ray from origin is blocked (dimmed
// instead by the glass it crosses, in scenes with refraction) before shadow_reach, just
// short of the light.
// Mirror of src/tracer/shading/shade.rs::point_light — change both.
fn point_light(lit: LitPoint, origin: vec3<f32>, position: vec3<f32>, light: PackedLight) -> vec3<f32> {
    // Lights behind the surface (as seen from the viewer's side) add nothing.
    let term = unshadowed_term(lit, position, light);
    if term.w == 0.0 {
        return vec3<f32>(0.0);
    }
    let s = lit.s;
    // With dielectrics, light passes through glass, dimmed (see dielectric.wgsl).
// #if REFRACTION
    let transmittance = shadow_transmittance(origin, position, s.magnitude);
// #else
    var transmittance = 1.0;
    if shadow_blocked(origin, position, s.magnitude) {
        transmittance = 0.0;
    }
// #endif
    return shadowed_term(term.xyz, transmittance);
}

// point_light's A4 term before its shadow ray, (kd·N·L + ks·spec)·I·attenuation, in w 1;
// w 0 where the light point is behind the surface (N·L ≤ 0 or NaN: no shadow ray, the
// light adds zero). The hardware variant's shade pass computes the same term and leaves
// the shadow ray to its shadow pass, which finishes it with shadowed_term as point_light
// does (their Rust twins say where).
// Mirror of src/tracer/shading/shade.rs::unshadowed_term — change both.
fn unshadowed_term(lit: LitPoint, position: vec3<f32>, light: PackedLight) -> vec4<f32> {
    let s = lit.s;
    let n = lit.n;
    let m = load_material(s.material);
    let to_light = position - s.p;
    let distance = length(to_light);
    let l = to_light / distance;
    let n_dot_l = dot(n, l);
    if !(n_dot_l > 0.0) {
        return vec4<f32>(0.0);
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(dot(r, lit.v), m.shininess);
    let c0 = light.falloff.x;
    let c1 = light.falloff.y;
    let c2 = light.falloff.z;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    return vec4<f32>((lit.phong.kd * n_dot_l + lit.phong.ks * specular) * light.colour * attenuation, 1.0);
}

// A light point's term once its shadow ray is traced: zero where nothing gets through
// (transmittance ≤ 0: a blocked ray), else term × transmittance (point_light's last
// product, and the hardware variant's shadow pass's).
// Mirror of src/tracer/shading/shade.rs::shadowed_term — change both.
fn shadowed_term(term: vec3<f32>, transmittance: f32) -> vec3<f32> {
    if transmittance <= 0.0 {
        return vec3<f32>(0.0);
    }
    return term * transmittance;
}

// Whether anything blocks the shadow ray from origin to a light at position before
// shadow_reach (magnitude: the shaded surface's), just short of the light, so that a
// surface through the light does not speckle.
// Mirror of src/tracer/shading/shade.rs::shadow_blocked — change both.
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
// Mirror of src/tracer/shading/shade.rs::area_light — change both.
fn area_light(lit: LitPoint, origin: vec3<f32>, light: PackedLight, index: u32, seed: SampleSeed) -> vec3<f32> {
    let k = light.samples;
    let scale = 1.0 / f32(k);
    var sum = vec3<f32>(0.0);
    var lit_strata = 0u;
    let stream = shadow_stream(seed, index);
    for (var stratum = 0u; stratum < k * k; stratum++) {
        let a = (f32(stratum % k) + shadow_random(stream, stratum, 0u)) * scale - 0.5;
        let b = (f32(stratum / k) + shadow_random(stream, stratum, 1u)) * scale - 0.5;
        let position = light.position + light.edge_u * a + light.edge_v * b;
        let c = point_light(lit, origin, position, light);
        lit_strata += select(0u, 1u, any(c != vec3<f32>(0.0)));
        sum += c;
    }
    if seed.depth == 0u && lit_strata > 0u && lit_strata < k * k {
        fine_detail_seen = true;
    }
    return sum * (scale * scale);
}
// #endif

// Colour of a ray that hits nothing: the environment map where the scene has one,
// else the vertical gradient by direction (solid when top = bottom), "up" being the
// camera's up.
// Mirror of src/tracer/shading/shade.rs::background — change both.
fn background(dir: vec3<f32>) -> vec3<f32> {
// #if ENVIRONMENT
    return environment(dir);
// #else
    let t = 0.5 * (dot(dir, globals.up) + 1.0);
    return globals.background_bottom * (1.0 - t) + globals.background_top * t;
// #endif
}
