//! The tracer's first layer, used by every other: small numeric helpers, rays and camera
//! rays, and the stateless random numbers both tracers draw.

pub mod math;
pub mod ray;
pub mod rng;
