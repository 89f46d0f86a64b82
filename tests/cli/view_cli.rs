//! `glint view` without a window: no display is exit code 2 with one message that
//! suggests `glint render`, before anything else happens; its flags are refused like
//! `render`'s. (The window itself is tested under Xvfb in the gpu binary: tests/gpu/view.rs.)

use std::process::Command;

fn view(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .arg("view")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("glint runs")
}

#[test]
fn no_display_is_exit_code_2_suggesting_render() {
    let out = view(&["scenes/demo.lua"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "one message: {stderr}");
    assert!(
        stderr.contains("DISPLAY") && stderr.contains("glint render"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn a_wayland_only_session_is_told_this_build_opens_x11_windows() {
    let out = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["view", "scenes/demo.lua"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("DISPLAY")
        .env("WAYLAND_DISPLAY", "wayland-0")
        .output()
        .expect("glint runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        stderr.contains("XWayland") && stderr.contains("glint render"),
        "{stderr}"
    );
}

#[test]
fn adaptive_sampling_is_refused_naming_the_choices() {
    let out = view(&["scenes/demo.lua", "--aa", "adaptive"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        stderr.contains("uniform") && stderr.contains("none"),
        "{stderr}"
    );
}

#[test]
fn a_screenshot_needs_a_frame_count() {
    let out = view(&["scenes/demo.lua", "--screenshot", "x.png"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--frames"));
}

#[test]
fn an_unreachable_display_is_exit_code_2_too() {
    let out = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["view", "scenes/demo.lua"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("DISPLAY", ":65000")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("glint runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains("glint render"), "{stderr}");
}
