//! The sandbox flags every subcommand that runs a script takes (`render`, `bench`, `view`),
//! parsed by clap and turned into the library's [`ScriptSettings`] (one script driver:
//! `glint::script_driver`).

use glint::scene::lua::{ScriptConfig, DEFAULT_MEMORY_LIMIT, DEFAULT_TIME_LIMIT};
use glint::scene::TransformOrder;
use glint::script_driver::ScriptSettings;
use std::path::PathBuf;
use std::time::Duration;

/// The sandbox flags every subcommand that runs a script takes (`render`, `bench`).
#[derive(Clone, Debug, clap::Args)]
pub struct ScriptArgs {
    /// Lua instructions a script may run before it is stopped as a runaway.
    #[arg(long, default_value_t = ScriptConfig::default().instruction_limit,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub instruction_limit: u64,
    /// Wall-clock seconds the script may run (renders not counted).
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_TIME_LIMIT.as_secs(),
          value_parser = clap::value_parser!(u64).range(1..=86_400))]
    pub script_timeout: u64,
    /// Memory budget in MiB: the Lua heap, the scene and each render's build.
    #[arg(long, value_name = "MIB", default_value_t = (DEFAULT_MEMORY_LIMIT >> 20) as u64,
          value_parser = clap::value_parser!(u64).range(16..=1 << 20))]
    pub memory_limit: u64,
    /// A folder the scene may read meshes, textures and modules from, besides its own
    /// (repeatable).
    #[arg(long, value_name = "DIR")]
    pub allow_read: Vec<PathBuf>,
    /// A Lua file run before the scene, in the same sandbox and limits, with its own
    /// folder readable: maps another CS488 tracer's calls onto glint's (repeatable, run
    /// in order; see scenes/dialects/).
    #[arg(long, value_name = "FILE")]
    pub prelude: Vec<PathBuf>,
    /// No notes on stderr about arguments the scene passes that glint does not use (as
    /// the scene's own gr.ignore_extra_arguments()).
    #[arg(long)]
    pub ignore_extra_arguments: bool,
    /// Most gr.render calls one script may make.
    #[arg(long, value_name = "N", default_value_t = ScriptConfig::default().max_renders,
          value_parser = clap::value_parser!(u64).range(1..=1 << 20))]
    pub max_renders: u64,
    /// Most pixels all of a script's gr.render calls may ask for together.
    #[arg(long, value_name = "N", default_value_t = ScriptConfig::default().max_render_pixels,
          value_parser = clap::value_parser!(u64).range(1..=1 << 40))]
    pub max_render_pixels: u64,
}

impl ScriptArgs {
    /// The settings these flags ask for, with the command line's hard time limit; a
    /// `--allow-read` that names no folder is a usage error (the message says which).
    pub fn settings(
        &self,
        transform_order: Option<TransformOrder>,
    ) -> Result<ScriptSettings, String> {
        for dir in &self.allow_read {
            if !dir.is_dir() {
                return Err(format!(
                    "--allow-read {}: not a folder",
                    glint::display_path::shown(dir)
                ));
            }
        }
        for file in &self.prelude {
            if !file.is_file() {
                return Err(format!(
                    "--prelude {}: not a file",
                    glint::display_path::shown(file)
                ));
            }
        }
        Ok(ScriptSettings {
            transform_order,
            instruction_limit: Some(self.instruction_limit),
            script_timeout: Some(Duration::from_secs(self.script_timeout)),
            memory_limit: Some((self.memory_limit << 20) as usize),
            allow_read: self.allow_read.clone(),
            preludes: self.prelude.clone(),
            hard_time_limit: true,
            ignore_extra_arguments: self.ignore_extra_arguments,
            max_renders: Some(self.max_renders),
            max_render_pixels: Some(self.max_render_pixels),
            frame: None,
        })
    }
}
