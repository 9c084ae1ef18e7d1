//! `scenesmith view DIR`: a scene in the browser, served from 127.0.0.1.
//!
//! The page itself lives in `src/view/web/` (three.js from npm, bundled by
//! `scripts/build_viewer.sh` into `target/viewer/`, so nothing is fetched from the internet at
//! run time). This module is the small HTTP server behind it:
//! - `GET /` and `GET /<file>`: the built page (`index.html`, the bundle, its style sheet);
//! - `GET /scene/<path>`: the file at `<path>` inside the scene directory
//!   (`export/scene.glb`, `scene.json`, `metrics.json`, `renders/*.png`).
//!
//! Only GET and HEAD, only files inside those two directories (no `..`, no absolute paths, no
//! hidden files, no symbolic links leading out), one thread per connection, every response
//! closes its connection.

use std::io::{BufRead, BufReader, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};
use std::time::Duration;

/// Why the viewer cannot start.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// The directory is not a scene directory.
    #[error("{0} is not a scene directory (no scene.json)")]
    NotAScene(PathBuf),
    /// The page has not been built.
    #[error(
        "the viewer page is not built ({0} has no index.html): run scripts/build_viewer.sh \
         (needs node and npm), or set SCENESMITH_VIEWER_DIR"
    )]
    NoBundle(PathBuf),
    /// The port could not be opened.
    #[error("cannot listen on 127.0.0.1:{port}: {source}")]
    Listen {
        /// The port asked for.
        port: u16,
        /// The cause.
        source: std::io::Error,
    },
}

/// Where the built page is: `SCENESMITH_VIEWER_DIR`, else `<repository>/target/viewer`.
pub fn bundle_dir() -> PathBuf {
    std::env::var_os("SCENESMITH_VIEWER_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| crate::physics::bridge::project_home().join("target/viewer"))
}

/// A bound viewer, not yet serving.
#[derive(Debug)]
pub struct Viewer {
    listener: TcpListener,
    bundle: PathBuf,
    scene: PathBuf,
}

impl Viewer {
    /// Binds 127.0.0.1:`port` (0: any free port) for the scene in `scene`, with the page from
    /// `bundle`.
    pub fn bind(scene: &Path, bundle: &Path, port: u16) -> Result<Viewer, ViewError> {
        if !scene.join("scene.json").is_file() {
            return Err(ViewError::NotAScene(scene.to_path_buf()));
        }
        if !bundle.join("index.html").is_file() {
            return Err(ViewError::NoBundle(bundle.to_path_buf()));
        }
        let listener = TcpListener::bind(("127.0.0.1", port))
            .map_err(|source| ViewError::Listen { port, source })?;
        Ok(Viewer {
            listener,
            bundle: bundle.to_path_buf(),
            scene: scene.to_path_buf(),
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> std::io::Result<SocketAddr> {
        self.listener.local_addr()
    }

    /// Serves until the process ends; a broken connection affects only itself.
    pub fn serve(self) {
        let roots = std::sync::Arc::new((self.bundle, self.scene));
        for stream in self.listener.incoming() {
            let Ok(stream) = stream else { continue };
            let roots = roots.clone();
            std::thread::spawn(move || {
                // A client that goes away mid-response is its own problem.
                let _ = handle(stream, &roots.0, &roots.1);
            });
        }
    }
}

/// Answers one request on `stream`.
fn handle(mut stream: TcpStream, bundle: &Path, scene: &Path) -> std::io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(10)))?;
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut request_line = String::new();
    reader.read_line(&mut request_line)?;
    // The headers are read and ignored: nothing here depends on them.
    let mut header = String::new();
    while reader.read_line(&mut header)? > 2 {
        header.clear();
    }
    let mut parts = request_line.split_whitespace();
    let (method, target) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
    if method != "GET" && method != "HEAD" {
        return respond(&mut stream, 405, "text/plain", b"only GET and HEAD\n", true);
    }
    let path = target.split(['?', '#']).next().unwrap_or("/");
    let file = match resolve(path, bundle, scene) {
        Some(f) => f,
        None => return respond(&mut stream, 404, "text/plain", b"not found\n", true),
    };
    match std::fs::read(&file) {
        Ok(bytes) => respond(&mut stream, 200, mime(&file), &bytes, method == "GET"),
        Err(_) => respond(&mut stream, 404, "text/plain", b"not found\n", true),
    }
}

/// The file a URL path names, if it is one we serve.
fn resolve(url_path: &str, bundle: &Path, scene: &Path) -> Option<PathBuf> {
    let decoded = percent_decode(url_path)?;
    let (root, rest) = match decoded.strip_prefix("/scene/") {
        Some(rest) => (scene, rest.to_string()),
        None => {
            let rest = decoded.trim_start_matches('/');
            (
                bundle,
                if rest.is_empty() {
                    "index.html".to_string()
                } else {
                    rest.to_string()
                },
            )
        }
    };
    let rel = Path::new(&rest);
    let plain = rel.components().all(|c| match c {
        Component::Normal(s) => !s.to_string_lossy().starts_with('.'),
        _ => false,
    });
    if !plain {
        return None;
    }
    let file = root.join(rel);
    // A symbolic link inside the directory must not lead out of it.
    let (real_root, real_file) = (root.canonicalize().ok()?, file.canonicalize().ok()?);
    (real_file.starts_with(&real_root) && real_file.is_file()).then_some(real_file)
}

/// `%XX` escapes decoded; `None` for a malformed escape or bytes that are not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k] == b'%' {
            let hex = std::str::from_utf8(bytes.get(k + 1..k + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            k += 3;
        } else {
            out.push(bytes[k]);
            k += 1;
        }
    }
    String::from_utf8(out).ok()
}

