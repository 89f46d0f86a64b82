//! One camera sample's path: Whitted tracing with an explicit stack of secondary rays,
//! and the media that contain the camera; built on `shading` and below.

pub mod camera_media;
pub mod trace;
