//! A stable-Rust fuzzer (cargo-fuzz needs nightly): a mutation loop over the gallery nets
//! written as OBJ, OFF and PLY. Every mutant goes through the mesh reader in-process (no panic:
//! a net or an error) and a share of them through `fairsub subdivide`, `render` and `check`
//! (exit code 0 or 1, never a signal; on 0 the output is read back by fairsub's own readers, on
//! 1 no output exists).
//!
//! CI runs a bounded number of cases (`FAIRSUB_FUZZ_CASES`, default 300; one in 10 through the
//! command line). The mutations are seeded (`FAIRSUB_FUZZ_SEED`), so a failure is reproducible.

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
    let o = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    // a signal (abort, segfault) has no code
    o.status.code().unwrap_or(-1)
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
    let cases: usize = std::env::var("FAIRSUB_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(300);
    let seed: u64 = std::env::var("FAIRSUB_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x9e37_79b9_7f4a_7c15);
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
