//! What the view's keys and mouse mean: one [`Action`] per key, and the mouse drag
//! state (which button, where it was), kept apart from the window so the mapping is
//! tested without one.

use winit::event::MouseButton;
use winit::keyboard::KeyCode;

/// The keys, as H prints them (and docs/view.md lists them).
pub const KEYS_HELP: &str = "\
glint view keys:
  left drag          orbit about the pivot
  right/middle drag  pan
  wheel              dolly towards / away from the pivot
  W A S D            fly forward, left, back, right
  Q E                fly down, up
  R                  reset to the script's camera
  F                  frame the scene's bounds
  C                  print the camera as gr.render arguments (stdout)
  Ctrl+S             save the image (-o, or NAME-view-0001.png, …)
  G                  switch between the GPU and CPU tracers
  H                  print these keys
  Esc, Ctrl+Q        quit";

/// What a key press asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Fly one step along (forward, right, up).
    Fly(f64, f64, f64),
    Reset,
    Frame,
    PrintCamera,
    Save,
    ToggleTracer,
    Help,
    Quit,
}

/// The action of `key` pressed with Ctrl held (`ctrl`) or not.
pub fn key_action(key: KeyCode, ctrl: bool) -> Option<Action> {
    if ctrl {
        return match key {
            KeyCode::KeyS => Some(Action::Save),
            KeyCode::KeyQ => Some(Action::Quit),
            _ => None,
        };
    }
    Some(match key {
        KeyCode::KeyW => Action::Fly(1.0, 0.0, 0.0),
        KeyCode::KeyS => Action::Fly(-1.0, 0.0, 0.0),
        KeyCode::KeyA => Action::Fly(0.0, -1.0, 0.0),
        KeyCode::KeyD => Action::Fly(0.0, 1.0, 0.0),
        KeyCode::KeyQ => Action::Fly(0.0, 0.0, -1.0),
        KeyCode::KeyE => Action::Fly(0.0, 0.0, 1.0),
        KeyCode::KeyR => Action::Reset,
        KeyCode::KeyF => Action::Frame,
        KeyCode::KeyC => Action::PrintCamera,
        KeyCode::KeyG => Action::ToggleTracer,
        KeyCode::KeyH => Action::Help,
        KeyCode::Escape => Action::Quit,
        _ => return None,
    })
}

/// A mouse drag in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DragKind {
    Orbit,
    Pan,
}

/// Which drag a button starts.
pub fn drag_kind(button: MouseButton) -> Option<DragKind> {
    match button {
        MouseButton::Left => Some(DragKind::Orbit),
        MouseButton::Right | MouseButton::Middle => Some(DragKind::Pan),
        _ => None,
    }
}

/// The cursor and the drag it makes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Mouse {
    pub cursor: Option<(f64, f64)>,
    pub drag: Option<DragKind>,
}

impl Mouse {
    /// Moves the cursor to `to`; returns the drag and the movement in pixels when a
    /// button is held.
    pub fn moved(&mut self, to: (f64, f64)) -> Option<(DragKind, f64, f64)> {
        let from = self.cursor.replace(to)?;
        let drag = self.drag?;
        Some((drag, to.0 - from.0, to.1 - from.1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_in_the_help_has_an_action() {
        for (key, ctrl, action) in [
            (KeyCode::KeyW, false, Action::Fly(1.0, 0.0, 0.0)),
            (KeyCode::KeyS, false, Action::Fly(-1.0, 0.0, 0.0)),
            (KeyCode::KeyS, true, Action::Save),
            (KeyCode::KeyQ, true, Action::Quit),
            (KeyCode::Escape, false, Action::Quit),
            (KeyCode::KeyE, false, Action::Fly(0.0, 0.0, 1.0)),
            (KeyCode::KeyG, false, Action::ToggleTracer),
        ] {
            assert_eq!(key_action(key, ctrl), Some(action), "{key:?} ctrl={ctrl}");
        }
        assert_eq!(key_action(KeyCode::KeyZ, false), None);
    }

    #[test]
    fn a_drag_reports_movement_only_while_a_button_is_held() {
        let mut m = Mouse::default();
        assert_eq!(m.moved((10.0, 10.0)), None);
        m.drag = drag_kind(MouseButton::Left);
        assert_eq!(m.moved((15.0, 7.0)), Some((DragKind::Orbit, 5.0, -3.0)));
        m.drag = None;
        assert_eq!(m.moved((20.0, 7.0)), None);
    }
}
