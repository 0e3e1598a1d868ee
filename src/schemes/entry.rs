//! A registry row ([`Entry`]): a scheme's id, aliases, the name suffixes that set typed
//! parameters ([`Suffix`]), its catalogue text ([`About`]) and its descriptor.
//!
//! Each family writes its own rows in its `entry.rs` (the only files that spell scheme names),
//! beside its rules; the registry (`super::registry`) lists the families' rows in catalogue
//! order.

use crate::schemes::descriptor::{Capabilities, Descriptor};
use crate::schemes::options::{Params, RulesChoice, SchemeId};

/// The catalogue row of a scheme (`fairsub schemes`): what it takes, what it gives, what its
/// paper proves, where it applies, and how complete fairsub's implementation is.
#[derive(Debug, Clone, Copy)]
pub struct About {
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
    /// Implementation status.
    pub status: &'static str,
}

/// The `-derived` suffix of the schemes with printed and derived rules (EG and the QAS+
/// schemes: `eg-derived`, `qas-plus-derived`): fairsub's derived rules also where the paper
/// prints rules, as `--rules derived`.
pub const DERIVED_SUFFIX: &[Suffix] = &[Suffix {
    text: "-derived",
    set: |p| p.rules = RulesChoice::Derived,
}];

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
