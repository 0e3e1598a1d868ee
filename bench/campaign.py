#!/usr/bin/env python3
"""Hostile-input campaign (issue 20): mutated nets (OBJ, OFF, ASCII PLY), .bv surfaces, q-files,
FCV files, crease side files and analyze/charmap options through every command, each run under
`timeout 10` and a 4 GiB address-space limit. Prints the tally: exit codes, panics (101),
signals, timeouts, memory aborts, outputs that fairsub cannot read back, half-written outputs.

    bench/campaign.py [CASES] [SEED]      # defaults 3000 and the current time; BIN=target/release/fairsub

Not part of `cargo test`; its last tally is quoted in the README's limits section.
"""

import os
import random
import resource
import subprocess
import sys
import tempfile

BIN = os.environ.get("BIN", "target/release/fairsub")
CASES = int(sys.argv[1]) if len(sys.argv) > 1 else 3000
SEED = int(sys.argv[2]) if len(sys.argv) > 2 else int.from_bytes(os.urandom(4), "little")
TOKENS = [b"1e100", b"-1e308", b"nan", b"inf", b"0", b"-1", b"4294967296", b"99999", b"\xff",
          b"\n", b" ", b"f", b"v", b"#", b"/", b"3", b"1e-300", b"t", b"group", b"4", b"5",
          b"vertex", b"*", b"-0"]


def limits():
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))


def run(args):
    try:
        p = subprocess.run(["timeout", "10", BIN] + args, capture_output=True, preexec_fn=limits)
        return p.returncode, p.stderr.decode("utf-8", "replace")
    except OSError as e:
        return -999, str(e)


def mutate(b, rng):
    b = bytearray(b)
    for _ in range(1 + rng.randrange(4)):
        n = len(b)
        k = rng.randrange(5)
        if k == 0 and n:
            b[rng.randrange(n)] = rng.randrange(256)
        elif k == 1:
            i = rng.randrange(n + 1)
            b[i:i] = rng.choice(TOKENS)
        elif k == 2 and n:
            i = rng.randrange(n)
            del b[i:i + 1 + rng.randrange(64)]
        elif k == 3 and n:
            i = rng.randrange(n)
            j = min(n, i + 1 + rng.randrange(256))
            b[j:j] = b[i:j]
        else:
            del b[rng.randrange(n + 1):]
    return bytes(b)


