// math.wgsl — small numeric helpers that several intersection routines share.

// (Always compiled: enter_scene clips every ray to the scene bounds with it.)
// 1/x, or ±SAFE_RCP_LIMIT when |x| is too small to invert without overflow.
// Mirror of src/tracer/base/math.rs::safe_rcp — change both.
fn safe_rcp(x: f32) -> f32 {
    if abs(x) > 1.0 / SAFE_RCP_LIMIT {
        return 1.0 / x;
    }
    return copysign(SAFE_RCP_LIMIT, x);
}

// safe_rcp of each component.
// Mirror of src/tracer/base/math.rs::safe_rcp3 — change both.
fn safe_rcp3(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(safe_rcp(v.x), safe_rcp(v.y), safe_rcp(v.z));
}
