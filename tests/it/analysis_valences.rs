//! `analyze` and `charmap` at every valence below a scheme's minimum: a clear error naming the
//! valence, never a panic (the fuzzer found `analyze --scheme tps --valence 2` panicking in the
//! c-net builder), for every scheme of the registry at valences 0 to 3.

use fairsub::schemes::registry::registry;

#[test]
fn valences_below_the_minimum_are_clear_errors() {
    let out = std::env::temp_dir().join(format!("fairsub-valences-{}.svg", std::process::id()));
    let out = out.to_str().expect("utf-8 path");
    let mut refused = 0;
    for e in registry().entries() {
        for n in 0..=3usize {
            for command in ["analyze", "charmap"] {
                let n_text = n.to_string();
                let mut words = vec!["fairsub", command, "--scheme", e.name, "--valence", &n_text];
                if command == "charmap" {
                    words.extend(["-o", out]);
                }
                let what = format!("{command} --scheme {} --valence {n}", e.name);
                let got = std::panic::catch_unwind(|| fairsub::cli::run_words(&words));
                let result = got.unwrap_or_else(|_| panic!("{what} panicked"));
                let Err(err) = result else {
                    assert!(n >= 3, "{what}: accepted");
                    continue;
                };
                let msg = err.to_string();
                // schemes without analysis or characteristic map say so; the others name the
                // valence and the minimum
                if msg.contains("no analysis for scheme")
                    || msg.contains("has no characteristic map")
                {
                    continue;
                }
                assert!(n < 3, "{what}: {msg}");
                refused += 1;
                assert!(msg.contains(&n_text), "{what}: {msg}");
                assert!(
                    msg.contains("at least 3") || msg.contains(">= 3") || msg.contains("3..="),
                    "{what}: {msg}"
                );
            }
        }
    }
    assert!(refused > 50, "{refused} refusals");
}
