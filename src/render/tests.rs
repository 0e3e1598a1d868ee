//! Unit tests of the render entry points (the acceptance tests are in `tests/it/render.rs`).

use super::*;

#[crate::unit::test]
fn modes_parse_and_name() {
    for m in Mode::ALL {
        assert_eq!(m.name().parse::<Mode>().unwrap(), m);
    }
    let e = "curvy".parse::<Mode>().unwrap_err().to_string();
    assert!(
        e.contains("unknown mode 'curvy'") && e.contains("highlight"),
        "{e}"
    );
}

#[crate::unit::test]
fn sizes_parse() {
    assert_eq!(parse_size("800x600").unwrap(), (800, 600));
    assert_eq!(parse_size("256").unwrap(), (256, 256));
    assert!(parse_size("80x").is_err());
    let o = RenderOptions {
        width: 4,
        ..RenderOptions::default()
    };
    assert!(
        o.validate()
            .unwrap_err()
            .to_string()
            .contains("bad --size 4x800")
    );
}

#[crate::unit::test]
fn nice_ceil_rounds_up_to_two_digits() {
    assert_eq!(nice_ceil(0.01234), 0.013);
    assert_eq!(nice_ceil(1.0), 1.0);
    assert_eq!(nice_ceil(987.0), 990.0);
}

#[crate::unit::test]
fn png_bytes_are_deterministic_and_decodable() {
    let mut img = Image::filled(17, 9, [10, 20, 30]);
    img.set(3, 4, [200, 100, 0]);
    let a = img.to_png().unwrap();
    assert_eq!(a, img.to_png().unwrap());
    let dec = png::Decoder::new(std::io::Cursor::new(a));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (17, 9));
    assert_eq!(&buf[..info.buffer_size()], &img.data[..]);
}

#[crate::unit::test]
fn overlays_parse() {
    let o = Overlays::parse(&["net,patches"]).unwrap();
    assert!(o.net && o.patches);
    assert!(
        Overlays::parse(&["grid"])
            .unwrap_err()
            .to_string()
            .contains("unknown overlay")
    );
}
