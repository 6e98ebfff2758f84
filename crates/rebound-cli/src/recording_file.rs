//! Opening a recording file for the commands that read one.

use crate::error::CliError;
use rebound_record::FrameReader;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;

/// A reader of the recording at `path`, its header and manifest read and checked.
///
/// # Errors
/// [`CliError::Read`] if the file cannot be opened; [`CliError::Recording`] if it is not a recording.
pub fn open(path: &Path) -> Result<FrameReader<BufReader<File>>, CliError> {
    let file = File::open(path).map_err(|source| CliError::Read {
        path: path.to_owned(),
        source,
    })?;
    Ok(FrameReader::new(BufReader::new(file))?)
}
