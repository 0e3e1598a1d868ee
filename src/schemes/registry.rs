//! The one table of schemes: every scheme fairsub knows, in catalogue order, as the rows its
//! family writes (`FAMILY/entry.rs`: canonical name, aliases, the name suffixes that set typed
//! parameters, catalogue text, [`Descriptor`]).
//!
//! The registry sits at the top of `schemes/`: it imports the families, and no family imports
//! it. Everything else refers to a scheme by a [`SchemeId`] constant of [`ids`] or looks a name
//! up here ([`Registry::lookup`]); the catalogue (`fairsub schemes`) lists the rows in order.
//!
//! Adding a scheme: one folder under `src/schemes/` with a [`Descriptor`] and an `entry.rs`,
//! its id in [`ids`], and one line in [`Registry::builtin`] (or, outside the crate,
//! [`register`]).

use super::Scheme;
use super::descriptor::{Capabilities, Descriptor, ParamKind, Params, SchemeId, Spec};
use super::{
    bi2, butterfly, catmull_clark, doo_sabin, eg, guided, loop_subdivision, nonbox, qas, sqrt3,
};
use crate::error::{Error, Result};
use std::sync::{LazyLock, RwLock};

pub use super::entry::{Entry, Suffix};

/// The ids of the built-in schemes (defined at the bottom of `schemes/`, in [`super::options`]).
pub use super::options::ids;

/// The schemes, in catalogue order.
#[derive(Debug, Clone)]
pub struct Registry {
    entries: Vec<Entry>,
}

/// The registry in use: the built-in schemes and those added by [`register`]. Each version is
/// leaked, so a caller may keep the `&'static` it got while a scheme is added.
static CURRENT: LazyLock<RwLock<&'static Registry>> =
    LazyLock::new(|| RwLock::new(Box::leak(Box::new(Registry::builtin()))));

/// The registry: the built-in schemes and those added with [`register`]. Every front end
/// (command line, demo, surface builder, analysis) looks schemes up here.
pub fn registry() -> &'static Registry {
    *CURRENT.read().unwrap_or_else(|e| e.into_inner())
}

/// Adds a scheme defined outside the crate (its [`Descriptor`] and catalogue row) to the
/// registry, so that every front end offers it. Errors when its name or an alias is taken.
pub fn register(entry: Entry) -> Result<()> {
    let mut current = CURRENT.write().unwrap_or_else(|e| e.into_inner());
    let taken = current.entries.iter().any(|e| {
        let names = || std::iter::once(e.name).chain(e.aliases.iter().copied());
        std::iter::once(entry.name)
            .chain(entry.aliases.iter().copied())
            .any(|n| names().any(|m| m == n))
    });
    if taken {
        return Err(Error::InvalidArgument(format!(
            "a scheme named '{}' (or one of its aliases) is already registered",
            entry.name
        )));
    }
    *current = Box::leak(Box::new((*current).clone().with(entry)));
    Ok(())
}

impl Registry {
    /// Every built-in scheme, in catalogue order: the families' rows.
    pub fn builtin() -> Registry {
        let families: [&[Entry]; 10] = [
            catmull_clark::entry::ENTRIES,
            doo_sabin::entry::ENTRIES,
            loop_subdivision::entry::ENTRIES,
            nonbox::entry::ENTRIES,
            eg::entry::ENTRIES,
            qas::entry::ENTRIES,
            bi2::entry::ENTRIES,
            guided::entry::ENTRIES,
            sqrt3::entry::ENTRIES,
            butterfly::entry::ENTRIES,
        ];
        Registry {
            entries: families.concat(),
        }
    }

    /// This registry with one more row (a scheme defined outside the crate).
    pub fn with(mut self, entry: Entry) -> Registry {
        self.entries.push(entry);
        self
    }

    /// The rows, in catalogue order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The row of a scheme.
    ///
    /// # Panics
    /// If the id has no row (ids come from this registry).
    pub fn entry(&self, id: SchemeId) -> &Entry {
        self.entries
            .iter()
            .find(|e| e.id == id)
            .unwrap_or_else(|| panic!("scheme {id} is not in the registry"))
    }

