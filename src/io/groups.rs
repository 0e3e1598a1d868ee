//! Numbering of names by first appearance in constant time per name: the groups of `.bv` files
//! (read and written) and the entity labels of IGES files.

use std::collections::HashMap;

/// Numbers names 0, 1, 2, ... in order of first appearance.
#[derive(Debug, Default)]
pub(crate) struct FirstSeen {
    numbers: HashMap<String, usize>,
}

impl FirstSeen {
    /// The number of `name`, and whether this is its first appearance.
    pub fn number(&mut self, name: &str) -> (usize, bool) {
        if let Some(&k) = self.numbers.get(name) {
            return (k, false);
        }
        let k = self.numbers.len();
        self.numbers.insert(name.to_string(), k);
        (k, true)
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn numbers_by_first_appearance() {
        let mut s = FirstSeen::default();
        let got: Vec<(usize, bool)> = ["a", "b", "a", "c", "b"]
            .iter()
            .map(|n| s.number(n))
            .collect();
        assert_eq!(
            got,
            [(0, true), (1, true), (0, false), (2, true), (1, false)]
        );
    }
}
