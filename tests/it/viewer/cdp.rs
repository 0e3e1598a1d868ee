//! A small Chrome DevTools Protocol client for the viewer's test and frame-rate benchmark:
//! headless Chromium (SwiftShader WebGL2) with a remote-debugging port, one page driven over
//! a WebSocket (written here: the handshake, masked text frames out, text frames in), so that
//! the page runs in real time and takes real input events. No browser automation crate.

// The test and the benchmark use different parts.
#![allow(dead_code)]

use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The browser of the environment: `chromium` or `chromium-browser`, if one runs.
pub fn find() -> Option<PathBuf> {
    ["chromium", "chromium-browser"].iter().find_map(|c| {
        let ok = Command::new(c)
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .ok()?
            .success();
        ok.then(|| PathBuf::from(c))
    })
}

/// A headless Chromium with one page under control; killed (and its profile removed) on drop.
pub struct Browser {
    child: Child,
    profile: PathBuf,
    ws: TcpStream,
    next: u64,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// The body of an HTTP GET on 127.0.0.1 (empty when the server is not ready yet). DevTools
/// answers HTTP/1.1 only and keeps the connection: the body is read by its Content-Length.
fn http_get(port: u16, path: &str) -> String {
    let get = || -> std::io::Result<String> {
        let s = TcpStream::connect(("127.0.0.1", port))?;
        s.set_read_timeout(Some(Duration::from_secs(10)))?;
        write!(&s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n")?;
        let mut r = BufReader::new(s);
        let mut len = 0;
        loop {
            let mut l = String::new();
            r.read_line(&mut l)?;
            if l.trim().is_empty() {
                break;
            }
            if let Some((k, v)) = l.split_once(':')
                && k.eq_ignore_ascii_case("content-length")
            {
                len = v.trim().parse().unwrap_or(0);
            }
        }
        let mut body = vec![0; len];
        r.read_exact(&mut body)?;
        Ok(String::from_utf8_lossy(&body).into_owned())
    };
    get().unwrap_or_default()
}

impl Browser {
    /// Starts Chromium with a `width` x `height` viewport on about:blank and connects to it.
    pub fn launch(exe: &Path, width: u32, height: u32) -> Browser {
        static LAUNCHED: AtomicUsize = AtomicUsize::new(0);
        let profile = std::env::temp_dir().join(format!(
            "fairsub-cdp-{}-{}",
            std::process::id(),
            LAUNCHED.fetch_add(1, Ordering::SeqCst)
        ));
        let _ = std::fs::remove_dir_all(&profile);
        std::fs::create_dir_all(&profile).unwrap();
        let child = Command::new(exe)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu-sandbox",
                "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--disable-extensions",
                "--no-first-run",
                "--hide-scrollbars",
                "--remote-debugging-port=0",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(format!("--window-size={width},{height}"))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromium starts");
        // Chromium writes its port to DevToolsActivePort in the profile.
        let t0 = Instant::now();
        let port: u16 = loop {
            if let Ok(s) = std::fs::read_to_string(profile.join("DevToolsActivePort"))
                && let Some(Ok(p)) = s.lines().next().map(str::parse)
            {
                break p;
            }
            assert!(t0.elapsed() < Duration::from_secs(30), "no DevTools port");
            std::thread::sleep(Duration::from_millis(50));
        };
        let page = loop {
            let list: Value =
                serde_json::from_str(&http_get(port, "/json/list")).unwrap_or_default();
            let found = list.as_array().and_then(|l| {
                l.iter()
                    .find(|t| t["type"] == "page" && t["url"] == "about:blank")
                    .and_then(|t| t["webSocketDebuggerUrl"].as_str().map(str::to_string))
            });
            if let Some(u) = found {
                break u;
            }
            assert!(t0.elapsed() < Duration::from_secs(30), "no page target");
            std::thread::sleep(Duration::from_millis(50));
        };
        let path = &page[page.find("/devtools").expect("ws path")..];
        let mut ws = TcpStream::connect(("127.0.0.1", port)).unwrap();
        ws.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
        write!(
            ws,
            "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n\
             Connection: Upgrade\r\nSec-WebSocket-Key: ZmFpcnN1YnZpZXdlcnRlc3Q=\r\n\
             Sec-WebSocket-Version: 13\r\n\r\n"
        )
        .unwrap();
        let mut r = BufReader::new(ws.try_clone().unwrap());
        let mut status = String::new();
        r.read_line(&mut status).unwrap();
        assert!(status.contains(" 101 "), "websocket upgrade: {status}");
        loop {
            let mut l = String::new();
            r.read_line(&mut l).unwrap();
            if l == "\r\n" {
                break;
            }
        }
        let mut b = Browser {
            child,
            profile,
            ws,
            next: 0,
        };
        b.call(
            "Emulation.setDeviceMetricsOverride",
            json!({"width": width, "height": height, "deviceScaleFactor": 1, "mobile": false}),
        );
        b
    }

    fn send(&mut self, text: &str) {
        let p = text.as_bytes();
        let mut f = vec![0x81u8];
        match p.len() {
            n if n < 126 => f.push(0x80 | n as u8),
            n if n < 65536 => {
                f.push(0x80 | 126);
                f.extend_from_slice(&(n as u16).to_be_bytes());
            }
            n => {
                f.push(0x80 | 127);
                f.extend_from_slice(&(n as u64).to_be_bytes());
            }
        }
        let mask = [0x5a, 0x17, 0xc3, 0x88];
        f.extend_from_slice(&mask);
        f.extend(p.iter().enumerate().map(|(i, b)| b ^ mask[i % 4]));
        self.ws.write_all(&f).unwrap();
    }

    /// One message (a text frame and its continuations).
    fn receive(&mut self) -> String {
        let mut msg = Vec::new();
        loop {
            let mut h = [0u8; 2];
            self.ws.read_exact(&mut h).expect("devtools message");
            let len = match h[1] & 0x7f {
                126 => {
                    let mut b = [0u8; 2];
                    self.ws.read_exact(&mut b).unwrap();
                    u16::from_be_bytes(b) as usize
                }
                127 => {
                    let mut b = [0u8; 8];
                    self.ws.read_exact(&mut b).unwrap();
                    u64::from_be_bytes(b) as usize
                }
                n => n as usize,
            };
            let mut body = vec![0u8; len];
            self.ws.read_exact(&mut body).unwrap();
            match h[0] & 0x0f {
                0 | 1 => msg.extend_from_slice(&body),
                8 => panic!("devtools closed the connection"),
                _ => continue, // ping / pong: not sent by Chromium to a client that does not ask
            }
            if h[0] & 0x80 != 0 {
                return String::from_utf8(msg).expect("UTF-8");
            }
        }
    }

    /// Calls a DevTools method and returns its result (events in between are skipped).
    pub fn call(&mut self, method: &str, params: Value) -> Value {
        self.next += 1;
        let id = self.next;
        self.send(&json!({"id": id, "method": method, "params": params}).to_string());
        loop {
            let m: Value = serde_json::from_str(&self.receive()).unwrap();
            if m["id"] == id {
                assert!(m["error"].is_null(), "{method}: {}", m["error"]);
                return m["result"].clone();
            }
        }
    }

    /// Evaluates a JavaScript expression in the page (promises awaited) and returns its value.
    pub fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": expr, "returnByValue": true, "awaitPromise": true}),
        );
        assert!(
            r["exceptionDetails"].is_null(),
            "{expr}: {}",
            r["exceptionDetails"]
        );
        r["result"]["value"].clone()
    }

