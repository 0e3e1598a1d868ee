//! Resource limits of the command line: every command estimates what it will allocate and
//! refuses up front, with the estimate and the way out, instead of running until the allocator
//! aborts.
//!
//! # The memory budget
//!
//! `--max-memory SIZE` (a global option: `4G`, `512M`, `2.5GiB`, `100000000`; binary units)
//! sets it. The default is **half of the memory the process may use**: the smallest of the
//! machine's physical memory, the address-space limit (`ulimit -v`), the data-segment limit
//! (`ulimit -d`) and the cgroup's memory limit (`/sys/fs/cgroup/memory.max`). Half, because
//! the estimates count the large arrays only, and the process needs room for its code,
//! threads, allocator arenas and the smaller arrays beside them.
//!
//! | command | estimate |
//! | --- | --- |
//! | `subdivide --levels`, `render --levels` | the net after each level from the scheme's own growth rule ([`crate::schemes::Scheme::step_size`]): parent, child and the step's stencil table ([`crate::schemes::growth`]) |
//! | `--rings` (`subdivide`, `check`, `render`, `compare`) | the patches: regular patches per input corner and ring patches per unit of element size per ring, measured by building one ring of the scheme on small canonical nets; plus one refinement step of the net (dense face rules) |
//! | tessellated `.obj`/`.off`/`.ply` | `(tess + 1)^2` points and `2 tess^2` triangles per patch with the arrays of the tessellation and of the validated mesh |
//! | `analyze`, `charmap` | the local matrix, `centre + n x points per sector` rows, from the scheme's local rules at a small valence; above [`MAX_ANALYSIS_DIMENSION`] rows, the sparse rows and the `n` Fourier blocks of a block-circulant matrix (of the Bloch basis for guided subdivision) |
//! | `render`, `compare` | the samples (`width x height x aa^2` per cell) |
//!
//! Besides the budget, bounds that hold on every machine: outputs have fewer than 2^31
//! vertices and corners (fairsub's meshes index with 32 bits), `--rings` is at most
//! [`MAX_RINGS`] (beyond about 70 rings every scheme's rings are smaller than the welding
//! tolerance of double precision), dense analysis at most [`MAX_ANALYSIS_DIMENSION`] rows
//! (its eigen-decomposition costs the cube of that), and the Fourier-block analysis of
//! block-circulant local matrices ([`crate::schemes::circulant`], above that many rows) and of
//! guided subdivision's bi-5 guide ([`crate::schemes::guided::fourier`]) at most valence
//! [`MAX_FOURIER_VALENCE`]; local matrices without sectors (the guided `-g4` / `-g3` guides)
//! at most valence [`MAX_SECTORLESS_VALENCE`].

use crate::error::{Error, Result};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::growth::{self, NetSize};
use crate::schemes::{Scheme, Spec, registry};
use crate::surface::{ComplexOptions, PatchComplex, Provenance};

mod budget;

pub use budget::{Budget, budget, default_budget, human, parse_memory};
use budget::{count, within_budget, within_indices};
pub(crate) use budget::{max_memory, with_budget};

/// Most rings per extraordinary element.
pub const MAX_RINGS: usize = 100;

/// Most rows of a local matrix that `analyze` and `charmap` decompose: the dense
/// eigen-decomposition's bound ([`crate::linalg::MAX_DENSE_EIGEN_ROWS`], where it is measured).
pub const MAX_ANALYSIS_DIMENSION: usize = crate::linalg::MAX_DENSE_EIGEN_ROWS;

/// Largest valence of the Fourier-block analysis of `analyze` and `charmap` (schemes with a
/// block-circulant local matrix, above [`MAX_ANALYSIS_DIMENSION`] rows). The blocks cost
/// `n (centre + sector)^3`; the characteristic map's certificate (3n to 36n patches and their
/// boundary curves) and the grouping of the `n x sector` eigenvalues grow a little faster.
/// Measured in release on one core of a shared 2-core machine at valence 1000: non-box-4dir
/// 7.1 s (36 000 ring patches), non-box 4.8 s, Catmull-Clark 4.3 s, PGS and TPS 3.5 s, at
/// most 180 MB (before the certificate's simplicity test moved from strips to a grid). The
/// guided schemes (bi-5 guide: Fourier blocks in a Bloch basis,
/// [`crate::schemes::guided::fourier`]), after it, under a load of about 7: guided-bi5 2.4 s,
/// bi6 2.9 s, bi4-macro 4.2 s, bi3-macro 8.7 s (the slowest: 27 000 ring pieces, whose
/// winding samples dominate), at most 182 MB; so 1000 keeps every accepted case within about
/// 10 s.
pub const MAX_FOURIER_VALENCE: usize = 1000;