def main():
    rng = random.Random(SEED)
    d = tempfile.mkdtemp(prefix="fairsub-campaign-")
    p = lambda n: os.path.join(d, n)
    seeds = {}
    for net in ["cube", "torus-evs", "open-grid", "tri-grid", "prism-5", "cnet-5-convex", "icosahedron"]:
        for ext, fmt in [("obj", []), ("off", []), ("ply", ["--format", "ply-ascii"])]:
            out = p(f"{net}.{ext}")
            run(["subdivide", f"gallery:{net}", "--scheme", "catmull-clark", "--levels", "0", "-o", out] + fmt)
            if os.path.exists(out):
                seeds.setdefault(ext, []).append(open(out, "rb").read())
    run(["subdivide", "gallery:cube", "--scheme", "catmull-clark", "-o", p("seed.bv")])
    seeds["bv"] = [open(p("seed.bv"), "rb").read()]
    seeds["q"] = [b"# q\nvertex 0\nkind c1\np 0 0 0\nq 0 2 0.1 0 0\n"]
    seeds["fcv"] = [b"0 0 0\n*\n*\n0.5 0.5 1.2\n*\n*\n"]
    seeds["txt"] = [b"t crease 2/1/0 0 1 2.5\nt corner 1/1/0 6 10\nt hole 1/0/0 2\n"]
    cube_off = p("cube.off")
    run(["subdivide", "gallery:cube", "--scheme", "catmull-clark", "--levels", "0", "-o", cube_off])
    net_cmds = [
        lambda f: (["info", f], None),
        lambda f: (["subdivide", f, "--scheme", "catmull-clark", "--levels", "2", "-o", p("o.obj")], p("o.obj")),
        lambda f: (["subdivide", f, "--scheme", "loop", "--levels", "2", "-o", p("o.ply")], p("o.ply")),
        lambda f: (["subdivide", f, "--scheme", "doo-sabin", "--levels", "2", "-o", p("o.off")], p("o.off")),
        lambda f: (["subdivide", f, "--scheme", "catmull-clark", "--rings", "2", "-o", p("o.bv")], p("o.bv")),
        lambda f: (["subdivide", f, "--scheme", "eg", "--rings", "2", "-o", p("o.obj")], p("o.obj")),
        lambda f: (["subdivide", f, "--scheme", "qas-plus", "-o", p("o.bv")], p("o.bv")),
        lambda f: (["subdivide", f, "--scheme", "nonbox", "--levels", "2", "-o", p("o.obj")], p("o.obj")),
        lambda f: (["subdivide", f, "--scheme", "pgs", "--rings", "2", "-o", p("o.ply")], p("o.ply")),
        lambda f: (["check", f, "--scheme", "catmull-clark"], None),
        lambda f: (["render", f, "--size", "48x48", "-o", p("o.png")], p("o.png")),
    ]
    side_cmds = {
        "bv": [lambda f: (["check", f], None), lambda f: (["render", f, "--size", "48x48", "-o", p("o.png")], p("o.png"))],
        "q": [lambda f: (["subdivide", "gallery:cnet-5-convex", "--scheme", "qas-plus", "--q-file", f, "-o", p("o.bv")], p("o.bv"))],
        "fcv": [lambda f: (["subdivide", "gallery:cube", "--scheme", "nonbox", "--fcv-file", f, "--levels", "2", "-o", p("o.obj")], p("o.obj")),
                lambda f: (["subdivide", "gallery:cube", "--scheme", "nonbox", "--fcv-file", f, "--rings", "2", "-o", p("o.obj")], p("o.obj"))],
        "txt": [lambda f: (["subdivide", cube_off, "--scheme", "catmull-clark", "--levels", "2", "--creases", f, "-o", p("o.obj")], p("o.obj")),
                lambda f: (["subdivide", cube_off, "--scheme", "loop", "--levels", "2", "--creases", f, "-o", p("o.obj")], p("o.obj"))],
    }
    tally = {k: 0 for k in ["runs", "exit0", "exit1", "exit2", "panic", "signal", "timeout",
                            "memory-abort", "other-exit", "unreadable-output", "output-after-error",
                            "error-without-place"]}
    bad = []
    for case in range(CASES):
        kind = rng.choice(["obj", "off", "ply", "obj", "off", "ply", "bv", "q", "fcv", "txt", "opts"])
        if kind == "opts":
            s = rng.choice(["catmull-clark", "guided-bi5", "pgs", "nonbox", "eg", "qas-plus", "loop",
                            "doo-sabin", "polar", "ternary", "nonsense"])
            n = rng.choice(["0", "1", "2", "3", "4", "5", "7", "16", "17", "40", "84", "100", "10000", "-1", "x"])
            cmds = [(["analyze", "--scheme", s, "--valence", n], None),
                    (["charmap", "--scheme", s, "--valence", n, "-o", p("o.bv")], p("o.bv"))]
            args, out = rng.choice(cmds)
        else:
            f = p(f"case.{kind}")
            open(f, "wb").write(mutate(rng.choice(seeds[kind]), rng))
            args, out = rng.choice(side_cmds.get(kind, net_cmds))(f)
        if out and os.path.exists(out):
            os.remove(out)
        code, err = run(args)
        tally["runs"] += 1
        label = None
        if code == 0:
            tally["exit0"] += 1
            if out and out.endswith(".png"):
                if not os.path.getsize(out):
                    label = "unreadable-output"
            elif out:
                rc, e2 = run(["check", out] if out.endswith(".bv") else ["info", out])
                if rc != 0:
                    label = "unreadable-output"
        elif code in (1, 2):
            tally[f"exit{code}"] += 1
            if out and os.path.exists(out):
                label = "output-after-error"
            if code == 1 and ":0:" in err:
                label = "error-without-place"
        elif code == 101:
            label = "panic"
        elif code == 124:
            label = "timeout"
        elif "memory allocation" in err:
            label = "memory-abort"
        elif code < 0 or code >= 128:
            label = "signal"
        else:
            label = "other-exit"
        if label:
            tally[label] += 1
            keep = p(f"bad-{case}")
            if kind != "opts":
                os.rename(p(f"case.{kind}"), keep)
            bad.append((case, label, code, args, err.strip().splitlines()[:2]))
    print(f"campaign: {CASES} cases, seed {SEED}, binary {BIN}, timeout 10 s, address space 4 GiB")
    for k, v in tally.items():
        print(f"  {k:22} {v}")
    for b in bad[:40]:
        print("  BAD", b)
    print(f"  inputs kept in {d}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
