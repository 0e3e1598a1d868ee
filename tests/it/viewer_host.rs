//! The viewer's server answers only requests addressed to itself: a `Host` header that is not
//! its own loopback address and port (a page elsewhere whose name was rebound to 127.0.0.1, a
//! missing header, another port) gets 421 and nothing computed.

use crate::viewer_helpers::server;

use server::{get, get_as, start};

#[test]
fn only_requests_to_its_own_host_are_answered() {
    let v = start(&["gallery:cube", "--scheme", "catmull-clark", "--rings", "2"]);
    assert_eq!(get(v.port, "/").0, 200);
    assert_eq!(
        get_as(v.port, "/", Some(&format!("localhost:{}", v.port))).0,
        200
    );
    // Only requests addressed to the server itself are answered: a page of another site that
    // rebinds its own name to 127.0.0.1 sends its own name as Host, and gets nothing.
    let other_port = format!("127.0.0.1:{}", v.port.wrapping_add(1));
    let rebound = format!("attacker.example:{}", v.port);
    for host in [
        Some(rebound.as_str()),
        Some("attacker.example"),
        Some(other_port.as_str()),
        Some("127.0.0.1"),
        None,
    ] {
        for path in [
            "/",
            "/api/info",
            "/api/surface?scheme=catmull-clark&rings=2",
        ] {
            let (status, body) = get_as(v.port, path, host);
            let text = String::from_utf8_lossy(&body);
            assert_eq!(status, 421, "Host {host:?}, {path}: {text}");
            assert!(
                text.contains("answers only requests to http://127.0.0.1:")
                    && !text.contains("FSV1")
                    && !text.contains("vertices"),
                "Host {host:?}, {path}: {text}"
            );
        }
    }
    assert_eq!(get(v.port, "/viewer.js").0, 200);
    // and the server still answers its own page afterwards
    assert_eq!(get(v.port, "/api/info").0, 200);
}