/// Largest valence of `analyze` and `charmap` for a local matrix without sectors: the guided
/// schemes' bi-4 and bi-3 guides (`-g4`, `-g3`), whose guide space is a numeric null space
/// over all sectors' coefficients, and whose fit and step matrix are dense over it (no Bloch
/// basis; the bi-5 guide has one, [`crate::schemes::guided::fourier`]). Measured in release on
/// a shared 2-core machine: `-g4` 1.8 s at valence 24 (14 s at 44), `-g3` 2.0 s at 40 (8.2 s
/// at 56, 102 s at 111).
pub const MAX_SECTORLESS_VALENCE: usize = 24;

/// Largest count of vertices or corners of an output (32-bit indices, one bit to spare).
pub const MAX_ELEMENTS: f64 = 2147483648.0;

/// Bytes per sample of a rendered frame (the sample record, the z-buffer and the triangles
/// that cover it), measured: 3.29 GB peak for 8192 x 8192 samples is 49 bytes per sample.
const BYTES_PER_SAMPLE: f64 = 56.0;

/// `levels` refinement steps of `scheme` on `mesh`: the largest level in memory at once (the
/// parent, the child and the step's stencils, and the per-vertex data of both with the
/// buffers of one group of channels) within the budget, the result within the index range.
/// The error says which `--levels` would fit.
pub fn check_levels(scheme: &dyn Scheme, mesh: &PolyMesh, levels: usize) -> Result<()> {
    let start = NetSize::of(mesh);
    let data_bytes = vertex_data_bytes(mesh);
    let sizes = growth::levels(start, levels, |s| scheme.step_size(s));
    let peak_after = |k: usize| -> f64 {
        let mut parent = start;
        let mut peak: f64 = 0.0;
        for s in &sizes[..k] {
            let parent_bytes = NetSize {
                stencil: 0.0,
                ..parent
            }
            .bytes();
            let data = data_bytes * (parent.vertices + s.vertices);
            peak = peak.max(parent_bytes + s.bytes() + data);
            parent = *s;
        }
        peak
    };
    let Some(last) = sizes.last() else {
        return Ok(());
    };
    let b = budget();
    let fits = |k: usize| {
        let s = sizes[k - 1];
        peak_after(k) <= b.bytes && s.vertices < MAX_ELEMENTS && s.corners < MAX_ELEMENTS
    };
    let what = || {
        format!(
            "{levels} refinement step(s) of {} on this net ({} vertices, {} faces) would make \
             about {} vertices and {} faces; that",
            scheme.name(),
            mesh.num_vertices(),
            mesh.num_faces(),
            count(last.vertices),
            count(last.faces)
        )
    };
    if sizes.len() == levels && fits(levels) {
        return Ok(());
    }
    let best = (1..sizes.len().min(levels)).rev().find(|&k| fits(k));
    let lower = match best {
        Some(k) => format!("lower --levels (--levels {k} fits)"),
        None => "even one step does not fit: use a smaller net".to_string(),
    };
    within_indices(what, last.vertices, last.corners, &lower)?;
    within_budget(what, peak_after(sizes.len()), &lower)
}

/// Bytes per vertex of a net's per-vertex data in refinement: the values (8 bytes per
/// channel) and one group of channels in `VertexData::through`'s buffers (`8 x GROUP`); 0
/// without data.
fn vertex_data_bytes(mesh: &PolyMesh) -> f64 {
    let Some(d) = mesh.extras().and_then(|e| e.vertex_data.as_ref()) else {
        return 0.0;
    };
    8.0 * (d.width() + crate::mesh::VertexData::GROUP) as f64
}