    /// Polls `expr` until it is true (panics after `secs` seconds).
    pub fn wait_for(&mut self, expr: &str, secs: u64) {
        let t0 = Instant::now();
        while self.eval(&format!("!!({expr})")) != json!(true) {
            assert!(
                t0.elapsed() < Duration::from_secs(secs),
                "waited {secs} s for {expr}; title '{}', error '{}'",
                self.eval("document.title"),
                self.eval("(document.getElementById('error')||{}).textContent")
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Navigates to `url` and waits until the viewer says it is ready (or fails on its error).
    pub fn open(&mut self, url: &str) {
        self.call("Page.navigate", json!({ "url": url }));
        self.wait_for(
            "location.href !== 'about:blank' && document.readyState === 'complete' && \
             document.title === 'fairsub view: ready'",
            120,
        );
    }

    /// A screenshot of the viewport as PNG bytes.
    pub fn png(&mut self) -> Vec<u8> {
        let r = self.call("Page.captureScreenshot", json!({"format": "png"}));
        base64(r["data"].as_str().expect("data"))
    }

    /// A mouse event at (x, y) in CSS pixels: `kind` is mousePressed, mouseMoved,
    /// mouseReleased; `modifiers` 8 is shift.
    pub fn mouse(&mut self, kind: &str, x: f64, y: f64, modifiers: u32) {
        let pressed = kind != "mouseReleased";
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": kind, "x": x, "y": y, "button": "left",
                   "buttons": if pressed { 1 } else { 0 }, "clickCount": 1,
                   "modifiers": modifiers}),
        );
    }

    /// A drag from (x0, y0) to (x1, y1) in `steps` moves.
    pub fn drag(&mut self, from: (f64, f64), to: (f64, f64), modifiers: u32) {
        self.mouse("mousePressed", from.0, from.1, modifiers);
        for i in 1..=8 {
            let t = i as f64 / 8.0;
            let (x, y) = (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
            self.mouse("mouseMoved", x, y, modifiers);
        }
        self.mouse("mouseReleased", to.0, to.1, modifiers);
    }

    /// A wheel turn of `dy` at (x, y).
    pub fn wheel(&mut self, x: f64, y: f64, dy: f64) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": "mouseWheel", "x": x, "y": y, "deltaX": 0, "deltaY": dy}),
        );
    }
}

/// Decodes standard base64 (what DevTools sends screenshots in).
fn base64(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let b: Vec<u8> = s.bytes().filter(|&c| c != b'=' && c != b'\n').collect();
    let mut out = Vec::with_capacity(b.len() * 3 / 4);
    for chunk in b.chunks(4) {
        let mut n = 0u32;
        for (i, &c) in chunk.iter().enumerate() {
            n |= (val(c) as u32) << (18 - 6 * i);
        }
        out.extend_from_slice(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}
