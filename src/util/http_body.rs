//! Reading HTTP response bodies with a size limit, so a misbehaving server cannot make the
//! tool hold an unbounded body in memory.

/// Why a body could not be read.
#[derive(Debug, thiserror::Error)]
pub enum BodyError {
    /// The body is (or announced it would be) larger than the limit.
    #[error("the response body exceeds the limit of {limit} bytes")]
    TooLarge {
        /// The limit, bytes.
        limit: usize,
    },
    /// The transfer failed.
    #[error(transparent)]
    Read(#[from] reqwest::Error),
}

impl BodyError {
    /// Whether the transfer stopped on the client's timeout.
    pub fn is_timeout(&self) -> bool {
        matches!(self, BodyError::Read(e) if e.is_timeout())
    }
}

/// Reads the whole body of `resp`, stopping as soon as it passes `limit` bytes (or at once
/// when its `Content-Length` does).
pub async fn read_limited(mut resp: reqwest::Response, limit: usize) -> Result<Vec<u8>, BodyError> {
    if resp.content_length().is_some_and(|n| n > limit as u64) {
        return Err(BodyError::TooLarge { limit });
    }
    let mut body = Vec::new();
    while let Some(chunk) = resp.chunk().await? {
        if body.len() + chunk.len() > limit {
            return Err(BodyError::TooLarge { limit });
        }
        body.extend_from_slice(&chunk);
    }
    Ok(body)
}
