// procedural.wgsl — procedural (solid) textures: checker, Perlin's improved noise with its
// analytic gradient, fBm, marble and wood, at the hit point in the primitive's own
// coordinates, filtered by the pixel's footprint. Derivations and conventions are in
// src/tracer/shading/procedural.rs; the parameter blocks and the permutation table are
// src/pack/procedural.rs's, in texels.

// #if PROCEDURAL
// Perlin's fade curve, 6t⁵ − 15t⁴ + 10t³, in his reference code's form.
// Mirror of src/tracer/shading/procedural.rs::fade — change both.
fn fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// The fade's derivative, 30t²(t − 1)².
// Mirror of src/tracer/shading/procedural.rs::fade_slope — change both.
fn fade_slope(t: f32) -> f32 {
    let s = t * (t - 1.0);
    return 30.0 * s * s;
}

// a + t·(b − a), the reference code's lerp.
// Mirror of src/tracer/shading/procedural.rs::lerp — change both.
fn lerp(t: f32, a: f32, b: f32) -> f32 {
    return a + t * (b - a);
}

// lerp of vectors.
// Mirror of src/tracer/shading/procedural.rs::lerp_vec3 — change both.
fn lerp_vec3(t: f32, a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return a + (b - a) * t;
}

// The gradient direction Perlin's grad(hash, x, y, z) dots with (x, y, z).
// Mirror of src/tracer/shading/procedural.rs::gradient_direction — change both.
fn gradient_direction(hash: u32) -> vec3<f32> {
    let h = hash & 15u;
    let su = select(-1.0, 1.0, (h & 1u) == 0u);
    let sv = select(-1.0, 1.0, (h & 2u) == 0u);
    var g = vec3<f32>(0.0);
    if h < 8u {
        g.x = su;
    } else {
        g.y = su;
    }
    if h < 4u {
        g.y = sv;
    } else if h == 12u || h == 14u {
        g.x = sv;
    } else {
        g.z = sv;
    }
    return g;
}

// Perlin's improved noise at p (the permutation table at word `table` of texels) and its
// gradient: (n, ∂n/∂x, ∂n/∂y, ∂n/∂z).
// Mirror of src/tracer/shading/procedural.rs::perlin_noise — change both.
fn perlin_noise(table: u32, p: vec3<f32>) -> vec4<f32> {
    let cell = floor(p);
    let f = p - cell;
    let x = u32(i32(cell.x) & 255);
    let y = u32(i32(cell.y) & 255);
    let z = u32(i32(cell.z) & 255);
    let a = texel_word(table + x) + y;
    let aa = texel_word(table + a) + z;
    let ab = texel_word(table + a + 1u) + z;
    let b = texel_word(table + x + 1u) + y;
    let ba = texel_word(table + b) + z;
    let bb = texel_word(table + b + 1u) + z;
    let g000 = gradient_direction(texel_word(table + aa));
    let g100 = gradient_direction(texel_word(table + ba));
    let g010 = gradient_direction(texel_word(table + ab));
    let g110 = gradient_direction(texel_word(table + bb));
    let g001 = gradient_direction(texel_word(table + aa + 1u));
    let g101 = gradient_direction(texel_word(table + ba + 1u));
    let g011 = gradient_direction(texel_word(table + ab + 1u));
    let g111 = gradient_direction(texel_word(table + bb + 1u));
    let n000 = dot(g000, f);
    let n100 = dot(g100, vec3<f32>(f.x - 1.0, f.y, f.z));
    let n010 = dot(g010, vec3<f32>(f.x, f.y - 1.0, f.z));
    let n110 = dot(g110, vec3<f32>(f.x - 1.0, f.y - 1.0, f.z));
    let n001 = dot(g001, vec3<f32>(f.x, f.y, f.z - 1.0));
    let n101 = dot(g101, vec3<f32>(f.x - 1.0, f.y, f.z - 1.0));
    let n011 = dot(g011, vec3<f32>(f.x, f.y - 1.0, f.z - 1.0));
    let n111 = dot(g111, vec3<f32>(f.x - 1.0, f.y - 1.0, f.z - 1.0));
    let u = fade(f.x);
    let v = fade(f.y);
    let w = fade(f.z);
    let x00 = lerp(u, n000, n100);
    let x10 = lerp(u, n010, n110);
    let x01 = lerp(u, n001, n101);
    let x11 = lerp(u, n011, n111);
    let y0 = lerp(v, x00, x10);
    let y1 = lerp(v, x01, x11);
    let value = lerp(w, y0, y1);
    // d/dp of the blend: the blended corner gradients, plus each fade's slope times the
    // blend's derivative in that fade.
    let blended = lerp_vec3(
        w,
        lerp_vec3(v, lerp_vec3(u, g000, g100), lerp_vec3(u, g010, g110)),
        lerp_vec3(v, lerp_vec3(u, g001, g101), lerp_vec3(u, g011, g111)),
    );
    let d_u = lerp(
        w,
        lerp(v, n100 - n000, n110 - n010),
        lerp(v, n101 - n001, n111 - n011),
    );
    let d_v = lerp(w, x10 - x00, x11 - x01);
    let d_w = y1 - y0;
    let slope = vec3<f32>(
        fade_slope(f.x) * d_u,
        fade_slope(f.y) * d_v,
        fade_slope(f.z) * d_w,
    );
    let gradient = blended + slope;
    return vec4<f32>(value, gradient.x, gradient.y, gradient.z);
}

