//! The request head, read and checked before the HTTP server (hyper) sees it, so that every
//! refusal has a JSON body: hyper answers a head it cannot parse (too large, malformed) with
//! a bare status line and no way to set the body. Here the head is read up to
//! [`MAX_HEAD_BYTES`](crate::limits::MAX_HEAD_BYTES), parsed with `httparse` (the parser
//! hyper itself uses) and refused with 400, 414 or 431 and a JSON error; a head that passes
//! is handed to hyper unchanged, together with the rest of the stream.

use axum::http::StatusCode;
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};

/// The sizes a request head may have.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HeadLimits {
    /// Request line and header fields, in bytes.
    pub max_head_bytes: usize,
    /// The request target (path and query), in bytes.
    pub max_uri_bytes: usize,
    /// Header fields.
    pub max_headers: usize,
}

/// Why a head was not accepted.
#[derive(Debug)]
pub(crate) enum HeadError {
    /// The client closed the connection (or it failed) before a complete head.
    Closed,
    /// The head is refused: answer with this status and message.
    Refused(StatusCode, String),
}

/// Reads from `rd` until the end of the request head (an empty line) and checks it; returns
/// every byte read (the head and whatever followed it in the same reads).
pub(crate) async fn read_head<R: AsyncRead + Unpin>(
    rd: &mut R,
    lim: &HeadLimits,
) -> Result<Vec<u8>, HeadError> {
    let mut buf: Vec<u8> = Vec::with_capacity(2048);
    loop {
        let scan_from = buf.len().saturating_sub(3);
        let room = lim.max_head_bytes + 1 - buf.len().min(lim.max_head_bytes);
        let n = (&mut *rd)
            .take(room.min(8192) as u64)
            .read_buf(&mut buf)
            .await
            .map_err(|_| HeadError::Closed)?;
        if n == 0 {
            return Err(HeadError::Closed);
        }
        // parse only once an empty line has arrived: a client sending one byte at a time
        // then costs one scan of the head, not one parse per byte
        if has_empty_line(&buf[scan_from..]) && check(&buf, lim)? {
            return Ok(buf);
        }
        if buf.len() > lim.max_head_bytes {
            return Err(too_large(&buf, lim));
        }
    }
}

/// An empty line (`\n\n` or `\n\r\n`) in `bytes`.
fn has_empty_line(bytes: &[u8]) -> bool {
    bytes.windows(2).any(|w| w == b"\n\n") || bytes.windows(3).any(|w| w == b"\n\r\n")
}

/// Parses the head: Ok(true) when complete and within the limits, Ok(false) when more bytes
/// are needed (e.g. empty lines before the request line).
fn check(buf: &[u8], lim: &HeadLimits) -> Result<bool, HeadError> {
    let mut headers = vec![httparse::EMPTY_HEADER; lim.max_headers];
    let mut req = httparse::Request::new(&mut headers);
    match req.parse(buf) {
        Ok(httparse::Status::Partial) => Ok(false),
        Ok(httparse::Status::Complete(len)) => {
            if len > lim.max_head_bytes {
                return Err(too_large(&buf[..len], lim));
            }
            let target = req.path.map_or(0, str::len);
            if target > lim.max_uri_bytes {
                return Err(uri_too_long(target, lim));
            }
            Ok(true)
        }
        Err(httparse::Error::TooManyHeaders) => Err(HeadError::Refused(
            StatusCode::REQUEST_HEADER_FIELDS_TOO_LARGE,
            format!(
                "too many header fields: at most {} are accepted",
                lim.max_headers
            ),
        )),
        Err(e) => Err(HeadError::Refused(
            StatusCode::BAD_REQUEST,
            format!("malformed HTTP request: {e}"),
        )),
    }
}

/// A head beyond the size limit: 414 while the request line has not ended, else 431.
fn too_large(buf: &[u8], lim: &HeadLimits) -> HeadError {
    if !buf.contains(&b'\n') {
        return uri_too_long(buf.len(), lim);
    }
    HeadError::Refused(
        StatusCode::REQUEST_HEADER_FIELDS_TOO_LARGE,
        format!(
            "request head larger than {} bytes (request line and header fields)",
            lim.max_head_bytes
        ),
    )
}

fn uri_too_long(len: usize, lim: &HeadLimits) -> HeadError {
    HeadError::Refused(
        StatusCode::URI_TOO_LONG,
        format!(
            "request target too long: {}{len} bytes, at most {} are accepted",
            if len > lim.max_uri_bytes.max(lim.max_head_bytes) {
                "more than "
            } else {
                ""
            },
            lim.max_uri_bytes
        ),
    )
}