/// How many patches a scheme makes, measured on canonical nets: regular patches per corner of
/// the input, ring patches per unit of element size (valence or facet size) and ring, and the
/// bytes of its largest patch.
#[derive(Debug, Clone, Copy)]
struct PatchRate {
    regular_per_corner: f64,
    ring_per_size: f64,
    bytes_per_patch: f64,
}

/// The nets a scheme's rate is measured on, tried in turn until the scheme takes one: an
/// extended c-net of valence 5 (quad schemes), a pentagonal prism (facet schemes), an
/// icosahedron (triangle schemes).
fn probe_nets() -> [PolyMesh; 3] {
    use crate::mesh::nets;
    [
        nets::cnet(5, nets::CnetShape::Convex, 3),
        nets::prism(5),
        nets::icosahedron(),
    ]
}

/// Measures [`PatchRate`] by building one ring without fill on the first probe net the
/// scheme takes; `None` when it takes none (the real build then fails with its own message).
fn patch_rate(spec: &Spec) -> Option<PatchRate> {
    let rules = registry().descriptor(spec.id).patch_rules(spec).ok()??;
    for net in probe_nets() {
        let opts = ComplexOptions {
            rings: 1,
            fill: false,
        };
        let Ok(out) = rules.build(&net, opts, &mut |_| {}) else {
            continue;
        };
        let c = out.complex;
        let mut regular = 0usize;
        let mut ring = 0usize;
        let mut elements = std::collections::HashSet::new();
        for p in &c.provenance {
            match p {
                Provenance::Ring { element, .. } | Provenance::Cap { element, .. } => {
                    ring += 1;
                    elements.insert(*element);
                }
                _ => regular += 1,
            }
        }
        let size: usize = elements
            .iter()
            .map(|e| match *e {
                Element::Vertex(v) if (v as usize) < net.num_vertices() => net.valence(v as usize),
                Element::Face(f) if (f as usize) < net.num_faces() => net.face_size(f as usize),
                // an element of a refined net (schemes that refine before building, e.g. a
                // Doo-Sabin step): every extraordinary element of the probe nets has size 5
                _ => 5,
            })
            .sum();
        let largest = c.patches.iter().map(|p| p.cps.len()).max().unwrap_or(16);
        return Some(PatchRate {
            regular_per_corner: regular as f64 / net.corners().len() as f64,
            ring_per_size: ring as f64 / size.max(1) as f64,
            bytes_per_patch: 24.0 * largest as f64 + 64.0,
        });
    }
    None
}

/// The total size of the elements any scheme may treat as extraordinary: vertices whose
/// valence is not regular (4; 6 in a triangle net) and faces that are not quads (in a net
/// that is not all triangles).
fn element_size(mesh: &PolyMesh) -> f64 {
    let triangles = mesh.is_all_triangles();
    let regular = if triangles { 6 } else { 4 };
    let mut valence = vec![0usize; mesh.num_vertices()];
    for e in mesh.edges() {
        valence[e[0] as usize] += 1;
        valence[e[1] as usize] += 1;
    }
    let mut s: f64 = valence
        .iter()
        .filter(|&&d| d != regular)
        .map(|&d| d as f64)
        .sum();
    if !triangles {
        let st = mesh.face_starts();
        s += (0..mesh.num_faces())
            .map(|f| (st[f + 1] - st[f]) as usize)
            .filter(|&k| k != 4)
            .map(|k| k as f64)
            .sum::<f64>();
    }
    s
}

/// Checks, before it is read, that `eval --at-file`'s points file fits the memory budget: it
/// is read whole, and each of its bytes can become up to 4 more of points (a point of 24 bytes
/// from a line of at least 6, `0:0:0` and its newline).
///
/// # Errors
/// [`Error::TooLarge`] naming the file and its size; the file's own read errors.
pub fn check_points_file(path: &std::path::Path) -> Result<()> {
    let size = std::fs::metadata(path)
        .map_err(|e| crate::io::io_error(path, e))?
        .len() as f64;
    within_budget(
        || {
            format!(
                "the points file {} ({}) is read whole and with its points",
                path.display(),
                human(size)
            )
        },
        5.0 * size,
        "split the points over several runs",
    )
}

