//! The output formats and how they are chosen: by a `--format` name or by the file extension.

use crate::error::{Error, Result};
use std::path::Path;

/// The mesh file formats fairsub writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`v` and `f` lines, 1-based indices).
    Obj,
    /// Geomview OFF (ascii).
    Off,
    /// PLY, ascii encoding.
    PlyAscii,
    /// PLY, binary little endian (double coordinates, `list uchar int` faces).
    PlyBinary,
}

impl MeshFormat {
    /// The usual file extension (without the dot).
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Obj => "obj",
            MeshFormat::Off => "off",
            MeshFormat::PlyAscii | MeshFormat::PlyBinary => "ply",
        }
    }
}

/// What an output file holds: a mesh (tessellation, refined net) or exact patches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// A polygon mesh in one of the [`MeshFormat`]s.
    Mesh(MeshFormat),
    /// BezierView `.bv` patches.
    Bv,
    /// IGES 5.3, one entity 128 per face.
    Iges,
    /// A scene format (USD, glTF): a mesh with normals, texture coordinates, curvature.
    Scene(SceneFormat),
    /// STEP (ISO 10303-21, AP214): B-spline faces with B-rep topology.
    Step,
}

/// The scene formats fairsub writes ([`crate::io::usd`], [`crate::io::gltf`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneFormat {
    /// USD in one of its encodings.
    Usd(crate::io::usd::UsdFlavor),
    /// glTF 2.0 in one of its containers.
    Gltf(crate::io::gltf::GltfFlavor),
}

/// The `--format` names [`OutputFormat::choose`] accepts, for help texts and errors.
pub const FORMAT_NAMES: &str = "obj, off, ply (binary), ply-ascii, ply-binary, bv, igs / iges, step / stp, usda / usd, usdz, glb, gltf";

/// The scene format of a `--format` name or extension (`usd` is the crate encoding).
fn scene_format(name: &str) -> Option<OutputFormat> {
    use crate::io::gltf::GltfFlavor;
    use crate::io::usd::UsdFlavor;
    let f = match name {
        "usda" | "usd" => SceneFormat::Usd(UsdFlavor::Usda),
        "usdz" => SceneFormat::Usd(UsdFlavor::Usdz),
        "glb" => SceneFormat::Gltf(GltfFlavor::Glb),
        "gltf" => SceneFormat::Gltf(GltfFlavor::Gltf),
        _ => return None,
    };
    Some(OutputFormat::Scene(f))
}

impl OutputFormat {
    /// Chooses the output format: by `format` (a `--format` name, case-insensitive) when given,
    /// else by the extension of `path` (`.obj .off .ply .bv .igs .iges`). PLY is binary unless
    /// `ply-ascii` is asked for. Unknown names or extensions give an error listing the choices.
    pub fn choose(path: &Path, format: Option<&str>) -> Result<OutputFormat> {
        let name = format.map(|f| f.trim().to_ascii_lowercase());
        if name.as_deref().or(extension_lowercase(path).as_deref()) == Some("usdc") {
            return Err(Error::Unsupported(crate::io::usd::NO_USDC.to_string()));
        }
        if let Some(name) = format {
            return match name.trim().to_ascii_lowercase().as_str() {
                "obj" => Ok(OutputFormat::Mesh(MeshFormat::Obj)),
                "off" => Ok(OutputFormat::Mesh(MeshFormat::Off)),
                "ply" | "ply-binary" | "ply_binary" => {
                    Ok(OutputFormat::Mesh(MeshFormat::PlyBinary))
                }
                "ply-ascii" | "ply_ascii" => Ok(OutputFormat::Mesh(MeshFormat::PlyAscii)),
                "bv" => Ok(OutputFormat::Bv),
                "igs" | "iges" => Ok(OutputFormat::Iges),
                "step" | "stp" => Ok(OutputFormat::Step),
                n if scene_format(n).is_some() => Ok(scene_format(n).expect("checked")),
                _ => Err(Error::InvalidArgument(format!(
                    "unknown output format '{name}' (choose one of: {FORMAT_NAMES})"
                ))),
            };
        }
        match extension_lowercase(path).as_deref() {
            Some("obj") => Ok(OutputFormat::Mesh(MeshFormat::Obj)),
            Some("off") => Ok(OutputFormat::Mesh(MeshFormat::Off)),
            Some("ply") => Ok(OutputFormat::Mesh(MeshFormat::PlyBinary)),
            Some("bv") => Ok(OutputFormat::Bv),
            Some("igs") | Some("iges") => Ok(OutputFormat::Iges),
            Some("step") | Some("stp") => Ok(OutputFormat::Step),
            Some(ext) if scene_format(ext).is_some() => Ok(scene_format(ext).expect("checked")),
            Some(ext) => Err(Error::InvalidArgument(format!(
                "cannot tell the output format of '{}' from its extension '.{ext}': use .obj, .off, \
                 .ply, .bv, .igs, .iges, .step, .stp, .usda, .usd, .usdz, .glb or .gltf, or give \
                 --format ({FORMAT_NAMES})",
                path.display()
            ))),
            None => Err(Error::InvalidArgument(format!(
                "'{}' has no extension to tell the output format: use .obj, .off, .ply, .bv, .igs, \
                 .iges, .step, .stp, .usda, .usd, .usdz, .glb or .gltf, or give --format \
                 ({FORMAT_NAMES})",
                path.display()
            ))),
        }
    }
}

/// The extension of `path`, lower-cased, when it has one that is valid UTF-8.
pub(crate) fn extension_lowercase(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn output_format_by_name_and_extension() {
        use MeshFormat::*;
        let p = Path::new("out.PLY");
        assert_eq!(
            OutputFormat::choose(p, None).unwrap(),
            OutputFormat::Mesh(PlyBinary)
        );
        assert_eq!(
            OutputFormat::choose(p, Some("ply-ascii")).unwrap(),
            OutputFormat::Mesh(PlyAscii)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.obj"), None).unwrap(),
            OutputFormat::Mesh(Obj)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.Off"), None).unwrap(),
            OutputFormat::Mesh(Off)
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.bv"), None).unwrap(),
            OutputFormat::Bv
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.igs"), None).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.IGES"), None).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x.txt"), Some("IGES")).unwrap(),
            OutputFormat::Iges
        );
        assert_eq!(
            OutputFormat::choose(Path::new("x"), Some("bv")).unwrap(),
            OutputFormat::Bv
        );
        let e = OutputFormat::choose(Path::new("x.stl"), None).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains(".stl") && m.contains(".iges") && m.contains("ply-ascii"),
            "{m}"
        );
        let e = OutputFormat::choose(Path::new("x.obj"), Some("stl")).unwrap_err();
        assert!(e.to_string().contains("'stl'"), "{e}");
        assert!(OutputFormat::choose(Path::new("noext"), None).is_err());
    }
}
