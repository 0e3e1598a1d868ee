//! Unit tests of the crease machinery.
