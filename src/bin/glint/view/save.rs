//! Where S writes: `-o` (numbered -2, -3… after the first save, as `render` numbers a
//! script's later images), else the script's own image name numbered `-view-0001`,
//! `-view-0002`… under the same write rule as `render` ([`WritePolicy`]).

use super::config::ViewConfig;
use glint::pipeline::output_path;
use glint::write_policy::WritePolicy;
use std::path::{Path, PathBuf};

/// `name` with `-view-NNNN` (k + 1, at least four digits) before its extension.
pub fn numbered(name: &Path, k: usize) -> PathBuf {
    let numbered = format!("-view-{:04}", k + 1);
    match (name.file_stem(), name.extension()) {
        (None, _) => name.with_file_name(format!("view{numbered}.png")),
        (Some(_), None) => glint::file_name::with_suffix(name, &format!("{numbered}.png")),
        (Some(_), Some(_)) => glint::file_name::with_suffix(name, &numbered),
    }
}

/// The path of the `k`-th save (0-based) of a view whose script names `script_output`.
pub fn save_path(config: &ViewConfig, script_output: &Path, k: usize) -> Result<PathBuf, String> {
    if let Some(o) = config.output.as_deref() {
        return Ok(output_path(Some(o), script_output, k));
    }
    let policy = WritePolicy::new(config.output_dir.as_deref(), &config.allow_write)?;
    policy.place(&numbered(script_output, k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saves_are_numbered_before_the_extension() {
        assert_eq!(
            numbered(Path::new("out/demo.png"), 0),
            Path::new("out/demo-view-0001.png")
        );
        assert_eq!(
            numbered(Path::new("demo.exr"), 11),
            Path::new("demo-view-0012.exr")
        );
        assert_eq!(
            numbered(Path::new("demo"), 0),
            Path::new("demo-view-0001.png")
        );
    }
}
