//! The view's camera: the script's `gr.render` camera (eye, view, up, fov, in f64 as the
//! scene language keeps them) moved by the mouse and keys, and written into the packed
//! globals with exactly the arithmetic `pack` uses, so that pasting the printed camera
//! into the script and running `glint render` traces the same rays.
//!
//! Every move is scale-free: orbit turns about a pivot, pan and fly move by shares of the
//! distance to the pivot or of the scene's bounds, dolly multiplies that distance.

use glam::DVec3;
use glint::pack::{camera_frame, PackedGlobals};
use glint::scene::Camera;

/// Radians turned per pixel of mouse drag when orbiting (a drag across a 640-pixel window
/// turns about 1.1 turns).
const ORBIT_RADIANS_PER_PIXEL: f64 = 0.011;
/// Closest the view direction may come to the up axis when orbiting (radians): at the
/// pole, `forward × up` vanishes and the camera frame would flip.
const POLE_MARGIN: f64 = 0.02;
/// Dolly: distance to the pivot multiplied by this per wheel notch towards it.
const DOLLY_PER_NOTCH: f64 = 0.9;
/// Fly: one key press (or key repeat) moves by this share of the bounds' diagonal.
const FLY_SHARE: f64 = 0.02;

/// The scene's bounds (the packed grid's), for framing and fly speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: DVec3,
    pub max: DVec3,
}

impl Bounds {
    /// The packed scene's grid bounds (every item lies inside them).
    pub fn of_globals(g: &PackedGlobals) -> Bounds {
        Bounds {
            min: DVec3::from(g.grid_min.map(f64::from)),
            max: DVec3::from(g.grid_max.map(f64::from)),
        }
    }

    pub fn centre(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Length of the diagonal; at least a tiny positive share of the coordinates'
    /// magnitude, so an empty or flat scene still moves.
    pub fn diagonal(&self) -> f64 {
        let d = (self.max - self.min).length();
        let scale = self.min.abs().max(self.max.abs()).max_element().max(1e-30);
        if d.is_finite() && d > scale * 1e-9 {
            d
        } else {
            scale.max(1.0)
        }
    }
}

/// The camera the view shows and the point it orbits about.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewCamera {
    pub camera: Camera,
    pub pivot: DVec3,
}

impl ViewCamera {
    /// The script's camera, orbiting about the point on its view ray nearest the bounds'
    /// centre (or the centre's distance ahead, when that point is behind the eye).
    pub fn from_script(camera: &Camera, bounds: &Bounds) -> ViewCamera {
        let forward = camera.view.normalize();
        let to_centre = bounds.centre() - camera.eye;
        let along = to_centre.dot(forward);
        let distance = if along > 0.0 {
            along
        } else {
            to_centre.length().max(bounds.diagonal() * 0.5)
        };
        ViewCamera {
            camera: camera.clone(),
            pivot: camera.eye + forward * distance,
        }
    }

    fn forward(&self) -> DVec3 {
        self.camera.view.normalize()
    }

    /// The camera's right and true up vectors (as `pack` computes them).
    fn right_up(&self) -> (DVec3, DVec3) {
        let forward = self.forward();
        let right = forward.cross(self.camera.up).normalize();
        (right, right.cross(forward))
    }

    fn distance(&self) -> f64 {
        (self.pivot - self.camera.eye).length()
    }

