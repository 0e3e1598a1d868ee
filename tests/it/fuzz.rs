//! A stable-Rust fuzzer (cargo-fuzz needs nightly): a mutation loop over the gallery nets
//! written as OBJ, OFF and PLY. Every mutant goes through the mesh reader in-process (no panic:
//! a net or an error) and a share of them through `fairsub subdivide`, `render` and `check`
//! (exit code 0 or 1, never a signal; on 0 the output is read back by fairsub's own readers, on
//! 1 no output exists).
//!
//! A second loop mutates the other inputs: a `.bv` surface (through `check` and `render`), a
//! q-file (`--q-file` with qas-plus), an FCV file (`--fcv-file` with nonbox), a crease side file
//! (`--creases` with catmull-clark), and the options of `analyze` / `charmap` (schemes,
//! valences, sizes). Its contract adds the message: on exit 1 it names the mutated file with a
//! line >= 1 (or no line), or the element (patch, vertex, face, valence).
//!
//! CI runs a bounded number of cases (`FAIRSUB_FUZZ_CASES`, default 300 nets, one in 10 through
//! the command line, and a fifteenth as many side-file cases per kind). The mutations are seeded
//! (`FAIRSUB_FUZZ_SEED`), so a failure is reproducible.

use std::path::Path;
use std::process::Command;

/// xorshift64*: a small seeded generator, enough to pick mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const TOKENS: &[&[u8]] = &[
    b"1e100",
    b"-1e308",
    b"nan",
    b"inf",
    b"0",
    b"-1",
    b"4294967296",
    b"99999",
    b"\xff",
    b"\n",
    b" ",
    b"f",
    b"v",
    b"#",
    b"/",
    b"3",
    b"1e-300",
];

/// One random edit of `b`: flip a byte, insert a token, delete or duplicate a span.
fn mutate(b: &mut Vec<u8>, rng: &mut Rng) {
    let n = b.len();
    match rng.below(5) {
        0 if n > 0 => {
            let i = rng.below(n);
            b[i] = rng.next() as u8;
        }
        1 => {
            let t = TOKENS[rng.below(TOKENS.len())];
            let i = rng.below(n + 1);
            b.splice(i..i, t.iter().copied());
        }
        2 if n > 0 => {
            let i = rng.below(n);
            let j = (i + 1 + rng.below(64)).min(n);
            b.drain(i..j);
        }
        3 if n > 0 => {
            let i = rng.below(n);
            let j = (i + 1 + rng.below(256)).min(n);
            let span: Vec<u8> = b[i..j].to_vec();
            b.splice(j..j, span);
        }
        _ => b.truncate(rng.below(n + 1)),
    }
}

fn run(args: &[&str]) -> i32 {
    run_err(args).0
}

