//! `fairsub view`: the interactive viewer, a small HTTP server on 127.0.0.1 that serves one
//! embedded WebGL2 page (`view/assets/`) and the geometry it draws.
//!
//! The server answers a fixed set of routes only: the page, its scripts and style sheet, and the
//! API of [`api`] (surface buffers, net info, the `check` summary, the schemes). Every other
//! path is a 404, so nothing outside the embedded assets can be read (no file system access by
//! path at all). Surfaces are recomputed on the server when the page asks for another scheme or
//! ring count, within the CLI's limits.
//!
//! Only requests addressed to the server itself are answered: the `Host` header must name its
//! own loopback address and port (`127.0.0.1:PORT`, or `localhost:PORT`); any other `Host`, or
//! none, gets 421 and a short message. A web page elsewhere could otherwise reach the server
//! through DNS rebinding (its own name resolved to 127.0.0.1) and make it compute for it.

mod api;
mod mesh;

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Arguments of `fairsub view`.
#[derive(Debug, clap::Args)]
pub struct ViewArgs {
    /// A control net (file or gallery:NAME), or a BezierView file (.bv) to show as it is.
    pub input: String,
    /// The scheme the page starts with (a net's default: the first scheme with patch output).
    #[arg(long, short)]
    pub scheme: Option<String>,
    /// Rings of the exact surface the page starts with.
    #[arg(long, short, default_value_t = super::subdivide::DEFAULT_RINGS)]
    pub rings: usize,
    /// The start scheme's options, as `fairsub subdivide` takes them (the page changes those
    /// with a value; files stay as given here).
    #[command(flatten)]
    pub options: super::subdivide::SchemeArgs,
    /// Samples per patch edge of the tessellation sent to the page.
    #[arg(long, default_value_t = api::DEFAULT_TESS)]
    pub tess: usize,
    /// Port on 127.0.0.1 (0: any free port; the URL on the first line says which).
    #[arg(long, default_value_t = 8765)]
    pub port: u16,
    /// Do not open the default browser.
    #[arg(long)]
    pub no_browser: bool,
}

/// The embedded assets: route, content type, bytes.
const ASSETS: [(&str, &str, &[u8]); 4] = [
    (
        "/",
        "text/html; charset=utf-8",
        include_bytes!("view/assets/index.html"),
    ),
    (
        "/gl.js",
        "text/javascript; charset=utf-8",
        include_bytes!("view/assets/gl.js"),
    ),
    (
        "/viewer.js",
        "text/javascript; charset=utf-8",
        include_bytes!("view/assets/viewer.js"),
    ),
    (
        "/viewer.css",
        "text/css; charset=utf-8",
        include_bytes!("view/assets/viewer.css"),
    ),
];

/// Set by the SIGINT / SIGTERM handler; the request loop stops when it is set.
static STOP: AtomicBool = AtomicBool::new(false);

extern "C" fn on_signal(_: libc::c_int) {
    STOP.store(true, Ordering::SeqCst);
}

/// Installs [`on_signal`] for Ctrl-C and SIGTERM.
fn install_stop_handler() {
    let handler: extern "C" fn(libc::c_int) = on_signal;
    // SAFETY: the handler only stores into an atomic, which is async-signal-safe.
    unsafe {
        libc::signal(libc::SIGINT, handler as libc::sighandler_t);
        libc::signal(libc::SIGTERM, handler as libc::sighandler_t);
    }
}

/// Runs `fairsub view`: loads the input, serves the page until Ctrl-C.
pub fn run(a: ViewArgs) -> Result<()> {
    let state = api::State::load(&a)?;
    let server = tiny_http::Server::http(("127.0.0.1", a.port)).map_err(|e| {
        Error::InvalidArgument(format!("cannot listen on 127.0.0.1:{}: {e}", a.port))
    })?;
    let port = server
        .server_addr()
        .to_ip()
        .map(|s| s.port())
        .unwrap_or(a.port);
    let url = format!("http://127.0.0.1:{port}/{}", state.start_query());
    say!("{url}");
    eprintln!("fairsub view: serving {} at {url} (Ctrl-C stops)", a.input);
    if !a.no_browser {
        open_browser(&url);
    }
    install_stop_handler();
    let mut state = state;
    while !STOP.load(Ordering::SeqCst) {
        match server.recv_timeout(Duration::from_millis(200)) {
            Ok(Some(req)) => respond(&mut state, req, port),
            Ok(None) => {}
            Err(e) => eprintln!("warning: fairsub view: {e}"),
        }
    }
    eprintln!("fairsub view: stopped");
    Ok(())
}

/// Opens `url` in the default browser; failure is a warning.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    let spawned = std::process::Command::new(opener)
        .arg(url)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if let Err(e) = spawned {
        eprintln!("warning: could not open a browser with {opener} ({e}); open {url} yourself");
    }
}

/// A response: status, content type, body.
pub(crate) struct Reply {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
}

