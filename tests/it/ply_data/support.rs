//! The nets, values and PLY files of `tests/it/ply_data.rs`: the peer's OBJ nets, the test's own
//! per-vertex values of every PLY type, a PLY writer for the three encodings (independent of
//! fairsub's), a reader of fairsub's PLY output, and a row-by-row stencil multiply.

use fairsub::stencil::StencilTable;
use std::path::{Path, PathBuf};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// An OBJ net of the peer: points, faces (0-based) and its `t` tag lines.
pub struct Net {
    pub v: Vec<[f64; 3]>,
    pub f: Vec<Vec<usize>>,
    pub tags: String,
}

pub fn read_net(name: &str) -> Net {
    let text = std::fs::read_to_string(root().join("tests/data/osd").join(name)).unwrap();
    let mut n = Net {
        v: vec![],
        f: vec![],
        tags: String::new(),
    };
    for l in text.lines() {
        let t: Vec<&str> = l.split_whitespace().collect();
        match t.first() {
            Some(&"v") => n.v.push([1, 2, 3].map(|i| t[i].parse().unwrap())),
            Some(&"f") => n.f.push(
                t[1..]
                    .iter()
                    .map(|c| c.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                    .collect(),
            ),
            Some(&"t") => {
                n.tags.push_str(l);
                n.tags.push('\n');
            }
            _ => {}
        }
    }
    n
}

/// The test's vertex properties: (name, PLY type).
pub const CHANNELS: [(&str, &str); 8] = [
    ("red", "uchar"),
    ("green", "uchar"),
    ("blue", "uchar"),
    ("alpha", "float"),
    ("nx", "float"),
    ("quality", "double"),
    ("temperature", "short"),
    ("label", "char"),
];

/// The value of channel `c` at vertex `v`, as the file stores it (so exactly representable in
/// its type). The colours take the extremes 0 and 255 (Catmull-Clark's and Loop's weights are
/// positive, so the refined values stay in range; the rounding is what the integer check sees).
pub fn value(v: usize, c: usize) -> f64 {
    let s = (v * 7 + c * 13) as f64;
    match CHANNELS[c].1 {
        "uchar" => [0.0, 255.0, 37.0, 200.0, 255.0, 0.0, 128.0][(v * 3 + c) % 7],
        "float" => f64::from((0.37 * s).sin() as f32),
        "double" => (0.21 * s).cos() * 3.0 + 0.5,
        "short" => ((v * 977 + c * 131) % 65536) as f64 - 32768.0,
        "char" => [-128.0, 127.0, 5.0, -3.0][(v + c) % 4],
        t => unreachable!("{t}"),
    }
}

pub fn type_range(t: &str) -> (f64, f64) {
    match t {
        "uchar" => (0.0, 255.0),
        "short" => (-32768.0, 32767.0),
        "char" => (-128.0, 127.0),
        _ => (f64::NEG_INFINITY, f64::INFINITY),
    }
}

#[derive(Clone, Copy, PartialEq)]
pub enum Enc {
    Ascii,
    Little,
    Big,
}

/// Writes `net` as PLY in `enc` with double `x y z`, the properties of [`CHANNELS`] when
/// `data` (the alpha and normal channels between `y` and `z`, to test the header order), and a
/// vertex list property `ids` when `list`.
pub fn write_ply(path: &Path, net: &Net, enc: Enc, data: bool, list: bool) {
    let format = match enc {
        Enc::Ascii => "ascii",
        Enc::Little => "binary_little_endian",
        Enc::Big => "binary_big_endian",
    };
    // Property order: x y [alpha nx] z [the others] [ids].
    let mut props: Vec<(String, &str)> = vec![("x".into(), "double"), ("y".into(), "double")];
    let order: Vec<usize> = if data {
        vec![3, 4, 0, 1, 2, 5, 6, 7]
    } else {
        vec![]
    };
    let mut cols: Vec<Option<usize>> = vec![Some(100), Some(101)];
    for (k, &c) in order.iter().enumerate() {
        if k == 2 {
            props.push(("z".into(), "double"));
            cols.push(Some(102));
        }
        props.push((CHANNELS[c].0.into(), CHANNELS[c].1));
        cols.push(Some(c));
    }
    if !data {
        props.push(("z".into(), "double"));
        cols.push(Some(102));
    }
    let mut head = format!("ply\nformat {format} 1.0\nelement vertex {}\n", net.v.len());
    for (n, t) in &props {
        head.push_str(&format!("property {t} {n}\n"));
    }
    if list {
        head.push_str("property list uchar int ids\n");
    }
    head.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        net.f.len()
    ));
    let mut bytes = head.into_bytes();
    let put = |bytes: &mut Vec<u8>, t: &str, x: f64| match enc {
        Enc::Ascii => bytes.extend_from_slice(
            match t {
                "float" => format!(" {}", x as f32),
                "double" => format!(" {x:?}"),
                _ => format!(" {}", x as i64),
            }
            .as_bytes(),
        ),
        Enc::Little | Enc::Big => {
            let b: Vec<u8> = match t {
                "uchar" => vec![x as u8],
                "char" => vec![x as i8 as u8],
                "short" => (x as i16).to_be_bytes().to_vec(),
                "int" => (x as i32).to_be_bytes().to_vec(),
                "float" => (x as f32).to_be_bytes().to_vec(),
                "double" => x.to_be_bytes().to_vec(),
                t => unreachable!("{t}"),
            };
            if enc == Enc::Big {
                bytes.extend_from_slice(&b);
            } else {
                bytes.extend(b.iter().rev());
            }
        }
    };
    for (v, p) in net.v.iter().enumerate() {
        for ((_, t), col) in props.iter().zip(&cols) {
            let x = match col.unwrap() {
                c @ 100..=102 => p[c - 100],
                c => value(v, c),
            };
            put(&mut bytes, t, x);
        }
        if list {
            put(&mut bytes, "uchar", 2.0);
            put(&mut bytes, "int", v as f64);
            put(&mut bytes, "int", 7.0);
        }
        if enc == Enc::Ascii {
            bytes.push(b'\n');
        }
    }
    for face in &net.f {
        put(&mut bytes, "uchar", face.len() as f64);
        for &i in face {
            put(&mut bytes, "int", i as f64);
        }
        if enc == Enc::Ascii {
            bytes.push(b'\n');
        }
    }
    // The ascii lines start with a space from `put`: harmless for PLY readers.
    std::fs::write(path, bytes).unwrap();
}

