//! Frame rate of `fairsub view` in headless Chromium: the page's `?bench=N` mode (N frames
//! paced by requestAnimationFrame while the camera turns, then N frames each drawn and waited
//! for by reading one pixel back) on EG's surface of the torus with valence-3 and valence-5 vertices,
//! 4 rings, at tessellations from 16k to 1M triangles. Besides the frame rate it prints the
//! JavaScript time of one frame (the calls handed to the GPU process, median) and one frame's
//! WebGL calls and data uploads (the drawing path a real GPU gets).
//!
//! ```text
//! cargo bench --bench viewer_fps          # FRAMES=30 SIZE=1280x800 TESS=4,8,16,32 MODE=highlight
//! FRAMES=60 SIZE=1920x1080 TESS=32 MODE=shaded cargo bench --bench viewer_fps
//! ```
//!
//! The browser is Debian's chromium with SwiftShader (WebGL2 on the CPU; the machine's cores
//! rasterise): it measures the drawing path, not a laptop GPU. Skips without chromium.

#[path = "../tests/it/viewer/cdp.rs"]
mod cdp;

use std::io::BufRead;
use std::process::{Command, Stdio};

fn main() {
    let Some(exe) = cdp::find() else {
        eprintln!("viewer_fps: no chromium; skipped");
        return;
    };
    let frames: usize = std::env::var("FRAMES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30);
    let size = std::env::var("SIZE").unwrap_or_else(|_| "1280x800".into());
    let (w, h) = size
        .split_once('x')
        .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)))
        .expect("SIZE is WxH");
    let tess = std::env::var("TESS").unwrap_or_else(|_| "4,8,16,32".into());
    let mode = std::env::var("MODE").unwrap_or_else(|_| "highlight".into());
    println!(
        "viewer frame rate: EG on gallery:torus-evs, 4 rings; {mode} mode; {frames} frames; \
         window {w}x{h}"
    );
    println!(
        "{:>5} {:>10} {:>9} {:>10} {:>14} {:>8} {:>6} {:>8}",
        "tess", "triangles", "frames/s", "ms/frame", "draw+read ms", "JS ms", "calls", "uploads"
    );
    let mut renderer = String::new();
    for t in tess.split(',') {
        let mut child = Command::new(env!("CARGO_BIN_EXE_fairsub"))
            .args([
                "view",
                "gallery:torus-evs",
                "--scheme",
                "eg",
                "--rings",
                "4",
            ])
            .args(["--tess", t, "--port", "0", "--no-browser"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("fairsub runs");
        let mut url = String::new();
        std::io::BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut url)
            .unwrap();
        let mut b = cdp::Browser::launch(&exe, w, h);
        b.open(&format!("{}&mode={mode}&bench={frames}", url.trim()));
        let r = b.eval("window.fairsubBench");
        println!(
            "{:>5} {:>10} {:>9.2} {:>10.1} {:>14.1} {:>8.3} {:>6} {:>8}",
            t,
            r["triangles"],
            r["fps"].as_f64().unwrap(),
            r["msPerFrame"].as_f64().unwrap(),
            r["drawMsMedian"].as_f64().unwrap(),
            r["jsMsMedian"].as_f64().unwrap(),
            r["callsTotal"],
            r["uploads"],
        );
        renderer = r["renderer"].as_str().unwrap_or("?").to_string();
        drop(b);
        let _ = child.kill();
        let _ = child.wait();
    }
    println!("renderer: {renderer}");
}