// fBm of perlin_noise at p with its gradient (lacunarity 2, gain ½, divided by the sum of
// the weights); octaves finer than the footprint fade to their mean, 0.
// Mirror of src/tracer/shading/procedural.rs::fbm — change both.
fn fbm(table: u32, p: vec3<f32>, octaves: u32, footprint: f32) -> vec4<f32> {
    var sum = vec4<f32>(0.0);
    var weights = 0.0;
    var amplitude = 1.0;
    var frequency = 1.0;
    for (var o = 0u; o < min(octaves, PROCEDURAL_MAX_OCTAVES); o++) {
        weights += amplitude;
        let keep = clamp(2.0 - 2.0 * footprint * frequency, 0.0, 1.0);
        if keep > 0.0 {
            let n = perlin_noise(table, p * frequency);
            let scaled = vec4<f32>(n.x, n.y * frequency, n.z * frequency, n.w * frequency);
            sum += scaled * (amplitude * keep);
        }
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    return sum / weights;
}

// ∫₀ˣ s, s the square wave +1 on [0, 1), −1 on [1, 2): a triangle wave.
// Mirror of src/tracer/shading/procedural.rs::square_wave_integral — change both.
fn square_wave_integral(x: f32) -> f32 {
    let m = x - 2.0 * floor(x * 0.5);
    if m < 1.0 {
        return m;
    }
    return 2.0 - m;
}

// The square wave (+1 where ⌊x⌋ is even) box-filtered over `width` centred on x; the
// wave itself below PROCEDURAL_CHECKER_MIN_WIDTH or where the width holds no cell edge.
// Mirror of src/tracer/shading/procedural.rs::filtered_square_wave — change both.
fn filtered_square_wave(x: f32, width: f32) -> f32 {
    let half = 0.5 * width;
    if !(width > PROCEDURAL_CHECKER_MIN_WIDTH) || floor(x - half) == floor(x + half) {
        let cell = floor(x);
        return select(-1.0, 1.0, cell - 2.0 * floor(cell * 0.5) == 0.0);
    }
    let filtered = (square_wave_integral(x + half) - square_wave_integral(x - half)) / width;
    return clamp(filtered, -1.0, 1.0);
}

// How much of a periodic pattern's contrast a footprint keeps (all up to a quarter
// period, none from half a period).
// Mirror of src/tracer/shading/procedural.rs::pattern_contrast — change both.
fn pattern_contrast(width: f32, period: f32) -> f32 {
    return clamp(2.0 - 4.0 * width / period, 0.0, 1.0);
}

// The extent along an axis of a footprint disc `width` wide whose unit normal has the
// component n along it.
// Mirror of src/tracer/shading/procedural.rs::footprint_along_axis — change both.
fn footprint_along_axis(width: f32, n: f32) -> f32 {
    return width * sqrt(max(1.0 - n * n, 0.0));
}

// The unit object normal at a hit and object units per world unit along the surface.
// Mirror of src/tracer/shading/procedural.rs::ObjectFrame — change both.
struct ObjectFrame {
    normal: vec3<f32>,
    scale: f32,
}

// The object frame of inst where the world normal is n (see procedural.rs).
// Mirror of src/tracer/shading/procedural.rs::object_frame — change both.
fn object_frame(inst: PackedInstance, n: vec3<f32>) -> ObjectFrame {
    let o2w = inst.object_to_world;
    let r0 = o2w[0].xyz;
    let r1 = o2w[1].xyz;
    let r2 = o2w[2].xyz;
    let m = r0 * n.x + r1 * n.y + r2 * n.z;
    let len = length(m);
    let det = abs(dot(r0, cross(r1, r2)));
    if !(len > 0.0 && det > 0.0) {
        return ObjectFrame(n, 0.0);
    }
    return ObjectFrame(m / len, sqrt(len / det));
}

// The pattern of the procedural texture whose block is at word `block`, at the object
// point p with unit object normal `normal`, filtered over `footprint` (object units):
// (t, ∂t/∂p).
// Mirror of src/tracer/shading/procedural.rs::procedural_pattern — change both.
fn procedural_pattern(block: u32, p: vec3<f32>, normal: vec3<f32>, footprint: f32) -> vec4<f32> {
    let kind = texel_word(block);
    let table = texel_word(block + 1u);
    let scale = bitcast<f32>(texel_word(block + 8u));
    let octaves = texel_word(block + 9u);
    let strength = bitcast<f32>(texel_word(block + 10u));
    if kind == PROCEDURAL_CHECKER {
        // scale is the cube side; the pattern's gradient is 0 (flat steps).
        let q = p / scale;
        let w = footprint / scale;
        let c = filtered_square_wave(q.x, footprint_along_axis(w, normal.x))
            * filtered_square_wave(q.y, footprint_along_axis(w, normal.y))
            * filtered_square_wave(q.z, footprint_along_axis(w, normal.z));
        return vec4<f32>(0.5 - 0.5 * c, 0.0, 0.0, 0.0);
    }
    let q = p * scale;
    let w = footprint * scale;
    let n = fbm(table, q, octaves, w);
    if kind == PROCEDURAL_NOISE {
        let t = 0.5 + 0.5 * n.x;
        let inside = select(0.0, 0.5 * scale, t > 0.0 && t < 1.0);
        return vec4<f32>(clamp(t, 0.0, 1.0), n.y * inside, n.z * inside, n.w * inside);
    }
    if kind == PROCEDURAL_MARBLE {
        // Veins across object x, two units of q apart, bent by the noise.
        let k = pattern_contrast(w, 2.0);
        let phase = (0.5 * TWO_PI) * (q.x + strength * n.x);
        let slope = 0.5 * k * (0.5 * TWO_PI) * cos(phase) * scale;
        let d = vec3<f32>(1.0 + strength * n.y, strength * n.z, strength * n.w) * slope;
        return vec4<f32>(0.5 + 0.5 * k * sin(phase), d.x, d.y, d.z);
    }
    // Wood: rings around object z, one unit of q apart, bent by the noise.
    let k = pattern_contrast(w, 1.0);
    let rho = sqrt(q.x * q.x + q.y * q.y);
    var radial = vec3<f32>(0.0);
    if rho > 0.0 {
        radial = vec3<f32>(q.x / rho, q.y / rho, 0.0);
    }
    let r = rho + strength * n.x;
    let ring = r - floor(r);
    let d = (radial + vec3<f32>(n.y, n.z, n.w) * strength) * (k * scale);
    return vec4<f32>(0.5 + k * (ring - 0.5), d.x, d.y, d.z);
}

// Whether the material's texture index (not NO_TEXTURE) is a procedural's.
// Mirror of src/tracer/shading/procedural.rs::is_procedural — change both.
fn is_procedural(texture: u32) -> bool {
    return (texture & PROCEDURAL_TEXTURE) != 0u;
}

// A procedural texture's pattern at a hit and the object frame it was looked up in.
// Mirror of src/tracer/shading/procedural.rs::ProceduralLookup — change both.
struct ProceduralLookup {
    pattern: vec4<f32>,
    frame: ObjectFrame,
}

// The pattern of procedural texture `texture` at s for a footprint world_footprint wide.
// Mirror of src/tracer/shading/procedural.rs::procedural_lookup — change both.
fn procedural_lookup(texture: u32, s: Surface, world_footprint: f32) -> ProceduralLookup {
    let frame = object_frame(load_instance(s.instance), s.normal);
    let block = texture & ~PROCEDURAL_TEXTURE;
    let pattern = procedural_pattern(block, s.p_object, frame.normal, world_footprint * frame.scale);
    return ProceduralLookup(pattern, frame);
}

// The colour stored as three f32 words from word `at` of texels.
// Mirror of src/tracer/shading/procedural.rs::procedural_colour_word — change both.
fn procedural_colour_word(at: u32) -> vec3<f32> {
    return vec3<f32>(
        bitcast<f32>(texel_word(at)),
        bitcast<f32>(texel_word(at + 1u)),
        bitcast<f32>(texel_word(at + 2u)),
    );
}

// The colour of procedural texture `texture` at s, filtered over world_footprint.
// Mirror of src/tracer/shading/procedural.rs::procedural_colour — change both.
fn procedural_colour(texture: u32, s: Surface, world_footprint: f32) -> vec3<f32> {
    let lookup = procedural_lookup(texture, s, world_footprint);
    let block = texture & ~PROCEDURAL_TEXTURE;
    let c1 = procedural_colour_word(block + 2u);
    let c2 = procedural_colour_word(block + 5u);
    return lerp_vec3(lookup.pattern.x, c1, c2);
}

// The normal of s bumped by material m's procedural bump texture (see procedural.rs).
// Mirror of src/tracer/shading/procedural.rs::procedural_bump_normal — change both.
fn procedural_bump_normal(m: PackedMaterial, s: Surface) -> vec3<f32> {
    let n = s.normal;
    let lookup = procedural_lookup(m.bump_texture, s, s.world_footprint);
    if !(lookup.frame.scale > 0.0) {
        return n;
    }
    let w2o = load_instance(s.instance).world_to_object;
    let g = lookup.pattern;
    let world = (w2o[0].xyz * g.y + w2o[1].xyz * g.z + w2o[2].xyz * g.w) / lookup.frame.scale;
    let along = world - n * dot(world, n);
    let bumped = n - along * m.bump_strength;
    // along ⟂ n, so the sum is at least as long as n: never zero.
    return normalize(bumped);
}
// #endif
