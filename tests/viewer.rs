//! `fairsub view` end to end: the server as a child process, its routes over raw HTTP, and the
//! page in headless Chromium (SwiftShader WebGL2) judged by the pixels of its screenshots.
//!
//! The browser part skips when `chromium` is missing, unless FAIRSUB_REQUIRE_BROWSER is set
//! (CI sets it and installs Debian's chromium).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A running `fairsub view`, killed when dropped.
struct Viewer {
    child: Child,
    url: String,
    port: u16,
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(args: &[&str]) -> Viewer {
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

/// Status and body of a raw GET of `path` (sent as it is, no normalisation).
fn get(port: u16, path: &str) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect");
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    write!(s, "GET {path} HTTP/1.0\r\nHost: x\r\n\r\n").unwrap();
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

#[test]
fn serves_only_its_routes_and_only_on_loopback() {
    let v = start(&["gallery:cube", "--scheme", "catmull-clark", "--rings", "2"]);
    assert_eq!(get(v.port, "/").0, 200);
    assert_eq!(get(v.port, "/viewer.js").0, 200);
    for bad in [
        "/../Cargo.toml",
        "/%2e%2e/Cargo.toml",
        "/%2E%2E%2FCargo.toml",
        "/..%2fCargo.toml",
        "/viewer.js/../../Cargo.toml",
        "/api/../../Cargo.toml",
        "/Cargo.toml",
        "/src/cli/view.rs",
    ] {
        let (status, body) = get(v.port, bad);
        assert_eq!(status, 404, "{bad}");
        assert!(
            !String::from_utf8_lossy(&body).contains("[package]"),
            "{bad}"
        );
    }
    // The surface buffer: magic, counts, and sizes that match the layout.
    let (status, body) = get(v.port, "/api/surface?scheme=catmull-clark&rings=2");
    assert_eq!(status, 200);
    assert_eq!(&body[..4], b"FSV1");
    let word = |i: usize| u32::from_le_bytes(body[4 * i..4 * i + 4].try_into().unwrap()) as usize;
    let (nv, nt, nb, ne) = (word(1), word(2), word(3), word(4));
    assert!(
        nt > 1000 && nv > 500 && nb > 0,
        "{nv} vertices, {nt} triangles"
    );
    assert_eq!(ne, 12, "the cube's edges");
    assert_eq!(body.len(), 48 + 36 * nv + 12 * nt + 24 * nb + 24 * ne);
    // A scheme that cannot take the net, or no such scheme: a JSON error, no crash.
    let (status, body) = get(v.port, "/api/surface?scheme=no-such-scheme");
    assert_eq!(status, 422);
    assert!(String::from_utf8_lossy(&body).contains("\"error\""));
    // The check panel's report is `fairsub check --json`'s own.
    let (status, body) = get(v.port, "/api/check?scheme=catmull-clark&rings=2");
    assert_eq!(status, 200);
    let (r, cli) = fairsub::cli::capture(|| {
        fairsub::cli::run_words([
            "fairsub",
            "check",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--rings",
            "2",
            "--json",
        ])
    });
    r.unwrap();
    let page: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(
        page,
        serde_json::from_str::<serde_json::Value>(&cli).unwrap()
    );
    let (status, body) = get(v.port, "/api/schemes");
    assert_eq!(status, 200);
    let s: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(s["schemes"].as_array().unwrap().len() >= 5);
    // Bound to 127.0.0.1 only: another loopback address of this machine is refused.
    assert!(TcpStream::connect(("127.0.0.2", v.port)).is_err());
}

#[test]
fn stops_cleanly_on_ctrl_c() {
    let mut v = start(&["gallery:cube", "--scheme", "catmull-clark", "--rings", "1"]);
    assert_eq!(get(v.port, "/").0, 200);
    // SAFETY: signals our own child process.
    assert_eq!(unsafe { libc::kill(v.child.id() as i32, libc::SIGINT) }, 0);
    let t0 = std::time::Instant::now();
    let status = loop {
        if let Some(s) = v.child.try_wait().unwrap() {
            break s;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(10),
            "no stop after Ctrl-C"
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "exit status after Ctrl-C: {status}");
}

fn chromium() -> Option<PathBuf> {
    let found = ["chromium", "chromium-browser"].iter().find_map(|c| {
        let ok = Command::new(c)
            .arg("--version")
            .output()
            .ok()?
            .status
            .success();
        ok.then(|| PathBuf::from(c))
    });
    if found.is_none() && std::env::var_os("FAIRSUB_REQUIRE_BROWSER").is_some() {
        panic!("FAIRSUB_REQUIRE_BROWSER is set but chromium is missing");
    }
    found
}

/// An RGB screenshot.
struct Shot {
    w: usize,
    h: usize,
    rgb: Vec<[u8; 3]>,
}

const W: usize = 640;
const H: usize = 400;
/// The canvas: below the 30-pixel bar, left of the 240-pixel side panel.
const CANVAS: (usize, usize, usize, usize) = (0, 30, W - 240, H);

fn screenshot(browser: &Path, url: &str, out: &Path) -> Shot {
    let profile = std::env::temp_dir().join(format!("fairsub-viewer-{}", std::process::id()));
    let status = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu-sandbox",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--no-first-run",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={W},{H}"))
        .arg("--virtual-time-budget=20000")
        .arg(format!("--screenshot={}", out.display()))
        .arg(url)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .expect("chromium runs");
    assert!(status.success(), "chromium failed on {url}");
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(out).unwrap()));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    let ch = info.color_type.samples();
    let rgb = buf[..info.buffer_size()]
        .chunks(ch)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    Shot {
        w: info.width as usize,
        h: info.height as usize,
        rgb,
    }
}

impl Shot {
    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.rgb[y * self.w + x]
    }
    fn lum(&self, x: usize, y: usize) -> f64 {
        let [r, g, b] = self.at(x, y);
        0.3 * r as f64 + 0.59 * g as f64 + 0.11 * b as f64
    }
    /// The most light/dark alternations along one row of the canvas.
    fn max_alternations(&self) -> usize {
        let (x0, y0, x1, y1) = CANVAS;
        (y0..y1.min(self.h))
            .step_by(4)
            .map(|y| {
                let (mut n, mut last) = (0, None);
                for x in x0..x1.min(self.w) {
                    let l = self.lum(x, y);
                    let s = if l < 70.0 {
                        Some(false)
                    } else if l > 170.0 {
                        Some(true)
                    } else {
                        None
                    };
                    if s.is_some() && last.is_some() && s != last {
                        n += 1;
                    }
                    last = s.or(last);
                }
                n
            })
            .max()
            .unwrap_or(0)
    }
    /// Distinct hues (of 12 buckets) among saturated pixels in rows y0..y1, each covering at
    /// least `min` pixels.
    fn hues(&self, y0: usize, y1: usize, min: usize) -> usize {
        let mut count = [0usize; 12];
        for y in y0..y1.min(self.h) {
            for x in 0..CANVAS.2.min(self.w) {
                let [r, g, b] = self.at(x, y).map(|c| c as f64 / 255.0);
                let (mx, mn) = (r.max(g).max(b), r.min(g).min(b));
                if mx - mn < 0.3 {
                    continue;
                }
                let h = if mx == r {
                    ((g - b) / (mx - mn)).rem_euclid(6.0)
                } else if mx == g {
                    (b - r) / (mx - mn) + 2.0
                } else {
                    (r - g) / (mx - mn) + 4.0
                };
                count[((h / 6.0 * 12.0) as usize).min(11)] += 1;
            }
        }
        count.iter().filter(|&&c| c >= min).count()
    }
    /// Fraction of canvas pixels in columns x0..x1 that are not the background.
    fn covered(&self, x0: usize, x1: usize) -> f64 {
        let (_, y0, _, y1) = CANVAS;
        let mut n = 0;
        for y in y0..y1 {
            for x in x0..x1 {
                let [r, g, b] = self.at(x, y);
                if (r as i32 - 31).abs() + (g as i32 - 31).abs() + (b as i32 - 36).abs() > 12 {
                    n += 1;
                }
            }
        }
        n as f64 / ((x1 - x0) * (y1 - y0)) as f64
    }
}

