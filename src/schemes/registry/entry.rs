//! A registry row ([`Entry`]) and the name suffixes that set typed parameters ([`Suffix`]):
//! the types of the table in [`super`], which alone spells the names.

use crate::schemes::descriptor::{About, Capabilities, Descriptor, Params, SchemeId};

/// A name suffix that sets a typed parameter (`guided-bi6-g4-half`); suffixes are read in the
/// order of the row's list.
#[derive(Clone, Copy)]
pub struct Suffix {
    /// The suffix, with its leading dash.
    pub text: &'static str,
    /// What it sets.
    pub set: fn(&mut Params),
}

impl std::fmt::Debug for Suffix {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.text)
    }
}

/// One row of the registry.
#[derive(Clone, Copy)]
pub struct Entry {
    /// The scheme (its canonical name).
    pub id: SchemeId,
    /// The canonical name (= `id.name()`).
    pub name: &'static str,
    /// Other names the command line accepts.
    pub aliases: &'static [&'static str],
    /// Name suffixes that set parameters.
    pub suffixes: &'static [Suffix],
    /// The catalogue text.
    pub about: About,
    /// What the scheme is and does.
    pub descriptor: &'static dyn Descriptor,
}

impl std::fmt::Debug for Entry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Entry")
            .field("name", &self.name)
            .field("aliases", &self.aliases)
            .finish()
    }
}

impl Entry {
    /// A row without suffixes.
    pub const fn new(
        id: SchemeId,
        aliases: &'static [&'static str],
        about: About,
        descriptor: &'static dyn Descriptor,
    ) -> Entry {
        Entry {
            id,
            name: id.name(),
            aliases,
            suffixes: &[],
            about,
            descriptor,
        }
    }

    /// The row with name suffixes.
    pub const fn with_suffixes(mut self, suffixes: &'static [Suffix]) -> Entry {
        self.suffixes = suffixes;
        self
    }

    /// What the scheme offers.
    pub fn capabilities(&self) -> Capabilities {
        self.descriptor.capabilities()
    }
}
