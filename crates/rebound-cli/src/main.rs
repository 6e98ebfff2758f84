//! `rebound`: run Rebound scene files and see what happened.
//!
//! ```text
//! rebound run scenes/newtons_cradle.ron --gif cradle.gif
//! rebound run newtons_cradle --gif cradle.gif     # the same scene, built in: from any directory
//! rebound run scenes/pyramid.ron --seconds 5 --png-every 60 frames/ --camera 14,12,26:0,7,0:45
//! rebound run scenes/rope_bridge.ron --record bridge.rrec --plot bridge.svg
//! rebound info bridge.rrec --json
//! rebound render bridge.rrec --gif bridge.gif --size 320x240
//! rebound plot bridge.rrec -o bridge.svg
//! rebound view cradle.rrec
//! ```
//!
//! Each subcommand lives in its own module; `main` parses the arguments (clap), runs the subcommand and turns
//! an error into a message on standard error and exit status 1 (clap's own usage errors exit with 2).

mod bundled;
mod cli;
mod drawing;
mod error;
mod info;
mod pictures;
mod plot;
mod progress;
mod recording_file;
mod render;
mod run;
mod view;

use clap::Parser;
use std::io::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    let result = match &cli.command {
        cli::Command::Run(args) => run::run(args),
        cli::Command::Info(args) => info::info(args),
        cli::Command::Render(args) => render::render(args),
        cli::Command::Plot(args) => plot::plot(args),
        cli::Command::View(args) => view::view(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            let mut message = format!("error: {error}");
            let mut source = std::error::Error::source(&error);
            while let Some(cause) = source {
                // Most errors quote their cause already; print only what is new.
                let cause_text = cause.to_string();
                if !message.contains(&cause_text) {
                    message.push_str(&format!("\n  caused by: {cause_text}"));
                }
                source = cause.source();
            }
            let _ = writeln!(std::io::stderr(), "{message}");
            ExitCode::FAILURE
        }
    }
}
