//! The non-box part of `fairsub subdivide`: the FCV options, reading nets with their FCVs, and
//! writing refined nets with FCVs and limit meshes with normals. Kept apart from the generic
//! command so that the non-box schemes' extra data stay out of the other schemes' paths.

use crate::error::{Error, Result};
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
pub fn load_net(spec: &Spec, arg: &str, o: &FcvArgs) -> Result<PolyMesh> {
    // FCV options for other schemes were refused when the options were resolved.
    if !crate::schemes::registry()
        .descriptor(spec.id)
        .params()
        .contains(&ParamKind::Fcv)
    {
        return Ok(super::super::load_net(arg)?.mesh);
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
        None if o.fcv_scale.is_some() || o.fcv_file.is_some() => {
            Ok(fcv::choose_fcv_net(&mesh, scale, o.fcv_file.as_deref())?.to_layout_mesh())
        }
        None => Ok(mesh),
    }
}

/// Refines `mesh` `levels` times under a non-box scheme and writes the net: OBJ gets the
/// FCVs as the last `v` lines (`nonbox`); with `limit`, `nonbox` writes the limit mesh (the
/// refined quads split into four triangles around their FCVs, every point at its limit; OBJ
/// with the exact limit normals as `vn` lines) and `nonbox-4dir` its refined triangle mesh at
/// the limit positions. Prints how the input was read.
pub fn write_net(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    limit: bool,
    fmt: OutputFormat,
    output: &Path,
) -> Result<()> {
    for n in scheme.input_notes(mesh) {
        eprintln!("note: {n}");
    }
    let obj = matches!(fmt, OutputFormat::Mesh(MeshFormat::Obj));
    let limit_mesh = if limit {
        scheme.limit_mesh_with_normals(mesh, levels)
    } else {
        None
    };
    let quad_net = scheme.fcv_layout() == FcvLayout::Quads;
    let refined = if let Some(r) = limit_mesh {
        let (m, normals) = r?;
        if obj {
            fcv::write_limit_obj(output, &m, &normals)?;
        } else {
            write_plain(&m, fmt, output)?;
        }
        m
    } else {
        let m = super::refine_with(scheme, mesh, levels, limit)?;
        match FcvNet::from_layout_mesh(&m) {
            Some(net) if quad_net && !limit && obj => fcv::write_fcv_obj(output, &net)?,
            _ => write_plain(&m, fmt, output)?,
        }
        m
    };
    eprintln!(
        "wrote {} vertices, {} faces ({} x {}{}) to {}",
        refined.num_vertices(),
        refined.num_faces(),
        levels,
        scheme.name(),
        if limit { ", limit" } else { "" },
        output.display()
    );
    Ok(())
}

fn write_plain(m: &PolyMesh, fmt: OutputFormat, output: &Path) -> Result<()> {
    match fmt {
        OutputFormat::Mesh(mf) => crate::io::write_mesh(output, m, mf),
        OutputFormat::Bv => crate::io::write_bv_mesh(output, m),
        OutputFormat::Iges => Err(Error::InvalidArgument(
            "IGES holds patches: use --rings K instead of --levels".into(),
        )),
    }
}
