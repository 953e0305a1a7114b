//! Progress: a bar on a terminal, and `OUTPUT_FILE: path` lines (as Houdini PDG reads them)
//! otherwise.

use std::io::{IsTerminal, Write};
use std::path::Path;

use indicatif::{ProgressBar, ProgressStyle};

use crate::bake::Progress;

/// One line per written file on stdout: `OUTPUT_FILE: path`.
pub struct Lines;

impl Progress for Lines {
    fn start(&mut self, _: u64) {}
    fn written(&mut self, path: &Path) {
        let mut out = std::io::stdout().lock();
        let _ = writeln!(out, "OUTPUT_FILE: {}", path.display());
        let _ = out.flush();
    }
}

/// A progress bar on stderr.
pub struct Bar(Option<ProgressBar>);

impl Progress for Bar {
    fn start(&mut self, files: u64) {
        let bar = ProgressBar::new(files);
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed_precise} [{wide_bar}] {pos}/{len} files, {per_sec}, {eta} left",
            )
            .expect("a valid template"),
        );
        self.0 = Some(bar);
    }
    fn written(&mut self, _: &Path) {
        if let Some(bar) = &self.0 {
            bar.inc(1);
        }
    }
    fn finish(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish();
            // The summary that follows starts on a line of its own.
            eprintln!();
        }
    }
}

/// A bar when stdout is a terminal, lines otherwise.
pub fn for_stdout() -> Box<dyn Progress> {
    if std::io::stdout().is_terminal() {
        Box::new(Bar(None))
    } else {
        Box::new(Lines)
    }
}