#[test]
fn page_draws_stripes_curvature_split_views_and_schemes() {
    let Some(browser) = chromium() else {
        eprintln!("skipped: no chromium (set FAIRSUB_REQUIRE_BROWSER to require it)");
        return;
    };
    let v = start(&["gallery:torus-evs", "--scheme", "eg", "--rings", "4"]);
    let dir = std::env::temp_dir().join(format!("fairsub-viewer-shots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = format!("http://127.0.0.1:{}/", v.port);
    assert!(v.url.starts_with(&base));
    let shot = |name: &str, q: &str| screenshot(&browser, &format!("{base}?{q}"), &dir.join(name));

    let hl = shot(
        "highlight.png",
        "mode=highlight&scheme=eg&rings=4&stripes=20",
    );
    let alt = hl.max_alternations();
    assert!(
        alt >= 8,
        "highlight lines: {alt} light/dark alternations along the best row"
    );

    let k = shot("gauss.png", "mode=gauss&scheme=eg&rings=4&overlay=patches");
    let surface_hues = k.hues(CANVAS.1, CANVAS.3 - 40, 40);
    let legend_hues = k.hues(CANVAS.3 - 40, CANVAS.3, 10);
    assert!(
        surface_hues >= 4,
        "Gauss curvature map: {surface_hues} hues"
    );
    assert!(legend_hues >= 5, "legend: {legend_hues} hues");

    let split = shot(
        "split.png",
        "mode=highlight&scheme=eg&split=catmull-clark&rings=4",
    );
    let half = CANVAS.2 / 2;
    let (left, right) = (split.covered(0, half), split.covered(half, CANVAS.2));
    let seam = split.covered(half - 2, half + 2);
    let centres = split.covered(half / 2 - 2, half / 2 + 2);
    assert!(
        left > 0.1 && right > 0.1,
        "both panels drawn: {left:.3} {right:.3}"
    );
    assert!(
        seam < centres,
        "two separate panels: seam {seam:.3}, panel centres {centres:.3}"
    );

    // The same highlight view under EG and Catmull-Clark: the stripes move where the
    // surfaces differ, around the extraordinary points (138 pixels when measured; an
    // unchanged picture should give 0: SwiftShader draws deterministically).
    let look = "mode=highlight&rings=4&stripes=20";
    let eg = shot("eg-hl.png", &format!("{look}&scheme=eg"));
    let cc = shot("cc-hl.png", &format!("{look}&scheme=catmull-clark"));
    let (_, y0, x1, y1) = CANVAS;
    let changed = (y0..y1)
        .flat_map(|y| (0..x1).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let (a, b) = (eg.at(x, y), cc.at(x, y));
            (0..3).any(|c| (a[c] as i32 - b[c] as i32).abs() > 40)
        })
        .count();
    assert!(
        changed > 50,
        "EG -> Catmull-Clark changes {changed} canvas pixels"
    );
    if let Some(out) = std::env::var_os("FAIRSUB_VIEWER_SHOT") {
        std::fs::copy(dir.join("gauss.png"), out).unwrap();
    }
    let _ = std::fs::remove_dir_all(&dir);
}
