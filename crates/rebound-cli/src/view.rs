//! `rebound view RECORDING`: serves the web viewer (`viewer/`) and one recording on 127.0.0.1.
//!
//! The viewer is plain static files (HTML, ES modules, three.js from `viewer/node_modules`), so serving it is
//! mapping URL paths to files under the viewer directory; tiny_http does the HTTP. The recording is served at
//! `/recording/<its file name>`, and the printed address opens the page with `?file=` pointing there.
//! The server runs until the process ends: Ctrl-C's default action stops it, and nothing needs cleaning up.

use std::fmt;
use std::fs::File;
use std::io::{self, Read, Write};
use std::net::{Ipv4Addr, SocketAddr};
use std::path::{Component, Path, PathBuf};

use rebound_record::{MAGIC, VERSION};
use tiny_http::{Header, Method, Request, Response, Server};

use crate::cli::ServeArgs;
use crate::error::{CliError, ViewError};

/// The file the viewer needs from `npm ci`, checked before serving so a missing install is named up front.
const THREE_MODULE: &str = "node_modules/three/build/three.module.js";

/// Where the recording is served; any name after it (the file's own, for the page's title) gives the file.
const RECORDING_PREFIX: &str = "/recording/";

/// Serves the viewer and `args.recording` until the process ends, after printing the address to open.
///
/// # Errors
/// The viewer directory is incomplete, the recording is not one, or no port can be bound; nothing is served.
pub fn view(args: &ServeArgs) -> Result<(), CliError> {
    let viewer_dir = args.viewer_dir.clone().unwrap_or_else(default_viewer_dir);
    let site = Site::new(&viewer_dir, &args.recording)?;
    let server = ViewServer::bind(site, args.port)?;
    let mut out = io::stdout().lock();
    writeln!(
        out,
        "serving {} at {} (Ctrl-C stops)",
        args.recording.display(),
        server.page_url()
    )
    .and_then(|()| out.flush())
    .map_err(|source| CliError::Write {
        path: "standard output".into(),
        source,
    })?;
    drop(out);
    server.serve();
    Ok(())
}

/// The viewer directory used when none is given: `REBOUND_VIEWER_DIR`, else `viewer/` of this source tree.
#[must_use]
pub fn default_viewer_dir() -> PathBuf {
    std::env::var_os("REBOUND_VIEWER_DIR").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../../viewer"),
        PathBuf::from,
    )
}

/// The files one `rebound view` serves: the viewer directory and one recording.
#[derive(Debug, Clone)]
pub struct Site {
    viewer_dir: PathBuf,
    recording: PathBuf,
    recording_name: String,
}

impl Site {
    /// Checks that the viewer directory is complete and the recording opens as one (its header only: the
    /// page checks the rest and says what is wrong).
    ///
    /// # Errors
    /// [`ViewError::ViewerIncomplete`] naming the missing file, [`ViewError::Recording`] if the recording
    /// cannot be opened, [`ViewError::NotARecording`] if it does not start with the format's header.
    pub fn new(viewer_dir: &Path, recording: &Path) -> Result<Self, ViewError> {
        for missing in ["index.html", THREE_MODULE] {
            if !viewer_dir.join(missing).is_file() {
                return Err(ViewError::ViewerIncomplete {
                    dir: viewer_dir.to_path_buf(),
                    missing,
                });
            }
        }
        let opened = |source| ViewError::Recording {
            path: recording.to_path_buf(),
            source,
        };
        let not_a_recording = || ViewError::NotARecording {
            path: recording.to_path_buf(),
        };
        let mut header = [0u8; 12];
        match File::open(recording)
            .map_err(opened)?
            .read_exact(&mut header)
        {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return Err(not_a_recording()),
            Err(e) => return Err(opened(e)),
        }
        if header[..8] != MAGIC || header[8..] != VERSION.to_le_bytes() {
            return Err(not_a_recording());
        }
        let recording_name = recording.file_name().map_or_else(
            || "recording.rrec".to_owned(),
            |n| n.to_string_lossy().into_owned(),
        );
        Ok(Self {
            viewer_dir: viewer_dir.to_path_buf(),
            recording: recording.to_path_buf(),
            recording_name,
        })
    }

    /// The page's path and query that open the recording: `/?file=/recording/<name>`.
    #[must_use]
    pub fn page_path(&self) -> String {
        format!(
            "/?file={RECORDING_PREFIX}{}",
            percent_encode(&self.recording_name)
        )
    }

    /// The file answering the URL path `url` (query and fragment ignored), or `None` for "not found".
    /// Only files inside the viewer directory and the recording are ever answered: a path with `..`, an
    /// empty segment or a backslash resolves to nothing.
    #[must_use]
    pub fn resolve(&self, url: &str) -> Option<PathBuf> {
        let path = url.split(['?', '#']).next().unwrap_or_default();
        let path = percent_decode(path)?;
        if path.starts_with(RECORDING_PREFIX) {
            return Some(self.recording.clone());
        }
        let relative = match path.strip_prefix('/')? {
            "" => "index.html",
            rest => rest,
        };
        if relative.contains('\\')
            || relative
                .split('/')
                .any(|s| s.is_empty() || s == "." || s == "..")
        {
            return None;
        }
        let relative = Path::new(relative);
        if !relative
            .components()
            .all(|c| matches!(c, Component::Normal(_)))
        {
            return None;
        }
        let file = self.viewer_dir.join(relative);
        file.is_file().then_some(file)
    }
}

/// A running `rebound view` server on 127.0.0.1.
pub struct ViewServer {
    server: Server,
    site: Site,
    address: SocketAddr,
}

impl fmt::Debug for ViewServer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ViewServer")
            .field("site", &self.site)
            .field("address", &self.address)
            .finish()
    }
}

