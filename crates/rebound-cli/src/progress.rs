//! A progress bar for long runs and renders (indicatif), drawn on standard error only when both standard
//! output and standard error are terminals, so that pipes, files and tests see no control characters.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Runs shorter than this many items get no bar.
const MIN_ITEMS: u64 = 200;

/// Files smaller than this many bytes get no bar.
const MIN_BYTES: u64 = 1 << 20;

/// A bar of `total` items labelled `what`, hidden when not on a terminal or for short jobs.
#[must_use]
pub fn bar(total: u64, what: &str) -> ProgressBar {
    styled(total, total >= MIN_ITEMS, what, "{pos}/{len}")
}

/// A bar over `total` bytes of a file being read, hidden when not on a terminal or for small files.
#[must_use]
pub fn byte_bar(total: u64, what: &str) -> ProgressBar {
    styled(total, total >= MIN_BYTES, what, "{bytes}/{total_bytes}")
}

fn styled(total: u64, long: bool, what: &str, counts: &str) -> ProgressBar {
    let on_terminal = std::io::stdout().is_terminal() && std::io::stderr().is_terminal();
    if !on_terminal || !long {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let template = format!("{{msg:>10}} [{{bar:40}}] {counts} ({{eta}} left)");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_owned());
    bar
}
