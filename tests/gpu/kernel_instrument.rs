//! `glint kernels` (the kernel instrument, docs/gpu.md) on RADV's null device, and
//! `glint render --dump-kernels` on lavapipe: a kernel known to spill reports scratch,
//! the dumped SPIR-V is the SPIR-V the instrument compiles, and the register budgets of
//! the GPU kernels over every scene.

use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder for one test.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("kernels-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub(crate) fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("glint runs")
}

pub(crate) fn text(out: &Output) -> String {
    format!(
        "status {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// The value of `"key": N` in one JSON line.
pub(crate) fn number(line: &str, key: &str) -> Option<u64> {
    let at = line.find(&format!("\"{key}\": "))? + key.len() + 4;
    let digits: String = line[at..]
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().ok()
}

/// The value of `"key": "text"` in one JSON line.
pub(crate) fn string<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    let at = line.find(&format!("\"{key}\": \""))? + key.len() + 5;
    line[at..].split('"').next()
}

/// A private array of 2 KiB indexed at run time: RADV keeps arrays over 256 bytes in
/// scratch memory, so this kernel must report scratch (or the instrument reads nothing).
const SPILLING_KERNEL: &str = r#"
@group(0) @binding(0) var<uniform> params: vec4<u32>;
@group(0) @binding(8) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    var stack: array<vec4<f32>, 128>;
    for (var i = 0u; i < 128u; i++) {
        stack[(i * params.x + gid.x) % 128u] = vec4<f32>(f32(i), f32(gid.y), 0.0, 1.0);
    }
    var sum = vec4<f32>(0.0);
    for (var i = 0u; i < 128u; i++) {
        sum += stack[(i * params.y + gid.y) % 128u];
    }
    out[gid.x + 64u * gid.y] = sum;
}
"#;

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_kernel_with_a_private_array_reports_scratch_and_breaks_the_budget() {
    let dir = scratch_dir("spill");
    let file = dir.join("spill.wgsl");
    std::fs::write(&file, SPILLING_KERNEL).unwrap();
    let file = file.to_str().unwrap();
    let out = glint(&[
        "kernels", "--wgsl", file, "--family", "NAVI21", "--format", "json",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<&str> = stdout.lines().filter(|l| l.contains("\"entry\"")).collect();
    assert_eq!(rows.len(), 2, "wave64 and wave32: {stdout}");
    for row in rows {
        let scratch = number(row, "scratch_bytes").expect("scratch reported");
        assert!(scratch >= 2048, "2 KiB a lane in scratch: {row}");
        assert!(number(row, "vgprs").is_some_and(|v| v > 0), "{row}");
    }
    let checked = glint(&[
        "kernels",
        "--wgsl",
        file,
        "--family",
        "NAVI21",
        "--check-budget",
    ]);
    assert_eq!(checked.status.code(), Some(7), "{}", text(&checked));
    assert!(String::from_utf8_lossy(&checked.stderr).contains("B scratch"));
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn an_unknown_family_is_a_clear_error() {
    let out = glint(&["kernels", "scenes/csg.lua", "--family", "NAVI99"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("unknown GPU family 'NAVI99'") && stderr.contains("NAVI21"),
        "{stderr}"
    );
}

/// `--entry main` in the hardware variant, whose modules have no megakernel `main`, is
/// refused with the variant named (rather than measuring nothing); the software variant
/// compiles it.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn main_is_the_software_variants_alone() {
    let scene = "scenes/cs488/a4-2021plus/simple.lua";
    let args = [
        "kernels", scene, "--family", "NAVI21", "--wave", "64", "--format", "json",
    ];
    let out = glint(&[&args[..], &["--entry", "main"]].concat());
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("entry point 'main' is in no render module of the hardware kernel variant")
            && stderr.contains("--kernel-variant software"),
        "{stderr}"
    );
    let software = ["--kernel-variant", "software", "--entry", "main"];
    let out = glint(&[&args[..], &software].concat());
    assert!(out.status.success(), "{}", text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<&str> = stdout.lines().filter(|l| l.contains("\"entry\"")).collect();
    assert!(!rows.is_empty(), "{stdout}");
    assert!(
        rows.iter().all(|r| string(r, "entry") == Some("main")),
        "{stdout}"
    );
}

/// What `render --dump-kernels` writes is, byte for byte, what `glint kernels` compiles
/// for the same scene and variant (on lavapipe, with the hardware variant forced).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn dumped_kernels_are_the_kernels_the_instrument_compiles() {
    let dir = scratch_dir("dump");
    let dump = dir.join("dump");
    let image = dir.join("simple.png");
    let scene = "scenes/cs488/a4-2021plus/simple.lua";
    let out = glint(&[
        "render",
        scene,
        "--backend",
        "gpu",
        "--kernel-variant",
        "hardware",
        "--aa",
        "none",
        "--width",
        "8",
        "--height",
        "8",
        "-o",
        image.to_str().unwrap(),
        "--dump-kernels",
        dump.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let mut names: Vec<String> = std::fs::read_dir(&dump)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    // The hardware variant traces AA none through the wavefront kernels, not `main`.
    let kernels = ["args", "camera", "closest", "gather", "shade", "shadow"];
    let expected: Vec<String> = kernels
        .iter()
        .flat_map(|k| [format!("wavefront_{k}.spv"), format!("wavefront_{k}.wgsl")])
        .collect();
    assert_eq!(
        names, expected,
        "AA none compiles the wavefront kernels alone"
    );
    let wgsl = std::fs::read_to_string(dump.join("wavefront_closest.wgsl")).unwrap();
    assert!(
        wgsl.contains("kernel: workgroup 8×8/64, last-item mailbox, ray lists in storage"),
        "the hardware variant"
    );
    let spv = std::fs::read(dump.join("wavefront_closest.spv")).unwrap();
    assert_eq!(&spv[..4], &[0x03, 0x02, 0x23, 0x07], "SPIR-V magic");
    let digest: String = Sha256::digest(&spv)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();

    let out = glint(&[
        "kernels",
        scene,
        "--family",
        "NAVI21",
        "--entry",
        "wavefront_closest",
        "--wave",
        "64",
        "--format",
        "json",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let row = stdout
        .lines()
        .find(|l| l.contains("\"entry\": \"wavefront_closest\""))
        .unwrap();
    assert_eq!(string(row, "spirv_sha256"), Some(digest.as_str()), "{row}");
}

/// The budgets on NAVI21 for every kernel of every scene of scenes/ and the CS488 corpus,
/// both wave sizes: no spills, no scratch, ≤ 128 VGPRs in wave32, ≤ 96 for traversal
/// kernels. The hardware variant's module holds no megakernel: every AA mode and the view,
/// glass included, run the wavefront kernels (the tree's rounds and fold with glass) and
/// adaptive AA's decide, work-args and integrate passes. textures.lua's
/// `wavefront_closest` is 96 VGPRs in wave32 only because it keeps the path's depth out of
/// the traversal's registers (docs/journal/2026-12-02-textures-closest-kernel.md; 112 with
/// it held).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn every_kernel_of_every_scene_meets_the_navi21_budgets() {
    check_navi21_budgets();
}

/// `glint kernels --check-budget` over every scene of scenes/ and the CS488 corpus, both
/// wave sizes, every entry point: success, and rows for every scene of scenes/.
fn check_navi21_budgets() {
    let mut args = vec!["kernels".to_string()];
    let mut scenes: Vec<String> = std::fs::read_dir(repo().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "lua"))
        .map(|p| format!("scenes/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    scenes.sort();
    args.extend(scenes.iter().cloned());
    // The meshes and the corpus, by folder (the dialect examples need their preludes).
    for dir in ["scenes/meshes", "scenes/cs488"] {
        args.push(dir.to_string());
    }
    for flag in [
        "--format",
        "json",
        "--family",
        "NAVI21",
        "--wave",
        "64",
        "--wave",
        "32",
        "--check-budget",
    ] {
        args.push(flag.to_string());
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = glint(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = String::from_utf8_lossy(&out.stdout);
    for scene in &scenes {
        for wave in [32, 64] {
            let row = format!("\"scene\": \"{scene}\"");
            assert!(
                rows.lines()
                    .any(|l| l.contains(&row) && l.contains(&format!("\"wave\": {wave},"))),
                "no wave{wave} row of {scene}"
            );
        }
    }
}