/// A PLY file fairsub wrote: vertex property (name, type) pairs and the vertex rows.
pub struct Out {
    pub props: Vec<(String, String)>,
    pub rows: Vec<Vec<f64>>,
}

impl Out {
    pub fn column(&self, name: &str) -> Option<usize> {
        self.props.iter().position(|p| p.0 == name)
    }
}

/// Reads fairsub's PLY output (ascii or binary little endian) up to the vertex rows.
pub fn read_out(path: &Path) -> Out {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    let head = std::str::from_utf8(&bytes[..end]).unwrap();
    let ascii = head.contains("format ascii");
    let mut props = Vec::new();
    let mut nv = 0;
    let mut in_vertex = false;
    for l in head.lines() {
        let t: Vec<&str> = l.split_whitespace().collect();
        match t.as_slice() {
            ["element", "vertex", n] => {
                nv = n.parse().unwrap();
                in_vertex = true;
            }
            ["element", ..] => in_vertex = false,
            ["property", ty, name] if in_vertex => props.push((name.to_string(), ty.to_string())),
            _ => {}
        }
    }
    let mut rows = Vec::with_capacity(nv);
    if ascii {
        let text = std::str::from_utf8(&bytes[end..]).unwrap();
        for l in text.lines().take(nv) {
            let row = l
                .split_whitespace()
                .zip(&props)
                .map(|(x, (_, t))| match t.as_str() {
                    "float" => f64::from(x.parse::<f32>().unwrap()),
                    _ => x.parse().unwrap(),
                });
            rows.push(row.collect());
        }
    } else {
        let mut at = end;
        for _ in 0..nv {
            let mut row = Vec::new();
            for (_, t) in &props {
                let take = |n: usize| {
                    let mut b = [0u8; 8];
                    b[..n].copy_from_slice(&bytes[at..at + n]);
                    b
                };
                let (x, n) = match t.as_str() {
                    "uchar" => (f64::from(bytes[at]), 1),
                    "char" => (f64::from(bytes[at] as i8), 1),
                    "short" => (f64::from(i16::from_le_bytes([bytes[at], bytes[at + 1]])), 2),
                    "float" => (
                        f64::from(f32::from_le_bytes(take(4)[..4].try_into().unwrap())),
                        4,
                    ),
                    "double" => (f64::from_le_bytes(take(8)), 8),
                    t => panic!("unexpected type {t}"),
                };
                row.push(x);
                at += n;
            }
            rows.push(row);
        }
    }
    Out { props, rows }
}

/// `table` applied to per-vertex values, row by row (the test's own multiply).
pub fn multiply(table: &StencilTable, src: &[Vec<f64>]) -> Vec<Vec<f64>> {
    (0..table.num_rows())
        .map(|r| {
            let (idx, w) = table.row(r);
            let mut acc = vec![0.0; src[0].len()];
            for (&i, &w) in idx.iter().zip(w) {
                for (a, x) in acc.iter_mut().zip(&src[i as usize]) {
                    *a += w * x;
                }
            }
            acc
        })
        .collect()
}