    /// The descriptor of a scheme.
    pub fn descriptor(&self, id: SchemeId) -> &'static dyn Descriptor {
        self.entry(id).descriptor
    }

    /// The scheme a command-line name means, with the parameters its suffixes set: the
    /// canonical name, an alias, or a name followed by suffixes of its row. Unknown names get
    /// [`Error::UnknownScheme`] listing the names.
    pub fn lookup(&self, name: &str) -> Result<Spec> {
        for e in &self.entries {
            for base in std::iter::once(e.name).chain(e.aliases.iter().copied()) {
                let Some(mut rest) = name.strip_prefix(base) else {
                    continue;
                };
                let mut params = Params::default();
                for s in e.suffixes {
                    if let Some(r) = rest.strip_prefix(s.text) {
                        (s.set)(&mut params);
                        rest = r;
                    }
                }
                if rest.is_empty() {
                    return Ok(Spec { id: e.id, params });
                }
            }
        }
        Err(Error::UnknownScheme {
            name: name.to_string(),
            purpose: "",
            available: self.entries.iter().map(|e| e.name).collect(),
        })
    }

    /// [`Registry::lookup`] for a purpose: a name that is unknown, or whose scheme lacks the
    /// capability `pick`, gets [`Error::UnknownScheme`] listing the names that have it
    /// (`purpose` as `" for refinement"`).
    pub fn lookup_for(
        &self,
        name: &str,
        purpose: &'static str,
        pick: impl Fn(Capabilities) -> bool,
    ) -> Result<Spec> {
        match self.lookup(name) {
            Ok(s) if pick(self.entry(s.id).capabilities()) => Ok(s),
            _ => Err(Error::UnknownScheme {
                name: name.to_string(),
                purpose,
                available: self.names_with(pick),
            }),
        }
    }

    /// The catalogue: one row per scheme, in order.
    pub fn catalog(&self) -> Vec<SchemeInfo> {
        self.entries
            .iter()
            .map(|e| {
                let c = e.capabilities();
                SchemeInfo {
                    name: e.name,
                    family: e.about.family,
                    input: e.about.input,
                    patches: e.about.patches,
                    smoothness: e.about.smoothness,
                    valences: e.about.valences,
                    refine: c.refine,
                    rings: c.patches,
                    status: e.about.status,
                }
            })
            .collect()
    }

    /// The names of the schemes with the given capability, in catalogue order.
    pub fn names_with(&self, pick: impl Fn(Capabilities) -> bool) -> Vec<&'static str> {
        self.entries
            .iter()
            .filter(|e| pick(e.capabilities()))
            .map(|e| e.name)
            .collect()
    }

    /// The names of the schemes whose options include `kind`, in catalogue order.
    pub fn names_taking(&self, kind: ParamKind) -> Vec<&'static str> {
        self.entries
            .iter()
            .filter(|e| e.descriptor.params().contains(&kind))
            .map(|e| e.name)
            .collect()
    }
}

/// What `fairsub schemes` tells about a scheme.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SchemeInfo {
    /// Command-line name.
    pub name: &'static str,
    /// Family and paper.
    pub family: &'static str,
    /// Input nets it accepts.
    pub input: &'static str,
    /// Patches it outputs (degree and layout), if it has exact patch output.
    pub patches: &'static str,
    /// Smoothness claimed by its paper (or the classical result).
    pub smoothness: &'static str,
    /// Valences / element sizes with rules.
    pub valences: &'static str,
    /// Whether refinement (`--levels`) is available.
    pub refine: bool,
    /// Whether exact patch output (`--rings`) is available.
    pub rings: bool,
    /// Implementation status.
    pub status: &'static str,
}

/// Every scheme fairsub knows, with its properties (the registry's catalogue).
pub fn catalog() -> Vec<SchemeInfo> {
    registry().catalog()
}

/// The refinement scheme of a command-line name (default parameters); the error lists the
/// names available for refinement.
pub fn by_name(name: &str) -> Result<Box<dyn Scheme>> {
    let r = registry();
    let spec = r.lookup_for(name, " for refinement", |c| c.refine)?;
    r.descriptor(spec.id)
        .mesh_rules(&spec)?
        .ok_or_else(|| unreachable_rules(&spec))
}

/// The error of a descriptor that claims a capability it does not deliver.
fn unreachable_rules(spec: &Spec) -> crate::error::Error {
    crate::error::Error::InvalidArgument(format!(
        "scheme '{}' has no rules for this operation",
        spec.name()
    ))
}
