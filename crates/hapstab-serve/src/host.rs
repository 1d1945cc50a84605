//! Host and authority validation (defence against DNS rebinding): a request names the server
//! it is meant for in exactly one `Host` header and, in absolute form, in its target URI. A
//! server bound to a loopback address answers only requests naming `localhost` or a loopback
//! address, with its own port or none.

use std::net::IpAddr;

use axum::http::uri::Authority;
use axum::http::{HeaderMap, StatusCode, Uri, header};

use crate::query::{ApiError, clip};

/// What the server accepts as the authority of a request.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HostPolicy {
    /// Only loopback names and addresses (the server is bound to a loopback address).
    pub loopback_only: bool,
    /// The port the server listens on (checked when `loopback_only`).
    pub port: u16,
}

/// Checks the `Host` header(s) and an absolute-form target of a request: 400 when the Host
/// header is missing, repeated or malformed, 403 when it names another host or port.
pub(crate) fn check(policy: HostPolicy, headers: &HeaderMap, uri: &Uri) -> Result<(), ApiError> {
    let mut hosts = headers.get_all(header::HOST).iter();
    let (Some(host), None) = (hosts.next(), hosts.next()) else {
        let n = headers.get_all(header::HOST).iter().count();
        return Err(ApiError::status(
            StatusCode::BAD_REQUEST,
            if n == 0 {
                "missing Host header: a request must name the server it is meant for".into()
            } else {
                format!("{n} Host headers: a request must carry exactly one")
            },
        ));
    };
    let host = host.to_str().map_err(|_| {
        ApiError::status(
            StatusCode::BAD_REQUEST,
            "malformed Host header: not visible ASCII".into(),
        )
    })?;
    check_authority(policy, host, "Host header")?;
    if let Some(target) = uri.authority() {
        check_authority(policy, target.as_str(), "request target")?;
    }
    Ok(())
}

/// One authority (`host[:port]`): well formed, without user information, and allowed by the
/// policy.
fn check_authority(policy: HostPolicy, text: &str, what: &str) -> Result<(), ApiError> {
    let auth: Authority = text
        .parse()
        .ok()
        .filter(|_| !text.contains('@') && !text.is_empty())
        .ok_or_else(|| {
            ApiError::status(
                StatusCode::BAD_REQUEST,
                format!("malformed {what} '{}'", clip(text)),
            )
        })?;
    if !policy.loopback_only {
        return Ok(());
    }
    if !is_loopback_name(auth.host()) {
        return Err(ApiError::status(
            StatusCode::FORBIDDEN,
            format!(
                "{what} names host '{}', not allowed: this server answers requests for localhost and loopback addresses only",
                clip(auth.host())
            ),
        ));
    }
    match auth.port_u16() {
        Some(p) if p != policy.port => Err(ApiError::status(
            StatusCode::FORBIDDEN,
            format!(
                "{what} names port {p}, not allowed: this server listens on port {}",
                policy.port
            ),
        )),
        _ => Ok(()),
    }
}

/// `localhost` (any case) or a loopback IP address (IPv6 in brackets).
fn is_loopback_name(host: &str) -> bool {
    let bare = host
        .strip_prefix('[')
        .and_then(|h| h.strip_suffix(']'))
        .unwrap_or(host);
    host.eq_ignore_ascii_case("localhost")
        || bare.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::http::HeaderValue;

    const POLICY: HostPolicy = HostPolicy {
        loopback_only: true,
        port: 8717,
    };

    fn status(hosts: &[&str], uri: &str) -> Option<u16> {
        let mut h = HeaderMap::new();
        for v in hosts {
            h.append(header::HOST, HeaderValue::from_str(v).unwrap());
        }
        check(POLICY, &h, &uri.parse().unwrap())
            .err()
            .map(|e| e.status.as_u16())
    }

    #[test]
    fn loopback_names_with_the_right_port_or_none_pass() {
        for h in [
            "localhost",
            "LocalHost:8717",
            "127.0.0.1",
            "127.0.0.1:8717",
            "127.1.2.3:8717",
            "[::1]",
            "[::1]:8717",
        ] {
            assert_eq!(status(&[h], "/api/limits"), None, "{h}");
        }
        assert_eq!(
            status(&["localhost"], "http://127.0.0.1:8717/api/limits"),
            None
        );
    }

    #[test]
    fn other_hosts_ports_and_shapes_are_refused() {
        assert_eq!(status(&[], "/"), Some(400));
        assert_eq!(status(&["localhost", "evil.example"], "/"), Some(400));
        assert_eq!(status(&["localhost", "localhost"], "/"), Some(400));
        assert_eq!(status(&["evil.example"], "/"), Some(403));
        assert_eq!(status(&["localhost.evil.example"], "/"), Some(403));
        assert_eq!(status(&["10.0.0.1:8717"], "/"), Some(403));
        assert_eq!(status(&["localhost:80"], "/"), Some(403));
        assert_eq!(status(&["user@localhost"], "/"), Some(400));
        assert_eq!(status(&["local host"], "/"), Some(400));
        assert_eq!(status(&[""], "/"), Some(400));
        assert_eq!(
            status(&["localhost"], "http://evil.example/api/limits"),
            Some(403)
        );
        assert_eq!(
            status(&["localhost"], "http://localhost:9/api/limits"),
            Some(403)
        );
    }

    #[test]
    fn a_network_bind_checks_the_shape_only() {
        let open = HostPolicy {
            loopback_only: false,
            port: 8717,
        };
        let mut h = HeaderMap::new();
        h.insert(
            header::HOST,
            HeaderValue::from_static("lab-pc.example:8717"),
        );
        assert!(check(open, &h, &"/".parse().unwrap()).is_ok());
        h.append(header::HOST, HeaderValue::from_static("other"));
        assert!(check(open, &h, &"/".parse().unwrap()).is_err());
    }
}