/// A complete HTTP/1.1 response with a JSON error body `{"error": message}`, closing the
/// connection.
pub(crate) fn error_response(status: StatusCode, message: &str) -> Vec<u8> {
    let body = serde_json::json!({ "error": message }).to_string();
    format!(
        "HTTP/1.1 {} {}\r\ncontent-type: application/json\r\ncontent-length: {}\r\nconnection: close\r\ncache-control: no-store\r\nx-content-type-options: nosniff\r\n\r\n{body}",
        status.as_u16(),
        status.canonical_reason().unwrap_or(""),
        body.len()
    )
    .into_bytes()
}

/// Sends a JSON error and closes the writing side, then reads and discards what the client
/// still sends for a moment (at most `drain` bytes), so that closing does not reset the
/// connection before the client has read the answer.
pub(crate) async fn refuse<R, W>(
    rd: &mut R,
    wr: &mut W,
    status: StatusCode,
    message: &str,
    drain: u64,
) where
    R: AsyncRead + Unpin,
    W: AsyncWrite + Unpin,
{
    let send = async {
        wr.write_all(&error_response(status, message)).await?;
        wr.shutdown().await
    };
    if !matches!(
        tokio::time::timeout(std::time::Duration::from_secs(1), send).await,
        Ok(Ok(()))
    ) {
        return;
    }
    let mut sink = tokio::io::sink();
    let _ = tokio::time::timeout(
        std::time::Duration::from_millis(500),
        tokio::io::copy(&mut (&mut *rd).take(drain), &mut sink),
    )
    .await;
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIM: HeadLimits = HeadLimits {
        max_head_bytes: 1024,
        max_uri_bytes: 256,
        max_headers: 8,
    };

    fn read(bytes: &[u8]) -> Result<Vec<u8>, HeadError> {
        let rt = tokio::runtime::Builder::new_current_thread()
            .build()
            .expect("runtime");
        let mut r = bytes;
        rt.block_on(read_head(&mut r, &LIM))
    }

    fn refused(bytes: &[u8]) -> u16 {
        match read(bytes) {
            Err(HeadError::Refused(s, _)) => s.as_u16(),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_complete_head_passes_with_what_follows() {
        let req = b"GET /api/limits HTTP/1.1\r\nHost: localhost\r\n\r\nEXTRA";
        assert_eq!(read(req).unwrap(), req.to_vec());
        // bare line feeds are accepted like hyper accepts them
        assert!(read(b"GET / HTTP/1.1\nHost: localhost\n\n").is_ok());
    }

    #[test]
    fn oversized_and_malformed_heads_are_refused() {
        let long_uri = format!("GET /{} HTTP/1.1\r\nHost: x\r\n\r\n", "a".repeat(300));
        assert_eq!(refused(long_uri.as_bytes()), 414);
        let endless_line = format!("GET /{}", "a".repeat(5000));
        assert_eq!(refused(endless_line.as_bytes()), 414);
        let big = format!("GET / HTTP/1.1\r\nX: {}\r\n\r\n", "b".repeat(2000));
        assert_eq!(refused(big.as_bytes()), 431);
        let many: String = (0..20).map(|i| format!("X-{i}: 1\r\n")).collect();
        assert_eq!(
            refused(format!("GET / HTTP/1.1\r\n{many}\r\n").as_bytes()),
            431
        );
        assert_eq!(refused(b"GET / HTTP/1.1\r\nbad header\r\n\r\n"), 400);
        assert_eq!(refused(b"\x00\x01\x02 / HTTP/1.1\r\n\r\n"), 400);
        assert_eq!(refused(b"GET / HTTP/9.9\r\n\r\n"), 400);
        assert!(matches!(
            read(b"GET / HTTP/1.1\r\nHost: x\r\n"),
            Err(HeadError::Closed)
        ));
        assert!(matches!(read(b""), Err(HeadError::Closed)));
    }

    #[test]
    fn error_responses_are_json() {
        let r = String::from_utf8(error_response(StatusCode::URI_TOO_LONG, "a \"q\"")).unwrap();
        assert!(r.starts_with("HTTP/1.1 414 URI Too Long\r\n"), "{r}");
        let body = r.split("\r\n\r\n").nth(1).unwrap();
        let v: serde_json::Value = serde_json::from_str(body).unwrap();
        assert_eq!(v["error"], "a \"q\"");
        assert!(r.contains(&format!("content-length: {}\r\n", body.len())));
    }
}
