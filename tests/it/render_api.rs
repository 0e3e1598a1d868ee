//! The library's typed render call (`fairsub::render` with `RenderOptions`) and the command
//! line's `fairsub render` agree: the same PNG bytes for the same options (written by the
//! same encoder), the defaults the command's, and the same message for a bad value.

use crate::common::{run, scratch};
use fairsub::{Element, Mode, Options, Overlays, RenderOptions, Surface, render, surface};

/// `fairsub render NET --scheme catmull-clark --rings 3 WORDS -o FILE`'s PNG bytes.
fn cli_png(words: &[&str], tag: &str) -> Vec<u8> {
    let png = scratch("render-api").join(format!("{tag}.png"));
    let mut args = vec![
        "render",
        "gallery:cnet-5-saddle",
        "--scheme",
        "catmull-clark",
        "--rings",
        "3",
    ];
    args.extend_from_slice(words);
    let p = png.display().to_string();
    args.extend(["-o", &p]);
    let (code, _, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    std::fs::read(&png).unwrap()
}

/// The library's surface of the command's net: cnet-5-saddle under Catmull-Clark.
fn saddle(rings: usize) -> Surface {
    surface(
        "gallery:cnet-5-saddle",
        "catmull-clark",
        rings,
        true,
        &Options::default(),
    )
    .unwrap()
}

/// The library's picture of `s` with `o`, encoded by the command's PNG writer.
fn lib_png(s: &Surface, o: &RenderOptions, tag: &str) -> Vec<u8> {
    let png = scratch("render-api-lib").join(format!("{tag}.png"));
    render(s, o).unwrap().write_png(&png).unwrap();
    std::fs::read(&png).unwrap()
}

#[test]
fn the_command_and_the_typed_call_draw_the_same_bytes() {
    let small = RenderOptions {
        width: 72,
        height: 48,
        ..RenderOptions::default()
    };
    // defaults besides the size: shaded, aa 2, azimuth -60, elevation 40, ...
    let cases: Vec<(&str, Vec<&str>, RenderOptions)> = vec![
        ("shaded", vec!["--size", "72x48"], small.clone()),
        (
            "highlight",
            vec![
                "--size",
                "72x48",
                "--mode",
                "highlight",
                "--azimuth",
                "-30",
                "--elevation",
                "55",
                "--stripes",
                "7",
                "--stripe-width",
                "0.3",
                "--light-angle",
                "20",
                "--overlay",
                "net,patches",
                "--aa",
                "1",
            ],
            {
                let mut o = small.clone();
                o.mode = Mode::Highlight;
                o.view.azimuth_deg = -30.0;
                o.view.elevation_deg = 55.0;
                o.shade.stripes = 7.0;
                o.shade.stripe_width = 0.3;
                o.shade.light_angle_deg = 20.0;
                o.overlays = Overlays {
                    net: true,
                    patches: true,
                };
                o.supersample = 1;
                o
            },
        ),
        (
            "mean",
            vec![
                "--size",
                "64x64",
                "--mode",
                "mean",
                "--focus",
                "vertex:0",
                "--zoom-rings",
                "2..3",
                "--range",
                "0.5",
                "--fov",
                "25",
            ],
            {
                let mut o = small.clone();
                (o.width, o.height) = (64, 64);
                o.mode = Mode::Mean;
                o.view.focus = Some(Element::Vertex(0));
                o.view.zoom_rings = Some((2, 3));
                o.shade.range = Some(0.5);
                o.view.fov_deg = 25.0;
                o
            },
        ),
    ];
    let s = saddle(3);
    let mut pictures = Vec::new();
    for (tag, words, o) in &cases {
        let a = cli_png(words, tag);
        let b = lib_png(&s, o, tag);
        assert!(a.len() > 100, "{tag}: {} bytes", a.len());
        assert!(
            a == b,
            "{tag}: the command's PNG differs from the typed call's"
        );
        pictures.push(b);
    }
    // and the pictures differ from each other: the options reached the renderer
    assert_ne!(pictures[0], pictures[1]);
}

#[test]
fn a_bad_value_gives_the_same_message_both_ways() {
    let s = saddle(2);
    let cases: [(&[&str], RenderOptions); 3] = [
        (&["--stripe-width", "1.5"], {
            let mut o = RenderOptions::default();
            o.shade.stripe_width = 1.5;
            o
        }),
        (
            &["--size", "4x64"],
            RenderOptions {
                width: 4,
                height: 64,
                ..RenderOptions::default()
            },
        ),
        (
            &["--aa", "9"],
            RenderOptions {
                supersample: 9,
                ..RenderOptions::default()
            },
        ),
    ];
    let want = [
        "bad --stripe-width 1.5: must lie strictly between 0 and 1",
        "bad --size 4x64: width and height must be between 8 and 16384 pixels",
        "bad --aa 9: samples per pixel axis must be 1 to 8",
    ];
    let out = scratch("render-api-bad")
        .join("bad.png")
        .display()
        .to_string();
    for ((words, o), want) in cases.iter().zip(want) {
        let mut args = vec!["render", "gallery:cube", "-o", &out];
        args.extend_from_slice(words);
        let (code, _, err) = run(&args);
        assert_eq!(code, 1, "{err}");
        // the crate's error for a bad argument: "invalid argument: " and the message
        assert_eq!(err.trim(), format!("error: invalid argument: {want}"));
        let lib = render(&s, o).unwrap_err().to_string();
        assert_eq!(lib, format!("invalid argument: {want}"));
        let bad = o.check().unwrap_err();
        assert_eq!(bad.cli_message(), want);
    }
}