impl Reply {
    fn ok(content_type: &'static str, body: Vec<u8>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body,
        }
    }

    /// A JSON body with status 200.
    pub(crate) fn json(v: &impl serde::Serialize) -> Reply {
        Reply::ok(
            "application/json",
            serde_json::to_vec(v).expect("serialisable"),
        )
    }

    /// A JSON body already serialised.
    pub(crate) fn json_text(text: String) -> Reply {
        Reply::ok("application/json", text.into_bytes())
    }

    /// A JSON `{"error": ...}` with `status`.
    pub(crate) fn error(status: u16, message: &str) -> Reply {
        let mut r = Reply::json(&serde_json::json!({ "error": message }));
        r.status = status;
        r
    }

    /// A binary body.
    pub(crate) fn binary(body: Vec<u8>) -> Reply {
        Reply::ok("application/octet-stream", body)
    }
}

/// Splits a request URL into its path and its decoded query pairs.
fn split_url(url: &str) -> (&str, Vec<(String, String)>) {
    let (path, query) = url.split_once('?').unwrap_or((url, ""));
    let pairs = query
        .split('&')
        .filter(|s| !s.is_empty())
        .map(|kv| {
            let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
            (percent_decode(k), percent_decode(v))
        })
        .collect();
    (path, pairs)
}

/// Decodes `%XX` escapes and `+` (invalid escapes stay as they are).
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'+' => out.push(b' '),
            b'%' if i + 2 < b.len() => match (hex(b[i + 1]), hex(b[i + 2])) {
                (Some(h), Some(l)) => {
                    out.push(h * 16 + l);
                    i += 2;
                }
                _ => out.push(b'%'),
            },
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The value of a hexadecimal digit.
fn hex(c: u8) -> Option<u8> {
    (c as char).to_digit(16).map(|d| d as u8)
}

/// The reply to a path: an asset, an API answer, or 404 for anything else (so `/../x` and its
/// encoded forms never reach a file).
fn route(state: &mut api::State, url: &str) -> Reply {
    let (path, query) = split_url(url);
    if let Some((_, ty, bytes)) = ASSETS.iter().find(|(p, _, _)| *p == path) {
        return Reply::ok(ty, bytes.to_vec());
    }
    match path.strip_prefix("/api/") {
        Some(name) => state.api(name, &query),
        None => Reply::error(404, &format!("no such page: {path}")),
    }
}

/// Whether a `Host` header value names this server: `127.0.0.1:PORT` or `localhost:PORT`
/// (case-insensitive; a trailing dot of the name is not accepted). Without the port, or with
/// another one, it is not this server.
fn host_is_own(host: &str, port: u16) -> bool {
    let Some((name, p)) = host.trim().rsplit_once(':') else {
        return false;
    };
    p.parse::<u16>() == Ok(port) && (name == "127.0.0.1" || name.eq_ignore_ascii_case("localhost"))
}

/// The reply to a request whose `Host` is not this server's (see the module notes), if so.
fn foreign_host(req: &tiny_http::Request, port: u16) -> Option<Reply> {
    let hosts: Vec<&str> = req
        .headers()
        .iter()
        .filter(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str())
        .collect();
    match hosts[..] {
        [h] if host_is_own(h, port) => None,
        _ => Some(Reply::error(
            421,
            &format!(
                "this fairsub viewer answers only requests to http://127.0.0.1:{port}/ (Host \
                 header {})",
                if hosts.is_empty() {
                    "missing".to_string()
                } else {
                    format!("'{}'", hosts.join("', '"))
                }
            ),
        )),
    }
}

/// Answers one request (only GET to this server's own `Host` is served).
fn respond(state: &mut api::State, req: tiny_http::Request, port: u16) {
    let reply = if let Some(r) = foreign_host(&req, port) {
        r
    } else if *req.method() == tiny_http::Method::Get {
        route(state, req.url())
    } else {
        Reply::error(405, "only GET is served")
    };
    let header =
        tiny_http::Header::from_bytes("Content-Type", reply.content_type).expect("valid header");
    let resp = tiny_http::Response::from_data(reply.body)
        .with_status_code(reply.status)
        .with_header(header);
    if let Err(e) = req.respond(resp) {
        eprintln!("warning: fairsub view: reply not sent: {e}");
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn queries_decode_and_unknown_paths_are_404() {
        let (p, q) = split_url("/api/surface?scheme=a%2Db&rings=3&x");
        assert_eq!(p, "/api/surface");
        assert_eq!(q[0], ("scheme".into(), "a-b".into()));
        assert_eq!(q[1], ("rings".into(), "3".into()));
        assert_eq!(q[2], ("x".into(), "".into()));
        assert_eq!(percent_decode("%2e%2E/%zz%"), "../%zz%");
    }

    #[crate::unit::test]
    fn only_the_own_host_and_port_are_served() {
        for ok in [
            "127.0.0.1:8765",
            "localhost:8765",
            "LocalHost:8765",
            " 127.0.0.1:8765 ",
        ] {
            assert!(host_is_own(ok, 8765), "{ok}");
        }
        for bad in [
            "127.0.0.1",
            "127.0.0.1:8766",
            "localhost",
            "evil.example:8765",
            "127.0.0.1.evil.example:8765",
            "localhost.:8765",
            "[::1]:8765",
            "127.0.0.2:8765",
            "",
            ":8765",
        ] {
            assert!(!host_is_own(bad, 8765), "{bad}");
        }
    }
}
