//! Pictures (`fairsub render`): a surface or a net drawn with typed [`RenderOptions`], by the
//! renderer the command uses, so the same options give the same bytes as the command's PNG.

use super::Surface;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::render::{Image, RenderOptions, Scene};
use crate::surface::PatchComplex;

/// What [`render`] draws: an exact surface (with its net for the `net` overlay), a patch
/// complex (with an optional net), or a plain net (interpolated normals: no curvature or
/// provenance modes).
#[derive(Debug, Clone, Copy)]
pub enum Drawn<'a> {
    /// A [`Surface`] and the net it was built on.
    Surface(&'a Surface),
    /// A patch complex, and the net its `net` overlay draws.
    Complex(&'a PatchComplex, Option<&'a PolyMesh>),
    /// A polygon net, flat-faced.
    Net(&'a PolyMesh),
}

impl<'a> From<&'a Surface> for Drawn<'a> {
    fn from(s: &'a Surface) -> Self {
        Drawn::Surface(s)
    }
}

impl<'a> From<&'a PatchComplex> for Drawn<'a> {
    fn from(c: &'a PatchComplex) -> Self {
        Drawn::Complex(c, None)
    }
}

impl<'a> From<&'a PolyMesh> for Drawn<'a> {
    fn from(m: &'a PolyMesh) -> Self {
        Drawn::Net(m)
    }
}

/// A picture as `fairsub render` draws it (`fairsub render NET [--scheme S --rings K] --mode
/// M ...` without the PNG file): the same scene, camera, lights, range and legend.
///
/// # Errors
/// A bad option (the message names the command-line option: see
/// [`RenderOptions::check`] for the option itself), a mode the drawing cannot show
/// (curvature or provenance of a plain net), an empty complex, or a focus element or ring
/// range the surface does not have.
///
/// ```
/// use fairsub::{Mode, Options, RenderOptions, render, surface};
/// let s = surface("gallery:cnet-5-saddle", "catmull-clark", 3, true, &Options::default())?;
/// let o = RenderOptions { width: 64, height: 48, mode: Mode::Mean, legend: false, ..RenderOptions::default() };
/// let img = render(&s, &o)?;
/// assert_eq!((img.width, img.height, img.data.len()), (64, 48, 64 * 48 * 3));
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn render<'a>(what: impl Into<Drawn<'a>>, options: &RenderOptions) -> Result<Image> {
    let scene = match what.into() {
        Drawn::Surface(s) => Scene::patches(s.complex().clone(), Some(s.net().clone())),
        Drawn::Complex(c, net) => {
            if c.is_empty() {
                return Err(Error::InvalidArgument(
                    "nothing to render: the complex has no patches".into(),
                ));
            }
            Scene::patches(c.clone(), net.cloned())
        }
        Drawn::Net(m) => Scene::mesh(m),
    };
    Ok(crate::render::render(&scene, options)?.image)
}
