//! The render's progress bar on stderr (indicatif): the library's
//! [`ProgressSink`](glint::pipeline::ProgressSink) drawn, one bar per render.

use glint::pipeline::ProgressSink;
use std::path::Path;
use std::sync::Mutex;

/// A bar for each render, drawn while it runs and cleared when its film is made.
#[derive(Debug, Default)]
pub struct ProgressBars {
    current: Mutex<Option<indicatif::ProgressBar>>,
}

impl ProgressSink for ProgressBars {
    fn begin(&self, output: &Path) {
        *self.current.lock().unwrap_or_else(|e| e.into_inner()) = Some(progress_bar(output));
    }

    fn advance(&self, done: u64, total: u64) {
        if let Some(bar) = self
            .current
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .as_ref()
        {
            bar.set_length(total);
            bar.set_position(done);
        }
    }

    fn end(&self) {
        if let Some(bar) = self
            .current
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
        {
            bar.finish_and_clear();
        }
    }
}

fn progress_bar(output: &Path) -> indicatif::ProgressBar {
    // indicatif draws only when stderr is a terminal.
    let bar = indicatif::ProgressBar::new(1);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {percent}% ({elapsed} < {eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(format!("rendering {}", glint::display_path::shown(output)));
    bar
}