/// The exit code (-1 for a signal: an abort or a segfault has no code) and the error text.
fn run_err(args: &[&str]) -> (i32, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn cases_and_seed() -> (usize, u64) {
    let cases = std::env::var("FAIRSUB_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(300);
    let seed = std::env::var("FAIRSUB_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x9e37_79b9_7f4a_7c15);
    (cases, seed)
}

/// `command ... -o out`: exit 0 with a readable output, or exit 1 and no output.
fn contract(args: &[&str], out: &Path, read_back: impl Fn(&Path) -> bool, case: &str) {
    let _ = std::fs::remove_file(out);
    let code = run(args);
    match code {
        0 => assert!(
            read_back(out),
            "{case}: {args:?} wrote an unreadable output"
        ),
        1 => assert!(!out.exists(), "{case}: {args:?} failed but left an output"),
        c => panic!("{case}: {args:?} exited with {c}"),
    }
}

#[test]
fn mutated_nets_never_panic_and_outputs_are_valid_or_absent() {
    let (cases, seed) = cases_and_seed();
    let dir = std::env::temp_dir().join(format!("fairsub-fuzz-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut seeds = Vec::new();
    for (name, mesh) in fairsub::gallery::all() {
        if mesh.num_vertices() > 200 {
            continue;
        }
        for (ext, fmt) in [
            ("obj", fairsub::io::MeshFormat::Obj),
            ("off", fairsub::io::MeshFormat::Off),
            ("ply", fairsub::io::MeshFormat::PlyAscii),
            ("ply", fairsub::io::MeshFormat::PlyBinary),
        ] {
            let p = dir.join(format!("{name}-{}.{ext}", seeds.len()));
            fairsub::io::write_mesh(&p, &mesh, fmt).unwrap();
            seeds.push((ext, std::fs::read(&p).unwrap()));
        }
    }
    assert!(!seeds.is_empty());
    let mut rng = Rng(seed | 1);
    let reads = |p: &Path| fairsub::io::read_mesh(p).is_ok();
    let bv_reads = |p: &Path| fairsub::io::read_bv(p).is_ok();
    let png_written = |p: &Path| std::fs::metadata(p).map(|m| m.len() > 0).unwrap_or(false);
    let (mut accepted, mut through_cli) = (0, 0);
    for case in 0..cases {
        let (ext, seed_bytes) = &seeds[rng.below(seeds.len())];
        let mut b = seed_bytes.clone();
        for _ in 0..1 + rng.below(4) {
            mutate(&mut b, &mut rng);
        }
        let p = dir.join(format!("case.{ext}"));
        std::fs::write(&p, &b).unwrap();
        let label = format!("case {case} (seed {seed})");
        let read = std::panic::catch_unwind(|| fairsub::io::read_mesh(&p).is_ok());
        let ok = read.unwrap_or_else(|_| panic!("{label}: the reader panicked"));
        accepted += ok as usize;
        if case % 10 != 0 {
            continue;
        }
        through_cli += 1;
        let net = p.to_str().unwrap();
        let obj = dir.join("out.obj");
        let bv = dir.join("out.bv");
        let png = dir.join("out.png");
        let o = obj.to_str().unwrap();
        contract(
            &[
                "subdivide",
                net,
                "--scheme",
                "catmull-clark",
                "--rings",
                "1",
                "-o",
                o,
            ],
            &obj,
            reads,
            &label,
        );
        contract(
            &[
                "subdivide",
                net,
                "--scheme",
                "catmull-clark",
                "--levels",
                "2",
                "-o",
                o,
            ],
            &obj,
            reads,
            &label,
        );
        contract(
            &[
                "subdivide",
                net,
                "--scheme",
                "catmull-clark",
                "-o",
                bv.to_str().unwrap(),
            ],
            &bv,
            bv_reads,
            &label,
        );
        if bv.exists() {
            let code = run(&["check", bv.to_str().unwrap()]);
            assert!(code == 0 || code == 1, "{label}: check exited with {code}");
        }
        contract(
            &[
                "render",
                net,
                "--size",
                "64x64",
                "-o",
                png.to_str().unwrap(),
            ],
            &png,
            png_written,
            &label,
        );
    }
    // the mutations leave some nets readable, so the commands see nets, not only errors
    assert!(
        accepted > 0 && through_cli > 0,
        "{accepted} of {cases} read"
    );
}

/// Exit 0, 1 or 2 (never a panic's 101 or a signal); on 1 the message names `file` (at a line
/// >= 1 when it gives one) or an element; the output `out` is valid on 0 and absent otherwise.
fn side_contract(args: &[&str], file: &str, out: Option<(&Path, bool)>, case: &str) {
    if let Some((o, _)) = out {
        let _ = std::fs::remove_file(o);
    }
    let (code, err) = run_err(args);
    assert!(
        code == 0 || code == 1 || code == 2,
        "{case}: {args:?} exited with {code}: {err}"
    );
    if code == 1 {
        let named = err.contains(file) && !err.contains(&format!("{file}:0:"));
        let element = ["patch", "vertex", "face", "valence", "too large", "scheme"]
            .iter()
            .any(|w| err.contains(w));
        assert!(
            named || element,
            "{case}: {args:?}: message names nothing: {err}"
        );
    }
    if let Some((o, is_bv)) = out {
        if code == 0 {
            let ok = if is_bv {
                fairsub::io::read_bv(o).is_ok()
            } else {
                fairsub::io::read_mesh(o).is_ok()
            };
            assert!(ok, "{case}: {args:?} wrote an unreadable output");
        } else {
            assert!(!o.exists(), "{case}: {args:?} failed but left an output");
        }
    }
}

const CUBE_OFF: &str = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
    4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

#[test]
fn mutated_side_files_and_options_keep_the_contract() {
    let (cases, seed) = cases_and_seed();
    let per_kind = cases.div_ceil(15).max(5);
    let dir = std::env::temp_dir().join(format!("fairsub-fuzz-side-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let (cube, obj, bv_out, png) = (
        path("cube.off"),
        path("out.obj"),
        path("out.bv"),
        path("out.png"),
    );
    std::fs::write(&cube, CUBE_OFF).unwrap();
    let seed_bv = path("seed.bv");
    assert_eq!(
        run(&[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "-o",
            &seed_bv
        ]),
        0
    );
    let bv_bytes = std::fs::read(&seed_bv).unwrap();
    let kinds: [(&str, Vec<u8>); 4] = [
        ("case.bv", bv_bytes),
        (
            "case.q",
            b"# expansion\nvertex 0\nkind c1\np 0 0 0\nq 0 2 0.1 0 0\n".to_vec(),
        ),
        ("case.fcv", b"0 0 0\n*\n*\n0.5 0.5 1.2\n*\n*\n".to_vec()),
        (
            "case.txt",
            b"t crease 2/1/0 0 1 2.5\nt corner 1/1/0 6 10\nt hole 1/0/0 2\n".to_vec(),
        ),
    ];
    let mut rng = Rng(seed ^ 0x5151_5151 | 1);
    for (k, (name, seed_bytes)) in kinds.iter().enumerate() {
        let file = path(name);
        for case in 0..per_kind {
            let mut b = seed_bytes.clone();
            for _ in 0..1 + rng.below(4) {
                mutate(&mut b, &mut rng);
            }
            std::fs::write(&file, &b).unwrap();
            let label = format!("{name} case {case} (seed {seed})");
            let o = |p: &str, bv: bool| Some((Path::new(p).to_path_buf(), bv));
            let (target, args): (Option<(std::path::PathBuf, bool)>, Vec<&str>) = match k {
                0 => {
                    side_contract(&["check", &file], name, None, &label);
                    (
                        o(&png, false).map(|(p, _)| (p, false)),
                        vec!["render", &file, "--size", "48x48", "-o", &png],
                    )
                }
                1 => (
                    o(&bv_out, true),
                    vec![
                        "subdivide",
                        "gallery:cnet-5-convex",
                        "--scheme",
                        "qas-plus",
                        "--q-file",
                        &file,
                        "-o",
                        &bv_out,
                    ],
                ),
                2 => (
                    o(&obj, false),
                    vec![
                        "subdivide",
                        "gallery:cube",
                        "--scheme",
                        "nonbox",
                        "--fcv-file",
                        &file,
                        "--levels",
                        "1",
                        "-o",
                        &obj,
                    ],
                ),
                _ => (
                    o(&obj, false),
                    vec![
                        "subdivide",
                        &cube,
                        "--scheme",
                        "catmull-clark",
                        "--levels",
                        "2",
                        "--creases",
                        &file,
                        "-o",
                        &obj,
                    ],
                ),
            };
            if k == 0 {
                // a PNG is not read back: it exists on 0 and is absent otherwise
                let p = target.unwrap().0;
                let _ = std::fs::remove_file(&p);
                let (code, err) = run_err(&args);
                assert!(
                    code == 0 || code == 1,
                    "{label}: render exited with {code}: {err}"
                );
                assert_eq!(
                    p.exists(),
                    code == 0,
                    "{label}: render output and exit code disagree"
                );
            } else {
                let t = target.as_ref().map(|(p, bv)| (p.as_path(), *bv));
                side_contract(&args, name, t, &label);
            }
        }
    }
    // analyze / charmap with mutated options
    let schemes = [
        "catmull-clark",
        "guided-bi5",
        "pgs",
        "nonbox",
        "eg",
        "qas-plus",
        "loop",
        "doo-sabin",
        "polar",
        "no-such-scheme",
        "",
    ];
    let valences = [
        "0",
        "1",
        "2",
        "3",
        "5",
        "7",
        "16",
        "17",
        "24",
        "25",
        "44",
        "45",
        "-1",
        "99999999999",
        "1e3",
        "x",
    ];
    for case in 0..per_kind {
        let s = schemes[rng.below(schemes.len())];
        let n = valences[rng.below(valences.len())];
        let label = format!("analyze case {case} (seed {seed})");
        if rng.below(2) == 0 {
            side_contract(
                &["analyze", "--scheme", s, "--valence", n],
                "--valence",
                None,
                &label,
            );
        } else {
            let t = Some((Path::new(&bv_out), true));
            side_contract(
                &["charmap", "--scheme", s, "--valence", n, "-o", &bv_out],
                "--valence",
                t,
                &label,
            );
        }
    }
}