/// The patch complex of `mesh` under `spec` with `rings` rings: the ring count within
/// [`MAX_RINGS`], the patches and one refinement step of the net (the adaptive levels refine
/// the neighbourhoods of the elements with the scheme's rules) within the budget.
pub fn check_complex(spec: &Spec, mesh: &PolyMesh, rings: usize, fill: bool) -> Result<()> {
    if rings > MAX_RINGS {
        return Err(Error::InvalidArgument(format!(
            "--rings {rings}: at most {MAX_RINGS} rings per extraordinary element (ring k \
             shrinks like lambda^k, lambda <= 0.75 for every scheme: beyond about 70 rings the \
             patches are smaller than the welding tolerance of double precision and add \
             nothing)"
        )));
    }
    let desc = registry().descriptor(spec.id);
    if let Ok(Some(scheme)) = desc.mesh_rules(spec) {
        let step = scheme.step_size(&NetSize::of(mesh));
        within_budget(
            || {
                format!(
                    "the rings of {} refine the net's elements with its rules; one step on \
                     this net ({} faces, the largest with {} corners) makes {} stencil entries \
                     and",
                    spec.name(),
                    mesh.num_faces(),
                    largest_face(mesh),
                    count(step.stencil)
                )
            },
            step.bytes() + NetSize::of(mesh).bytes(),
            "use a net with smaller faces",
        )?;
    }
    let Some(rate) = patch_rate(spec) else {
        return Ok(());
    };
    let ring_units = (rings as f64 + f64::from(u8::from(fill))) * element_size(mesh);
    let patches =
        rate.regular_per_corner * mesh.corners().len() as f64 + rate.ring_per_size * ring_units;
    // the complex, and about as much again for what is computed from it (adjacency, output)
    let bytes = 2.0 * patches * rate.bytes_per_patch;
    within_budget(
        || {
            format!(
                "the surface of {} with {rings} rings on this net would have about {} patches; it",
                spec.name(),
                count(patches)
            )
        },
        bytes,
        "lower --rings",
    )
}

/// Weights per coefficient a patch table is budgeted for (16 for a regular bi-3 patch, more
/// near extraordinary elements and in caps).
const TABLE_WEIGHTS_PER_ROW: f64 = 32.0;
/// Bytes per weight while a patch table is built: the probes' entries (16) and the table (12).
const TABLE_BYTES_PER_WEIGHT: f64 = 28.0;

/// A patch stencil table of `c` (`subdivide --stencils`) within the budget: its weights, and a
/// probe complex per core beside the complex.
pub fn check_table(c: &PatchComplex) -> Result<()> {
    let coefficients: f64 = c.patches.iter().map(|p| p.cps.len() as f64).sum();
    let weights = coefficients * TABLE_WEIGHTS_PER_ROW;
    let probes = rayon::current_num_threads() as f64 * coefficients * 2.0 * 24.0;
    within_budget(
        || {
            format!(
                "the patch table of {} patches ({} coefficients) would hold about {} weights; it",
                count(c.len() as f64),
                count(coefficients),
                count(weights)
            )
        },
        weights * TABLE_BYTES_PER_WEIGHT + probes,
        "lower --rings or write the table of a smaller net",
    )?;
    if weights >= MAX_ELEMENTS * 2.0 {
        return Err(Error::TooLarge(format!(
            "the patch table would hold about {} weights; its rows index with 32 bits",
            count(weights)
        )));
    }
    Ok(())
}

/// The largest face size of `mesh`.
fn largest_face(mesh: &PolyMesh) -> usize {
    let st = mesh.face_starts();
    (0..mesh.num_faces())
        .map(|f| (st[f + 1] - st[f]) as usize)
        .max()
        .unwrap_or(0)
}

/// Bytes per point of a tessellation written as a mesh: position, normal, domain point and
/// patch (68), the copy handed to the mesh and its vertex half-edge (28), welding slots (16).
const TESS_BYTES_PER_POINT: f64 = 112.0;
/// Bytes per triangle: corners and patch (16), face offsets and corners of the copy (16), the
/// topology of the validated mesh (twins, edges: 28).
const TESS_BYTES_PER_TRIANGLE: f64 = 60.0;