impl ViewServer {
    /// Listens on 127.0.0.1 at `port` (0 picks a free one).
    ///
    /// # Errors
    /// [`ViewError::Bind`] if the port cannot be bound.
    pub fn bind(site: Site, port: u16) -> Result<Self, ViewError> {
        let server = Server::http((Ipv4Addr::LOCALHOST, port)).map_err(|e| ViewError::Bind {
            port,
            reason: e.to_string(),
        })?;
        let address = server
            .server_addr()
            .to_ip()
            .ok_or_else(|| ViewError::Bind {
                port,
                reason: "not an IP socket".to_owned(),
            })?;
        Ok(Self {
            server,
            site,
            address,
        })
    }

    /// The address to open in a browser: the viewer with the recording loaded.
    #[must_use]
    pub fn page_url(&self) -> String {
        format!("http://{}{}", self.address, self.site.page_path())
    }

    /// Answers requests until the process ends.
    pub fn serve(&self) {
        for request in self.server.incoming_requests() {
            self.answer(request);
        }
    }

    /// Answers one request: the file for its path, 404 if none, 405 for anything but GET and HEAD.
    fn answer(&self, request: Request) {
        // A client that hangs up mid-answer is its own business; the server goes on.
        let _ignored = match request.method() {
            Method::Get | Method::Head => match self
                .site
                .resolve(request.url())
                .map(|p| (File::open(&p), p))
            {
                Some((Ok(file), path)) => {
                    let mut response = Response::from_file(file);
                    if let Ok(header) = Header::from_bytes("Content-Type", content_type(&path)) {
                        response = response.with_header(header);
                    }
                    request.respond(response)
                }
                Some((Err(_), _)) | None => {
                    request.respond(Response::from_string("not found").with_status_code(404))
                }
            },
            _ => request.respond(Response::from_string("method not allowed").with_status_code(405)),
        };
    }
}

/// The Content-Type for a served file, by extension (ES modules must be served as JavaScript).
fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("json") => "application/json",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        _ => "application/octet-stream",
    }
}

/// `%XX` escapes decoded; `None` for a malformed escape or bytes that are not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Every byte outside `A–Z a–z 0–9 - . _ ~` as `%XX`, for a file name in a URL.
fn percent_encode(s: &str) -> String {
    use std::fmt::Write as _;
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~') {
            out.push(char::from(b));
        } else {
            let _infallible = write!(out, "%{b:02X}");
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory under the system's temporary directory, removed on drop.
    struct TempDir(PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            let dir =
                std::env::temp_dir().join(format!("rebound-view-{}-{name}", std::process::id()));
            let _absent = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).expect("a temporary directory");
            Self(dir)
        }

        fn path(&self) -> &Path {
            &self.0
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _best_effort = std::fs::remove_dir_all(&self.0);
        }
    }

    fn site(name: &str) -> (TempDir, Site) {
        let dir = TempDir::new(name);
        std::fs::create_dir_all(dir.path().join("viewer/node_modules/three/build")).expect("dirs");
        std::fs::create_dir_all(dir.path().join("viewer/src")).expect("dirs");
        std::fs::write(dir.path().join("viewer/index.html"), "<!doctype html>").expect("write");
        std::fs::write(dir.path().join("viewer").join(THREE_MODULE), "export {}").expect("write");
        std::fs::write(dir.path().join("viewer/src/main.js"), "// main").expect("write");
        std::fs::write(dir.path().join("secret.txt"), "outside").expect("write");
        let mut header = MAGIC.to_vec();
        header.extend_from_slice(&VERSION.to_le_bytes());
        std::fs::write(dir.path().join("run 1.rrec"), header).expect("write");
        let site =
            Site::new(&dir.path().join("viewer"), &dir.path().join("run 1.rrec")).expect("site");
        (dir, site)
    }

    #[test]
    fn paths_map_to_viewer_files_and_the_recording_only() {
        let (dir, site) = site("paths");
        let viewer = dir.path().join("viewer");
        assert_eq!(site.resolve("/"), Some(viewer.join("index.html")));
        assert_eq!(
            site.resolve("/?file=/recording/x"),
            Some(viewer.join("index.html"))
        );
        assert_eq!(
            site.resolve("/src/main.js"),
            Some(viewer.join("src/main.js"))
        );
        assert_eq!(
            site.resolve("/recording/run%201.rrec"),
            Some(dir.path().join("run 1.rrec"))
        );
        assert_eq!(site.page_path(), "/?file=/recording/run%201.rrec");
        for outside in [
            "/../secret.txt",
            "/src/../../secret.txt",
            "/%2e%2e/secret.txt",
            "//etc/passwd",
            "/src\\..\\x",
        ] {
            assert_eq!(site.resolve(outside), None, "{outside}");
        }
        assert_eq!(site.resolve("/missing.js"), None);
        assert_eq!(site.resolve("/bad%zzescape"), None);
    }

    #[test]
    fn an_incomplete_viewer_or_a_missing_recording_is_named() {
        let (dir, _) = site("incomplete");
        std::fs::remove_file(dir.path().join("viewer").join(THREE_MODULE)).expect("remove");
        let error = Site::new(&dir.path().join("viewer"), &dir.path().join("run 1.rrec"))
            .expect_err("incomplete");
        assert!(
            error
                .to_string()
                .contains("node_modules/three/build/three.module.js"),
            "{error}"
        );
        assert!(error.to_string().contains("npm ci"), "{error}");
        let error = Site::new(&dir.path().join("nowhere"), &dir.path().join("run 1.rrec"))
            .expect_err("no viewer");
        assert!(error.to_string().contains("index.html"), "{error}");
    }
}
