//! `tools/benches/first_gpu.sh` (the table for the first hardware GPU, docs/gpu.md) end to end
//! on whatever adapter there is — lavapipe here — at a tiny size on one scene: every row
//! and section is there, and a column the device cannot give says so.

use std::path::Path;
use std::process::Command;

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn the_first_gpu_script_runs_end_to_end() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("bash")
        .arg(repo.join("tools/benches/first_gpu.sh"))
        .args(["--glint", env!("CARGO_BIN_EXE_glint"), "--size", "8"])
        .arg("scenes/cs488/a4-2021plus/simple.lua")
        .current_dir(repo)
        .output()
        .expect("bash runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let all = format!(
        "{stdout}\nstderr:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{all}");
    let row = stdout
        .lines()
        .find(|l| l.starts_with("| simple |"))
        .unwrap_or_else(|| panic!("no row for simple: {all}"));
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    assert_eq!(cells.len(), 11, "nine columns: {row}");
    assert!(!row.contains("failed"), "{row}");
    // rays counted by the CPU tracer: 8×8 pixels, at least one ray each.
    assert!(cells[8].parse::<u64>().is_ok_and(|r| r >= 64), "{row}");
    assert!(
        stdout.contains("## Kernel registers on this device"),
        "{all}"
    );
    // Either the device reports registers (a table) or the script says it cannot.
    assert!(
        stdout.contains("| VGPRs |") || stdout.contains("not exposed:"),
        "{all}"
    );
}
