//! `fairsub view` as a child process, and raw HTTP requests to it (shared by the viewer
//! tests; each test binary uses part of it).
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A running `fairsub view`, killed when dropped.
pub struct Viewer {
    pub child: Child,
    pub url: String,
    pub port: u16,
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

pub fn start(args: &[&str]) -> Viewer {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .arg("view")
        .args(args)
        .args(["--no-browser", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("fairsub runs");
    let mut line = String::new();
    BufReader::new(child.stdout.take().expect("piped"))
        .read_line(&mut line)
        .expect("first line");
    let url = line.trim().to_string();
    let rest = url
        .strip_prefix("http://127.0.0.1:")
        .unwrap_or_else(|| panic!("first line is the URL on 127.0.0.1, got '{url}'"));
    let port = rest[..rest.find('/').expect("path")].parse().expect("port");
    Viewer { child, url, port }
}

/// Status and body of a raw GET of `path` (sent as it is, no normalisation), addressed to the
/// server itself (`Host: 127.0.0.1:PORT`).
pub fn get(port: u16, path: &str) -> (u16, Vec<u8>) {
    get_as(port, path, Some(&format!("127.0.0.1:{port}")))
}

/// [`get`] with the given `Host` header (none with `None`).
pub fn get_as(port: u16, path: &str, host: Option<&str>) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    let host = host.map(|h| format!("Host: {h}\r\n")).unwrap_or_default();
    write!(s, "GET {path} HTTP/1.0\r\n{host}\r\n").unwrap();
    let mut buf = Vec::new();
    s.read_to_end(&mut buf).expect("reply");
    let head_end = buf
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("headers");
    let head = String::from_utf8_lossy(&buf[..head_end]).to_string();
    let status = head
        .split(' ')
        .nth(1)
        .expect("status")
        .parse()
        .expect("code");
    (status, buf[head_end + 4..].to_vec())
}
