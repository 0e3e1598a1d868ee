//! `fairsub view` end to end: the server as a child process, its routes over raw HTTP, and the
//! page in headless Chromium (SwiftShader WebGL2) judged by the pixels of its screenshots.
//!
//! The page is driven over the DevTools protocol (`viewer/cdp.rs`), in real time: menus and
//! fields through their change events, orbit, pan and zoom through real mouse events. The
//! browser part skips when `chromium` is missing, unless FAIRSUB_REQUIRE_BROWSER is set (CI sets
//! it and installs Debian's chromium).

#[path = "viewer/cdp.rs"]
mod cdp;
use crate::viewer_helpers::server;
#[path = "viewer/shot.rs"]
mod shot;

use server::{Viewer, get, start};

use shot::{Shot, decode, weighted_percentile};

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

#[test]
fn serves_only_its_routes_and_only_on_loopback() {
    let v = start(&["gallery:cube", "--scheme", "catmull-clark", "--rings", "2"]);
    assert_eq!(get(v.port, "/").0, 200);
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
    // Files are named on the command line only: a page cannot make the server read one.
    for q in [
        "creases=/etc/passwd",
        "q-file=%2Fetc%2Fpasswd",
        "fcv-file=Cargo.toml",
    ] {
        let (status, body) = get(v.port, &format!("/api/surface?scheme=catmull-clark&{q}"));
        let text = String::from_utf8_lossy(&body);
        assert_eq!(status, 422, "{q}");
        assert!(
            text.contains("names a file") && !text.contains("root:"),
            "{q}: {text}"
        );
    }
    // An option the scheme does not take is the command line's error.
    let (status, body) = get(v.port, "/api/surface?scheme=catmull-clark&split-ratio=0.3");
    assert_eq!(status, 422);
    assert!(String::from_utf8_lossy(&body).contains("--split-ratio and --alpha-rule apply to"));
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

/// Without `--no-browser` the page is opened with `xdg-open URL` (a stand-in on PATH here that
/// records its argument), the URL printed on the first line.
#[cfg(target_os = "linux")]
#[test]
fn opens_the_default_browser() {
    let dir = std::env::temp_dir().join(format!("fairsub-viewer-open-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("opened");
    let opener = dir.join("xdg-open");
    std::fs::write(
        &opener,
        format!("#!/bin/sh\necho \"$1\" > '{}'\n", log.display()),
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&opener, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!(
        "{}:{}",
        dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args([
            "view",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--rings",
            "1",
        ])
        .args(["--port", "0"])
        .env("PATH", path)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("fairsub runs");
    let mut url = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut url)
        .unwrap();
    let v = Viewer {
        child,
        url: url.trim().to_string(),
        port: 0,
    };
    let t0 = std::time::Instant::now();
    while std::fs::read_to_string(&log).map_or(true, |s| !s.ends_with('\n')) {
        assert!(t0.elapsed() < Duration::from_secs(10), "xdg-open not run");
        std::thread::sleep(Duration::from_millis(50));
    }
    assert_eq!(std::fs::read_to_string(&log).unwrap().trim(), v.url);
    drop(v);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The browser, or `None` (the test skips) unless FAIRSUB_REQUIRE_BROWSER is set.
fn chromium() -> Option<PathBuf> {
    if crate::common::skip_slow("chromium") {
        return None;
    }
    let found = cdp::find();
    if found.is_none() && std::env::var_os("FAIRSUB_REQUIRE_BROWSER").is_some() {
        panic!("FAIRSUB_REQUIRE_BROWSER is set but chromium is missing");
    }
    if found.is_none() {
        eprintln!("skipped: no chromium (set FAIRSUB_REQUIRE_BROWSER to require it)");
    }
    found
}

/// The window of the browser tests: narrow, so the bar must wrap.
const W: u32 = 640;
const H: u32 = 400;

/// A screenshot of the page (the canvas rectangle read from the page).
/// The schemes without exact patches (sqrt(3), modified butterfly) show their refined net: the
/// points `fairsub subdivide --levels N --limit` writes, fanned into triangles, with discrete
/// normals and curvatures (outward normals and negative mean curvature everywhere on the convex
/// icosahedron, as the exact patches' sign has it).
#[test]
fn schemes_without_patches_show_their_refined_net() {
    let v = start(&["gallery:icosahedron", "--scheme", "loop", "--rings", "2"]);
    let (_, body) = get(v.port, "/api/schemes");
    let s: serde_json::Value = serde_json::from_slice(&body).unwrap();
    let patches = |name: &str| {
        s["schemes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|x| x["name"] == name)
            .unwrap_or_else(|| panic!("{name} listed"))["patches"]
            .as_bool()
            .unwrap()
    };
    assert!(!patches("sqrt3") && !patches("butterfly") && patches("loop"));
    let dir = std::env::temp_dir().join(format!("fairsub-viewer-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for scheme in ["sqrt3", "butterfly"] {
        let (status, body) = get(v.port, &format!("/api/surface?scheme={scheme}&rings=2"));
        assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
        let word = |i: usize| u32::from_le_bytes(body[4 * i..4 * i + 4].try_into().unwrap());
        let float = |i: usize| f32::from_le_bytes(body[4 * i..4 * i + 4].try_into().unwrap());
        let (nv, nt, nb, ne, faces) = [1, 2, 3, 4, 5].map(|i| word(i) as usize).into();
        assert_eq!(body.len(), 48 + 36 * nv + 12 * nt + 24 * nb + 24 * ne);
        // the command line's refined net, point by point
        let obj = dir.join(format!("{scheme}.obj"));
        fairsub::cli::run_words([
            "fairsub",
            "subdivide",
            "gallery:icosahedron",
            "--scheme",
            scheme,
            "--levels",
            "2",
            "--limit",
            "-o",
            obj.to_str().unwrap(),
        ])
        .unwrap();
        let text = std::fs::read_to_string(&obj).unwrap();
        let points: Vec<[f64; 3]> = text
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let x: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
                [x[0], x[1], x[2]]
            })
            .collect();
        let tris = text.lines().filter(|l| l.starts_with("f ")).count();
        assert_eq!((nv, nt, faces), (points.len(), tris, tris), "{scheme}");
        assert_eq!(ne, 30, "the icosahedron's edges");
        let (pos, nrm, gauss, mean) = (12, 12 + 3 * nv, 12 + 6 * nv, 12 + 7 * nv);
        for (i, p) in points.iter().enumerate() {
            let q = [0, 1, 2].map(|k| float(pos + 3 * i + k) as f64);
            let n = [0, 1, 2].map(|k| float(nrm + 3 * i + k) as f64);
            assert!(
                (0..3).all(|k| (p[k] - q[k]).abs() < 1e-6),
                "{scheme} vertex {i}: {q:?} vs {p:?}"
            );
            let out: f64 = (0..3).map(|k| n[k] * p[k]).sum();
            let len: f64 = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((len - 1.0).abs() < 1e-6 && out > 0.0, "{scheme} normal {i}");
            let (k, h) = (float(gauss + i), float(mean + i));
            assert!(
                h < 0.0 && k.is_finite(),
                "{scheme} vertex {i}: K {k}, H {h}"
            );
        }
        let (status, body) = get(v.port, &format!("/api/check?scheme={scheme}&rings=2"));
        assert_eq!(status, 200);
        let r: serde_json::Value = serde_json::from_slice(&body).unwrap();
        assert_eq!(r["mesh"]["faces"], tris, "{scheme}");
        assert_eq!(r["mesh"]["levels"], 2);
        assert!(r["notes"][0].as_str().unwrap().contains("no exact patches"));
    }
    std::fs::remove_dir_all(&dir).unwrap();
    // the refined net grows by 3 or 4 each level: the viewer takes at most 6
    let (status, body) = get(v.port, "/api/surface?scheme=sqrt3&rings=7");
    assert_eq!(status, 422);
    assert!(String::from_utf8_lossy(&body).contains("at most 6 levels"));
}

fn shot(b: &mut cdp::Browser) -> Shot {
    let r = b.eval("JSON.stringify(document.getElementById('gl').getBoundingClientRect())");
    let r: serde_json::Value = serde_json::from_str(r.as_str().unwrap()).unwrap();
    let f = |k: &str| r[k].as_f64().unwrap().round() as usize;
    let canvas = (f("left"), f("top"), f("right"), f("bottom"));
    let png = b.png();
    if let Some(dir) = std::env::var_os("FAIRSUB_VIEWER_DEBUG") {
        // every screenshot kept, numbered, to look at when a check fails
        static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = N.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        std::fs::write(PathBuf::from(dir).join(format!("shot-{n:02}.png")), &png).unwrap();
    }
    decode(&png, canvas)
}

/// Sets a control of the page as a user does (value, then its change / input event) and waits
/// until the page is ready again (or shows an error).
fn set_control(b: &mut cdp::Browser, selector: &str, value: &str, event: &str) {
    let js = format!(
        "(() => {{ const e = document.querySelector({sel}); e.value = {value}; \
         e.dispatchEvent(new Event('{event}')); return true; }})()",
        sel = serde_json::json!(selector),
        value = serde_json::json!(value)
    );
    b.eval(&js);
    b.wait_for("document.title !== 'fairsub view: loading'", 120);
    settle(b);
}

/// Waits for the next frames to be drawn and the URL to follow the state.
fn settle(b: &mut cdp::Browser) {
    b.eval("new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(() => r(true), 250))))");
}

/// The value of a query parameter of the page's URL.
fn url_param(b: &mut cdp::Browser, key: &str) -> Option<String> {
    let v = b.eval(&format!(
        "new URLSearchParams(location.search).get({})",
        serde_json::json!(key)
    ));
    v.as_str().map(str::to_string)
}

#[test]
fn slow_page_in_headless_chromium() {
    let Some(exe) = chromium() else { return };
    let v = start(&["gallery:torus-evs", "--scheme", "eg", "--rings", "4"]);
    let base = format!("http://127.0.0.1:{}/", v.port);
    assert!(v.url.starts_with(&base));
    let mut b = cdp::Browser::launch(&exe, W, H);

    let body = layout_and_panels(&mut b, &v);
    let canvas_px = modes_and_legend(&mut b, &body);
    overlays_and_camera(&mut b, canvas_px);
    url_split_and_screenshot(&mut b, &base);
    scheme_options(&mut b, &v, &base);
    if let Some(out) = std::env::var_os("FAIRSUB_VIEWER_SHOT") {
        // the README's picture, in a larger window
        let mut big = cdp::Browser::launch(&exe, 1000, 600);
        big.open(&format!(
            "{base}?mode=gauss&scheme=eg&split=catmull-clark&rings=4&overlay=patches&el=40"
        ));
        std::fs::write(out, big.png()).unwrap();
    }
}

// The frame-rate census is a test of its own (its own viewer and browser), so that libtest's
// two threads share the Chromium work instead of one long test finishing the run alone.
#[test]
fn slow_frame_rate_census_in_headless_chromium() {
    let Some(exe) = chromium() else { return };
    let v = start(&["gallery:torus-evs", "--scheme", "eg", "--rings", "4"]);
    let base = format!("http://127.0.0.1:{}/", v.port);
    let mut b = cdp::Browser::launch(&exe, W, H);
    // The frame-rate measurement runs (its times are the benchmark's, not asserted here). A
    // frame of a loaded surface sends no data to the GPU and makes one draw, and its WebGL
    // calls do not depend on the number of triangles (4 rings against 2, 65k against 39k
    // triangles: the same census).
    let mut census = Vec::new();
    for rings in [4, 2] {
        b.open(&format!(
            "{base}?mode=highlight&scheme=eg&rings={rings}&bench=5"
        ));
        let frames = b.eval("+document.body.dataset.benchFrames");
        let fps = b.eval("+document.body.dataset.benchFps").as_f64().unwrap();
        assert_eq!(frames, 5);
        assert!(fps > 0.0, "frames per second {fps}");
        assert_eq!(b.eval("+document.body.dataset.benchUploads"), 0);
        assert_eq!(b.eval("+document.body.dataset.benchDraws"), 1);
        let triangles = b.eval("+document.body.dataset.triangles").as_u64().unwrap();
        let calls = b.eval("document.body.dataset.benchCalls");
        census.push((triangles, calls));
    }
    assert!(census[0].0 > census[1].0 + 20_000, "triangles {census:?}");
    assert_eq!(census[0].1, census[1].1, "WebGL calls per frame");
}

/// The start URL shows the server's state; the bar fits the 640-pixel window (it wraps); the
/// info and check panels. Returns the start surface's buffer.
fn layout_and_panels(b: &mut cdp::Browser, v: &Viewer) -> Vec<u8> {
    b.open(&v.url);
    let overflow = b.eval(
        "(() => { const bar = document.getElementById('bar'); let worst = 0; \
         for (const e of bar.querySelectorAll('label, button, b')) \
           worst = Math.max(worst, e.getBoundingClientRect().right); \
         return [bar.scrollWidth - bar.clientWidth, worst, innerWidth, \
                 document.getElementById('gl').getBoundingClientRect().height]; })()",
    );
    let o: Vec<f64> = serde_json::from_value(overflow).unwrap();
    assert!(
        o[0] <= 0.0 && o[1] <= o[2],
        "the bar overflows: scroll {} px, rightmost control at {} of {}",
        o[0],
        o[1],
        o[2]
    );
    assert!(o[3] > 200.0, "canvas height {} after the bar", o[3]);

    // The info and check panels: the net's `info` and check's report of the left surface.
    let (_, body) = get(v.port, "/api/surface?scheme=eg&rings=4");
    let patches = u32::from_le_bytes(body[20..24].try_into().unwrap());
    b.wait_for(
        "document.getElementById('check').textContent.startsWith('patches')",
        60,
    );
    let check = b.eval("document.getElementById('check').textContent");
    assert!(
        check
            .as_str()
            .unwrap()
            .starts_with(&format!("patches {patches}, open sides 0")),
        "{check} (the buffer has {patches} patches)"
    );
    // Readable tables, not JSON: the net's facts as rows, the joins and the curvature per ring
    // under their headers.
    let rows = |b: &mut cdp::Browser, id: &str| -> Vec<Vec<String>> {
        let js = format!(
            "[...document.querySelectorAll('#{id} tr')].map(r => [...r.cells].map(c => c.textContent))"
        );
        serde_json::from_value(b.eval(&js)).unwrap()
    };
    let info = rows(b, "info");
    let row = |t: &[Vec<String>], k: &str| t.iter().find(|r| r[0] == k).cloned();
    assert_eq!(
        row(&info, "vertices"),
        Some(vec!["vertices".into(), "48".into()]),
        "{info:?}"
    );
    assert_eq!(
        row(&info, "faces"),
        Some(vec!["faces".into(), "48".into()]),
        "{info:?}"
    );
    assert!(
        row(&info, "extraord. vertices").is_some_and(|r| r[1].contains("(n=3)")),
        "{info:?}"
    );
    assert!(
        !b.eval("document.getElementById('info').textContent")
            .as_str()
            .unwrap()
            .contains('{')
    );
    let joins = rows(b, "check");
    assert_eq!(
        joins[0],
        ["join", "pieces", "C0", "C1", "C2", "G1 rad"],
        "{joins:?}"
    );
    let all = row(&joins, "all").expect("an 'all' row");
    assert!(all[1].parse::<u64>().unwrap() > 0, "{all:?}");
    assert!(
        joins.iter().any(|r| r[0] == "element") && joins.iter().any(|r| r[1] == "ring 1"),
        "the curvature table: {joins:?}"
    );
    assert!(!check.as_str().unwrap().contains('{'), "{check}");
    body
}

/// Every mode draws, each differently; the curvature legend's automatic and fixed ranges.
/// Returns the canvas's pixel count.
fn modes_and_legend(b: &mut cdp::Browser, body: &[u8]) -> usize {
    // Every mode draws, each differently; the legend only in the curvature modes.
    let modes = [
        "shaded",
        "highlight",
        "reflection",
        "isophotes",
        "gauss",
        "mean",
        "provenance",
    ];
    let mut shots = Vec::new();
    for m in modes {
        set_control(b, "#mode", m, "change");
        let s = shot(b);
        let cover = s.covered(0, s.width());
        assert!(cover > 0.1, "{m}: {cover:.3} of the canvas drawn");
        let legend = b.eval("getComputedStyle(document.getElementById('legend')).display");
        assert_eq!(
            legend == "block",
            m == "gauss" || m == "mean",
            "{m}: legend {legend}"
        );
        assert_eq!(url_param(b, "mode").as_deref(), Some(m));
        shots.push(s);
    }
    let canvas_px = shots[0].width() * (shots[0].canvas.3 - shots[0].canvas.1);
    for i in 0..modes.len() {
        for j in 0..i {
            let d = shots[i].changed(&shots[j], 40);
            assert!(
                d * 50 > canvas_px,
                "{} and {} differ in {d} of {canvas_px} pixels",
                modes[i],
                modes[j]
            );
        }
    }
    let alt = shots[1].max_alternations();
    assert!(alt >= 8, "highlight lines: {alt} light/dark alternations");

    // Curvature: a colour map, the legend's automatic range (the area-weighted 98th percentile
    // of |K|, recomputed here from the buffer), then a fixed range.
    set_control(b, "#mode", "gauss", "change");
    let k = shot(b);
    let (y0, y1) = (k.canvas.1, k.canvas.3);
    assert!(
        k.hues(y0, y1 - 40, 40) >= 4,
        "Gauss map: {} hues",
        k.hues(y0, y1 - 40, 40)
    );
    assert!(
        k.hues(y1 - 40, y1, 10) >= 5,
        "legend: {} hues",
        k.hues(y1 - 40, y1, 10)
    );
    let auto: f64 = b
        .eval("+document.getElementById('lmax').textContent")
        .as_f64()
        .unwrap();
    let expect = weighted_percentile(body, true);
    assert!(
        (auto - expect).abs() <= 0.005 * expect,
        "automatic range {auto}, the buffer's 98th percentile {expect}"
    );
    assert_eq!(
        b.eval("document.getElementById('lmid').textContent"),
        "K auto"
    );
    set_control(b, "#range", "0.05", "input");
    assert_eq!(
        b.eval("document.getElementById('lmid').textContent"),
        "K fixed"
    );
    assert_eq!(
        b.eval("document.getElementById('lmax').textContent"),
        "0.0500"
    );
    assert_eq!(url_param(b, "range").as_deref(), Some("0.05"));
    let fixed = shot(b);
    assert!(
        fixed.changed(&k, 40) * 20 > canvas_px,
        "a fixed range changes the map"
    );
    set_control(b, "#range", "", "input");
    canvas_px
}

/// The overlays, and orbit, zoom and pan with the mouse, reset.
fn overlays_and_camera(b: &mut cdp::Browser, canvas_px: usize) {
    // Overlays: the net in red, the patch boundaries in near-black.
    set_control(b, "#mode", "shaded", "change");
    let plain = shot(b);
    b.eval("document.getElementById('net').click()");
    settle(b);
    let net = shot(b);
    b.eval("document.getElementById('net').click(); document.getElementById('patches').click()");
    settle(b);
    let lines = shot(b);
    b.eval("document.getElementById('patches').click()");
    settle(b);
    let red = [255, 77, 51];
    let (red0, red1) = (plain.count_near(red, 30), net.count_near(red, 30));
    assert!(
        red1 > red0 + 500,
        "net overlay: {red0} -> {red1} red pixels"
    );
    let dark = [26, 26, 26];
    let (dark0, dark1) = (plain.count_near(dark, 12), lines.count_near(dark, 12));
    assert!(
        dark1 > dark0 + 1000,
        "patch overlay: {dark0} -> {dark1} dark pixels"
    );

    // Orbit, zoom, pan with the mouse; reset frames the surface as at the start.
    let (x0, y0, x1, y1) = plain.canvas;
    let c = ((x0 + x1) as f64 / 2.0, (y0 + y1) as f64 / 2.0);
    b.drag(c, (c.0 + 60.0, c.1 + 60.0), 0);
    settle(b);
    let az: f64 = url_param(b, "az").unwrap().parse().unwrap();
    let el: f64 = url_param(b, "el").unwrap().parse().unwrap();
    assert!(
        (az - (-60.0 - 24.0)).abs() < 1e-3 && (el - 54.0).abs() < 1e-3,
        "orbit: az {az}, el {el}"
    );
    let orbit = shot(b);
    let d = orbit.changed(&plain, 40);
    assert!(
        d * 50 > canvas_px,
        "orbit changes {d} of {canvas_px} pixels"
    );
    b.wheel(c.0, c.1, 500.0);
    settle(b);
    let dist: f64 = url_param(b, "dist").unwrap().parse().unwrap();
    assert!((dist - 0.5f64.exp()).abs() < 0.01, "zoom: dist {dist}");
    let far = shot(b);
    let (c_orbit, c_far) = (orbit.covered(0, orbit.width()), far.covered(0, far.width()));
    assert!(
        c_far < 0.7 * c_orbit,
        "zooming out: {c_orbit:.3} -> {c_far:.3} covered"
    );
    let before = far.centroid();
    b.drag(c, (c.0 + 50.0, c.1), 8);
    settle(b);
    let px: f64 = url_param(b, "px").unwrap().parse().unwrap();
    let after = shot(b).centroid();
    assert!(px < 0.0, "pan: px {px}");
    assert!(
        after.0 - before.0 > 30.0 && (after.1 - before.1).abs() < 10.0,
        "pan moves the surface right: {before:?} -> {after:?}"
    );
    b.eval("document.getElementById('reset').click()");
    settle(b);
    let reset = shot(b);
    assert_eq!(
        reset.changed(&plain, 8),
        0,
        "reset gives the start view back"
    );
    assert_eq!(url_param(b, "az").as_deref(), Some("-60"));
}

/// The URL carries the state; the side-by-side view; the screenshot button.
fn url_split_and_screenshot(b: &mut cdp::Browser, base: &str) {
    let start = shot(b);
    let (x0, y0, x1, y1) = start.canvas;
    let c = ((x0 + x1) as f64 / 2.0, (y0 + y1) as f64 / 2.0);
    // The URL carries the state: a view opened from the URL is the same picture.
    set_control(b, "#mode", "highlight", "change");
    b.drag(c, (c.0 - 40.0, c.1 - 30.0), 0);
    b.wheel(c.0, c.1, -200.0);
    b.eval("document.getElementById('patches').click()");
    settle(b);
    let here = shot(b);
    let url = b.eval("location.href").as_str().unwrap().to_string();
    b.open(&url);
    settle(b);
    let again = shot(b);
    assert_eq!(
        again.changed(&here, 8),
        0,
        "{url} reopened draws the same picture"
    );

    // Side by side: two panels, one camera, a gap between them.
    b.open(&format!(
        "{base}?mode=highlight&scheme=eg&split=catmull-clark&rings=4"
    ));
    let split = shot(b);
    let half = split.width() / 2;
    let (left, right) = (split.covered(0, half), split.covered(half, split.width()));
    let seam = split.covered(half - 2, half + 2);
    let centres = split.covered(half / 2 - 2, half / 2 + 2);
    assert!(
        left > 0.1 && right > 0.1,
        "both panels drawn: {left:.3} {right:.3}"
    );
    assert!(
        seam < centres,
        "two separate panels: seam {seam:.3}, centres {centres:.3}"
    );
    let labels = b.eval("document.getElementById('label1').textContent");
    assert!(
        labels.as_str().unwrap().starts_with("catmull-clark ("),
        "{labels}"
    );

    // The screenshot button saves the canvas as a PNG.
    let dir = std::env::temp_dir().join(format!("fairsub-viewer-dl-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    b.call(
        "Browser.setDownloadBehavior",
        serde_json::json!({"behavior": "allow", "downloadPath": dir.to_str().unwrap()}),
    );
    b.eval("document.getElementById('shot').click()");
    let file = dir.join("fairsub-eg-highlight.png");
    let t0 = std::time::Instant::now();
    while !file.exists() {
        assert!(t0.elapsed() < Duration::from_secs(20), "no download");
        std::thread::sleep(Duration::from_millis(100));
    }
    std::thread::sleep(Duration::from_millis(300));
    let canvas_px_size: Vec<usize> = serde_json::from_value(
        b.eval("[document.getElementById('gl').width, document.getElementById('gl').height]"),
    )
    .unwrap();
    let saved = decode(
        &std::fs::read(&file).unwrap(),
        (0, 0, canvas_px_size[0], canvas_px_size[1]),
    );
    assert_eq!(saved.rgb.len(), canvas_px_size[0] * canvas_px_size[1]);
    // The saved canvas is the canvas on screen (up to the panel labels over it).
    assert_eq!(saved.width(), split.width());
    let on_screen = Shot {
        w: saved.width(),
        rgb: split.pixels().map(|(x, y)| split.at(x, y)).collect(),
        canvas: saved.canvas,
    };
    let (differ, all) = (saved.changed(&on_screen, 8), saved.pixels().count());
    assert!(
        differ * 50 < all,
        "the saved PNG differs from the canvas in {differ} of {all} pixels"
    );
    assert!(saved.covered(0, saved.width()) > 0.1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The scheme options offered are the scheme's own, and reach the server.
fn scheme_options(b: &mut cdp::Browser, v: &Viewer, base: &str) {
    // Scheme options: the controls are the scheme's own option words (its ParamKinds), and
    // a value reaches the server as the command-line option.
    let shown = |b: &mut cdp::Browser| -> Vec<String> {
        serde_json::from_value(b.eval(
            "[...document.querySelectorAll('#opts [data-option]')].map((e) => e.dataset.option)",
        ))
        .unwrap()
    };
    let words = |name: &str| -> Vec<String> {
        let spec = fairsub::schemes::registry().lookup(name).unwrap();
        let d = fairsub::schemes::registry().descriptor(spec.id);
        fairsub::cli::api::option_words(d.params())
            .into_iter()
            .map(|o| o.name)
            .collect()
    };
    b.open(&format!("{base}?mode=gauss&scheme=eg&rings=2"));
    assert_eq!(shown(b), words("eg"));
    set_control(b, "#opts [data-option=rules]", "derived", "change");
    assert_eq!(url_param(b, "rules").as_deref(), Some("derived"));
    b.wait_for(
        "document.getElementById('check').textContent.startsWith('patches')",
        60,
    );
    let notes = b.eval("document.getElementById('check').textContent");
    assert!(
        notes
            .as_str()
            .unwrap()
            .contains("chosen by --rules derived"),
        "the check panel names the derived rules: {notes}"
    );
    set_control(b, "#scheme", "tps-adjustable", "change");
    assert_eq!(shown(b), words("tps-adjustable"));
    set_control(b, "#opts [data-option=split-ratio]", "0.45", "change");
    assert_eq!(url_param(b, "split-ratio").as_deref(), Some("0.45"));
    let asked = b.eval("document.body.dataset.query");
    let asked = asked.as_str().unwrap();
    assert!(asked.contains("split-ratio=0.45"), "{asked}");
    // The page's surface is the ratio's: the extraordinary vertices' neighbourhoods move.
    let (s1, e45) = get(v.port, &format!("/api/surface?{asked}"));
    let (s2, e20) = get(v.port, "/api/surface?scheme=tps-adjustable&rings=2");
    assert_eq!((s1, s2), (200, 200));
    let same = e45.len() == e20.len()
        && e45[..48] == e20[..48]
        && (0..3 * u32::from_le_bytes(e45[4..8].try_into().unwrap()) as usize).all(|i| {
            let at = |b: &[u8]| f32::from_le_bytes(b[48 + 4 * i..52 + 4 * i].try_into().unwrap());
            (at(&e45) - at(&e20)).abs() < 1e-3
        });
    assert!(!same, "split ratio 0.45 gives the default surface");
    set_control(b, "#opts [data-option=split-ratio]", "0.7", "change");
    let err = b.eval("document.getElementById('error').textContent");
    assert!(
        err.as_str().unwrap().contains("split"),
        "an out-of-range ratio: {err}"
    );
}

/// The scheme menu, driven as a user does, switches EG to Catmull-Clark on a valence-5 saddle:
/// in mean-curvature mode with a fixed range the two surfaces are told apart near the
/// extraordinary point (EG's mean curvature there stays within 0.004 of zero over rings 4..6,
/// Catmull-Clark's reaches 0.14: `fairsub check` on this net).
#[test]
fn slow_scheme_menu_switches_the_surface() {
    let Some(exe) = chromium() else { return };
    let v = start(&["gallery:cnet-5-saddle", "--scheme", "eg", "--rings", "4"]);
    // The camera looks down on the extraordinary vertex (the net's vertex 0, at the origin),
    // zoomed to its rings: the pan (px, py in bounding-sphere radii) that puts the origin in
    // the middle, with the page's camera basis.
    let (_, body) = get(v.port, "/api/surface?scheme=eg&rings=4");
    let float =
        |i: usize| f32::from_le_bytes(body[24 + 4 * i..28 + 4 * i].try_into().unwrap()) as f64;
    let (lo, hi) = (
        [float(0), float(1), float(2)],
        [float(3), float(4), float(5)],
    );
    let centre = [0, 1, 2].map(|i| (lo[i] + hi[i]) / 2.0);
    let radius = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt() / 2.0;
    let (az, el) = ((-60f64).to_radians(), 89.9f64.to_radians());
    let dir = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    let norm = (dir[1] * dir[1] + dir[0] * dir[0]).sqrt();
    let right = [-dir[1] / norm, dir[0] / norm, 0.0];
    let up = [
        dir[1] * right[2] - dir[2] * right[1],
        dir[2] * right[0] - dir[0] * right[2],
        dir[0] * right[1] - dir[1] * right[0],
    ];
    let pan = |axis: [f64; 3]| -(0..3).map(|i| centre[i] * axis[i]).sum::<f64>() / radius;
    let (px, py) = (pan(right), pan(up));
    let mut b = cdp::Browser::launch(&exe, W, H);
    b.open(&format!(
        "{}&mode=mean&range=0.1&az=-60&el=89.9&dist=0.03&px={px:.6}&py={py:.6}",
        v.url
    ));
    let eg = shot(&mut b);
    set_control(&mut b, "#scheme", "catmull-clark", "change");
    assert_eq!(
        url_param(&mut b, "scheme").as_deref(),
        Some("catmull-clark")
    );
    let cc = shot(&mut b);
    let (px, changed) = (eg.pixels().count(), cc.changed(&eg, 60));
    eprintln!("EG -> Catmull-Clark: {changed} of {px} canvas pixels changed");
    // measured: 102,470 of 150,420 (68%)
    assert!(
        changed * 2 > px,
        "EG -> Catmull-Clark changes only {changed} of {px} canvas pixels"
    );
    let check = b.eval("document.getElementById('check').textContent");
    assert!(check.as_str().unwrap().starts_with("patches"), "{check}");
    // A scheme without exact patches: its refined net at the field's level, the field named
    // "levels", the check panel saying what is shown.
    let ico = start(&["gallery:icosahedron", "--scheme", "loop", "--rings", "3"]);
    b.open(&format!("{}&mode=mean&overlay=patches", ico.url));
    let loop_surface = shot(&mut b);
    set_control(&mut b, "#scheme", "sqrt3", "change");
    let sqrt3 = shot(&mut b);
    let text = |b: &mut cdp::Browser, id: &str| {
        let t = b.eval(&format!("document.getElementById('{id}').textContent"));
        t.as_str().unwrap().to_string()
    };
    assert_eq!(text(&mut b, "ringsname"), "levels");
    let check = text(&mut b, "check");
    assert!(
        check.starts_with("net at level 3 (limit points): 540 faces"),
        "{check}"
    );
    assert_eq!(text(&mut b, "error"), "");
    let drawn = b.eval("document.body.dataset.triangles");
    assert_eq!(drawn.as_str(), Some("540"), "the net's triangles drawn");
    // the same sphere-like surface, drawn as large, with other lines in the patches overlay:
    // measured 7,778 of 150,420 canvas pixels changed, coverage 0.228 (Loop 0.227)
    let w = sqrt3.width();
    let (a, c) = (loop_surface.covered(0, w), sqrt3.covered(0, w));
    let (px, changed) = (sqrt3.pixels().count(), sqrt3.changed(&loop_surface, 60));
    eprintln!(
        "Loop -> sqrt(3) net: {changed} of {px} canvas pixels changed, coverage {a:.3} -> {c:.3}"
    );
    assert!((c - a).abs() < 0.1 * a && a > 0.1, "coverage {a} -> {c}");
    assert!(
        changed * 40 > px,
        "Loop -> sqrt(3) changes only {changed} of {px} canvas pixels"
    );
    set_control(&mut b, "#scheme", "loop", "change");
    assert_eq!(text(&mut b, "ringsname"), "rings");
}

/// `fairsub view FILE.bv`: the file's patches as they are.
#[test]
fn slow_bv_file_is_served_and_drawn() {
    let dir = std::env::temp_dir().join(format!("fairsub-viewer-bv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bv = dir.join("saddle.bv");
    let (r, _) = fairsub::cli::capture(|| {
        fairsub::cli::run_words([
            "fairsub",
            "subdivide",
            "gallery:cnet-5-saddle",
            "--scheme",
            "catmull-clark",
            "--rings",
            "2",
            "-o",
            bv.to_str().unwrap(),
        ])
    });
    r.unwrap();
    let file = fairsub::io::read_bv(&bv).unwrap();
    let n = file.patches.len();
    let v = start(&[bv.to_str().unwrap()]);
    assert!(
        v.url.ends_with('/'),
        "no scheme in the start URL: {}",
        v.url
    );
    let (status, body) = get(v.port, "/api/surface");
    assert_eq!(status, 200);
    let word = |i: usize| u32::from_le_bytes(body[4 * i..4 * i + 4].try_into().unwrap()) as usize;
    let (nv, nt, nb, ne, np) = (word(1), word(2), word(3), word(4), word(5));
    assert_eq!(np, n, "the buffer's patches are the file's");
    assert_eq!(nb, 4 * 8 * n, "8 boundary segments per patch side");
    assert_eq!(ne, 0, "no polyhedron in the file");
    assert!(nt >= 2 * 64 * n, "{nt} triangles for {n} patches");
    assert_eq!(body.len(), 48 + 36 * nv + 12 * nt + 24 * nb + 24 * ne);
    // Every vertex within the control points' box (a Bezier patch lies in their hull).
    let float = |off: usize| f32::from_le_bytes(body[off..off + 4].try_into().unwrap()) as f64;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &file.patches.patches {
        for q in &p.cps {
            for i in 0..3 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
    }
    for vtx in 0..nv {
        for i in 0..3 {
            let x = float(48 + 12 * vtx + 4 * i);
            assert!(
                x >= lo[i] - 1e-5 && x <= hi[i] + 1e-5,
                "vertex {vtx} outside the hull box"
            );
        }
    }
    assert_eq!(get(v.port, "/api/check").0, 200);
    let (status, info) = get(v.port, "/api/info");
    assert_eq!(status, 200);
    let info: serde_json::Value = serde_json::from_slice(&info).unwrap();
    assert_eq!(info["patches"], n);
    assert_eq!(info["kinds"]["tensor"], n);
    let Some(exe) = chromium() else { return };
    let mut b = cdp::Browser::launch(&exe, W, H);
    b.open(&format!("{}?mode=gauss", v.url));
    let s = shot(&mut b);
    let cover = s.covered(0, s.width());
    assert!(cover > 0.1, ".bv surface: {cover:.3} of the canvas");
    assert!(
        s.hues(s.canvas.1, s.canvas.3 - 40, 40) >= 3,
        "a curvature map of the file"
    );
    assert_eq!(b.eval("document.getElementById('scheme').disabled"), true);
    let _ = std::fs::remove_dir_all(&dir);
}
