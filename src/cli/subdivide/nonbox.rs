//! The non-box part of `fairsub subdivide`: the FCV options, reading nets with their FCVs, and
//! writing refined nets with FCVs and limit meshes with normals. Kept apart from the generic
//! command so that the non-box schemes' extra data stay out of the other schemes' paths.

use super::Computed;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::io::{MeshFormat, OutputFormat, fcv};
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::ParamKind;
use crate::schemes::nonbox::FcvNet;
use crate::schemes::{FcvLayout, Scheme, Spec};
use std::path::{Path, PathBuf};

/// Face-control-vertex options of `fairsub subdivide` (non-box schemes only).
#[derive(Debug, Clone, clap::Args)]
pub struct FcvArgs {
    /// Non-box schemes: the FCVs are S times the face barycentres, scaled about the origin (the
    /// paper's Fig. 10 takes 0.5, 1, 1.5 on a cube). Default 1; ignored when an OBJ net lists
    /// its FCVs.
    #[arg(long, value_name = "S")]
    pub fcv_scale: Option<f64>,
    /// Non-box schemes: an FCV side file, one `x y z` line (or `*` for the default) per face in
    /// face order; replaces the FCVs of the net.
    #[arg(long, value_name = "FILE")]
    pub fcv_file: Option<PathBuf>,
}

/// Loads the net `arg` for `scheme`. For the non-box schemes an OBJ file keeps the FCVs it
/// lists (the layout of `crate::io::fcv`) and `--fcv-file` / `--fcv-scale` set
/// them otherwise; the result is then a layout mesh (else the plain mesh, whose FCVs are its
/// barycentres). Other schemes get the plain net, and an error if FCV options were given.
///
/// With `given`, that mesh stands for the net `arg` names (no file is read): its FCVs are its
/// face barycentres scaled by `--fcv-scale`, or the `--fcv-file`'s.
pub fn load_net(spec: &Spec, arg: &str, o: &FcvArgs, given: Option<PolyMesh>) -> Result<PolyMesh> {
    // FCV options for other schemes were refused when the options were resolved.
    if !crate::schemes::registry()
        .descriptor(spec.id)
        .params()
        .contains(&ParamKind::Fcv)
    {
        return match given {
            Some(m) => Ok(m),
            None => Ok(super::super::load_net(arg)?.mesh),
        };
    }
    if let Some(mesh) = given {
        return choose(mesh, o, arg);
    }
    let path = Path::new(arg);
    let is_obj = !arg.starts_with("gallery:")
        && path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    let (mesh, fcvs) = if is_obj {
        let (mesh, fcvs, warnings) = fcv::read_obj_fcvs(path)?;
        for w in warnings {
            eprintln!("warning: {arg}: {w}");
        }
        (mesh, fcvs)
    } else {
        (super::super::load_net(arg)?.mesh, None)
    };
    let scale = o.fcv_scale.unwrap_or(1.0);
    match fcvs {
        Some(fcvs) => {
            let net = FcvNet::new(mesh, fcvs)?;
            if o.fcv_scale.is_some() && o.fcv_file.is_none() {
                eprintln!("note: --fcv-scale is ignored: {arg} lists its own FCVs");
            }
            let net = match &o.fcv_file {
                Some(file) => fcv::load_fcv_file(net.mesh, file, scale)?,
                None => net,
            };
            Ok(net.to_layout_mesh())
        }
        None => choose(mesh, o, arg),
    }
}

/// The net of a mesh without listed FCVs: FCVs from `--fcv-scale` / `--fcv-file` when given
/// (a layout mesh), else the plain mesh (its FCVs are its barycentres).
fn choose(mesh: PolyMesh, o: &FcvArgs, arg: &str) -> Result<PolyMesh> {
    if o.fcv_scale.is_some() || o.fcv_file.is_some() {
        if let Some(d) = mesh.extras().and_then(|e| e.vertex_data.as_ref()) {
            // Given FCVs are not affine in the net's points: the data has no value there.
            eprintln!(
                "warning: {arg}: the per-vertex properties ({}) are not carried into a net with \
                 given FCVs (--fcv-scale, --fcv-file); the output has positions only",
                d.names.join(", ")
            );
        }
        let scale = o.fcv_scale.unwrap_or(1.0);
        Ok(fcv::choose_fcv_net(&mesh, scale, o.fcv_file.as_deref())?.to_layout_mesh())
    } else {
        Ok(mesh)
    }
}

/// Refines `mesh` `levels` times under a non-box scheme: with `limit`, `nonbox`'s limit mesh
/// (the refined quads split into four triangles around their FCVs, every point at its limit,
/// with the exact limit normals) and `nonbox-4dir`'s refined triangle mesh at the limit
/// positions; without, the refined net in its FCV layout. Prints how the input was read.
pub fn compute_net(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    limit: bool,
) -> Result<Computed> {
    for n in scheme.input_notes(mesh) {
        eprintln!("note: {n}");
    }
    if limit && let Some(r) = scheme.limit_mesh_with_normals(mesh, levels) {
        let (m, normals) = r?;
        return Ok(Computed::LimitMesh(m, normals));
    }
    // hole faces are refined for support and not written
    let m = crate::schemes::nonbox::holes::without_hole_faces(super::refine_with(
        scheme, mesh, levels, limit,
    )?);
    Ok(if scheme.fcv_layout() == FcvLayout::Quads && !limit {
        Computed::FcvNet(m)
    } else {
        Computed::Net(m)
    })
}

/// Writes a non-box limit mesh: OBJ with the exact limit normals as `vn` lines, other formats
/// the plain mesh.
pub fn write_limit(
    m: &PolyMesh,
    normals: &[Point],
    fmt: OutputFormat,
    output: &Path,
) -> Result<()> {
    if matches!(fmt, OutputFormat::Mesh(MeshFormat::Obj)) {
        fcv::write_limit_obj(output, m, normals)
    } else {
        write_plain(m, fmt, output)
    }
}

/// Writes a refined non-box net in its FCV layout: OBJ lists the FCVs as the last `v` lines
/// (`nonbox`), other formats get the plain mesh.
pub fn write_refined(m: &PolyMesh, fmt: OutputFormat, output: &Path) -> Result<()> {
    match FcvNet::from_layout_mesh(m) {
        Some(net) if matches!(fmt, OutputFormat::Mesh(MeshFormat::Obj)) => {
            fcv::write_fcv_obj(output, &net)
        }
        _ => write_plain(m, fmt, output),
    }
}

fn write_plain(m: &PolyMesh, fmt: OutputFormat, output: &Path) -> Result<()> {
    match fmt {
        OutputFormat::Mesh(mf) => crate::io::write_mesh(output, m, mf),
        OutputFormat::Bv => crate::io::write_bv_mesh(output, m),
        OutputFormat::Scene(sf) => super::scene::write_net(output, m, None, sf),
        OutputFormat::Iges | OutputFormat::Step => Err(Error::InvalidArgument(
            "IGES and STEP hold surfaces: use --rings K instead of --levels".into(),
        )),
    }
}