/// A tessellation of `c` with `tess` samples per patch edge within the index range and the
/// budget.
pub fn check_tessellation(c: &PatchComplex, tess: usize) -> Result<()> {
    let n = tess.max(1) as f64;
    let p = c.len() as f64;
    let points = p * (n + 1.0) * (n + 1.0);
    let triangles = p * 2.0 * n * n;
    let what = || {
        format!(
            "a tessellation of {} patches with --tess {tess} ({} points, {} triangles)",
            c.len(),
            count(points),
            count(triangles)
        )
    };
    within_indices(what, points, 3.0 * triangles, "lower --tess")?;
    within_budget(
        what,
        points * TESS_BYTES_PER_POINT + triangles * TESS_BYTES_PER_TRIANGLE,
        "lower --tess, or write the patches themselves (.bv, .igs)",
    )
}

/// The local matrix of `analyze` / `charmap` at valence `n`: its size, measured from the
/// scheme's local rules at small valences (`centre + n x sector` rows), within
/// [`MAX_ANALYSIS_DIMENSION`] and the budget. Schemes whose rules refuse the valence refuse it
/// themselves afterwards.
pub fn check_analysis(spec: &Spec, n: usize, replicated_centre: bool) -> Result<()> {
    let Ok(rules) = crate::analysis::report::local_rules(spec) else {
        return Ok(());
    };
    if (3..=8).contains(&n) {
        return Ok(());
    }
    let Some(lm) = [5, 6, 7, 3, 8].iter().find_map(|&k| rules.matrix(k).ok()) else {
        return Ok(());
    };
    // A matrix without sectors (a numeric basis of the guided schemes' bi-4 and bi-3 guide
    // spaces) grows all the same: its rows per valence are measured between two valences, and
    // its valence is bounded by MAX_SECTORLESS_VALENCE.
    if lm.sector == 0 && n > MAX_SECTORLESS_VALENCE {
        return Err(Error::TooLarge(format!(
            "valence {n}: the local matrix of {} is built on a numeric basis of its space over \
             all sectors (a dense null space whose cost grows with the cube of the valence): \
             take a valence of at most {MAX_SECTORLESS_VALENCE}",
            spec.name()
        )));
    }
    let (lm_centre, lm_sector) = match lm.sector {
        0 => match rules.matrix(lm.n + 2) {
            Ok(m2) => {
                let per = m2.centre.saturating_sub(lm.centre) / 2;
                (lm.centre.saturating_sub(per * lm.n), per)
            }
            Err(_) => (lm.centre, 0),
        },
        _ => (lm.centre, lm.sector),
    };
    let centre = if replicated_centre {
        lm_centre * n
    } else {
        lm_centre
    };
    let dim = centre + n.saturating_mul(lm_sector);
    if dim > MAX_ANALYSIS_DIMENSION {
        if let Ok(Some(sparse)) = rules.sparse(lm.n) {
            return check_blocks(spec, n, &sparse);
        }
        // Blocks of the scheme's own (not of the replicated-centre form, which stays dense).
        if rules.own_blocks(n) && !replicated_centre {
            return check_fourier(spec, n, (lm.centre, lm.sector), lm.sector as f64);
        }
        let max_n = (MAX_ANALYSIS_DIMENSION.saturating_sub(lm_centre)) / lm_sector.max(1);
        return Err(Error::TooLarge(format!(
            "valence {n}: the local matrix of {} would have {dim} rows ({} centre + {n} x {} \
             points); fairsub decomposes dense local matrices of at most \
             {MAX_ANALYSIS_DIMENSION} rows (the cost grows with the cube of the size; the bound \
             keeps every scheme within seconds; {} has no block-circulant form): take a \
             valence of at most {max_n}",
            spec.name(),
            centre,
            lm_sector,
            spec.name()
        )));
    }
    // the matrix, its eigen-decomposition (complex Schur form and vectors) and the Fourier
    // blocks: about 8 dense copies
    let d = dim as f64;
    within_budget(
        || format!("the local matrix at valence {n} ({dim} x {dim})"),
        8.0 * 8.0 * d * d,
        "take a smaller valence",
    )
}

