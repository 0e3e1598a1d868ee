//! OpenSubdiv's hole faces under non-box (`nonbox::holes`, fairsub's reading): the surface is
//! that of the net without the tags less the patches over the hole faces, patch for patch; the
//! G^1 caps of the vertices on a hole face are built whole and partly kept, and the patch
//! table repeats them for moved points; `--levels` refines the hole faces and leaves them out.

use crate::sharp_helpers::support::{osd, osd_path, run, table_reapplies};
use fairsub::analysis::continuity;
use fairsub::host::ComplexOptions;
use fairsub::schemes::registry::registry;
use fairsub::surface::eval::Surface;

const NET: &str = "catmark_hole_test1";
/// The net's hole face.
const HOLE: u32 = 1;

fn build(scheme: &str, m: &fairsub::mesh::PolyMesh) -> fairsub::host::SurfaceOutput {
    let spec = registry().lookup(scheme).unwrap();
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    fairsub::surface::build(&spec, m, opts, &mut |_| {}).unwrap_or_else(|e| panic!("{e}"))
}

/// The cube with one hole face: of the surface of the cube without the tag, exactly the
/// patches over the other five faces, bit for bit and in order; the four vertices on the hole
/// face keep two of their three cap patches (the caps' `kept` sectors); G^1 to rounding, open
/// along the hole's rim only. Before, non-box refused hole tags.
#[test]
fn hole_faces_leave_out_their_patches_only() {
    let m = osd(NET);
    let bare = m.clone().with_extras(None);
    for scheme in ["nonbox", "nonbox-4dir"] {
        let out = build(scheme, &m);
        let whole = build(scheme, &bare).complex;
        let expect: Vec<usize> = (0..whole.len())
            .filter(|&i| whole.domain(i).expect("a domain").face != HOLE)
            .collect();
        let c = &out.complex;
        assert_eq!((whole.len(), c.len()), (600, 500), "{scheme}");
        assert_eq!(c.len(), expect.len(), "{scheme}");
        for (k, &i) in expect.iter().enumerate() {
            assert_eq!(
                c.patches[k].cps, whole.patches[i].cps,
                "{scheme}: patch {k}"
            );
        }
        let note = format!("{:?}", out.notes);
        assert!(
            note.contains("1 hole faces") && note.contains("their 100 patches left out"),
            "{note}"
        );
        // the four partly kept caps are still caps: no note of a C^0 fill
        assert!(!note.contains("no G^1 cap"), "{note}");
        let kept: Vec<&Vec<u32>> = c.caps.iter().filter_map(|s| s.kept.as_ref()).collect();
        assert_eq!((c.caps.len(), kept.len()), (8, 4), "{scheme}");
        assert!(kept.iter().all(|k| k.len() == 2), "{kept:?}");
        let r = continuity::check(c);
        eprintln!(
            "{scheme}: {} patches, G1 {:.1e}, open {}",
            c.len(),
            r.all.g1,
            r.open_sides
        );
        assert!(
            r.all.c0 < 1e-12 && r.all.g1 < 1e-12,
            "{scheme}: {:e}",
            r.all.g1
        );
        // the rim of the hole face: 4 edges, 2 levels below the third ring's cells
        assert_eq!(r.open_sides, 24, "{scheme}");
    }
}

/// `eval` on the other faces is the surface of the net without the tag; on the hole face it
/// says that no patch covers it and why.
#[test]
fn eval_on_a_hole_face_names_it() {
    let m = osd(NET);
    let surface = Surface::new(&m, build("nonbox", &m).complex);
    let bare = m.clone().with_extras(None);
    let bare = Surface::new(&bare, build("nonbox", &bare).complex);
    for f in [0, 2, 5] {
        let (a, b) = (
            surface.evaluate(f, 0.3, 0.6).unwrap(),
            bare.evaluate(f, 0.3, 0.6).unwrap(),
        );
        assert_eq!(a.point, b.point, "face {f}");
    }
    let e = surface.evaluate(HOLE, 0.5, 0.5).unwrap_err().to_string();
    assert!(e.contains("face 1") && e.contains("hole faces"), "{e}");
}

/// The patch table re-applies to moved points within 1e-12 of the rebuilt surface, the partly
/// kept caps included (before the caps recorded their kept sectors, the table of such a net
/// was refused as not linear: 9.9e-5 away at moved points); the file's cap lines name the
/// kept sectors and read back.
#[test]
fn partly_kept_caps_reapply_and_round_trip() {
    let m = osd(NET);
    table_reapplies("nonbox", NET, &m, |_| true);
    let dir = crate::common::scratch("nonbox-holes-table");
    let (bv, tab) = (dir.join("c.bv"), dir.join("c.tab"));
    let (code, _, err) = run(&[
        "subdivide",
        &osd_path(NET),
        "-s",
        "nonbox",
        "--rings",
        "2",
        "-o",
        bv.to_str().unwrap(),
        "--stencils",
        tab.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&tab).unwrap();
    let kept_lines = text
        .lines()
        .filter(|l| l.starts_with("c ") && l.contains(" kept "))
        .count();
    assert_eq!(kept_lines, 4);
    let file = fairsub::io::table::read_table(&tab).unwrap();
    let partial: Vec<&Vec<u32>> = file.cap_sectors.iter().flatten().collect();
    assert_eq!(partial.len(), 4);
    assert!(partial.iter().all(|k| k.len() == 2));
    std::fs::remove_dir_all(&dir).ok();
}

/// `--levels 2` refines the hole face for support and leaves its 16 quads out (the FCV layout
/// keeps one FCV per written face), `--limit` its 64 triangles; the vertices are those of the
/// net without the tag.
#[test]
fn levels_leave_the_hole_faces_out() {
    let dir = crate::common::scratch("nonbox-holes-levels");
    let bare_net = dir.join("bare.obj");
    let text = std::fs::read_to_string(osd_path(NET)).unwrap();
    std::fs::write(
        &bare_net,
        text.lines()
            .filter(|l| !l.starts_with("t "))
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .unwrap();
    for (limit, faces, bare_faces) in [(false, 80, 96), (true, 320, 384)] {
        let (mut counts, mut points) = (Vec::new(), Vec::new());
        let nets = [
            (osd_path(NET), "holes.obj"),
            (bare_net.display().to_string(), "b.obj"),
        ];
        for (net, name) in nets {
            let out = dir.join(name);
            let mut args = vec!["subdivide", &net, "-s", "nonbox", "--levels", "2", "-o"];
            args.push(out.to_str().unwrap());
            if limit {
                args.push("--limit");
            }
            let (code, _, err) = run(&args);
            assert_eq!(code, 0, "{err}");
            // (unused points kept: the FCVs, and the vertices of hole faces only)
            let m = fairsub::io::read_mesh_as(&out, true).unwrap().mesh;
            counts.push(m.num_faces());
            // the level's 98 vertices come first
            points.push(m.positions()[..98].to_vec());
        }
        assert_eq!(counts, [faces, bare_faces], "limit {limit}");
        assert_eq!(points[0], points[1], "limit {limit}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