    /// Turns the eye about the pivot: `dx` pixels about the script's up axis, `dy` about
    /// the camera's right axis (dragging down looks from higher up).
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        let axis = self.camera.up.normalize();
        let offset = self.camera.eye - self.pivot;
        let yaw = glam::DQuat::from_axis_angle(axis, -dx * ORBIT_RADIANS_PER_PIXEL);
        let mut offset = yaw * offset;
        let (right, _) = self.right_up();
        let right = yaw * right;
        // Pitch, clamped short of the poles of the up axis.
        let current = offset.normalize().dot(axis).clamp(-1.0, 1.0).acos();
        let wanted = current - dy * ORBIT_RADIANS_PER_PIXEL;
        let target = wanted.clamp(POLE_MARGIN, std::f64::consts::PI - POLE_MARGIN);
        offset = glam::DQuat::from_axis_angle(right, target - current) * offset;
        self.camera.eye = self.pivot + offset;
        self.camera.view =
            (self.pivot - self.camera.eye) * (self.camera.view.length() / offset.length());
    }

    /// Moves eye and pivot across the view: `dx`, `dy` pixels of a window `height` pixels
    /// tall, so the point at the pivot's depth follows the cursor.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64) {
        let (right, up) = self.right_up();
        let tan_half = (self.camera.fov_deg.to_radians() * 0.5).tan();
        let per_pixel = 2.0 * self.distance() * tan_half / height.max(1.0);
        let shift = (-right * dx + up * dy) * per_pixel;
        self.camera.eye += shift;
        self.pivot += shift;
    }

    /// Moves the eye towards the pivot by `notches` wheel steps (negative: away).
    pub fn dolly(&mut self, notches: f64) {
        let offset = self.camera.eye - self.pivot;
        self.camera.eye = self.pivot + offset * DOLLY_PER_NOTCH.powf(notches);
    }

    /// Moves eye and pivot by one step along the camera's (forward, right, up) axes in
    /// the amounts given (each −1, 0 or 1).
    pub fn fly(&mut self, forward: f64, right: f64, up: f64, bounds: &Bounds) {
        let (r, u) = self.right_up();
        let step = bounds.diagonal() * FLY_SHARE;
        let shift = (self.forward() * forward + r * right + u * up) * step;
        self.camera.eye += shift;
        self.pivot += shift;
    }

    /// Keeps the view direction and looks at the bounds' centre from the distance at
    /// which the bounds' sphere fills the narrower field of view.
    pub fn frame(&mut self, bounds: &Bounds, aspect: f64) {
        let forward = self.forward();
        let radius = bounds.diagonal() * 0.5;
        let tan_half = (self.camera.fov_deg.to_radians() * 0.5).tan();
        let narrow = tan_half.min(tan_half * aspect).atan();
        let distance = radius / narrow.sin();
        self.pivot = bounds.centre();
        self.camera.eye = self.pivot - forward * distance;
    }

    /// Writes this camera into `globals` the way `pack` does for a script's camera.
    pub fn apply(&self, globals: &mut PackedGlobals) {
        let frame = camera_frame(&self.camera);
        globals.eye = frame.eye;
        globals.tan_half_fov = frame.tan_half_fov;
        globals.forward = frame.forward;
        globals.right = frame.right;
        globals.up = frame.up;
    }

    /// The camera as the 5th to 8th arguments of `gr.render`, as a Lua assignment to
    /// paste into the script (numbers in shortest round-trip form, so pasting them
    /// reproduces this camera exactly).
    pub fn as_lua(&self) -> String {
        let v = |d: DVec3| format!("{{{}, {}, {}}}", d.x, d.y, d.z);
        let c = &self.camera;
        format!(
            "eye, view, up, fov = {}, {}, {}, {}  -- gr.render(root, 'out.png', w, h, eye, view, up, fov, ambient, lights)",
            v(c.eye),
            v(c.view),
            v(c.up),
            c.fov_deg
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(scale: f64) -> (ViewCamera, Bounds) {
        let bounds = Bounds {
            min: DVec3::splat(-scale),
            max: DVec3::splat(scale),
        };
        let script = Camera {
            eye: DVec3::new(0.0, 0.0, 10.0 * scale),
            view: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
            fov_deg: 50.0,
        };
        (ViewCamera::from_script(&script, &bounds), bounds)
    }

    #[test]
    fn orbit_keeps_the_distance_to_the_pivot_at_every_scale() {
        for scale in [1e-3, 1.0, 1e3] {
            let (mut c, _) = camera(scale);
            let d0 = c.distance();
            c.orbit(57.0, -23.0);
            let d1 = c.distance();
            assert!((d1 - d0).abs() <= d0 * 1e-12, "scale {scale}: {d0} → {d1}");
            // It still looks at the pivot.
            let to_pivot = (c.pivot - c.camera.eye).normalize();
            assert!(to_pivot.dot(c.forward()) > 1.0 - 1e-12, "scale {scale}");
            assert_ne!(c.camera.eye, DVec3::new(0.0, 0.0, 10.0 * scale));
        }
    }

    #[test]
    fn orbit_stops_short_of_the_pole() {
        let (mut c, _) = camera(1.0);
        c.orbit(0.0, 1e6);
        let (right, up) = c.right_up();
        assert!(right.is_finite() && up.is_finite());
        assert!(c.forward().dot(DVec3::Y).abs() < 1.0 - 1e-5);
    }

    #[test]
    fn pan_dolly_and_fly_are_scale_free() {
        for scale in [1e-3, 1e3] {
            let (mut c, bounds) = camera(scale);
            let eye = c.camera.eye;
            c.pan(10.0, 0.0, 400.0);
            // 10 of 400 pixels at distance 10·scale and fov 50°: 10 · 2 · 10 · tan 25° / 400.
            let expected = 10.0 * 2.0 * 10.0 * 25f64.to_radians().tan() / 400.0;
            assert!(((c.camera.eye - eye).length() / scale - expected).abs() < 1e-9);
            c.dolly(1.0);
            assert!((c.distance() / (10.0 * scale) - 0.9).abs() < 1e-9);
            let before = c.camera.eye;
            c.fly(1.0, 0.0, 0.0, &bounds);
            let moved = (c.camera.eye - before).length();
            assert!((moved - bounds.diagonal() * FLY_SHARE).abs() <= moved * 1e-9);
        }
    }

    #[test]
    fn frame_fits_the_bounds_sphere() {
        let (mut c, bounds) = camera(1.0);
        c.camera.eye = DVec3::new(0.0, 0.0, 1000.0);
        c.frame(&bounds, 1.6);
        let radius = bounds.diagonal() * 0.5;
        let half = (25.0f64).to_radians();
        assert!((c.distance() - radius / half.sin()).abs() < 1e-9);
        assert_eq!(c.pivot, bounds.centre());
    }

    #[test]
    fn the_printed_camera_reads_back_exactly() {
        let (mut c, _) = camera(1.0);
        c.orbit(13.0, 7.0);
        let text = c.as_lua();
        let eye = text.split('{').nth(1).unwrap().split('}').next().unwrap();
        let xs: Vec<f64> = eye.split(", ").map(|x| x.parse().unwrap()).collect();
        assert_eq!(DVec3::new(xs[0], xs[1], xs[2]), c.camera.eye);
    }

    #[test]
    fn the_script_camera_applies_as_pack_writes_it() {
        let (c, _) = camera(1.0);
        let mut g: PackedGlobals = bytemuck::Zeroable::zeroed();
        c.apply(&mut g);
        assert_eq!(g.eye, [0.0, 0.0, 10.0]);
        assert_eq!(g.forward, [0.0, 0.0, -1.0]);
        assert_eq!(g.up, [0.0, 1.0, 0.0]);
    }
}
