//! The on-disk pipeline cache from the environment, end to end: `GLINT_CACHE_DIR` and
//! `$XDG_CACHE_HOME/glint` are where its files go, `GLINT_PIPELINE_CACHE=off` writes
//! nothing, and any other value of the switch is an error naming it. (What the files
//! hold, and how damaged ones are refused, is `tests/gpu/gpu_disk_cache.rs`.)

use crate::common;

use common::{corpus, temp_dir};
use std::path::Path;
use std::process::{Command, Output};

/// A 16² GPU render of simple.lua (AA none: one pipeline) in `dir` with `env` set and
/// the cache variables of the caller's environment removed.
fn render(dir: &Path, env: &[(&str, &Path)], switch: Option<&str>) -> Output {
    let scene = corpus().join("a4-2021plus/simple.lua");
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command
        .args(["render", scene.to_str().unwrap(), "-o", "out.png"])
        .args(["--width", "16", "--height", "16", "--aa", "none"])
        .args(["--backend", "gpu", "--stats"])
        .current_dir(dir)
        .env_remove("GLINT_CACHE_DIR")
        .env_remove("GLINT_PIPELINE_CACHE");
    for (var, value) in env {
        command.env(var, value);
    }
    if let Some(switch) = switch {
        command.env("GLINT_PIPELINE_CACHE", switch);
    }
    command.output().expect("glint runs")
}

fn cache_files(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    entries
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn the_cache_goes_where_the_environment_says_and_off_writes_nothing() {
    let dir = temp_dir("pipeline-cache-env");
    let (named, xdg, off) = (dir.join("named"), dir.join("xdg"), dir.join("off"));
    let home = dir.join("home");

    let out = render(&dir, &[("GLINT_CACHE_DIR", &named), ("HOME", &home)], None);
    assert!(out.status.success(), "{}", stderr(&out));
    let log = stderr(&out);
    assert!(log.contains("pipeline cache: 0 reused, 1 written"), "{log}");
    assert_eq!(cache_files(&named).len(), 1, "{:?}", cache_files(&named));

    let out = render(&dir, &[("XDG_CACHE_HOME", &xdg), ("HOME", &home)], None);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(cache_files(&xdg.join("glint")).len(), 1);

    let off: &Path = &off;
    let env = [
        ("GLINT_CACHE_DIR", off),
        ("XDG_CACHE_HOME", off),
        ("HOME", off),
    ];
    let out = render(&dir, &env, Some("off"));
    assert!(out.status.success(), "{}", stderr(&out));
    let log = stderr(&out);
    assert!(log.contains("1 uncached"), "{log}");
    // Mesa's own shader cache may go under $HOME or $XDG_CACHE_HOME; glint's does not.
    let glint_files: Vec<String> = cache_files(off)
        .into_iter()
        .chain(cache_files(&off.join("glint")))
        .filter(|n| n.ends_with(".bin") || n == "glint")
        .collect();
    assert!(glint_files.is_empty(), "{glint_files:?}");
    assert!(!home.join(".cache").join("glint").exists());
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn another_value_of_the_switch_is_an_error_naming_it() {
    let dir = temp_dir("pipeline-cache-switch");
    let named = dir.join("named");
    let out = render(&dir, &[("GLINT_CACHE_DIR", &named)], Some("no"));
    assert!(!out.status.success());
    let err = stderr(&out);
    assert!(
        err.contains("GLINT_PIPELINE_CACHE=\"no\": expected on or off"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(!dir.join("out.png").exists() && !named.exists());
}
