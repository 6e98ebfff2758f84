//! `rebound view`: the command serves the viewer's files and the recording on 127.0.0.1 at the address it
//! prints, and refuses to start without a complete viewer directory. Every wait is bounded.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const WAIT: Duration = Duration::from_secs(30);

/// A fresh directory under the system's temporary directory, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("rebound-cli-view-{}-{name}", std::process::id()));
        let _absent = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _best_effort = std::fs::remove_dir_all(&self.0);
    }
}

/// The server process, killed when the test ends however it ends.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _gone = self.0.kill();
        let _reaped = self.0.wait();
    }
}

const INDEX: &str = "<!doctype html><title>viewer</title>";
const THREE: &str = "export const REVISION = 'test';";

/// A viewer directory with the two files `rebound view` checks for, and a recording (a valid file header:
/// the server checks the magic and version, and serves the bytes as they are).
fn fixture(name: &str) -> (TempDir, PathBuf, Vec<u8>) {
    let dir = TempDir::new(name);
    let viewer = dir.0.join("viewer");
    std::fs::create_dir_all(viewer.join("node_modules/three/build")).expect("dirs");
    std::fs::write(viewer.join("index.html"), INDEX).expect("write");
    std::fs::write(
        viewer.join("node_modules/three/build/three.module.js"),
        THREE,
    )
    .expect("write");
    // The header `rebound view` checks before serving (magic and format version), then bytes it passes on.
    let mut recording = rebound_record::MAGIC.to_vec();
    recording.extend_from_slice(&rebound_record::VERSION.to_le_bytes());
    recording.extend_from_slice(&[7u8; 100]);
    let file = dir.0.join("the run.rrec");
    std::fs::write(&file, &recording).expect("write");
    (dir, viewer, recording)
}

fn view(viewer: &Path, recording: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rebound"));
    command
        .arg("view")
        .arg(recording)
        .arg("--viewer-dir")
        .arg(viewer)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    command
}

/// One GET over loopback: the status code, the headers (lower-cased) and the body.
fn get(address: &str, path: &str) -> (u16, String, Vec<u8>) {
    let mut stream = TcpStream::connect(address).expect("connect");
    stream.set_read_timeout(Some(WAIT)).expect("timeout");
    stream.set_write_timeout(Some(WAIT)).expect("timeout");
    write!(
        stream,
        "GET {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\n\r\n"
    )
    .expect("request");
    let mut response = Vec::new();
    stream.read_to_end(&mut response).expect("response");
    let split = response
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header block");
    let head = String::from_utf8_lossy(&response[..split]).to_lowercase();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("a status code");
    (status, head, response[split + 4..].to_vec())
}

#[test]
fn view_serves_the_viewer_and_the_recording_at_the_printed_address() {
    let (dir, viewer, recording) = fixture("serves");
    let mut child = view(&viewer, &dir.0.join("the run.rrec"))
        .spawn()
        .expect("rebound view starts");
    let stdout = child.stdout.take().expect("stdout");
    let _server = Server(child);
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _read = BufReader::new(stdout).read_line(&mut line);
        let _sent = sender.send(line);
    });
    let line = receiver
        .recv_timeout(WAIT)
        .expect("rebound view prints its address");
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .expect("an http:// address");
    let rest = url.strip_prefix("http://").expect("http");
    let (address, page) = rest.split_at(rest.find('/').expect("a path"));
    assert!(address.starts_with("127.0.0.1:"), "{line}");
    assert_eq!(page, "/?file=/recording/the%20run.rrec");

    let (status, head, body) = get(address, page);
    assert_eq!((status, body.as_slice()), (200, INDEX.as_bytes()));
    assert!(head.contains("content-type: text/html"), "{head}");
    let (status, head, body) = get(address, "/node_modules/three/build/three.module.js");
    assert_eq!((status, body.as_slice()), (200, THREE.as_bytes()));
    assert!(head.contains("content-type: text/javascript"), "{head}");
    let (status, _, body) = get(address, "/recording/the%20run.rrec");
    assert_eq!((status, body), (200, recording));
    assert_eq!(get(address, "/../the%20run.rrec").0, 404);
    assert_eq!(get(address, "/missing.js").0, 404);
}

/// Waits for `child` to exit, at most WAIT; its status and standard error.
fn exit_of(mut child: Child) -> (Option<i32>, String) {
    let deadline = Instant::now() + WAIT;
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            let mut stderr = String::new();
            let _read = child
                .stderr
                .take()
                .expect("stderr")
                .read_to_string(&mut stderr);
            return (status.code(), stderr);
        }
        assert!(Instant::now() < deadline, "rebound view did not exit");
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn view_refuses_a_viewer_without_three_and_a_file_that_is_not_a_recording() {
    let (dir, viewer, _) = fixture("refuses");
    std::fs::remove_file(viewer.join("node_modules/three/build/three.module.js")).expect("remove");
    let (code, stderr) = exit_of(
        view(&viewer, &dir.0.join("the run.rrec"))
            .spawn()
            .expect("starts"),
    );
    assert_eq!(code, Some(1));
    assert!(
        stderr.contains("node_modules/three/build/three.module.js") && stderr.contains("npm ci"),
        "{stderr}"
    );

    let (dir, viewer, _) = fixture("not-a-recording");
    std::fs::write(dir.0.join("notes.txt"), "just text").expect("write");
    let (code, stderr) = exit_of(
        view(&viewer, &dir.0.join("notes.txt"))
            .spawn()
            .expect("starts"),
    );
    assert_eq!(code, Some(1));
    assert!(
        stderr.contains("notes.txt") && stderr.contains("not a Rebound recording"),
        "{stderr}"
    );
}