fn mime(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "js" | "mjs" => "application/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "json" | "map" => "application/json",
        "glb" => "model/gltf-binary",
        "gltf" => "model/gltf+json",
        "png" => "image/png",
        "jpg" | "jpeg" => "image/jpeg",
        "svg" => "image/svg+xml",
        "txt" | "yaml" | "sdf" | "xml" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

fn respond(
    stream: &mut TcpStream,
    status: u16,
    content_type: &str,
    body: &[u8],
    with_body: bool,
) -> std::io::Result<()> {
    let reason = match status {
        200 => "OK",
        404 => "Not Found",
        _ => "Method Not Allowed",
    };
    let head = format!(
        "HTTP/1.1 {status} {reason}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\n\
         Cache-Control: no-cache\r\nConnection: close\r\n\r\n",
        body.len()
    );
    stream.write_all(head.as_bytes())?;
    if with_body {
        stream.write_all(body)?;
    }
    stream.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dirs() -> (tempfile::TempDir, PathBuf, PathBuf) {
        let t = tempfile::tempdir().expect("temp dir");
        let bundle = t.path().join("bundle");
        let scene = t.path().join("scene");
        std::fs::create_dir_all(bundle.join("assets")).expect("mkdir");
        std::fs::create_dir_all(scene.join("export")).expect("mkdir");
        std::fs::write(bundle.join("index.html"), "<html>").expect("write");
        std::fs::write(bundle.join("assets/app.js"), "1").expect("write");
        std::fs::write(scene.join("scene.json"), "{}").expect("write");
        std::fs::write(scene.join("export/scene.glb"), "glTF").expect("write");
        std::fs::write(t.path().join("secret"), "x").expect("write");
        (t, bundle, scene)
    }

    #[test]
    fn urls_resolve_inside_the_two_roots_only() {
        let (t, bundle, scene) = dirs();
        let ok = |u: &str| resolve(u, &bundle, &scene);
        assert!(ok("/").is_some_and(|p| p.ends_with("index.html")));
        assert!(ok("/assets/app.js").is_some());
        assert!(ok("/scene/export/scene.glb").is_some());
        assert!(ok("/scene/export%2Fscene.glb").is_some());
        for bad in [
            "/../secret",
            "/scene/../secret",
            "/scene/%2e%2e/secret",
            "/scene/missing.json",
            "/scene/",
            "/%zz",
        ] {
            assert_eq!(ok(bad), None, "{bad}");
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(t.path().join("secret"), scene.join("link"))
                .expect("symlink");
            assert_eq!(ok("/scene/link"), None);
        }
    }

    #[test]
    fn serves_files_with_their_types_over_http() {
        let (_t, bundle, scene) = dirs();
        let viewer = Viewer::bind(&scene, &bundle, 0).expect("bind");
        let addr = viewer.addr().expect("addr");
        std::thread::spawn(move || viewer.serve());
        let get = |path: &str| {
            let mut s = TcpStream::connect(addr).expect("connect");
            write!(s, "GET {path} HTTP/1.1\r\nHost: x\r\n\r\n").expect("send");
            let mut text = String::new();
            std::io::Read::read_to_string(&mut s, &mut text).expect("read");
            text
        };
        let page = get("/");
        assert!(page.starts_with("HTTP/1.1 200"), "{page}");
        assert!(
            page.contains("text/html") && page.ends_with("<html>"),
            "{page}"
        );
        let glb = get("/scene/export/scene.glb");
        assert!(glb.contains("model/gltf-binary"), "{glb}");
        assert!(get("/scene/nothing").starts_with("HTTP/1.1 404"));
    }

    #[test]
    fn refuses_a_directory_without_a_scene_or_a_page() {
        let (t, bundle, scene) = dirs();
        assert!(matches!(
            Viewer::bind(t.path(), &bundle, 0),
            Err(ViewError::NotAScene(_))
        ));
        assert!(matches!(
            Viewer::bind(&scene, t.path(), 0),
            Err(ViewError::NoBundle(_))
        ));
    }
}