/// The Fourier-block analysis at valence `n` ([`crate::schemes::circulant`]), from the scheme's
/// sparse rows at a small valence (`small`): within [`MAX_FOURIER_VALENCE`] and the budget.
/// Memory: the sparse rows (a row that reads every sector at the small valence, like
/// Doo-Sabin's, is counted as reading every point at `n`), the `n` blocks of
/// `(centre + sector)^2` complex entries with their eigen-decompositions, and a few vectors
/// on the local net.
fn check_blocks(
    spec: &Spec,
    n: usize,
    small: &crate::schemes::circulant::SparseLocal,
) -> Result<()> {
    let widest = small.rows.iter().map(Vec::len).max().unwrap_or(0) as f64;
    let rows = small.centre as f64 + n as f64 * small.sector as f64;
    let per_row = if widest >= small.n as f64 {
        rows
    } else {
        widest
    };
    check_fourier(spec, n, (small.centre, small.sector), per_row)
}

/// The Fourier-block analysis at valence `n` of a matrix with `centre + n sector` rows of
/// `per_row` entries (held sparse, or as the scheme's own blocks): within
/// [`MAX_FOURIER_VALENCE`] and the budget.
fn check_fourier(
    spec: &Spec,
    n: usize,
    (centre, sector): (usize, usize),
    per_row: f64,
) -> Result<()> {
    if n > MAX_FOURIER_VALENCE {
        return Err(Error::TooLarge(format!(
            "valence {n}: {} is analysed by the Fourier blocks of its local matrix above \
             {MAX_ANALYSIS_DIMENSION} rows, for valences up to {MAX_FOURIER_VALENCE} (the \
             characteristic map's certificate and the spectrum's grouping grow faster than \
             linearly beyond): take a valence of at most {MAX_FOURIER_VALENCE}",
            spec.name()
        )));
    }
    let k = (centre + sector) as f64;
    let nf = n as f64;
    let rows = centre as f64 + nf * sector as f64;
    let bytes = 2.0 * 16.0 * rows * per_row.max(1.0) + 8.0 * 16.0 * nf * k * k + 64.0 * rows * 8.0;
    within_budget(
        || format!("the Fourier blocks at valence {n} ({n} blocks of {k} rows)"),
        bytes,
        "take a smaller valence",
    )
}

/// A picture of `cells` cells of `width x height` pixels with `aa x aa` samples each.
pub fn check_render(width: usize, height: usize, aa: usize, cells: usize) -> Result<()> {
    let samples = width as f64 * height as f64 * (aa * aa) as f64 * cells.max(1) as f64;
    within_budget(
        || {
            format!(
                "{} cell(s) of {width}x{height} pixels with {aa}x{aa} samples each ({} samples)",
                cells.max(1),
                count(samples)
            )
        },
        samples * BYTES_PER_SAMPLE,
        "lower --size or --aa",
    )
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::budget::GIB;
    use super::*;

    #[crate::unit::test]
    fn sizes_parse_in_binary_units() {
        assert_eq!(parse_memory("4G").unwrap(), 4 << 30);
        assert_eq!(parse_memory("512m").unwrap(), 512 << 20);
        assert_eq!(parse_memory("2.5GiB").unwrap(), 5 << 29);
        assert_eq!(parse_memory("1000").unwrap(), 1000);
        assert_eq!(parse_memory("3kb").unwrap(), 3072);
        for bad in ["", "G", "-1G", "4X", "nan", "1e30T"] {
            assert!(parse_memory(bad).is_err(), "{bad}");
        }
    }

    #[crate::unit::test]
    fn sizes_print_readably() {
        assert_eq!(human(512.0), "512 bytes");
        assert_eq!(human(3.0 * GIB + 0.2 * GIB), "3.2 GiB");
    }

    #[crate::unit::test]
    fn the_default_budget_is_half_a_known_limit() {
        let b = default_budget();
        assert!(b.bytes > 0.0 && b.bytes.is_finite(), "{b:?}");
        assert!(b.source.starts_with("half of"), "{b:?}");
    }

    #[crate::unit::test]
    fn a_budget_set_on_one_thread_is_used_there_only() {
        with_budget(Some(1 << 20), || {
            assert_eq!(budget().bytes, 1048576.0);
            assert_eq!(budget().source, "set by --max-memory");
        });
        assert!(budget().source.starts_with("half of"));
    }
}
